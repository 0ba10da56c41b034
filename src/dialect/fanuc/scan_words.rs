//! A streamed translator's first scan of a plain CAM line straight from the read buffer,
//! with FANUC's rules: the quick reader (`sinumerik::scan_words::quick_line`) and what
//! `fast::scan_words_raw` would decide on the lines it takes.

use crate::dialect::sinumerik::scan_words::{quick_line, Canon, QLine, QWord};
use crate::span::Span;

/// [`quick_line`] with FANUC's rules, for `crate::stream::scan_words` (see
/// `Reader::scan_plain_words`): the line when `fast::scan_words_raw` would take it with
/// these words and this number (its block then spans the whole line: no skip, no blank
/// at either end, no `;`).
///
/// Why: `fast::plain_words` reads such a line alike (each word a letter, a sign, digits
/// and a point, at most 15 digits, followed by a blank and the next letter or the end)
/// and hands `each` the same letter, value, point and span, but for the words it judges:
/// an N word only first and as a number 1..=99999 (checked here), O and M words, and G10,
/// G65, G66 and G67 written without sign or point (refused here, so the full reader
/// takes those lines).
#[inline(always)]
pub fn scan_words_bytes(b: &[u8], start: u32, push: impl FnMut(u8, f64, bool, Span, Canon)) -> Option<QLine> {
    let ok = |w: &QWord| match w.letter {
        b'N' | b'O' | b'M' => false,
        b'G' => w.point || w.signed || !matches!(w.mant, 10 | 65 | 66 | 67),
        _ => true,
    };
    let line = quick_line(b, start, ok, push)?;
    match line.number {
        Some((n, ..)) if !(1..=99_999).contains(&n) => None,
        _ => Some(line),
    }
}
