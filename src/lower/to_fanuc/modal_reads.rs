//! Siemens `$P_GG[1]` (the active G function of group 1 as its internal number: G0..G3 are
//! 1..4, docs/semantics.md, Modal information) on FANUC. FANUC's `#4001` holds the G code
//! of the preceding block (0..3, and 33 or others for codes the Siemens list numbers
//! otherwise), and the translation of cycles and calls may leave the two groups apart, so no
//! expression of `#4001` is exact everywhere. What is exact is the constant, where the
//! program itself has selected G0..G3 on every path to the read in a block that does not
//! set group 1 itself: a walk of the program's structures (`comp_flow::walk`, as
//! `tool_reads`) from nothing known, a call, a cycle, a computed or other group 1 code
//! (CIP, G33, splines …) making the mode unknown. Reads elsewhere (and in IF/WHILE
//! conditions, and of the other groups, whose numbering has no source) stay refused by
//! `varmap` (NC342), naming the group.

use super::*;
use crate::lower::comp_flow::{self, FlowState, K};

#[derive(Clone, Debug, PartialEq)]
struct St {
    /// `$P_GG[1]`: 1..4 for G0..G3.
    motion: K<f64>,
}

impl FlowState for St {
    fn unknown() -> St {
        St { motion: K::Unknown }
    }

    fn merge(&self, o: &St) -> St {
        St { motion: self.motion.merge(&o.motion) }
    }

    fn watches_every_block(&self) -> bool {
        true
    }
}

/// The Siemens words of group 1 other than G0..G3 (named; G33 and the like are numbers).
const OTHER_GROUP1: [&str; 9] = ["CIP", "CT", "ASPLINE", "BSPLINE", "CSPLINE", "POLY", "INVCW", "INVCCW", "OEMIPO1"];

/// The state after a block's items, and whether they set group 1 (or may).
fn apply(items: &[Item], mut st: St) -> (St, bool) {
    let opaque = |it: &Item| match &it.kind {
        ItemKind::Call(_) | ItemKind::IfBlock { .. } => true,
        // An `IF … GOTOF` only jumps; other conditional items may set anything.
        ItemKind::IfThen { then, .. } => !matches!(then.kind, ItemKind::Goto(_)),
        _ => false,
    };
    if items.iter().any(opaque) {
        return (St::unknown(), true);
    }
    let mut touches = false;
    for it in items {
        let ItemKind::Word(w) = &it.kind else { continue };
        match &w.addr {
            Addr::Letter(b'G') => {
                let v = comp_flow::const_word(w);
                let index = match v {
                    Some(g) if g == 0.0 || g == 1.0 || g == 2.0 || g == 3.0 => Some(g + 1.0),
                    // Another literal G code of another group leaves the mode as it is.
                    Some(g) if !group1_other(g) => continue,
                    _ => None,
                };
                st.motion = index.map_or(K::Unknown, K::Known);
                touches = true;
            }
            Addr::Name(n) if OTHER_GROUP1.iter().any(|o| n.eq_ignore_ascii_case(o)) => {
                st.motion = K::Unknown;
                touches = true;
            }
            _ => {}
        }
    }
    (st, touches)
}

/// A literal G number of Siemens group 1 other than G0..G3: G33..G35 (threads), G331/G332
/// (tapping).
fn group1_other(g: f64) -> bool {
    [33.0, 34.0, 35.0, 331.0, 332.0].contains(&g)
}

/// The group a `$P_GG[…]` read names, where its index is a literal.
pub fn group(indices: &[Expr]) -> Option<f64> {
    match indices {
        [e] => comp_flow::const_expr(e),
        _ => None,
    }
}

/// The value a read of `$P_GG[1]` has in state `st`, where known.
fn value(_: &str, indices: &[Expr], st: &St) -> Option<f64> {
    (group(indices) == Some(1.0)).then(|| st.motion.known().copied()).flatten()
}

pub fn run(prog: &mut Program) {
    comp_flow::fold_reads(prog, &["P_GG"], apply, value);
}

/// The refusal text of a `$P_GG` read left after [`run`] (`varmap` adds "cannot be
/// translated").
pub fn refusal(indices: &[Expr]) -> String {
    match group(indices) {
        Some(1.0) => "$P_GG[1] (G0..G3 as 1..4) read where the program has not selected G0, G1, G2 or G3 itself on \
                      every path to it, in a block that does not set group 1 (FANUC's #4001 numbers G00..G03 as 0..3 \
                      and holds other codes; in an IF/WHILE condition, read it into a variable first)"
            .to_string(),
        Some(n) => format!(
            "{} (no source read here gives the internal numbers of that group's G functions)",
            crate::eval::sysvars::p_gg_group(n)
        ),
        None => "$P_GG[…] with a computed group number".to_string(),
    }
}
