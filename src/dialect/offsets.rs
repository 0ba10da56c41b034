//! The tool offset map of a machine set-up: which FANUC registers (H, D) hold each Siemens
//! cutting edge's length and radius (`[offsets]` in nctrans.toml, `--offset-map`). A fact
//! of the set-up both compensation translations (`lower::comp_flow`) and the configuration
//! read, kept with the other dialect facts (`Semantics::offsets`).

use std::collections::BTreeMap;

/// A Siemens edge: (tool number, edge number).
pub type Edge = (u32, u32);
/// The FANUC registers of an edge: (H, D).
pub type Registers = (u32, u32);

/// The FANUC registers (H, D) of each Siemens edge (tool number, edge), beyond the default
/// (edge 1 of tool n: H n, D n).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct OffsetMap {
    pub edges: BTreeMap<Edge, Registers>,
}

impl OffsetMap {
    /// The (H, D) registers of edge `edge` of tool `tool`.
    pub fn registers(&self, tool: u32, edge: u32) -> Option<(u32, u32)> {
        match self.edges.get(&(tool, edge)) {
            Some(&r) => Some(r),
            None if edge == 1 && !self.edges.keys().any(|&(t, _)| t == tool) => Some((tool, tool)),
            None if edge == 1 => None,
            None => None,
        }
    }

    /// The edge of `tool` whose length register is `h`.
    pub fn edge_of_h(&self, tool: u32, h: u32) -> Option<u32> {
        (1..=99).find(|&e| self.registers(tool, e).is_some_and(|r| r.0 == h))
    }

    /// Parses an `[offsets]` line `"6.2" = "H26,D46"` (key and value).
    pub fn parse_entry(key: &str, value: &str) -> Result<(Edge, Registers), String> {
        let bad = || format!("bad offset map entry '{key}={value}' (expected like '6.2=H26,D46')");
        let (t, e) = key.trim().trim_matches('"').split_once('.').ok_or_else(bad)?;
        let (t, e): (u32, u32) = (t.trim().parse().map_err(|_| bad())?, e.trim().parse().map_err(|_| bad())?);
        let mut h = None;
        let mut d = None;
        for part in value.trim().trim_matches('"').split(',') {
            let part = part.trim();
            let n = |p: &str| p[1..].trim().parse::<u32>().map_err(|_| bad());
            match part.as_bytes().first() {
                Some(b'H' | b'h') => h = Some(n(part)?),
                Some(b'D' | b'd') => d = Some(n(part)?),
                _ => return Err(bad()),
            }
        }
        if e == 0 {
            return Err(format!("offset map entry '{key}': edge 0 is D0, no compensation"));
        }
        Ok(((t, e), (h.ok_or_else(bad)?, d.ok_or_else(bad)?)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_mapping_is_edge_1_of_tool_n_and_a_configured_tool_uses_its_own() {
        let mut m = OffsetMap::default();
        assert_eq!(m.registers(6, 1), Some((6, 6)));
        assert_eq!(m.registers(6, 2), None);
        assert_eq!(m.edge_of_h(6, 6), Some(1));
        assert_eq!(m.edge_of_h(6, 7), None);
        let (k, v) = OffsetMap::parse_entry("6.2", "H26,D46").unwrap();
        m.edges.insert(k, v);
        assert_eq!(m.registers(6, 2), Some((26, 46)));
        assert_eq!(m.registers(6, 1), None, "a tool in the map has only the edges given");
        assert_eq!(m.edge_of_h(6, 26), Some(2));
        assert!(OffsetMap::parse_entry("6", "H1,D1").is_err());
        assert!(OffsetMap::parse_entry("6.0", "H1,D1").is_err());
    }
}
