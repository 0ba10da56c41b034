//! Segmented streaming translation (FANUC → Sinumerik) of programs with a macro part: the
//! top-level statements that are not straight blocks (macro statements, IF/GOTO,
//! WHILE/DO loops, program ends, jump targets) are kept as IR, each maximal run of
//! top-level straight blocks between them stands in that IR as ONE placeholder block (a
//! comment `NCTRANS SEGMENT k`), and the whole-program translator translates that skeleton
//! (variable map, DEF lines, labels, structures come out as for the whole file). The
//! skeleton's text is then written with each placeholder line replaced by its run, re-read
//! from the source and translated block by block by the straight stream's fast path (or,
//! for a block it declines, by the passes on that block alone). Memory follows the macro
//! part, not the motion part.
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
//! line ends and N values above 2^24. The source is read once before verification: ONE
//! scan (`one`) builds the skeleton (and collects the N values jumps name) and translates
//! each run as it reaches it into a spill (`segmented::spill`: memory, then a temporary
//! file about the output's size), since the arc mode a run depends on is followed in
//! textual order and known there; a run block the fast path declines is kept (up to a few
//! thousand) and translated alone with the skeleton's plan after the scan. The skeleton's
//! text is then written with each placeholder line replaced by a byte copy of its run's
//! spilled translation, the blocks translated alone put in at their places. When a jump
//! names the N of a run block, a second scan builds the skeleton again with those blocks
//! kept out of runs, and a writing scan (`writer`) fills the runs, as it does when more
//! blocks are declined or a declined line turns out to be no run block.

use super::nset::{kept, NSet, MAX_TRACKED_N};
use super::spill::{assemble, Spill};
use super::splice::{self, Splice};
use super::{LoadCallees, MARK};
use crate::dialect::{Dialect, ParseOptions};
use crate::ir::{Addr, BlockMeta, Item, ItemKind, Program, Stmt, StmtKind, Target, Unit, VarKind, Word, WordValue};
use crate::lower::to_sinumerik::fast_write as fast;
use crate::lower::to_sinumerik::{self as passes, Options};
use crate::read::{LineEnding, RawBlock};
use crate::span::Span;
use crate::stream::lines::{first_line_ending, has_bom, NotStreamable};
use crate::stream::target::sinumerik::{plain_g, straight, Planned, Streamed};
use crate::stream::{Fallback, Index, PlainWord, ProgressFn, WordsSink};
use crate::translate::to_sinumerik::{self as ts, OutFile};
use one::One;
use std::io::Write;
use std::path::Path;
use writer::{kept_warning, Writer};

mod one;
mod subs;
mod writer;

pub use subs::{to_sinumerik_with_stand_in, to_sinumerik_with_subs};

/// The arc mode after G code `g10` (×10) as `words::lower` follows it.
fn arc_after(arc: bool, g10: u32) -> bool {
    match g10 {
        20 | 30 => true,
        0 | 10 => false,
        _ => arc,
    }
}

/// The arc mode after a block's own G codes.
fn follow_items(arc: bool, items: &[Item]) -> bool {
    passes::g_codes(items).into_iter().fold(arc, arc_after)
}

/// The arc mode after a plain line's G words.
fn follow_words(arc: bool, words: &[PlainWord]) -> bool {
    words.iter().filter(|w| w.letter == b'G').fold(arc, |a, w| arc_after(a, fast::round(w.value * 10.0) as u32))
}

/// Whether an M value is a program end, call or return (never a plain word of a run).
fn special_m(v: f64) -> bool {
    v == 2.0 || v == 30.0 || v == 97.0 || v == 98.0 || v == 99.0
}

/// A block the translation surely keeps as a line with an item, a number or a label (so
/// `take_inputs` stops there): a number, a program end, a constant motion word or a G code
/// the words pass keeps. Anything else counts as not (runs start later).
fn solid(s: &Stmt) -> bool {
    let StmtKind::Block(b) = &s.kind else { return true };
    b.meta.number.is_some()
        || b.items.iter().any(|it| match &it.kind {
            ItemKind::End { .. } => true,
            ItemKind::Word(Word { addr: Addr::Letter(l), value: WordValue::Expr(e), .. }) => {
                let v = crate::lower::literal(e);
                match l {
                    b'G' => v.is_some_and(|v| {
                        matches!((v * 10.0).round() as u32, 0 | 10 | 20 | 30 | 170 | 180 | 190 | 900 | 910 | 940 | 950)
                    }),
                    b'X' | b'Y' | b'Z' | b'A' | b'B' | b'C' | b'F' | b'S' | b'T' | b'D' => v.is_some(),
                    _ => false,
                }
            }
            _ => false,
        })
}

/// What declines an item of the skeleton (see the module comment); its jump target.
fn check_item(it: &Item, calls: bool, targets: &mut Vec<u32>) -> Option<&'static str> {
    match &it.kind {
        ItemKind::Call(c) if calls && subs::plain_call(c) => None,
        ItemKind::ModalCallOff if calls => None,
        ItemKind::Call(_) | ItemKind::ModalCallOff => Some("a call of another program"),
        ItemKind::Return { .. } => Some("M99"),
        ItemKind::ParamWrite(_) => Some("G10"),
        ItemKind::Goto(g) => match &g.target {
            Target::Number(n) => {
                targets.push(n.value);
                None
            }
            _ => Some("a computed jump"),
        },
        ItemKind::Assign { target, .. } => match target.kind {
            VarKind::Hash(5221..=5340) | VarKind::HashIndirect(_) => Some("a work offset or indirect write"),
            _ => None,
        },
        ItemKind::Word(Word { addr, value: WordValue::Expr(e), .. }) if addr.is(b'G') => {
            // A drilling cycle makes the blocks after it holes: read whole.
            crate::lower::literal(e).and_then(|v| match (v * 10.0).round() as u32 {
                100 | 110 => Some("G10"),
                730 | 740 | 760 | 810..=890 => Some("a drilling cycle"),
                _ => None,
            })
        }
        _ => None,
    }
}

/// Which top-level statements are run blocks; the same in every scan (it changes only
/// on statements that are not).
#[derive(Clone, Default)]
struct Class {
    /// N values jumps name (their blocks stay in the skeleton).
    keep: NSet,
    /// A `solid` statement has been seen.
    solid: bool,
}

impl Class {
    /// Whether a plain line is a run block (else it is to come as a statement).
    fn plain_run(&self, meta: &BlockMeta, words: &[PlainWord]) -> bool {
        self.solid
            && meta.label.is_none()
            && !kept(&self.keep, meta)
            && words.iter().all(|w| match w.letter {
                // G0..G3 (plain) without `plain_g`'s rounding: CAM lines are made of them.
                // Not G20: the runs are written metric, and a G20 in the skeleton reads the
                // program whole.
                b'G' => {
                    let g = w.value as u32;
                    (g <= 3 && f64::from(g) == w.value) || (plain_g(w.value) && w.value != 20.0)
                }
                b'M' => !special_m(w.value),
                _ => true,
            })
    }

    fn stmt_run(&self, s: &Stmt) -> bool {
        let StmtKind::Block(b) = &s.kind else { return false };
        self.solid
            && straight(s).is_ok()
            && !crate::lower::to_sinumerik::modal::has_g(std::slice::from_ref(s), &[200])
            && !kept(&self.keep, &b.meta)
            && !b.items.iter().any(|it| matches!(it.kind, ItemKind::End { .. }))
    }

    /// After a statement of the skeleton.
    fn observe(&mut self, s: &Stmt) {
        self.solid |= solid(s);
    }
}

/// The first scans' sink: builds the skeleton.
struct Skel {
    class: Class,
    body: Vec<Stmt>,
    /// The run being collected (the span of its first block).
    run: Option<Span>,
    /// The arc mode at the start of each run.
    arcs: Vec<bool>,
    /// The arc mode after everything so far (what the words pass has on the whole file)…
    arc: bool,
    /// … and after the skeleton's statements alone (what it has on the skeleton).
    own_arc: bool,
    run_ns: NSet,
    targets: NSet,
    stop: Option<String>,
    /// Calls by a constant number are kept, and the programs after the main one are
    /// collected whole (`subs`); else both decline.
    calls: bool,
    /// The bodies of the programs after the main one (program k + 1 at k), read whole.
    subs: Vec<Vec<Stmt>>,
    /// Those programs, with their bodies (after `finish`).
    sub_programs: Vec<Program>,
}

impl Skel {
    fn decline(&mut self, why: impl Into<String>) {
        self.stop.get_or_insert_with(|| why.into());
    }

    fn run_block(&mut self, meta: &BlockMeta) {
        if let Some(n) = &meta.number {
            if n.value > MAX_TRACKED_N {
                return self.decline("an N number above 16777216");
            }
            self.run_ns.insert(n.value);
        }
        if self.run.is_none() {
            self.run = Some(meta.span);
            self.arcs.push(self.arc);
        }
    }

    fn close_run(&mut self) {
        if let Some(span) = self.run.take() {
            let k = self.arcs.len() - 1;
            self.body.push(passes::comment_stmt(format!("{MARK}{k}"), span));
        }
    }

    /// Checks a statement of the skeleton, collects its jump targets, follows its arc mode.
    fn macro_stmt(&mut self, s: &Stmt) {
        let mut why: Option<&'static str> = None;
        let mut targets = Vec::new();
        let (mut arc, mut own) = (self.arc, self.own_arc);
        crate::ir::visit::walk_stmts(std::slice::from_ref(s), &mut |s| {
            let StmtKind::Block(b) = &s.kind else { return };
            if b.meta.number.as_ref().is_some_and(|n| n.value > MAX_TRACKED_N) {
                why = why.or(Some("an N number above 16777216"));
            }
            arc = follow_items(arc, &b.items);
            own = follow_items(own, &b.items);
            if arc != own && b.items.iter().any(|it| matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'R'))) {
                why = why.or(Some("an R word in the macro part after an arc mode set in a run"));
            }
            for it in &b.items {
                why = why.or(check_item(it, self.calls, &mut targets));
                if let ItemKind::IfThen { then, .. } = &it.kind {
                    if matches!(then.kind, ItemKind::Word(_)) {
                        why = why.or(Some("IF..THEN with an address word"));
                    }
                    why = why.or(check_item(then, self.calls, &mut targets));
                }
            }
        });
        if let Some(w) = why {
            return self.decline(w);
        }
        for n in targets {
            if n > MAX_TRACKED_N {
                return self.decline("a jump to an N number above 16777216");
            }
            self.targets.insert(n);
        }
        (self.arc, self.own_arc) = (arc, own);
        self.class.observe(s);
        self.body.push(s.clone());
    }
}

impl WordsSink for Skel {
    fn active(&self) -> bool {
        self.stop.is_none()
    }

    fn plain(&mut self, prog: usize, meta: &BlockMeta, words: &[PlainWord], _: &RawBlock<'_>) -> bool {
        if self.stop.is_some() {
            return true;
        }
        if words.iter().any(|w| crate::lower::comp_flow::stream_relevant_word(w.letter, Some(w.value), true, true)) {
            self.decline(crate::stream::target::sinumerik::COMP_M6);
            return true;
        }
        if prog != 0 {
            if !self.calls {
                self.decline("more than one program");
            }
            // A subprogram's line: it comes as a statement, kept whole.
            return !self.calls;
        }
        if !self.class.plain_run(meta, words) {
            return false;
        }
        self.run_block(meta);
        self.arc = follow_words(self.arc, words);
        true
    }

    fn stmt(&mut self, prog: usize, s: &Stmt) {
        if self.stop.is_some() {
            return;
        }
        if crate::lower::comp_flow::stream_relevant(std::slice::from_ref(s), true, true) {
            return self.decline(crate::stream::target::sinumerik::COMP_M6);
        }
        if prog != 0 {
            return self.sub_stmt(prog, s);
        }
        if self.class.stmt_run(s) {
            if let StmtKind::Block(b) = &s.kind {
                self.run_block(&b.meta);
                self.arc = follow_items(self.arc, &b.items);
            }
            return;
        }
        self.close_run();
        self.macro_stmt(s);
    }
}

/// A skeleton scan's sink before the scan, with the N values `keep` kept out of runs.
fn new_skel(keep: NSet, calls: bool) -> Skel {
    Skel {
        class: Class { keep, solid: false },
        body: Vec::new(),
        run: None,
        arcs: Vec::new(),
        arc: false,
        own_arc: false,
        run_ns: NSet::default(),
        targets: NSet::default(),
        stop: None,
        calls,
        subs: Vec::new(),
        sub_programs: Vec::new(),
    }
}

/// A skeleton after its scan of `path` (whose index is `ix`): the skeleton, the program it
/// is the body of, and the index.
fn finish(path: &Path, eol: LineEnding, mut sk: Skel, ix: Index) -> Result<(Skel, Program, Index), Fallback> {
    sk.close_run();
    if let Some(why) = sk.stop.take() {
        return Err(Fallback::NotStraight(why));
    }
    if !ix.diags.is_empty() {
        return Err(Fallback::Diagnostics);
    }
    // `header_inputs` reads a whole text by LF lines, an index's header by any line end.
    let cr = eol == LineEnding::Cr || first_line_ending(path).map_err(Fallback::NotStreamable)? == LineEnding::Cr;
    if cr && ix.header.contains("nctrans:") {
        return Err(Fallback::NotStraight("`nctrans: set` lines with CR line ends".into()));
    }
    if ix.programs.len() != 1 && !sk.calls || ix.programs.is_empty() || sk.subs.len() >= ix.programs.len() {
        return Err(Fallback::NotStraight("more than one program".into()));
    }
    let mut subs = std::mem::take(&mut sk.subs).into_iter();
    sk.sub_programs = ix.programs[1..]
        .iter()
        .map(|p| Program { body: subs.next().unwrap_or_default(), ..p.program.clone() })
        .collect();
    let program = ix.programs[0].program.clone();
    Ok((sk, program, ix))
}

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
    segment(path, opts, eol, out, progress, None, None).map(|(s, _)| s)
}

fn segment(
    path: &Path,
    opts: &Options,
    eol: LineEnding,
    out: &mut dyn Write,
    progress: Option<ProgressFn<'_>>,
    mut load: Option<LoadCallees<'_>>,
    stand_in: Option<crate::span::FileId>,
) -> Result<(Streamed, Vec<OutFile>), Fallback> {
    let calls = load.is_some();
    let popts = ParseOptions { semantics: opts.source.clone() };
    let mut progress = progress;
    // One scan builds the skeleton and spills the runs' translations (`one`).
    let mut one = One {
        sk: new_skel(NSet::default(), calls),
        opts,
        eol,
        spill: Spill::new(),
        starts: Vec::new(),
        pending: false,
        deferred: Vec::new(),
        ok: true,
    };
    let ix = super::super::scan_words_path(
        path,
        0,
        Dialect::Fanuc,
        &popts,
        &mut one,
        progress.as_mut().map(|p| &mut **p as _),
    )
    .map_err(Fallback::NotStreamable)?;
    let (mut sk, mut program, ix) = finish(path, eol, one.sk, ix)?;
    let live = one.ok && !one.pending && one.spill.io.is_none() && one.starts.len() == sk.arcs.len();
    let mut spilled = live.then_some((one.spill, one.starts, one.deferred, ix));
    if sk.targets.meets(&sk.run_ns) {
        // Jumps name N values of run blocks: scan again keeping those blocks real, and
        // write the runs in a writing scan.
        spilled = None;
        let mut again = new_skel(sk.targets.clone(), calls);
        let ix = super::super::scan_words_path(path, 0, Dialect::Fanuc, &popts, &mut again, None)
            .map_err(Fallback::NotStreamable)?;
        (sk, program, _) = finish(path, eol, again, ix)?;
        if sk.targets.meets(&sk.run_ns) {
            return Err(Fallback::NotStraight("a jump into a run of straight blocks".into()));
        }
    }
    let keep = sk.class.keep.clone();
    program.body = std::mem::take(&mut sk.body);
    let mut programs = vec![program];
    programs.append(&mut sk.sub_programs);
    // The runs are written metric: a G20 anywhere (never in a run, `PLAIN_G`) reads whole.
    if programs.iter().any(|p| crate::lower::to_sinumerik::modal::has_g(&p.body, &[200])) {
        return Err(Fallback::NotStraight("G20 (a program with inch values is read whole)".into()));
    }
    let unit = Unit { dialect: Dialect::Fanuc, file: 0, programs };
    // The callees beside the file, as the whole path loads them (`subs`).
    let callees = match load.as_mut() {
        Some(load) => load(&unit)?,
        None => Vec::new(),
    };
    subs::callees_ok(&callees)?;
    let units: Vec<&Unit> = std::iter::once(&unit).chain(&callees).collect();
    let tr = ts::translate(&units, opts, eol);
    if !tr.diags.iter().all(|d| kept_warning(d) && d.labels.iter().all(|l| l.file == 0)) {
        return Err(Fallback::Diagnostics);
    }
    // A stand-in caller's program (`subs::to_sinumerik_with_stand_in`) is no file of the
    // result; a diagnostic on it has declined above (its file is not 0).
    let files: Vec<OutFile> = tr.files.iter().filter(|f| Some(f.source) != stand_in).cloned().collect();
    let (f, subs) = subs::split_files(&files, calls)?;
    let places = splice::placeholders(&f.text, (sk.arcs.len(), eol.as_str()), (MARK, ""), |h| h == "; ", false)
        .ok_or_else(|| Fallback::NotStraight("a comment that reads as a segment marker".into()))?;
    // The main program's plan, made with every program as the whole translation makes it.
    let alone = {
        let all: Vec<(crate::span::FileId, &Program)> =
            units.iter().flat_map(|u| u.programs.iter().map(move |p| (u.file, p))).collect();
        Planned::of_first(&all, opts).ok_or_else(|| Fallback::NotStraight("no plan".into()))?
    };
    drop(units);
    drop(callees);
    drop(unit);
    let bom = has_bom(path).map_err(|e| Fallback::NotStreamable(e.into()))?;
    // The words pass warns block by block in text order: the skeleton's warnings and the
    // runs' interleave by their place in the file.
    let finish = |index: super::super::Index, mut run_diags: Vec<crate::diag::Diagnostic>| {
        let mut diags = tr.diags.clone();
        diags.append(&mut run_diags);
        diags.sort_by_key(|d| d.labels.first().map_or(0, |l| l.span.lo));
        Streamed {
            blocks: index.blocks,
            index,
            diags,
            file_name: f.name.clone(),
            program: f.program.clone(),
            fanuc_number: f.fanuc_number,
            symbols: tr.symbols.sinumerik().clone(),
        }
    };
    if let Some((spill, starts, deferred, index)) = spilled {
        // The blocks the fast path declined, as the writing scan translates them.
        let mut inserts = Vec::with_capacity(deferred.len());
        let mut run_diags = Vec::new();
        for d in deferred {
            let Some((text, diags)) = writer::alone(&alone, opts, &d.stmt, d.arc, eol) else {
                return Err(Fallback::Diagnostics);
            };
            run_diags.extend(diags);
            inserts.push((d.run, d.at, text));
        }
        let io = |e| Fallback::NotStreamable(NotStreamable::Io(e));
        if bom {
            out.write_all(b"\xEF\xBB\xBF").map_err(io)?;
        }
        assemble(&f.text, &places, spill, &starts, &inserts, out).map_err(io)?;
        return Ok((finish(index, run_diags), subs));
    }
    let mut w = Writer {
        class: Class { keep, solid: false },
        opts,
        alone,
        eol,
        arcs: sk.arcs,
        pending: false,
        arc: false,
        out: Splice::new(&f.text, places, out),
        diags: Vec::new(),
    };
    if bom {
        w.out.buf.extend_from_slice(b"\xEF\xBB\xBF");
    }
    let index = super::super::scan_words_path(path, 0, Dialect::Fanuc, &popts, &mut w, progress)
        .map_err(Fallback::NotStreamable)?;
    if w.out.bad || !index.diags.is_empty() {
        return Err(Fallback::Diagnostics);
    }
    w.out.finish()?;
    Ok((finish(index, w.diags), subs))
}
