//! Numbers written from the digits of their source literal: a plain word's value is the
//! double nearest to its literal, and when the literal has at most 15 digits the writers'
//! form of that double (the shortest round-trip decimal, `fmt_num`'s and `{}`'s digits) is
//! the literal itself without leading and trailing zeros. Taking the digits from the text
//! spares formatting the double (most of a streamed translation's cost per block).
//!
//! Why the digits are the same: a decimal `D` of at most 15 significant digits is the
//! only decimal of at most 15 digits whose nearest double is `round(D)` (two such decimals
//! are further apart than a double's spacing), so no shorter decimal reads back as
//! `round(D)`, and the shortest one is `D` stripped. The readers compute the value from the
//! same digits, correctly rounded (`read::exact`, `read::scaled`, or Rust's parser).
//! [`Src::push_word`] takes the usual word (`X-0.4750`, `F800`) whole in one integer and
//! writes it in one store; [`Lit`] takes the rest of the literals (a `+`, leading zeros,
//! a bare point) byte by byte.
//! Whatever the conditions here do not cover (more digits, a scaled value, an exponent,
//! blanks inside the word) is written from the value, as before. The differential tests
//! (`tests/stream_translate_fast.rs`, `tests/stream_to_sinumerik_fast.rs`, the unit tests
//! below) hold both to the general writers' bytes.

use crate::dialect::sinumerik::scan_words::Canon;
use crate::read::RawBlock;
use crate::span::Span;

/// A literal `[+-]digits[.digits]` (at least one digit, at most 15) as offsets into its
/// bytes `b` (the word without its letter).
#[derive(Clone, Copy, Debug)]
pub struct Lit<'t> {
    pub b: &'t [u8],
    pub neg: bool,
    /// Where the integer digits start (after the sign), where the first non-zero one is
    /// (`dot` when none), and where they end (the point, or the end of `b`).
    pub int: usize,
    pub nz: usize,
    pub dot: usize,
    /// The end of the fraction digits without their trailing zeros (`dot + 1` when all are
    /// zeros or there are none after a point; `dot` without a point).
    pub end: usize,
}

impl<'t> Lit<'t> {
    /// The literal of word `span` (letter included) in `line`; `None` when it is not of
    /// the form above.
    #[inline(always)]
    pub fn of(line: &RawBlock<'t>, span: Span) -> Option<Lit<'t>> {
        let lo = span.lo.checked_sub(line.start)? as usize + 1;
        let hi = span.hi.checked_sub(line.start)? as usize;
        Lit::parse(line.text.as_bytes().get(lo..hi)?)
    }

    #[inline(always)]
    pub fn parse(b: &'t [u8]) -> Option<Lit<'t>> {
        let len = b.len();
        let (neg, int) = match b.first()? {
            b'-' => (true, 1),
            b'+' => (false, 1),
            _ => (false, 0),
        };
        let mut i = int;
        while i < len && b[i] == b'0' {
            i += 1;
        }
        let nz = i;
        while i < len && b[i].is_ascii_digit() {
            i += 1;
        }
        let dot = i;
        let mut end = dot;
        if i < len {
            if b[i] != b'.' {
                return None;
            }
            i += 1;
            while i < len && b[i].is_ascii_digit() {
                i += 1;
            }
            if i != len {
                return None;
            }
            end = len;
            while end > dot + 1 && b[end - 1] == b'0' {
                end -= 1;
            }
        }
        // Digits written: the literal less its sign and point.
        let digits = len - int - usize::from(dot < len);
        if digits == 0 || digits > 15 {
            return None;
        }
        Some(Lit { b, neg, int, nz, dot, end })
    }

    /// Significant integer digits.
    #[inline(always)]
    fn ni(&self) -> usize {
        self.dot - self.nz
    }

    /// Fraction digits without the trailing zeros.
    #[inline(always)]
    fn nf(&self) -> usize {
        self.end.saturating_sub(self.dot + 1)
    }

    /// Whether the literal, from its sign, is already in the written form up to `end`:
    /// no `+`, integer digits, and no leading zero but the one before a point.
    #[inline(always)]
    fn canonical(&self) -> bool {
        self.b[0] != b'+'
            && self.dot > self.int
            && (self.nz == self.int || (self.nz == self.dot && self.dot == self.int + 1))
    }

    /// Appends `-`, the integer digits (`0` when none), and when `point` or with fraction
    /// digits, the point and those digits.
    #[inline(always)]
    fn push_parts(&self, out: &mut Vec<u8>, point: bool) {
        if self.canonical() {
            let end = if self.nf() > 0 { self.end } else { self.dot };
            out.extend_from_slice(&self.b[..end]);
            if self.nf() == 0 && point {
                out.push(b'.');
            }
            return;
        }
        if self.neg {
            out.push(b'-');
        }
        if self.ni() == 0 {
            out.push(b'0');
        } else {
            out.extend_from_slice(&self.b[self.nz..self.dot]);
        }
        if self.nf() > 0 {
            out.extend_from_slice(&self.b[self.dot..self.end]);
        } else if point {
            out.push(b'.');
        }
    }

    /// `fast::push_num(out, v, point)` for the literal's value `v` when that writes the
    /// literal's digits (what `emit::fmt_num` writes: at most 7 integer digits, with a
    /// fraction at most 8 digits in all); `false`, writing nothing, for the rest. Without
    /// `point`, only an integer is written.
    #[inline(always)]
    pub fn push_fanuc(&self, out: &mut Vec<u8>, point: bool) -> bool {
        let (ni, nf) = (self.ni(), self.nf());
        if ni > 7 || nf > 8 || (ni > 0 && ni + nf > 8) || (!point && nf > 0) {
            return false;
        }
        if ni == 0 && nf == 0 {
            // Zero, of either sign (`push_num` writes -0 as 0).
            out.extend_from_slice(if point { b"0." } else { b"0" });
            return true;
        }
        self.push_parts(out, point);
        true
    }

    /// `format!("{v}")` of the literal's value `v != 0` (Rust's shortest round-trip
    /// decimal: the digits as written); `false`, writing nothing, for zero.
    #[inline(always)]
    pub fn push_display(&self, out: &mut Vec<u8>) -> bool {
        if self.ni() == 0 && self.nf() == 0 {
            return false;
        }
        self.push_parts(out, false);
        true
    }
}

/// How a word's number is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Form {
    /// `fast::push_num(v, true)`: FANUC's dimension, with a point.
    Point,
    /// `fast::push_num(v, false)` of an integer `v`: FANUC's integer address.
    Int,
    /// `format!("{v}")`: Sinumerik.
    Display,
}

/// [`Src::push_word`] on a word of `2 <= n <= $w` bytes held in one integer of type `$t`
/// (`$w` bytes wide): its first byte (the letter) in the low byte, zeros above it.
/// Made for `u64` (nearly every CAM word) and `u128` (the longer ones), as the
/// arithmetic on a `u128` costs about twice as much.
macro_rules! word_in {
    ($name:ident, $t:ty, $w:expr) => {
        #[inline(always)]
        fn $name(t: &[u8], a: usize, n: usize, letter: u8, form: Form, out: &mut Vec<u8>) -> bool {
            const fn bytes(b: u8) -> $t {
                <$t>::from_le_bytes([b; $w])
            }
            let mask: $t = <$t>::MAX >> (($w - n) * 8);
            // 16 (8) bytes from the letter on or, near the line's end, up to the word's end.
            let w = if let Some(x) = t.get(a..a + $w) {
                let Ok(x) = x.try_into() else { return false };
                <$t>::from_le_bytes(x) & mask
            } else {
                let Some(x) = (a + n).checked_sub($w).and_then(|lo| t.get(lo..a + n)) else { return false };
                let Ok(x) = x.try_into() else { return false };
                <$t>::from_le_bytes(x) >> (($w - n) * 8)
            };
            let head = w as u32;
            let s = usize::from((head >> 8) as u8 == b'-');
            let first = (head >> (8 + 8 * s)) as u8;
            let second = (head >> (16 + 8 * s)) as u8;
            // `+`, a blank, a bare point, a leading zero before another digit.
            if !first.is_ascii_digit() || (first == b'0' && second.is_ascii_digit()) {
                return false;
            }
            // The point: the one byte of the literal equal to `.` (exact zero-byte test).
            let d = w ^ bytes(b'.');
            let nonzero = (((d & bytes(0x7f)) + bytes(0x7f)) | d) & bytes(0x80);
            let dots = !nonzero & mask & bytes(0x80) & !0xff;
            let dot = dots != 0;
            // Trailing `0`s after the point: the word's last byte moved to the top, then the
            // zero bytes of `w ^ "000…"` counted from there (the point stops them).
            let strip = if dot { (((w ^ bytes(b'0')) << (($w - n) * 8)).leading_zeros() / 8) as usize } else { 0 };
            let mut end = n - strip;
            let nf = if dot { end - (dots.trailing_zeros() / 8) as usize - 1 } else { 0 };
            let sig = end - 1 - s - usize::from(dot);
            let mut w = (w & !0xff) | <$t>::from(letter);
            match form {
                Form::Point => {
                    if sig > 8 || (!dot && sig > 7) {
                        return false;
                    }
                    if !dot {
                        if end >= $w {
                            return false;
                        }
                        w |= <$t>::from(b'.') << (end * 8);
                        end += 1;
                    }
                }
                Form::Int => {
                    if nf > 0 || sig > 7 {
                        return false;
                    }
                    end -= usize::from(dot);
                }
                Form::Display => end -= usize::from(dot && nf == 0),
            }
            let at = out.len();
            out.extend_from_slice(&w.to_le_bytes());
            out.truncate(at + end);
            true
        }
    };
}

word_in!(word_u64, u64, 8);
word_in!(word_u128, u128, 16);

/// Where a plain word's text is: its line and its span (letter included), and its
/// canonical form when the quick reader found it (`Canon::NONE` otherwise).
#[derive(Clone, Copy)]
pub struct Src<'t> {
    pub line: &'t RawBlock<'t>,
    pub span: Span,
    pub canon: Canon,
}

impl<'t> Src<'t> {
    /// The literal, for [`Lit`]'s writers.
    #[inline(always)]
    pub fn lit(self) -> Option<Lit<'t>> {
        Lit::of(self.line, self.span)
    }

    /// Appends `letter` and the number `v != 0` of this word in `form`, when the literal
    /// is already that form up to its trailing zeros (and a point FANUC adds): `-` or no
    /// sign, no leading zero but the one before a point, no blank, and (`Point`, `Int`) at
    /// most 8 significant digits, 7 without a fraction. The word (at most 15 bytes) is
    /// handled in one integer (no loop over its bytes) and written whole, then cut to its
    /// length. `false`, writing nothing, for the rest ([`Lit`] and the value writers take
    /// them).
    #[inline(always)]
    pub fn push_word(self, letter: u8, v: f64, form: Form, out: &mut Vec<u8>) -> bool {
        let c = self.canon;
        if c.len != 0 && c.lo as u8 == letter {
            // The form the quick reader found (not zero, no `+`, no leading zero): what
            // `word_u64`/`word_u128` below write for it, where they write anything (for
            // `Point` at most 7 digits, where they take 8 with a point).
            let (dot, frac) = (c.dot, c.len > c.dot + 1);
            let len = match form {
                Form::Point if c.sig <= 7 => c.len,
                Form::Int if !frac && c.sig <= 7 => dot,
                Form::Display if frac => c.len,
                Form::Display => dot,
                _ => 0,
            };
            if len != 0 {
                let at = out.len();
                out.extend_from_slice(&c.bytes());
                out.truncate(at + usize::from(len));
                return true;
            }
        }
        if v == 0.0 {
            return false;
        }
        let (Some(a), Some(hi)) =
            (self.span.lo.checked_sub(self.line.start), self.span.hi.checked_sub(self.line.start))
        else {
            return false;
        };
        let (a, hi) = (a as usize, hi as usize);
        let Some(n) = hi.checked_sub(a) else { return false };
        let t = self.line.text.as_bytes();
        if (2..=8).contains(&n) {
            word_u64(t, a, n, letter, form, out)
        } else if (2..16).contains(&n) {
            word_u128(t, a, n, letter, form, out)
        } else {
            false
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dialect::numwrite::push_num;
    use crate::test_rng::Rng;

    /// Literals as CAM systems and people write them: 1..15 digits, 0..8 decimals,
    /// leading and trailing zeros, signs, a bare point at either end.
    fn literal(r: &mut Rng) -> String {
        let sign = ["", "", "-", "+"][(r.next() % 4) as usize];
        let lead = "0".repeat((r.next() % 3) as usize);
        let int_digits = (r.next() % 9) as usize;
        let int = if int_digits == 0 { String::new() } else { (r.next() % 10u64.pow(int_digits as u32)).to_string() };
        let body = match r.next() % 5 {
            0 => format!("{lead}{int}"),
            1 => format!("{lead}{int}."),
            _ => {
                let d = (r.next() % 9) as usize;
                let frac = if d == 0 { String::new() } else { format!("{:0d$}", r.next() % 10u64.pow(d as u32)) };
                let trail = "0".repeat((r.next() % 3) as usize);
                format!("{lead}{int}.{frac}{trail}")
            }
        };
        format!("{sign}{body}")
    }

    fn value(s: &str) -> Option<f64> {
        let v: f64 = s.parse().ok()?;
        Some(v)
    }

    #[test]
    fn literal_digits_are_what_the_value_writers_write() {
        let mut r = Rng(0x5851_f42d_4c95_7f2d);
        let mut fixed: Vec<String> = [
            "0",
            "-0",
            "+0",
            "0.",
            "-0.",
            ".0",
            "-.0",
            "00.1000",
            "X",
            "-",
            ".",
            "-.",
            "+3",
            ".5",
            "-.5",
            "5.",
            "0.5",
            "000",
            "1234567",
            "12345678",
            "1234567.8",
            "1234567.89",
            "0.12345678",
            "0.123456789",
            "0.00000001",
            "0.000000001",
            "0.000001",
            "0.0000001",
            "123456789012345",
            "1234567890123456",
            "99999999.",
            "9999999.9",
            "1.00000000000000",
            "1e5",
            "1 2",
            "- 1",
            "1.2.3",
            "1-2",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        for _ in 0..300_000 {
            fixed.push(literal(&mut r));
        }
        let mut taken = 0;
        for s in &fixed {
            let Some(l) = Lit::parse(s.as_bytes()) else {
                // Declined only where the literal is not one (or has more than 15 digits).
                let digits = s.bytes().filter(u8::is_ascii_digit).count();
                assert!(value(s).is_none() || digits == 0 || digits > 15 || s.contains(['e', ' ']), "{s}");
                continue;
            };
            let v = value(s).unwrap_or(f64::NAN);
            assert_eq!(l.neg, s.starts_with('-'), "{s}");
            for point in [true, false] {
                let mut a = Vec::new();
                if l.push_fanuc(&mut a, point) {
                    taken += 1;
                    let mut b = Vec::new();
                    assert!(push_num(&mut b, v, point), "{s}");
                    assert_eq!(String::from_utf8_lossy(&a), String::from_utf8_lossy(&b), "{s} point {point}");
                } else {
                    assert!(a.is_empty(), "{s}");
                }
            }
            let mut a = Vec::new();
            if l.push_display(&mut a) {
                assert_eq!(String::from_utf8_lossy(&a), format!("{v}"), "{s}");
            } else {
                assert!(a.is_empty() && v == 0.0, "{s}");
            }
        }
        assert!(taken > 300_000, "{taken}");
    }

    /// `Src::push_word` (the word read as one integer, from the letter on or up to the
    /// word's end) against the value writers, with the word at the start, in the middle and
    /// at the end of lines of every length.
    #[test]
    fn whole_words_are_what_the_value_writers_write() {
        let mut r = Rng(0x0bad_cafe_1234_5678);
        let mut taken = [0usize; 3];
        for i in 0..300_000 {
            let lit = literal(&mut r);
            let Some(v) = value(&lit) else { continue };
            let before = " ".repeat((r.next() % 12) as usize);
            let after = " Y1".repeat((r.next() % 6) as usize);
            let letter = [b'X', b'x', b'F'][i % 3];
            let text = format!("{before}{}{lit}{after}", letter as char);
            let line = RawBlock { text: &text, start: 1000, line: 1 };
            let lo = 1000 + before.len() as u32;
            let src = Src { line: &line, span: Span::new(lo, lo + 1 + lit.len() as u32), canon: Canon::NONE };
            let up = letter.to_ascii_uppercase();
            for (k, form) in [Form::Point, Form::Int, Form::Display].into_iter().enumerate() {
                let mut a = Vec::new();
                if !src.push_word(up, v, form, &mut a) {
                    assert!(a.is_empty(), "{text:?}");
                    continue;
                }
                taken[k] += 1;
                let b = written(up, v, form, &text);
                assert_eq!(String::from_utf8_lossy(&a), String::from_utf8_lossy(&b), "{text:?} {form:?}");
            }
        }
        assert!(taken.iter().all(|&n| n > 20_000), "{taken:?}");
    }

    /// The word `letter` `v` as the value writers write it in `form` (what `Src::push_word`
    /// must give from the digits).
    fn written(letter: u8, v: f64, form: Form, text: &str) -> Vec<u8> {
        let mut b = vec![letter];
        match form {
            Form::Point => assert!(push_num(&mut b, v, true), "{text:?}"),
            Form::Int => {
                assert_eq!(v.fract(), 0.0, "{text:?}");
                push_num(&mut b, v, false);
            }
            Form::Display => b.extend_from_slice(format!("{v}").as_bytes()),
        }
        b
    }

    /// `Src::push_word` from the form the quick reader found (`Canon`) against the value
    /// writers: literals of every shape as words of a line the quick reader takes, with
    /// and without 16 bytes after the word in the buffer.
    #[test]
    fn canonical_forms_are_what_the_value_writers_write() {
        use crate::dialect::sinumerik::scan_words::scan_words_bytes;
        let mut r = Rng(0x1357_9bdf_2468_ace0);
        let mut taken = [0usize; 3];
        let mut none = 0;
        for i in 0..300_000 {
            let lit = literal(&mut r);
            let number = if i % 4 == 0 { "N10 " } else { "" };
            let before = if i % 3 == 0 { "G1 " } else { "" };
            let after = [" Y1", "", " Z-2.5"][i % 3];
            let pad = ["\n", "\nG1 X2 Y3 Z4 F5000\n", "\r\n"][(r.next() % 3) as usize];
            let text = format!("{number}{before}X{lit}{after}{pad}");
            let mut words = Vec::new();
            let Some(found) = scan_words_bytes(text.as_bytes(), 1000, |l, v, _, span, c| words.push((l, v, span, c)))
            else {
                continue;
            };
            let line = RawBlock { text: &text[..found.len], start: 1000, line: 1 };
            for &(letter, v, span, canon) in &words {
                if canon.len == 0 {
                    none += 1;
                    continue;
                }
                let src = Src { line: &line, span, canon };
                for (k, form) in [Form::Point, Form::Int, Form::Display].into_iter().enumerate() {
                    let mut a = Vec::new();
                    if !src.push_word(letter, v, form, &mut a) {
                        assert!(a.is_empty(), "{text:?}");
                        continue;
                    }
                    taken[k] += 1;
                    let b = written(letter, v, form, &text);
                    assert_eq!(String::from_utf8_lossy(&a), String::from_utf8_lossy(&b), "{text:?} {form:?}");
                }
            }
        }
        assert!(taken.iter().all(|&n| n > 20_000) && none > 20_000, "{taken:?} {none}");
    }
}
