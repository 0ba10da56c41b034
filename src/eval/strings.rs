//! The Siemens string functions (828D/840D Job Planning, "String operations"): `STRLEN`,
//! `TOUPPER`, `TOLOWER`, `INDEX`, `RINDEX`, `SUBSTR`, `NUMBER`, `ISNUMBER`. Positions count
//! characters from 0; a search that finds nothing gives −1. Numbers given where a string is
//! wanted are read as `<<` writes them.

use super::expr::{as_text, Cx};
use super::fault::Fault;
use super::value::{round_half_away, Value};
use crate::ir::Func;
use crate::span::Span;

/// A number a string spells as Siemens writes one (sign, digits, point, exponent `EX`).
fn parse_number(s: &str) -> Option<f64> {
    let t = s.trim();
    if t.is_empty() || !t.bytes().all(|b| b.is_ascii_digit() || b"+-.EeXx".contains(&b)) {
        return None;
    }
    let t = t.to_ascii_uppercase().replacen("EX", "E", 1);
    t.parse::<f64>().ok().filter(|x| x.is_finite())
}

/// `f` applied to the values `vs`.
pub fn call(f: Func, vs: &[Value], span: Span, cx: &Cx) -> Result<Value, Fault> {
    let domain = |what: String| Fault::alarm(cx.alarms.domain, what, span);
    let text = |i: usize| vs.get(i).map(as_text).unwrap_or_default();
    let int = |i: usize| -> Result<i64, Fault> {
        match vs.get(i) {
            Some(Value::Num(x)) => Ok(round_half_away(*x) as i64),
            _ => Err(domain(format!("argument {} of a string function must be a number", i + 1))),
        }
    };
    let chars: Vec<char> = text(0).chars().collect();
    Ok(match f {
        Func::StrLen => Value::Num(chars.len() as f64),
        Func::ToUpper => Value::Str(text(0).to_ascii_uppercase()),
        Func::ToLower => Value::Str(text(0).to_ascii_lowercase()),
        Func::Index | Func::RIndex => {
            let want: Vec<char> = text(1).chars().collect();
            let [c] = want.as_slice() else {
                return Err(domain("INDEX/RINDEX search for one character".into()));
            };
            let found =
                if f == Func::Index { chars.iter().position(|x| x == c) } else { chars.iter().rposition(|x| x == c) };
            Value::Num(found.map_or(-1.0, |p| p as f64))
        }
        Func::Substr => {
            let start = int(1)?;
            let count = if vs.len() > 2 { int(2)? } else { chars.len() as i64 - start };
            if start < 0 || count < 0 || start as usize > chars.len() {
                return Err(domain(format!("SUBSTR from {start} for {count} is outside the string")));
            }
            Value::Str(chars.iter().skip(start as usize).take(count as usize).collect())
        }
        Func::Number => match parse_number(&text(0)) {
            Some(x) => Value::Num(x),
            None => return Err(domain(format!("NUMBER: \"{}\" is not a number", text(0)))),
        },
        Func::IsNumber => Value::Num(if parse_number(&text(0)).is_some() { 1.0 } else { 0.0 }),
        Func::GetT => {
            return Err(Fault::error(
                crate::diag::Diagnostic::error(
                    "NC508",
                    "GETT: the T number tool management gives a tool name is not modelled",
                )
                .primary(cx.file, span, "here")
                .hint("give the set-up's tool map (--tool-map NAME=n, [tools] in nctrans.toml), or select the tool by name (T=\"NAME\") or by number"),
            ))
        }
        _ => return Err(domain("not a string function".into())),
    })
}

/// `GETT("NAME")`: the T number the set-up's tool map gives `name` (`known`: `None` when
/// the run has no tool map, `Some(None)` when the map lacks the name). A duplo number
/// (`GETT("NAME", 2)`, the n-th replacement tool of that name) is refused: the map holds one
/// T number per name.
pub fn gett(known: Option<Option<u32>>, name: &str, duplo: bool, span: Span, cx: &Cx) -> Result<Value, Fault> {
    let err = |code: &'static str, msg: String, hint: String| {
        Err(Fault::error(crate::diag::Diagnostic::error(code, msg).primary(cx.file, span, "here").hint(hint)))
    };
    match known {
        _ if duplo => err(
            "NC526",
            format!("GETT(\"{name}\", duplo): a duplo number (which replacement tool of that name) is not modelled"),
            "the tool map holds one T number per name: write GETT(\"NAME\") or give each replacement tool its own name"
                .into(),
        ),
        None => call(Func::GetT, &[], span, cx),
        Some(None) => err(
            "NC525",
            format!("GETT(\"{name}\"): the tool map has no tool \"{name}\""),
            format!("give its T number: --tool-map {name}=<number>, or `\"{name}\" = <number>` under [tools]"),
        ),
        Some(Some(n)) => Ok(Value::Num(f64::from(n))),
    }
}

/// The refusal of a function the evaluator does not model: `SPRINT` (its format rules are
/// not documented to the digit here), `ISVAR` (it asks the control's tables of machine,
/// setting, system and user data), `ISFILE` (the control's file system), `GETSELT` (tool
/// management, as `GETT`).
pub fn refused(f: Func, span: Span, cx: &Cx) -> Fault {
    let (code, msg, hint) = match f {
        Func::Sprint => (
            "NC565",
            "SPRINT: the text a format makes of numbers is not modelled",
            "build the text with << (its number form is modelled)",
        ),
        Func::IsVar => (
            "NC565",
            "ISVAR: whether the control knows a name (machine, setting, system or user data) is not modelled",
            "test the variable's own value, or give the answer as an input",
        ),
        Func::IsFile => {
            ("NC565", "ISFILE: the control's file system is not modelled", "give the answer as an input variable")
        }
        _ => (
            "NC508",
            "GETSELT: the tool tool management preselected for the spindle is not modelled (no source read here says \
             what it returns, or whether it is the last T word)",
            "keep the T number in a variable where the program selects the tool (T=R10), or select it by name \
             (T=\"NAME\")",
        ),
    };
    Fault::error(crate::diag::Diagnostic::error(code, msg).primary(cx.file, span, "here").hint(hint))
}
