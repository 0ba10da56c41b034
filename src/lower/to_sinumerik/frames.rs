//! FANUC → Sinumerik: the local coordinate system, extended work offsets and reference
//! returns (docs/translation-fanuc-to-sinumerik.md, "Coordinate systems").
//!
//! - `G52 X.. Y..` → `TRANS X.. Y..`: G52 replaces the shift of the axes it names and keeps
//!   the others, TRANS replaces the whole programmable frame. The two agree when the block
//!   names every axis any G52 of the program may have shifted (a called program: X, Y and Z,
//!   since its caller's shift is not known) and that a path to the block may leave shifted
//!   (`ModalScan::g52_before`), so that is required (NC442). G52 under G68,
//!   G51 or G51.1 is refused by the evaluator (so no proven program has one), so TRANS,
//!   which would delete their frames too, is exact. `G52 X0 Y0 Z0` → bare `TRANS`.
//! - `G53 ..` stays `G53 ..` (words.rs): Sinumerik G53 suppresses the settable and
//!   programmable frames for the block, which is all FANUC G53 ignores that translates (the
//!   external offset `G10 L2 P0` / `#5201+` is refused), and the streamed translators agree.
//! - `G54.1 Pn` (and `G54 Pn`) → `G50(6+n)`: `G507` for P1 (the trace numbers both 6 + n).
//! - `G28 ..` → the intermediate point as `G0 ..` (left out for `G91 G28 Z0`, where it is
//!   the current position), then `G74 Z1=0 ..`, then the motion G code again if it was not
//!   G0 (FANUC G28 leaves the motion mode alone). `G30 Pn` → `G75 FP=n-1` the same way.

use super::modal::ModalScan;
use super::words::scale;
use super::*;

/// What a block becomes: statements before it, the block still to lower as usual (if
/// any), statements after it.
pub struct Split {
    pub before: Vec<Stmt>,
    pub block: Option<Block>,
    pub after: Vec<Stmt>,
}

const AXIS_LETTERS: &[u8; 9] = b"XYZABCUVW";

fn axis_bit(l: u8) -> Option<u16> {
    AXIS_LETTERS.iter().position(|&c| c == l).map(|i| 1 << i)
}

fn g_of(it: &Item) -> Option<u32> {
    match &it.kind {
        ItemKind::Word(Word { addr: Addr::Letter(b'G'), value: WordValue::Expr(e), .. }) => {
            literal(e).map(|v| (v * 10.0).round() as u32)
        }
        _ => None,
    }
}

fn letter_of(it: &Item) -> Option<(u8, &Expr)> {
    match &it.kind {
        ItemKind::Word(Word { addr: Addr::Letter(l), value: WordValue::Expr(e), .. }) => Some((*l, e)),
        _ => None,
    }
}

pub use crate::lower::g52_axes;

/// A literal axis value in the unit in force (the decimal-point rule: `inch` is G20 at the
/// block), other values as written; `None` for a value without a decimal point where the
/// unit is not known (it cannot be written exactly).
fn axis_value(ctx: &Ctx, e: &Expr, inch: Option<bool>) -> Option<Expr> {
    let mut e = e.clone();
    if let ExprKind::Num(n) = &mut e.kind {
        if !n.point {
            n.value = scale(ctx.opts, n.value, inch?, false);
            n.point = true;
        }
    }
    Some(e)
}

fn name_word(name: &str, v: Expr, span: Span) -> Item {
    Item { kind: ItemKind::Word(Word { addr: Addr::Name(name.into()), value: WordValue::Expr(v), span }), span }
}

/// Splits off what this module translates; `Err(b)` hands the block back untouched.
pub fn split(ctx: &mut Ctx, b: Block, span: Span, modal: &ModalScan, gs: &[u32]) -> Result<Split, Block> {
    let b = match super::rotation::split(ctx, b, span, modal, gs) {
        Ok(split) => return Ok(split),
        Err(b) => b,
    };
    let b = match super::polar::split(ctx, b, span, modal, gs) {
        Ok(split) => return Ok(split),
        Err(b) => b,
    };
    if gs.contains(&920) && !gs.contains(&681) && !gs.contains(&290) {
        return Ok(g92(ctx, b, span, modal));
    }
    if gs.contains(&290) && !gs.contains(&681) && !gs.contains(&920) {
        return Ok(g29(ctx, b, span, modal));
    }
    if let Some(&g) = gs.iter().find(|g| matches!(g, 681 | 290 | 920)) {
        let what = match g {
            681 => "G68.1 (three-dimensional coordinate rotation)",
            290 => "G29 (return from the reference point)",
            _ => "G92 (coordinate system setting)",
        };
        let st = ctx.refuse(
            "NC446",
            span,
            &format!(
                "{what} is not translated: nctrans does not model it yet, so its Sinumerik form could not be proven"
            ),
            what,
            "translate the feature by hand (e.g. G68 about a centre: TRANS to the centre, AROT RPL=, ATRANS back)",
        );
        return Ok(Split { before: Vec::new(), block: None, after: st.into_iter().collect() });
    }
    if gs.contains(&520) {
        Ok(local_shift(ctx, b, span, modal))
    } else if gs.contains(&280) || gs.contains(&300) {
        Ok(reference_return(ctx, b, span, modal, gs.contains(&300)))
    } else if gs.contains(&541)
        || (gs.contains(&540) && b.items.iter().any(|it| matches!(letter_of(it), Some((b'P', _)))))
    {
        Ok(extended_offset(ctx, b, span))
    } else {
        Err(b)
    }
}

fn refused(ctx: &mut Ctx, code: &'static str, span: Span, what: &str, hint: &str) -> Split {
    Split { before: Vec::new(), block: None, after: ctx.unsupported(code, span, what, hint).into_iter().collect() }
}

fn only_words(b: &Block, allowed_g: &[u32], letters: &[u8]) -> bool {
    b.items.iter().all(|it| match letter_of(it) {
        Some((b'G', _)) => g_of(it).is_some_and(|g| allowed_g.contains(&g)),
        Some((l, _)) => axis_bit(l).is_some() || letters.contains(&l),
        None => false,
    })
}

fn local_shift(ctx: &mut Ctx, b: Block, span: Span, modal: &ModalScan) -> Split {
    if !only_words(&b, &[520, 900], &[]) || modal.incremental_at(span.lo) != Some(false) {
        return refused(
            ctx,
            "NC442",
            span,
            "G52 with other words, or where G91 may be in force",
            "write G52 alone in its block, under G90: `G90 G52 X.. Y..`",
        );
    }
    if modal.incremental_motion {
        return refused(
            ctx,
            "NC442",
            span,
            "G52 in a program with incremental (G91) moves (after a TRANS a Sinumerik incremental move also travels the shift, a FANUC one does not)",
            "program the moves after G52 in G90",
        );
    }
    let (shifted, main) = modal.g52;
    // An axis no path to the block leaves shifted keeps 0 under TRANS too.
    let need = (if main { shifted } else { shifted | 0b111 }) & modal.g52_before(span.lo);
    let named: u16 = b.items.iter().filter_map(letter_of).filter_map(|(l, _)| axis_bit(l)).fold(0, |a, x| a | x);
    if need & !named != 0 {
        let missing: String =
            (0..9).filter(|i| need & !named & (1 << i) != 0).map(|i| AXIS_LETTERS[i] as char).collect();
        return refused(
            ctx,
            "NC442",
            span,
            &format!("a G52 that keeps the shift of {missing} (Sinumerik TRANS replaces the whole shift)"),
            &format!("name every shifted axis in each G52, e.g. `G52 {}0`", missing.chars().next().unwrap_or('X')),
        );
    }
    // Under G68/G51/G51.1 a bare TRANS would also delete the rotation, scaling or mirror the
    // programmable frame holds; a G52 of zeros with no shift to cancel changes nothing (the
    // FANUC run takes it so), so only its G90 is written.
    let zeros = b.items.iter().filter_map(letter_of).all(|(l, e)| axis_bit(l).is_none() || literal(e) == Some(0.0));
    if zeros && need == 0 && modal.rot_before(span.lo) != Some(0) {
        let g90: Vec<Item> = b.items.iter().filter(|it| g_of(it) == Some(900)).cloned().collect();
        let mut meta = b.meta;
        meta.span = span;
        let keep = !g90.is_empty() || meta.number.is_some() || meta.label.is_some() || !meta.comments.is_empty();
        let after = if keep { vec![block_stmt(meta, g90)] } else { Vec::new() };
        return Split { before: Vec::new(), block: None, after };
    }
    let mut words = Vec::new();
    let inch = modal.inch_at(span.lo);
    for it in &b.items {
        if let Some((l, e)) = letter_of(it) {
            if axis_bit(l).is_some() && literal(e) != Some(0.0) {
                let Some(v) = axis_value(ctx, e, inch) else {
                    return refused(
                        ctx,
                        "NC375",
                        it.span,
                        "a G52 value without a decimal point where the unit (G20/G21) depends on the path taken or on the caller",
                        "write the value with a decimal point",
                    );
                };
                words.push(Word { addr: Addr::Letter(l), value: WordValue::Expr(v), span: it.span });
            }
        }
    }
    let frame = Item { kind: ItemKind::Frame { op: "TRANS".into(), words }, span };
    // The block's G90 stays in force after it: it goes first, in a block of its own.
    let g90: Vec<Item> = b.items.iter().filter(|it| g_of(it) == Some(900)).cloned().collect();
    let mut meta = b.meta;
    meta.span = span;
    // The first block keeps the number and label: a jump to the block runs both.
    let after = if g90.is_empty() {
        vec![block_stmt(meta, vec![frame])]
    } else {
        vec![block_stmt(meta, g90), plain_block(vec![frame], span)]
    };
    Split { before: Vec::new(), block: None, after }
}

fn extended_offset(ctx: &mut Ctx, mut b: Block, span: Span) -> Split {
    let p = b.items.iter().find_map(|it| match letter_of(it) {
        Some((b'P', e)) => Some(literal(e)),
        _ => None,
    });
    let n = match p {
        Some(Some(n)) if n.fract() == 0.0 && (1.0..=48.0).contains(&n) => n as u32,
        _ => {
            return refused(
                ctx,
                "NC443",
                span,
                "G54.1 without a constant P1..P48",
                "write the extended offset number as a constant: `G54.1 P3`",
            )
        }
    };
    b.items.retain(|it| !matches!(g_of(it), Some(540 | 541)) && !matches!(letter_of(it), Some((b'P', _))));
    let sel = plain_block(vec![super::words::g_word(5060 + 10 * n, span)], span);
    Split { before: vec![sel], block: if b.items.is_empty() { None } else { Some(b) }, after: Vec::new() }
}

fn reference_return(ctx: &mut Ctx, mut b: Block, span: Span, modal: &ModalScan, g30: bool) -> Split {
    let letters: &[u8] = if g30 { b"P" } else { b"" };
    // M5 and M9 act after a block's motion (trace order), and G74/G75 must stand alone on
    // Sinumerik: they move to a block of their own after the return, where they act the same.
    let (stops, rest): (Vec<Item>, Vec<Item>) = b.items.into_iter().partition(
        |it| matches!(letter_of(it), Some((b'M', e)) if matches!(literal(e), Some(v) if v == 5.0 || v == 9.0)),
    );
    b.items = rest;
    // A G00/G01 beside it only sets the motion mode (the return itself is at rapid), which
    // `motion` below holds.
    if !only_words(&b, &[280, 300, 900, 910, 0, 10], letters) || b.items.iter().any(|it| g_of(it) == Some(280)) == g30 {
        return refused(
            ctx,
            "NC444",
            span,
            "G28/G30 with other words in the block",
            "write the reference return alone in its block: `G91 G28 Z0`",
        );
    }
    let fp = if g30 {
        let p = b.items.iter().find_map(|it| match letter_of(it) {
            Some((b'P', e)) => Some(literal(e)),
            _ => None,
        });
        match p {
            None => 1,
            Some(Some(n)) if n.fract() == 0.0 && (2.0..=4.0).contains(&n) => n as i64 - 1,
            _ => {
                return refused(
                    ctx,
                    "NC444",
                    span,
                    "G30 without a constant P2..P4",
                    "write the reference point number as a constant: `G30 P2`",
                )
            }
        }
    } else {
        0
    };
    let axes: Vec<&Item> =
        b.items.iter().filter(|it| letter_of(it).is_some_and(|(l, _)| axis_bit(l).is_some())).collect();
    if axes.is_empty() {
        return refused(ctx, "NC444", span, "G28/G30 without an axis", "name the axes to return: `G91 G28 Z0`");
    }
    let incremental = modal.incremental_at(span.lo) == Some(true);
    let stays = incremental && axes.iter().all(|it| letter_of(it).is_some_and(|(_, e)| literal(e) == Some(0.0)));
    let motion = modal.motion_at(span.lo);
    if !stays && motion.is_none() {
        return refused(
            ctx,
            "NC444",
            span,
            "G28/G30 with an intermediate point where the motion mode (G0/G1/G2/G3) depends on the path taken",
            "program G0 or G1 before the reference return on every path",
        );
    }
    let mut home = vec![super::words::g_word(if g30 { 750 } else { 740 }, span)];
    if g30 {
        home.push(name_word("FP", int(fp, span), span));
    }
    for it in &axes {
        if let Some((l, _)) = letter_of(it) {
            home.push(name_word(&format!("{}1", l as char), int(0, it.span), it.span));
        }
    }
    let mut after = vec![plain_block(home, span)];
    let first = if stays {
        // The intermediate point is where the tool stands: only the G90/G91 and G0/G1 words remain.
        let mut b = b;
        b.items.retain(|it| matches!(g_of(it), Some(900 | 910 | 0 | 10)));
        if b.items.is_empty() && b.meta.number.is_none() && b.meta.comments.is_empty() {
            None
        } else {
            Some(b)
        }
    } else {
        let mut b = b;
        b.items.retain(|it| !matches!(g_of(it), Some(280 | 300 | 0 | 10)) && !matches!(letter_of(it), Some((b'P', _))));
        b.items.insert(0, super::words::g_word(0, span));
        if let Some(m) = motion.filter(|m| *m != 0) {
            after.push(plain_block(vec![super::words::g_word(m, span)], span));
        }
        Some(b)
    };
    if !stops.is_empty() {
        after.push(plain_block(stops, span));
    }
    Split { before: Vec::new(), block: first, after }
}

/// `G92 X v ..` → `ATRANS X=$P_EP[X]-v ..`: the current position on each named axis gets
/// the coordinate v, by a shift added to the programmable frame, which (as the G92 shift
/// does every work offset) stays through G54..G599 selections and reference returns. Exact
/// where nothing else writes that frame and no increment would travel its change: refused
/// (NC547) in a called program, in one with G52, G68, G51, G51.1 or G16 (their TRANS,
/// AROT, … would replace or turn it), with incremental moves (after ATRANS a Sinumerik
/// increment also travels the shift, MD42440), under G91, and with other words.
fn g92(ctx: &mut Ctx, b: Block, span: Span, modal: &ModalScan) -> Split {
    let refuse = |ctx: &mut Ctx, what: &str, hint: &str| refused(ctx, "NC547", span, what, hint);
    if !only_words(&b, &[920, 900], &[]) || modal.incremental_at(span.lo) != Some(false) {
        return refuse(
            ctx,
            "G92 with other words, or where G91 may be in force",
            "write G92 alone in its block, under G90: `G90 G92 X.. Y..`",
        );
    }
    if !modal.g52.1 {
        return refuse(
            ctx,
            "G92 in a called program (its Sinumerik shift would add to the caller's frame, which is not known here)",
            "set the coordinate system in the main program",
        );
    }
    if modal.frames() {
        return refuse(
            ctx,
            "G92 in a program with G52, G68, G51, G51.1 or G16 (their Sinumerik frames would replace or turn the shift G92 becomes)",
            "use one kind of coordinate shift in the program: G92, or G52/G54..",
        );
    }
    if modal.incremental_motion {
        return refuse(
            ctx,
            "G92 in a program with incremental (G91) moves (after a frame change a Sinumerik incremental move also travels the shift, a FANUC one does not)",
            "program the moves after G92 in G90",
        );
    }
    let inch = modal.inch_at(span.lo);
    let mut words = Vec::new();
    for it in &b.items {
        let Some((l, e)) = letter_of(it) else { continue };
        let Some(i) = b"XYZABC".iter().position(|&c| c == l) else {
            if axis_bit(l).is_some() {
                return refuse(
                    ctx,
                    "G92 on an axis other than X Y Z A B C",
                    "set the coordinate of X, Y, Z, A, B or C",
                );
            }
            continue;
        };
        let Some(v) = axis_value(ctx, e, inch) else {
            return refused(
                ctx,
                "NC375",
                it.span,
                "a G92 value without a decimal point where the unit (G20/G21) depends on the path taken or on the caller",
                "write the value with a decimal point",
            );
        };
        let Some(ep) = super::words::system_var(5001 + i as u32, it.span) else { continue };
        let at = var_expr(ep, it.span);
        let shift = if literal(&v) == Some(0.0) { at } else { bin(BinOp::Sub, at, v) };
        words.push(Word { addr: Addr::Letter(l), value: WordValue::Expr(shift), span: it.span });
    }
    if words.is_empty() {
        return refuse(ctx, "G92 without an axis", "name the axes whose coordinate is set: `G92 X0 Y0`");
    }
    let frame = Item { kind: ItemKind::Frame { op: "ATRANS".into(), words }, span };
    let g90: Vec<Item> = b.items.iter().filter(|it| g_of(it) == Some(900)).cloned().collect();
    let mut meta = b.meta;
    meta.span = span;
    let after = if g90.is_empty() {
        vec![block_stmt(meta, vec![frame])]
    } else {
        vec![block_stmt(meta, g90), plain_block(vec![frame], span)]
    };
    Split { before: Vec::new(), block: None, after }
}

/// `G29 Z..` → `G0 Z<intermediate point>` (with `=AC(..)` where G91 may be in force), then
/// the block's words in `G0`, then the motion G code again if it was not G0. The
/// intermediate point must be known from the text ([`ModalScan::intermediate_at`]): the
/// absolute constant of the last G28/G30 on every path, with no offset, G52, G92, unit
/// change or call since; else NC548.
fn g29(ctx: &mut Ctx, b: Block, span: Span, modal: &ModalScan) -> Split {
    if !only_words(&b, &[290, 900, 910], &[]) {
        return refused(
            ctx,
            "NC548",
            span,
            "G29 with other words in the block",
            "write the return alone in its block: `G29 Z..`",
        );
    }
    let incremental = modal.incremental_at(span.lo);
    let inch = modal.inch_at(span.lo);
    let mut via = vec![super::words::g_word(0, span)];
    for it in &b.items {
        let Some((l, _)) = letter_of(it) else { continue };
        if axis_bit(l).is_none() {
            continue;
        }
        let known = b"XYZABC".iter().position(|&c| c == l).and_then(|i| modal.intermediate_at(span.lo, i));
        let Some(v) = known.and_then(|(_, e)| axis_value(ctx, e, inch)) else {
            return refused(
                ctx,
                "NC548",
                it.span,
                &format!("G29 on {} where the intermediate point is not known from the text (the last G28/G30 on every path, absolute and constant, with no work offset, G52, G92, unit change or call since)", l as char),
                "move back with G0 to the point itself, or write the G28 intermediate point as a constant under G90",
            );
        };
        let value = if incremental == Some(false) { WordValue::Expr(v) } else { WordValue::Ac(v) };
        via.push(Item { kind: ItemKind::Word(Word { addr: Addr::Letter(l), value, span: it.span }), span: it.span });
    }
    if via.len() == 1 {
        return refused(ctx, "NC548", span, "G29 without an axis", "name the axes to return: `G29 Z5.`");
    }
    let motion = modal.motion_at(span.lo);
    let Some(motion) = motion else {
        return refused(
            ctx,
            "NC548",
            span,
            "G29 where the motion mode (G0/G1/G2/G3) depends on the path taken",
            "program G0 or G1 before the return on every path",
        );
    };
    // The first block keeps the number and label: a jump to the G29 runs both moves.
    let mut b = b;
    let mut meta = std::mem::take(&mut b.meta);
    meta.span = span;
    b.meta.span = span;
    b.items.retain(|it| g_of(it) != Some(290));
    b.items.insert(0, super::words::g_word(0, span));
    let mut after = Vec::new();
    if motion != 0 {
        after.push(plain_block(vec![super::words::g_word(motion, span)], span));
    }
    Split { before: vec![block_stmt(meta, via)], block: Some(b), after }
}
