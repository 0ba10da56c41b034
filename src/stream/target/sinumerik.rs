//! The Sinumerik target of the straight-line stream (`stream::straight`, FANUC source): the
//! first [`FIRST_STMTS`] statements go through the whole translator (its header handling:
//! it writes the header); after them each plain block is written straight from its words
//! (`lower::to_sinumerik::fast_write`: the passes' exact bytes), and the blocks the fast
//! path declines go, up to [`CHUNK_STMTS`] at a time, through the ordinary FANUC →
//! Sinumerik passes and writer with the program's plan made once ([`Planned`], which the
//! segmented stream shares). Neither the source nor the output is ever held whole.
//! Verification is `stream::verify` (read back, [`compare`](crate::stream::verify::compare)).
//!
//! Only programs whose translation is local to each block stream ([`straight`]): one
//! program (`%`, `O`/`:` head), blocks of plain words with constant values and G codes that
//! need no other block, program ends (M30, M2), comments, N numbers and skips. No macro
//! statements, variables (so nothing vacant), jumps, loops, calls (M98, G65, G66), G10.
//! The states the passes carry from block to block, the arc mode that makes `R` a radius
//! (`CR=`) and the unit (G20/G21) a number without a point is counted in, are followed
//! block by block: the fast path is given them, and a chunk of declined blocks gets a
//! stand-in `G2` block in front (taken out after lowering) and starts in the unit in force
//! (`ProgPlan::start_inch`). Anything else (or any error, or a warning other
//! than a dropped G43/G44/G49) falls back to the whole-file path, which writes the same.

use crate::diag::Diagnostic;
use crate::dialect::digits::Src;
use crate::dialect::sinumerik::emit::{emit_program, Frame};
use crate::dialect::{Dialect, ParseOptions};
use crate::ir::{
    Addr, Block, BlockMeta, ExprKind, Item, ItemKind, ProgName, Program, Stmt, StmtKind, UnOp, Unit, Word, WordValue,
};
use crate::lower::to_sinumerik::fast_write as fast;
use crate::lower::to_sinumerik::{self as passes, Ctx, Options, ProgPlan};
use crate::read::{LineEnding, RawBlock};
use crate::span::{SourceFile, Span};
use crate::stream::lines::{first_line_ending, has_bom, Lines};
use crate::stream::straight::{self, Fallback, Target};
use crate::stream::Out;
use crate::stream::{Index, ItemView, PlainWord, ProgressFn};
use crate::translate::to_sinumerik::{self as ts, SymbolMap};
use std::collections::BTreeMap;
use std::io::Write;
use std::path::Path;

/// Statements translated at a time.
pub const CHUNK_STMTS: usize = 4096;

/// Statements of the first chunk, which the whole translator writes (with the header).
/// Its plan is made twice and every pass runs on it, some 50,000 instructions a statement,
/// so it is kept short; the fast path (or the passes, chunk by chunk) takes the rest.
pub const FIRST_STMTS: usize = 64;

/// The one warning a streamed translation keeps (and reports): a tool length G code
/// dropped (`G43 H1`, `G49`), common in CAM output. Other diagnostics fall back.
pub const KEPT_WARNING: &str = "NC368";

/// G codes (×10) whose translation needs nothing but their own block: motion, planes,
/// units, cutter radius and tool length compensation, work offsets, exact stop, path mode,
/// cycle cancel, absolute/incremental, feed modes, and the dwell (written as its own block).
/// G20 makes every later value without a decimal point count 0.0001 in: the straight
/// stream follows it as it follows the arc mode (the segmented one reads such programs whole).
const PLAIN_G: [u32; 30] = [
    0, 10, 20, 30, 40, 170, 180, 190, 200, 210, 400, 410, 420, 430, 440, 490, 530, 540, 550, 560, 570, 580, 590, 610,
    640, 800, 900, 910, 940, 950,
];

/// [`PLAIN_G`] as a set (one test instead of a search on every G word of a CAM file).
struct GSet([u64; 16]);

impl GSet {
    const fn of(codes: &[u32]) -> GSet {
        let mut bits = [0u64; 16];
        let mut i = 0;
        while i < codes.len() {
            let g = codes[i] as usize;
            bits[g / 64] |= 1 << (g % 64);
            i += 1;
        }
        GSet(bits)
    }

    #[inline(always)]
    fn contains(&self, g: u32) -> bool {
        let g = g as usize;
        self.0.get(g / 64).is_some_and(|b| b >> (g % 64) & 1 == 1)
    }
}

const PLAIN_G_SET: GSet = GSet::of(&PLAIN_G);

/// A stand-in block's span: no statement read from a file has it.
const STAND_IN: Span = Span::new(u32::MAX, u32::MAX);

/// A FANUC block whose translation does not depend on any other block (see the module
/// documentation); `Err` names what it has instead, for the "read whole" note.
pub fn straight(s: &Stmt) -> Result<(), String> {
    let StmtKind::Block(b) = &s.kind else { return Err("a loop".into()) };
    straight_block(b)
}

/// [`straight`] of a block.
fn straight_block(b: &Block) -> Result<(), String> {
    if b.meta.label.is_some() {
        return Err("a label".into());
    }
    if crate::lower::comp_flow::stream_relevant_items(&b.items, true, false) {
        return Err(COMP.into());
    }
    for it in &b.items {
        let w = match &it.kind {
            ItemKind::Word(w) => w,
            ItemKind::End { .. } => continue,
            ItemKind::Call(_) => return Err("a call".into()),
            ItemKind::Return { .. } => return Err("M99".into()),
            ItemKind::Goto(_) | ItemKind::IfThen { .. } | ItemKind::IfBlock { .. } => {
                return Err("a jump or an IF".into())
            }
            ItemKind::Assign { .. } => return Err("a macro statement".into()),
            _ => return Err("a block that is not plain words".into()),
        };
        let Addr::Letter(letter) = w.addr else { return Err(format!("the address {}", w.addr.as_str())) };
        let value = match &w.value {
            WordValue::Expr(e) => match &e.kind {
                ExprKind::Num(n) => Some(n.value),
                ExprKind::Unary(UnOp::Neg, x) => match &x.kind {
                    ExprKind::Num(n) => Some(-n.value),
                    _ => None,
                },
                _ => None,
            },
            _ => None,
        };
        let Some(v) = value else { return Err(format!("a computed {} word", letter as char)) };
        if letter == b'G' && !plain_g(v) {
            return Err(format!("G{v}"));
        }
    }
    Ok(())
}

/// A G code whose translation needs nothing but its own block ([`PLAIN_G`]).
pub(crate) fn plain_g(v: f64) -> bool {
    let g10 = fast::round(v * 10.0);
    (0.0..=9990.0).contains(&g10) && (g10 - v * 10.0).abs() <= 1e-9 && PLAIN_G_SET.contains(g10 as u32)
}

/// Why a program with a compensation word is translated whole: the translation carries the
/// tool and the compensation in force from block to block (`passes::to_sinumerik::comp`).
/// The segmented path reads a program with a tool change whole too ([`COMP_M6`]).
pub const COMP: &str = "tool compensation (D, H, G40-G49)";

/// [`COMP`] of the segmented path, which also reads a program with a tool change whole.
pub const COMP_M6: &str = "a tool change or tool compensation (M6, D, H, G40-G49)";

/// A finished streamed translation.
pub struct Streamed {
    /// The source's first-scan index.
    pub index: Index,
    pub blocks: u64,
    /// Kept warnings ([`KEPT_WARNING`]); spans into the source (file 0).
    pub diags: Vec<Diagnostic>,
    /// The written file's name (`NAME.MPF`) and program name.
    pub file_name: String,
    pub program: String,
    /// The FANUC program number it came from.
    pub fanuc_number: Option<u32>,
    /// The symbol map of the translation (what the whole-file translator reports).
    pub symbols: SymbolMap,
}

/// The program head (`O1234 (TITLE)`) from the first lines of the file, parsed by the
/// FANUC reader: the chunks are translated as parts of a program of this name. The full
/// scan's head is compared with it at the end.
fn head(path: &Path, popts: &ParseOptions) -> Result<(Option<ProgName>, Option<BlockMeta>), Fallback> {
    let (input, _) = crate::stream::open(path).map_err(Fallback::NotStreamable)?;
    let mut lines = Lines::new(input).map_err(Fallback::NotStreamable)?;
    let mut text = String::new();
    for _ in 0..10_000 {
        let Some(l) = lines.next_line().map_err(Fallback::NotStreamable)? else { break };
        let t = l.text.trim();
        // Keep the offsets: the prefix is the file's text up to here.
        while (text.len() as u64) < l.start {
            text.push('\n');
        }
        text.push_str(l.text);
        if !(t.is_empty() || t.bytes().all(|b| b == b'%') || t.starts_with('(') || t.starts_with(';')) {
            break;
        }
    }
    let parsed = crate::dialect::fanuc::parse(&SourceFile::new("head", text), 0, popts);
    if crate::diag::has_errors(&parsed.diags) {
        return Err(Fallback::Diagnostics);
    }
    Ok(parsed.unit.programs.first().map_or((None, None), |p| (p.name.clone(), p.head.clone())))
}

/// What the passes decide for the whole program before they rewrite its body: for a
/// straight-line program it does not depend on the blocks (no variables, no calls). With it
/// a chunk of blocks (or one block) is lowered alone.
pub(crate) struct Planned {
    pub(crate) plan: ProgPlan,
    pub(crate) commons: BTreeMap<u32, u32>,
    pub(crate) common_flags: BTreeMap<u32, u32>,
}

/// Why [`Planned::lower`] wrote nothing.
pub(crate) enum LoweredAlone {
    /// The passes changed the stand-in G2 (the arc mode would not run into the blocks).
    ArcChanged,
    /// The writer cannot spell the result.
    Unwritable,
}

impl Planned {
    /// The first of the programs `programs` are lowered with (the main one).
    pub(crate) fn of_first(programs: &[(crate::span::FileId, &Program)], opts: &Options) -> Option<Planned> {
        let mut l = passes::lower(programs, opts);
        if l.programs.is_empty() {
            return None;
        }
        let (plan, _) = l.programs.swap_remove(0);
        Some(Planned { plan, commons: l.commons, common_flags: l.common_flags })
    }

    fn of(prog: &Program, opts: &Options) -> Option<Planned> {
        Planned::of_first(&[(0, prog)], opts)
    }

    /// `body` through the passes with this plan, after a stand-in G2 when the arc mode `arc`
    /// runs into it (taken out again), starting in the unit `inch` (G20, G21, not known), written without the
    /// frame (no PROC line, header or DEF lines) with LF line ends; and the passes' diagnostics.
    pub(crate) fn lower(
        &self,
        opts: &Options,
        mut body: Vec<Stmt>,
        arc: bool,
        inch: Option<bool>,
    ) -> (Vec<crate::diag::Diagnostic>, Result<String, LoweredAlone>) {
        if arc {
            let word = Word {
                addr: Addr::Letter(b'G'),
                value: WordValue::Expr(crate::ir::Expr::num(2.0, false, STAND_IN)),
                span: STAND_IN,
            };
            let meta = BlockMeta { span: STAND_IN, ..BlockMeta::default() };
            let items = vec![Item { kind: ItemKind::Word(word), span: STAND_IN }];
            body.insert(0, Stmt { kind: StmtKind::Block(Block { meta, items }), span: STAND_IN });
        }
        let mut plan = self.plan.clone();
        plan.start_inch = inch;
        let mut ctx = Ctx {
            opts,
            progs: vec![plan],
            commons: self.commons.clone(),
            common_flags: self.common_flags.clone(),
            diags: Vec::new(),
            cur: 0,
            guard_ok: false,
            modal: Default::default(),
            index_bases: Default::default(),
            end_flag: None,
            end_codes: Default::default(),
        };
        // `passes::lower` without its first step (`indirect::resolve`: nothing to resolve
        // without variables) and with the plan made once.
        let mut body = passes::lower_body(&mut ctx, body);
        if arc {
            let before = body.len();
            body.retain(|s| s.span != STAND_IN);
            if before != body.len() + 1 {
                return (ctx.diags, Err(LoweredAlone::ArcChanged));
            }
        }
        let p = Program { name: None, head: None, params: vec![], save: false, body, span: Span::default() };
        let e = emit_program(&p, &Frame { header: &[], defs: &[], proc_line: false });
        let text = if e.problems.is_empty() { Ok(e.text) } else { Err(LoweredAlone::Unwritable) };
        (ctx.diags, text)
    }

    fn same(&self, other: &Planned) -> bool {
        // Whether the program selects G20/G21, G90/G91, a plane or changes the tool matters
        // only to its callers (a straight program has none, and a streamed one never holds G20).
        let plan = |p: &ProgPlan| ProgPlan {
            sets_units: false,
            sets_plane: (false, false),
            sets_distance: false,
            sets_g90: false,
            tools: false,
            ..p.clone()
        };
        format!("{:?}", (plan(&self.plan), &self.commons, &self.common_flags))
            == format!("{:?}", (plan(&other.plan), &other.commons, &other.common_flags))
    }
}

/// The Sinumerik target of the straight-line stream (`stream::straight`).
struct ToSinumerik<'a> {
    opts: &'a Options,
    planned: Option<Planned>,
    eol: LineEnding,
    name: Option<ProgName>,
    head: Option<BlockMeta>,
    buf: Vec<Stmt>,
    /// Whether a block of the buffer has words: the first chunk is written only then. The
    /// translator takes `nctrans: set` comments off the top of a program up to its first
    /// block with words, an N number or a label, and refuses a program without a block with
    /// words (NC146), which a first chunk of only an `N10` would be.
    buf_real: bool,
    first: bool,
    /// The arc mode (G2/G3 last) before the first buffered statement, and after the last.
    arc_at_start: bool,
    arc: bool,
    /// G20 in force before the first buffered statement, and after the last (a value
    /// without a decimal point counts the inch increment; the program starts metric;
    /// `None`: not known, after a skippable unit word).
    inch_at_start: Option<bool>,
    inch: Option<bool>,
    /// Statements in the first chunk (the whole translator writes it, header included).
    first_stmts: usize,
    /// The line ending as bytes, for the fast path.
    eol_bytes: &'static [u8],
    /// One fast-path line being built.
    line: Vec<u8>,
    out: Out<'a>,
    stop: Option<Fallback>,
    diags: Vec<Diagnostic>,
    file_name: String,
    program: String,
    fanuc_number: Option<u32>,
    symbols: SymbolMap,
    /// The axes outside X, Y, Z (bits of `ABCUVW`) the first chunk names: the whole
    /// translation writes one `FGROUP(X,Y,Z,…)` for every such axis of the program
    /// (`lower::to_sinumerik::feed_group`), so a later block naming another reads whole.
    extra_axes: u8,
}

/// The bit of an axis letter outside X, Y, Z (`ABCUVW`), 0 for any other letter.
fn extra_axis(letter: u8) -> u8 {
    b"ABCUVW".iter().position(|&c| c == letter).map_or(0, |i| 1 << i)
}

impl ToSinumerik<'_> {
    /// Notes the extra axes of a block's letters: the first chunk's, or a stop where a later
    /// block names one the first chunk did not (the FGROUP at the start would lack it).
    fn axes(&mut self, letters: impl Iterator<Item = u8>) {
        let bits = letters.fold(0, |b, l| b | extra_axis(l));
        if self.first {
            self.extra_axes |= bits;
        } else if bits & !self.extra_axes != 0 && self.stop.is_none() {
            self.stop = Some(Fallback::NotStraight(
                "an axis after the first blocks that the feed group written at the start (FGROUP) must name".into(),
            ));
        }
    }

    fn program(&self, body: Vec<Stmt>) -> Program {
        Program {
            name: self.name.clone(),
            head: self.head.clone(),
            params: vec![],
            save: false,
            body,
            span: Span::default(),
        }
    }

    fn keep(&mut self, diags: Vec<Diagnostic>) -> bool {
        if diags.iter().any(|d| d.is_error() || d.code != KEPT_WARNING) {
            self.stop = Some(Fallback::Diagnostics);
            return false;
        }
        self.diags.extend(diags);
        true
    }

    fn write(&mut self, text: &str) {
        match self.eol {
            LineEnding::Lf => self.out.buf.extend_from_slice(text.as_bytes()),
            other => self.out.buf.extend_from_slice(text.replace('\n', other.as_str()).as_bytes()),
        }
        self.out.flush_some();
    }

    /// A block after the first chunk through the fast path: its line is written (after the
    /// statements waiting for the passes); `false` when the passes must translate it.
    fn fast<'t, I: ItemView>(&mut self, meta: &BlockMeta, items: &[I], lit: impl Fn(&I) -> Option<Src<'t>>) -> bool {
        // A plan with variables fails in `flush_rest`: the fast path must not write past it.
        if !self.planned.as_ref().is_some_and(|p| p.plan.defs.is_empty() && p.plan.params.is_empty()) {
            return false;
        }
        if self.buf.is_empty() && self.stop.is_none() && self.out.io.is_none() {
            // Nothing waits for the passes: the line goes straight into the output buffer.
            let at = self.out.buf.len();
            let ok = fast::block(meta, items, lit, self.arc, self.inch, self.opts, self.eol_bytes, &mut self.out.buf)
                .is_ok();
            if !ok {
                self.out.buf.truncate(at);
            } else {
                self.out.flush_some();
            }
            return ok;
        }
        let mut line = std::mem::take(&mut self.line);
        line.clear();
        let ok = fast::block(meta, items, lit, self.arc, self.inch, self.opts, self.eol_bytes, &mut line).is_ok();
        if ok {
            self.flush();
            if self.stop.is_none() && self.out.io.is_none() {
                self.out.buf.extend_from_slice(&line);
                self.out.flush_some();
            }
        }
        self.line = line;
        ok
    }

    /// The first chunk goes through the whole translator: it writes the header lines
    /// (program name, `nctrans: set` inputs in Siemens names) exactly as for the file.
    fn flush_first(&mut self, body: Vec<Stmt>) {
        // The later chunks are lowered with the plan of an empty program of this name: the
        // same as the first chunk's, or the program is not one a stream can translate.
        let unit = Unit { dialect: Dialect::Fanuc, file: 0, programs: vec![self.program(body)] };
        let planned = Planned::of(&self.program(vec![]), self.opts);
        let first = unit.programs.first().and_then(|p| Planned::of(p, self.opts));
        match (planned, first) {
            (Some(a), Some(b)) if a.same(&b) => self.planned = Some(a),
            _ => {
                self.stop = Some(Fallback::NotStraight("a plan that depends on its blocks".into()));
                return;
            }
        }
        let tr = ts::translate(&[&unit], self.opts, LineEnding::Lf);
        if !self.keep(tr.diags) {
            return;
        }
        let [f] = tr.files.as_slice() else {
            self.stop = Some(Fallback::NotStraight("more than one program".into()));
            return;
        };
        self.file_name = f.name.clone();
        self.program = f.program.clone();
        self.fanuc_number = f.fanuc_number;
        self.symbols = tr.symbols.sinumerik().clone();
        let text = f.text.clone();
        self.write(&text);
    }

    /// Later chunks: the passes on the chunk alone (after a stand-in G2 when an arc mode
    /// runs into it), then the writer without the frame (header, DEF lines).
    fn flush_rest(&mut self, body: Vec<Stmt>) {
        let Some(pl) = &self.planned else {
            self.stop = Some(Fallback::NotStraight("no plan".into()));
            return;
        };
        if !pl.plan.defs.is_empty() || !pl.plan.params.is_empty() {
            self.stop = Some(Fallback::NotStraight("variables".into()));
            return;
        }
        let (diags, text) = pl.lower(self.opts, body, self.arc_at_start, self.inch_at_start);
        if !self.keep(diags) {
            return;
        }
        match text {
            Ok(text) => self.write(&text),
            Err(LoweredAlone::ArcChanged) => {
                self.stop = Some(Fallback::NotStraight("an arc mode the passes change".into()))
            }
            Err(LoweredAlone::Unwritable) => self.stop = Some(Fallback::Diagnostics),
        }
    }

    fn flush(&mut self) {
        if self.buf.is_empty() || self.stop.is_some() || self.out.io.is_some() {
            return;
        }
        let body = std::mem::take(&mut self.buf);
        if self.first {
            self.first = false;
            self.flush_first(body);
        } else {
            self.flush_rest(body);
        }
        self.arc_at_start = self.arc;
        self.inch_at_start = self.inch;
        self.buf_real = false;
    }

    /// A block that may be skipped (`/`) and changes the unit leaves it unknown, as where
    /// paths meet in `lower::to_sinumerik::modal` (a value without a decimal point is then
    /// declined by the fast path and refused by the passes, NC375).
    fn skipped_unit(&mut self, skip: bool, inch_before: Option<bool>) {
        if skip && self.inch != inch_before {
            self.inch = None;
        }
    }

    /// The arc mode and `buf_real` after block `b`.
    fn follow(&mut self, b: &Block) {
        let inch_before = self.inch;
        // The arc mode as `words::lower` follows it (`g_codes`, without its vector).
        for it in &b.items {
            let ItemKind::Word(w) = &it.kind else { continue };
            let WordValue::Expr(e) = &w.value else { continue };
            if !w.addr.is(b'G') {
                continue;
            }
            if let Some(g10) = crate::lower::literal(e).map(|v| (v * 10.0).round() as u32) {
                self.follow_g(g10);
            }
        }
        self.skipped_unit(b.meta.skip.is_some(), inch_before);
        self.buf_real |= !b.items.is_empty();
    }

    /// The arc mode and the unit after G code `g10` (×10).
    fn follow_g(&mut self, g10: u32) {
        match g10 {
            20 | 30 => self.arc = true,
            0 | 10 => self.arc = false,
            200 => self.inch = Some(true),
            210 => self.inch = Some(false),
            _ => {}
        }
    }

    /// [`ToSinumerik::push`] of the words of a plain line when the fast path takes them; else
    /// nothing has changed and the caller pushes its statement.
    fn push_plain(&mut self, meta: &BlockMeta, words: &[PlainWord], line: &RawBlock<'_>) -> bool {
        if self.first {
            return false;
        }
        self.axes(words.iter().map(|w| w.letter));
        let (arc, inch, buf_real) = (self.arc, self.inch, self.buf_real);
        // `follow` of the block the words are.
        for w in words.iter().filter(|w| w.letter == b'G') {
            self.follow_g(fast::round(w.value * 10.0) as u32);
        }
        self.skipped_unit(meta.skip.is_some(), inch);
        self.buf_real |= !words.is_empty() || meta.number.is_some() || meta.label.is_some();
        if self.fast(meta, words, |w| Some(Src { line, span: w.span, canon: w.canon })) {
            return true;
        }
        (self.arc, self.inch, self.buf_real) = (arc, inch, buf_real);
        false
    }

    fn push(&mut self, s: &Stmt) {
        let (arc_before, inch_before) = (self.arc, self.inch);
        if let StmtKind::Block(b) = &s.kind {
            self.follow(b);
            self.axes(b.items.iter().filter_map(|it| match &it.kind {
                ItemKind::Word(Word { addr: Addr::Letter(l), .. }) => Some(*l),
                _ => None,
            }));
        }
        if !self.first {
            if let StmtKind::Block(b) = &s.kind {
                if self.fast(&b.meta, &b.items, |_| None) {
                    return;
                }
            }
            if self.buf.is_empty() {
                self.arc_at_start = arc_before;
                self.inch_at_start = inch_before;
            }
        }
        self.buf.push(s.clone());
        let chunk = if self.first { self.first_stmts } else { CHUNK_STMTS };
        if self.buf.len() >= chunk && (self.buf_real || !self.first) {
            self.flush();
        } else if self.first && self.buf.len() >= 64 * CHUNK_STMTS {
            // A quarter million comment lines before the first block: read whole.
            self.stop = Some(Fallback::NotStraight("a long run of comments at the top".into()));
        }
    }
}

impl Target for ToSinumerik<'_> {
    const SOURCE: Dialect = Dialect::Fanuc;
    const COMP: &'static str = COMP;
    const STRAIGHT: fn(&Stmt) -> Result<(), String> = straight;

    fn stopped(&self) -> bool {
        self.stop.is_some()
    }

    fn stop(&mut self) -> &mut Option<Fallback> {
        &mut self.stop
    }

    fn stmt(&mut self, s: &Stmt) {
        self.push(s);
    }

    fn plain(&mut self, meta: &BlockMeta, words: &[PlainWord], line: &RawBlock<'_>) -> bool {
        if !self.first {
            self.axes(words.iter().map(|w| w.letter));
        }
        // The usual CAM line, when nothing waits for the passes (as `ToSinumerik::fast` with
        // an empty buffer): written at once (`fast::plain_words`, the same bytes as
        // `push_plain`; its G0..G3 are straight).
        if !self.first
            && self.buf.is_empty()
            && self.out.io.is_none()
            && self.planned.as_ref().is_some_and(|p| p.plan.defs.is_empty() && p.plan.params.is_empty())
            && fast::plain_words(meta, words, &mut self.arc, self.eol_bytes, &mut self.out.buf)
        {
            self.buf_real = true;
            self.out.flush_some();
            return true;
        }
        // Constant letter words without a label: straight when their G codes are.
        let straight = words.iter().all(|w| w.letter != b'G' || plain_g(w.value));
        straight && self.push_plain(meta, words, line)
    }
}

/// Translates `path` (FANUC) to Sinumerik into `out`, reading it once. On `Err` nothing
/// useful was written (the caller discards `out` and translates whole).
pub fn to_sinumerik(
    path: &Path,
    opts: &Options,
    eol: LineEnding,
    out: &mut dyn Write,
    progress: Option<ProgressFn<'_>>,
) -> Result<Streamed, Fallback> {
    to_sinumerik_first(path, opts, eol, out, progress, FIRST_STMTS)
}

/// [`to_sinumerik`] with the first `first_stmts` statements (from the first block that
/// does more than carry comments) translated whole, the rest block by block: the tests
/// set it low so that short programs go through the fast path too.
#[doc(hidden)]
pub fn to_sinumerik_first(
    path: &Path,
    opts: &Options,
    eol: LineEnding,
    out: &mut dyn Write,
    progress: Option<ProgressFn<'_>>,
    first_stmts: usize,
) -> Result<Streamed, Fallback> {
    let popts = ParseOptions { semantics: opts.source.clone() };
    let (name, head) = head(path, &popts)?;
    let bom = has_bom(path).map_err(|e| Fallback::NotStreamable(e.into()))?;
    let mut st = ToSinumerik {
        opts,
        planned: None,
        eol,
        name,
        head,
        buf: Vec::new(),
        buf_real: false,
        first: true,
        arc_at_start: false,
        arc: false,
        inch_at_start: Some(false),
        inch: Some(false),
        first_stmts: first_stmts.max(1),
        eol_bytes: eol.as_str().as_bytes(),
        line: Vec::new(),
        out: Out::new(out),
        stop: None,
        diags: Vec::new(),
        file_name: String::new(),
        program: String::new(),
        fanuc_number: None,
        symbols: SymbolMap::default(),
        extra_axes: 0,
    };
    if bom {
        st.out.buf.extend_from_slice(b"\xEF\xBB\xBF");
    }
    let (index, blocks) = straight::run(path, &popts, &mut st, progress)?;
    let [p] = index.programs.as_slice() else {
        return Err(Fallback::NotStraight("more than one program".into()));
    };
    if p.program.name != st.name || p.program.head.is_some() != st.head.is_some() {
        return Err(Fallback::NotStraight("a program head after other lines".into()));
    }
    // `header_inputs` reads a whole text by LF lines, an index's header by any line end.
    let cr = eol == LineEnding::Cr || first_line_ending(path).map_err(Fallback::NotStreamable)? == LineEnding::Cr;
    if cr && index.header.contains("nctrans:") {
        return Err(Fallback::NotStraight("`nctrans: set` lines with CR line ends".into()));
    }
    if st.first {
        // A short program (or one without blocks): all of it is the first chunk.
        let body = std::mem::take(&mut st.buf);
        st.first = false;
        st.flush_first(body);
    } else {
        st.flush();
    }
    if let Some(f) = st.stop.take() {
        return Err(f);
    }
    st.out.finish()?;
    Ok(Streamed {
        index,
        blocks,
        diags: st.diags,
        file_name: st.file_name,
        program: st.program,
        fanuc_number: st.fanuc_number,
        symbols: st.symbols,
    })
}
