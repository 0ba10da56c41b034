//! The machine model: modal state, units, offsets, the decimal-point rule, and turning one
//! block's evaluated address words into trace events in the order the trace spec fixes.

use super::arc;
use super::fault::{AlarmNumbers, Fault};
use super::trace::{axis_index, Axes, Event, Plane, SpindleDir, ToolId};
use super::value::{is_decimal_scale, round_half_away, round_to, round_to_decimal, round_to_scaled};
use crate::dialect::lit::AbsInc;
use crate::ir::cycle::Retract;
use crate::span::Span;

/// Warning code for a compensation construct the `comp` event does not carry (FANUC G44's
/// direction, Siemens ISO-mode G43/G44/G49): `check` does not call two programs equivalent
/// when a run met it (it reports "tool compensation not compared").
pub const COMPENSATION_NOTE: &str = "NC387";

pub mod comp;
pub mod corners;
mod fanuc_frames;
mod fast;
mod frames;
mod grid;
mod haas_mirror;
mod lengths;
pub mod lookahead;
mod modal;
mod motion;
mod offsets;
pub mod path_feed;
mod polar;
pub mod probe;
mod refs;
pub use fanuc_frames::FanucScale;
pub use fast::{fast_path_on, set_fast_path, LitDone};
pub use frames::{framed_cycle, FanucRot, Xform};
pub use modal::{g_index, Modal};
pub use motion::{DWELL_FANUC_POINT, DWELL_HAAS_COMPUTED};
pub use polar::Pole;
use refs::{fmt_g, unsupported};

/// A word after evaluation of its value.
#[derive(Clone, Debug)]
pub struct WordVal {
    /// Upper-case address (`X`, `CR`, `I1`); letters borrow a static string.
    pub addr: std::borrow::Cow<'static, str>,
    pub val: WV,
    pub mode: AbsInc,
    /// FANUC: a literal written without a decimal point (the decimal-point rule applies).
    pub bare: bool,
    /// The value was written as a number (`P0.5`, `P500`), not computed (`P#1`, `P[#1/2]`):
    /// a Haas G04 P takes its unit from the written decimal point.
    pub literal: bool,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub enum WV {
    Num(f64),
    Str(String),
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Motion {
    Rapid,
    Linear,
    Cw,
    Ccw,
}

/// What a block asks of the program flow after its NC words ran.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BlockEffect {
    /// An axis moved (for modal calls).
    pub moved: bool,
    /// `M30`/`M2` written as a word.
    pub end: Option<&'static str>,
    /// `M99`/`M17` written as a word.
    pub ret: bool,
}

/// A warning from the machine model: code, message, span.
pub type Warn = (&'static str, String, Span);

pub struct Machine {
    pub fanuc: bool,
    /// Siemens: the master spindle's number as written after `M`/`S` (`Semantics::master_spindle`).
    pub master_spindle: Option<String>,
    /// A Haas control (`Semantics::haas`): G103 is its look-ahead limit.
    pub haas: bool,
    /// Tool offset data the run was given or the program wrote (`eval::tool_data`): keyed
    /// `#11005` (FANUC memory C) or `$TC_DP3[5,1]` (Siemens), the value as written.
    pub tool_data: std::collections::HashMap<String, f64>,
    pub alarms: AlarmNumbers,
    /// FANUC decimal-point rule active (IS-B, not calculator input).
    pub scaling: bool,
    /// Least increment in mm (metric); inch increment is a tenth of it in inches.
    pub inc_mm: f64,
    /// Motion mode, plane, G90/G91, units and feed type (what [`Modal::g`] changes).
    pub modal: Modal,
    /// Feed in mm/min (mm/rev under G95).
    pub feed: Option<f64>,
    pub speed: f64,
    pub spindle: SpindleDir,
    pub tool_sel: Option<ToolId>,
    pub tool: Option<ToolId>,
    pub d: f64,
    pub h: f64,
    pub coolant: bool,
    /// Position in the machine frame in mm (workpiece position + active offset).
    pub pos: [f64; 9],
    pub seen: [bool; 9],
    /// Offset tables: FANUC 0 = external, 1..6 = G54..G59; Siemens 0 = G500, 1.. = G54..
    pub offsets: Vec<[f64; 9]>,
    /// Selected offset table index (FANUC default G54 = 1; Siemens default G500 = 0).
    pub wo: usize,
    /// Siemens: the frame values copied at selection (writing `$P_UIFR` does not
    /// activate them until G54.. is selected again).
    pub frame: [f64; 9],
    /// Siemens programmable offset (`TRANS`/`ATRANS`).
    pub trans: [f64; 9],
    /// FANUC local coordinate system (`G52`), added to every work offset.
    pub local: [f64; 9],
    /// FANUC `G92` shift, added to every work offset (it moves them all in parallel).
    pub g92: [f64; 9],
    /// FANUC: the intermediate point of the last G28/G30 on each axis it homed (machine
    /// position, and the active offset then), for G29 (refs.rs).
    pub inter: [Option<(f64, f64)>; 9],
    /// The frame's rotation, scaling and mirroring (FANUC G68; Siemens ROT, SCALE, MIRROR):
    /// programmed → workpiece coordinates before the offsets above ([`frames`]).
    pub xf: Xform,
    /// The FANUC G68 rotation in force.
    pub rot: Option<FanucRot>,
    /// The FANUC G51 scaling in force.
    pub scale: Option<FanucScale>,
    /// The FANUC G51.1 axis of symmetry of X, Y, Z (mirrored where set).
    pub mirror: [Option<f64>; 3],
    /// Axes (bits 0..2) to be positioned absolute before they move incrementally, and
    /// (bits 4..6) before a FANUC move leaves them out: their frame changed, turning them
    /// ([`Machine::set_xform`]).
    pub fresh: u8,
    /// Per axis, its programmed value and offset when its frame last turned ([`Machine::kept_bits`]).
    pub kept: [(f64, f64); 3],
    /// `fresh != 0` or a frame that turns: moves take [`Machine::framed_motion`].
    pub framed: bool,
    /// FANUC G16: polar coordinates in force.
    pub polar: bool,
    /// The Siemens pole (G110/G111/G112) and the polar angle and radius stored with it.
    pub pole: Pole,
    /// FANUC parameter 5400#0 RIN: the G68 angle R is incremental under G91.
    pub rotation_angle_incremental: bool,
    /// Work-offset selections so far (a Siemens SAVE return re-selects after one).
    pub wo_selections: u64,
    /// Last programmed end point (workpiece frame), for `#5001+`/`$P_EP`.
    pub last_m: f64,
    pub last_n: f64,
    /// Last G code of FANUC groups without an effect on the trace, for `#4007`.. reads:
    /// 07 cutter compensation, 08 length compensation, 09 canned cycle, 10 return level,
    /// 15 path mode (values ×10: 400 = G40).
    pub group_g: [(u8, i64); 5],
    /// Semantics::incremental_travels_offset.
    pub incr_travels_offset: bool,
    /// The offset in effect when each axis last moved (for the rule above).
    pub applied: [f64; 9],
    /// `RunOptions::probe_contact`: where along a probe move the skip signal arrives.
    pub probe_contact: Option<f64>,
    /// The probe test inputs and what the controls keep of probing moves ([`probe`]).
    pub probe: probe::Probe,
    /// The block measures with Siemens MEAW (the move does not stop at the trigger).
    pub meaw: bool,
    /// `(inc, 1.0 / inc, decimal)` of the metric and inch increments, for
    /// [`round_to_scaled`]; `decimal`: [`is_decimal_scale`], so [`round_to_decimal`] does.
    scales: [(f64, f64, bool); 2],
    /// Buffers of [`Machine::apply`], kept to save two allocations per block.
    gs_buf: Vec<(f64, Span)>,
    ms_buf: Vec<(f64, Span)>,
    /// The trace position on the 0.001 grid and the move given to sinks ([`grid::Grid`]).
    grid: grid::Grid,
    /// The drilling cycle mode and the data it keeps between holes.
    pub cycle: super::cycles::State,
    /// `RunOptions::expand_cycles`: holes are written as their moves.
    pub expand: Option<super::cycles::expand::Retracts>,
    /// Tool length and cutter radius compensation ([`comp`]).
    pub comp: comp::Comp,
    /// Chamfers and roundings: a held move, Siemens modal rounding ([`corners`]).
    pub corners: corners::Corners,
    /// The Siemens feed group (`FGROUP`) and which moves' feeds [`path_feed`] works out.
    pub fgroup: path_feed::Group,
}

impl Machine {
    pub fn new(fanuc: bool, alarms: AlarmNumbers, scaling: bool, inc_mm: f64) -> Machine {
        Machine {
            fanuc,
            master_spindle: (!fanuc).then(|| "1".to_string()),
            haas: false,
            tool_data: Default::default(),
            alarms,
            scaling,
            inc_mm,
            modal: Modal {
                motion: Motion::Rapid,
                plane: Plane::XY,
                absolute: true,
                inch: false,
                inch_feed: false,
                per_rev: false,
            },
            feed: None,
            speed: 0.0,
            spindle: SpindleDir::Stop,
            tool_sel: None,
            tool: None,
            d: 0.0,
            h: 0.0,
            coolant: false,
            pos: [0.0; 9],
            seen: [false; 9],
            offsets: vec![[0.0; 9]; 100],
            wo: if fanuc { 1 } else { 0 },
            frame: [0.0; 9],
            trans: [0.0; 9],
            local: [0.0; 9],
            g92: [0.0; 9],
            inter: [None; 9],
            xf: Xform::ID,
            rot: None,
            scale: None,
            mirror: [None; 3],
            fresh: 0,
            kept: [(0.0, 0.0); 3],
            framed: false,
            rotation_angle_incremental: false,
            polar: false,
            pole: Pole::default(),
            wo_selections: 0,
            last_m: 0.0,
            last_n: 0.0,
            group_g: [(7, 400), (8, 490), (9, 800), (10, 980), (15, 640)],
            probe_contact: None,
            probe: probe::Probe::default(),
            meaw: false,
            expand: None,
            incr_travels_offset: !fanuc,
            applied: [0.0; 9],
            scales: [inc_mm, inc_mm / 10.0].map(|inc| (inc, 1.0 / inc, is_decimal_scale(1.0 / inc))),
            gs_buf: Vec::new(),
            ms_buf: Vec::new(),
            grid: grid::Grid::new(inc_mm),
            cycle: super::cycles::State::default(),
            comp: comp::Comp::default(),
            corners: corners::Corners::default(),
            fgroup: path_feed::Group::new(fanuc),
        }
    }

    /// The offset added to a workpiece position to get the machine position.
    #[inline]
    pub fn active_offset(&self, axis: usize) -> f64 {
        if self.fanuc {
            // FANUC: external + selected table, live (a `#5221=` write acts at once).
            self.offsets[0][axis] + self.offsets[self.wo][axis] + self.local[axis] + self.g92[axis]
        } else {
            self.frame[axis] + self.trans[axis]
        }
    }

    /// Workpiece-frame position of every axis (for the trace and position variables).
    pub fn work_pos(&self, axis: usize) -> f64 {
        self.pos[axis] - self.active_offset(axis)
    }

    /// The trace position: the machine-frame position of every axis positioned so far
    /// (workpiece zero + active work offset, docs/semantics.md).
    #[inline]
    pub fn trace_pos(&self) -> Axes {
        let mut a = [None; 9];
        for (i, slot) in a.iter_mut().enumerate() {
            if self.seen[i] {
                *slot = Some(clean(self.pos[i]));
            }
        }
        a
    }

    /// Records `gi` as the last G code of FANUC group `group` (for `#4001`.. reads).
    pub fn set_group_g(&mut self, group: u8, gi: i64) {
        if let Some(slot) = self.group_g.iter_mut().find(|s| s.0 == group) {
            slot.1 = gi;
        }
    }

    /// Selects offset table `n` (Siemens copies the frame now).
    pub fn select_offset(&mut self, n: usize) {
        self.wo = n.min(self.offsets.len() - 1);
        if !self.fanuc {
            self.frame = self.offsets[self.wo];
        }
    }

    /// Runs one block's NC words. Events go to `out` in the trace's in-block order.
    /// `stop_message`: a FANUC `#3006` stop of this block.
    pub fn apply(
        &mut self,
        words: &[WordVal],
        stop_message: Option<String>,
        out: &mut Vec<(Event, Span)>,
        warns: &mut Vec<Warn>,
    ) -> Result<BlockEffect, Fault> {
        // The G and M lists are reused from block to block.
        let (mut gs, mut ms) = (std::mem::take(&mut self.gs_buf), std::mem::take(&mut self.ms_buf));
        gs.clear();
        ms.clear();
        // Polar coordinates become the plane's Cartesian words first (polar.rs).
        let polar = match self.polar_words(words) {
            Ok(p) => p,
            Err(e) => {
                (self.gs_buf, self.ms_buf) = (gs, ms);
                return Err(e);
            }
        };
        let words = polar.as_deref().unwrap_or(words);
        let (before, start) = (self.pos, out.len());
        let r = self.apply_words(words, stop_message, out, warns, &mut gs, &mut ms);
        (self.gs_buf, self.ms_buf) = (gs, ms);
        let eff = match r {
            Ok(eff) => eff,
            Err(e) => {
                self.corners.word = None;
                return Err(e);
            }
        };
        if self.corners.word.is_some() || self.corners.held.is_some() {
            let span = words.iter().map(|w| w.span).reduce(Span::to).unwrap_or_default();
            self.corner_after_block(before, out, start, eff.end.is_some() || eff.ret, span)?;
        }
        Ok(eff)
    }

    fn apply_words(
        &mut self,
        words: &[WordVal],
        stop_message: Option<String>,
        out: &mut Vec<(Event, Span)>,
        warns: &mut Vec<Warn>,
        gs: &mut Vec<(f64, Span)>,
        ms: &mut Vec<(f64, Span)>,
    ) -> Result<BlockEffect, Fault> {
        let mut eff = BlockEffect::default();
        let mut axes: [Option<(&WordVal, f64)>; 9] = [None; 9];
        let mut ijk: [Option<(&WordVal, f64)>; 3] = [None; 3];
        let (mut r, mut ar, mut f, mut s, mut p, mut l) = (None, None, None, None, None, None);
        let mut t: Option<(ToolId, Span)> = None;
        let mut block_span = Span::default();
        // Siemens MEAS=/MEAW=: the probe number.
        let mut measuring: Option<usize> = None;
        // FANUC Q is read by the drilling cycles; anywhere else it is ignored (a warning).
        let mut q_word = None;
        let (mut q_val, mut e_word) = (None, None);
        let mut lookahead = false;
        // Siemens G74/G75: the machine axes named (`Z1=0`) and the fixed point (`FP=`).
        let (mut named, mut fp) = (Vec::new(), None);
        let mut bc = comp::BlockComp::default();
        let (mut corner, mut rndm) = (None, None);
        for w in words {
            block_span = if block_span == Span::default() { w.span } else { block_span.to(w.span) };
            let num = match &w.val {
                WV::Num(x) => Some(*x),
                WV::Str(_) => None,
            };
            let a: &str = &w.addr;
            // One-letter addresses with a number (nearly every word) by their byte; the
            // match below decides the same for them, and everything else.
            if let (&[c], Some(x)) = (a.as_bytes(), num) {
                let handled = match c {
                    b'G' => {
                        gs.push((x, w.span));
                        true
                    }
                    b'M' => {
                        ms.push((round_half_away(x), w.span));
                        true
                    }
                    b'I' | b'J' | b'K' => {
                        ijk[usize::from(c - b'I')] = Some((w, x));
                        true
                    }
                    b'R' if self.fanuc => {
                        r = Some((w, x));
                        true
                    }
                    b'F' => {
                        f = Some((w, x));
                        true
                    }
                    b'S' => {
                        s = Some((w, x));
                        true
                    }
                    b'P' => {
                        p = Some((w, x));
                        true
                    }
                    b'L' => {
                        l = Some(x);
                        true
                    }
                    b'D' => {
                        bc.d = Some((x, w.span));
                        true
                    }
                    b'H' if self.fanuc => {
                        bc.h = Some((x, w.span));
                        true
                    }
                    b'H' => {
                        self.h = round_half_away(x);
                        true
                    }
                    c => match axis_index(c) {
                        Some(i) => {
                            axes[i] = Some((w, x));
                            true
                        }
                        None => false,
                    },
                };
                if handled {
                    continue;
                }
            }
            match (a, num) {
                ("T", _) => {
                    t = Some((
                        match &w.val {
                            WV::Str(s) => ToolId::Name(s.clone()),
                            WV::Num(x) => ToolId::Number(round_half_away(*x)),
                        },
                        w.span,
                    ))
                }
                (_, None) => return Err(Fault::alarm(0, format!("address {a} needs a number, not a string"), w.span)),
                ("G", Some(x)) => gs.push((x, w.span)),
                ("M", Some(x)) => ms.push((round_half_away(x), w.span)),
                // `M1=3` / `S1=1000`: the master spindle addressed by its number.
                (a, Some(x))
                    if self.master_spindle.as_deref().is_some_and(|n| a.get(1..) == Some(n)) && a.starts_with('M') =>
                {
                    ms.push((round_half_away(x), w.span))
                }
                (a, Some(x))
                    if self.master_spindle.as_deref().is_some_and(|n| a.get(1..) == Some(n)) && a.starts_with('S') =>
                {
                    s = Some((w, x))
                }
                ("I", Some(x)) => ijk[0] = Some((w, x)),
                ("J", Some(x)) => ijk[1] = Some((w, x)),
                ("K", Some(x)) => ijk[2] = Some((w, x)),
                ("R", Some(x)) if self.fanuc => r = Some((w, x)),
                ("CR", Some(x)) => r = Some((w, x)),
                ("AR", Some(x)) => ar = Some(x),
                ("F", Some(x)) => f = Some((w, x)),
                ("S", Some(x)) => s = Some((w, x)),
                ("P", Some(x)) => p = Some((w, x)),
                ("L", Some(x)) => l = Some(x),
                ("Q", Some(x)) if self.fanuc => {
                    q_word = Some(w.span);
                    q_val = Some(x);
                }
                // Haas G187's corner tolerance; anywhere else ignored (a warning, below).
                ("E", Some(x)) if self.haas => e_word = Some((w.span, x)),
                ("D", Some(x)) => bc.d = Some((x, w.span)),
                ("H", Some(x)) if self.fanuc => bc.h = Some((x, w.span)),
                ("H", Some(x)) => self.h = round_half_away(x),
                (a, Some(x)) if a.len() == 1 && axis_index(a.as_bytes()[0]).is_some() => {
                    if let Some(i) = axis_index(a.as_bytes()[0]) {
                        axes[i] = Some((w, x));
                    }
                }
                // A measuring move (`probe.rs`): where it stops is a test input.
                ("MEAS" | "MEAW", v) => (measuring, self.meaw) = (Some(self.measuring_probe(v, w.span)?), a == "MEAW"),
                ("FP", Some(x)) if !self.fanuc => fp = Some((w, x)),
                (a, _) if !self.fanuc && Machine::machine_axis(a).is_some() => {
                    named.extend(Machine::machine_axis(a).map(|i| (i, w.span)))
                }
                (
                    "CIP" | "CT" | "ASPLINE" | "BSPLINE" | "CSPLINE" | "POLY" | "TURN" | "AP" | "RP" | "I1" | "J1"
                    | "K1",
                    _,
                ) => return Err(unsupported(&format!("{a} (circle/spline/polar motion) is not modelled"), w.span)),
                // Contour geometry the trace would otherwise show as a sharp corner or the
                // plain end point: refused, never ignored. `RNDM=0` / `OFFN=0` (off) change nothing.
                ("OFFN", Some(0.0)) => {}
                ("CHF" | "CHR" | "RND", Some(x)) => {
                    if corner.is_some() {
                        return Err(corners::two_in_one_block(w.span));
                    }
                    corner = Some((w, x))
                }
                ("RNDM", Some(x)) if !self.fanuc => rndm = Some((w, x)),
                ("FRC" | "FRCM", _) if !self.fanuc => return Err(corners::own_feed(a, w.span)),
                ("ANG" | "OFFN", _) => {
                    return Err(unsupported(&format!("{a} (contour angle or contour offset) is not modelled"), w.span))
                }
                (a, _) => {
                    warns.push(("NC405", format!("address {a} has no effect on the trace and is ignored"), w.span))
                }
            }
        }

        // G codes: modal state first; one-shot meanings remembered.
        let (mut dwell, mut g53, mut g10, mut probe) = (false, false, false, measuring);
        let mut g31 = None;
        let (mut cycle_g, mut motion_g) = (None, None);
        let (mut g52, mut g68, mut g51, mut g92, mut home, mut g29) = (false, false, None, false, None, false);
        for &(g, span) in gs.iter() {
            let gi = g_index(g);
            if matches!(gi, 0 | 10 | 20 | 30) {
                motion_g = Some(span);
            }
            if !(gi == 520 && self.fanuc && self.g52_keeps_shift(&axes)) {
                self.check_fanuc_frames(gi, span)?;
            }
            // `Modal::g` changes nothing for a code it does not take.
            if self.modal.g(self.fanuc, gi) {
                continue;
            }
            match gi {
                40 => dwell = true,
                100 => g10 = true,
                310 if self.fanuc => {
                    probe = Some(1);
                    g31 = Some(span);
                }
                530 | 1530 => g53 = true,
                // FANUC `G54 Pn` is `G54.1 Pn` (extended offsets).
                540 | 541 if self.fanuc && (gi == 541 || p.is_some()) => self.extended_offset(p, out, span)?,
                540..=590 if gi % 10 == 0 && self.fanuc => self.select_work_offset((gi / 10 - 53) as usize, out, span),
                540..=570 if gi % 10 == 0 => self.select_work_offset((gi / 10 - 53) as usize, out, span),
                5000 if !self.fanuc => self.select_work_offset(0, out, span),
                5050..=5990 if !self.fanuc && gi % 10 == 0 => {
                    self.select_work_offset((gi / 10 - 500) as usize, out, span)
                }
                520 if self.fanuc => g52 = true,
                920 if self.fanuc => g92 = true,
                680 if self.fanuc => g68 = true,
                690 if self.fanuc => self.g69(),
                // G51 / G51.1, and their cancels G50 / G50.1.
                510 | 511 if self.fanuc => g51 = Some(gi),
                500 if self.fanuc => {
                    self.scale = None;
                    self.fanuc_compose();
                }
                501 if self.fanuc => g51 = Some(gi),
                // Haas mirror image: G51.1/G50.1 about the work zero (haas_mirror.rs).
                1010 | 1000 if self.fanuc && self.haas => g51 = Some(gi),
                // Polar coordinates and poles: their words were made Cartesian (polar.rs).
                160 | 150 if self.fanuc => {}
                1100 | 1110 | 1120 if !self.fanuc => {}
                280 if self.fanuc => home = Some(refs::Home { point: 1, via_words: true }),
                290 if self.fanuc => g29 = true,
                300 if self.fanuc => {
                    home = Some(refs::Home { point: self.second_reference(p, span)?, via_words: true })
                }
                // Compensation (comp.rs): applied after the block's tool change.
                400 | 410 | 420 => bc.radius_g = Some((gi, span)),
                430 | 440 | 490 if self.fanuc => bc.length_g = Some((gi, span)),
                740 if !self.fanuc => {
                    self.approach_alone(words, 74.0)?;
                    home = Some(refs::Home { point: 1, via_words: false })
                }
                750 if !self.fanuc => {
                    self.approach_alone(words, 75.0)?;
                    home = Some(refs::Home { point: self.fixed_point(fp, span)?, via_words: false })
                }
                // Path control, compensation (the trace holds programmed positions), cycle
                // cancel, exact stop: no effect on the trace.
                // Drilling cycles (eval::cycles): select, cancel, return level.
                gi if self.fanuc && super::cycles::fanuc::is_cycle_g(gi) => cycle_g = Some((gi, span)),
                800 if self.fanuc => {
                    self.cycle.cancel();
                    self.set_group_g(9, 800);
                }
                980 | 990 if self.fanuc => {
                    self.cycle.retract = if gi == 980 { Retract::Initial } else { Retract::R };
                    self.set_group_g(10, gi);
                }
                90 | 600 | 610 | 620 | 630 | 640 | 430 | 440 | 490 | 800 | 6010 | 6020 | 6410 | 6420 | 150 | 670
                | 690 | 970 | 960 | 980 | 990 => {
                    let group = match gi {
                        430 | 440 | 490 => 8,
                        800 => 9,
                        980 | 990 => 10,
                        610..=640 => 15,
                        _ => 0,
                    };
                    self.set_group_g(group, gi);
                    let inert = || format!("G{} has no effect on the trace", fmt_g(g));
                    warns.push(match lookahead::smoothing(gi, self.fanuc) {
                        Some(what) => (lookahead::NOT_COMPARED, what, span),
                        // Siemens G43/G44/G49 (ISO mode): not in the `comp` event.
                        None if matches!(gi, 430..=490) => (COMPENSATION_NOTE, inert(), span),
                        None => ("NC405", inert(), span),
                    });
                }
                920 | 520 | 680 | 160 => {
                    return Err(unsupported(
                        &format!("G{} ({}) is not modelled", fmt_g(g), refs::unmodelled_frame(gi)),
                        span,
                    ))
                }
                // Look-ahead modes (lookahead.rs): the path is the same; not compared.
                gi if self.fanuc && lookahead::is_mode_g(gi, self.haas) => {
                    lookahead = true;
                    self.lookahead_g(gi, p.map(|p| p.1), q_val, e_word.map(|e| e.1), span, warns)?
                }
                _ => return Err(unsupported(&refs::unmodelled_g(&fmt_g(g), gi, self.haas), span)),
            }
        }

        if self.fanuc {
            super::cycles::fanuc::select(self, cycle_g, motion_g)?;
        }
        if let (Some((span, _)), false) = (e_word, lookahead) {
            warns.push(("NC405", "address E has no effect on the trace and is ignored".into(), span));
        }
        let q_word = q_word.filter(|_| !lookahead);
        if let (Some(span), None) = (q_word, self.cycle.active) {
            warns.push(("NC405", "address Q has no effect on the trace and is ignored".into(), span));
        }
        if g10 {
            if self.g10(l, [p, r], &axes, out, warns, block_span)? {
                // A write to the active (or the external) offset acts at once: as a re-selection.
                out.push((Event::WorkOffset { n: self.wo as u32 }, block_span));
            }
            return Ok(eff);
        }
        if g52 {
            self.local_shift(&axes, block_span)?;
            return Ok(eff);
        }
        if g92 {
            self.g92_shift(&axes, block_span)?;
            return Ok(eff);
        }
        if g68 {
            self.g68(&axes, ijk.iter().any(Option::is_some), r, block_span)?;
            return Ok(eff);
        }
        match g51 {
            Some(510) => self.g51(&axes, &ijk, p, block_span)?,
            Some(g @ (1010 | 1000)) => self.haas_mirror(g == 1010, &axes, block_span)?,
            Some(g) => self.g51_1(g == 511, &axes, block_span)?,
            None => {}
        }
        if g51.is_some() {
            return Ok(eff);
        }
        if home.is_none() {
            for (_, span) in named.drain(..) {
                warns.push(("NC405", "a machine-axis word outside G74/G75 has no effect on the trace".into(), span));
            }
        }

        // F, S, T.
        // Siemens `G4 F..` is the dwell time, not a feed.
        if let Some((_, x)) = f {
            if !dwell {
                self.feed = Some(self.feed_value(x));
                self.fgroup.feed_inch = self.modal.inch_feed;
            }
        }
        let mut speed_changed = false;
        if let Some((_, x)) = s {
            if !dwell || self.fanuc {
                let x = if self.fanuc { round_half_away(x) } else { x };
                speed_changed = x != self.speed;
                self.speed = x;
            }
        }
        if let Some((id, _)) = t {
            self.tool_sel = Some(id);
        }

        // 1. tool change
        let mut changed = false;
        for &(m, span) in ms.iter() {
            if m == 6.0 {
                match &self.tool_sel {
                    Some(id) => {
                        self.tool = Some(id.clone());
                        out.push((Event::Tool { tool: id.clone() }, span));
                        changed = true;
                    }
                    None => warns.push(("NC405", "M6 without a selected tool".into(), span)),
                }
            }
        }
        // 1a. compensation, in force from this block's motion on
        self.apply_comp(&bc, changed, out, warns, block_span);
        // 2. spindle start or S change
        let mut spindle_cmd = false;
        for &(m, span) in ms.iter() {
            let dir = match m as i64 {
                3 => SpindleDir::Cw,
                4 => SpindleDir::Ccw,
                _ => continue,
            };
            spindle_cmd = true;
            self.spindle = dir;
            out.push((Event::Spindle { rpm: self.speed, dir }, span));
        }
        let has_m5 = ms.iter().any(|m| m.0 == 5.0);
        if !spindle_cmd && !has_m5 && speed_changed && self.spindle != SpindleDir::Stop {
            out.push((Event::Spindle { rpm: self.speed, dir: self.spindle }, s.map_or(block_span, |w| w.0.span)));
        }
        // 3. coolant on
        for &(m, span) in ms.iter() {
            if m == 7.0 || m == 8.0 {
                self.coolant = true;
                out.push((Event::Coolant { on: true }, span));
            }
        }
        // The frame is judged where the corner is made (`corners`: in the plane of the corner).
        let plain =
            !(g29 || home.is_some() || dwell || g53 || probe.is_some() || self.cycle.active.is_some() || self.polar);
        self.corner_words(corner, rndm, plain)?;
        // 4. motion or dwell
        if probe.is_some() {
            self.probe_allowed(g31, p.map(|w| w.0.span), home.is_some() || dwell || g53 || g29, block_span)?;
        }
        if g29 {
            eff.moved = self.return_from_reference(&axes, out, block_span)?;
        } else if let Some(h) = home {
            let named: Vec<usize> = named.iter().map(|n| n.0).collect();
            eff.moved = self.reference_return(h, &axes, &named, out, block_span)?;
        } else if dwell {
            let secs = self.dwell_seconds(&axes, p, f, s, block_span)?;
            out.push((Event::Dwell { seconds: secs }, block_span));
        } else if self.cycle.active.is_some() && !g53 {
            eff.moved = super::cycles::fanuc::holes(self, words, out, warns, block_span)?;
        } else if self.framed && !g53 {
            eff.moved = self.framed_motion(&axes, &ijk, r, ar, probe.is_some(), out, block_span)?;
        } else {
            eff.moved = self.motion_block(&axes, &ijk, r, ar, g53, probe, out, block_span)?;
        }
        // 5. spindle stop, coolant off
        for &(m, span) in ms.iter() {
            if m == 5.0 {
                self.spindle = SpindleDir::Stop;
                out.push((Event::Spindle { rpm: self.speed, dir: SpindleDir::Stop }, span));
            }
        }
        for &(m, span) in ms.iter() {
            if m == 9.0 {
                self.coolant = false;
                out.push((Event::Coolant { on: false }, span));
            }
        }
        // 6. M0/M1 and #3006
        for &(m, span) in ms.iter() {
            if m == 0.0 || m == 1.0 {
                out.push((Event::Stop { optional: m == 1.0, message: None }, span));
            }
        }
        if let Some(text) = stop_message {
            out.push((Event::Stop { optional: false, message: Some(text) }, block_span));
        }
        for &(m, span) in ms.iter() {
            self.last_m = m;
            match m as i64 {
                0 | 1 | 3 | 4 | 5 | 6 | 7 | 8 | 9 => {}
                // Rigid tapping for the tapping cycles that follow (not visible in the trace).
                29 if self.fanuc => self.cycle.rigid = true,
                30 => eff.end = Some("M30"),
                2 => eff.end = Some("M2"),
                99 | 17 => eff.ret = true,
                _ => warns.push((
                    "NC405",
                    format!("M{} is machine-specific and has no meaning here; nothing emitted", m),
                    span,
                )),
            }
        }
        Ok(eff)
    }
}

/// Removes float noise below the trace precision and negative zero.
pub(crate) fn clean(x: f64) -> f64 {
    let r = super::value::round(x * 1e9) / 1e9;
    if r == 0.0 {
        0.0
    } else {
        r
    }
}
