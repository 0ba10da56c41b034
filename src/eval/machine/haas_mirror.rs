//! Haas programmable mirror image, `G101` on and `G100` off for the axes named (Haas VF
//! programming manual 96-8000 p. 201: mirroring "will reflect programmed motion around your
//! work coordinate zero point"; one axis of the plane mirrored reverses G02/G03 and G41/G42).
//! It is FANUC's `G51.1` about zero, and runs as that: the axis words must be 0 (what another
//! value does is not on the page), and under a G52 shift it is refused, as the page does not
//! say whether "work coordinate zero" is the shifted one (docs/semantics.md, Haas mirror).

use super::frames::error;
use super::{Fault, Machine, Span, WordVal};

impl Machine {
    /// `G101` (`on`) or `G100` with the axis words `axes` (X, Y, Z; the values as read).
    pub(super) fn haas_mirror(
        &mut self,
        on: bool,
        axes: &[Option<(&WordVal, f64)>; 9],
        span: Span,
    ) -> Result<(), Fault> {
        let g = if on { "G101" } else { "G100" };
        if axes.iter().skip(3).any(Option::is_some) || axes.iter().all(Option::is_none) {
            return Err(error(
                "NC490",
                format!("{g} names no geometry axis X, Y, Z"),
                span,
                "name the axes to mirror about the work zero: `G101 X0.`; cancel them with `G100 X0.`",
            ));
        }
        if on {
            if let Some((w, x)) = axes.iter().flatten().find(|(_, x)| *x != 0.0) {
                return Err(error(
                    "NC490",
                    format!("{g} {}{x} (an axis value other than 0)", w.addr),
                    w.span,
                    "the Haas manual mirrors about the work coordinate zero and gives no meaning to another value: \
                     write the axis with 0 (`G101 X0.`) and shift the zero with G52 or a work offset",
                ));
            }
            if self.local.iter().take(3).any(|v| *v != 0.0) {
                return Err(error(
                    "NC491",
                    format!("{g} under a G52 shift is not modelled"),
                    span,
                    "the Haas manual mirrors about \"your work coordinate zero point\", which it does not relate to \
                     G52: cancel the shift (G52 X0 Y0 Z0) before G101, or move the zero with a work offset",
                ));
            }
        }
        self.check_fanuc_frames(if on { 511 } else { 501 }, span)?;
        self.g51_1(on, axes, span)
    }
}
