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

use crate::eval::lit::{milli, LitBlock};
use crate::span::Span;

/// One word as read: upper-case letter, its digits as one whole number with `frac` of
/// them after the point, whether a sign (`neg`: `-`) and a point were written.
#[derive(Clone, Copy, Debug)]
pub struct Quick {
    pub letter: u8,
    pub mant: u64,
    pub frac: usize,
    pub signed: bool,
    pub neg: bool,
    pub point: bool,
}

/// Reads the line `text` (starting at file offset `start`) into `b` when it has the shape
/// above and `ok` takes each word; `false` otherwise, and then `b` may hold some of its
/// words (to be cleared). Each word is pushed as the dialects' readers push it: value
/// `read::exact(mant, frac)` with its sign, point, thousandths from the digits, span from
/// its letter to its last digit.
#[inline(always)]
pub fn lit_words(text: &str, start: u32, b: &mut LitBlock, ok: impl Fn(&Quick) -> bool) -> bool {
    let s = text.as_bytes();
    let len = s.len();
    let mut i = 0;
    loop {
        let Some(&letter) = s.get(i) else { return false };
        if !letter.is_ascii_uppercase() {
            return false;
        }
        let mut j = i + 1;
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
                let Some(&p) = POW10.get(m) else { return false };
                (mant, frac) = (value(w, n) * p + value(rest, m), m);
                j = at + m;
            }
        }
        // None is no number; eight in a run may go on (the full reader reads them).
        if n + frac == 0 || n == 8 {
            return false;
        }
        let w = Quick { letter, mant, frac, signed, neg, point };
        if !ok(&w) {
            return false;
        }
        // At most 14 digits: below 2^53, `exact` answers.
        let v = crate::read::exact(mant, frac).unwrap_or(0.0);
        let value = if neg { -v } else { v };
        let span = Span::new(start + i as u32, start + j as u32);
        if !b.push(letter, value, point, milli(neg, Some((mant, frac))), span) {
            return false;
        }
        if j == len {
            return true;
        }
        // One blank, then the next word's letter (checked there).
        if s[j] != b' ' {
            return false;
        }
        i = j + 1;
    }
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
    use crate::eval::lit::{LitWord, MAX_WORDS, NO_MILLI};
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
            let plain_sin = |w: &Quick| !matches!(w.letter, b'L' | b'M' | b'N' | b'O' | b'P');
            quick += usize::from(lit_words(raw.text, raw.start, &mut probe, plain_sin));

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
