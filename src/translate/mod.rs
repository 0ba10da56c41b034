//! The library's one translation entry: [`translate`] takes the programs of one dialect and
//! gives back one [`Translation`] (the files written, the symbol map that relates them to the
//! source, every diagnostic, and what could not be expressed) for every pair of dialects.
//!
//! Owns: the entry, the result type, the options of every target ([`Options`]), the one
//! proof ([`verify`], [`VerifyOptions`]), and the work per target behind them: `to_fanuc/`
//! (Sinumerik → FANUC) and `to_sinumerik/` (FANUC → Sinumerik, with its proof in
//! `to_sinumerik/verify.rs`), the library index a proof runs called programs with
//! (`library`: which programs call which with which arguments) and those runs (`called`).
//! May use: `lower` (lowering), `dialect` (writing), `check` and `eval` (the proof),
//! `unfinished`, `ir`, `diag`, `read`, `span`; never `batch`, `stream`, `config` or the
//! CLI (`tests/layering.rs`). Used by the CLI, `batch` and `stream`. A new target adds a
//! module here and an arm in [`translate`] and [`verify`].

pub mod called;
pub mod generic;
pub mod library;
pub mod to_fanuc;
pub mod to_sinumerik;

use crate::check::{CheckReport, Verdict};
use crate::diag::{self, Diagnostic};
use crate::dialect::Dialect;
use crate::ir::{ProgName, Unit};
use crate::read::LineEnding;
use crate::span::{FileId, SourceDb, Span};
use std::collections::BTreeMap;
use to_fanuc::{TranslateOptions, DEFAULT_MAIN_NUMBER};

/// One written file.
#[derive(Clone, Debug, PartialEq)]
pub struct OutFile {
    /// File name: `NAME.MPF` or `NAME.SPF` on Sinumerik; `O0001.nc` on FANUC, where the
    /// command line and the batch name the file after the input instead.
    pub name: String,
    /// The program name calls use (`PROBE_X`, `O0001`).
    pub program: String,
    /// The FANUC program number it came from (FANUC → Sinumerik).
    pub fanuc_number: Option<u32>,
    pub main: bool,
    pub text: String,
    /// The source file the (main) program came from.
    pub source: FileId,
    /// Source span of every output line (`None` for generated header lines); empty when the
    /// target's writer does not record them (FANUC).
    pub lines: Vec<Option<Span>>,
}

/// How the source's names appear in the output: the target's symbol map.
#[derive(Clone, Debug, PartialEq)]
pub enum Symbols {
    /// Boxed: the FANUC map is many times the Sinumerik one.
    Fanuc(Box<to_fanuc::SymbolMap>),
    Sinumerik(to_sinumerik::SymbolMap),
}

static NO_FANUC: to_fanuc::SymbolMap = to_fanuc::SymbolMap {
    vars: Vec::new(),
    labels: BTreeMap::new(),
    tools: BTreeMap::new(),
    programs: BTreeMap::new(),
    alarms: BTreeMap::new(),
    gud_seeds: Vec::new(),
    globals: Vec::new(),
    haas: false,
    haas_ngc: false,
    macro_interrupt: false,
    offsets: crate::dialect::offsets::OffsetMap { edges: BTreeMap::new() },
    fixed: BTreeMap::new(),
    def_inputs: std::collections::BTreeSet::new(),
    signals: crate::dialect::signals::SignalMap { pairs: BTreeMap::new() },
};
static NO_SINUMERIK: to_sinumerik::SymbolMap = to_sinumerik::SymbolMap { vars: Vec::new(), programs: Vec::new() };

impl Symbols {
    /// The map of a translation to FANUC (empty for another target).
    pub fn fanuc(&self) -> &to_fanuc::SymbolMap {
        match self {
            Symbols::Fanuc(m) => m,
            Symbols::Sinumerik(_) => &NO_FANUC,
        }
    }

    /// The map of a translation to Sinumerik (empty for another target).
    pub fn sinumerik(&self) -> &to_sinumerik::SymbolMap {
        match self {
            Symbols::Sinumerik(m) => m,
            Symbols::Fanuc(_) => &NO_SINUMERIK,
        }
    }
}

/// The result of a translation, for every pair of dialects.
#[derive(Clone, Debug)]
pub struct Translation {
    /// The files written, the main program's first on FANUC (one file holds every program),
    /// one per program on Sinumerik.
    pub files: Vec<OutFile>,
    pub symbols: Symbols,
    pub diags: Vec<Diagnostic>,
    /// Constructs the target cannot express that were written as marked comments (the warn
    /// policy); the FANUC target also counts those refused under the error policy.
    pub unsupported: usize,
}

impl Translation {
    /// The dialect written.
    pub fn target(&self) -> Dialect {
        match self.symbols {
            Symbols::Fanuc(_) => Dialect::Fanuc,
            Symbols::Sinumerik(_) => Dialect::Sinumerik,
        }
    }

    pub fn has_errors(&self) -> bool {
        diag::has_errors(&self.diags)
    }

    /// True when the files are a complete translation (no error, nothing unsupported).
    pub fn ok(&self) -> bool {
        !self.has_errors() && self.unsupported == 0
    }

    /// The main program's file (the first `.MPF`).
    pub fn main(&self) -> Option<&OutFile> {
        self.files.iter().find(|f| f.main).or_else(|| self.files.first())
    }

    /// The main file's text (empty when nothing was written).
    pub fn text(&self) -> &str {
        self.main().map_or("", |f| f.text.as_str())
    }
}

impl From<to_fanuc::Output> for Translation {
    fn from(o: to_fanuc::Output) -> Translation {
        let number = match o.unit.programs.first().and_then(|p| p.name.as_ref()) {
            Some(ProgName::Number(n)) => *n,
            _ => DEFAULT_MAIN_NUMBER,
        };
        let file = OutFile {
            name: format!("O{number:04}.nc"),
            program: format!("O{number:04}"),
            fanuc_number: None,
            main: true,
            text: o.text,
            source: o.unit.file,
            lines: vec![],
        };
        Translation {
            files: vec![file],
            symbols: Symbols::Fanuc(Box::new(o.symbol_map)),
            diags: o.diags,
            unsupported: o.unsupported,
        }
    }
}

/// The result of checking a translation.
#[derive(Default)]
pub struct Verification {
    /// Both programs ran to the same trace (in every run).
    pub equivalent: bool,
    /// One line for the user: `equivalent (N events)`, `diverged …`, `inconclusive …`.
    pub summary: String,
    /// Rendered diagnostics (parse errors of the output, the divergence).
    pub rendered: String,
    /// The output parsed back as FANUC.
    pub reparsed: Option<Unit>,
    /// Every run of the proof with its label (the plain run's is empty), in order: the
    /// callers' argument vectors, a called macro alone (see [`VerifyOptions`]).
    pub runs: Vec<(String, CheckReport)>,
    /// The output's errors when it does not read back as the target (no run was made).
    pub unreadable: Vec<Diagnostic>,
}

impl Verification {
    /// The verdict of a check, in the words both targets give it; `rendered` holds the
    /// check's diagnostics (and the trace diff of a divergence).
    fn of(report: &CheckReport) -> Verification {
        let mut rendered = diag::render(&report.db, &report.diags);
        if matches!(report.verdict, Verdict::Diverged { .. }) {
            rendered.push_str(&report.diff);
        }
        let (equivalent, summary) = report.verdict_line();
        Verification { equivalent, summary, rendered, ..Verification::default() }
    }

    /// The verdict of several runs: the first that is not an equivalence (named by its
    /// label), or the events of all added up.
    fn of_runs(runs: Vec<(String, CheckReport)>) -> Verification {
        let not = runs.iter().find(|(_, r)| !matches!(r.verdict, Verdict::Equivalent { .. }));
        let mut v = match (not, runs.as_slice()) {
            (_, []) => Verification::none("not verified: no program of the file was found in its translation"),
            (Some((label, r)), _) if !label.is_empty() => {
                let v = Verification::of(r);
                Verification { summary: format!("in the run{label}: {}", v.summary), ..v }
            }
            (Some((_, r)), _) | (None, [(_, r)]) => Verification::of(r),
            (None, _) => {
                let mut excluded = crate::check::Excluded::default();
                runs.iter().for_each(|(_, r)| excluded.add(r.excluded.clone()));
                let events =
                    runs.iter().map(|(_, r)| if let Verdict::Equivalent { events } = r.verdict { events } else { 0 });
                let summary = called::Combined::summary(events.sum(), runs.len(), &excluded);
                Verification { equivalent: true, summary, ..Verification::default() }
            }
        };
        v.runs = runs;
        v
    }

    /// No verdict: `summary` says why.
    fn none(summary: &str) -> Verification {
        Verification { summary: summary.to_string(), ..Verification::default() }
    }
}

/// What a proof is given beyond the translation. A step limit alone (`max_steps.into()`)
/// proves a single file as `nctrans --to DIALECT` does.
#[derive(Clone, Debug)]
pub struct VerifyOptions<'a> {
    /// The step limit of each run.
    pub max_steps: u64,
    /// The two runs' control profiles (`None`: each dialect's default).
    pub profiles: Option<to_sinumerik::verify::Profiles>,
    /// `--set` inputs of every run (FANUC `#n=…` ones are mapped for the Siemens side).
    pub set: &'a [String],
    /// The library the file belongs to (a batch): its programs also run with the arguments
    /// the library's calls pass, and a program only another file calls runs too.
    pub library: Option<InLibrary<'a>>,
    /// FANUC → Sinumerik: a macro written for every possible caller (not
    /// `--specialise-callers`) also runs with each argument vacant (`called::cases`).
    pub each_vacant: bool,
}

/// A translated file's place in a library (see [`VerifyOptions::library`]).
#[derive(Clone, Copy, Debug)]
pub struct InLibrary<'a> {
    pub library: &'a crate::translate::library::Library,
    /// The file's index in the library.
    pub file: usize,
    /// The name the library knows the file's main program by when the program names
    /// itself none (its file stem, upper case).
    pub main_name: &'a str,
}

impl From<u64> for VerifyOptions<'static> {
    fn from(max_steps: u64) -> Self {
        VerifyOptions { max_steps, profiles: None, set: &[], library: None, each_vacant: true }
    }
}

/// Proves a translation of `inputs` (as given to [`translate`], in `db`): the output is read
/// back as the target (so it is valid syntax there), both programs run in the evaluator and
/// their traces are compared, once per run the options call for. `out` names the output in
/// diagnostics: the file on FANUC, the folder of the files on Sinumerik. Every path proves
/// through here: the command line, the batch jobs (with their library, profiles and `--set`).
pub fn verify<'a>(
    db: &mut SourceDb,
    inputs: &[&Unit],
    t: &Translation,
    out: &str,
    opts: impl Into<VerifyOptions<'a>>,
) -> Verification {
    let opts = opts.into();
    let Some((main, subs)) = inputs.split_first() else {
        return Verification::none("not verified: no program to run");
    };
    match t.target() {
        Dialect::Fanuc => to_fanuc::verify(db, main, subs, t, out, opts),
        Dialect::Sinumerik => Verification::of_runs(to_sinumerik::verify::runs(db, inputs, t, out, &opts)),
    }
}

/// The options of a translation: each target's own, and the output's line ending.
#[derive(Clone, Debug)]
pub struct Options {
    /// A translation to FANUC (its `line_ending` is [`Options::line_ending`]'s).
    pub fanuc: TranslateOptions,
    /// A translation to Sinumerik.
    pub sinumerik: to_sinumerik::Options,
    pub line_ending: LineEnding,
}

impl Default for Options {
    fn default() -> Self {
        Options { fanuc: TranslateOptions::default(), sinumerik: Default::default(), line_ending: LineEnding::Lf }
    }
}

impl Options {
    /// The options of a translation to FANUC (the output's line ending is `o`'s).
    pub fn to_fanuc(o: TranslateOptions) -> Options {
        Options { line_ending: o.line_ending, fanuc: o, ..Options::default() }
    }

    /// The options of a translation to Sinumerik.
    pub fn to_sinumerik(o: to_sinumerik::Options, line_ending: LineEnding) -> Options {
        Options { sinumerik: o, line_ending, ..Options::default() }
    }
}

/// Translates `inputs` to `to`: the main file's unit first, then the units of the files
/// its callees were found in. The source dialect is the units' own ([`Unit::dialect`]);
/// it must not be `to`. Refused constructs are errors (NC3xx) by default; under the warn
/// policy they are marked comments and the main program alarms on its first line.
pub fn translate(inputs: &[&Unit], to: Dialect, opts: &Options) -> Translation {
    debug_assert!(inputs.iter().all(|u| u.dialect != to), "a translation to the dialect it is in");
    match to {
        Dialect::Fanuc => {
            let Some((main, subs)) = inputs.split_first() else {
                return to_fanuc::to_fanuc(&empty(), &[], &opts.fanuc).into();
            };
            let fanuc = TranslateOptions { line_ending: opts.line_ending, ..opts.fanuc.clone() };
            to_fanuc::to_fanuc(main, subs, &fanuc).into()
        }
        Dialect::Sinumerik => to_sinumerik::translate(inputs, &opts.sinumerik, opts.line_ending),
    }
}

fn empty() -> Unit {
    Unit { dialect: Dialect::Sinumerik, file: 0, programs: vec![] }
}
