//! A byte-level reader for the plain motion blocks that make up CAM programs
//! (`N10 G1 X1.234 Y-2.5 F1000 ; comment`): letter + constant words, an optional leading
//! block number and a trailing comment. It gives exactly the IR the grammar gives (a test
//! compares them on many generated blocks) and declines anything else, which then goes to pest.

use super::parse::word_item;
use super::structure::{Line, LineKind};
use crate::ir::*;
use crate::read::Normalised;
use crate::span::Span;

/// The line for `text`, or `None` when the block needs the grammar.
pub fn line(norm: &Normalised<'_>, whole: Span) -> Option<Line> {
    let text: &str = &norm.text;
    let b = text.as_bytes();
    let mut i = 0;
    let mut meta = BlockMeta { span: whole, ..Default::default() };
    let mut items: Vec<Item> = Vec::with_capacity(6);
    let blank = |c: u8| c == b' ' || c == b'\t';
    while i < b.len() && blank(b[i]) {
        i += 1;
    }
    // Optional block number `N123` (not `N1.`, not followed by `=`).
    if i < b.len() && (b[i] == b'N' || b[i] == b'n') {
        let start = i;
        let mut j = i + 1;
        while j < b.len() && b[j].is_ascii_digit() {
            j += 1;
        }
        if j == i + 1 || j - i > 10 || (j < b.len() && !(blank(b[j]) || b[j] == b';' || b[j].is_ascii_alphabetic())) {
            return None;
        }
        let value: u32 = text[i + 1..j].parse().ok()?;
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
        if !c.is_ascii_alphabetic() || matches!(c.to_ascii_uppercase(), b'L' | b'N' | b'P') {
            return None;
        }
        let start = i;
        let mut j = i + 1;
        if j < b.len() && (b[j] == b'-' || b[j] == b'+') {
            j += 1;
        }
        let num = j;
        let mut digits = 0;
        while j < b.len() && b[j].is_ascii_digit() {
            j += 1;
            digits += 1;
        }
        let mut point = false;
        if j < b.len() && b[j] == b'.' {
            point = true;
            j += 1;
            while j < b.len() && b[j].is_ascii_digit() {
                j += 1;
                digits += 1;
            }
        }
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
        let value: f64 = text[num..j].parse().ok()?;
        let value = if b[i + 1] == b'-' { -value } else { value };
        let span = norm.span(start, j);
        let vspan = norm.span(start + 1, j);
        let letter = c.to_ascii_uppercase();
        items.push(Item { kind: word_item(letter, &text[start + 1..j], value, point, span, vspan), span });
        i = j;
    }
    if items.is_empty() && meta.number.is_none() && meta.comments.is_empty() {
        return None;
    }
    Some(Line { meta, kind: LineKind::Plain(items), kw: whole })
}
