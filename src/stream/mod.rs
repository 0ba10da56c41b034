//! Streaming: reading, running and checking programs of any length in constant memory.
//!
//! Owns: the streamed drivers: index scan, pager, transcoding, the one straight-line
//! translation driver ([`straight`]) with what each target supplies to it ([`target`]), the
//! segmented translation ([`segmented`]) and the one streamed verification ([`verify`]).
//! May use everything below it: `read`, `dialect`, `ir`, `lower` (the targets' fast writers
//! are `lower::to_<name>::fast_write`), `eval`, `check`, `translate`; never `batch`, `config` or the CLI (`tests/layering.rs`). Nothing below imports `stream`: the
//! evaluator reads pages through `eval::paged::PagedSource`, which [`paged::Pager`] implements.
//!
//! The whole-file path (`dialect::parse`) holds the decoded text and the IR tree; for a CAM
//! program of ten million blocks that is gigabytes. Here the file is read line by line
//! through a fixed buffer ([`lines`]), each line goes through the dialect's own reader (the
//! same code as the whole-file path, so the IR is the same), and finished top-level
//! statements are handed out and dropped. A first scan builds an [`index`]: chunk offsets
//! with the reader state to resume there, labels and N numbers as runs. The evaluator then
//! executes chunk by chunk ([`paged`]), re-reading through the index what a backward jump or
//! loop end needs. The approach and its limits are in docs/architecture.md ("Streaming").

mod chunker;
pub mod index;
pub mod lines;
pub use lines::line_at;
pub mod paged;
pub mod segmented;
pub mod straight;
pub use straight::Fallback;
pub mod target;
pub mod transcode;
pub mod verify;
pub use reread::{reread, RereadSink};
mod reread;
mod words;

use crate::diag::Diagnostic;
use crate::dialect::lit::LitBlock;
use crate::dialect::{fanuc, sinumerik, Dialect, ParseOptions};
use crate::ir::{Comment, Stmt};
use crate::read::RawBlock;
use crate::span::{FileId, Span};
use chunker::{close, take_plain_run, Chunker};
pub use index::CHUNK_OPS;
use index::{ProgIndex, Resume};
use lines::{Input, Lines, NotStreamable};
use std::path::{Path, PathBuf};

pub use crate::dialect::plain::{ItemView, PlainWord, View};
pub use crate::dialect::sinumerik::scan_words::Canon;

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

/// What a first scan hands out besides the index.
enum Want<'a> {
    /// Nothing: an index-only scan.
    Index,
    /// [`Want::Index`] with every line read the general way (no [`take_plain_run`](chunker::take_plain_run)): for tests.
    IndexGeneral,
    /// Every finished top-level statement, as the whole-file reader builds it.
    Each(EachFn<'a>),
    /// Plain top-level lines as their words, the rest as statements (see [`scan_words`]).
    Words(&'a mut dyn WordsSink),
}

/// Where [`scan_words`] puts what it reads (each call with its program's index).
pub trait WordsSink {
    /// A plain top-level line of constant letter words (see [`scan_words`] for what the
    /// block holds); `false` asks for the line as a statement instead ([`WordsSink::stmt`]
    /// is then called with it, and nothing of the block is to be kept). `line` is the line
    /// read (the words' spans are offsets into the file, `line.start` that of `line.text`).
    fn plain(&mut self, prog: usize, meta: &crate::ir::BlockMeta, words: &[PlainWord], line: &RawBlock<'_>) -> bool;
    /// A finished top-level statement of any other line, as the whole-file reader builds it.
    fn stmt(&mut self, prog: usize, s: &Stmt);
    /// Whether the sink still wants anything (once `false`, it stays so: the rest of the
    /// file is read for the index only).
    fn active(&self) -> bool;
    /// Whether plain lines may be read straight from the read buffer by the quick readers
    /// (`scan_words_bytes`); `false` reads every line the general way: the same results,
    /// for the differential tests.
    fn quick(&self) -> bool {
        true
    }
    /// Whether the scan may stop reading once the sink is no longer active: its caller
    /// discards the index then (the straight-line translators, which fall back at their
    /// first line that is not straight). The index it returns covers only the lines read.
    fn abandon(&self) -> bool {
        false
    }
}

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
    /// What a run of the program changes in the statements it re-reads, as
    /// `translate::to_fanuc::align_source` does for the whole path: set for verifying a segmented
    /// translation (`segmented::SourceAlign`), empty elsewhere.
    pub align: segmented::SourceAlign,
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

    /// A words scan: [`Reader::scan_plain`] of a plain top-level line that also hands its
    /// words to `words` (appended; on `None` they are to be cleared), as
    /// `Reader::plain_words` of a re-reading reader would (for FANUC, without a block skip),
    /// in one pass (see `sinumerik::Reader::scan_plain_words`,
    /// `fanuc::Reader::scan_plain_words`). Gives the span, the number and, for Sinumerik,
    /// where the comment starts (the `;`).
    #[allow(clippy::type_complexity)]
    fn scan_plain_words(
        &mut self,
        raw: &RawBlock<'_>,
        ascii: bool,
        words: &mut Vec<PlainWord>,
    ) -> Option<(Span, Option<crate::ir::SeqNo>, Option<usize>)> {
        let push = |letter: u8, value: f64, point: bool, span: Span| {
            words.push(PlainWord { letter, value, point, span, canon: Canon::NONE });
            true
        };
        match self {
            Reader::Sin(r) => r.scan_plain_words(raw, ascii, push),
            Reader::Fan(r) => r.scan_plain_words(raw, ascii, push).map(|(span, number)| (span, number, None)),
        }
    }

    fn diags(&self) -> &[Diagnostic] {
        match self {
            Reader::Sin(r) => r.diags(),
            Reader::Fan(r) => r.diags(),
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
    /// constant letter words at top level (see `sinumerik::Reader::lit`,
    /// `fanuc::Reader::lit`); `false`
    /// when it must go through [`Reader::line`] (`b` is then to be dropped).
    fn lit(&mut self, raw: &RawBlock<'_>, ascii: bool, b: &mut LitBlock) -> bool {
        let got = match self {
            Reader::Sin(r) => r.lit(raw, ascii, b),
            Reader::Fan(r) => r.lit(raw, ascii, b),
        };
        let Some((span, number)) = got else { return false };
        b.span = span;
        b.number = number;
        b.line = raw.line;
        true
    }

    /// The dialect whose quick reader reads the next line straight from the read buffer
    /// when the reader is where it does (see `sinumerik::Reader::lit_ready`,
    /// `fanuc::Reader::lit_ready`; a line the dialect's `fast::lit_buf` then takes is
    /// taken as `lit` would take it), `None` otherwise. It holds for a whole run of such
    /// lines: taking them ([`Reader::took_run`]) changes no condition.
    #[inline(always)]
    fn quick_dialect(&self) -> Option<Dialect> {
        match self {
            Reader::Sin(r) => r.lit_ready().then_some(Dialect::Sinumerik),
            Reader::Fan(r) => r.lit_ready().then_some(Dialect::Fanuc),
        }
    }

    /// What `took_lit` of each line of a run taken by the quick reader does to the reader,
    /// at once: `span` runs from the first line's start to the last line's end. Once is as
    /// good as each time: the Sinumerik reader notes code seen, the FANUC one grows its
    /// program's span (by the smallest start and largest end: these) and marks it drained.
    fn took_run(&mut self, span: Span) {
        match self {
            Reader::Sin(r) => r.took_lit(),
            Reader::Fan(r) => r.took_lit(span),
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
    scan_with(input, size, path, file, dialect, opts, chunk_ops, Want::Each(each), progress)
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
    scan_with(input, size, path, file, dialect, opts, chunk_ops, Want::Index, progress)
}

/// [`scan_index`] reading every line through `Lines::next_line` and `Reader::scan_plain`
/// or `Reader::line`, never straight from the buffer: what the fast first scan must give
/// (for the differential tests).
#[doc(hidden)]
#[allow(clippy::too_many_arguments)]
pub fn scan_index_general(
    input: Input,
    size: u64,
    path: &Path,
    file: FileId,
    dialect: Dialect,
    opts: &ParseOptions,
    chunk_ops: usize,
) -> Result<Index, NotStreamable> {
    scan_with(input, size, path, file, dialect, opts, chunk_ops, Want::IndexGeneral, None)
}

/// The first scan for a streamed translator: the index, diagnostics and header of
/// [`scan_index`] (the same reader builds them), and for the translator each plain
/// top-level line as a block of words ([`WordsSink::plain`]), every other statement as the
/// whole-file reader builds it ([`WordsSink::stmt`]).
///
/// A plain line is one the index-only reader takes whole (`Reader::scan_plain`) and a
/// re-reading reader would read straight into its words (`Reader::plain_words`, as
/// [`reread`] with `direct` does; for FANUC, without a block skip); the index reader reads
/// both in one pass (`Reader::scan_plain_words`). The sink gets the
/// block's meta (span, number, for Sinumerik the comment after
/// the `;`) and its words ([`PlainWord`]: the items the whole-file reader builds are
/// exactly these, letter words with number values), without the line's statement. For the other lines (and a plain line
/// the sink asks to have as a statement) a whole-file reader is fed, which has then seen
/// every line but the plain ones taken as words: each of those is a top-level block that
/// the reader would have handed out at once, changing of its state only what decides
/// diagnostics (numbers as jump targets, "code seen", the program span); the diagnostics
/// reported are the index reader's, which read every line.
#[allow(clippy::too_many_arguments)]
pub fn scan_words(
    input: Input,
    size: u64,
    path: &Path,
    file: FileId,
    dialect: Dialect,
    opts: &ParseOptions,
    chunk_ops: usize,
    sink: &mut dyn WordsSink,
    progress: Option<ProgressFn<'_>>,
) -> Result<Index, NotStreamable> {
    scan_with(input, size, path, file, dialect, opts, chunk_ops, Want::Words(sink), progress)
}

/// [`scan_words`] of a file on disk with the default chunk size.
pub fn scan_words_path(
    path: &Path,
    file: FileId,
    dialect: Dialect,
    opts: &ParseOptions,
    sink: &mut dyn WordsSink,
    progress: Option<ProgressFn<'_>>,
) -> Result<Index, NotStreamable> {
    let (input, size) = open(path)?;
    scan_words(input, size, path, file, dialect, opts, CHUNK_OPS, sink, progress)
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

/// The first scan; unless [`Want::Each`], the reader builds only what the index needs.
#[allow(clippy::too_many_arguments)]
fn scan_with(
    input: Input,
    size: u64,
    path: &Path,
    file: FileId,
    dialect: Dialect,
    opts: &ParseOptions,
    chunk_ops: usize,
    mut want: Want<'_>,
    mut progress: Option<ProgressFn<'_>>,
) -> Result<Index, NotStreamable> {
    let mut lines = Lines::new(input)?;
    let bom = lines.bom();
    let text_len = size.saturating_sub(if bom { 3 } else { 0 });
    let index_only = !matches!(want, Want::Each(_));
    let new_reader = |index_only: bool| match dialect {
        Dialect::Sinumerik => {
            let mut r = sinumerik::Reader::new(file, opts, text_len.min(u64::from(u32::MAX)) as u32);
            r.compact_targets();
            if index_only {
                r.index_only();
            }
            Reader::Sin(Box::new(r))
        }
        Dialect::Fanuc => {
            let mut r = fanuc::Reader::new(file, opts);
            if index_only {
                r.index_only();
            }
            Reader::Fan(Box::new(r))
        }
    };
    let mut reader = new_reader(index_only);
    // For `Want::Words`: the whole-file reader of the lines not taken as words.
    let mut full = matches!(want, Want::Words(_)).then(|| new_reader(false));
    // Whether a words scan may read plain lines straight from the buffer (tests compare).
    let quick_words = matches!(&want, Want::Words(s) if s.quick());
    let mut meta = crate::ir::BlockMeta::default();
    let mut plain: Vec<PlainWord> = Vec::new();
    let mut chunks = Chunker {
        progs: Vec::new(),
        open: None,
        boundary: (0u64, 1u32, reader.checkpoint()),
        chunk_ops: chunk_ops.max(1),
        close_at: 0,
    };
    let mut header = String::new();
    let mut in_header = true;
    let mut count = 0u64;
    // The statements finished by one line; reused, so a line costs no new vector.
    let mut stmts: Vec<Stmt> = Vec::new();
    let mut full_stmts: Vec<Stmt> = Vec::new();
    if text_len > u64::from(u32::MAX) {
        // Spans are 32-bit offsets into the text.
        return Err(NotStreamable::TooLarge);
    }
    loop {
        // An index-only scan (or a words scan whose sink wants no more) past the header:
        // the plain top-level lines from here read straight from the buffer (see
        // `take_plain_run`).
        let index_now = match &want {
            Want::Index => true,
            Want::Words(s) if !s.active() && s.abandon() => break,
            Want::Words(s) => !s.active(),
            Want::Each(_) | Want::IndexGeneral => false,
        };
        if index_now
            && !in_header
            && take_plain_run(&mut lines, &mut reader, &mut chunks, &mut count, &mut progress, size)
        {
            continue;
        }
        // A words scan: a plain top-level line read straight from the buffer (see
        // `words::take_plain_words`).
        if quick_words && !in_header {
            if let Want::Words(s) = &mut want {
                if s.active() {
                    let mut st = words::WordsState {
                        reader: &mut reader,
                        full: &mut full,
                        chunks: &mut chunks,
                        meta: &mut meta,
                        plain: &mut plain,
                        full_stmts: &mut full_stmts,
                        chunk_ops,
                    };
                    if let Some(t) = words::take_plain_words(&mut lines, &mut st, &mut **s) {
                        count += 1;
                        if count.is_multiple_of(65536) {
                            if let Some(p) = progress.as_mut() {
                                let blocks = chunks.progs.iter().map(|p| p.ops as u64).sum();
                                p(Progress { done: t.next, total: size, blocks });
                            }
                        }
                        continue;
                    }
                }
            }
        }
        let Some(l) = lines.next_line()? else { break };
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
        // The sink of a words scan that still wants the lines.
        let (mut sink, mut each) = match &mut want {
            Want::Words(s) if s.active() => (Some(&mut **s), None),
            Want::Each(e) => (None, Some(&mut **e)),
            _ => (None, None),
        };
        if let Some(sink) = sink.as_mut() {
            // A plain top-level line: the index as an index-only scan has it, and its words.
            plain.clear();
            if let Some((span, number, comment)) = reader.scan_plain_words(&raw, l.ascii, &mut plain) {
                let prog = reader.current();
                chunks.before(prog);
                chunks.progs[prog].add_plain(span, number.as_ref());
                chunks.after(&reader, chunk_ops, line_end, l.line + 1);
                meta.span = span;
                meta.number = number;
                meta.comments.clear();
                // What the Sinumerik fast reader keeps of a comment: all after the first
                // `;`, which comes after the last word (words hold none).
                if let Some(i) = comment {
                    let span = Span::new(raw.start + i as u32, raw.start + l.text.len() as u32);
                    meta.comments.push(Comment { text: l.text[i + 1..].to_string(), span });
                }
                // A test input line goes as a statement: the target's straight test
                // leaves it to the whole translation (`own_header::is_test_input`).
                let input = meta.comments.iter().any(|c| crate::lower::own_header::is_test_input(&c.text));
                if input || !sink.plain(prog, &meta, &plain, &raw) {
                    if let Some(f) = full.as_mut() {
                        f.line(&raw);
                        full_stmts.clear();
                        f.drain_into(&mut full_stmts);
                        for s in &full_stmts {
                            sink.stmt(prog, s);
                        }
                    }
                }
                continue;
            }
        }
        // An index-only scan (or a words scan whose sink wants no more) takes a plain
        // top-level line (nearly every line of CAM code) straight to the index: the one statement `line` and a drain would give, added.
        if sink.is_none() && each.is_none() {
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
        full_stmts.clear();
        if let (Some(_), Some(f)) = (&sink, full.as_mut()) {
            f.line(&raw);
            f.drain_into(&mut full_stmts);
        }
        if stmts.is_empty() && full_stmts.is_empty() {
            continue;
        }
        let prog = reader.current();
        if let Some(sink) = sink.as_mut() {
            for s in &full_stmts {
                sink.stmt(prog, s);
            }
        }
        if stmts.is_empty() {
            continue;
        }
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
    // A words scan hands out what the whole-file reader closed at the end (the index
    // reader keeps no words in its blocks).
    let mut full_bodies: Vec<Vec<Stmt>> = match full {
        Some(Reader::Sin(r)) => vec![r.finish().0.body],
        Some(Reader::Fan(r)) => r.finish_indexed().0.unit.programs.into_iter().map(|p| p.body).collect(),
        None => Vec::new(),
    };
    let mut out = Vec::new();
    for (k, (mut p, raw)) in programs.into_iter().zip(kept).enumerate() {
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
            match &mut want {
                Want::Each(each) => p.body.iter().for_each(|s| each(raw, s)),
                Want::Words(sink) if sink.active() => match full_bodies.get_mut(k).filter(|b| !b.is_empty()) {
                    Some(body) => body.iter().for_each(|s| sink.stmt(raw, s)),
                    None => p.body.iter().for_each(|s| sink.stmt(raw, s)),
                },
                _ => {}
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
    // A program-less file is NC145 here as in the whole-file parse. Only a file whose lines
    // all look like comments or headers can be one; that (small) file is parsed whole.
    if !crate::diag::has_errors(&diags) && crate::dialect::empty::may_be_program_less(path) {
        if let Ok(bytes) = std::fs::read(path) {
            let src = crate::span::SourceFile::new(path.display().to_string(), crate::read::decode(&bytes, None).text);
            let whole = crate::dialect::parse(&src, file, dialect, opts);
            diags.extend(whole.diags.into_iter().filter(|d| d.code == "NC145"));
        }
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
        align: segmented::SourceAlign::default(),
    })
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

/// Output the streamed translators hand to their writer in pieces of about this size.
pub(crate) const WRITE_BYTES: usize = 1 << 16;

/// A streamed translator's output (straight or segmented, every target): gathered in
/// [`Out::buf`] and handed to the writer in pieces of about [`WRITE_BYTES`]. The first
/// write error is kept in [`Out::io`] (later output is dropped: the caller discards the file).
pub(crate) struct Out<'a> {
    pub(crate) buf: Vec<u8>,
    out: &'a mut dyn std::io::Write,
    pub(crate) io: Option<std::io::Error>,
}

impl<'a> Out<'a> {
    pub(crate) fn new(out: &'a mut dyn std::io::Write) -> Out<'a> {
        Out { buf: Vec::with_capacity(WRITE_BYTES + 4096), out, io: None }
    }

    /// Hands the buffer to the writer once it holds a write's worth.
    #[inline]
    pub(crate) fn flush_some(&mut self) {
        if self.buf.len() >= WRITE_BYTES {
            self.spill();
        }
    }

    /// Hands the buffer to the writer.
    pub(crate) fn spill(&mut self) {
        if self.io.is_none() {
            if let Err(e) = self.out.write_all(&self.buf) {
                self.io = Some(e);
            }
        }
        self.buf.clear();
    }

    /// Writes the rest and flushes the writer; the first write error is the fallback.
    pub(crate) fn finish(mut self) -> Result<(), Fallback> {
        self.spill();
        match self.io.map_or_else(|| self.out.flush(), Err) {
            Ok(()) => Ok(()),
            Err(e) => Err(Fallback::NotStreamable(lines::NotStreamable::Io(e))),
        }
    }
}

/// A check side that runs a streamed file (see `check::check_runners`); its pager is made
/// on the thread that runs it.
pub fn runner(
    ix: std::sync::Arc<Index>,
    mut callees: Box<dyn crate::eval::CalleeSource + Send>,
    opts: crate::eval::RunOptions,
) -> crate::check::Runner {
    crate::check::Runner::new(ix.file, move |db, sink| {
        let pager = std::rc::Rc::new(paged::Pager::new(ix));
        crate::eval::run_stream(db, pager, callees.as_mut(), &opts, sink)
    })
}
