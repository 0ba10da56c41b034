//! Offsets and frames a program writes: FANUC `G10 L2`/`G10 L20` work offsets and Siemens
//! `TRANS`/`ATRANS` programmable frames (docs/semantics.md).

use super::{axis_index, round_half_away, unsupported, Fault, Machine, Span, Warn, WordVal, WV};

impl Machine {
    pub(super) fn g10(
        &mut self,
        l: Option<f64>,
        [p, r]: [Option<(&WordVal, f64)>; 2],
        axes: &[Option<(&WordVal, f64)>; 9],
        out: &mut Vec<(crate::eval::trace::Event, Span)>,
        warns: &mut Vec<Warn>,
        span: Span,
    ) -> Result<bool, Fault> {
        match l.map(round_half_away) {
            Some(2.0) => {
                let n = p.map_or(0.0, |(_, x)| round_half_away(x));
                if !(0.0..=6.0).contains(&n) {
                    return Err(Fault::alarm(self.alarms.bad_index, format!("G10 L2 P{n}: no such work offset"), span));
                }
                for (i, a) in axes.iter().enumerate() {
                    if let Some((w, x)) = a {
                        let v = self.length(w, *x, (3..6).contains(&i));
                        let slot = &mut self.offsets[n as usize][i];
                        *slot = if self.modal.absolute { v } else { *slot + v };
                    }
                }
                Ok(n as usize == self.wo || n == 0.0)
            }
            // `G10 L20 Pn`: extended work offset n (G54.1 Pn), table 6 + n.
            Some(20.0) => {
                let n = p.map_or(0.0, |(_, x)| round_half_away(x));
                if !(1.0..=48.0).contains(&n) {
                    return Err(Fault::alarm(
                        self.alarms.bad_index,
                        format!("G10 L20 P{n}: no such extended work offset (P1..P48)"),
                        span,
                    ));
                }
                let t = 6 + n as usize;
                for (i, a) in axes.iter().enumerate() {
                    if let Some((w, x)) = a {
                        let v = self.length(w, *x, (3..6).contains(&i));
                        let slot = &mut self.offsets[t][i];
                        *slot = if self.modal.absolute { v } else { *slot + v };
                    }
                }
                Ok(t == self.wo)
            }
            // Tool compensation memory C: L10 H geometry, L11 H wear, L12 D geometry, L13 D
            // wear; R the value, added under G91 (docs/semantics.md, Tool offset data).
            Some(l) if !self.haas && crate::eval::tool_data::g10_field(l).is_some() => {
                self.g10_tool(l as u32, p, r, out, span)?;
                Ok(false)
            }
            _ => {
                warns.push((
                    "NC405",
                    "G10 other than L2/L20 (tool or parameter data) has no effect on the trace".into(),
                    span,
                ));
                Ok(false)
            }
        }
    }

    fn g10_tool(
        &mut self,
        l: u32,
        p: Option<(&WordVal, f64)>,
        r: Option<(&WordVal, f64)>,
        out: &mut Vec<(crate::eval::trace::Event, Span)>,
        span: Span,
    ) -> Result<(), Fault> {
        use crate::eval::trace::{CompReg, Event, ToolDataEv};
        let Some(field) = crate::eval::tool_data::g10_field(f64::from(l)) else {
            return Err(Fault::alarm(self.alarms.bad_index, format!("G10 L{l}: not a tool offset write"), span));
        };
        let n = p.map_or(0.0, |(_, x)| round_half_away(x));
        if !(1.0..=999.0).contains(&n) {
            return Err(Fault::alarm(self.alarms.bad_index, format!("G10 L{l} P{n}: no such tool offset"), span));
        }
        let Some((w, x)) = r else {
            return Err(Fault::alarm(self.alarms.bad_index, format!("G10 L{l} P{n} without the value R"), span));
        };
        // In the input unit, as a macro variable holds it: the decimal-point rule applies.
        let v = self.length(w, x, false) / if self.modal.inch { 25.4 } else { 1.0 };
        let key = format!("#{}", crate::eval::tool_data::fanuc_var(field, n as u32));
        let value = if self.modal.absolute {
            v
        } else {
            match self.tool_data.get(&key) {
                Some(old) => old + v,
                None => {
                    return Err(Fault::Error(Box::new(
                        crate::diag::Diagnostic::error(
                            "NC571",
                            format!("G91 G10 L{l} P{n} adds to {key}, which the run was not given"),
                        )
                        .primary(usize::MAX, span, "here")
                        .hint(format!(
                            "give the machine's value: --set '{key}=…' or a header line `nctrans: set {key}=…`"
                        )),
                    )))
                }
            }
        };
        self.tool_data.insert(key, value);
        let ev = ToolDataEv { register: CompReg::Fanuc(n as i64), field, value };
        out.push((Event::ToolData(Box::new(ev)), span));
        Ok(())
    }

    /// Siemens frame instructions: `TRANS`/`ATRANS` with axis words (values in the current
    /// unit; `ATRANS` in the turned system of the frame so far), the bare absolute ones, and
    /// `ROT`/`SCALE`/`MIRROR` and their additive forms ([`Machine::siemens_frame`]).
    pub fn frame_op(&mut self, op: &str, words: &[WordVal], span: Span) -> Result<(), Fault> {
        // A bare absolute frame instruction deletes the whole programmable frame.
        if words.is_empty() && matches!(op, "TRANS" | "ROT" | "SCALE" | "MIRROR") {
            self.set_trans([0.0; 9]);
            self.set_xform(super::Xform::ID);
            return Ok(());
        }
        let additive = match op {
            "TRANS" => false,
            "ATRANS" => true,
            _ => return self.siemens_frame(op, words, span),
        };
        let mut t = if additive { self.trans } else { [0.0; 9] };
        let mut shift = [0.0; 9];
        for w in words {
            let i = w.addr.as_bytes().first().copied().and_then(axis_index);
            match (i, &w.val) {
                (Some(i), WV::Num(x)) if w.addr.len() == 1 => {
                    shift[i] += self.length(w, *x, (3..6).contains(&i));
                }
                _ => return Err(unsupported(&format!("{op} with {}", w.addr), w.span)),
            }
        }
        // The shift is along the axes of the frame so far (identity unless it turns).
        let geo =
            if additive { self.xf.vector([shift[0], shift[1], shift[2]]) } else { [shift[0], shift[1], shift[2]] };
        for (i, slot) in t.iter_mut().enumerate() {
            *slot += if i < 3 { geo[i] } else { shift[i] };
        }
        self.set_trans(t);
        if !additive {
            self.set_xform(super::Xform::ID);
        }
        Ok(())
    }
}
