//! The trace feed `f` of a feed move that a rotary axis, or an axis outside the Siemens
//! feed group (`FGROUP`), takes part in: one canonical meaning for both controls, the speed
//! along the path of every axis that moves with degrees counted as millimetres
//! (docs/semantics.md, "Feed of moves with rotary axes and FGROUP").
//!
//! FANUC moves a linear and a rotary axis together with F along exactly that path (metric
//! input), so there `f` is F. Siemens F is the path feed of the group's axes only (the
//! geometry axes until `FGROUP(…)` names others); the other axes are dragged along to
//! arrive together, so the move takes `L_group / F` and `f = F · L_all / L_group`. A move
//! whose feed no stored source settles is refused, never given a near value. Moves of the
//! group's axes only (every linear move under the default group) never get here: the
//! caller asks only when an axis of [`Group::watch`] moves.

use super::Machine;
use crate::eval::fault::Fault;
use crate::eval::trace::AXES;
use crate::span::Span;

/// A feed move whose feed the evaluator does not model (a rotary axis under G95, inch feeds,
/// on a Haas, in an arc; a Siemens move none of whose FGROUP axes moves).
pub const FEED_NOT_MODELLED: &str = "NC662";
/// An `FGROUP(…)` argument that is not one of the axes the trace knows.
pub const FGROUP_AXIS: &str = "NC663";

/// A, B, C.
pub const ROTARY: u16 = 0b111 << 3;
/// The Siemens geometry axes X, Y, Z: the feed group until `FGROUP(…)` names another.
pub const GEOMETRY: u16 = 0b111;
const ALL: u16 = (1 << 9) - 1;

/// The Siemens feed group and the axes whose motion makes a move's feed worth working out.
#[derive(Clone, Copy, Debug)]
pub struct Group {
    /// The axes F refers to (bits as [`AXES`]); Siemens only.
    pub axes: u16,
    /// Where the group in force was set (`None`: the default group).
    pub set_at: Option<Span>,
    /// Axes whose motion needs [`Machine::path_feed`]: the rotary ones, and on Siemens every
    /// axis outside the group. A move of none of them has `f` = F.
    pub watch: u16,
    /// The feed in force was programmed under inch feeds (`Modal::inch_feed`).
    pub feed_inch: bool,
    /// `FGREF[A]=r` (A, B, C): the reference radius that turns the rotary axis's degrees into
    /// the millimetres of the group's path (`None`: the default, 1 degree counts as 1 mm,
    /// a radius of 360/2π mm).
    pub fgref: [Option<f64>; 3],
}

impl Group {
    pub fn new(fanuc: bool) -> Group {
        let mut g = Group { axes: GEOMETRY, set_at: None, watch: 0, feed_inch: false, fgref: [None; 3] };
        g.refresh(fanuc);
        g
    }

    fn refresh(&mut self, fanuc: bool) {
        self.watch = if fanuc { ROTARY } else { ROTARY | (ALL & !self.axes) };
    }

    /// `FGROUP(…)` with these axes (`0`: `FGROUP()`, the default group again).
    pub fn set(&mut self, axes: u16, span: Span) {
        (self.axes, self.set_at) = if axes == 0 { (GEOMETRY, None) } else { (axes, Some(span)) };
        self.refresh(false);
    }
}

/// The axis letters of a bit set, comma separated (`X, A`).
pub fn names(bits: u16) -> String {
    let v: Vec<String> = (0..9).filter(|i| bits & (1 << i) != 0).map(|i| AXES[i].to_string()).collect();
    v.join(", ")
}

fn length(d: &[f64; 9], bits: u16) -> f64 {
    (0..9).filter(|i| bits & (1 << i) != 0).map(|i| d[i] * d[i]).sum::<f64>().sqrt()
}

/// The Siemens path length of the group's axes `bits`: a rotary axis with a reference radius
/// (`FGREF`) travels its arc at that radius, `degrees · π · r / 180` mm.
fn group_length(d: &[f64; 9], bits: u16, fgref: &[Option<f64>; 3]) -> f64 {
    (0..9)
        .filter(|i| bits & (1 << i) != 0)
        .map(|i| match (3..6).contains(&i).then(|| fgref[i - 3]).flatten() {
            Some(r) => d[i] * r * std::f64::consts::PI / 180.0,
            None => d[i],
        })
        .map(|x| x * x)
        .sum::<f64>()
        .sqrt()
}

impl Machine {
    /// The canonical `f` of a feed move from `from` to `to` (machine positions, mm and
    /// degrees); `arc`: a G2/G3. The feed is known to be set (the caller's alarm).
    #[inline]
    pub(super) fn path_feed(
        &self,
        from: &[f64; 9],
        to: &[f64; 9],
        arc: bool,
        span: Span,
    ) -> Result<Option<f64>, Fault> {
        let mut moved = 0u16;
        let mut d = [0.0; 9];
        for i in 0..9 {
            d[i] = to[i] - from[i];
            if d[i].abs() > 1e-9 {
                moved |= 1 << i;
            }
        }
        if moved & self.fgroup.watch == 0 {
            return Ok(self.feed);
        }
        self.path_feed_of(&d, moved, arc, span).map(Some)
    }

    fn path_feed_of(&self, d: &[f64; 9], moved: u16, arc: bool, span: Span) -> Result<f64, Fault> {
        let mut f = self.feed.unwrap_or(0.0);
        let which = names(moved);
        if moved & ROTARY != 0 {
            let rotary_only = moved & !ROTARY == 0;
            let why = if self.haas {
                Some("on a Haas the feed of a move with a rotary axis depends on the rotary axis diameter settings (Setting 34, 79), which no program states")
            } else if self.modal.per_rev {
                Some("under feed per revolution (G95) no stored source gives the feed of a move with a rotary axis")
            } else if rotary_only && self.fgroup.feed_inch != self.modal.inch_feed {
                Some("the feed in force was programmed in the other unit system: whether a rotary axis then reads it as degrees/min of the number or of the speed is not settled")
            } else if self.modal.inch_feed && self.fanuc && !rotary_only {
                Some("under G20 no stored source gives the feed of a linear and a rotary axis moving together (the FANUC rule read here is for metric input)")
            } else if arc {
                Some("the feed of an arc with a rotary axis moving (helical interpolation B) depends on a parameter of the control")
            } else {
                None
            };
            if let Some(why) = why {
                return Err(refuse(&which, why, span));
            }
            if rotary_only && self.modal.inch_feed {
                // F of rotary axes alone is degrees/min in either unit system (F-ROT,
                // P-FB's G700 example); the feed in force is held in mm/min.
                f /= 25.4;
            }
        }
        if self.fanuc {
            // F along the path of every axis, degrees as millimetres (F-ROT).
            return Ok(f);
        }
        let group = self.fgroup.axes;
        let outside = moved & !group;
        if arc {
            if outside != 0 {
                return Err(refuse(
                    &which,
                    &format!("the arc moves {} outside the feed group ({}): how the control shares the feed then is not modelled", names(outside), names(group)),
                    span,
                ));
            }
            return Ok(f);
        }
        let l_group = group_length(d, moved & group, &self.fgroup.fgref);
        if l_group > 0.0 {
            return Ok(f * length(d, moved) / l_group);
        }
        // None of the group's axes moves: a rotary axis alone has F in degrees/min (V1),
        // unless it has a reference radius, which P-FB applies to rotary axes alone too but
        // reads inside FGROUP only.
        if moved & !ROTARY == 0 && moved.count_ones() == 1 {
            let has_radius = (3..6).any(|i| moved & (1 << i) != 0 && self.fgroup.fgref[i - 3].is_some());
            if has_radius {
                return Err(refuse(
                    &which,
                    "it has a reference radius (FGREF) but is not in the feed group: no stored source says whether F is then degrees/min or mm/min at the radius",
                    span,
                ));
            }
            return Ok(f);
        }
        Err(refuse(
            &which,
            &format!(
                "none of the feed group's axes ({}) moves, and no stored source gives the feed then",
                names(group)
            ),
            span,
        ))
    }
}

fn refuse(which: &str, why: &str, span: Span) -> Fault {
    Fault::Error(Box::new(
        crate::diag::Diagnostic::error(FEED_NOT_MODELLED, format!("the feed of this move of {which} is not modelled"))
            .primary(usize::MAX, span, "feed move")
            .note(why.to_string())
            .hint("name every axis that moves in FGROUP (Siemens), or move the axes the feed is not known for in blocks of their own"),
    ))
}
