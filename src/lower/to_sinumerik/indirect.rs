//! Indirect variables `#[expr]` whose number is known at translation time.
//!
//! Siemens can index R parameters (`R[…]`) but not DEF variables, and FANUC's numbering has
//! no single linear image on the Siemens side. So before anything else, a constant
//! propagation over each program's control-flow graph (the same graph as the vacancy
//! analysis: FANUC GOTO search order, loops, calls killing what the callee may write) finds
//! the indices that have one value on every path — `#1=100 … #[#1+1]=7.` is `#101=7.` —
//! and rewrites them to plain variables (FANUC rounds the computed number). Indices that
//! stay unknown are left for `exprs`, which reports them as unsupported (NC361). A G code
//! taken from a variable (`G#4`) is folded the same way, and so is a computed program number
//! (`#1=9010 … M98 P#1`, `G65 P#1`): with one value on every path it is the call of that
//! program, which every later pass (roles, parameters, names) sees as written so; one that
//! stays unknown is refused by `calls` (NC356).

use super::vacancy::flatten;
use super::*;

type Env = BTreeMap<u32, f64>;

fn eval(e: &Expr, env: &Env) -> Option<f64> {
    let v = match &e.kind {
        ExprKind::Num(n) => n.value,
        ExprKind::Var(v) => match &v.kind {
            VarKind::Hash(n) => *env.get(n)?,
            VarKind::HashIndirect(x) => *env.get(&index(x, env)?)?,
            _ => return None,
        },
        ExprKind::Unary(UnOp::Neg, a) => -eval(a, env)?,
        ExprKind::Binary(op, a, b) => {
            let (x, y) = (eval(a, env)?, eval(b, env)?);
            match op {
                BinOp::Add => x + y,
                BinOp::Sub => x - y,
                BinOp::Mul => x * y,
                BinOp::Div if y != 0.0 => x / y,
                _ => return None,
            }
        }
        _ => return None,
    };
    v.is_finite().then_some(v)
}

/// The variable number an index expression selects (FANUC rounds it).
fn index(x: &Expr, env: &Env) -> Option<u32> {
    let v = eval(x, env)?.round();
    (0.0..=99_999.0).contains(&v).then_some(v as u32)
}

fn kill_call(c: &Call, env: &mut Env) {
    match c.kind {
        // A macro has its own locals; it can only change commons.
        CallKind::G65 | CallKind::G66 => env.retain(|n, _| *n <= 33),
        _ => env.clear(),
    }
}

fn transfer(it: &Item, env: &mut Env) {
    match &it.kind {
        ItemKind::Assign { target, value } => {
            let n = match &target.kind {
                VarKind::Hash(n) => Some(*n),
                VarKind::HashIndirect(x) => index(x, env),
                _ => return,
            };
            match (n, eval(value, env)) {
                (Some(n), Some(v)) => {
                    env.insert(n, v);
                }
                (Some(n), None) => {
                    env.remove(&n);
                }
                (None, _) => env.clear(),
            }
        }
        ItemKind::IfThen { then, .. } => {
            let mut after = env.clone();
            transfer(then, &mut after);
            env.retain(|k, v| after.get(k) == Some(v));
        }
        ItemKind::Call(c) => kill_call(c, env),
        _ => {}
    }
}

fn meet(a: &Env, b: &Env) -> Env {
    a.iter().filter(|(k, v)| b.get(k) == Some(v)).map(|(k, v)| (*k, *v)).collect()
}

/// Whether the program has an indirect variable or a G code from a variable.
fn has_indirect(body: &[Stmt]) -> bool {
    fn expr(e: &Expr) -> bool {
        matches!(&e.kind, ExprKind::Var(v) if matches!(v.kind, VarKind::HashIndirect(_)))
            || e.children().into_iter().any(expr)
    }
    let mut found = false;
    crate::ir::visit::walk_stmts(body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            for it in block_items(b) {
                if let ItemKind::Assign { target, .. } = &it.kind {
                    found |= matches!(target.kind, VarKind::HashIndirect(_));
                }
                if let ItemKind::Word(Word { addr, value: WordValue::Expr(e), .. }) = &it.kind {
                    found |= addr.is(b'G') && literal(e).is_none();
                }
                found |= matches!(&it.kind, ItemKind::Call(c) if matches!(c.target, CallTarget::Computed(_)));
                found |= crate::ir::visit::item_exprs(it).into_iter().any(expr);
            }
        }
    });
    found
}

/// Resolves the indirect variables of a program whose index is a known constant; `None`
/// when the program has none (the common case: no copy is made).
pub fn resolve(p: &Program) -> Option<Program> {
    if !has_indirect(&p.body) {
        return None;
    }
    let mut p = p.clone();
    let ins: Vec<Env> = {
        let flat = flatten(&p.body);
        let (ins, settled) = super::forward::run(&flat, Env::new(), transfer, meet);
        if !settled {
            return Some(p);
        }
        ins.into_iter().map(Option::unwrap_or_default).collect()
    };
    let mut counter = 0usize;
    rewrite(&mut p.body, &ins, &mut counter);
    Some(p)
}

fn rewrite(body: &mut [Stmt], ins: &[Env], counter: &mut usize) {
    for s in body.iter_mut() {
        match &mut s.kind {
            StmtKind::Block(b) => {
                let mut env = ins.get(*counter).cloned().unwrap_or_default();
                *counter += 1;
                for it in &mut b.items {
                    fix_item(it, &env);
                    transfer(it, &mut env);
                }
            }
            StmtKind::Do(d) => {
                let env = ins.get(*counter).cloned().unwrap_or_default();
                *counter += 1;
                if let Some(c) = &mut d.cond {
                    fix_expr(c, &env);
                }
                rewrite(&mut d.body, ins, counter);
                *counter += 1;
            }
            other => {
                // (DO has its own arm above.)
                for b in crate::ir::visit::child_bodies_mut(other) {
                    rewrite(b, ins, counter);
                }
            }
        }
    }
}

fn fix_var(v: &mut VarRef, env: &Env) {
    if let VarKind::HashIndirect(x) = &mut v.kind {
        fix_expr(x, env);
        if let Some(n) = index(x, env) {
            v.kind = VarKind::Hash(n);
        }
    }
}

fn fix_expr(e: &mut Expr, env: &Env) {
    if let ExprKind::Var(v) = &mut e.kind {
        fix_var(v, env);
        return;
    }
    for c in super::vacancy::children_mut(e) {
        fix_expr(c, env);
    }
}

fn fix_item(it: &mut Item, env: &Env) {
    if let ItemKind::Assign { target, .. } = &mut it.kind {
        fix_var(target, env);
    }
    if let ItemKind::IfThen { then, cond } = &mut it.kind {
        fix_expr(cond, env);
        fix_item(then, env);
        return;
    }
    item_exprs_mut(it, &mut |e| fix_expr(e, env));
    // `M98 P#1` with a known #1: the call of that program (FANUC rounds the number).
    if let ItemKind::Call(c) = &mut it.kind {
        if let CallTarget::Computed(e) = &c.target {
            if let Some(v) = eval(e, env).map(crate::eval::value::round_half_away) {
                if (1.0..=99_999_999.0).contains(&v) {
                    c.target = CallTarget::Number(v as u32);
                }
            }
        }
    }
    // `G#1` with a known #1: Siemens cannot take a G code from a variable.
    if let ItemKind::Word(Word { addr, value: WordValue::Expr(e), .. }) = &mut it.kind {
        if addr.is(b'G') && literal(e).is_none() {
            if let Some(v) = eval(e, env) {
                *e = Expr::num(v, true, e.span);
            }
        }
    }
}
