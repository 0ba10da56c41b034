//! The kept skip position of Z (`#5063`, from the Siemens `$AA_MW[Z]`/`$AA_IW[Z]` form that
//! `probe` recognises) where a cutting edge may carry a length: the edge becomes `G43 H` on
//! FANUC, and FANUC's `#5063` under G43 includes the length offset in force at the G31
//! (docs/semantics.md, Probing), while Siemens measures the tool tip. Where the compensation
//! flow (`comp`) knows the H register FANUC applies at the G31, the keep right after the
//! measuring block takes it off: `T=#5063-[#11000+h+#10000+h]` (geometry plus wear, memory
//! C, read where nothing has written them since the G31), and under G49 it stays `T=#5063`.
//! Refused (NC551) where the H at the G31 is not known (a path or call that decides it, a
//! `PROC` run under its caller's edge, an edge change in the measuring block), and for a
//! `#5063` read away from its measuring block (the translation's own skip variable); on a
//! Haas target, whose offset tables are not the registers the length is read from, NC655.
//! A program that selects no edge but `D0` (no D word other than `D0`, no tool change
//! without `D0` in its block) and is not a `PROC` needs nothing.

use super::*;

/// The diagnostic of a Z skip position read where the edge's H register is not known.
pub const UNDER_EDGE: &str = "NC551";

/// The diagnostic of a Z skip position read where an edge may be active on a Haas target.
pub const HAAS: &str = "NC655";

/// Whether a block selects an edge other than `D0` (a D word, or a tool change without D0).
fn selects_edge(items: &[Item]) -> bool {
    let word = |l: u8| {
        items.iter().filter_map(move |it| match &it.kind {
            ItemKind::Word(Word { addr: Addr::Letter(a), value: WordValue::Expr(e), .. }) if *a == l => {
                Some(crate::lower::literal(e))
            }
            _ => None,
        })
    };
    let d0 = word(b'D').any(|d| d == Some(0.0));
    let other_d = word(b'D').any(|d| d != Some(0.0));
    let m6 = word(b'M').any(|m| m == Some(6.0));
    other_d || (m6 && !d0)
}

fn reads_z_skip(e: &Expr, out: &mut Vec<Span>) {
    if let ExprKind::Var(v) = &e.kind {
        if let VarKind::Hash(5063) = v.kind {
            out.push(v.span);
        }
    }
    for c in e.children() {
        reads_z_skip(c, out);
    }
}

/// Whether a cutting edge may be active somewhere in `prog`: a block selects one (a D other
/// than `D0`, a tool change without `D0`), or it is a `PROC` (run under its caller's edge).
pub fn may_select_edge(prog: &Program) -> bool {
    let mut edge = prog.head.is_some() && matches!(prog.name, Some(ProgName::Name(_)));
    crate::ir::visit::walk_stmts(&prog.body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            edge |= selects_edge(&b.items);
        }
    });
    edge
}

/// Refuses the `#5063` reads of `prog` (after `probe::take`) where an edge may be active,
/// but for the keeps [`apply`] decides; whether it must run.
pub fn check(ctx: &mut Ctx, prog: &Program) -> bool {
    let mut reads = Vec::new();
    let edge = may_select_edge(prog);
    crate::ir::visit::walk_stmts(&prog.body, &mut |s| match &s.kind {
        StmtKind::Block(b) => {
            for it in &b.items {
                for e in crate::ir::visit::item_exprs(it) {
                    reads_z_skip(e, &mut reads);
                }
            }
        }
        StmtKind::If(i) => reads_z_skip(&i.cond, &mut reads),
        StmtKind::While(w) => reads_z_skip(&w.cond, &mut reads),
        _ => {}
    });
    if !edge {
        return false;
    }
    // The own skip variable's reads where every keep of it added a length: `apply` proves
    // that length is the H's.
    let own_lengths = !ctx.own_z_keeps.is_empty() && ctx.own_z_keeps.iter().all(|k| k.1.is_some());
    for sp in reads {
        let keep = ctx.z_keeps.iter().any(|k| k.1 == sp) || (own_lengths && ctx.own_z_reads.contains(&sp));
        if ctx.haas {
            ctx.unsupported(
                HAAS,
                sp,
                "the measured Z position (#5063) where a cutting edge may be active on a Haas target (FANUC's #5063 \
                 under the G43 H the edge becomes includes the tool length offset, and the Haas offset tables are \
                 not the registers #11000+/#10000+ its length would be taken off from)",
                "measure Z with D0 selected (in the tool change block, `T20 M6 D0`), and no other edge in the program",
            );
        } else if !keep {
            ctx.unsupported(
                UNDER_EDGE,
                sp,
                "the measured Z position (#5063) read away from its measuring block where a cutting edge may be \
                 active (FANUC's #5063 under the G43 H the edge becomes includes the tool length offset in force at \
                 the G31; the Siemens measured value is the tool tip)",
                "keep the measurement right after the measuring block (`IF $AC_MEA[1]==1 R1=$AA_MW[Z] ELSE \
                 R1=$AA_IW[Z] ENDIF`), or measure Z with D0 selected",
            );
        }
    }
    !ctx.haas
}

fn hash(n: u32, span: Span) -> Expr {
    var_expr(&VarRef { kind: VarKind::Hash(n), span })
}

/// `[#11000+h+#10000+h]`: the length of H register `h` (memory C geometry plus wear).
fn h_length(h: u32, span: Span) -> Expr {
    use crate::eval::tool_data::fanuc_var;
    use crate::eval::trace::ToolField;
    bin(
        BinOp::Add,
        hash(fanuc_var(ToolField::LengthGeometry, h), span),
        hash(fanuc_var(ToolField::LengthWear, h), span),
    )
}

/// Takes the length of the H FANUC applies at each G31 off the keep after it (runs after
/// `comp`, which records that H); refuses the keeps where it is not known.
pub fn apply(ctx: &mut Ctx, prog: &mut Program) {
    let keeps = std::mem::take(&mut ctx.z_keeps);
    let mut h_of = std::collections::BTreeMap::new();
    for (meas, keep) in &keeps {
        let h = ctx.skip_lengths.iter().find(|l| l.0 == *meas).and_then(|l| l.1);
        h_of.insert(*keep, h);
    }
    let mut unknown = Vec::new();
    crate::lower::map_exprs(&mut prog.body, &mut |e: &mut Expr| {
        let is_skip = |e: &Expr| matches!(&e.kind, ExprKind::Var(v) if v.kind == VarKind::Hash(5063));
        // The keep `T=#5063`, or `T=#5063+R` (R read at the keep on both controls).
        let (span, rest) = match &e.kind {
            ExprKind::Var(v) if is_skip(e) => (v.span, None),
            ExprKind::Binary(BinOp::Add, x, r) if is_skip(x) => (x.span, Some((**r).clone())),
            _ => return,
        };
        match h_of.get(&span) {
            Some(Some(Some(h))) if *h > 0 => {
                let length = h_length(*h, span);
                *e = match rest {
                    // `$AA_MW[Z]+($TC_DP3+$TC_DP12)` of the edge that is this H: #5063 itself.
                    Some(r) if crate::ir::dump::expr(&r) == crate::ir::dump::expr(&length) => hash(5063, span),
                    Some(r) => bin(BinOp::Add, bin(BinOp::Sub, hash(5063, span), length), r),
                    None => bin(BinOp::Sub, hash(5063, span), length),
                };
            }
            Some(Some(_)) => {}
            Some(None) => unknown.push(span),
            None => {}
        }
    });
    // The own skip variable (read as `#5063`) holds the tip plus each keep's R: exact where
    // every R is the length of the H at its G31.
    let own = std::mem::take(&mut ctx.own_z_keeps);
    let own_lengths = !own.is_empty() && own.iter().all(|k| k.1.is_some());
    let own_ok = own.iter().all(|(meas, r)| {
        let h = ctx.skip_lengths.iter().find(|l| l.0 == *meas).and_then(|l| l.1).flatten();
        match (h, r) {
            (Some(h), Some(r)) if h > 0 => crate::ir::dump::expr(r) == crate::ir::dump::expr(&h_length(h, r.span)),
            _ => false,
        }
    });
    if own_lengths && !own_ok {
        for sp in ctx.own_z_reads.clone() {
            ctx.unsupported(
                UNDER_EDGE,
                sp,
                "the translation's own Z skip variable (NCTRANS_SKIP_Z, read as #5063) where a keep of it adds a \
                 length that is not the one of the H register FANUC applies at its G31, or that H is not known",
                "keep the measurement with the length of the edge active at the measuring block, or keep it in a \
                 variable of the program's own (`IF $AC_MEA[1]==1 R1=$AA_MW[Z]+… ELSE R1=$AA_IW[Z]+… ENDIF`)",
            );
        }
    }
    for sp in unknown {
        ctx.unsupported(
            UNDER_EDGE,
            sp,
            "the measured Z position (#5063) where the cutting edge at the measuring block is not known on every \
             path (FANUC's #5063 under the G43 H the edge becomes includes the tool length offset in force at the \
             G31; the Siemens measured value is the tool tip, so the H register's length must be taken off)",
            "select the edge (`T20 M6 D1`, or D0) before the measuring block on every path, in the program that \
             measures, and not in the measuring block itself",
        );
    }
}
