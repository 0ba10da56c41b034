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
//!
//! One path for every target ([`run`]): staging, encoding, the report entry, the read-back
//! and the streamed proof are here; what a target does as its own (which files stream, its
//! translators, each side's inputs and callees, its further runs and outputs) is its
//! [`Streams`] in `batch::target::<name>`.

use super::discover::{self, InputFile};
use super::jobs::{self, apply, combine, Job, Verified};
use super::streamed_macro::LibItems;
use super::{rel_string, write, BatchContext, DiagRecord, FileOutcome, Status};
use crate::check::{CheckReport, Verdict};
use crate::diag::Diagnostic;
use crate::dialect::{Dialect, ParseOptions, Semantics};
use crate::eval::{CalleeSource, RunOptions};
use crate::ir::ProgName;
use crate::read::LineEnding;
use crate::span::{FileId, SourceDb};
use crate::stream;
use crate::stream::lines::{first_line_ending, has_bom, Lines, NotStreamable};
use crate::stream::transcode::{self, TempCopy, TempFile};
use crate::stream::verify::{self as sv, ReadBack, StreamSide};
use crate::translate::library::{self, FileInfo, ProgKey, Scan};
use std::collections::BTreeMap;
use std::io::Write;
use std::path::{Path, PathBuf};

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
pub(crate) fn streamable(file: &InputFile, ctx: &BatchContext) -> bool {
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
pub(crate) fn streamable_with_callees(file: &InputFile, ctx: &BatchContext) -> Option<Vec<usize>> {
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
pub(crate) fn records(diags: &[Diagnostic], files: &[(FileId, &str, &Path)]) -> Vec<DiagRecord> {
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
pub(crate) fn verdict(runs: Vec<(String, CheckReport)>, files: &[(FileId, &str, &Path)]) -> Verified {
    let diags = runs.first().map(|(_, r)| r.diags.clone()).unwrap_or_default();
    let mut v = combine(runs);
    if !v.diagnostics.is_empty() {
        v.diagnostics = records(&diags, files);
    }
    v
}

/// A check that could not run (the output does not read back, a bad header line).
pub(crate) fn failed(diags: Vec<Diagnostic>) -> CheckReport {
    CheckReport::failed(SourceDb::new(), diags)
}

pub(crate) fn run_options(inputs: Vec<crate::eval::Input>, max_steps: u64, sem: &Semantics) -> RunOptions {
    RunOptions { inputs, max_steps, semantics: Some(sem.clone()), ..RunOptions::default() }
}

/// What a target's streamed job does as its own (`batch::target::<name>`); the rest is
/// [`run`]'s, the same for every target.
pub trait Streams: jobs::Target {
    /// The scratch file a translation is written to in UTF-8 when its output is encoded.
    const SCRATCH: &'static str;
    /// What the trace comparison leaves out (as the whole job's proof does).
    const EXCLUDE: crate::check::Exclude;
    /// What a file streams with (the callee files of a main that calls).
    type With;
    /// What a translation keeps for its proof and its other outputs.
    type Kept;
    /// A source read from a decoded copy is translated into UTF-8 first too.
    const SCRATCH_DECODED: bool;
    /// Whether the job may stream the file, and with what; `None` leaves it to the whole job.
    fn with(h: Here<'_, Self>) -> Option<Self::With>;
    /// Translates `path` (the file, or its decoded copy; `eol` its first line ending) into
    /// `into`, which gets a byte-order mark first when `bom` says so; `None` declines
    /// (nothing is left at `into`).
    fn translate(
        h: Here<'_, Self>,
        with: &Self::With,
        path: &Path,
        eol: LineEnding,
        into: &Path,
        bom: bool,
    ) -> Option<Translated<Self::Kept>>;
    /// The parse options the output is read back with.
    fn read_back(job: &Job<Self>) -> ParseOptions;
    /// The proof of an output that does not read back (of a translation without calls).
    fn unreadable(e: ReadBack, files: &[(FileId, &str, &Path)]) -> Verified;
    /// Each side's run options and callees (source first), from the `nctrans: set` headers
    /// of the source and the output read back; `Err` is the check that could not run.
    fn sides(
        job: &Job<Self>,
        kept: &Self::Kept,
        headers: (&str, &str),
        out_dir: &str,
    ) -> Result<[Side; 2], Box<CheckReport>>;
    /// The runs after the main program's of a translation with calls, as the whole job
    /// makes them; `None` declines.
    fn more_runs(
        _: Here<'_, Self>,
        _: &Self::Kept,
        _header: &str,
        _out_dir: &str,
    ) -> Option<Vec<(String, CheckReport)>> {
        Some(Vec::new())
    }
    /// The outputs staged after the main one (the file's own subprograms) in the output
    /// encoding `out`; `None` declines.
    fn stage_more(
        _: Here<'_, Self>,
        _: &Self::Kept,
        _out: &'static encoding_rs::Encoding,
        _bom: bool,
    ) -> Option<Staged> {
        Some(Vec::new())
    }
}

/// The file a streamed job translates, with its job and batch.
pub type Here<'a, T> = (&'a Job<T>, &'a BatchContext, &'a InputFile);

/// Staged outputs: where each goes (relative to the output folder) and its staged file.
pub type Staged = Vec<(PathBuf, PathBuf)>;

/// One side of a streamed proof: its run options and the callees it is served.
pub type Side = (RunOptions, Box<dyn CalleeSource + Send>);

/// A streamed translation, as [`run`] reports and proves it.
pub struct Translated<K> {
    /// The source's first-scan index.
    pub index: stream::Index,
    /// The translation's diagnostics on the file (spans into it), listed as the whole job
    /// lists them.
    pub diags: Vec<Diagnostic>,
    pub used: crate::batch::maps::Used,
    /// The main output, relative to the output folder, and its name in the proof.
    pub rel_out: PathBuf,
    pub shown: String,
    /// Callees came in: the proof then takes only an equivalence (the diagnostics of any
    /// other verdict may point into a callee or subprogram file, which the streamed records
    /// do not name as the whole job does; the whole job then gives that verdict itself).
    pub with_calls: bool,
    pub kept: K,
}

/// The streamed job of a large file (see the module documentation); `None` leaves the file
/// to the whole-file job.
pub fn run<T: Streams>(job: &Job<T>, file: &InputFile, ctx: &BatchContext) -> Option<FileOutcome> {
    if job.fault.is_some() {
        return None;
    }
    let h = (job, ctx, file);
    let with = T::with(h)?;
    with_source(&file.abs, ctx.options.encoding, |path, copy| from(h, path, copy, &with))
}

/// [`run`] reading `path` (the file, or its decoded `copy`).
fn from<T: Streams>(h: Here<'_, T>, path: &Path, copy: Option<&TempCopy>, with: &T::With) -> Option<FileOutcome> {
    let (job, ctx, file) = h;
    let s = &job.settings;
    let (enc, bom, eol) = source_form(&file.abs, copy)?;
    let out_enc = s.output_encoding.unwrap_or(enc);
    let part = write::staged_path(&ctx.options.output, file.index);
    // Not UTF-8 in or out: the stream writes UTF-8 into a temporary file, encoded into
    // `part` and read back from there; in UTF-8 the mark is written as the whole path does.
    let utf8 =
        (T::SCRATCH_DECODED && copy.is_some() || out_enc != encoding_rs::UTF_8).then(|| TempFile::new(T::SCRATCH));
    let into = utf8.as_ref().map_or(part.as_path(), |u| u.path());
    let done = T::translate(h, with, path, eol, into, bom && utf8.is_none())?;
    if let Some(u) = &utf8 {
        encode_part(u.path(), out_enc, bom, &part)?;
    }
    // Declined after the main's output is staged: nothing of the file is left staged.
    let decline = || -> Option<FileOutcome> {
        let _ = std::fs::remove_file(&part);
        None
    };
    let name = rel_string(&file.rel);
    let mut outcome = FileOutcome::new(Status::TranslatedUnverified, "translated, not verified (--no-verify)");
    outcome.blocks = done.index.blocks;
    outcome.used = done.used;
    outcome.diagnostics = records(&done.diags, &[(0, &name, path)]);
    outcome.staged = vec![(done.rel_out, part.clone())];
    // The main file first, then its subprograms, as the whole job lists its outputs.
    let stage_more = |outcome: &mut FileOutcome| match T::stage_more(h, &done.kept, out_enc, bom) {
        Some(more) => {
            outcome.staged.extend(more);
            Some(())
        }
        None => decline().map(drop),
    };
    if !ctx.options.verify {
        stage_more(&mut outcome)?;
        return Some(outcome);
    }
    // As the whole job runs the file's (first) program: its header inputs and `--set`.
    let out_dir = rel_string(file.rel.parent().unwrap_or(Path::new("")));
    let files: [(FileId, &str, &Path); 2] = [(0, &name, path), (1, &done.shown, into)];
    let back = match sv::read_back(into, 1, T::DIALECT, &T::read_back(job), None) {
        Ok(back) => back,
        Err(_) if done.with_calls => return decline(),
        Err(e) => {
            apply(&mut outcome, T::unreadable(e, &files));
            stage_more(&mut outcome)?;
            return Some(outcome);
        }
    };
    let header = if done.with_calls { done.index.header.clone() } else { String::new() };
    let report = match T::sides(job, &done.kept, (&done.index.header, &back.header), &out_dir) {
        Ok([(run_a, a_callees), (run_b, b_callees)]) => {
            let a = StreamSide { index: done.index, name: name.clone(), callees: a_callees, run: run_a };
            let b = StreamSide { index: back, name: done.shown.clone(), callees: b_callees, run: run_b };
            sv::compare_excluding(a, b, T::EXCLUDE)
        }
        Err(report) => *report,
    };
    if done.with_calls && !matches!(report.verdict, Verdict::Equivalent { .. }) {
        return decline();
    }
    // The file's own macros alone, as the whole job runs them after its main program.
    let mut runs = vec![(String::new(), report)];
    if done.with_calls {
        match T::more_runs(h, &done.kept, &header, &out_dir) {
            Some(more) => runs.extend(more),
            None => return decline(),
        }
    }
    apply(&mut outcome, verdict(runs, &files));
    stage_more(&mut outcome)?;
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
