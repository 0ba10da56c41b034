//! The streamed translator's fast path: the FANUC lines of one straight-line Sinumerik block
//! (constant address words, program ends, comments, block numbers, skips) written straight
//! into the output, byte for byte what the whole-program translator writes for it
//! (`lower::to_fanuc::blocks`, `words`, `exprs`, `labels`, then `dialect::fanuc::emit`), without
//! building FANUC IR or formatting through `format!`. CAM programs are millions of such
//! blocks, and the general translator costs some 40,000 instructions on each.
//!
//! Whatever the general translator would report on (an unknown G code, a dwell in
//! revolutions, a number of more than 8 digits) is declined: the caller translates that
//! block the general way, which gives the diagnostic. The differential tests
//! (`tests/stream_translate.rs`, the unit tests below) hold the two paths to the same bytes.

use crate::dialect::digits::{Form, Lit, Src};
use crate::dialect::fanuc::emit::{self, CommentMode, KEEP_PREFIX};
use crate::dialect::numwrite::{push_num, push_skip, push_u64};
use crate::dialect::plain::{ItemView, PlainWord, View};
use crate::ir::{BlockMeta, EndCode, Stmt, StmtKind};
use crate::lower::to_fanuc::words::units::{FeedConv, Units};
use crate::lower::to_fanuc::words::SAME_G;
use crate::read::RawBlock;

/// Highest block number FANUC keeps (`lower::to_fanuc::labels` drops the others).
const MAX_N: u32 = 99999;
/// Letters (as bits, `A` lowest) whose words `Fast::word` writes otherwise than as a
/// dimension: G and M codes and the integer addresses; anything not a capital letter.
const SPECIAL: u64 = {
    let mut m = !((1u64 << 26) - 1);
    let s = b"GMSTHDPLNO";
    let mut i = 0;
    while i < s.len() {
        m |= 1 << (s[i] - b'A');
        i += 1;
    }
    m
};

/// A letter's bit in [`SPECIAL`] (above the 26 letters for any other byte).
#[inline(always)]
fn letter_bit(l: u8) -> u64 {
    1u64 << (l.wrapping_sub(b'A') as u64).min(63)
}

/// [`SAME_G`] as bits (all below 128), so a G word is judged without searching the list.
const SAME_G_BITS: u128 = {
    let mut m = 0u128;
    let mut i = 0;
    while i < SAME_G.len() {
        assert!(SAME_G[i] < 128);
        m |= 1 << SAME_G[i];
        i += 1;
    }
    m
};

/// `SAME_G.contains(&g)`.
#[inline(always)]
fn same_g(g: u32) -> bool {
    g < 128 && SAME_G_BITS >> g & 1 != 0
}

/// `v.fract() == 0.0`, which calls `trunc` (a library call on the baseline x86-64): below
/// 2^52 the truncating cast back to f64 gives `v` exactly when `v` is an integer; larger
/// magnitudes, infinities and NaN keep `fract`.
#[inline(always)]
fn is_int(v: f64) -> bool {
    if v.abs() < 4_503_599_627_370_496.0 {
        (v as i64) as f64 == v
    } else {
        v.fract() == 0.0
    }
}

/// The block needs the general translator (it would report something on it).
#[derive(Debug, PartialEq, Eq)]
pub struct Declined;

/// The translation state that spans blocks: the words pass's length and feed units (an F
/// word is converted where they differ: `F[v/25.4]` or `F[v*25.4]`).
pub struct Fast {
    pub units: Units,
    comments: CommentMode,
    eol: &'static str,
}

impl Fast {
    pub fn new(comments: CommentMode, eol: &'static str) -> Fast {
        Fast { units: Units::default(), comments, eol }
    }

    /// Appends the lines of `s`. On `Err` nothing was appended, but the units have taken
    /// the block's G words into account, as the words pass does before it reports.
    pub fn block(&mut self, s: &Stmt, out: &mut Vec<u8>) -> Result<(), Declined> {
        let StmtKind::Block(b) = &s.kind else { return Err(Declined) };
        self.plain(&b.meta, &b.items, out)
    }

    /// [`Fast::block`] of a block's meta and items (IR items, or the words of a plain line).
    pub fn plain<I: ItemView>(&mut self, meta: &BlockMeta, items: &[I], out: &mut Vec<u8>) -> Result<(), Declined> {
        self.with_lits(meta, items, |_| None, out)
    }

    /// [`Fast::plain`] of the words of a plain line `line`: their numbers are written from
    /// their digits where those are the written form ([`Lit`]).
    pub fn words(
        &mut self,
        meta: &BlockMeta,
        words: &[PlainWord],
        line: &RawBlock<'_>,
        out: &mut Vec<u8>,
    ) -> Result<(), Declined> {
        if meta.label.is_some() || words.is_empty() {
            return self.with_lits(meta, words, |w| Some(Src { line, span: w.span, canon: w.canon }), out);
        }
        // What `lines` does for a block of words only, in one loop over them after the
        // words pass's modes: a dimension word (neither an integer address, nor G/M, nor a
        // feed under a dwell or converted) goes straight from its literal to the output.
        let mut dwell = false;
        for w in words {
            if w.letter == b'G' {
                let v = w.value;
                if !self.units.g(v) && v == 4.0 {
                    dwell = true;
                }
            }
        }
        let convert = self.units.feed() != FeedConv::Same;
        let special = if dwell || convert { SPECIAL | letter_bit(b'F') } else { SPECIAL };
        let start = out.len();
        let (line_start, mut sep) = self.open(out, meta, true);
        for w in words {
            if sep {
                out.push(b' ');
            }
            sep = true;
            if w.letter == b'G' {
                // The usual G code (G0..G9 the target has): what `word` and `num_word`
                // write for it, `G0n`.
                let g = w.value as u32;
                if g < 10 && f64::from(g) == w.value && same_g(g) {
                    out.extend_from_slice(&[b'G', b'0', b'0' + g as u8]);
                    continue;
                }
            }
            let src = Src { line, span: w.span, canon: w.canon };
            if special & letter_bit(w.letter) == 0 && src.push_word(w.letter, w.value, Form::Point, out) {
                continue;
            }
            let v = Some(w.value);
            if self.word(Some(w.letter), v, v, dwell, || Some(src), out).is_err() {
                out.truncate(start);
                return Err(Declined);
            }
        }
        self.close(out, line_start, meta, true);
        Ok(())
    }

    /// [`Fast::words`] of the usual CAM line read by the quick reader, in one loop: no
    /// label, skip or comment; words G0..G9 the target has but G4 (a dwell changes F and S)
    /// and dimension words (not [`SPECIAL`], nor a converted F) in their canonical form
    /// (`Canon`, `push_word`'s `Point` bytes, at most 7 digits). What [`Fast::words`]
    /// writes for such a line: the N number FANUC keeps, the words one space apart, the
    /// line end. `false`, nothing changed, for any other line.
    #[inline(always)]
    pub fn plain_words(&self, meta: &BlockMeta, words: &[PlainWord], out: &mut Vec<u8>) -> bool {
        if meta.label.is_some() || meta.skip.is_some() || !meta.comments.is_empty() || words.is_empty() {
            return false;
        }
        let special = if self.units.feed() != FeedConv::Same { SPECIAL | letter_bit(b'F') } else { SPECIAL };
        let start = out.len();
        if let Some(n) = meta.number.as_ref().map(|n| n.value).filter(|n| (1..=MAX_N).contains(n)) {
            out.push(b'N');
            push_u64(out, u64::from(n));
            out.push(b' ');
        }
        for w in words {
            if w.letter == b'G' {
                let g = w.value as u32;
                if g >= 10 || g == 4 || f64::from(g) != w.value || !same_g(g) {
                    out.truncate(start);
                    return false;
                }
                out.extend_from_slice(&[b'G', b'0', b'0' + g as u8, b' ']);
                continue;
            }
            let c = &w.canon;
            if c.len == 0 || c.sig > 7 || special & letter_bit(w.letter) != 0 {
                out.truncate(start);
                return false;
            }
            let at = out.len();
            out.extend_from_slice(&c.bytes());
            out.truncate(at + usize::from(c.len));
            out.push(b' ');
        }
        out.pop();
        out.extend_from_slice(self.eol.as_bytes());
        true
    }

    /// [`Fast::plain`] with `lit` giving an item's literal, when known.
    #[inline(always)]
    fn with_lits<'t, I: ItemView>(
        &mut self,
        meta: &BlockMeta,
        items: &[I],
        lit: impl Fn(&I) -> Option<Src<'t>>,
        out: &mut Vec<u8>,
    ) -> Result<(), Declined> {
        let start = out.len();
        let r = self.lines(meta, items, lit, out);
        if r.is_err() {
            out.truncate(start);
        }
        r
    }

    #[inline(always)]
    fn lines<'t, I: ItemView>(
        &mut self,
        meta: &BlockMeta,
        items: &[I],
        lit: impl Fn(&I) -> Option<Src<'t>>,
        out: &mut Vec<u8>,
    ) -> Result<(), Declined> {
        if meta.label.is_some() {
            return Err(Declined);
        }
        // The words pass: the block's modal G words apply to all its words.
        let mut dwell = false;
        let mut words = false;
        for it in items {
            match it.view() {
                View::Word { is_g, num, .. } => {
                    words = true;
                    if is_g {
                        match num.map(|n| n.0) {
                            Some(v) if self.units.g(v) => {}
                            Some(4.0) => dwell = true,
                            _ => {}
                        }
                    }
                }
                View::End(_) => {}
                View::Other => return Err(Declined),
            }
        }
        // The blocks pass: the words are one block (it keeps the block's number, label and
        // comments), then each program end is a block of its own (keeping only the skip).
        let mut first = true;
        if words {
            let (line, mut sep) = self.open(out, meta, true);
            for it in items {
                if let View::Word { letter, num, folded, .. } = it.view() {
                    if sep {
                        out.push(b' ');
                    }
                    sep = true;
                    self.word(letter, num.map(|n| n.0), folded, dwell, || lit(it), out)?;
                }
            }
            self.close(out, line, meta, true);
            first = false;
        }
        for it in items {
            if let View::End(code) = it.view() {
                let (line, any) = self.open(out, meta, first);
                if any {
                    out.push(b' ');
                }
                out.extend_from_slice(match code {
                    EndCode::M30 => b"M30",
                    EndCode::M2 => b"M02",
                });
                self.close(out, line, meta, first);
                first = false;
            }
        }
        if first {
            // No items: a line of its own for the number, the comments or the skip.
            let (line, _) = self.open(out, meta, true);
            self.close(out, line, meta, true);
        }
        Ok(())
    }

    /// Starts a line (`Writer::line`): the skip and, on a block's first line, its number.
    /// Returns where the line starts and whether anything was written (the code then
    /// follows after a space).
    fn open(&self, out: &mut Vec<u8>, m: &BlockMeta, first: bool) -> (usize, bool) {
        let start = out.len();
        push_skip(out, m.skip);
        if first {
            if let Some(n) = m.number.as_ref().map(|n| n.value).filter(|n| (1..=MAX_N).contains(n)) {
                if out.len() > start {
                    out.push(b' ');
                }
                out.push(b'N');
                push_u64(out, u64::from(n));
            }
        }
        (start, out.len() > start)
    }

    /// Ends a line: the comments (on a block's first line), then the line end, or nothing
    /// when the line is empty or a lone `/` (the writer leaves those out).
    fn close(&self, out: &mut Vec<u8>, line_start: usize, m: &BlockMeta, first: bool) {
        if first {
            for c in &m.comments {
                let keep = c.text.starts_with(KEEP_PREFIX) || c.text.starts_with("*** NCTRANS");
                if self.comments == CommentMode::Drop && !keep {
                    continue;
                }
                if out.len() > line_start {
                    out.push(b' ');
                }
                out.push(b'(');
                out.extend_from_slice(emit::comment_text(&c.text, self.comments).as_bytes());
                out.push(b')');
            }
        }
        let line = &out[line_start..];
        if line.is_empty() || line == b"/" {
            out.truncate(line_start);
        } else {
            out.extend_from_slice(self.eol.as_bytes());
        }
    }

    /// One word: the words pass's address rules, the expression pass's folding of `-n`,
    /// then `Writer::word`.
    /// `letter`: the word's when it has a letter address and an expression value; `num`
    /// its value when a number as written, `folded` after folding `-n`; `lit` the literal
    /// of `folded`, when known.
    #[inline(always)]
    fn word<'t>(
        &self,
        letter: Option<u8>,
        num: Option<f64>,
        folded: Option<f64>,
        dwell: bool,
        lit: impl FnOnce() -> Option<Src<'t>>,
        out: &mut Vec<u8>,
    ) -> Result<(), Declined> {
        let mut letter = letter.ok_or(Declined)?;
        let mut conv: &[u8] = b"";
        match letter {
            b'G' => {
                // A G code must be a written constant the target has.
                let v = num.ok_or(Declined)?;
                // Tool radius compensation is refused by the passes (`lower::compensation`).
                if (40.0..=42.0).contains(&v) {
                    return Err(Declined);
                }
                let g = if v == 70.0 || v == 700.0 {
                    20.0
                } else if v == 71.0 || v == 710.0 {
                    21.0
                } else if is_int(v) && same_g(v as u32) {
                    v
                } else {
                    return Err(Declined);
                };
                return self.num_word(b'G', g, None, out);
            }
            b'F' if dwell => letter = b'X',
            b'S' if dwell => return Err(Declined),
            // A cutting edge: refused by the passes (`lower::compensation`).
            b'D' => return Err(Declined),
            b'F' => match self.units.feed() {
                FeedConv::Same => {}
                FeedConv::PerInch => conv = b"/25.4]",
                FeedConv::PerMm => conv = b"*25.4]",
            },
            _ => {}
        }
        let v = folded.ok_or(Declined)?;
        if !conv.is_empty() {
            // `F[v/25.4]`, `F[v*25.4]`: a binary expression is bracketed in an address;
            // neither constant is.
            out.push(letter);
            out.push(b'[');
            number(out, v, lit().and_then(Src::lit))?;
            out.extend_from_slice(conv);
            return Ok(());
        }
        self.num_word(letter, v, lit(), out)
    }

    /// `Writer::word` for a constant value (`src`: where its literal is, when known).
    #[inline(always)]
    fn num_word(&self, letter: u8, v: f64, src: Option<Src<'_>>, out: &mut Vec<u8>) -> Result<(), Declined> {
        let int_addr = matches!(letter, b'G' | b'M' | b'S' | b'T' | b'H' | b'D' | b'P' | b'L' | b'N' | b'O');
        let integer = is_int(v);
        if !matches!(letter, b'G' | b'M') {
            // The usual word: straight from its literal.
            let form = if int_addr && integer { Form::Int } else { Form::Point };
            if src.is_some_and(|s| s.push_word(letter, v, form, out)) {
                return Ok(());
            }
        }
        out.push(letter);
        if matches!(letter, b'G' | b'M') {
            if (0.0..10.0).contains(&v) && integer {
                out.extend_from_slice(&[b'0', b'0' + v as u8]);
                return Ok(());
            }
            if letter == b'G' && v >= 0.0 {
                push_num(out, v, false);
                return Ok(());
            }
        }
        let lit = src.and_then(Src::lit);
        if int_addr && integer {
            // An integer in an integer address: written as it is, without a warning.
            if !lit.is_some_and(|l| l.push_fanuc(out, false)) {
                push_num(out, v, false);
            }
            return Ok(());
        }
        number(out, v, lit)
    }
}

/// A constant in a dimension or an expression (`Writer::number`): declined when it has more
/// than 8 digits, where the general writer rounds it with a warning. From the digits of
/// `lit` (its literal) when they are the written form.
#[inline(always)]
fn number(out: &mut Vec<u8>, v: f64, lit: Option<Lit<'_>>) -> Result<(), Declined> {
    if lit.is_some_and(|l| l.push_fanuc(out, true)) || push_num(out, v, true) {
        Ok(())
    } else {
        Err(Declined)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn is_int_and_same_g_agree_with_fract_and_the_list() {
        let vs = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.5,
            -0.5,
            2.5,
            1e15,
            4503599627370495.5,
            4503599627370496.0,
            1e20,
            -1e20,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            f64::MIN_POSITIVE,
            95.0,
            96.0,
            127.0,
            128.0,
            1e10,
        ];
        for v in vs {
            assert_eq!(is_int(v), v.fract() == 0.0, "{v}");
        }
        for g in 0..300 {
            assert_eq!(same_g(g), SAME_G.contains(&g), "{g}");
        }
        assert!(!same_g(u32::MAX));
    }
}
