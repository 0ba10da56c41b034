//! Offsets and frames a program writes: FANUC `G10 L2` work offsets and Siemens
//! `TRANS`/`ATRANS` programmable frames (docs/semantics.md).

use super::{axis_index, round_half_away, unsupported, Fault, Machine, Span, Warn, WordVal, WV};

impl Machine {
    pub(super) fn g10(
        &mut self,
        l: Option<f64>,
        p: Option<(&WordVal, f64)>,
        axes: &[Option<(&WordVal, f64)>; 9],
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
            _ => {
                warns.push((
                    "NC405",
                    "G10 other than L2 (tool or parameter data) has no effect on the trace".into(),
                    span,
                ));
                Ok(false)
            }
        }
    }

    /// Siemens `TRANS`/`ATRANS` with axis words (values in the current unit).
    pub fn frame_op(&mut self, op: &str, words: &[WordVal], span: Span) -> Result<(), Fault> {
        // A bare absolute frame instruction deletes the whole programmable frame.
        if words.is_empty() && matches!(op, "TRANS" | "ROT" | "SCALE" | "MIRROR") {
            self.trans = [0.0; 9];
            return Ok(());
        }
        let additive = match op {
            "TRANS" => false,
            "ATRANS" => true,
            _ => return Err(unsupported(&format!("frame instruction {op} is not modelled"), span)),
        };
        if !additive {
            self.trans = [0.0; 9];
        }
        for w in words {
            let i = w.addr.as_bytes().first().copied().and_then(axis_index);
            match (i, &w.val) {
                (Some(i), WV::Num(x)) if w.addr.len() == 1 => {
                    let v = self.length(w, *x, (3..6).contains(&i));
                    self.trans[i] += v;
                }
                _ => return Err(unsupported(&format!("{op} with {}", w.addr), w.span)),
            }
        }
        Ok(())
    }
}
