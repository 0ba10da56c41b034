//! A large FANUC main program of a batch that calls subprograms (`M98 P`, `G65 P`, `G66 P`
//! by a constant number), after its `M30` in the same file and/or in other files of the
//! batch, streamed to Sinumerik with them (`segmented::to_sinumerik_with_subs`): which
//! files may stream so, the callee units the whole-file job would translate with them, and
//! the subprogram outputs of the file (`streamed.rs` does the rest).
//!
//! The whole job (`batch::target::sinumerik`) translates the file with its callee files and a
//! stand-in for the calls other files make to any of those programs, renames programs
//! whose number an earlier file defines, and verifies the first program and every other
//! one its own file does not call. A file streams only where that comes down to the
//! streamed job's one translation and one run: no program of the file defined twice or
//! called from elsewhere, and each program after the first called by the file itself. The
//! stand-in (the shop's common case: many CAM mains calling the macros of one library
//! file) is the whole job's own (`target::sinumerik::stand_in`, same text, same file id after
//! the callees'), translated with the rest and dropped from the files
//! (`segmented::to_sinumerik_with_stand_in`; a diagnostic on it declines, where the whole
//! job drops its warnings); like the whole job, the check runs without it. After the main's
//! run, the macros the file calls by G65/G66 run alone as the whole job runs them (`macro_runs`,
//! the same `target::sinumerik::in_file_macro_runs`).

use super::discover::{self, InputFile};
use super::jobs;
use super::jobs::Job;
use super::target::sinumerik::{self as target_sinumerik, Sinumerik};
use super::{write, BatchContext};
use crate::dialect::Dialect;
use crate::ir::Unit;
use crate::span::{FileId, SourceDb};
use crate::stream::Fallback;
use crate::translate::to_sinumerik::OutFile;
use std::io::Write;
use std::path::{Path, PathBuf};

/// The callee files of a FANUC `file` (as `Library::callee_files` gives them, the order the
/// whole job loads them in) when its job may stream it with them (see the module comment);
/// `None` when it may not.
pub(super) fn callees(file: &InputFile, ctx: &BatchContext) -> Option<Vec<usize>> {
    let lib = &ctx.library;
    let info = lib.files.get(file.index)?;
    if !info.streamed || info.dialect != Some(Dialect::Fanuc) {
        return None;
    }
    for (i, key) in info.programs.iter().enumerate() {
        let Some(k) = key else {
            // A nameless program after the first would be verified as a main of its own.
            if i == 0 {
                continue;
            }
            return None;
        };
        if lib.programs.get(k).map(|p| p.file) != Some(file.index) || lib.duplicates.contains_key(k) {
            return None;
        }
        let callers: Vec<usize> = lib.calls.iter().filter(|c| &c.target == k).map(|c| c.file).collect();
        // The first program is called by nothing (else it runs once per argument vector);
        // the others only and surely by this file (else each runs as a main too).
        let ok =
            if i == 0 { callers.is_empty() } else { !callers.is_empty() && callers.iter().all(|&f| f == file.index) };
        if !ok {
            return None;
        }
    }
    let callees = lib.callee_files(file.index);
    for &i in &callees {
        let c = lib.files.get(i)?;
        if c.dialect != Some(Dialect::Fanuc) || c.parse_errors > 0 || c.read_error.is_some() {
            return None;
        }
    }
    // Calls from outside the job to its programs: the stand-in `load` gives, as the whole
    // job makes it.
    Some(callees)
}

/// The file id of the stand-in caller of a job with `callees` callee files: after the
/// main's 0 and theirs, as the whole job adds it.
pub(super) fn stand_in_id(callees: &[usize]) -> FileId {
    callees.len() + 1
}

/// The units of the `callees` files, loaded as `jobs::load_with_callees` loads them for the
/// whole job (file ids from 1 up after the main's 0, the job's encoding and FANUC profile),
/// and the job's stand-in caller (`target::sinumerik::stand_in`, from the calls other files
/// make to the programs of the main `file`, whose skeleton unit is `main`, and of the
/// callees; file [`stand_in_id`]) when there is one; declines a file that does not read or
/// has any diagnostic.
pub(super) fn load(
    job: &Job<Sinumerik>,
    ctx: &BatchContext,
    file: &InputFile,
    main: &Unit,
    callees: &[usize],
) -> Result<(Vec<Unit>, Option<Unit>), Fallback> {
    let no = |why: &str| Fallback::NotStraight(why.into());
    let mut db = SourceDb::new();
    db.add("", String::new());
    let mut units = Vec::with_capacity(callees.len());
    for &i in callees {
        let f = ctx.files.get(i).ok_or_else(|| no("a callee not in the batch"))?;
        let l =
            jobs::load(&mut db, f, Dialect::Fanuc, ctx.options.encoding, &job.settings.fanuc).map_err(|e| no(&e))?;
        if !l.diags.is_empty() {
            return Err(no("a callee with diagnostics"));
        }
        units.push(l.unit);
    }
    let files = std::iter::once(file.index).chain(callees.iter().copied());
    let all: Vec<(usize, &Unit)> = files.zip(std::iter::once(main).chain(&units)).collect();
    let stand_in = target_sinumerik::stand_in(&mut db, ctx, &all, &job.settings.fanuc);
    match stand_in {
        Some((id, _)) if id != stand_in_id(callees) => Err(no("the stand-in caller's file id")),
        Some((_, unit)) => Ok((units, Some(unit))),
        None => Ok((units, None)),
    }
}

/// The runs of the macros the file calls by G65/G66 among its own programs, alone, as the
/// whole job makes them (`target::sinumerik::in_file_macro_runs`): the FANUC side from the
/// streamed skeleton `main` (its macro part and the file's other programs, whole) with the
/// file's `header` (its `nctrans: set` lines), its callees from `units`, the Siemens side
/// from the translation's other files `subs` and `symbols`. `None` when one of them is not
/// an equivalence: the whole job then gives that verdict, with its diagnostics' lines.
#[allow(clippy::too_many_arguments)]
pub(super) fn macro_runs(
    job: &Job<Sinumerik>,
    ctx: &BatchContext,
    file: &InputFile,
    (main, header): (&Unit, &str),
    units: &[Unit],
    (subs, symbols): (&[OutFile], &crate::translate::to_sinumerik::SymbolMap),
    out_dir: &str,
) -> Option<Vec<(String, crate::check::CheckReport)>> {
    let s = &job.settings;
    // The whole job's file ids: the main's 0, its callees' from 1 up, the stand-in's next.
    let mut db = SourceDb::new();
    db.add(crate::batch::rel_string(&file.rel), header.to_string());
    for _ in 0..=units.len() {
        db.add("", String::new());
    }
    let tr = crate::translate::Translation {
        files: subs.to_vec(),
        symbols: crate::translate::Symbols::Sinumerik(symbols.clone()),
        diags: Vec::new(),
        unsupported: 0,
    };
    let profiles =
        crate::translate::to_sinumerik::verify::Profiles { fanuc: s.fanuc.clone(), sinumerik: s.sinumerik.clone() };
    let settings =
        crate::translate::called::RunSettings { out_dir, max_steps: s.max_steps, profiles: &profiles, set: &s.set };
    let served = || {
        Box::new(crate::translate::called::MemCallees(units.to_vec()))
            as Box<dyn crate::eval::calls::CalleeSource + Send>
    };
    let runs = target_sinumerik::in_file_macro_runs(&db, ctx, file, main, &tr, &settings, &served);
    runs.iter().all(|(_, r)| matches!(r.verdict, crate::check::Verdict::Equivalent { .. })).then_some(runs)
}

/// The file's own subprograms among the translation's other files (the callees' are
/// written by their own jobs), in the translation's order.
pub(super) fn own(subs: &[OutFile]) -> impl Iterator<Item = &OutFile> {
    subs.iter().filter(|f| f.source == 0)
}

/// Stages the file's own subprogram outputs (`own`) beside its streamed main output `main`,
/// encoded as the whole job encodes them: the staged list (output name, staged file), in
/// order; `None` (nothing left staged) when one cannot be written.
pub(super) fn stage_own(
    file: &InputFile,
    ctx: &BatchContext,
    subs: &[OutFile],
    enc: &'static encoding_rs::Encoding,
    bom: bool,
) -> Option<Vec<(PathBuf, PathBuf)>> {
    let main = write::staged_path(&ctx.options.output, file.index);
    let dir = main.parent()?;
    let mut staged: Vec<(PathBuf, PathBuf)> = Vec::new();
    for (k, f) in own(subs).enumerate() {
        // Beside the main's part (the folder `Writer::adopt` takes), under a name
        // `Writer::stage` never uses.
        let part = dir.join(format!("stream-{}-{k}.part", file.index));
        let rel = discover::sinumerik_output(&file.rel, &f.program, !f.main);
        if put(&part, &crate::read::encode(&f.text, enc, bom)).is_none() {
            for (_, p) in &staged {
                let _ = std::fs::remove_file(p);
            }
            return None;
        }
        staged.push((rel, part));
    }
    Some(staged)
}

/// Writes `bytes` to `part`, on disk before the rename into place like every staged output;
/// nothing is left at `part` on failure.
fn put(part: &Path, bytes: &[u8]) -> Option<()> {
    let done = (|| {
        let mut f = std::fs::File::create(part)?;
        f.write_all(bytes)?;
        f.sync_data()
    })();
    if done.is_err() {
        let _ = std::fs::remove_file(part);
    }
    done.ok()
}
