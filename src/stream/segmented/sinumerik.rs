//! The Sinumerik target's rules and spelling for the one segmented driver (FANUC source, see
//! `segmented`): macro statements, IF/GOTO, WHILE/DO loops, program ends and jump targets
//! stay in the skeleton, whose translation gives the variable map, DEF lines, labels and
//! structures as for the whole file; each run's placeholder is a comment `NCTRANS SEGMENT k`.
//!
//! Why the output is the whole translation's, byte for byte (pass by pass, see
//! `lower::to_sinumerik::lower`):
//! - a straight block (`stream::target::sinumerik::straight`) has no variable, jump, call or structure:
//!   `vacancy::rewrite`, `gotos`, `structures`, `calls` and `exprs` leave it as it is, and
//!   the variable plan (`calls::plan_programs`, `vacancy::analyse`, `varmap::build`) sees
//!   no use of anything in it. The one exception is a program end (M30/M2): the vacancy
//!   dataflow stops there, so blocks with one are never in a run;
//! - jumps: a run never holds a block whose N value any jump names (a second scan keeps
//!   them out when the first finds one), so `gotos`/`vacancy` resolve every jump to the
//!   same block, in the same direction, with the same `LBL_n_k` count (every block of a
//!   named N value is in the skeleton). Computed jumps (`GOTO#1`, every N a target),
//!   calls (M98, G65, G66/G67; but see `subs`), M99, G10 and writes of work offsets (`words` re-selects
//!   the G54.. in force at that point of the text, which may lie in a run) are declined;
//! - the arc mode (`words::lower`, G2/G3 last makes `R` a `CR=`) is ONE flag the words
//!   pass carries over every block of the program in text order, nested bodies included,
//!   whatever the control flow: the translation is static. Its value at the start of each
//!   run is the same fold over the skeleton's blocks before the placeholder and the runs
//!   before (each with its own G codes), which is what this module computes; inside a run
//!   it follows block by block as in the straight stream. The earlier passes only add
//!   blocks without G codes (labels, the N/comment line in front of an IF) or repeat a
//!   block's own constant G words in each variant of a vacancy IF (the same last G code);
//!   an `IF[..]THEN` with a word (its G codes land in an inner block) is declined. The
//!   flag is read only by `R` words; the skeleton's own blocks see it without the runs'
//!   G codes (a placeholder has none), so a skeleton block with an `R` word where the two
//!   folds differ declines;
//! - `take_inputs` takes `nctrans: set` comment blocks off the top up to the first block
//!   that keeps an item, number or label: no run starts before the first statement that
//!   surely does (`solid`), and that statement is itself in the skeleton;
//! - a placeholder is a comment-only block at the top level: no pass changes it, and the
//!   writer writes it as `; NCTRANS SEGMENT k` alone on its line (a skeleton whose text
//!   holds the marker anywhere else is declined).
//!
//! Calls by a constant number (`M98 P`, `G65 P`) stay in the skeleton through
//! [`to_sinumerik_with_subs`]: the file's other programs are kept whole beside it and the
//! callees beside the file are loaded whole, and all are translated together as the whole
//! job is (see `subs`); the subprogram files are returned for the caller to write.
//!
//! Any diagnostic of the source, or of the skeleton or a block alone other than the
//! straight stream's [`KEPT_WARNING`](crate::stream::target::sinumerik::KEPT_WARNING) (kept, in file order as the
//! words pass gives them), declines, as do several programs (but through
//! [`to_sinumerik_with_subs`]), `nctrans: set` lines with CR
//! line ends and N values above 2^24.
//!
//! The flow is `segmented::driver`'s; this target's part is [`ToSinumerik`]
//! (what the skeleton keeps and follows and the fast writer of run blocks are `track`). The
//! arc mode a run depends on is followed in textual order; a run block the fast path
//! declines is held (up to a few thousand, `MAX_DEFERRED`) and translated alone with the
//! skeleton's plan after the one scan, put in at its place; more, or a declined line that
//! turns out to be no run block (`STRICT_DECLINED`), take the writing scan.

use super::driver::{places, segment, Place, SegTarget, Skeleton, Translated};
use super::sinks::Skel;
use crate::diag::Diagnostic;
use crate::dialect::{Dialect, ParseOptions};
use crate::ir::{Program, Stmt, Unit};
use crate::lower::to_sinumerik::Options;
use crate::read::LineEnding;
use crate::span::FileId;
use crate::stream::lines::{first_line_ending, has_bom};
use crate::stream::target::sinumerik::{Planned, Streamed, KEPT_WARNING};
use crate::stream::{Fallback, Index, PlainWord, ProgressFn};
use crate::translate::to_sinumerik::{self as ts, OutFile};
use std::io::Write;
use std::path::Path;
use track::{Class, Fast, Track};

mod subs;
mod track;

pub use subs::{to_sinumerik_with_stand_in, to_sinumerik_with_subs};

/// Translates `path` (FANUC) to Sinumerik into `out` as a skeleton translated whole with its
/// runs of straight blocks streamed (see the module comment), with `eol` line ends. On
/// `Err` nothing useful was written (the caller discards `out` and translates whole).
pub fn to_sinumerik(
    path: &Path,
    opts: &Options,
    eol: LineEnding,
    out: &mut dyn Write,
    progress: Option<ProgressFn<'_>>,
) -> Result<Streamed, Fallback> {
    segment(&ToSinumerik { opts, eol, stand_in: None }, path, out, progress, None).map(|(s, _)| s)
}

/// A diagnostic the straight stream keeps (and reports): the dropped G43/G44/G49 warning.
fn kept_warning(d: &Diagnostic) -> bool {
    !d.is_error() && d.code == KEPT_WARNING
}

/// The Sinumerik target of the segmented driver.
struct ToSinumerik<'a> {
    opts: &'a Options,
    eol: LineEnding,
    /// A stand-in caller's file (`subs::to_sinumerik_with_stand_in`): no file of the result.
    stand_in: Option<FileId>,
}

/// What the result takes from the skeleton's translation.
struct Done {
    diags: Vec<Diagnostic>,
    file: OutFile,
    symbols: ts::SymbolMap,
    subs: Vec<OutFile>,
}

impl<'a> SegTarget for ToSinumerik<'a> {
    const SOURCE: Dialect = Dialect::Fanuc;
    const COMP: &'static str = crate::stream::target::sinumerik::COMP_M6;
    const SUBS_IN_FILE: bool = true;
    /// A few thousand (their statements are held).
    const MAX_DEFERRED: usize = 4096;
    const STRICT_DECLINED: bool = true;
    type Mode = bool;
    type Track = Track;
    type Fast = Fast<'a>;
    type Class = Class;
    /// For a run block translated alone: the main program's plan, made with every program
    /// as the whole translation makes it.
    type Alone = Planned;
    type Done = Done;
    type Output = (Streamed, Vec<OutFile>);
    /// `; NCTRANS SEGMENT k` alone on its line.
    const PLACE: Place = ("", "", |h| h == "; ", false);

    fn parse_options(&self) -> ParseOptions {
        ParseOptions { semantics: self.opts.source.clone() }
    }

    fn fast(&self) -> Fast<'a> {
        Fast { opts: self.opts, eol: self.eol.as_str().as_bytes(), arc: false }
    }

    /// The fast path followed the arc mode as `follow_words` does.
    #[inline]
    fn plain_taken(t: &mut Track, fast: &Fast<'a>, _: &[PlainWord]) {
        t.arc = fast.arc;
    }

    fn sub_declines(s: &Stmt) -> Option<&'static str> {
        subs::declines(std::slice::from_ref(s))
    }

    fn source_ok(&self, path: &Path, ix: &Index) -> Result<(), Fallback> {
        // `header_inputs` reads a whole text by LF lines, an index's header by any line end.
        let cr =
            self.eol == LineEnding::Cr || first_line_ending(path).map_err(Fallback::NotStreamable)? == LineEnding::Cr;
        if cr && ix.header.contains("nctrans:") {
            return Err(Fallback::NotStraight("`nctrans: set` lines with CR line ends".into()));
        }
        Ok(())
    }

    fn skeleton_ok(&self, _: &mut Skel<Self>, programs: &mut [Program]) -> Result<(), Fallback> {
        // The runs are written metric: a G20 anywhere (never in a run, `PLAIN_G`) reads whole.
        if programs.iter().any(|p| crate::lower::to_sinumerik::modal::has_g(&p.body, &[200])) {
            return Err(Fallback::NotStraight("G20 (a program with inch values is read whole)".into()));
        }
        Ok(())
    }

    fn translate(&self, s: Skeleton<'_, Self>) -> Result<Translated<Self>, Fallback> {
        let Skeleton { path, sk, unit, callees } = s;
        let (opts, eol) = (self.opts, self.eol);
        // The callees beside the file decline as its own subprograms do (`subs`).
        subs::callees_ok(&callees)?;
        // A G68 without a centre turns about the tool position in the plane in force, which
        // a plane word in a run (`G18` is a run block) decides: such a job is read whole.
        let centreless = |u: &Unit| u.programs.iter().any(|p| crate::lower::to_sinumerik::planes::needs_plane(&p.body));
        if centreless(&unit) || callees.iter().any(centreless) {
            return Err(Fallback::NotStraight("G68 without a centre (its plane may be set in any block)".into()));
        }
        let units: Vec<&Unit> = std::iter::once(&unit).chain(&callees).collect();
        let tr = ts::translate(&units, opts, eol);
        if !tr.diags.iter().all(|d| kept_warning(d) && d.labels.iter().all(|l| l.file == 0)) {
            return Err(Fallback::Diagnostics);
        }
        // A stand-in caller's program (`subs::to_sinumerik_with_stand_in`) is no file of the
        // result; a diagnostic on it has declined above (its file is not 0).
        let files: Vec<OutFile> = tr.files.iter().filter(|f| Some(f.source) != self.stand_in).cloned().collect();
        let (mut file, subs) = subs::split_files(files, sk.calls)?;
        let places = places::<Self>(&file.text, sk.runs, eol.as_str())?;
        // The main program's plan, made with every program as the whole translation makes it.
        let plan = {
            let all: Vec<(FileId, &Program)> =
                units.iter().flat_map(|u| u.programs.iter().map(move |p| (u.file, p))).collect();
            Planned::of_first(&all, opts).ok_or_else(|| Fallback::NotStraight("no plan".into()))?
        };
        let bom = has_bom(path).map_err(|e| Fallback::NotStreamable(e.into()))?;
        Ok(Translated {
            text: std::mem::take(&mut file.text),
            places,
            alone: plan,
            prefix: if bom { b"\xEF\xBB\xBF" } else { b"" },
            done: Done { diags: tr.diags, file, symbols: tr.symbols.sinumerik().clone(), subs },
        })
    }

    /// A run block the fast path declines, lowered alone with the skeleton's plan and the
    /// arc mode running into it: its text and diagnostics, when those are all kept warnings.
    fn alone(&self, plan: &Planned, s: &Stmt, arc: bool) -> Option<(String, Vec<Diagnostic>)> {
        // Metric: a program with G20 is not segmented.
        match plan.lower(self.opts, vec![s.clone()], arc, Some(false)) {
            (diags, Ok(text)) if diags.iter().all(kept_warning) => match self.eol {
                LineEnding::Lf => Some((text, diags)),
                other => Some((text.replace('\n', other.as_str()), diags)),
            },
            _ => None,
        }
    }

    fn class(_: &mut Track) -> Class {
        Class { solid: false }
    }

    /// The words pass warns block by block in text order: the skeleton's warnings and the
    /// runs' interleave by their place in the file.
    fn done(&self, d: Done, index: Index, mut run_diags: Vec<Diagnostic>) -> (Streamed, Vec<OutFile>) {
        let mut diags = d.diags;
        diags.append(&mut run_diags);
        diags.sort_by_key(|d| d.labels.first().map_or(0, |l| l.span.lo));
        let f = d.file;
        let s = Streamed {
            blocks: index.blocks,
            index,
            diags,
            file_name: f.name,
            program: f.program,
            fanuc_number: f.fanuc_number,
            symbols: d.symbols,
        };
        (s, d.subs)
    }
}
