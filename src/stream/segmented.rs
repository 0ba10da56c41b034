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
//! - a straight block's translation depends on no other block but through the G70 mode
//!   (see `translate::fast`), and programs with G70/G700 anywhere are declined; the words
//!   pass's G90/G91 mode reaches only AC()/IC() words, which are declined too;
//! - the labels pass sees the same jumps and the same jump targets: a run never holds a
//!   block whose N value any jump names (those stay real blocks of the skeleton), and
//!   labelled blocks are not straight; it picks fresh numbers above the highest N of the
//!   program, which the placeholder carries as its own N (programs whose numbers could
//!   run out and wrap to low numbers are declined);
//! - nothing else in the passes looks from one block at another one outside a structure
//!   (MSG followed by M0 does; MSG is declined).
//!
//! The source is read two or three times: a scan builds the skeleton (and collects the N
//! values jumps name); when such a value is also the N of a run block, a second scan
//! builds it again with those blocks kept out of runs; the writing scan fills the runs.

use super::lines::NotStreamable;
use super::translate::{fast, straight, Fallback};
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
    /// The skeleton's translation's symbol map: the names the whole translation uses.
    pub symbol_map: translate::SymbolMap,
}

/// Whether `meta`'s N value is one a jump names (such a block stays in the skeleton).
fn kept(keep: &NSet, meta: &BlockMeta) -> bool {
    meta.number.as_ref().is_some_and(|n| keep.has(n.value))
}

/// A G70/G700 word (the inch mode the fast path carries across blocks: declined).
fn is_inch(letter: u8, v: f64) -> bool {
    letter == b'G' && (v == 70.0 || v == 700.0)
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
            None => self.run = Some((valid, meta.span)),
        }
    }

    fn close_run(&mut self) {
        if let Some((hi, span)) = self.run.take() {
            let meta = BlockMeta {
                span,
                number: hi.map(|value| SeqNo { value, span }),
                comments: vec![Comment { text: format!("{MARK}{}", self.runs), span }],
                ..BlockMeta::default()
            };
            self.body.push(crate::passes::meta_stmt(meta, vec![]));
            self.runs += 1;
        }
    }

    /// Checks a statement of the macro part and collects its jump targets.
    fn macro_stmt(&mut self, s: &Stmt) {
        let mut why: Option<&'static str> = None;
        let mut targets = Vec::new();
        let mut max_n = 0;
        crate::ir::visit::walk_stmts(std::slice::from_ref(s), &mut |s| {
            let StmtKind::Block(b) = &s.kind else { return };
            if let Some(n) = &b.meta.number {
                if n.value <= MAX_N {
                    max_n = max_n.max(n.value);
                }
            }
            for it in &b.items {
                match &it.kind {
                    ItemKind::Call(_) => why = why.or(Some("a call of another program")),
                    ItemKind::Message { .. } | ItemKind::StopMessage { .. } => why = why.or(Some("a MSG")),
                    ItemKind::Goto(g) => match &g.target {
                        Target::Number(n) => targets.push(n.value),
                        Target::Label(_) => {}
                        Target::Computed(_) => why = why.or(Some("a computed jump")),
                    },
                    ItemKind::Word(w) => match &w.value {
                        WordValue::Ac(_) | WordValue::Ic(_) => why = why.or(Some("AC()/IC()")),
                        WordValue::Expr(e) => match &e.kind {
                            ExprKind::Str(_) => why = why.or(Some("a string-valued word")),
                            ExprKind::Num(x) if matches!(w.addr, Addr::Letter(l) if is_inch(l, x.value)) => {
                                why = why.or(Some("G70/G700 (inch)"));
                            }
                            _ if w.addr.is(b'G') && !matches!(e.kind, ExprKind::Num(_)) => {
                                why = why.or(Some("a computed G word"));
                            }
                            _ => {}
                        },
                    },
                    _ => {}
                }
            }
        });
        if let Some(w) = why {
            return self.decline(w);
        }
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

/// Whether a straight statement holds G70/G700.
fn stmt_inch(s: &Stmt) -> bool {
    let StmtKind::Block(b) = &s.kind else { return false };
    b.items.iter().any(|it| match &it.kind {
        ItemKind::Word(w) => match (&w.addr, &w.value) {
            (Addr::Letter(l), WordValue::Expr(e)) => matches!(&e.kind, ExprKind::Num(x) if is_inch(*l, x.value)),
            _ => false,
        },
        _ => false,
    })
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
        if kept(&self.keep, meta) {
            return false;
        }
        if words.iter().any(|w| is_inch(w.letter, w.value)) {
            self.decline("G70/G700 (inch)");
            return true;
        }
        self.run_block(meta);
        true
    }

    fn stmt(&mut self, prog: usize, s: &Stmt) {
        if self.stop.is_some() {
            return;
        }
        if prog != 0 {
            return self.decline("more than one program");
        }
        if let StmtKind::Block(b) = &s.kind {
            if straight(s).is_ok() && !kept(&self.keep, &b.meta) {
                if stmt_inch(s) {
                    return self.decline("G70/G700 (inch)");
                }
                return self.run_block(&b.meta);
            }
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
    Ok(Segmented { blocks: index.blocks, index, inputs, symbol_map: t.symbol_map })
}

/// The byte ranges of the placeholder lines of a translated skeleton with `runs` runs, in
/// order: each `(NCTRANS SEGMENT k)` or `Nn (NCTRANS SEGMENT k)` alone on its line; `None`
/// when the text holds the marker anywhere else.
fn placeholders(text: &str, runs: usize, eol: &str) -> Option<Vec<(usize, usize)>> {
    let open = format!("({MARK}");
    let mut v = Vec::with_capacity(runs);
    let mut from = 0;
    while let Some(at) = text[from..].find(&open).map(|k| k + from) {
        let lo = text[..at].rfind('\n').map_or(0, |k| k + 1);
        let head = &text[lo..at];
        let numbered = head
            .strip_prefix('N')
            .and_then(|h| h.strip_suffix(' '))
            .is_some_and(|d| !d.is_empty() && d.bytes().all(|c| c.is_ascii_digit()));
        if !(head.is_empty() || numbered) {
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
                self.next += 1;
            }
            None => self.bad = true,
        }
    }

    /// A straight block of a run the fast path declined: translated alone (as
    /// `stream::translate` does).
    fn alone(&mut self, s: &Stmt) {
        let mut u = self.lone.clone();
        if let Some(p) = u.programs.first_mut() {
            p.body = vec![s.clone()];
        }
        let t = translate::to_fanuc(&u, &[], self.opts);
        if !t.diags.is_empty() || t.unsupported > 0 {
            self.bad = true;
            return;
        }
        let skip = self.header_len;
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
        if kept(self.keep, meta) {
            return false;
        }
        self.enter();
        if self.fast.words(meta, words, line, &mut self.buf).is_err() {
            // Nothing was written; the block comes again as a statement (still a run block).
            self.fast.g70 = false;
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
            StmtKind::Block(b) => straight(s).is_ok() && !kept(self.keep, &b.meta),
            _ => false,
        };
        if !run {
            self.in_run = false;
            return;
        }
        self.enter();
        if self.fast.block(s, &mut self.buf).is_err() {
            self.fast.g70 = false;
            self.alone(s);
        }
        self.flush_some();
    }
}
