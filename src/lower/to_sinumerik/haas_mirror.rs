//! Haas `G101`/`G100` (mirror image on/off about the work zero, the Haas spelling of FANUC's
//! `G51.1`/`G50.1` about 0; `eval/machine/haas_mirror.rs`) before anything is planned: where
//! the Haas run and the G51.1 one are the same — every axis of a G101 written as 0, and no job
//! program with a G52 shift that is not literally zero (the Haas page does not relate the
//! mirror's zero to G52) — the words become G51.1/G50.1, which the frame translation carries
//! (`AMIRROR`). Elsewhere they stay, and the words pass refuses them naming why (NC363).

use crate::ir::*;
use crate::lower::literal;

/// Whether `p` has a G52 word that may shift (not every axis a literal 0).
pub fn shifts(p: &Program) -> bool {
    let mut any = false;
    crate::ir::visit::walk_stmts(&p.body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            if super::g_codes(&b.items).contains(&520) {
                any |= b.items.iter().any(|it| match &it.kind {
                    ItemKind::Word(w) if matches!(w.addr, Addr::Letter(b'X' | b'Y' | b'Z')) => match &w.value {
                        WordValue::Expr(e) => literal(e) != Some(0.0),
                        _ => true,
                    },
                    _ => false,
                });
            }
        }
    });
    any
}

/// `p` with its G101/G100 spelt G51.1/G50.1 where exact, or `None` when nothing changes.
/// `shifted`: a program of the job has a G52 that may shift.
pub fn spell(p: &Program, shifted: bool) -> Option<Program> {
    let mut any = false;
    crate::ir::visit::walk_stmts(&p.body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            any |= exact(&b.items, shifted).is_some();
        }
    });
    if !any {
        return None;
    }
    let mut p = p.clone();
    p.body = crate::lower::map_bodies(std::mem::take(&mut p.body), &mut |list| {
        list.into_iter()
            .map(|mut st| {
                if let StmtKind::Block(b) = &mut st.kind {
                    if let Some(to) = exact(&b.items, shifted) {
                        for it in &mut b.items {
                            if let ItemKind::Word(w) = &mut it.kind {
                                if let (true, WordValue::Expr(e)) = (w.addr.is(b'G'), &mut w.value) {
                                    if matches!(literal(e), Some(v) if v == 101.0 || v == 100.0) {
                                        *e = Expr::num(to(literal(e) == Some(101.0)), true, e.span);
                                    }
                                }
                            }
                        }
                    }
                }
                st
            })
            .collect()
    });
    Some(p)
}

/// The new G value (of whether it is G101) when the block's G101/G100 is exact as G51.1/G50.1.
fn exact(items: &[Item], shifted: bool) -> Option<fn(bool) -> f64> {
    let gs = super::g_codes(items);
    let on = gs.contains(&1010);
    if !on && !gs.contains(&1000) {
        return None;
    }
    if on && gs.contains(&1000) {
        return None;
    }
    let zero = items.iter().all(|it| match &it.kind {
        ItemKind::Word(w) if matches!(w.addr, Addr::Letter(b'X' | b'Y' | b'Z')) => match &w.value {
            WordValue::Expr(e) => literal(e) == Some(0.0),
            _ => false,
        },
        _ => true,
    });
    (!on || (zero && !shifted)).then_some(|on: bool| if on { 51.1 } else { 50.1 })
}
