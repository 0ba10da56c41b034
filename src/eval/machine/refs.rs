//! Coordinate systems and reference points (trace v2): work-offset selection as
//! `work_offset` events, the FANUC local coordinate system (G52), and reference-point
//! returns (FANUC G28/G30, Siemens G74/G75) as `home` events and the FANUC return from
//! the reference point (G29) as moves (docs/semantics.md,
//! "Coordinate systems and reference points").

use super::{axis_index, round_half_away, AbsInc, Event, Fault, Machine, Span, WordVal, WV};

/// The machine position of every reference and fixed point (trace spec: machine 0 on every
/// axis; no profile key sets another yet).
const REFERENCE_POSITION: f64 = 0.0;

/// A reference-point return asked for by a block.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Home {
    /// 1: reference point (G28, G74); 2..4: FANUC G30 Pn, Siemens G75 FP=n-1.
    pub point: u8,
    /// FANUC: the axis words give an intermediate point; Siemens: they only name the axes.
    pub via_words: bool,
}

fn error(code: &'static str, msg: String, span: Span, hint: &str) -> Fault {
    Fault::Error(Box::new(crate::diag::Diagnostic::error(code, msg).primary(usize::MAX, span, "here").hint(hint)))
}

/// What an unmodelled coordinate-system G code (×10) is, for its error.
pub fn unmodelled_frame(gi: i64) -> &'static str {
    match gi {
        290 => "return from the reference point",
        920 => "coordinate system setting",
        680 => "coordinate system rotation",
        160 => "polar coordinates",
        _ => "local coordinate system, a FANUC code",
    }
}

/// The refusal of a G code the evaluator does not run (`shown` as written), with its Haas
/// name under a Haas profile (`G13 (Haas circular pocket milling, …)`).
pub fn unmodelled_g(shown: &str, gi: i64, haas: bool) -> String {
    match crate::dialect::fanuc::haas_g_meaning(gi as u32) {
        Some(m) if haas => format!("G{shown} ({m}) is not modelled by the evaluator"),
        _ => format!("G{shown} is not modelled by the evaluator"),
    }
}

impl Machine {
    /// Selects work offset `n` (the trace's `work_offset` number, also the table index) and
    /// emits its event, also when it is the one already active.
    pub(super) fn select_work_offset(&mut self, n: usize, out: &mut Vec<(Event, Span)>, span: Span) {
        self.select_offset(n);
        self.wo_selections += 1;
        out.push((Event::WorkOffset { n: self.wo as u32 }, span));
    }

    /// FANUC `G54.1 Pn` (and `G54 Pn`, the same on 0i/30i): extended offset n = 7.. in the
    /// trace, table `6 + n`.
    pub(super) fn extended_offset(
        &mut self,
        p: Option<(&WordVal, f64)>,
        out: &mut Vec<(Event, Span)>,
        span: Span,
    ) -> Result<(), Fault> {
        let n = p.map(|(_, x)| round_half_away(x)).unwrap_or(1.0);
        if !(1.0..=48.0).contains(&n) {
            return Err(Fault::alarm(
                self.alarms.bad_index,
                format!("G54.1 P{n}: no such extended work offset (P1..P48)"),
                span,
            ));
        }
        self.select_work_offset(6 + n as usize, out, span);
        Ok(())
    }

    /// FANUC `G52 X.. Y..`: each axis given replaces that axis's local shift (in every work
    /// offset); `G52 X0 Y0 Z0` cancels. No motion.
    pub(super) fn local_shift(&mut self, axes: &[Option<(&WordVal, f64)>; 9], span: Span) -> Result<(), Fault> {
        if !self.modal.absolute || axes.iter().flatten().any(|(w, _)| w.mode != AbsInc::Plain) {
            return Err(error(
                "NC440",
                "G52 under G91 (an incremental local shift) is not modelled".into(),
                span,
                "write G52 with the absolute shift under G90",
            ));
        }
        for (i, a) in axes.iter().enumerate() {
            if let Some((w, x)) = a {
                self.local[i] = self.length(w, *x, (3..6).contains(&i));
            }
        }
        Ok(())
    }

    /// A G52 that names axes and gives each the shift it already has (`G52 X0 Y0 Z0` with
    /// none in force): it changes nothing whatever order the frame modes apply in, so it
    /// may stand under G68/G51/G51.1 (Haas templates end so while still mirrored).
    pub(super) fn g52_keeps_shift(&self, axes: &[Option<(&WordVal, f64)>; 9]) -> bool {
        self.modal.absolute
            && axes.iter().any(Option::is_some)
            && axes.iter().enumerate().all(|(i, a)| match a {
                Some((w, x)) => w.mode == AbsInc::Plain && self.length(w, *x, (3..6).contains(&i)) == self.local[i],
                None => true,
            })
    }

    /// A Siemens G74/G75 stands alone in its block: only the G code, the axes to approach
    /// and FP= (geometry-axis words are left to NC441). "G75 requires a separate block"
    /// (802D programming manual 07/2009 §10.3.6); no source says G74 may share its block,
    /// so it is refused alike rather than run in a guessed order (docs/semantics.md).
    pub(super) fn approach_alone(&self, words: &[WordVal], g: f64) -> Result<(), Fault> {
        for w in words {
            let a: &str = &w.addr;
            let own = match (a, &w.val) {
                ("G", WV::Num(x)) => *x == g,
                ("FP", _) => g == 75.0,
                (a, _) => Self::machine_axis(a).is_some() || (a.len() == 1 && axis_index(a.as_bytes()[0]).is_some()),
            };
            if !own {
                let name = if g == 75.0 { "G75" } else { "G74" };
                let a = match &w.val {
                    WV::Num(x) if a.len() == 1 => format!("{a}{}", crate::eval::value::fmt_num(*x)),
                    _ => a.to_string(),
                };
                return Err(error(
                    "NC569",
                    format!(
                        "{name} with `{a}` in its block: the approach must stand alone (\"G75 requires a separate \
                         block\", Siemens 802D programming manual §10.3.6; G74 is held to the same rule, no source \
                         allows other words with it)"
                    ),
                    w.span,
                    &format!("write `{a}` in a block of its own before or after the `{name}` block"),
                ));
            }
        }
        Ok(())
    }

    /// The homed axes of a Siemens G74/G75 block: machine-axis words `X1=0` (or `X=0`),
    /// whose values are ignored.
    pub(super) fn machine_axis(addr: &str) -> Option<usize> {
        let b = addr.as_bytes();
        match b {
            [c, b'1'] => axis_index(*c),
            _ => None,
        }
    }

    /// A reference-point return of the axes in `axes` (FANUC: with the intermediate point
    /// they give; Siemens: `named` machine axes). Emits the rapid to the intermediate point
    /// (FANUC, unless every word is an incremental 0: the point is where the tool stands),
    /// then the `home` event, and leaves the homed axes at the reference position.
    pub(super) fn reference_return(
        &mut self,
        home: Home,
        axes: &[Option<(&WordVal, f64)>; 9],
        named: &[usize],
        out: &mut Vec<(Event, Span)>,
        span: Span,
    ) -> Result<bool, Fault> {
        let mut homed = [false; 9];
        if home.via_words {
            let mut target = self.pos;
            let mut stays = true;
            for (i, a) in axes.iter().enumerate() {
                let Some((w, x)) = a else { continue };
                let v = self.length(w, *x, (3..6).contains(&i));
                let inc = w.mode == AbsInc::Ic || (w.mode == AbsInc::Plain && !self.modal.absolute);
                stays &= inc && v == 0.0;
                target[i] = self.axis_target(i, v, w.mode, false);
                homed[i] = true;
            }
            if !stays {
                for (i, h) in homed.iter().enumerate() {
                    if *h {
                        self.applied[i] = self.active_offset(i);
                        self.seen[i] = true;
                        self.pos[i] = target[i];
                    }
                }
                out.push((Event::Move { rapid: true, to: self.trace_pos(), f: None, probe: false }, span));
            }
        } else {
            for &i in named {
                homed[i] = true;
            }
            if let Some((w, _)) = axes.iter().flatten().next() {
                return Err(error(
                    "NC441",
                    format!("G74/G75 names machine axes (`{}1=0`), not {}", w.addr, w.addr),
                    w.span,
                    "write the axes to approach as machine axes with the value 0: `G74 X1=0 Y1=0 Z1=0`",
                ));
            }
        }
        if !homed.iter().any(|h| *h) {
            return Ok(false);
        }
        let mut list = Vec::new();
        let mut via = [None; 9];
        for (i, h) in homed.iter().enumerate() {
            if *h {
                list.push(i as u8);
                via[i] = Some(super::clean(self.pos[i]));
                if home.via_words {
                    self.inter[i] = Some((self.pos[i], self.active_offset(i)));
                }
                self.pos[i] = REFERENCE_POSITION;
                self.seen[i] = true;
                self.applied[i] = self.active_offset(i);
            }
        }
        let at = self.trace_pos();
        out.push((Event::Home(Box::new(crate::eval::trace::HomeEv { axes: list, via, point: home.point, at })), span));
        Ok(true)
    }

    /// FANUC `G29 X.. Z..`: the named axes go at rapid to the intermediate point of the
    /// last G28/G30 that homed them, then to the point the words give (G90: absolute; G91:
    /// the increment from the intermediate point). Two `move rapid` events; the other axes
    /// stay. An axis no G28/G30 has homed, or one whose work offset (G54.., G52, G92, a G10
    /// write) changed since, is NC548: the sources do not settle what the control does then.
    pub(super) fn return_from_reference(
        &mut self,
        axes: &[Option<(&WordVal, f64)>; 9],
        out: &mut Vec<(Event, Span)>,
        span: Span,
    ) -> Result<bool, Fault> {
        let mut target = self.pos;
        let mut via = self.pos;
        let mut any = false;
        for (i, a) in axes.iter().enumerate() {
            let Some((w, x)) = a else { continue };
            let Some((at, off)) = self.inter[i] else {
                return Err(error(
                    "NC548",
                    format!("G29 on {} with no intermediate point (no G28/G30 has homed it)", w.addr),
                    w.span,
                    "return the axis with G28 or G30 before G29",
                ));
            };
            if off != self.active_offset(i) {
                return Err(error(
                    "NC548",
                    format!("G29 on {} after its work offset changed since the G28/G30 (where the intermediate point then lies is not modelled)", w.addr),
                    w.span,
                    "return with G29 before changing the offset, or move to the point with G0",
                ));
            }
            let v = self.length(w, *x, (3..6).contains(&i));
            let inc = w.mode == AbsInc::Ic || (w.mode == AbsInc::Plain && !self.modal.absolute);
            via[i] = at;
            target[i] = if inc { at + v } else { v + self.active_offset(i) };
            any = true;
        }
        if !any {
            // Alone, some controls return the last G28's axes to its intermediate point,
            // others not at all (docs/semantics.md, MILL-G29): not modelled.
            return Err(error(
                "NC548",
                "G29 without an axis word is not modelled (which axes it returns is not settled)".into(),
                span,
                "name the axes to return: `G29 Z5.`",
            ));
        }
        for (i, a) in axes.iter().enumerate() {
            if a.is_some() {
                self.seen[i] = true;
                self.applied[i] = self.active_offset(i);
                self.pos[i] = via[i];
            }
        }
        out.push((Event::Move { rapid: true, to: self.trace_pos(), f: None, probe: false }, span));
        for (i, a) in axes.iter().enumerate() {
            if a.is_some() {
                self.pos[i] = target[i];
            }
        }
        out.push((Event::Move { rapid: true, to: self.trace_pos(), f: None, probe: false }, span));
        Ok(true)
    }

    /// The point number of Siemens `G75 FP=k` (k 1..4, default 1) in the trace: k + 1, so
    /// that it meets FANUC `G30 P(k+1)`.
    pub(super) fn fixed_point(&self, fp: Option<(&WordVal, f64)>, span: Span) -> Result<u8, Fault> {
        let k = match fp {
            None => 1.0,
            Some((w, x)) => match w.val {
                WV::Num(_) => round_half_away(x),
                WV::Str(_) => 0.0,
            },
        };
        if !(1.0..=4.0).contains(&k) {
            return Err(Fault::alarm(
                self.alarms.bad_index,
                format!("G75 FP={k}: no such fixed point (FP=1..4)"),
                span,
            ));
        }
        Ok(k as u8 + 1)
    }

    /// The point number of FANUC `G30 Pn` (n 2..4, default 2).
    pub(super) fn second_reference(&self, p: Option<(&WordVal, f64)>, span: Span) -> Result<u8, Fault> {
        let n = p.map(|(_, x)| round_half_away(x)).unwrap_or(2.0);
        if !(2.0..=4.0).contains(&n) {
            return Err(Fault::alarm(
                self.alarms.bad_index,
                format!("G30 P{n}: no such reference point (P2..P4)"),
                span,
            ));
        }
        Ok(n as u8)
    }
}

/// A G value as messages write it (`G05.1`, `G54`).
pub(super) fn fmt_g(g: f64) -> String {
    crate::eval::value::fmt_num(g)
}

/// A construct the evaluator does not model (NC403): never a silently wrong position.
pub(super) fn unsupported(msg: &str, span: Span) -> Fault {
    Fault::Error(Box::new(
        crate::diag::Diagnostic::error("NC403", msg.to_string())
            .primary(usize::MAX, span, "here")
            .hint("this construct cannot be proven equivalent; rewrite it with G0/G1/G2/G3 moves"),
    ))
}
