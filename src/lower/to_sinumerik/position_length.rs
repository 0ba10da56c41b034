//! FANUC current position of Z in workpiece coordinates (`#5043`) where tool length
//! compensation may be in force: FANUC includes the length offset there (F-POS; G43 adds
//! the H register on Z), Siemens `$AA_IW[Z]` is the tool tip (docs/semantics.md, Probing and
//! position reads). Where every path to the read has set G43 (`modal_reads`), the G43 H the
//! translation wrote is the active edge of the tool in the spindle (`comp`), whose length is
//! `$TC_DP3` plus its wear `$TC_DP12`: the read becomes `$AA_IW[Z]+($TC_DP3[t,d]+$TC_DP12[t,d])`
//! for the edge of the H every path set (the tool data map's), else of the active edge
//! `[$P_TOOLNO,$P_TOOL]`. Where G43/G44 may be
//! in force but is not known on every path (or the read's block selects it), refused
//! (NC643). `#5023` (machine coordinates) needs nothing: Siemens `$AA_IM` holds the edge's
//! length as FANUC holds the offset; the other axes carry no length. G44 itself is refused
//! by `comp` (NC474); on a Haas profile, whose offset tables are not the tool data, NC644.

use super::probe_length::{may_flow, selects_length};
use super::vacancy::{flatten, Node};
use super::*;

/// The diagnostic of a `#5043` read where the length compensation is not settled.
pub const UNSETTLED: &str = "NC643";

/// The diagnostic of a `#5043` read under G43/G44 on a Haas profile.
pub const HAAS: &str = "NC644";

/// Per block (and loop condition) of a program, in text order: its start and whether
/// G43/G44 may be in force there (on entry, or from the block's own words).
#[derive(Default)]
pub struct Lengths {
    at: Vec<(u32, bool)>,
}

impl Lengths {
    /// The flow over `body` (the program as read; `main`: it starts in G49).
    pub fn new(body: &[Stmt], main: bool) -> Lengths {
        let flat = flatten(body);
        let (may, seen) = may_flow(&flat, main);
        let mut at = Vec::new();
        for (i, node) in flat.nodes.iter().enumerate() {
            // A block no path reaches never reads: as if under G49.
            let m = seen[i] && may[i];
            match node {
                Node::Items(items) => {
                    if let Some((lo, _)) = flat.blocks[i] {
                        at.push((lo, m || (seen[i] && selects_length(items))));
                    }
                }
                Node::Head { cond: Some(c), .. } => at.push((c.span.lo, m)),
                _ => {}
            }
        }
        at.sort_by_key(|a| a.0);
        Lengths { at }
    }

    pub(super) fn may(&self, lo: u32) -> bool {
        let i = self.at.partition_point(|a| a.0 <= lo);
        // An expression outside any block (none is): take the safe side.
        i.checked_sub(1).and_then(|i| self.at.get(i)).is_none_or(|a| a.1)
    }
}

fn sys(name: &str, indices: Vec<Expr>, span: Span) -> Expr {
    var_expr(VarKind::System { name: name.into(), indices }, span)
}

/// The Siemens form of `#5043` read at `span`, `None` where no length may be in force (the
/// plain `$AA_IW[Z]` of `words::system_var`); a refusal where it is not known.
pub fn read(ctx: &mut Ctx, span: Span) -> Option<Result<Expr, Vec<Stmt>>> {
    if !ctx.modal.lengths.may(span.lo) {
        return None;
    }
    if ctx.opts.source.haas && ctx.modal.reads.known(4008, span.lo) != Some(49.0) {
        let message = "#5043 (the current Z position, which includes the tool length offset) read where G43/G44 may \
                       be in force on a Haas profile cannot be translated: the Haas offset tables (#2001+) are not \
                       the tool data the edge's $TC_DP3/$TC_DP12 are written from, so the length cannot be proven";
        let hint = "read the block end position #5003 (the tip, no offset), or cancel the offset (G49) before the read";
        let what = "#5043 under G43/G44 on a Haas profile";
        return Some(Err(ctx.refuse(HAAS, span, message, what, hint).into_iter().collect()));
    }
    match ctx.modal.reads.known(4008, span.lo) {
        Some(49.0) => None,
        Some(43.0) => {
            // The H every path set names the edge (so the form reads back to FANUC as
            // `#5003+[#11000+h+#10000+h]`); else the active edge.
            let h = ctx.modal.reads.known(4111, span.lo).filter(|h| *h >= 1.0 && h.fract() == 0.0);
            let named = h
                .filter(|_| !ctx.opts.source.haas)
                .and_then(|h| super::tool_data::length_edge(&ctx.opts.source.offsets, h as u32));
            let edge = || match named {
                Some((t, d)) => vec![Expr::num(f64::from(t), false, span), Expr::num(f64::from(d), false, span)],
                None => vec![sys("P_TOOLNO", vec![], span), sys("P_TOOL", vec![], span)],
            };
            let length = bin(BinOp::Add, sys("TC_DP3", edge(), span), sys("TC_DP12", edge(), span));
            let tip = sys("AA_IW", vec![Expr::new(ExprKind::Ident("Z".into()), span)], span);
            Some(Ok(bin(BinOp::Add, tip, length)))
        }
        _ => {
            let message = "#5043 (the current Z position, which includes the tool length offset) read where G43/G44 \
                           may be in force but is not set on every path to the read cannot be translated: Siemens \
                           $AA_IW[Z] is the tool tip, so the length must be added exactly where FANUC adds it";
            let hint = "select G43 H (or G49) before the read on every path, in a block of its own, or read the \
                        block end position #5003 (the tip, no offset)";
            let what = "#5043 where the tool length compensation is not known";
            Some(Err(ctx.refuse(UNSETTLED, span, message, what, hint).into_iter().collect()))
        }
    }
}
