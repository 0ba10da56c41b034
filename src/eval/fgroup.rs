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
            let name = self.named_axis(e)?;
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

    /// `FGREF[A]=r`: the reference radius of rotary axis A in the feed group (K2: the
    /// degrees of a rotary axis in FGROUP count as the arc at that radius; the default is
    /// 360/2π mm, 1 degree as 1 mm; the radius in the length unit in force, P-FB). A linear
    /// axis, or a radius not above 0, is refused.
    pub(super) fn fgref(&mut self, index: &crate::ir::Expr, value: f64, span: Span) -> Result<(), Fault> {
        let name = self.named_axis(index)?;
        let slot = match name.as_str() {
            "A" => 0,
            "B" => 1,
            "C" => 2,
            _ => {
                return Err(self.fgroup_refusal(
                    &format!("FGREF[{name}]: a reference radius belongs to a rotary axis (A, B, C)"),
                    index.span,
                ))
            }
        };
        if !(value > 0.0 && value.is_finite()) {
            return Err(
                self.fgroup_refusal(&format!("FGREF[{name}]={value}: the reference radius must be above 0"), span)
            );
        }
        // The radius is a length in the unit in force (G70/G700: inch; P-FB).
        let mm = if self.m.modal.inch { value * 25.4 } else { value };
        self.m.fgroup.fgref[slot] = Some(mm);
        Ok(())
    }

    /// The axis an FGROUP argument or FGREF index names: a bare letter no variable shadows is
    /// the axis itself (`FGROUP(Z)`, `FGREF[A]`), anything else is resolved as `AX[…]` is.
    fn named_axis(&mut self, e: &crate::ir::Expr) -> Result<String, Fault> {
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
        match bare {
            Some(n) => Ok(n),
            None => self.axis_name(e),
        }
    }

    fn fgroup_refusal(&self, what: &str, span: Span) -> Fault {
        Fault::error(
            Diagnostic::error(FGROUP_AXIS, what.to_string())
                .primary(self.file(), span, "here")
                .hint("name the axes by their letters (FGROUP(X,Y,A)), AXNAME(\"X\") or AXIS variables holding them"),
        )
    }
}
