//! Mirror image on a Haas target: Haas programs it with `G101`/`G100` about the work zero
//! (Haas VF programming manual 96-8000 p. 201), where FANUC writes `G51.1`/`G50.1` about a
//! position. After the frame translation wrote its G51.1/G50.1 (`rotation.rs`, `frame_seq.rs`),
//! each becomes G101/G100 with the same axis words where that is the same mirror: a G51.1
//! whose axes are all 0 in a program without a G52 that may shift (the page does not relate
//! the mirror's zero to G52, and the run refuses G101 under a shift). Anything else is refused
//! (NC552) rather than written as a code the Haas manual does not list.

use super::*;

const CODE: &str = "NC552";

/// Runs on a lowered program when the target is a Haas control.
pub fn run(ctx: &mut Ctx, prog: &mut Program) {
    if !ctx.haas {
        return;
    }
    let shifted = crate::lower::g52_axes(&prog.body) & 0b111 != 0;
    prog.body = crate::lower::map_bodies(std::mem::take(&mut prog.body), &mut |list| {
        let mut out = Vec::with_capacity(list.len());
        for mut st in list {
            if let StmtKind::Block(b) = &mut st.kind {
                match respell(b, shifted) {
                    Ok(()) => {}
                    Err(why) => {
                        let span = b.meta.span;
                        let hint = "Haas mirrors with G101 about the work zero only: mirror about 0 with no G52 shift \
                                    in force (MIRROR X0 before any TRANS), or shift the zero with a work offset";
                        if let Some(mark) = ctx.unsupported(CODE, span, why, hint) {
                            out.push(mark);
                        }
                        continue;
                    }
                }
            }
            out.push(st);
        }
        out
    });
}

/// G51.1 → G101 and G50.1 → G100 in block `b`; `Err` says why a G51.1 has no Haas form.
fn respell(b: &mut Block, shifted: bool) -> Result<(), &'static str> {
    let gs = crate::lower::g_codes(&b.items);
    let on = gs.contains(&511);
    if !on && !gs.contains(&501) {
        return Ok(());
    }
    if on {
        let zero = crate::lower::xyz_words_zero(&b.items);
        if !zero {
            return Err("a mirror about a position other than the work zero (Haas G101 mirrors about zero)");
        }
        if shifted {
            return Err("a mirror in a program that shifts the zero with G52 (Haas G101 is about the work zero)");
        }
    }
    crate::lower::respell_g(&mut b.items, &[(511, 101.0), (501, 100.0)]);
    Ok(())
}
