//! What a length or feed word means in mm on this control (decimal-point rule, increment
//! rounding, unit) and where an axis word sends its axis.

use super::*;

impl Machine {
    #[inline]
    pub(super) fn inc_in_unit(&self) -> f64 {
        crate::dialect::semantics::input_increment(self.inc_mm, self.modal.inch, false)
    }

    /// A length word's value in mm: decimal-point rule, rounding to the increment, unit.
    pub(crate) fn length(&self, w: &WordVal, x: f64, rotary: bool) -> f64 {
        self.length_of(w.bare, x, rotary)
    }

    /// [`Machine::length`] of a value `x` written bare (without a decimal point) or not.
    #[inline(always)]
    pub(crate) fn length_of(&self, bare: bool, x: f64, rotary: bool) -> f64 {
        let inc = if rotary { self.inc_mm } else { self.inc_in_unit() };
        let v = if bare && self.scaling { x * inc } else { x };
        // The slot of this unit holds `inc` (unless `inc_mm` changed since `new`): no search.
        let slot = self.scales[usize::from(self.modal.inch && !rotary)];
        let v = if slot.0 == inc && inc > 0.0 {
            if slot.2 {
                round_to_decimal(v, slot.1)
            } else {
                round_to_scaled(v, inc, slot.1)
            }
        } else {
            match self.scales.iter().find(|s| s.0 == inc && inc > 0.0) {
                Some(&(_, scale, _)) => round_to_scaled(v, inc, scale),
                None => round_to(v, inc),
            }
        };
        if self.modal.inch && !rotary {
            v * 25.4
        } else {
            v
        }
    }

    /// Where axis `i` goes (machine frame) for the length `v` (mm) of its word, written
    /// in `mode`; `g53`: machine coordinates. Reads only axis `i`'s state.
    #[inline(always)]
    pub(crate) fn axis_target(&self, i: usize, v: f64, mode: AbsInc, g53: bool) -> f64 {
        self.target_from(i, v, mode, g53, self.active_offset(i))
    }

    /// [`Machine::axis_target`] with `off`, the [`Machine::active_offset`] of axis `i`.
    #[inline(always)]
    pub(super) fn target_from(&self, i: usize, v: f64, mode: AbsInc, g53: bool, off: f64) -> f64 {
        let inc = match mode {
            AbsInc::Ac => false,
            AbsInc::Ic => true,
            AbsInc::Plain => !self.modal.absolute && !g53,
        };
        if g53 {
            // G53: machine coordinates, one block; G91 is ignored (docs/semantics.md).
            v
        } else if inc && self.incr_travels_offset {
            self.pos[i] - self.applied[i] + v + off
        } else if inc {
            self.pos[i] + v
        } else {
            v + off
        }
    }

    pub(super) fn feed_value(&self, x: f64) -> f64 {
        if self.modal.inch_feed {
            x * 25.4
        } else {
            x
        }
    }
}
