//! FANUC drilling cycles (G73, G74, G76, G81–G89) in the machine: the block that selects
//! or cancels a cycle, and the holes a block drills in the cycle mode. The rules and their
//! sources are in docs/semantics.md ("Drilling cycles").

use super::Level;
use crate::diag::Diagnostic;
use crate::dialect::fanuc::cycles::{cycle_of, is_manual_retract, takes_dwell};
use crate::eval::fault::Fault;
use crate::eval::machine::{clean, Machine, Warn, WordVal, WV};
use crate::eval::trace::{axis_index, Event, SpindleDir};
use crate::eval::value::round_half_away;
use crate::ir::cycle::{CycleKind, Hole, Retract, Tapping};
use crate::span::Span;

/// FANUC alarm PS0045 "ADDRESS Q NOT FOUND (G73/G83)": a peck cycle without Q, or Q0.
pub const NO_Q: i64 = 45;
/// The warning beside alarm 45: what was missing and what to write.
pub const NO_Q_NOTE: &str = "NC524";
/// A bottom not below the R plane (outside G87): refused, the control's reaction is not
/// established by a source (docs/semantics.md, "Drilling cycles").
pub const BOTTOM_CODE: &str = "NC522";

/// The warning on rigid tapping from a turning spindle (docs/semantics.md, "Drilling
/// cycles", rigid tapping).
pub const RIGID_TURNING: &str = "NC592";

/// The largest repeat count K (L) the control takes (four digits).
const MAX_REPEATS: f64 = 9999.0;

/// Whether `gi` (a G code ×10) selects a drilling cycle.
pub fn is_cycle_g(gi: i64) -> bool {
    cycle_of(gi).is_some()
}

/// The cycle codes of one block, before its motion: a group-01 code (G00–G03) cancels
/// the cycle, a cycle code selects one (the initial level is where the drilling axis
/// stands when the cycle mode begins).
pub fn select(m: &mut Machine, cycle_g: Option<(i64, Span)>, motion_g: Option<Span>) -> Result<(), Fault> {
    if let (Some((gi, span)), Some(_)) = (cycle_g, motion_g) {
        return Err(refuse(
            "NC416",
            format!("G{} and a G00–G03 motion code in one block", gi / 10),
            span,
            "the motion code cancels the cycle; write them in separate blocks",
        ));
    }
    if motion_g.is_some() {
        m.cycle.cancel();
        m.set_group_g(9, 800);
    }
    if let Some((gi, _)) = cycle_g {
        let Some(kind) = cycle_of(gi) else { return Ok(()) };
        if m.cycle.active.is_none() {
            m.cycle.initial = m.pos[m.modal.plane.axes().2];
        }
        m.cycle.active = Some((kind, gi));
        m.set_group_g(9, gi);
    }
    Ok(())
}

/// The words of a block in the cycle mode that the cycle reads.
#[derive(Default)]
struct CycleWords<'a> {
    plane: [Option<(&'a WordVal, f64)>; 2],
    depth: Option<(&'a WordVal, f64)>,
    r: Option<(&'a WordVal, f64)>,
    q: Option<(&'a WordVal, f64)>,
    p: Option<f64>,
    count: Option<(f64, Span)>,
}

/// Runs a block in the cycle mode: stores its cycle data (R, Z, Q, P stay until G80 or
/// G00–G03) and, when it has an axis word or R, drills its hole K times (`true`). A block
/// without them (an F, an M) drills nothing.
pub fn holes(
    m: &mut Machine,
    words: &[WordVal],
    out: &mut Vec<(Event, Span)>,
    warns: &mut Vec<Warn>,
    span: Span,
) -> Result<bool, Fault> {
    let Some((kind, gi)) = m.cycle.active else { return Ok(false) };
    let (u, v, n) = m.modal.plane.axes();
    let mut cw = CycleWords::default();
    for w in words {
        let WV::Num(x) = w.val else { continue };
        let a: &str = &w.addr;
        match (a, a.as_bytes()) {
            ("R", _) => cw.r = Some((w, x)),
            ("Q", _) => cw.q = Some((w, x)),
            ("P", _) => cw.p = Some(x),
            // K is the repeat count (the 0i/30i spelling), L the older one.
            ("K", _) => cw.count = Some((x, w.span)),
            ("L", _) if cw.count.is_none() => cw.count = Some((x, w.span)),
            (_, &[c]) => match axis_index(c) {
                Some(i) if i == u => cw.plane[0] = Some((w, x)),
                Some(i) if i == v => cw.plane[1] = Some((w, x)),
                Some(i) if i == n => cw.depth = Some((w, x)),
                Some(_) => {
                    return Err(refuse(
                        "NC417",
                        format!("axis {a} in a drilling cycle block is not modelled"),
                        w.span,
                        "position the other axes before the cycle, or cancel it with G80 first",
                    ))
                }
                None => {}
            },
            _ => {}
        }
    }
    // The cycle data of this block, kept for the holes after it.
    let incremental = !m.modal.absolute;
    if let Some((w, x)) = cw.r {
        m.cycle.r = Some(Level { mm: m.length(w, x, false), incremental });
    }
    if let Some((w, x)) = cw.depth {
        m.cycle.z = Some(Level { mm: m.length(w, x, false), incremental });
    }
    if let Some((w, x)) = cw.q {
        let q = m.length(w, x, false);
        if q < 0.0 {
            return Err(refuse(
                "NC418",
                "a negative Q in a drilling cycle is not modelled".into(),
                w.span,
                "write the infeed (G73/G83) or the shift (G76/G87) as a positive distance",
            ));
        }
        m.cycle.q = Some(q);
    }
    if let Some(p) = cw.p {
        m.cycle.p = Some(round_half_away(p) / 1000.0);
    }
    if cw.plane.iter().all(Option::is_none) && cw.depth.is_none() && cw.r.is_none() {
        return Ok(false);
    }
    let count = match cw.count {
        None => 1,
        Some((k, at)) => {
            let k = round_half_away(k);
            if !(0.0..=MAX_REPEATS).contains(&k) {
                return Err(refuse(
                    "NC419",
                    format!("repeat count {} out of the range 0 to 9999", crate::eval::value::fmt_num(k)),
                    at,
                    "K (or L) counts the holes of the block: 0 stores the cycle data only",
                ));
            }
            k as u32
        }
    };
    let Some(z) = m.cycle.z else {
        return Err(refuse(
            "NC420",
            format!("G{} without a hole depth {}", gi / 10, crate::eval::trace::AXES[n]),
            span,
            "program the bottom of the hole in the cycle block",
        ));
    };
    let Some(r) = m.cycle.r else {
        return Err(refuse(
            "NC421",
            format!("G{} without an R plane", gi / 10),
            span,
            "program R in the cycle block (the control's behaviour without one is not modelled)",
        ));
    };
    let peck = if kind.pecks() {
        match m.cycle.q {
            Some(q) if q > 0.0 => Some(q),
            _ => {
                let at = cw.q.map_or(span, |q| q.0.span);
                // The alarm ends the trace; the warning says why and what to write.
                let given = if cw.q.is_some() { "Q0" } else { "no Q" };
                warns.push((
                    NO_Q_NOTE,
                    format!(
                        "G{} with {given}: the control stops with alarm PS{NO_Q:04} (a peck drilling cycle needs \
                         its infeed Q, a positive distance, in the cycle block or before it in the cycle mode)",
                        gi / 10
                    ),
                    at,
                ));
                return Err(Fault::alarm(NO_Q, format!("ADDRESS Q NOT FOUND (G{})", gi / 10), at));
            }
        }
    } else {
        None
    };
    let Some(f) = m.feed else {
        return Err(Fault::alarm(m.alarms.no_feed, "drilling cycle without any feed programmed", span));
    };
    let dwell = if takes_dwell(gi) { Some(m.cycle.p.unwrap_or(0.0)) } else { None };
    // G87 positions below the part: it can only return to the initial level.
    let retract = if kind == CycleKind::BackBore { Retract::Initial } else { m.cycle.retract };
    let off = m.active_offset(n);
    // Under G91, R is measured from the initial level and Z from the R plane.
    let r_abs = if r.incremental { m.cycle.initial + r.mm } else { r.mm + off };
    let bottom = if z.incremental { r_abs + z.mm } else { z.mm + off };
    if kind != CycleKind::BackBore && bottom >= r_abs {
        let ax = crate::eval::trace::AXES[n];
        let at = cw.depth.or(cw.r).map_or(span, |(w, _)| w.span);
        return Err(refuse(
            BOTTOM_CODE,
            format!(
                "G{}: the bottom of the hole (at {ax}={}) is not below the R plane (at {ax}={}), which is not modelled",
                gi / 10,
                crate::eval::value::fmt_num(clean(bottom - off)),
                crate::eval::value::fmt_num(clean(r_abs - off))
            ),
            at,
            &format!(
                "the cycle feeds from R to {ax}: program {ax} below R (under G91 a negative {ax}, counted from R); \
                 only G87 (back boring) starts below the part"
            ),
        ));
    }
    for _ in 0..count {
        let mut at = [(u, 0.0), (v, 0.0)];
        let framed = m.framed;
        if framed {
            // A rotation in the cycle's plane: the hole goes through it as a move would.
            m.framed_hole(cw.plane, span)?;
        }
        for (k, axis) in [u, v].into_iter().enumerate() {
            if let (Some((w, x)), false) = (cw.plane[k], framed) {
                m.pos[axis] = m.axis_target(axis, m.length(w, x, false), w.mode, false);
                m.applied[axis] = m.active_offset(axis);
            }
            m.seen[axis] = true;
            at[k] = (axis, clean(m.pos[axis]));
        }
        if cw.plane.iter().any(Option::is_some) {
            // The positioning to the hole: a rapid at the level the tool stands at (the
            // same move a Sinumerik positioning block makes before its modal cycle).
            out.push((Event::Move { rapid: true, to: m.trace_pos(), f: None, probe: false }, span));
        }
        let start = m.trace_pos();
        m.pos[n] = match retract {
            Retract::Initial => m.cycle.initial,
            Retract::R => r_abs,
        };
        m.seen[n] = true;
        m.applied[n] = off;
        // G98 from an initial level that is the R plane returns to the R plane: the event
        // names that level `r`, as the Sinumerik reader does for RTP = RFP + SDIS (G87 keeps
        // `initial`: its R plane is under the part).
        let retract =
            if retract == Retract::Initial && kind != CycleKind::BackBore && same_level(m.cycle.initial, r_abs) {
                Retract::R
            } else {
                retract
            };
        let tapping = matches!(kind, CycleKind::Tap | CycleKind::TapLeft).then_some(if m.cycle.rigid {
            Tapping::Rigid
        } else {
            Tapping::Floating
        });
        // Rigid tapping from a turning spindle: what the control does with it at M29 and
        // after the cycle is settled by no source at hand; the trace keeps the spindle as it
        // was, which nothing proves. Said once per cycle.
        if tapping == Some(Tapping::Rigid) && m.spindle != SpindleDir::Stop && !m.cycle.rigid_noted {
            m.cycle.rigid_noted = true;
            warns.push((
                RIGID_TURNING,
                format!(
                    "rigid tapping (M29) with the spindle turning {}: what FANUC does with a turning spindle at M29 \
                     and the state it leaves after the cycle are not settled by a source; the trace keeps it \
                     turning, unproven (M5 before M29 is the settled form)",
                    if m.spindle == SpindleDir::Cw { "M3" } else { "M4" }
                ),
                span,
            ));
        }
        let hole =
            Hole { kind, at, r: clean(r_abs), bottom: clean(bottom), peck, dwell, retract, f, tapping }.normalised();
        // G88 halts at the bottom for the operator to retract by hand.
        let halt = is_manual_retract(gi);
        let cx = super::expand::Context { start, axis: n, end: m.pos[n], rpm: m.speed, spindle: m.spindle, halt };
        super::push_hole(m.expand.as_ref(), hole, &cx, span, &mut |e| out.push((e, span)))?;
        m.cycle_positioned();
    }
    Ok(count > 0)
}

/// Two levels of the drilling axis that are the same place (the tolerance the Sinumerik
/// reader compares RTP with RFP + SDIS at).
fn same_level(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-9
}

fn refuse(code: &'static str, msg: String, span: Span, hint: &str) -> Fault {
    Fault::error(Diagnostic::error(code, msg).primary(usize::MAX, span, "here").hint(hint))
}
