//! The index-only first scan's reader of a plain Sinumerik line straight from the read
//! buffer ([`skeleton_bytes`]): a byte automaton ([`STEP`]) over the words; it stands for
//! `fast::skeleton_raw` (tests/skeleton_diff.rs holds it to that).

/// For an index-only first scan straight from the read buffer (`crate::stream::scan_index`):
/// `b` starts at a line start and runs on past it (the line ends at the first CR or LF). The
/// line when `fast::skeleton_raw` would take it with the same number and words, and it holds only
/// plain bytes (printable ASCII, tab, form feed, SUB: valid UTF-8, no control character to
/// count); `None` when it may not be so (the caller then reads the line the general way),
/// which includes a line not ending within `b`.
///
/// Why this is `fast::read`'s decision: the block number is read by the same steps; the words
/// by an automaton ([`STEP`]) whose states are where `read` is in a word, one step per
/// byte, the end of the line being a CR or LF here where it is the end of the text there.
/// It declines what `read` declines; an `EX` after a word's digits too (`read` looks for it
/// after the word, the automaton finds an `E` word without a value: both decline). After a
/// blank it does not look for `=`, `[` or `(` as `read` does: the next step declines them.
#[inline(always)]
pub fn skeleton_bytes(b: &[u8]) -> Option<crate::read::SkelLine> {
    let len = b.len();
    let mut i = 0;
    let mut number = None;
    while i < len && blank(b[i]) {
        i += 1;
    }
    if i < len && (b[i] | 0x20) == b'n' {
        let mut j = i + 1;
        let mut value: u32 = 0;
        while j < len {
            let d = b[j].wrapping_sub(b'0');
            if d > 9 {
                break;
            }
            if j - i > 9 {
                return None;
            }
            value = value * 10 + u32::from(d);
            j += 1;
        }
        let c = *b.get(j)?;
        if j == i + 1 || !(blank(c) || c == b';' || c.is_ascii_alphabetic() || c == b'\n' || c == b'\r') {
            return None;
        }
        number = Some((value, i, j));
        i = j;
        while i < len && blank(b[i]) {
            i += 1;
        }
    }
    // The first word, if any, starts here (the automaton declines anything else but a
    // comment or the line end).
    let words = b.get(i).is_some_and(u8::is_ascii_alphabetic);
    let (at, how) = crate::read::run_automaton(&STEP, &b[i..], 0, STOP)?;
    let at = i + at;
    match how {
        EOL if words || number.is_some() => Some(crate::read::SkelLine { len: at, lo: 0, hi: at, number, words }),
        SEMI => {
            let (k, plain) = crate::read::line_end(&b[at + 1..]);
            let end = at + 1 + k;
            (plain && end < len).then_some(crate::read::SkelLine { len: end, lo: 0, hi: end, number, words })
        }
        // A blank line (`read` declines it) or a decline.
        _ => None,
    }
}

/// The states of [`skeleton_bytes`]'s automaton: between words (after a blank), after a
/// word's letter, after its sign; `I0 + k` after `k` digits (no point), `P0 + k` after the
/// point and `k` digits in all (below 64). The last three: it stops (decline, comment, line end).
const SEP: u8 = 0;
const LET: u8 = 1;
const SIGN: u8 = 2;
const I0: u8 = 2;
const P0: u8 = 18;
const REJECT: u8 = 0xFD;
const SEMI_STATE: u8 = 0xFE;
const EOL_STATE: u8 = 0xFF;
/// Where the automaton stops, as [`STEP`] holds it.
const SEMI: u16 = (SEMI_STATE as u16) << 8;
const EOL: u16 = (EOL_STATE as u16) << 8;

/// One step of `fast::read` in a word: `state` (below 64) and the next byte `c`.
const fn step(state: u8, c: u8) -> u8 {
    let blank = c == b' ' || c == b'\t';
    let digit = c.is_ascii_digit();
    let up = c & !0x20;
    // `read`'s letters: L, N, O and P are left to the grammar.
    let letter = up.is_ascii_uppercase() && !matches!(up, b'L' | b'N' | b'O' | b'P');
    // What may follow a word's digits: a blank, the next word, the comment or the end.
    let ends = if blank {
        SEP
    } else if letter {
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
            if state == LET && (c == b'-' || c == b'+') {
                SIGN
            } else if digit {
                I0 + 1
            } else if c == b'.' {
                P0
            } else {
                REJECT
            }
        }
        // `I0 + k`: `k` digits (1..=15).
        3..=17 => {
            if digit {
                if state < I0 + 15 {
                    state + 1
                } else {
                    REJECT
                }
            } else if c == b'.' {
                P0 + (state - I0)
            } else {
                ends
            }
        }
        // A point and no digit yet: a digit must follow.
        P0 => {
            if digit {
                P0 + 1
            } else {
                REJECT
            }
        }
        // `P0 + k`: a point and `k` digits (1..=15) in all.
        19..=33 => {
            if digit {
                if state < P0 + 15 {
                    state + 1
                } else {
                    REJECT
                }
            } else {
                ends
            }
        }
        _ => REJECT,
    }
}

/// [`step`] for every state and byte, at `state << 8 | byte`, each next state as its row
/// (`state << 8`) or, where the automaton stops, as [`STOP`] and up (`read::run_automaton`
/// runs it); 64 rows, a power of two (the rows past the last state decline).
static STEP: [u16; 64 * 256] = crate::read::automaton_table!(64, step);

/// Rows at and above this are where the automaton stops.
const STOP: u16 = 64 << 8;

/// A blank between words (`fast::blank`).
#[inline(always)]
fn blank(c: u8) -> bool {
    c == b' ' || c == b'\t'
}
