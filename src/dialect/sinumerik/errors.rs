//! Syntax errors in human words: a pest failure becomes one diagnostic that says what was
//! expected at the failing column ("an expression", "`)`", "a label or block number"), with a
//! hint. Also the pre-checks that keep pest's recursion bounded.

use super::Rule;
use crate::diag::Diagnostic;
use crate::dialect::limits::{self, MAX_NESTING};
use crate::read::Normalised;
use crate::span::FileId;

/// What a grammar rule means to a reader, or `None` when it should not be listed.
fn describe(r: Rule) -> Option<&'static str> {
    use Rule::*;
    Some(match r {
        expr | number | hex_const | bin_const | string | true_kw | false_kw | paren | func_call | r_param
        | r_indirect | sys_var | named_var | op_not | op_bnot | op_neg | op_plus | arg_slot | ac_ic | def_init
        | set_init | rep_init => "an expression",
        op_eq | op_ne | op_concat | op_ge | op_le | op_gt | op_lt | op_add | op_sub | op_mul | op_div | op_intdiv
        | op_mod | op_band | op_bor | op_bxor | op_and | op_or | op_xor => "an operator",
        lparen => "`(`",
        rparen => "`)`",
        lbracket | dims | subscripts => "`[`",
        rbracket => "`]`",
        comma => "`,`",
        eq => "`=`",
        colon => "`:`",
        kw_to => "`TO`",
        kw_of => "`OF`",
        kw_default => "`DEFAULT`",
        goto_stmt | goto_kw => "a jump (GOTOF, GOTOB, GOTO, GOTOC)",
        target_number | target_label => "a label or block number",
        label_ref => "a label",
        case_arm | case_value => "a CASE constant",
        p_count => "`P=` count",
        comment => "a comment",
        EOI => "the end of the block",
        user_name | def_var | for_var | param => "a name",
        type_real | type_int | type_bool | type_char | type_axis | type_frame | type_string => {
            "a data type (REAL, INT, BOOL, CHAR, STRING[n], AXIS, FRAME)"
        }
        uint => "a whole number",
        word_const | assign | call | bare_name | items => "an address word, assignment or call",
        proc_attr => "a PROC attribute (SAVE, DISPLOF)",
        kw_var => "`VAR`",
        _ => return None,
    })
}

/// The order expectations are listed in: the most useful first.
const ORDER: &[&str] = &[
    "`)`",
    "`]`",
    "`=`",
    "`TO`",
    "`OF`",
    "a label or block number",
    "a label",
    "a data type (REAL, INT, BOOL, CHAR, STRING[n], AXIS, FRAME)",
    "a name",
    "a whole number",
    "an expression",
    "a CASE constant",
    "`DEFAULT`",
    "a jump (GOTOF, GOTOB, GOTO, GOTOC)",
    "`P=` count",
    "`(`",
    "`[`",
    "`,`",
    "`:`",
    "an operator",
    "an address word, assignment or call",
    "a PROC attribute (SAVE, DISPLOF)",
    "`VAR`",
    "a comment",
    "the end of the block",
];

fn join(words: &[&str]) -> String {
    match words {
        [] => "something else".to_string(),
        [one] => (*one).to_string(),
        [rest @ .., last] => format!("{} or {last}", rest.join(", ")),
    }
}

/// One diagnostic for a block pest rejected.
pub fn syntax(e: &pest::error::Error<Rule>, norm: &Normalised<'_>, file: FileId) -> Diagnostic {
    let text: &str = &norm.text;
    let pos = match e.location {
        pest::error::InputLocation::Pos(p) => p,
        pest::error::InputLocation::Span((p, _)) => p,
    }
    .min(text.len());
    if let Some(d) = unbalanced(text, norm, file) {
        return d;
    }
    let mut words: Vec<&str> = match &e.variant {
        pest::error::ErrorVariant::ParsingError { positives, .. } => {
            positives.iter().filter_map(|r| describe(*r)).collect()
        }
        pest::error::ErrorVariant::CustomError { .. } => Vec::new(),
    };
    words.sort_by_key(|w| ORDER.iter().position(|o| o == w).unwrap_or(usize::MAX));
    words.dedup();
    // An operator or the end of the block is always possible after a complete operand;
    // listing them next to the real need only adds noise.
    if words.len() > 1 && words.iter().any(|w| w.starts_with('`') || w.starts_with("a label")) {
        words.retain(|w| *w != "an operator" && *w != "the end of the block" && *w != "a comment");
    }
    words.truncate(4);
    let found_char = text[pos..].chars().next();
    let span = match found_char {
        Some(c) => norm.span(pos, pos + c.len_utf8()),
        None => norm.span(pos, pos),
    };
    let found = match found_char {
        Some(c) => format!("found `{c}`"),
        None => "the block ends here".to_string(),
    };
    if let Some(d) = two_points(text, pos, norm, file) {
        return d;
    }
    if words.contains(&"a name") {
        if let Ok(mut kw) = <super::SinumerikParser as pest::Parser<Rule>>::parse(Rule::keyword, &text[pos..]) {
            let word = kw.next().map_or("", |k| k.as_str()).to_ascii_uppercase();
            let span = norm.span(pos, pos + word.len());
            return Diagnostic::error("NC136", format!("{word} is a reserved word, not a name"))
                .primary(file, span, "reserved word")
                .hint(format!("choose another name, e.g. `U_{word}`"));
        }
    }
    let expected = join(&words);
    let hint = match words.first().copied() {
        Some("`)`") => "close every `(` with `)`".to_string(),
        Some("`]`") => "close every `[` with `]`".to_string(),
        Some("`=`") => "multi-letter addresses and variables take their value after `=`, e.g. `X=R1`, `CR=5`".to_string(),
        Some("`TO`") => "write `FOR I=1 TO 10`".to_string(),
        Some("`OF`") => "write `CASE (R1) OF 1 GOTOF L1 DEFAULT GOTOF L2`".to_string(),
        Some("a label or block number") => "jump to a label (`GOTOF END1`) or a block number (`GOTOF N100`)".to_string(),
        Some("an expression") => "complete the expression, e.g. `R1=R2+1`; a value with operators needs `=` after the address (`X=R1+2`)".to_string(),
        Some("a CASE constant") => "each CASE branch is a constant and a jump: `1 GOTOF L1`".to_string(),
        _ => "check the block against the Sinumerik syntax: keywords and names need a blank between them; `X=…` is needed for any value that is not a plain number".to_string(),
    };
    let label =
        if found_char.is_some() { format!("expected {expected}; {found}") } else { format!("expected {expected}") };
    Diagnostic::error("NC120", format!("syntax error: expected {expected}")).primary(file, span, label).hint(hint)
}

/// `X1.2.3`: the run of digits and points around the failing column has two points.
fn two_points(text: &str, pos: usize, norm: &Normalised<'_>, file: FileId) -> Option<Diagnostic> {
    let b = text.as_bytes();
    let num = |c: u8| c.is_ascii_digit() || c == b'.';
    if !b.get(pos).is_some_and(|c| num(*c)) {
        return None;
    }
    let mut lo = pos;
    while lo > 0 && num(b[lo - 1]) {
        lo -= 1;
    }
    let mut hi = pos;
    while hi < b.len() && num(b[hi]) {
        hi += 1;
    }
    if b[lo..hi].iter().filter(|c| **c == b'.').count() < 2 {
        return None;
    }
    Some(
        Diagnostic::error("NC122", "a number has more than one decimal point")
            .primary(file, norm.span(lo, hi), "not a number")
            .hint("write one decimal point, e.g. `X1.23`"),
    )
}

/// Positions of `(`/`[` that are never closed, or a `)`/`]` without opener: a clearer message
/// than pest's for unbalanced and truncated blocks. Strings and the comment are skipped.
fn unbalanced(text: &str, norm: &Normalised<'_>, file: FileId) -> Option<Diagnostic> {
    let mut stack: Vec<(usize, u8)> = Vec::new();
    for (i, c) in code_bytes(text) {
        match c {
            b'(' | b'[' => stack.push((i, c)),
            c @ (b')' | b']') => {
                let want = if c == b')' { b'(' } else { b'[' };
                match stack.pop() {
                    Some((_, o)) if o == want => {}
                    Some((at, o)) => {
                        let close = if o == b'(' { ")" } else { "]" };
                        return Some(
                            Diagnostic::error("NC121", format!("`{}` closed by `{}`", o as char, c as char))
                                .primary(file, norm.span(i, i + 1), format!("expected `{close}`"))
                                .secondary(file, norm.span(at, at + 1), "opened here")
                                .hint("parentheses `( )` group expressions and call arguments; brackets `[ ]` index arrays"),
                        );
                    }
                    None => {
                        return Some(
                            Diagnostic::error("NC121", format!("`{}` without matching `{}`", c as char, want as char))
                                .primary(file, norm.span(i, i + 1), "nothing to close")
                                .hint(format!("remove it or add the opening `{}`", want as char)),
                        )
                    }
                }
            }
            _ => {}
        }
    }
    let (at, o) = stack.pop()?;
    let close = if o == b'(' { ')' } else { ']' };
    Some(
        Diagnostic::error("NC121", format!("`{}` is never closed", o as char))
            .primary(file, norm.span(at, at + 1), "opened here")
            .secondary(
                file,
                norm.span(text.len(), text.len()),
                format!("expected `{close}` before the end of the block"),
            )
            .hint(format!("add `{close}`")),
    )
}

/// Rejects a block whose parentheses/brackets nest deeper than [`MAX_NESTING`], so that pest
/// and the converter never recurse deeper than that.
pub fn too_deep(text: &str, norm: &Normalised<'_>, file: FileId) -> Option<Diagnostic> {
    let mut depth = 0u32;
    for (i, c) in code_bytes(text) {
        match c {
            b'(' | b'[' => {
                depth += 1;
                if depth > MAX_NESTING {
                    return Some(limits::too_nested(file, norm.span(i, i + 1), depth, HINT));
                }
            }
            b')' | b']' => depth = depth.saturating_sub(1),
            _ => {}
        }
    }
    None
}

/// What to do about an expression that is too long or too deep (NC130).
pub const HINT: &str = "split the calculation into several assignments with intermediate R parameters";

/// The bytes of a block's code with their offsets: string contents (`"…"`) are skipped and
/// the `;` comment ends it.
fn code_bytes(text: &str) -> impl Iterator<Item = (usize, u8)> + '_ {
    let mut in_string = false;
    text.bytes()
        .enumerate()
        .map_while(move |(i, c)| match c {
            b'"' => {
                in_string = !in_string;
                Some(None)
            }
            _ if in_string => Some(None),
            b';' => None,
            _ => Some(Some((i, c))),
        })
        .flatten()
}
