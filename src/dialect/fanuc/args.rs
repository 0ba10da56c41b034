//! `G65`/`G66` macro calls and `M98` subprogram calls: the program number, the repeat count,
//! and the argument letters resolved to local variables (argument specification I and II,
//! sources H1 and I1 of `docs/semantics.md`).

use super::parse::{RawWord, Seg};
use crate::diag::Diagnostic;
use crate::ir::{Arg, Call, CallKind, CallTarget, Expr, ExprKind, Item, ItemKind};
use crate::span::Span;

/// Argument specification I: the local variable each letter fills.
pub fn spec_i(letter: u8) -> Option<u8> {
    Some(match letter {
        b'A' => 1,
        b'B' => 2,
        b'C' => 3,
        b'I' => 4,
        b'J' => 5,
        b'K' => 6,
        b'D' => 7,
        b'E' => 8,
        b'F' => 9,
        b'H' => 11,
        b'M' => 13,
        b'Q' => 17,
        b'R' => 18,
        b'S' => 19,
        b'T' => 20,
        b'U' => 21,
        b'V' => 22,
        b'W' => 23,
        b'X' => 24,
        b'Y' => 25,
        b'Z' => 26,
        _ => return None,
    })
}

/// Resolves argument letters in written order. A, B, C and the letters other than I/J/K use
/// specification I; I, J, K fill specification II sets (I1 J1 K1 → #4 #5 #6, I2 J2 K2 → #7 #8
/// #9, …, up to ten sets), a new set starting whenever a letter repeats or goes backwards in
/// I-J-K order. Where both forms name the same variable, both arguments are kept in written
/// order, so the later one wins when the call assigns them (`A1 I3 I4 D5` → #7 = 5).
#[derive(Default)]
pub struct ArgResolver {
    set: u8,
    last: Option<u8>,
}

impl ArgResolver {
    pub fn new() -> Self {
        Self::default()
    }

    /// The variable for `letter`, or `None` when the letter cannot be an argument or an
    /// eleventh I/J/K set would be needed (`Err(())`).
    pub fn var(&mut self, letter: u8) -> Result<Option<u8>, ()> {
        let pos = match letter {
            b'I' => 0,
            b'J' => 1,
            b'K' => 2,
            _ => return Ok(spec_i(letter)),
        };
        if self.last.is_some_and(|l| pos <= l) {
            self.set += 1;
        }
        self.last = Some(pos);
        if self.set > 9 {
            return Err(());
        }
        Ok(Some(4 + 3 * self.set + pos))
    }
}

fn cover(words: &[&RawWord]) -> Span {
    words.iter().map(|w| w.span).reduce(Span::to).unwrap_or_default()
}

/// A program number written after `P`: a literal (`P9010`) or a variable/expression.
fn target(seg: &Seg<'_>, p: &RawWord, what: &str) -> Result<CallTarget, Diagnostic> {
    if p.lit.is_none() {
        // `M98 P[10]`: a bracketed whole number is that program (nothing is computed).
        if let ExprKind::Num(n) = &p.value.kind {
            if n.value.fract() == 0.0 && (1.0..=99_999_999.0).contains(&n.value) {
                return Ok(CallTarget::Number(n.value as u32));
            }
        }
        return Ok(CallTarget::Computed(p.value.clone()));
    }
    match p.int() {
        Some(n) if (1..=99_999_999).contains(&n) => Ok(CallTarget::Number(n as u32)),
        _ => Err(Diagnostic::error("NC174", format!("`P` of {what} is not a program number"))
            .primary(seg.file, p.span, "program number expected")
            .note("program numbers are whole numbers 1..99999999 written without a decimal point")
            .hint(format!("write e.g. `{what} P9010`"))),
    }
}

/// `G65`/`G66 P… [L…] args`: every word of the block except the G code itself belongs to the call.
pub fn macro_call(seg: &Seg<'_>, kind: CallKind, g: &RawWord, others: &[&RawWord]) -> Result<Item, Diagnostic> {
    let what = if kind == CallKind::G66 { "G66" } else { "G65" };
    let mut prog = None;
    let mut repeat = None;
    let mut args = Vec::new();
    let mut res = ArgResolver::new();
    for w in others {
        match w.letter {
            b'P' if prog.is_none() => prog = Some(target(seg, w, what)?),
            b'L' if repeat.is_none() => repeat = Some(w.value.clone()),
            letter => {
                let var = res.var(letter).map_err(|()| {
                    Diagnostic::error("NC176", "more than ten I/J/K argument sets")
                        .primary(seg.file, w.span, "an eleventh set starts here")
                        .note("argument specification II passes at most ten I, J, K sets (#4..#33)")
                        .hint("pass the remaining values in common variables (#100..) before the call")
                })?;
                let Some(var) = var else {
                    let l = letter as char;
                    return Err(Diagnostic::error("NC174", format!("`{l}` cannot be a {what} argument"))
                        .primary(seg.file, w.span, "not an argument letter")
                        .secondary(seg.file, g.span, format!("{what} call"))
                        .note("G, L, N, O and P cannot pass arguments (P and L only once: program and repeat count)")
                        .hint(if letter == b'G' {
                            format!("put other G codes in their own block before the {what} block")
                        } else {
                            "pass this value with another letter, or in a common variable".to_string()
                        }));
                };
                args.push(Arg::Letter { letter, var, value: w.value.clone() });
            }
        }
    }
    let Some(target) = prog else {
        return Err(Diagnostic::error("NC174", format!("{what} without a program number"))
            .primary(seg.file, g.span, "P missing")
            .hint(format!("write the macro's program number: `{what} P9010 …`")));
    };
    let mut all: Vec<&RawWord> = vec![g];
    all.extend_from_slice(others);
    Ok(Item { kind: ItemKind::Call(Box::new(Call { kind, target, args, repeat })), span: cover(&all) })
}

/// Haas `M97 Pn [Lm]`: the local subprogram at block Nn, m times.
pub fn m97(seg: &Seg<'_>, m: &RawWord, p: Option<&RawWord>, l: Option<&RawWord>) -> Result<Item, Diagnostic> {
    let target = match p.and_then(|p| p.int().map(|n| (n, p))) {
        Some((n, _)) if (1..=99_999).contains(&n) => CallTarget::Number(n as u32),
        _ => {
            return Err(Diagnostic::error("NC252", "M97 needs the sequence number of its local subprogram")
                .primary(seg.file, p.map_or(m.span, |p| p.span), "P with a block number 1..99999 expected")
                .note("Haas M97 Pn runs the blocks from Nn of this program up to their M99")
                .hint("write `M97 P1000` and start the subprogram with `N1000`"))
        }
    };
    let mut all = vec![m];
    all.extend(p);
    all.extend(l);
    let repeat = l.map(|l| l.value.clone());
    Ok(Item {
        kind: ItemKind::Call(Box::new(Call { kind: CallKind::M97, target, args: vec![], repeat })),
        span: cover(&all),
    })
}

/// `M98 P… [L…]`, with the packed form `P68003` (= O8003 six times) when no `L` is written.
pub fn m98(seg: &Seg<'_>, m: &RawWord, p: Option<&RawWord>, l: Option<&RawWord>) -> Result<Item, Diagnostic> {
    let Some(p) = p else {
        return Err(Diagnostic::error("NC174", "M98 without a program number")
            .primary(seg.file, m.span, "P missing")
            .hint("write the subprogram number: `M98 P1000`"));
    };
    let mut repeat = l.map(|l| l.value.clone());
    let target = match (p.int(), p.lit, l) {
        (Some(v), Some(lit), None) if p.digits() > 4 && v >= 10_000 => {
            // The digits before the last four are the count (`M98 P68003`, source R1).
            let split = lit.hi - 4;
            let count = v / 10_000;
            repeat = Some(Expr::new(
                ExprKind::Num(crate::ir::Number { value: count as f64, point: false }),
                seg.span(lit.lo, split),
            ));
            CallTarget::Number((v % 10_000) as u32)
        }
        _ => target(seg, p, "M98")?,
    };
    let mut all = vec![m, p];
    all.extend(l);
    Ok(Item {
        kind: ItemKind::Call(Box::new(Call { kind: CallKind::M98, target, args: vec![], repeat })),
        span: cover(&all),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn resolve(letters: &str) -> Vec<Option<u8>> {
        let mut r = ArgResolver::new();
        letters.bytes().map(|l| r.var(l).ok().flatten()).collect()
    }

    #[test]
    fn spec_i_and_ii() {
        assert_eq!(resolve("ABCXYZ"), vec![Some(1), Some(2), Some(3), Some(24), Some(25), Some(26)]);
        assert_eq!(resolve("IJKIJK"), vec![Some(4), Some(5), Some(6), Some(7), Some(8), Some(9)]);
        assert_eq!(resolve("IK"), vec![Some(4), Some(6)]);
        assert_eq!(resolve("II"), vec![Some(4), Some(7)]);
        assert_eq!(resolve("KI"), vec![Some(6), Some(7)]);
        // The F1 example: A1 B2 I-3 I4 D5: the second I is #7, D also #7 (later wins).
        assert_eq!(resolve("ABIID"), vec![Some(1), Some(2), Some(4), Some(7), Some(7)]);
        assert_eq!(resolve("GLNOP"), vec![None; 5]);
    }

    #[test]
    fn eleven_sets_are_refused() {
        let mut r = ArgResolver::new();
        for _ in 0..10 {
            assert!(r.var(b'I').is_ok());
        }
        assert_eq!(r.var(b'I'), Err(()));
    }
}
