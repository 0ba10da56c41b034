//! Siemens chamfers and roundings → FANUC chamfering and corner R: `CHR=` and `RND=` have
//! the meaning of `,C` and `,R` (the leg from the virtual corner, the radius) and stay words
//! of that name for the writer; modal rounding `RNDM=r` … `RNDM=0` becomes a `,R` on every
//! block that moves in its stretch where the program runs straight through it; `CHF=` (the
//! chamfer's own length) is first made the CHR of its leg where the corner's angle is known
//! at translation, else refused (`corners_chf`; docs/semantics.md, "Chamfers and roundings").

use super::Ctx;
use crate::eval::corner::MODAL_ROUND;
use crate::ir::*;
use crate::span::Span;

/// Runs the pass on one program (after `blocks`, before `words`).
pub fn run(ctx: &mut Ctx, prog: &mut Program, info: &super::ProgInfo) {
    super::corners_chf::run(ctx, prog, info);
    let jumps = crate::lower::landings::Landings::of(&prog.body).any();
    let body = std::mem::take(&mut prog.body);
    prog.body = body_pass(ctx, body, jumps, true);
}

fn is_addr(w: &Word, n: &str) -> bool {
    w.addr.as_str() == n
}

/// A word that makes the block move (or arc) under modal rounding.
fn moves(w: &Word) -> bool {
    match &w.addr {
        Addr::Letter(l) => b"XYZABCUVWIJK".contains(l),
        Addr::Name(n) => matches!(n.as_ref(), "CR" | "AR"),
        Addr::Axis(_) => true,
    }
}

fn body_pass(ctx: &mut Ctx, body: Vec<Stmt>, jumps: bool, top: bool) -> Vec<Stmt> {
    // The radius of the modal rounding in force and the RNDM word that set it.
    let mut on: Option<(Expr, Span)> = None;
    let mut out = Vec::with_capacity(body.len());
    for mut s in body {
        let StmtKind::Block(b) = &mut s.kind else {
            if let Some((_, span)) = &on {
                refuse_modal(ctx, *span, "a structure (IF, loop, CASE) runs while it is in force");
                on = None;
            }
            s = map_nested(ctx, s, jumps);
            out.push(s);
            continue;
        };
        // A streamed translation's stand-in for a stretch of plain blocks (`stream::segmented`
        // writes them one by one, without this pass): modal rounding cannot reach them. (The
        // FANUC one carries the G70/G90… words its run leaves: items or not, it stands in.)
        let stand_in = super::stand_in(&b.meta).is_some();
        if let (Some((_, span)), true) = (&on, stand_in) {
            refuse_modal(
                ctx,
                *span,
                "a streamed translation writes the blocks after it one by one: translate the file whole",
            );
            on = None;
        }
        let mut rndm = None;
        let mut own = None;
        let mut control = None;
        for it in &b.items {
            match &it.kind {
                ItemKind::Word(w) if is_addr(w, "RNDM") => rndm = Some(w.clone()),
                ItemKind::Word(w) if is_addr(w, "CHR") || is_addr(w, "RND") => own = Some(w.span),
                ItemKind::Goto(_) | ItemKind::Case(_) | ItemKind::Call(_) | ItemKind::Return { .. } => {
                    control = Some(it.span)
                }
                _ => {}
            }
        }
        b.items.retain(|it| !matches!(&it.kind, ItemKind::Word(w) if is_addr(w, "CHF") || is_addr(w, "RNDM")));
        if let Some(w) = rndm {
            let value = match &w.value {
                WordValue::Expr(e) => Some(e.clone()),
                _ => None,
            };
            match value.as_ref().and_then(literal) {
                Some(0.0) => on = None,
                Some(_) if jumps => {
                    refuse_modal(ctx, w.span, "the program jumps (GOTO, CASE): which blocks it reaches is not fixed");
                    on = None;
                }
                Some(_) => on = Some((value.unwrap_or_else(|| Expr::num(0.0, true, w.span)), w.span)),
                None => {
                    refuse_modal(
                        ctx,
                        w.span,
                        "its radius is computed: whether it is 0 (off) is known only at run time",
                    );
                    on = None;
                }
            }
        }
        if let Some((r, span)) = on.clone() {
            if b.meta.label.is_some() || control.is_some() {
                let at = control.unwrap_or(b.meta.span);
                refuse_modal(ctx, at, "a label, jump, call or return lies in its stretch");
                let _ = span;
                on = None;
            } else if let Some(own) = own {
                refuse_modal(ctx, own, "a block in its stretch has a corner of its own");
                on = None;
            } else if b.items.iter().any(|it| matches!(&it.kind, ItemKind::Word(w) if moves(w))) {
                let w = Word { addr: Addr::Name("RND".into()), value: WordValue::Expr(r), span };
                b.items.push(Item { kind: ItemKind::Word(w), span });
            }
        }
        out.push(s);
    }
    if let (Some((_, span)), false) = (&on, top) {
        refuse_modal(ctx, *span, "it is still in force where its structure ends");
    }
    out
}

fn literal(e: &Expr) -> Option<f64> {
    crate::lower::literal(e)
}

fn refuse_modal(ctx: &mut Ctx, span: Span, why: &str) {
    let what = format!("RNDM= (modal rounding) where {why}");
    let _ = ctx.unsupported(
        MODAL_ROUND,
        span,
        &what,
        "FANUC has no modal corner R: write RND= in each block of the contour, or keep the stretch straight",
    );
}

/// The structure's own bodies, each a stretch of its own.
fn map_nested(ctx: &mut Ctx, mut s: Stmt, jumps: bool) -> Stmt {
    let mut f = |b: Vec<Stmt>| body_pass(ctx, b, jumps, false);
    match &mut s.kind {
        StmtKind::Block(_) => {}
        StmtKind::If(i) => {
            i.then_body = f(std::mem::take(&mut i.then_body));
            if let Some(e) = &mut i.else_part {
                e.body = f(std::mem::take(&mut e.body));
            }
        }
        StmtKind::While(w) => w.body = f(std::mem::take(&mut w.body)),
        StmtKind::Loop(l) => l.body = f(std::mem::take(&mut l.body)),
        StmtKind::For(x) => x.body = f(std::mem::take(&mut x.body)),
        StmtKind::Repeat(r) => r.body = f(std::mem::take(&mut r.body)),
        StmtKind::Do(d) => d.body = f(std::mem::take(&mut d.body)),
    }
    s
}
