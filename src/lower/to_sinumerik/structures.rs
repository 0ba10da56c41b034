//! FANUC structures → Siemens structures: `WHILE[c]DOm … ENDm` → `WHILE c … ENDWHILE`,
//! bare `DOm … ENDm` → `LOOP … ENDLOOP`, `IF[c]THEN stmt` → `IF c` / stmt / `ENDIF`.
//!
//! Siemens forbids labels on structure lines, so a label that landed there (a GOTO target)
//! moves to a block of its own just before; the N number and comments stay on the line.

use super::*;

fn split_label(meta: &mut BlockMeta, out: &mut Vec<Stmt>) {
    if let Some(l) = meta.label.take() {
        out.push(label_stmt(&l.name, l.span));
    }
}

/// Lowers the structures of the current program.
pub fn lower(ctx: &mut Ctx, body: Vec<Stmt>) -> Vec<Stmt> {
    let _ = ctx;
    map_bodies(body, &mut |list| {
        let mut out = Vec::with_capacity(list.len());
        for s in list {
            let span = s.span;
            match s.kind {
                StmtKind::Do(d) => {
                    let d = *d;
                    let mut head = d.head;
                    split_label(&mut head, &mut out);
                    let mut end = d.end;
                    // A label on the END line: keep it inside the body, before ENDWHILE.
                    let mut body = d.body;
                    if let Some(l) = end.label.take() {
                        body.push(label_stmt(&l.name, l.span));
                    }
                    let kind = match d.cond {
                        Some(cond) => StmtKind::While(Box::new(WhileStmt { head, cond, body, end })),
                        None => StmtKind::Loop(Box::new(LoopStmt { head, body, end })),
                    };
                    out.push(Stmt { kind, span });
                }
                StmtKind::Block(mut b) if is_if_then(&b) => {
                    let Some(Item { kind: ItemKind::IfThen { cond, then }, span: isp }) = b.items.pop() else {
                        continue;
                    };
                    split_label(&mut b.meta, &mut out);
                    let inner = plain_block(vec![*then], isp);
                    let mut st = if_stmt(cond, vec![inner], None, span);
                    if let StmtKind::If(i) = &mut st.kind {
                        i.head = b.meta;
                    }
                    out.push(st);
                }
                kind => out.push(Stmt { kind, span }),
            }
        }
        out
    })
}

fn is_if_then(b: &Block) -> bool {
    matches!(b.items.as_slice(), [Item { kind: ItemKind::IfThen { .. }, .. }])
}
