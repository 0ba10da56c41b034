//! FANUC tool compensation memory C (`#11001+` H geometry, `#10001+` H wear, `#13001+` D
//! geometry, `#12001+` D wear) → Siemens cutting edge data `$TC_DP3/12/6/15[t,d]`, the
//! edge the set-up's offset map gives the register (by default H n and D n are edge 1 of
//! tool n), the inverse of `lower::to_fanuc::tool_data`. docs/semantics.md, Tool offset data.
//! Runs first on a body, while the variables are still FANUC's; a Haas source is left alone
//! (its numbers differ, and `#10000+` are commons on NGC).

use super::Ctx;
use crate::dialect::offsets::OffsetMap;
use crate::eval::tool_data::fanuc_field;
use crate::eval::trace::ToolField;
use crate::ir::*;
use crate::lower::to_fanuc::varmap::visit_vars;
use crate::span::Span;

/// The Siemens parameter number of a memory C value.
fn dp(field: ToolField) -> u32 {
    match field {
        ToolField::LengthGeometry => 3,
        ToolField::LengthWear => 12,
        ToolField::RadiusGeometry => 6,
        ToolField::RadiusWear => 15,
    }
}

fn int(v: u32, span: Span) -> Expr {
    Expr::num(f64::from(v), false, span)
}

/// The edge (tool, edge number) whose `field` register is `reg`: the offset map's entry,
/// else edge 1 of tool `reg` when that tool has no entry (the default).
fn edge_of(offsets: &OffsetMap, field: ToolField, reg: u32) -> Option<(u32, u32)> {
    let named = offsets.edges.iter().find(|(_, r)| if field.is_length() { r.0 } else { r.1 } == reg);
    match named {
        Some((&e, _)) => Some(e),
        None => offsets.registers(reg, 1).map(|_| (reg, 1)),
    }
}

/// The edge (tool, edge number) whose length registers are H `reg`, `None` when no edge has
/// them (for the length a `#5043` read includes, `position_length`).
pub fn length_edge(offsets: &OffsetMap, reg: u32) -> Option<(u32, u32)> {
    edge_of(offsets, ToolField::LengthGeometry, reg)
}

/// `$TC_DP3[12,1]` for `#11012` (an input line's variable), `None` when no edge has it.
pub fn edge_var(n: u32, offsets: &OffsetMap) -> Option<String> {
    let (field, reg) = fanuc_field(i64::from(n))?;
    let (t, d) = edge_of(offsets, field, reg as u32)?;
    Some(format!("$TC_DP{}[{t},{d}]", dp(field)))
}

pub fn lower(ctx: &mut Ctx, mut body: Vec<Stmt>) -> Vec<Stmt> {
    if ctx.opts.source.haas {
        return body;
    }
    let offsets = ctx.opts.source.offsets.clone();
    let mut errs: Vec<(Span, String, String)> = Vec::new();
    visit_vars(&mut body, &mut |v| {
        let span = v.span;
        let sys = |field: ToolField, t: Expr, d: u32| VarKind::System {
            name: format!("TC_DP{}", dp(field)),
            indices: vec![t, int(d, span)],
        };
        match &v.kind {
            VarKind::Hash(n) => {
                let Some((field, reg)) = fanuc_field(i64::from(*n)) else { return };
                let reg = reg as u32;
                match edge_of(&offsets, field, reg) {
                    Some((t, d)) => v.kind = sys(field, int(t, span), d),
                    None => errs.push((
                        span,
                        format!("#{n} (tool offset {reg}, {})", field.name()),
                        format!(
                            "no cutting edge has this register: name it under [offsets] (\"T.D\" = \"H{reg},D..\")"
                        ),
                    )),
                }
            }
            // `#[11000+#4120]`: a computed register, edge 1 of that tool with the default map.
            VarKind::HashIndirect(e) => {
                let ExprKind::Binary(BinOp::Add, a, b) = &e.kind else { return };
                let (base, rest) = match (&a.kind, &b.kind) {
                    (ExprKind::Num(x), _) => (x.value, b),
                    (_, ExprKind::Num(x)) => (x.value, a),
                    _ => return,
                };
                if base.fract() != 0.0 || !matches!(base as i64, 10000 | 11000 | 12000 | 13000) {
                    return;
                }
                let Some((field, _)) = fanuc_field(base as i64 + 1) else { return };
                if !offsets.edges.is_empty() {
                    errs.push((
                        span,
                        format!("#[{base}+…] (a computed tool offset register)"),
                        "with an [offsets] table the edge of a computed register is not known: write the register number"
                            .into(),
                    ));
                    return;
                }
                v.kind = sys(field, (**rest).clone(), 1);
            }
            _ => {}
        }
    });
    for (span, what, hint) in errs {
        ctx.unsupported("NC529", span, &what, &hint);
    }
    body
}

/// `G10 L10..L13 Pp Rv` (memory C: H geometry, H wear, D geometry, D wear) → the write of the
/// cutting edge data of the register's edge; `incremental` (G91, `None`: not known here)
/// adds to it. The block's G90/G91 stays in force for later blocks (G10's own G code not).
pub fn g10(
    ctx: &mut Ctx,
    field: ToolField,
    p: Option<Expr>,
    r: Option<Expr>,
    incremental: Option<bool>,
    meta: BlockMeta,
    span: Span,
) -> Vec<Stmt> {
    let l = crate::eval::tool_data::g10_l(field);
    let bare = matches!(&r.as_ref().map(|e| &e.kind), Some(ExprKind::Num(x)) if !x.point)
        && super::words::scales_bare(ctx.opts);
    let offsets = ctx.opts.source.offsets.clone();
    let mut refuse = |what: String, hint: &str| ctx.unsupported("NC529", span, &what, hint).into_iter().collect();
    let reg = match p.as_ref().map(|e| &e.kind) {
        Some(ExprKind::Num(x)) if x.value.fract() == 0.0 && x.value >= 1.0 => x.value as u32,
        _ => return refuse(format!("`G10 L{l}` with a P other than a constant offset number"), "write P as a number"),
    };
    let Some(r) = r else { return refuse(format!("`G10 L{l} P{reg}` without R"), "give the value with R") };
    if bare {
        return refuse(
            format!("`G10 L{l} P{reg} R` written without a decimal point (its value depends on the increment system)"),
            "write R with a decimal point",
        );
    }
    let Some(inc) = incremental else {
        return refuse(
            format!("`G10 L{l}` where G90/G91 depends on the path taken"),
            "write G90 or G91 in the G10 block",
        );
    };
    let Some((t, d)) = edge_of(&offsets, field, reg) else {
        return refuse(
            format!("`G10 L{l} P{reg}` (no cutting edge has register {reg})"),
            "name the edge under [offsets] (\"T.D\" = \"H..,D..\")",
        );
    };
    let target = VarRef {
        kind: VarKind::System { name: format!("TC_DP{}", dp(field)), indices: vec![int(t, span), int(d, span)] },
        span,
    };
    let value = if inc {
        crate::lower::bin(BinOp::Add, Expr::new(ExprKind::Var(Box::new(target.clone())), span), r)
    } else {
        r
    };
    let item = Item { kind: ItemKind::Assign { target: Box::new(target), value }, span };
    vec![Stmt { kind: StmtKind::Block(Block { meta, items: vec![item] }), span }]
}
