//! The skeleton scan of a segmented translation, for every target: the macro part kept as
//! IR, each run of straight blocks one placeholder, the N values of run blocks and of jump
//! targets collected, the target's modes followed in textual order (its `SegTarget::Track`).

use super::driver::SegTarget;
use super::nset::{NSet, MAX_TRACKED_N};
use crate::dialect::Dialect;
use crate::ir::{BlockMeta, Stmt, StmtKind};
use crate::read::RawBlock;
use crate::span::Span;
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
    pub(crate) keep: NSet,
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
    pub(crate) fn new(t: T::Track, keep: NSet, calls: bool) -> Skel<T> {
        Skel {
            t,
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
            self.modes.push(T::mode(&self.t));
        }
        T::run_block(&mut self.t, meta, starting);
    }

    /// Ends the run being collected with its placeholder.
    pub(crate) fn close_run(&mut self) {
        if let Some(span) = self.run.take() {
            let p = T::placeholder(&mut self.t, self.runs, span);
            self.body.push(p);
            self.runs += 1;
        }
    }

    /// Checks a statement of the macro part, follows its modes and collects its jump targets.
    fn macro_stmt(&mut self, s: &Stmt) {
        let mut targets = Vec::new();
        if let Some(w) = T::macro_stmt(&mut self.t, s, self.calls, &mut targets) {
            return self.decline(w);
        }
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
        if !T::plain_run(&self.t, &self.keep, meta, words) {
            // Asked for as a statement.
            return false;
        }
        self.run_block(meta);
        T::follow_plain(&mut self.t, words);
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
        if T::stmt_run(&mut self.t, &self.keep, s) {
            if let StmtKind::Block(b) = &s.kind {
                self.run_block(&b.meta);
                T::follow_stmt(&mut self.t, &b.items);
            }
            return;
        }
        self.close_run();
        self.macro_stmt(s);
    }
}
