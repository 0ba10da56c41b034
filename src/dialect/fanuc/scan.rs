//! Byte-level checks before the grammar: splitting a line at `;` end-of-block marks,
//! unclosed comments, unbalanced or too deeply nested brackets, `##`, and `<`/`>` in
//! conditions. Doing these first gives precise messages and bounds the grammar's recursion.

use super::parse::Seg;
use crate::diag::Diagnostic;
use crate::dialect::limits::MAX_NESTING;
use crate::dialect::ParseOptions;

/// Splits a normalised line into blocks at `;` outside comments. Yields `(lo, hi, end)`:
/// the trimmed block text `lo..hi` and `end`, one past its `;` (or `hi` without one).
/// Empty blocks (a lone `;`) are skipped. An iterator, so a line costs no allocation.
pub fn segments(text: &str) -> Segments<'_> {
    Segments { text, pos: 0 }
}

pub struct Segments<'a> {
    text: &'a str,
    /// Where the next block starts (`text.len() + 1` when done).
    pos: usize,
}

impl Iterator for Segments<'_> {
    type Item = (usize, usize, usize);

    fn next(&mut self) -> Option<(usize, usize, usize)> {
        let b = self.text.as_bytes();
        while self.pos < b.len() {
            let start = self.pos;
            // Up to the first `;` or `(` nothing can be in a comment; most lines have neither.
            let mut cut = None;
            match crate::read::find2(&b[start..], b';', b'(').map(|k| start + k) {
                Some(i) if b[i] == b';' => cut = Some(i),
                Some(i) => {
                    let mut in_comment = false;
                    for (i, &c) in b.iter().enumerate().skip(i) {
                        match c {
                            b'(' if !in_comment => in_comment = true,
                            b')' if in_comment => in_comment = false,
                            b';' if !in_comment => {
                                cut = Some(i);
                                break;
                            }
                            _ => {}
                        }
                    }
                }
                None => {}
            }
            let (hi, end) = match cut {
                Some(i) => (i, i + 1),
                None => (b.len(), b.len()),
            };
            self.pos = if cut.is_some() { hi + 1 } else { b.len() + 1 };
            if let Some(seg) = trimmed(self.text, start, hi, end) {
                return Some(seg);
            }
        }
        None
    }
}

fn trimmed(text: &str, lo: usize, hi: usize, end: usize) -> Option<(usize, usize, usize)> {
    let s = &text[lo..hi];
    let t = crate::read::trim_start(s);
    let lo2 = lo + (s.len() - t.len());
    let t = crate::read::trim_end(t);
    if t.is_empty() {
        return None;
    }
    let hi2 = lo2 + t.len();
    // A `;` that ends the block belongs to its span; otherwise the block ends at its text.
    let end2 = if end > hi { end } else { hi2 };
    Some((lo2, hi2, end2))
}

/// The `N` number a block starts with (after an optional `/n`), read textually; used to keep
/// GOTO checks quiet about blocks that failed to parse or were ignored.
pub fn leading_number(text: &str) -> Option<u32> {
    let t = text.trim_start();
    let t = t.strip_prefix('/').map_or(t, |r| r.trim_start_matches(|c: char| c.is_ascii_digit()));
    let t = t.trim_start();
    let rest = t.strip_prefix(['N', 'n'])?.trim_start();
    let digits: &str = &rest[..rest.find(|c: char| !c.is_ascii_digit()).unwrap_or(rest.len())];
    digits.parse().ok()
}

/// The number of a program-number line (`O1234 …`, `:1234`), if it is one.
pub fn program_number(text: &str) -> Option<u32> {
    let rest = text.trim_start().strip_prefix(['O', 'o', ':'])?.trim_start();
    let digits: &str = &rest[..rest.find(|c: char| !c.is_ascii_digit()).unwrap_or(rest.len())];
    digits.parse().ok()
}

/// Checks a block's brackets, comments and operator characters before parsing.
pub fn check(seg: &Seg<'_>, opts: &ParseOptions) -> Result<(), Diagnostic> {
    let b = seg.text.as_bytes();
    // Plain motion blocks have none of the characters checked here.
    if !b.iter().any(|&c| matches!(c, b'(' | b'[' | b']' | b'#' | b'<' | b'>' | b'!')) {
        return Ok(());
    }
    // Capped whatever the profile says, so no input makes the grammar recurse deeply.
    let max = opts.semantics.max_bracket_depth.min(MAX_NESTING);
    let mut depth: u32 = 0;
    let mut open: Vec<usize> = Vec::new();
    let mut comment: Option<usize> = None;
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        if comment.is_some() {
            if c == b')' {
                comment = None;
            }
            i += 1;
            continue;
        }
        match c {
            b'(' => comment = Some(i),
            b'[' => {
                depth += 1;
                if depth > max {
                    return Err(Diagnostic::error("NC163", format!("brackets nested more than {max} deep"))
                        .primary(seg.file, seg.span(i, i + 1), format!("bracket level {depth}"))
                        .secondary(seg.file, seg.span(open[0], open[0] + 1), "outermost bracket")
                        .note(format!(
                            "the control allows {max} levels of `[ ]`, function brackets included (alarm 118)"
                        ))
                        .hint("compute part of the expression into a variable first, e.g. `#100=[…]`"));
                }
                open.push(i);
            }
            b']' => {
                if open.pop().is_none() {
                    return Err(Diagnostic::error("NC162", "`]` without a matching `[`")
                        .primary(seg.file, seg.span(i, i + 1), "nothing to close here")
                        .hint("delete this `]` or add the missing `[` where the expression starts"));
                }
                depth -= 1;
            }
            b'#' => {
                let mut j = i + 1;
                while j < b.len() && (b[j] == b' ' || b[j] == b'\t') {
                    j += 1;
                }
                if b.get(j) == Some(&b'#') {
                    return Err(Diagnostic::error("NC164", "`##` is not a FANUC variable")
                        .primary(seg.file, seg.span(i, j + 1), "a variable number after `#` was expected")
                        .note("a variable number computed from another variable is written in brackets")
                        .hint("write `#[#1]` for the variable whose number is the value of #1"));
                }
            }
            b'<' | b'>' | b'!' => {
                let sym = c as char;
                let word = match (c, b.get(i + 1)) {
                    (b'<', Some(b'=')) => "LE",
                    (b'>', Some(b'=')) => "GE",
                    (b'<', Some(b'>')) | (b'!', _) => "NE",
                    (b'<', _) => "LT",
                    _ => "GT",
                };
                let next = b.get(i + 1).copied();
                let width = match (c, next) {
                    (b'<', Some(b'=' | b'>')) | (b'>' | b'!', Some(b'=')) => 2,
                    _ => 1,
                };
                return Err(Diagnostic::error(
                    "NC172",
                    format!("`{}` is not a FANUC comparison", &seg.text[i..i + width]),
                )
                .primary(seg.file, seg.span(i, i + width), format!("`{sym}` here"))
                .note(
                    "FANUC conditions use the two-letter operators EQ NE GT GE LT LE; `<`, `>` and `=` are not allowed",
                )
                .hint(format!("write `{word}`, e.g. `IF[#1 {word} 10]GOTO100`")));
            }
            _ => {}
        }
        i += 1;
    }
    if let Some(at) = comment {
        return Err(Diagnostic::error("NC161", "comment not closed")
            .primary(seg.file, seg.span(at, b.len()), "this `(` is never closed")
            .note("a comment runs from `(` to `)` on the same block; comments cannot span lines")
            .hint("add `)` at the end of the comment"));
    }
    if let Some(&at) = open.last() {
        return Err(Diagnostic::error("NC162", "`[` without a matching `]`")
            .primary(seg.file, seg.span(at, at + 1), "this `[` is never closed")
            .secondary(seg.file, seg.span(b.len(), b.len()), "the block ends here")
            .hint("add the missing `]` (every `[` needs its `]` in the same block)"));
    }
    Ok(())
}

/// A separator line: only `*`, `=`, `-`, `_` and blanks, at least three of the marks and
/// no `-` followed by a digit (never a signed value).
pub fn decorative(text: &str) -> bool {
    let b = text.as_bytes();
    let marks = b.iter().filter(|c| matches!(c, b'*' | b'=' | b'-' | b'_')).count();
    marks >= 3 && b.iter().all(|c| matches!(c, b'*' | b'=' | b'-' | b'_' | b' ' | b'\t'))
}
