//! A streamed translator's first scan (`super::scan_words`) of a plain top-level line
//! straight from the read buffer ([`take_plain_words`]): the line is read once, by the
//! dialect's quick reader (`scan_words_bytes`), where the general way splits it off
//! (`Lines::next_line`) and then reads it (`Reader::scan_plain_words`).

use super::chunker::Chunker;
use super::lines::{Lines, Taken};
use super::{PlainWord, Reader, WordsSink};
use crate::dialect::{fanuc, sinumerik};
use crate::ir::{BlockMeta, Stmt};
use crate::read::RawBlock;
use crate::span::Span;

/// What the words branch of `scan_with` keeps from line to line.
pub(super) struct WordsState<'r, 'o> {
    pub reader: &'r mut Reader<'o>,
    /// The whole-file reader of the lines not taken as words.
    pub full: &'r mut Option<Reader<'o>>,
    pub chunks: &'r mut Chunker,
    pub meta: &'r mut BlockMeta,
    pub plain: &'r mut Vec<PlainWord>,
    pub full_stmts: &'r mut Vec<Stmt>,
    pub chunk_ops: usize,
}

/// The next line, when it is one the quick reader takes and the reader is where
/// `Reader::scan_plain_words` reads lines (see `Reader::plain_ready`): exactly what the
/// general words branch of `scan_with` does with it (the index, the reader, the sink), and
/// the line moved past. `None` (nothing read, nothing changed but `plain`) otherwise: then
/// read the line the general way.
///
/// Why it is the same: the quick readers take only lines that `scan_plain_words` takes
/// with the same words, number, block span and no comment (see `scan_words_bytes`), which
/// change the reader only as `take_plain` does; the line is ASCII (so `ascii` holds, and the
/// text is what `next_line` gives), and `peek_plain` moves as `next_line` would.
#[inline]
pub(super) fn take_plain_words(
    lines: &mut Lines,
    st: &mut WordsState<'_, '_>,
    sink: &mut dyn WordsSink,
) -> Option<Taken> {
    let start = lines.offset() as u32;
    st.plain.clear();
    let plain = &mut *st.plain;
    let push = |letter, value, point, span, canon| plain.push(PlainWord { letter, value, point, span, canon });
    let ahead = lines.ahead();
    let found = match &*st.reader {
        Reader::Sin(r) if r.plain_ready() => sinumerik::scan_words::scan_words_bytes(ahead, start, push)?,
        Reader::Fan(r) if r.plain_ready() => fanuc::scan_words::scan_words_bytes(ahead, start, push)?,
        _ => return None,
    };
    let t = lines.peek_plain(found.len)?;
    let bytes = lines.ahead().get(..found.len)?;
    debug_assert!(bytes.is_ascii());
    // SAFETY: `quick_line` took the line only after looking at each of its `found.len`
    // bytes and finding an upper-case letter, a digit, a sign, a point or a blank: all
    // ASCII, which is valid UTF-8 on its own. Checking again costs a tenth of the scan.
    let text = unsafe { std::str::from_utf8_unchecked(bytes) };
    let raw = RawBlock { text, start, line: t.line };
    let at = |k: usize| start + k as u32;
    let number = found.number.map(|(value, lo, hi)| crate::ir::SeqNo { value, span: Span::new(at(lo), at(hi)) });
    let span = Span::new(start, at(found.len));
    match &mut *st.reader {
        Reader::Sin(r) => r.take_plain(number.as_ref(), true),
        Reader::Fan(r) => r.take_plain(span, number.as_ref().map(|n| n.value), true),
    }
    let prog = st.reader.current();
    st.chunks.before(prog);
    st.chunks.progs[prog].add_plain(span, number.as_ref());
    // Read only at the top level, where the reader stays.
    st.chunks.after_top(st.reader, st.chunk_ops, t.next, t.line + 1);
    st.meta.span = span;
    st.meta.number = number;
    st.meta.comments.clear();
    if !sink.plain(prog, st.meta, st.plain, &raw) {
        if let Some(f) = st.full.as_mut() {
            f.line(&raw);
            st.full_stmts.clear();
            f.drain_into(st.full_stmts);
            for s in st.full_stmts.iter() {
                sink.stmt(prog, s);
            }
        }
    }
    lines.skip_peeked(t);
    Some(t)
}
