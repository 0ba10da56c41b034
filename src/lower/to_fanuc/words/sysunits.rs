//! Siemens system variables with lengths (`$AA_IW`, `$AA_IM`, `$P_EP`, `$P_UIFR`) are read
//! and written in the basic system (mm) under G70/G71 and in the programmed one only under
//! G700/G710 (828D function manual G2, 7.3), the feeds' unit ([`super::units`]); their
//! FANUC counterparts (`#5041`, `#5021`, `#5001`, `#5221+`) in the G20/G21 unit, the
//! lengths'. Where the two differ (G70: FANUC inch, Siemens mm) a read is scaled to the
//! Siemens unit (`$AA_IW[X]` → `$AA_IW[X]*25.4`, the variable map then makes it
//! `#5041*25.4`) and a value written is scaled to the FANUC one, as the evaluator converts
//! (reads on every axis, `$P_UIFR` writes on X Y Z only). `$P_F` follows the same rule
//! (Siemens: mm/min under G70, FANUC `#4109`: inch/min under G20), so it is scaled alike
//! (`$P_F` → `#4109*25.4` under G70).

use super::units::FeedConv;
use crate::ir::{BinOp, Expr, ExprKind, Item, ItemKind, VarKind};
use crate::lower::{children_mut, item_exprs_mut};

/// The system variables with a length (and the feed `$P_F`) the translation to FANUC maps.
const LENGTHS: &[&str] = &["AA_IW", "AA_IM", "P_EP", "P_UIFR", "P_F"];

fn is_length(kind: &VarKind) -> bool {
    matches!(kind, VarKind::System { name, .. } if LENGTHS.contains(&name.as_str()))
}

/// A cycle's `FFR=$P_F` is the feed in force, which its translation keeps (`cycles_tap`):
/// no factor there (a call of a subprogram under G70 is refused by the words pass).
fn in_call(it: &Item) -> bool {
    matches!(it.kind, ItemKind::Call(_))
}

fn is_feed(e: &Expr) -> bool {
    matches!(&e.kind, ExprKind::Var(v) if matches!(&v.kind, VarKind::System { name, .. } if name == "P_F"))
}

fn by(e: Expr, op: BinOp) -> Expr {
    let span = e.span;
    let f = Expr::num(25.4, true, span);
    Expr::new(ExprKind::Binary(op, Box::new(e), Box::new(f)), span)
}

/// Whether an item reads or writes a length system variable.
pub(super) fn uses_lengths(it: &Item) -> bool {
    let mut any = false;
    if let ItemKind::Assign { target, .. } = &it.kind {
        any |= is_length(&target.kind);
    }
    for e in crate::ir::visit::item_exprs(it) {
        any |= if in_call(it) { reads_but_feed(e) } else { reads(e) };
    }
    any
}

fn reads_but_feed(e: &Expr) -> bool {
    let mut stack = vec![e];
    while let Some(x) = stack.pop() {
        if let ExprKind::Var(v) = &x.kind {
            if is_length(&v.kind) && !is_feed(x) {
                return true;
            }
        }
        stack.extend(x.children());
    }
    false
}

/// Whether `e` reads a length system variable.
pub(super) fn reads(e: &Expr) -> bool {
    let mut stack = vec![e];
    while let Some(x) = stack.pop() {
        if let ExprKind::Var(v) = &x.kind {
            if is_length(&v.kind) {
                return true;
            }
        }
        stack.extend(x.children());
    }
    false
}

/// Scales the reads in `e` for the units `conv` (nothing for [`FeedConv::Same`]).
pub(super) fn expr(e: &mut Expr, conv: FeedConv) {
    let op = match conv {
        FeedConv::Same => return,
        // FANUC reads inch, Siemens means mm.
        FeedConv::PerInch => BinOp::Mul,
        FeedConv::PerMm => BinOp::Div,
    };
    scale_reads(e, op, true);
}

fn scale_reads(e: &mut Expr, op: BinOp, feed: bool) {
    for c in children_mut(e) {
        scale_reads(c, op, feed);
    }
    if matches!(&e.kind, ExprKind::Var(v) if is_length(&v.kind)) && (feed || !is_feed(e)) {
        let var = std::mem::replace(e, Expr::num(0.0, false, e.span));
        *e = by(var, op);
    }
}

/// Scales the reads of an item and a value written to `$P_UIFR` (X Y Z) for `conv`.
pub(super) fn item(it: &mut Item, conv: FeedConv) {
    if conv == FeedConv::Same {
        return;
    }
    if let ItemKind::Assign { target, value } = &mut it.kind {
        let linear = matches!(&target.kind, VarKind::System { name, indices } if name == "P_UIFR"
            && indices.get(1).is_some_and(|a| matches!(&a.kind, ExprKind::Ident(s) if matches!(s.as_str(), "X" | "Y" | "Z"))));
        if linear {
            // Siemens writes mm (G70), FANUC takes the G20 unit: the inverse of a read.
            let op = if conv == FeedConv::PerInch { BinOp::Div } else { BinOp::Mul };
            let v = std::mem::replace(value, Expr::num(0.0, false, value.span));
            *value = by(v, op);
            // The value's own reads, and the target's indices, are scaled below.
        }
    }
    if in_call(it) {
        let op = if conv == FeedConv::PerInch { BinOp::Mul } else { BinOp::Div };
        item_exprs_mut(it, &mut |e| scale_reads(e, op, false));
        return;
    }
    item_exprs_mut(it, &mut |e| expr(e, conv));
}
