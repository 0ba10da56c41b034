//! A quick reader for the one shape nearly every line of CAM output has, `G1 X0.1394
//! Y-0.475 Z-0.0225 F800`, for the streamed re-read of both dialects only (see
//! `sinumerik::fast::lit_raw`, `fanuc::fast::lit_block`): upper-case letters, each
//! followed at once by an optional sign and at most seven digits before and seven after an
//! optional point (up to seven in all are read in one go), the words one blank apart,
//! nothing before the first or after the last.
//! It reads eight bytes at a time where the dialects' readers go byte by byte. A line of
//! any other shape, or with a word its dialect's `ok` refuses, is left to the dialect's
//! full reader, which then takes exactly the same decisions on it as before; on the lines
//! this reader takes, the full reader would give exactly these words (tests: the dialects'
//! `quick_*` tests compare both on generated lines, tests/stream_direct.rs the pages).

use crate::dialect::lit::{milli, LitBlock, NO_MILLI};
use crate::span::Span;

/// Which words a dialect's full reader reads alike (the others, the quick reader leaves to
/// it): a letter whose bit (`1 << (letter - b'A')`) is set in `refuse` is not taken, nor
/// with `g_macro` a `G10`, `G65`, `G66` or `G67` written without sign or point. Plain data
/// checked in line, not a callback (a callback per word was not inlined).
#[derive(Clone, Copy, Debug)]
pub struct Rule {
    pub refuse: u32,
    pub g_macro: bool,
}

impl Rule {
    /// The bits of `letters` for [`Rule::refuse`].
    pub const fn letters(letters: &[u8]) -> u32 {
        let mut m = 0;
        let mut k = 0;
        while k < letters.len() {
            m |= 1 << (letters[k] - b'A');
            k += 1;
        }
        m
    }
}

/// Reads the line `text` (starting at file offset `start`) into `b` when it has the shape
/// above and `rule` takes each word; `false` otherwise, and then `b` may hold some of its
/// words (to be cleared). Each word is pushed as the dialects' readers push it: value
/// `read::exact(mant, frac)` with its sign, point, thousandths from the digits, span from
/// its letter to its last digit.
#[inline(always)]
pub fn lit_words(text: &str, start: u32, b: &mut LitBlock, rule: Rule) -> bool {
    words::<false>(text.as_bytes(), 0, start, b, rule).is_some()
}

/// [`lit_words`] on a line read straight from a read buffer (`crate::stream::reread`):
/// `s` starts at the line's start and runs on past its end, which is the first CR or LF.
/// Gives the line's length (the offset of its CR or LF) when [`lit_words`] would take the
/// line `s[..len]` with the same words; `None` otherwise, which includes a line that does
/// not end within `s` (then `b` may hold some words, to be cleared). A line it takes holds
/// only upper-case letters, signs, digits, points and blanks: plain ASCII.
///
/// Why the bytes after the line do not matter: every run of digits stops at the first
/// byte that is no digit, here the CR or LF where [`lit_words`] has the end of the text
/// (which [`load8`] reads as 0, no digit either), and after a word's digits the CR or LF
/// ends the line where the end of the text does.
#[inline(always)]
pub fn lit_words_buf(s: &[u8], start: u32, b: &mut LitBlock, rule: Rule) -> Option<usize> {
    // Word by word from a window of fixed size (one bounds check a word, none a load);
    // the words too near the end of `s` for one, the general loop.
    let mut i = 0;
    while let Some(win) = s.get(i..).and_then(<[u8]>::first_chunk::<WIN>) {
        let letter = win[0];
        let k = letter.wrapping_sub(b'A');
        if k >= 26 || (rule.refuse >> k) & 1 != 0 {
            return None;
        }
        // The sign is the lowest byte of the window after the letter; the digits start
        // there or one on, and the bytes after a point one on from that.
        let w1 = win8::<1>(win);
        let sign = w1 as u8;
        let neg = sign == b'-';
        let signed = neg || sign == b'+';
        let (w, off) = if signed { (win8::<2>(win), 2) } else { (w1, 1) };
        let non = nondigits(w);
        let n = (non.trailing_zeros() / 8) as usize;
        let point = n < 8 && (w >> (8 * n)) as u8 == b'.';
        let (mant, frac, j);
        if !point {
            (mant, frac, j) = (value(w, n), 0, off + n);
        } else {
            // The digits on both sides of the point closed up (the bytes after it moved
            // down one), as in `word_number`; which of them are digits, from `non` moved
            // alike, without a second look at the bytes. The top byte is the one after
            // `w`: taken for no digit here, and looked at only when the seven below are
            // all digits.
            let low = (1u64 << (8 * n)) - 1;
            let all = ((((non >> 8) | (0x80 << 56)) & !low).trailing_zeros() / 8) as usize;
            if all < 7 || !win[(off + 8) & (WIN - 1)].is_ascii_digit() {
                let joined = (w & low) | ((w >> 8) & !low);
                (mant, frac, j) = (value(joined, all), all - n, off + all + 1);
            } else {
                let at = off + n + 1;
                let rest = u64::from_le_bytes(*win.get(at..)?.first_chunk::<8>()?);
                let m = run(rest);
                let &p = POW10.get(m)?;
                (mant, frac, j) = (value(w, n) * p + value(rest, m), m, at + m);
            }
        }
        if n + frac == 0 || n == 8 {
            return None;
        }
        if letter == b'G' && rule.g_macro && !point && !signed && matches!(mant, 10 | 65 | 66 | 67) {
            return None;
        }
        let v = crate::read::exact_short(mant, frac);
        let value = if neg { -v } else { v };
        let span = Span::new(start + i as u32, start + (i + j) as u32);
        // No count of thousandths for a G word: only axis and F words' are read.
        let q = if letter == b'G' { NO_MILLI } else { milli(neg, Some((mant, frac))) };
        if !b.push_upper(letter, value, point, q, span) {
            return None;
        }
        // `j` is at most 18 (a sign, seven digits, a point, seven digits after the letter).
        match win[j & (WIN - 1)] {
            b'\n' | b'\r' => return Some(i + j),
            b' ' => {}
            _ => return None,
        }
        i += j + 1;
    }
    words::<true>(s, i, start, b, rule)
}

/// The window [`lit_words_buf`] reads a word from (a power of two).
const WIN: usize = 32;

/// The eight bytes of `win` from `AT` as a little-endian word.
#[inline(always)]
fn win8<const AT: usize>(win: &[u8; WIN]) -> u64 {
    let mut w = [0u8; 8];
    w.copy_from_slice(&win[AT..AT + 8]);
    u64::from_le_bytes(w)
}

/// [`lit_words`] (`BUF` false: the line is all of `s`) and [`lit_words_buf`] (`BUF` true:
/// the line ends at the first CR or LF of `s`), from the word at `from`; the line's length.
#[inline(always)]
fn words<const BUF: bool>(s: &[u8], from: usize, start: u32, b: &mut LitBlock, rule: Rule) -> Option<usize> {
    let len = s.len();
    let mut i = from;
    loop {
        let &letter = s.get(i)?;
        let k = letter.wrapping_sub(b'A');
        if k >= 26 || (rule.refuse >> k) & 1 != 0 {
            return None;
        }
        let Num { mant, frac, neg, signed, point, end: j } = word_number(s, i + 1)?;
        // The letter first: it is known here, the rest only for a `G` (one word a line).
        if letter == b'G' && rule.g_macro && !point && !signed && matches!(mant, 10 | 65 | 66 | 67) {
            return None;
        }
        // At most 14 digits, at most seven after the point (`word_number`).
        let v = crate::read::exact_short(mant, frac);
        let value = if neg { -v } else { v };
        let span = Span::new(start + i as u32, start + j as u32);
        // The letter is upper case (checked above): `push_upper` skips that check.
        let q = if letter == b'G' { NO_MILLI } else { milli(neg, Some((mant, frac))) };
        if !b.push_upper(letter, value, point, q, span) {
            return None;
        }
        if BUF {
            match s.get(j) {
                Some(b'\n' | b'\r') => return Some(j),
                Some(b' ') => {}
                _ => return None,
            }
        } else {
            if j == len {
                return Some(j);
            }
            // One blank, then the next word's letter (checked there).
            if s[j] != b' ' {
                return None;
            }
        }
        i = j + 1;
    }
}

/// A word's number as the quick readers take it: its digits as one whole number `mant`
/// with `frac` of them after the point, its sign, and `end`, the offset just past its last
/// digit.
pub(crate) struct Num {
    pub mant: u64,
    pub frac: usize,
    pub neg: bool,
    pub signed: bool,
    pub point: bool,
    pub end: usize,
}

/// The number at `s[j..]` (after a word's letter): an optional sign, then at most seven
/// digits before and seven after an optional point, at least one digit; `None` for any
/// other shape (eight digits in a run may go on: the full readers read those).
#[inline(always)]
pub(crate) fn word_number(s: &[u8], mut j: usize) -> Option<Num> {
    let sign = s.get(j).copied().unwrap_or(0);
    let neg = sign == b'-';
    let signed = neg || sign == b'+';
    j += usize::from(signed);
    let w = load8(s, j);
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
        let after = u64::from(s.get(j + 8).copied().unwrap_or(0));
        let joined = (w & low) | ((w >> 8) & !low & !(0xFF << 56)) | (after << 56);
        let all = run(joined);
        if all < 8 {
            (mant, frac) = (value(joined, all), all - n);
            j += all + 1;
        } else {
            // Longer: the digits after the point from their own window.
            let at = j + n + 1;
            let rest = load8(s, at);
            let m = run(rest);
            let &p = POW10.get(m)?;
            (mant, frac) = (value(w, n) * p + value(rest, m), m);
            j = at + m;
        }
    }
    // None is no number; eight in a run may go on (the full reader reads them).
    if n + frac == 0 || n == 8 {
        return None;
    }
    Some(Num { mant, frac, neg, signed, point, end: j })
}

/// 10^0 ..= 10^7.
pub(crate) const POW10: [u64; 8] = [1, 10, 100, 1000, 10_000, 100_000, 1_000_000, 10_000_000];

/// The eight bytes of `s` from `i` as a little-endian word (the first byte lowest), bytes
/// past the end 0 (not a digit).
#[inline(always)]
pub(crate) fn load8(s: &[u8], i: usize) -> u64 {
    if let Some(Ok(w)) = s.get(i..i + 8).map(<[u8; 8]>::try_from) {
        return u64::from_le_bytes(w);
    }
    // Near the end of a line (its last word): its last eight bytes, shifted down.
    let len = s.len();
    if let (Some(Ok(w)), Some(k @ 1..=7)) = (s.get(len.wrapping_sub(8)..).map(<[u8; 8]>::try_from), len.checked_sub(i))
    {
        return u64::from_le_bytes(w) >> (8 * (8 - k));
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
pub(crate) fn run(w: u64) -> usize {
    (nondigits(w).trailing_zeros() / 8) as usize
}

/// The top bit of each byte of `w` that is no ASCII digit (the other bits 0).
#[inline(always)]
fn nondigits(w: u64) -> u64 {
    // Digits become 0..=9; a byte is one exactly when it is below 10 then: adding 0x76 to
    // its low seven bits sets bit 7 from 10 on (no carry out of the byte), and bytes from
    // 0x80 on have it set already.
    let v = w ^ (LO * 0x30);
    (((v & (LO * 0x7F)) + LO * 0x76) | v) & (LO * 0x80)
}

/// The whole number the first `n` bytes of `w` (digits, see [`run`]) spell.
#[inline(always)]
pub(crate) fn value(w: u64, n: usize) -> u64 {
    if n == 0 {
        return 0;
    }
    // The digits moved to the top bytes, zeros (leading zero digits) below them; then
    // pairs, fours and eights of digits are combined: each step's lanes hold at most 99,
    // 9999 and 99999999, so nothing carries into the next lane.
    let d = (w ^ (LO * 0x30)) << (64 - 8 * n.min(8));
    let d = (d.wrapping_mul(10).wrapping_add(d >> 8)) & 0x00FF_00FF_00FF_00FF;
    let d = (d.wrapping_mul(100).wrapping_add(d >> 16)) & 0x0000_FFFF_0000_FFFF;
    (d.wrapping_mul(10_000).wrapping_add(d >> 32)) & 0xFFFF_FFFF
}

/// [`run`] and [`value`] at once.
#[cfg(test)]
fn digits8(w: u64) -> (usize, u64) {
    let n = run(w);
    (n, value(w, n))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dialect::lit::{LitWord, MAX_WORDS};
    use crate::read::RawBlock;

    struct Rng(u64);
    impl Rng {
        fn next(&mut self) -> u64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            self.0
        }
        fn below(&mut self, n: usize) -> usize {
            (self.next() % n as u64) as usize
        }
        fn pick<'a>(&mut self, xs: &[&'a str]) -> &'a str {
            xs[self.below(xs.len())]
        }
    }

    /// A line mostly of the quick shape, often just off it (other blanks, letters the
    /// dialects judge, long digit runs, signs, points, comments, skips).
    fn line(r: &mut Rng) -> String {
        let mut s = String::new();
        if r.below(20) == 0 {
            s.push_str(r.pick(&[" ", "/", "N10 ", "\t", "n5 "]));
        }
        for k in 0..r.below(9) {
            if k > 0 {
                s.push_str(r.pick(&[" ", " ", " ", " ", " ", "", "  ", "\t"]));
            }
            let letter = r.pick(&[
                "G", "X", "Y", "Z", "F", "X", "Y", "Z", "A", "C", "S", "M", "N", "O", "L", "P", "E", "x", "g", "H",
            ]);
            s.push_str(letter);
            if r.below(30) == 0 {
                s.push(' ');
            }
            s.push_str(r.pick(&["", "", "", "-", "+"]));
            let int = r.below(10);
            let frac = r.below(10);
            let point = r.below(3) > 0;
            for _ in 0..int {
                s.push(char::from(b'0' + r.below(10) as u8));
            }
            if letter == "G" && r.below(3) == 0 {
                s.push_str(r.pick(&["10", "65", "1", "0", "66", "67", "90"]));
            }
            if point {
                s.push('.');
                for _ in 0..frac {
                    s.push(char::from(b'0' + r.below(10) as u8));
                }
                if r.below(4) == 0 {
                    s.push_str(r.pick(&["5", "0005", "49999", "50001"]));
                }
            }
        }
        if r.below(15) == 0 {
            s.push_str(r.pick(&[" ", ";", " ; note", "(C)", "=1", " [", "EX"]));
        }
        s
    }

    fn words(b: &LitBlock) -> Vec<(u8, u64, bool, Span)> {
        b.words().iter().map(|w: &LitWord| (w.letter, w.value.to_bits(), w.point, w.span)).collect()
    }

    fn millis_right(b: &LitBlock) {
        for w in b.words() {
            if w.milli != NO_MILLI {
                assert_eq!(Some(i64::from(w.milli)), crate::eval::value::decimal_count(w.value, 1000.0), "{w:?}");
            }
        }
    }

    /// Both dialects' re-read into compact blocks (quick reader first) against their full
    /// readers' callbacks: the same lines taken, the same words, spans and numbers.
    #[test]
    fn quick_lines_read_as_the_full_readers_read_them() {
        let mut r = Rng(0x1234_5678_9abc_def1);
        let (mut quick, mut taken) = (0, 0);
        for n in 0..200_000u32 {
            let text = line(&mut r);
            let raw = RawBlock { text: &text, start: 1000 + n, line: n + 1 };
            let mut probe = LitBlock::EMPTY;
            quick += usize::from(lit_words(raw.text, raw.start, &mut probe, crate::dialect::sinumerik::fast::QUICK));

            let mut b = LitBlock::EMPTY;
            let got = crate::dialect::sinumerik::fast::lit_raw(&raw, &mut b).map(|(s, n, _)| (s, n));
            let mut v = Vec::new();
            let want = crate::dialect::sinumerik::fast::words_raw(&raw, |l, x, p, sp| {
                v.push((l, x.to_bits(), p, sp));
                v.len() <= MAX_WORDS
            });
            assert_eq!(got, want, "sinumerik {text:?}");
            if got.is_some() {
                taken += 1;
                assert_eq!(words(&b), v, "sinumerik {text:?}");
                millis_right(&b);
            }

            let mut b = LitBlock::EMPTY;
            let got = crate::dialect::fanuc::fast::lit_block(&raw, 0, &mut b);
            let mut v = Vec::new();
            let want = crate::dialect::fanuc::fast::lit_raw(&raw, 0, |l, x, p, sp| {
                v.push((l, x.to_bits(), p, sp));
                v.len() <= MAX_WORDS
            });
            assert_eq!(got, want, "fanuc {text:?}");
            if got.is_some() {
                assert_eq!(words(&b), v, "fanuc {text:?}");
                millis_right(&b);
            }
        }
        assert!(quick > 5_000 && taken > quick + 5_000, "{quick} quick, {taken} taken");
    }

    /// The buffer reader against the line reader: on each generated line followed by a line
    /// end (LF, CR LF, CR) and more text, it takes the line when and only when the line
    /// reader takes it, with the same words, and gives the line's length; without a line
    /// end after the line (a line cut by the buffer's end) it never takes it. And the
    /// dialects' `lit_buf` take a line only as their `lit_raw` / `lit_block` take it.
    #[test]
    fn buffer_lines_read_as_whole_lines() {
        let mut r = Rng(0x0bad_cafe_1234_5678);
        let mut taken = 0;
        for n in 0..200_000u32 {
            let text = line(&mut r);
            let after = [&line(&mut r)[..], "7", "0.5", ".", "", "X1"][r.below(6)].to_string();
            let end = ["\n", "\r\n", "\r", ""][r.below(4)];
            // Often more text after it, so that every word of the line is read from a
            // full window (`lit_words_buf` reads the words near the end of `s` otherwise).
            let more =
                if end.is_empty() || r.below(2) == 0 { "" } else { "G1 X12.5 Y-0.125 Z7 F800 ; more text after" };
            let buf = format!("{text}{end}{after}{more}");
            let start = 1000 + n;
            let sin = crate::dialect::sinumerik::fast::QUICK;
            let fan = crate::dialect::fanuc::fast::QUICK;
            for (rule, name) in [(sin, "sinumerik"), (fan, "fanuc")] {
                let mut want = LitBlock::EMPTY;
                let whole = lit_words(&text, start, &mut want, rule);
                let mut got = LitBlock::EMPTY;
                let len = lit_words_buf(buf.as_bytes(), start, &mut got, rule);
                if end.is_empty() {
                    assert_eq!(len, None, "{name} {buf:?}");
                    continue;
                }
                assert_eq!(len, whole.then_some(text.len()), "{name} {buf:?}");
                if whole {
                    taken += 1;
                    assert_eq!(words(&got), words(&want), "{name} {buf:?}");
                    millis_right(&got);
                }
            }
            let raw = RawBlock { text: &text, start, line: 1 };
            let mut b = LitBlock::EMPTY;
            if crate::dialect::sinumerik::fast::lit_buf(buf.as_bytes(), start, &mut b).is_some() {
                let mut w = LitBlock::EMPTY;
                let whole = Span::new(start, start + text.len() as u32);
                assert_eq!(crate::dialect::sinumerik::fast::lit_raw(&raw, &mut w), Some((whole, None, true)));
                assert_eq!(words(&b), words(&w), "{buf:?}");
            }
            let mut b = LitBlock::EMPTY;
            if crate::dialect::fanuc::fast::lit_buf(buf.as_bytes(), start, &mut b).is_some() {
                let mut w = LitBlock::EMPTY;
                let whole = Span::new(start, start + text.len() as u32);
                assert_eq!(crate::dialect::fanuc::fast::lit_block(&raw, 0, &mut w), Some((whole, None)));
                assert_eq!(words(&b), words(&w), "{buf:?}");
            }
        }
        assert!(taken > 10_000, "{taken} taken");
    }

    /// `digits8` against counting and adding the digits one by one, on every run length
    /// and bytes around the digits.
    #[test]
    fn eight_bytes_read_as_the_digits_they_start_with() {
        let mut seed = 0x5eed_u64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        let others = [b'.', b' ', b'-', b'/', b':', b'A', 0, 0x80, 0xFF, 0xB0, 0x3A, 0x2F, b'\t'];
        for _ in 0..200_000 {
            let mut w = [0u8; 8];
            for c in &mut w {
                *c = if next() % 3 == 0 {
                    others[(next() % others.len() as u64) as usize]
                } else {
                    b'0' + (next() % 10) as u8
                };
            }
            let n = w.iter().take_while(|c| c.is_ascii_digit()).count();
            let v = w[..n].iter().fold(0u64, |a, &c| a * 10 + u64::from(c - b'0'));
            assert_eq!(digits8(u64::from_le_bytes(w)), (n, if n == 0 { 0 } else { v }), "{w:?}");
        }
    }
}
