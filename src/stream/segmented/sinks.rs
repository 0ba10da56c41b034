//! The three sinks of the segmented driver, for every target: the skeleton scan (the macro
//! part kept as IR, each run of straight blocks one placeholder, the N values of run blocks
//! and of jump targets collected, the target's modes followed in textual order); the one
//! scan, the skeleton scan that also translates each run as it reaches it into a spill
//! (a run's translation depends on the one mode the target's fast writer carries, which
//! the skeleton scan follows: at a run's start it is the mode the writing scan would start
//! it in); and the writing scan (the translated skeleton's text with each placeholder line
//! replaced by its run, each run block written by the fast writer or, when it declines,
//! translated alone). See `segmented`.

use super::driver::{Deferred, RunTests, SegTarget, SkelPart};
use super::nset::{Keep, NSet, MAX_TRACKED_N};
use super::spill::Spill;
use super::splice::Splice;
use crate::diag::Diagnostic;
use crate::dialect::Dialect;
use crate::ir::{BlockMeta, Stmt, StmtKind};
use crate::read::RawBlock;
use crate::span::Span;
use crate::stream::target::RunWriter;
use crate::stream::{PlainWord, WordsSink};

/// Whether a word of a `T::SOURCE` program sends a segmented stream to the whole path
/// (a tool change too: the translation carries the tool from block to block).
#[inline]
pub(crate) fn comp_word<T: SegTarget>(w: &PlainWord) -> bool {
    crate::lower::comp_flow::stream_relevant_word(w.letter, Some(w.value), T::SOURCE == Dialect::Fanuc, true)
}

/// The skeleton scans' sink: builds the skeleton.
pub(crate) struct Skel<T: SegTarget> {
    /// The target's part.
    pub(crate) t: T::Track,
    /// N values kept out of runs (the second scan's: those jumps name).
    pub(crate) keep: Keep,
    pub(crate) body: Vec<Stmt>,
    /// The run being collected (the span of its first block).
    pub(crate) run: Option<Span>,
    /// Runs closed so far.
    pub(crate) runs: usize,
    /// The mode at the start of each run.
    pub(crate) modes: Vec<T::Mode>,
    /// N values of run blocks.
    pub(crate) run_ns: NSet,
    /// N values jumps name.
    pub(crate) targets: NSet,
    pub(crate) stop: Option<String>,
    /// Calls of other programs may stay in the skeleton (translated with the callees).
    pub(crate) calls: bool,
    /// The bodies of the programs after the main one (program k + 1 at k), read whole
    /// (`SegTarget::SUBS_IN_FILE`).
    pub(crate) subs: Vec<Vec<Stmt>>,
}

impl<T: SegTarget> Skel<T> {
    /// A skeleton scan's sink before the scan, with the N values `keep` kept out of runs.
    pub(crate) fn new(keep: Keep, calls: bool) -> Skel<T> {
        Skel {
            t: T::Track::default(),
            keep,
            body: Vec::new(),
            run: None,
            runs: 0,
            modes: Vec::new(),
            run_ns: NSet::default(),
            targets: NSet::default(),
            stop: None,
            calls,
            subs: Vec::new(),
        }
    }

    pub(crate) fn decline(&mut self, why: impl Into<String>) {
        self.stop.get_or_insert_with(|| why.into());
    }

    /// A run block (`plain_run`/`stmt_run` have judged it so).
    #[inline]
    pub(crate) fn run_block(&mut self, meta: &BlockMeta) {
        if let Some(n) = &meta.number {
            if n.value > MAX_TRACKED_N {
                return self.decline("an N number above 16777216");
            }
            self.run_ns.insert(n.value);
        }
        let starting = self.run.is_none();
        if starting {
            self.run = Some(meta.span);
            self.modes.push(self.t.mode());
        }
        self.t.run_block(meta, starting);
    }

    /// Ends the run being collected with its placeholder.
    pub(crate) fn close_run(&mut self) {
        if let Some(span) = self.run.take() {
            let p = self.t.placeholder(super::mark(self.runs), span);
            self.body.push(p);
            self.runs += 1;
        }
    }

    /// Checks a statement of the macro part, follows its modes and collects its jump targets.
    fn macro_stmt(&mut self, s: &Stmt) {
        let (mut walk, mut targets, mut why, calls) = (self.t.walk(), Vec::new(), None, self.calls);
        crate::ir::visit::walk_stmts(std::slice::from_ref(s), &mut |s| {
            if let StmtKind::Block(b) = &s.kind {
                why = why.or(T::Track::macro_block(&mut walk, b, calls, &mut targets));
            }
        });
        if let Some(w) = why {
            return self.decline(w);
        }
        self.t.walked(walk, s);
        for n in targets {
            if n > MAX_TRACKED_N {
                return self.decline("a jump to an N number above 16777216");
            }
            self.targets.insert(n);
        }
        self.body.push(s.clone());
    }

    /// A statement of a program after the main one: kept whole (the runs are the main
    /// program's only) where the target keeps them.
    fn sub_stmt(&mut self, prog: usize, s: &Stmt) {
        if !(T::SUBS_IN_FILE && self.calls) {
            return self.decline("more than one program");
        }
        self.close_run();
        if let Some(w) = T::sub_declines(s) {
            return self.decline(w);
        }
        let k = prog - 1;
        if self.subs.len() <= k {
            self.subs.resize_with(k + 1, Vec::new);
        }
        self.subs[k].push(s.clone());
    }
}

impl<T: SegTarget> WordsSink for Skel<T> {
    fn active(&self) -> bool {
        self.stop.is_none()
    }

    fn plain(&mut self, prog: usize, meta: &BlockMeta, words: &[PlainWord], _: &RawBlock<'_>) -> bool {
        if self.stop.is_some() {
            return true;
        }
        if words.iter().any(comp_word::<T>) {
            self.decline(T::COMP);
            return true;
        }
        if prog != 0 {
            if T::SUBS_IN_FILE && self.calls {
                // A subprogram's line: it comes as a statement, kept whole.
                return false;
            }
            self.decline("more than one program");
            return true;
        }
        if !self.t.plain_run(&self.keep, meta, words) {
            // Asked for as a statement.
            return false;
        }
        self.run_block(meta);
        self.t.follow_plain(words);
        true
    }

    fn stmt(&mut self, prog: usize, s: &Stmt) {
        if self.stop.is_some() {
            return;
        }
        if crate::lower::comp_flow::stream_relevant(std::slice::from_ref(s), T::SOURCE == Dialect::Fanuc, true) {
            return self.decline(T::COMP);
        }
        if prog != 0 {
            return self.sub_stmt(prog, s);
        }
        if self.t.stmt_run(&self.keep, s) {
            if let StmtKind::Block(b) = &s.kind {
                self.run_block(&b.meta);
                self.t.follow_stmt(&b.items);
            }
            return;
        }
        self.close_run();
        self.macro_stmt(s);
    }
}

/// The one scan's sink.
pub(crate) struct One<T: SegTarget> {
    pub(crate) sk: Skel<T>,
    pub(crate) fast: T::Fast,
    pub(crate) spill: Spill,
    /// Where each run's translation starts in the spill.
    pub(crate) starts: Vec<u64>,
    /// The last plain line was a run block the fast writer declined: its statement comes.
    pub(crate) pending: bool,
    /// The run blocks the fast writer declined, in order (at most `T::MAX_DEFERRED`).
    pub(crate) deferred: Vec<Deferred<T::Mode>>,
    /// The spill and `deferred` hold the runs' translations. Once `false` (a block to
    /// translate alone past `T::MAX_DEFERRED`, or with `T::STRICT_DECLINED` the statement of
    /// a declined line that is no run block) the scan only builds the skeleton and the
    /// writing scan fills the runs (and judges the case).
    pub(crate) ok: bool,
}

impl<T: SegTarget> One<T> {
    fn live(&self) -> bool {
        self.ok && self.spill.io.is_none()
    }
}

impl<T: SegTarget> WordsSink for One<T> {
    fn active(&self) -> bool {
        self.sk.active()
    }

    #[inline]
    fn plain(&mut self, prog: usize, meta: &BlockMeta, words: &[PlainWord], line: &RawBlock<'_>) -> bool {
        let sk = &self.sk;
        if !self.live()
            || sk.stop.is_some()
            || prog != 0
            || !sk.t.plain_run(&sk.keep, meta, words)
            || words.iter().any(comp_word::<T>)
        {
            return self.sk.plain(prog, meta, words, line);
        }
        // A run block (as `Skel::plain` takes it): translated first, so that a block the fast
        // writer declines comes as a statement with the skeleton not yet changed.
        let starting = sk.run.is_none();
        if starting {
            self.fast.start(sk.t.mode());
        }
        let at = self.spill.len();
        if !self.fast.plain(meta, words, line, &mut self.spill.buf) {
            self.pending = true;
            return false;
        }
        if starting {
            self.starts.push(at);
        }
        // What `Skel::plain` does with a run block.
        self.sk.run_block(meta);
        T::plain_taken(&mut self.sk.t, &self.fast, words);
        self.spill.flush_some();
        true
    }

    fn stmt(&mut self, prog: usize, s: &Stmt) {
        let pending = std::mem::take(&mut self.pending);
        let (was_run, before) = (self.sk.run.is_some(), self.sk.t.mode());
        self.sk.stmt(prog, s);
        if !self.live() || self.sk.stop.is_some() {
            return;
        }
        if self.sk.run.is_none() {
            // Not a run block: with `STRICT_DECLINED`, a declined line before it must have
            // been one (the writing scan judges that case).
            self.ok &= !(T::STRICT_DECLINED && pending);
            return;
        }
        let at = self.spill.len();
        if !was_run {
            self.fast.start(before);
            self.starts.push(at);
        }
        if let Err(mode) = self.fast.block(s, &mut self.spill.buf) {
            // Translated alone after the scan (with what the skeleton's translation gives),
            // and put in here.
            if self.deferred.len() >= T::MAX_DEFERRED {
                self.ok = false;
                return;
            }
            let run = self.starts.len().saturating_sub(1);
            self.deferred.push(Deferred { run, at, stmt: s.clone(), mode });
        }
        self.spill.flush_some();
    }
}

/// The writing scan's sink.
pub(crate) struct Writer<'a, T: SegTarget> {
    pub(crate) t: &'a T,
    pub(crate) class: T::Class,
    /// The N values kept out of runs (the skeleton scan's).
    pub(crate) keep: Keep,
    pub(crate) fast: T::Fast,
    /// The mode at each run's start (the skeleton scan's).
    pub(crate) modes: Vec<T::Mode>,
    pub(crate) alone: T::Alone,
    /// The last plain line was a run block the fast writer declined: its statement comes.
    pub(crate) pending: bool,
    /// The translated skeleton, written with the runs in their places.
    pub(crate) out: Splice<'a>,
    /// Kept diagnostics of run blocks translated alone.
    pub(crate) diags: Vec<Diagnostic>,
}

impl<T: SegTarget> Writer<'_, T> {
    /// A run block comes: at a run's first, the mode it starts in.
    fn enter(&mut self) {
        if let Some(k) = self.out.enter() {
            match self.modes.get(k) {
                Some(&m) => self.fast.start(m),
                None => self.out.bad = true,
            }
        }
    }
}

impl<T: SegTarget> WordsSink for Writer<'_, T> {
    fn active(&self) -> bool {
        self.out.live()
    }

    #[inline]
    fn plain(&mut self, prog: usize, meta: &BlockMeta, words: &[PlainWord], line: &RawBlock<'_>) -> bool {
        if !self.out.live() {
            return true;
        }
        if prog != 0 {
            // A subprogram's line (the skeleton took them whole): nothing to write.
            self.out.leave();
            return true;
        }
        if !self.class.plain_run(&self.keep, meta, words) {
            return false;
        }
        self.enter();
        if self.fast.plain(meta, words, line, &mut self.out.buf) {
            self.out.flush_some();
            return true;
        }
        // Nothing was written; the block comes again as a statement (still a run block).
        self.pending = true;
        false
    }

    fn stmt(&mut self, prog: usize, s: &Stmt) {
        if !self.out.live() {
            return;
        }
        let pending = std::mem::take(&mut self.pending);
        if prog != 0 || !self.class.stmt_run(&self.keep, s) {
            // With `STRICT_DECLINED`, the skeleton scan took a declined line as a run block.
            self.out.bad |= T::STRICT_DECLINED && pending;
            self.out.leave();
            return;
        }
        self.enter();
        if let Err(m) = self.fast.block(s, &mut self.out.buf) {
            match self.t.alone(&self.alone, s, m) {
                Some((text, diags)) => {
                    self.diags.extend(diags);
                    self.out.buf.extend_from_slice(text.as_bytes());
                }
                None => self.out.bad = true,
            }
        }
        self.out.flush_some();
    }
}
