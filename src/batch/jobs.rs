//! The per-file job of a batch, one for every target: read the file and its callees,
//! translate them with the batch's maps through `translate::translate`, verify the files
//! written by running both programs, and hand back the output bytes. What differs per
//! target (its options from the maps, its output files' names, the names it used, what it
//! refuses, its proof's runs) is the target's [`Target`] (`batch::target::fanuc`,
//! `batch::target::sinumerik`).

use super::{maps, BatchContext, DiagRecord, FileJob, FileOutcome, InputFile, OutputFile, Status};
use crate::check::{self, Verdict};
use crate::config::{Comments, Config, LineEnds, Unsupported};
use crate::diag::{self, Diagnostic};
use crate::dialect::{Dialect, ParseOptions, Semantics};
use crate::eval;
use crate::ir::Unit;
use crate::read::LineEnding;
use crate::span::{FileId, SourceDb};
use crate::translate::to_sinumerik::verify::Profiles;
use crate::translate::{self, OutFile, Translation};
use std::collections::BTreeSet;
use std::marker::PhantomData;
use std::path::{Path, PathBuf};

use super::target::{fanuc::Fanuc, sinumerik::Sinumerik};

/// The job of a batch to `target`.
pub fn for_target(target: Dialect, settings: JobSettings) -> Box<dyn FileJob> {
    match target {
        Dialect::Fanuc => Box::new(Job::<Fanuc>::new(settings)),
        Dialect::Sinumerik => Box::new(Job::<Sinumerik>::new(settings)),
    }
}

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
        Ok(JobSettings::of(c))
    }

    /// The settings of `c`, its `--set` inputs unchecked (the command line's, which runs none).
    pub fn of(c: &Config) -> JobSettings {
        JobSettings {
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
        }
    }

    /// The output's line ending for an input written with `input`.
    pub fn line_ending(&self, input: LineEnding) -> LineEnding {
        match self.line_ends {
            LineEnds::Keep => input,
            LineEnds::Lf => LineEnding::Lf,
            LineEnds::CrLf => LineEnding::CrLf,
            LineEnds::Cr => LineEnding::Cr,
        }
    }
}

/// One file read and parsed into a job's own source database.
pub struct LoadedFile {
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
    let mut indexes = Vec::new();
    for i in ctx.library.callee_files(file.index) {
        let Some(f) = ctx.files.get(i) else { continue };
        indexes.push(i);
        let mut sub = load(db, f, dialect, enc, sem).map_err(read_error)?;
        // The name the library gave the file's program (a Siemens file without PROC: its stem).
        if let (Dialect::Sinumerik, Some([Some(crate::translate::library::ProgKey::Name(n))])) =
            (dialect, ctx.library.files.get(i).map(|x| &x.programs[..]))
        {
            crate::dialect::sinumerik::name_after_file(&mut sub.unit, n);
        }
        subs.push(sub);
    }
    if let Some(mut o) = empty_callees(db, ctx, &main, (&subs, &indexes), sem) {
        o.blocks = crate::ir::visit::count_blocks(&main.unit) as u64;
        return Err(Box::new(o));
    }
    let mut all: Vec<&LoadedFile> = vec![&main];
    all.extend(subs.iter());
    if let Some(mut o) = parse_failure(db, &all) {
        o.blocks = crate::ir::visit::count_blocks(&main.unit) as u64;
        return Err(Box::new(o));
    }
    Ok((main, subs))
}

/// The outcome of a file that calls a program whose file holds no program (NC593 at each
/// call, in place of the empty file's NC145, which that file's own outcome reports): an
/// `error`, not a parse error, when nothing else fails to parse.
fn empty_callees(
    db: &mut SourceDb,
    ctx: &BatchContext,
    main: &LoadedFile,
    (subs, indexes): (&[LoadedFile], &[usize]),
    sem: &Semantics,
) -> Option<FileOutcome> {
    use crate::dialect::empty_call;
    use crate::translate::library::ProgKey;
    let mut empties = Vec::new();
    for (sub, &index) in subs.iter().zip(indexes).filter(|(s, _)| empty_call::is_program_less(&s.diags)) {
        for p in ctx.library.programs.values().filter(|p| p.file == index) {
            let key = match &p.key {
                ProgKey::Number(n) => crate::ir::ProgName::Number(*n),
                ProgKey::Name(s) => crate::ir::ProgName::Name(s.clone()),
            };
            empties.push((sub.unit.file, key));
        }
    }
    // An empty FANUC file holds no `O` line: the library cannot know its number, its name
    // says it (`O0060.nc`), as beside a single file (`eval::callee_files`). Only the job's
    // own calls of numbers the library lacks are looked up.
    let mut unknown = std::collections::BTreeSet::new();
    for l in std::iter::once(main).chain(subs) {
        unknown.extend(empty_call::numbers_called(&l.unit));
    }
    unknown.retain(|n| !ctx.library.programs.contains_key(&ProgKey::Number(*n)));
    for n in unknown {
        let named = |f: &&super::InputFile| {
            let info = ctx.library.files.get(f.index);
            info.is_some_and(|i| i.programs.is_empty() && i.parse_errors > 0 && i.dialect == Some(Dialect::Fanuc))
                && f.rel.file_stem().and_then(|s| s.to_str()).is_some_and(|s| eval::callee_files::names_number(s, n))
        };
        let Some(f) = ctx.files.iter().find(named) else { continue };
        let Ok(l) = load(db, f, Dialect::Fanuc, ctx.options.encoding, sem) else { continue };
        if empty_call::is_program_less(&l.diags) {
            empties.push((l.unit.file, crate::ir::ProgName::Number(n)));
        }
    }
    if empties.is_empty() {
        return None;
    }
    let mut errors: Vec<Diagnostic> =
        std::iter::once(main).chain(subs).flat_map(|l| l.diags.iter().filter(|d| d.is_error()).cloned()).collect();
    let callers: Vec<&crate::ir::Unit> = std::iter::once(main).chain(subs).map(|l| &l.unit).collect();
    empty_call::at_call_sites(db, &callers, &empties, &mut errors);
    let first = errors.first()?;
    if first.code != empty_call::CODE {
        return None;
    }
    let calls = errors.iter().filter(|d| d.code == empty_call::CODE).count();
    let (status, summary) = if errors.len() > calls {
        (Status::ParseError, format!("{} parse error(s); {}", errors.len() - calls, first.message))
    } else if calls > 1 {
        (Status::Error, format!("{} (and {} more such call(s))", first.message, calls - 1))
    } else {
        (Status::Error, first.message.clone())
    };
    Some(failed(status, summary, DiagRecord::from_diags(db, &errors)))
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

/// What verification found.
pub struct Verified {
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
                excluded.add(r.excluded.clone());
                continue;
            }
            Verdict::Diverged { index } => {
                (Status::Diverged, crate::check::diverged_summary(*index, label, r.diverged_on_alarm))
            }
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

/// What a batch job does differently for its target, beside the target's translation
/// (`translate::to_<name>::job`); the rest of the job is [`Job`]'s, the same for all.
pub trait Target: Sized + Send + Sync + 'static {
    /// The dialect written.
    const DIALECT: Dialect;
    /// The target as messages name it (`… construct(s) FANUC cannot express`).
    const NAME: &'static str;
    /// Every program goes into one file (FANUC); else one file per program, and the proof
    /// names the folder of the files.
    const ONE_FILE: bool;

    /// The options of the translation of `main` (read with profile `source`) and its
    /// callees `subs`, from the batch's maps; an `Err` is the file's error (NC606).
    fn prepare(job: &Job<Self>, input: &mut Input, source: Semantics) -> Result<Prepared, String>;

    /// The names the file's own outputs (those from file `own`) used.
    fn used(t: &Translation, own: FileId) -> maps::Used;

    /// How many constructs the target cannot express, when the translation is refused
    /// (errors, or marked comments under the warn policy); `own_diags` are the
    /// translation's diagnostics about the job's own files.
    fn refused(t: &Translation, own_diags: &[Diagnostic], own: FileId) -> Option<usize>;

    /// Where an output file of the input `rel` is written, relative to the output folder.
    fn output(rel: &Path, f: &OutFile) -> PathBuf;
}

/// A job's input once read: its file, the batch, and the parsed file and callees in `db`.
pub struct Input<'a> {
    pub file: &'a InputFile,
    pub ctx: &'a BatchContext,
    pub db: SourceDb,
    pub main: LoadedFile,
    pub subs: Vec<LoadedFile>,
}

/// What a target makes of a job's input before it translates.
pub struct Prepared {
    pub opts: translate::Options,
    /// Notes for the report, in front of the reading diagnostics.
    pub notes: Vec<DiagRecord>,
    /// Program numbers of the file that another file writes (not written here).
    pub copies: BTreeSet<u32>,
    /// A program translated with the file's but not written (its file and unit): the calls
    /// the rest of the library makes (FANUC → Sinumerik, `to_sinumerik::job::stand_in`).
    pub stand_in: Option<(FileId, Unit)>,
}

impl Prepared {
    pub fn new(opts: translate::Options) -> Prepared {
        Prepared { opts, notes: vec![], copies: BTreeSet::new(), stand_in: None }
    }
}

/// The per-file job of a batch to the target `T`.
pub struct Job<T> {
    pub settings: JobSettings,
    /// The tests' injected bug, applied to the text of every output of the file.
    pub fault: Option<Box<Fault>>,
    target: PhantomData<T>,
}

impl<T: Target> Job<T> {
    pub fn new(settings: JobSettings) -> Job<T> {
        Job { settings, fault: None, target: PhantomData }
    }
}

/// The profile a file of `source` is read with: the settings' own, and for Sinumerik the
/// global user data and macros of the library (the `.DEF` files nearest the program, up to
/// the batch root, or the configured ones). A definition file that does not read is the
/// file's outcome.
pub(crate) fn source_profile(
    s: &JobSettings,
    db: &mut SourceDb,
    file: &InputFile,
    source: Dialect,
) -> Result<Semantics, Box<FileOutcome>> {
    match source {
        Dialect::Fanuc => Ok(s.fanuc.clone()),
        Dialect::Sinumerik => {
            let mut sem = s.sinumerik.clone();
            let root = crate::gud::root_of(&file.abs, &file.rel);
            let gud = crate::gud::apply(&mut sem, db, &file.abs, root.as_deref(), &s.definitions);
            if diag::has_errors(&gud) {
                let records = DiagRecord::from_diags(db, &gud);
                return Err(Box::new(failed(Status::Error, "the definition files do not read".into(), records)));
            }
            Ok(sem)
        }
    }
}

/// A large file is streamed (`batch::streamed`, the target's `Streams`) when it can be.
impl<T: super::streamed::Streams> FileJob for Job<T> {
    fn run(&self, file: &InputFile, ctx: &BatchContext) -> FileOutcome {
        if let Some(o) = super::streamed::run(self, file, ctx) {
            return o;
        }
        let mut db = SourceDb::new();
        let source = ctx.options.source();
        let sem = match source_profile(&self.settings, &mut db, file, source) {
            Ok(s) => s,
            Err(o) => return *o,
        };
        let (main, subs) = match load_with_callees(&mut db, file, ctx, source, &sem) {
            Ok(l) => l,
            Err(o) => return *o,
        };
        let blocks = crate::ir::visit::count_blocks(&main.unit) as u64;
        let mut input = Input { file, ctx, db, main, subs };
        let p = match T::prepare(self, &mut input, sem) {
            Ok(p) => p,
            Err(e) => return failed(Status::Error, e.clone(), vec![DiagRecord::error("NC606", e)]),
        };
        let mut diagnostics = p.notes.clone();
        diagnostics.extend(DiagRecord::from_diags(&input.db, &input.main.diags));
        let mut units: Vec<&Unit> = std::iter::once(&input.main).chain(&input.subs).map(|l| &l.unit).collect();
        if let Some((_, u)) = &p.stand_in {
            units.push(u);
        }
        let mut t = translate::translate(&units, T::DIALECT, &p.opts);
        // The stand-in's own program is not an output; its warnings are about nothing real.
        let stand_in = p.stand_in.as_ref().map(|(id, _)| *id);
        t.files.retain(|f| Some(f.source) != stand_in);
        let own_diags: Vec<_> = t
            .diags
            .iter()
            .filter(|d| d.is_error() || d.labels.iter().find(|l| l.primary).is_none_or(|l| Some(l.file) != stand_in))
            .cloned()
            .collect();
        diagnostics.extend(DiagRecord::from_diags(&input.db, &own_diags));

        // What this file's programs use (not the callees', not the stand-in's).
        let own = input.main.loaded.file;
        let used = T::used(&t, own);
        if let Some(n) = T::refused(&t, &own_diags, own) {
            return unsupported(n, T::NAME, blocks, diagnostics);
        }
        if let Some(fault) = &self.fault {
            for f in t.files.iter_mut().filter(|f| f.source == own) {
                fault(file, &mut f.text);
            }
        }
        let loaded = &input.main.loaded;
        let encoding = self.settings.output_encoding.unwrap_or(loaded.encoding);
        let mut outcome = FileOutcome::new(Status::TranslatedUnverified, "translated, not verified (--no-verify)");
        outcome.blocks = blocks;
        outcome.used = used;
        outcome.outputs = t
            .files
            .iter()
            .filter(|f| f.source == own && !f.fanuc_number.is_some_and(|n| p.copies.contains(&n)))
            .map(|f| OutputFile {
                rel: T::output(&file.rel, f),
                bytes: crate::read::encode(&f.text, encoding, loaded.bom),
            })
            .collect();
        outcome.diagnostics = diagnostics;
        if outcome.outputs.is_empty() {
            outcome.status = Status::Unsupported;
            outcome.summary = "not translated: the file holds no program".into();
            return outcome;
        }
        if ctx.options.verify {
            let (v, reached) = self.verify(&mut input, &t);
            apply(&mut outcome, v);
            outcome.calls = call_proof::<T>(&t, own, reached, outcome.status, (file.index, &ctx.library));
        }
        outcome
    }
}

impl<T: Target> Job<T> {
    /// Proves the translation `t` through `translate::verify`, with the batch's profiles,
    /// `--set` and library (each program also runs with the arguments its callers pass).
    fn verify(&self, input: &mut Input, t: &Translation) -> (Verified, BTreeSet<String>) {
        let (file, ctx, s) = (input.file, input.ctx, &self.settings);
        let out = match t.main() {
            Some(f) if T::ONE_FILE => T::output(&file.rel, f),
            _ => file.rel.parent().unwrap_or(Path::new("")).to_path_buf(),
        };
        let main_name = file.rel.file_stem().and_then(|x| x.to_str()).unwrap_or("MAIN").to_ascii_uppercase();
        let opts = translate::VerifyOptions {
            max_steps: s.max_steps,
            profiles: Some(Profiles { fanuc: s.fanuc.clone(), sinumerik: s.sinumerik.clone() }),
            set: &s.set,
            library: Some(translate::InLibrary { library: &ctx.library, file: file.index, main_name: &main_name }),
            each_vacant: !ctx.options.specialise_callers,
        };
        let units: Vec<&Unit> = std::iter::once(&input.main).chain(&input.subs).map(|l| &l.unit).collect();
        let v = translate::verify(&mut input.db, &units, t, &super::rel_string(&out), opts);
        let reached = v
            .runs
            .iter()
            .filter(|(_, r)| matches!(r.verdict, Verdict::Equivalent { .. }))
            .flat_map(|(_, r)| r.called.iter().cloned())
            .collect();
        (self.verified(input, v), reached)
    }

    fn verified(&self, input: &Input, v: translate::Verification) -> Verified {
        if !v.unreadable.is_empty() {
            return Verified {
                status: Status::Diverged,
                summary: format!("the output does not parse as {} (a bug in nctrans)", T::NAME),
                events: None,
                excluded: Default::default(),
                diagnostics: DiagRecord::from_diags(&input.db, &v.unreadable),
            };
        }
        if v.runs.is_empty() {
            let summary = v.summary;
            return Verified {
                status: Status::Inconclusive,
                summary,
                events: None,
                excluded: Default::default(),
                diagnostics: vec![],
            };
        }
        combine(v.runs)
    }
}

/// What a file's proof ran of the library (see [`super::CallProof`]): the programs of other
/// files its equivalent runs called, the fingerprints of every program its translation held
/// and of its own, and whether it waits for its callers: its runs alone were inconclusive
/// (not divergent) and every program of the file is called by another file.
fn call_proof<T: Target>(
    t: &Translation,
    own: FileId,
    reached: BTreeSet<String>,
    status: super::Status,
    (index, lib): (usize, &crate::translate::library::Library),
) -> super::CallProof {
    let fanuc = T::DIALECT == Dialect::Fanuc;
    let programs = lib.files.get(index).map_or(&[][..], |f| &f.programs[..]);
    let called_elsewhere = |k: &Option<crate::translate::library::ProgKey>| {
        k.as_ref().is_some_and(|k| lib.calls.iter().any(|c| c.file != index && &c.target == k))
    };
    let waits = status == Status::Inconclusive && !programs.is_empty() && programs.iter().all(called_elsewhere);
    super::CallProof {
        reached: if status == Status::Verified { reached } else { BTreeSet::new() },
        ran: fingerprints(t.files.iter(), fanuc),
        waits,
        own: fingerprints(t.files.iter().filter(|f| f.source == own), fanuc),
    }
}

/// Each translated program of `files` by its target name, with a fingerprint of its text
/// without comment lines (a program's header says which file it was translated for). A
/// FANUC file holds several programs, each from its `O` line.
fn fingerprints<'a>(files: impl Iterator<Item = &'a OutFile>, fanuc: bool) -> Vec<(String, u64)> {
    use std::hash::{Hash, Hasher};
    let print = |body: &str| {
        let mut h = std::collections::hash_map::DefaultHasher::new();
        body.hash(&mut h);
        h.finish()
    };
    let mut out = Vec::new();
    for f in files {
        let (mut key, mut body) = (f.program.clone(), String::new());
        for line in f.text.lines().map(str::trim) {
            let o_line = line.strip_prefix('O').map(|r| r.split(|c: char| !c.is_ascii_digit()).next().unwrap_or(""));
            if let Some(n) = o_line.filter(|n| fanuc && !n.is_empty()).and_then(|n| n.parse::<u32>().ok()) {
                if !body.is_empty() {
                    out.push((key, print(&body)));
                }
                (key, body) = (crate::translate::library::ProgKey::Number(n).to_string(), String::new());
                continue;
            }
            let comment = (line.starts_with('(') && line.ends_with(')')) || line.starts_with(';');
            if !(line.is_empty() || line == "%" || comment) {
                body.push_str(line);
                body.push('\n');
            }
        }
        out.push((key, print(&body)));
    }
    out
}
