//! The map tables of `nctrans.toml` that a batch's map file (`batch::maps`) reads too:
//! program names to numbers (`[programs]`), tool names to T numbers (`[tools]`), and lists
//! of rule strings; each error names the key it came from.

use crate::dialect::Dialect;
use crate::translate::library::ProgKey;
use std::collections::BTreeMap;

/// `[programs]`: `"CONTOUR" = "O9000"` or `= 9000` (to FANUC), `"O9010" = "PROBE_X"` (to
/// Sinumerik). With a known target the keys are read as that direction's source names.
pub fn program_table(
    value: &toml::Value,
    what: &str,
    dialect: Option<Dialect>,
) -> Result<BTreeMap<ProgKey, ProgKey>, String> {
    let t = value.as_table().ok_or_else(|| format!("{what}: expected a table of \"NAME\" = \"O9000\""))?;
    let mut out = BTreeMap::new();
    for (k, v) in t {
        let target = match v {
            toml::Value::Integer(n) if (1..=99_999_999).contains(n) => ProgKey::Number(*n as u32),
            toml::Value::String(s) if !s.trim().is_empty() => ProgKey::parse(s),
            _ => {
                return Err(format!(
                    "{what}.{k}: expected an O number (9000 or \"O9000\") or a Siemens program name (\"PROBE_X\")"
                ))
            }
        };
        if let ProgKey::Name(n) = &target {
            if !n.starts_with(|c: char| c.is_ascii_alphabetic())
                || !n.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
            {
                return Err(format!(
                    "{what}.{k}: '{n}' is not a Siemens program name (letters, digits and _, starting with a letter)"
                ));
            }
        }
        let key = match (dialect, ProgKey::parse(k)) {
            (Some(Dialect::Fanuc), _) => ProgKey::Name(k.trim().to_ascii_uppercase()),
            (Some(Dialect::Sinumerik), key @ ProgKey::Number(_)) => key,
            (Some(Dialect::Sinumerik), _) => {
                return Err(format!("{what}.{k}: a FANUC program is named by its O number (\"O9010\" or \"9010\")"))
            }
            (None, key) => key,
        };
        out.insert(key, target);
    }
    Ok(out)
}

/// `[tools]`: `"DRILL_5" = 12`.
pub fn tool_table(value: &toml::Value, what: &str) -> Result<BTreeMap<String, u32>, String> {
    let t = value.as_table().ok_or_else(|| format!("{what}: expected a table of \"TOOL NAME\" = T number"))?;
    let mut out = BTreeMap::new();
    for (k, v) in t {
        match v.as_integer() {
            Some(n) if (0..=99_999_999).contains(&n) => {
                out.insert(k.clone(), n as u32);
            }
            _ => return Err(format!("{what}.{k}: expected a T number from 0 to 99999999")),
        }
    }
    Ok(out)
}

/// A list of strings.
pub fn string_list(value: &toml::Value, what: &str) -> Result<Vec<String>, String> {
    let a = value.as_array().ok_or_else(|| format!("{what}: expected a list of strings like [\"R0-R99=#100\"]"))?;
    a.iter()
        .map(|v| v.as_str().map(str::to_string).ok_or_else(|| format!("{what}: every entry must be a string")))
        .collect()
}
