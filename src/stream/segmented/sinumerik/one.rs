//! The one scan of a segmented FANUC → Sinumerik translation: the skeleton scan that also
//! translates each run as it reaches it, into a spill (see `segmented`). A run block's
//! translation depends on the arc mode only, which the skeleton scan follows in textual
//! order: at a run's start it is the mode the writing scan (`writer`) would start it in.

use super::{follow_words, Skel};
use crate::dialect::digits::Src;
use crate::ir::{BlockMeta, Stmt, StmtKind};
use crate::lower::to_sinumerik::fast_write as fast;
use crate::lower::to_sinumerik::Options;
use crate::read::{LineEnding, RawBlock};
use crate::stream::segmented::spill::Spill;
use crate::stream::{PlainWord, WordsSink};

/// The one scan's sink.
pub(super) struct One<'a> {
    pub(super) sk: Skel,
    pub(super) opts: &'a Options,
    pub(super) eol: LineEnding,
    pub(super) spill: Spill,
    /// Where each run's translation starts in the spill.
    pub(super) starts: Vec<u64>,
    /// The last plain line was a run block the fast path declined: its statement comes.
    pub(super) pending: bool,
    /// The run blocks the fast path declined, in order: each is translated alone with the
    /// skeleton's plan (known after the scan) and put in at its place in the spill.
    pub(super) deferred: Vec<Deferred>,
    /// The spill and `deferred` hold the runs' translations. Once `false` (too many blocks
    /// to translate alone, or the statement of a declined line is no run block) the scan
    /// only builds the skeleton and the writing scan fills the runs (and judges the case).
    pub(super) ok: bool,
}

/// Most run blocks kept for translating alone after the scan (their statements are held).
const MAX_DEFERRED: usize = 4096;

/// A run block to translate alone after the scan.
pub(super) struct Deferred {
    /// Its run.
    pub(super) run: usize,
    /// Where its translation goes in the spill (between the blocks around it).
    pub(super) at: u64,
    pub(super) stmt: Stmt,
    /// The arc mode running into it.
    pub(super) arc: bool,
}

impl One<'_> {
    fn live(&self) -> bool {
        self.ok && self.spill.io.is_none()
    }
}

impl WordsSink for One<'_> {
    fn active(&self) -> bool {
        self.sk.active()
    }

    fn plain(&mut self, prog: usize, meta: &BlockMeta, words: &[PlainWord], line: &RawBlock<'_>) -> bool {
        let sk = &self.sk;
        let comp =
            words.iter().any(|w| crate::lower::comp_flow::stream_relevant_word(w.letter, Some(w.value), true, true));
        if !self.live() || sk.stop.is_some() || prog != 0 || comp || !sk.class.plain_run(meta, words) {
            return self.sk.plain(prog, meta, words, line);
        }
        // A run block (as `Skel::plain` takes it): translated first, so that a block the fast
        // path declines comes as a statement with the skeleton not yet changed. The arc mode
        // the skeleton follows through the runs is the one each run block starts in
        // (`fast::plain_words` follows it as `follow_words` does).
        let mut arc = sk.arc;
        let at = self.spill.len();
        let eol = self.eol.as_str().as_bytes();
        let buf = &mut self.spill.buf;
        if !fast::plain_words(meta, words, &mut arc, eol, buf) {
            let after = follow_words(arc, words);
            let mark = buf.len();
            let lit = |w: &PlainWord| Some(Src { line, span: w.span, canon: w.canon });
            if fast::block(meta, words, lit, after, Some(false), self.opts, eol, buf).is_err() {
                // Nothing is kept; the block comes again as a statement.
                buf.truncate(mark);
                self.pending = true;
                return false;
            }
            arc = after;
        }
        if self.sk.run.is_none() {
            self.starts.push(at);
        }
        // What `Skel::plain` does with a run block.
        self.sk.run_block(meta);
        self.sk.arc = arc;
        self.spill.flush_some();
        true
    }

    fn stmt(&mut self, prog: usize, s: &Stmt) {
        let pending = std::mem::take(&mut self.pending);
        let (was_run, before) = (self.sk.run.is_some(), self.sk.arc);
        self.sk.stmt(prog, s);
        if !self.live() || self.sk.stop.is_some() {
            return;
        }
        let run = match &s.kind {
            StmtKind::Block(b) if self.sk.run.is_some() => Some(b),
            _ => None,
        };
        let Some(b) = run else {
            // Not a run block: a declined line before it must have been one (the writing
            // scan judges that case).
            self.ok &= !pending;
            return;
        };
        let at = self.spill.len();
        if !was_run {
            self.starts.push(at);
        }
        // The skeleton has followed the block's arc mode (`follow_items`).
        let after = self.sk.arc;
        let eol = self.eol.as_str().as_bytes();
        if fast::block(&b.meta, &b.items, |_| None, after, Some(false), self.opts, eol, &mut self.spill.buf).is_err() {
            // Translated alone after the scan (with the skeleton's plan), and put in here.
            self.spill.buf.truncate((at - self.spill.flushed()) as usize);
            if self.deferred.len() >= MAX_DEFERRED {
                self.ok = false;
                return;
            }
            let run = self.starts.len().saturating_sub(1);
            self.deferred.push(Deferred { run, at, stmt: s.clone(), arc: before });
        }
        self.spill.flush_some();
    }
}
