//! Values the machine's set-up fixes (`[variables] fixed`, `Semantics::fixed`): reading the
//! table, and the notes by which a run says which of them it read, so that every verdict
//! names them (`check::Excluded::assumed`).

use std::collections::BTreeMap;

/// The diagnostic of a program writing a value the set-up fixes (run and translation).
pub const WRITTEN: &str = "NC544";
/// The note of a run reading a value the set-up fixes (and of a translation refusing a
/// global STRING the table does not give, or an axis the FANUC profile lacks).
pub const ASSUMED: &str = "NC543";

const NOTE_HEAD: &str = "the run assumes the set-up value ";
const NOTE_TAIL: &str = " (variables.fixed)";

/// The note of a run that read `name`: `the run assumes the set-up value AXIS_HORI = "Z" (…)`.
pub fn note_message(name: &str, value: &str) -> String {
    format!("{NOTE_HEAD}{name} = \"{value}\"{NOTE_TAIL}")
}

/// The set-up values the notes among `diags` name (`AXIS_HORI = "Z"`), sorted, once each,
/// as one text; `None` for none.
pub fn assumed_in<'a>(diags: impl Iterator<Item = &'a crate::diag::Diagnostic>) -> Option<String> {
    let mut parts: Vec<&str> = diags
        .filter(|d| d.code == ASSUMED && d.severity == crate::diag::Severity::Note)
        .filter_map(|d| d.message.strip_prefix(NOTE_HEAD)?.strip_suffix(NOTE_TAIL))
        .collect();
    parts.sort_unstable();
    parts.dedup();
    (!parts.is_empty()).then(|| parts.join(", "))
}

/// Both lists of assumed values as one (`Excluded::add`).
pub fn joined(a: Option<String>, b: Option<String>) -> Option<String> {
    match (a, b) {
        (Some(x), Some(y)) if x != y => {
            let mut parts: Vec<&str> = x.split(", ").chain(y.split(", ")).collect();
            parts.sort_unstable();
            parts.dedup();
            Some(parts.join(", "))
        }
        (x, y) => x.or(y),
    }
}

/// `{ AXIS_HORI = "Z" }`: Siemens names (letters, digits, `_`, not starting with a digit)
/// to non-empty texts of at most 200 characters (the longest Siemens STRING). Names are
/// upper-cased, as the reader spells every name.
pub fn table(key: &str, v: &toml::Value) -> Result<BTreeMap<String, String>, String> {
    let t = v.as_table().ok_or_else(|| format!("{key}: expected a table of NAME = \"text\""))?;
    let mut out = BTreeMap::new();
    for (k, val) in t {
        let name = k.trim().to_ascii_uppercase();
        let good_name = name.bytes().next().is_some_and(|b| b.is_ascii_alphabetic() || b == b'_')
            && name.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_');
        if !good_name {
            return Err(format!("{key}.{k}: not a Siemens variable name (letters, digits and _)"));
        }
        match val.as_str() {
            Some(s) if !s.is_empty() && s.chars().count() <= 200 => {
                out.insert(name, s.to_string());
            }
            _ => {
                return Err(format!(
                    "{key}.{k}: expected a text like \"Z\" (a STRING value the set-up fixes; numbers are not taken)"
                ))
            }
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_checked_and_upper_cased() {
        let v: toml::Value = toml::from_str::<toml::Table>("t = { axis_hori = \"Z\" }").unwrap()["t"].clone();
        assert_eq!(table("variables.fixed", &v).unwrap().get("AXIS_HORI").map(String::as_str), Some("Z"));
        let bad: toml::Value = toml::from_str::<toml::Table>("t = { AXIS = 3 }").unwrap()["t"].clone();
        assert!(table("variables.fixed", &bad).unwrap_err().contains("expected a text"));
        let bad: toml::Value = toml::from_str::<toml::Table>("t = { \"1A\" = \"Z\" }").unwrap()["t"].clone();
        assert!(table("variables.fixed", &bad).is_err());
    }

    #[test]
    fn the_notes_give_the_assumed_values_once_each() {
        let note =
            |n: &str, v: &str| crate::diag::Diagnostic::new(crate::diag::Severity::Note, ASSUMED, note_message(n, v));
        let d = [note("AXIS_VER", "X"), note("AXIS_HORI", "Z"), note("AXIS_VER", "X")];
        assert_eq!(assumed_in(d.iter()).as_deref(), Some("AXIS_HORI = \"Z\", AXIS_VER = \"X\""));
        assert_eq!(assumed_in(d[..0].iter()), None);
        let (a, b) = (Some("A = \"X\"".to_string()), Some("B = \"Z\"".to_string()));
        assert_eq!(joined(a, b).as_deref(), Some("A = \"X\", B = \"Z\""));
    }
}
