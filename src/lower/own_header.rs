//! The header comments nctrans itself writes, recognised when a translation is translated
//! again, so a round trip (S→F→S, F→S→F) does not pile up old headers: the new header says
//! the same about the new file. Only the comment-only blocks at the very top of a program
//! are dropped, and `nctrans: set` input lines always stay (the evaluator reads them).

use crate::ir::*;

/// Whether a comment is a test input line (`nctrans: set R1=5`). A translation writes it in
/// the output's variable names, which needs the whole program's variable map: the streamed
/// writers leave blocks holding one to the whole translation.
pub fn is_test_input(text: &str) -> bool {
    text.trim().get(..12).is_some_and(|h| h.eq_ignore_ascii_case("nctrans: set"))
}

/// Whether `body` starts with the header of a Sinumerik → FANUC translation
/// (`(NCTRANS: SINUMERIK … TO FANUC MACRO B)`): its `O` line's title is then the name
/// nctrans gave it, not the programmer's, and a translation back leaves it out.
pub fn translated_by_nctrans(body: &[Stmt]) -> bool {
    body.iter()
        .map_while(|s| match &s.kind {
            StmtKind::Block(b) if b.items.is_empty() => Some(&b.meta.comments),
            _ => None,
        })
        .flatten()
        .any(|c| c.text.trim().starts_with("NCTRANS: SINUMERIK "))
}

/// Whether `text` is a header line nctrans wrote (`after_map`: a `FANUC variable map:`
/// line came before it in the same header, so `#500 = R0` lines are its entries).
fn is_own(text: &str, after_map: bool) -> bool {
    let t = text.trim();
    if is_test_input(t) {
        return false;
    }
    t.starts_with("NCTRANS: ")
        || t.starts_with("Translated by nctrans from FANUC")
        || t == "FANUC variable map:"
        || (after_map && (t.starts_with('#') && t.contains(" = ") || t.starts_with("(an is-set flag")))
}

/// The indices of the leading comment-only blocks of `body` that are nctrans header lines.
fn own_lines(body: &[Stmt]) -> Vec<usize> {
    let mut out = Vec::new();
    let mut after_map = false;
    for (i, s) in body.iter().enumerate() {
        let StmtKind::Block(b) = &s.kind else { break };
        let m = &b.meta;
        if !b.items.is_empty() || m.label.is_some() || m.number.is_some() || m.skip.is_some() || m.comments.len() != 1 {
            break;
        }
        let t = &m.comments[0].text;
        if is_own(t, after_map) {
            after_map |= t.trim() == "FANUC variable map:";
            out.push(i);
        }
    }
    out
}

/// Whether the program starts with header lines of an earlier translation.
pub fn has_own_header(p: &Program) -> bool {
    !own_lines(&p.body).is_empty()
}

/// Drops the header lines of an earlier translation from the top of `p`.
pub fn drop_own_header(p: &mut Program) {
    let drop = own_lines(&p.body);
    let mut i = 0;
    p.body.retain(|_| {
        let keep = !drop.contains(&i);
        i += 1;
        keep
    });
}

#[cfg(test)]
mod tests {
    use super::is_own;

    #[test]
    fn own_header_lines_are_told_from_user_comments() {
        assert!(is_own(" NCTRANS: SINUMERIK A.MPF TO FANUC MACRO B", false));
        assert!(is_own("NCTRANS: R1 = #501", false));
        assert!(is_own("Translated by nctrans from FANUC O0001", false));
        assert!(is_own("  #500 = R0", true));
        assert!(!is_own("  #500 = R0", false));
        assert!(!is_own(" nctrans: set R1=2", false));
        assert!(!is_own("NCTRANS: SET #1=2", false));
        assert!(!is_own("Seed 000 6.1: hemisphere", false));
        assert!(!is_own("直径 8 毫米球头立铣刀", false));
    }
}
