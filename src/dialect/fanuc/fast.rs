//! A byte-level reader for the blocks that dominate CAM output: an optional `/n`, then only
//! letter+number words (`N10 G01 X1.234 Y-2.5 F1000.`). It gives exactly the parts the
//! grammar gives (tested on generated blocks in tests.rs and tests/fast_path_diff.rs) and
//! declines anything else, which then goes to pest. For plain word blocks it also reads
//! straight to the items `block::plain` makes of those parts (`plain_line`), or for an
//! index-only scan to the block's number alone (`skeleton`), or for a streamed re-read to
//! its words alone (`lit_line`); all are tested against the parts route or the IR route.

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
        let w = word::<true>(seg, &mut i)?;
        let value = w.value(seg);
        let value = if w.neg == Some(true) { -value } else { value };
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
    let (skip, number, stop) = plain_words::<true>(seg, |letter, value, point, span, vspan, _| {
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
    // A segment holds no `;` (the block must be all of it).
    (stop == seg.text.len()).then_some((skip, number, items))
}

/// For an index-only first scan: [`plain_line`] without building the items, only how many
/// there would be.
pub fn skeleton(seg: &Seg<'_>) -> Option<(Option<u8>, Option<SeqNo>, usize)> {
    let mut words = 0;
    let (skip, number, stop) = plain_words::<false>(seg, |_, _, _, _, _, _| {
        words += 1;
        true
    })?;
    (stop == seg.text.len()).then_some((skip, number, words))
}

/// For an index-only first scan of a whole line taken as it is (`Reader::scan_plain`):
/// [`skeleton`] of the one block `line` holds, with the block cut as `scan::segments`
/// cuts it: `(lo, hi, end)` of that block (see there), its number and whether it has
/// words. `None` when the line holds anything else, or more than one block.
/// `seg` is the whole line (`base` 0): [`plain_words`] stops at a `;`, which a segment
/// never holds.
#[allow(clippy::type_complexity)]
pub fn skeleton_line(seg: &Seg<'_>) -> Option<((usize, usize, usize), Option<SeqNo>, bool)> {
    let mut words = false;
    let (_, number, stop) = plain_words::<false>(seg, |_, _, _, _, _, _| {
        words = true;
        true
    })?;
    Some((cut(seg.text.as_bytes(), stop)?, number, words))
}

/// For a re-read of a checked file (`crate::stream::reread`), a whole line taken as it is
/// (`Reader::plain_words`): the same decision as [`plain_line`] on the one block the line
/// holds, cut as [`skeleton_line`] cuts it, but each of the items it would build is handed
/// to `each` as (letter, value with its sign, point, span) instead; the block is declined
/// when `each` returns `false`. Gives `(lo, hi, end)` of the block and its number.
#[allow(clippy::type_complexity)]
pub fn lit_line(
    seg: &Seg<'_>,
    mut each: impl FnMut(u8, f64, bool, Span) -> bool,
) -> Option<((usize, usize, usize), Option<SeqNo>)> {
    let (_, number, stop) =
        plain_words::<true>(seg, |letter, value, point, span, _, _| each(letter, value, point, span))?;
    Some((cut(seg.text.as_bytes(), stop)?, number))
}

/// [`skeleton_line`] on an ASCII line `raw` taken as it is (`Reader::scan_plain` says why
/// that is what normalising would give): the block's span, number and whether it has
/// words. The unchanged `Normalised` is made here, where nothing is left of it to drop.
pub fn skeleton_raw(raw: &crate::read::RawBlock<'_>, file: crate::span::FileId) -> Option<(Span, Option<SeqNo>, bool)> {
    let norm = crate::read::Normalised::unchanged(raw);
    let seg = Seg { norm: &norm, base: 0, text: raw.text, file };
    let ((lo, _, end), number, words) = skeleton_line(&seg)?;
    Some((norm.span(lo, end), number, words))
}

/// [`lit_line`] on an ASCII line `raw` taken as it is (`Reader::plain_words` says why):
/// the block's span and number.
pub fn lit_raw(
    raw: &crate::read::RawBlock<'_>,
    file: crate::span::FileId,
    each: impl FnMut(u8, f64, bool, Span) -> bool,
) -> Option<(Span, Option<SeqNo>)> {
    let norm = crate::read::Normalised::unchanged(raw);
    let seg = Seg { norm: &norm, base: 0, text: raw.text, file };
    let ((lo, _, end), number) = lit_line(&seg, each)?;
    Some((norm.span(lo, end), number))
}

/// [`lit_raw`] straight into the compact block `b` (`Reader::lit`): each word is pushed as
/// (letter, value with its sign, point, [`LitWord::milli`] from its digits, span) without a
/// callback between; the line is declined where `b.push` declines a word (`b` is then to
/// be dropped). The block's span and number.
///
/// [`LitWord::milli`]: crate::dialect::lit::LitWord::milli
pub fn lit_block(
    raw: &crate::read::RawBlock<'_>,
    file: crate::span::FileId,
    b: &mut crate::dialect::lit::LitBlock,
) -> Option<(Span, Option<SeqNo>)> {
    // Most lines are taken by `quick::lit_words`: the words it takes are ones
    // [`plain_words`] takes alike (see [`QUICK`]), in a line without a skip, blanks
    // at either end, or a `;`, so cut from its start to its end.
    if crate::dialect::quick::lit_words(raw.text, raw.start, b, QUICK) {
        return Some((Span::new(raw.start, raw.start + raw.text.len() as u32), None));
    }
    b.clear();
    let norm = crate::read::Normalised::unchanged(raw);
    let seg = Seg { norm: &norm, base: 0, text: raw.text, file };
    let (_, number, stop) = plain_words::<true>(&seg, |letter, value, point, span, _, digits| {
        let neg = value.is_sign_negative();
        b.push(letter, value, point, crate::dialect::lit::milli(neg, digits), span)
    })?;
    let (lo, _, end) = cut(seg.text.as_bytes(), stop)?;
    Some((norm.span(lo, end), number))
}

/// The words `quick::lit_words` may take for [`lit_block`]: ones [`plain_words`] takes
/// alike (no N, O or M, which it judges, no G it refuses).
pub const QUICK: crate::dialect::quick::Rule =
    crate::dialect::quick::Rule { refuse: crate::dialect::quick::Rule::letters(b"MNO"), g_macro: true };

/// [`lit_block`]'s quick reader on a line read straight from a read buffer (see
/// `quick::lit_words_buf`): the line's length when it takes the line, as [`lit_block`]
/// would with the line's whole span and no number.
#[inline(always)]
pub fn lit_buf(ahead: &[u8], start: u32, b: &mut crate::dialect::lit::LitBlock) -> Option<usize> {
    crate::dialect::quick::lit_words_buf(ahead, start, b, QUICK)
}

/// For a streamed translator's first scan of a whole line taken as it is
/// (`Reader::scan_plain_words`): [`skeleton_raw`] and [`lit_raw`] in one pass (the words
/// are read with their values; no decision depends on that, see [`plain_words`]). `None`
/// also for a block with a skip (`/`, `/2`): its skip level is not handed out.
pub fn scan_words_raw(
    raw: &crate::read::RawBlock<'_>,
    file: crate::span::FileId,
    mut each: impl FnMut(u8, f64, bool, Span) -> bool,
) -> Option<(Span, Option<SeqNo>, bool)> {
    let norm = crate::read::Normalised::unchanged(raw);
    let seg = Seg { norm: &norm, base: 0, text: raw.text, file };
    let mut words = false;
    let (skip, number, stop) = plain_words::<true>(&seg, |letter, value, point, span, _, _| {
        words = true;
        each(letter, value, point, span)
    })?;
    if skip.is_some() {
        return None;
    }
    let (lo, _, end) = cut(seg.text.as_bytes(), stop)?;
    Some((norm.span(lo, end), number, words))
}

/// Where `scan::segments` puts the one block of a line `b` that [`plain_words`] read up to
/// `stop` (the end, or a `;`): `(lo, hi, end)`; `None` when more follows the `;` (more
/// blocks, or a comment).
#[inline(always)]
fn cut(b: &[u8], stop: usize) -> Option<(usize, usize, usize)> {
    // Only blanks and `;` after the end-of-block `;`: empty segments, skipped.
    if stop < b.len() && !b[stop + 1..].iter().all(|c| matches!(c, b' ' | b'\t' | b'\x0C' | b';')) {
        return None;
    }
    // The block starts at its first word or skip (only blanks before), and ends at its
    // last character that is not a blank, or after its `;`.
    let lo = b.iter().position(|c| !matches!(c, b' ' | b'\t' | b'\x0C'))?;
    let mut hi = stop;
    while hi > lo && matches!(b[hi - 1], b' ' | b'\t' | b'\x0C') {
        hi -= 1;
    }
    let end = if stop < b.len() { stop + 1 } else { hi };
    Some((lo, hi, end))
}

/// All of the above: `item` gets each item's word (upper-case letter, value with its sign
/// when `VALUES`, else 0, point, span of the word and of its value, and when `VALUES` and
/// at most 15 digits, the digits as one number and how many follow the point, else
/// `None`) and may decline the
/// block by returning `false`; every other decision is the same whatever `item` does. Also
/// gives where the block stopped: the end of `seg`, or a `;` (which only a whole line read
/// as one, see [`skeleton_line`], can hold).
#[inline(always)]
fn plain_words<const VALUES: bool>(
    seg: &Seg<'_>,
    mut item: impl FnMut(u8, f64, bool, Span, Span, Option<(u64, usize)>) -> bool,
) -> Option<(Option<u8>, Option<SeqNo>, usize)> {
    let b = seg.text.as_bytes();
    let mut i = 0;
    let skip = skip_prefix(seg, &mut i)?;
    let mut number = None;
    let mut first = true;
    loop {
        skip_ws(b, &mut i);
        if i >= b.len() || b[i] == b';' {
            // `plain` hands back a block without words (a lone skip).
            return (!first).then_some((skip, number, i));
        }
        let w = word::<VALUES>(seg, &mut i)?;
        // `RawWord::int`: a literal without sign or point (its value is not negative).
        // Only N, G and M words are judged by it.
        let int =
            if matches!(w.letter, b'N' | b'G' | b'M') && !w.point && w.neg.is_none() { Some(w.int(seg)) } else { None };
        let ok = match w.letter {
            b'N' => first && int.is_some_and(|n| (1..=99_999).contains(&n)),
            b'O' => false,
            b'G' => !matches!(int, Some(10 | 65 | 66 | 67)),
            b'M' => !matches!(int, Some(2 | 30 | 96 | 97 | 98 | 99)),
            _ => true,
        };
        if !ok {
            return None;
        }
        match (w.letter, int) {
            (b'N', Some(n)) => number = Some(SeqNo { value: n as u32, span: seg.span(w.start, w.hi) }),
            _ => {
                let value = if VALUES { w.value(seg) } else { 0.0 };
                let value = if w.neg == Some(true) { -value } else { value };
                let digits = w.mant.filter(|_| w.digits <= 15).map(|m| (m, w.frac));
                if !item(w.letter, value, w.point, seg.span(w.start, w.hi), seg.span(w.vstart, w.hi), digits) {
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
    /// How many digits, how many after the point, and when read, their value as one
    /// whole number (meaningful up to 15 digits).
    digits: usize,
    frac: usize,
    mant: Option<u64>,
}

impl Word {
    /// The value of the digits (without the sign): up to 15 digits read as one whole
    /// number with how many follow the point, which is exact (`read::scaled`); longer
    /// ones are parsed.
    #[inline(always)]
    fn value(&self, seg: &Seg<'_>) -> f64 {
        if self.digits <= 15 {
            if let Some(mant) = self.mant {
                if let Some(v) = crate::read::exact(mant, self.frac) {
                    return v;
                }
            }
            let text = &seg.text.as_bytes()[self.lo..self.hi];
            let mut mant: u64 = 0;
            let mut frac = 0;
            let mut after = false;
            for &c in text {
                if c == b'.' {
                    after = true;
                } else {
                    mant = mant * 10 + u64::from(c - b'0');
                    frac += usize::from(after);
                }
            }
            if let Some(v) = crate::read::scaled(mant, frac) {
                return v;
            }
        }
        literal(&seg.text[self.lo..self.hi]).value
    }
}

impl Word {
    /// `value as u64` for a literal without sign or point: its digits as read, when they
    /// are (at most 15 digits: the value is exactly `mant`).
    #[inline(always)]
    fn int(&self, seg: &Seg<'_>) -> u64 {
        match self.mant {
            Some(mant) if self.digits <= 15 && self.frac == 0 => mant,
            // Not read (an index-only scan): only digits between `lo` and `hi` (no point).
            None if self.digits <= 15 && !self.point => {
                seg.text.as_bytes()[self.lo..self.hi].iter().fold(0, |n, &c| n * 10 + u64::from(c - b'0'))
            }
            _ => self.value(seg) as u64,
        }
    }
}

/// The word at `*i` (a letter, blanks, an optional sign, digits with an optional point),
/// or `None` when it is anything else or not followed by a separator, a letter or the end.
#[inline(always)]
fn word<const VALUES: bool>(seg: &Seg<'_>, at: &mut usize) -> Option<Word> {
    let b = seg.text.as_bytes();
    let len = b.len();
    let mut i = *at;
    let letter = *b.get(i)?;
    if !letter.is_ascii_alphabetic() {
        return None;
    }
    let start = i;
    i += 1;
    while i < len && blank(b[i]) {
        i += 1;
    }
    let vstart = i;
    let mut neg = None;
    if i < len && (b[i] == b'-' || b[i] == b'+') {
        neg = Some(b[i] == b'-');
        i += 1;
        while i < len && blank(b[i]) {
            i += 1;
        }
    }
    let lo = i;
    // All the digits as one whole number (the point left out), when wanted.
    let mut mant: u64 = 0;
    i = crate::read::digit_run(b, i, VALUES, &mut mant);
    let mut digits = i - lo;
    let mut point = false;
    let mut frac = 0;
    if i < len && b[i] == b'.' {
        point = true;
        i += 1;
        let from = i;
        i = crate::read::digit_run(b, i, VALUES, &mut mant);
        frac = i - from;
        digits += frac;
    }
    if digits == 0 || !ends_token(b, i) {
        return None;
    }
    *at = i;
    let mant = VALUES.then_some(mant);
    Some(Word { letter: letter.to_ascii_uppercase(), start, vstart, lo, hi: i, neg, point, digits, mant, frac })
}

/// A blank between the parts of a block.
#[inline(always)]
fn blank(c: u8) -> bool {
    matches!(c, b' ' | b'\t' | b'\x0C')
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

/// A literal may be followed only by a separator, the next letter, or the end (a `;` ends
/// a block: only a whole line read as one holds it, see [`skeleton_line`]).
fn ends_token(b: &[u8], i: usize) -> bool {
    match b.get(i) {
        None => true,
        Some(c) => matches!(c, b' ' | b'\t' | b'\x0C' | b';') || c.is_ascii_alphabetic(),
    }
}
