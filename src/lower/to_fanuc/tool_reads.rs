//! Siemens `$P_TOOLNO` (the active tool) and `$P_TOOL` (the active cutting edge) on FANUC.
//! FANUC has neither: `#4120` is the T word of the preceding block (also before M6) and
//! `#4107` the D register, which the translation numbers otherwise (edge D1 of tool n is
//! `D n`, `lower::comp_flow`). What is exact is the constant, where the program itself has
//! changed to that tool (`T5 M6`) or selected that edge (`D1`) on every path to the read: a
//! walk of the program's structures (`comp_flow::walk`: branches merged, loop heads to a
//! fixed point, jump targets knowing nothing) from nothing known, a call making everything
//! unknown. Reads elsewhere, and in IF/WHILE conditions, stay refused (NC342, `varmap`).
//! docs/semantics.md, Modal information.

use super::*;
use crate::lower::comp_flow::{self, FlowState, K};

#[derive(Clone, Debug, PartialEq)]
struct St {
    /// The T word last written (the tool an M6 changes to).
    sel: K<f64>,
    /// `$P_TOOLNO`.
    tool: K<f64>,
    /// `$P_TOOL`.
    edge: K<f64>,
}

impl FlowState for St {
    fn unknown() -> St {
        St { sel: K::Unknown, tool: K::Unknown, edge: K::Unknown }
    }

    fn merge(&self, o: &St) -> St {
        St { sel: self.sel.merge(&o.sel), tool: self.tool.merge(&o.tool), edge: self.edge.merge(&o.edge) }
    }

    fn watches_every_block(&self) -> bool {
        true
    }
}

/// The state after a block's items (whether they touch the tool or the edge: the second).
fn apply(items: &[Item], mut st: St) -> (St, bool) {
    if items.iter().any(|it| matches!(it.kind, ItemKind::Call(_) | ItemKind::IfBlock { .. } | ItemKind::IfThen { .. }))
    {
        return (St::unknown(), true);
    }
    let mut touches = false;
    let (mut m6, mut d) = (false, false);
    for it in items {
        let ItemKind::Word(w) = &it.kind else { continue };
        let v = comp_flow::const_word(w);
        match w.addr {
            Addr::Letter(b'T') => {
                st.sel = v.map_or(K::Unknown, K::Known);
                touches = true;
            }
            Addr::Letter(b'D') => {
                st.edge = v.map_or(K::Unknown, K::Known);
                (touches, d) = (true, true);
            }
            Addr::Letter(b'M') if v == Some(6.0) => (touches, m6) = (true, true),
            _ => {}
        }
    }
    if items.iter().any(
        |it| matches!(&it.kind, ItemKind::Word(w) if matches!(&w.addr, Addr::Name(n) if n.eq_ignore_ascii_case("T"))),
    ) {
        st.sel = K::Unknown;
        touches = true;
    }
    if m6 {
        st.tool = st.sel.clone();
        // The edge a tool change selects without D is machine data (MD20270).
        if !d {
            st.edge = K::Unknown;
        }
    }
    (st, touches)
}

/// The value a read of `$P_TOOLNO` / `$P_TOOL` has in state `st`, where known.
fn value(name: &str, indices: &[Expr], st: &St) -> Option<f64> {
    match name {
        "P_TOOLNO" if indices.is_empty() => st.tool.known().copied(),
        "P_TOOL" if indices.is_empty() => st.edge.known().copied(),
        _ => None,
    }
}

pub fn run(prog: &mut Program) {
    comp_flow::fold_reads(prog, &["P_TOOLNO", "P_TOOL"], apply, value);
}
