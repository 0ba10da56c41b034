//! The inputs of a translation to FANUC's proof in FANUC names: a check's `--set` and the
//! source's `nctrans: set` header lines, which the written program carries as its own.

use super::SymbolMap;
use crate::dialect::{Dialect, Semantics};
use crate::ir::{Param, Stmt, StmtKind, Unit};
use crate::lower::to_fanuc as passes;

/// The main program's `nctrans: set` header lines in the FANUC names the translation gave
/// the variables (`R1=5` → `#501=5`), so `run` and `check` of the output start where the
/// source's do; a line left with nothing the output can take is dropped.
pub(super) fn map_set_lines(body: &mut Vec<Stmt>, map: &SymbolMap) {
    let mut i = 0;
    while let Some(StmtKind::Block(b)) = body.get_mut(i).map(|s| &mut s.kind) {
        if !b.items.is_empty() || b.meta.number.is_some() || b.meta.label.is_some() {
            break;
        }
        let mut emptied = false;
        for c in &mut b.meta.comments {
            let Some(rest) = c.text.trim().strip_prefix("nctrans: set") else { continue };
            let words: Vec<String> = rest.split_whitespace().map(str::to_string).collect();
            let mapped = fanuc_set_inputs(&super::proof_sets(&words, map).0, map);
            emptied |= mapped.is_empty();
            c.text = format!("nctrans: set {}", mapped.join(" "));
        }
        if emptied {
            b.meta.comments.retain(|c| c.text.trim() != "nctrans: set");
            if b.meta.comments.is_empty() {
                body.remove(i);
                continue;
            }
        }
        i += 1;
    }
}

/// The FANUC side's inputs for a check's `--set` inputs of the Siemens side: `#n=…` as given;
/// `Rn=…` (and a main program's DEF variable, and scalar global user data: `DEPTH=…`)
/// into the variable the translation put it in;
/// `$TC_DP3/6/12/15[t,d]=…` into the tool compensation memory C register the translation
/// reads for that edge (`#11000+H`, `#10000+H`, `#13000+D`, `#12000+D` through the offset map,
/// as `lower::to_fanuc::tool_data`); a machine signal `$A_DBB[2]=…` into the FANUC interface
/// signal `[signals]` wires it to. Others (no counterpart) stay on the Siemens side only.
pub fn fanuc_set_inputs(set: &[String], map: &SymbolMap) -> Vec<String> {
    use crate::eval::tool_data::{fanuc_var, siemens_field, tc_dp};
    let mut out = Vec::new();
    for s in set {
        let Some((lhs, rhs)) = s.split_once('=') else { continue };
        let (lhs, rhs) = (lhs.trim(), rhs.trim());
        if lhs.starts_with('#') {
            out.push(s.clone());
        } else if let Ok(sig) = crate::dialect::signals::Signal::parse(lhs) {
            // The variable the wiring gives it; a value it cannot hold is refused by the run.
            if let Some(f) = map.signals.fanuc_of(sig) {
                out.push(format!("{}={rhs}", f.key()));
            }
        } else if let Some(sys) = lhs.strip_prefix('$') {
            let Some((name, idx)) = sys.split_once('[') else { continue };
            let Some(field) = tc_dp(&name.to_ascii_uppercase()).and_then(siemens_field) else { continue };
            let idx: Vec<Option<u32>> =
                idx.trim_end_matches(']').split(',').map(|x| x.trim().parse::<u32>().ok()).collect();
            let [Some(t), Some(d)] = idx.as_slice() else { continue };
            let Some((h, dr)) = map.offsets.registers(*t, *d).filter(|_| !map.haas) else { continue };
            let reg = if field.is_length() { h } else { dr };
            out.push(format!("#{}={rhs}", fanuc_var(field, reg)));
        } else if let Some(n) = map.fanuc_var(lhs).or_else(|| gud_var(map, lhs)) {
            out.push(format!("#{n}={rhs}"));
        }
    }
    out
}

/// `#n=v` for every common variable global user data went to, at its definition's start
/// value: where the FANUC side of a run against the Siemens source starts them (the Siemens
/// side declares them at those values). The one rule of the translation's proof, the batch's
/// and `nctrans check` ([`gud_homes_in`]).
pub fn gud_seed_inputs(map: &SymbolMap) -> Vec<String> {
    map.gud_seeds.iter().map(|(n, v)| format!("#{n}={v}")).collect()
}

/// The homes a FANUC translation's header gives global user data (`(NCTRANS: DEPTH [global
/// user data] = #600)`, `(NCTRANS: TAB[…] [4 elements, global user data] = #700)`, as
/// `header` writes them): each name with its first common variable.
pub fn gud_homes_in(fanuc_text: &str) -> Vec<(String, u32)> {
    let mut out = Vec::new();
    for line in fanuc_text.lines() {
        let Some(rest) = line.trim().strip_prefix('(').and_then(|l| l.strip_suffix(')')) else { continue };
        let Some(rest) = rest.strip_prefix(super::KEEP_PREFIX).and_then(|r| r.strip_prefix(": ")) else { continue };
        let Some((source, number)) = rest.rsplit_once(" = #") else { continue };
        if !source.ends_with("global user data]") {
            continue;
        }
        let name: String = source.chars().take_while(|c| c.is_ascii_alphanumeric() || *c == '_').collect();
        if let (false, Ok(n)) = (name.is_empty(), number.trim().parse()) {
            out.push((name, n));
        }
    }
    out
}

/// The common variable scalar global user data `lhs` (`DEPTH`) went to (a run's inputs set
/// no array element).
fn gud_var(map: &SymbolMap, lhs: &str) -> Option<u32> {
    let name = lhs.trim().to_ascii_uppercase();
    let scalar = map.globals.iter().flat_map(|d| &d.vars).any(|v| v.name == name && v.dims.is_empty());
    let home = map.vars.iter().find(|m| m.program.is_none() && m.source == format!("{name} (global user data)"));
    home.filter(|_| scalar).map(|m| m.number)
}

/// The Siemens side's profile with the set-up values the translation assumed
/// (`[variables] fixed`), so its run rests on them as the output does.
pub(super) fn with_fixed(s: Option<crate::dialect::Semantics>, map: &SymbolMap) -> Option<crate::dialect::Semantics> {
    if map.fixed.is_empty() {
        return s;
    }
    let mut s = s.unwrap_or_else(|| crate::dialect::Semantics::default_for(crate::dialect::Dialect::Sinumerik));
    let mut fixed = (*s.fixed).clone();
    fixed.extend(map.fixed.clone());
    s.fixed = std::sync::Arc::new(fixed);
    Some(s)
}

/// The FANUC inputs of a subprogram run on its own, as the evaluator runs the Siemens one:
/// parameters are 0 (the G65 argument locals would be vacant); VAR parameters as
/// [`var_param_inputs`] gives them. (The generic proof's inputs; [`verify`] builds the same
/// per run.)
pub fn standalone_args(main: &Unit, map: &SymbolMap) -> Vec<crate::eval::Input> {
    let Some(p) = main.programs.first() else { return vec![] };
    let letters = passes::words::param_letters(p.params.len()).unwrap_or_default();
    let mut texts: Vec<String> =
        p.params.iter().zip(letters).filter(|(prm, _)| !prm.by_ref).map(|(_, (_, var))| format!("#{var}=0")).collect();
    texts.extend(var_param_inputs(&p.params, map));
    texts.iter().filter_map(|t| crate::eval::parse_input(t).ok()).collect()
}

/// `#n=v` for every common variable global user data went to: the FANUC side's inputs,
/// so it starts where the Siemens side's definitions start.
pub fn gud_inputs(t: &crate::translate::Translation) -> Vec<crate::eval::Input> {
    gud_seed_inputs(t.symbols.fanuc()).iter().filter_map(|s| crate::eval::parse_input(s).ok()).collect()
}

/// For a subprogram run on its own: each VAR parameter, which holds the number of its
/// caller's variable, gets a free common variable (from #999 down, past every number the
/// translation uses) that starts at 0, as the Siemens parameter then does.
pub fn var_param_inputs(params: &[Param], map: &SymbolMap) -> Vec<String> {
    let letters = passes::words::param_letters(params.len()).unwrap_or_default();
    let used: std::collections::BTreeSet<u32> = map.vars.iter().map(|m| m.number).collect();
    let mut next = 999u32;
    let mut texts = Vec::new();
    for (prm, (_, var)) in params.iter().zip(letters).filter(|(p, _)| p.by_ref) {
        let size = crate::ir::elements(&prm.dims);
        // An array larger than the commons below `next` has no home to give: no inputs (the
        // run then reads past them and says so).
        if size > next {
            break;
        }
        while next >= 500 + size && (next + 1 - size..=next).any(|k| used.contains(&k)) {
            next -= 1;
        }
        let base = next + 1 - size;
        texts.push(format!("#{var}={base}"));
        texts.extend((base..=next).map(|k| format!("#{k}=0")));
        next = base.saturating_sub(1);
    }
    texts
}

/// `#n=0` for each R parameter the translation maps: the FANUC side's inputs when it is
/// compared with the Siemens program, whose R parameters start at 0 (FANUC's would be vacant).
pub fn r_param_inputs(map: &SymbolMap) -> Vec<crate::eval::Input> {
    r_param_homes(map).iter().filter_map(|s| crate::eval::parse_input(s).ok()).collect()
}

/// What every FANUC side of a proof against the Siemens source starts with before its own
/// inputs: the mapped R parameters at 0 ([`r_param_homes`]), the commons of global user data
/// at their definitions' values ([`gud_seed_inputs`]).
pub fn proof_homes(map: &SymbolMap) -> Vec<String> {
    let mut out = r_param_homes(map);
    out.extend(gud_seed_inputs(map));
    out
}

/// [`r_param_inputs`] as `--set` texts (`#501=0`).
pub fn r_param_homes(map: &SymbolMap) -> Vec<String> {
    map.vars
        .iter()
        .filter(|m| m.program.is_none() && m.source.starts_with('R') && !m.source.contains('['))
        .map(|m| format!("#{}=0", m.number))
        .collect()
}

/// The Siemens side's profile of a proof against the translation (`base`: its profile with
/// the global user data): GETT("NAME") returns what the tool map says, as T="NAME" is
/// aligned, and the set-up values the translation assumed hold. The whole path's proof and
/// the streamed one ([`main_proof`]) alike.
pub fn proof_source(base: Option<Semantics>, map: &SymbolMap) -> Option<Semantics> {
    let sinumerik = match base {
        _ if map.tools.is_empty() => base,
        s => {
            let mut s = s.unwrap_or_else(|| Semantics::default_for(Dialect::Sinumerik));
            s.tools = std::sync::Arc::new(map.tools.clone());
            Some(s)
        }
    };
    with_fixed(sinumerik, map)
}

/// What the proof of a main program without parameters runs with, for a streamed
/// translation as [`super::verify`] has it for the whole one.
pub struct MainProof {
    /// The Siemens side's profile: the default one with the global user data the map holds
    /// ([`proof_source`]).
    pub source: Option<Semantics>,
    /// The FANUC side's (read back and run): what the output was written for, a Haas NGC's
    /// variables among it ([`super::target_semantics`]).
    pub target: Option<Semantics>,
    /// The source's `nctrans: set` header lines.
    pub source_inputs: Vec<crate::eval::Input>,
    /// [`proof_homes`], then those lines in the output's names.
    pub target_inputs: Vec<crate::eval::Input>,
}

/// The [`MainProof`] of a translation with the symbol map `map` of a source whose header
/// lines are `header`.
pub fn main_proof(map: &SymbolMap, header: &str) -> MainProof {
    let sets: Vec<String> =
        crate::eval::input::header_words(header, "nctrans: set", false).map(str::to_string).collect();
    let sets = super::proof_sets(&sets, map).0;
    let mut b_in = proof_homes(map);
    b_in.extend(fanuc_set_inputs(&sets, map));
    let parse_all = |v: &[String]| v.iter().filter_map(|s| crate::eval::parse_input(s).ok()).collect::<Vec<_>>();
    MainProof {
        source: proof_source(super::with_globals(None, map), map),
        target: super::target_semantics(None, map),
        source_inputs: parse_all(&sets),
        target_inputs: parse_all(&b_in),
    }
}
