//! `nctrans check` of a Siemens program against a FANUC one: the FANUC commons that hold the
//! Siemens side's global user data start where the translation's proof starts them
//! (`translate::to_fanuc::gud_seed_inputs`), at the `.DEF` start values. Which commons those
//! are is what a translation of the Siemens side places them in: the FANUC program's own
//! header (`(NCTRANS: DEPTH [global user data] = #600)`), then the `--map` rules, then
//! `[variables] to_fanuc` of nctrans.toml.

use nctrans::dialect::{Dialect, ParseOptions, Semantics};
use nctrans::eval::Input;
use nctrans::ir::Unit;
use nctrans::lower::to_fanuc::varmap::{self, VarRule};
use nctrans::span::SourceDb;
use nctrans::translate::to_fanuc::{self, SymbolMap};
use std::path::Path;

/// What the FANUC side starts with, and the words the verdict says it in.
pub struct Seeded {
    pub inputs: Vec<Input>,
    pub said: String,
    /// The translation the homes were read from has errors other than NC504 (data without
    /// a home): what it marked may hang on blocks a streamed side leaves out.
    pub doubtful: bool,
}

impl Seeded {
    /// Adds the seeds to a FANUC run's inputs; an input the run sets itself (its `nctrans:
    /// set` header, `--set`) wins, as the run's own inputs win in the proof, and the verdict
    /// names it.
    pub fn give(&mut self, inputs: &mut Vec<Input>) {
        let mut own = Vec::new();
        for i in &self.inputs {
            match inputs.iter().find(|h| h.target == i.target) {
                Some(h) => own.push(h.text.clone()),
                None => inputs.push(i.clone()),
            }
        }
        if !own.is_empty() {
            self.said.push_str(&format!(" (but the FANUC run's own inputs set {})", own.join(" ")));
        }
    }
}

/// The seeding of the FANUC side (its text `fanuc_text`) against the Siemens `siemens` (read
/// from `path` with `sem`, which holds the library's global user data); `map_rules` are the
/// `--map` file's rules. `None` when there is no global user data or none has a FANUC home.
pub fn seeding(siemens: &Unit, path: &Path, sem: &Semantics, fanuc_text: &str, map_rules: &[String]) -> Option<Seeded> {
    if sem.globals.is_empty() {
        return None;
    }
    let config = crate::cli::profile::project().ok()?;
    let mut opts = crate::cli::translate::job::fanuc_options(&config, path, nctrans::read::LineEnding::Lf).ok()?;
    // The first rule that covers a variable places it: what the FANUC program says it uses first.
    let mut rules: Vec<VarRule> =
        to_fanuc::gud_homes_in(fanuc_text).into_iter().map(|(name, number)| VarRule::Name { name, number }).collect();
    for r in map_rules {
        rules.extend(varmap::parse_rules(r).ok()?);
    }
    rules.append(&mut opts.var_rules);
    opts.var_rules = rules;
    opts.source = sem.clone();
    let subs = callees(siemens, path, sem, config.l_numbers);
    let refs: Vec<&Unit> = subs.iter().collect();
    // The translation is made for its symbol map alone: where it put the global user data
    // and with which start values (its other refusals do not matter here).
    let t = to_fanuc::to_fanuc(siemens, &refs, &opts);
    // (Refused constructs are marked and translated again: their errors come back as warnings.)
    let doubtful = t.diags.iter().any(|d| (d.is_error() || nctrans::unfinished::is_marked(d)) && d.code != "NC504");
    let map = t.symbol_map;
    let seeds = to_fanuc::gud_seed_inputs(&map);
    if seeds.is_empty() {
        return None;
    }
    let inputs = seeds.iter().filter_map(|s| nctrans::eval::parse_input(s).ok()).collect();
    Some(Seeded { inputs, said: said(&map), doubtful })
}

/// `global user data started on FANUC as a translation's proof starts it: DEPTH #600=5, TAB
/// #700..#703`.
fn said(map: &SymbolMap) -> String {
    let mut parts = Vec::new();
    for m in map.vars.iter().filter(|m| m.program.is_none() && m.source.ends_with("global user data)")) {
        let name: String = m.source.chars().take_while(|c| c.is_ascii_alphanumeric() || *c == '_').collect();
        let size = map
            .globals
            .iter()
            .flat_map(|d| &d.vars)
            .find(|v| v.name == name)
            .map_or(1, |v| v.dims.iter().fold(1u64, |a, d| a.saturating_mul(*d as u64)));
        let start = map.gud_seeds.iter().find(|(n, _)| *n == m.number).map_or(0.0, |s| s.1);
        parts.push(match size {
            1 => format!("{name} #{}={start}", m.number),
            n => format!("{name} #{}..#{}", m.number, m.number as u64 + n - 1),
        });
    }
    format!(
        "global user data started on FANUC at its definitions' values, as a translation's proof starts it: {}",
        parts.join(", ")
    )
}

/// The subprograms `main` calls found beside it, transitively, read quietly (they were not
/// asked for: a callee that does not read is left out of the map's translation).
fn callees(main: &Unit, path: &Path, sem: &Semantics, l_numbers: bool) -> Vec<Unit> {
    use crate::cli::translate::job;
    let mut db = SourceDb::new();
    let popts = ParseOptions { semantics: sem.clone() };
    let l_names = job::l_names_beside(path, l_numbers);
    let found = job::callees::<()>(main, &l_names, |callee| {
        let Some(file) = job::find_beside(path, callee) else { return Ok(None) };
        let Ok(bytes) = std::fs::read(&file) else { return Ok(None) };
        let l = nctrans::load(&mut db, &file.display().to_string(), &bytes, None);
        let mut p = nctrans::parse(&db, l.file, Dialect::Sinumerik, &popts);
        if nctrans::diag::has_errors(&p.diags) {
            return Ok(None);
        }
        nctrans::dialect::sinumerik::name_after_file(&mut p.unit, callee);
        Ok(Some(p.unit))
    });
    found.unwrap_or_default()
}

/// The lines of a streamed FANUC file that can name homes of global user data (those
/// [`to_fanuc::gud_homes_in`] reads: it reads each line alone), read line by line: for
/// [`seeding`], which then sees what it sees in the whole text.
pub fn home_lines(path: &Path) -> Result<String, String> {
    use nctrans::stream::lines::Lines;
    let (input, _) = nctrans::stream::open(path).map_err(|e| e.to_string())?;
    let mut lines = Lines::new(input).map_err(|e| e.to_string())?;
    let mut out = String::new();
    while let Some(l) = lines.next_line().map_err(|e| e.to_string())? {
        if l.text.contains("global user data]") {
            out.push_str(l.text);
            out.push('\n');
        }
    }
    Ok(out)
}
