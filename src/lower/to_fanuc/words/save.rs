//! `PROC … SAVE` on FANUC: a Siemens SAVE subprogram ends in the modal G functions it was
//! called in; a FANUC macro keeps whatever it set. The translation reads each modal group
//! the subprogram sets from its `#40xx` variable on entry and selects them again, with
//! `G#t` words, before each return.

use super::effects::GROUPS;
use super::*;

/// Saves the groups in `sets` at the start of `prog` and restores them before each
/// return (and at the end, where the return is implicit).
pub(super) fn restore_on_return(ctx: &mut Ctx, prog: &mut Program, sets: u16) {
    let span = prog.span;
    let mut saves = Vec::new();
    let mut words = Vec::new();
    for &(bit, var, _) in GROUPS {
        if sets & bit == 0 {
            continue;
        }
        let t = ctx.temp(span);
        let sys = var_expr(&VarRef { kind: VarKind::Hash(var), span });
        saves.push(block_stmt(vec![assign_item(&t, sys, span)], span));
        words.push(item(
            ItemKind::Word(Word { addr: Addr::Letter(b'G'), value: WordValue::Expr(var_expr(&t)), span }),
            span,
        ));
    }
    let restore = block_stmt(words, span);
    let body = std::mem::take(&mut prog.body);
    let mut body = before_returns(body, &restore);
    let ends = body.last().is_some_and(|s| matches!(&s.kind, StmtKind::Block(b) if b.items.iter().any(ends_run)));
    if !ends {
        body.push(restore);
    }
    saves.append(&mut body);
    prog.body = saves;
}

fn ends_run(it: &Item) -> bool {
    matches!(it.kind, ItemKind::Return { .. } | ItemKind::End { .. })
}

/// `body` with `restore` run before every return: a block that returns and does more
/// first does the rest, then the restore, then returns in a block of its own.
fn before_returns(body: Vec<Stmt>, restore: &Stmt) -> Vec<Stmt> {
    let mut out = Vec::with_capacity(body.len() + 2);
    for mut s in body {
        match &mut s.kind {
            StmtKind::Block(b) if b.items.iter().any(|it| matches!(it.kind, ItemKind::Return { .. })) => {
                let (ret, rest): (Vec<Item>, Vec<Item>) =
                    std::mem::take(&mut b.items).into_iter().partition(|it| matches!(it.kind, ItemKind::Return { .. }));
                let span = s.span;
                if rest.is_empty() && b.meta.number.is_none() && b.meta.label.is_none() && b.meta.comments.is_empty() {
                    out.push(restore.clone());
                    b.items = ret;
                    out.push(s);
                } else {
                    b.items = rest;
                    out.push(s);
                    out.push(restore.clone());
                    out.push(block_stmt(ret, span));
                }
            }
            StmtKind::Block(_) => out.push(s),
            kind => {
                for body in crate::ir::visit::child_bodies_mut(kind) {
                    let b = std::mem::take(body);
                    *body = before_returns(b, restore);
                }
                out.push(s);
            }
        }
    }
    out
}
