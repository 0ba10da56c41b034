//! Text output as the trace's `print` event: a FANUC `DPRNT[…]` of text alone, and a Siemens
//! `WRITE(err, "file", text)` with the STRING as built. The text a DPRNT number field
//! (`#100[53]`) produces is not modelled: no stored source settles it (docs/semantics.md,
//! "External output", lists the searches): the Haas manual's rules (leading spaces, the
//! fraction rounded, no point with no fraction places) disagree with its own example, and
//! FANUC's leading-zero setting (parameter PRT), the sign's place and a vacant variable's
//! text are in none of them. So such a DPRNT warns (NC554) and a run with it is never called
//! equivalent. On the Haas profile a field whose places add up to 0 or more than 8 is an error
//! (NC587: the Haas manual calls it illegal). Siemens `EXTOPEN`/`EXTCLOSE` (an external device
//! of the control's set-up) are refused by name (NC586).

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

/// The `#v[wf]` of a field Haas does not accept: its places `w + f` are 0 or more than 8
/// (HAAS-DPRNT: "cannot be equal to zero or greater than eight").
fn haas_illegal(p: &PrintPart) -> Option<String> {
    match p {
        PrintPart::Field { int, frac, .. } if *int + *frac == 0 || *int + *frac > 8 => field_format(p),
        _ => None,
    }
}

impl Interp<'_> {
    pub(super) fn print(&mut self, p: &Print, span: Span) -> Result<(), Fault> {
        if self.sem.haas {
            if let Some(f) = p.parts.iter().find_map(haas_illegal) {
                return Err(Fault::error(
                    crate::diag::Diagnostic::error(
                        "NC587",
                        format!("DPRNT field `{f}`: not a legal format on Haas (the places reserved add up to 1..8)"),
                    )
                    .primary(self.file(), span, "illegal field format")
                    .note("Haas mill operator's manual 96-8000, \"Formatted Output\": [00], [54], [45] and [36] are illegal")
                    .hint("reserve at most 8 places in all, at least one: e.g. [44] or [53]"),
                ));
            }
        }
        if let Some(f) = p.parts.iter().find_map(field_format) {
            let msg = format!(
                "DPRNT field `{f}`: the text a number field prints is not modelled (no source settles its \
                 leading spaces or zeros, the sign's place, the rounding or a vacant variable's text), so this \
                 output is not compared"
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

/// `EXTOPEN(…)` / `EXTCLOSE(…)` as the Sinumerik reader keeps them.
pub fn is_external_device(name: &str) -> bool {
    name.starts_with("EXTOPEN(") || name.starts_with("EXTCLOSE(")
}

/// The refusal of `EXTOPEN`/`EXTCLOSE`: they open and close an external device
/// (`/dev/ext/1`…`/dev/ext/9`, a file or share the machine's extdev.ini names) for the WRITEs
/// between them (Siemens cnc4you, "Output on an external device"). Which device that is and the
/// error codes they set are the set-up's, so the run does not go on as if they had succeeded.
pub fn external_device(name: &str, span: Span, file: crate::span::FileId) -> Fault {
    let what = if name.starts_with("EXTOPEN(") { "opens" } else { "closes" };
    Fault::error(
        crate::diag::Diagnostic::error(
            "NC586",
            format!(
                "{name}: {what} an external device of the control's set-up (extdev.ini); the device and the \
                 error code it sets are not modelled"
            ),
        )
        .primary(file, span, "external device")
        .hint("WRITE to a file of the program memory needs no EXTOPEN: write WRITE(ERR,\"FILE\",\"TEXT\") alone"),
    )
}
