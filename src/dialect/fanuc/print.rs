//! FANUC `DPRNT[…]` as the IR's [`Print`]: its text, and each `#n[wf]` number field with its
//! places. What is not read here (`BPRNT`, a literal space, a character outside the ones the
//! sources list) stays the instruction it was written as, which the evaluator and the
//! translation name (NC554, NC510).

use crate::ir::{Expr, ExprKind, ItemKind, Print, PrintPart, VarKind, VarRef};
use crate::span::Span;

/// The characters a DPRNT text may hold besides `#n[wf]` fields and `*` (a space): letters,
/// digits, `+ - /` (Haas mill operator's manual 96-8000, "Formatted Output"; FANUC-compatible
/// NCT 2000M manual, "Decimal data output - DPRNT").
pub fn is_print_char(c: char) -> bool {
    c.is_ascii_uppercase() || c.is_ascii_digit() || matches!(c, '+' | '-' | '/')
}

/// `text` is the block's `DPRNT[…]` (upper case, as read) starting at `span.lo`; `None`
/// when it is not a DPRNT this module reads.
pub fn dprnt(text: &str, span: Span) -> Option<ItemKind> {
    let body = text.strip_prefix("DPRNT[")?.strip_suffix(']')?;
    let base = span.lo + 6;
    let b = body.as_bytes();
    let mut parts: Vec<PrintPart> = Vec::new();
    let mut lit = String::new();
    let mut i = 0;
    while i < b.len() {
        let c = b[i] as char;
        if c == '#' {
            let start = i;
            i += 1;
            let digits = b[i..].iter().take_while(|x| x.is_ascii_digit()).count();
            // `#n[wf]`: the number, then exactly two digits in brackets.
            let fmt = b.get(i + digits..i + digits + 4)?;
            if digits == 0 || fmt[0] != b'[' || fmt[3] != b']' || !fmt[1].is_ascii_digit() || !fmt[2].is_ascii_digit() {
                return None;
            }
            let n: u32 = body[i..i + digits].parse().ok()?;
            let vspan = Span::new(base + start as u32, base + (i + digits) as u32);
            let var = VarRef { kind: VarKind::Hash(n), span: vspan };
            let value = Expr::new(ExprKind::Var(Box::new(var)), vspan);
            if !lit.is_empty() {
                parts.push(PrintPart::Text(std::mem::take(&mut lit)));
            }
            parts.push(PrintPart::Field { value, int: fmt[1] - b'0', frac: fmt[2] - b'0' });
            i += digits + 4;
            continue;
        }
        match c {
            '*' => lit.push(' '),
            c if is_print_char(c) => lit.push(c),
            _ => return None,
        }
        i += 1;
    }
    if !lit.is_empty() {
        parts.push(PrintPart::Text(lit));
    }
    Some(ItemKind::Print(Box::new(Print { parts, file: None, status: None })))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parts(t: &str) -> Option<Vec<PrintPart>> {
        match dprnt(t, Span::new(0, t.len() as u32))? {
            ItemKind::Print(p) => Some(p.parts),
            _ => None,
        }
    }

    #[test]
    fn text_and_fields_are_read_and_the_rest_is_left() {
        assert_eq!(parts("DPRNT[PART*OK]"), Some(vec![PrintPart::Text("PART OK".into())]));
        assert_eq!(parts("DPRNT[]"), Some(vec![]));
        let p = parts("DPRNT[X#100[53]]").unwrap();
        assert!(matches!(&p[..], [PrintPart::Text(t), PrintPart::Field { int: 5, frac: 3, .. }] if t == "X"));
        assert_eq!(parts("DPRNT[A B]"), None, "a literal space");
        assert_eq!(parts("DPRNT[X#100]"), None, "a field without its format");
        assert_eq!(parts("DPRNT[X#[#1][53]]"), None);
        assert_eq!(parts("DPRNT[DIA.]"), None);
        assert_eq!(parts("BPRNT[X#1[3]]"), None);
    }
}
