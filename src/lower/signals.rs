//! Where a program uses machine signals, for both translations (`to_fanuc::signals`,
//! `to_sinumerik::signals`): every variable a statement reads or writes, with whether the
//! read is directly compared with the literal 0 or 1. A signal wired to one of narrower
//! range (a PLC byte to a FANUC bit) carries the program's meaning only there
//! (docs/translation.md, Machine signals). Synchronized actions are left out: they stay
//! refused as a whole.

use crate::ir::*;

/// How a statement uses a variable.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Use {
    /// Read; `bit_compared`: as one side of a comparison whose other side is 0 or 1.
    Read {
        bit_compared: bool,
    },
    Write,
}

/// Calls `f` on every variable of `body` with its use.
pub fn walk(body: &mut [Stmt], f: &mut dyn FnMut(&mut VarRef, Use)) {
    for s in body {
        match &mut s.kind {
            StmtKind::Block(b) => b.items.iter_mut().for_each(|it| item(it, f)),
            StmtKind::If(i) => {
                expr(&mut i.cond, f);
                walk(&mut i.then_body, f);
                if let Some(e) = &mut i.else_part {
                    walk(&mut e.body, f);
                }
            }
            StmtKind::While(w) => {
                expr(&mut w.cond, f);
                walk(&mut w.body, f);
            }
            StmtKind::Loop(l) => walk(&mut l.body, f),
            StmtKind::For(x) => {
                f(&mut x.var, Use::Write);
                expr(&mut x.from, f);
                expr(&mut x.to, f);
                walk(&mut x.body, f);
            }
            StmtKind::Repeat(r) => {
                walk(&mut r.body, f);
                expr(&mut r.until, f);
            }
            StmtKind::Do(d) => {
                if let Some(c) = &mut d.cond {
                    expr(c, f);
                }
                walk(&mut d.body, f);
            }
        }
    }
}

fn item(it: &mut Item, f: &mut dyn FnMut(&mut VarRef, Use)) {
    match &mut it.kind {
        ItemKind::SyncAction(_) => {}
        ItemKind::Assign { target, value } => {
            f(target, Use::Write);
            match &mut target.kind {
                VarKind::HashIndirect(x) | VarKind::RIndirect(x) => expr(x, f),
                VarKind::Named { indices, .. } | VarKind::System { indices, .. } => {
                    indices.iter_mut().for_each(|x| expr(x, f))
                }
                VarKind::Hash(_) | VarKind::R(_) => {}
            }
            expr(value, f);
        }
        ItemKind::IfThen { cond, then } => {
            expr(cond, f);
            item(then, f);
        }
        ItemKind::IfBlock { cond, items } => {
            expr(cond, f);
            items.iter_mut().for_each(|i| item(i, f));
        }
        _ => super::item_exprs_mut(it, &mut |e| expr(e, f)),
    }
}

fn is_bit_literal(e: &Expr) -> bool {
    matches!(&e.kind, ExprKind::Num(x) if x.value == 0.0 || x.value == 1.0)
}

fn expr(e: &mut Expr, f: &mut dyn FnMut(&mut VarRef, Use)) {
    match &mut e.kind {
        ExprKind::Var(v) => {
            f(v, Use::Read { bit_compared: false });
            super::children_mut(e).into_iter().for_each(|c| expr(c, f));
        }
        ExprKind::Cmp(_, _, a, b) => {
            let (bit_a, bit_b) = (is_bit_literal(a), is_bit_literal(b));
            for (x, other) in [(&mut **a, bit_b), (&mut **b, bit_a)] {
                match &mut x.kind {
                    ExprKind::Var(v) if other => {
                        f(v, Use::Read { bit_compared: true });
                        super::children_mut(x).into_iter().for_each(|c| expr(c, f));
                    }
                    _ => expr(x, f),
                }
            }
        }
        _ => super::children_mut(e).into_iter().for_each(|c| expr(c, f)),
    }
}
