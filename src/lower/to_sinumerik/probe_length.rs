//! A FANUC `G31` under tool length compensation whose skip position the program reads: on
//! FANUC `#5063` then holds the position with the length offset in force at the G31 (G43 +,
//! G44 −; docs/semantics.md, Probing), on Siemens the kept `$AA_MW[Z]` is the tool tip. Where
//! every path to the G31 has set G43 (`modal_reads`, the same rule as `position_length`), the
//! G43 H the translation wrote is the active edge at the G31, so the kept Z adds that edge's
//! `$TC_DP3+$TC_DP12` ([`length_at`]): of the edge the offset map gives the H every path set,
//! else of `[$P_TOOLNO,$P_TOOL]` (the keep stands right after the measuring block, under the
//! same edge). Elsewhere such a G31 is refused (NC550): G43/G44 may be in force where some
//! path reaches the G31 through one (or through a call, or from the caller's modes in a
//! called program) without a G49 after it, and the flow does not know it on every path. X
//! and Y carry no length (G17). G44 is refused by `comp` (NC474); on a Haas profile, whose
//! offset tables are not the tool data, NC654.

use super::vacancy::{flatten, succs, Flat, Node};
use super::*;

/// The diagnostic of a skip position read where the length compensation is not settled.
pub const UNDER_LENGTH: &str = "NC550";

/// The diagnostic of a skip position read under G43/G44 on a Haas profile.
pub const HAAS: &str = "NC654";

fn is_g31(it: &Item) -> bool {
    matches!(&it.kind, ItemKind::Word(Word { addr: Addr::Letter(b'G'), value: WordValue::Expr(e), .. })
        if literal(e) == Some(31.0))
}

/// Whether G43/G44 may be in force after a block entered with `may`.
fn after(items: &[Item], may: bool) -> bool {
    let computed_g = items.iter().any(|it| {
        matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'G') && !matches!(&w.value, WordValue::Expr(e) if literal(e).is_some()))
    });
    let calls = items.iter().any(|it| {
        matches!(it.kind, ItemKind::Call(_) | ItemKind::IfBlock { .. })
            || matches!(&it.kind, ItemKind::IfThen { then, .. } if !matches!(then.kind, ItemKind::Assign { .. }))
    });
    let gs = g_codes(items);
    if computed_g || calls || gs.iter().any(|g| matches!(g, 430 | 440)) {
        true
    } else if gs.contains(&490) {
        false
    } else {
        may
    }
}

/// Whether G43/G44 may be in force entering each node of `flat` (`main`: the program starts
/// in G49, power-on; a called one in its caller's mode), and whether the node is reached.
pub(super) fn may_flow(flat: &Flat, main: bool) -> (Vec<bool>, Vec<bool>) {
    let len = flat.nodes.len();
    let mut may = vec![false; len];
    let mut seen = vec![false; len];
    if len == 0 {
        return (may, seen);
    }
    let mut stack = vec![(0usize, !main)];
    while let Some((i, m)) = stack.pop() {
        if seen[i] && (may[i] || !m) {
            continue;
        }
        seen[i] = true;
        may[i] |= m;
        let out = match &flat.nodes[i] {
            Node::Items(items) => after(items, may[i]),
            _ => may[i],
        };
        // A block that may be skipped (`/`) passes its entry state on as well.
        let skip = flat.blocks[i].is_some_and(|b| b.1);
        for j in succs(flat, i) {
            if j < len {
                stack.push((j, out || (skip && may[i])));
            }
        }
    }
    (may, seen)
}

/// Whether a block's own words select G43/G44.
pub(super) fn selects_length(items: &[Item]) -> bool {
    g_codes(items).iter().any(|g| matches!(g, 430 | 440))
}

/// Refuses each G31 of `body` that G43/G44 may be in force at without the flow knowing it
/// on every path (`main`: the program starts in G49, power-on; a called one in its caller's
/// mode). Called only when the program reads `#5061+`.
pub fn check(ctx: &mut Ctx, body: &[Stmt], main: bool) {
    let flat = flatten(body);
    let (may, seen) = may_flow(&flat, main);
    for i in (0..flat.nodes.len()).filter(|&i| seen[i]) {
        let Node::Items(items) = &flat.nodes[i] else { continue };
        let Some(g31) = items.iter().find(|it| is_g31(it)) else { continue };
        if !(may[i] || selects_length(items)) {
            continue;
        }
        let known = ctx.modal.reads.known(4008, g31.span.lo);
        if known == Some(49.0) {
            continue;
        }
        if ctx.opts.source.haas {
            ctx.refuse(
                HAAS,
                g31.span,
                "G31 where G43/G44 may be in force on a Haas profile, in a program that reads the skip position \
                 (#5061+), cannot be translated: FANUC's #5063 then includes the tool length offset, and the Haas \
                 offset tables (#2001+) are not the tool data the edge's $TC_DP3/$TC_DP12 are written from, so the \
                 length cannot be proven",
                "G31 under G43/G44 on a Haas profile with its skip position read",
                "probe under G49 (cancel the length offset before the G31 on every path), or read the block end \
                 position #5003",
            );
        } else if !matches!(known, Some(43.0 | 44.0)) {
            ctx.refuse(
                UNDER_LENGTH,
                g31.span,
                "G31 where G43/G44 may be in force but is not set on every path to it, in a program that reads the \
                 skip position (#5061+), cannot be translated: FANUC's #5063 then includes the tool length offset in \
                 force at the G31, the Siemens measured value is the tool tip, so the length must be added exactly \
                 where FANUC adds it",
                "G31 where the tool length compensation is not known",
                "select G43 H (or G49) before the G31 on every path, in a block of its own and in the program that \
                 probes, or read the block end position #5003",
            );
        }
    }
}

fn sys(name: &str, indices: Vec<Expr>, span: Span) -> Expr {
    var_expr(VarKind::System { name: name.into(), indices }, span)
}

/// The kept skip position of Z `tip` for the G31 block at `span`: the tip with the length
/// offset in force there (G43 +, G44 −), the tip alone where none is (or [`check`] refused).
pub fn with_length(ctx: &Ctx, span: Span, tip: Expr) -> Expr {
    match length_at(ctx, span) {
        Some((op, length)) => bin(op, tip, length),
        None => tip,
    }
}

fn length_at(ctx: &Ctx, span: Span) -> Option<(BinOp, Expr)> {
    if !ctx.modal.lengths.may(span.lo) || ctx.opts.source.haas {
        return None;
    }
    let g = ctx.modal.reads.known(4008, span.lo)?;
    if g != 43.0 && g != 44.0 {
        return None;
    }
    // The H every path set names the edge (the G43 H the translation wrote); else the
    // active edge, the one at the G31 since the keep follows the measuring block.
    let h = ctx.modal.reads.known(4111, span.lo).filter(|h| *h >= 1.0 && h.fract() == 0.0);
    let named = h.and_then(|h| super::tool_data::length_edge(&ctx.opts.source.offsets, h as u32));
    let edge = || match named {
        Some((t, d)) => vec![Expr::num(f64::from(t), false, span), Expr::num(f64::from(d), false, span)],
        None => vec![sys("P_TOOLNO", vec![], span), sys("P_TOOL", vec![], span)],
    };
    let length = bin(BinOp::Add, sys("TC_DP3", edge(), span), sys("TC_DP12", edge(), span));
    Some((if g == 44.0 { BinOp::Sub } else { BinOp::Add }, length))
}
