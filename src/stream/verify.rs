//! Verifying a streamed translation, for every target: reading the written output back as a
//! stream ([`read_back`]), and running source and output side by side with their traces
//! compared as they come ([`compare`]); [`verify`] is both for a translation to FANUC.

use super::{Index, ProgressFn};
use crate::check::{self, CheckReport, Runner};
use crate::diag::Diagnostic;
use crate::dialect::{Dialect, ParseOptions, Semantics};
use crate::eval::{CalleeSource, DirCallees, NoCallees, RunOptions};
use crate::span::{FileId, SourceDb};
use std::path::Path;
use std::sync::Arc;

/// Why a written translation cannot be compared with its source.
pub enum ReadBack {
    /// The file cannot be read back as a stream (I/O, not UTF-8, …).
    Unreadable(String),
    /// The output has diagnostics in its own dialect (a bug in the writer).
    Diags(Vec<Diagnostic>),
}

/// Reads a written translation back (streamed) as `dialect`, as file `file` of the check.
pub fn read_back(
    output: &Path,
    file: FileId,
    dialect: Dialect,
    popts: &ParseOptions,
    progress: Option<ProgressFn<'_>>,
) -> Result<Index, ReadBack> {
    let ix = super::scan_index_path(output, file, dialect, popts, progress)
        .map_err(|e| ReadBack::Unreadable(e.to_string()))?;
    if !ix.diags.is_empty() {
        return Err(ReadBack::Diags(ix.diags));
    }
    Ok(ix)
}

/// One program of a streamed check.
pub struct StreamSide {
    pub index: Index,
    /// The name diagnostics show for the file.
    pub name: String,
    pub callees: Box<dyn CalleeSource + Send>,
    pub run: RunOptions,
}

impl StreamSide {
    fn runner(self) -> Runner {
        super::runner(Arc::new(self.index), self.callees, self.run)
    }
}

/// Runs two streamed programs side by side and compares their traces as they come.
///
/// The check runs on a thread of its own, so its two runs are two threads whatever the
/// caller's mode: a batch worker's checks run in its one thread with the second trace
/// buffered (`check::in_one_thread`), which for a program of millions of blocks is
/// memory that grows with its length. A streamed check keeps both traces in step instead.
pub fn compare(a: StreamSide, b: StreamSide) -> CheckReport {
    compare_excluding(a, b, check::Exclude::default())
}

/// [`compare`] leaving out (and counting) what `exclude` names.
pub fn compare_excluding(a: StreamSide, b: StreamSide, exclude: check::Exclude) -> CheckReport {
    let mut db = SourceDb::new();
    // File ids are the indexes' own: the source 0, the translation 1.
    let (first, second) = if a.index.file <= b.index.file { (&a, &b) } else { (&b, &a) };
    while db.len() < first.index.file {
        db.add("", String::new());
    }
    db.add(first.name.clone(), String::new());
    while db.len() < second.index.file {
        db.add("", String::new());
    }
    db.add(second.name.clone(), String::new());
    let (ra, rb) = (a.runner(), b.runner());
    let fail_db = db.clone();
    let joined = std::thread::scope(|s| {
        let thread = std::thread::Builder::new().stack_size(crate::dialect::limits::THREAD_STACK);
        let check = || check::check_runners_excluding(&db, ra, rb, exclude);
        thread.spawn_scoped(s, check).expect("start the checker's thread").join()
    });
    joined.unwrap_or_else(|_| {
        let stopped =
            Diagnostic::error("NC499", "the streamed check stopped unexpectedly (please report this program)");
        CheckReport::failed(fail_db, vec![stopped])
    })
}

/// The outcome of verifying a streamed translation.
pub struct Verified {
    pub equivalent: bool,
    pub summary: String,
    /// Diagnostics of the output's parse or of the check (files: 0 source, 1 output).
    pub diags: Vec<Diagnostic>,
    pub diff: String,
    /// The files the runs loaded after the two (the callees, with their text: ids from 2
    /// up), for rendering `diags` as the whole path renders them.
    pub callees: Vec<(String, String)>,
}

/// Verifies a streamed translation to FANUC: the output is read back as FANUC (streamed),
/// then both programs run streamed side by side ([`compare_excluding`]) and their traces are
/// compared as they come. `inputs` are set on the output's side before it runs: for a
/// segmented translation the R parameters its symbol map maps start at 0, as
/// `translate::verify` sets them (a straight-line translation has none).
pub fn verify(
    source: Index,
    output: &Path,
    max_steps: u64,
    inputs: Vec<crate::eval::Input>,
    progress: Option<ProgressFn<'_>>,
) -> Verified {
    verify_for((source, SourceRun::default()), output, max_steps, inputs, false, progress)
}

/// How the source side of a streamed proof to FANUC runs (default: the default profile,
/// no inputs), as `translate::to_fanuc::main_proof` gives it.
#[derive(Default)]
pub struct SourceRun {
    /// The run's profile (with the global user data the translation mapped).
    pub semantics: Option<Semantics>,
    /// The profile the subprograms it calls are read with (the one the source was read with).
    pub callees: Option<Semantics>,
    pub inputs: Vec<crate::eval::Input>,
    /// The output's profile, read back and run (`None`: FANUC's default).
    pub output: Option<Semantics>,
}

/// [`verify`] of a translation for a target with the custom macro interrupt
/// (`Semantics::macro_interrupt`): its `M96`/`M97` are read back as interrupts; the source
/// runs as `src` says. Both runs meet the source's interrupt inputs (`nctrans: interrupt`),
/// as the whole path's proof does.
pub fn verify_for(
    (source, src): (Index, SourceRun),
    output: &Path,
    max_steps: u64,
    inputs: Vec<crate::eval::Input>,
    macro_interrupt: bool,
    progress: Option<ProgressFn<'_>>,
) -> Verified {
    let mut popts = ParseOptions::for_dialect(Dialect::Fanuc);
    if let Some(s) = &src.output {
        popts.semantics = s.clone();
    }
    popts.semantics.macro_interrupt |= macro_interrupt;
    let not_verified = |summary: String, diags: Vec<Diagnostic>| Verified {
        equivalent: false,
        summary: format!("not verified: {summary}"),
        diags,
        diff: String::new(),
        callees: Vec::new(),
    };
    let out_ix = match read_back(output, 1, Dialect::Fanuc, &popts, progress) {
        Ok(ix) => ix,
        Err(ReadBack::Unreadable(e)) => return not_verified(format!("the output cannot be read back ({e})"), vec![]),
        Err(ReadBack::Diags(d)) => {
            return not_verified("the output does not parse as FANUC (a bug in nctrans)".into(), d);
        }
    };
    let interrupts = crate::eval::header_interrupts(&source.header).unwrap_or_default();
    let run = RunOptions { max_steps, interrupts, ..RunOptions::default() };
    let out_semantics = src.output.is_some().then(|| popts.semantics.clone());
    let out_run = RunOptions { inputs, semantics: out_semantics, ..run.clone() };
    let run = RunOptions { semantics: src.semantics, inputs: src.inputs, ..run };
    let name = source.path.display().to_string();
    let a = StreamSide { index: source, name, callees: Box::new(DirCallees { semantics: src.callees }), run };
    let b =
        StreamSide { index: out_ix, name: output.display().to_string(), callees: Box::new(NoCallees), run: out_run };
    let report = compare_excluding(a, b, crate::translate::to_fanuc::EXCLUDE);
    let (equivalent, summary) = report.verdict_line();
    let callees =
        (2..report.db.len()).map(|id| (report.db.get(id).name.clone(), report.db.get(id).text.clone())).collect();
    Verified { equivalent, summary, diags: report.diags, diff: report.diff, callees }
}
