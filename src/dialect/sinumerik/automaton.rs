//! The index-only scan's reader of plain lines (`fast::skeleton_raw`): the decision of the
//! fast reader (`fast::read`) as a table-driven automaton over byte classes, one table
//! look-up per byte and no branch on what the byte is, since the index needs only whether
//! the line is a plain block, its number and whether it has words, not its values.
//! A test compares it with `fast::read` on many generated lines.

use crate::ir::SeqNo;
use crate::span::Span;

// Byte classes.
const BLANK: u8 = 0;
const DIGIT: u8 = 1;
const POINT: u8 = 2;
const SIGN: u8 = 3;
const SEMI: u8 = 4;
/// A letter that may address a word.
const LETTER: u8 = 5;
/// L, N, O, P: left to the grammar (calls, numbers, the letter O for zero, repeat counts).
const BAD: u8 = 6;
/// E: after a number, `EX` is an exponent.
const E: u8 = 7;
const X: u8 = 8;
const OTHER: u8 = 9;
const CLASSES: usize = 10;

const fn class_of(c: u8) -> u8 {
    match c {
        b' ' | b'\t' => BLANK,
        b'0'..=b'9' => DIGIT,
        b'.' => POINT,
        b'-' | b'+' => SIGN,
        b';' => SEMI,
        b'L' | b'N' | b'O' | b'P' | b'l' | b'n' | b'o' | b'p' => BAD,
        b'E' | b'e' => E,
        b'X' | b'x' => X,
        b'A'..=b'Z' | b'a'..=b'z' => LETTER,
        _ => OTHER,
    }
}

static CLASS: [u8; 256] = {
    let mut t = [OTHER; 256];
    let mut c = 0;
    while c < 256 {
        t[c] = class_of(c as u8);
        c += 1;
    }
    t
};

// States. At most 15 digits in a number (`fast::read` declines more).
const REJECT: u8 = 0;
/// Between words (blanks), or at the start after the block number.
const TOP: u8 = 1;
/// After a word's letter.
const AFTER_LETTER: u8 = 2;
/// After its sign.
const AFTER_SIGN: u8 = 3;
/// After a letter E that follows a number directly.
const AFTER_E: u8 = 4;
const COMMENT: u8 = 5;
/// `INT + k - 1`: k digits, no point (k = 1..=15).
const INT: u8 = 6;
/// `FRAC + k`: after the point, k digits in all (k = 0..=15).
const FRAC: u8 = 21;
const STATES: usize = 37;

/// Where a number ends (it has digits) and byte class `c` follows: `fast::read`'s check
/// of what may follow a word, then its start of the next word.
const fn after_number(c: u8) -> u8 {
    match c {
        BLANK => TOP,
        SEMI => COMMENT,
        LETTER | X => AFTER_LETTER,
        E => AFTER_E,
        _ => REJECT,
    }
}

/// Where a word's value starts (after its letter, or an E that is no exponent).
const fn value_start(c: u8) -> u8 {
    match c {
        SIGN => AFTER_SIGN,
        DIGIT => INT,
        POINT => FRAC,
        _ => REJECT,
    }
}

/// The transitions, `(state, class)` at `state * CLASSES + class`.
const TABLE: [u8; STATES * CLASSES] = {
    let mut t = [REJECT; STATES * CLASSES];
    let mut c = 0;
    while c < CLASSES {
        let cl = c as u8;
        t[TOP as usize * CLASSES + c] = match cl {
            BLANK => TOP,
            SEMI => COMMENT,
            LETTER | X | E => AFTER_LETTER,
            _ => REJECT,
        };
        t[AFTER_LETTER as usize * CLASSES + c] = value_start(cl);
        t[AFTER_SIGN as usize * CLASSES + c] = match cl {
            DIGIT => INT,
            POINT => FRAC,
            _ => REJECT,
        };
        t[AFTER_E as usize * CLASSES + c] = if cl == X { REJECT } else { value_start(cl) };
        t[COMMENT as usize * CLASSES + c] = COMMENT;
        let mut k = 1;
        while k <= 15 {
            let s = (INT + k as u8 - 1) as usize;
            t[s * CLASSES + c] = match cl {
                DIGIT if k < 15 => INT + k as u8,
                DIGIT => REJECT,
                POINT => FRAC + k as u8,
                _ => after_number(cl),
            };
            k += 1;
        }
        let mut k = 0;
        while k <= 15 {
            let s = (FRAC + k as u8) as usize;
            t[s * CLASSES + c] = match cl {
                DIGIT if k < 15 => FRAC + k as u8 + 1,
                DIGIT | POINT => REJECT,
                _ if k == 0 => REJECT,
                _ => after_number(cl),
            };
            k += 1;
        }
        c += 1;
    }
    t
};

/// Row stride of [`NEXT`]: at least [`CLASSES`], a power of two.
const STRIDE: usize = 16;
/// [`TABLE`] laid out for the scan loop: the entry for `(state, class)` at
/// `state * STRIDE + class` holds the next state times [`STRIDE`], so a step is one add,
/// and the table is 1024 long, so an index masked to 10 bits needs no bounds check.
static NEXT: [u16; 1024] = {
    let mut t = [0u16; 1024];
    let mut s = 0;
    while s < STATES {
        let mut c = 0;
        while c < CLASSES {
            t[s * STRIDE + c] = TABLE[s * CLASSES + c] as u16 * STRIDE as u16;
            c += 1;
        }
        s += 1;
    }
    t
};

/// Whether a line may end in state `s` (after a word, a number or a comment; `TOP` only
/// when something came before it, which the caller knows).
fn ends(s: u8) -> bool {
    s == COMMENT || (INT..FRAC + 16).contains(&s) && s != FRAC
}

/// `fast::read`'s decision on `b` (the line at file offset `start`) with no sink: the
/// block number and whether the block has words, or `None` when it declines the line.
pub fn skeleton(b: &[u8], start: u32) -> Option<(Option<SeqNo>, bool)> {
    let len = b.len();
    let mut i = 0;
    while i < len && matches!(b[i], b' ' | b'\t') {
        i += 1;
    }
    // Optional block number `N123` (not `N1.`, not followed by `=`), at most nine digits.
    let mut number = None;
    if i < len && (b[i] | 0x20) == b'n' {
        let mut j = i + 1;
        let mut value: u32 = 0;
        while j < len && b[j].is_ascii_digit() {
            if j - i > 9 {
                return None;
            }
            value = value * 10 + u32::from(b[j] - b'0');
            j += 1;
        }
        if j == i + 1 {
            return None;
        }
        number = Some(SeqNo { value, span: Span::new(start + i as u32, start + j as u32) });
        i = j;
    }
    // Words follow when, past blanks, something other than the comment does.
    let mut k = i;
    while k < len && matches!(b[k], b' ' | b'\t') {
        k += 1;
    }
    let words = k < len && b[k] != b';';
    let mut at = usize::from(TOP) * STRIDE;
    for &c in &b[i..] {
        at = usize::from(NEXT[(at + usize::from(CLASS[usize::from(c)])) & 1023]);
    }
    let s = (at / STRIDE) as u8;
    let ok = ends(s) || (s == TOP && (words || number.is_some()));
    (ok && (words || number.is_some() || s == COMMENT)).then_some((number, words))
}

#[cfg(test)]
mod tests {
    use super::super::fast::skeleton_by_read;
    use super::*;

    #[test]
    fn decides_as_the_fast_reader() {
        let pieces = [
            "G1",
            "X",
            "x",
            "-",
            "+",
            ".",
            "0",
            "12",
            "3.5",
            " ",
            "\t",
            ";",
            "; c",
            "N",
            "n",
            "N10",
            "E",
            "e",
            "EX",
            "ex",
            "X1",
            "Y-2.",
            "Z.5",
            "L",
            "O",
            "P",
            "=",
            "[",
            "(",
            "/",
            "123456789",
            "0000000",
            "1234567890123456",
            "é",
            "\0",
            "A",
            "F800",
            "M30",
            "G0O",
            "1EX3",
            "X1=",
            "X1 =",
            "X1 (",
        ];
        let mut state = 0x2545_F491_4F6C_DD1Du64;
        let mut next = |n: u64| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state % n
        };
        let mut taken = 0;
        for _ in 0..300_000 {
            let mut s = String::new();
            for _ in 0..next(9) {
                s.push_str(pieces[next(pieces.len() as u64) as usize]);
            }
            let want = skeleton_by_read(&s, 7);
            assert_eq!(skeleton(s.as_bytes(), 7), want, "{s:?}");
            taken += usize::from(want.is_some());
        }
        assert!(taken > 10_000, "only {taken} lines taken");
    }
}
