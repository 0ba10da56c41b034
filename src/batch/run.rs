//! The parallel engine: scan every file, fix the maps, run the job over the files on `-j`
//! worker threads, and commit the results strictly in input order, so the outputs, the
//! report and even the progress lines are the same whatever the thread timing. Ctrl-C sets
//! the cancel flag: workers finish the file they hold, take no new one, and what is done
//! is committed and reported.

use super::discover::{self, InputFile};
use super::maps;
use super::write::{WriteError, Writer};
use super::*;
use crate::translate::library::{self, Library};
use std::collections::{BTreeMap, HashMap};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc;
use std::time::Instant;

/// A problem that stops the batch before any file runs.
#[derive(Clone, Debug, PartialEq)]
pub enum BatchError {
    /// The input folder cannot be read.
    Input(String),
    /// The output folder cannot be created.
    Output(String),
    /// A batch that must not run, refused before anything is written: the folders overlap
    /// (NC610), the folder holds no program (NC611) or none in the source dialect (NC612).
    Refused { code: &'static str, message: String, hint: String },
}

impl std::fmt::Display for BatchError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            BatchError::Input(s) | BatchError::Output(s) => f.write_str(s),
            BatchError::Refused { code, message, hint } => write!(f, "{message} [{code}]\n  = hint: {hint}"),
        }
    }
}

/// A dialect as messages name it.
fn shown(d: Dialect) -> &'static str {
    match d {
        Dialect::Sinumerik => "Sinumerik",
        Dialect::Fanuc => "FANUC",
    }
}

/// Refuses input and output folders of which one is, or lies in, the other: outputs
/// written into the library would mix with the programs (and be read as inputs by the
/// next run), and inputs inside the output folder could be written over.
fn separate_folders(input: &Path, output: &Path, target: Dialect) -> Result<(), BatchError> {
    use crate::same_file::within;
    let (i, o) = (input.display(), output.display());
    let message = match (within(output, input), within(input, output)) {
        (true, true) => {
            format!("the output folder {o} is the input folder: the outputs would be written into the library")
        }
        (true, false) => {
            format!(
                "the output folder {o} lies inside the input folder {i}: the outputs would be written into the library"
            )
        }
        (false, true) => {
            format!("the input folder {i} lies inside the output folder {o}: outputs could land on the programs")
        }
        (false, false) => return Ok(()),
    };
    // A folder beside the library, named after it.
    let name = crate::same_file::resolved(input)
        .and_then(|p| p.file_name().map(|n| n.to_string_lossy().to_string()))
        .unwrap_or_else(|| "programs".into());
    let beside = format!("{name}-{}", target.name());
    let beside = match input.components().next_back() {
        Some(std::path::Component::Normal(_)) => input.with_file_name(beside),
        Some(std::path::Component::CurDir) if input.components().count() == 1 => Path::new("..").join(beside),
        _ => input.join("..").join(beside),
    };
    Err(BatchError::Refused {
        code: "NC610",
        message,
        hint: format!(
            "give an output folder that neither holds nor lies in the input folder, e.g. -o {}/",
            beside.display()
        ),
    })
}

/// Runs `work` on every item on `jobs` threads; `on_result` gets each result on the calling
/// thread as it arrives (in any order). Items are taken in order; after `cancel` is set no
/// new item is taken. A panicking `work` gives `None` for its item.
pub fn parallel<T: Sync, R: Send>(
    items: &[T],
    jobs: usize,
    cancel: &AtomicBool,
    work: &(dyn Fn(&T) -> R + Sync),
    on_result: &mut dyn FnMut(usize, Option<R>),
) {
    let next = AtomicUsize::new(0);
    let (tx, rx) = mpsc::channel::<(usize, Option<R>)>();
    std::thread::scope(|s| {
        for _ in 0..jobs.clamp(1, items.len().max(1)) {
            let tx = tx.clone();
            let next = &next;
            let worker = std::thread::Builder::new().stack_size(crate::dialect::limits::THREAD_STACK);
            // The same stack as the main thread (see `limits::THREAD_STACK`).
            let started = worker.spawn_scoped(s, move || loop {
                if cancel.load(Ordering::SeqCst) {
                    break;
                }
                let i = next.fetch_add(1, Ordering::SeqCst);
                let Some(item) = items.get(i) else { break };
                let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| work(item))).ok();
                if tx.send((i, r)).is_err() {
                    break;
                }
            });
            started.expect("start a batch worker");
        }
        drop(tx);
        for (i, r) in rx {
            on_result(i, r);
        }
    });
}

fn error_record(file: &InputFile, code: &str, msg: String) -> FileRecord {
    FileRecord {
        path: rel_string(&file.rel),
        outputs: vec![],
        status: Status::Error,
        summary: msg.clone(),
        diagnostics: vec![DiagRecord::error(code, msg)],
        events: None,
        excluded: Default::default(),
        blocks: 0,
        time: Duration::ZERO,
    }
}

/// Runs a batch: everything of the issue except the per-file translation, which is `job`.
/// `progress` is called on this thread, in input order.
pub fn run_batch(
    opts: BatchOptions,
    job: &dyn FileJob,
    cancel: Arc<AtomicBool>,
    progress: &mut dyn FnMut(Progress),
) -> Result<BatchResult, BatchError> {
    let start = Instant::now();
    if !opts.input.is_dir() {
        return Err(BatchError::Input(format!("{} is not a folder", opts.input.display())));
    }
    separate_folders(&opts.input, &opts.output, opts.target)?;
    let found = discover::discover(&opts.input, Some(&opts.output))
        .map_err(|e| BatchError::Input(format!("cannot read {}: {e}", opts.input.display())))?;
    let files = found.files;
    if files.is_empty() {
        return Err(BatchError::Refused {
            code: "NC611",
            message: format!("no NC program found in {} (nothing translated)", opts.input.display()),
            hint: "programs are files named .mpf .spf .nc .tap .fnc .cnc (any case) or O1234, in the folder \
                   and its subfolders; hidden folders are not entered"
                .into(),
        });
    }
    let jobs = opts.jobs.max(1);

    // 1. Read every file once: what it defines and calls.
    let mut scans: Vec<Option<library::Scan>> = vec![None; files.len()];
    let enc = opts.encoding;
    // A large straight-line program is read as a stream (see `streamed::library_scan`).
    let stream_bytes = opts.stream_bytes;
    let read = |f: &InputFile| {
        super::streamed::library_scan(f, enc, stream_bytes).unwrap_or_else(|| super::discover::scan(f, enc))
    };
    parallel(&files, jobs, &cancel, &read, &mut |i, s| scans[i] = s);
    let scans: Vec<library::Scan> = scans
        .into_iter()
        .map(|s| {
            s.unwrap_or_else(|| library::Scan {
                info: library::FileInfo {
                    read_error: Some("not read (stopped, or the reader failed)".into()),
                    ..Default::default()
                },
                ..Default::default()
            })
        })
        .collect();
    let scans = super::streamed::without_shared_streamed(scans, &files, enc);
    let mut library = Library::build(scans);
    library.l_numbers = opts.l_numbers && opts.target == Dialect::Fanuc;

    // 2. One set of maps for the batch.
    let stems: Vec<String> =
        files.iter().map(|f| f.rel.file_stem().and_then(|s| s.to_str()).unwrap_or("").to_string()).collect();
    let (maps, problems) = maps::allocate(&library, &opts.pinned, opts.target, &stems);
    for p in problems {
        progress(Progress::Note(p));
    }

    // 3. Which files run: those in the source dialect that could be read.
    let source = opts.source();
    let mut records: Vec<Option<FileRecord>> = vec![None; files.len()];
    let mut runnable: Vec<InputFile> = Vec::new();
    let mut skipped = 0;
    for (f, info) in files.iter().zip(&library.files) {
        if let Some(e) = &info.read_error {
            records[f.index] = Some(error_record(f, "NC600", e.clone()));
        } else if info.dialect != Some(source) {
            skipped += 1;
            // Say how its dialect was decided: a wrong extension is then seen at once.
            let how = match f.rel.extension().and_then(|e| e.to_str()) {
                Some(e) if super::discover::dialect_of_name(&f.rel).is_some() => format!("by its extension .{e}"),
                _ if super::discover::dialect_of_name(&f.rel).is_some() => "by its name".to_string(),
                _ => "judged from its content".to_string(),
            };
            let mut r = error_record(f, "", format!("already {}, {how}: left alone", opts.target.name()));
            r.status = Status::Skipped;
            r.diagnostics.clear();
            records[f.index] = Some(r);
        } else {
            runnable.push(f.clone());
        }
    }
    if runnable.is_empty() && skipped == files.len() {
        return Err(BatchError::Refused {
            code: "NC612",
            message: format!(
                "none of the {} program(s) in {} is {}: nothing to translate to {}",
                files.len(),
                opts.input.display(),
                shown(source),
                shown(opts.target)
            ),
            hint: format!(
                "they are {} already; --to {} translates them the other way",
                shown(opts.target),
                source.name()
            ),
        });
    }
    let inputs: Vec<PathBuf> = files.iter().map(|f| f.abs.clone()).collect();
    let (writer, stale) = Writer::new(&opts.output, opts.force, &inputs)
        .map_err(|e| BatchError::Output(format!("cannot create {}: {e}", opts.output.display())))?;
    if stale {
        progress(Progress::Note(format!(
            "removed the unfinished files of an earlier run that was killed ({}/{})",
            opts.output.display(),
            write::STAGING
        )));
    }
    if skipped > 0 {
        // Named (the first few), so a file whose extension says the wrong dialect is seen.
        let mut named: Vec<String> = records
            .iter()
            .flatten()
            .filter(|r| r.status == Status::Skipped)
            .take(10)
            .map(|r| format!("{} ({})", r.path, r.summary.trim_end_matches(": left alone")))
            .collect();
        if skipped > named.len() {
            named.push(format!("and {} more (see --report)", skipped - named.len()));
        }
        progress(Progress::Note(format!("left alone: {}", named.join(", "))));
    }
    progress(Progress::Started { total: runnable.len(), skipped });

    // 4. Translate in parallel; stage outputs in the workers, commit here in input order.
    let ctx = BatchContext { options: opts.clone(), files: files.clone(), library, maps, cancel: cancel.clone() };
    let work = |f: &InputFile| {
        let t0 = Instant::now();
        // One core per worker: the file's check runs in this thread (see check::in_one_thread).
        let outcome = crate::check::in_one_thread(|| job.run(f, &ctx));
        let mut staged = Vec::new();
        let mut stage_error = None;
        // A file waiting for its callers' verdicts (`callers`) is staged as one to write.
        let writes = outcome.status.writes_output() || outcome.calls.waits;
        if writes {
            for o in &outcome.outputs {
                match writer.stage(&o.bytes) {
                    Ok(s) => staged.push((o.rel.clone(), s)),
                    Err(e) => {
                        stage_error = Some(WriteError::Io(o.rel.clone(), e.to_string()));
                        break;
                    }
                }
            }
        }
        // Outputs the job wrote itself (streamed): staged already; removed when not kept.
        for (rel, path) in &outcome.staged {
            if !writes || stage_error.is_some() {
                let _ = std::fs::remove_file(path);
                continue;
            }
            match writer.adopt(path) {
                Ok(s) => staged.push((rel.clone(), s)),
                Err(e) => {
                    let _ = std::fs::remove_file(path);
                    stage_error = Some(WriteError::Io(rel.clone(), e.to_string()));
                }
            }
        }
        (outcome, staged, stage_error, t0.elapsed())
    };
    let total = runnable.len();
    let mut pending: BTreeMap<usize, _> = BTreeMap::new();
    let mut next_commit = 0usize;
    let mut claimed: HashMap<PathBuf, String> = HashMap::new();
    let mut done = 0usize;
    let mut failures = 0usize;
    let mut used_in_order: Vec<(usize, maps::Used)> = Vec::new();
    // Each committed file's status and proof, for the files that wait for their callers.
    let mut proofs: HashMap<usize, (Status, CallProof)> = HashMap::new();
    let mut waiting = Vec::new();
    let mut commit = |k: usize,
                      result: Option<(FileOutcome, _, _, _)>,
                      records: &mut Vec<Option<FileRecord>>,
                      (proofs, waiting): (&mut HashMap<usize, (Status, CallProof)>, &mut Vec<_>)| {
        let f = &runnable[k];
        if result.as_ref().is_some_and(|r| r.0.calls.waits) {
            waiting.push((k, result));
            return;
        }
        let proof = result.as_ref().map(|r| r.0.calls.clone()).unwrap_or_default();
        let rec = match result {
            None => error_record(
                f,
                "NC609",
                "internal error: the translation of this file failed (a bug in nctrans)".into(),
            ),
            Some((outcome, staged, stage_error, time)) => {
                let (rec, used) = commit_one(f, outcome, staged, stage_error, time, &writer, &mut claimed);
                used_in_order.push((k, used));
                rec
            }
        };
        proofs.insert(f.index, (rec.status, proof));
        done += 1;
        if rec.status.is_failure() {
            failures += 1;
        }
        progress(Progress::FileDone { record: &rec, done, total, failures, elapsed: start.elapsed() });
        records[f.index] = Some(rec);
    };
    parallel(&runnable, jobs, &cancel, &work, &mut |k, r| {
        pending.insert(k, r);
        while let Some(r) = pending.remove(&next_commit) {
            commit(next_commit, r, &mut records, (&mut proofs, &mut waiting));
            next_commit += 1;
        }
    });
    // Stopped: commit what finished after a hole, still in order.
    let cancelled = cancel.load(Ordering::SeqCst) && (next_commit < total || !pending.is_empty());
    for (k, r) in std::mem::take(&mut pending) {
        commit(k, r, &mut records, (&mut proofs, &mut waiting));
    }
    // The files that wait for their callers, now that those are committed.
    let names = |i: usize| files.get(i).map_or_else(String::new, |f| rel_string(&f.rel));
    for (k, r) in std::mem::take(&mut waiting) {
        let Some(mut r) = r else { continue };
        let f = &runnable[k];
        r.0.calls.waits = false;
        match callers::proven_by_callers(f.index, &r.0.calls, &ctx.library, &proofs, &names) {
            Some(summary) => {
                r.0.summary = format!("{summary} (alone: {})", r.0.summary);
                r.0.status = Status::Verified;
                // The run alone's findings stay, as notes: they say why it is not its proof.
                for d in &mut r.0.diagnostics {
                    d.severity = "note";
                    d.message = format!("alone: {}", d.message);
                }
            }
            None => r.0.outputs.clear(),
        }
        commit(k, Some(r), &mut records, (&mut proofs, &mut waiting));
    }

    // 5. The map file: the batch's maps plus what the translations used.
    let mut maps = ctx.maps.clone();
    used_in_order.sort_by_key(|(k, _)| *k);
    for (_, used) in &used_in_order {
        for c in maps.merge_used(used) {
            progress(Progress::Note(format!("variables disagree between files: {c}; map it with --var-map")));
        }
    }
    let map_text = maps::to_toml(&maps, opts.target);
    let map_rel = Path::new(MAP_FILE);
    let existing = std::fs::read(opts.output.join(map_rel)).ok();
    let map_written = if existing.as_deref() == Some(map_text.as_bytes()) {
        true
    } else {
        match writer.write(map_rel, map_text.as_bytes()) {
            Ok(()) => true,
            Err(e) => {
                progress(Progress::Note(format!("map not written: {}", e.message())));
                false
            }
        }
    };
    if let Err(e) = writer.finish() {
        progress(Progress::Note(format!("cannot remove the staging folder {}: {e}", write::STAGING)));
    }
    let files_out = files
        .iter()
        .zip(records)
        .map(|(f, r)| r.unwrap_or_else(|| error_record(f, "NC605", "not run: the batch was stopped (Ctrl-C)".into())))
        .collect();
    Ok(BatchResult { files: files_out, maps, map_written, cancelled, elapsed: start.elapsed(), jobs })
}

/// Commits one file's staged outputs (or discards them) and builds its record.
fn commit_one(
    f: &InputFile,
    outcome: FileOutcome,
    staged: Vec<(PathBuf, write::Staged)>,
    stage_error: Option<WriteError>,
    time: Duration,
    writer: &Writer,
    claimed: &mut HashMap<PathBuf, String>,
) -> (FileRecord, maps::Used) {
    let path = rel_string(&f.rel);
    let mut rec = FileRecord {
        path: path.clone(),
        outputs: vec![],
        status: outcome.status,
        summary: outcome.summary,
        diagnostics: outcome.diagnostics,
        events: outcome.events,
        excluded: outcome.excluded,
        blocks: outcome.blocks,
        time,
    };
    let fail = |rec: &mut FileRecord, code: &str, msg: String| {
        rec.status = Status::Error;
        rec.summary = msg.clone();
        rec.diagnostics.push(DiagRecord::error(code, msg));
    };
    if let Some(e) = stage_error {
        fail(&mut rec, e.code(), e.message());
    } else if outcome.status.writes_output() {
        // Check every output before writing any, so a file is written whole or not at all.
        for (rel, _) in &staged {
            if let Some(other) = claimed.get(rel) {
                fail(&mut rec, "NC604", format!("{} is also the output of {other}; not written", rel_string(rel)));
                break;
            }
            if let Err(e) = writer.check(rel) {
                fail(&mut rec, e.code(), e.message());
                break;
            }
        }
    }
    if rec.status.writes_output() {
        let mut written: Vec<PathBuf> = Vec::new();
        let mut iter = staged.into_iter();
        for (rel, s) in iter.by_ref() {
            match writer.commit(s, &rel) {
                Ok(()) => written.push(rel),
                Err(e) => {
                    // Undo: a failing file leaves no output.
                    for w in &written {
                        let _ = std::fs::remove_file(writer.root().join(w));
                    }
                    written.clear();
                    fail(&mut rec, e.code(), e.message());
                    break;
                }
            }
        }
        for (_, s) in iter {
            writer.discard(s);
        }
        for w in &written {
            claimed.insert(w.clone(), path.clone());
        }
        rec.outputs = written.iter().map(|w| rel_string(w)).collect();
        (rec, outcome.used)
    } else {
        for (_, s) in staged {
            writer.discard(s);
        }
        (rec, maps::Used::default())
    }
}
