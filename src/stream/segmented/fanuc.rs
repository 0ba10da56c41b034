//! The FANUC target's rules and spelling for the one segmented driver (Sinumerik source, see
//! `segmented`): R assignments, IF/WHILE/LOOP, jumps and labels stay in the skeleton, whose
//! translation gives the labels, structures and the variable map header as for the whole file.
//!
//! Why the output is the whole translation's, byte for byte:
//! - a straight block's translation depends on no other block but through the words
//!   pass's modes, and the words pass follows them in TEXTUAL order (`body_pass` walks the
//!   statements and every structure's bodies in source order with one `Modal`; it never
//!   follows jumps or loops). So the mode at any block is a function of the text before
//!   it, and textual order is all there is to follow: the skeleton scan does it
//!   (`track::Modes`, the same rules: `lower::to_fanuc::words::units`, G90/G91), through runs and
//!   through the macro statements' blocks (`walk_stmts` is that same pre-order), and
//!   - each run's fast path starts in the units the text before it leaves (a block the
//!     fast path declines is translated alone after a block setting those units when they
//!     are not the start's, `G70` for inch lengths with metric feeds);
//!   - each placeholder carries the modes its run leaves as a unit word (`G70`, `G700`,
//!     `G710`: each sets any state from any other) and G90/G91 words
//!     (only where the run changes them), so the skeleton's words pass reads the modes
//!     the whole translation has at the macro statements after the run: converted F, the
//!     G90/G91 switch around AC()/IC() words. The placeholder's line is replaced whole,
//!     so these words never reach the output.
//!   - whether textual order is the mode a jump or a loop head runs in is the verifier's
//!     question, the same for both paths: they write the same bytes.
//! - the labels pass sees the same jumps and the same jump targets: a run never holds a
//!   block whose N value any jump names (those stay real blocks of the skeleton), and
//!   labelled blocks are not straight; it picks fresh numbers above the highest N of the
//!   program, which the placeholder carries as its own N. When those would pass N99999
//!   it numbers them from N1 up, skipping every N in use: then the run blocks' N values
//!   up to where enough free numbers are passed go into the skeleton as carrier blocks
//!   (`carry_numbers`), and the translated skeleton is checked for a fresh number a run
//!   block has (`fresh_numbers_ok`: declined);
//! - a DEF's start value (`v=0`) that a later assignment replaces is dropped when nothing
//!   between can read it (`lower::to_fanuc::blocks::drop_dead_zero_stores`, a search of at
//!   most 64 statements that stops at a skipped block or a program end): the search would
//!   see a placeholder as one plain block, so the skeleton's translation is told what each
//!   run is to it (`to_fanuc_runs`, `Track::search`: its number of blocks, or that one of
//!   them stops it) and counts a placeholder as its run's blocks. (Without it, a start value
//!   the whole translation keeps, with a skipped block or more than 64 blocks before the
//!   assignment, was dropped: the difference once seen on `axis-vars-dressing-trans.spf`,
//!   which `DEF AXIS` was declined for, but it never was about axis variables.)
//! - a section repeated (`REPEAT`, `REPEATB`, `ENDLABEL`) is copied where its REPEAT stands
//!   (`lower::to_fanuc::repeat_sections`), its blocks without N numbers and in the modes
//!   there, so a run's spilled bytes cannot stand for a copy: every block from the first
//!   label a repetition names to the last repetition stays in the skeleton (a second scan,
//!   `driver::repeated`). The units the copy leaves reach the runs after it in the whole
//!   translation, not in text order: the words pass gives the units it has at each
//!   placeholder and a run translated in others declines (`units_ok`).
//! - nothing else in the passes looks from one block at another one outside a structure
//!   but MSG: a block holding only `MSG("…")` and a lone M0 block right after it become
//!   one stop with the message. Such an M0 stays a real block of the skeleton (never a
//!   run's), so the pair meets there. A MSG not so paired becomes a comment with a note
//!   (NC320) in the skeleton as in the whole file: [`to_fanuc_with_notes`] returns the
//!   notes for the caller to render, [`to_fanuc`] declines them. A MSG beside other items
//!   is split off by the blocks pass and its piece may pair the same way: a lone M0 after
//!   any block with a MSG stays in the skeleton, so the skeleton holds every pair the
//!   whole file has.
//!
//! Why verification gives the whole path's verdict: the whole path runs `align_source` of
//! the source, which differs from it only in string-valued words (a tool name the
//! translation maps becomes its number), and its check leaves the messages kept as
//! comments out of the comparison (`translate::to_fanuc::EXCLUDE`), as the streamed check does. The
//! streamed source numbers the tool names in the statements it re-reads alike
//! (`stream::paged`, [`SourceAlign`]).
//!
//! Calls of subprograms by a constant name (`L100`, `NAME(…)`) stay in the skeleton through
//! [`to_fanuc_with_subs`]: it is translated with the callees as the whole program is (the
//! passes never look through a call at the caller's blocks; the labels pass numbers each
//! program on its own, so only the main program's text is checked for fresh numbers), and
//! the streamed verifier finds them beside the file (`DirCallees`) and the output's own `O`
//! programs in the read-back index: callees the whole path's verifier would align
//! differently (a tool name) are declined.
//!
//! Still declined (the whole path takes them): other calls (modal, computed, without the
//! callees), PROC parameters,
//! more than one program, computed jumps and G words, a repeated section that changes the
//! units of the runs after its REPEAT, N numbers above
//! 16777216 or near N99999 with most numbers in use, `--number-blocks`, a subprogram as main, and anything
//! the translation has a warning or an error on (notes only through
//! [`to_fanuc_with_notes`]).
//!
//! The flow is `segmented::driver`'s; this target's part is [`ToFanuc`] (what the skeleton
//! keeps and follows is `track`). A run block the fast path declines is translated alone in
//! the program's frame, known after the scan: the one scan holds none (`MAX_DEFERRED` is 0)
//! and the writing scan fills the runs.

mod track;

use super::driver::{places, segment, Place, RunTests, SegTarget, Skeleton, Translated};
use super::nset::{kept, Keep};
use super::sinks::Skel;
use super::{LoadCallees, SourceAlign};
use crate::diag::{Diagnostic, Severity};
use crate::dialect::fanuc::emit::EmitOptions;
use crate::dialect::{Dialect, ParseOptions};
use crate::eval::Input;
use crate::ir::{BlockMeta, ItemKind, Program, Stmt, StmtKind, Unit};
use crate::lower::to_fanuc::fast_write as fast;
use crate::lower::to_fanuc::words::units::Units;
use crate::stream::target::fanuc::{alone, run_block};
use crate::stream::{Fallback, Index, PlainWord, ProgressFn};
use crate::translate::{self, to_fanuc::TranslateOptions};
use std::io::Write;
use std::path::Path;
use track::{Track, MAX_N};

/// A finished segmented translation.
pub struct Segmented {
    /// The source's first-scan index (of the writing scan).
    pub index: Index,
    pub blocks: u64,
    /// `#n=0` for the R parameters the translation maps and the commons of global user
    /// data at their start values: the output side's inputs when verifying before its own
    /// (as `translate::verify` sets them, `translate::to_fanuc::proof_homes`).
    pub inputs: Vec<Input>,
    /// The skeleton's translation's symbol map: the names the whole translation uses.
    pub symbol_map: translate::to_fanuc::SymbolMap,
}

/// Translates `path` (Sinumerik) to FANUC into `out` as a skeleton translated whole with its
/// runs of straight blocks streamed (see the module comment). On `Err` nothing useful was
/// written (the caller discards `out` and translates whole). Declines a translation with
/// notes (a MSG left as a comment, a dropped STOPRE): [`to_fanuc_with_notes`] takes those.
pub fn to_fanuc(
    path: &Path,
    opts: &TranslateOptions,
    out: &mut dyn Write,
    progress: Option<ProgressFn<'_>>,
) -> Result<Segmented, Fallback> {
    segment(&ToFanuc { opts, notes_ok: false }, path, out, progress, None).map(|(s, _)| s)
}

/// [`to_fanuc`] of a program whose translation may have notes (remarks, no warning or
/// error): they are returned, as `translate::to_fanuc` gives them for the whole file
/// (spans into the source), for the caller to render (`excerpt::render`).
pub fn to_fanuc_with_notes(
    path: &Path,
    opts: &TranslateOptions,
    out: &mut dyn Write,
    progress: Option<ProgressFn<'_>>,
) -> Result<(Segmented, Vec<Diagnostic>), Fallback> {
    segment(&ToFanuc { opts, notes_ok: true }, path, out, progress, None)
}

/// [`to_fanuc_with_notes`] of a program that may call other programs by a constant name
/// (`L100`, `NAME`, `NAME(…)`; not MCALL): the skeleton keeps the calls, `load` gives the
/// callees (each loaded as `cli::translate` loads them: file ids from 1 up, the main being
/// file 0), and the skeleton is translated with them as `translate::to_fanuc::to_fanuc(main, subs, …)`
/// translates the whole program: the main program with its runs, then each subprogram.
/// Notes are declined unless all of them are on the main file.
pub fn to_fanuc_with_subs(
    path: &Path,
    opts: &TranslateOptions,
    load: LoadCallees<'_>,
    out: &mut dyn Write,
    progress: Option<ProgressFn<'_>>,
) -> Result<(Segmented, Vec<Diagnostic>), Fallback> {
    segment(&ToFanuc { opts, notes_ok: true }, path, out, progress, Some(load))
}

/// Whether every call in `unit` is one a skeleton keeps with its callees (by a constant
/// name, not modal): the callees a [`LoadCallees`] gives must call only such.
pub fn calls_plain(unit: &Unit) -> bool {
    let mut ok = true;
    for p in &unit.programs {
        crate::ir::visit::walk_stmts(&p.body, &mut |s| {
            if let StmtKind::Block(b) = &s.kind {
                ok &= b.items.iter().all(|it| !matches!(&it.kind, ItemKind::Call(c) if !track::plain_call(c)));
            }
        });
    }
    ok
}

/// The FANUC target of the segmented driver.
struct ToFanuc<'a> {
    opts: &'a TranslateOptions,
    /// Notes (no warning or error) of the main file are returned, not declined.
    notes_ok: bool,
}

/// The writing scan's tests: the lone M0 blocks kept for a MSG.
struct Class {
    forced: Vec<u32>,
}

impl RunTests for Class {
    #[inline]
    fn plain_run(&self, keep: &Keep, meta: &BlockMeta, _: &[PlainWord]) -> bool {
        !kept(keep, meta) && self.forced.binary_search(&meta.span.lo).is_err()
    }

    fn stmt_run(&mut self, keep: &Keep, s: &Stmt) -> bool {
        matches!(&s.kind, StmtKind::Block(b) if run_block(s) && self.plain_run(keep, &b.meta, &[]))
    }
}

impl<'a> SegTarget for ToFanuc<'a> {
    const SOURCE: Dialect = Dialect::Sinumerik;
    const COMP: &'static str = crate::stream::target::fanuc::COMP;
    const SUBS_IN_FILE: bool = false;
    const MAX_DEFERRED: usize = 0;
    const STRICT_DECLINED: bool = false;
    type Mode = Units;
    type Track = Track;
    type Fast = fast::Fast;
    type Class = Class;
    /// For a block translated alone: the program with an empty body, its header's length.
    type Alone = (Unit, usize);
    /// The skeleton's translation's symbol map and notes.
    type Done = (translate::to_fanuc::SymbolMap, Vec<Diagnostic>);
    type Output = (Segmented, Vec<Diagnostic>);
    /// `Nn G20 G91 (NCTRANS SEGMENT k)`, with carrier lines `Nn (NCTRANS SEGMENT k)`.
    const PLACE: Place = ("(", ")", place_head, true);

    fn check(&self) -> Result<(), Fallback> {
        if self.opts.number_blocks.is_some() || self.opts.main_is_sub {
            return Err(Fallback::NotStraight("--number-blocks or a subprogram as main".into()));
        }
        Ok(())
    }

    /// The source's profile (its library's macros and global user data), as the whole
    /// translation reads it.
    fn parse_options(&self) -> ParseOptions {
        ParseOptions { semantics: self.opts.source.clone() }
    }

    fn fast(&self) -> fast::Fast {
        fast::Fast::new(self.opts.comments, self.opts.line_ending.as_str())
    }

    fn main_ok(&self, main: &Program) -> Result<(), Fallback> {
        if !main.params.is_empty() {
            return Err(Fallback::NotStraight("a PROC with parameters".into()));
        }
        Ok(())
    }

    fn skeleton_ok(&self, sk: &mut Skel<Self>, programs: &mut [Program]) -> Result<(), Fallback> {
        let main = &mut programs[0];
        let mut nodes = 0usize;
        crate::ir::visit::walk_stmts(&main.body, &mut |_| nodes += 1);
        // The labels pass numbers jump targets from the next thousand above the highest N, and
        // from 1 when those would pass N99999: then it skips every N in use, the runs' too.
        let fresh = 4 * nodes as u64 + 16;
        if u64::from((sk.t.max_n / 1000 + 1) * 1000) + fresh > u64::from(MAX_N) {
            carry_numbers(sk, &mut main.body, fresh)?;
        }
        Ok(())
    }

    fn translate(&self, s: Skeleton<'_, Self>) -> Result<Translated<Self>, Fallback> {
        let Skeleton { sk, mut unit, callees: subs, .. } = s;
        let (opts, eol) = (self.opts, self.opts.line_ending.as_str());

        // The main program's header alone, for a block translated alone.
        let body = std::mem::take(&mut unit.programs[0].body);
        let lone = unit.programs[0].clone();
        unit.programs[0].body = body;
        let sub_refs: Vec<&Unit> = subs.iter().collect();
        // The passes count each placeholder as its run's blocks (`Ctx::stand_in_runs`).
        let t = translate::to_fanuc::to_fanuc_runs(&unit, &sub_refs, opts, &sk.t.search);
        drop(unit);
        // The runs take the units the scan follows in text order. (G90/G91 merged where paths
        // meet is read by the skeleton's own AC()/IC() words only: the placeholders carry each
        // run's last G90/G91, jump targets and skippable G90/G91 blocks are never in a run.)
        if !t.units_follow_text {
            return Err(Fallback::NotStraight("units that depend on the path taken or on a call".into()));
        }
        units_ok(&t.stand_in_units, sk)?;
        // The whole path's verifier runs the callees aligned (`align_source`), the streamed one
        // as read from their files: only callees alignment leaves alone stream.
        if subs.iter().any(|u| translate::to_fanuc::align_source(u, &t.symbol_map) != *u) {
            return Err(Fallback::NotStraight("a subprogram with a tool name".into()));
        }
        drop(subs);
        // A run after a frame change, before its axes are programmed absolutely again: the
        // whole translation looks into the run's blocks (`frames_incr`).
        if t.diags
            .iter()
            .any(|d| d.code == "NC445" && d.message.starts_with(crate::lower::to_fanuc::frames_incr::STAND_IN))
        {
            return Err(Fallback::NotStraight(
                "a run where a frame change leaves an axis to be programmed again".into(),
            ));
        }
        let notes_only = t.diags.iter().all(|d| d.severity == Severity::Note && d.labels.iter().all(|l| l.file == 0));
        if !(t.diags.is_empty() || self.notes_ok && notes_only) || t.unsupported > 0 {
            return Err(Fallback::Diagnostics);
        }
        // (No run is in a section a REPEAT copies: `driver::repeated` keeps those blocks.)
        let places = places::<Self>(&t.text, sk.runs, eol)?;
        // The labels pass numbers each program on its own: only the main program's text is
        // checked for fresh numbers (the subprograms' follow it, each from its `O` line).
        let main_end = main_text_end(&t, eol, places.last().map_or(0, |p| p.1));
        fresh_numbers_ok(&t.text[..main_end], eol, &places, sk)?;
        // A block the fast path declines is translated alone, as the straight stream does: the
        // header of an empty program comes first, then the block.
        let lone = Unit { dialect: Dialect::Sinumerik, file: 0, programs: vec![lone] };
        let head = translate::to_fanuc::to_fanuc(&lone, &[], opts);
        let header_len = head.unit.programs.first().map_or(0, |p| p.body.len());
        Ok(Translated { text: t.text, places, alone: (lone, header_len), prefix: b"", done: (t.symbol_map, t.diags) })
    }

    /// A straight block of a run the fast path declined: translated alone, as the straight
    /// stream does (`stream::target::fanuc::alone`).
    fn alone(&self, (lone, header_len): &(Unit, usize), s: &Stmt, units: Units) -> Option<(String, Vec<Diagnostic>)> {
        let eo = EmitOptions { comments: self.opts.comments, line_ending: self.opts.line_ending, file: 0 };
        let (text, diags, unsupported) = alone(lone.clone(), *header_len, units, s, self.opts, &eo);
        (diags.is_empty() && unsupported == 0).then_some((text, diags))
    }

    fn class(t: &mut Track) -> Class {
        Class { forced: std::mem::take(&mut t.forced) }
    }

    fn done(&self, (symbol_map, notes): Self::Done, mut index: Index, _: Vec<Diagnostic>) -> Self::Output {
        index.align = SourceAlign { tools: symbol_map.tools.clone() };
        let homes = crate::translate::to_fanuc::proof_homes(&symbol_map);
        let inputs = homes.iter().filter_map(|s| crate::eval::parse_input(s).ok()).collect();
        (Segmented { blocks: index.blocks, index, inputs, symbol_map }, notes)
    }
}

/// Checks the units the skeleton's words pass had going into each placeholder (the first line
/// of its run's; carrier lines follow) against the ones its run was translated in, as text
/// order gives them: a section repeated (REPEAT) is written again where the REPEAT stands,
/// so units it changes reach the runs after it in the whole translation.
fn units_ok(met: &[(usize, Option<Units>)], sk: &Skel<ToFanuc<'_>>) -> Result<(), Fallback> {
    let mut last = None;
    for &(k, units) in met {
        // Runs come in order; a run met again is a carrier line (or a repeated section's copy,
        // which `places` declines).
        if last.is_some_and(|l| k <= l) {
            continue;
        }
        last = Some(k);
        if units.is_none() || units != sk.modes.get(k).copied() {
            return Err(Fallback::NotStraight("units that differ from the text's at a run".into()));
        }
    }
    Ok(())
}

/// What precedes a placeholder's marker on its line: its N number and mode words
/// (`Nn G20 G90 `), or nothing.
fn place_head(head: &str) -> bool {
    head.is_empty()
        || head.strip_suffix(' ').is_some_and(|h| {
            h.split(' ').enumerate().all(|(k, t)| {
                let d = t.strip_prefix('G').or_else(|| t.strip_prefix('N').filter(|_| k == 0));
                d.is_some_and(|d| !d.is_empty() && d.bytes().all(|c| c.is_ascii_digit()))
            })
        })
}

/// Where the main program's text ends in a translation of several programs: at the line
/// break before the second program's `O` line (searched after `from`, past every run).
fn main_text_end(t: &translate::to_fanuc::Output, eol: &str, from: usize) -> usize {
    let Some(crate::ir::ProgName::Number(n)) = t.unit.programs.get(1).and_then(|p| p.name.as_ref()) else {
        return t.text.len();
    };
    let o = format!("{eol}O{n:04}");
    // From the line end `from` follows (a run's placeholder line may be the main's last).
    let mut at = from.saturating_sub(eol.len()).min(t.text.len());
    while let Some(k) = t.text.get(at..).and_then(|r| r.find(&o)) {
        let hi = at + k + o.len();
        if !t.text[hi..].starts_with(|c: char| c.is_ascii_digit()) {
            return at + k + eol.len();
        }
        at = hi;
    }
    t.text.len()
}

/// Most carrier blocks (run N numbers) a skeleton takes.
const MAX_CARRIED: usize = 20_000;

/// For a labels pass that will number jump targets from N1 up: the N values of run blocks
/// up to where `fresh` numbers no block uses are passed (the most targets the lowered
/// skeleton can have: a few per statement) go into the skeleton as carrier blocks, empty
/// blocks with that N and the last run's marker, right after its placeholder (their lines
/// are replaced with it). They give the labels pass the same numbers in use there as the
/// whole program has; they are not jump targets (a target N in a run was kept out of the
/// runs) and hold no label, so they change nothing else. `fresh_numbers_ok` checks the
/// result. Declines when the numbers run out.
fn carry_numbers(sk: &Skel<ToFanuc<'_>>, body: &mut Vec<Stmt>, fresh: u64) -> Result<(), Fallback> {
    let (mut free, mut v, mut carried) = (0u64, 0u32, Vec::new());
    while free < fresh {
        v += 1;
        if v > MAX_N || carried.len() > MAX_CARRIED {
            return Err(Fallback::NotStraight("N numbers close to N99999, most of them in use".into()));
        }
        if sk.t.skel_ns.has(v) {
            continue;
        }
        if sk.run_ns.has(v) {
            carried.push(v);
        } else {
            free += 1;
        }
    }
    let Some(last) = sk.runs.checked_sub(1) else { return Ok(()) };
    let mark = super::mark(last);
    let is_last =
        |s: &Stmt| matches!(&s.kind, StmtKind::Block(b) if b.meta.comments.first().is_some_and(|c| c.text == mark));
    let Some(at) = body.iter().rposition(is_last) else {
        return Err(Fallback::NotStraight("a lost placeholder (a bug in nctrans)".into()));
    };
    let span = body[at].span;
    let carriers = carried.into_iter().map(|value| {
        let meta = crate::ir::BlockMeta {
            span,
            number: Some(crate::ir::SeqNo { value, span }),
            comments: vec![crate::ir::Comment { text: mark.clone(), span }],
            ..crate::ir::BlockMeta::default()
        };
        crate::lower::meta_stmt(meta, vec![])
    });
    body.splice(at + 1..at + 1, carriers);
    Ok(())
}

/// Checks that no N number the labels pass gave a jump target in the translated skeleton
/// `text` (an N at a line start, outside the placeholders, that no skeleton block has in
/// the source) is one a run block has: the whole translation would have skipped it.
fn fresh_numbers_ok(text: &str, eol: &str, places: &[(usize, usize)], sk: &Skel<ToFanuc<'_>>) -> Result<(), Fallback> {
    let mut at = 0;
    let mut places = places.iter().peekable();
    for line in text.split_inclusive(eol) {
        let lo = at;
        at += line.len();
        while places.next_if(|p| p.1 <= lo).is_some() {}
        if places.peek().is_some_and(|p| p.0 <= lo) {
            continue;
        }
        let l = line.trim_start_matches(|c: char| c == '/' || c.is_ascii_digit() || c == ' ');
        let l = if line.starts_with('/') { l } else { line };
        let Some(d) = l.strip_prefix('N') else { continue };
        let digits = d.bytes().take_while(u8::is_ascii_digit).count();
        let Ok(n) = d[..digits].parse::<u32>() else { continue };
        if n <= MAX_N && !sk.t.skel_ns.has(n) && sk.run_ns.has(n) {
            return Err(Fallback::NotStraight("N numbers close to N99999, too many jump targets".into()));
        }
    }
    Ok(())
}
