//! The first scan's bookkeeping per line (`super::scan_with`): the chunks as statements
//! arrive ([`Chunker`]), and the plain top-level lines of an index-only scan read straight
//! from the read buffer ([`take_plain_run`]).

use super::index::{Chunk, ProgIndex, Resume};
use super::lines::Lines;
use super::{Progress, ProgressFn, Reader};
use crate::dialect::{fanuc, sinumerik};
use crate::span::Span;

/// An index-only scan of the plain top-level lines from here straight from the read buffer,
/// while there are such lines: for each what [`Reader::scan_plain`] would give for the line
/// [`Lines::next_line`] gives, the same change to the reader and the lines, and the index's
/// bookkeeping of `scan_with` (the line counted in `count`, `progress` told at every
/// 65536th line, where `scan_with` tells it), without making the line's text or looking at
/// its bytes twice (the dialect's `skeleton_bytes` finds the line's end as it reads it).
/// A line that is another, or not known to be such a line (see `skeleton_bytes`), ends the
/// run unread: then read it the general way. Whether any line was taken.
///
/// The run holds what does not change from line to line: taking a plain line changes
/// neither the reader's program (so `prog` and the open chunk stay) nor whether it takes
/// plain lines (`plain_ready`: the reader stays at the top level with nothing pending);
/// for FANUC not its resume state either (tape, parameter mode), so the boundary's resume
/// state is set only where it is read (a chunk opened after one closed in the run) and at
/// the end of the run, the line ends in between. (A Sinumerik line changes its resume
/// state, "code seen": the boundary is set as `Chunker::after_top` sets it.)
#[inline]
pub(super) fn take_plain_run(
    lines: &mut Lines,
    reader: &mut Reader<'_>,
    chunks: &mut Chunker,
    count: &mut u64,
    progress: &mut Option<ProgressFn<'_>>,
    size: u64,
) -> bool {
    let mut tell = Tell { count, progress, size };
    // One function each: together in one, the FANUC loop ran slower.
    match reader {
        Reader::Fan(r) if r.plain_ready() => fanuc_run(lines, r, chunks, &mut tell),
        Reader::Sin(r) if r.plain_ready() => sinumerik_run(lines, r, chunks, &mut tell),
        _ => false,
    }
}

/// Counts the lines of a run and tells `progress` as `scan_with` does.
struct Tell<'a, 'p> {
    count: &'a mut u64,
    progress: &'a mut Option<ProgressFn<'p>>,
    size: u64,
}

impl Tell<'_, '_> {
    #[inline(always)]
    fn line(&mut self, chunks: &Chunker, done: u64) {
        *self.count += 1;
        if self.count.is_multiple_of(65536) {
            if let Some(p) = self.progress.as_mut() {
                p(Progress { done, total: self.size, blocks: chunks.progs.iter().map(|p| p.ops as u64).sum() });
            }
        }
    }
}

/// [`take_plain_run`] of a Sinumerik reader that takes plain lines. One program (0);
/// a plain line changes the resume state ("code seen"): it is asked where a chunk closed.
#[inline(never)]
fn sinumerik_run(lines: &mut Lines, r: &mut sinumerik::Reader, chunks: &mut Chunker, tell: &mut Tell) -> bool {
    let mut any = false;
    loop {
        let start = lines.offset();
        let Some(found) = sinumerik::skeleton_bytes(lines.ahead()) else { break };
        let Some(t) = lines.skip_plain(found.len) else { break };
        let at = |k: usize| start as u32 + k as u32;
        let number = found.number.map(|(value, lo, hi)| crate::ir::SeqNo { value, span: Span::new(at(lo), at(hi)) });
        let span = Span::new(at(found.lo), at(found.hi));
        r.take_plain(number.as_ref(), found.words);
        tell.line(chunks, t.next);
        chunks.before(0);
        let p = &mut chunks.progs[0];
        p.add_plain(span, number.as_ref());
        debug_assert_eq!(chunks.close_at, base(p) + chunks.chunk_ops);
        if p.ops >= chunks.close_at {
            chunks.close_open(t.next);
        }
        if chunks.open.is_none() {
            chunks.boundary = (t.next, t.line + 1, Resume::Sinumerik(r.checkpoint()));
        }
        any = true;
    }
    any
}

/// [`take_plain_run`] of a FANUC reader that takes plain lines.
#[inline(never)]
fn fanuc_run(lines: &mut Lines, r: &mut fanuc::Reader, chunks: &mut Chunker, tell: &mut Tell) -> bool {
    let prog = r.current();
    let now = r.checkpoint();
    let mut any = false;
    loop {
        let start = lines.offset();
        let Some(found) = fanuc::skeleton_bytes(lines.ahead()) else { break };
        let Some(t) = lines.skip_plain(found.len) else { break };
        let at = |k: usize| start as u32 + k as u32;
        let number = found.number.map(|(value, lo, hi)| crate::ir::SeqNo { value, span: Span::new(at(lo), at(hi)) });
        let span = Span::new(at(found.lo), at(found.hi));
        r.take_plain(span, found.number.map(|n| n.0), found.words);
        tell.line(chunks, t.next);
        chunks.before(prog);
        let p = &mut chunks.progs[prog];
        p.add_plain(span, number.as_ref());
        debug_assert_eq!(chunks.close_at, base(p) + chunks.chunk_ops);
        if p.ops >= chunks.close_at {
            chunks.boundary.2 = Resume::Fanuc(now);
            chunks.close_open(t.next);
        }
        chunks.boundary.0 = t.next;
        chunks.boundary.1 = t.line + 1;
        any = true;
    }
    if any {
        chunks.boundary.2 = Resume::Fanuc(now);
    }
    any
}

/// The chunks of a scan as statements arrive.
pub(super) struct Chunker {
    pub(super) progs: Vec<ProgIndex>,
    /// The open chunk: (program, lo, line, resume state).
    pub(super) open: Option<(usize, u64, u32, Resume)>,
    /// Where the next chunk would start: (offset, line, resume state).
    pub(super) boundary: (u64, u32, Resume),
    /// Ops per chunk (at least one).
    pub(super) chunk_ops: usize,
    /// While a chunk is open: the op count of its program at which it may close (its ops
    /// reach `chunk_ops`), kept so a line need not work it out from the closed chunks.
    pub(super) close_at: usize,
}

impl Chunker {
    /// Before the statements a line finished, all of program `prog`: a chunk is open for them.
    #[inline(always)]
    pub(super) fn before(&mut self, prog: usize) {
        if !matches!(self.open, Some((p, ..)) if p == prog) {
            // The chunk open is not this program's (seldom).
            self.open_for(prog);
        }
    }

    /// [`Chunker::before`] when no chunk of program `prog` is open.
    #[inline(never)]
    fn open_for(&mut self, prog: usize) {
        while self.progs.len() <= prog {
            self.progs.push(ProgIndex::new());
        }
        // The chunks of `prog` stay as they are while its chunk is open (`close` of
        // another program's chunk below does not touch them).
        self.close_at = base(&self.progs[prog]) + self.chunk_ops;
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
    pub(super) fn after(&mut self, reader: &Reader<'_>, chunk_ops: usize, line_end: u64, next_line: u32) {
        debug_assert_eq!(chunk_ops.max(1), self.chunk_ops);
        let at_top = reader.at_top();
        if let Some((p, lo, line, resume)) = &self.open {
            debug_assert_eq!(self.close_at, base(&self.progs[*p]) + self.chunk_ops);
            if at_top && self.progs[*p].ops >= self.close_at {
                close(&mut self.progs[*p], *lo, line_end, *line, resume.clone());
                self.open = None;
            }
        }
        if at_top && (self.open.is_none() || matches!(reader, Reader::Fan(_))) {
            self.boundary = (line_end, next_line, reader.checkpoint());
        }
    }
}

impl Chunker {
    /// [`Chunker::after`] of a line read where the reader is and stays at the top level
    /// (`reader.at_top()`, which it then need not ask). The same chunks and boundaries.
    #[inline(always)]
    pub(super) fn after_top(&mut self, reader: &Reader<'_>, chunk_ops: usize, line_end: u64, next_line: u32) {
        debug_assert_eq!(chunk_ops.max(1), self.chunk_ops);
        if let Some((p, ..)) = &self.open {
            debug_assert_eq!(self.close_at, base(&self.progs[*p]) + self.chunk_ops);
            if self.progs[*p].ops >= self.close_at {
                self.close_open(line_end);
            }
        }
        match reader {
            Reader::Fan(r) => {
                // The boundary moves with every line; its resume state is set in place.
                self.boundary.0 = line_end;
                self.boundary.1 = next_line;
                let now = r.checkpoint();
                match &mut self.boundary.2 {
                    Resume::Fanuc(was) => *was = now,
                    other => *other = Resume::Fanuc(now),
                }
            }
            Reader::Sin(_) if self.open.is_none() => self.boundary = (line_end, next_line, reader.checkpoint()),
            Reader::Sin(_) => {}
        }
    }

    /// Closes the open chunk at `hi`.
    #[inline(never)]
    fn close_open(&mut self, hi: u64) {
        if let Some((p, lo, line, resume)) = self.open.take() {
            close(&mut self.progs[p], lo, hi, line, resume);
        }
    }
}

/// The op index where the next chunk of `p` starts.
fn base(p: &ProgIndex) -> usize {
    p.chunks.last().map_or(0, |c| c.op_base + c.ops)
}

pub(super) fn close(p: &mut ProgIndex, lo: u64, hi: u64, line: u32, resume: Resume) {
    let base = base(p);
    if p.ops > base {
        p.chunks.push(Chunk { lo, hi, line, op_base: base, ops: p.ops - base, resume });
    }
}
