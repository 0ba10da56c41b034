//! FANUC → Sinumerik: coordinate rotation G68/G69 (docs/translation-fanuc-to-sinumerik.md,
//! "Coordinate systems").
//!
//! - `G68 X cx Y cy R a` (the centre in the plane's two axes, absolute) →
//!   `ATRANS X=cx Y=cy` / `AROT RPL=a` / `ATRANS X=-cx Y=-cy`: a rotation about the same
//!   point, added to the frame in force (the G52 shift, a TRANS), as FANUC rotates in the
//!   local coordinate system. About the origin only `AROT RPL=a`. Both rotate in the plane
//!   selected at the block (RPL= in the active plane), so the plane need not be known here.
//! - `G69` → the same three instructions undoing that G68 (`ATRANS`, `AROT RPL=-a`,
//!   `ATRANS`), which keeps any shift exactly; where no rotation is in force, nothing.
//!
//! The G68 in force at a G69 must be known from the program's text on every path (the
//! modal scan, `State::rot`), and its values must be constants; a G68 or G69 in a called
//! program (whose caller's rotation is not known here), a G68 in G68 mode, one without a
//! centre (the tool position) or an angle (parameter 5410), and one under G91 are refused
//! (NC497).

use super::modal::ModalScan;
use super::words::scale;
use super::*;

/// What [`split`] makes of a block.
pub type Out = super::frames::Split;

fn letter_of(it: &Item) -> Option<(u8, &Expr)> {
    match &it.kind {
        ItemKind::Word(Word { addr: Addr::Letter(l), value: WordValue::Expr(e), .. }) => Some((*l, e)),
        _ => None,
    }
}

fn g_of(it: &Item) -> Option<u32> {
    match letter_of(it) {
        Some((b'G', e)) => literal(e).map(|v| (v * 10.0).round() as u32),
        _ => None,
    }
}

fn frame(op: &str, words: Vec<Word>, span: Span) -> Stmt {
    plain_block(vec![Item { kind: ItemKind::Frame { op: op.into(), words }, span }], span)
}

/// The centre (axis letter, value) and angle of a G68 block, as constants in mm and
/// degrees; `Err` with what is wrong.
fn rotation_of(ctx: &Ctx, items: &[Item], inch: Option<bool>) -> Result<(Vec<(u8, f64)>, f64), &'static str> {
    let mut centre = Vec::new();
    let mut angle = None;
    for it in items {
        match letter_of(it) {
            Some((b'G', _)) if matches!(g_of(it), Some(680 | 900 | 170 | 180 | 190)) => {}
            Some((l, e)) if b"XYZR".contains(&l) => {
                let Some(v) = literal(e) else { return Err("a G68 centre or angle that is not a constant") };
                let point = matches!(&e.kind, ExprKind::Num(n) if n.point)
                    || matches!(&e.kind, ExprKind::Unary(_, a) if matches!(&a.kind, ExprKind::Num(n) if n.point));
                let v = if point {
                    v
                } else if l == b'R' {
                    // An angle counts the metric increment in either unit.
                    scale(ctx.opts, v, false, true)
                } else {
                    let Some(inch) = inch else {
                        return Err("a G68 centre without a decimal point where the unit depends on the path taken");
                    };
                    scale(ctx.opts, v, inch, false)
                };
                if l == b'R' {
                    angle = Some(v);
                } else {
                    centre.push((l, v));
                }
            }
            _ => return Err("G68 with other words than its centre, R and G90"),
        }
    }
    let Some(angle) = angle else { return Err("G68 without R (the angle is then machine parameter 5410)") };
    if centre.len() != 2 {
        return Err("G68 without its centre in both axes of the plane (the tool position is then the centre)");
    }
    Ok((centre, angle))
}

fn sequence(centre: &[(u8, f64)], angle: f64, span: Span) -> Vec<Stmt> {
    let shift = |sign: f64| -> Vec<Word> {
        centre
            .iter()
            .map(|&(l, v)| Word { addr: Addr::Letter(l), value: WordValue::Expr(num(sign * v, span)), span })
            .collect()
    };
    let about_origin = centre.iter().all(|c| c.1 == 0.0);
    let rot = Word { addr: Addr::Name("RPL".into()), value: WordValue::Expr(num(angle, span)), span };
    let mut out = Vec::new();
    if !about_origin {
        out.push(frame("ATRANS", shift(1.0), span));
    }
    out.push(frame("AROT", vec![rot], span));
    if !about_origin {
        out.push(frame("ATRANS", shift(-1.0), span));
    }
    out
}

fn refused(ctx: &mut Ctx, span: Span, what: &str, hint: &str) -> Out {
    Out {
        before: Vec::new(),
        block: None,
        after: ctx.refuse("NC497", span, &format!("{what}: not translated"), what, hint).into_iter().collect(),
    }
}

/// Translates a block with G68 or G69 (`gs`); `Err(b)` hands any other block back.
pub fn split(ctx: &mut Ctx, b: Block, span: Span, modal: &ModalScan, gs: &[u32]) -> Result<Out, Block> {
    let g68 = gs.contains(&680);
    if !g68 && !gs.contains(&690) {
        return Err(b);
    }
    let first = b.items.first().map_or(span.lo, |it| it.span.lo);
    let in_force = modal.rot_before(first);
    if g68 {
        if in_force != Some(0) {
            return Ok(refused(
                ctx,
                span,
                "G68 in G68 mode, in a called program, or where a rotation may be in force on some path",
                "cancel the rotation with G69 before each G68, in the main program",
            ));
        }
        if modal.incremental_at(span.lo) != Some(false) || gs.contains(&910) {
            return Ok(refused(
                ctx,
                span,
                "G68 where G91 may be in force (the centre and, with parameter 5400#0, the angle read incrementally)",
                "write G68 under G90: `G90 G68 X.. Y.. R..`",
            ));
        }
        return Ok(match rotation_of(ctx, &b.items, modal.inch_at(span.lo)) {
            Err(what) => refused(ctx, span, what, "write `G68 X.. Y.. R..` with constants, alone in its block"),
            Ok((centre, angle)) => {
                let mut meta = b.meta;
                meta.span = span;
                let mut after = Vec::new();
                let g90: Vec<Item> = b.items.iter().filter(|it| g_of(it) == Some(900)).cloned().collect();
                let planes: Vec<Item> =
                    b.items.iter().filter(|it| matches!(g_of(it), Some(170 | 180 | 190))).cloned().collect();
                // The block's modal words first (the plane the rotation is in), numbered as
                // the source block so a jump to it runs the whole rotation.
                let modes: Vec<Item> = g90.into_iter().chain(planes).collect();
                if !modes.is_empty() || meta.number.is_some() || meta.label.is_some() || !meta.comments.is_empty() {
                    after.push(block_stmt(meta, modes));
                }
                after.extend(sequence(&centre, angle, span));
                Out { before: Vec::new(), block: None, after }
            }
        });
    }
    // G69: undo the G68 in force, if any.
    let undo = match in_force {
        Some(0) => Vec::new(),
        Some(k) => match modal.g68_block(k) {
            Some((lo, items)) => match rotation_of(ctx, items, modal.inch_at(lo)) {
                Ok((centre, angle)) => sequence(&centre, -angle, span),
                Err(_) => return Ok(refused(ctx, span, "G69 after a G68 that is not translated", "see the G68's error")),
            },
            None => return Ok(refused(ctx, span, "G69 where the rotation in force is not known", "cancel in the main program")),
        },
        None => {
            return Ok(refused(
                ctx,
                span,
                "G69 in a called program, or where the rotation in force depends on the path taken (which G68 it cancels is not known here)",
                "cancel the rotation in the main program, on a path where one G68 is in force",
            ))
        }
    };
    let mut b = b;
    b.items.retain(|it| g_of(it) != Some(690));
    let mut undo = undo;
    if !undo.is_empty() && (b.meta.number.is_some() || b.meta.label.is_some()) {
        // A jump to the block runs the cancel too: the number and label go first.
        let meta = BlockMeta { number: b.meta.number.take(), label: b.meta.label.take(), span, ..BlockMeta::default() };
        undo.insert(0, block_stmt(meta, Vec::new()));
    }
    let rest = if b.items.is_empty() && b.meta.number.is_none() && b.meta.comments.is_empty() && b.meta.label.is_none() {
        None
    } else {
        Some(b)
    };
    Ok(Out { before: undo, block: rest, after: Vec::new() })
}
