//! Haas machine data read by macros: settings `#20000..#29999` (setting n is `#20000+n`) and
//! parameters `#30000..#39999` (parameter n is `#30000+n`), Haas NGC macro variable table.
//! Their values are the machine's, not the program's: a run takes them from its inputs
//! (`--set '#20009=1'`, or a header `(nctrans: set #20009=1.)`), and a read of one it was not
//! given, or a write (they are read-only to macros), is refused (NC564) naming the setting.

use super::exec::Interp;
use super::fault::Fault;
use super::value::Value;
use crate::diag::Diagnostic;
use crate::span::Span;

pub const CODE: &str = "NC564";

/// `("Setting", 9)` for `#20009`, `("parameter", 57)` for `#30057`; `None` outside both.
pub fn machine_data(n: i64) -> Option<(&'static str, i64)> {
    match n {
        20000..=29999 => Some(("Setting", n - 20000)),
        30000..=39999 => Some(("parameter", n - 30000)),
        _ => None,
    }
}

impl Interp<'_> {
    /// `#n` is Haas machine data on this control.
    pub fn is_haas_data(&self, n: i64) -> bool {
        self.sem.haas && machine_data(n).is_some()
    }

    /// An input for Haas machine data: kept as the machine's value.
    pub fn set_haas_data(&mut self, n: i64, v: &Value) -> Result<(), Fault> {
        match v {
            Value::Num(x) => {
                self.sys_store.insert(format!("#{n}"), *x);
                Ok(())
            }
            _ => Err(Fault::error(Diagnostic::error(CODE, format!("input #{n}: Haas machine data is a number")))),
        }
    }

    pub fn read_haas_data(&mut self, n: i64, span: Span) -> Result<Value, Fault> {
        if let Some(x) = self.sys_store.get(&format!("#{n}")) {
            return Ok(Value::Num(*x));
        }
        let (kind, k) = machine_data(n).unwrap_or(("Setting", 0));
        Err(Fault::error(
            Diagnostic::error(CODE, format!("#{n} is Haas {kind} {k}: its value is the machine's, not the program's"))
                .primary(self.file(), span, "read here")
                .note("a run knows only the machine data it is given")
                .hint(format!("give the machine's value: --set '#{n}=…' or a header line (nctrans: set #{n}=…)")),
        ))
    }

    pub fn write_haas_data(&mut self, n: i64, span: Span) -> Result<(), Fault> {
        let (kind, k) = machine_data(n).unwrap_or(("Setting", 0));
        Err(Fault::error(
            Diagnostic::error(CODE, format!("#{n} (Haas {kind} {k}) is read-only to a macro"))
                .primary(self.file(), span, "written here")
                .hint(format!("change {kind} {k} on the control; keep the program's own value in a common variable")),
        ))
    }
}
