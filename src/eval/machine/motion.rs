//! The motion of a block once its words are read: the dwell time and the move (or arc) it
//! makes, with the events they emit.

use super::*;

/// A Haas `G04 P` whose value is computed: its unit is not settled (docs/semantics.md).
pub const DWELL_HAAS_COMPUTED: &str = "NC512";
/// A FANUC `G04 P` literal with a decimal point: not settled (docs/semantics.md).
pub const DWELL_FANUC_POINT: &str = "NC513";

impl Machine {
    pub(super) fn dwell_seconds(
        &self,
        axes: &[Option<(&WordVal, f64)>; 9],
        p: Option<(&WordVal, f64)>,
        f: Option<(&WordVal, f64)>,
        s: Option<(&WordVal, f64)>,
        span: Span,
    ) -> Result<f64, Fault> {
        if self.fanuc {
            if let Some((w, x)) = axes[0] {
                // G04 X: seconds; without a decimal point in increments of the increment
                // system, not of the unit (IS-B X1000 = 1 s, IS-C 0.1 s: S28).
                let inc = crate::dialect::semantics::input_increment(self.inc_mm, self.modal.inch, true);
                let v = if w.bare && self.scaling { x * inc } else { x };
                return Ok(round_to(v, inc));
            }
            if let Some((w, x)) = p {
                return self.dwell_p(w, x);
            }
        } else {
            if let Some((_, x)) = f {
                return Ok(x);
            }
            if let Some((_, revs)) = s {
                if self.speed <= 0.0 {
                    return Err(Fault::alarm(self.alarms.no_feed, "G4 S (revolutions) with the spindle speed 0", span));
                }
                return Ok(revs * 60.0 / self.speed);
            }
        }
        Err(Fault::alarm(self.alarms.no_feed, "dwell without a time", span))
    }

    /// `G04 P`: FANUC milliseconds (an integer address: a value from a variable is rounded
    /// to whole milliseconds); a literal with a decimal point is refused, the manuals read
    /// here do not say what a FANUC makes of it. Haas (`Semantics::haas`): a literal with a
    /// decimal point is seconds, one without milliseconds (Haas mill operator's manual, G04:
    /// "if the P has no fractional part, the delay is in milliseconds"); a computed P has no
    /// written point, and the manual does not say which unit it takes, so it is refused.
    fn dwell_p(&self, w: &WordVal, x: f64) -> Result<f64, Fault> {
        let refuse = |code: &'static str, msg: &str, hint: &str| {
            Fault::error(
                crate::diag::Diagnostic::error(code, msg.to_string())
                    .primary(usize::MAX, w.span, "dwell time")
                    .hint(hint),
            )
        };
        match (self.haas, w.literal, w.bare) {
            (true, true, false) => Ok(x),
            (true, false, _) => Err(refuse(
                DWELL_HAAS_COMPUTED,
                "a Haas G04 P from a variable or expression: the unit (seconds with a decimal point, milliseconds \
                 without) is the written one's, and a computed value has none",
                "write the time as a literal (P0.5 is 0.5 s, P500 is 500 ms) or as G04 X<seconds>",
            )),
            (false, true, false) => Err(refuse(
                DWELL_FANUC_POINT,
                "a FANUC G04 P with a decimal point: P is whole milliseconds and what the control makes of a point \
                 there is not settled",
                "write the milliseconds without a point (G04 P500) or the seconds as G04 X0.5",
            )),
            _ => Ok(round_half_away(x) / 1000.0),
        }
    }

    #[allow(clippy::too_many_arguments)]
    pub(super) fn motion_block(
        &mut self,
        axes: &[Option<(&WordVal, f64)>; 9],
        ijk: &[Option<(&WordVal, f64)>; 3],
        r: Option<(&WordVal, f64)>,
        ar: Option<f64>,
        g53: bool,
        probe_n: Option<usize>,
        out: &mut Vec<(Event, Span)>,
        span: Span,
    ) -> Result<bool, Fault> {
        let probe = probe_n.is_some();
        let any_axis = axes.iter().any(Option::is_some);
        let arc_mode = matches!(self.modal.motion, Motion::Cw | Motion::Ccw) && !g53 && !probe;
        let any_ijk = ijk.iter().any(Option::is_some);
        if !any_axis && !(arc_mode && (any_ijk || ar.is_some())) {
            return Ok(false);
        }
        let mut target = self.pos;
        for (i, a) in axes.iter().enumerate() {
            let Some((w, x)) = a else { continue };
            target[i] = self.axis_target(i, self.length(w, *x, (3..6).contains(&i)), w.mode, g53);
        }
        // The probe input stops the move part way (`probe.rs`).
        let hit = if probe { self.probe_stop(&mut target, span)? } else { None };
        let rapid = self.modal.motion == Motion::Rapid && !probe;
        if !rapid && self.feed.is_none() {
            return Err(Fault::alarm(self.alarms.no_feed, "feed motion without any feed programmed", span));
        }
        for (i, a) in axes.iter().enumerate() {
            if a.is_some() {
                self.applied[i] = self.active_offset(i);
            }
        }
        if !arc_mode {
            // Only an axis of `watch` (a rotary one, or outside FGROUP) makes `f` other than F.
            let named = axes.iter().enumerate().fold(0u16, |m, (i, a)| m | (u16::from(a.is_some()) << i));
            let f = if rapid {
                None
            } else if named & self.fgroup.watch == 0 {
                self.feed
            } else {
                self.path_feed(&self.pos, &target, false, span)?
            };
            for (i, a) in axes.iter().enumerate() {
                if a.is_some() {
                    self.seen[i] = true;
                    // Axes without a word keep their position in `target` (a probe move
                    // may change every axis: copied whole below). Copying axis by axis
                    // also spares the CPU a stalled reload of `target` just written.
                    self.pos[i] = target[i];
                }
            }
            if probe {
                self.pos = target;
                let programmed = axes.map(|a| a.is_some());
                self.probe_record(hit, &programmed, probe_n);
            }
            out.push((Event::Move { rapid, to: self.trace_pos(), f, probe }, span));
            return Ok(any_axis);
        }
        let cw = self.modal.motion == Motion::Cw;
        let (u, v, _) = self.modal.plane.axes();
        let s = (self.pos[u], self.pos[v]);
        let e = (target[u], target[v]);
        let ijk_of = |axis: usize| -> Option<(&WordVal, f64)> {
            match axis {
                0 => ijk[0],
                1 => ijk[1],
                2 => ijk[2],
                _ => None,
            }
        };
        let centre_coord = |m: &Machine, axis: usize| -> Option<f64> {
            ijk_of(axis).map(|(w, x)| {
                let val = m.length(w, x, false);
                if w.mode == AbsInc::Ac {
                    val + m.active_offset(axis)
                } else {
                    m.pos[axis] + val
                }
            })
        };
        let given = arc::Given {
            radius: r.map(|(w, rv)| self.length(w, rv, false)),
            centre: any_ijk.then(|| (centre_coord(self, u).unwrap_or(s.0), centre_coord(self, v).unwrap_or(s.1))),
            angle: ar,
            end_named: axes[u].is_some() || axes[v].is_some(),
        };
        let (c, e) = arc::resolve(s, e, &given, cw).map_err(|why| Fault::alarm(self.alarms.arc, why, span))?;
        target[u] = e.0;
        target[v] = e.1;
        for (i, a) in axes.iter().enumerate() {
            if a.is_some() {
                self.seen[i] = true;
            }
        }
        self.seen[u] = true;
        self.seen[v] = true;
        self.applied[u] = self.active_offset(u);
        self.applied[v] = self.active_offset(v);
        let named = axes.iter().enumerate().fold((1u16 << u) | (1 << v), |m, (i, a)| m | (u16::from(a.is_some()) << i));
        let f =
            if named & self.fgroup.watch == 0 { self.feed } else { self.path_feed(&self.pos, &target, true, span)? };
        self.pos = target;
        out.push((
            Event::Arc {
                cw,
                plane: self.modal.plane,
                to: self.trace_pos(),
                center: [(u, clean(c.0)), (v, clean(c.1))],
                f,
            },
            span,
        ));
        Ok(true)
    }
}
