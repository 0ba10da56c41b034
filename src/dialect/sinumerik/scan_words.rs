//! A streamed translator's first scan of the one line shape nearly all CAM output has
//! (`N10 G1 X0.1394 Y-0.475 F800`), read straight from the read buffer eight bytes at a
//! time: [`quick_line`] for both dialects, [`scan_words_bytes`] with Sinumerik's rules
//! (FANUC's: `fanuc::scan_words_bytes`). A line of any other shape is left to the
//! dialect's full reader (`Reader::scan_plain_words`), which takes the same decisions on
//! the lines taken here (tests: `tests/stream_words.rs` and the unit tests below).

use crate::dialect::quick::{load8, run, value, word_number, Num};
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

/// A word's text in the writers' canonical form, found while [`quick_line`] reads it (the
/// word's bytes are at hand then): the letter, `-` when negative, the integer digits, a
/// point, the fraction digits without their trailing zeros: `bytes()[..len]` (the rest
/// is whatever followed in the text).
/// Only for a literal already so written up to its trailing zeros and point: no `+`, at
/// least one integer digit and no leading zero before another one, not zero. `len == 0`:
/// not known (the writers then look at the text themselves, `dialect::digits`).
///
/// Why these are the writers' digits: see `dialect::digits` (a literal of at most 15
/// digits is the shortest decimal of its double, up to leading and trailing zeros).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Canon {
    /// `bytes` (see [`Canon::bytes`]) as two integers, first byte lowest.
    pub lo: u64,
    pub hi: u64,
    /// Bytes of the form with its point (`X-1.5`: 5, `F800`: 5 as `F800.`); 0: not known.
    pub len: u8,
    /// Where the point is (letter, sign and integer digits before it).
    pub dot: u8,
    /// Significant digits written (integer and fraction, the `0` of `0.5` counted).
    pub sig: u8,
}

impl Canon {
    /// Not known.
    pub const NONE: Canon = Canon { lo: 0, hi: 0, len: 0, dot: 0, sig: 0 };

    /// The 16 bytes: the form, then whatever followed in the text.
    #[inline(always)]
    pub fn bytes(&self) -> [u8; 16] {
        (u128::from(self.hi) << 64 | u128::from(self.lo)).to_le_bytes()
    }

    /// The canonical form of the word at `b[i..j]`, read by `word_number` as `num`: `NONE`
    /// when the literal is not already in that form or fewer than 16 bytes follow `i`.
    #[inline(always)]
    fn of(b: &[u8], i: usize, j: usize, num: &Num) -> Canon {
        let s = usize::from(num.neg);
        let digits = j - i - 1 - usize::from(num.signed) - usize::from(num.point);
        let n_int = digits.wrapping_sub(num.frac);
        // A `+` (signed, not negative), no integer digit or more than 7, zero.
        if num.signed != num.neg || n_int.wrapping_sub(1) >= 7 || num.mant == 0 {
            return Canon::NONE;
        }
        // The word's 16 bytes as two integers, changed in registers: a byte stored into
        // them in memory and read back whole stalls the load (store forwarding fails).
        let (Some(Ok(lo)), Some(Ok(hi))) =
            (b.get(i..i + 8).map(<[u8; 8]>::try_from), b.get(i + 8..i + 16).map(<[u8; 8]>::try_from))
        else {
            return Canon::NONE;
        };
        let (mut lo, mut hi) = (u64::from_le_bytes(lo), u64::from_le_bytes(hi));
        let dot = 1 + s + n_int;
        // A leading zero before another integer digit.
        if n_int > 1 && b.get(i + 1 + s) == Some(&b'0') {
            return Canon::NONE;
        }
        // Without the fraction's trailing zeros (the point FANUC writes in its place
        // when the literal has none; the writers cut off what follows `len`).
        let mut nf = num.frac;
        if dot + nf >= 16 {
            return Canon::NONE;
        }
        while nf > 0 && b.get(i + dot + nf) == Some(&b'0') {
            nf -= 1;
        }
        if dot < 8 {
            lo = (lo & !(0xff << (8 * dot))) | (u64::from(b'.') << (8 * dot));
        } else {
            hi = (hi & !(0xff << (8 * (dot - 8)))) | (u64::from(b'.') << (8 * (dot - 8)));
        }
        Canon { lo, hi, len: (dot + 1 + nf) as u8, dot: dot as u8, sig: (n_int + nf) as u8 }
    }
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
    mut push: impl FnMut(u8, f64, bool, Span, Canon),
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
        let num = word_number(b, i + 1)?;
        let Num { mant, frac, neg, signed, point, end: j } = num;
        let w = QWord { letter, mant, frac, signed, neg, point };
        if !ok(&w) {
            return None;
        }
        // At most 14 digits: below 2^53, `exact` answers.
        let v = crate::read::exact(mant, frac).unwrap_or(0.0);
        let canon = Canon::of(b, i, j, &num);
        push(letter, if neg { -v } else { v }, point, Span::new(start + i as u32, start + j as u32), canon);
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
pub fn scan_words_bytes(b: &[u8], start: u32, push: impl FnMut(u8, f64, bool, Span, Canon)) -> Option<QLine> {
    quick_line(b, start, |w| !matches!(w.letter, b'L' | b'M' | b'N' | b'O' | b'P'), push)
}
