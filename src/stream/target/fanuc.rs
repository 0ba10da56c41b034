//! The FANUC target of the straight-line stream (`stream::straight`, Sinumerik source):
//! each block is written as it comes (`lower::to_fanuc::fast_write`: the exact text the
//! whole-program translator writes for it; a block that translator has something to say on
//! goes through `translate::to_fanuc` alone), so neither the source nor the output is ever
//! held whole. Its header is what the translator writes for an empty program of the name on
//! the `%_N_` line. The only state carried from block to block is the length and feed units
//! (F converted where they differ, `lower::to_fanuc::words::units`). Verification is
//! `stream::verify::verify`.
//!
//! Only programs whose translation is local to each block stream: every block holds plain
//! words with constant values (G1 X.. Y.. F..), program ends (M30, M2), comments, block
//! numbers and skips; no labels, jumps, variables, structures, calls or PROC; no
//! `--number-blocks`. Anything else needs the whole-program passes (labels → N numbers,
//! structure lowering, the variable map written in the header) and is translated whole by
//! the caller.

use crate::diag::Diagnostic;
use crate::dialect::fanuc::emit::{self, EmitOptions};
use crate::dialect::{Dialect, ParseOptions};
use crate::ir::{
    Addr, Block, BlockMeta, ExprKind, ItemKind, ProgName, Program, Stmt, StmtKind, UnOp, Unit, Word, WordValue,
};
use crate::lower::to_fanuc::fast_write as fast;
use crate::lower::to_fanuc::words::units::Units;
use crate::read::RawBlock;
use crate::span::Span;
use crate::stream::lines::NotStreamable;
use crate::stream::straight::{self, Fallback, Target};
use crate::stream::target::RunWriter;
use crate::stream::Out;
use crate::stream::{Index, PlainWord, ProgressFn};
use crate::translate::{self, to_fanuc::TranslateOptions};
use std::io::Write;
use std::path::Path;

/// A finished streamed translation.
pub struct Streamed {
    /// The source's first-scan index.
    pub index: Index,
    pub blocks: u64,
    /// Translator diagnostics (spans into the source).
    pub diags: Vec<Diagnostic>,
    pub unsupported: usize,
}

/// Why a program with a tool change or compensation word is translated whole: the
/// translation carries the tool and the cutting edge from block to block
/// (`passes::comp_to_fanuc`).
pub const COMP: &str = "a tool change or tool compensation (M6, D, G40/G41/G42)";

/// A block whose translation does not depend on any other block.
pub fn straight(s: &Stmt) -> Result<(), String> {
    let StmtKind::Block(b) = &s.kind else { return Err("a control structure".into()) };
    straight_block(b)
}

/// A straight block that may also stand in a run of a segmented translation: not one that
/// may be skipped and sets G90/G91 (the mode AC()/IC() words of the skeleton read, merged
/// both ways there; a straight stream has no such words).
pub fn run_block(s: &Stmt) -> bool {
    straight(s).is_ok() && !matches!(&s.kind, StmtKind::Block(b) if b.meta.skip.is_some() && sets_g(b, &[90.0, 91.0]))
}

/// Whether `b` holds one of the constant G words `codes`.
fn sets_g(b: &Block, codes: &[f64]) -> bool {
    b.items.iter().any(|it| match &it.kind {
        ItemKind::Word(w) if w.addr.is(b'G') => {
            matches!(&w.value, WordValue::Expr(e) if matches!(&e.kind, ExprKind::Num(n) if codes.contains(&n.value)))
        }
        _ => false,
    })
}

/// [`straight`] of a block.
fn straight_block(b: &Block) -> Result<(), String> {
    if b.meta.label.is_some() {
        return Err("a label".into());
    }
    // The whole translation writes the main program's test inputs in its own variable
    // names (`R1=5` → `#501=5`), which needs the variable map of the whole program.
    if b.meta.comments.iter().any(|c| crate::lower::own_header::is_test_input(&c.text)) {
        return Err("a test input line (nctrans: set)".into());
    }
    if crate::lower::comp_flow::stream_relevant_items(&b.items, false, true) {
        return Err(COMP.into());
    }
    for it in &b.items {
        let w = match &it.kind {
            ItemKind::Word(w) => w,
            ItemKind::End { .. } => continue,
            _ => return Err("a block that is not plain words".into()),
        };
        let constant = match &w.value {
            WordValue::Expr(e) => match &e.kind {
                ExprKind::Num(_) => true,
                ExprKind::Unary(UnOp::Neg, x) => matches!(x.kind, ExprKind::Num(_)),
                _ => false,
            },
            _ => false,
        };
        if !constant || !matches!(w.addr, Addr::Letter(_)) {
            return Err(format!("a computed or named {} word", w.addr.as_str()));
        }
        // Skipped or not, the units differ after it: the translator merges both ways
        // (`lower::to_fanuc::words::modes`), a stream follows the text.
        if b.meta.skip.is_some() && sets_g(b, &[70.0, 71.0, 700.0, 710.0]) {
            return Err("a block that may be skipped (/) with G70/G71/G700/G710".into());
        }
    }
    Ok(())
}

/// The FANUC target of the straight-line stream (`stream::straight`).
struct ToFanuc<'a> {
    opts: &'a TranslateOptions,
    eo: EmitOptions,
    name: Option<String>,
    fast: fast::Fast,
    /// Statements the translator puts before a program's body (its header comments).
    header_len: usize,
    out: Out<'a>,
    stop: Option<Fallback>,
    diags: Vec<Diagnostic>,
    unsupported: usize,
}

impl ToFanuc<'_> {
    fn unit(&self, body: Vec<Stmt>) -> Unit {
        let program = Program {
            name: self.name.clone().map(ProgName::Name),
            head: None,
            params: vec![],
            save: false,
            body,
            span: Span::default(),
        };
        Unit { dialect: Dialect::Sinumerik, file: self.eo.file, programs: vec![program] }
    }

    /// Whether the output will be discarded (the caller translates whole): only the
    /// straight-line check still matters.
    fn discarded(&self) -> bool {
        self.out.io.is_some() || !self.diags.is_empty() || self.unsupported > 0
    }
}

impl Target for ToFanuc<'_> {
    const SOURCE: Dialect = Dialect::Sinumerik;
    const COMP: &'static str = COMP;
    const STRAIGHT: fn(&Stmt) -> Result<(), String> = straight;

    fn stopped(&self) -> bool {
        self.stop.is_some()
    }

    fn stop(&mut self) -> &mut Option<Fallback> {
        &mut self.stop
    }

    /// Translates one straight block: the fast path, else (when the translator has
    /// something to say on it) the whole-program translator on the block alone, in the
    /// units the blocks before it left.
    fn stmt(&mut self, s: &Stmt) {
        if self.discarded() {
            return;
        }
        if let Err(units) = RunWriter::block(&mut self.fast, s, &mut self.out.buf) {
            let (text, diags, unsupported) = alone(self.unit(vec![]), self.header_len, units, s, self.opts, &self.eo);
            self.unsupported += unsupported;
            self.diags.extend(diags);
            self.out.buf.extend_from_slice(text.as_bytes());
        }
        self.out.flush_some();
    }

    /// [`Target::stmt`] of the block when the fast path takes it; else nothing has changed
    /// (the units are set back) and the statement is asked for. A plain block is straight
    /// (constant letter words, no label): not checked again.
    fn plain(&mut self, meta: &BlockMeta, words: &[PlainWord], line: &RawBlock<'_>) -> bool {
        if self.discarded() {
            return true;
        }
        if !RunWriter::plain(&mut self.fast, meta, words, line, &mut self.out.buf) {
            return false;
        }
        self.out.flush_some();
        true
    }
}

/// The fast path carries the length and feed units from block to block.
impl RunWriter for fast::Fast {
    type Mode = Units;

    #[inline]
    fn start(&mut self, m: Units) {
        self.units = m;
    }

    #[inline]
    fn plain(&mut self, meta: &BlockMeta, words: &[PlainWord], line: &RawBlock<'_>, out: &mut Vec<u8>) -> bool {
        // The usual CAM line in one loop (it changes no mode), as the straight stream does.
        if self.plain_words(meta, words, out) {
            return true;
        }
        let units = self.units;
        if self.words(meta, words, line, out).is_err() {
            self.units = units;
            return false;
        }
        true
    }

    fn block(&mut self, s: &Stmt, out: &mut Vec<u8>) -> Result<(), Units> {
        let units = self.units;
        // The units are the ones after the block already on `Err` (`Fast::block`).
        fast::Fast::block(self, s, out).map_err(|_| units)
    }
}

/// A straight block translated alone by the whole-program translator, as the program
/// `unit` (its body replaced) with a header of `header_len` statements, after a block setting
/// `units` when they are not the units a program starts in (the translation of that block
/// is skipped too): its text, diagnostics and unsupported count.
pub(crate) fn alone(
    mut unit: Unit,
    header_len: usize,
    units: Units,
    s: &Stmt,
    opts: &TranslateOptions,
    eo: &EmitOptions,
) -> (String, Vec<Diagnostic>, usize) {
    let set = (units != Units::default()).then(|| {
        let items = units.words().iter().map(|&v| g_item(v, Span::default())).collect();
        crate::lower::block_stmt(items, Span::default())
    });
    let skip = header_len + usize::from(set.is_some());
    if let Some(p) = unit.programs.first_mut() {
        p.body = set.into_iter().chain([s.clone()]).collect();
    }
    let mut t = translate::to_fanuc::to_fanuc(&unit, &[], opts);
    let body = t.unit.programs.first().map_or(&[][..], |p| &p.body[skip.min(p.body.len())..]);
    let e = emit::emit_body(body, eo);
    t.diags.extend(e.diags);
    (e.text, t.diags, t.unsupported)
}

/// A constant G word.
pub(crate) fn g_item(v: f64, span: Span) -> crate::ir::Item {
    let w = Word { addr: Addr::Letter(b'G'), value: WordValue::Expr(crate::ir::Expr::num(v, false, span)), span };
    crate::ir::Item { kind: ItemKind::Word(w), span }
}

/// Translates `path` (Sinumerik) to FANUC into `out`, reading it once. On `Err` nothing
/// useful was written (the caller discards `out` and translates whole).
pub fn to_fanuc(
    path: &Path,
    opts: &TranslateOptions,
    out: &mut dyn Write,
    progress: Option<ProgressFn<'_>>,
) -> Result<Streamed, Fallback> {
    if opts.number_blocks.is_some() || opts.main_is_sub {
        return Err(Fallback::NotStraight("--number-blocks or a subprogram as main".into()));
    }
    let name = first_header(path).map_err(Fallback::NotStreamable)?;
    let eo = EmitOptions { comments: opts.comments, line_ending: opts.line_ending, file: 0 };
    let eol = opts.line_ending.as_str();
    let mut st = ToFanuc {
        opts,
        eo,
        name,
        fast: fast::Fast::new(opts.comments, eol),
        header_len: 0,
        out: Out::new(out),
        stop: None,
        diags: Vec::new(),
        unsupported: 0,
    };
    // The program's head (`%`, the `O` line, the header comments) is what the translator
    // writes for an empty program, without its closing `%`.
    let head = translate::to_fanuc::to_fanuc(&st.unit(vec![]), &[], opts);
    st.header_len = head.unit.programs.first().map_or(0, |p| p.body.len());
    st.unsupported += head.unsupported;
    st.diags.extend(head.diags);
    let closing = format!("%{eol}");
    st.out.buf.extend_from_slice(head.text.strip_suffix(&closing).unwrap_or(&head.text).as_bytes());
    // The source's profile (its library's macros), as the whole translation reads it.
    let popts = ParseOptions { semantics: opts.source.clone() };
    let (index, blocks) = straight::run(path, &popts, &mut st, progress)?;
    if !st.diags.is_empty() || st.unsupported > 0 {
        return Err(Fallback::Diagnostics);
    }
    // The name was taken from the `%_N_` line before reading; a PROC may rename the program.
    let read_name = index.programs.first().and_then(|p| match &p.program.name {
        Some(ProgName::Name(n)) => Some(n.clone()),
        _ => None,
    });
    if index.programs.first().is_some_and(|p| !p.program.params.is_empty()) || read_name != st.name {
        return Err(Fallback::NotStraight("a PROC".into()));
    }
    st.out.buf.extend_from_slice(closing.as_bytes());
    st.out.finish()?;
    Ok(Streamed { index, blocks, diags: st.diags, unsupported: st.unsupported })
}

/// The program name of a `%_N_NAME_MPF` first line.
fn first_header(path: &Path) -> Result<Option<String>, NotStreamable> {
    let (input, _) = crate::stream::open(path)?;
    let mut l = crate::stream::lines::Lines::new(input)?;
    while let Some(x) = l.next_line()? {
        let t = x.text.trim_start_matches([' ', '\t']);
        if t.is_empty() {
            continue;
        }
        return Ok(if t.starts_with('%') { crate::dialect::sinumerik::header_name(t.trim_end()) } else { None });
    }
    Ok(None)
}

/// The program of the streamed Siemens file `ix` (read from `path`) without its motion
/// blocks: straight blocks ([`straight`]) without a block number, an end or any word but
/// axis, arc, radius and feed words and G0..G3. Those name no variable nor call, set no
/// mode the translation follows and are no jump target, so what a translation's symbol map
/// makes of the variables the program uses, global user data first, is that of the whole
/// program (`nctrans check` seeds a FANUC side's commons from it; its caller refuses a
/// translation with other errors, which the context of a dropped block might decide).
/// Held whole is only the rest (as the segmented stream holds its skeleton).
pub fn without_straight(path: &Path, ix: &Index) -> Result<Unit, NotStreamable> {
    let mut body = Vec::new();
    let mut keep = |_: usize, s: &Stmt| {
        if straight(s).is_err() || !motion_only(s) {
            body.push(s.clone());
        }
    };
    crate::stream::scan_path(path, ix.file, Dialect::Sinumerik, &ix.opts, &mut keep, None)?;
    let program = ix.programs.first().map(|p| Program { body, ..p.program.clone() });
    Ok(Unit { dialect: Dialect::Sinumerik, file: ix.file, programs: program.into_iter().collect() })
}

/// A straight block of motion alone (see [`without_straight`]).
fn motion_only(s: &Stmt) -> bool {
    let StmtKind::Block(b) = &s.kind else { return false };
    b.meta.number.is_none()
        && b.items.iter().all(|it| match &it.kind {
            ItemKind::Word(w) => match w.addr {
                Addr::Letter(b'G') => sets_g(b, &[0.0, 1.0, 2.0, 3.0]) && !sets_other_g(b),
                Addr::Letter(l) => b"XYZABCUVWIJKRF".contains(&l),
                _ => false,
            },
            _ => false,
        })
}

/// Whether `b` holds a G word other than G0..G3.
fn sets_other_g(b: &Block) -> bool {
    b.items.iter().any(|it| match &it.kind {
        ItemKind::Word(w) if w.addr.is(b'G') => !matches!(&w.value, WordValue::Expr(e)
            if matches!(&e.kind, ExprKind::Num(n) if [0.0, 1.0, 2.0, 3.0].contains(&n.value))),
        _ => false,
    })
}
