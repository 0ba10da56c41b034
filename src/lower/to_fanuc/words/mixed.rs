//! A Siemens block whose axis words are partly absolute and partly incremental
//! (`X=IC(5) Y=AC(10)`, `G91 X5 Y=AC(10)`) → one FANUC block in one mode, the words of the
//! other mode written through the block-end position `#5001+` (the last programmed end point
//! in the workpiece system, `$P_EP`): under G90 an increment `d` is `X[#5001+d]`, under G91
//! an absolute `v` is `Y[v-#5002]`. On FANUC both are the move `G91 X d` / `G90 Y v` makes,
//! which is what the block's single-mode words translate to already (docs/translation.md,
//! "Coordinate systems").
//!
//! The block keeps the mode in force; where that is not known and the block has no plain
//! axis word it is written in G90 (the switch and its restore are the caller's). Refused
//! (NC313) where `#5001` does not read what the rewrite needs or the block is another
//! thing than a move: in a program that rotates, scales or mirrors (G68, G51, G51.1: the
//! block-end position there is not modelled), in a called program (the caller's G52 may be
//! in force), with G53 (machine coordinates), with a unit word or a work offset selection
//! (the block's expressions are read in the unit and offset before them), with a call (a drilling cycle reads the words itself), on an
//! axis other than X Y Z A B C, and a plain axis word where G90/G91 is not known.

use super::*;

/// Rewrites the words of `out` (with their `forms`, AC = `Some(true)`) into one mode;
/// returns it (`true`: G90).
pub(super) fn rewrite(
    ctx: &mut Ctx,
    out: &mut [Word],
    forms: &[Option<bool>],
    m: &Modal,
    plain_axis: bool,
    has_call: bool,
    span: Span,
) -> Result<bool, Vec<Stmt>> {
    let refuse = |ctx: &mut Ctx, why: &str, hint: &str| {
        let what = format!("a block mixing absolute and incremental axis words {why}");
        Err(unsup(ctx, "NC313", span, &what, hint))
    };
    let own = "put the AC()/IC() words in a block of their own";
    let mode = match m.s.abs {
        Some(a) => a,
        None if !plain_axis => true,
        None => {
            return refuse(
                ctx,
                "where G90/G91 depends on the path taken or on the caller",
                "select G90 or G91 before the block",
            )
        }
    };
    if m.rot.any != 0 {
        return refuse(ctx, "in a program that rotates, scales or mirrors (the FANUC block-end position #5001+ under G68/G51/G51.1 is not modelled)", own);
    }
    if m.is_sub {
        return refuse(
            ctx,
            "in a called program (the caller's G52 shift may be in force, under which #5001+ is not modelled)",
            own,
        );
    }
    if has_call {
        return refuse(ctx, "with a call or cycle", own);
    }
    if out.iter().any(|w| w.addr.is(b'G') && const_of(&w.value) == Some(53.0)) {
        return refuse(ctx, "in machine coordinates (SUPA, G153, G53)", own);
    }
    // The block's expressions are read before its own G20/G21 or G54.. acts: #5001 in the
    // old unit or work offset.
    let gs = || out.iter().filter(|w| w.addr.is(b'G')).filter_map(|w| const_of(&w.value));
    if gs().any(|v| v == 20.0 || v == 21.0) {
        return refuse(
            ctx,
            "with a unit word (G70/G71/G700/G710; #5001+ is read in the unit before it)",
            "put the unit word in a block of its own",
        );
    }
    if gs().any(|v| (54.0..=59.0).contains(&v)) {
        return refuse(
            ctx,
            "with a work offset selection (#5001+ is read in the offset before it)",
            "select the work offset in a block of its own",
        );
    }
    for (w, form) in out.iter_mut().zip(forms) {
        let Addr::Letter(l) = w.addr else { continue };
        if !AXES.contains(&l) {
            continue;
        }
        let word_mode = form.unwrap_or(mode);
        if word_mode == mode {
            continue;
        }
        let Some(i) = b"XYZABC".iter().position(|&c| c == l) else {
            return refuse(
                ctx,
                &format!("on axis {} (only X Y Z A B C have a block-end position #5001..#5006)", l as char),
                own,
            );
        };
        let WordValue::Expr(e) = &w.value else { continue };
        let end = var_expr(&VarRef { kind: VarKind::Hash(5001 + i as u32), span: w.span });
        // A negative increment subtracts, an absolute 0 is the negated position: as a
        // machinist writes them.
        w.value = WordValue::Expr(match (mode, crate::lower::literal(e)) {
            (true, Some(d)) if d < 0.0 => bin(BinOp::Sub, end, Expr::num(-d, true, e.span)),
            (true, _) => bin(BinOp::Add, end, e.clone()),
            (false, Some(0.0)) => Expr::new(ExprKind::Unary(UnOp::Neg, Box::new(end)), e.span),
            (false, _) => bin(BinOp::Sub, e.clone(), end),
        });
    }
    Ok(mode)
}
