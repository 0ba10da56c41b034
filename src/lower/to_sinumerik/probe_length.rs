//! A FANUC `G31` under tool length compensation whose skip position the program reads: on
//! FANUC `#5063` then holds the position with the length offset in force (G43 +, G44 −;
//! docs/semantics.md, Probing), on Siemens the kept `$AA_MW[Z]` is the tool tip. The exact
//! counterpart would add the length of the edge the G43 became, which the translation does
//! not write, so such a G31 is refused (NC550). Found by a forward flow over the program as
//! read: G43/G44 may be in force where some path reaches the G31 through one (or through a
//! call, or from the caller's modes in a called program) without a G49 after it.

use super::vacancy::{flatten, succs, Flat, Node};
use super::*;

/// The diagnostic of a skip position read under tool length compensation.
pub const UNDER_LENGTH: &str = "NC550";

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

/// Refuses each G31 of `body` that G43/G44 may be in force at (`main`: the program starts
/// in G49, power-on; a called one in its caller's mode). Called only when the program reads
/// `#5061+`.
pub fn check(ctx: &mut Ctx, body: &[Stmt], main: bool) {
    let flat = flatten(body);
    let (may, seen) = may_flow(&flat, main);
    for i in (0..flat.nodes.len()).filter(|&i| seen[i]) {
        let Node::Items(items) = &flat.nodes[i] else { continue };
        let Some(g31) = items.iter().find(|it| is_g31(it)) else { continue };
        if may[i] || selects_length(items) {
            ctx.refuse(
                UNDER_LENGTH,
                g31.span,
                "G31 where G43/G44 may be in force, in a program that reads the skip position (#5061+), cannot be \
                 translated: FANUC's #5063 then includes the tool length offset, the Siemens measured value is the tool tip",
                "G31 under tool length compensation with its skip position read",
                "probe under G49 (cancel the length offset before the G31 on every path, in the program that probes), \
                 or read the block end position #5003",
            );
        }
    }
}
