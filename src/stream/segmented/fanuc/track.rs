//! The FANUC target's part of a segmented skeleton scan (Sinumerik source): the words
//! pass's modes followed in textual order, the placeholder carrying them and the run's
//! highest N, the N numbers of the skeleton's own blocks, and the lone M0 after a MSG kept
//! in the skeleton (see `segmented::fanuc`).

use crate::ir::{Addr, BlockMeta, CallKind, CallTarget, Comment, ExprKind, ItemKind, SeqNo, Stmt, StmtKind, WordValue};
use crate::lower::to_fanuc::words::units::Units;
use crate::lower::to_fanuc::RUN_STOPS_SEARCH as STOPS;
use crate::span::Span;
use crate::stream::segmented::driver::{jump_or_call, SkelPart, Why};
use crate::stream::segmented::nset::{kept, Keep, NSet, MAX_TRACKED_N};
use crate::stream::target::fanuc::{g_item, run_block};
use crate::stream::PlainWord;

/// The labels pass's highest N number.
pub(super) const MAX_N: u32 = 99999;

/// The two modes of the words pass that reach from block to block outside a structure, in
/// textual order (`lower::to_fanuc::words::words_pass`): the length and feed units (G70, G71, G700,
/// G710: the fast path's `units`) and G90/G91 (read by AC()/IC() words).
#[derive(Clone, Copy, Default)]
pub(crate) struct Modes {
    units: Units,
    /// G91 in force.
    inc: bool,
}

/// Which of the two modes a block's words touched.
#[derive(Clone, Copy, Default)]
pub(super) struct Touched {
    inch: bool,
    abs: bool,
}

impl Modes {
    /// A constant G word, as the words pass takes it.
    fn g(&mut self, v: f64, t: &mut Touched) {
        if self.units.g(v) {
            t.inch = true;
            return;
        }
        if v == 90.0 || v == 91.0 {
            self.inc = v == 91.0;
            t.abs = true;
        }
    }

    /// The G words of a block's items.
    fn items(&mut self, items: &[crate::ir::Item], t: &mut Touched) {
        for it in items {
            if let ItemKind::Word(w) = &it.kind {
                if let (Addr::Letter(b'G'), WordValue::Expr(e)) = (&w.addr, &w.value) {
                    if let ExprKind::Num(x) = &e.kind {
                        self.g(x.value, t);
                    }
                }
            }
        }
    }
}

/// The FANUC target's part of the skeleton scan.
#[derive(Default)]
pub(crate) struct Track {
    /// The highest valid N value of the run being collected (its placeholder's N).
    hi: Option<u32>,
    pub(super) max_n: u32,
    /// N values of the skeleton's own blocks (up to [`MAX_TRACKED_N`]).
    pub(super) skel_ns: NSet,
    /// The modes in textual order up to here.
    pub(super) modes: Modes,
    /// Which modes the run being collected changes.
    touched: Touched,
    /// The last statement was a block holding a MSG.
    after_msg: bool,
    /// Where the lone M0 blocks right after such a block start: kept in the skeleton (the
    /// words pass may pair the two).
    pub(super) forced: Vec<u32>,
    /// Per run, what a dead start value's search (`lower::to_fanuc::blocks`) does in it
    /// (`Ctx::stand_in_runs`): its block count (up to the search's window) when every block
    /// lets the search go on (no `/`, no program end), else [`STOPS`].
    pub(super) search: Vec<u8>,
}

impl Track {
    /// The run being collected has a block that stops a dead start value's search.
    fn stops(&mut self) {
        if let Some(c) = self.search.last_mut() {
            *c = STOPS;
        }
    }
}

impl SkelPart for Track {
    type Mode = Units;

    /// A plain line is a run block unless a jump names its N or it may pair with a MSG.
    #[inline]
    fn plain_run(&self, keep: &Keep, meta: &BlockMeta, _: &[PlainWord]) -> bool {
        !kept(keep, meta) && !self.after_msg
    }

    /// A statement is a run block when `run_block` and no jump names its N, but for a lone
    /// M0 right after a block with a MSG.
    fn stmt_run(&mut self, keep: &Keep, s: &Stmt) -> bool {
        let after_msg = std::mem::replace(&mut self.after_msg, false);
        if let StmtKind::Block(b) = &s.kind {
            if after_msg && crate::lower::to_fanuc::words::is_lone_m0(b) {
                self.forced.push(b.meta.span.lo);
            } else if run_block(s) && !kept(keep, &b.meta) {
                return true;
            }
            // Any block with a MSG: its last piece (`lower::to_fanuc::blocks`) may be the MSG alone.
            self.after_msg = b.items.iter().any(|i| matches!(i.kind, ItemKind::Message { .. }));
        }
        false
    }

    #[inline]
    fn mode(&self) -> Units {
        self.modes.units
    }

    #[inline]
    fn run_block(&mut self, meta: &BlockMeta, starting: bool) {
        let n = meta.number.as_ref().map(|n| n.value);
        if let Some(n) = n {
            self.max_n = self.max_n.max(if n <= MAX_N { n } else { 0 });
        }
        let valid = n.filter(|n| *n <= MAX_N);
        self.hi = if starting { valid } else { self.hi.max(valid) };
        if starting {
            self.search.push(0);
        }
        if let Some(c) = self.search.last_mut() {
            // A straight block is one statement of the lowered program (its words), or,
            // with a program end, two (the end a statement of its own, which stops it).
            let cap = crate::lower::to_fanuc::blocks::DEAD_STORE_WINDOW as u8;
            *c = if meta.skip.is_some() || *c == STOPS { STOPS } else { (*c + 1).min(cap) };
        }
    }

    #[inline]
    fn follow_plain(&mut self, words: &[PlainWord]) {
        let mut t = self.touched;
        for w in words {
            if w.letter == b'G' {
                self.modes.g(w.value, &mut t);
            } else if w.letter == b'M' && (w.value == 2.0 || w.value == 30.0) {
                self.stops();
            }
        }
        self.touched = t;
    }

    fn follow_stmt(&mut self, items: &[crate::ir::Item]) {
        if items.iter().any(|it| matches!(it.kind, ItemKind::End { .. })) {
            self.stops();
        }
        let mut t = self.touched;
        self.modes.items(items, &mut t);
        self.touched = t;
    }

    /// A run's placeholder: it carries the modes the run leaves (as unit words,
    /// `Units::words`, and G90/G91 words, where it changes them) for the words pass to
    /// follow into the skeleton after it, and the run's highest N; its line is replaced whole.
    fn placeholder(&mut self, mark: String, span: Span) -> Stmt {
        let t = std::mem::take(&mut self.touched);
        let mut items = Vec::new();
        if t.inch {
            items.extend(self.modes.units.words().iter().map(|&v| g_item(v, span)));
        }
        if t.abs {
            items.push(g_item(if self.modes.inc { 91.0 } else { 90.0 }, span));
        }
        let meta = BlockMeta {
            span,
            number: self.hi.take().map(|value| SeqNo { value, span }),
            comments: vec![Comment { text: mark, span }],
            ..BlockMeta::default()
        };
        crate::lower::meta_stmt(meta, items)
    }

    /// The modes, the highest N and the N values of the statement's blocks.
    type Walk = (Modes, u32, Vec<u32>);

    fn walk(&self) -> Self::Walk {
        (self.modes, 0, Vec::new())
    }

    fn macro_block(
        (modes, max_n, own): &mut Self::Walk,
        b: &crate::ir::Block,
        calls_ok: bool,
        targets: &mut Vec<u32>,
    ) -> Why {
        if let Some(n) = b.meta.number.as_ref().map(|n| n.value) {
            *max_n = (*max_n).max(if n <= MAX_N { n } else { 0 });
            own.extend((n <= MAX_TRACKED_N).then_some(n));
        }
        modes.items(&b.items, &mut Touched::default());
        let mut why = None;
        for it in &b.items {
            if let Some(w) = jump_or_call(it, calls_ok, plain_call, targets) {
                why = why.or(w);
                continue;
            }
            match &it.kind {
                ItemKind::StopMessage { .. } => why = why.or(Some("a stop with a message")),
                ItemKind::Word(w)
                    if w.addr.is(b'G')
                        && matches!(&w.value, WordValue::Expr(e) if !matches!(e.kind, ExprKind::Num(_))) =>
                {
                    why = why.or(Some("a computed G word"))
                }
                _ => {}
            }
        }
        why
    }

    fn walked(&mut self, (modes, max_n, own): Self::Walk, _: &Stmt) {
        self.modes = modes;
        self.max_n = self.max_n.max(max_n);
        own.into_iter().for_each(|n| self.skel_ns.insert(n));
    }
}

/// Whether a call may stay in a skeleton translated with its callees: by a constant name,
/// not modal (the whole path loads exactly these callees, `called_names`).
pub(crate) fn plain_call(c: &crate::ir::Call) -> bool {
    matches!(c.kind, CallKind::Named | CallKind::LNumber) && matches!(c.target, CallTarget::Name(_))
}
