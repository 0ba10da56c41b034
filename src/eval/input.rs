//! Inputs set before a run: `--set R1=5`, `--set '#24=10.'`, `--set NAME=3`, and the same
//! as header comment lines in a program: `; nctrans: set R1=5` (Siemens) or
//! `(nctrans: set #24=10.)` (FANUC), several per line separated by spaces.

use super::value::Value;

#[derive(Clone, Debug, PartialEq)]
pub enum InputTarget {
    /// FANUC `#n`.
    Hash(u32),
    /// Siemens `Rn`.
    R(u32),
    /// A Siemens DEF variable or PROC parameter (upper case).
    Name(String),
    /// Siemens cutting edge data `$TC_DPn[t,d]` (the machine's tool offsets), as the key
    /// `$TC_DP3[5,1]` (`eval::tool_data`).
    ToolData(String),
    /// A Siemens machine signal `$A_DBB[2]`, `$A_IN[1]` … (`eval::signals`).
    Signal(crate::dialect::signals::Signal),
}

#[derive(Clone, Debug, PartialEq)]
pub struct Input {
    pub target: InputTarget,
    pub value: Value,
    /// As written, for messages.
    pub text: String,
}

/// Parses one `TARGET=VALUE` (`#24=10.`, `R1=-2.5`, `NAME=3`, `TOOL="T1"`, `#1=#0`).
pub fn parse_input(s: &str) -> Result<Input, String> {
    let (lhs, rhs) = s.split_once('=').ok_or_else(|| format!("'{s}': expected TARGET=VALUE, e.g. R1=5 or #24=10."))?;
    let (lhs, rhs) = (lhs.trim(), rhs.trim());
    let up = lhs.to_ascii_uppercase();
    let target = if let Some(rest) = up.strip_prefix("$TC_DP") {
        let bad = || format!("'{lhs}': expected $TC_DPn[tool,edge], e.g. $TC_DP3[5,1]");
        let (n, idx) = rest.split_once('[').ok_or_else(bad)?;
        let (t, d) = idx.strip_suffix(']').and_then(|x| x.split_once(',')).ok_or_else(bad)?;
        let (n, t, d): (u32, u32, u32) = (
            n.trim().parse().map_err(|_| bad())?,
            t.trim().parse().map_err(|_| bad())?,
            d.trim().parse().map_err(|_| bad())?,
        );
        InputTarget::ToolData(format!("$TC_DP{n}[{t},{d}]"))
    } else if up.starts_with("$A_") {
        InputTarget::Signal(crate::dialect::signals::Signal::parse(lhs)?)
    } else if let Some(n) = up.strip_prefix('#') {
        InputTarget::Hash(n.parse().map_err(|_| format!("'{lhs}': bad variable number"))?)
    } else if up.len() > 1 && up.starts_with('R') && up[1..].bytes().all(|b| b.is_ascii_digit()) {
        InputTarget::R(up[1..].parse().map_err(|_| format!("'{lhs}': bad R number"))?)
    } else if !up.is_empty()
        && up.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_')
        && !up.as_bytes()[0].is_ascii_digit()
    {
        InputTarget::Name(up)
    } else {
        return Err(format!("'{lhs}': expected #n, Rn or a variable name"));
    };
    let value = if rhs == "#0" {
        Value::Vacant
    } else if rhs.len() >= 2 && rhs.starts_with('"') && rhs.ends_with('"') {
        Value::Str(rhs[1..rhs.len() - 1].to_string())
    } else {
        Value::Num(rhs.parse::<f64>().map_err(|_| format!("'{rhs}': expected a number"))?)
    };
    Ok(Input { target, value, text: s.to_string() })
}

/// Inputs written in a file's header comments: lines `; nctrans: set A=1 B=2` or
/// `(nctrans: set #24=10.)`. Only comment lines before the first other line count.
pub fn header_inputs(text: &str) -> Result<Vec<Input>, String> {
    header_words(text, "nctrans: set", false).map(parse_input).collect()
}

/// The space-separated words after `key` in a file's header comments (`; key …` or
/// `(key …)`), the lines before its first block: blank lines, `%`, the program's name line
/// (`O…`, `PROC …`) and, with `skip_defs`, Siemens `DEF` lines (a translation to Sinumerik
/// writes them first) may come between them.
pub(crate) fn header_words<'a>(text: &'a str, key: &'a str, skip_defs: bool) -> impl Iterator<Item = &'a str> + 'a {
    text.lines()
        .map(str::trim)
        .filter(|t| !t.is_empty() && !t.starts_with('%'))
        .filter(move |t| !(t.starts_with('O') || t.starts_with("PROC") || (skip_defs && t.starts_with("DEF "))))
        .map_while(|t| {
            if let Some(r) = t.strip_prefix(';') {
                Some(r)
            } else {
                t.strip_prefix('(').map(|r| r.trim_end_matches(';').trim_end().trim_end_matches(')'))
            }
        })
        .filter_map(move |body| body.trim().strip_prefix(key))
        .flat_map(str::split_whitespace)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_targets() {
        assert_eq!(parse_input("R1=5").unwrap().target, InputTarget::R(1));
        assert_eq!(parse_input("#24=10.").unwrap().value, Value::Num(10.0));
        assert_eq!(parse_input("depth=2").unwrap().target, InputTarget::Name("DEPTH".into()));
        assert_eq!(parse_input("#1=#0").unwrap().value, Value::Vacant);
        assert!(parse_input("R1").is_err());
        assert!(parse_input("R1=x").is_err());
        assert!(matches!(parse_input("$A_DBB[2]=1").unwrap().target, InputTarget::Signal(_)));
    }

    #[test]
    fn header_lines() {
        let t = "%\nO1000 (X)\n(nctrans: set #24=10. #26=-5.)\nG0 X1\n(nctrans: set #1=1)\n";
        let i = header_inputs(t).unwrap();
        assert_eq!(i.len(), 2);
        let t = "; nctrans: set R1=5\n; other\nR2=1\n";
        assert_eq!(header_inputs(t).unwrap().len(), 1);
    }
}
