//! The writing scan of a segmented FANUC → Sinumerik translation: the translated
//! skeleton's text with each placeholder line replaced by its run, each run block written
//! by the straight stream's fast path or, when it declines, by the passes on the block
//! alone (with the skeleton's plan and the arc mode running into it).

use super::super::super::translate::digits::Src;
use super::super::super::{PlainWord, WordsSink, WRITE_BYTES};
use super::super::{fast, KEPT_WARNING, STAND_IN};
use super::{follow_items, follow_words, Class};
use crate::diag::Diagnostic;
use crate::dialect::sinumerik::emit::{emit_program, Frame};
use crate::ir::{Addr, Block, BlockMeta, Expr, Item, ItemKind, Program, Stmt, StmtKind, Word, WordValue};
use crate::passes::to_sinumerik::{self as passes, Ctx, Options, ProgPlan};
use crate::read::{LineEnding, RawBlock};
use crate::span::Span;
use std::collections::BTreeMap;
use std::io::Write;

/// A diagnostic the straight stream keeps (and reports): the dropped G43/G44/G49 warning.
pub(super) fn kept_warning(d: &Diagnostic) -> bool {
    !d.is_error() && d.code == KEPT_WARNING
}

/// What the passes need to lower one block of a run alone: the skeleton's plan.
pub(super) struct Alone {
    pub(super) plan: ProgPlan,
    pub(super) commons: BTreeMap<u32, u32>,
    pub(super) common_flags: BTreeMap<u32, u32>,
}

impl Alone {
    /// The Sinumerik text (LF line ends) of straight block `s` translated alone, with the
    /// arc mode `arc` running into it (a stand-in G2 in front, taken out after lowering),
    /// and its diagnostics; `None` when the passes change the stand-in or the writer fails.
    fn block(&self, opts: &Options, s: &Stmt, arc: bool) -> Option<(String, Vec<Diagnostic>)> {
        let mut body = Vec::with_capacity(2);
        if arc {
            let word = Word {
                addr: Addr::Letter(b'G'),
                value: WordValue::Expr(Expr::num(2.0, false, STAND_IN)),
                span: STAND_IN,
            };
            let meta = BlockMeta { span: STAND_IN, ..BlockMeta::default() };
            let items = vec![Item { kind: ItemKind::Word(word), span: STAND_IN }];
            body.push(Stmt { kind: StmtKind::Block(Block { meta, items }), span: STAND_IN });
        }
        body.push(s.clone());
        let mut ctx = Ctx {
            opts,
            progs: vec![self.plan.clone()],
            commons: self.commons.clone(),
            common_flags: self.common_flags.clone(),
            diags: Vec::new(),
            cur: 0,
            guard_ok: false,
            modal: Default::default(),
        };
        let mut body = passes::lower_body(&mut ctx, body);
        if arc {
            let before = body.len();
            body.retain(|s| s.span != STAND_IN);
            if before != body.len() + 1 {
                return None;
            }
        }
        let p = Program { name: None, head: None, params: vec![], save: false, body, span: Span::default() };
        let e = emit_program(&p, &Frame { header: &[], defs: &[], proc_line: false });
        e.problems.is_empty().then_some((e.text, ctx.diags))
    }
}

impl Alone {
    /// [`Alone::block`] with `eol` line ends, when its diagnostics are all kept warnings.
    pub(super) fn written(
        &self,
        opts: &Options,
        s: &Stmt,
        arc: bool,
        eol: LineEnding,
    ) -> Option<(String, Vec<Diagnostic>)> {
        match self.block(opts, s, arc) {
            Some((text, diags)) if diags.iter().all(kept_warning) => match eol {
                LineEnding::Lf => Some((text, diags)),
                other => Some((text.replace('\n', other.as_str()), diags)),
            },
            _ => None,
        }
    }
}

/// The writing scan's sink: the skeleton's text with each placeholder line replaced by its
/// run, translated as it is read.
pub(super) struct Writer<'a> {
    pub(super) class: Class,
    pub(super) opts: &'a Options,
    pub(super) alone: Alone,
    pub(super) eol: LineEnding,
    /// The translated skeleton.
    pub(super) text: &'a str,
    pub(super) places: Vec<(usize, usize)>,
    pub(super) arcs: Vec<bool>,
    /// How far `text` is written.
    pub(super) pos: usize,
    /// The next run.
    pub(super) next: usize,
    pub(super) in_run: bool,
    /// The last plain line was a run block the fast path declined: its statement comes.
    pub(super) pending: bool,
    pub(super) arc: bool,
    pub(super) buf: Vec<u8>,
    pub(super) out: &'a mut dyn Write,
    pub(super) io: Option<std::io::Error>,
    /// The scan does not match the skeleton's (the file changed), or a block alone has
    /// diagnostics: the output is discarded.
    pub(super) bad: bool,
    /// Kept warnings of run blocks.
    pub(super) diags: Vec<Diagnostic>,
}

impl Writer<'_> {
    pub(super) fn copy_to(&mut self, to: usize) {
        if let Some(s) = self.text.get(self.pos..to) {
            self.buf.extend_from_slice(s.as_bytes());
        }
        self.pos = to;
    }

    /// A run block comes: at a run's first, the skeleton up to its placeholder is written.
    fn enter(&mut self) {
        if self.in_run {
            return;
        }
        self.in_run = true;
        match (self.places.get(self.next), self.arcs.get(self.next)) {
            (Some(&(lo, hi)), Some(&arc)) => {
                self.copy_to(lo);
                self.pos = hi;
                self.arc = arc;
                self.next += 1;
            }
            _ => self.bad = true,
        }
    }

    /// A run block the fast path declined, through the passes alone.
    fn alone(&mut self, s: &Stmt, arc: bool) {
        match self.alone.written(self.opts, s, arc, self.eol) {
            Some((text, diags)) => {
                self.diags.extend(diags);
                self.buf.extend_from_slice(text.as_bytes());
            }
            None => self.bad = true,
        }
    }

    fn flush_some(&mut self) {
        if self.buf.len() >= WRITE_BYTES {
            self.write();
        }
    }

    pub(super) fn write(&mut self) {
        super::super::super::spill(self.out, &mut self.buf, &mut self.io);
    }

    fn live(&self) -> bool {
        !self.bad && self.io.is_none()
    }
}

impl WordsSink for Writer<'_> {
    fn active(&self) -> bool {
        self.live()
    }

    fn plain(&mut self, prog: usize, meta: &BlockMeta, words: &[PlainWord], line: &RawBlock<'_>) -> bool {
        if !self.live() {
            return true;
        }
        if prog != 0 {
            // A subprogram's line (the skeleton took them whole, `subs`): nothing to write.
            self.in_run = false;
            return true;
        }
        if !self.class.plain_run(meta, words) {
            return false;
        }
        self.enter();
        let eol = self.eol.as_str().as_bytes();
        if fast::plain_words(meta, words, &mut self.arc, eol, &mut self.buf) {
            self.flush_some();
            return true;
        }
        let after = follow_words(self.arc, words);
        let at = self.buf.len();
        let lit = |w: &PlainWord| Some(Src { line, span: w.span, canon: w.canon });
        if fast::block(meta, words, lit, after, self.opts, eol, &mut self.buf).is_ok() {
            self.arc = after;
            self.flush_some();
            return true;
        }
        // Nothing is kept; the block comes again as a statement (still a run block).
        self.buf.truncate(at);
        self.pending = true;
        false
    }

    fn stmt(&mut self, prog: usize, s: &Stmt) {
        if !self.live() {
            return;
        }
        if prog != 0 {
            self.bad |= std::mem::take(&mut self.pending);
            self.in_run = false;
            return;
        }
        let pending = std::mem::take(&mut self.pending);
        let StmtKind::Block(b) = &s.kind else {
            self.bad |= pending;
            self.in_run = false;
            self.class.observe(s);
            return;
        };
        if !self.class.stmt_run(s) {
            // The skeleton scan took the line as a run block.
            self.bad |= pending;
            self.in_run = false;
            self.class.observe(s);
            return;
        }
        self.enter();
        let before = self.arc;
        let after = follow_items(before, &b.items);
        let at = self.buf.len();
        let eol = self.eol.as_str().as_bytes();
        if fast::block(&b.meta, &b.items, |_| None, after, self.opts, eol, &mut self.buf).is_err() {
            self.buf.truncate(at);
            self.alone(s, before);
        }
        self.arc = after;
        self.flush_some();
    }
}
