//! Siemens `$AA_IW[Z]` (the tool tip in workpiece coordinates) where a cutting edge may be
//! active: the edge becomes `G43 H` on FANUC, and FANUC's current position `#5043` under G43
//! includes the length offset (F-POS; docs/semantics.md, Probing and position reads), while
//! the block end position `#5003` does not. So where the program may select an edge
//! (`probe_length::may_select_edge`) the read is written as the Siemens `$P_EP[Z]`, the
//! programmed end point in the workpiece system, which the variable map makes `#5003`: the
//! tip on both controls. `$AA_IM` needs nothing: the Siemens machine position holds the
//! edge's length as FANUC's `#5021+` holds the offset of the G43 H it became. Runs after
//! `probe::take` (the kept-skip form keeps its `$AA_IW`).

use super::varmap::visit_vars;
use super::*;

fn is_z(e: &Expr) -> bool {
    matches!(&e.kind, ExprKind::Ident(s) if s.eq_ignore_ascii_case("Z"))
        || matches!(&e.kind, ExprKind::Var(v) if matches!(&v.kind, VarKind::Named { name, indices } if indices.is_empty() && name.eq_ignore_ascii_case("Z")))
}

/// Rewrites the `$AA_IW[Z]` reads of `prog` where an edge may be active.
pub fn run(prog: &mut Program) {
    if !probe_length::may_select_edge(prog) {
        return;
    }
    visit_vars(&mut prog.body, &mut |v| {
        if let VarKind::System { name, indices } = &mut v.kind {
            if name.as_str() == "AA_IW" && indices.len() == 1 && is_z(&indices[0]) {
                *name = "P_EP".into();
            }
        }
    });
}
