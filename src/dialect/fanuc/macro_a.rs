//! Macro A (`G65 Hm P#i Q#j R#k`), lowered at parse time to the Macro B meaning it has
//! (the H-code table, source G1 of `docs/semantics.md`), so later phases never see H codes. Every lowered node keeps the span
//! of the word it came from.

use super::parse::{RawWord, Seg};
use crate::diag::Diagnostic;
use crate::ir::{
    AlarmStyle, BinOp, CmpOp, Expr, ExprKind, Func, Goto, Item, ItemKind, Search, SeqNo, Target, Tolerance, VarKind,
};
use crate::span::Span;

fn bin(op: BinOp, a: Expr, b: Expr) -> Expr {
    let span = a.span.to(b.span);
    Expr::new(ExprKind::Binary(op, Box::new(a), Box::new(b)), span)
}

fn call(f: Func, args: Vec<Expr>, span: Span) -> Expr {
    Expr::new(ExprKind::Func(f, args), span)
}

/// Lowers one Macro A block. `g` is the G65 word, `others` every other word in order.
pub fn lower(seg: &Seg<'_>, g: &RawWord, others: &[&RawWord]) -> Result<Item, Diagnostic> {
    let find = |l: u8| others.iter().copied().find(|w| w.letter == l);
    let h = find(b'H').ok_or_else(|| internal(seg, g.span))?;
    let span = others.iter().fold(g.span, |s, w| s.to(w.span));
    for w in others {
        if !matches!(w.letter, b'H' | b'P' | b'Q' | b'R') {
            return Err(Diagnostic::error("NC175", format!("`{}` is not a Macro A operand", w.letter as char))
                .primary(seg.file, w.span, "unexpected in a G65 H block")
                .note("a Macro A block is `G65 Hm P#i Q#j R#k`")
                .hint("put other words in a separate block"));
        }
    }
    let code = match h.int() {
        Some(c) if c <= 99 => c as u8,
        _ => return Err(unknown(seg, h)),
    };
    let operand = |l: u8| -> Result<Expr, Diagnostic> {
        find(l).map(|w| w.value.clone()).ok_or_else(|| {
            Diagnostic::error("NC175", format!("G65 H{code:02} needs {}", l as char))
                .primary(seg.file, span, format!("{} missing", l as char))
                .note("Macro A operands: P#i = result variable, Q and R = variables (#j) or constants")
                .hint(format!("write e.g. `G65 H{code:02} P#101 Q#102 R#103`"))
        })
    };
    // The jumps take a sequence number in P.
    if (80..=86).contains(&code) {
        let p = find(b'P').ok_or_else(|| missing_p(seg, span, code))?;
        let target = match p.int() {
            Some(n) if (1..=99_999).contains(&n) => Target::Number(SeqNo { value: n as u32, span: p.value.span }),
            _ if p.lit.is_none() => Target::Computed(p.value.clone()),
            _ => {
                return Err(Diagnostic::error("NC173", "the jump target must be a sequence number 1..99999")
                    .primary(seg.file, p.span, "not a sequence number")
                    .hint(format!("write `G65 H{code} P100` to jump to N100")))
            }
        };
        let cond = if code == 80 {
            None
        } else {
            let (q, r) = (operand(b'Q')?, operand(b'R')?);
            let op = match code {
                81 => CmpOp::Eq,
                82 => CmpOp::Ne,
                83 => CmpOp::Gt,
                84 => CmpOp::Lt,
                85 => CmpOp::Ge,
                _ => CmpOp::Le,
            };
            let s = q.span.to(r.span);
            Some(Expr::new(ExprKind::Cmp(op, Tolerance::Exact, Box::new(q), Box::new(r)), s))
        };
        return Ok(Item {
            kind: ItemKind::Goto(Box::new(Goto {
                search: Search::ForwardThenWrap,
                target,
                cond,
                missing_continues: false,
            })),
            span,
        });
    }
    if code == 99 {
        let p = operand(b'P')?;
        let base = Expr::num(500.0, false, h.span);
        return Ok(Item {
            kind: ItemKind::Alarm {
                // H99 shows alarm 500+n: an alarm whose number is the value itself.
                style: AlarmStyle::Setal,
                number: bin(BinOp::Add, base, p),
                text: None,
            },
            span,
        });
    }
    let p = find(b'P').ok_or_else(|| missing_p(seg, span, code))?;
    let target = match &p.value.kind {
        ExprKind::Var(v) if !matches!(v.kind, VarKind::Hash(0)) => v.clone(),
        _ => {
            return Err(Diagnostic::error("NC175", "Macro A result must be a variable")
                .primary(seg.file, p.span, "`P#i` expected")
                .hint(format!("write the result variable after P: `G65 H{code:02} P#101 …`")))
        }
    };
    let q = || operand(b'Q');
    let r = || operand(b'R');
    let value = match code {
        1 => q()?,
        2 => bin(BinOp::Add, q()?, r()?),
        3 => bin(BinOp::Sub, q()?, r()?),
        4 => bin(BinOp::Mul, q()?, r()?),
        // "The remainder is not kept": the quotient truncated toward zero.
        5 => {
            let d = bin(BinOp::Div, q()?, r()?);
            let s = d.span;
            call(Func::Trunc, vec![d], s)
        }
        11 => bin(BinOp::FanucBitOr, q()?, r()?),
        12 => bin(BinOp::FanucBitAnd, q()?, r()?),
        13 => bin(BinOp::FanucBitXor, q()?, r()?),
        21 => {
            let a = q()?;
            let s = a.span;
            call(Func::Sqrt, vec![a], s)
        }
        22 => {
            let a = q()?;
            let s = a.span;
            call(Func::Abs, vec![a], s)
        }
        // Remainder of #j / #k with the H05 quotient: #j - FIX[#j/#k]*#k.
        23 => {
            let (a, b) = (q()?, r()?);
            let quo = bin(BinOp::Div, a.clone(), b.clone());
            let s = quo.span;
            let fix = call(Func::Trunc, vec![quo], s);
            bin(BinOp::Sub, a, bin(BinOp::Mul, fix, b))
        }
        24 => {
            let a = q()?;
            let s = a.span;
            call(Func::Bin, vec![a], s)
        }
        25 => {
            let a = q()?;
            let s = a.span;
            call(Func::Bcd, vec![a], s)
        }
        26 => {
            let own = Expr::new(ExprKind::Var(target.clone()), p.value.span);
            bin(BinOp::Div, bin(BinOp::Mul, own, q()?), r()?)
        }
        27 => {
            let (a, b) = (q()?, r()?);
            let sum = bin(BinOp::Add, bin(BinOp::Mul, a.clone(), a), bin(BinOp::Mul, b.clone(), b));
            let s = sum.span;
            call(Func::Sqrt, vec![sum], s)
        }
        31..=33 => {
            let f = [Func::Sin, Func::Cos, Func::Tan][(code - 31) as usize];
            let (a, b) = (q()?, r()?);
            let s = b.span;
            bin(BinOp::Mul, a, call(f, vec![b], s))
        }
        34 => {
            let (a, b) = (q()?, r()?);
            let s = a.span.to(b.span);
            call(Func::FanucAtan2, vec![a, b], s)
        }
        _ => return Err(unknown(seg, h)),
    };
    Ok(Item { kind: ItemKind::Assign { target, value }, span })
}

fn missing_p(seg: &Seg<'_>, span: Span, code: u8) -> Diagnostic {
    Diagnostic::error("NC175", format!("G65 H{code:02} needs P")).primary(seg.file, span, "P missing").hint(
        if (80..=86).contains(&code) {
            format!("write the target sequence number: `G65 H{code} P100`")
        } else {
            format!("write the result variable: `G65 H{code:02} P#101 Q#102 R#103`")
        },
    )
}

fn unknown(seg: &Seg<'_>, h: &RawWord) -> Diagnostic {
    Diagnostic::error("NC175", "unknown Macro A operation")
        .primary(seg.file, h.span, "not an H code of G65")
        .note("Macro A H codes: 01-05 11-13 21-27 31-34 80-86 99")
        .hint("check the H number, or rewrite the statement as Macro B: `#101=#102+#103`")
}

fn internal(seg: &Seg<'_>, span: Span) -> Diagnostic {
    Diagnostic::error("NC199", "Macro A block without H")
        .primary(seg.file, span, "here")
        .hint("please report this block (a bug in nctrans)")
}
