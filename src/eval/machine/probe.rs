//! Probing moves (FANUC `G31`, Siemens `MEAS=`/`MEAW=`): where the move stops (the test
//! input of `RunOptions::probes`) and the values the controls keep of it. FANUC stores the
//! position where the skip signal arrived, or the end point when it did not, in `#5061+`
//! (every axis, workpiece coordinates); Siemens writes `$AA_MM` (machine) and `$AA_MW`
//! (workpiece) only when the probe switched, only for the axes programmed in the block, and
//! sets `$AC_MEA[n]` (0 at the start of every measuring block). Sources in docs/semantics.md
//! (Probing).

use super::*;
use crate::eval::probe::ProbeInput;

/// How far a trigger point may lie from the programmed line (the trace tolerance).
const ON_LINE: f64 = 1e-6;

#[derive(Clone, Debug)]
pub struct Probe {
    /// The test inputs, one per probing move in run order.
    pub inputs: Vec<ProbeInput>,
    /// Probing moves made so far (the index of the next input).
    pub moves: usize,
    /// FANUC `#5061+`: the skip position, workpiece coordinates, mm.
    pub skip: [f64; 9],
    /// Siemens `$AA_MM`: the measured position, machine coordinates, mm.
    pub meas_m: [f64; 9],
    /// Siemens `$AA_MW`: the measured position, workpiece coordinates, mm.
    pub meas_w: [f64; 9],
    /// Siemens `$AC_MEA[1]`, `$AC_MEA[2]`: the probe switched in the last measuring block.
    pub mea: [bool; 2],
    /// Siemens: the length of the cutting edge active at the last hit, which the kept
    /// machine position `$AA_MM[Z]` holds, or why the run does not know it (then `$AA_MM`
    /// reads are refused, NC534).
    pub edge_length: Result<f64, String>,
    /// FANUC: the tool length offset `#5063` includes (G43 +, G44 −, the H register's
    /// geometry plus wear at the G31, on Z), or why it is not known (then `#5061+` reads are
    /// refused, NC534). docs/semantics.md, Probing and position reads.
    pub length: Result<f64, String>,
}

impl Default for Probe {
    fn default() -> Probe {
        Probe {
            inputs: Vec::new(),
            moves: 0,
            skip: [0.0; 9],
            meas_m: [0.0; 9],
            meas_w: [0.0; 9],
            mea: [false; 2],
            edge_length: Ok(0.0),
            length: Ok(0.0),
        }
    }
}

fn error(code: &'static str, msg: String, span: Span, hint: &str) -> Fault {
    Fault::Error(Box::new(
        crate::diag::Diagnostic::error(code, msg).primary(usize::MAX, span, "this probing move").hint(hint),
    ))
}

fn axes_text(p: &[f64; 9], which: impl Fn(usize) -> bool) -> String {
    let mut s = String::new();
    for (i, v) in p.iter().enumerate().filter(|(i, _)| which(*i)) {
        if !s.is_empty() {
            s.push(' ');
        }
        s.push_str(&format!("{}={}", crate::eval::trace::AXES[i], crate::eval::value::fmt_num(clean(*v))));
    }
    s
}

impl Machine {
    /// The probe number of a Siemens `MEAS=`/`MEAW=` value: 1 or 2, the sign the edge
    /// (rising / falling), both of which the test input decides alike.
    pub(super) fn measuring_probe(&self, v: Option<f64>, span: Span) -> Result<usize, Fault> {
        match v.map(round_half_away) {
            Some(n) if n.abs() == 1.0 || n.abs() == 2.0 => Ok(n.abs() as usize),
            _ => Err(error(
                "NC531",
                format!(
                    "MEAS=/MEAW= takes the probe 1 or 2 (negative: the falling edge), not {}",
                    v.map_or("a string".into(), crate::eval::value::fmt_num)
                ),
                span,
                "write MEAS=1 (probe 1, rising edge)",
            )),
        }
    }

    /// Where the probing move from `self.pos` towards `target` (machine positions) stops,
    /// and whether the probe switched: the next test input, or the old fraction of
    /// `RunOptions::probe_contact`, or no trigger.
    pub(super) fn probe_stop(&mut self, target: &mut [f64; 9], span: Span) -> Result<Option<[f64; 9]>, Fault> {
        let from = self.pos;
        let input = self.probe.inputs.get(self.probe.moves).cloned();
        self.probe.moves += 1;
        let t = match input {
            Some(ProbeInput::Miss) => return Ok(None),
            None if self.probe.inputs.is_empty() => match self.probe_contact {
                Some(frac) => frac,
                None => return Ok(None),
            },
            None => return Ok(None),
            Some(ProbeInput::At(point)) => {
                let moved: Vec<(usize, f64)> = point.iter().map(|&(a, _)| (a, target[a] - from[a])).collect();
                // The parameter along the line from the named axis that travels most.
                let along = moved.iter().zip(&point).max_by(|x, y| x.0 .1.abs().total_cmp(&y.0 .1.abs()));
                let t = match along {
                    Some(((_, d), &(a, v))) if d.abs() > ON_LINE => (v - from[a]) / d,
                    _ if (0..9).all(|i| (target[i] - from[i]).abs() <= ON_LINE) => 1.0,
                    _ => {
                        return Err(error(
                            "NC530",
                            format!(
                                "the probe input {} names no axis this probing move travels (from {} to {})",
                                axes_text_of(&point),
                                axes_text(&from, |i| target[i] != from[i]),
                                axes_text(target, |i| target[i] != from[i]),
                            ),
                            span,
                            "give the trigger position of an axis that moves in this block (--probe X=..)",
                        ))
                    }
                };
                let off_line = point.iter().any(|&(a, v)| (from[a] + (target[a] - from[a]) * t - v).abs() > ON_LINE);
                if !(-ON_LINE..=1.0 + ON_LINE).contains(&t) || off_line {
                    return Err(error(
                        "NC530",
                        format!(
                            "the probe input {} does not lie on this probing move (from {} to {})",
                            axes_text_of(&point),
                            axes_text(&from, |i| self.seen[i] || target[i] != from[i]),
                            axes_text(target, |i| self.seen[i] || target[i] != from[i]),
                        ),
                        span,
                        "give a point between the start and the end of the move (trace coordinates), or `miss`",
                    ));
                }
                t.clamp(0.0, 1.0)
            }
        };
        let mut at = *target;
        for (to, from) in at.iter_mut().zip(from) {
            *to = from + (*to - from) * t;
        }
        // Siemens MEAW measures without deleting the distance to go: the move goes on.
        if !self.meaw {
            *target = at;
        }
        Ok(Some(at))
    }

    /// Records what the controls keep of a probing move that has just ended at `self.pos`.
    /// `programmed`: the axes with a word in the block; `probe`: the Siemens probe number
    /// (`None` for FANUC).
    pub(super) fn probe_record(&mut self, hit: Option<[f64; 9]>, programmed: &[bool; 9], probe: Option<usize>) {
        if self.fanuc {
            self.probe.length = self.length_offset();
            let at = hit.unwrap_or(self.pos);
            for (i, x) in at.iter().enumerate() {
                self.probe.skip[i] = x - self.active_offset(i);
            }
            return;
        }
        let n = probe.unwrap_or(1).clamp(1, 2);
        self.probe.mea[n - 1] = hit.is_some();
        if let Some(at) = hit {
            let length = self.edge_length();
            for i in (0..9).filter(|&i| programmed[i]) {
                // The machine position is the tool carrier's: the tip plus the edge's length on Z.
                self.probe.meas_m[i] = at[i] + if i == 2 { *length.as_ref().unwrap_or(&0.0) } else { 0.0 };
                self.probe.meas_w[i] = at[i] - self.active_offset(i);
            }
            self.probe.edge_length = length;
        }
    }
}

impl Machine {
    /// The FANUC tool length offset in force on Z (G43 adds, G44 subtracts the H register,
    /// memory C: geometry `#11000+H` plus wear `#10000+H`, F-MEMC), for the position reads
    /// that include it; `Err` says why the run does not know it.
    pub fn length_offset(&self) -> Result<f64, String> {
        if self.comp.length_g == 490 || self.h == 0.0 {
            return Ok(0.0);
        }
        if self.haas {
            return Err("on a Haas profile, whose offset tables (#2001+) the run does not take as tool data".into());
        }
        if self.modal.plane != crate::eval::trace::Plane::XY {
            return Err("outside G17 (the axis G43 offsets then depends on the length compensation type)".into());
        }
        if self.modal.sys_inch() {
            return Err("under G20 (the offset values are kept in the machine's unit)".into());
        }
        let h = self.h as i64;
        let value = |n: i64| self.tool_data.get(&format!("#{n}")).copied();
        match (value(11000 + h), value(10000 + h)) {
            (Some(g), Some(w)) => Ok(if self.comp.length_g == 440 { -(g + w) } else { g + w }),
            (g, _) => Err(format!(
                "with the length of H{h} not given (--set '#{}=…')",
                if g.is_none() { 11000 + h } else { 10000 + h }
            )),
        }
    }

    /// The inputs that give the run the length a position read includes: the H register's
    /// geometry and wear (FANUC), the active edge's length 1 and its wear (Siemens).
    pub fn length_inputs(&self) -> String {
        let (a, b) = if self.fanuc {
            let h = self.h as i64;
            (format!("#{}", 11000 + h), format!("#{}", 10000 + h))
        } else {
            let t = match &self.tool {
                Some(ToolId::Number(t)) => crate::eval::value::fmt_num(*t),
                _ => "t".into(),
            };
            let d = self.comp.edge;
            (format!("$TC_DP3[{t},{d}]"), format!("$TC_DP12[{t},{d}]"))
        };
        format!("--set '{a}=…' --set '{b}=…', or header lines `nctrans: set {a}=…` and `nctrans: set {b}=…`")
    }

    /// The length of the Siemens cutting edge active (length 1 `$TC_DP3` plus its wear
    /// `$TC_DP12` of the tool in the spindle, S-DP), which machine positions (`$AA_IM`,
    /// `$AA_MM`) hold on Z under G17: the tool carrier reference point stands the length
    /// above the tip. `Err` says why the run does not know it.
    pub fn edge_length(&self) -> Result<f64, String> {
        let d = self.comp.edge;
        if d == 0 {
            return Ok(0.0);
        }
        if self.modal.plane != crate::eval::trace::Plane::XY {
            return Err("outside G17 (length 1 of a milling tool lies on the axis normal to the plane)".into());
        }
        if self.modal.sys_inch() {
            return Err("under G700 (the edge data are kept in the basic system)".into());
        }
        let t = match &self.tool {
            Some(ToolId::Number(t)) => *t,
            Some(ToolId::Name(n)) => return Err(format!("with the tool {n:?} named (its edge data are numbered)")),
            None => return Err(format!("with edge D{d} active and no tool in the spindle")),
        };
        let tn = crate::eval::value::fmt_num(t);
        let value = |k: u32| self.tool_data.get(&format!("$TC_DP{k}[{tn},{d}]")).copied();
        match (value(3), value(12)) {
            (Some(g), Some(w)) => Ok(g + w),
            (g, _) => Err(format!(
                "with the length of edge D{d} of tool {tn} not given (--set '$TC_DP{}[{tn},{d}]=…')",
                if g.is_none() { 3 } else { 12 }
            )),
        }
    }
}

fn axes_text_of(point: &[(usize, f64)]) -> String {
    point
        .iter()
        .map(|&(a, v)| format!("{}={}", crate::eval::trace::AXES[a], crate::eval::value::fmt_num(v)))
        .collect::<Vec<_>>()
        .join(",")
}

impl Machine {
    /// Refuses the probing blocks the evaluator does not model (each named), before any
    /// motion: FANUC G31 P (multi-step skip), a probing move combined with a reference
    /// return, dwell or G53, in a drilling cycle mode, under cutter radius compensation
    /// (FANUC alarm PS0035; Siemens path), and a Siemens measuring block outside G1.
    pub(super) fn probe_allowed(
        &self,
        g31: Option<Span>,
        p: Option<Span>,
        other: bool,
        span: Span,
    ) -> Result<(), Fault> {
        let what = if self.fanuc { "G31" } else { "MEAS=/MEAW=" };
        if let (Some(_), Some(p)) = (g31, p) {
            return Err(error(
                "NC532",
                "G31 P (multi-step skip: the skip signal chosen by P) is not modelled".into(),
                p,
                "write G31 without P (skip signal 1)",
            ));
        }
        let why = if other {
            Some("combined with G28/G30/G74/G75, a dwell or G53 in one block")
        } else if self.cycle.active.is_some() {
            Some("in a drilling cycle mode")
        } else if self.comp.side.is_some() {
            Some("under cutter radius compensation (G41/G42)")
        } else if !self.fanuc && self.modal.motion != Motion::Linear {
            Some("outside G1 (a rapid or circular measuring block)")
        } else {
            None
        };
        match why {
            Some(why) => Err(error(
                "NC533",
                format!("a probing move ({what}) {why} is not modelled"),
                span,
                "probe with a G1 move of its own, with G40 and no cycle in force",
            )),
            None => Ok(()),
        }
    }
}
