//! The kept skip position of Z (`#5063`, from the Siemens `$AA_MW[Z]`/`$AA_IW[Z]` form that
//! `probe` recognises) where a cutting edge may carry a length: the edge becomes `G43 H` on
//! FANUC, and FANUC's `#5063` under G43 includes the length offset (docs/semantics.md,
//! Probing), while Siemens measures the tool tip. Refused (NC551) unless the program selects
//! no edge but `D0`: no D word other than `D0` and no tool change without `D0` in its block
//! (a tool change selects the edge of MD20270), in a program that is not a `PROC` (a called
//! one runs under its caller's edge).

use super::*;

/// The diagnostic of a Z skip position read where an edge may be active.
pub const UNDER_EDGE: &str = "NC551";

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

/// Refuses the `#5063` reads of `prog` (after `probe::take`) where an edge may be active.
pub fn check(ctx: &mut Ctx, prog: &Program) {
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
        return;
    }
    for sp in reads {
        ctx.unsupported(
            UNDER_EDGE,
            sp,
            "the measured Z position (#5063) where a cutting edge may be active (FANUC's #5063 under the G43 H it \
             becomes includes the tool length offset; the Siemens measured value is the tool tip)",
            "measure Z with D0 selected (in the tool change block, `T20 M6 D0`), and no other edge in the program",
        );
    }
}
