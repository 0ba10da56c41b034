//! A byte-level reader for the plain motion blocks that make up CAM programs
//! (`N10 G1 X1.234 Y-2.5 F1000 ; comment`): letter + constant words, an optional leading
//! block number and a trailing comment. It gives exactly the IR the grammar gives (a test
//! compares them on many generated blocks) and declines anything else, which then goes to pest.
//! For an index-only scan, `skeleton` takes the same decisions without building the items.

use super::parse::word_item;
use super::structure::{Line, LineKind};
use crate::dialect::lit::LitBlock;
use crate::ir::*;
use crate::read::Normalised;
use crate::span::Span;

/// The line for `text`, or `None` when the block needs the grammar.
pub fn line(norm: &Normalised<'_>, whole: Span) -> Option<Line> {
    let mut items = Items(Vec::with_capacity(6));
    let head = read(norm, &mut items)?;
    Some(Line { meta: head.meta(norm, whole), kind: LineKind::Plain(items.0), kw: whole })
}

/// For an index-only first scan (`crate::stream::scan_index`): the same decision as
/// [`line`], the block's meta and whether it has words, without building the items.
pub fn skeleton(norm: &Normalised<'_>, whole: Span) -> Option<(BlockMeta, bool)> {
    let head = read(norm, &mut Count)?;
    let words = head.words > 0;
    Some((head.meta(norm, whole), words))
}

/// For an index-only first scan of a plain top-level line (`Reader::scan_plain`): the
/// decision of [`skeleton`] on `raw` taken as it is, its block number and whether it has
/// words. Only for an ASCII line: [`read`] declines every letter O, and a letter O in a G
/// word is the only ASCII text `read::normalise` changes, so `raw` is what normalising
/// would give (see `read::Normalised::unchanged`).
pub fn skeleton_raw(raw: &crate::read::RawBlock<'_>) -> Option<(Option<SeqNo>, bool)> {
    let norm = Normalised::unchanged(raw);
    let head = read(&norm, &mut Count)?;
    Some((head.number, head.words > 0))
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
    let head = read(norm, &mut Each(each))?;
    Some((whole, head.number.map(|n| n.value)))
}

/// [`words`] on an ASCII line `raw` taken as it is (see [`skeleton_raw`] for why that is
/// what normalising would give); its whole span is the line's.
pub fn words_raw(
    raw: &crate::read::RawBlock<'_>,
    each: impl FnMut(u8, f64, bool, Span) -> bool,
) -> Option<(Span, Option<u32>)> {
    let norm = Normalised::unchanged(raw);
    let whole = Span::new(raw.start, raw.start + raw.text.len() as u32);
    words(&norm, whole, each)
}

/// [`words_raw`] straight into the compact block `b` (`crate::stream::reread`): each
/// word is pushed as (letter, value, point, [`LitWord::milli`] from its digits, span),
/// without a callback between; the line is declined where `b.push` declines a word (`b`
/// is then to be dropped). Gives the line's span, its number and whether it has words.
///
/// [`LitWord::milli`]: crate::dialect::lit::LitWord::milli
///
/// Most lines are taken by `quick::lit_words` (the words it takes are ones [`read`] reads
/// alike: no M, which `item` judges, no letter [`read`] leaves to the grammar, and those
/// it does not begin with: N, lower case); the others, read by [`read`].
pub fn lit_raw(raw: &crate::read::RawBlock<'_>, b: &mut LitBlock) -> Option<(Span, Option<u32>, bool)> {
    let whole = Span::new(raw.start, raw.start + raw.text.len() as u32);
    if crate::dialect::quick::lit_words(raw.text, raw.start, b, QUICK) {
        return Some((whole, None, true));
    }
    b.clear();
    let norm = Normalised::unchanged(raw);
    let head = read(&norm, &mut Lit(b))?;
    Some((whole, head.number.map(|n| n.value), head.words > 0))
}

/// [`lit_raw`]'s quick reader on a line read straight from a read buffer (see
/// `quick::lit_words_buf`): the line's length when it takes the line, as [`lit_raw`]
/// would with the line's whole span, no number and words.
#[inline(always)]
pub fn lit_buf(ahead: &[u8], start: u32, b: &mut LitBlock) -> Option<usize> {
    crate::dialect::quick::lit_words_buf(ahead, start, b, QUICK)
}

/// The words `quick::lit_words` may take for [`lit_raw`]: those [`read`] reads alike
/// (see there).
pub const QUICK: crate::dialect::quick::Rule =
    crate::dialect::quick::Rule { refuse: crate::dialect::quick::Rule::letters(b"LMNOP"), g_macro: false };

/// For a streamed translator's first scan of a plain top-level line
/// (`Reader::scan_plain_words`): [`skeleton_raw`] and [`words_raw`] in one pass. The
/// decisions are [`read`]'s, the same for both; the line is declined when `each` declines
/// a word (as [`words_raw`] declines it). Gives the block number, whether it has words and
/// where its comment starts (its `;`, an offset into `raw.text`).
pub fn scan_words_raw(
    raw: &crate::read::RawBlock<'_>,
    each: impl FnMut(u8, f64, bool, Span) -> bool,
) -> Option<(Option<SeqNo>, bool, Option<usize>)> {
    let norm = Normalised::unchanged(raw);
    let head = read(&norm, &mut Each(each))?;
    Some((head.number, head.words > 0, head.comment))
}

/// One word as [`read`] found it: `text[start..end]`, its letter (upper case), its digits
/// as one whole number `mant` with `frac` of them after the point (when the sink wants
/// values), its sign and whether it had a decimal point.
struct Found<'t> {
    text: &'t str,
    start: usize,
    end: usize,
    letter: u8,
    mant: u64,
    frac: usize,
    neg: bool,
    point: bool,
}

impl Found<'_> {
    /// The value with its sign: at most 15 digits (below 2^53), so `read::exact` is exact
    /// and always answers (the `0.0` is never taken).
    #[inline(always)]
    fn value(&self) -> f64 {
        let v = crate::read::exact(self.mant, self.frac).unwrap_or(0.0);
        if self.neg {
            -v
        } else {
            v
        }
    }
}

/// What [`read`] does with each word it reads.
trait Sink {
    /// Whether the sink wants the words' values (`Found::mant` is 0 otherwise).
    const VALUES: bool;
    /// The next word; `None` declines the block.
    fn word(&mut self, w: Found<'_>, norm: &Normalised<'_>) -> Option<()>;
}

/// The IR item of a word (`word_item` gives a plain word for every letter but L, left to
/// the grammar, and M: M17, M2, M30 mean more; the others are built directly).
#[inline(always)]
fn item(w: &Found<'_>, norm: &Normalised<'_>) -> (ItemKind, Span) {
    let span = norm.span(w.start, w.end);
    let vspan = norm.span(w.start + 1, w.end);
    let value = w.value();
    let kind = if w.letter == b'M' {
        word_item(w.letter, &w.text[w.start + 1..w.end], value, w.point, span, vspan)
    } else {
        ItemKind::Word(Word {
            addr: Addr::Letter(w.letter),
            value: WordValue::Expr(Expr::num(value, w.point, vspan)),
            span,
        })
    };
    (kind, span)
}

/// The IR items.
struct Items(Vec<Item>);

impl Sink for Items {
    const VALUES: bool = true;
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
    const VALUES: bool = false;
    #[inline(always)]
    fn word(&mut self, _: Found<'_>, _: &Normalised<'_>) -> Option<()> {
        Some(())
    }
}

/// Plain words to a callback (see [`words`]).
struct Each<F>(F);

impl<F: FnMut(u8, f64, bool, Span) -> bool> Sink for Each<F> {
    const VALUES: bool = true;
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
        (self.0)(w.letter, w.value(), w.point, norm.span(w.start, w.end)).then_some(())
    }
}

/// Plain words into a compact block (see [`lit_raw`]): what [`Each`] hands its callback.
struct Lit<'b>(&'b mut LitBlock);

impl Sink for Lit<'_> {
    const VALUES: bool = true;
    #[inline(always)]
    fn word(&mut self, w: Found<'_>, norm: &Normalised<'_>) -> Option<()> {
        let value = w.value();
        // At most 15 digits (`read` declines more): `mant` is the digits' number.
        let mut milli = crate::dialect::lit::milli(w.neg, Some((w.mant, w.frac)));
        if w.letter == b'M' {
            // Exactly the item `Items` builds: a plain word, or the block is declined.
            let (kind, span) = item(&w, norm);
            let ItemKind::Word(Word { addr: Addr::Letter(letter), value: WordValue::Expr(e), .. }) = kind else {
                return None;
            };
            let ExprKind::Num(n) = e.kind else { return None };
            if n.value.to_bits() != value.to_bits() {
                milli = crate::dialect::lit::NO_MILLI;
            }
            return self.0.push(letter, n.value, n.point, milli, span).then_some(());
        }
        self.0.push(w.letter, value, w.point, milli, norm.span(w.start, w.end)).then_some(())
    }
}

/// What [`read`] found besides the words: the block number, how many words, and where
/// the comment starts (its `;`).
struct Head {
    number: Option<SeqNo>,
    words: usize,
    comment: Option<usize>,
}

impl Head {
    /// The block's meta (its span is the whole line).
    fn meta(self, norm: &Normalised<'_>, whole: Span) -> BlockMeta {
        let mut meta = BlockMeta { span: whole, number: self.number, ..Default::default() };
        if let Some(i) = self.comment {
            let span = norm.span(i, norm.text.len());
            meta.comments.push(Comment { text: norm.text[i + 1..].to_string(), span });
        }
        meta
    }
}

/// A blank between words.
#[inline(always)]
fn blank(c: u8) -> bool {
    c == b' ' || c == b'\t'
}

/// One reader for all: the sink says what to build. Every decision is taken the same way
/// whatever the sink (but a sink may decline the block).
#[inline(always)]
fn read<S: Sink>(norm: &Normalised<'_>, sink: &mut S) -> Option<Head> {
    let text: &str = &norm.text;
    let b = text.as_bytes();
    let len = b.len();
    let mut i = 0;
    let mut head = Head { number: None, words: 0, comment: None };
    while i < len && blank(b[i]) {
        i += 1;
    }
    // Optional block number `N123` (not `N1.`, not followed by `=`), at most nine digits.
    if i < len && (b[i] | 0x20) == b'n' {
        let start = i;
        let mut j = i + 1;
        let mut value: u32 = 0;
        while j < len && b[j].is_ascii_digit() {
            if j - i > 9 {
                return None;
            }
            value = value * 10 + u32::from(b[j] - b'0');
            j += 1;
        }
        if j == i + 1 || (j < len && !(blank(b[j]) || b[j] == b';' || b[j].is_ascii_alphabetic())) {
            return None;
        }
        head.number = Some(SeqNo { value, span: norm.span(start, j) });
        i = j;
    }
    // Blanks are skipped here and after each word (where the next word is looked for).
    while i < len && blank(b[i]) {
        i += 1;
    }
    loop {
        if i >= len {
            break;
        }
        let c = b[i];
        if c == b';' {
            head.comment = Some(i);
            break;
        }
        // Letters that mean more than a word (L calls, N numbers, P repeat counts after a
        // call) are left to the grammar; so is O, so that a line read without normalising
        // is read only when normalising would not change it (`GO1` → `G01`).
        let letter = c & !0x20;
        if !letter.is_ascii_uppercase() || matches!(letter, b'L' | b'N' | b'O' | b'P') {
            return None;
        }
        let start = i;
        let mut j = i + 1;
        let sign = if j < len { b[j] } else { 0 };
        let neg = sign == b'-';
        if neg || sign == b'+' {
            j += 1;
        }
        // The digits as one whole number (the point left out) and how many follow the
        // point: the value is then exact (see `read::scaled`), no second pass needed.
        let from = j;
        let mut mant: u64 = 0;
        j = crate::read::digit_run(b, j, S::VALUES, &mut mant);
        let mut digits = j - from;
        let point = j < len && b[j] == b'.';
        let mut frac = 0;
        if point {
            j += 1;
            let from = j;
            j = crate::read::digit_run(b, j, S::VALUES, &mut mant);
            frac = j - from;
            digits += frac;
        }
        if digits == 0 || digits > 15 {
            return None;
        }
        // The word must end at a blank, the comment, the end, or the next letter word (`G1X10`),
        // and must not be an exponent (`1EX3`) or a numbered address (`X1=`).
        // Where the next word or the comment is looked for (past the blanks looked over).
        let mut next = j;
        if j < len {
            let n = b[j];
            if n.is_ascii_alphabetic() {
                if (n | 0x20) == b'e' && j + 1 < len && (b[j + 1] | 0x20) == b'x' {
                    return None;
                }
            } else if blank(n) {
                next += 1;
                while next < len && blank(b[next]) {
                    next += 1;
                }
                if next < len && matches!(b[next], b'=' | b'[' | b'(') {
                    return None;
                }
            } else if n != b';' {
                return None;
            }
        }
        head.words += 1;
        sink.word(Found { text, start, end: j, letter, mant, frac, neg, point }, norm)?;
        i = next;
    }
    if head.words == 0 && head.number.is_none() && head.comment.is_none() {
        return None;
    }
    Some(head)
}
