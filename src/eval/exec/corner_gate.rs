//! The rule a held corner puts on what runs next (`machine::corners`): only the next
//! block of NC words at the same call level may follow.

use super::{Interp, Op};
use crate::diag::Diagnostic;
use crate::eval::Fault;
use crate::ir::{Block, ItemKind};

impl Interp<'_> {
    /// With a corner held (`machine::corners`), the next thing run must be a block of NC
    /// words at the same call level: the manuals read say the block after a corner is its
    /// next move, and nothing about macro statements or calls between (docs/semantics.md).
    pub(super) fn corner_gate(&self, op: Option<&Op>) -> Result<(), Fault> {
        let Some(corner) = self.m.corners.held_span() else { return Ok(()) };
        let words_only = |b: &Block| b.items.iter().all(|i| matches!(i.kind, ItemKind::Word(_)));
        let (why, at) = match op {
            None => ("the end of the program", None),
            Some(op) if self.frames.len() != self.corner_depth => ("a call or a return", Some(op.span())),
            Some(Op::Lit(_)) => return Ok(()),
            Some(Op::Block(b)) if words_only(b) => return Ok(()),
            Some(op @ Op::Block(_)) => ("a block with a macro statement, a call or an end", Some(op.span())),
            Some(op) => ("a macro or control statement", Some(op.span())),
        };
        let mut d = Diagnostic::error(
            crate::eval::corner::NO_NEXT_MOVE,
            format!("the corner needs the next block to be its next move in the plane; what follows is {why}"),
        )
        .primary(self.file(), corner, "corner");
        if let Some(at) = at {
            d = d.secondary(self.file(), at, "runs next");
        }
        Err(Fault::error(d.hint("put the next move of the contour right after the block with the corner")))
    }
}
