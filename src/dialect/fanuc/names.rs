//! FANUC spellings: the function table, and the human words for grammar rules used in
//! "expected …" messages.

use super::parse::Rule;
use crate::ir::Func;

pub struct FuncSpec {
    pub func: Func,
    pub arity: usize,
}

/// Every function name the grammar's generic call form may carry (ATAN has its own rule).
pub fn function(name: &str) -> Option<FuncSpec> {
    let (func, arity) = match name {
        "SIN" => (Func::Sin, 1),
        "COS" => (Func::Cos, 1),
        "TAN" => (Func::Tan, 1),
        "ASIN" => (Func::FanucAsin, 1),
        "ACOS" => (Func::FanucAcos, 1),
        "SQRT" => (Func::Sqrt, 1),
        "ABS" => (Func::Abs, 1),
        "ROUND" => (Func::FanucRound, 1),
        "FIX" => (Func::Trunc, 1),
        "FUP" => (Func::FanucFup, 1),
        "LN" => (Func::Ln, 1),
        "EXP" => (Func::Exp, 1),
        "BIN" => (Func::Bin, 1),
        "BCD" => (Func::Bcd, 1),
        "POW" => (Func::Pow, 2),
        "ADP" => (Func::Adp, 1),
        _ => return None,
    };
    Some(FuncSpec { func, arity })
}

pub const FUNCTION_LIST: &str = "SIN COS TAN ASIN ACOS ATAN SQRT ABS ROUND FIX FUP LN EXP BIN BCD POW ADP";

/// A suggestion for an unknown function name (Siemens spellings are a common cause).
pub fn function_hint(name: &str) -> String {
    let fanuc = match name {
        "TRUNC" | "INT" => Some("FIX[x]"),
        "ROUNDUP" | "CEIL" => Some("FUP[x] (note: FUP rounds away from zero)"),
        "ATAN2" | "ATN" => Some("ATAN[y]/[x]"),
        "POT" | "SQR" => Some("[x*x]"),
        "SQT" => Some("SQRT[x]"),
        "ASN" => Some("ASIN[x]"),
        "ACS" => Some("ACOS[x]"),
        "MINVAL" | "MAXVAL" | "MIN" | "MAX" => Some("IF[…]GOTO with a comparison"),
        _ => None,
    };
    match fanuc {
        Some(f) => format!("FANUC writes this as {f}"),
        None => format!("use one of the FANUC functions: {FUNCTION_LIST}"),
    }
}

pub fn function_usage(name: &str) -> String {
    match name {
        "POW" => "write `POW[base,exponent]`".into(),
        _ => format!("write `{name}[x]` with one argument"),
    }
}

/// What a grammar rule means to someone reading an "expected …" message.
pub fn describe(rule: Rule, after_hash: bool) -> &'static str {
    match rule {
        Rule::uint | Rule::var_number if after_hash => "a variable number after `#`",
        Rule::var_number => "a variable number after `#`",
        Rule::uint => "a number",
        Rule::unsigned | Rule::value => "a value (a number, a `#` variable or `[expression]`)",
        Rule::expr
        | Rule::factor
        | Rule::cond
        | Rule::variable
        | Rule::bracket
        | Rule::atan_call
        | Rule::func_call
        | Rule::func_name
        | Rule::kw_atan
        | Rule::sign => "an expression",
        Rule::add_op | Rule::mul_op => "an operator",
        Rule::rel_op => "a comparison (EQ, NE, GT, GE, LT, LE)",
        Rule::rbracket => "`]`",
        Rule::lbracket => "`[`",
        Rule::comma => "`,`",
        Rule::equals => "`=`",
        Rule::atan_slash => "`/`",
        Rule::loop_id => "a loop number (1, 2 or 3)",
        Rule::kw_do => "`DO`",
        Rule::kw_goto | Rule::kw_then => "`GOTO` or `THEN`",
        Rule::then_part => "`THEN`",
        Rule::assign => "an assignment (`#i=…`)",
        Rule::EOI => "the end of the block",
        Rule::comment_text => "comment text",
        Rule::skip => "`/`",
        _ => "an address word or a macro statement",
    }
}

/// Label and hint for a grammar failure, from what was found and what was expected.
pub fn hint_for(found: Option<char>, expected: &[&str], in_brackets: bool) -> (String, String) {
    let has = |w: &str| expected.contains(&w);
    match found {
        Some('=') if in_brackets => (
            "`=` is not a comparison".into(),
            "compare with EQ, e.g. `IF[#1 EQ 5]GOTO10`".into(),
        ),
        Some(')') => (
            "`)` without an open comment".into(),
            "comments do not nest: `(A (B) C)` ends at the first `)`; remove the inner parentheses".into(),
        ),
        Some(c) if !c.is_ascii() => (
            "not a FANUC character".into(),
            "put text in a comment `( … )`; outside comments a block holds only address words and macro statements".into(),
        ),
        None if has("an expression") => (
            "the block ends here".into(),
            "the block ends in the middle of an expression; complete it".into(),
        ),
        _ if has("a variable number after `#`") => (
            "not a variable number".into(),
            "write `#` followed by the number (`#100`) or a bracketed expression (`#[#1+2]`)".into(),
        ),
        _ if has("a loop number (1, 2 or 3)") => (
            "loop number expected".into(),
            "write the loop number right after DO/END, e.g. `WHILE[#1 LT 10]DO1` … `END1`".into(),
        ),
        _ if has("`GOTO` or `THEN`") => (
            "GOTO or THEN expected".into(),
            "write `IF[cond]GOTO n` or `IF[cond]THEN #i=…`".into(),
        ),
        _ if has("`DO`") => (
            "DO expected".into(),
            "a WHILE block ends with its loop number: `WHILE[#1 LT 10]DO1`".into(),
        ),
        _ if has("an expression") => (
            "expression expected".into(),
            "a value is a number, `#n`, `#[expr]`, a function like `SIN[…]`, or `[expression]`".into(),
        ),
        _ if has("a value (a number, a `#` variable or `[expression]`)") => (
            "value expected after the address letter".into(),
            "an address is a letter followed by a number (`X10.`), a variable (`X#1`, `X-#1`) or an expression (`X[#1+#2]`)".into(),
        ),
        _ if has("`]`") => (
            "`]` expected".into(),
            "close the bracket, or join values with an operator (+ - * / AND OR XOR MOD)".into(),
        ),
        _ => (
            "unexpected here".into(),
            "a block holds address words (`G1 X10.`) or one macro statement (`#1=…`, `IF[…]GOTO n`, `WHILE[…]DO1`)".into(),
        ),
    }
}

/// What a Haas-only G code does, for the refusals of the codes neither the evaluator nor a
/// translation carries (`g10` is ten times the code: 130 for G13). Haas documents these
/// cycles by a list of addresses and a drawing of the tool path, not by the moves, so they
/// cannot be run or written as moves exactly (docs/semantics.md, "Haas-only cycles").
pub fn haas_g_meaning(g10: u32) -> Option<&'static str> {
    Some(match g10 {
        120 => "Haas circular pocket milling, clockwise",
        130 => "Haas circular pocket milling, counterclockwise",
        470 => "Haas text engraving",
        700 => "Haas bolt hole circle",
        710 => "Haas bolt hole arc",
        720 => "Haas bolt holes along an angle",
        1000 => "Haas mirror image off",
        1010 => "Haas mirror image on",
        1020 => "Haas programmable output of the position to RS-232",
        1070 => "Haas cylindrical mapping",
        1410 => "Haas 3D+ cutter compensation",
        1500 => "Haas general purpose pocket milling",
        _ => return None,
    })
}
