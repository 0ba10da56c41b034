//! A byte-level reader for the blocks that dominate CAM output: an optional `/n`, then only
//! letter+number words (`N10 G01 X1.234 Y-2.5 F1000.`). It gives exactly the parts the
//! grammar gives (tested on generated blocks in tests.rs) and declines anything else, which
//! then goes to pest. This keeps large programs well above 400,000 blocks per second.

use super::parse::{literal, skip_level, Lit, Part, Parts, RawWord, Seg};
use crate::ir::Expr;

/// The parts of a plain block, or `None` when the block needs the grammar.
pub fn parse_fast(seg: &Seg<'_>) -> Option<Parts> {
    let b = seg.text.as_bytes();
    let mut i = 0;
    // Most blocks have a handful of words; one allocation up front.
    let mut out = Parts { skip: None, parts: Vec::with_capacity(6) };
    skip_ws(b, &mut i);
    if b.get(i) == Some(&b'/') {
        let mut j = i + 1;
        if b.get(j).is_some_and(u8::is_ascii_digit) {
            j += 1;
        }
        out.skip = Some(skip_level(&seg.text[i..j]));
        i = j;
        if !ends_token(b, i) {
            return None;
        }
    }
    loop {
        skip_ws(b, &mut i);
        if i >= b.len() {
            return Some(out);
        }
        let letter = b[i];
        if !letter.is_ascii_alphabetic() {
            return None;
        }
        let start = i;
        i += 1;
        skip_ws(b, &mut i);
        let vstart = i;
        let mut neg = None;
        if let Some(&c @ (b'-' | b'+')) = b.get(i) {
            neg = Some(c == b'-');
            i += 1;
            skip_ws(b, &mut i);
        }
        let lo = i;
        // The digits as one whole number and how many follow the point: up to 15 digits
        // the value is exact without a second pass (`read::scaled`); longer ones are parsed.
        let mut mant: u64 = 0;
        let mut digits = 0;
        while let Some(&c @ b'0'..=b'9') = b.get(i) {
            mant = mant.wrapping_mul(10).wrapping_add(u64::from(c - b'0'));
            i += 1;
            digits += 1;
        }
        let mut point = false;
        let mut frac = 0;
        if b.get(i) == Some(&b'.') {
            point = true;
            i += 1;
            while let Some(&c @ b'0'..=b'9') = b.get(i) {
                mant = mant.wrapping_mul(10).wrapping_add(u64::from(c - b'0'));
                i += 1;
                frac += 1;
            }
        }
        digits += frac;
        if digits == 0 || !ends_token(b, i) {
            return None;
        }
        let n = match crate::read::scaled(mant, frac).filter(|_| digits <= 15) {
            Some(v) => v,
            None => literal(&seg.text[lo..i]).value,
        };
        let value = if neg == Some(true) { -n } else { n };
        out.parts.push(Part::Word(RawWord {
            letter: letter.to_ascii_uppercase(),
            value: Expr::num(value, point, seg.span(vstart, i)),
            span: seg.span(start, i),
            lit: Some(Lit { lo, hi: i, point, signed: neg.is_some() }),
        }));
    }
}

/// For tests: the fast path on one line of text.
pub fn parse_fast_for_test(text: &str) -> Option<Parts> {
    super::parse::with_seg(text, |seg, _| parse_fast(seg))
}

fn skip_ws(b: &[u8], i: &mut usize) {
    while matches!(b.get(*i), Some(b' ' | b'\t' | b'\x0C')) {
        *i += 1;
    }
}

/// A literal may be followed only by a separator, the next letter, or the end.
fn ends_token(b: &[u8], i: usize) -> bool {
    match b.get(i) {
        None => true,
        Some(c) => matches!(c, b' ' | b'\t' | b'\x0C') || c.is_ascii_alphabetic(),
    }
}
