//! A byte-level reader for the plain motion blocks that make up CAM programs
//! (`N10 G1 X1.234 Y-2.5 F1000 ; comment`): letter + constant words, an optional leading
//! block number and a trailing comment. It gives exactly the IR the grammar gives (a test
//! compares them on many generated blocks) and declines anything else, which then goes to pest.
//! For an index-only scan, `skeleton` takes the same decisions without building the items.

use super::parse::word_item;
use super::structure::{Line, LineKind};
use crate::ir::*;
use crate::read::Normalised;
use crate::span::Span;

/// The line for `text`, or `None` when the block needs the grammar.
pub fn line(norm: &Normalised<'_>, whole: Span) -> Option<Line> {
    let (meta, items, _) = read(norm, whole, true)?;
    Some(Line { meta, kind: LineKind::Plain(items), kw: whole })
}

/// For an index-only first scan (`crate::stream::scan_index`): the same decision as
/// [`line`], the block's meta and whether it has words, without building the items.
pub fn skeleton(norm: &Normalised<'_>, whole: Span) -> Option<(BlockMeta, bool)> {
    let (meta, _, words) = read(norm, whole, false)?;
    Some((meta, words > 0))
}

/// One reader for both: `keep` says whether to build the items. Every decision is taken
/// the same way either way; only the pushing of items depends on `keep`.
#[inline(always)]
fn read(norm: &Normalised<'_>, whole: Span, keep: bool) -> Option<(BlockMeta, Vec<Item>, usize)> {
    let text: &str = &norm.text;
    let b = text.as_bytes();
    let mut i = 0;
    let mut meta = BlockMeta { span: whole, ..Default::default() };
    let mut items: Vec<Item> = if keep { Vec::with_capacity(6) } else { Vec::new() };
    let mut words = 0;
    let blank = |c: u8| c == b' ' || c == b'\t';
    while i < b.len() && blank(b[i]) {
        i += 1;
    }
    // Optional block number `N123` (not `N1.`, not followed by `=`), at most nine digits.
    if i < b.len() && (b[i] | 0x20) == b'n' {
        let start = i;
        let mut j = i + 1;
        let mut value: u32 = 0;
        while j < b.len() && b[j].is_ascii_digit() {
            if j - i > 9 {
                return None;
            }
            value = value * 10 + u32::from(b[j] - b'0');
            j += 1;
        }
        if j == i + 1 || (j < b.len() && !(blank(b[j]) || b[j] == b';' || b[j].is_ascii_alphabetic())) {
            return None;
        }
        meta.number = Some(SeqNo { value, span: norm.span(start, j) });
        i = j;
    }
    loop {
        while i < b.len() && blank(b[i]) {
            i += 1;
        }
        if i >= b.len() {
            break;
        }
        if b[i] == b';' {
            let span = norm.span(i, b.len());
            meta.comments.push(Comment { text: text[i + 1..].to_string(), span });
            break;
        }
        let c = b[i];
        // Letters that mean more than a word (L calls, N numbers, P repeat counts after a
        // call) are left to the grammar.
        if !c.is_ascii_alphabetic() || matches!(c | 0x20, b'l' | b'n' | b'p') {
            return None;
        }
        let start = i;
        let mut j = i + 1;
        if j < b.len() && (b[j] == b'-' || b[j] == b'+') {
            j += 1;
        }
        // The digits as one whole number and how many follow the point: the value is then
        // exact (see `read::scaled`), so no second pass over the text is needed.
        let mut mant: u64 = 0;
        let mut digits = 0;
        while j < b.len() && b[j].is_ascii_digit() {
            mant = mant.wrapping_mul(10).wrapping_add(u64::from(b[j] - b'0'));
            j += 1;
            digits += 1;
        }
        let mut point = false;
        let mut frac = 0;
        if j < b.len() && b[j] == b'.' {
            point = true;
            j += 1;
            while j < b.len() && b[j].is_ascii_digit() {
                mant = mant.wrapping_mul(10).wrapping_add(u64::from(b[j] - b'0'));
                j += 1;
                frac += 1;
            }
        }
        digits += frac;
        if digits == 0 || digits > 15 {
            return None;
        }
        // The word must end at a blank, the comment, the end, or the next letter word (`G1X10`),
        // and must not be an exponent (`1EX3`) or a numbered address (`X1=`).
        if j < b.len() {
            let n = b[j];
            if n == b'.' || n == b'=' || n == b'[' || n == b'(' {
                return None;
            }
            if n.is_ascii_alphabetic() {
                if (n == b'E' || n == b'e') && b.get(j + 1).is_some_and(|x| *x == b'X' || *x == b'x') {
                    return None;
                }
            } else if !(blank(n) || n == b';') {
                return None;
            }
            let mut k = j;
            while k < b.len() && blank(b[k]) {
                k += 1;
            }
            if k < b.len() && matches!(b[k], b'=' | b'[' | b'(') {
                return None;
            }
        }
        // At most 15 digits: below 2^53, so `scaled` is exact and always answers.
        let value = crate::read::scaled(mant, frac)?;
        words += 1;
        if keep {
            let value = if b[i + 1] == b'-' { -value } else { value };
            let span = norm.span(start, j);
            let vspan = norm.span(start + 1, j);
            let letter = c.to_ascii_uppercase();
            // `word_item` gives a plain word for every letter but L (left to the grammar
            // above) and M (M17, M2, M30 mean more); build those directly.
            let kind = if letter == b'M' {
                word_item(letter, &text[start + 1..j], value, point, span, vspan)
            } else {
                ItemKind::Word(Word {
                    addr: Addr::Letter(letter),
                    value: WordValue::Expr(Expr::num(value, point, vspan)),
                    span,
                })
            };
            items.push(Item { kind, span });
        }
        i = j;
    }
    if words == 0 && meta.number.is_none() && meta.comments.is_empty() {
        return None;
    }
    Some((meta, items, words))
}
