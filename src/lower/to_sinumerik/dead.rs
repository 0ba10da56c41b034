//! Conditions the vacancy analysis decided (`IF[#26 EQ #0]` where #26 is set on every path
//! becomes `0`) are folded out of the output instead of written as `IF 0` / `IF 1 GOTOF L`:
//! `IF 0 … ENDIF` is dropped with its body, `IF 1 … ENDIF` is its body, `IF 0 GOTOF L` is
//! dropped and `IF 1 GOTOF L` is `GOTOF L`. A body holding a block that may be a jump target
//! (a label or an N number) and a block under block skip (`/`) are left as they are.

use super::*;
use crate::lower::meta_stmt;

fn is_const(e: &Expr) -> Option<bool> {
    literal(e).map(|v| v != 0.0)
}

fn plain(m: &BlockMeta) -> bool {
    m.label.is_none() && m.number.is_none() && m.skip.is_none()
}

/// Whether `body` has no block a jump may target.
fn no_targets(body: &[Stmt]) -> bool {
    let mut ok = true;
    crate::ir::visit::walk_stmts(body, &mut |s| {
        let metas: Vec<&BlockMeta> = match &s.kind {
            StmtKind::Block(b) => vec![&b.meta],
            StmtKind::If(i) => {
                let mut v = vec![&i.head, &i.end];
                v.extend(i.else_part.iter().map(|e| &e.head));
                v
            }
            StmtKind::While(w) => vec![&w.head, &w.end],
            StmtKind::Loop(l) => vec![&l.head, &l.end],
            StmtKind::For(f) => vec![&f.head, &f.end],
            StmtKind::Repeat(r) => vec![&r.head, &r.end],
            StmtKind::Do(d) => vec![&d.head, &d.end],
        };
        ok &= metas.iter().all(|m| m.label.is_none() && m.number.is_none());
    });
    ok
}

/// The comments of `m` kept as a comment-only block (nothing when it has none).
fn comments_of(m: BlockMeta, out: &mut Vec<Stmt>) {
    if !m.comments.is_empty() {
        out.push(meta_stmt(BlockMeta { span: m.span, comments: m.comments, ..BlockMeta::default() }, vec![]));
    }
}

pub fn fold(body: Vec<Stmt>) -> Vec<Stmt> {
    map_bodies(body, &mut |list| {
        let mut out = Vec::with_capacity(list.len());
        for s in list {
            match s.kind {
                StmtKind::If(i) if plain(&i.head) && plain(&i.end) && is_const(&i.cond).is_some() => {
                    let taken = is_const(&i.cond) == Some(true);
                    let else_body = i.else_part.as_ref().map_or(&[][..], |e| &e.body[..]);
                    let dropped = if taken { else_body } else { &i.then_body[..] };
                    if !no_targets(dropped) || i.else_part.as_ref().is_some_and(|e| !plain(&e.head)) {
                        out.push(Stmt { kind: StmtKind::If(i), span: s.span });
                        continue;
                    }
                    let i = *i;
                    comments_of(i.head, &mut out);
                    if taken {
                        out.extend(i.then_body);
                    } else if let Some(e) = i.else_part {
                        comments_of(e.head, &mut out);
                        out.extend(e.body);
                    }
                    comments_of(i.end, &mut out);
                }
                StmtKind::Block(mut b) if b.meta.skip.is_none() => {
                    let had = b.items.len();
                    b.items.retain_mut(|it| match &mut it.kind {
                        ItemKind::Goto(g) => match g.cond.as_ref().and_then(is_const) {
                            Some(true) => {
                                g.cond = None;
                                true
                            }
                            Some(false) => false,
                            None => true,
                        },
                        _ => true,
                    });
                    let empty = had > 0 && b.items.is_empty() && plain(&b.meta) && b.meta.comments.is_empty();
                    if !empty {
                        out.push(Stmt { kind: StmtKind::Block(b), span: s.span });
                    }
                }
                kind => out.push(Stmt { kind, span: s.span }),
            }
        }
        out
    })
}
