//! The Sinumerik target's rules for a segmented main program that calls subprograms
//! (`M98 P9010`, `G65 P9020 A1.`, `G66 P9050 R2.`): the calls stay in the skeleton, the
//! programs after the main one in the same file are read whole (statement by statement
//! from the same scan),
//! the callees beside the file are loaded whole by the caller, and the skeleton is
//! translated with all of them as `translate_sinumerik::translate` translates the whole job.
//!
//! Why the files are the whole translation's, byte for byte: the passes translate each
//! program on its own but for the variable plan (`calls::plan_programs`, commons, the
//! locals an `M98` shares), which the runs do not enter (a run block has no variable, call
//! or jump); the words pass's modes (arc mode, G54.., G90/G91 of `ModalScan`) start afresh
//! in each program, so a subprogram's text depends on no run of the main program; the
//! program names (`main_name`, `--program-map`, `O` numbers) come from the programs'
//! headers, which the skeleton unit has as the whole file has them. The subprograms of the
//! file are taken from the scan and not re-parsed from a tail of the text: the scan gives
//! each statement as the whole-file reader builds it (spans into the file included), which
//! re-parsing a tail would not (offsets, the `%` line, header lines).
//! A modal call (`G66 P<n>` … `G67`) is kept too: both become `MCALL` lines at their own
//! blocks (`calls::lower`), the vacancy dataflow takes the G66 block as the call site, and
//! the moves of a run under it are translated as any others; that the macro runs after each
//! of them is the evaluators' business, the same in the whole and the streamed runs.
//! Declined: computed call targets anywhere, M99 in the main program (as before),
//! `M99 P<n>` in any subprogram (see `declines`), a callee not found or with any
//! diagnostic (the caller's `LoadCallees`), a diagnostic of the translation on a callee
//! file, and a marker comment in a subprogram's translation.

use super::ToSinumerik;
use crate::ir::{Call, CallKind, CallTarget, ItemKind, Stmt, StmtKind, Unit};
use crate::lower::to_sinumerik::Options;
use crate::read::LineEnding;
use crate::span::FileId;
use crate::stream::segmented::driver::segment;
use crate::stream::segmented::LoadCallees;
use crate::stream::{Fallback, ProgressFn};
use crate::translate::to_sinumerik::OutFile;
use std::io::Write;
use std::path::Path;

/// A call the skeleton keeps: `M98 P<n>`, `G65 P<n> …` or `G66 P<n> …` (not computed).
pub(super) fn plain_call(c: &Call) -> bool {
    matches!(c.kind, CallKind::M98 | CallKind::G65 | CallKind::G66) && matches!(c.target, CallTarget::Number(_))
}

/// [`super::to_sinumerik`] of a FANUC main program that may call subprograms by a constant
/// number, in the same file after it or beside it (`load`): the main program's translation
/// is written to `out` (streamed, runs copied in), and every other file of the whole
/// translation is returned, in its order, for the caller to write.
pub fn to_sinumerik_with_subs(
    path: &Path,
    opts: &Options,
    eol: LineEnding,
    load: LoadCallees<'_>,
    out: &mut dyn Write,
    progress: Option<ProgressFn<'_>>,
) -> Result<(super::Streamed, Vec<OutFile>), Fallback> {
    segment(&ToSinumerik { opts, eol, stand_in: None }, path, out, progress, Some(load))
}

/// [`to_sinumerik_with_subs`] where `load` may also give a stand-in caller unit (file
/// `stand_in`: calls other files make to the callees, so their `PROC` lines come out as in
/// every other job): it is translated with the rest, as the whole batch job translates it,
/// and its program is no file of the result (any diagnostic on it declines).
pub fn to_sinumerik_with_stand_in(
    path: &Path,
    opts: &Options,
    eol: LineEnding,
    load: LoadCallees<'_>,
    stand_in: FileId,
    out: &mut dyn Write,
    progress: Option<ProgressFn<'_>>,
) -> Result<(super::Streamed, Vec<OutFile>), Fallback> {
    segment(&ToSinumerik { opts, eol, stand_in: Some(stand_in) }, path, out, progress, Some(load))
}

/// The translation's main file (the first, the only main) and the others; with `calls`
/// off, the main must be the only file. A subprogram's text holding the marker declines
/// (only the main file's placeholders are replaced, but a reader could not tell).
pub(super) fn split_files(mut rest: Vec<OutFile>, calls: bool) -> Result<(OutFile, Vec<OutFile>), Fallback> {
    let no = |why: &str| Err(Fallback::NotStraight(why.into()));
    let Some(f) = (!rest.is_empty()).then(|| rest.remove(0)) else { return no("no program") };
    if !f.main || rest.iter().any(|r| r.main) {
        return no("a program that is not a main program");
    }
    if !calls && !rest.is_empty() {
        return no("more than one program");
    }
    if rest.iter().any(|r| r.text.contains(crate::stream::segmented::MARK)) {
        return no("a comment that reads as a segment marker");
    }
    Ok((f, rest))
}

/// Why a subprogram's statements decline (`None`: they do not): a call the skeleton would
/// not keep, and `M99 P<n>`. A caller of a program with `M99 P<n>` gets a CASE over every N
/// number it has (`calls::lower`), run blocks' included, which the skeleton does not have.
pub(super) fn declines(body: &[Stmt]) -> Option<&'static str> {
    let mut why = None;
    crate::ir::visit::walk_stmts(body, &mut |s| {
        let StmtKind::Block(b) = &s.kind else { return };
        for it in &b.items {
            let then = if let ItemKind::IfThen { then, .. } = &it.kind { Some(&**then) } else { None };
            for it in std::iter::once(it).chain(then) {
                why = why.or(match &it.kind {
                    ItemKind::Call(c) if !plain_call(c) => Some("a modal or computed call"),
                    ItemKind::Return { to: Some(_) } => Some("M99 P in a subprogram"),
                    _ => None,
                });
            }
        }
    });
    why
}

/// Declines callees (loaded beside the file) as the skeleton scan declines the file's own
/// subprograms (`SegTarget::sub_declines`).
pub(super) fn callees_ok(units: &[Unit]) -> Result<(), Fallback> {
    match units.iter().flat_map(|u| &u.programs).find_map(|p| declines(&p.body)) {
        Some(why) => Err(Fallback::NotStraight(why.into())),
        None => Ok(()),
    }
}
