//! Blocks made only of one-letter words with constant values (`N10 G1 X1.5 Y-2 F800`,
//! nearly every block of CAM output), kept in a compact op: their values need no
//! evaluation, and a page of them is freed without walking the IR. Running one does
//! exactly what running the IR block does (`exec::exec_block` with literal words); the
//! tests run every corpus program and generated ones both ways.

use crate::ir::{Addr, Block, ExprKind, ItemKind, WordValue};
use crate::span::Span;

/// How a word's value is given: plain, or Siemens `=AC(…)` / `=IC(…)` (absolute or
/// incremental for this word alone).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AbsInc {
    Plain,
    Ac,
    Ic,
}

/// Words kept in place (a CAM block has up to six or so: `G1 X Y Z A F`); blocks with
/// more stay IR. In place, not boxed: an allocation per block would cost more than the
/// evaluation this saves.
pub const MAX_WORDS: usize = 7;

/// A block of constant one-letter words.
#[derive(Clone, Debug)]
pub struct LitBlock {
    /// The block's span (`BlockMeta::span`).
    pub span: Span,
    /// The block number (`BlockMeta::number`).
    pub number: Option<u32>,
    /// The block's 1-based line in its file when its reader knows it (0: not known): a
    /// streamed re-read can set it, and the trace writer then takes it for `@line`
    /// instead of looking the span up ([`crate::eval::trace::WriterSink::block_lines`]).
    pub line: u32,
    len: u8,
    words: [LitWord; MAX_WORDS],
}

/// One word: upper-case letter, the literal's value and whether it had a decimal point
/// (the FANUC decimal-point rule), its `AC`/`IC` form, its span, and when its reader
/// worked it out from the digits, the count of thousandths `decimal_count(value, 1000.0)`
/// gives ([`thousandths`] with the sign; [`NO_MILLI`]: not known).
/// 24 bytes, as without the count (it fills what was padding).
#[derive(Clone, Copy, Debug)]
pub struct LitWord {
    pub value: f64,
    pub span: Span,
    pub milli: i32,
    pub letter: u8,
    pub point: bool,
    pub mode: AbsInc,
}

/// [`LitWord::milli`] of a word whose count of thousandths is not known.
pub const NO_MILLI: i32 = i32::MIN;

/// [`LitWord::milli`] for a literal read as the digits `mant` with `frac` of them after the
/// point (`None`: not read so, e.g. more than 15 digits), negated with `neg`.
#[inline(always)]
pub fn milli(neg: bool, digits: Option<(u64, usize)>) -> i32 {
    match digits.and_then(|(mant, frac)| thousandths(mant, frac)) {
        // At most 10⁹ (see `thousandths`).
        Some(q) => {
            let q = q as i32;
            if neg {
                -q
            } else {
                q
            }
        }
        None => NO_MILLI,
    }
}

/// A slot of [`LitBlock::EMPTY`] (all zero bytes), and the unused ones of
/// [`LitBlock::of`] (so that both routes give the same op, unused slots included).
const ZERO_WORD: LitWord =
    LitWord { value: 0.0, span: Span { lo: 0, hi: 0 }, milli: 0, letter: 0, point: false, mode: AbsInc::Plain };

impl LitBlock {
    /// The compact form of `b`, when it has at most [`MAX_WORDS`] items, each a word with
    /// an upper-case letter address and a number literal (or a negated one) as its value.
    pub fn of(b: &Block) -> Option<LitBlock> {
        if disabled() || b.items.len() > MAX_WORDS {
            return None;
        }
        let mut words = [ZERO_WORD; MAX_WORDS];
        for (slot, item) in words.iter_mut().zip(&b.items) {
            let ItemKind::Word(w) = &item.kind else { return None };
            let Addr::Letter(letter) = w.addr else { return None };
            if !letter.is_ascii_uppercase() {
                return None;
            }
            let (e, mode) = match &w.value {
                WordValue::Expr(e) => (e, AbsInc::Plain),
                WordValue::Ac(e) => (e, AbsInc::Ac),
                WordValue::Ic(e) => (e, AbsInc::Ic),
                WordValue::Rotary(..) => return None,
            };
            let (value, point) = match &e.kind {
                ExprKind::Num(n) => (n.value, n.point),
                ExprKind::Unary(crate::ir::UnOp::Neg, a) => match &a.kind {
                    ExprKind::Num(n) => (-n.value, n.point),
                    _ => return None,
                },
                _ => return None,
            };
            *slot = LitWord { value, span: w.span, milli: NO_MILLI, letter, point, mode };
        }
        Some(LitBlock {
            span: b.meta.span,
            number: b.meta.number.as_ref().map(|n| n.value),
            line: 0,
            len: b.items.len() as u8,
            words,
        })
    }

    /// An empty block to fill with [`LitBlock::push`] from words read straight from the
    /// text (a streamed chunk's re-read, see `crate::stream::reread`). A constant, so that
    /// it is copied straight from read-only data into its op slot (one built at run time
    /// is built on the stack and copied twice: a memmove per re-read line).
    /// Its words past `len` (never read) are all zero bytes, as is the rest of it: a
    /// constant of zeros is written with a few stores in line, any other with a call to
    /// `memcpy`.
    pub const EMPTY: LitBlock =
        LitBlock { span: Span { lo: 0, hi: 0 }, number: None, line: 0, len: 0, words: [ZERO_WORD; MAX_WORDS] };

    /// Whether the compact form is on (tests turn it off, see [`without`]).
    pub fn enabled() -> bool {
        !disabled()
    }

    /// Adds a plain word (what [`LitBlock::of`] makes of a `Word` with a letter address and
    /// a number literal `value`, negated when written with `-`), with its [`LitWord::milli`];
    /// `false` when the block is full or `letter` is not upper case (the block then must
    /// stay IR).
    #[inline(always)]
    pub fn push(&mut self, letter: u8, value: f64, point: bool, milli: i32, span: Span) -> bool {
        letter.is_ascii_uppercase() && self.push_upper(letter, value, point, milli, span)
    }

    /// [`LitBlock::push`] of a word whose `letter` the caller has checked to be upper case
    /// (the quick reader's lines): the same, one check fewer per word.
    #[inline(always)]
    pub fn push_upper(&mut self, letter: u8, value: f64, point: bool, milli: i32, span: Span) -> bool {
        debug_assert!(letter.is_ascii_uppercase());
        let Some(slot) = self.words.get_mut(usize::from(self.len)) else { return false };
        *slot = LitWord { value, span, milli, letter, point, mode: AbsInc::Plain };
        self.len += 1;
        true
    }

    /// Drops the words pushed so far.
    #[inline(always)]
    pub fn clear(&mut self) {
        self.len = 0;
    }

    pub fn words(&self) -> &[LitWord] {
        &self.words[..usize::from(self.len)]
    }
}

/// [`decimal_count`]`(x, 1000.0)` for the literal `x` whose digits, read as one whole
/// number, are `mant` with `frac` of them after the point (no sign: the count of `-x` is
/// minus this one), worked out from the digits; `None` where that is not shown to be the
/// same (then round the double).
///
/// Why it is the same: `x` is the double nearest `mant / 10^frac` (`read::exact`), and
/// `decimal_count` first rounds `raw = (x × 1000) × 10⁶` to an integer `k`. Here
/// `R = mant × 10^(9-frac)` is an integer below 10¹⁵ (`frac <= 9`, `mant < 10^(6+frac)`),
/// and `raw` is `R` with three roundings, each of relative error at most 2⁻⁵³, so within
/// `R × 3.4·10⁻¹⁶ < 0.34` of it: `k` is `R` exactly (ties of the thousandth included, the
/// point of that pre-rounding), and its count is `R / 10⁶` rounded half away from zero,
/// which is what this works out, each `frac` with its own constant divisor. Every such
/// count is at most 10⁹ (so fits an `i32`).
#[inline(always)]
pub fn thousandths(mant: u64, frac: usize) -> Option<i64> {
    const LIMIT: [u64; 10] = [
        1_000_000,
        10_000_000,
        100_000_000,
        1_000_000_000,
        10_000_000_000,
        100_000_000_000,
        1_000_000_000_000,
        10_000_000_000_000,
        100_000_000_000_000,
        1_000_000_000_000_000,
    ];
    if mant >= *LIMIT.get(frac)? {
        return None;
    }
    let q = match frac {
        0 => mant * 1000,
        1 => mant * 100,
        2 => mant * 10,
        3 => mant,
        4 => (mant + 5) / 10,
        5 => (mant + 50) / 100,
        6 => (mant + 500) / 1000,
        7 => (mant + 5000) / 10_000,
        8 => (mant + 50_000) / 100_000,
        _ => (mant + 500_000) / 1_000_000,
    };
    Some(q as i64)
}

#[cfg(test)]
thread_local! {
    /// Tests run programs with and without the compact form to compare the two.
    static DISABLED: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

#[cfg(test)]
fn disabled() -> bool {
    DISABLED.with(|d| d.get())
}

#[cfg(not(test))]
fn disabled() -> bool {
    false
}

/// Runs `f` with the compact form off (every block stays IR).
#[cfg(test)]
pub fn without<T>(f: impl FnOnce() -> T) -> T {
    DISABLED.with(|d| d.set(true));
    let r = f();
    DISABLED.with(|d| d.set(false));
    r
}

#[cfg(test)]
mod size_tests {
    /// The thousandths count fills what was padding: a page of compact blocks is no larger.
    #[test]
    fn a_word_is_24_bytes() {
        assert_eq!(std::mem::size_of::<super::LitWord>(), 24);
    }
}
