//! The skeleton scan of a segmented translation: the macro part kept as IR, each run of
//! straight blocks one placeholder, the modes followed in textual order (see `segmented`).

use crate::ir::{
    Addr, BlockMeta, CallKind, CallTarget, Comment, ExprKind, ItemKind, Program, SeqNo, Stmt, StmtKind, Target,
    WordValue,
};
use crate::lower::to_fanuc::words::units::Units;
use crate::read::RawBlock;
use crate::span::Span;
use crate::stream::segmented::nset::{kept, NSet, MAX_TRACKED_N};
use crate::stream::target::fanuc::run_block;
use crate::stream::{Fallback, Index, PlainWord, WordsSink};

pub(super) use crate::stream::segmented::MARK;
/// The labels pass's highest N number.
pub(super) const MAX_N: u32 = 99999;

/// The two modes of the words pass that reach from block to block outside a structure, in
/// textual order (`lower::to_fanuc::words::words_pass`): the length and feed units (G70, G71, G700,
/// G710: the fast path's `units`) and G90/G91 (read by AC()/IC() words).
#[derive(Clone, Copy)]
pub(super) struct Modes {
    units: Units,
    abs: bool,
}

/// Which of the two modes a block's words touched.
#[derive(Clone, Copy, Default)]
pub(super) struct Touched {
    inch: bool,
    abs: bool,
}

impl Modes {
    /// The length and feed units in force.
    pub(super) fn units(&self) -> Units {
        self.units
    }

    /// A constant G word, as the words pass takes it.
    fn g(&mut self, v: f64, t: &mut Touched) {
        if self.units.g(v) {
            t.inch = true;
            return;
        }
        if v == 90.0 || v == 91.0 {
            self.abs = v == 90.0;
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

/// A constant G word (for a placeholder).
pub(super) fn g_item(v: f64, span: Span) -> crate::ir::Item {
    let w = crate::ir::Word {
        addr: Addr::Letter(b'G'),
        value: WordValue::Expr(crate::ir::Expr::num(v, false, span)),
        span,
    };
    crate::ir::Item { kind: ItemKind::Word(w), span }
}

/// The first scan's sink: builds the skeleton.
pub(super) struct Skel {
    pub(super) keep: NSet,
    pub(super) body: Vec<Stmt>,
    /// The run being collected: its highest valid N value, the span of its first block.
    pub(super) run: Option<(Option<u32>, Span)>,
    pub(super) runs: usize,
    /// N values of run blocks.
    pub(super) run_ns: NSet,
    /// N values jumps name.
    pub(super) targets: NSet,
    pub(super) max_n: u32,
    /// N values of the skeleton's own blocks (up to [`MAX_TRACKED_N`]).
    pub(super) skel_ns: NSet,
    /// The modes in textual order up to here.
    pub(super) modes: Modes,
    /// Which modes the run being collected changes.
    pub(super) touched: Touched,
    /// The units at the start of each run.
    pub(super) run_units: Vec<Units>,
    /// The last statement was a block holding a MSG.
    pub(super) after_msg: bool,
    /// Where the lone M0 blocks right after such a block start: kept in the skeleton (the
    /// words pass may pair the two).
    pub(super) forced: Vec<u32>,
    pub(super) stop: Option<String>,
    /// Calls of other programs by a constant name (`L100`, `NAME`, `NAME(…)`) may stay in
    /// the skeleton: the caller translates it with the callees (`segmented::to_fanuc_with_subs`).
    pub(super) calls_ok: bool,
}

/// Whether a call may stay in a skeleton translated with its callees: by a constant name,
/// not modal (the whole path loads exactly these callees, `called_names`).
pub(crate) fn plain_call(c: &crate::ir::Call) -> bool {
    matches!(c.kind, CallKind::Named | CallKind::LNumber) && matches!(c.target, CallTarget::Name(_))
}

impl Skel {
    fn decline(&mut self, why: impl Into<String>) {
        self.stop.get_or_insert_with(|| why.into());
    }

    fn run_block(&mut self, meta: &BlockMeta) {
        let n = meta.number.as_ref().map(|n| n.value);
        if let Some(n) = n {
            if n > MAX_TRACKED_N {
                return self.decline("an N number above 16777216");
            }
            self.run_ns.insert(n);
            self.max_n = self.max_n.max(if n <= MAX_N { n } else { 0 });
        }
        let valid = n.filter(|n| *n <= MAX_N);
        match &mut self.run {
            Some((hi, _)) => *hi = (*hi).max(valid),
            None => {
                self.run = Some((valid, meta.span));
                self.run_units.push(self.modes.units);
            }
        }
    }

    /// A plain line that is a run block (`WordsSink::plain` has judged it so).
    #[inline]
    pub(super) fn plain_run_block(&mut self, meta: &BlockMeta, words: &[PlainWord]) {
        self.run_block(meta);
        let mut t = self.touched;
        for w in words {
            if w.letter == b'G' {
                self.modes.g(w.value, &mut t);
            }
        }
        self.touched = t;
    }

    /// Ends the run being collected: its placeholder block carries the modes the run leaves
    /// (as unit words, `Units::words`, and G90/G91 words, where it changes them) for the
    /// words pass to follow
    /// into the skeleton after it; the placeholder's line is replaced whole.
    fn close_run(&mut self) {
        if let Some((hi, span)) = self.run.take() {
            let t = std::mem::take(&mut self.touched);
            let mut items = Vec::new();
            if t.inch {
                items.extend(self.modes.units.words().iter().map(|&v| g_item(v, span)));
            }
            if t.abs {
                items.push(g_item(if self.modes.abs { 90.0 } else { 91.0 }, span));
            }
            let meta = BlockMeta {
                span,
                number: hi.map(|value| SeqNo { value, span }),
                comments: vec![Comment { text: format!("{MARK}{}", self.runs), span }],
                ..BlockMeta::default()
            };
            self.body.push(crate::lower::meta_stmt(meta, items));
            self.runs += 1;
        }
    }

    /// Checks a statement of the macro part, follows its modes and collects its jump targets.
    fn macro_stmt(&mut self, s: &Stmt) {
        let mut why: Option<&'static str> = None;
        let mut targets = Vec::new();
        let mut max_n = 0;
        let mut own = Vec::new();
        let mut modes = self.modes;
        let calls_ok = self.calls_ok;
        crate::ir::visit::walk_stmts(std::slice::from_ref(s), &mut |s| {
            let StmtKind::Block(b) = &s.kind else { return };
            if let Some(n) = &b.meta.number {
                if n.value <= MAX_N {
                    max_n = max_n.max(n.value);
                }
                if n.value <= MAX_TRACKED_N {
                    own.push(n.value);
                }
            }
            modes.items(&b.items, &mut Touched::default());
            for it in &b.items {
                match &it.kind {
                    ItemKind::Call(c) if calls_ok && plain_call(c) => {}
                    ItemKind::Call(_) => why = why.or(Some("a call of another program")),
                    ItemKind::StopMessage { .. } => why = why.or(Some("a stop with a message")),
                    ItemKind::Goto(g) => match &g.target {
                        Target::Number(n) => targets.push(n.value),
                        Target::Label(_) => {}
                        Target::Computed(_) => why = why.or(Some("a computed jump")),
                    },
                    ItemKind::Word(w) => match &w.value {
                        WordValue::Expr(e) => match &e.kind {
                            _ if w.addr.is(b'G') && !matches!(e.kind, ExprKind::Num(_)) => {
                                why = why.or(Some("a computed G word"));
                            }
                            _ => {}
                        },
                        WordValue::Ac(_) | WordValue::Ic(_) | WordValue::Rotary(..) => {}
                    },
                    _ => {}
                }
            }
        });
        if let Some(w) = why {
            return self.decline(w);
        }
        self.modes = modes;
        self.max_n = self.max_n.max(max_n);
        for n in own {
            self.skel_ns.insert(n);
        }
        for n in targets {
            if n > MAX_TRACKED_N {
                return self.decline("a jump to an N number above 16777216");
            }
            self.targets.insert(n);
        }
        self.body.push(s.clone());
    }
}

impl WordsSink for Skel {
    fn active(&self) -> bool {
        self.stop.is_none()
    }

    fn plain(&mut self, prog: usize, meta: &BlockMeta, words: &[PlainWord], _: &RawBlock<'_>) -> bool {
        if self.stop.is_some() {
            return true;
        }
        if words.iter().any(|w| crate::lower::comp_flow::stream_relevant_word(w.letter, Some(w.value), false, true)) {
            self.decline(crate::stream::target::fanuc::COMP);
            return true;
        }
        if prog != 0 {
            self.decline("more than one program");
            return true;
        }
        if kept(&self.keep, meta) || self.after_msg {
            // Asked for as a statement (a lone M0 after a MSG is judged there).
            return false;
        }
        self.plain_run_block(meta, words);
        true
    }

    fn stmt(&mut self, prog: usize, s: &Stmt) {
        if self.stop.is_some() {
            return;
        }
        if crate::lower::comp_flow::stream_relevant(std::slice::from_ref(s), false, true) {
            return self.decline(crate::stream::target::fanuc::COMP);
        }
        if prog != 0 {
            return self.decline("more than one program");
        }
        let after_msg = std::mem::replace(&mut self.after_msg, false);
        if let StmtKind::Block(b) = &s.kind {
            if after_msg && crate::lower::to_fanuc::words::is_lone_m0(b) {
                self.forced.push(b.meta.span.lo);
            } else if run_block(s) && !kept(&self.keep, &b.meta) {
                self.run_block(&b.meta);
                let mut t = self.touched;
                self.modes.items(&b.items, &mut t);
                self.touched = t;
                return;
            }
            // Any block with a MSG: its last piece (`lower::to_fanuc::blocks`) may be the MSG alone.
            self.after_msg = b.items.iter().any(|i| matches!(i.kind, ItemKind::Message { .. }));
        }
        self.close_run();
        self.macro_stmt(s);
    }
}

/// A skeleton scan's sink before the scan, with the N values `keep` kept out of runs.
pub(super) fn new_skel(keep: NSet, calls_ok: bool) -> Skel {
    Skel {
        keep,
        body: Vec::new(),
        run: None,
        runs: 0,
        run_ns: NSet::default(),
        targets: NSet::default(),
        max_n: 0,
        skel_ns: NSet::default(),
        modes: Modes { units: Units::default(), abs: true },
        touched: Touched::default(),
        run_units: Vec::new(),
        after_msg: false,
        forced: Vec::new(),
        stop: None,
        calls_ok,
    }
}

/// A skeleton after its scan (whose index is `ix`): the skeleton, the program it is the
/// body of, and the index.
pub(super) fn finish(mut sk: Skel, ix: Index) -> Result<(Skel, Program, Index), Fallback> {
    sk.close_run();
    if let Some(why) = sk.stop.take() {
        return Err(Fallback::NotStraight(why));
    }
    if !ix.diags.is_empty() {
        return Err(Fallback::Diagnostics);
    }
    if ix.programs.len() != 1 {
        return Err(Fallback::NotStraight("more than one program".into()));
    }
    if !ix.programs[0].program.params.is_empty() {
        return Err(Fallback::NotStraight("a PROC with parameters".into()));
    }
    let program = ix.programs[0].program.clone();
    Ok((sk, program, ix))
}
