//! Re-reading one chunk of a streamed file for a page: its statements parsed again from
//! the file with the reader state the first scan saved there, plain lines straight into
//! compact ops where they can be (see docs/architecture.md, Streaming).

use super::index::{Chunk, Resume};
use super::lines::Lines;
use super::{Index, NotStreamable, Reader};
use crate::diag::Diagnostic;
use crate::dialect::lit::LitBlock;
use crate::dialect::{fanuc, sinumerik, Dialect};
use crate::ir::Stmt;
use crate::read::RawBlock;
use crate::span::Span;

/// Where a re-read puts what it reads.
pub trait RereadSink {
    /// The next top-level statement.
    fn stmt(&mut self, s: Stmt);
    /// A fresh compact block for the next line to be read into in place (`None`: read
    /// the line as a statement).
    fn lit(&mut self) -> Option<&mut LitBlock>;
    /// Drops the block [`RereadSink::lit`] gave last (its line was not such a block).
    fn unlit(&mut self);
    /// An error the reader reports on a line it re-reads. The first scan found none (a file
    /// with errors is not run streamed), so the file is not what was scanned, or not what
    /// was written: what is read must not be run as if it were.
    fn error(&mut self, d: Diagnostic);
}

/// Re-reads one chunk: the statements of `chunk`, parsed again from the file. With
/// `direct`, plain blocks of constant letter words at top level skip the IR and are read
/// into [`RereadSink::lit`] (the op the statement would flatten to).
/// Generic over the sink and `on_line`, so that their calls per line are inlined.
pub fn reread<S: RereadSink + ?Sized, F: FnMut(u64, u32) + ?Sized>(
    lines: &mut Lines,
    ix: &Index,
    chunk: &Chunk,
    direct: bool,
    sink: &mut S,
    on_line: &mut F,
) -> Result<(), NotStreamable> {
    lines.seek_near(chunk.lo, chunk.line)?;
    let mut stmts: Vec<Stmt> = Vec::new();
    let mut reader = match &chunk.resume {
        Resume::Sinumerik(r) => Reader::Sin(Box::new(sinumerik::Reader::resume(ix.file, &ix.opts, r))),
        Resume::Fanuc(r) => Reader::Fan(Box::new(fanuc::Reader::resume(ix.file, &ix.opts, *r))),
    };
    loop {
        // The direct route: a run of plain lines read straight from the read buffer where
        // it can be (the reader's conditions checked once for the run, what taking its
        // lines does to the reader done once after it: `Reader::quick_dialect`, `took_run`),
        // else the line as `next_line` gives it; a block made for the one is used for the
        // other.
        let mut lit = None;
        if direct {
            if lines.offset() >= chunk.hi {
                break;
            }
            if let Some(dialect) = reader.quick_dialect() {
                // A text offset fits 32 bits (the first scan refused larger files).
                let first = lines.offset() as u32;
                let mut end = first;
                // `lit` is set on each way out of the run (a block is borrowed from `sink`
                // for one line at a time only). One loop for each dialect, its quick reader
                // with its rule built in.
                macro_rules! run {
                    ($lit_buf:path) => {
                        loop {
                            let Some(b) = sink.lit() else {
                                lit = None;
                                break false;
                            };
                            let start = lines.offset() as u32;
                            // The quick reader takes only plain bytes up to a CR or LF.
                            let Some((t, len)) = $lit_buf(lines.ahead(), start, b)
                                .and_then(|len| lines.skip_plain(len).map(|t| (t, len)))
                            else {
                                b.clear();
                                lit = Some(b);
                                break false;
                            };
                            end = start + len as u32;
                            b.span = Span::new(start, end);
                            b.number = None;
                            b.line = t.line;
                            on_line(t.start, t.line);
                            if lines.offset() >= chunk.hi {
                                lit = None;
                                break true;
                            }
                        }
                    };
                }
                let chunk_end = match dialect {
                    Dialect::Sinumerik => run!(sinumerik::fast::lit_buf),
                    Dialect::Fanuc => run!(fanuc::fast::lit_buf),
                };
                if end != first {
                    reader.took_run(Span::new(first, end));
                }
                if chunk_end {
                    break;
                }
            } else if let Some(b) = sink.lit() {
                b.clear();
                lit = Some(b);
            }
        }
        let Some(l) = lines.next_line()? else {
            if lit.is_some() {
                sink.unlit();
            }
            break;
        };
        if l.start >= chunk.hi {
            if lit.is_some() {
                sink.unlit();
            }
            break;
        }
        on_line(l.start, l.line);
        let raw = RawBlock { text: l.text, start: l.start as u32, line: l.line };
        if let Some(b) = lit {
            if reader.lit(&raw, l.ascii, b) {
                continue;
            }
            sink.unlit();
        }
        reader.line(&raw);
        reader.drain_into(&mut stmts);
        for s in stmts.drain(..) {
            sink.stmt(s);
        }
    }
    // Warnings were reported by the first scan; an error now means the text changed (the
    // reader resumes with the state the first scan had at the chunk, so it judges alike).
    for d in reader.diags().iter().filter(|d| d.is_error()) {
        sink.error(d.clone());
    }
    Ok(())
}
