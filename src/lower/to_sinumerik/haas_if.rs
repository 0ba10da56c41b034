//! The Haas `IF [c] <NC words>` block (ItemKind::IfBlock), before anything else is planned:
//! it becomes `IF [NOT c] GOTO n` / the words / `Nn`, with n a sequence number the program
//! does not use, so the vacancy, variable and call passes see only FANUC's own forms. A
//! skipped (`/`) Haas IF block is refused: skipping the jump alone would run the words.

use super::{map_bodies, Ctx};
use crate::ir::*;

/// The program with every Haas IF block split, or `None` when it has none.
pub fn split(p: &Program) -> Option<Program> {
    let mut any = false;
    let mut used = std::collections::BTreeSet::new();
    crate::ir::visit::walk_stmts(&p.body, &mut |s| match &s.kind {
        StmtKind::Block(b) => {
            any |= b.meta.skip.is_none() && b.items.iter().any(|i| matches!(i.kind, ItemKind::IfBlock { .. }));
            used.extend(b.meta.number.as_ref().map(|n| n.value));
        }
        StmtKind::Do(d) => {
            used.extend(d.head.number.as_ref().map(|n| n.value));
            used.extend(d.end.number.as_ref().map(|n| n.value));
        }
        _ => {}
    });
    if !any {
        return None;
    }
    let mut free = (1..=99_999u32).rev().filter(|n| !used.contains(n)).collect::<Vec<_>>().into_iter();
    let mut p = p.clone();
    p.body = map_bodies(std::mem::take(&mut p.body), &mut |list| {
        let mut out = Vec::with_capacity(list.len());
        for st in list {
            let StmtKind::Block(b) = &st.kind else {
                out.push(st);
                continue;
            };
            let splits =
                b.meta.skip.is_none() && matches!(b.items.as_slice(), [Item { kind: ItemKind::IfBlock { .. }, .. }]);
            let Some(n) = splits.then(|| free.next()).flatten() else {
                out.push(st);
                continue;
            };
            let StmtKind::Block(mut b) = st.kind else { continue };
            let Some(Item { kind: ItemKind::IfBlock { cond, items }, span }) = b.items.pop() else { continue };
            let cs = cond.span;
            let skip = Expr::new(ExprKind::Unary(UnOp::Not, Box::new(cond)), cs);
            // `Forward` (the target is the next block but one, and its number is unused
            // elsewhere, so FANUC's search finds the same block) marks the jump as ours.
            let goto = Goto {
                search: Search::Forward,
                target: Target::Number(SeqNo { value: n, span: cs }),
                cond: Some(skip),
                missing_continues: false,
            };
            b.items = vec![Item { kind: ItemKind::Goto(Box::new(goto)), span: cs }];
            out.push(Stmt { kind: StmtKind::Block(b), span: st.span });
            let meta = BlockMeta { span, ..BlockMeta::default() };
            out.push(Stmt { kind: StmtKind::Block(Block { meta, items }), span });
            let end = BlockMeta { span, number: Some(SeqNo { value: n, span }), ..BlockMeta::default() };
            out.push(Stmt { kind: StmtKind::Block(Block { meta: end, items: Vec::new() }), span });
        }
        out
    });
    Some(p)
}

/// What [`split`] leaves: a Haas IF block with block skip.
pub fn refuse(ctx: &mut Ctx, body: Vec<Stmt>) -> Vec<Stmt> {
    map_bodies(body, &mut |list| {
        let mut out = Vec::with_capacity(list.len());
        for st in list {
            if let StmtKind::Block(b) = &st.kind {
                if let Some(it) = b.items.iter().find(|i| matches!(i.kind, ItemKind::IfBlock { .. })) {
                    let span = it.span;
                    out.extend(ctx.unsupported(
                        "NC633",
                        span,
                        "a skippable (`/`) Haas `IF [cond]` block with NC words",
                        "split it by hand: `/IF [NOT cond] GOTO n` cannot express it; write `IF [cond] GOTO n` blocks",
                    ));
                    continue;
                }
            }
            out.push(st);
        }
        out
    })
}

/// After the vacancy rewrite: each split Haas IF block still in its three-block form (`IF
/// [NOT c] GOTO n`, the words, an empty `Nn` no other jump targets) becomes `IF c … ENDIF`,
/// as a programmer writes it. Only [`split`] makes a FANUC jump with `Search::Forward`.
pub fn restructure(body: Vec<Stmt>) -> Vec<Stmt> {
    let mut targets: Vec<u32> = Vec::new();
    crate::ir::visit::walk_stmts(&body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            for it in &b.items {
                if let ItemKind::Goto(g) = &it.kind {
                    if let Target::Number(n) = &g.target {
                        targets.push(n.value);
                    }
                }
            }
        }
    });
    map_bodies(body, &mut |list| {
        let mut out: Vec<Stmt> = Vec::with_capacity(list.len());
        let mut it = list.into_iter().peekable();
        while let Some(st) = it.next() {
            let Some((n, _)) = split_jump(&st).filter(|(n, _)| targets.iter().filter(|t| *t == n).count() == 1) else {
                out.push(st);
                continue;
            };
            let (Some(words), Some(end)) = (it.next(), it.peek()) else {
                out.push(st);
                continue;
            };
            if !is_split_end(end, n) || !matches!(&words.kind, StmtKind::Block(b) if b.meta.number.is_none()) {
                out.push(st);
                out.push(words);
                continue;
            }
            it.next();
            let StmtKind::Block(b) = st.kind else { continue };
            let Some(Item { kind: ItemKind::Goto(g), .. }) = b.items.into_iter().next() else { continue };
            let Some(Expr { kind: ExprKind::Unary(UnOp::Not, c), .. }) = g.cond else { continue };
            let span = st.span.to(words.span);
            let mut s = super::if_stmt(*c, vec![words], None, span);
            if let StmtKind::If(i) = &mut s.kind {
                // The N number and comments of the Haas block stay on the IF line.
                i.head = BlockMeta { span: b.meta.span, ..b.meta };
            }
            out.push(s);
        }
        out
    })
}

fn split_jump(st: &Stmt) -> Option<(u32, ())> {
    let StmtKind::Block(b) = &st.kind else { return None };
    let [Item { kind: ItemKind::Goto(g), .. }] = b.items.as_slice() else { return None };
    match (&g.cond, &g.target, b.meta.skip) {
        (Some(Expr { kind: ExprKind::Unary(UnOp::Not, _), .. }), Target::Number(n), None)
            if g.search == Search::Forward =>
        {
            Some((n.value, ()))
        }
        _ => None,
    }
}

fn is_split_end(st: &Stmt, n: u32) -> bool {
    matches!(&st.kind, StmtKind::Block(b) if b.items.is_empty() && b.meta.label.is_none()
        && b.meta.comments.is_empty() && b.meta.number.as_ref().is_some_and(|x| x.value == n))
}
