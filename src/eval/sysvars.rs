//! System variables (`docs/semantics.md`, System variables): the common FANUC `#1000+` and Siemens `$` ones.
//! Reading or writing one that is not modelled is an error naming it, never a silent 0.

use super::exec::Interp;
use super::expr;
use super::fault::Fault;
use super::trace::{axis_index, Event, ToolId};
use super::value::{round_half_away, Value};
use crate::diag::Diagnostic;
use crate::ir::{Expr, ExprKind};
use crate::span::Span;

impl Interp<'_> {
    fn unmodelled(&self, name: &str, span: Span) -> Fault {
        Fault::error(
            Diagnostic::error("NC400", format!("system variable {name} is not modelled by the evaluator"))
                .primary(self.file(), span, "used here")
                .note("modelled: see docs/semantics.md, section system variables")
                .hint("give the value as an input (--set) or replace the variable"),
        )
    }

    /// `#4014` under an extended work offset, `#4130` (the P of G54.1), `#4102` (B) and
    /// `#4115` (O): the values a FANUC returns there (54.1, the P number …) are in no source read for this work
    /// (docs/semantics.md, Modal information), so they are refused, not guessed.
    fn modal_unsourced(&self, n: i64, wo: usize, span: Span) -> Fault {
        let what = match n {
            4014 => format!("#4014 read under the extended work offset G54.1 P{}", wo.saturating_sub(6)),
            // B is the second auxiliary function only on a machine without a B axis; which
            // program's number #4115 holds in a subprogram is in no source read here.
            4102 => "#4102 (the B code of the preceding block, where B is no axis)".to_string(),
            4115 => "#4115 (the program number of the preceding block)".to_string(),
            _ => "#4130 (the P number of the additional work offset G54.1)".to_string(),
        };
        Fault::error(
            Diagnostic::error("NC549", format!("{what} is not modelled: no source read here gives its value"))
                .primary(self.file(), span, "read here")
                .note("modelled: #4014 under G54..G59 (54..59); docs/semantics.md, Modal information")
                .hint("keep the offset number in a variable where the program selects it"),
        )
    }

    /// `$P_GG[n]`, the active G function of group n as its internal number in the group's
    /// list (Siemens programming manual, list of G functions; docs/semantics.md, Modal
    /// information): group 1 G0..G3 = 1..4, group 6 G17/G18/G19 = 1..3, group 7
    /// G40/G41/G42 = 1..3. The evaluator models no other function of those groups (CIP, G33,
    /// splines … are NC403), so each match is exhaustive; the groups whose list no source
    /// read here gives are refused (NC656).
    fn p_gg(&mut self, idx: &[Expr], span: Span) -> Result<f64, Fault> {
        let [e] = idx else {
            return Err(self.unmodelled("$P_GG without one group number", span));
        };
        let cx = self.cx(false);
        let n = round_half_away(expr::eval_num(self, e, &cx)?);
        Ok(match n as i64 {
            1 => match self.m.modal.motion {
                super::machine::Motion::Rapid => 1.0,
                super::machine::Motion::Linear => 2.0,
                super::machine::Motion::Cw => 3.0,
                super::machine::Motion::Ccw => 4.0,
            },
            6 => match self.m.modal.plane {
                super::trace::Plane::XY => 1.0,
                super::trace::Plane::ZX => 2.0,
                super::trace::Plane::YZ => 3.0,
            },
            7 => match self.m.comp.side {
                None => 1.0,
                Some(super::trace::Side::Left) => 2.0,
                Some(super::trace::Side::Right) => 3.0,
            },
            _ => {
                return Err(Fault::error(
                    Diagnostic::error("NC656", format!("{} is not modelled", p_gg_group(n)))
                        .primary(self.file(), span, "read here")
                        .note(P_GG_SOURCED)
                        .hint("keep the mode in a variable where the program selects it"),
                ))
            }
        })
    }

    /// Refuses a current position read under G41/G42, whose tool centre stands off the
    /// programmed contour the trace keeps (docs/semantics.md, Probing and position reads).
    fn radius_guard(&self, name: &str, span: Span) -> Result<(), Fault> {
        match self.m.comp.side {
            None => Ok(()),
            Some(_) => Err(Fault::error(
                Diagnostic::error(
                    "NC534",
                    format!("{name} read under G41/G42 (the tool centre stands off the programmed contour) is not modelled"),
                )
                .primary(self.file(), span, "read here")
                .note("the evaluator keeps programmed positions; the tool centre path of radius compensation is not modelled")
                .hint("read the position with the radius compensation cancelled (G40), or the programmed end point (#5001+, $P_EP)"),
            )),
        }
    }

    /// A current position read under a tool length (FANUC G43/G44, a Siemens edge) whose
    /// value the run does not know: `why` from `Machine::length_offset`/`edge_length`.
    fn current_length_unknown(&self, name: &str, why: &str, span: Span) -> Fault {
        let (under, holds) = if self.m.fanuc {
            ("G43/G44", "FANUC's current positions include the tool length offset")
        } else {
            (
                "a cutting edge D active",
                "Siemens machine positions are the tool carrier's, the tip plus the edge's length",
            )
        };
        Fault::error(
            Diagnostic::error("NC534", format!("{name} read under {under} (the value includes the tool length) {why}"))
                .primary(self.file(), span, "read here")
                .note(format!("{holds} (docs/semantics.md, Probing and position reads)"))
                .hint(format!("give the length: {}", self.m.length_inputs())),
        )
    }

    /// The length a current position read includes on Z, or the refusal naming why the run
    /// does not know it.
    fn current_length(&self, name: &str, axis: usize, span: Span) -> Result<f64, Fault> {
        // Under G17 the length lies on Z only: the other axes need no register (not on a
        // Haas, whose offset tables the run does not take).
        if axis != 2 && self.m.modal.plane == super::trace::Plane::XY && !self.m.haas {
            return Ok(0.0);
        }
        let length = if self.m.fanuc { self.m.length_offset() } else { self.m.edge_length() };
        match length {
            Ok(l) => Ok(if axis == 2 { l } else { 0.0 }),
            Err(why) => Err(self.current_length_unknown(name, &why, span)),
        }
    }

    /// A `#5061+` read whose tool length offset (G43/G44 at the G31) the run does not know.
    fn length_unknown(&self, n: i64, why: &str, span: Span) -> Fault {
        Fault::error(
            Diagnostic::error("NC534", format!("#{n} read under G43/G44 (the value includes the tool length offset) {why}"))
                .primary(self.file(), span, "read here")
                .note("FANUC keeps the skip position with the tool length offset in force at the G31 (docs/semantics.md, Probing)")
                .hint(format!("give the length: {}; or probe under G49", self.m.length_inputs())),
        )
    }

    /// A position in the current input unit.
    fn in_unit(&self, mm: f64) -> f64 {
        if self.m.modal.sys_inch() {
            mm / 25.4
        } else {
            mm
        }
    }

    /// FANUC offset variable `n` → (table, axis): #5201+ external, #5221+ G54 … #5321+ G59.
    fn offset_var(n: i64) -> Option<(usize, usize)> {
        if !(5201..=5329).contains(&n) {
            return None;
        }
        let k = (n - 5201) as usize;
        let (table, axis) = (k / 20, k % 20);
        (axis < 9).then_some((table, axis))
    }

    pub fn fanuc_sys_read(&mut self, n: i64, span: Span) -> Result<Value, Fault> {
        let m = &self.m;
        let x = match n {
            3000 | 3006 => return Err(self.unmodelled(&format!("#{n} (write-only)"), span)),
            3001 | 3002 | 3003 | 3004 | 3901 | 3902 => self.sys_store.get(&format!("#{n}")).copied().unwrap_or(0.0),
            4001 => match m.modal.motion {
                super::machine::Motion::Rapid => 0.0,
                super::machine::Motion::Linear => 1.0,
                super::machine::Motion::Cw => 2.0,
                super::machine::Motion::Ccw => 3.0,
            },
            4002 => match m.modal.plane {
                super::trace::Plane::XY => 17.0,
                super::trace::Plane::ZX => 18.0,
                super::trace::Plane::YZ => 19.0,
            },
            4003 => {
                if m.modal.absolute {
                    90.0
                } else {
                    91.0
                }
            }
            4005 => {
                if m.modal.per_rev {
                    95.0
                } else {
                    94.0
                }
            }
            4006 => {
                if m.modal.inch {
                    20.0
                } else {
                    21.0
                }
            }
            // G54..G59 are tables 1..6; an extended offset (G54.1 Pn, table 6 + n) reads a
            // value (and #4130 its P) that no source read here settles.
            4014 if m.wo <= 6 => 53.0 + m.wo as f64,
            4014 | 4102 | 4115 | 4130 => return Err(self.modal_unsourced(n, m.wo, span)),
            4007..=4010 | 4015 => {
                let group = (n - 4000) as u8;
                match m.group_g.iter().find(|s| s.0 == group) {
                    Some(s) => s.1 as f64 / 10.0,
                    None => return Err(self.unmodelled(&format!("#{n}"), span)),
                }
            }
            4012 => {
                if self.modal_call.is_some() {
                    66.0
                } else {
                    67.0
                }
            }
            4107 => m.d,
            4109 => {
                let f = m.feed.unwrap_or(0.0);
                if m.modal.inch_feed {
                    f / 25.4
                } else {
                    f
                }
            }
            4111 => m.h,
            4113 => m.last_m,
            4114 => m.last_n,
            4119 => m.speed,
            4120 => match &m.tool_sel {
                Some(ToolId::Number(t)) => *t,
                _ => 0.0,
            },
            // The skip position kept by the last G31 (`machine::probe`), 0 before any.
            // Under G43/G44 they include the offset in force at the G31 (F-POS), on Z: the
            // value where the run knows it.
            5061..=5069 => {
                let length = match &m.probe.length {
                    Ok(l) => *l,
                    Err(why) => return Err(self.length_unknown(n, why, span)),
                };
                let i = (n - 5061) as usize;
                self.in_unit(m.probe.skip[i]) + if i == 2 { length } else { 0.0 }
            }
            // The current positions include the tool length offset (F-POS): G43 adds the H
            // register on Z, G44 subtracts it, where the run knows it.
            5001..=5009 | 5041..=5049 => {
                let axis = ((n - 1) % 20) as usize;
                let length = if n >= 5041 {
                    self.radius_guard(&format!("#{n}"), span)?;
                    self.current_length(&format!("#{n}"), axis, span)?
                } else {
                    0.0
                };
                if m.transforms() {
                    return Err(self.unmodelled(&format!("#{n} under a rotated, scaled or mirrored frame"), span));
                }
                self.in_unit(m.work_pos(axis) + length)
            }
            5021..=5029 => {
                self.radius_guard(&format!("#{n}"), span)?;
                let axis = ((n - 1) % 20) as usize;
                let length = self.current_length(&format!("#{n}"), axis, span)?;
                self.in_unit(m.pos[axis] + length)
            }
            n => match Self::offset_var(n) {
                Some((t, a)) => self.in_unit(m.offsets[t][a]),
                None => return Err(self.unmodelled(&format!("#{n}"), span)),
            },
        };
        Ok(Value::Num(x))
    }

    pub fn fanuc_sys_write(&mut self, n: i64, x: Option<f64>, span: Span) -> Result<(), Fault> {
        let v = x.unwrap_or(0.0);
        match n {
            3000 => Err(Fault::alarm(3000 + round_half_away(v) as i64, "", span)),
            3006 => {
                self.emit(Event::Stop { optional: false, message: None }, span);
                Ok(())
            }
            // Single-block / feed-hold control: no effect on the toolpath (pitfall 46).
            3003 | 3004 => {
                self.warn("NC405", format!("#{n} (single block / feed hold control) has no effect on the trace"), span);
                self.sys_store.insert(format!("#{n}"), v);
                Ok(())
            }
            3001 | 3002 | 3901 | 3902 => {
                if n >= 3901 && v < 0.0 {
                    return Err(Fault::alarm(self.alarms.bad_index, format!("#{n} cannot be negative"), span));
                }
                self.sys_store.insert(format!("#{n}"), v);
                Ok(())
            }
            5001..=5009 | 5021..=5029 | 5041..=5049 | 5061..=5069 | 4001..=4130 => {
                Err(Fault::alarm(self.alarms.read_only, format!("#{n} is read-only"), span))
            }
            n => match Self::offset_var(n) {
                Some((t, a)) => {
                    let mm = if self.m.modal.sys_inch() && !(3..6).contains(&a) { v * 25.4 } else { v };
                    self.m.offsets[t][a] = mm;
                    // The active offset changed (live on FANUC): as a re-selection.
                    if t == self.m.wo || t == 0 {
                        self.emit(Event::WorkOffset { n: self.m.wo as u32 }, span);
                    }
                    Ok(())
                }
                None => Err(self.unmodelled(&format!("#{n}"), span)),
            },
        }
    }

    fn axis_arg(&mut self, e: Option<&Expr>, name: &str, span: Span) -> Result<usize, Fault> {
        let id = match e.map(|e| &e.kind) {
            Some(ExprKind::Ident(s)) => s.to_ascii_uppercase(),
            Some(ExprKind::Var(v)) => match &v.kind {
                crate::ir::VarKind::Named { name, indices } if indices.is_empty() => name.to_ascii_uppercase(),
                _ => String::new(),
            },
            _ => String::new(),
        };
        match (id.len(), id.bytes().next().and_then(axis_index)) {
            (1, Some(i)) => Ok(i),
            _ => Err(Fault::error(
                Diagnostic::error("NC400", format!("${name} needs an axis name as its index"))
                    .primary(self.file(), span, "here")
                    .hint("write it as $AA_IW[X]"),
            )),
        }
    }

    fn frame_index(&mut self, e: Option<&Expr>, span: Span) -> Result<usize, Fault> {
        let Some(e) = e else {
            return Err(self.unmodelled("$P_UIFR without an index", span));
        };
        let cx = self.cx(false);
        let n = round_half_away(expr::eval_num(self, e, &cx)?);
        if !(0.0..100.0).contains(&n) {
            return Err(Fault::alarm(self.alarms.bad_index, format!("$P_UIFR[{n}] does not exist"), span));
        }
        Ok(n as usize)
    }

    fn uifr_component(&self, idx: &[Expr], span: Span) -> Result<(), Fault> {
        match idx.get(2).map(|e| &e.kind) {
            None => Ok(()),
            Some(ExprKind::Ident(s)) if s.eq_ignore_ascii_case("TR") => Ok(()),
            Some(ExprKind::Var(v)) if matches!(&v.kind, crate::ir::VarKind::Named { name, .. } if name == "TR") => {
                Ok(())
            }
            _ => Err(self.unmodelled("$P_UIFR component other than TR", span)),
        }
    }

    pub fn sie_sys_read(&mut self, name: &str, idx: &[Expr], span: Span) -> Result<Value, Fault> {
        let x = match name {
            // The last measured values (`machine::probe`): written only when the probe
            // switched, for the axes of the measuring block; 0 before any.
            "AA_MW" | "AA_MM" => {
                let a = self.axis_arg(idx.first(), name, span)?;
                if name == "AA_MM" {
                    if let Err(why) = &self.m.probe.edge_length {
                        return Err(self.current_length_unknown("$AA_MM", why, span));
                    }
                }
                let p = &self.m.probe;
                self.in_unit(if name == "AA_MW" { p.meas_w[a] } else { p.meas_m[a] })
            }
            "AC_MEA" => {
                let n = match idx.first() {
                    Some(e) => {
                        let cx = self.cx(false);
                        round_half_away(expr::eval_num(self, e, &cx)?)
                    }
                    None => return Err(self.unmodelled("$AC_MEA without the probe number", span)),
                };
                if n != 1.0 && n != 2.0 {
                    return Err(Fault::alarm(self.alarms.bad_index, format!("$AC_MEA[{n}] does not exist"), span));
                }
                f64::from(u8::from(self.m.probe.mea[n as usize - 1]))
            }
            "AA_IW" | "P_EP" => {
                let a = self.axis_arg(idx.first(), name, span)?;
                if name == "AA_IW" {
                    self.radius_guard("$AA_IW", span)?;
                }
                if self.m.turns_axis(a) {
                    return Err(self.unmodelled(&format!("${name} under a rotated, scaled or mirrored frame"), span));
                }
                self.in_unit(self.m.work_pos(a))
            }
            "AA_IM" => {
                let a = self.axis_arg(idx.first(), name, span)?;
                // The tool carrier reference point: the tip plus the edge's length on Z (S-MEAS).
                self.radius_guard("$AA_IM", span)?;
                let length = self.current_length("$AA_IM", a, span)?;
                self.in_unit(self.m.pos[a] + length)
            }
            "P_UIFR" => {
                let f = self.frame_index(idx.first(), span)?;
                let a = self.axis_arg(idx.get(1), name, span)?;
                self.uifr_component(idx, span)?;
                self.in_unit(self.m.offsets[f][a])
            }
            "PI" => std::f64::consts::PI,
            "AC_TIME" => {
                self.warn("NC405", "$AC_TIME reads 0: time is not modelled".into(), span);
                0.0
            }
            "AC_ACTUAL_PARTS" | "AC_REQUIRED_PARTS" | "AC_TOTAL_PARTS" | "AC_SPECIAL_PARTS" => {
                self.sys_store.get(name).copied().unwrap_or(0.0)
            }
            // In the programmed unit under G700 (inch/min), else the basic system's.
            "P_F" => {
                let f = self.m.feed.unwrap_or(0.0);
                if self.m.modal.sys_inch() {
                    f / 25.4
                } else {
                    f
                }
            }
            "P_S" => self.m.speed,
            "P_TOOLNO" => match &self.m.tool {
                Some(ToolId::Number(t)) => *t,
                _ => 0.0,
            },
            "P_TOOL" => self.m.d,
            "P_GG" => self.p_gg(idx, span)?,
            _ => return Err(self.unmodelled(&format!("${name}"), span)),
        };
        Ok(Value::Num(x))
    }

    pub fn sie_sys_write(&mut self, name: &str, idx: &[Expr], v: Value, span: Span) -> Result<(), Fault> {
        let cx = self.cx(false);
        let x = v.num().ok_or_else(|| Fault::alarm(self.alarms.domain, format!("${name} needs a number"), span))?;
        let _ = cx;
        match name {
            "P_UIFR" => {
                let f = self.frame_index(idx.first(), span)?;
                let a = self.axis_arg(idx.get(1), name, span)?;
                self.uifr_component(idx, span)?;
                let mm = if self.m.modal.sys_inch() && !(3..6).contains(&a) { x * 25.4 } else { x };
                // Written, not active: G54.. must be selected again (source S20 of docs/semantics.md).
                self.m.offsets[f][a] = mm;
                Ok(())
            }
            "AC_ACTUAL_PARTS" | "AC_REQUIRED_PARTS" | "AC_TOTAL_PARTS" | "AC_SPECIAL_PARTS" => {
                self.sys_store.insert(name.to_string(), x);
                Ok(())
            }
            "AA_IW" | "AA_IM" | "P_EP" | "AA_MW" | "AA_MM" | "AC_MEA" | "PI" | "AC_TIME" | "P_F" | "P_S"
            | "P_TOOLNO" | "P_TOOL" | "P_GG" => {
                Err(Fault::alarm(self.alarms.read_only, format!("${name} is read-only"), span))
            }
            _ => Err(self.unmodelled(&format!("${name}"), span)),
        }
    }
}

/// The groups `$P_GG` reads, with the numbers the sources give (docs/semantics.md, Modal
/// information).
pub const P_GG_SOURCED: &str = "no source read here gives the internal numbers of that group's G functions; modelled: \
     group 1 G0..G3 = 1..4, group 6 G17/G18/G19 = 1..3, group 7 G40/G41/G42 = 1..3 (docs/semantics.md, Modal information)";

/// `$P_GG[n]` named with what group n holds, for the groups programs test most often.
pub fn p_gg_group(n: f64) -> String {
    let what = match n as i64 {
        1 => " (group 1: G0, G1, G2, G3, CIP …)",
        6 => " (group 6: the plane G17/G18/G19)",
        7 => " (group 7: the radius compensation G40/G41/G42)",
        8 => " (group 8: the work offset G500/G54..G599)",
        13 => " (group 13: the units G70/G71/G700/G710)",
        14 => " (group 14: G90/G91)",
        15 => " (group 15: the feed type G93/G94/G95 …)",
        _ => "",
    };
    format!("$P_GG[{n}]{what}")
}
