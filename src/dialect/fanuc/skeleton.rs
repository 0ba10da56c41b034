//! The index-only first scan's reader of a plain FANUC line straight from the read buffer
//! ([`skeleton_bytes`]): a byte automaton ([`STEP`]) for most words, G and M words of one
//! or two digits read on the spot; it stands for `fast::skeleton_raw` (tests/skeleton_diff.rs
//! holds it to that).

use crate::read::SkelLine;

/// For an index-only first scan straight from the read buffer (`crate::stream::scan_index`):
/// `b` starts at a line start and runs on past it (the line ends at the first CR or LF). The
/// line when `fast::skeleton_raw` would take it with the same block, number and words, and it
/// holds only plain bytes (printable ASCII, tab, form feed, SUB: valid UTF-8, no control
/// character to count); `None` when it may not be so (the caller then reads the line the
/// general way), which includes a line not ending within `b`.
///
/// Why this is `fast::skeleton_line`'s decision: the words of letters other than N, G, M and O
/// are read by an automaton ([`STEP`]) whose states are where `word` is in a word, one
/// step per byte, and whose stops are `ends_token`'s and `plain_words`'s (the end of the
/// line being a CR or LF here where it is the end of the text there); N, G and M words are
/// read by `word`'s steps and judged by `plain_words`'s rules; then `cut`'s steps.
/// Besides what they decline it declines a block skip (`/`, rare in CAM output) and an N, G
/// or M word of 16 or more digits without sign or point (whose value `plain_words` takes
/// as parsed: `G0000000000000065`).
#[inline(always)]
pub fn skeleton_bytes(b: &[u8]) -> Option<SkelLine> {
    let len = b.len();
    let eol = |c: u8| c == b'\n' || c == b'\r';
    let mut i = 0;
    while i < len && blank(b[i]) {
        i += 1;
    }
    let lo = i;
    let mut number = None;
    // Whether a word other than the N word comes (only an N word first may not be one).
    let mut words = b.get(lo).is_some_and(|c| (c | 0x20) != b'n');
    let stop = loop {
        // A G or M word where the automaton would start (a line's first word, mostly) is
        // where it would stop at once.
        let how = if matches!(*b.get(i)? & !0x20, b'G' | b'M') {
            NGM
        } else {
            let (k, how) = crate::read::run_automaton(&STEP, &b[i..], 0, STOP)?;
            i += k;
            how
        };
        if how != NGM {
            if how == EOL_WORD {
                // The line ends right after a word's digits (nearly every CAM line): no
                // blank or `;` before the line end to step over or trim.
                debug_assert!(i > lo && eol(b[i]) && !blank(b[i - 1]));
                return Some(SkelLine { len: i, lo, hi: i, number, words });
            }
            if how == REJECT_ROW {
                return None;
            }
            break i;
        }
        // An N, G or M word: `word`'s steps, then `RawWord::int` and `plain_words`'s rule.
        let letter = b[i] & !0x20;
        let start = i;
        if letter != b'N' {
            // Nearly every G and M word of CAM output: one or two digits, then a blank
            // (which the automaton, restarted between words, then reads).
            let d1 = b.get(i + 1)?.wrapping_sub(b'0');
            let c2 = *b.get(i + 2)?;
            let d2 = c2.wrapping_sub(b'0');
            let short = if d1 > 9 {
                None
            } else if c2 == b' ' {
                Some((d1, i + 2))
            } else if d2 <= 9 && *b.get(i + 3)? == b' ' {
                Some((d1 * 10 + d2, i + 3))
            } else {
                None
            };
            if let Some((value, next)) = short {
                let ok = if letter == b'G' {
                    !matches!(value, 10 | 65 | 66 | 67)
                } else {
                    !matches!(value, 2 | 30 | 96 | 97 | 98 | 99)
                };
                if !ok {
                    return None;
                }
                i = next;
                continue;
            }
        }
        i += 1;
        while i < len && blank(b[i]) {
            i += 1;
        }
        let mut signed = false;
        if i < len && (b[i] == b'-' || b[i] == b'+') {
            signed = true;
            i += 1;
            while i < len && blank(b[i]) {
                i += 1;
            }
        }
        let from = i;
        while i < len && b[i].is_ascii_digit() {
            i += 1;
        }
        let int_end = i;
        let mut point = false;
        if i < len && b[i] == b'.' {
            point = true;
            i += 1;
            while i < len && b[i].is_ascii_digit() {
                i += 1;
            }
        }
        let digits = i - from - usize::from(point);
        let n = *b.get(i)?;
        if digits == 0 || !(blank(n) || n == b';' || n.is_ascii_alphabetic() || eol(n)) {
            return None;
        }
        let int = if !point && !signed {
            if digits > 15 {
                return None;
            }
            Some(b[from..int_end].iter().fold(0u64, |n, &c| n * 10 + u64::from(c - b'0')))
        } else {
            None
        };
        let ok = match letter {
            b'N' => start == lo && int.is_some_and(|n| (1..=99_999).contains(&n)),
            b'G' => !matches!(int, Some(10 | 65 | 66 | 67)),
            _ => !matches!(int, Some(2 | 30 | 96 | 97 | 98 | 99)),
        };
        if !ok {
            return None;
        }
        if letter == b'N' {
            number = int.map(|n| (n as u32, start, i));
            let mut j = i;
            while j < len && blank(b[j]) {
                j += 1;
            }
            words = b.get(j).is_some_and(u8::is_ascii_alphabetic);
        }
    };
    if stop == lo {
        // No word: `plain_words` hands back a block without words.
        return None;
    }
    // The line end, past only blanks and `;` after an end-of-block `;` (else `cut` declines).
    let mut k = stop;
    while !eol(*b.get(k)?) {
        if !matches!(b[k], b' ' | b'\t' | b'\x0C' | b';') {
            return None;
        }
        k += 1;
    }
    let mut hi = stop;
    while hi > lo && blank(b[hi - 1]) {
        hi -= 1;
    }
    let end = if b[stop] == b';' { stop + 1 } else { hi };
    Some(SkelLine { len: k, lo, hi: end, number, words })
}

/// The states of [`skeleton_bytes`]'s automaton: between words, after a word's letter (and
/// blanks), after its sign (and blanks), in its digits before a point, after a point with
/// no digit before it, after a point and a digit. Then where it stops: an N, G or M word,
/// a decline, a `;`, the line end (after a blank or not: after a word's digits).
const SEP: u8 = 0;
const LET: u8 = 1;
const SIGN: u8 = 2;
const INT: u8 = 3;
const POINT0: u8 = 4;
const POINT: u8 = 5;
const NGM_STATE: u8 = 8;
const REJECT: u8 = 9;
const SEMI_STATE: u8 = 10;
const EOL_STATE: u8 = 11;
/// The line end right after a word's digits (not after a blank).
const EOL_WORD_STATE: u8 = 12;
/// Where the automaton stops, as [`STEP`] holds it.
const STOP: u16 = (NGM_STATE as u16) << 8;
const NGM: u16 = (NGM_STATE as u16) << 8;
const REJECT_ROW: u16 = (REJECT as u16) << 8;
const EOL_WORD: u16 = (EOL_WORD_STATE as u16) << 8;

/// One step of `word` and `plain_words` for a word of another letter than N, G, M or O:
/// `state` (below 8) and the next byte `c`.
const fn step(state: u8, c: u8) -> u8 {
    let blank = matches!(c, b' ' | b'\t' | b'\x0C');
    let digit = c.is_ascii_digit();
    let up = c & !0x20;
    let letter = up.is_ascii_uppercase();
    // What may follow a word's digits (`ends_token`), and then start the next word.
    let ends = if blank {
        SEP
    } else if letter && matches!(up, b'N' | b'G' | b'M') {
        NGM_STATE
    } else if letter && up != b'O' {
        LET
    } else if c == b';' {
        SEMI_STATE
    } else if c == b'\n' || c == b'\r' {
        EOL_STATE
    } else {
        REJECT
    };
    match state {
        SEP => ends,
        LET | SIGN => {
            if blank {
                state
            } else if state == LET && (c == b'-' || c == b'+') {
                SIGN
            } else if digit {
                INT
            } else if c == b'.' {
                POINT0
            } else {
                REJECT
            }
        }
        INT => {
            if digit {
                INT
            } else if c == b'.' {
                POINT
            } else if ends == EOL_STATE {
                EOL_WORD_STATE
            } else {
                ends
            }
        }
        POINT0 => {
            if digit {
                POINT
            } else {
                REJECT
            }
        }
        POINT => {
            if digit {
                POINT
            } else if ends == EOL_STATE {
                EOL_WORD_STATE
            } else {
                ends
            }
        }
        _ => REJECT,
    }
}

/// [`step`] for every state and byte, at `state << 8 | byte`, each next state as its row
/// (`state << 8`) or, where the automaton stops, as [`STOP`] and up (`read::run_automaton`
/// runs it); 8 rows, a power of two (the rows past the last state decline).
static STEP: [u16; 8 * 256] = crate::read::automaton_table!(8, step);

/// A blank between the parts of a block (`fast::blank`).
#[inline(always)]
fn blank(c: u8) -> bool {
    matches!(c, b' ' | b'\t' | b'\x0C')
}
