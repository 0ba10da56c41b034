//! FANUC → Sinumerik: polar coordinates G16/G15 (docs/translation-fanuc-to-sinumerik.md,
//! "Coordinate systems").
//!
//! - `G16` → `G111 X0 Y0`: the pole at the workpiece zero (with a G52 shift, its TRANS),
//!   where FANUC measures the radius from under G90.
//! - A block with the radius and the angle in G16 mode (`G1 X50. Y45.`) → `G1 RP=50 AP=45`;
//!   `G15` → nothing (Sinumerik polar words act in their block only).
//!
//! In G17 programs only (the plane G16 reads its words in must be known). The mode must be
//! known on every path (`State::polar`; after a call of a program that may leave G16 on, it
//! is not: `modal::frame_calls`); a call in G16 mode is refused (a called program
//! is translated as starting without polar coordinates), as is a polar block without both
//! words or under G91, which the evaluator refuses too (NC497).

use super::modal::ModalScan;
use super::words::scale;
use super::*;

fn letter_of(it: &Item) -> Option<(u8, &Expr)> {
    match &it.kind {
        ItemKind::Word(Word { addr: Addr::Letter(l), value: WordValue::Expr(e), .. }) => Some((*l, e)),
        _ => None,
    }
}

fn refused(ctx: &mut Ctx, span: Span, what: &str, hint: &str) -> super::frames::Split {
    super::frames::Split {
        before: Vec::new(),
        block: None,
        after: ctx.refuse("NC497", span, &format!("{what}: not translated"), what, hint).into_iter().collect(),
    }
}

fn name_word(name: &str, v: Expr, span: Span) -> Item {
    Item { kind: ItemKind::Word(Word { addr: Addr::Name(name.into()), value: WordValue::Expr(v), span }), span }
}

/// A value with the decimal-point rule applied (`rotary`: an angle); `None` where a bare
/// length's unit is not known.
fn value(ctx: &Ctx, e: &Expr, inch: Option<bool>, rotary: bool) -> Option<Expr> {
    let mut e = e.clone();
    if let ExprKind::Num(n) = &mut e.kind {
        if !n.point {
            n.value = scale(ctx.opts, n.value, if rotary { false } else { inch? }, rotary);
            n.point = true;
        }
    }
    Some(e)
}

/// Translates a block with G16/G15 or in G16 mode; `Err(b)` hands any other block back.
pub fn split(
    ctx: &mut Ctx,
    b: Block,
    span: Span,
    modal: &ModalScan,
    gs: &[u32],
) -> Result<super::frames::Split, Block> {
    let polar = modal.polar_at(span.lo);
    let mentions = gs.contains(&160) || gs.contains(&150);
    if !mentions && polar == Some(false) {
        return Err(b);
    }
    // A drilling cycle (the cycles pass made it a CYCLE8x call) drills where the tool
    // stands; a subprogram would run its moves in G16 mode on FANUC only.
    let has_call = b.items.iter().any(|it| match &it.kind {
        ItemKind::Call(c) => !matches!(&c.target, CallTarget::Name(n) if n.starts_with("CYCLE")),
        _ => false,
    });
    let xy: Vec<(u8, Expr, Span)> = b
        .items
        .iter()
        .filter_map(|it| letter_of(it).filter(|(l, _)| matches!(l, b'X' | b'Y')).map(|(l, e)| (l, e.clone(), it.span)))
        .collect();
    // Blocks whose axis words stay Cartesian in G16 mode.
    let cartesian = gs.iter().any(|g| matches!(g, 100 | 520 | 920 | 530 | 680 | 510 | 511 | 501));
    if polar != Some(false)
        && (modal.other_plane() || has_call || polar.is_none())
        && (has_call || !xy.is_empty())
        && !cartesian
    {
        return Ok(refused(
            ctx,
            span,
            "a block in G16 mode in a program that selects G18/G19, a call in G16 mode, or a move where G16 depends on the path taken",
            "program polar coordinates in G17, cancel them (G15) before calls, on every path alike",
        ));
    }
    if !mentions && (xy.is_empty() || cartesian) {
        return Err(b);
    }
    let mut b = b;
    let mut before = Vec::new();
    if gs.contains(&160) {
        let zero = |l| Item {
            kind: ItemKind::Word(Word { addr: Addr::Letter(l), value: WordValue::Expr(num(0.0, span)), span }),
            span,
        };
        before.push(plain_block(vec![super::words::g_word(1110, span), zero(b'X'), zero(b'Y')], span));
    }
    b.items.retain(
        |it| !matches!(letter_of(it), Some((b'G', e)) if matches!(literal(e), Some(v) if v == 16.0 || v == 15.0)),
    );
    if polar == Some(true) && !xy.is_empty() && !cartesian {
        let (Some(r), Some(a)) = (xy.iter().rev().find(|w| w.0 == b'X'), xy.iter().rev().find(|w| w.0 == b'Y')) else {
            return Ok(refused(
                ctx,
                span,
                "a G16 block without both the radius and the angle",
                "write X (radius) and Y (angle)",
            ));
        };
        if modal.incremental_at(span.lo) != Some(false) {
            return Ok(refused(
                ctx,
                span,
                "polar coordinates where G91 may be in force",
                "program polar coordinates under G90",
            ));
        }
        let inch = modal.inch_at(span.lo);
        let (Some(rv), Some(av)) = (value(ctx, &r.1, inch, false), value(ctx, &a.1, inch, true)) else {
            return Ok(refused(
                ctx,
                span,
                "a radius without a decimal point where the unit depends on the path taken",
                "write it with a decimal point",
            ));
        };
        let (rs, as_) = (r.2, a.2);
        b.items.retain(|it| !matches!(letter_of(it), Some((b'X' | b'Y', _))));
        b.items.push(name_word("RP", rv, rs));
        b.items.push(name_word("AP", av, as_));
    }
    let keep = !b.items.is_empty() || b.meta.number.is_some() || b.meta.label.is_some() || !b.meta.comments.is_empty();
    if keep && !before.is_empty() && (b.meta.number.is_some() || b.meta.label.is_some()) {
        // A jump to the block sets the pole too: the number and label go first.
        let meta = BlockMeta { number: b.meta.number.take(), label: b.meta.label.take(), span, ..BlockMeta::default() };
        before.insert(0, block_stmt(meta, Vec::new()));
    }
    Ok(super::frames::Split { before, block: keep.then_some(b), after: Vec::new() })
}
