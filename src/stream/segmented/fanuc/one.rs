//! The one scan of a segmented translation: the skeleton scan (`skel`) that also translates
//! each run as it reaches it, into a spill (see `segmented`). A run block starts in the
//! units the text before it leaves, which the skeleton scan follows in textual order: the
//! units the writing scan (`write`) would set at the run's start (`Skel::run_units`).

use super::skel::Skel;
use crate::ir::{BlockMeta, Stmt};
use crate::lower::to_fanuc::fast_write as fast;
use crate::read::RawBlock;
use crate::stream::segmented::nset::kept;
use crate::stream::segmented::spill::Spill;
use crate::stream::{PlainWord, WordsSink};

/// The one scan's sink.
pub(super) struct One {
    pub(super) sk: Skel,
    pub(super) fast: fast::Fast,
    pub(super) spill: Spill,
    /// Where each run's translation starts in the spill.
    pub(super) starts: Vec<u64>,
    /// Every run block so far went through the fast path: the spill holds the runs'
    /// translations. Once `false` (a block translated alone needs the program's head, known
    /// after the scan) the scan only builds the skeleton and the writing scan fills the runs.
    pub(super) ok: bool,
}

impl One {
    fn live(&self) -> bool {
        self.ok && self.spill.io.is_none()
    }
}

impl WordsSink for One {
    fn active(&self) -> bool {
        self.sk.active()
    }

    fn plain(&mut self, prog: usize, meta: &BlockMeta, words: &[PlainWord], line: &RawBlock<'_>) -> bool {
        let sk = &self.sk;
        let comp =
            words.iter().any(|w| crate::lower::comp_flow::stream_relevant_word(w.letter, Some(w.value), false, true));
        if !self.live() || sk.stop.is_some() || prog != 0 || kept(&sk.keep, meta) || sk.after_msg || comp {
            return self.sk.plain(prog, meta, words, line);
        }
        // A run block (as `Skel::plain` takes it): translated first, so that a block the fast
        // path declines comes as a statement with the skeleton not yet changed.
        let starting = sk.run.is_none();
        let units = if starting { sk.modes.units() } else { self.fast.units };
        self.fast.units = units;
        let at = self.spill.len();
        // The usual CAM line in one loop (it changes no mode), as the straight stream does.
        if !self.fast.plain_words(meta, words, &mut self.spill.buf)
            && self.fast.words(meta, words, line, &mut self.spill.buf).is_err()
        {
            // Nothing was written.
            self.fast.units = units;
            return false;
        }
        if starting {
            self.starts.push(at);
        }
        self.spill.flush_some();
        // What `Skel::plain` does with a run block.
        self.sk.plain_run_block(meta, words);
        true
    }

    fn stmt(&mut self, prog: usize, s: &Stmt) {
        let (was_run, units) = (self.sk.run.is_some(), self.sk.modes.units());
        let runs = self.sk.run_units.len();
        self.sk.stmt(prog, s);
        if !self.live() || self.sk.stop.is_some() || self.sk.run.is_none() {
            // Not a run block (or nothing more to translate).
            return;
        }
        let at = self.spill.len();
        if !was_run || self.sk.run_units.len() != runs {
            self.fast.units = units;
            self.starts.push(at);
        }
        if self.fast.block(s, &mut self.spill.buf).is_err() {
            self.ok = false;
            return;
        }
        self.spill.flush_some();
    }
}
