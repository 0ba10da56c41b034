//! Verifying a streamed translation: reading the written output back as a stream, and
//! running source and output side by side with their traces compared as they come.

use super::*;

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
    let ix = crate::stream::scan_index_path(output, file, dialect, popts, progress)
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
        crate::stream::runner(Arc::new(self.index), self.callees, self.run)
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
        let none = || Outcome { ending: Ending::Error, steps: 0, diags: vec![] };
        CheckReport {
            verdict: Verdict::Failed,
            excluded: Default::default(),
            db: fail_db,
            diags: vec![Diagnostic::error(
                "NC499",
                "the streamed check stopped unexpectedly (please report this program)",
            )],
            diff: String::new(),
            outcome_a: none(),
            outcome_b: none(),
        }
    })
}
