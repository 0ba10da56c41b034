//! The writing scan of a segmented translation: the translated skeleton's text with each
//! placeholder line replaced by its run, translated as it is read (see `segmented`).

use super::skel::MARK;
use crate::dialect::fanuc::emit::{self, EmitOptions};
use crate::ir::{BlockMeta, Stmt, StmtKind, Unit};
use crate::lower::to_fanuc::fast_write as fast;
use crate::lower::to_fanuc::words::units::Units;
use crate::read::RawBlock;
use crate::stream::segmented::nset::{kept, NSet};
use crate::stream::segmented::splice::{self, Splice};
use crate::stream::target::fanuc::{run_block, units_block};
use crate::stream::{PlainWord, WordsSink};
use crate::translate::{self, to_fanuc::TranslateOptions};

/// The byte ranges of the placeholder lines of a translated skeleton with `runs` runs, in
/// order: each `(NCTRANS SEGMENT k)` alone on its line, after the placeholder's N number
/// and G words if any (`Nn G20 G91 (NCTRANS SEGMENT k)`), with the carrier lines right
/// after it (`Nn (NCTRANS SEGMENT k)`, same `k`); `None` when the text holds the marker
/// anywhere else.
pub(super) fn placeholders(text: &str, runs: usize, eol: &str) -> Option<Vec<(usize, usize)>> {
    // The placeholder's N number and mode words (`Nn G20 G90 `), or nothing.
    let head = |head: &str| {
        head.is_empty()
            || head.strip_suffix(' ').is_some_and(|h| {
                h.split(' ').enumerate().all(|(k, t)| {
                    let d = t.strip_prefix('G').or_else(|| t.strip_prefix('N').filter(|_| k == 0));
                    d.is_some_and(|d| !d.is_empty() && d.bytes().all(|c| c.is_ascii_digit()))
                })
            })
    };
    splice::placeholders(text, (runs, eol), (&format!("({MARK}"), ")"), head, true)
}

/// The writing scan's sink: the skeleton's text with each placeholder line replaced by its
/// run, translated as it is read.
pub(super) struct Writer<'a> {
    pub(super) keep: &'a NSet,
    /// The units at each run's start (the skeleton scan's).
    pub(super) run_units: &'a [Units],
    /// Where the straight blocks kept in the skeleton for a MSG start.
    pub(super) forced: &'a [u32],
    pub(super) fast: fast::Fast,
    pub(super) opts: &'a TranslateOptions,
    pub(super) eo: EmitOptions,
    /// The program with an empty body (for a block translated alone).
    pub(super) lone: Unit,
    pub(super) header_len: usize,
    /// The translated skeleton, written with the runs in their places.
    pub(super) out: Splice<'a>,
}

impl Writer<'_> {
    /// A run block comes: at a run's first, the units it starts in.
    fn enter(&mut self) {
        if let Some(k) = self.out.enter() {
            self.fast.units = self.run_units.get(k).copied().unwrap_or_default();
        }
    }

    /// Whether a block starting at `lo` was kept in the skeleton for a MSG before it.
    fn forced(&self, lo: u32) -> bool {
        self.forced.binary_search(&lo).is_ok()
    }

    /// A straight block of a run the fast path declined: translated alone (as
    /// `stream::target::fanuc` does), after a block setting `units` when they are not the
    /// program's start units.
    fn alone(&mut self, s: &Stmt, units: Units) {
        let mut u = self.lone.clone();
        let set = units_block(units);
        let set_units = set.is_some();
        if let Some(p) = u.programs.first_mut() {
            p.body = set.into_iter().chain([s.clone()]).collect();
        }
        let t = translate::to_fanuc::to_fanuc(&u, &[], self.opts);
        if !t.diags.is_empty() || t.unsupported > 0 {
            self.out.bad = true;
            return;
        }
        let skip = self.header_len + usize::from(set_units);
        let body = t.unit.programs.first().map_or(&[][..], |p| &p.body[skip.min(p.body.len())..]);
        let e = emit::emit_body(body, &self.eo);
        if !e.diags.is_empty() {
            self.out.bad = true;
        }
        self.out.buf.extend_from_slice(e.text.as_bytes());
    }
}

impl WordsSink for Writer<'_> {
    fn active(&self) -> bool {
        self.out.live()
    }

    fn plain(&mut self, _: usize, meta: &BlockMeta, words: &[PlainWord], line: &RawBlock<'_>) -> bool {
        if !self.out.live() {
            return true;
        }
        if kept(self.keep, meta) || self.forced(meta.span.lo) {
            return false;
        }
        self.enter();
        // The usual CAM line in one loop (it changes no mode), as the straight stream does.
        if self.fast.plain_words(meta, words, &mut self.out.buf) {
            self.out.flush_some();
            return true;
        }
        let units = self.fast.units;
        if self.fast.words(meta, words, line, &mut self.out.buf).is_err() {
            // Nothing was written; the block comes again as a statement (still a run block).
            self.fast.units = units;
            return false;
        }
        self.out.flush_some();
        true
    }

    fn stmt(&mut self, _: usize, s: &Stmt) {
        if !self.out.live() {
            return;
        }
        let run = match &s.kind {
            StmtKind::Block(b) => run_block(s) && !kept(self.keep, &b.meta) && !self.forced(b.meta.span.lo),
            _ => false,
        };
        if !run {
            self.out.leave();
            return;
        }
        self.enter();
        let units = self.fast.units;
        if self.fast.block(s, &mut self.out.buf).is_err() {
            // The units are the ones after the block already (`Fast::block`).
            self.alone(s, units);
        }
        self.out.flush_some();
    }
}
