//! Global user data (GUD, `DEF NCK …` in a library's `.DEF` file) → FANUC common
//! variables. A GUD variable keeps its value between programs (the HMI and other programs
//! write it), so its FANUC home must be the same number in every program of the library
//! and a retained common (`#500..#999`): nctrans never picks one, a `--var-map NAME=#n`
//! rule (or `[variables] to_fanuc`) places it, and without a rule the use is refused (NC504).
//! On a Haas NGC (`[fanuc] series = "haas-ngc"`) the NGC-only general-purpose ranges are
//! retained too (`dialect::fanuc::haas_vars`), so a rule may place a table in one of them.

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
    let size: u32 = crate::ir::elements(g.dims());
    if matches!(g.def.ty, DataType::String(_) | DataType::Axis | DataType::Frame) {
        let what = format!("global user data {} {name}", g.def.ty);
        let hint = if matches!(g.def.ty, DataType::String(_)) {
            "FANUC variables hold numbers only; a STRING GUD becomes the O number of the program it names when \
             the programs calling through it (CALL v, EXECSTRING(v)) are translated with those writing it, every \
             write being a literal program name of the translation"
        } else {
            "FANUC variables hold numbers only; an AXIS/FRAME GUD variable has no counterpart"
        };
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
             program of the library: map it with --var-map {name}=#n ({}), or [variables] to_fanuc in nctrans.toml",
            if ctx.haas_ngc { homes(true, true) } else { format!("#500..#{}", 1000 - size) }
        );
        ctx.error("NC504", span, &msg, &hint);
        return None;
    };
    let last = n.saturating_add(size - 1);
    if let Err(why) = fits(n, last, true, ctx.haas_ngc) {
        let msg = format!("global user data {name}{shape} would be #{n}..#{last}, {why}");
        let hint =
            format!("GUD keeps its value across programs and power-off: map it into {}", homes(true, ctx.haas_ngc));
        ctx.error("NC504", span, &msg, &hint);
        return None;
    }
    if seeds(g).is_none() {
        let msg = format!("global user data {name} has a start value that is not a number");
        ctx.error("NC504", span, &msg, "write the start value in the .DEF file as a number");
        return None;
    }
    Some(n)
}

/// The FANUC common-variable ranges a rule may place a variable in: the retained
/// `#500..#999` (with `#100..#199` unless `retained`), and on a Haas NGC (`ngc`) the
/// NGC-only general-purpose ranges, kept on power off as `#500..#999` are (Haas NGC
/// operator's manual, "Macros"; docs/semantics.md, HAAS-NGC).
pub(in crate::lower::to_fanuc) fn ranges(retained: bool, ngc: bool) -> Vec<(u32, u32)> {
    let mut out = if retained { vec![(500, 999)] } else { vec![(100, 199), (500, 999)] };
    if ngc {
        out.extend([(10000, 10099), (10200, 10499), (10700, 10799)]);
    }
    out
}

/// The ranges of [`ranges`], written out for a hint.
pub(in crate::lower::to_fanuc) fn homes(retained: bool, ngc: bool) -> String {
    let list: Vec<String> = ranges(retained, ngc).iter().map(|(a, b)| format!("#{a}..#{b}")).collect();
    match list.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
        _ => list.join(""),
    }
}

/// Whether `#lo..#hi` lies wholly inside one of [`ranges`]; the error says why not. The
/// NGC numbers with a legacy number (`#10100..#10199`, `#10500..#10699`, `#10800..#10999`)
/// are the same variables as it, so a table there would silently share `#100`/`#500`/`#800`
/// with what lives at the legacy number: refused, naming the alias. A table across two
/// ranges is refused too (the numbers between are other variables or absent).
pub(in crate::lower::to_fanuc) fn fits(lo: u32, hi: u32, retained: bool, ngc: bool) -> Result<(), String> {
    let all = ranges(retained, ngc);
    if all.iter().any(|&(a, b)| a <= lo && hi <= b) {
        return Ok(());
    }
    if ngc {
        let alias = (lo..=hi.min(lo.saturating_add(1000)))
            .find_map(|k| crate::dialect::fanuc::haas_vars::legacy(k).map(|l| (k, l)));
        if let Some((k, l)) = alias {
            return Err(format!("but #{k} on a Haas NGC is the same variable as #{l} (its NGC spelling)"));
        }
    }
    if let Some((a, b)) = all.iter().find(|&&(a, b)| ngc && a <= hi && lo <= b) {
        return Err(format!("which does not lie wholly inside #{a}..#{b}"));
    }
    Err(match (retained, lo == hi) {
        (true, true) => "not a retained common variable",
        (true, false) => "not retained common variables",
        (false, true) => "not a common variable",
        (false, false) => "not common variables",
    }
    .to_string())
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
    let len = crate::ir::elements(g.dims()) as usize;
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

#[cfg(test)]
mod tests {
    use super::fits;

    #[test]
    fn a_table_fits_wholly_inside_one_range_and_never_on_an_ngc_alias() {
        assert!(fits(500, 999, true, false).is_ok() && fits(10200, 10499, true, true).is_ok());
        assert!(fits(10000, 10099, true, true).is_ok() && fits(10700, 10799, true, true).is_ok());
        // Off the NGC profile the NGC numbers are something else.
        assert_eq!(fits(10200, 10279, true, false).unwrap_err(), "not retained common variables");
        // #100..#199 is a common, not retained: for names only.
        assert!(fits(100, 120, true, false).is_err() && fits(100, 120, false, false).is_ok());
        assert!(fits(10450, 10529, true, true)
            .unwrap_err()
            .contains("#10500 on a Haas NGC is the same variable as #500"));
        assert!(fits(10099, 10099, true, true).is_ok() && fits(10099, 10100, true, true).is_err());
        assert!(fits(980, 1000, true, true).unwrap_err().contains("wholly inside #500..#999"));
        assert_eq!(fits(11000, 11000, true, true).unwrap_err(), "not a retained common variable");
    }
}
