//! Axes chosen at run time: Siemens `AX[e]=v`, where `e` is an axis name (`AX[X]`), an AXIS
//! variable or `AXNAME("X")`. The word then acts on that axis like `X=v`.

use super::exec::Interp;
use super::expr;
use super::fault::Fault;
use super::value::Value;
use crate::diag::Diagnostic;
use crate::ir::{Expr, ExprKind};

impl Interp<'_> {
    /// The upper-case name of the axis `e` designates.
    pub fn axis_name(&mut self, e: &Expr) -> Result<String, Fault> {
        if let ExprKind::Ident(name) = &e.kind {
            return Ok(name.to_ascii_uppercase());
        }
        let cx = self.cx(false);
        match expr::eval(self, e, &cx)? {
            Value::Str(s) if is_axis_name(&s) => Ok(s.trim().to_ascii_uppercase()),
            _ => Err(Fault::error(
                Diagnostic::error("NC433", "AX[…] needs an axis name")
                    .primary(self.file(), e.span, "not an axis")
                    .hint("give an AXIS variable, `AXNAME(\"X\")` or an axis letter, e.g. `AX[X]=10`"),
            )),
        }
    }
}

/// A machine axis name: a letter, then letters or digits (`X`, `X1`, `SP1`, `C`).
fn is_axis_name(s: &str) -> bool {
    let s = s.trim();
    let b = s.as_bytes();
    !b.is_empty() && b[0].is_ascii_alphabetic() && b.iter().all(u8::is_ascii_alphanumeric)
}
