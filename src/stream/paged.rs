//! The evaluator's view of a streamed file: ops are read page by page (one index chunk per
//! page) by re-reading the file from the chunk's offset with the reader state saved there,
//! and flattened with absolute op indices. A few recent pages are cached, so a loop whose
//! body fits in a page or two costs no re-reading; a backward jump to a page that has left
//! the cache re-reads that one page. Jumps to block numbers are resolved in the index's runs.

use super::index::CHUNK_OPS;
use super::lines::{Input, Lines, NotStreamable};
use super::Index;
use super::RereadSink;
use crate::diag::Diagnostic;
use crate::dialect::lit::LitBlock;
use crate::eval::flow::ChunkOps;
use crate::eval::paged::{Page, PagedSource};
use crate::ir::{Search, Stmt};
use std::cell::{Cell, RefCell};
use std::collections::VecDeque;
use std::rc::Rc;
use std::sync::Arc;

/// Pages kept (the one running, the loop start it jumps back to, a few more).
const CACHE: usize = 4;

type ProgressBox = Box<dyn FnMut(super::Progress)>;

/// Reads pages of one streamed file.
pub struct Pager {
    ix: Arc<Index>,
    lines: RefCell<Option<Lines>>,
    cache: RefCell<VecDeque<Rc<Page>>>,
    /// The page and line index [`Pager::line_of`] found last (it may outlive the cache by
    /// one page).
    hint: RefCell<Option<(Rc<Page>, usize)>>,
    /// Pages read so far (for tests and benchmarks: how much re-reading happened).
    pub reads: RefCell<u64>,
    /// Lines read straight into compact ops (see [`super::reread`]).
    pub direct_lines: RefCell<u64>,
    /// Whether re-reads take the direct route (tests compare it with the general one).
    direct: Cell<bool>,
    progress: RefCell<Option<ProgressBox>>,
}

impl Pager {
    pub fn new(ix: Arc<Index>) -> Pager {
        Pager {
            ix,
            lines: RefCell::new(None),
            cache: RefCell::new(VecDeque::new()),
            hint: RefCell::new(None),
            reads: RefCell::new(0),
            direct_lines: RefCell::new(0),
            direct: Cell::new(true),
            progress: RefCell::new(None),
        }
    }

    /// Reports each page read: bytes up to the page's end, ops up to its last op.
    pub fn set_progress(&self, f: Box<dyn FnMut(super::Progress)>) {
        *self.progress.borrow_mut() = Some(f);
    }

    /// Turns the direct route of re-reads on or off (on by default; for tests that compare
    /// the two).
    pub fn set_direct(&self, on: bool) {
        self.direct.set(on);
    }

    pub fn index(&self) -> &Index {
        &self.ix
    }

    fn err(&self, e: impl std::fmt::Display) -> Diagnostic {
        Diagnostic::error("NC103", format!("cannot re-read {}: {e}", self.ix.path.display()))
            .note("a streamed program is read again where a jump or loop needs it")
            .hint("do not change or move the file while it runs")
    }

    fn read(&self, prog: usize, ci: usize) -> Result<Page, Diagnostic> {
        let chunk = &self.ix.programs[prog].chunks[ci];
        *self.reads.borrow_mut() += 1;
        let mut slot = self.lines.borrow_mut();
        if slot.is_none() {
            let f = std::fs::File::open(&self.ix.path).map_err(|e| self.err(e))?;
            let size = f.metadata().map_err(|e| self.err(e))?.len();
            if size != self.ix.size {
                return Err(self.err("its size changed since it was first read"));
            }
            *slot = Some(Lines::new(Input::File(f)).map_err(|e| self.err(e))?);
        }
        let Some(lines) = slot.as_mut() else { return Err(self.err("no reader")) };
        let mut sink = Sink {
            ops: ChunkOps::new(self.ix.file, chunk.op_base, chunk.ops),
            failed: None,
            direct: 0,
            align: &self.ix.align,
        };
        let mut starts = Vec::with_capacity(CHUNK_OPS);
        super::reread(lines, &self.ix, chunk, self.direct.get(), &mut sink, &mut |lo, line| {
            starts.push((lo as u32, line))
        })
        .map_err(|e: NotStreamable| self.err(e))?;
        if let Some(d) = sink.failed {
            return Err(d);
        }
        *self.direct_lines.borrow_mut() += sink.direct;
        let ops = sink.ops.finish();
        if let Some(p) = self.progress.borrow_mut().as_mut() {
            p(super::Progress { done: chunk.hi, total: self.ix.size, blocks: (chunk.op_base + chunk.ops) as u64 });
        }
        if ops.len() != chunk.ops {
            return Err(self.err(format!("chunk at line {} changed since it was first read", chunk.line)));
        }
        Ok(Page { prog, base: chunk.op_base, ops, lo: chunk.lo, hi: chunk.hi, lines: starts })
    }

    /// 1-based line of text offset `lo` (for trace origins), from the cached pages, else by
    /// reading the page that holds it.
    pub fn line_of(&self, lo: u32) -> Option<usize> {
        if let Some(l) = self.line_from_hint(lo) {
            return Some(l);
        }
        let at = u64::from(lo);
        // Some(index of the line in the page) when the page holds `at`.
        let hit = |p: &Page| (p.lo <= at && at < p.hi).then(|| p.lines.partition_point(|l| l.0 <= lo).checked_sub(1));
        let found = self.cache.borrow().iter().find_map(|p| hit(p).map(|i| (Rc::clone(p), i)));
        if let Some((page, i)) = found {
            let line = i.map(|i| page.lines[i].1 as usize);
            if let Some(i) = i {
                *self.hint.borrow_mut() = Some((page, i));
            }
            return line;
        }
        let mut from = (0u64, 1u32);
        for (prog, pi) in self.ix.programs.iter().enumerate() {
            let i = pi.chunks.partition_point(|c| c.lo <= at);
            let Some(c) = i.checked_sub(1).map(|i| &pi.chunks[i]) else { continue };
            if at < c.hi {
                let page = self.page(prog, c.op_base).ok()??;
                return hit(&page).flatten().map(|i| page.lines[i].1 as usize);
            }
            if c.lo >= from.0 {
                // The line after the chunk: count from its start.
                from = (c.lo, c.line);
            }
        }
        self.count_lines(from, at)
    }

    /// The line of `lo` when it is the line last found or one of the next two (a trace asks
    /// for lines in program order, so this nearly always answers without a search).
    fn line_from_hint(&self, lo: u32) -> Option<usize> {
        let mut hint = self.hint.borrow_mut();
        let (page, i) = hint.as_mut()?;
        let at = u64::from(lo);
        if !(page.lo <= at && at < page.hi) {
            return None;
        }
        let lines = &page.lines;
        for j in *i..(*i + 3).min(lines.len()) {
            let next = lines.get(j + 1).map_or(u64::MAX, |l| u64::from(l.0));
            if lines[j].0 <= lo && at < next {
                *i = j;
                return Some(lines[j].1 as usize);
            }
        }
        None
    }

    /// The line of `at` by reading lines from a known line start (outside every chunk:
    /// headers, blank and comment lines between programs, an empty program's end).
    fn count_lines(&self, from: (u64, u32), at: u64) -> Option<usize> {
        let mut slot = self.lines.borrow_mut();
        if slot.is_none() {
            let f = std::fs::File::open(&self.ix.path).ok()?;
            *slot = Some(Lines::new(Input::File(f)).ok()?);
        }
        let lines = slot.as_mut()?;
        lines.seek(from.0, from.1).ok()?;
        let mut line = from.1 as usize;
        while let Ok(Some(l)) = lines.next_line() {
            if at < l.next || l.next == l.start + l.text.len() as u64 {
                // Inside this line, or the last line (no line end after it).
                return Some(l.line as usize);
            }
            line = l.line as usize + 1;
        }
        // After a final line end (or an empty file).
        Some(line)
    }
}

impl PagedSource for Pager {
    fn dialect(&self) -> crate::dialect::Dialect {
        self.ix.dialect
    }

    fn file(&self) -> crate::span::FileId {
        self.ix.file
    }

    fn programs(&self) -> usize {
        self.ix.programs.len()
    }

    fn program(&self, prog: usize) -> &crate::ir::Program {
        &self.ix.programs[prog].program
    }

    fn labels(&self, prog: usize) -> &[(usize, String)] {
        self.ix.programs.get(prog).map_or(&[], |p| &p.labels)
    }

    fn last_span(&self, prog: usize) -> crate::span::Span {
        self.ix.programs.get(prog).map_or(crate::span::Span::default(), |p| p.last_span)
    }

    /// The page holding op `pc` of program `prog`, or `None` past its end.
    fn page(&self, prog: usize, pc: usize) -> Result<Option<Rc<Page>>, Diagnostic> {
        {
            let cache = self.cache.borrow();
            if let Some(p) = cache.iter().find(|p| p.prog == prog && pc >= p.base && pc < p.base + p.ops.len()) {
                return Ok(Some(Rc::clone(p)));
            }
        }
        let Some(pi) = self.ix.programs.get(prog) else { return Ok(None) };
        let Some(ci) = pi.chunk_of(pc) else { return Ok(None) };
        let page = Rc::new(self.read(prog, ci)?);
        let mut cache = self.cache.borrow_mut();
        if cache.len() >= CACHE {
            cache.pop_back();
        }
        cache.push_front(Rc::clone(&page));
        Ok(Some(page))
    }

    /// Jump search for block number `n` from op `from` (see `Code::find`).
    fn find_number(&self, prog: usize, from: usize, search: Search, n: u32) -> Option<usize> {
        let runs = &self.ix.programs.get(prog)?.numbers;
        let from = from as u64;
        let fwd = || runs.first_from(n, from + 1);
        let bwd = || runs.last_to(n, from);
        let head = || runs.first_from(n, 0).filter(|p| p.0 <= from);
        let hit = match search {
            Search::Forward => fwd(),
            Search::Backward => bwd(),
            Search::ForwardThenBackward => fwd().or_else(bwd),
            Search::ForwardThenWrap => fwd().or_else(head),
        };
        hit.map(|p| p.0 as usize)
    }

    /// The first op with number `n` at or after `from`, then from the top.
    fn find_number_from(&self, prog: usize, from: usize, n: u32) -> Option<usize> {
        let runs = &self.ix.programs.get(prog)?.numbers;
        runs.first_from(n, from as u64).or_else(|| runs.first_from(n, 0)).map(|p| p.0 as usize)
    }
}

/// A page's ops as a re-read makes them.
struct Sink<'a> {
    ops: ChunkOps,
    /// `Index::align`.
    align: &'a super::segmented::SourceAlign,
    /// The first error flattening a statement (the page is then not used).
    failed: Option<Diagnostic>,
    /// Lines read straight into compact ops.
    direct: u64,
}

impl RereadSink for Sink<'_> {
    fn stmt(&mut self, mut s: Stmt) {
        if !self.align.is_empty() {
            self.align.stmt(&mut s);
        }
        if self.failed.is_none() {
            self.failed = self.ops.stmt(s).err();
        }
    }

    #[inline(always)]
    fn lit(&mut self) -> Option<&mut LitBlock> {
        let l = self.ops.lit();
        self.direct += u64::from(l.is_some());
        l
    }

    fn unlit(&mut self) {
        self.direct -= 1;
        self.ops.unlit();
    }

    fn error(&mut self, d: Diagnostic) {
        if self.failed.is_none() {
            self.failed = Some(d);
        }
    }
}

impl std::fmt::Debug for Pager {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Pager({})", self.ix.path.display())
    }
}
