//! The streamed FANUC → Sinumerik translator's fast path: the Sinumerik line of one plain
//! FANUC block (constant letter words, program ends, N number, skip, comments) written
//! straight into the output, byte for byte what the passes (`vacancy`, `calls`, `words`,
//! `exprs` in `lower::to_sinumerik`) and `dialect::sinumerik::emit` write for it, without
//! building Sinumerik IR or formatting through `format!`. The general path costs some
//! 20,000 instructions on a CAM block; this one a few hundred.
//!
//! Whatever the passes would report on or rewrite into more than one line (a dwell, G43/
//! G44/G49 with their warning, an `R` outside an arc, P/L/Q/E/O/H, a computed value, a
//! number the writer spells with `EX`) is declined: the caller translates that block the
//! general way. The states carried from block to block are the arc mode (G2/G3 last) and
//! the unit (G20/G21: a value without a decimal point counts 0.0001 in under G20), which
//! the caller keeps. `tests/stream_to_sinumerik_fast.rs` holds the two paths to the
//! same bytes.

use crate::dialect::digits::{Form, Src};
use crate::dialect::numwrite::{push_decimal, push_short, push_skip, push_u64, shortest};
use crate::dialect::plain::{ItemView, PlainWord, View};
use crate::ir::{BlockMeta, EndCode};
use crate::lower::to_sinumerik::words::{rotary_letter, scale, scaled_letter};
use crate::lower::to_sinumerik::Options;

/// The block needs the general passes.
#[derive(Debug, PartialEq, Eq)]
pub struct Declined;

/// The Siemens G code (×10) `words::map_g` gives a FANUC one, `Ok(None)` when the words
/// pass drops it without a word (G80); `Err` for everything the fast path leaves to the
/// passes (the dwell G4, tool compensation G40..G49, codes without a counterpart).
fn map_g(g: u32) -> Result<Option<u32>, Declined> {
    Ok(Some(match g {
        // G40/G41/G42 (and D) are refused by the passes (`lower::compensation`).
        0 | 10 | 20 | 30 | 90 | 170 | 180 | 190 | 530 | 540 | 550 | 560 | 570 | 640 | 900 | 910 | 940 | 950 => g,
        200 => 7000,
        210 => 7100,
        580 => 5050,
        590 => 5060,
        610 => 600,
        800 => return Ok(None),
        _ => return Err(Declined),
    }))
}

/// Appends the line of `b` (with `eol`), or nothing when the passes drop the block. `arc`
/// is the arc mode after the block's own G codes (as the words pass sees it), `inch` the
/// unit (G20, `None`: not known) after them (as `lower::to_sinumerik::modal` finds it). On `Err` what
/// was appended is to be discarded. `lit` gives an item's literal, when known: its digits
/// are written where they are the written form.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub fn block<'t, I: ItemView>(
    meta: &BlockMeta,
    items: &[I],
    lit: impl Fn(&I) -> Option<Src<'t>>,
    arc: bool,
    inch: Option<bool>,
    opts: &Options,
    eol: &[u8],
    out: &mut Vec<u8>,
) -> Result<(), Declined> {
    if meta.label.is_some() {
        return Err(Declined);
    }
    let start = out.len();
    // The writer: skip, N number, items, comments, each after a space when not first.
    push_skip(out, meta.skip);
    if let Some(n) = &meta.number {
        if out.len() > start {
            out.push(b' ');
        }
        out.push(b'N');
        push_u64(out, u64::from(n.value));
    }
    let mut any = false;
    for it in items {
        let (letter, num) = match it.view() {
            View::Word { letter, num, .. } => (letter, num),
            View::End(code) => {
                if out.len() > start {
                    out.push(b' ');
                }
                out.extend_from_slice(match code {
                    EndCode::M30 => b"M30",
                    EndCode::M2 => b"M2",
                });
                any = true;
                continue;
            }
            _ => return Err(Declined),
        };
        let (Some(letter), Some((value, point))) = (letter, num) else { return Err(Declined) };
        let mut v = value;
        // Whether `v` is still the value of the literal.
        let mut as_written = true;
        match letter {
            b'G' => {
                let g10 = v * 10.0;
                if !(0.0..=9990.0).contains(&g10) {
                    return Err(Declined);
                }
                let Some(sg) = map_g(round(g10) as u32)? else { continue };
                if sg % 10 == 0 {
                    // A whole G code: what `push_display` (or the `0` of G0) writes for
                    // it, without formatting a double.
                    if out.len() > start {
                        out.push(b' ');
                    }
                    any = true;
                    out.push(b'G');
                    match sg / 10 {
                        g @ 0..=9 => out.push(b'0' + g as u8),
                        g => push_u64(out, u64::from(g)),
                    }
                    continue;
                }
                v = f64::from(sg) / 10.0;
                as_written = false;
            }
            b'P' | b'L' | b'Q' | b'E' | b'O' | b'H' | b'D' => return Err(Declined),
            // A tool change: the passes write it with D0 (`passes::to_sinumerik::comp`).
            b'M' if v == 6.0 => return Err(Declined),
            _ => {
                if scaled_letter(letter) && !point {
                    let rotary = rotary_letter(letter);
                    // Where the unit is not known the passes refuse the value (NC375).
                    let Some(inch) = inch.or(rotary.then_some(false)) else { return Err(Declined) };
                    v = scale(opts, v, inch, rotary);
                    as_written = false;
                }
            }
        }
        if out.len() > start {
            out.push(b' ');
        }
        any = true;
        let range = (1e-6..1e15).contains(&v.abs());
        if as_written && range && letter != b'R' {
            // The usual word: straight from its literal.
            if let Some(src) = lit(it) {
                if src.push_word(letter, v, Form::Display, out) {
                    continue;
                }
                out.push(letter);
                if !src.lit().is_some_and(|l| l.push_display(out)) {
                    push_display(out, v);
                }
                continue;
            }
        }
        if letter == b'R' {
            // `CR=` in an arc; elsewhere a cycle's R plane, which the passes report.
            if !arc {
                return Err(Declined);
            }
            out.extend_from_slice(b"CR=");
        } else {
            out.push(letter);
        }
        // `word_into`/`number`: 0, the shortest decimal, or an `EX` form (left to the passes).
        if v == 0.0 {
            out.push(b'0');
        } else if range {
            push_display(out, v);
        } else {
            return Err(Declined);
        }
    }
    let mut comments = false;
    for (i, c) in meta.comments.iter().enumerate() {
        comments = true;
        if i == 0 {
            if out.len() > start {
                out.push(b' ');
            }
            out.extend_from_slice(b"; ");
        } else {
            out.extend_from_slice(b" ; ");
        }
        // `emit::comment_text`: line ends become spaces, then the text is trimmed.
        let t = c.text.as_str();
        if t.contains(['\n', '\r']) {
            out.extend_from_slice(t.replace(['\n', '\r'], " ").trim().as_bytes());
        } else {
            out.extend_from_slice(t.trim().as_bytes());
        }
    }
    // `calls::lower` and `words::lower` drop a block left with nothing but a skip.
    if !any && meta.number.is_none() && !comments {
        out.truncate(start);
        return Ok(());
    }
    // `Writer::line_str` trims the end of the line.
    let keep = out[start..].trim_ascii_end().len();
    out.truncate(start + keep);
    out.extend_from_slice(eol);
    Ok(())
}

/// A letter's bit (`A` lowest); 0 for a byte that is not a capital letter.
#[inline(always)]
const fn bit(l: u8) -> u32 {
    if l.is_ascii_uppercase() {
        1 << (l - b'A')
    } else {
        0
    }
}

/// Bits of `letters`.
const fn bits(letters: &[u8]) -> u32 {
    let mut m = 0;
    let mut i = 0;
    while i < letters.len() {
        m |= bit(letters[i]);
        i += 1;
    }
    m
}

/// Letters [`plain_words`] writes from their literal: all but G (its own case), those
/// [`block`] declines (P L Q E O H D) and R (`CR=` in an arc).
const FROM_LITERAL: u32 = ((1 << 26) - 1) & !bits(b"GPLQEOHDR");
/// `words::scaled_letter`'s letters: written from the literal only with a point.
const SCALED: u32 = bits(b"XYZUVWABCIJKRQ");

/// [`block`] of the usual CAM line read by the quick reader, in one loop: no label, skip
/// or comment; words G0..G3 (arc mode G2/G3 into `arc`) and words [`FROM_LITERAL`] in
/// their canonical form (`Canon`: `push_word`'s `Display` bytes), a scaled letter with a
/// point, at least 10^-6 (smaller ones `block` leaves to the passes). What [`block`] writes
/// for such a line: the N number, the words one space apart, the line end. `false`,
/// nothing changed, for any other line ([`block`] takes it).
#[inline(always)]
pub fn plain_words(meta: &BlockMeta, words: &[PlainWord], arc: &mut bool, eol: &[u8], out: &mut Vec<u8>) -> bool {
    if meta.label.is_some() || meta.skip.is_some() || !meta.comments.is_empty() || words.is_empty() {
        return false;
    }
    let start = out.len();
    let mut a = *arc;
    if let Some(n) = &meta.number {
        out.push(b'N');
        push_u64(out, u64::from(n.value));
        out.push(b' ');
    }
    for w in words {
        if w.letter == b'M' && w.value == 6.0 {
            // A tool change: `block` leaves it to the passes (D0).
            out.truncate(start);
            return false;
        }
        if w.letter == b'G' {
            // `map_g` keeps G0..G3 (the arc mode as `push_plain` follows it).
            let g = w.value as u32;
            if g > 3 || f64::from(g) != w.value {
                out.truncate(start);
                return false;
            }
            a = g >= 2;
            out.extend_from_slice(&[b'G', b'0' + g as u8, b' ']);
            continue;
        }
        let c = &w.canon;
        let b = bit(w.letter);
        if c.len == 0 || FROM_LITERAL & b == 0 || (SCALED & b != 0 && !w.point) || w.value.abs() < 1e-6 {
            out.truncate(start);
            return false;
        }
        let len = if c.len > c.dot + 1 { c.len } else { c.dot };
        let at = out.len();
        out.extend_from_slice(&c.bytes());
        out.truncate(at + usize::from(len));
        out.push(b' ');
    }
    out.pop();
    out.extend_from_slice(eol);
    *arc = a;
    true
}

/// `x.round()`, without a call to the library's `round` for the usual `0 <= x < 2^31`
/// (a G code times ten): the integer part, plus one from a half up (`x - t` is exact).
#[inline(always)]
pub fn round(x: f64) -> f64 {
    // Not -0.0 (its `round` keeps the sign).
    if x.is_sign_positive() && x < 2_147_483_648.0 {
        let t = f64::from(x as u32);
        if x - t >= 0.5 {
            t + 1.0
        } else {
            t
        }
    } else {
        x.round()
    }
}

/// Appends `format!("{v}")` for a finite `v != 0` (Rust's shortest round-trip decimal).
pub fn push_display(out: &mut Vec<u8>, v: f64) {
    if push_short(out, v, false, false) {
        return;
    }
    match shortest(v.abs()) {
        Some((m, d)) => push_decimal(out, m, d, v < 0.0, false),
        None => {
            use std::io::Write;
            let _ = write!(out, "{v}");
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::Rng;

    #[test]
    fn numbers_are_written_as_display_writes_them() {
        let mut values: Vec<f64> = vec![
            1.0,
            -1.0,
            0.5,
            10.0,
            0.1,
            0.2,
            0.3,
            1e-6,
            1.5e-6,
            0.1 + 0.2,
            1e14,
            999999999999999.9,
            1.0 / 3.0,
            2.675,
        ];
        let mut rng = Rng(0x1234_5678_9abc_def1);
        for _ in 0..200_000 {
            let int = rng.next() % 10u64.pow((rng.next() % 9) as u32);
            let dec = (rng.next() % 9) as usize;
            let frac = rng.next() % 10u64.pow(dec as u32);
            let v: f64 = format!("{int}.{frac:0dec$}").parse().unwrap_or(1.0);
            values.push(if rng.next().is_multiple_of(2) { v } else { -v });
            values.push(f64::from_bits(rng.next()));
            values.push((rng.next() % 1_000_000) as f64 / 7.0);
            values.push((rng.next() % 100_000_000) as f64 * 0.001);
        }
        for &v in &values {
            for x in [v, v * 10.0, v.abs(), 0.5, 2.5, 0.49999999999999994, 2_147_483_647.5, 4_503_599_627_370_495.5] {
                assert_eq!(round(x).to_bits(), x.round().to_bits(), "{x:e}");
            }
        }
        for v in values {
            if v == 0.0 || !(1e-6..1e15).contains(&v.abs()) {
                continue;
            }
            let mut out = Vec::new();
            push_display(&mut out, v);
            assert_eq!(String::from_utf8_lossy(&out), format!("{v}"), "{v:e}");
        }
    }
}
