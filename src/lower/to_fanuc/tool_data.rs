//! Siemens cutting edge data `$TC_DP3/6/12/15[t,d]` → FANUC tool compensation memory C
//! variables (`#11000+H` length geometry, `#10000+H` length wear, `#13000+D` radius geometry,
//! `#12000+D` radius wear), through the set-up's offset map (`[offsets]`: edge t.d is H and D;
//! by default edge 1 of tool n is H n, D n), the same map the D → G43 H / G41 D translation
//! uses. docs/semantics.md, Tool offset data. Runs before the variable mapping, which leaves
//! `#n` alone.

use super::varmap::visit_vars;
use super::Ctx;
use crate::eval::tool_data::{fanuc_var, siemens_field, siemens_field_name, tc_dp};
use crate::ir::*;
use crate::lower::{bin, num};
use crate::span::Span;

pub fn run(ctx: &mut Ctx, prog: &mut Program) {
    let mut errs: Vec<(&'static str, Span, String, String)> = Vec::new();
    let (haas, offsets) = (ctx.haas, ctx.offsets.clone());
    visit_vars(&mut prog.body, &mut |v| {
        let VarKind::System { name, indices } = &v.kind else { return };
        if let Some(k) = name.strip_prefix("TC_TP") {
            // Tool data (name, duplo, size, holder …): the tool map knows names and numbers only.
            let what = format!("$TC_TP{k} (tool data of tool management: name, duplo number, size, …)");
            let hint = "FANUC has no tool management data; the tool map gives names their T numbers: use T=\"NAME\" or GETT(\"NAME\")";
            errs.push(("NC526", v.span, what, hint.into()));
            return;
        }
        let Some(n) = tc_dp(name) else { return };
        let span = v.span;
        let Some(field) = siemens_field(n) else {
            let what = format!("$TC_DP{n} ({})", siemens_field_name(n));
            let hint = "FANUC tool compensation memory holds a length and a radius per register (geometry and wear): \
                        only $TC_DP3, $TC_DP6, $TC_DP12 and $TC_DP15 have counterparts";
            errs.push(("NC526", span, what, hint.into()));
            return;
        };
        if haas {
            let what = format!("$TC_DP{n} on a Haas control");
            let hint = "Haas numbers its tool offset variables differently (#2001+, and #10000+ are commons on NGC); \
                        this translation knows FANUC memory C only";
            errs.push(("NC528", span, what, hint.into()));
            return;
        }
        let konst = |e: &Expr| match &e.kind {
            ExprKind::Num(x) if x.value.fract() == 0.0 && x.value >= 1.0 => Some(x.value as u32),
            _ => None,
        };
        let [t, d] = indices.as_slice() else {
            errs.push(("NC527", span, format!("$TC_DP{n} without the two indices [tool, edge]"), String::new()));
            return;
        };
        let pick = |(h, dr): (u32, u32)| if field.is_length() { h } else { dr };
        v.kind = match (konst(t), konst(d)) {
            (Some(t), Some(d)) => match offsets.registers(t, d) {
                Some(r) => VarKind::Hash(fanuc_var(field, pick(r))),
                None => {
                    let what = format!("$TC_DP{n}[{t},{d}] (edge {t}.{d} has no FANUC registers)");
                    let hint = format!(
                        "give its H and D registers under [offsets] in nctrans.toml: \"{t}.{d}\" = \"H..,D..\""
                    );
                    errs.push(("NC527", span, what, hint));
                    return;
                }
            },
            // A computed tool on edge 1 with the default map: the register is the tool number.
            (None, Some(1)) if offsets.edges.is_empty() => {
                let base = f64::from(fanuc_var(field, 0));
                VarKind::HashIndirect(Box::new(bin(BinOp::Add, t.clone(), num(base, span))))
            }
            _ => {
                let what = format!("$TC_DP{n}[…] with a computed edge (its FANUC register depends on the offset map)");
                let hint =
                    "write the tool and edge as numbers, or a computed tool on edge 1 without an [offsets] table";
                errs.push(("NC527", span, what, hint.into()));
                return;
            }
        };
    });
    for (code, span, what, hint) in errs {
        ctx.unsupported(code, span, &what, &hint);
    }
}
