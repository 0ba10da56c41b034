//! The Haas `IF [c] <NC words>` block (ItemKind::IfBlock): refused for Sinumerik until the
//! passes that look inside items (vacancy, variable map, calls) also look inside it; a
//! translation that skipped them could change which variables are vacant.

use super::{map_bodies, Ctx};
use crate::ir::*;

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
                        "Haas `IF [cond]` followed by NC words (no GOTO or THEN)",
                        "split it by hand: `IF [NOT cond] GOTO n` before the block and `Nn` after it",
                    ));
                    continue;
                }
            }
            out.push(st);
        }
        out
    })
}
