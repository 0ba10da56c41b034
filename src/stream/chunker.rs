//! The first scan's bookkeeping per line (`super::scan_with`): the chunks as statements
//! arrive ([`Chunker`]), and a plain top-level line of an index-only scan read straight
//! from the read buffer ([`take_plain`]).

use super::index::{Chunk, ProgIndex, Resume};
use super::lines::{self, Lines};
use super::Reader;
use crate::dialect::{fanuc, sinumerik};
use crate::span::Span;

/// An index-only scan of a plain top-level line straight from the read buffer: what
/// [`Reader::scan_plain`] would give for the line [`Lines::next_line`] gives, and the same
/// change to the reader and the lines, without making the line's text or looking at its
/// bytes twice (the dialect's `skeleton_bytes` finds the line's end as it reads it). `None`
/// (nothing read, nothing changed) when the line is another, or not known to be such a line
/// (see `skeleton_bytes`): then read it the general way.
#[inline]
pub(super) fn take_plain(
    lines: &mut Lines,
    reader: &mut Reader<'_>,
) -> Option<(lines::Taken, Span, Option<crate::ir::SeqNo>)> {
    let (found, start) = match reader {
        Reader::Sin(r) if r.plain_ready() => (sinumerik::skeleton_bytes(lines.ahead())?, lines.offset()),
        Reader::Fan(r) if r.plain_ready() => (fanuc::skeleton_bytes(lines.ahead())?, lines.offset()),
        _ => return None,
    };
    let t = lines.skip_plain(found.len)?;
    debug_assert_eq!(t.start, start);
    let at = |k: usize| start as u32 + k as u32;
    let number = found.number.map(|(value, lo, hi)| crate::ir::SeqNo { value, span: Span::new(at(lo), at(hi)) });
    let span = Span::new(at(found.lo), at(found.hi));
    match reader {
        Reader::Sin(r) => r.take_plain(number.as_ref(), found.words),
        Reader::Fan(r) => r.take_plain(span, number.as_ref().map(|n| n.value), found.words),
    }
    Some((t, span, number))
}

/// The chunks of a scan as statements arrive.
pub(super) struct Chunker {
    pub(super) progs: Vec<ProgIndex>,
    /// The open chunk: (program, lo, line, resume state).
    pub(super) open: Option<(usize, u64, u32, Resume)>,
    /// Where the next chunk would start: (offset, line, resume state).
    pub(super) boundary: (u64, u32, Resume),
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

impl Chunker {
    /// [`Chunker::after`] of a line read where the reader is and stays at the top level
    /// (`reader.at_top()`, which it then need not ask). The same chunks and boundaries.
    #[inline(always)]
    pub(super) fn after_top(&mut self, reader: &Reader<'_>, chunk_ops: usize, line_end: u64, next_line: u32) {
        if let Some((p, ..)) = &self.open {
            let prog = &self.progs[*p];
            let base = prog.chunks.last().map_or(0, |c| c.op_base + c.ops);
            if prog.ops - base >= chunk_ops.max(1) {
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

pub(super) fn close(p: &mut ProgIndex, lo: u64, hi: u64, line: u32, resume: Resume) {
    let base = p.chunks.last().map_or(0, |c| c.op_base + c.ops);
    if p.ops > base {
        p.chunks.push(Chunk { lo, hi, line, op_base: base, ops: p.ops - base, resume });
    }
}
