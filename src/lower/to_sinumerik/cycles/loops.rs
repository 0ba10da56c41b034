//! FANUC drilling cycles in WHILE/DO loops whose every pass ends with the cycle still active
//! (`cycles::lower_list` ends such a pass's MCALL): which loop bodies those are.

use super::*;

/// The loop bodies (by the span of their first statement) whose every pass may end with the
/// cycle still active on FANUC, with the motion mode in force before the loop: the body has
/// a cycle G code and no jump, and the loop is followed (comment lines apart) by a block that
/// cancels the cycle (G80, G00–G03, the end).
/// A pass that starts its cycle before any move is then one cycle: the Siemens pass ends its
/// MCALL, as FANUC, whose cycle stays in force over the loop's test, makes no hole before
/// the next pass's cycle block defines it again or the block after the loop cancels it.
pub(super) fn closable_bodies(ctx: &Ctx, body: &[Stmt], out: &mut BTreeMap<Span, Option<u32>>) {
    for (i, s) in body.iter().enumerate() {
        let inner = crate::ir::visit::child_bodies(&s.kind);
        for b in &inner {
            closable_bodies(ctx, b, out);
        }
        if !matches!(s.kind, StmtKind::While(_) | StmtKind::Do(_) | StmtKind::Loop(_) | StmtKind::For(_)) {
            continue;
        }
        let Some(first) = inner.first().and_then(|b| b.first()) else { continue };
        let mut cycle = false;
        let mut jumps = false;
        visit_blocks(inner[0], &mut |b| {
            cycle |= g_codes(&b.items).iter().copied().any(cycle_g);
            jumps |= b.items.iter().any(|it| matches!(it.kind, ItemKind::Goto(_) | ItemKind::IfThen { .. }));
        });
        let next = body[i + 1..].iter().find(|n| !matches!(&n.kind, StmtKind::Block(b) if b.items.is_empty()));
        let cancels = match next.map(|n| &n.kind) {
            Some(StmtKind::Block(b)) => {
                g_codes(&b.items).iter().any(|g| matches!(g, 800 | 0 | 10 | 20 | 30))
                    || b.items.iter().any(|it| matches!(it.kind, ItemKind::End { .. }))
            }
            _ => false,
        };
        if cycle && !jumps && cancels {
            let before = body[..i].iter().rev().find(|p| matches!(p.kind, StmtKind::Block(_)));
            out.insert(first.span, before.and_then(|p| ctx.modal.motion_at(p.span.lo)));
        }
    }
}

/// A structure entered with a FANUC cycle in force (`G81 … L0` before a `WHILE` that
/// computes the bolt-circle positions) whose blocks are only hole positions (X and Y words
/// alone) and macro statements (assignments, comment lines), in bodies no jump lands in:
/// on FANUC each position block drills a hole with the cycle's data, and nothing else does;
/// under the MCALL that is in force on Siemens each of them, written `G0 X… Y…` as the
/// translation writes every hole, calls the cycle at its position, and an assignment moves
/// nothing, so it calls nothing. `Some` (the structure with `G0` in its hole blocks) only
/// then; `None` otherwise (the caller refuses as before).
pub(super) fn holes_only(s: &Stmt, plane: (u8, u8)) -> Option<Stmt> {
    let is_hole = |b: &Block| {
        !b.items.is_empty()
            && b.items.iter().all(|it| {
                matches!(&it.kind, ItemKind::Word(w)
                    if (w.addr.is(plane.0) || w.addr.is(plane.1)) && matches!(w.value, WordValue::Expr(_)))
            })
    };
    let rapid = |b: &mut Block| b.items.insert(0, crate::lower::to_sinumerik::words::g_word(0, b.meta.span));
    crate::lower::hole_loops::rewritten(s, &is_hole, &rapid)
}
