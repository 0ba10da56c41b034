//! Migration batch jobs: a whole program library in, a translated (and verified) library
//! and a per-file report out.
//!
//! The engine does not know how one file is translated: the work per file is a
//! [`FileJob`]. The engine finds the files ([`discover`]), reads what every program defines
//! and calls (`discover::scan` into `translate::library`), fixes one program, tool and variable map for the whole batch
//! ([`maps`]), runs the job over the files in parallel ([`run`]), writes every output
//! atomically ([`write`]) and summarises ([`report`]). Everything a file's output depends on
//! is decided before the parallel part, so the output does not depend on thread timing.
//!
//! Owns: the engine above and the one per-file job (`jobs`: read, translate through the one
//! entry, verify, outputs; what a target does as its own is its `jobs::Target`, in
//! [`target`]), and `streamed*`: a large file streamed.
//! May use: `config`, `stream`, `translate` (the entry, the proof, the library index),
//! `check`, `gud`, `same_file`, `lower`, `eval`, `dialect`, `ir`, base; never the command
//! line (`tests/layering.rs`).

mod callers;
pub mod discover;
pub mod jobs;
pub mod maps;
pub mod report;
pub mod run;
pub mod streamed;
mod streamed_calls;
mod streamed_macro;
pub mod target;
pub mod write;

use crate::dialect::Dialect;
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::sync::Arc;
use std::time::Duration;

pub use discover::InputFile;
pub use maps::BatchMaps;
pub use run::{run_batch, BatchError};

/// Name of the map file written into the output folder.
pub const MAP_FILE: &str = "nctrans-map.toml";

/// Input files this large are read and translated as a stream when they are straight-line
/// programs (the single-file commands use the same size, `cli::stream::AUTO_BYTES`).
pub const STREAM_BYTES: u64 = 8 * 1024 * 1024;

/// What happened to one file. (`report::rank` orders them by how bad they are.)
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Status {
    /// Translated, and the translation ran to the same trace as the source.
    Verified,
    /// In the target dialect already (or not a program of the source dialect): left alone.
    Skipped,
    /// Translated; verification was switched off (`--no-verify`).
    TranslatedUnverified,
    /// Verification hit a limit (steps, call depth) or could not decide.
    Inconclusive,
    /// A construct has no counterpart on the target.
    Unsupported,
    /// The translation runs differently from the source.
    Diverged,
    /// The input could not be read as a program.
    ParseError,
    /// The file could not be read or its output could not be written (exists, collides,
    /// disk error), or the run was stopped before it.
    Error,
}

impl Status {
    pub const ALL: [Status; 8] = [
        Status::Verified,
        Status::TranslatedUnverified,
        Status::Diverged,
        Status::Inconclusive,
        Status::Unsupported,
        Status::ParseError,
        Status::Error,
        Status::Skipped,
    ];

    /// The spelling in reports (`verified`, `translated-unverified`, …).
    pub fn as_str(self) -> &'static str {
        match self {
            Status::Verified => "verified",
            Status::TranslatedUnverified => "translated-unverified",
            Status::Diverged => "diverged",
            Status::Inconclusive => "inconclusive",
            Status::Unsupported => "unsupported",
            Status::ParseError => "parse-error",
            Status::Error => "error",
            Status::Skipped => "skipped",
        }
    }

    /// Whether the file's translation is written out. A failing file gets no output file.
    pub fn writes_output(self) -> bool {
        matches!(self, Status::Verified | Status::TranslatedUnverified)
    }

    /// Whether the file counts against the exit code (everything but verified and skipped).
    pub fn is_failure(self) -> bool {
        !matches!(self, Status::Verified | Status::Skipped)
    }
}

/// A diagnostic as the report keeps it: plain data, with the line and column resolved.
#[derive(Clone, Debug, PartialEq)]
pub struct DiagRecord {
    /// `error`, `warning` or `note`.
    pub severity: &'static str,
    pub code: String,
    pub message: String,
    /// The file the primary label is in (the input, a callee, or an output), as given to the job.
    pub file: Option<String>,
    /// 1-based line and column of the primary label.
    pub line: Option<usize>,
    pub column: Option<usize>,
}

impl DiagRecord {
    /// A batch-level error with no place in a file (I/O, collisions).
    pub fn error(code: &str, message: impl Into<String>) -> DiagRecord {
        DiagRecord {
            severity: "error",
            code: code.to_string(),
            message: message.into(),
            file: None,
            line: None,
            column: None,
        }
    }

    /// Converts library diagnostics, resolving the primary label's line and column in `db`.
    pub fn from_diags(db: &crate::span::SourceDb, diags: &[crate::diag::Diagnostic]) -> Vec<DiagRecord> {
        diags
            .iter()
            .map(|d| {
                let primary = d.labels.iter().find(|l| l.primary).or(d.labels.first());
                let (file, line, column) = match primary {
                    Some(l) if l.file < db.len() => {
                        let src = db.get(l.file);
                        let (line, col) = src.line_col(l.span.lo.min(src.text.len() as u32));
                        (Some(src.name.clone()), Some(line), Some(col))
                    }
                    _ => (None, None, None),
                };
                DiagRecord {
                    severity: match d.severity {
                        crate::diag::Severity::Error => "error",
                        crate::diag::Severity::Warning => "warning",
                        crate::diag::Severity::Note => "note",
                    },
                    code: d.code.to_string(),
                    message: d.message.clone(),
                    file,
                    line,
                    column,
                }
            })
            .collect()
    }
}

/// One file a job wants written: a path relative to the output folder and its bytes.
#[derive(Clone, Debug, PartialEq)]
pub struct OutputFile {
    pub rel: PathBuf,
    pub bytes: Vec<u8>,
}

/// What a job reports for one input file.
#[derive(Clone, Debug, PartialEq)]
pub struct FileOutcome {
    pub status: Status,
    /// The files to write (ignored unless `status.writes_output()`).
    pub outputs: Vec<OutputFile>,
    pub diagnostics: Vec<DiagRecord>,
    /// Trace events compared by verification.
    pub events: Option<u64>,
    /// Trace events verification knowingly left out (a `MSG` kept as a comment).
    pub excluded: crate::check::Excluded,
    /// Blocks read from the input (for blocks/s).
    pub blocks: u64,
    /// One line for people: `equivalent (120 events)`, the first divergence, …
    pub summary: String,
    /// The names this file's translation used (merged into the written map).
    pub used: maps::Used,
    /// Outputs the job wrote itself, whole, into the staging folder (a translation streamed
    /// as it was made, too large to hold): the path relative to the output folder and the
    /// staged file ([`write::staged_path`]). Committed like `outputs`, or removed.
    pub staged: Vec<(PathBuf, PathBuf)>,
    /// What the file's proof ran of the library, and whether it waits for its callers'
    /// (`run`: a program that cannot run alone, proven in its callers' runs).
    pub calls: CallProof,
}

/// A file's proof as its callers' proofs see it (see [`FileOutcome::calls`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CallProof {
    /// The programs of other files its equivalent runs called (`O9100`, `DRILL`).
    pub reached: std::collections::BTreeSet<String>,
    /// Every translated program its translation held, by target name, with a fingerprint
    /// of its text (comment lines left out): what those runs ran.
    pub ran: Vec<(String, u64)>,
    /// The file's runs alone were not conclusive (no divergence) and every program of it
    /// is called by another file: its outputs wait for its callers' verdicts.
    pub waits: bool,
    /// The fingerprints of the file's own translated programs (as in `ran`).
    pub own: Vec<(String, u64)>,
}

impl FileOutcome {
    pub fn new(status: Status, summary: impl Into<String>) -> FileOutcome {
        FileOutcome {
            status,
            outputs: vec![],
            diagnostics: vec![],
            events: None,
            excluded: Default::default(),
            blocks: 0,
            summary: summary.into(),
            used: maps::Used::default(),
            staged: vec![],
            calls: CallProof::default(),
        }
    }
}

/// Everything a job may read while it translates one file. Shared by all workers.
pub struct BatchContext {
    /// The batch's options.
    pub options: BatchOptions,
    /// Every input file of the batch, in batch order (`InputFile::index`).
    pub files: Vec<InputFile>,
    /// Every program in the library: who defines it, who calls it and how.
    pub library: crate::translate::library::Library,
    /// The program, tool and variable maps of the whole batch, fixed before any file runs.
    pub maps: BatchMaps,
    /// Set by Ctrl-C: a long job may stop early and report `Error` ("stopped").
    pub cancel: Arc<AtomicBool>,
}

/// The work done for one input file: translate, verify, produce outputs. Must be
/// deterministic: the same file and context give the same outcome.
pub trait FileJob: Sync {
    fn run(&self, file: &InputFile, ctx: &BatchContext) -> FileOutcome;
}

impl<F: Fn(&InputFile, &BatchContext) -> FileOutcome + Sync> FileJob for F {
    fn run(&self, file: &InputFile, ctx: &BatchContext) -> FileOutcome {
        self(file, ctx)
    }
}

/// How a batch runs.
#[derive(Clone, Debug)]
pub struct BatchOptions {
    /// The folder read (never written).
    pub input: PathBuf,
    /// The folder written.
    pub output: PathBuf,
    /// The dialect written.
    pub target: Dialect,
    /// Worker threads (at least 1).
    pub jobs: usize,
    /// Replace existing output files.
    pub force: bool,
    /// Verify every translation (off: `--no-verify`).
    pub verify: bool,
    /// Pinned maps (`--map FILE`, the project config, or `OUT/nctrans-map.toml` of an earlier run).
    pub pinned: BatchMaps,
    /// `--encoding`: decode every input with this encoding instead of detecting it.
    pub encoding: Option<&'static encoding_rs::Encoding>,
    /// Straight-line programs of this many bytes and more are read, translated and
    /// verified as a stream, in constant memory ([`STREAM_BYTES`]; 0 with `--stream`).
    pub stream_bytes: u64,
    /// FANUC → Sinumerik `--specialise-callers`: each macro written for the library's calls
    /// only (see `translate::to_sinumerik::Options::specialise_callers`).
    pub specialise_callers: bool,
    /// Sinumerik → FANUC `--l-numbers` (`[programs] l_numbers`): every program `L<k>` of the
    /// library is `O<k>`, so a `CALL "L"<<n` is `G65 P<n>` (`lower::to_fanuc::words::built`).
    pub l_numbers: bool,
}

impl BatchOptions {
    pub fn new(input: impl Into<PathBuf>, output: impl Into<PathBuf>, target: Dialect) -> BatchOptions {
        BatchOptions {
            input: input.into(),
            output: output.into(),
            target,
            jobs: default_jobs(),
            force: false,
            verify: true,
            pinned: BatchMaps::default(),
            encoding: None,
            stream_bytes: STREAM_BYTES,
            specialise_callers: false,
            l_numbers: false,
        }
    }

    /// The dialect read: the other one.
    pub fn source(&self) -> Dialect {
        match self.target {
            Dialect::Fanuc => Dialect::Sinumerik,
            Dialect::Sinumerik => Dialect::Fanuc,
        }
    }
}

/// The number of cores, the default for `-j`.
pub fn default_jobs() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// The result of one file, as reported.
#[derive(Clone, Debug, PartialEq)]
pub struct FileRecord {
    /// Input path relative to the input folder, `/`-separated.
    pub path: String,
    /// Output paths relative to the output folder (empty when nothing was written).
    pub outputs: Vec<String>,
    pub status: Status,
    pub summary: String,
    pub diagnostics: Vec<DiagRecord>,
    pub events: Option<u64>,
    /// Trace events verification knowingly left out of the comparison.
    pub excluded: crate::check::Excluded,
    pub blocks: u64,
    pub time: Duration,
}

/// What a batch did.
#[derive(Clone, Debug)]
pub struct BatchResult {
    /// One record per input file, in input order (sorted paths).
    pub files: Vec<FileRecord>,
    /// The maps written to `OUT/nctrans-map.toml`.
    pub maps: BatchMaps,
    /// Whether the map file was written (false when stopped or when nothing was translated).
    pub map_written: bool,
    /// Ctrl-C stopped the run: `files` holds what was done, the rest are `Error` ("not run").
    pub cancelled: bool,
    pub elapsed: Duration,
    pub jobs: usize,
}

impl BatchResult {
    /// True when every file (not skipped) verified; the exit code is 0 only then.
    pub fn all_verified(&self) -> bool {
        !self.cancelled && self.files.iter().all(|f| !f.status.is_failure())
    }

    pub fn count(&self, s: Status) -> usize {
        self.files.iter().filter(|f| f.status == s).count()
    }
}

/// Progress, reported to the caller's callback from one thread, in order.
#[derive(Clone, Debug)]
pub enum Progress<'a> {
    /// Discovery and the library scan are done; `total` files will run.
    Started { total: usize, skipped: usize },
    /// One file finished.
    FileDone { record: &'a FileRecord, done: usize, total: usize, failures: usize, elapsed: Duration },
    /// A note for the user (a pinned map read, leftovers of a killed run removed).
    Note(String),
}

/// The relative path as the report writes it: `/` separators on every platform.
pub fn rel_string(p: &Path) -> String {
    p.components().map(|c| c.as_os_str().to_string_lossy()).collect::<Vec<_>>().join("/")
}
