//! Text output as the trace's `print` event: a FANUC `DPRNT[…]` of text alone, and a Siemens
//! `WRITE(err, "file", text)` with the STRING as built. The text a DPRNT number field
//! (`#100[53]`) produces is not modelled: the sources found disagree on its spacing (leading
//! spaces or zeros, the sign's place) and FANUC's parameter for leading zeros is not among
//! them, so such a DPRNT warns (NC554) and a run with it is never called equivalent.

use super::exec::Interp;
use super::expr::{self, as_text};
use super::fault::Fault;
use super::trace::Event;
use super::value::Value;
use crate::ir::{Print, PrintPart};
use crate::span::Span;

/// The warning for output whose text is not modelled; `check` is inconclusive with it.
pub const PRINT_NOT_MODELLED: &str = "NC554";

/// The `[wf]` of a DPRNT field as written.
pub fn field_format(p: &PrintPart) -> Option<String> {
    match p {
        PrintPart::Field { value, int, frac } => {
            let var = match &value.kind {
                crate::ir::ExprKind::Var(v) => match v.kind {
                    crate::ir::VarKind::Hash(n) => format!("#{n}"),
                    _ => "#…".into(),
                },
                _ => "#…".into(),
            };
            Some(format!("{var}[{int}{frac}]"))
        }
        _ => None,
    }
}

impl Interp<'_> {
    pub(super) fn print(&mut self, p: &Print, span: Span) -> Result<(), Fault> {
        if let Some(f) = p.parts.iter().find_map(field_format) {
            let msg = format!(
                "DPRNT field `{f}`: the text a number field prints is not modelled (its spacing, sign and \
                 leading zeros are machine parameters without a source here), so this output is not compared"
            );
            self.warn(PRINT_NOT_MODELLED, msg, span);
            return Ok(());
        }
        let cx = self.cx(false);
        let mut text = String::new();
        for part in &p.parts {
            match part {
                PrintPart::Text(t) => text.push_str(t),
                PrintPart::Str(e) => text.push_str(&as_text(&expr::eval(self, e, &cx)?)),
                PrintPart::Field { .. } => {}
            }
        }
        if let Some(f) = &p.file {
            // The file name is evaluated (a fault in it is the program's), not compared.
            expr::eval(self, f, &cx)?;
        }
        // WRITE succeeded: its error variable reads 0 (no error). A failed write (a full
        // passive file system, MD11420) is not modelled.
        if let Some(v) = &p.status {
            self.write_var(v, Value::Num(0.0))?;
        }
        self.emit(Event::Print { text }, span);
        Ok(())
    }
}
