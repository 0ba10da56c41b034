//! `nctrans check A B --tool-map NAME=n --map nctrans-map.toml`: the names a translation
//! used, so a Siemens program and its FANUC translation can be checked again later exactly
//! as the translation was verified (tool names read as their T numbers, a `MSG` the
//! translation wrote as a comment left out, mapped R parameters starting at 0 on FANUC).

use nctrans::dialect::Dialect;
use nctrans::ir::Unit;
use nctrans::translate::{self, SymbolMap};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The flags of `check` that name a translation's maps.
#[derive(clap::Args)]
pub struct MapOpts {
    /// Compare as the translation to FANUC was verified, with this tool name → T number
    /// (NAME=n, repeatable; wins over --map and nctrans.toml [tools]).
    #[arg(long = "tool-map", value_name = "NAME=N")]
    pub tool_map: Vec<String>,
    /// Compare as a translation that used this map (nctrans-map.toml of a batch): its tools
    /// and the variables R parameters went to.
    #[arg(long, value_name = "FILE")]
    pub map: Option<PathBuf>,
}

/// The translation's names, when a map was asked for (`None`: a plain check).
pub struct Names {
    tools: BTreeMap<String, u32>,
    /// FANUC variables R parameters were mapped to (`R1` → 501).
    r_vars: Vec<u32>,
}

impl MapOpts {
    /// Reads the maps: `./nctrans.toml` `[tools]` (as a translation reads it), then `--map`,
    /// then `--tool-map`. `None` when neither flag is given.
    pub fn names(&self) -> Result<Option<Names>, String> {
        if self.tool_map.is_empty() && self.map.is_none() {
            return Ok(None);
        }
        let mut tools = BTreeMap::new();
        let project = Path::new(nctrans::config::FILE_NAME);
        if project.is_file() {
            tools.extend(nctrans::config::Config::load(project)?.tools);
        }
        let mut r_vars = Vec::new();
        if let Some(p) = &self.map {
            let text = std::fs::read_to_string(p).map_err(|e| format!("cannot read {}: {e}", p.display()))?;
            let (maps, target) = nctrans::batch::maps::from_toml(&text).map_err(|e| format!("{}: {e}", p.display()))?;
            if target == Some(Dialect::Sinumerik) {
                return Err(format!(
                    "{}: this map is of a translation to Sinumerik; tool names are mapped only to FANUC",
                    p.display()
                ));
            }
            tools.extend(maps.tools);
            for (source, target) in &maps.variables {
                let is_r = source.strip_prefix('R').is_some_and(|n| n.parse::<u32>().is_ok());
                if let (true, Some(n)) = (is_r, target.strip_prefix('#').and_then(|n| n.parse().ok())) {
                    r_vars.push(n);
                }
            }
        }
        for m in &self.tool_map {
            let (name, n) = m.split_once('=').ok_or_else(|| format!("--tool-map '{m}': expected NAME=N"))?;
            let n: u32 = n.trim().parse().map_err(|_| format!("--tool-map '{m}': expected a T number after ="))?;
            tools.insert(name.trim().to_string(), n);
        }
        Ok(Some(Names { tools, r_vars }))
    }
}

impl Names {
    /// A Siemens side compared with a FANUC one: aligned as the translation's verification
    /// aligns it (`translate::align_source`).
    pub fn align(&self, unit: &Unit) -> Unit {
        let map = SymbolMap { tools: self.tools.clone(), ..SymbolMap::default() };
        translate::align_source(unit, &map)
    }

    /// A FANUC side compared with a Siemens one: the variables mapped R parameters went to
    /// start at 0, as R parameters do (unless the run's inputs set them).
    pub fn fanuc_inputs(&self, inputs: &mut Vec<nctrans::eval::Input>) {
        for n in &self.r_vars {
            if let Ok(i) = nctrans::eval::parse_input(&format!("#{n}=0")) {
                if !inputs.iter().any(|h| h.target == i.target) {
                    inputs.push(i);
                }
            }
        }
    }
}
