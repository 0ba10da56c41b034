//! A byte-level reader for the blocks that dominate CAM output: an optional `/n`, then only
//! letter+number words (`N10 G01 X1.234 Y-2.5 F1000.`). It gives exactly the parts the
//! grammar gives (tested on generated blocks in tests.rs and tests/fast_path_diff.rs) and
//! declines anything else, which then goes to pest. For plain word blocks it also reads
//! straight to the items `block::plain` makes of those parts (`plain_line`), or for an
//! index-only scan to the block's number alone (`skeleton`), or for a streamed re-read to
//! its words alone (`lit_words`); all are tested against the parts route or the IR route.

use super::parse::{literal, skip_level, Lit, Part, Parts, RawWord, Seg};
use crate::ir::{Addr, Expr, Item, ItemKind, SeqNo, WordValue};
use crate::span::Span;

/// The parts of a plain block, or `None` when the block needs the grammar.
pub fn parse_fast(seg: &Seg<'_>) -> Option<Parts> {
    let b = seg.text.as_bytes();
    let mut i = 0;
    // Most blocks have a handful of words; one allocation up front.
    let mut out = Parts { skip: skip_prefix(seg, &mut i)?, parts: Vec::with_capacity(6) };
    loop {
        skip_ws(b, &mut i);
        if i >= b.len() {
            return Some(out);
        }
        let w = word(seg, &mut i)?;
        let value = if w.neg == Some(true) { -w.value } else { w.value };
        out.parts.push(Part::Word(RawWord {
            letter: w.letter,
            value: Expr::num(value, w.point, seg.span(w.vstart, w.hi)),
            span: seg.span(w.start, w.hi),
            lit: Some(Lit { lo: w.lo, hi: w.hi, point: w.point, signed: w.neg.is_some() }),
        }));
    }
}

/// What `block::plain` makes of the parts [`parse_fast`] gives, outside parameter-write
/// mode, without building the parts: the skip level, the block number and the items.
/// `None` when the fast path declines the block or `plain` would hand it back (the caller
/// then takes the full route). The words are read by the same code as in `parse_fast`,
/// each is judged with `plain`'s rule on what `RawWord::int` would give, and its item is
/// the one `plain` makes of its `RawWord`.
pub fn plain_line(seg: &Seg<'_>) -> Option<(Option<u8>, Option<SeqNo>, Vec<Item>)> {
    let mut items = Vec::with_capacity(6);
    let (skip, number) = plain_words(seg, |letter, value, point, span, vspan| {
        items.push(Item {
            kind: ItemKind::Word(crate::ir::Word {
                addr: Addr::Letter(letter),
                value: WordValue::Expr(Expr::num(value, point, vspan)),
                span,
            }),
            span,
        });
        true
    })?;
    Some((skip, number, items))
}

/// For an index-only first scan: [`plain_line`] without building the items, only how many
/// there would be.
pub fn skeleton(seg: &Seg<'_>) -> Option<(Option<u8>, Option<SeqNo>, usize)> {
    let mut words = 0;
    let (skip, number) = plain_words(seg, |_, _, _, _, _| {
        words += 1;
        true
    })?;
    Some((skip, number, words))
}

/// For a re-read of a checked file (`crate::stream::reread`): the same decision as
/// [`plain_line`], but each of the items it would build is handed to `each` as (letter,
/// value with its sign, point, span) instead; the block is declined when `each` returns
/// `false`. Gives the skip level and the block number.
pub fn lit_words(
    seg: &Seg<'_>,
    mut each: impl FnMut(u8, f64, bool, Span) -> bool,
) -> Option<(Option<u8>, Option<SeqNo>)> {
    plain_words(seg, |letter, value, point, span, _| each(letter, value, point, span))
}

/// All of the above: `item` gets each item's word (upper-case letter, value with its sign,
/// point, span of the word and of its value) and may decline the block by returning
/// `false`; every other decision is the same whatever `item` does.
#[inline(always)]
fn plain_words(
    seg: &Seg<'_>,
    mut item: impl FnMut(u8, f64, bool, Span, Span) -> bool,
) -> Option<(Option<u8>, Option<SeqNo>)> {
    let b = seg.text.as_bytes();
    let mut i = 0;
    let skip = skip_prefix(seg, &mut i)?;
    let mut number = None;
    let mut first = true;
    loop {
        skip_ws(b, &mut i);
        if i >= b.len() {
            // `plain` hands back a block without words (a lone skip).
            return (!first).then_some((skip, number));
        }
        let w = word(seg, &mut i)?;
        // `RawWord::int`: a literal without sign or point (its value is not negative).
        let int = (!w.point && w.neg.is_none()).then_some(w.value as u64);
        let ok = match w.letter {
            b'N' => first && int.is_some_and(|n| (1..=99_999).contains(&n)),
            b'O' => false,
            b'G' => !matches!(int, Some(10 | 65 | 66 | 67)),
            b'M' => !matches!(int, Some(2 | 30 | 98 | 99)),
            _ => true,
        };
        if !ok {
            return None;
        }
        match (w.letter, int) {
            (b'N', Some(n)) => number = Some(SeqNo { value: n as u32, span: seg.span(w.start, w.hi) }),
            _ => {
                let value = if w.neg == Some(true) { -w.value } else { w.value };
                if !item(w.letter, value, w.point, seg.span(w.start, w.hi), seg.span(w.vstart, w.hi)) {
                    return None;
                }
            }
        }
        first = false;
    }
}

/// An optional block skip `/` or `/n` at `*i` (after blanks): `None` when it is not
/// followed by a separator, a letter or the end.
fn skip_prefix(seg: &Seg<'_>, i: &mut usize) -> Option<Option<u8>> {
    let b = seg.text.as_bytes();
    skip_ws(b, i);
    if b.get(*i) != Some(&b'/') {
        return Some(None);
    }
    let mut j = *i + 1;
    if b.get(j).is_some_and(u8::is_ascii_digit) {
        j += 1;
    }
    let level = skip_level(&seg.text[*i..j]);
    *i = j;
    ends_token(b, j).then_some(Some(level))
}

/// One address word as the fast path reads it.
struct Word {
    /// Upper case.
    letter: u8,
    /// Where the letter, the value (its sign) and the digits start; one past the end.
    start: usize,
    vstart: usize,
    lo: usize,
    hi: usize,
    /// The sign, if written: `Some(true)` for `-`.
    neg: Option<bool>,
    point: bool,
    /// The value of the digits (without the sign).
    value: f64,
}

/// The word at `*i` (a letter, blanks, an optional sign, digits with an optional point),
/// or `None` when it is anything else or not followed by a separator, a letter or the end.
#[inline(always)]
fn word(seg: &Seg<'_>, i: &mut usize) -> Option<Word> {
    let b = seg.text.as_bytes();
    let letter = *b.get(*i)?;
    if !letter.is_ascii_alphabetic() {
        return None;
    }
    let start = *i;
    *i += 1;
    skip_ws(b, i);
    let vstart = *i;
    let mut neg = None;
    if let Some(&c @ (b'-' | b'+')) = b.get(*i) {
        neg = Some(c == b'-');
        *i += 1;
        skip_ws(b, i);
    }
    let lo = *i;
    // The digits as one whole number and how many follow the point: up to 15 digits
    // the value is exact without a second pass (`read::scaled`); longer ones are parsed.
    let mut mant: u64 = 0;
    let mut digits = 0;
    while let Some(&c @ b'0'..=b'9') = b.get(*i) {
        mant = mant.wrapping_mul(10).wrapping_add(u64::from(c - b'0'));
        *i += 1;
        digits += 1;
    }
    let mut point = false;
    let mut frac = 0;
    if b.get(*i) == Some(&b'.') {
        point = true;
        *i += 1;
        while let Some(&c @ b'0'..=b'9') = b.get(*i) {
            mant = mant.wrapping_mul(10).wrapping_add(u64::from(c - b'0'));
            *i += 1;
            frac += 1;
        }
    }
    digits += frac;
    if digits == 0 || !ends_token(b, *i) {
        return None;
    }
    let value = match crate::read::scaled(mant, frac).filter(|_| digits <= 15) {
        Some(v) => v,
        None => literal(&seg.text[lo..*i]).value,
    };
    Some(Word { letter: letter.to_ascii_uppercase(), start, vstart, lo, hi: *i, neg, point, value })
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
