//! Siemens `FGROUP(axes)`: which axes the path feed F refers to (the others are dragged
//! along to arrive with them), and `FGROUP()`, the default group (the geometry axes) again.
//! The axes are written as letters, `AXNAME(…)` or AXIS and STRING variables, resolved as
//! `AX[…]` resolves them; the group acts on the feed of later moves
//! (`machine::path_feed`).

use super::exec::{Flow, Interp};
use super::fault::Fault;
use super::machine::path_feed::FGROUP_AXIS;
use super::trace::axis_index;
use crate::diag::Diagnostic;
use crate::ir::{Arg, Call, ExprKind, VarKind};
use crate::span::Span;

impl Interp<'_> {
    pub(super) fn fgroup(&mut self, call: &Call, span: Span) -> Result<Flow, Fault> {
        let mut axes = 0u16;
        for a in &call.args {
            let (e, aspan) = match a {
                Arg::Value(e) => (e, e.span),
                Arg::Omitted(s) => return Err(self.fgroup_refusal("an empty FGROUP argument", *s)),
                Arg::Letter { value, .. } => (value, value.span),
            };
            // A bare letter no variable shadows is the axis itself (`FGROUP(Z)`).
            let bare = match &e.kind {
                ExprKind::Var(v) => match &v.kind {
                    VarKind::Named { name, indices } if indices.is_empty() => {
                        let cur = self.cur_sframe();
                        self.vars.frame_of(cur, name).is_none().then(|| name.to_ascii_uppercase())
                    }
                    _ => None,
                },
                _ => None,
            };
            let name = match bare {
                Some(n) => n,
                None => self.axis_name(e)?,
            };
            let i = match name.as_bytes() {
                [c] => axis_index(*c),
                _ => None,
            };
            let Some(i) = i else {
                return Err(self.fgroup_refusal(
                    &format!("FGROUP names the axis {name}, which is not one of the axes the trace knows (X Y Z A B C U V W)"),
                    aspan,
                ));
            };
            axes |= 1 << i;
        }
        self.m.fgroup.set(axes, span);
        Ok(Flow::Next)
    }

    fn fgroup_refusal(&self, what: &str, span: Span) -> Fault {
        Fault::error(
            Diagnostic::error(FGROUP_AXIS, what.to_string())
                .primary(self.file(), span, "here")
                .hint("name the axes by their letters (FGROUP(X,Y,A)), AXNAME(\"X\") or AXIS variables holding them"),
        )
    }
}
