//! The writing scan of a segmented translation, for every target: the translated
//! skeleton's text with each placeholder line replaced by its run, each run block written
//! by the target's fast writer or, when it declines, translated alone (see `segmented`).

use super::driver::{RunWriter, SegTarget};
use super::splice::Splice;
use crate::diag::Diagnostic;
use crate::ir::{BlockMeta, Stmt};
use crate::read::RawBlock;
use crate::stream::{PlainWord, WordsSink};

/// The writing scan's sink.
pub(crate) struct Writer<'a, T: SegTarget> {
    class: T::Class,
    fast: T::Fast,
    /// The mode at each run's start (the skeleton scan's).
    modes: Vec<T::Mode>,
    alone: T::Alone,
    /// The last plain line was a run block the fast writer declined: its statement comes.
    pending: bool,
    /// The translated skeleton, written with the runs in their places.
    pub(crate) out: Splice<'a>,
    /// Kept diagnostics of run blocks translated alone.
    diags: Vec<Diagnostic>,
}

impl<'a, T: SegTarget> Writer<'a, T> {
    pub(crate) fn new(
        class: T::Class,
        fast: T::Fast,
        modes: Vec<T::Mode>,
        alone: T::Alone,
        out: Splice<'a>,
    ) -> Writer<'a, T> {
        Writer { class, fast, modes, alone, pending: false, out, diags: Vec::new() }
    }

    /// The output and the kept diagnostics of run blocks.
    pub(crate) fn finish(self) -> (Splice<'a>, Vec<Diagnostic>) {
        (self.out, self.diags)
    }

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
        if !T::write_plain_run(&self.class, meta, words) {
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
        if prog != 0 || !T::write_stmt_run(&mut self.class, s) {
            // With `STRICT_DECLINED`, the skeleton scan took a declined line as a run block.
            self.out.bad |= T::STRICT_DECLINED && pending;
            self.out.leave();
            return;
        }
        self.enter();
        if let Err(m) = self.fast.block(s, &mut self.out.buf) {
            match T::alone(&self.alone, s, m) {
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
