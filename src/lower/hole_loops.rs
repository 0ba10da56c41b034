//! What both drilling-cycle translations share for a structure entered with a cycle in force
//! (the macro bolt circle): whether the structure holds only hole positions and macro
//! statements, and its copy with each hole block rewritten for the target (`G0` added for
//! Sinumerik's MCALL, the `G0` taken off for FANUC's cycle). Each direction says what a hole
//! block is in its own dialect.

use crate::ir::*;

/// `s` (a structure, not a block) with every hole block rewritten by `hole`, where each of
/// its blocks, at any depth, is either assignments only or a hole block (`is_hole`), and
/// none has a label, a number or a skip; `None` otherwise.
pub fn rewritten(s: &Stmt, is_hole: &dyn Fn(&Block) -> bool, hole: &dyn Fn(&mut Block)) -> Option<Stmt> {
    fn fits(body: &[Stmt], is_hole: &dyn Fn(&Block) -> bool) -> bool {
        body.iter().all(|s| match &s.kind {
            StmtKind::Block(b) => {
                let assigns = b.items.iter().all(|it| matches!(it.kind, ItemKind::Assign { .. }));
                b.meta.label.is_none() && b.meta.number.is_none() && b.meta.skip.is_none() && (assigns || is_hole(b))
            }
            k => crate::ir::visit::child_bodies(k).into_iter().all(|c| fits(c, is_hole)),
        })
    }
    fn apply(body: &mut Vec<Stmt>, is_hole: &dyn Fn(&Block) -> bool, hole: &dyn Fn(&mut Block)) {
        for s in body {
            match &mut s.kind {
                StmtKind::Block(b) => {
                    if is_hole(b) {
                        hole(b);
                    }
                }
                k => crate::ir::visit::child_bodies_mut(k).into_iter().for_each(|c| apply(c, is_hole, hole)),
            }
        }
    }
    if matches!(s.kind, StmtKind::Block(_)) || !fits(std::slice::from_ref(s), is_hole) {
        return None;
    }
    let mut v = vec![s.clone()];
    apply(&mut v, is_hole, hole);
    v.pop()
}
