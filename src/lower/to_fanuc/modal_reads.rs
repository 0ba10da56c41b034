//! Siemens `$P_GG[1]`, `$P_GG[6]`, `$P_GG[7]` (the active G function of groups 1, 6 and 7
//! as its internal number: G0..G3 are 1..4, G17/G18/G19 and G40/G41/G42 1..3,
//! docs/semantics.md, Modal information) on FANUC. FANUC's `#4001` holds the G code of the
//! preceding block (0..3, and 33 or others for codes the Siemens list numbers otherwise), and
//! the translation of cycles and calls may leave the groups apart, so no expression of
//! `#4001`, `#4002` or `#4007` is shown exact everywhere. What is exact is the constant,
//! where the program itself has selected a function of the group on every path to the read
//! in a block that does not set that group itself: a walk of the program's structures
//! (`comp_flow::walk`, as `tool_reads`) from nothing known, a call, a cycle, a computed or
//! other group 1 code (CIP, G33, splines …) making the mode unknown. Reads elsewhere (and in
//! IF/WHILE conditions, and of the other groups, whose numbering has no source) stay refused
//! by `varmap` (NC342), naming the group.

use super::*;
use crate::lower::comp_flow::{self, FlowState, K};

#[derive(Clone, Debug, PartialEq)]
struct St {
    /// `$P_GG[1]`: 1..4 for G0..G3.
    motion: K<f64>,
    /// `$P_GG[6]`: 1..3 for G17..G19.
    plane: K<f64>,
    /// `$P_GG[7]`: 1..3 for G40..G42.
    comp: K<f64>,
}

impl FlowState for St {
    fn unknown() -> St {
        St { motion: K::Unknown, plane: K::Unknown, comp: K::Unknown }
    }

    fn merge(&self, o: &St) -> St {
        St { motion: self.motion.merge(&o.motion), plane: self.plane.merge(&o.plane), comp: self.comp.merge(&o.comp) }
    }

    fn watches_every_block(&self) -> bool {
        true
    }
}

/// The Siemens words of group 1 other than G0..G3 (named; G33 and the like are numbers).
const OTHER_GROUP1: [&str; 9] = ["CIP", "CT", "ASPLINE", "BSPLINE", "CSPLINE", "POLY", "INVCW", "INVCCW", "OEMIPO1"];

/// The state after a block's items, and whether they set one of the groups followed (or may).
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
                match comp_flow::const_word(w) {
                    Some(g) if g == 0.0 || g == 1.0 || g == 2.0 || g == 3.0 => st.motion = K::Known(g + 1.0),
                    Some(g) if g == 17.0 || g == 18.0 || g == 19.0 => st.plane = K::Known(g - 16.0),
                    Some(g) if g == 40.0 || g == 41.0 || g == 42.0 => st.comp = K::Known(g - 39.0),
                    Some(g) if group1_other(g) => st.motion = K::Unknown,
                    // Another literal G code of another group leaves the modes as they are.
                    Some(_) => continue,
                    None => st = St::unknown(),
                }
                // A read in this block sees the modes before it: not folded (any group, to
                // keep the rule one).
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

/// The value a read of `$P_GG[1]`, `[6]` or `[7]` has in state `st`, where known.
fn value(_: &str, indices: &[Expr], st: &St) -> Option<f64> {
    let k = match group(indices)? as i64 {
        1 => &st.motion,
        6 => &st.plane,
        7 => &st.comp,
        _ => return None,
    };
    k.known().copied()
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
        Some(6.0) => "$P_GG[6] (G17/G18/G19 as 1..3) read where the program has not selected G17, G18 or G19 itself on \
                      every path to it, in a block that does not set the plane (in an IF/WHILE condition, read it into a \
                      variable first)"
            .to_string(),
        Some(7.0) => "$P_GG[7] (G40/G41/G42 as 1..3) read where the program has not selected G40, G41 or G42 itself on \
                      every path to it, in a block that does not set the compensation (in an IF/WHILE condition, read it \
                      into a variable first)"
            .to_string(),
        Some(n) => format!(
            "{} (no source read here gives the internal numbers of that group's G functions)",
            crate::eval::sysvars::p_gg_group(n)
        ),
        None => "$P_GG[…] with a computed group number".to_string(),
    }
}
