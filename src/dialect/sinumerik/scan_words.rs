//! A streamed translator's first scan of the one line shape nearly all CAM output has
//! (`N10 G1 X0.1394 Y-0.475 F800`), read straight from the read buffer eight bytes at a
//! time: [`quick_line`] for both dialects, [`scan_words_bytes`] with Sinumerik's rules
//! (FANUC's: `fanuc::scan_words_bytes`). A line of any other shape is left to the
//! dialect's full reader (`Reader::scan_plain_words`), which takes the same decisions on
//! the lines taken here (tests: `tests/stream_words.rs` and the unit tests below).

use crate::span::Span;

/// One word as [`quick_line`] read it: upper-case letter, its digits as one whole number
/// (`mant`, at most 14 digits) with `frac` of them after the point, whether a sign
/// (`neg`: `-`) and a point were written.
#[derive(Clone, Copy, Debug)]
pub struct QWord {
    pub letter: u8,
    pub mant: u64,
    pub frac: usize,
    pub signed: bool,
    pub neg: bool,
    pub point: bool,
}

/// A line [`quick_line`] took: its length (the line end, CR or LF, follows in the buffer)
/// and its block number (value, and its letter and end as offsets into the line).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct QLine {
    pub len: usize,
    pub number: Option<(u32, usize, usize)>,
}

/// Reads the line at the start of `b` (which runs on past it: the line ends at the first
/// CR or LF) when it has the shape: an optional block number `N` + 1..=7 digits and one
/// blank, then upper-case letters each followed at once by an optional sign and at most
/// seven digits before and seven after an optional point (at least one digit), the words
/// one blank apart, nothing before the first or after the last (but the line end). `ok`
/// judges each word (not the number); `push` gets each word taken as (letter, value with
/// its sign as `read::exact` gives it, point, span from its letter to its last digit, at
/// file offset `start` + offset in the line). `None` when the line is of another shape,
/// `ok` refuses a word or the line end is not within `b`; `push` may then have had some
/// words (to be dropped). Every byte of a line taken is ASCII.
#[inline(always)]
pub fn quick_line(
    b: &[u8],
    start: u32,
    ok: impl Fn(&QWord) -> bool,
    mut push: impl FnMut(u8, f64, bool, Span),
) -> Option<QLine> {
    let mut i = 0;
    let mut number = None;
    if b.first() == Some(&b'N') {
        let w = load8(b, 1);
        let n = run(w);
        if n == 0 || n > 7 || b.get(1 + n) != Some(&b' ') {
            return None;
        }
        number = Some((value(w, n) as u32, 0, 1 + n));
        i = n + 2;
    }
    loop {
        let letter = *b.get(i)?;
        if !letter.is_ascii_uppercase() {
            return None;
        }
        let mut j = i + 1;
        let sign = b.get(j).copied().unwrap_or(0);
        let neg = sign == b'-';
        let signed = neg || sign == b'+';
        j += usize::from(signed);
        let w = load8(b, j);
        let n = run(w);
        let point = n < 8 && (w >> (8 * n)) as u8 == b'.';
        let (mant, frac);
        if !point {
            (mant, frac) = (value(w, n), 0);
            j += n;
        } else {
            // The digits on both sides of the point closed up into one word (the byte
            // after the window shifted in on top): one conversion for the number.
            let low = (1u64 << (8 * n)) - 1;
            let after = u64::from(b.get(j + 8).copied().unwrap_or(0));
            let joined = (w & low) | ((w >> 8) & !low & !(0xFF << 56)) | (after << 56);
            let all = run(joined);
            if all < 8 {
                (mant, frac) = (value(joined, all), all - n);
                j += all + 1;
            } else {
                // Longer: the digits after the point from their own window.
                let at = j + n + 1;
                let rest = load8(b, at);
                let m = run(rest);
                let p = *POW10.get(m)?;
                (mant, frac) = (value(w, n) * p + value(rest, m), m);
                j = at + m;
            }
        }
        // None is no number; eight in a run may go on (the full reader reads them).
        if n + frac == 0 || n == 8 {
            return None;
        }
        let w = QWord { letter, mant, frac, signed, neg, point };
        if !ok(&w) {
            return None;
        }
        // At most 14 digits: below 2^53, `exact` answers.
        let v = crate::read::exact(mant, frac).unwrap_or(0.0);
        push(letter, if neg { -v } else { v }, point, Span::new(start + i as u32, start + j as u32));
        match *b.get(j)? {
            b' ' => i = j + 1,
            b'\n' | b'\r' => return Some(QLine { len: j, number }),
            _ => return None,
        }
    }
}

/// [`quick_line`] with Sinumerik's rules, for `crate::stream::scan_words` (see
/// `Reader::scan_plain_words`): the line when `fast::scan_words_raw` would take it with
/// these words, this number, words, and no comment.
///
/// Why: `fast::read` reads such a line alike (a number of at most nine digits followed by a
/// blank; each word a letter, a sign, digits and a point, at most 15 digits, followed by a
/// blank and the next letter or the end) and hands `Each` the same letter, value, point and
/// span, but for the letters it declines (L, N, O, P) and M (which `Each` judges): they are
/// refused here, so the full reader takes those lines.
#[inline(always)]
pub fn scan_words_bytes(b: &[u8], start: u32, push: impl FnMut(u8, f64, bool, Span)) -> Option<QLine> {
    quick_line(b, start, |w| !matches!(w.letter, b'L' | b'M' | b'N' | b'O' | b'P'), push)
}

/// 10^0 ..= 10^7.
const POW10: [u64; 8] = [1, 10, 100, 1000, 10_000, 100_000, 1_000_000, 10_000_000];

/// The eight bytes of `s` from `i` as a little-endian word (the first byte lowest), bytes
/// past the end 0 (not a digit).
#[inline(always)]
fn load8(s: &[u8], i: usize) -> u64 {
    if let Some(Ok(w)) = s.get(i..i + 8).map(<[u8; 8]>::try_from) {
        return u64::from_le_bytes(w);
    }
    let mut w = [0u8; 8];
    let rest = s.get(i..).unwrap_or(&[]);
    for (d, &c) in w.iter_mut().zip(rest) {
        *d = c;
    }
    u64::from_le_bytes(w)
}

const LO: u64 = 0x0101_0101_0101_0101;

/// How many ASCII digits `w` starts with (its first byte lowest), 0..=8.
#[inline(always)]
fn run(w: u64) -> usize {
    // Digits become 0..=9; a byte is one exactly when it is below 10 then: adding 0x76 to
    // its low seven bits sets bit 7 from 10 on (no carry out of the byte), and bytes from
    // 0x80 on have it set already.
    let v = w ^ (LO * 0x30);
    let non = (((v & (LO * 0x7F)) + LO * 0x76) | v) & (LO * 0x80);
    (non.trailing_zeros() / 8) as usize
}

/// The whole number the first `n` bytes of `w` (digits, see [`run`]) spell.
#[inline(always)]
fn value(w: u64, n: usize) -> u64 {
    if n == 0 {
        return 0;
    }
    // The digits moved to the top bytes, zeros below them; then pairs, fours and eights of
    // digits are combined: each step's lanes hold at most 99, 9999 and 99999999, so nothing
    // carries into the next lane.
    let d = (w ^ (LO * 0x30)) << (64 - 8 * n.min(8));
    let d = (d.wrapping_mul(10).wrapping_add(d >> 8)) & 0x00FF_00FF_00FF_00FF;
    let d = (d.wrapping_mul(100).wrapping_add(d >> 16)) & 0x0000_FFFF_0000_FFFF;
    (d.wrapping_mul(10_000).wrapping_add(d >> 32)) & 0xFFFF_FFFF
}
