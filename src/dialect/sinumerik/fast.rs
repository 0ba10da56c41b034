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
    let mut items = Items(Vec::with_capacity(6));
    let (meta, _) = read(norm, whole, &mut items)?;
    Some(Line { meta, kind: LineKind::Plain(items.0), kw: whole })
}

/// For an index-only first scan (`crate::stream::scan_index`): the same decision as
/// [`line`], the block's meta and whether it has words, without building the items.
pub fn skeleton(norm: &Normalised<'_>, whole: Span) -> Option<(BlockMeta, bool)> {
    let (meta, words) = read(norm, whole, &mut Count)?;
    Some((meta, words > 0))
}

/// For a re-read of a checked file (`crate::stream::reread`): the same decision as
/// [`line`], but each item is handed to `each` as (letter, value, point, span) when it is
/// a plain letter word with a number literal (the value negated when written with `-`),
/// and the block is declined when it has another kind of item (`M30`, `M17`: they mean
/// more) or `each` returns `false`. Gives the span and number of the block; its comments
/// are not kept.
pub fn words(
    norm: &Normalised<'_>,
    whole: Span,
    each: impl FnMut(u8, f64, bool, Span) -> bool,
) -> Option<(Span, Option<u32>)> {
    let (meta, _) = read(norm, whole, &mut Each(each))?;
    Some((meta.span, meta.number.map(|n| n.value)))
}

/// One word as [`read`] found it: `text[start..end]`, its letter (upper case), its value
/// (with its sign) and whether it had a decimal point.
struct Found<'t> {
    text: &'t str,
    start: usize,
    end: usize,
    letter: u8,
    value: f64,
    point: bool,
}

/// What [`read`] does with each word it reads.
trait Sink {
    /// Whether the block's comments are kept in its meta.
    const COMMENTS: bool;
    /// The next word; `None` declines the block.
    fn word(&mut self, w: Found<'_>, norm: &Normalised<'_>) -> Option<()>;
}

/// The IR item of a word (`word_item` gives a plain word for every letter but L, left to
/// the grammar, and M: M17, M2, M30 mean more; the others are built directly).
#[inline(always)]
fn item(w: &Found<'_>, norm: &Normalised<'_>) -> (ItemKind, Span) {
    let span = norm.span(w.start, w.end);
    let vspan = norm.span(w.start + 1, w.end);
    let kind = if w.letter == b'M' {
        word_item(w.letter, &w.text[w.start + 1..w.end], w.value, w.point, span, vspan)
    } else {
        ItemKind::Word(Word {
            addr: Addr::Letter(w.letter),
            value: WordValue::Expr(Expr::num(w.value, w.point, vspan)),
            span,
        })
    };
    (kind, span)
}

/// The IR items.
struct Items(Vec<Item>);

impl Sink for Items {
    const COMMENTS: bool = true;
    #[inline(always)]
    fn word(&mut self, w: Found<'_>, norm: &Normalised<'_>) -> Option<()> {
        let (kind, span) = item(&w, norm);
        self.0.push(Item { kind, span });
        Some(())
    }
}

/// Nothing (an index-only scan counts the words).
struct Count;

impl Sink for Count {
    const COMMENTS: bool = true;
    #[inline(always)]
    fn word(&mut self, _: Found<'_>, _: &Normalised<'_>) -> Option<()> {
        Some(())
    }
}

/// Plain words to a callback (see [`words`]).
struct Each<F>(F);

impl<F: FnMut(u8, f64, bool, Span) -> bool> Sink for Each<F> {
    const COMMENTS: bool = false;
    #[inline(always)]
    fn word(&mut self, w: Found<'_>, norm: &Normalised<'_>) -> Option<()> {
        if w.letter == b'M' {
            // Exactly the item `Items` builds: a plain word, or the block is declined.
            let (kind, span) = item(&w, norm);
            let ItemKind::Word(Word { addr: Addr::Letter(letter), value: WordValue::Expr(e), .. }) = kind else {
                return None;
            };
            let ExprKind::Num(n) = e.kind else { return None };
            return (self.0)(letter, n.value, n.point, span).then_some(());
        }
        (self.0)(w.letter, w.value, w.point, norm.span(w.start, w.end)).then_some(())
    }
}

/// One reader for all: the sink says what to build. Every decision is taken the same way
/// whatever the sink (but a sink may decline the block).
#[inline(always)]
fn read<S: Sink>(norm: &Normalised<'_>, whole: Span, sink: &mut S) -> Option<(BlockMeta, usize)> {
    let text: &str = &norm.text;
    let b = text.as_bytes();
    let mut i = 0;
    let mut meta = BlockMeta { span: whole, ..Default::default() };
    let mut words = 0;
    let mut commented = false;
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
            commented = true;
            if S::COMMENTS {
                let span = norm.span(i, b.len());
                meta.comments.push(Comment { text: text[i + 1..].to_string(), span });
            }
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
        let value = if b[i + 1] == b'-' { -value } else { value };
        let letter = c.to_ascii_uppercase();
        sink.word(Found { text, start, end: j, letter, value, point }, norm)?;
        i = j;
    }
    if words == 0 && meta.number.is_none() && !commented {
        return None;
    }
    Some((meta, words))
}
