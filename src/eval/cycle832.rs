//! Siemens `CYCLE832(tolerance, machining type, …)`, the high-speed settings cycle: it sets
//! tolerances, compressor and dynamic response, never the programmed path, so it runs as a
//! warning that it is not compared (`machine::lookahead`). The plain texts of its machining
//! types (`_OFF`, `_FINISH`, `_SEMIFIN`, `_ROUGH`) read as their numbers.

use super::exec::Flow;
use super::exec::Interp;
use super::fault::Fault;
use super::machine::lookahead::{cycle832_mode, BAD_VALUE, NOT_COMPARED};
use super::value::Value;
use crate::diag::Diagnostic;
use crate::ir::{Arg, Call, ExprKind, VarKind};
use crate::span::Span;

/// `_OFF`, `_FINISH`, `_SEMIFIN`, `_ROUGH`: CYCLE832's machining types as the programming
/// manual writes them (deselection, finishing, semi-finishing, roughing).
pub fn type_name(name: &str) -> Option<f64> {
    Some(match name.to_ascii_uppercase().as_str() {
        "_OFF" => 0.0,
        "_FINISH" => 1.0,
        "_SEMIFIN" => 2.0,
        "_ROUGH" => 3.0,
        _ => return None,
    })
}

/// The machining-type argument written as its plain text, if it is.
pub fn named_type(a: &Arg) -> Option<f64> {
    let Arg::Value(e) = a else { return None };
    let ExprKind::Var(v) = &e.kind else { return None };
    match &v.kind {
        VarKind::Named { name, indices } if indices.is_empty() => type_name(name),
        _ => None,
    }
}

impl Interp<'_> {
    pub(super) fn cycle832(&mut self, call: &Call, span: Span) -> Result<Flow, Fault> {
        let mut vals = Vec::new();
        for (i, a) in call.args.iter().enumerate().take(2) {
            let v = match (i, named_type(a)) {
                (1, Some(x)) => Some(x),
                _ => match a {
                    Arg::Omitted(_) => None,
                    Arg::Value(e) | Arg::Letter { value: e, .. } => {
                        let cx = self.cx(false);
                        match super::expr::eval(self, e, &cx)? {
                            Value::Num(x) => Some(x),
                            _ => {
                                return Err(
                                    self.cycle832_refusal("CYCLE832 with an argument that is not a number", span)
                                )
                            }
                        }
                    }
                },
            };
            vals.push(v);
        }
        vals.resize(2, None);
        match cycle832_mode(vals[0], vals[1]) {
            Ok(what) => {
                self.warn(NOT_COMPARED, format!("{what} changes how the control plans feed and corners, not the programmed positions: not compared"), span);
                Ok(Flow::Next)
            }
            Err(what) => Err(self.cycle832_refusal(&what, span)),
        }
    }

    fn cycle832_refusal(&self, what: &str, span: Span) -> Fault {
        Fault::error(
            Diagnostic::error(BAD_VALUE, what.to_string())
                .primary(self.file(), span, "here")
                .hint("CYCLE832(tolerance, 0 to 4) with numbers, or _OFF/_FINISH/_SEMIFIN/_ROUGH"),
        )
    }
}
