//! The runs that prove a FANUC → Sinumerik translation's called programs on their own, one
//! rule for every path (the batch job, `nctrans --to sinumerik` whole and streamed): a
//! macro is written for every possible caller (`translate_sinumerik::Options::
//! specialise_callers` off), so it is run with the arguments its callers pass and again with
//! each of those arguments left vacant, where its vacancy logic (a default, an alarm) must
//! be right for a caller added later.

use crate::check::{CheckReport, Excluded, Verdict};
use crate::diag::Diagnostic;
use crate::dialect::Dialect;
use crate::eval::calls::{CalleeName, CalleeSource};
use crate::eval::{self, Input as RunInput};
use crate::ir::{CallKind, ProgName, Unit};
use crate::span::{FileId, SourceDb};
use crate::translate::library::{self, Library, ProgKey};
use crate::translate::to_sinumerik::verify::{self as vs, Profiles, RunSpec};
use crate::translate::to_sinumerik::{OutFile, Translation};
use crate::translate::InLibrary;
use std::collections::BTreeSet;

/// The runs that prove a program alone: without inputs, and once per constant argument
/// vector the library calls it with. A macro (called by G65/G66) is not run without its
/// arguments: its callers always give some. With no constant call in the library it runs
/// once with 0 for the arguments the first call gives surely. With `each_vacant` (a macro
/// written for every possible caller, not `--specialise-callers`) it also runs with each of
/// those arguments left out in turn: a caller added later may leave any one out, and the
/// macro's vacancy logic (a default, an alarm) must be right for it.
/// Each case is a label for the verdict and the `#n=value` inputs of the FANUC side.
pub fn cases(lib: &Library, key: &ProgKey, each_vacant: bool) -> Vec<(String, Vec<String>)> {
    let macro_calls: Vec<_> =
        lib.calls.iter().filter(|c| &c.target == key && matches!(c.kind, CallKind::G65 | CallKind::G66)).collect();
    let mut out: Vec<(String, Vec<String>)> = Vec::new();
    if macro_calls.is_empty() {
        out.push((String::new(), vec![]));
    }
    for (k, v) in lib.arg_vectors(key).iter().enumerate() {
        // A letter written twice for one local (`I-3. I4. D5.` fill #7 twice): the later
        // one is what the macro gets, and the one input to give.
        let mut sets: Vec<String> = Vec::new();
        for (i, a) in v.iter().enumerate() {
            if !v[i + 1..].iter().any(|b| b.var == a.var) {
                sets.push(a.to_set());
            }
        }
        out.push((format!(" (with the arguments of call site {})", k + 1), sets));
    }
    if out.is_empty() {
        if let Some(c) = macro_calls.first() {
            let sets = c.given.iter().filter(|g| g.sure).map(|g| format!("#{}=0.", g.var)).collect();
            out.push((" (with 0 for the arguments of its first call)".to_string(), sets));
        }
    }
    if each_vacant && !macro_calls.is_empty() {
        let mut seen: BTreeSet<Vec<String>> = out.iter().map(|(_, v)| v.clone()).collect();
        for (label, sets) in out.clone() {
            for (k, s) in sets.iter().enumerate() {
                let mut fewer = sets.clone();
                fewer.remove(k);
                if seen.insert(fewer.clone()) {
                    let var = s.split_once('=').map_or(s.as_str(), |x| x.0);
                    let base = label.strip_suffix(')').unwrap_or(&label);
                    out.push((format!("{base} but {var} vacant)"), fewer));
                }
            }
        }
    }
    out
}

/// What every run of a proof shares.
pub struct RunSettings<'a> {
    /// The folder the Siemens files are shown in.
    pub out_dir: &'a str,
    pub max_steps: u64,
    pub profiles: &'a Profiles,
    /// Inputs given to every run (`--set`): FANUC `#n=…` ones are mapped for the Siemens side.
    pub set: &'a [String],
}

/// Runs the first program of the FANUC `unit` (file `fanuc_file` in `db`) against its
/// translation `out` once per case (`cases`), each run's FANUC callees from `callees`.
/// `name` goes in front of each case's label.
#[allow(clippy::too_many_arguments)]
pub fn case_runs(
    db: &SourceDb,
    fanuc_file: FileId,
    unit: &Unit,
    tr: &Translation,
    out: &OutFile,
    (name, cases): (&str, Vec<(String, Vec<String>)>),
    settings: &RunSettings,
    callees: &dyn Fn() -> Box<dyn CalleeSource + Send>,
) -> Vec<(String, CheckReport)> {
    let mut runs = Vec::new();
    for (label, mut fanuc) in cases {
        fanuc.extend(settings.set.iter().cloned());
        let siemens = siemens_inputs(tr, &out.program, &fanuc);
        fanuc.retain(|s| s.trim_start().starts_with('#'));
        let spec = RunSpec {
            main: out,
            out_dir: settings.out_dir,
            max_steps: settings.max_steps,
            profiles: settings.profiles,
            fanuc_callees: callees(),
            extra_fanuc: parse_all(&fanuc),
            extra_siemens: parse_all(&siemens),
        };
        runs.push((format!("{name}{label}"), vs::verify_run(db, fanuc_file, unit, tr, spec)));
    }
    runs
}

/// The runs of a single file's translation beyond its main program's: every program the
/// FANUC `units` (the file, then the callees found beside it) call by G65/G66, run alone as
/// a main program with the cases of [`cases`] (the calls among `units` are the library),
/// its FANUC callees served from `units`. The labels name the program
/// (` (O_9100 alone, with the arguments of call site 1 but #11 vacant)`).
pub fn called_runs(
    db: &SourceDb,
    units: &[&Unit],
    tr: &Translation,
    settings: &RunSettings,
    each_vacant: bool,
) -> Vec<(String, CheckReport)> {
    let scans = units.iter().map(|u| library::scan_unit(u, db.get(u.file), "")).collect::<Vec<library::Scan>>();
    let lib = Library::build(scans);
    let mut targets: Vec<u32> = Vec::new();
    for c in lib.calls.iter().filter(|c| matches!(c.kind, CallKind::G65 | CallKind::G66)) {
        if let ProgKey::Number(n) = c.target {
            if !targets.contains(&n) {
                targets.push(n);
            }
        }
    }
    let all: Vec<Unit> = units.iter().map(|u| (*u).clone()).collect();
    let mut runs = Vec::new();
    for n in targets {
        let here = units
            .iter()
            .find_map(|u| u.programs.iter().position(|p| p.name == Some(ProgName::Number(n))).map(|i| (*u, i)));
        let (Some((u, i)), Some(out)) = (here, tr.files.iter().find(|f| f.fanuc_number == Some(n))) else {
            // Not translated here (a call the translation reports) or not found.
            continue;
        };
        let mut unit = u.clone();
        let entry = unit.programs.remove(i);
        unit.programs.insert(0, entry);
        let served = || Box::new(MemCallees(all.clone())) as Box<dyn CalleeSource + Send>;
        let alone = Alone { db, file: u.file, unit: &unit, tr, out };
        runs.extend(macro_runs(&alone, &lib, &ProgKey::Number(n), settings, each_vacant, &served));
    }
    runs
}

/// A macro run alone as a main program: the FANUC `unit` (file `file` in `db`) with the
/// macro as its first program, and the macro's translation `out` in `tr`.
pub struct Alone<'a> {
    pub db: &'a SourceDb,
    pub file: FileId,
    pub unit: &'a Unit,
    pub tr: &'a Translation,
    pub out: &'a OutFile,
}

/// The runs of one macro (`key` in `lib`) alone (see [`Alone`]), with the cases of
/// [`cases`], each run's FANUC callees from `callees`; labelled by the program
/// (` (O_9100 alone, with the arguments of call site 1 but #11 vacant)`). Shared by the
/// single-file paths ([`called_runs`]) and the batch (a macro its own file calls).
///
/// The gate: the macro runs first with its callers' own arguments. Its translation may rest
/// on what the callers leave (their unit for values without a decimal point, common
/// variables they set), which a run alone does not have; where one of those runs is not
/// equivalent, none is kept and the callers' runs are the macro's proof, as before. Only a
/// macro that runs alone as it runs called is also run with each argument vacant.
pub fn macro_runs(
    alone: &Alone,
    lib: &Library,
    key: &ProgKey,
    settings: &RunSettings,
    each_vacant: bool,
    callees: &dyn Fn() -> Box<dyn CalleeSource + Send>,
) -> Vec<(String, CheckReport)> {
    let name = format!(" ({} alone,", alone.out.program);
    let label = |(label, sets): (String, Vec<String>)| {
        let label = match label.strip_prefix(" (") {
            Some(l) => format!(" {l}"),
            None => format!("{label})"),
        };
        (label, sets)
    };
    let mut all_cases = cases(lib, key, each_vacant).into_iter().map(label);
    let given: Vec<_> = all_cases.by_ref().take(cases(lib, key, false).len()).collect();
    let run =
        |cases| case_runs(alone.db, alone.file, alone.unit, alone.tr, alone.out, (&name, cases), settings, callees);
    let mut runs = run(given);
    if runs.iter().any(|(_, r)| !matches!(r.verdict, Verdict::Equivalent { .. })) {
        return Vec::new();
    }
    runs.extend(run(all_cases.collect()));
    runs
}

/// Several runs' verdicts as one: the first that is not an equivalence (with its label), or
/// the events and exclusions added up.
pub enum Combined {
    /// Every run equivalent: the events and what was left out, over `runs` runs.
    Equivalent { events: u64, runs: usize, excluded: Excluded },
    /// The first run that was not, with its label.
    Not(String, Box<CheckReport>),
}

/// Combines runs (see [`Combined`]).
pub fn combine(runs: Vec<(String, CheckReport)>) -> Combined {
    let (mut events, mut excluded, n) = (0, Excluded::default(), runs.len());
    for (label, r) in runs {
        match r.verdict {
            Verdict::Equivalent { events: e } => {
                events += e;
                excluded.add(r.excluded);
            }
            _ => return Combined::Not(label, Box::new(r)),
        }
    }
    Combined::Equivalent { events, runs: n, excluded }
}

impl Combined {
    /// `equivalent (N events)`, or `equivalent (N events in K runs)` for several.
    pub fn summary(events: u64, runs: usize, excluded: &Excluded) -> String {
        if runs > 1 {
            excluded.equivalent(&format!("{events} events in {runs} runs"))
        } else {
            excluded.equivalent(&format!("{events} events"))
        }
    }
}

/// Called programs served from memory: Siemens ones by name, FANUC ones by `O` number.
pub struct MemCallees(pub Vec<Unit>);

impl CalleeSource for MemCallees {
    fn find(
        &mut self,
        _db: &mut SourceDb,
        _caller: FileId,
        _dialect: Dialect,
        name: &CalleeName,
    ) -> Result<Option<Unit>, Diagnostic> {
        let found = match name {
            CalleeName::Name(n) => {
                let want = n.to_ascii_uppercase();
                self.0.iter().find(|u| unit_name(u).as_deref() == Some(want.as_str()))
            }
            CalleeName::Number(n) => {
                self.0.iter().find(|u| u.programs.iter().any(|p| p.name == Some(ProgName::Number(*n))))
            }
        };
        Ok(found.cloned())
    }
}

fn unit_name(u: &Unit) -> Option<String> {
    match u.programs.first().and_then(|p| p.name.as_ref()) {
        Some(ProgName::Name(n)) => Some(n.to_ascii_uppercase()),
        _ => None,
    }
}

/// The Siemens inputs for FANUC inputs `#n=value` of a run of `program`: each variable by
/// the symbol map, with its is-set flag (`#0` is value 0, flag 0). Variables the
/// translation does not use are left out.
pub fn siemens_inputs(tr: &Translation, program: &str, fanuc: &[String]) -> Vec<String> {
    let mut out = Vec::new();
    for s in fanuc {
        let Some((lhs, rhs)) = s.split_once('=') else { continue };
        let Some(n) = lhs.trim().strip_prefix('#').and_then(|n| n.parse::<u32>().ok()) else {
            // Not a FANUC variable: meant for the Siemens side as written.
            out.push(s.clone());
            continue;
        };
        let entry = match n {
            1..=33 => {
                let key = format!("#{n}");
                tr.symbols.sinumerik().vars.iter().find(|v| v.program.as_deref() == Some(program) && v.fanuc == key)
            }
            _ => tr.symbols.sinumerik().common(n),
        };
        let Some(e) = entry else { continue };
        let vacant = rhs.trim() == "#0";
        out.push(format!("{}={}", e.siemens, if vacant { "0" } else { rhs.trim() }));
        if let Some(f) = &e.flag {
            out.push(format!("{f}={}", u8::from(!vacant)));
        }
    }
    out
}

pub fn parse_all(v: &[String]) -> Vec<RunInput> {
    v.iter().filter_map(|s| eval::parse_input(s).ok()).collect()
}

/// The runs of the proof of a FANUC file of a library (`translate::verify` with
/// `VerifyOptions::library`): the file's first program against its translation, and each
/// other program the file does not call itself (a second main program, a macro only other
/// files call), each as the main program: with the inputs of the header lines and `--set`,
/// and once per argument vector the library calls it with. The programs the file calls run
/// where it calls them (and in their callers' jobs); a macro it calls by G65/G66 also runs
/// alone (`in_file_macro_runs`). `inputs` are the file's unit and its callees'.
pub fn library_runs(
    db: &SourceDb,
    inputs: &[&Unit],
    tr: &Translation,
    settings: &RunSettings,
    (lib, each_vacant): (&InLibrary, bool),
) -> Vec<(String, CheckReport)> {
    let (library, index, main) = (lib.library, lib.file, inputs[0]);
    let subs: Vec<Unit> = inputs[1..].iter().map(|u| (*u).clone()).collect();
    let served = || Box::new(MemCallees(subs.clone())) as Box<dyn CalleeSource + Send>;
    let mut runs = Vec::new();
    for (i, p) in main.programs.iter().enumerate() {
        let key = number_of(p).map(ProgKey::Number);
        let called_here = key.as_ref().is_some_and(|k| library.calls.iter().any(|c| c.file == index && &c.target == k));
        if i > 0 && called_here {
            continue;
        }
        let Some(out) = tr.files.iter().find(|f| f.source == main.file && first_of(f, p)) else {
            // A copy written by another file (see `duplicates`), verified there.
            continue;
        };
        let mut unit = main.clone();
        let entry = unit.programs.remove(i);
        unit.programs.insert(0, entry);
        let mine = key.filter(|k| library.programs.get(k).is_some_and(|d| d.file == index));
        let cases = match &mine {
            Some(k) => cases(library, k, each_vacant),
            None => vec![(String::new(), vec![])],
        };
        let name = if i > 0 { format!(" ({})", out.program) } else { String::new() };
        runs.extend(case_runs(db, main.file, &unit, tr, out, (&name, cases), settings, &served));
    }
    // The macros the file calls, alone (see `in_file_macro_runs`).
    runs.extend(macro_runs_in(db, (library, index, each_vacant), main, tr, settings, &served));
    runs
}

/// [`in_file_macro_runs`] of the file `index` of `lib`.
pub fn macro_runs_in(
    db: &SourceDb,
    (lib, index, each_vacant): (&Library, usize, bool),
    unit: &Unit,
    tr: &Translation,
    settings: &RunSettings,
    callees: &dyn Fn() -> Box<dyn CalleeSource + Send>,
) -> Vec<(String, CheckReport)> {
    let mut runs = Vec::new();
    for (i, p) in unit.programs.iter().enumerate().skip(1) {
        let Some(key) = number_of(p).map(ProgKey::Number) else { continue };
        // A copy of a program an earlier file defines is verified there (see `duplicates`).
        let mine = lib.programs.get(&key).is_some_and(|d| d.file == index);
        let macro_call = |c: &crate::translate::library::CallSite| {
            c.file == index && c.target == key && matches!(c.kind, CallKind::G65 | CallKind::G66)
        };
        if !mine || !lib.calls.iter().any(macro_call) {
            continue;
        }
        let Some(out) = tr.files.iter().find(|f| f.source == unit.file && first_of(f, p)) else { continue };
        let mut alone = unit.clone();
        let entry = alone.programs.remove(i);
        alone.programs.insert(0, entry);
        let a = Alone { db, file: unit.file, unit: &alone, tr, out };
        runs.extend(macro_runs(&a, lib, &key, settings, each_vacant, callees));
    }
    runs
}

/// The `O` number of a FANUC program, if it has one.
pub fn number_of(p: &crate::ir::Program) -> Option<u32> {
    match p.name {
        Some(ProgName::Number(n)) => Some(n),
        _ => None,
    }
}

/// Whether `f` is the translation of the FANUC program `p` (by number, else the unnamed main).
fn first_of(f: &OutFile, p: &crate::ir::Program) -> bool {
    match number_of(p) {
        Some(n) => f.fanuc_number == Some(n),
        None => f.fanuc_number.is_none(),
    }
}

/// The programs a run found through its callee source, recorded as it runs: what a caller's
/// proof ran of the library (`CheckReport::called`), so that a program that cannot run alone
/// may be proven in its callers' runs (`batch::run`).
#[derive(Clone, Default)]
pub struct Reached(std::sync::Arc<std::sync::Mutex<BTreeSet<ProgKey>>>);

impl Reached {
    /// `inner`, recording every program it finds.
    pub fn wrap(&self, inner: Box<dyn CalleeSource + Send>) -> Box<dyn CalleeSource + Send> {
        Box::new(Recording { inner, seen: self.clone() })
    }

    /// The programs found so far, as the library names them (`O9100`, `DRILL`).
    pub fn names(&self) -> Vec<String> {
        self.0.lock().map(|s| s.iter().map(ProgKey::to_string).collect()).unwrap_or_default()
    }
}

struct Recording {
    inner: Box<dyn CalleeSource + Send>,
    seen: Reached,
}

impl CalleeSource for Recording {
    fn find(
        &mut self,
        db: &mut SourceDb,
        caller: FileId,
        dialect: Dialect,
        name: &CalleeName,
    ) -> Result<Option<Unit>, Diagnostic> {
        let found = self.inner.find(db, caller, dialect, name)?;
        if found.is_some() {
            let key = match name {
                CalleeName::Number(n) => ProgKey::Number(*n),
                CalleeName::Name(n) => ProgKey::Name(n.to_ascii_uppercase()),
            };
            if let Ok(mut s) = self.seen.0.lock() {
                s.insert(key);
            }
        }
        Ok(found)
    }
}
