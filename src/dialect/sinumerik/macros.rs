//! Siemens macros: `DEFINE NAME AS text` in a definition file (`_N_UMAC_DEF`, `_N_MGUD_DEF`,
//! …) makes the control read `text` wherever NAME stands in program code. The reader does the
//! same on each normalised block before the grammar sees it; every byte of a replacement
//! points back into the NAME it replaced, so diagnostics show the real source text. Names
//! are matched whole and without regard to case, never inside comments, strings or `$` names.
//! A macro's text is not searched for macros again (the control does not nest them).

use crate::read::Normalised;

fn ident_start(c: u8) -> bool {
    c.is_ascii_alphabetic() || c == b'_'
}

fn ident_char(c: u8) -> bool {
    c.is_ascii_alphanumeric() || c == b'_'
}

/// `norm` with every macro name replaced by its text; `None` when the block holds none.
pub fn expand(norm: &Normalised<'_>, macros: &[(String, String)]) -> Option<Normalised<'static>> {
    let text: &str = &norm.text;
    let b = text.as_bytes();
    let mut out: Option<(String, Vec<u32>)> = None;
    let mut copied = 0usize;
    let (mut i, mut quote) = (0usize, false);
    while i < b.len() {
        let c = b[i];
        if quote {
            quote = c != b'"';
            i += 1;
            continue;
        }
        match c {
            b'"' => {
                quote = true;
                i += 1;
            }
            b';' => break,
            _ if ident_start(c) && (i == 0 || !(ident_char(b[i - 1]) || b[i - 1] == b'$')) => {
                let start = i;
                while i < b.len() && ident_char(b[i]) {
                    i += 1;
                }
                let word = &text[start..i];
                let Some((_, body)) = macros.iter().find(|(n, _)| n.eq_ignore_ascii_case(word)) else { continue };
                let (s, map) = out.get_or_insert_with(|| (String::with_capacity(text.len() + 16), Vec::new()));
                for k in copied..start {
                    map.push(norm.offset(k));
                }
                s.push_str(&text[copied..start]);
                // The replacement's bytes point into the name, so its parts stay inside it.
                let (lo, last) = (norm.offset(start), norm.offset(i - 1));
                for k in 0..body.len() {
                    map.push((lo + k as u32).min(last));
                }
                s.push_str(body);
                copied = i;
            }
            _ => i += 1,
        }
    }
    let (mut s, mut map) = out?;
    for k in copied..b.len() {
        map.push(norm.offset(k));
    }
    s.push_str(&text[copied..]);
    map.push(norm.offset(b.len()).max(map.last().copied().unwrap_or(0)));
    Some(norm.rewritten(s, map))
}

/// Whether no macro of `macros` can stand in a line the fast reader takes (`fast::read`):
/// there every letter is followed by a sign, a digit or a point, so a whole word (`expand`'s)
/// never holds two letters in a row nor `_`. A name that does (`LINE`, `MAX_STAGE`) is
/// never met in such a line; one that does not (`M6`, `X`) may be, and then every line must
/// go through the reader's `line`, which expands it (the quick readers of a stream read
/// lines raw).
pub fn raw_safe(macros: &[(String, String)]) -> bool {
    macros.iter().all(|(name, _)| {
        let b = name.as_bytes();
        b.contains(&b'_') || b.windows(2).any(|w| w[0].is_ascii_alphabetic() && w[1].is_ascii_alphabetic())
    })
}

/// The `DEFINE NAME AS text` lines of a definition file's text, in order: the name upper
/// case, the text without its comment and outer blanks, and the byte range of the line.
pub fn defines(text: &str) -> Vec<(String, String, std::ops::Range<usize>)> {
    let mut out = Vec::new();
    let mut at = 0usize;
    for line in text.split_inclusive('\n') {
        let range = at..at + line.trim_end_matches(['\r', '\n']).len();
        at += line.len();
        let code = line.split(';').next().unwrap_or("").trim();
        let mut words = code.splitn(2, char::is_whitespace);
        if !words.next().is_some_and(|w| w.eq_ignore_ascii_case("DEFINE")) {
            continue;
        }
        let rest = words.next().unwrap_or("").trim_start();
        let name_len = rest.bytes().take_while(|&c| ident_char(c)).count();
        let (name, after) = rest.split_at(name_len);
        let after = after.trim_start();
        let body = match after.get(..2) {
            Some(kw) if kw.eq_ignore_ascii_case("AS") && after[2..].starts_with(char::is_whitespace) => {
                after[2..].trim()
            }
            _ => continue,
        };
        if !name.is_empty() && ident_start(name.as_bytes()[0]) && !body.is_empty() {
            out.push((name.to_ascii_uppercase(), body.to_string(), range));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::read::{normalise, CommentStyle, RawBlock};

    #[test]
    fn names_are_replaced_whole_outside_comments_strings_and_system_names() {
        let macros = vec![("LINE".to_string(), "G1 G94 F300".to_string()), ("STAGES".to_string(), "4".to_string())];
        let raw = RawBlock { text: "line X=STAGES $LINE MSG(\"LINE\") LINES ; LINE", start: 10, line: 1 };
        let n = normalise(&raw, CommentStyle::Semicolon);
        let e = expand(&n, &macros).expect("expanded");
        assert_eq!(e.text, "G1 G94 F300 X=4 $LINE MSG(\"LINE\") LINES ; LINE");
        // The replacement points into `line` (file 10..14), what follows is where it was.
        assert_eq!(e.span(0, 2), crate::span::Span::new(10, 12));
        assert_eq!(e.span(12, 13), crate::span::Span::new(15, 16));
        assert_eq!(e.span(14, 15), crate::span::Span::new(17, 23));
        let plain = RawBlock { text: "G1 X10", start: 0, line: 1 };
        assert!(expand(&normalise(&plain, CommentStyle::Semicolon), &macros).is_none());
    }

    /// A name with two letters in a row or `_` never is a whole word of a line the fast
    /// reader takes; `M6` or `X` may be (`M6`, `X-5`): then the raw readers stand down.
    #[test]
    fn raw_reading_stands_down_for_names_a_plain_line_can_hold() {
        let m = |names: &[&str]| names.iter().map(|n| (n.to_string(), "G1".to_string())).collect::<Vec<_>>();
        assert!(raw_safe(&m(&[])));
        assert!(raw_safe(&m(&["LINE", "MAX_STAGE", "_A", "GX1"])));
        for bad in ["M6", "X", "G1X", "N10"] {
            assert!(!raw_safe(&m(&["LINE", bad])), "{bad}");
        }
        // What the reader would expand there.
        for text in ["M6 X1", "G1 X-5", "G1X-1 Y2", "N10 G1"] {
            let raw = RawBlock { text, start: 0, line: 1 };
            let norm = normalise(&raw, CommentStyle::Semicolon);
            assert!(crate::dialect::sinumerik::fast::skeleton_raw(&raw).is_some(), "{text}");
            let all = m(&["M6", "X", "G1X", "N10"]);
            assert!(expand(&norm, &all).is_some(), "{text}");
        }
    }

    #[test]
    fn define_lines_are_read_with_their_text() {
        let d = defines(
            "; macros\nDEFINE LINE AS G1 G94 F300 ; feed\r\nDefine MaxStage As 5\nDEFINE BAD\nDEF NCK REAL X\n",
        );
        let got: Vec<(&str, &str)> = d.iter().map(|(n, t, _)| (n.as_str(), t.as_str())).collect();
        assert_eq!(got, vec![("LINE", "G1 G94 F300"), ("MAXSTAGE", "5")]);
        assert_eq!(d[1].2, 44..64);
    }
}
