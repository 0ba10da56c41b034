//! The real per-file jobs: translate one file with the batch's maps, verify it by running
//! both programs, and hand back the output bytes. Sinumerik → FANUC here, with what both
//! directions share (settings, loading, outcomes, combining verdicts); FANUC → Sinumerik in
//! `jobs_sinumerik.rs`.

use super::library::ProgKey;
use super::{discover, BatchContext, DiagRecord, FileJob, FileOutcome, InputFile, OutputFile, Status};
use crate::check::{self, Side, Verdict};
use crate::config::{Comments, Config, LineEnds, Unsupported};
use crate::diag::{self, Diagnostic};
use crate::dialect::{Dialect, ParseOptions, Semantics};
use crate::eval::{self, CalleeName, CalleeSource, NoCallees, RunOptions};
use crate::ir::{ProgName, Unit};
use crate::lower::to_fanuc::{varmap, UnsupportedPolicy};
use crate::read::LineEnding;
use crate::span::{FileId, SourceDb};
use crate::translate::{self, TranslateOptions, Translation};

/// Changes a translation before it is verified: the tests' injected bug, which verification
/// must catch. Never set outside tests.
pub type Fault = dyn Fn(&InputFile, &mut String) + Sync;

/// Settings shared by both directions, from the configuration.
#[derive(Clone, Debug)]
pub struct JobSettings {
    pub unsupported: Unsupported,
    pub comments: Comments,
    pub number_blocks: Option<u32>,
    pub compound_conditions: bool,
    pub fanuc: Semantics,
    pub sinumerik: Semantics,
    pub output_encoding: Option<&'static encoding_rs::Encoding>,
    pub line_ends: LineEnds,
    pub max_steps: u64,
    /// `--set` inputs for every run.
    pub set: Vec<String>,
    /// `[sinumerik] definitions`: global user data files for every program (empty: found
    /// beside each program, `crate::gud`).
    pub definitions: Vec<std::path::PathBuf>,
}

impl JobSettings {
    pub fn from_config(c: &Config) -> Result<JobSettings, String> {
        for s in &c.set {
            eval::parse_input(s).map_err(|e| format!("verify.set: {e}"))?;
        }
        Ok(JobSettings {
            unsupported: c.unsupported,
            comments: c.comments,
            number_blocks: (c.number_blocks > 0).then_some(c.number_blocks),
            compound_conditions: c.fanuc.compound_conditions,
            fanuc: c.fanuc_semantics(),
            sinumerik: c.sinumerik_semantics(),
            output_encoding: c.output_encoding,
            line_ends: c.line_ends,
            max_steps: c.max_steps,
            set: c.set.clone(),
            definitions: c.definitions.clone(),
        })
    }

    pub(crate) fn line_ending(&self, input: LineEnding) -> LineEnding {
        match self.line_ends {
            LineEnds::Keep => input,
            LineEnds::Lf => LineEnding::Lf,
            LineEnds::CrLf => LineEnding::CrLf,
            LineEnds::Cr => LineEnding::Cr,
        }
    }
}

/// One file read and parsed into a job's own source database.
pub(crate) struct LoadedFile {
    pub unit: Unit,
    pub loaded: crate::Loaded,
    pub diags: Vec<Diagnostic>,
    /// FANUC program numbers after the closing `%` (`Parsed::after_end_programs`).
    pub after_end: Vec<u32>,
}

/// Reads and parses `file` as `dialect` into `db`.
pub(crate) fn load(
    db: &mut SourceDb,
    file: &InputFile,
    dialect: Dialect,
    encoding: Option<&'static encoding_rs::Encoding>,
    sem: &Semantics,
) -> Result<LoadedFile, String> {
    let bytes = std::fs::read(&file.abs).map_err(|e| format!("cannot read {}: {e}", file.rel.display()))?;
    let loaded = crate::load(db, &super::rel_string(&file.rel), &bytes, encoding);
    let opts = ParseOptions { semantics: sem.clone() };
    let parsed = crate::parse(db, loaded.file, dialect, &opts);
    Ok(LoadedFile { unit: parsed.unit, loaded, diags: parsed.diags, after_end: parsed.after_end_programs })
}

/// A job's input file and the files holding the programs it calls (transitively, from the
/// library), read and parsed as `dialect`. A read or parse failure is the file's outcome.
pub(crate) fn load_with_callees(
    db: &mut SourceDb,
    file: &InputFile,
    ctx: &BatchContext,
    dialect: Dialect,
    sem: &Semantics,
) -> Result<(LoadedFile, Vec<LoadedFile>), Box<FileOutcome>> {
    let enc = ctx.options.encoding;
    let read_error = |e: String| Box::new(failed(Status::Error, e.clone(), vec![DiagRecord::error("NC600", e)]));
    let main = load(db, file, dialect, enc, sem).map_err(read_error)?;
    let mut subs = Vec::new();
    for i in ctx.library.callee_files(file.index) {
        let Some(f) = ctx.files.get(i) else { continue };
        subs.push(load(db, f, dialect, enc, sem).map_err(read_error)?);
    }
    let mut all: Vec<&LoadedFile> = vec![&main];
    all.extend(subs.iter());
    if let Some(mut o) = parse_failure(db, &all) {
        o.blocks = crate::ir::visit::count_blocks(&main.unit) as u64;
        return Err(Box::new(o));
    }
    Ok((main, subs))
}

/// The outcome of a file whose translation was refused: `n` constructs the target cannot
/// express (errors, or marked comments under the warn policy). No output.
pub(crate) fn unsupported(n: usize, target: &str, blocks: u64, diagnostics: Vec<DiagRecord>) -> FileOutcome {
    let mut o =
        failed(Status::Unsupported, format!("not translated: {n} construct(s) {target} cannot express"), diagnostics);
    o.blocks = blocks;
    o
}

/// Puts verification's findings into an outcome.
pub(crate) fn apply(outcome: &mut FileOutcome, v: Verified) {
    outcome.status = v.status;
    outcome.summary = v.summary;
    outcome.events = v.events;
    outcome.excluded = v.excluded;
    outcome.diagnostics.extend(v.diagnostics);
}

/// An outcome for a file that could not be read or parsed.
pub(crate) fn failed(status: Status, summary: String, diagnostics: Vec<DiagRecord>) -> FileOutcome {
    let mut o = FileOutcome::new(status, summary);
    o.diagnostics = diagnostics;
    o
}

/// Parse errors of a file and of the files it calls, as a `parse-error` outcome.
pub(crate) fn parse_failure(db: &SourceDb, all: &[&LoadedFile]) -> Option<FileOutcome> {
    let errors: Vec<Diagnostic> = all.iter().flat_map(|l| l.diags.iter().filter(|d| d.is_error()).cloned()).collect();
    if errors.is_empty() {
        return None;
    }
    let first = DiagRecord::from_diags(db, &errors[..1]);
    let where_ = first[0].file.clone().unwrap_or_default();
    Some(failed(
        Status::ParseError,
        format!("{} parse error(s), the first in {where_}", errors.len()),
        DiagRecord::from_diags(db, &errors),
    ))
}

/// Sinumerik → FANUC.
pub struct ToFanucJob {
    pub settings: JobSettings,
    pub fault: Option<Box<Fault>>,
}

impl ToFanucJob {
    pub fn new(settings: JobSettings) -> ToFanucJob {
        ToFanucJob { settings, fault: None }
    }

    pub(crate) fn options(
        &self,
        ctx: &BatchContext,
        file: &InputFile,
        eol: LineEnding,
    ) -> Result<TranslateOptions, String> {
        let mut var_rules = Vec::new();
        for r in &ctx.maps.var_rules {
            var_rules.extend(varmap::parse_rules(r).map_err(|e| format!("variables.to_fanuc: {e}"))?);
        }
        let s = &self.settings;
        Ok(TranslateOptions {
            unsupported: match s.unsupported {
                Unsupported::Error => UnsupportedPolicy::Error,
                Unsupported::Warn => UnsupportedPolicy::Warn,
            },
            var_rules,
            tool_map: ctx.maps.tools.clone(),
            program_map: ctx.maps.fanuc_numbers(),
            program_number: None,
            comments: match s.comments {
                Comments::Keep => crate::dialect::fanuc::emit::CommentMode::Keep,
                Comments::Ascii => crate::dialect::fanuc::emit::CommentMode::Ascii,
                Comments::Drop => crate::dialect::fanuc::emit::CommentMode::Drop,
            },
            number_blocks: s.number_blocks,
            line_ending: s.line_ending(eol),
            compound_conditions: s.compound_conditions,
            target: s.fanuc.clone(),
            source: s.sinumerik.clone(),
            main_name: file.rel.file_stem().and_then(|x| x.to_str()).unwrap_or("MAIN").to_ascii_uppercase(),
            source_name: file.rel.file_name().and_then(|x| x.to_str()).unwrap_or("").to_string(),
            main_is_sub: file.rel.extension().is_some_and(|e| e.eq_ignore_ascii_case("spf")),
        })
    }
}

impl FileJob for ToFanucJob {
    fn run(&self, file: &InputFile, ctx: &BatchContext) -> FileOutcome {
        if let Some(o) = super::streamed::to_fanuc(self, file, ctx) {
            return o;
        }
        let mut db = SourceDb::new();
        // Global user data and macros of the library (`.DEF` files nearest the program, up to
        // the batch root, or the configured ones).
        let mut sem = self.settings.sinumerik.clone();
        let root = crate::gud::root_of(&file.abs, &file.rel);
        let gud = crate::gud::apply(&mut sem, &mut db, &file.abs, root.as_deref(), &self.settings.definitions);
        if diag::has_errors(&gud) {
            return failed(Status::Error, "the definition files do not read".into(), DiagRecord::from_diags(&db, &gud));
        }
        let (main, subs) = match load_with_callees(&mut db, file, ctx, Dialect::Sinumerik, &sem) {
            Ok(l) => l,
            Err(o) => return *o,
        };
        let blocks = crate::ir::visit::count_blocks(&main.unit) as u64;
        let mut opts = match self.options(ctx, file, main.loaded.line_ending) {
            Ok(o) => o,
            Err(e) => return failed(Status::Error, e.clone(), vec![DiagRecord::error("NC606", e)]),
        };
        opts.source = sem;
        let sub_units: Vec<&Unit> = subs.iter().map(|l| &l.unit).collect();
        let inputs: Vec<&Unit> = std::iter::once(&main.unit).chain(sub_units.iter().copied()).collect();
        let main_name = opts.main_name.clone();
        let opts = translate::Options::to_fanuc(opts);
        let mut t = translate::translate(&inputs, Dialect::Fanuc, &opts);
        let mut diagnostics = DiagRecord::from_diags(&db, &main.diags);
        diagnostics.extend(DiagRecord::from_diags(&db, &t.diags));
        let used = used_names(t.symbols.fanuc());
        if !t.ok() {
            let n = t.diags.iter().filter(|d| d.is_error() || d.code.starts_with("NC3")).count().max(t.unsupported);
            return unsupported(n, "FANUC", blocks, diagnostics);
        }
        if let (Some(fault), Some(f)) = (&self.fault, t.files.first_mut()) {
            fault(file, &mut f.text);
        }
        let encoding = self.settings.output_encoding.unwrap_or(main.loaded.encoding);
        let bytes = crate::read::encode(t.text(), encoding, main.loaded.bom);
        let mut outcome = FileOutcome::new(Status::TranslatedUnverified, "translated, not verified (--no-verify)");
        outcome.blocks = blocks;
        outcome.used = used;
        outcome.outputs = vec![OutputFile { rel: discover::fanuc_output(&file.rel), bytes }];
        if ctx.options.verify {
            let key = main.unit.programs.first().map(|p| match &p.name {
                Some(ProgName::Name(n)) => ProgKey::Name(n.to_ascii_uppercase()),
                _ => ProgKey::Name(main_name.clone()),
            });
            let vectors = key.map(|k| ctx.library.arg_vectors(&k)).unwrap_or_default();
            let out_name = super::rel_string(&discover::fanuc_output(&file.rel));
            let v = self.verify(&mut db, &main.unit, &sub_units, &t, &out_name, &vectors);
            outcome.diagnostics = diagnostics;
            apply(&mut outcome, v);
        } else {
            outcome.diagnostics = diagnostics;
        }
        outcome
    }
}

/// The names a translation to FANUC used: programs, tools, variables.
pub(crate) fn used_names(map: &translate::SymbolMap) -> super::maps::Used {
    let mut used = super::maps::Used::default();
    for (name, n) in &map.programs {
        used.programs.insert(ProgKey::Name(name.clone()), ProgKey::Number(*n));
    }
    used.tools = map.tools.clone();
    for m in &map.vars {
        let key = match &m.program {
            Some(p) => format!("{p}.{}", m.source),
            None => m.source.clone(),
        };
        used.variables.insert(key, format!("#{}", m.number));
    }
    used
}

/// What verification found.
pub(crate) struct Verified {
    pub status: Status,
    pub summary: String,
    pub events: Option<u64>,
    /// What the checks left out of the comparison (equivalences only).
    pub excluded: check::Excluded,
    pub diagnostics: Vec<DiagRecord>,
}

/// Combines the verdicts of several runs (the plain run and one per argument vector): any
/// divergence wins, then anything unproven; events add up.
pub(crate) fn combine(runs: Vec<(String, check::CheckReport)>) -> Verified {
    let mut events = 0u64;
    let mut excluded = check::Excluded::default();
    let mut worst: Option<Verified> = None;
    for (label, r) in &runs {
        let diagnostics = DiagRecord::from_diags(&r.db, &r.diags);
        let (status, summary) = match &r.verdict {
            Verdict::Equivalent { events: n } => {
                events += n;
                excluded.add(r.excluded);
                continue;
            }
            Verdict::Diverged { index } => (
                Status::Diverged,
                format!("diverged at trace event {}{label}: the translation is wrong (a bug in nctrans)", index + 1),
            ),
            Verdict::Inconclusive { reason } => (Status::Inconclusive, format!("inconclusive{label}: {reason}")),
            Verdict::Failed => (Status::Inconclusive, format!("not verified{label}: a run could not be evaluated")),
        };
        let rank = |s: Status| super::report::rank(s);
        if worst.as_ref().is_none_or(|w| rank(status) > rank(w.status)) {
            worst = Some(Verified { status, summary, events: None, excluded: Default::default(), diagnostics });
        }
    }
    match worst {
        Some(w) => w,
        None => Verified {
            status: Status::Verified,
            summary: crate::translate::called::Combined::summary(events, runs.len(), &excluded),
            events: Some(events),
            excluded,
            diagnostics: vec![],
        },
    }
}

impl ToFanucJob {
    /// Parses the output back as FANUC (it must be valid FANUC), then runs both programs:
    /// once with the program's own inputs, and once per argument vector its callers use.
    fn verify(
        &self,
        db: &mut SourceDb,
        main: &Unit,
        subs: &[&Unit],
        t: &Translation,
        out_name: &str,
        vectors: &[Vec<super::library::ArgValue>],
    ) -> Verified {
        let parsed = translate::reparse(db, t, out_name);
        if diag::has_errors(&parsed.diags) {
            return Verified {
                status: Status::Diverged,
                summary: "the output does not parse as FANUC (a bug in nctrans)".into(),
                events: None,
                excluded: Default::default(),
                diagnostics: DiagRecord::from_diags(db, &parsed.diags),
            };
        }
        // The Siemens side starts with R parameters 0; their FANUC homes are set to 0 too
        // (FANUC commons may be vacant), like `nctrans --to fanuc` does.
        let map = t.symbols.fanuc();
        let mut fanuc_inputs: Vec<String> = translate::to_fanuc::r_param_homes(map);
        fanuc_inputs.extend(map.gud_seeds.iter().map(|(n, v)| format!("#{n}={v}")));
        let sinumerik = translate::to_fanuc::source_semantics(t, Some(&self.settings.sinumerik))
            .unwrap_or_else(|| self.settings.sinumerik.clone());
        let params = main.programs.first().map(|p| p.params.clone()).unwrap_or_default();
        let letters = crate::lower::to_fanuc::words::param_letters(params.len()).unwrap_or_default();
        let mut runs = Vec::new();
        let mut cases: Vec<(String, Vec<(usize, String)>)> = vec![(String::new(), vec![])];
        for (k, v) in vectors.iter().enumerate() {
            let vals = v
                .iter()
                .filter_map(|a| {
                    params.iter().position(|p| p.name.eq_ignore_ascii_case(&a.var)).map(|i| (i, a.to_set()))
                })
                .collect();
            cases.push((format!(" (with the arguments of call site {})", k + 1), vals));
        }
        for (label, vals) in cases {
            let mut a_in = Vec::new();
            let mut b_in = std::mem::take(&mut fanuc_inputs);
            fanuc_inputs = b_in.clone();
            // Parameters not passed are 0 on Siemens; the argument locals get the same value.
            for (i, (_, var)) in letters.iter().enumerate() {
                if params.get(i).is_some_and(|p| p.by_ref) {
                    continue;
                }
                let given = vals.iter().find(|(j, _)| *j == i);
                let value = given.map_or("0".to_string(), |(_, s)| s.split_once('=').map_or("0", |x| x.1).to_string());
                b_in.push(format!("#{var}={value}"));
                if let Some((_, s)) = given {
                    a_in.push(s.clone());
                }
            }
            b_in.extend(translate::var_param_inputs(&params, map));
            a_in.extend(self.settings.set.iter().cloned());
            b_in.extend(self.settings.set.iter().filter(|s| s.trim_start().starts_with('#')).cloned());
            let parse_all = |v: &[String]| v.iter().filter_map(|s| eval::parse_input(s).ok()).collect::<Vec<_>>();
            let run = |inputs, sem: &Semantics| RunOptions {
                max_steps: self.settings.max_steps,
                inputs,
                semantics: Some(sem.clone()),
                probe_contact: None,
                probes: Vec::new(),
                expand_cycles: None,
            };
            let source = translate::align_source(main, map);
            let callees = MemCallees(subs.iter().map(|u| translate::align_source(u, map)).collect());
            let a = Side { unit: source, callees: Box::new(callees), run: run(parse_all(&a_in), &sinumerik) };
            let b = Side {
                unit: parsed.unit.clone(),
                callees: Box::new(NoCallees),
                run: run(parse_all(&b_in), &self.settings.fanuc),
            };
            runs.push((label, check::check_excluding(db, a, b, translate::EXCLUDE)));
        }
        combine(runs)
    }
}

/// Called programs served from memory: Siemens ones by name, FANUC ones by `O` number.
pub(crate) struct MemCallees(pub Vec<Unit>);

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
