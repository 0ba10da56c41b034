//! A tool map for a Sinumerik program's named tools (`T="NAME"`), numbered 1, 2, … in the
//! order they first appear, as the translation tests give `--tool-map`.

use std::collections::BTreeMap;

/// Each tool name of `src` with its number.
pub fn tool_map(src: &str) -> BTreeMap<String, u32> {
    let mut m = BTreeMap::new();
    for part in src.replace("t=\"", "T=\"").split("T=\"").skip(1) {
        if let Some(name) = part.split('"').next() {
            let n = m.len() as u32 + 1;
            m.entry(name.to_string()).or_insert(n);
        }
    }
    m
}
