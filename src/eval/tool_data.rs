//! Tool offset data read and written by programs: Siemens cutting edge data
//! `$TC_DP3/6/12/15[t,d]` (length 1 and radius, geometry and wear) and FANUC tool compensation
//! memory C (`#11001+` H geometry, `#10001+` H wear, `#13001+` D geometry, `#12001+` D wear),
//! docs/semantics.md, Tool offset data. The values are the machine's: a run takes them from
//! its inputs (`--set '#11005=120.5'`, `--set '$TC_DP3[5,1]=120.5'`) or from the program's own
//! writes; a read of one it does not know is refused (NC571), never a silent 0. Every write
//! is a `tool_data` trace event naming the register, so a translation that writes another
//! register (or geometry for wear) than the moves use is caught by the check.

use super::exec::Interp;
use super::expr;
use super::fault::Fault;
use super::trace::{CompReg, Event, ToolDataEv, ToolField};
use super::value::{round_half_away, Value};
use crate::diag::Diagnostic;
use crate::ir::Expr;
use crate::span::Span;

/// The cutting edge parameter `n` of `$TC_DPn` that has a FANUC memory C counterpart.
pub fn siemens_field(n: u32) -> Option<ToolField> {
    match n {
        3 => Some(ToolField::LengthGeometry),
        12 => Some(ToolField::LengthWear),
        6 => Some(ToolField::RadiusGeometry),
        15 => Some(ToolField::RadiusWear),
        _ => None,
    }
}

/// What Siemens cutting edge parameter `n` is (840D PGA 04.00, 8.1, tool parameters).
pub fn siemens_field_name(n: u32) -> &'static str {
    match n {
        1 => "the tool type",
        2 => "the cutting edge position (turning)",
        3 => "length 1 (geometry)",
        4 => "length 2 (geometry)",
        5 => "length 3 (geometry)",
        6 => "the radius (geometry)",
        7 => "the slot width / corner radius",
        8 => "the overhang",
        11 => "the angle of a cone milling tool",
        12 => "length 1 wear",
        13 => "length 2 wear",
        14 => "length 3 wear",
        15 => "the radius wear",
        16 => "the slot width / corner radius wear",
        17 => "the overhang wear",
        20 => "the cone angle wear",
        21..=23 => "an adapter (base) length",
        24 => "the clearance angle",
        _ => "a reserved or machine builder's parameter",
    }
}

/// FANUC memory C variable `n`: (field, register number).
pub fn fanuc_field(n: i64) -> Option<(ToolField, i64)> {
    let (f, base) = match n {
        10001..=10999 => (ToolField::LengthWear, 10000),
        11001..=11999 => (ToolField::LengthGeometry, 11000),
        12001..=12999 => (ToolField::RadiusWear, 12000),
        13001..=13999 => (ToolField::RadiusGeometry, 13000),
        _ => return None,
    };
    Some((f, n - base))
}

/// The data a `G10 L10..L13` writes (memory C: H geometry, H wear, D geometry, D wear);
/// `None` for any other L, a fractional one among them.
pub fn g10_field(l: f64) -> Option<ToolField> {
    Some(match l {
        10.0 => ToolField::LengthGeometry,
        11.0 => ToolField::LengthWear,
        12.0 => ToolField::RadiusGeometry,
        13.0 => ToolField::RadiusWear,
        _ => return None,
    })
}

/// The L of the `G10` that writes `field` (the inverse of [`g10_field`]).
pub fn g10_l(field: ToolField) -> u32 {
    match field {
        ToolField::LengthGeometry => 10,
        ToolField::LengthWear => 11,
        ToolField::RadiusGeometry => 12,
        ToolField::RadiusWear => 13,
    }
}

/// The FANUC memory C variable of `field` for register `reg` (the inverse of [`fanuc_field`]).
pub fn fanuc_var(field: ToolField, reg: u32) -> u32 {
    let base = match field {
        ToolField::LengthWear => 10000,
        ToolField::LengthGeometry => 11000,
        ToolField::RadiusWear => 12000,
        ToolField::RadiusGeometry => 13000,
    };
    base + reg
}

/// The key of a Siemens edge value in the store.
fn edge_key(n: u32, t: i64, d: i64) -> String {
    format!("$TC_DP{n}[{t},{d}]")
}

impl Interp<'_> {
    /// `#n` is tool compensation memory C on this control (not on a Haas, whose numbers differ).
    pub fn is_tool_data(&self, n: i64) -> bool {
        !self.sem.haas && fanuc_field(n).is_some()
    }

    /// An input of the machine's value: kept, no event.
    pub fn set_tool_data(&mut self, key: String, v: &Value) -> Result<(), Fault> {
        match v {
            Value::Num(x) => {
                self.m.tool_data.insert(key, *x);
                Ok(())
            }
            _ => Err(Fault::error(Diagnostic::error("NC571", format!("input {key}: tool offset data is a number")))),
        }
    }

    fn not_given(&self, key: &str, what: &str, span: Span) -> Fault {
        Fault::error(
            Diagnostic::error("NC571", format!("{key} ({what}) is read before the program wrote it"))
                .primary(self.file(), span, "read here")
                .note("tool offsets are the machine's data: a run knows only those it is given or the program writes")
                .hint(format!("give the machine's value: --set '{key}=…' or a header line `nctrans: set {key}=…`")),
        )
    }

    pub fn read_fanuc_tool_data(&mut self, n: i64, span: Span) -> Result<Value, Fault> {
        let key = format!("#{n}");
        match self.m.tool_data.get(&key) {
            Some(x) => Ok(Value::Num(*x)),
            None => {
                let (f, r) = fanuc_field(n).unwrap_or((ToolField::LengthGeometry, 0));
                Err(self.not_given(&key, &format!("offset {r} {}", f.name()), span))
            }
        }
    }

    pub fn write_fanuc_tool_data(&mut self, n: i64, x: Option<f64>, span: Span) -> Result<(), Fault> {
        let (field, reg) = fanuc_field(n).unwrap_or((ToolField::LengthGeometry, 0));
        let value = x.unwrap_or(0.0);
        self.m.tool_data.insert(format!("#{n}"), value);
        self.emit(Event::ToolData(Box::new(ToolDataEv { register: CompReg::Fanuc(reg), field, value })), span);
        Ok(())
    }

    /// The edge `[t, d]` of a `$TC_DPn` access.
    fn edge_of(&mut self, n: u32, idx: &[Expr], span: Span) -> Result<(i64, i64), Fault> {
        let [t, d] = idx else {
            return Err(Fault::error(
                Diagnostic::error("NC571", format!("$TC_DP{n} takes two indices, [tool, edge]"))
                    .primary(self.file(), span, "here")
                    .hint(format!("write $TC_DP{n}[T, D], e.g. $TC_DP{n}[5,1]")),
            ));
        };
        let cx = self.cx(false);
        let t = round_half_away(expr::eval_num(self, t, &cx)?) as i64;
        let d = round_half_away(expr::eval_num(self, d, &cx)?) as i64;
        if t < 1 || d < 1 {
            return Err(Fault::alarm(self.alarms.bad_index, format!("$TC_DP{n}[{t},{d}] does not exist"), span));
        }
        Ok((t, d))
    }

    fn siemens_modelled(&self, n: u32, span: Span) -> Result<ToolField, Fault> {
        siemens_field(n).ok_or_else(|| {
            Fault::error(
                Diagnostic::error("NC526", format!("$TC_DP{n} ({}) is not modelled", siemens_field_name(n)))
                    .primary(self.file(), span, "here")
                    .note("modelled: $TC_DP3 (length 1), $TC_DP6 (radius), $TC_DP12, $TC_DP15 (their wear)")
                    .hint("FANUC tool compensation memory has a length and a radius per register, geometry and wear"),
            )
        })
    }

    pub fn read_siemens_tool_data(&mut self, n: u32, idx: &[Expr], span: Span) -> Result<Value, Fault> {
        let field = self.siemens_modelled(n, span)?;
        let (t, d) = self.edge_of(n, idx, span)?;
        let key = edge_key(n, t, d);
        match self.m.tool_data.get(&key) {
            Some(x) => Ok(Value::Num(*x)),
            None => Err(self.not_given(&key, field.name(), span)),
        }
    }

    pub fn write_siemens_tool_data(&mut self, n: u32, idx: &[Expr], x: f64, span: Span) -> Result<(), Fault> {
        let field = self.siemens_modelled(n, span)?;
        let (t, d) = self.edge_of(n, idx, span)?;
        self.m.tool_data.insert(edge_key(n, t, d), x);
        let register = CompReg::Edge(format!("{t}.{d}"));
        self.emit(Event::ToolData(Box::new(ToolDataEv { register, field, value: x })), span);
        Ok(())
    }
}

/// `$TC_DPn` as a name: `Some(n)`.
pub fn tc_dp(name: &str) -> Option<u32> {
    name.strip_prefix("TC_DP").and_then(|s| s.parse().ok()).filter(|n| (1..=25).contains(n))
}
