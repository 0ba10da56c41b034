//! The one scan of a segmented translation, for every target: the skeleton scan (`skel`)
//! that also translates each run as it reaches it, into a spill (see `segmented`). A run's
//! translation depends on the one mode the target's fast writer carries, which the skeleton
//! scan follows in textual order: at a run's start it is the mode the writing scan
//! (`write`) would start it in.

use super::driver::{Deferred, RunWriter, SegTarget};
use super::skel::{comp_word, Skel};
use super::spill::Spill;
use crate::ir::{BlockMeta, Stmt};
use crate::read::RawBlock;
use crate::stream::{PlainWord, WordsSink};

/// The one scan's sink.
pub(crate) struct One<T: SegTarget> {
    pub(crate) sk: Skel<T>,
    fast: T::Fast,
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
    pub(crate) fn new(sk: Skel<T>, fast: T::Fast) -> One<T> {
        One { sk, fast, spill: Spill::new(), starts: Vec::new(), pending: false, deferred: Vec::new(), ok: true }
    }

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
            || !T::plain_run(&sk.t, &sk.keep, meta, words)
            || words.iter().any(comp_word::<T>)
        {
            return self.sk.plain(prog, meta, words, line);
        }
        // A run block (as `Skel::plain` takes it): translated first, so that a block the fast
        // writer declines comes as a statement with the skeleton not yet changed.
        let starting = sk.run.is_none();
        if starting {
            self.fast.start(T::mode(&sk.t));
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
        let (was_run, before) = (self.sk.run.is_some(), T::mode(&self.sk.t));
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
