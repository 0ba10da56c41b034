//! Sinumerik drilling cycles CYCLE81–CYCLE89 and CYCLE840: called at the current position,
//! or modally with `MCALL CYCLEnn(…)` after every block that moves until `MCALL` alone.
//! Each hole is one `cycle` event; parameters, defaults and sources are in
//! docs/semantics.md ("Drilling cycles").

use crate::diag::Diagnostic;
use crate::dialect::sinumerik::cycles::{metric_coarse_pitch, SieCycle};
use crate::eval::exec::{Flow, Interp};
use crate::eval::fault::Fault;
use crate::eval::machine::{clean, Machine};
use crate::eval::trace::{Event, SpindleDir};
use crate::eval::value::Value;
use crate::ir::cycle::{CycleKind, Hole, Retract, Tapping};
use crate::ir::{Call, CallKind};
use crate::span::Span;

/// The warning for a cycle call without DP and DPR.
pub const NO_DEPTH_NOTE: &str = "NC523";

/// A cycle made modal by `MCALL`, with its arguments as evaluated at the MCALL.
#[derive(Clone, Debug, PartialEq)]
pub struct McallCycle {
    pub cycle: SieCycle,
    pub args: Vec<Option<f64>>,
    pub span: Span,
}

/// The arguments of one call by parameter name; an empty or missing argument is 0, the
/// default of every cycle parameter.
struct Args<'a> {
    cycle: SieCycle,
    vals: &'a [Option<f64>],
}

impl Args<'_> {
    fn get(&self, name: &str) -> f64 {
        self.opt(name).unwrap_or(0.0)
    }

    fn opt(&self, name: &str) -> Option<f64> {
        let i = self.cycle.params().iter().position(|p| *p == name)?;
        self.vals.get(i).copied().flatten()
    }
}

impl Interp<'_> {
    /// A call of a drilling cycle: the hole now, or (MCALL) the cycle made modal.
    pub(crate) fn siemens_cycle_call(&mut self, call: &Call, cycle: SieCycle, span: Span) -> Result<Flow, Fault> {
        let vals = self.sie_args(call)?;
        let args = numeric(cycle, &vals, span).map_err(|f| self.fix_file(f))?;
        let a = Args { cycle, vals: &args };
        if cycle.params().contains(&"DP") && a.opt("DP").is_none() && a.opt("DPR").is_none() {
            // Empty is 0 (the documented default), so the hole ends at DP = 0: run as
            // written, and said, since a depth left out is rarely meant.
            self.warn(
                NO_DEPTH_NOTE,
                format!(
                    "{} without a final drilling depth: DP and DPR are empty, so the hole ends at DP=0 (give DP, \
                     absolute, or DPR, from RFP)",
                    cycle.name()
                ),
                span,
            );
        }
        if call.kind == CallKind::Mcall {
            // One modal call at a time: a cycle replaces a modal subprogram and back.
            self.modal_call = None;
            self.m.cycle.mcall = Some(McallCycle { cycle, args, span });
            return Ok(Flow::Next);
        }
        self.siemens_hole(cycle, &args, span)?;
        Ok(Flow::Next)
    }

    /// The hole of the modal cycle after a block that moved.
    pub(crate) fn mcall_hole(&mut self, span: Span) -> Result<(), Fault> {
        let Some(mc) = self.m.cycle.mcall.clone() else { return Ok(()) };
        self.siemens_hole(mc.cycle, &mc.args, span)
    }

    fn siemens_hole(&mut self, cycle: SieCycle, vals: &[Option<f64>], span: Span) -> Result<(), Fault> {
        // Under a rotation in the cycle's plane the hole is where the tool stands (the frame
        // took its positioning through) and the levels along the drilling axis are the frame's.
        if self.m.framed {
            self.m.cycle_frame(span).map_err(|f| self.fix_file(f))?;
        }
        let mut out = Vec::new();
        let r = hole(&mut self.m, Args { cycle, vals }, span, &mut out);
        self.m.cycle_positioned();
        for ev in out {
            self.emit(ev, span);
        }
        r.map_err(|f| self.fix_file(f))
    }
}

/// The call's arguments as numbers (at most the cycle's parameter count).
fn numeric(cycle: SieCycle, vals: &[Option<Value>], span: Span) -> Result<Vec<Option<f64>>, Fault> {
    if vals.len() > cycle.params().len() {
        return Err(refuse(
            "NC424",
            format!("{} takes at most {} arguments, {} given", cycle.name(), cycle.params().len(), vals.len()),
            span,
            &format!("the parameters are {}", cycle.params().join(", ")),
        ));
    }
    let mut out = Vec::new();
    for (i, v) in vals.iter().enumerate() {
        out.push(match v {
            None | Some(Value::Vacant) => None,
            Some(Value::Num(x)) => Some(*x),
            Some(Value::Str(_)) => {
                return Err(refuse(
                    "NC424",
                    format!("{} parameter {} needs a number", cycle.name(), cycle.params()[i]),
                    span,
                    "the drilling cycles take numbers only",
                ))
            }
        });
    }
    Ok(out)
}

/// The parameters the event cannot show: each must be empty or hold its default.
fn require_default(a: &Args, names: &[&str], span: Span) -> Result<(), Fault> {
    for name in names {
        if let Some(x) = a.opt(name) {
            if x != 0.0 {
                return Err(refuse(
                    "NC423",
                    format!(
                        "{} with {name}={}: this setting is not modelled",
                        a.cycle.name(),
                        crate::eval::value::fmt_num(x)
                    ),
                    span,
                    &format!("leave {name} empty (its default) or write the motion with G0/G1 moves"),
                ));
            }
        }
    }
    Ok(())
}

/// Whether `x` lies strictly between `a` and `b`.
fn between(x: f64, a: f64, b: f64) -> bool {
    (a < x && x < b) || (b < x && x < a)
}

fn same(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-9
}

/// One hole at the tool's plane position: the events go to `out` (an approach to the
/// retraction plane, the hole, a stop, a retract beyond the start level).
fn hole(m: &mut Machine, a: Args, span: Span, out: &mut Vec<Event>) -> Result<(), Fault> {
    let c = a.cycle;
    require_default(&a, &["_GMODE", "_DMODE", "_AMODE", "_AXN"], span)?;
    let (u, v, n) = m.modal.plane.axes();
    let off = m.active_offset(n);
    let len = |x: f64| m.length_of(false, x, false);
    let (rtp, rfp, sdis) = (len(a.get("RTP")) + off, len(a.get("RFP")) + off, len(a.get("SDIS")));
    // The cycle drills away from the retraction plane.
    let dir = if rtp < rfp { -1.0 } else { 1.0 };
    let r = rfp + dir * sdis.abs();
    // DPR (depth relative to RFP) wins over DP when both are given.
    let dpr = len(a.get("DPR"));
    let bottom = if dpr != 0.0 { rfp - dir * dpr.abs() } else { len(a.get("DP")) + off };
    if (bottom - r) * dir >= 0.0 {
        return Err(refuse(
            "NC425",
            format!("{}: the final depth is not beyond the reference plane plus the safety distance", c.name()),
            span,
            "DP (absolute) or DPR (from RFP) must lie on the far side of RFP from RTP",
        ));
    }
    let dtb = a.get("DTB");
    let mut peck = None;
    let mut dwell = None;
    let mut stop = false;
    let mut f = m.feed;
    let kind = match c {
        SieCycle::C81 => CycleKind::Drill,
        SieCycle::C82 => {
            dwell = Some(dtb);
            CycleKind::DwellDrill
        }
        SieCycle::C83 => {
            require_default(&a, &["DAM", "DTB", "DTS", "_MDEP", "_DTD", "_DIS1"], span)?;
            if a.opt("FRF").is_some_and(|x| x != 0.0 && x != 1.0) {
                return Err(refuse(
                    "NC423",
                    "CYCLE83 with a feed factor FRF for the first infeed is not modelled".into(),
                    span,
                    "leave FRF empty or 1",
                ));
            }
            if sdis != 0.0 {
                return Err(refuse(
                    "NC426",
                    "CYCLE83 with a safety distance: its infeeds are measured from RFP, not from where feeding starts, which the cycle event cannot show".into(),
                    span,
                    "write SDIS 0 and RFP at the plane where feeding starts",
                ));
            }
            let fdpr = len(a.get("FDPR")).abs();
            let first = if fdpr != 0.0 { fdpr } else { (rfp - (len(a.get("FDEP")) + off)) * dir };
            if first <= 0.0 {
                return Err(refuse(
                    "NC427",
                    "CYCLE83 without a first drilling depth (FDEP or FDPR)".into(),
                    span,
                    "give the infeed as FDPR (from RFP) or FDEP (absolute)",
                ));
            }
            peck = Some(first);
            match a.get("VARI") {
                0.0 => CycleKind::ChipBreak,
                1.0 => CycleKind::Peck,
                x => {
                    return Err(refuse(
                        "NC423",
                        format!(
                            "CYCLE83 with VARI={}: only 0 (chip breaking) and 1 (chip removal) exist",
                            crate::eval::value::fmt_num(x)
                        ),
                        span,
                        "VARI 0 breaks the chip, 1 retracts to remove it",
                    ))
                }
            }
        }
        SieCycle::C84 | SieCycle::C840 => {
            let (kind, feed) = tapping(m, &a, span)?;
            dwell = Some(dtb);
            f = feed.or(f);
            kind
        }
        SieCycle::C85 => {
            let (ffr, rff) = (a.get("FFR"), a.get("RFF"));
            if ffr <= 0.0 || !same(ffr, rff) {
                return Err(refuse(
                    "NC423",
                    "CYCLE85 with a retract feed RFF other than its infeed FFR is not modelled".into(),
                    span,
                    "give FFR > 0 and RFF equal to it",
                ));
            }
            f = Some(if m.modal.inch_feed { ffr * 25.4 } else { ffr });
            dwell = Some(dtb);
            CycleKind::BoreDwell
        }
        SieCycle::C86 => {
            spindle_is(m, &a, span)?;
            dwell = Some(dtb);
            CycleKind::FineBore
        }
        SieCycle::C87 | SieCycle::C88 => {
            spindle_is(m, &a, span)?;
            dwell = Some(if c == SieCycle::C88 { dtb } else { 0.0 });
            stop = true;
            CycleKind::BoreStop
        }
        SieCycle::C89 => {
            dwell = Some(dtb);
            CycleKind::BoreDwell
        }
    };
    let Some(f) = f else {
        return Err(Fault::alarm(m.alarms.no_feed, format!("{} without any feed programmed", c.name()), span));
    };
    // Where the tool returns: the R plane, or the level it started at; a retraction plane
    // between the two is approached first (the same straight rapid), one beyond the start
    // level is reached after the hole.
    let p = m.pos[n];
    let (retract, before, after) = if same(rtp, r) {
        (Retract::R, false, false)
    } else if same(rtp, p) {
        (Retract::Initial, false, false)
    } else if same(p, r) && (rtp - r) * dir > 0.0 {
        // The tool stands at RFP + SDIS (a FANUC G98 hole after G99 ones, translated): no
        // approach, and the retraction plane is the level the hole returns to, as G98's
        // initial level is.
        (Retract::Initial, false, false)
    } else if between(rtp, p, r) {
        (Retract::Initial, true, false)
    } else if between(p, rtp, r) {
        (Retract::Initial, false, true)
    } else {
        return Err(refuse(
            "NC422",
            format!("{}: the retraction plane RTP lies below the reference plane plus the safety distance", c.name()),
            span,
            "RTP must be at or above RFP + SDIS",
        ));
    };
    for axis in [u, v, n] {
        m.seen[axis] = true;
    }
    if before {
        m.pos[n] = rtp;
        m.applied[n] = off;
        out.push(Event::Move { rapid: true, to: m.trace_pos(), f: None, probe: false });
    }
    let at = [(u, clean(m.pos[u])), (v, clean(m.pos[v]))];
    let tapping = match c {
        SieCycle::C84 => Some(Tapping::Rigid),
        SieCycle::C840 => Some(Tapping::Floating),
        _ => None,
    };
    let hole = Hole { kind, at, r: clean(r), bottom: clean(bottom), peck, dwell, retract, f, tapping }.normalised();
    // The hole ends at the R plane or at the level the tool stands at now (an RTP beyond
    // it is the rapid after the hole).
    let end = if retract == Retract::R {
        r
    } else if same(p, r) {
        rtp
    } else {
        m.pos[n]
    };
    // CYCLE87/CYCLE88: M5 and M0 at the bottom; NC start retracts.
    // CYCLE84 turns the spindle at its own speed SST.
    let rpm = if c == SieCycle::C84 { a.get("SST") } else { m.speed };
    let cx = super::expand::Context { start: m.trace_pos(), axis: n, end, rpm, spindle: m.spindle, halt: stop };
    super::push_hole(m.expand.as_ref(), hole, &cx, span, &mut |e| out.push(e))?;
    m.pos[n] = rtp;
    m.applied[n] = off;
    if after {
        out.push(Event::Move { rapid: true, to: m.trace_pos(), f: None, probe: false });
    }
    Ok(())
}

/// The kind and feed of a tapping cycle: CYCLE84 from the pitch (its sign: the hand) and
/// the tapping speed SST; CYCLE840 from the spindle direction, with the pitch × speed
/// (encoder, ENC 0) or the programmed feed (no encoder, ENC 1).
fn tapping(m: &Machine, a: &Args, span: Span) -> Result<(CycleKind, Option<f64>), Fault> {
    let (mpit, pit) = (a.get("MPIT"), a.get("PIT"));
    let pitch = match (mpit != 0.0, pit != 0.0) {
        (_, true) => Some(pit),
        (true, false) => Some(metric_coarse_pitch(mpit.abs()).map(|p| p.copysign(mpit)).ok_or_else(|| {
            refuse("NC427", format!("MPIT={mpit}: not a metric coarse thread M3 to M48"), span, "give the pitch as PIT")
        })?),
        (false, false) => None,
    };
    // Under G70/G700 the sources at hand do not say whether PIT is read in inch (the
    // programmed unit) or in mm: the feed would be off by 25.4 either way, so it is refused.
    if pit != 0.0 && m.modal.inch {
        return Err(refuse(
            "NC423",
            format!("{} with a pitch PIT under G70/G700 (inch) is not modelled", a.cycle.name()),
            span,
            "program the tapping in G71/G710, or give the thread as MPIT (metric)",
        ));
    }
    if a.cycle == SieCycle::C84 {
        require_default(a, &["_PTAB", "_TECHNO", "_VARI", "_DAM"], span)?;
        let sst = a.get("SST");
        let Some(pitch) = pitch.filter(|_| sst > 0.0) else {
            return Err(refuse(
                "NC427",
                "CYCLE84 without a pitch (MPIT or PIT) and a tapping speed SST".into(),
                span,
                "give the thread pitch and SST",
            ));
        };
        if a.opt("SST1").is_some_and(|x| x != 0.0 && x != sst) {
            return Err(refuse(
                "NC423",
                "CYCLE84 with a retract speed SST1 other than SST is not modelled".into(),
                span,
                "leave SST1 empty",
            ));
        }
        if a.opt("SDAC").is_some_and(|x| x != 0.0 && Some(x) != spindle_code(m.spindle)) {
            return Err(refuse(
                "NC423",
                "CYCLE84 leaving the spindle in another state (SDAC) is not modelled".into(),
                span,
                "give SDAC as the spindle's state before the cycle (3 = M3, 4 = M4, 5 = M5)",
            ));
        }
        let kind = if pitch < 0.0 { CycleKind::TapLeft } else { CycleKind::Tap };
        return Ok((kind, Some(lead_feed(m, pitch, sst))));
    }
    require_default(a, &["_PTAB", "_TECHNO"], span)?;
    let (kind, inward) = match m.spindle {
        SpindleDir::Cw => (CycleKind::Tap, 3.0),
        SpindleDir::Ccw => (CycleKind::TapLeft, 4.0),
        SpindleDir::Stop => {
            return Err(refuse(
                "NC427",
                "CYCLE840 with the spindle stopped: the thread's hand comes from its direction".into(),
                span,
                "start the spindle with M3 (right hand) or M4 (left hand) before the cycle",
            ))
        }
    };
    let encoder = match a.get("ENC") {
        0.0 => true,
        1.0 => false,
        x => {
            return Err(refuse(
                "NC423",
                format!(
                    "CYCLE840 with ENC={}: only 0 (encoder) and 1 (no encoder) are modelled",
                    crate::eval::value::fmt_num(x)
                ),
                span,
                "ENC 1 taps at the programmed feed",
            ))
        }
    };
    // PGZ: SDR 0 (the cycle reverses the spindle itself) exists only with an encoder;
    // otherwise SDR names the retract direction and SDAC the direction for the next threads.
    let sdr = a.get("SDR");
    let reverse = 7.0 - inward;
    if sdr == 0.0 && !encoder {
        return Err(refuse(
            "NC480",
            "CYCLE840 without an encoder (ENC 1) and without a retract direction SDR".into(),
            span,
            &format!("give SDR {} (the reverse of the spindle's M{}): only tapping with an encoder reverses by itself (SDR 0)", reverse, inward),
        ));
    }
    if sdr != 0.0 {
        if sdr != reverse {
            return Err(refuse(
                "NC481",
                format!(
                    "CYCLE840 with SDR={} while the spindle turns M{}: the tap would not come out the way it went in",
                    crate::eval::value::fmt_num(sdr),
                    inward
                ),
                span,
                &format!("SDR is the retract direction: {reverse} after M{inward}"),
            ));
        }
        if a.get("SDAC") != inward {
            return Err(refuse(
                "NC482",
                format!(
                    "CYCLE840 with SDR={}: SDAC must be the spindle's direction, {inward}",
                    crate::eval::value::fmt_num(sdr)
                ),
                span,
                "SDAC is the direction the next threads start in (the one programmed before the first call)",
            ));
        }
    }
    // Without an encoder the pitch, where given, sets the feed from the speed (PGZ, SW 6.2).
    match (pitch, encoder) {
        (Some(p), _) => Ok((kind, Some(lead_feed(m, p, m.speed)))),
        (None, false) => Ok((kind, None)),
        (None, true) => {
            Err(refuse("NC427", "CYCLE840 with an encoder needs the pitch (MPIT or PIT)".into(), span, "give PIT"))
        }
    }
}

/// The feed a thread lead makes at `rpm`: per minute the lead × the speed, per revolution
/// (G95) the lead itself.
fn lead_feed(m: &Machine, pitch: f64, rpm: f64) -> f64 {
    if m.modal.per_rev {
        pitch.abs()
    } else {
        pitch.abs() * rpm
    }
}

fn spindle_code(d: SpindleDir) -> Option<f64> {
    Some(match d {
        SpindleDir::Cw => 3.0,
        SpindleDir::Ccw => 4.0,
        SpindleDir::Stop => 5.0,
    })
}

/// SDIR of the boring cycles: the spindle direction they turn in; only the direction the
/// spindle already has is modelled (another would start it, which the cycle event hides).
fn spindle_is(m: &Machine, a: &Args, span: Span) -> Result<(), Fault> {
    match a.opt("SDIR") {
        None => Ok(()),
        Some(x) if x == 0.0 || Some(x) == spindle_code(m.spindle) => Ok(()),
        Some(x) => Err(refuse(
            "NC423",
            format!(
                "{} with SDIR={} while the spindle is {}: not modelled",
                a.cycle.name(),
                crate::eval::value::fmt_num(x),
                m.spindle.name()
            ),
            span,
            "start the spindle in that direction (M3/M4) before the cycle",
        )),
    }
}

fn refuse(code: &'static str, msg: String, span: Span, hint: &str) -> Fault {
    Fault::error(Diagnostic::error(code, msg).primary(usize::MAX, span, "here").hint(hint))
}
