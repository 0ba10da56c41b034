//! Machine signals in a run (docs/semantics.md, Machine signals): Siemens PLC data
//! `$A_DBB/$A_DBW/$A_DBD/$A_DBR[n]` and NCK inputs/outputs `$A_IN[n]`/`$A_OUT[n]`, FANUC
//! interface signals `#1000..#1015`, `#1032`, `#1100..#1115`, `#1132`. What the machine's
//! inputs hold is no program's: a run knows a signal when its inputs give it (`--set
//! '$A_DBB[2]=1'`, `--set '#1002=1'`, `nctrans: set` header lines) or the program wrote it,
//! and refuses any other read (NC578) naming the input to give, never a silent 0. A write
//! has no trace event (the trace format has none for signals): the run keeps the value
//! and warns (NC579), which a check counts as not compared (`check::Excluded::signals`).

use super::exec::Interp;
use super::expr;
use super::fault::Fault;
use super::value::{round_half_away, Value};
use crate::diag::Diagnostic;
use crate::dialect::signals::{Kind, Signal};
use crate::ir::Expr;
use crate::span::Span;

/// A signal read the run was not given.
pub const NOT_GIVEN: &str = "NC578";
/// A signal write: no trace event, so not compared (a warning in a run, refused in translation).
pub const WRITE: &str = "NC579";
/// A value a signal cannot hold, or a wiring whose values cannot be carried.
pub const RANGE: &str = "NC597";

impl Interp<'_> {
    /// The FANUC interface signal `#n` is on this control (none on a Haas, which numbers
    /// its inputs otherwise).
    pub fn signal_at(&self, n: i64) -> Option<Signal> {
        u32::try_from(n).ok().and_then(Signal::fanuc).filter(|_| !self.sem.haas)
    }

    fn range_fault(&self, s: Signal, x: f64, span: Span) -> Fault {
        let mut d =
            Diagnostic::error(RANGE, format!("{} cannot hold {x}: it holds {}", s.named(), s.range().describe()));
        if span != Span::default() {
            d = d.primary(self.file(), span, "here");
        }
        Fault::error(d.note("docs/semantics.md, Machine signals"))
    }

    fn store(&mut self, s: Signal, x: f64, span: Span) -> Result<(), Fault> {
        if !s.range().holds(x) {
            return Err(self.range_fault(s, x, span));
        }
        match s.kind {
            // The 16 bits at once: each bit as its own variable, so both spellings agree.
            Kind::UiWord | Kind::UoWord => {
                let base = if s.kind == Kind::UiWord { 1000 } else { 1100 };
                let bits = x as u32;
                for i in 0..16 {
                    self.sys_store.insert(format!("#{}", base + i), f64::from((bits >> i) & 1));
                }
            }
            _ => {
                self.sys_store.insert(s.key(), x);
            }
        }
        Ok(())
    }

    /// An input of the machine's value (`--set`, header lines): kept, no event.
    pub fn set_signal(&mut self, s: Signal, v: &Value) -> Result<(), Fault> {
        match v {
            Value::Num(x) => self.store(s, *x, Span::default()),
            _ => Err(Fault::error(Diagnostic::error(RANGE, format!("input {}: a signal is a number", s.key())))),
        }
    }

    fn signal_not_given(&self, s: Signal, span: Span) -> Fault {
        Fault::error(
            Diagnostic::error(NOT_GIVEN, format!("{} is read but the run was not given it", s.named()))
                .primary(self.file(), span, "read here")
                .note("a signal is the machine's: a run knows only those its inputs give or the program writes")
                .hint(format!(
                    "give the machine's value: --set '{}=…' or a header line `nctrans: set {}=…`",
                    s.key(),
                    s.key()
                )),
        )
    }

    fn read_signal(&mut self, s: Signal, span: Span) -> Result<Value, Fault> {
        let x = match s.kind {
            Kind::UiWord | Kind::UoWord => {
                let base = if s.kind == Kind::UiWord { 1000 } else { 1100 };
                let mut sum = 0.0;
                for i in 0..16u32 {
                    match self.sys_store.get(&format!("#{}", base + i)) {
                        Some(b) => sum += b * f64::from(1u32 << i),
                        None => return Err(self.signal_not_given(Signal { kind: s.kind, index: s.index }, span)),
                    }
                }
                sum
            }
            _ => {
                self.overlap_guard(s, span)?;
                match self.sys_store.get(&s.key()) {
                    Some(x) => *x,
                    None => return Err(self.signal_not_given(s, span)),
                }
            }
        };
        Ok(Value::Num(x))
    }

    /// A PLC datum read while another width's datum over the same bytes is known: how the
    /// bytes make the word is machine data (MD10399, little or big endian), not modelled.
    fn overlap_guard(&self, s: Signal, span: Span) -> Result<(), Fault> {
        let Some((a, b)) = s.plc_bytes() else { return Ok(()) };
        for key in self.sys_store.keys() {
            let Ok(o) = Signal::parse(key) else { continue };
            let Some((c, d)) = o.plc_bytes() else { continue };
            if o != s && c <= b && a <= d {
                return Err(Fault::error(
                    Diagnostic::error(NOT_GIVEN, format!("{} overlaps {}, which the run knows", s.named(), o.named()))
                        .primary(self.file(), span, "read here")
                        .note("how PLC bytes make a word is machine data (MD10399 byte order), which the evaluator does not model")
                        .hint(format!("give {} itself, and no other width over the same bytes", s.key())),
                ));
            }
        }
        Ok(())
    }

    fn write_signal(&mut self, s: Signal, x: f64, span: Span) -> Result<(), Fault> {
        if s.read_only() {
            return Err(Fault::alarm(self.alarms.read_only, format!("{} is read-only", s.named()), span));
        }
        if s.kind == Kind::In {
            return Err(Fault::error(
                Diagnostic::error(WRITE, format!("writing {} is not modelled", s.named()))
                    .primary(self.file(), span, "here")
                    .note("no source read here says a part program may write an NCK input"),
            ));
        }
        self.store(s, x, span)?;
        self.warn(
            WRITE,
            format!("{} is written: the trace has no event for signals, so a check does not compare it", s.named()),
            span,
        );
        Ok(())
    }

    pub fn read_fanuc_signal(&mut self, s: Signal, span: Span) -> Result<Value, Fault> {
        self.read_signal(s, span)
    }

    pub fn write_fanuc_signal(&mut self, s: Signal, x: Option<f64>, span: Span) -> Result<(), Fault> {
        let Some(x) = x else {
            return Err(Fault::error(Diagnostic::error(RANGE, format!("{} cannot be vacant", s.named())).primary(
                self.file(),
                span,
                "here",
            )));
        };
        self.write_signal(s, x, span)
    }

    /// The signal `$name[i]` of a Siemens access (`name` upper case, without `$`).
    fn siemens_signal(&mut self, name: &str, idx: &[Expr], span: Span) -> Result<Signal, Fault> {
        let [e] = idx else {
            return Err(Fault::error(
                Diagnostic::error(NOT_GIVEN, format!("${name} takes one index"))
                    .primary(self.file(), span, "here")
                    .hint(format!("write ${name}[n]")),
            ));
        };
        let cx = self.cx(false);
        let n = round_half_away(expr::eval_num(self, e, &cx)?);
        match (n >= 0.0 && n <= f64::from(u32::MAX)).then(|| Signal::siemens(name, n as u32)).flatten() {
            Some(s) => Ok(s),
            None => Err(Fault::alarm(self.alarms.bad_index, format!("${name}[{n}] does not exist"), span)),
        }
    }

    pub fn read_siemens_signal(&mut self, name: &str, idx: &[Expr], span: Span) -> Result<Value, Fault> {
        let s = self.siemens_signal(name, idx, span)?;
        self.read_signal(s, span)
    }

    pub fn write_siemens_signal(&mut self, name: &str, idx: &[Expr], x: f64, span: Span) -> Result<(), Fault> {
        let s = self.siemens_signal(name, idx, span)?;
        self.write_signal(s, x, span)
    }
}
