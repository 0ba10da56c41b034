//! Global user data (GUD, `DEF NCK …` in a library's `.DEF` file) → FANUC common
//! variables. A GUD variable keeps its value between programs (the HMI and other programs
//! write it), so its FANUC home must be the same number in every program of the library
//! and a retained common (`#500..#999`): nctrans never picks one, a `--var-map NAME=#n`
//! rule (or `[variables] to_fanuc`) places it, and without a rule the use is refused (NC504).

use super::VarRule;
use crate::ir::{DataType, Def, ExprKind, Init, UnOp};
use crate::lower::to_fanuc::Ctx;
use crate::span::Span;

/// One global variable as the translation sees it.
pub(super) struct Global<'a> {
    pub def: &'a Def,
    pub index: usize,
}

impl Global<'_> {
    pub fn dims(&self) -> &[u32] {
        &self.def.vars[self.index].dims
    }
}

/// The global definition of `name`, if the profile has one.
pub(super) fn lookup<'a>(globals: &'a [Def], name: &str) -> Option<Global<'a>> {
    globals.iter().find_map(|d| d.vars.iter().position(|v| v.name == name).map(|index| Global { def: d, index }))
}

/// The first common variable of `name` (row-major for arrays), from its rule; the
/// refusals say precisely why. `None` when refused (the diagnostic is in `ctx`).
pub(super) fn number(ctx: &mut Ctx, g: &Global, name: &str, span: Span, rules: &[VarRule]) -> Option<u32> {
    let size: u32 = g.dims().iter().product::<u32>().max(1);
    if matches!(g.def.ty, DataType::String(_) | DataType::Axis | DataType::Frame) {
        let what = format!("global user data {} {name}", g.def.ty);
        let hint = "FANUC variables hold numbers only; a STRING/AXIS/FRAME GUD variable has no counterpart";
        ctx.unsupported("NC504", span, &what, hint);
        return None;
    }
    let rule = rules.iter().find_map(|r| match r {
        VarRule::Name { name: n, number } if n == name => Some(*number),
        _ => None,
    });
    let shape = if size > 1 { format!("[…] ({size} elements)") } else { String::new() };
    let Some(n) = rule else {
        let msg = format!("global user data {name}{shape} (DEF NCK/CHAN in a .DEF file) has no FANUC variable");
        let hint = format!(
            "it keeps its value between programs, so it needs the same retained common variables in every \
             program of the library: map it with --var-map {name}=#n (#500..#{}), or [variables] to_fanuc in nctrans.toml",
            1000 - size
        );
        ctx.error("NC504", span, &msg, &hint);
        return None;
    };
    if n < 500 || n + size - 1 > 999 {
        let msg =
            format!("global user data {name}{shape} would be #{n}..#{}, not retained common variables", n + size - 1);
        ctx.error("NC504", span, &msg, "GUD keeps its value across programs and power-off: map it into #500..#999");
        return None;
    }
    if seeds(g).is_none() {
        let msg = format!("global user data {name} has a start value that is not a number");
        ctx.error("NC504", span, &msg, "write the start value in the .DEF file as a number");
        return None;
    }
    Some(n)
}

fn constant(e: &crate::ir::Expr) -> Option<f64> {
    match &e.kind {
        ExprKind::Num(n) => Some(n.value),
        ExprKind::Unary(UnOp::Neg, x) => constant(x).map(|v| -v),
        _ => None,
    }
}

/// The start value of every element (the definition's, else 0), as the evaluator gives
/// them (`eval::access::define`): the FANUC side of a check starts its commons there.
pub(super) fn seeds(g: &Global) -> Option<Vec<f64>> {
    let len = g.dims().iter().product::<u32>().max(1) as usize;
    let mut out = vec![0.0; len];
    match &g.def.vars[g.index].init {
        None => {}
        Some(Init::Value(e)) => out[0] = constant(e)?,
        Some(Init::Set(list)) => {
            for (i, e) in list.iter().enumerate().take(len) {
                if let Some(e) = e {
                    out[i] = constant(e)?;
                }
            }
        }
        Some(Init::Rep { value, count }) => {
            let v = constant(value)?;
            let n = match count {
                Some(c) => (constant(c)?.round().max(0.0) as usize).min(len),
                None => len,
            };
            out.iter_mut().take(n).for_each(|x| *x = v);
        }
    }
    Some(out)
}
