//! FANUC modal information reads (`#4001` motion, `#4003` G90/G91, `#4006` G20/G21, `#4014`
//! work offset) on Siemens: the constant, where the program itself has selected that mode
//! on every path to the read (`modal::ModalScan::selected_before`); otherwise refused by
//! name (NC549). Siemens `$P_GG[n]` returns the group's internal index, and no source read
//! for this work gives that numbering, so a read whose value is only known at run time has
//! no counterpart (docs/translation-fanuc-to-sinumerik.md, Variables).

use super::*;

/// The diagnostic of a modal information read that cannot be folded.
pub const MODAL_READ: &str = "NC549";

/// `#n` as the constant it holds at `span`, `None` when `n` is not one of the four; a
/// refusal (NC549) when it is and the value is not known there.
pub fn read(ctx: &mut Ctx, n: u32, span: Span) -> Option<Result<Expr, Vec<Stmt>>> {
    let (bit, what) = match n {
        4001 => (1, "#4001 (the motion G code G00..G03 of the preceding block)"),
        4003 => (2, "#4003 (G90/G91 of the preceding block)"),
        4006 => (4, "#4006 (G20/G21 of the preceding block)"),
        4014 => (8, "#4014 (the work offset G54..G59 of the preceding block)"),
        _ => return None,
    };
    let (st, own) = ctx.modal.selected_before(span.lo);
    let value = match n {
        4001 => st.motion.map(|g| f64::from(g / 10)),
        4003 => st.incremental.map(|inc| if inc { 91.0 } else { 90.0 }),
        4006 => st.inch.map(|inch| if inch { 20.0 } else { 21.0 }),
        _ => st.offset.filter(|g| g % 10 == 0 && (540..=590).contains(g)).map(|g| f64::from(g / 10)),
    };
    match value {
        // The block's own G word of the group: which one a FANUC read sees is not settled.
        Some(v) if own & bit == 0 => Some(Ok(Expr::num(v, v.fract() != 0.0, span))),
        _ => {
            let why = if own & bit != 0 {
                "in a block that selects a G code of the same group"
            } else {
                "where the program has not selected the mode itself on every path to it (a path, the caller, a called program or the power-on state decides it)"
            };
            let message = format!("{what} read {why} cannot be translated");
            let hint = "select the mode in the program before the read, on every path, in a block of its own; \
                        Siemens $P_GG gives group indices, not G numbers";
            Some(Err(ctx.refuse(MODAL_READ, span, &message, what, hint).into_iter().collect()))
        }
    }
}
