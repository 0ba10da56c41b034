//! Haas `G101`/`G100` (mirror image on/off about the work zero, the Haas spelling of FANUC's
//! `G51.1`/`G50.1` about 0; `eval/machine/haas_mirror.rs`) before anything is planned: where
//! the Haas run and the G51.1 one are the same — every axis of a G101 written as 0, and no job
//! program with a G52 shift that is not literally zero (the Haas page does not relate the
//! mirror's zero to G52) — the words become G51.1/G50.1, which the frame translation carries
//! (`AMIRROR`). Elsewhere they stay, and the words pass refuses them naming why (NC363).

use crate::ir::*;

/// `p` with its G101/G100 spelt G51.1/G50.1 where exact, or `None` when nothing changes.
/// `shifted`: a program of the job has a G52 that may shift.
pub fn spell(p: &Program, shifted: bool) -> Option<Program> {
    let mut any = false;
    crate::ir::visit::walk_stmts(&p.body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            any |= exact(&b.items, shifted);
        }
    });
    if !any {
        return None;
    }
    let mut p = p.clone();
    p.body = crate::lower::map_bodies(std::mem::take(&mut p.body), &mut |mut list| {
        for st in &mut list {
            if let StmtKind::Block(b) = &mut st.kind {
                if exact(&b.items, shifted) {
                    crate::lower::respell_g(&mut b.items, &[(1010, 51.1), (1000, 50.1)]);
                }
            }
        }
        list
    });
    Some(p)
}

/// Whether the block has a G101 or G100 (not both) that is exact as G51.1/G50.1: a G100
/// always, a G101 with every axis 0 where no G52 may shift.
fn exact(items: &[Item], shifted: bool) -> bool {
    let gs = crate::lower::g_codes(items);
    match (gs.contains(&1010), gs.contains(&1000)) {
        (true, false) => !shifted && crate::lower::xyz_words_zero(items),
        (false, true) => true,
        _ => false,
    }
}
