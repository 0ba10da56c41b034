//! `nctrans run --expand-cycles`: one hole (`ir::cycle::Hole`) written as the moves, dwells
//! and spindle events the control makes for it, for viewing and plotting. One function for
//! both dialects: it reads only the hole's meaning, the position the tool stands at when the
//! cycle starts, the level it ends at, the spindle, and the profile's retract amounts.

use crate::eval::machine::clean;
use crate::eval::trace::{Axes, Event, SpindleDir};
use crate::ir::cycle::{CycleKind, Hole};

/// The retract amounts a pecking cycle takes from the machine (not from the program).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Retracts {
    /// Chip breaking (FANUC G73 parameter 5114 "d"; Sinumerik CYCLE83 VARI 0 `_VRT`): how
    /// far the tool backs off after each infeed.
    pub chip_break: f64,
    /// Chip removal (FANUC G83 parameter 5115 "d"; Sinumerik CYCLE83 VARI 1 anticipation
    /// distance): how far above the last depth the rapid back into the hole stops.
    pub peck_clearance: f64,
}

/// Where the hole starts and ends and what the spindle does.
#[derive(Clone, Copy, Debug)]
pub struct Context {
    /// The trace position when the cycle starts (over the hole).
    pub start: Axes,
    /// The drilling axis (index in `trace::AXES`).
    pub axis: usize,
    /// The drilling-axis level the hole ends at (the event's `retract` resolved).
    pub end: f64,
    pub rpm: f64,
    pub spindle: SpindleDir,
    /// The control halts at the bottom (FANUC G88, Sinumerik CYCLE87/CYCLE88): a `stop`
    /// between the spindle stop and the way out.
    pub halt: bool,
}

/// The events of one hole, or `None` for the kinds whose motion the event does not hold
/// (back boring and fine boring: the shift direction and amount are machine data the
/// event leaves out); the caller then writes the `cycle` event itself.
/// The most infeeds one hole is expanded into: a tiny peck over a deep hole would otherwise
/// write millions of moves for one block.
pub const MAX_INFEEDS: f64 = 10_000.0;

/// [`expand`] refused: the hole needs more infeeds than [`MAX_INFEEDS`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TooManyInfeeds(pub f64);

pub fn expand(h: &Hole, cx: &Context, rt: &Retracts) -> Result<Option<Vec<Event>>, TooManyInfeeds> {
    if matches!(h.kind, CycleKind::BackBore | CycleKind::FineBore) {
        return Ok(None);
    }
    if let Some(q) = h.peck.filter(|_| h.kind.pecks()) {
        let n = ((h.bottom - h.r).abs() / q.abs()).ceil();
        if n.is_nan() || n > MAX_INFEEDS {
            return Err(TooManyInfeeds(n));
        }
    }
    let mut w = Writer { pos: cx.start, axis: cx.axis, out: Vec::new() };
    // Towards the bottom: -1 when drilling down the axis.
    let dir = if h.bottom < h.r { -1.0 } else { 1.0 };
    w.rapid(h.r);
    match h.kind {
        CycleKind::Peck | CycleKind::ChipBreak => {
            let q = h.peck.unwrap_or((h.bottom - h.r).abs()).abs();
            let total = (h.bottom - h.r).abs();
            let mut done = 0.0_f64;
            let mut k = 0.0;
            while done < total - 1e-9 {
                // From the count, not by adding: no drift over many infeeds.
                k += 1.0;
                let next = (k * q).min(total);
                if done > 0.0 {
                    if h.kind == CycleKind::Peck {
                        w.rapid(h.r);
                        let back = (done - rt.peck_clearance).max(0.0);
                        w.rapid(h.r + dir * back);
                    } else {
                        let back = (done - rt.chip_break).max(0.0);
                        w.rapid(h.r + dir * back);
                    }
                }
                w.feed(h.r + dir * next, h.f);
                done = next;
            }
            w.dwell(h.dwell);
            w.rapid(cx.end);
        }
        CycleKind::Drill | CycleKind::DwellDrill => {
            w.feed(h.bottom, h.f);
            w.dwell(h.dwell);
            w.rapid(cx.end);
        }
        CycleKind::Bore | CycleKind::BoreDwell => {
            w.feed(h.bottom, h.f);
            w.dwell(h.dwell);
            w.feed(h.r, h.f);
            w.rapid(cx.end);
        }
        CycleKind::Tap | CycleKind::TapLeft => {
            let (inward, out) = if h.kind == CycleKind::Tap {
                (SpindleDir::Cw, SpindleDir::Ccw)
            } else {
                (SpindleDir::Ccw, SpindleDir::Cw)
            };
            // Rigid tapping may start with the spindle stopped (the cycle turns it itself)
            // and leaves it as it found it.
            if cx.spindle != inward {
                w.out.push(Event::Spindle { rpm: cx.rpm, dir: inward });
            }
            w.feed(h.bottom, h.f);
            w.dwell(h.dwell);
            w.out.push(Event::Spindle { rpm: cx.rpm, dir: out });
            w.feed(h.r, h.f);
            w.out.push(Event::Spindle { rpm: cx.rpm, dir: cx.spindle });
            w.rapid(cx.end);
        }
        CycleKind::BoreStop => {
            w.feed(h.bottom, h.f);
            w.dwell(h.dwell);
            w.out.push(Event::Spindle { rpm: cx.rpm, dir: SpindleDir::Stop });
            if cx.halt {
                w.out.push(Event::Stop { optional: false, message: None });
            }
            w.rapid(cx.end);
            // The control starts the spindle again for the next hole.
            if cx.spindle != SpindleDir::Stop {
                w.out.push(Event::Spindle { rpm: cx.rpm, dir: cx.spindle });
            }
        }
        CycleKind::BackBore | CycleKind::FineBore => unreachable!("returned above"),
    }
    Ok(Some(w.out))
}

struct Writer {
    pos: Axes,
    axis: usize,
    out: Vec<Event>,
}

impl Writer {
    fn go(&mut self, level: f64, f: Option<f64>) {
        let level = clean(level);
        // A move that goes nowhere (the tool already at R under G99) is not a move the
        // control makes.
        if self.pos[self.axis] == Some(level) {
            return;
        }
        self.pos[self.axis] = Some(level);
        self.out.push(Event::Move { rapid: f.is_none(), to: self.pos, f, probe: false });
    }
    fn rapid(&mut self, level: f64) {
        self.go(level, None);
    }
    fn feed(&mut self, level: f64, f: f64) {
        self.go(level, Some(f));
    }
    fn dwell(&mut self, d: Option<f64>) {
        if let Some(seconds) = d.filter(|&s| s > 0.0) {
            self.out.push(Event::Dwell { seconds });
        }
    }
}

#[cfg(test)]
#[path = "expand_tests.rs"]
mod tests;
