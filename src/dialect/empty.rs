//! Program-less files: an empty file, or one holding only blank lines, comments, `%` marks
//! and a program header, is one diagnostic (NC145) in every command and both dialects, so
//! a failed transfer is never "translated" into a program without an end or "equivalent".

use crate::diag::Diagnostic;
use crate::ir::{Program, StmtKind, Unit};
use crate::span::{FileId, Span};
use std::io::BufRead;
use std::path::Path;

/// Whether a parsed unit holds no executable block: every program (if any) is a header
/// and comment-only or empty blocks.
pub fn program_less(unit: &Unit) -> bool {
    !unit.programs.iter().any(has_content)
}

/// Whether a program holds an executable block (a structure counts, even when empty).
pub fn has_content(p: &Program) -> bool {
    p.body.iter().any(|s| match &s.kind {
        StmtKind::Block(b) => !b.items.is_empty(),
        _ => true,
    })
}

/// The NC145 diagnostic for `file` with `text`: the same in every command. It points at
/// the first line (empty for an empty file).
pub fn diagnostic(file: FileId, text: &str) -> Diagnostic {
    let first = text.find(['\n', '\r']).unwrap_or(text.len()) as u32;
    Diagnostic::error("NC145", "the file holds no program: nothing to run, check or translate")
        .primary(file, Span::new(0, first), "no block with a word or statement in this file")
        .note("the file is empty, or holds only blank lines, comments, `%` marks and a program header")
        .hint(
            "check that the right file was given and that its transfer finished (an empty file is often a failed copy)",
        )
}

/// Whether the file at `path` may be program-less, read as text line by line up to its
/// first line that is not blank, a comment, a `%` line or a program header. The streamed
/// paths take only files for which this is false, so the whole-file path (which parses and
/// reports NC145 exactly) sees every file that could be program-less. An unreadable file
/// is "may be": the whole path reports why it cannot be read.
pub fn may_be_program_less(path: &Path) -> bool {
    let Ok(f) = std::fs::File::open(path) else { return true };
    let mut r = std::io::BufReader::with_capacity(1 << 16, f);
    let mut line = Vec::new();
    let mut marks = 0;
    loop {
        line.clear();
        match r.read_until(b'\n', &mut line) {
            Ok(0) | Err(_) => return true,
            Ok(_) => {}
        }
        // Lone CR line ends: each piece is a line.
        for piece in line.split(|&b| b == b'\r' || b == b'\n') {
            let text = String::from_utf8_lossy(piece);
            // A second `%` line closes the tape (whatever follows it on the line): the
            // FANUC reader reads nothing after it, so content there does not count.
            if text.trim_start_matches('\u{feff}').trim_start().starts_with('%') {
                marks += 1;
                if marks >= 2 {
                    return true;
                }
            }
            if looks_like_content(&text) {
                return false;
            }
        }
    }
}

/// A line that surely holds a word or statement in either dialect. "No" may be wrong
/// (the whole-file parse then decides), "yes" must not be: everything that could leave a
/// block without items is taken away first (comments, `%`, headers, block skip, block
/// numbers and labels, `&`), and what is left is counted as content.
fn looks_like_content(line: &str) -> bool {
    let t = line.trim_start_matches('\u{feff}').trim();
    if t.starts_with('%') {
        return false;
    }
    // `;` comments to the end of the line; FANUC `( … )` comments anywhere.
    let t = t.split(';').next().unwrap_or("");
    let mut rest = String::with_capacity(t.len());
    let mut depth = 0u32;
    for c in t.chars() {
        match c {
            '(' => depth += 1,
            ')' if depth > 0 => depth -= 1,
            _ if depth == 0 && c != '&' => rest.push(c.to_ascii_uppercase()),
            _ => {}
        }
    }
    let mut r = rest.trim();
    // A FANUC separator line (`* * *`, `=====`) is read as a comment block (NC250).
    if crate::dialect::fanuc::decorative(r) {
        return false;
    }
    // FANUC `O1234` / `:1234` headers (whatever follows), Siemens `PROC NAME(…)`.
    if r.starts_with("PROC ") || r == "PROC" {
        return false;
    }
    let digits = |s: &str| s.trim_start_matches(|c: char| c.is_ascii_digit()).to_string();
    if r.strip_prefix(['O', ':']).is_some_and(|x| x.starts_with(|c: char| c.is_ascii_digit())) {
        return false;
    }
    // Block skip `/`, `/3`; block numbers `N10`, `:10`; a label `NAME:`.
    let owned;
    if let Some(x) = r.strip_prefix('/') {
        owned = digits(x);
        r = owned.trim();
    }
    let owned2;
    if let Some(x) = r.strip_prefix(['N', ':']).filter(|x| x.starts_with(|c: char| c.is_ascii_digit())) {
        owned2 = digits(x);
        r = owned2.trim();
    }
    if let Some((label, after)) = r.split_once(':') {
        if !label.is_empty() && label.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
            r = after.trim();
        }
    }
    !r.is_empty()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_and_comment_lines_are_not_content_but_a_word_is() {
        let none = [
            "",
            "  ",
            "; note",
            "(note)",
            "%",
            "%_N_PART_MPF",
            "O1000 (TITLE)",
            ":0100",
            "PROC SUB(REAL A)",
            "N10",
            "/N20 (skip)",
            "START:",
            "&",
            "* * * * * * * ",
            "=========",
        ];
        for l in none {
            assert!(!looks_like_content(l), "{l:?}");
        }
        for l in ["G0 X1", "M30", "R1=2", "#1=2", "N10 G1", "ORIGIN=1", "(C) G1 X1", "/2 M0", "LBL: G0 X1"] {
            assert!(looks_like_content(l), "{l:?}");
        }
    }

    #[test]
    fn content_after_the_closing_percent_does_not_count() {
        let dir = std::env::temp_dir().join(format!("nctrans-empty-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let closed = dir.join("closed.nc");
        std::fs::write(&closed, "%\nO1 (T)\n%21 G17\nT2 M06\nG0 X1\n").unwrap();
        assert!(may_be_program_less(&closed));
        let open = dir.join("open.nc");
        std::fs::write(&open, "%\nO1 (T)\nG0 X1\n%\n").unwrap();
        assert!(!may_be_program_less(&open));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
