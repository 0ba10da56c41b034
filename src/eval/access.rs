//! Variable access for the interpreter: FANUC locals, commons and system numbers,
//! Siemens R parameters, DEF variables (typed, arrays, VAR references) and `$` names.

use super::exec::{internal, Interp};
use super::expr::{self, Cx, Env};
use super::fault::Fault;
use super::value::{round_half_away, Value};
use super::vars::{flat_index, Place, Slot};
use crate::diag::Diagnostic;
use crate::ir::{Expr, ExprKind, VarKind, VarRef};
use crate::span::Span;

fn v_of(x: Option<f64>) -> Value {
    x.map_or(Value::Vacant, Value::Num)
}

impl Interp<'_> {
    pub(super) fn cur_level(&self) -> usize {
        self.frames.last().map_or(0, |f| f.level)
    }

    pub(super) fn cur_sframe(&self) -> usize {
        self.frames.last().map_or(0, |f| f.sframe)
    }

    pub(super) fn index_num(&mut self, e: &Expr) -> Result<i64, Fault> {
        let cx = self.cx(false);
        let x = expr::eval_num(self, e, &cx)?;
        Ok(round_half_away(x) as i64)
    }

    pub fn read_fanuc(&mut self, n: i64, span: Span) -> Result<Value, Fault> {
        match n {
            0 => Ok(Value::Vacant),
            1..=33 => {
                let lv = self.cur_level();
                let level = &self.vars.levels[lv];
                let v = level.vals[n as usize];
                if v.is_none() && level.written & (1u64 << n) == 0 {
                    self.warn("NC404", format!("#{n} is read but was never set (it is vacant)"), span);
                }
                Ok(v.map_or(Value::Vacant, Value::Num))
            }
            100..=999 => {
                let i = n as usize;
                let v = self.vars.commons[i];
                if v.is_none() && !self.vars.commons_written[i] {
                    self.warn("NC404", format!("#{n} is read but was never set (it is vacant)"), span);
                }
                Ok(v.map_or(Value::Vacant, Value::Num))
            }
            n if self.sem.haas_ngc && u32::try_from(n).is_ok_and(crate::dialect::fanuc::haas_vars::ngc_only) => {
                match self.vars.ngc.get(&(n as u32)) {
                    Some(x) => Ok(Value::Num(*x)),
                    None => {
                        self.warn("NC404", format!("#{n} is read but was never set (it is vacant)"), span);
                        Ok(Value::Vacant)
                    }
                }
            }
            n if self.sem.haas_ngc
                && u32::try_from(n).ok().and_then(crate::dialect::fanuc::haas_vars::legacy).is_some() =>
            {
                // A computed `#[…]` reaching an NGC number with a legacy one.
                self.read_fanuc(n - 10000, span)
            }
            n if self.is_haas_data(n) => self.read_haas_data(n, span),
            n if self.is_tool_data(n) => self.read_fanuc_tool_data(n, span),
            n if let Some(s) = self.signal_at(n) => self.read_fanuc_signal(s, span),
            n if n >= 1000 => self.fanuc_sys_read(n, span),
            _ => Err(Fault::alarm(self.alarms.bad_index, format!("variable #{n} does not exist"), span)),
        }
    }

    pub fn write_fanuc(&mut self, n: i64, v: Value, span: Span) -> Result<(), Fault> {
        let x = match v {
            Value::Vacant => None,
            Value::Num(x) => Some(x),
            Value::Str(_) => return Err(Fault::alarm(self.alarms.domain, "string value", span)),
        };
        match n {
            1..=33 => {
                let lv = self.cur_level();
                let level = &mut self.vars.levels[lv];
                level.vals[n as usize] = x;
                level.written |= 1u64 << n;
                Ok(())
            }
            100..=999 => {
                self.vars.commons[n as usize] = x;
                self.vars.commons_written[n as usize] = true;
                Ok(())
            }
            n if self.sem.haas_ngc && u32::try_from(n).is_ok_and(crate::dialect::fanuc::haas_vars::ngc_only) => {
                match x {
                    Some(x) => self.vars.ngc.insert(n as u32, x),
                    None => self.vars.ngc.remove(&(n as u32)),
                };
                Ok(())
            }
            n if self.sem.haas_ngc
                && u32::try_from(n).ok().and_then(crate::dialect::fanuc::haas_vars::legacy).is_some() =>
            {
                self.write_fanuc(n - 10000, v_of(x), span)
            }
            n if self.is_haas_data(n) => self.write_haas_data(n, span),
            n if self.is_tool_data(n) => self.write_fanuc_tool_data(n, x, span),
            n if let Some(s) = self.signal_at(n) => self.write_fanuc_signal(s, x, span),
            n if n >= 1000 => self.fanuc_sys_write(n, x, span),
            _ => Err(Fault::alarm(self.alarms.bad_index, format!("variable #{n} cannot be written"), span)),
        }
    }

    pub(super) fn r_index(&mut self, n: i64, span: Span) -> Result<usize, Fault> {
        if n < 0 || n as usize >= self.vars.r.len() {
            return Err(Fault::alarm(
                self.alarms.bad_index,
                format!("R{n} does not exist (R0..R{})", self.vars.r.len().saturating_sub(1)),
                span,
            ));
        }
        Ok(n as usize)
    }

    pub(super) fn read_r(&mut self, n: i64, span: Span) -> Result<Value, Fault> {
        let i = self.r_index(n, span)?;
        if !self.vars.r_written[i] {
            self.warn("NC404", format!("R{n} is read but was never set (it is 0)"), span);
        }
        Ok(Value::Num(self.vars.r[i]))
    }

    /// Resolves a Siemens named variable to its place (following VAR references).
    pub(super) fn place_of(&mut self, name: &str, indices: &[Expr], span: Span) -> Result<Place, Fault> {
        let cur = self.cur_sframe();
        let Some(fi) = self.vars.frame_of(cur, name) else {
            return Err(Fault::error(
                Diagnostic::error("NC412", format!("variable {name} is not defined"))
                    .primary(self.file(), span, "used here")
                    .hint("declare it with DEF at the start of the program"),
            ));
        };
        let mut idx = Vec::with_capacity(indices.len());
        for e in indices {
            idx.push(self.index_num(e)?);
        }
        let slot = self.vars.frames[fi].get(name).cloned();
        match slot {
            Some(Slot::Ref(Place::Named { frame, name: n2, index: None })) => {
                let dims = match self.vars.frames.get(frame).and_then(|f| f.get(&n2)) {
                    Some(Slot::Own { dims, .. }) => dims.clone(),
                    _ => vec![],
                };
                let flat = self.flat(&dims, &idx, name, span)?;
                Ok(Place::Named { frame, name: n2, index: Some(flat) })
            }
            Some(Slot::Ref(p)) => Ok(p),
            Some(Slot::Own { dims, .. }) => {
                let flat = self.flat(&dims, &idx, name, span)?;
                Ok(Place::Named { frame: fi, name: name.to_string(), index: Some(flat) })
            }
            None => Err(internal()),
        }
    }

    pub(super) fn flat(&self, dims: &[u32], idx: &[i64], name: &str, span: Span) -> Result<usize, Fault> {
        if dims.is_empty() && idx.is_empty() {
            return Ok(0);
        }
        flat_index(dims, idx).ok_or_else(|| {
            Fault::alarm(self.alarms.bad_index, format!("index {idx:?} outside the array {name}{dims:?}"), span)
        })
    }

    pub(super) fn read_place(&mut self, p: &Place, span: Span) -> Result<Value, Fault> {
        match p {
            Place::R(i) => self.read_r(*i as i64, span),
            Place::Named { frame, name, index } => match self.vars.frames.get(*frame).and_then(|f| f.get(name)) {
                Some(Slot::Own { data, .. }) => data.get(index.unwrap_or(0)).cloned().ok_or_else(internal),
                _ => Err(internal()),
            },
        }
    }

    pub(super) fn write_place(&mut self, p: &Place, v: Value, span: Span) -> Result<(), Fault> {
        match p {
            Place::R(i) => {
                let i = self.r_index(*i as i64, span)?;
                let x =
                    v.num().ok_or_else(|| Fault::alarm(self.alarms.domain, "a string cannot be stored in R", span))?;
                self.vars.r[i] = x;
                self.vars.r_written[i] = true;
                Ok(())
            }
            Place::Named { frame, name, index } => {
                let alarms = self.alarms;
                match self.vars.frames.get_mut(*frame).and_then(|f| f.get_mut(name)) {
                    Some(Slot::Own { ty, data, .. }) => {
                        let conv = super::value::convert_for(*ty, v).map_err(|e| match e {
                            super::value::ConvError::Range(x) => {
                                Fault::alarm(alarms.overflow, format!("value {x} out of range for {name}"), span)
                            }
                            super::value::ConvError::Type => {
                                Fault::alarm(alarms.domain, format!("wrong type of value for {name}"), span)
                            }
                        })?;
                        let slot = data.get_mut(index.unwrap_or(0)).ok_or_else(internal)?;
                        *slot = conv;
                        Ok(())
                    }
                    _ => Err(internal()),
                }
            }
        }
    }

    pub fn write_var(&mut self, v: &VarRef, val: Value) -> Result<(), Fault> {
        match &v.kind {
            VarKind::Hash(n) => self.write_fanuc(i64::from(*n), val, v.span),
            VarKind::HashIndirect(e) => {
                let n = self.index_num(e)?;
                self.write_fanuc(n, val, v.span)
            }
            VarKind::R(n) => self.write_place(&Place::R(*n as usize), val, v.span),
            VarKind::RIndirect(e) => {
                let n = self.index_num(e)?;
                let i = self.r_index(n, v.span)?;
                self.write_place(&Place::R(i), val, v.span)
            }
            VarKind::Named { name, indices }
                if indices.len() == 1 && name == "FGREF" && self.vars.frame_of(self.cur_sframe(), name).is_none() =>
            {
                let x = val.num().ok_or_else(|| Fault::alarm(self.alarms.domain, "FGREF needs a number", v.span))?;
                self.fgref(&indices[0], x, v.span)
            }
            VarKind::Named { name, indices } => {
                let p = self.place_of(name, indices, v.span)?;
                self.refuse_fixed_write(&p, v.span)?;
                self.write_place(&p, val, v.span)
            }
            VarKind::System { name, indices } => match super::tool_data::tc_dp(name) {
                Some(n) => {
                    let x = val
                        .num()
                        .ok_or_else(|| Fault::alarm(self.alarms.domain, format!("${name} needs a number"), v.span))?;
                    self.write_siemens_tool_data(n, indices, x, v.span)
                }
                None if crate::dialect::signals::is_siemens_signal(name) => {
                    let x = val
                        .num()
                        .ok_or_else(|| Fault::alarm(self.alarms.domain, format!("${name} needs a number"), v.span))?;
                    self.write_siemens_signal(name, indices, x, v.span)
                }
                None => self.sie_sys_write(name, indices, val, v.span),
            },
        }
    }

    /// A read of global user data the set-up fixes: the run rests on that value, and says so
    /// once per name (a check's verdict names it, `check::Excluded::assumed`).
    fn note_fixed_read(&mut self, p: &Place, span: Span) {
        let Place::Named { frame: 0, name, .. } = p else { return };
        let Some(value) = self.sem.fixed.get(name) else { return };
        if !self.sem.globals.iter().any(|d| d.vars.iter().any(|v| v.name == *name)) {
            return;
        }
        let msg = crate::dialect::fixed::note_message(name, value);
        if !self.diags.iter().any(|d| d.message == msg) {
            let file = self.file();
            let d = Diagnostic::new(crate::diag::Severity::Note, crate::dialect::fixed::ASSUMED, msg).primary(
                file,
                span,
                "read here",
            );
            self.diags.push(d);
        }
    }

    /// A write to global user data the set-up fixes (`Semantics::fixed`): the run's
    /// assumption that no program writes it would be false.
    fn refuse_fixed_write(&self, p: &Place, span: Span) -> Result<(), Fault> {
        let Place::Named { frame: 0, name, .. } = p else { return Ok(()) };
        let global = || self.sem.globals.iter().any(|d| d.vars.iter().any(|v| v.name == *name));
        if !self.sem.fixed.contains_key(name) || !global() {
            return Ok(());
        }
        Err(Fault::error(
            Diagnostic::error(
                crate::dialect::fixed::WRITTEN,
                format!("the program writes {name}, which the set-up fixes (variables.fixed)"),
            )
            .primary(self.file(), span, "written here")
            .note("[variables] fixed says no program writes it; this run and the translation rest on that")
            .hint(format!("take {name} out of [variables] fixed, or the write out of the program")),
        ))
    }

    pub(super) fn define(&mut self, def: &crate::ir::Def) -> Result<(), Fault> {
        let sf = self.cur_sframe();
        for dv in &def.vars {
            let Some(len) = super::vars::array_len(&dv.dims) else {
                return Err(Fault::alarm(self.alarms.bad_index, format!("array {} too large", dv.name), dv.span));
            };
            let zero = super::vars::zero_of(def.ty);
            let mut data = vec![zero; len];
            let input = if self.frames.len() == 1 {
                self.inputs
                    .iter()
                    .find(|i| matches!(&i.target, super::InputTarget::Name(n) if *n == dv.name))
                    .map(|i| i.value.clone())
            } else {
                None
            };
            // Global user data the set-up fixes starts at that value (an input still wins).
            let input =
                input.or_else(|| def.scope.and_then(|_| self.sem.fixed.get(&dv.name)).map(|t| Value::Str(t.clone())));
            let conv = |v: Value, s: &Self| {
                super::value::convert_for(def.ty, v)
                    .map_err(|_| Fault::alarm(s.alarms.domain, format!("bad start value for {}", dv.name), dv.span))
            };
            if let Some(v) = input {
                data[0] = conv(v, self)?;
            } else if let Some(init) = &dv.init {
                let cx = self.cx(false);
                match init {
                    crate::ir::Init::Value(e) => {
                        let v = expr::eval(self, e, &cx)?;
                        let v = conv(v, self)?;
                        for d in data.iter_mut() {
                            *d = v.clone();
                        }
                        if len > 1 {
                            // A scalar start value of an array sets the first element only.
                            for d in data.iter_mut().skip(1) {
                                *d = super::vars::zero_of(def.ty);
                            }
                        }
                    }
                    crate::ir::Init::Set(list) => {
                        for (i, e) in list.iter().enumerate() {
                            if let (Some(e), true) = (e, i < len) {
                                let v = expr::eval(self, e, &cx)?;
                                data[i] = conv(v, self)?;
                            }
                        }
                    }
                    crate::ir::Init::Rep { value, count } => {
                        let v = expr::eval(self, value, &cx)?;
                        let v = conv(v, self)?;
                        let n = match count {
                            Some(c) => (round_half_away(expr::eval_num(self, c, &cx)?).max(0.0) as usize).min(len),
                            None => len,
                        };
                        for d in data.iter_mut().take(n) {
                            *d = v.clone();
                        }
                    }
                }
            }
            self.vars.frames[sf].insert(dv.name.clone(), Slot::Own { ty: def.ty, dims: dv.dims.clone(), data });
        }
        Ok(())
    }

    /// A Siemens VAR argument's place in the caller.
    pub fn place_of_arg(&mut self, e: &Expr) -> Result<Option<Place>, Fault> {
        let ExprKind::Var(v) = &e.kind else {
            return Ok(None);
        };
        Ok(Some(match &v.kind {
            VarKind::R(n) => Place::R(*n as usize),
            VarKind::RIndirect(ix) => {
                let n = self.index_num(ix)?;
                Place::R(self.r_index(n, v.span)?)
            }
            VarKind::Named { name, indices } if indices.is_empty() => {
                let cur = self.cur_sframe();
                match self.vars.frame_of(cur, name) {
                    Some(fi) => match self.vars.frames[fi].get(name) {
                        Some(Slot::Ref(p)) => p.clone(),
                        _ => Place::Named { frame: fi, name: name.clone(), index: None },
                    },
                    None => return Ok(None),
                }
            }
            VarKind::Named { name, indices } => self.place_of(name, indices, v.span)?,
            _ => return Ok(None),
        }))
    }
}

impl Env for Interp<'_> {
    fn tool_number(&self, name: &str) -> Option<Option<u32>> {
        (!self.sem.tools.is_empty()).then(|| self.sem.tools.get(name).copied())
    }
    fn read(&mut self, var: &VarRef, _cx: &Cx) -> Result<Value, Fault> {
        match &var.kind {
            VarKind::Hash(n) => self.read_fanuc(i64::from(*n), var.span),
            VarKind::HashIndirect(e) => {
                let n = self.index_num(e)?;
                self.read_fanuc(n, var.span)
            }
            VarKind::R(n) => self.read_r(i64::from(*n), var.span),
            VarKind::RIndirect(e) => {
                let n = self.index_num(e)?;
                self.read_r(n, var.span)
            }
            VarKind::Named { name, indices } => {
                let p = self.place_of(name, indices, var.span)?;
                self.note_fixed_read(&p, var.span);
                self.read_place(&p, var.span)
            }
            VarKind::System { name, indices } => match super::tool_data::tc_dp(name) {
                Some(n) => self.read_siemens_tool_data(n, indices, var.span),
                None if crate::dialect::signals::is_siemens_signal(name) => {
                    self.read_siemens_signal(name, indices, var.span)
                }
                None => self.sie_sys_read(name, indices, var.span),
            },
        }
    }
}
