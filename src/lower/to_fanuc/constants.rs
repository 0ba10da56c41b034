//! Siemens constants FANUC spells as numbers: `$PI`. FANUC takes at most 8 digits in a
//! number, and 3.1415927 is 4.6e-8 off: it shows in a comparison near its limit and in a
//! position once the factor is large. So `$PI` is written `[3.1415926+.53589793/10000000]`,
//! two 8-digit literals whose double-precision value is exactly the one Siemens `$PI` has,
//! and the rest of the program computes what the Siemens one does (docs/translation.md).

use crate::ir::{BinOp, Expr, ExprKind, Program, VarKind};

/// Replaces every `$PI` read of `prog` by its FANUC expression.
pub fn run(prog: &mut Program) {
    crate::lower::map_exprs(&mut prog.body, &mut fold);
}

fn is_pi(e: &Expr) -> bool {
    matches!(&e.kind, ExprKind::Var(v) if matches!(&v.kind, VarKind::System { name, indices }
        if name.eq_ignore_ascii_case("PI") && indices.is_empty()))
}

fn fold(e: &mut Expr) {
    if is_pi(e) {
        *e = pi(e.span);
        return;
    }
    for c in crate::lower::children_mut(e) {
        fold(c);
    }
}

/// `[3.1415926+.53589793/10000000]`: each literal within FANUC's 8 digits.
// The first literal is π cut to 8 digits on purpose: the second one carries the rest.
#[allow(clippy::approx_constant)]
pub fn pi(span: crate::span::Span) -> Expr {
    let n = |v: f64| Expr::num(v, true, span);
    let bin = |op, a, b| Expr::new(ExprKind::Binary(op, Box::new(a), Box::new(b)), span);
    bin(BinOp::Add, n(3.1415926), bin(BinOp::Div, n(0.53589793), n(10_000_000.0)))
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_expression_is_the_double_of_pi() {
        let e = super::pi(crate::span::Span::new(0, 0));
        let crate::ir::ExprKind::Binary(_, a, b) = &e.kind else { panic!() };
        let (crate::ir::ExprKind::Num(a), crate::ir::ExprKind::Binary(_, c, d)) = (&a.kind, &b.kind) else { panic!() };
        let (crate::ir::ExprKind::Num(c), crate::ir::ExprKind::Num(d)) = (&c.kind, &d.kind) else { panic!() };
        assert_eq!(a.value + c.value / d.value, std::f64::consts::PI);
    }
}
