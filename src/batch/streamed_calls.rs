//! A large FANUC main program of a batch that calls subprograms (`M98 P`, `G65 P`, `G66 P`
//! by a constant number), after its `M30` in the same file and/or in other files of the
//! batch, streamed to Sinumerik with them (`segmented::to_sinumerik_with_subs`): which
//! files may stream so, the callee units the whole-file job would translate with them, and
//! the subprogram outputs of the file (`streamed.rs` does the rest).
//!
//! The whole job (`jobs_sinumerik`) translates the file with its callee files and a
//! stand-in for the calls other files make to any of those programs, renames programs
//! whose number an earlier file defines, and verifies the first program and every other
//! one its own file does not call. A file streams only where that comes down to the
//! streamed job's one translation and one run: no stand-in (no file outside the job calls
//! a program of the job), no program defined twice, no program of the file called from
//! elsewhere, and each program after the first called by the file itself.

use super::discover::{self, InputFile};
use super::jobs;
use super::jobs_sinumerik::ToSinumerikJob;
use super::{write, BatchContext};
use crate::dialect::Dialect;
use crate::ir::Unit;
use crate::span::SourceDb;
use crate::stream::translate::Fallback;
use crate::translate_sinumerik::OutFile;
use std::collections::BTreeSet;
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
    let job: BTreeSet<usize> = callees.iter().copied().chain([file.index]).collect();
    for &i in &callees {
        let c = lib.files.get(i)?;
        if c.dialect != Some(Dialect::Fanuc) || c.parse_errors > 0 || c.read_error.is_some() {
            return None;
        }
        // A call from outside the job to one of its programs makes the whole job's stand-in.
        for k in c.programs.iter().flatten() {
            if lib.calls.iter().any(|call| &call.target == k && !job.contains(&call.file)) {
                return None;
            }
        }
    }
    Some(callees)
}

/// The units of the `callees` files, loaded as `jobs::load_with_callees` loads them for the
/// whole job (file ids from 1 up after the main's 0, the job's encoding and FANUC profile);
/// declines a file that does not read or has any diagnostic.
pub(super) fn load(job: &ToSinumerikJob, ctx: &BatchContext, callees: &[usize]) -> Result<Vec<Unit>, Fallback> {
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
    Ok(units)
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
