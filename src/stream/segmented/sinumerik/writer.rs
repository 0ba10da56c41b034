//! The writing scan of a segmented FANUC → Sinumerik translation: the translated
//! skeleton's text with each placeholder line replaced by its run, each run block written
//! by the straight stream's fast path or, when it declines, by the passes on the block
//! alone (with the skeleton's plan and the arc mode running into it).

use super::{follow_items, follow_words, Class};
use crate::diag::Diagnostic;
use crate::dialect::digits::Src;
use crate::ir::{BlockMeta, Stmt, StmtKind};
use crate::lower::to_sinumerik::fast_write as fast;
use crate::lower::to_sinumerik::Options;
use crate::read::{LineEnding, RawBlock};
use crate::stream::segmented::splice::Splice;
use crate::stream::target::sinumerik::{Planned, KEPT_WARNING};
use crate::stream::{PlainWord, WordsSink};

/// A diagnostic the straight stream keeps (and reports): the dropped G43/G44/G49 warning.
pub(super) fn kept_warning(d: &Diagnostic) -> bool {
    !d.is_error() && d.code == KEPT_WARNING
}

/// A run block the fast path declines, lowered alone with the skeleton's plan and the arc
/// mode running into it, with `eol` line ends: its text and diagnostics, when those are all
/// kept warnings.
pub(super) fn alone(
    plan: &Planned,
    opts: &Options,
    s: &Stmt,
    arc: bool,
    eol: LineEnding,
) -> Option<(String, Vec<Diagnostic>)> {
    // Metric: a program with G20 is not segmented.
    match plan.lower(opts, vec![s.clone()], arc, Some(false)) {
        (diags, Ok(text)) if diags.iter().all(kept_warning) => match eol {
            LineEnding::Lf => Some((text, diags)),
            other => Some((text.replace('\n', other.as_str()), diags)),
        },
        _ => None,
    }
}

/// The writing scan's sink: the skeleton's text with each placeholder line replaced by its
/// run, translated as it is read.
pub(super) struct Writer<'a> {
    pub(super) class: Class,
    pub(super) opts: &'a Options,
    pub(super) alone: Planned,
    pub(super) eol: LineEnding,
    /// The arc mode at each run's start.
    pub(super) arcs: Vec<bool>,
    /// The last plain line was a run block the fast path declined: its statement comes.
    pub(super) pending: bool,
    pub(super) arc: bool,
    /// The translated skeleton, written with the runs in their places.
    pub(super) out: Splice<'a>,
    /// Kept warnings of run blocks.
    pub(super) diags: Vec<Diagnostic>,
}

impl Writer<'_> {
    /// A run block comes: at a run's first, the arc mode it starts in.
    fn enter(&mut self) {
        if let Some(k) = self.out.enter() {
            match self.arcs.get(k) {
                Some(&arc) => self.arc = arc,
                None => self.out.bad = true,
            }
        }
    }

    /// A run block the fast path declined, through the passes alone.
    fn alone(&mut self, s: &Stmt, arc: bool) {
        match alone(&self.alone, self.opts, s, arc, self.eol) {
            Some((text, diags)) => {
                self.diags.extend(diags);
                self.out.buf.extend_from_slice(text.as_bytes());
            }
            None => self.out.bad = true,
        }
    }
}

impl WordsSink for Writer<'_> {
    fn active(&self) -> bool {
        self.out.live()
    }

    fn plain(&mut self, prog: usize, meta: &BlockMeta, words: &[PlainWord], line: &RawBlock<'_>) -> bool {
        if !self.out.live() {
            return true;
        }
        if prog != 0 {
            // A subprogram's line (the skeleton took them whole, `subs`): nothing to write.
            self.out.leave();
            return true;
        }
        if !self.class.plain_run(meta, words) {
            return false;
        }
        self.enter();
        let eol = self.eol.as_str().as_bytes();
        if fast::plain_words(meta, words, &mut self.arc, eol, &mut self.out.buf) {
            self.out.flush_some();
            return true;
        }
        let after = follow_words(self.arc, words);
        let at = self.out.buf.len();
        let lit = |w: &PlainWord| Some(Src { line, span: w.span, canon: w.canon });
        if fast::block(meta, words, lit, after, Some(false), self.opts, eol, &mut self.out.buf).is_ok() {
            self.arc = after;
            self.out.flush_some();
            return true;
        }
        // Nothing is kept; the block comes again as a statement (still a run block).
        self.out.buf.truncate(at);
        self.pending = true;
        false
    }

    fn stmt(&mut self, prog: usize, s: &Stmt) {
        if !self.out.live() {
            return;
        }
        if prog != 0 {
            self.out.bad |= std::mem::take(&mut self.pending);
            self.out.leave();
            return;
        }
        let pending = std::mem::take(&mut self.pending);
        let StmtKind::Block(b) = &s.kind else {
            self.out.bad |= pending;
            self.out.leave();
            self.class.observe(s);
            return;
        };
        if !self.class.stmt_run(s) {
            // The skeleton scan took the line as a run block.
            self.out.bad |= pending;
            self.out.leave();
            self.class.observe(s);
            return;
        }
        self.enter();
        let before = self.arc;
        let after = follow_items(before, &b.items);
        let at = self.out.buf.len();
        let eol = self.eol.as_str().as_bytes();
        if fast::block(&b.meta, &b.items, |_| None, after, Some(false), self.opts, eol, &mut self.out.buf).is_err() {
            self.out.buf.truncate(at);
            self.alone(s, before);
        }
        self.arc = after;
        self.out.flush_some();
    }
}
