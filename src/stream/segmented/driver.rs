//! The one segmented driver, for every target: the one scan (skeleton and spilled runs),
//! the second skeleton scan when a jump names a run block's N, the skeleton's programs,
//! callees, translation and placeholder lines, then either the splice of the spilled runs into its text or the writing scan (the sinks
//! are `sinks`). What differs between targets is a [`SegTarget`]: what a skeleton keeps
//! and which modes it follows ([`SkelPart`]), the fast writer of run blocks ([`RunWriter`]), the
//! whole translation of the skeleton and the translation of a block alone. Generic, so
//! each target's calls are its own code (no dynamic dispatch per block).

use super::nset::Keep;
use super::sinks::{One, Skel, Writer};
use super::spill::{assemble, Spill};
use super::splice::{self, Splice};
use super::{LoadCallees, MARK};
use crate::diag::Diagnostic;
use crate::dialect::{Dialect, ParseOptions};
use crate::ir::{Block, BlockMeta, Call, Item, ItemKind, Program, Stmt, StmtKind, Target, Unit};
use crate::span::Span;
use crate::stream::lines::NotStreamable;
use crate::stream::target::RunWriter;
use crate::stream::{Fallback, Index, PlainWord, ProgressFn};
use std::io::Write;
use std::path::Path;

/// A target's part of the skeleton scan: which blocks are run blocks, the modes
/// it follows in textual order, its placeholder and what declines a macro statement.
pub(crate) trait SkelPart {
    type Mode: Copy;
    /// Whether a plain top-level line of the main program is a run block, with the N
    /// values `keep` kept out of runs.
    fn plain_run(&self, keep: &Keep, meta: &BlockMeta, words: &[PlainWord]) -> bool;
    /// Whether a top-level statement of the main program is a run block (noting what the
    /// target follows of the statements that are not).
    fn stmt_run(&mut self, keep: &Keep, s: &Stmt) -> bool;
    /// The mode a run starting here starts in.
    fn mode(&self) -> Self::Mode;
    /// A run block (its N already checked and recorded), `starting` a run.
    fn run_block(&mut self, _meta: &BlockMeta, _starting: bool) {}
    /// The modes after a plain run block's words, and after a run statement's items.
    fn follow_plain(&mut self, words: &[PlainWord]);
    fn follow_stmt(&mut self, items: &[Item]);
    /// The placeholder of a run (whose first block is at `span`): a block with the comment
    /// `mark` (its run's [`mark`](super::mark)).
    fn placeholder(&mut self, mark: String, span: Span) -> Stmt;
    /// What following a statement of the skeleton changes (taken only if none of its blocks
    /// declines, `walked`), from here.
    type Walk;
    fn walk(&self) -> Self::Walk;
    /// Each block of a statement of the skeleton in textual order: why it declines, with
    /// what it follows in `w` and the N values its jumps name in `targets`.
    fn macro_block(w: &mut Self::Walk, b: &Block, calls: bool, targets: &mut Vec<u32>) -> Why;
    fn walked(&mut self, w: Self::Walk, s: &Stmt);
}

/// Why a statement declines (`None`: it does not).
pub(crate) type Why = Option<&'static str>;

/// For `SkelPart::macro_block`, every target's rule for a jump or a call (`None`: neither): a jump's
/// N goes into `targets`, a computed one declines; a call declines unless `calls` and `plain`.
pub(crate) fn jump_or_call(it: &Item, calls: bool, plain: fn(&Call) -> bool, targets: &mut Vec<u32>) -> Option<Why> {
    match &it.kind {
        ItemKind::Goto(g) => {
            if let Target::Number(n) = &g.target {
                targets.push(n.value);
            }
            Some(matches!(g.target, Target::Computed(_)).then_some("a computed jump"))
        }
        ItemKind::Call(c) => Some((!(calls && plain(c))).then_some("a call of another program")),
        _ => None,
    }
}

/// The writing scan's run-block tests (the skeleton scan's, with what it found).
pub(crate) trait RunTests {
    fn plain_run(&self, keep: &Keep, meta: &BlockMeta, words: &[PlainWord]) -> bool;
    fn stmt_run(&mut self, keep: &Keep, s: &Stmt) -> bool;
}

/// What a target supplies to the segmented driver (see the module comment).
pub(crate) trait SegTarget: Sized {
    /// The dialect of the source read.
    const SOURCE: Dialect;
    /// Why a program with a tool change or compensation word is read whole.
    const COMP: &'static str;
    /// With calls, the other programs of the source file are kept whole beside the main
    /// one (else a second program declines).
    const SUBS_IN_FILE: bool;
    /// Most run blocks the fast writer declines that the one scan holds for translating
    /// alone after it (more take the writing scan).
    const MAX_DEFERRED: usize;
    /// A plain run line the fast writer declined must come back as a run block's
    /// statement (else the one scan gives up and the writing scan discards the output).
    const STRICT_DECLINED: bool;
    type Mode: Copy;
    type Track: SkelPart<Mode = Self::Mode> + Default;
    type Fast: RunWriter<Mode = Self::Mode>;
    type Class: RunTests;
    /// What translating a block alone needs (known after the skeleton's translation).
    type Alone;
    /// What the result needs from the skeleton's translation.
    type Done;
    type Output;
    /// How its placeholder lines read in the translated skeleton ([`places`]).
    const PLACE: Place;

    /// Options that send the file to the whole path before any scan.
    fn check(&self) -> Result<(), Fallback> {
        Ok(())
    }
    fn parse_options(&self) -> ParseOptions;
    fn fast(&self) -> Self::Fast;
    /// `SkelPart::follow_plain` after the fast writer took the line (it may know them).
    #[inline]
    fn plain_taken(t: &mut Self::Track, _fast: &Self::Fast, words: &[PlainWord]) {
        t.follow_plain(words)
    }
    /// Why a statement of a program after the main one declines (`SUBS_IN_FILE`).
    fn sub_declines(_: &Stmt) -> Option<&'static str> {
        None
    }

    /// Why the source declines, after a skeleton scan of `path` without a decline.
    fn source_ok(&self, _path: &Path, _ix: &Index) -> Result<(), Fallback> {
        Ok(())
    }
    /// Why the main program (its body still the scan's) declines, once counted.
    fn main_ok(&self, _main: &Program) -> Result<(), Fallback> {
        Ok(())
    }
    /// Why the skeleton's programs (the main one's body the skeleton) decline, before the
    /// callees are loaded (the target may change them).
    fn skeleton_ok(&self, _sk: &mut Skel<Self>, _programs: &mut [Program]) -> Result<(), Fallback> {
        Ok(())
    }
    /// Translates the skeleton into its text and placeholders ([`places`]).
    fn translate(&self, s: Skeleton<'_, Self>) -> Result<Translated<Self>, Fallback>;
    /// Lowers a run block alone, with the mode running into it: its text and the
    /// diagnostics kept with it (`None`: they decline).
    fn alone(&self, a: &Self::Alone, s: &Stmt, m: Self::Mode) -> Option<(String, Vec<Diagnostic>)>;
    /// The writing scan's tests, from the skeleton (its `keep` is the driver's).
    fn class(t: &mut Self::Track) -> Self::Class;
    /// The result, with the source's index and the kept diagnostics of run blocks.
    fn done(&self, d: Self::Done, index: Index, run_diags: Vec<Diagnostic>) -> Self::Output;
}

/// A skeleton to translate: the source, its scan, the unit of its programs (file 0, the
/// main one first with the skeleton as its body) and the callees loaded for it.
pub(crate) struct Skeleton<'s, T: SegTarget> {
    pub(crate) path: &'s Path,
    pub(crate) sk: &'s mut Skel<T>,
    pub(crate) unit: Unit,
    pub(crate) callees: Vec<Unit>,
}

/// How a target writes a placeholder line (`splice::placeholders`): the text before the marker
/// and after its run's index, the line heads it takes, whether carrier lines follow it.
pub(crate) type Place = (&'static str, &'static str, fn(&str) -> bool, bool);

/// The placeholder lines of a translated skeleton `text` of `runs` runs written with
/// `eol` line ends, in order, as `T` writes them; declines when the marker is anywhere else.
pub(crate) fn places<T: SegTarget>(text: &str, runs: usize, eol: &str) -> Result<Vec<(usize, usize)>, Fallback> {
    let (open, close, head, carriers) = T::PLACE;
    splice::placeholders(text, (runs, eol), (&format!("{open}{MARK}"), close), head, carriers)
        .ok_or_else(|| Fallback::NotStraight("a comment that reads as a segment marker".into()))
}

/// A translated skeleton.
pub(crate) struct Translated<T: SegTarget> {
    pub(crate) text: String,
    /// Its placeholder lines (`splice::placeholders`).
    pub(crate) places: Vec<(usize, usize)>,
    pub(crate) alone: T::Alone,
    /// Written before everything (a BOM).
    pub(crate) prefix: &'static [u8],
    pub(crate) done: T::Done,
}

/// A run block the fast writer declined in the one scan, translated alone after it.
pub(crate) struct Deferred<M> {
    /// Its run.
    pub(crate) run: usize,
    /// Where its translation goes in the spill (between the blocks around it).
    pub(crate) at: u64,
    pub(crate) stmt: Stmt,
    /// The mode running into it.
    pub(crate) mode: M,
}

/// A skeleton after its scan (whose index is `ix`): the skeleton, the programs and the index.
fn finish<T: SegTarget>(
    t: &T,
    path: &Path,
    mut sk: Skel<T>,
    ix: Index,
) -> Result<(Skel<T>, Vec<Program>, Index), Fallback> {
    sk.close_run();
    if let Some(why) = sk.stop.take() {
        return Err(Fallback::NotStraight(why));
    }
    if !ix.diags.is_empty() {
        return Err(Fallback::Diagnostics);
    }
    t.source_ok(path, &ix)?;
    // The programs after the main one are the ones the scan kept whole (`SUBS_IN_FILE`).
    let n = ix.programs.len();
    if n != 1 && !(T::SUBS_IN_FILE && sk.calls) || n == 0 || sk.subs.len() >= n {
        return Err(Fallback::NotStraight("more than one program".into()));
    }
    t.main_ok(&ix.programs[0].program)?;
    let mut subs = std::mem::take(&mut sk.subs).into_iter();
    let rest = ix.programs[1..].iter().map(|p| Program { body: subs.next().unwrap_or_default(), ..p.program.clone() });
    let programs = std::iter::once(ix.programs[0].program.clone()).chain(rest).collect();
    Ok((sk, programs, ix))
}

/// Where the sections a program-section repetition (`REPEAT`, `REPEATB`) may copy lie in a
/// skeleton: from the first block with a label a repetition names up to the last
/// repetition (source offsets). The copy of a run's placeholder would be a second line
/// of it, and the copy's blocks are written where the REPEAT stands, without N numbers
/// (`lower::to_fanuc::repeat_sections`), not as the run's bytes: the blocks there stay in
/// the skeleton, translated whole with their copies.
fn repeated(body: &[Stmt]) -> Option<(u32, u32)> {
    let (mut names, mut hi) = (Vec::new(), None);
    crate::ir::visit::walk_stmts(body, &mut |s| {
        let StmtKind::Block(b) = &s.kind else { return };
        for it in &b.items {
            if let ItemKind::RepeatSection(r) = &it.kind {
                names.push(r.start.name.clone());
                hi = hi.max(Some(s.span.lo));
            }
        }
    });
    let hi = hi?;
    let mut lo = hi;
    crate::ir::visit::walk_stmts(body, &mut |s| {
        // Any line of a statement (a structure's head or end may be labelled).
        if crate::ir::visit::metas(&s.kind).iter().any(|m| m.label.as_ref().is_some_and(|l| names.contains(&l.name))) {
            lo = lo.min(s.span.lo);
        }
    });
    Some((lo, hi))
}

/// Whether a run's placeholder of `body` lies in `sections`.
fn runs_in(body: &[Stmt], sections: Option<(u32, u32)>) -> bool {
    let Some((lo, hi)) = sections else { return false };
    body.iter().any(|s| {
        matches!(&s.kind, StmtKind::Block(b) if b.meta.comments.first().is_some_and(|c| c.text.starts_with(MARK)))
            && (lo..hi).contains(&s.span.lo)
    })
}

/// Translates `path` into `out` as a skeleton translated whole with its runs of straight
/// blocks streamed (see `segmented`). On `Err` nothing useful was written (the caller
/// discards `out` and translates whole).
pub(crate) fn segment<T: SegTarget>(
    t: &T,
    path: &Path,
    out: &mut dyn Write,
    mut progress: Option<ProgressFn<'_>>,
    load: Option<LoadCallees<'_>>,
) -> Result<T::Output, Fallback> {
    t.check()?;
    let calls = load.is_some();
    let popts = t.parse_options();
    // One scan builds the skeleton and spills the runs' translations.
    let sk = Skel::new(Keep::default(), calls);
    let mut one =
        One { sk, fast: t.fast(), spill: Spill::new(), starts: vec![], pending: false, deferred: vec![], ok: true };
    let ix =
        crate::stream::scan_words_path(path, 0, T::SOURCE, &popts, &mut one, progress.as_mut().map(|p| &mut **p as _))
            .map_err(Fallback::NotStreamable)?;
    let (mut sk, mut programs, ix) = finish(t, path, one.sk, ix)?;
    let live = one.ok && !(T::STRICT_DECLINED && one.pending) && one.spill.io.is_none() && one.starts.len() == sk.runs;
    let mut spilled = live.then_some((one.spill, one.starts, one.deferred, ix));
    let sections = repeated(&sk.body);
    if sk.targets.meets(&sk.run_ns) || runs_in(&sk.body, sections) {
        // Jumps name N values of run blocks, or a section repetition may copy runs: scan
        // again keeping those blocks real, and write the runs in a writing scan.
        spilled = None;
        let mut again = Skel::new(Keep { ns: sk.targets.clone(), spans: sections }, calls);
        let ix = crate::stream::scan_words_path(path, 0, T::SOURCE, &popts, &mut again, None)
            .map_err(Fallback::NotStreamable)?;
        (sk, programs, _) = finish(t, path, again, ix)?;
        if sk.targets.meets(&sk.run_ns) {
            return Err(Fallback::NotStraight("a jump into a run of straight blocks".into()));
        }
        if runs_in(&sk.body, sections) || repeated(&sk.body) != sections {
            return Err(Fallback::NotStraight("a run in a repeated section (a bug in nctrans)".into()));
        }
    }
    programs[0].body = std::mem::take(&mut sk.body);
    t.skeleton_ok(&mut sk, &mut programs)?;
    let unit = Unit { dialect: T::SOURCE, file: 0, programs };
    let callees = load.map_or(Ok(Vec::new()), |load| load(&unit))?;
    let Translated { text, places, alone, prefix, done } =
        t.translate(Skeleton { path, sk: &mut sk, unit, callees })?;
    if let Some((spill, starts, deferred, index)) = spilled {
        // The blocks the fast writer declined, as the writing scan translates them.
        let mut inserts = Vec::with_capacity(deferred.len());
        let mut run_diags = Vec::new();
        for d in deferred {
            let Some((text, diags)) = t.alone(&alone, &d.stmt, d.mode) else {
                return Err(Fallback::Diagnostics);
            };
            run_diags.extend(diags);
            inserts.push((d.run, d.at, text));
        }
        let io = |e| Fallback::NotStreamable(NotStreamable::Io(e));
        if !prefix.is_empty() {
            out.write_all(prefix).map_err(io)?;
        }
        assemble(&text, &places, spill, &starts, &inserts, out).map_err(io)?;
        return Ok(t.done(done, index, run_diags));
    }
    let modes = std::mem::take(&mut sk.modes);
    let out = Splice::new(&text, places, out);
    let (class, keep) = (T::class(&mut sk.t), std::mem::take(&mut sk.keep));
    let mut w = Writer { t, class, keep, fast: t.fast(), modes, alone, pending: false, out, diags: vec![] };
    w.out.buf.extend_from_slice(prefix);
    let index = crate::stream::scan_words_path(path, 0, T::SOURCE, &popts, &mut w, progress)
        .map_err(Fallback::NotStreamable)?;
    if w.out.bad || !index.diags.is_empty() {
        return Err(Fallback::Diagnostics);
    }
    w.out.finish()?;
    Ok(t.done(done, index, w.diags))
}
