//! Streaming: reading, running and checking programs of any length in constant memory.
//!
//! The whole-file path (`dialect::parse`) holds the decoded text and the IR tree; for a CAM
//! program of ten million blocks that is gigabytes. Here the file is read line by line
//! through a fixed buffer ([`lines`]), each line goes through the dialect's own reader (the
//! same code as the whole-file path, so the IR is the same), and finished top-level
//! statements are handed out and dropped. A first scan builds an [`index`]: chunk offsets
//! with the reader state to resume there, labels and N numbers as runs. The evaluator then
//! executes chunk by chunk ([`paged`]), re-reading through the index what a backward jump or
//! loop end needs. The approach and its limits are in docs/architecture.md ("Streaming").

pub mod index;
pub mod lines;
pub mod paged;
pub mod runs;
pub mod to_sinumerik;
pub mod translate;

use crate::diag::Diagnostic;
use crate::dialect::{fanuc, sinumerik, Dialect, ParseOptions};
use crate::eval::lit::LitBlock;
use crate::ir::Stmt;
use crate::read::RawBlock;
use crate::span::{FileId, Span};
pub use index::CHUNK_OPS;
use index::{Chunk, ProgIndex, Resume};
use lines::{Input, Lines, NotStreamable};
use std::path::{Path, PathBuf};

/// Where a scan is, for a progress line (the library reports, `main.rs` renders).
#[derive(Clone, Copy, Debug)]
pub struct Progress {
    /// Text bytes read.
    pub done: u64,
    /// File size in bytes.
    pub total: u64,
    /// Blocks (ops) read so far.
    pub blocks: u64,
}

/// Called now and then during a scan or run (every 64 Ki lines).
pub type ProgressFn<'a> = &'a mut dyn FnMut(Progress);

/// Called with each finished top-level statement during a scan (and its program's index).
type EachFn<'a> = &'a mut dyn FnMut(usize, &Stmt);

/// A streamed file after its first scan.
#[derive(Clone, Debug)]
pub struct Index {
    pub dialect: Dialect,
    pub file: FileId,
    pub path: PathBuf,
    pub opts: ParseOptions,
    /// File size in bytes.
    pub size: u64,
    /// Length of the decoded text (the size without a byte-order mark).
    pub text_len: u64,
    pub bom: bool,
    pub programs: Vec<ProgIndex>,
    /// Blocks as `ir::visit::count_blocks` counts them.
    pub blocks: u64,
    /// Every diagnostic of the file. Spans are exact for presence but, when not empty, the
    /// caller should read the file whole to render them (rendering needs the text).
    pub diags: Vec<Diagnostic>,
    /// `; nctrans: set …` header comment lines (evaluator inputs), as text.
    pub header: String,
}

/// The dialect reader behind a scan.
enum Reader<'o> {
    Sin(Box<sinumerik::Reader>),
    Fan(Box<fanuc::Reader<'o>>),
}

impl Reader<'_> {
    fn line(&mut self, raw: &RawBlock<'_>) {
        match self {
            Reader::Sin(r) => r.line(raw),
            Reader::Fan(r) => r.line(raw),
        }
    }

    /// An index-only scan: a plain top-level line read straight to its span and number
    /// (see `sinumerik::Reader::scan_plain`, `fanuc::Reader::scan_plain`).
    fn scan_plain(&mut self, raw: &RawBlock<'_>, ascii: bool) -> Option<(Span, Option<crate::ir::SeqNo>)> {
        match self {
            Reader::Sin(r) => r.scan_plain(raw, ascii),
            Reader::Fan(r) => r.scan_plain(raw, ascii),
        }
    }

    fn drain_into(&mut self, out: &mut Vec<Stmt>) {
        match self {
            Reader::Sin(r) => r.drain_into(out),
            Reader::Fan(r) => r.drain_into(out),
        }
    }

    fn current(&self) -> usize {
        match self {
            Reader::Sin(_) => 0,
            Reader::Fan(r) => r.current(),
        }
    }

    fn at_top(&self) -> bool {
        match self {
            Reader::Sin(r) => r.at_top(),
            Reader::Fan(r) => r.at_top(),
        }
    }

    /// Re-reading: `raw` straight into the compact op `b` when it is a plain block of
    /// constant letter words at top level (see `sinumerik::Reader::plain_words`,
    /// `fanuc::Reader::plain_words`); `false`
    /// when it must go through [`Reader::line`] (`b` is then to be dropped).
    fn lit(&mut self, raw: &RawBlock<'_>, ascii: bool, b: &mut LitBlock) -> bool {
        match self {
            Reader::Sin(r) => {
                let Some((span, number)) =
                    r.plain_words(raw, ascii, |letter, value, point, span| b.push(letter, value, point, span))
                else {
                    return false;
                };
                b.span = span;
                b.number = number;
                true
            }
            Reader::Fan(r) => {
                let Some((span, number)) =
                    r.plain_words(raw, ascii, |letter, value, point, span| b.push(letter, value, point, span))
                else {
                    return false;
                };
                b.span = span;
                b.number = number;
                true
            }
        }
    }

    fn checkpoint(&self) -> Resume {
        match self {
            Reader::Sin(r) => Resume::Sinumerik(r.checkpoint()),
            Reader::Fan(r) => Resume::Fanuc(r.checkpoint()),
        }
    }
}

/// Opens `path` for streaming.
pub fn open(path: &Path) -> Result<(Input, u64), NotStreamable> {
    let f = std::fs::File::open(path)?;
    let size = f.metadata()?.len();
    Ok((Input::File(f), size))
}

/// [`scan`] of a file on disk with the default chunk size.
pub fn scan_path(
    path: &Path,
    file: FileId,
    dialect: Dialect,
    opts: &ParseOptions,
    each: &mut dyn FnMut(usize, &Stmt),
    progress: Option<ProgressFn<'_>>,
) -> Result<Index, NotStreamable> {
    let (input, size) = open(path)?;
    scan(input, size, path, file, dialect, opts, CHUNK_OPS, each, progress)
}

/// The first scan: reads the whole file once, hands every finished top-level statement to
/// `each` (with its program's index among the programs started so far) and builds the index.
#[allow(clippy::too_many_arguments)]
pub fn scan(
    input: Input,
    size: u64,
    path: &Path,
    file: FileId,
    dialect: Dialect,
    opts: &ParseOptions,
    chunk_ops: usize,
    each: &mut dyn FnMut(usize, &Stmt),
    progress: Option<ProgressFn<'_>>,
) -> Result<Index, NotStreamable> {
    scan_with(input, size, path, file, dialect, opts, chunk_ops, Some(each), progress)
}

/// [`scan`] for a caller that needs only the index (`parse --summary`, `run`, `check`):
/// the same index, diagnostics and header, but plain blocks are read without building
/// their items, which the index does not hold (the chunks are read again for running).
#[allow(clippy::too_many_arguments)]
pub fn scan_index(
    input: Input,
    size: u64,
    path: &Path,
    file: FileId,
    dialect: Dialect,
    opts: &ParseOptions,
    chunk_ops: usize,
    progress: Option<ProgressFn<'_>>,
) -> Result<Index, NotStreamable> {
    scan_with(input, size, path, file, dialect, opts, chunk_ops, None, progress)
}

/// [`scan_index`] of a file on disk with the default chunk size.
pub fn scan_index_path(
    path: &Path,
    file: FileId,
    dialect: Dialect,
    opts: &ParseOptions,
    progress: Option<ProgressFn<'_>>,
) -> Result<Index, NotStreamable> {
    let (input, size) = open(path)?;
    scan_index(input, size, path, file, dialect, opts, CHUNK_OPS, progress)
}

/// The first scan; without `each` the reader builds only what the index needs.
#[allow(clippy::too_many_arguments)]
fn scan_with(
    input: Input,
    size: u64,
    path: &Path,
    file: FileId,
    dialect: Dialect,
    opts: &ParseOptions,
    chunk_ops: usize,
    mut each: Option<EachFn<'_>>,
    mut progress: Option<ProgressFn<'_>>,
) -> Result<Index, NotStreamable> {
    let mut lines = Lines::new(input)?;
    let bom = lines.bom();
    let text_len = size.saturating_sub(if bom { 3 } else { 0 });
    let mut reader = match dialect {
        Dialect::Sinumerik => {
            let mut r = sinumerik::Reader::new(file, opts, text_len.min(u64::from(u32::MAX)) as u32);
            r.compact_targets();
            if each.is_none() {
                r.index_only();
            }
            Reader::Sin(Box::new(r))
        }
        Dialect::Fanuc => {
            let mut r = fanuc::Reader::new(file, opts);
            if each.is_none() {
                r.index_only();
            }
            Reader::Fan(Box::new(r))
        }
    };
    let mut chunks = Chunker { progs: Vec::new(), open: None, boundary: (0u64, 1u32, reader.checkpoint()) };
    let mut header = String::new();
    let mut in_header = true;
    let mut count = 0u64;
    // The statements finished by one line; reused, so a line costs no new vector.
    let mut stmts: Vec<Stmt> = Vec::new();
    if text_len > u64::from(u32::MAX) {
        // Spans are 32-bit offsets into the text.
        return Err(NotStreamable::TooLarge);
    }
    while let Some(l) = lines.next_line()? {
        if in_header {
            in_header = header_line(l.text, &mut header);
        }
        let raw = RawBlock { text: l.text, start: l.start as u32, line: l.line };
        let line_end = l.next;
        count += 1;
        if count.is_multiple_of(65536) {
            if let Some(p) = progress.as_mut() {
                p(Progress { done: line_end, total: size, blocks: chunks.progs.iter().map(|p| p.ops as u64).sum() });
            }
        }
        // An index-only scan takes a plain top-level line (nearly every line of CAM code)
        // straight to the index: the one statement `line` and a drain would give, added.
        if each.is_none() {
            if let Some((span, number)) = reader.scan_plain(&raw, l.ascii) {
                let prog = reader.current();
                chunks.before(prog);
                chunks.progs[prog].add_plain(span, number.as_ref());
                chunks.after(&reader, chunk_ops, line_end, l.line + 1);
                continue;
            }
        }
        reader.line(&raw);
        stmts.clear();
        reader.drain_into(&mut stmts);
        if stmts.is_empty() {
            continue;
        }
        let prog = reader.current();
        chunks.before(prog);
        for s in &stmts {
            if let Some(each) = each.as_mut() {
                each(prog, s);
            }
            chunks.progs[prog].add(s);
        }
        chunks.after(&reader, chunk_ops, line_end, l.line + 1);
    }
    let Chunker { mut progs, mut open, .. } = chunks;
    if let Some((p, lo, line, resume)) = open.take() {
        close(&mut progs[p], lo, lines.offset(), line, resume);
    }
    if lines.controls * 20 > lines.offset().max(1) {
        return Err(NotStreamable::Binary);
    }
    // The end of the file: what is still open is closed (with diagnostics) by the reader.
    let (programs, kept, mut diags) = match reader {
        Reader::Sin(r) => {
            let (p, d) = r.finish();
            (vec![p], vec![0], d)
        }
        Reader::Fan(r) => {
            let (parsed, kept) = r.finish_indexed();
            (parsed.unit.programs, kept, parsed.diags)
        }
    };
    let mut out = Vec::new();
    for (mut p, raw) in programs.into_iter().zip(kept) {
        let mut ix = if raw < progs.len() { std::mem::take(&mut progs[raw]) } else { ProgIndex::new() };
        ix.raw = raw;
        if !p.body.is_empty() {
            // Statements closed only at the end of the file (an unclosed structure, an
            // error) are not in any chunk: the caller must not run this file streamed.
            diags.push(
                Diagnostic::error("NC102", "unclosed structure at the end of a streamed file")
                    .primary(file, p.span, "here")
                    .hint("read the file whole to see the full diagnostics"),
            );
            if let Some(each) = each.as_mut() {
                for s in &p.body {
                    each(raw, s);
                }
            }
        }
        p.body = Vec::new();
        ix.program = p;
        out.push(ix);
    }
    let blocks = out.iter().map(|p| p.ops as u64 + u64::from(p.program.head.is_some())).sum();
    if let Some(p) = progress.as_mut() {
        p(Progress { done: lines.offset(), total: size, blocks });
    }
    diags.sort_by_key(|d| d.labels.iter().find(|l| l.primary).map_or(u32::MAX, |l| l.span.lo));
    Ok(Index {
        dialect,
        file,
        path: path.to_path_buf(),
        opts: opts.clone(),
        size,
        text_len,
        bom,
        programs: out,
        blocks,
        diags,
        header,
    })
}

/// The chunks of a scan as statements arrive.
struct Chunker {
    progs: Vec<ProgIndex>,
    /// The open chunk: (program, lo, line, resume state).
    open: Option<(usize, u64, u32, Resume)>,
    /// Where the next chunk would start: (offset, line, resume state).
    boundary: (u64, u32, Resume),
}

impl Chunker {
    /// Before the statements a line finished, all of program `prog`: a chunk is open for them.
    #[inline]
    fn before(&mut self, prog: usize) {
        if matches!(self.open, Some((p, ..)) if p == prog) {
            // The chunk open is this program's (nearly always).
            return;
        }
        while self.progs.len() <= prog {
            self.progs.push(ProgIndex::new());
        }
        let boundary = &self.boundary;
        self.open = Some(match self.open.take() {
            Some((p, lo, line, resume)) if p != prog => {
                // A new program: the old chunk ends after its last statement.
                close(&mut self.progs[p], lo, boundary.0, line, resume);
                (prog, boundary.0, boundary.1, boundary.2.clone())
            }
            Some(o) => o,
            None => (prog, boundary.0, boundary.1, boundary.2.clone()),
        });
    }

    /// After them: the chunk closes when it is long enough and no structure is open; the
    /// next line (number `next_line`, at `line_end`) may then start the next one.
    #[inline]
    fn after(&mut self, reader: &Reader<'_>, chunk_ops: usize, line_end: u64, next_line: u32) {
        let at_top = reader.at_top();
        if let Some((p, lo, line, resume)) = &self.open {
            let base = self.progs[*p].chunks.last().map_or(0, |c| c.op_base + c.ops);
            if at_top && self.progs[*p].ops - base >= chunk_ops.max(1) {
                close(&mut self.progs[*p], *lo, line_end, *line, resume.clone());
                self.open = None;
            }
        }
        if at_top && (self.open.is_none() || matches!(reader, Reader::Fan(_))) {
            self.boundary = (line_end, next_line, reader.checkpoint());
        }
    }
}

fn close(p: &mut ProgIndex, lo: u64, hi: u64, line: u32, resume: Resume) {
    let base = p.chunks.last().map_or(0, |c| c.op_base + c.ops);
    if p.ops > base {
        p.chunks.push(Chunk { lo, hi, line, op_base: base, ops: p.ops - base, resume });
    }
}

/// Collects `; nctrans: set …` / `(nctrans: set …)` header lines (see
/// `eval::header_inputs`); returns whether the header may continue.
fn header_line(text: &str, header: &mut String) -> bool {
    let t = text.trim();
    let comment = t.is_empty()
        || t.starts_with('%')
        || t.starts_with(';')
        || t.starts_with('(')
        || t.starts_with('O')
        || t.starts_with("PROC");
    if comment && header.len() < 64 * 1024 {
        header.push_str(text);
        header.push('\n');
    }
    comment
}

/// Where a re-read puts what it reads.
pub trait RereadSink {
    /// The next top-level statement.
    fn stmt(&mut self, s: Stmt);
    /// A fresh compact block for the next line to be read into in place (`None`: read
    /// the line as a statement).
    fn lit(&mut self) -> Option<&mut LitBlock>;
    /// Drops the block [`RereadSink::lit`] gave last (its line was not such a block).
    fn unlit(&mut self);
}

/// Re-reads one chunk: the statements of `chunk`, parsed again from the file. With
/// `direct`, plain blocks of constant letter words at top level skip the IR and are read
/// into [`RereadSink::lit`] (the op the statement would flatten to).
pub fn reread(
    lines: &mut Lines,
    ix: &Index,
    chunk: &Chunk,
    direct: bool,
    sink: &mut dyn RereadSink,
    on_line: &mut dyn FnMut(u64, u32),
) -> Result<(), NotStreamable> {
    lines.seek(chunk.lo, chunk.line)?;
    let mut stmts: Vec<Stmt> = Vec::new();
    let mut reader = match &chunk.resume {
        Resume::Sinumerik(r) => Reader::Sin(Box::new(sinumerik::Reader::resume(ix.file, &ix.opts, r))),
        Resume::Fanuc(r) => Reader::Fan(Box::new(fanuc::Reader::resume(ix.file, &ix.opts, *r))),
    };
    while let Some(l) = lines.next_line()? {
        if l.start >= chunk.hi {
            break;
        }
        on_line(l.start, l.line);
        let raw = RawBlock { text: l.text, start: l.start as u32, line: l.line };
        if direct {
            if let Some(b) = sink.lit() {
                if reader.lit(&raw, l.ascii, b) {
                    continue;
                }
                sink.unlit();
            }
        }
        reader.line(&raw);
        reader.drain_into(&mut stmts);
        for s in stmts.drain(..) {
            sink.stmt(s);
        }
    }
    Ok(())
}

/// A span that marks "somewhere in this file" for diagnostics without text.
pub fn file_span(ix: &Index) -> Span {
    Span::new(0, ix.text_len.min(u64::from(u32::MAX)) as u32)
}

/// A check side that runs a streamed file (see `check::check_runners`); its pager is made
/// on the thread that runs it.
pub fn runner(
    ix: std::sync::Arc<Index>,
    mut callees: Box<dyn crate::eval::CalleeSource + Send>,
    opts: crate::eval::RunOptions,
) -> crate::check::Runner {
    Box::new(move |db, sink| {
        let pager = std::rc::Rc::new(paged::Pager::new(ix));
        crate::eval::run_stream(db, pager, callees.as_mut(), &opts, sink)
    })
}

/// The line holding text offset `lo` of a file on disk: its number, start offset and text,
/// read line by line from the start (constant memory; for rendering a few diagnostics of a
/// streamed file without loading it).
pub fn line_at(path: &Path, lo: u32) -> Option<(u32, u64, String)> {
    let (input, _) = open(path).ok()?;
    let mut lines = Lines::new(input).ok()?;
    let at = u64::from(lo);
    let mut last = None;
    while let Ok(Some(l)) = lines.next_line() {
        let found = at < l.next || l.next == l.start + l.text.len() as u64;
        last = Some((l.line, l.start, l.text.to_string()));
        if found {
            break;
        }
    }
    last
}
