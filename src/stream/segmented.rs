//! Segmented streaming translation (Sinumerik → FANUC) of programs with a macro part: the
//! top-level statements that are not straight-line blocks (R assignments, IF/WHILE/LOOP,
//! jumps, labels) are kept as IR, each maximal run of top-level straight blocks between
//! them stands in that IR as ONE placeholder block, and the whole-program translator
//! translates that skeleton (labels, structures, the variable map header come out as for
//! the whole file). The skeleton's text is then written with each placeholder line
//! replaced by its run, re-read from the source and translated block by block with the
//! straight-line stream's fast path. Memory follows the macro part, not the motion part.
//!
//! Why the output is the whole translation's, byte for byte:
//! - a straight block's translation depends on no other block but through the words
//!   pass's modes, and the words pass follows them in TEXTUAL order (`body_pass` walks the
//!   statements and every structure's bodies in source order with one `Modal`; it never
//!   follows jumps or loops). So the mode at any block is a function of the text before
//!   it, and textual order is all there is to follow: the skeleton scan does it
//!   ([`Modes`], the same rules: G70 on; G71, G700, G710 off; G90/G91), through runs and
//!   through the macro statements' blocks (`walk_stmts` is that same pre-order), and
//!   - each run's fast path starts in the G70 mode the text before it leaves (a block the
//!     fast path declines is translated alone after a G70 block when that mode is on);
//!   - each placeholder carries the modes its run leaves as G70/G71 and G90/G91 words
//!     (only where the run changes them), so the skeleton's words pass reads the modes
//!     the whole translation has at the macro statements after the run: F under G70, the
//!     G90/G91 switch around AC()/IC() words. The placeholder's line is replaced whole,
//!     so these words never reach the output.
//!   - whether textual order is the mode a jump or a loop head runs in is the verifier's
//!     question, the same for both paths: they write the same bytes.
//! - the labels pass sees the same jumps and the same jump targets: a run never holds a
//!   block whose N value any jump names (those stay real blocks of the skeleton), and
//!   labelled blocks are not straight; it picks fresh numbers above the highest N of the
//!   program, which the placeholder carries as its own N (programs whose numbers could
//!   run out and wrap to low numbers are declined);
//! - nothing else in the passes looks from one block at another one outside a structure
//!   but MSG: a block holding only `MSG("…")` and a lone M0 block right after it become
//!   one stop with the message. Such an M0 stays a real block of the skeleton (never a
//!   run's), so the pair meets there. A MSG not so paired becomes a comment with a note
//!   (NC320): the skeleton's translation then has a diagnostic and the whole path takes
//!   the file (its notes are rendered from the text). A MSG beside other items is
//!   declined: the blocks pass splits the block and a piece may pair with the M0 where
//!   the verifier's aligned source (`translate::align_source`: a MSG is kept only alone
//!   in its block before a lone M0) does not.
//!
//! Why verification gives the whole path's verdict: the streamed verifier runs the
//! source as it is, the whole path runs `align_source` of it, which differs only in MSG
//! items (dropped unless paired: here every MSG is paired, and a paired one is kept) and
//! string-valued T words (declined).
//!
//! The source is read two or three times: a scan builds the skeleton (and collects the N
//! values jumps name); when such a value is also the N of a run block, a second scan
//! builds it again with those blocks kept out of runs; the writing scan fills the runs.

use super::lines::NotStreamable;
use super::translate::{fast, g70_block, straight, Fallback};
use super::WRITE_BYTES;
use super::{Index, PlainWord, ProgressFn, WordsSink};
use crate::dialect::fanuc::emit::{self, EmitOptions};
use crate::dialect::{Dialect, ParseOptions};
use crate::eval::Input;
use crate::ir::{
    Addr, BlockMeta, Comment, ExprKind, ItemKind, Program, SeqNo, Stmt, StmtKind, Target, Unit, WordValue,
};
use crate::read::RawBlock;
use crate::span::Span;
use crate::translate::{self, TranslateOptions};
use std::io::Write;
use std::path::Path;

/// The text of a placeholder comment (`k`: the run's index); no source comment of the
/// skeleton may hold it (checked on the translated skeleton).
const MARK: &str = "NCTRANS SEGMENT ";
/// N values above this are not tracked (a run holding one declines).
const MAX_TRACKED_N: u32 = 1 << 24;
/// The labels pass's highest N number.
const MAX_N: u32 = 99999;
/// A set of N values (a bit per value up to [`MAX_TRACKED_N`]).
#[derive(Default, Clone)]
struct NSet(Vec<u64>);

impl NSet {
    fn insert(&mut self, n: u32) {
        let w = (n / 64) as usize;
        if self.0.len() <= w {
            self.0.resize(w + 1, 0);
        }
        self.0[w] |= 1 << (n % 64);
    }
    fn has(&self, n: u32) -> bool {
        self.0.get((n / 64) as usize).is_some_and(|w| w & (1 << (n % 64)) != 0)
    }
    fn meets(&self, o: &NSet) -> bool {
        self.0.iter().zip(&o.0).any(|(a, b)| a & b != 0)
    }
}

/// A finished segmented translation.
pub struct Segmented {
    /// The source's first-scan index (of the writing scan).
    pub index: Index,
    pub blocks: u64,
    /// `#n=0` for the R parameters the translation maps: the output side's inputs when
    /// verifying (as `translate::verify` sets them).
    pub inputs: Vec<Input>,
}

/// Whether `meta`'s N value is one a jump names (such a block stays in the skeleton).
fn kept(keep: &NSet, meta: &BlockMeta) -> bool {
    meta.number.as_ref().is_some_and(|n| keep.has(n.value))
}

/// The two modes of the words pass that reach from block to block outside a structure, in
/// textual order (`passes::words::words_pass`): G70 (inch lengths, metric feed: the fast
/// path's `g70`) and G90/G91 (read by AC()/IC() words).
#[derive(Clone, Copy)]
struct Modes {
    g70: bool,
    abs: bool,
}

/// Which of the two modes a block's words touched.
#[derive(Clone, Copy, Default)]
struct Touched {
    inch: bool,
    abs: bool,
}

impl Modes {
    /// A constant G word, as the words pass takes it.
    fn g(&mut self, v: f64, t: &mut Touched) {
        if v == 70.0 {
            self.g70 = true;
        } else if v == 71.0 || v == 700.0 || v == 710.0 {
            self.g70 = false;
        } else if v == 90.0 || v == 91.0 {
            self.abs = v == 90.0;
            t.abs = true;
            return;
        } else {
            return;
        }
        t.inch = true;
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
fn g_item(v: f64, span: Span) -> crate::ir::Item {
    let w = crate::ir::Word {
        addr: Addr::Letter(b'G'),
        value: WordValue::Expr(crate::ir::Expr::num(v, false, span)),
        span,
    };
    crate::ir::Item { kind: ItemKind::Word(w), span }
}

/// The first scan's sink: builds the skeleton.
struct Skel {
    keep: NSet,
    body: Vec<Stmt>,
    /// The run being collected: its highest valid N value, the span of its first block.
    run: Option<(Option<u32>, Span)>,
    runs: usize,
    /// N values of run blocks.
    run_ns: NSet,
    /// N values jumps name.
    targets: NSet,
    max_n: u32,
    /// The modes in textual order up to here.
    modes: Modes,
    /// Which modes the run being collected changes.
    touched: Touched,
    /// The G70 mode at the start of each run.
    run_g70: Vec<bool>,
    /// The last statement was a block holding only a MSG.
    after_msg: bool,
    /// Where the lone M0 blocks right after such a MSG start: kept in the skeleton (the
    /// words pass pairs the two).
    forced: Vec<u32>,
    stop: Option<String>,
}

impl Skel {
    fn decline(&mut self, why: impl Into<String>) {
        if self.stop.is_none() {
            self.stop = Some(why.into());
        }
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
                self.run_g70.push(self.modes.g70);
            }
        }
    }

    /// Ends the run being collected: its placeholder block carries the modes the run leaves
    /// (as G70/G71 and G90/G91 words, where it changes them) for the words pass to follow
    /// into the skeleton after it; the placeholder's line is replaced whole.
    fn close_run(&mut self) {
        if let Some((hi, span)) = self.run.take() {
            let t = std::mem::take(&mut self.touched);
            let mut items = Vec::new();
            if t.inch {
                items.push(g_item(if self.modes.g70 { 70.0 } else { 71.0 }, span));
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
            self.body.push(crate::passes::meta_stmt(meta, items));
            self.runs += 1;
        }
    }

    /// Checks a statement of the macro part, follows its modes and collects its jump targets.
    fn macro_stmt(&mut self, s: &Stmt) {
        let mut why: Option<&'static str> = None;
        let mut targets = Vec::new();
        let mut max_n = 0;
        let mut modes = self.modes;
        crate::ir::visit::walk_stmts(std::slice::from_ref(s), &mut |s| {
            let StmtKind::Block(b) = &s.kind else { return };
            if let Some(n) = &b.meta.number {
                if n.value <= MAX_N {
                    max_n = max_n.max(n.value);
                }
            }
            modes.items(&b.items, &mut Touched::default());
            let lone_msg = crate::passes::words::msg_text(b).is_some();
            for it in &b.items {
                match &it.kind {
                    ItemKind::Call(_) => why = why.or(Some("a call of another program")),
                    // A MSG alone in its block is paired with a lone M0 after it, or left
                    // as a comment with a note (declined: see `to_fanuc`); beside other
                    // items the pieces the blocks pass makes may pair where the verifier's
                    // aligned source does not.
                    ItemKind::Message { .. } if lone_msg => {}
                    ItemKind::Message { .. } => why = why.or(Some("a MSG beside other items")),
                    ItemKind::StopMessage { .. } => why = why.or(Some("a stop with a message")),
                    ItemKind::Goto(g) => match &g.target {
                        Target::Number(n) => targets.push(n.value),
                        Target::Label(_) => {}
                        Target::Computed(_) => why = why.or(Some("a computed jump")),
                    },
                    ItemKind::Word(w) => match &w.value {
                        WordValue::Expr(e) => match &e.kind {
                            ExprKind::Str(_) => why = why.or(Some("a string-valued word")),
                            _ if w.addr.is(b'G') && !matches!(e.kind, ExprKind::Num(_)) => {
                                why = why.or(Some("a computed G word"));
                            }
                            _ => {}
                        },
                        WordValue::Ac(_) | WordValue::Ic(_) => {}
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
        if prog != 0 {
            self.decline("more than one program");
            return true;
        }
        if kept(&self.keep, meta) || self.after_msg {
            // Asked for as a statement (a lone M0 after a MSG is judged there).
            return false;
        }
        self.run_block(meta);
        let mut t = self.touched;
        for w in words.iter().filter(|w| w.letter == b'G') {
            self.modes.g(w.value, &mut t);
        }
        self.touched = t;
        true
    }

    fn stmt(&mut self, prog: usize, s: &Stmt) {
        if self.stop.is_some() {
            return;
        }
        if prog != 0 {
            return self.decline("more than one program");
        }
        let after_msg = std::mem::replace(&mut self.after_msg, false);
        if let StmtKind::Block(b) = &s.kind {
            if after_msg && crate::passes::words::is_lone_m0(b) {
                self.forced.push(b.meta.span.lo);
            } else if straight(s).is_ok() && !kept(&self.keep, &b.meta) {
                self.run_block(&b.meta);
                let mut t = self.touched;
                self.modes.items(&b.items, &mut t);
                self.touched = t;
                return;
            }
            self.after_msg = crate::passes::words::msg_text(b).is_some();
        }
        self.close_run();
        self.macro_stmt(s);
    }
}

/// One skeleton scan of `path` with the N values `keep` kept out of runs; the skeleton and
/// the program (name, head, span) it is the body of.
fn skeleton(path: &Path, keep: NSet) -> Result<(Skel, Program), Fallback> {
    let mut sk = Skel {
        keep,
        body: Vec::new(),
        run: None,
        runs: 0,
        run_ns: NSet::default(),
        targets: NSet::default(),
        max_n: 0,
        modes: Modes { g70: false, abs: true },
        touched: Touched::default(),
        run_g70: Vec::new(),
        after_msg: false,
        forced: Vec::new(),
        stop: None,
    };
    let popts = ParseOptions::for_dialect(Dialect::Sinumerik);
    let ix =
        super::scan_words_path(path, 0, Dialect::Sinumerik, &popts, &mut sk, None).map_err(Fallback::NotStreamable)?;
    sk.close_run();
    if let Some(why) = sk.stop.take() {
        return Err(Fallback::NotStraight(why));
    }
    if !ix.diags.is_empty() {
        return Err(Fallback::Diagnostics);
    }
    let mut programs = ix.programs.into_iter();
    let (Some(p), None) = (programs.next(), programs.next()) else {
        return Err(Fallback::NotStraight("more than one program".into()));
    };
    if !p.program.params.is_empty() {
        return Err(Fallback::NotStraight("a PROC with parameters".into()));
    }
    Ok((sk, p.program))
}

/// Translates `path` (Sinumerik) to FANUC into `out` as a skeleton translated whole with its
/// runs of straight blocks streamed (see the module comment). On `Err` nothing useful was
/// written (the caller discards `out` and translates whole).
pub fn to_fanuc(
    path: &Path,
    opts: &TranslateOptions,
    out: &mut dyn Write,
    progress: Option<ProgressFn<'_>>,
) -> Result<Segmented, Fallback> {
    if opts.number_blocks.is_some() || opts.main_is_sub {
        return Err(Fallback::NotStraight("--number-blocks or a subprogram as main".into()));
    }
    let (mut sk, mut program) = skeleton(path, NSet::default())?;
    if sk.targets.meets(&sk.run_ns) {
        // Jumps name N values of run blocks: scan again keeping those blocks real.
        let keep = sk.targets.clone();
        (sk, program) = skeleton(path, keep)?;
        if sk.targets.meets(&sk.run_ns) {
            return Err(Fallback::NotStraight("a jump into a run of straight blocks".into()));
        }
    }
    // The labels pass numbers jump targets from the next thousand above the highest N, and
    // from 1 when those would pass N99999 (then it needs every N of the runs): declined.
    let mut nodes = 0usize;
    crate::ir::visit::walk_stmts(&sk.body, &mut |_| nodes += 1);
    if u64::from((sk.max_n / 1000 + 1) * 1000) + 4 * nodes as u64 + 16 > u64::from(MAX_N) {
        return Err(Fallback::NotStraight("N numbers close to N99999".into()));
    }
    let mut lone = program.clone();
    program.body = std::mem::take(&mut sk.body);
    let unit = Unit { dialect: Dialect::Sinumerik, file: 0, programs: vec![program] };
    let t = translate::to_fanuc(&unit, &[], opts);
    drop(unit);
    if !t.diags.is_empty() || t.unsupported > 0 {
        return Err(Fallback::Diagnostics);
    }
    let eol = opts.line_ending.as_str();
    let places = placeholders(&t.text, sk.runs, eol)
        .ok_or_else(|| Fallback::NotStraight("a comment that reads as a segment marker".into()))?;
    let inputs = crate::translate::r_param_inputs(&t.symbol_map);
    // A block the fast path declines is translated alone, as the straight stream does: the
    // header of an empty program comes first, then the block.
    lone.body = vec![];
    let lone_unit = Unit { dialect: Dialect::Sinumerik, file: 0, programs: vec![lone] };
    let head = translate::to_fanuc(&lone_unit, &[], opts);
    let header_len = head.unit.programs.first().map_or(0, |p| p.body.len());
    let mut w = Writer {
        keep: &sk.keep,
        run_g70: &sk.run_g70,
        forced: &sk.forced,
        fast: fast::Fast::new(opts.comments, eol),
        opts,
        eo: EmitOptions { comments: opts.comments, line_ending: opts.line_ending, file: 0 },
        lone: lone_unit,
        header_len,
        text: t.text,
        places,
        pos: 0,
        next: 0,
        in_run: false,
        buf: Vec::with_capacity(WRITE_BYTES + 4096),
        out,
        io: None,
        bad: false,
    };
    let popts = ParseOptions::for_dialect(Dialect::Sinumerik);
    let index = super::scan_words_path(path, 0, Dialect::Sinumerik, &popts, &mut w, progress)
        .map_err(Fallback::NotStreamable)?;
    if w.bad || w.next != w.places.len() || !index.diags.is_empty() {
        return Err(Fallback::Diagnostics);
    }
    let rest = w.text.len();
    w.copy_to(rest);
    w.write();
    if w.io.is_none() {
        if let Err(e) = w.out.flush() {
            w.io = Some(e);
        }
    }
    if let Some(e) = w.io {
        return Err(Fallback::NotStreamable(NotStreamable::Io(e)));
    }
    Ok(Segmented { blocks: index.blocks, index, inputs })
}

/// The byte ranges of the placeholder lines of a translated skeleton with `runs` runs, in
/// order: each `(NCTRANS SEGMENT k)` alone on its line, after the placeholder's N number
/// and G words if any (`Nn G20 G91 (NCTRANS SEGMENT k)`); `None`
/// when the text holds the marker anywhere else.
fn placeholders(text: &str, runs: usize, eol: &str) -> Option<Vec<(usize, usize)>> {
    let open = format!("({MARK}");
    let mut v = Vec::with_capacity(runs);
    let mut from = 0;
    while let Some(at) = text[from..].find(&open).map(|k| k + from) {
        let lo = text[..at].rfind('\n').map_or(0, |k| k + 1);
        let head = &text[lo..at];
        // The placeholder's N number and mode words (`Nn G20 G90 `), or nothing.
        let words = head.strip_suffix(' ').is_some_and(|h| {
            h.split(' ').enumerate().all(|(k, t)| {
                let d = t.strip_prefix('G').or_else(|| t.strip_prefix('N').filter(|_| k == 0));
                d.is_some_and(|d| !d.is_empty() && d.bytes().all(|c| c.is_ascii_digit()))
            })
        });
        if !(head.is_empty() || words) {
            return None;
        }
        let tail = format!("{}){eol}", v.len());
        let after = at + open.len();
        if !text[after..].starts_with(&tail) {
            return None;
        }
        let hi = after + tail.len();
        v.push((lo, hi));
        from = hi;
    }
    (v.len() == runs).then_some(v)
}

/// The writing scan's sink: the skeleton's text with each placeholder line replaced by its
/// run, translated as it is read.
struct Writer<'a> {
    keep: &'a NSet,
    /// The G70 mode at each run's start (the skeleton scan's).
    run_g70: &'a [bool],
    /// Where the straight blocks kept in the skeleton for a MSG start.
    forced: &'a [u32],
    fast: fast::Fast,
    opts: &'a TranslateOptions,
    eo: EmitOptions,
    /// The program with an empty body (for a block translated alone).
    lone: Unit,
    header_len: usize,
    /// The translated skeleton.
    text: String,
    places: Vec<(usize, usize)>,
    /// How far `text` is written.
    pos: usize,
    /// The next run.
    next: usize,
    in_run: bool,
    buf: Vec<u8>,
    out: &'a mut dyn Write,
    io: Option<std::io::Error>,
    /// The scan does not match the skeleton's (the file changed), or a block alone has
    /// diagnostics: the output is discarded.
    bad: bool,
}

impl Writer<'_> {
    fn copy_to(&mut self, to: usize) {
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
        match self.places.get(self.next) {
            Some(&(lo, hi)) => {
                self.copy_to(lo);
                self.pos = hi;
                self.fast.g70 = self.run_g70.get(self.next).copied().unwrap_or(false);
                self.next += 1;
            }
            None => self.bad = true,
        }
    }

    /// Whether a block starting at `lo` was kept in the skeleton for a MSG before it.
    fn forced(&self, lo: u32) -> bool {
        self.forced.binary_search(&lo).is_ok()
    }

    /// A straight block of a run the fast path declined: translated alone (as
    /// `stream::translate` does), after a G70 block when `g70` was the mode before it.
    fn alone(&mut self, s: &Stmt, g70: bool) {
        let mut u = self.lone.clone();
        if let Some(p) = u.programs.first_mut() {
            p.body = if g70 { vec![g70_block(), s.clone()] } else { vec![s.clone()] };
        }
        let t = translate::to_fanuc(&u, &[], self.opts);
        if !t.diags.is_empty() || t.unsupported > 0 {
            self.bad = true;
            return;
        }
        let skip = self.header_len + usize::from(g70);
        let body = t.unit.programs.first().map_or(&[][..], |p| &p.body[skip.min(p.body.len())..]);
        let e = emit::emit_body(body, &self.eo);
        if !e.diags.is_empty() {
            self.bad = true;
        }
        self.buf.extend_from_slice(e.text.as_bytes());
    }

    fn flush_some(&mut self) {
        if self.buf.len() >= WRITE_BYTES {
            self.write();
        }
    }

    fn write(&mut self) {
        super::spill(self.out, &mut self.buf, &mut self.io);
    }

    fn live(&self) -> bool {
        !self.bad && self.io.is_none()
    }
}

impl WordsSink for Writer<'_> {
    fn active(&self) -> bool {
        self.live()
    }

    fn plain(&mut self, _: usize, meta: &BlockMeta, words: &[PlainWord], line: &RawBlock<'_>) -> bool {
        if !self.live() {
            return true;
        }
        if kept(self.keep, meta) || self.forced(meta.span.lo) {
            return false;
        }
        self.enter();
        let g70 = self.fast.g70;
        if self.fast.words(meta, words, line, &mut self.buf).is_err() {
            // Nothing was written; the block comes again as a statement (still a run block).
            self.fast.g70 = g70;
            return false;
        }
        self.flush_some();
        true
    }

    fn stmt(&mut self, _: usize, s: &Stmt) {
        if !self.live() {
            return;
        }
        let run = match &s.kind {
            StmtKind::Block(b) => straight(s).is_ok() && !kept(self.keep, &b.meta) && !self.forced(b.meta.span.lo),
            _ => false,
        };
        if !run {
            self.in_run = false;
            return;
        }
        self.enter();
        let g70 = self.fast.g70;
        if self.fast.block(s, &mut self.buf).is_err() {
            // The mode is the one after the block already (`Fast::block`).
            self.alone(s, g70);
        }
        self.flush_some();
    }
}
