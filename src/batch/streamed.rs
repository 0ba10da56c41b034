//! Large programs in a batch: read for the library index, translated and verified as a
//! stream (`crate::stream`), in memory that follows the macro part, not the motion part. A
//! file of `BatchOptions::stream_bytes` (8 MB) and more whose dialect its name tells (in
//! any encoding: a legacy one is read from a decoded UTF-8 copy, `stream::transcode`, and
//! its output written as UTF-8, verified, then encoded), holding one program that no other
//! file of the batch calls or defines again and that calls nothing, or (Sinumerik) only
//! subprograms by a constant name, is read for the library as a stream; its job then tries
//! the streamed translators (straight-line, then segmented: `streamed_macro.rs`), which
//! write its output
//! straight into the staging folder (then committed atomically like any other), and its
//! report entry (status, summary, events, blocks, diagnostics with their lines) is what the
//! whole-file job gives. A Sinumerik main calling `.spf` subprograms of the batch streams to
//! FANUC with them (`segmented::to_fanuc_with_subs`, the callees read whole as the
//! whole-file job reads them, and verified against them as it verifies; any verdict but an
//! equivalence is left to the whole-file job). A FANUC main calling subprograms by a
//! constant number (its own after `M30`, other files') streams to Sinumerik with them
//! likewise (`streamed_calls.rs`, `segmented::to_sinumerik_with_subs`). Anything else, or a
//! file every streamed translator declines, is left to the whole-file job.

use super::discover::{self, InputFile};
use super::jobs::{self, apply, combine, Job, Verified};
use super::streamed_calls;
use super::streamed_macro::{self, LibItems};
use super::target::fanuc::{self as target_fanuc, Fanuc};
use super::target::sinumerik::{self as target_sinumerik, Sinumerik};
use super::{rel_string, write, BatchContext, DiagRecord, FileOutcome, Status};
use crate::check::{CheckReport, Verdict};
use crate::diag::Diagnostic;
use crate::dialect::{Dialect, ParseOptions, Semantics};
use crate::eval::{header_inputs, CalleeSource, Ending, NoCallees, Outcome, RunOptions};
use crate::ir::{ProgName, Unit};
use crate::read::LineEnding;
use crate::span::{FileId, SourceDb};
use crate::stream;
use crate::stream::lines::{first_line_ending, has_bom, Lines, NotStreamable};
use crate::stream::segmented::LoadCallees;
use crate::stream::transcode::{self, TempCopy, TempFile};
use crate::stream::verify::{self as sv, ReadBack, StreamSide};
use crate::stream::Fallback;
use crate::translate;
use crate::translate::called::{parse_all, siemens_inputs, MemCallees};
use crate::translate::library::{self, FileInfo, ProgKey, Scan};
use std::collections::BTreeMap;
use std::io::Write;
use std::path::Path;

/// Runs `attempt` on the file itself, or on a decoded copy when `--encoding` names a legacy
/// encoding or (only then, so a UTF-8 file costs nothing extra) when the attempt on the file
/// itself fails and the file is not UTF-8. `None` when it fails either way.
fn with_source<T>(
    abs: &Path,
    forced: Option<&'static encoding_rs::Encoding>,
    mut attempt: impl FnMut(&Path, Option<&TempCopy>) -> Option<T>,
) -> Option<T> {
    if !transcode::needs_copy(forced) {
        if let Some(t) = attempt(abs, None) {
            return Some(t);
        }
    }
    let copy = transcode::copy(abs, forced).ok()??;
    attempt(copy.path(), Some(&copy))
}

/// The source's encoding and byte-order mark as `read::decode` decides them, and its first
/// line ending.
fn source_form(abs: &Path, copy: Option<&TempCopy>) -> Option<(&'static encoding_rs::Encoding, bool, LineEnding)> {
    match copy {
        Some(c) => Some((c.detected.encoding, c.detected.bom, c.detected.line_ending)),
        None => Some((encoding_rs::UTF_8, has_bom(abs).ok()?, first_line_ending(abs).ok()?)),
    }
}

/// Encodes the UTF-8 translation `utf8` into the staged output `part` (on disk before the
/// rename into place, like every staged output); nothing is left at `part` on failure.
fn encode_part(utf8: &Path, enc: &'static encoding_rs::Encoding, bom: bool, part: &Path) -> Option<()> {
    let done = (|| {
        let mut w = std::io::BufWriter::with_capacity(1 << 16, std::fs::File::create(part)?);
        transcode::encode_to(utf8, enc, bom, &mut w)?;
        w.into_inner().map_err(|e| e.into_error())?.sync_data()
    })();
    if done.is_err() {
        let _ = std::fs::remove_file(part);
    }
    done.ok()
}

/// Reads `f` for the library index as a stream when it is at least `stream_bytes` long, its
/// name tells its dialect, it is UTF-8 (or no other encoding is forced) and it holds one
/// program without diagnostics (FANUC: one or more) that calls nothing, or only by a
/// constant name (Sinumerik, `segmented::calls_plain`) or number (FANUC `M98`/`G65`/`G66`);
/// `None` otherwise (the caller reads it whole). What it
/// reports is what `library::scan` reports (its calls, tools and FANUC commons too), but the
/// fingerprints (see
/// [`without_shared_streamed`]).
pub fn library_scan(
    f: &InputFile,
    encoding: Option<&'static encoding_rs::Encoding>,
    stream_bytes: u64,
) -> Option<Scan> {
    if std::fs::metadata(&f.abs).ok()?.len() < stream_bytes {
        return None;
    }
    if crate::dialect::empty::may_be_program_less(&f.abs) {
        return None;
    }
    let dialect = discover::dialect_of_name(&f.rel)?;
    let scan = |path: &Path| {
        let mut items = LibItems::default();
        let mut each = |_: usize, s: &crate::ir::Stmt| {
            if !items.other_calls {
                items.stmt(dialect, s);
            }
        };
        let r = stream::scan_path(path, 0, dialect, &ParseOptions::for_dialect(dialect), &mut each, None);
        r.map(|ix| (ix, items))
    };
    // A file that is not UTF-8 is scanned again from a decoded copy (only then).
    let mut copy = None;
    if transcode::needs_copy(encoding) {
        copy = Some(transcode::copy(&f.abs, encoding).ok()??);
    }
    let mut r = scan(copy.as_ref().map_or(f.abs.as_path(), |c: &TempCopy| c.path()));
    if copy.is_none() && matches!(r, Err(NotStreamable::NotUtf8 { .. })) {
        copy = Some(transcode::copy(&f.abs, encoding).ok()??);
        r = scan(copy.as_ref().map_or(f.abs.as_path(), |c: &TempCopy| c.path()));
    }
    let (ix, items) = r.ok()?;
    // A FANUC file may hold subprograms after the main one (a Siemens file's key is its
    // name only when it holds one program).
    let programs_ok = match dialect {
        Dialect::Fanuc => !ix.programs.is_empty(),
        Dialect::Sinumerik => ix.programs.len() == 1,
    };
    if items.other_calls || !ix.diags.is_empty() || !programs_ok {
        return None;
    }
    // The calls' lines, as `library::scan` gives them from the (decoded) text.
    let offsets: Vec<u32> = items.calls.iter().map(|(lo, _)| *lo).collect();
    let lines = if offsets.is_empty() {
        Vec::new()
    } else {
        positions(copy.as_ref().map_or(f.abs.as_path(), |c: &TempCopy| c.path()), &offsets)
    };
    let stem = f.rel.file_stem().and_then(|s| s.to_str()).unwrap_or("").to_ascii_uppercase();
    let mut scan = Scan {
        info: FileInfo {
            dialect: Some(dialect),
            blocks: ix.blocks,
            streamed: true,
            tools: items.tools,
            commons: items.commons,
            ..FileInfo::default()
        },
        calls: items.calls.into_iter().zip(lines).map(|((_, c), (line, _))| library::RawCall { line, ..c }).collect(),
        ..Scan::default()
    };
    for p in &ix.programs {
        let key = match (&p.program.name, dialect) {
            (Some(ProgName::Number(n)), _) => Some(ProgKey::Number(*n)),
            (Some(ProgName::Name(n)), _) => Some(ProgKey::Name(n.to_ascii_uppercase())),
            (None, Dialect::Sinumerik) if !stem.is_empty() => Some(ProgKey::Name(stem.clone())),
            (None, _) => None,
        };
        scan.info.programs.push(key.clone());
        scan.info.fingerprints.push(0);
        scan.defined.push((key, p.program.params.iter().map(|q| q.name.to_ascii_uppercase()).collect()));
    }
    Some(scan)
}

/// The scans with every streamed one whose program another file also defines read again
/// whole: which of two definitions is a copy of the other is told by the fingerprints of
/// their texts, which a streamed scan does not compute.
pub fn without_shared_streamed(
    mut scans: Vec<Scan>,
    files: &[InputFile],
    encoding: Option<&'static encoding_rs::Encoding>,
) -> Vec<Scan> {
    let mut defined_in: BTreeMap<&ProgKey, usize> = BTreeMap::new();
    for s in &scans {
        let mut keys: Vec<&ProgKey> = s.defined.iter().filter_map(|(k, _)| k.as_ref()).collect();
        keys.sort();
        keys.dedup();
        for k in keys {
            *defined_in.entry(k).or_default() += 1;
        }
    }
    let shared: Vec<usize> = scans
        .iter()
        .enumerate()
        .filter(|(_, s)| {
            s.info.streamed && s.defined.iter().flat_map(|(k, _)| k).any(|k| defined_in.get(k).is_some_and(|n| *n > 1))
        })
        .map(|(i, _)| i)
        .collect();
    for i in shared {
        if let Some(f) = files.get(i) {
            scans[i] = super::discover::scan(f, encoding);
        }
    }
    scans
}

/// Whether the job may stream `file`: the library scan streamed it, and no other file calls
/// its program, is called by it or defines it too.
fn streamable(file: &InputFile, ctx: &BatchContext) -> bool {
    ctx.library.callee_files(file.index).is_empty() && streamed_alone(file, ctx)
}

/// Whether the library scan streamed `file` and no file calls its program or defines it too.
fn streamed_alone(file: &InputFile, ctx: &BatchContext) -> bool {
    let lib = &ctx.library;
    let Some(info) = lib.files.get(file.index) else { return false };
    info.streamed
        && info.programs.iter().flatten().all(|k| {
            lib.programs.get(k).is_some_and(|p| p.file == file.index)
                && !lib.is_called(k)
                && !lib.duplicates.contains_key(k)
        })
}

/// The files of the programs a Sinumerik main `file` calls (as `jobs::load_with_callees`
/// loads them for the whole job), when its job may stream it with them: the library scan
/// streamed it (its calls are plain), no file calls its program or defines it too, each
/// call names a program of another file, and every callee file is a Sinumerik subprogram
/// file (`.spf`, read whole by the loader) defining one program no other file defines.
fn streamable_with_callees(file: &InputFile, ctx: &BatchContext) -> Option<Vec<usize>> {
    let lib = &ctx.library;
    if !streamed_alone(file, ctx) {
        return None;
    }
    for c in lib.calls.iter().filter(|c| c.file == file.index) {
        if lib.programs.get(&c.target)?.file == file.index {
            return None;
        }
    }
    let callees = lib.callee_files(file.index);
    for &i in &callees {
        let (info, f) = (lib.files.get(i)?, ctx.files.get(i)?);
        let spf = f.rel.extension().is_some_and(|e| e.eq_ignore_ascii_case("spf"));
        let one = matches!(&info.programs[..], [Some(k)] if !lib.duplicates.contains_key(k));
        if !spf || !one || info.parse_errors > 0 || info.dialect != Some(Dialect::Sinumerik) {
            return None;
        }
    }
    Some(callees)
}

/// Streams a translation into the file's staged output; on `Err` (the translator's error,
/// `None` for one of writing) nothing is left there.
pub(super) fn write_part<T, E>(
    part: &Path,
    bom: bool,
    translate: impl FnOnce(&mut dyn Write) -> Result<T, E>,
) -> Result<T, Option<E>> {
    let file = std::fs::File::create(part).map_err(|_| None)?;
    let mut w = std::io::BufWriter::with_capacity(1 << 16, file);
    let done = (|| {
        if bom {
            w.write_all(b"\xEF\xBB\xBF").map_err(|_| None)?;
        }
        let t = translate(&mut w).map_err(Some)?;
        // On disk before the rename into place, like every staged output.
        let f = w.into_inner().map_err(|_| None)?;
        f.sync_data().map_err(|_| None)?;
        Ok(t)
    })();
    if done.is_err() {
        let _ = std::fs::remove_file(part);
    }
    done
}

/// The 1-based line and column (in characters) of text offsets of a file, as
/// `SourceFile::line_col` gives them in the whole text, in one pass over the file.
fn positions(path: &Path, offsets: &[u32]) -> Vec<(usize, usize)> {
    let mut order: Vec<usize> = (0..offsets.len()).collect();
    order.sort_by_key(|&i| offsets[i]);
    let mut out = vec![(1, 1); offsets.len()];
    let Ok((input, _)) = stream::open(path) else { return out };
    let Ok(mut lines) = Lines::new(input) else { return out };
    let mut k = 0;
    let mut last = 0usize;
    while k < order.len() {
        let Ok(Some(l)) = lines.next_line() else { break };
        last = l.line as usize;
        // The last line (no line end) holds every offset up to the end of the text.
        let end = l.next == l.start + l.text.len() as u64;
        while k < order.len() && (u64::from(offsets[order[k]]) < l.next || end) {
            let at = (u64::from(offsets[order[k]]).saturating_sub(l.start)) as usize;
            let col = match l.text.get(..at.min(l.text.len())) {
                Some(t) => t.chars().count() + at.saturating_sub(l.text.len()),
                None => at,
            };
            out[order[k]] = (l.line as usize, col + 1);
            k += 1;
        }
    }
    // Past the last line end: the empty line after it.
    for &i in &order[k..] {
        out[i] = (last + 1, 1);
    }
    out
}

/// Report records of diagnostics that point into streamed files (id, name, path).
fn records(diags: &[Diagnostic], files: &[(FileId, &str, &Path)]) -> Vec<DiagRecord> {
    let mut db = SourceDb::new();
    for (id, name, _) in files {
        while db.len() < *id {
            db.add("", String::new());
        }
        db.add(name.to_string(), String::new());
    }
    let mut out = DiagRecord::from_diags(&db, diags);
    for (id, name, path) in files {
        let at: Vec<(usize, u32)> = diags
            .iter()
            .enumerate()
            .filter_map(|(i, d)| {
                let l = d.labels.iter().find(|l| l.primary).or(d.labels.first())?;
                (l.file == *id).then_some((i, l.span.lo))
            })
            .collect();
        let offsets: Vec<u32> = at.iter().map(|(_, lo)| *lo).collect();
        for ((i, _), (line, col)) in at.iter().zip(positions(path, &offsets)) {
            out[*i].file = Some(name.to_string());
            out[*i].line = Some(line);
            out[*i].column = Some(col);
        }
    }
    out
}

/// The verdict of one streamed check, as the whole-file jobs combine it, with the
/// diagnostics' lines read from the streamed files.
fn verdict(runs: Vec<(String, CheckReport)>, files: &[(FileId, &str, &Path)]) -> Verified {
    let diags = runs.first().map(|(_, r)| r.diags.clone()).unwrap_or_default();
    let mut v = combine(runs);
    if !v.diagnostics.is_empty() {
        v.diagnostics = records(&diags, files);
    }
    v
}

/// A check that could not run (the output does not read back, a bad header line).
fn failed(diags: Vec<Diagnostic>) -> CheckReport {
    let none = || Outcome { ending: Ending::Error, steps: 0, diags: vec![] };
    CheckReport {
        verdict: Verdict::Failed,
        excluded: Default::default(),
        db: SourceDb::new(),
        diags,
        diff: String::new(),
        outcome_a: none(),
        outcome_b: none(),
    }
}

fn run_options(inputs: Vec<crate::eval::Input>, max_steps: u64, sem: &Semantics) -> RunOptions {
    RunOptions { inputs, max_steps, semantics: Some(sem.clone()), ..RunOptions::default() }
}

/// FANUC → Sinumerik for a streamable file (see the module documentation); `None` leaves
/// the file to the whole-file job.
pub fn to_sinumerik(job: &Job<Sinumerik>, file: &InputFile, ctx: &BatchContext) -> Option<FileOutcome> {
    if job.fault.is_some() {
        return None;
    }
    // A main that calls subprograms (its own after M30, other files'): with its callees.
    let callees = if streamable(file, ctx) { None } else { Some(streamed_calls::callees(file, ctx)?) };
    let callees = callees.as_deref();
    with_source(&file.abs, ctx.options.encoding, |path, copy| to_sinumerik_from(job, file, ctx, path, copy, callees))
}

/// [`to_sinumerik`] reading `path` (the file, or its decoded `copy`), with the `callees`
/// files of a main that calls subprograms (`streamed_calls`).
fn to_sinumerik_from(
    job: &Job<Sinumerik>,
    file: &InputFile,
    ctx: &BatchContext,
    path: &Path,
    copy: Option<&TempCopy>,
    callees: Option<&[usize]>,
) -> Option<FileOutcome> {
    let s = &job.settings;
    let opts = job.options(ctx, file).ok()?;
    let (enc, bom, first_eol) = source_form(&file.abs, copy)?;
    let out_enc = s.output_encoding.unwrap_or(enc);
    let eol = s.line_ending(first_eol);
    let part = write::staged_path(&ctx.options.output, file.index);
    // Not UTF-8 in or out: the stream writes UTF-8 (with the UTF-8 source's mark, which
    // `encode_to` drops) into a temporary file, encoded into `part` and read back from there.
    let utf8 = (copy.is_some() || out_enc != encoding_rs::UTF_8).then(|| TempFile::new("batch.utf8.mpf"));
    let target = utf8.as_ref().map_or(part.as_path(), |u| u.path());
    // The callees' units, kept for the verifier's source side; the translation's other
    // files (the file's own subprograms, the callees'), for its Siemens side.
    let mut units: Vec<Unit> = Vec::new();
    let mut skeleton: Option<Unit> = None;
    let (done, subs) = match callees {
        None => (streamed_macro::to_sinumerik_part(path, &opts, eol, target)?, Vec::new()),
        Some(c) => {
            // The stand-in caller (if any) is translated with them, as the whole job does,
            // but neither run nor written.
            let mut load = |main: &Unit| {
                let stand_in;
                skeleton = Some(main.clone());
                (units, stand_in) = streamed_calls::load(job, ctx, file, main, c)?;
                Ok(units.iter().cloned().chain(stand_in).collect())
            };
            let stand_in = streamed_calls::stand_in_id(c);
            streamed_macro::to_sinumerik_subs_part(path, &opts, eol, target, &mut load, stand_in)?
        }
    };
    let with_calls = callees.is_some();
    if let Some(u) = &utf8 {
        encode_part(u.path(), out_enc, bom, &part)?;
    }
    // Declined after the main's output is staged: nothing of the file is left staged.
    let decline = || {
        let _ = std::fs::remove_file(&part);
        None
    };
    let read_back = utf8.as_ref().map_or(part.as_path(), |u| u.path());
    let name = rel_string(&file.rel);
    let rel_out = discover::sinumerik_output(&file.rel, &done.program, false);
    let mut outcome = FileOutcome::new(Status::TranslatedUnverified, "translated, not verified (--no-verify)");
    outcome.blocks = done.index.blocks;
    let programs: Vec<(Option<u32>, &str)> = std::iter::once((done.fanuc_number, done.program.as_str()))
        .chain(streamed_calls::own(&subs).map(|f| (f.fanuc_number, f.program.as_str())))
        .collect();
    outcome.used = target_sinumerik::used_names(&programs, &done.symbols);
    outcome.diagnostics = records(&done.diags, &[(0, &name, path)]);
    outcome.staged = vec![(rel_out, part.clone())];
    // The main file first, then its subprograms, as the whole job lists its outputs.
    let stage_subs = |outcome: &mut FileOutcome| match streamed_calls::stage_own(file, ctx, &subs, out_enc, bom) {
        Some(more) => {
            outcome.staged.extend(more);
            Some(())
        }
        None => {
            let _ = std::fs::remove_file(&part);
            None
        }
    };
    if !ctx.options.verify {
        stage_subs(&mut outcome)?;
        return Some(outcome);
    }
    // As `Job<Sinumerik>::verify` runs a file's only program: its header inputs and `--set`.
    let out_dir = rel_string(file.rel.parent().unwrap_or(Path::new("")));
    let shown = if out_dir.is_empty() { done.file_name.clone() } else { format!("{out_dir}/{}", done.file_name) };
    let files: [(FileId, &str, &Path); 2] = [(0, &name, path), (1, &shown, read_back)];
    let mut fanuc = s.set.clone();
    let header = done.index.header.clone();
    let symbols = crate::translate::Symbols::Sinumerik(done.symbols.clone());
    let tr = crate::translate::Translation { files: vec![], symbols, diags: vec![], unsupported: 0 };
    let siemens = siemens_inputs(&tr, &done.program, &fanuc);
    fanuc.retain(|x| x.trim_start().starts_with('#'));
    let report =
        match sv::read_back(read_back, 1, Dialect::Sinumerik, &ParseOptions { semantics: s.sinumerik.clone() }, None) {
            Ok(back) => match (header_inputs(&done.index.header), header_inputs(&back.header)) {
                (Ok(mut a), Ok(mut b)) => {
                    a.extend(parse_all(&fanuc));
                    b.extend(parse_all(&siemens));
                    // The callees as the whole job's verifier serves them: the FANUC units
                    // loaded, the translation's other files under the names it shows them.
                    let (a_callees, b_callees): (Box<dyn CalleeSource + Send>, Box<dyn CalleeSource + Send>) =
                        if with_calls {
                            let shown =
                                |n: &str| if out_dir.is_empty() { n.to_string() } else { format!("{out_dir}/{n}") };
                            let files =
                                subs.iter().map(|f| (f.program.clone(), shown(&f.name), f.text.clone())).collect();
                            let emitted = crate::translate::to_sinumerik::verify::Emitted {
                                files,
                                semantics: s.sinumerik.clone(),
                            };
                            (Box::new(MemCallees(units.clone())), Box::new(emitted))
                        } else {
                            (Box::new(NoCallees), Box::new(NoCallees))
                        };
                    let a = StreamSide {
                        index: done.index,
                        name: name.clone(),
                        callees: a_callees,
                        run: run_options(a, s.max_steps, &s.fanuc),
                    };
                    let b = StreamSide {
                        index: back,
                        name: shown.clone(),
                        callees: b_callees,
                        run: run_options(b, s.max_steps, &s.sinumerik),
                    };
                    sv::compare(a, b)
                }
                (Err(e), _) | (_, Err(e)) => {
                    failed(vec![Diagnostic::error("NC407", format!("bad `nctrans: set` header line: {e}"))])
                }
            },
            // With calls the whole job gives this verdict (see below).
            Err(_) if with_calls => return decline(),
            Err(ReadBack::Diags(mut d)) => {
                d.push(Diagnostic::error("NC372", "the translation does not read back as Sinumerik"));
                failed(d)
            }
            Err(ReadBack::Unreadable(e)) => {
                failed(vec![Diagnostic::error("NC372", format!("the translation cannot be read back: {e}"))])
            }
        };
    // With calls, only an equivalence is taken: the diagnostics of any other verdict may
    // point into a callee or subprogram file, which the streamed records do not name as
    // the whole job does; the whole job then gives that verdict itself.
    if with_calls && !matches!(report.verdict, Verdict::Equivalent { .. }) {
        return decline();
    }
    // The file's own macros alone, as the whole job runs them after its main program.
    let mut runs = vec![(String::new(), report)];
    if let (true, Some(main)) = (with_calls, &skeleton) {
        let got = streamed_calls::macro_runs(job, ctx, file, (main, &header), &units, (&subs, &done.symbols), &out_dir);
        match got {
            Some(more) => runs.extend(more),
            None => return decline(),
        }
    }
    apply(&mut outcome, verdict(runs, &files));
    stage_subs(&mut outcome)?;
    Some(outcome)
}

/// Sinumerik → FANUC for a streamable file (see the module documentation); `None` leaves
/// the file to the whole-file job.
pub fn to_fanuc(job: &Job<Fanuc>, file: &InputFile, ctx: &BatchContext) -> Option<FileOutcome> {
    let s = &job.settings;
    // The stream reads the Siemens file with the default profile.
    if job.fault.is_some() || s.sinumerik != Semantics::default_for(Dialect::Sinumerik) {
        return None;
    }
    let callees = streamable_with_callees(file, ctx)?;
    with_source(&file.abs, ctx.options.encoding, |path, copy| to_fanuc_from(job, file, ctx, path, copy, &callees))
}

/// The units of the `callees` files, loaded as `jobs::load_with_callees` loads them for the
/// whole job (file ids from 1 up after the main's 0, the job's encoding and profile);
/// declines one with any diagnostic or a call `segmented::to_fanuc_with_subs` cannot take.
fn load_callees(job: &Job<Fanuc>, ctx: &BatchContext, callees: &[usize]) -> Result<Vec<Unit>, Fallback> {
    let no = |why: &str| Fallback::NotStraight(why.into());
    let mut db = SourceDb::new();
    db.add("", String::new());
    let mut units = Vec::new();
    for &i in callees {
        let f = ctx.files.get(i).ok_or_else(|| no("a callee not in the batch"))?;
        let l = jobs::load(&mut db, f, Dialect::Sinumerik, ctx.options.encoding, &job.settings.sinumerik)
            .map_err(|e| no(&e))?;
        if !l.diags.is_empty() || !stream::segmented::fanuc::calls_plain(&l.unit) {
            return Err(no("a callee with diagnostics or a call of another kind"));
        }
        units.push(l.unit);
    }
    Ok(units)
}

/// [`to_fanuc`] reading `path` (the file, or its decoded `copy`).
fn to_fanuc_from(
    job: &Job<Fanuc>,
    file: &InputFile,
    ctx: &BatchContext,
    path: &Path,
    copy: Option<&TempCopy>,
    callees: &[usize],
) -> Option<FileOutcome> {
    let s = &job.settings;
    let (enc, bom, eol) = source_form(&file.abs, copy)?;
    let out_enc = s.output_encoding.unwrap_or(enc);
    let opts = job.options(ctx, file, eol).ok()?;
    let part = write::staged_path(&ctx.options.output, file.index);
    // Output not in UTF-8: the stream writes UTF-8 into a temporary file, encoded into
    // `part` and read back from there; in UTF-8 the mark is written as the whole path does.
    let utf8 = (out_enc != encoding_rs::UTF_8).then(|| TempFile::new("batch.utf8.nc"));
    let into = utf8.as_ref().map_or(part.as_path(), |u| u.path());
    // The callees' units, kept for the verifier's source side.
    let mut subs: Vec<Unit> = Vec::new();
    let mut load = |_: &Unit| {
        subs = load_callees(job, ctx, callees)?;
        Ok(subs.clone())
    };
    let load: Option<LoadCallees<'_>> = if callees.is_empty() { None } else { Some(&mut load) };
    let (index, map, notes) = streamed_macro::to_fanuc_part(path, &opts, into, bom && utf8.is_none(), load)?;
    if let Some(u) = &utf8 {
        encode_part(u.path(), out_enc, bom, &part)?;
    }
    let name = rel_string(&file.rel);
    let rel_out = discover::fanuc_output(&file.rel);
    let out_name = rel_string(&rel_out);
    let mut outcome = FileOutcome::new(Status::TranslatedUnverified, "translated, not verified (--no-verify)");
    outcome.blocks = index.blocks;
    outcome.used = target_fanuc::used_names(&map);
    outcome.staged = vec![(rel_out, part.clone())];
    // The translation's notes, as the whole-file job lists them before the check's.
    outcome.diagnostics = records(&notes, &[(0, &name, path)]);
    if !ctx.options.verify {
        return Some(outcome);
    }
    // As `Job<Fanuc>::verify` runs a program no file calls: `--set` on both sides, the
    // mapped R parameters 0 on FANUC.
    let files: [(FileId, &str, &Path); 2] = [(0, &name, path), (1, &out_name, into)];
    let back = match sv::read_back(into, 1, Dialect::Fanuc, &ParseOptions::for_dialect(Dialect::Fanuc), None) {
        Ok(b) => b,
        // With callees the whole job gives this verdict (see below).
        Err(_) if !subs.is_empty() => {
            let _ = std::fs::remove_file(&part);
            return None;
        }
        Err(e) => {
            let diagnostics = match e {
                ReadBack::Diags(d) => records(&d, &files),
                ReadBack::Unreadable(m) => vec![DiagRecord::error("NC603", format!("cannot read {out_name}: {m}"))],
            };
            let summary = "the output does not parse as FANUC (a bug in nctrans)".to_string();
            apply(
                &mut outcome,
                Verified { status: Status::Diverged, summary, events: None, excluded: Default::default(), diagnostics },
            );
            return Some(outcome);
        }
    };
    let mut b_in = crate::translate::to_fanuc::r_param_homes(&map);
    b_in.extend(s.set.iter().filter(|x| x.trim_start().starts_with('#')).cloned());
    // The callees as the whole job's verifier serves them (aligned as it aligns them); the
    // FANUC side finds the output's own O programs in the read-back index, as the whole
    // job's finds them in the parsed output.
    let with_subs = !subs.is_empty();
    let source_callees: Box<dyn CalleeSource + Send> = if with_subs {
        Box::new(MemCallees(subs.iter().map(|u| translate::to_fanuc::align_source(u, &map)).collect()))
    } else {
        Box::new(NoCallees)
    };
    let a = StreamSide {
        index,
        name: name.clone(),
        callees: source_callees,
        run: run_options(parse_all(&s.set), s.max_steps, &s.sinumerik),
    };
    let b = StreamSide {
        index: back,
        name: out_name.clone(),
        callees: Box::new(NoCallees),
        run: run_options(parse_all(&b_in), s.max_steps, &s.fanuc),
    };
    let report = sv::compare_excluding(a, b, translate::to_fanuc::EXCLUDE);
    // With callees, only an equivalence is taken: the diagnostics of any other verdict may
    // point into a callee file, which the streamed records do not name as the whole job
    // does; the whole job then gives that verdict itself.
    if with_subs && !matches!(report.verdict, Verdict::Equivalent { .. }) {
        let _ = std::fs::remove_file(&part);
        return None;
    }
    apply(&mut outcome, verdict(vec![(String::new(), report)], &files));
    Some(outcome)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn positions_are_the_whole_texts_lines_and_columns() {
        let dir = std::env::temp_dir().join(format!("nctrans-streamed-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let text = "G0 X1\r\nG1 Ä Y2\rZ3\n\nM30";
        let path = dir.join("p.mpf");
        std::fs::write(&path, text).unwrap();
        let src = crate::span::SourceFile::new("p", text);
        let offsets: Vec<u32> = (0..=text.len() as u32).filter(|&o| text.is_char_boundary(o as usize)).collect();
        let got = positions(&path, &offsets);
        for (o, g) in offsets.iter().zip(got) {
            assert_eq!(g, src.line_col(*o), "offset {o}");
        }
        let part = dir.join("x.part");
        assert!(write_part(&part, true, |_| Err::<(), ()>(())).is_err());
        assert!(!part.exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
