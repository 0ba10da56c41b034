//! FANUC → Sinumerik: coordinate rotation G68/G69, scaling G51/G50 and programmable mirror
//! image G51.1/G50.1 (docs/translation-fanuc-to-sinumerik.md, "Coordinate systems").
//!
//! Each becomes the additive frame about the same point, added to the frame in force (the
//! G52 shift, a TRANS), as FANUC applies them in the local coordinate system:
//! - `G68 X cx Y cy R a` → `ATRANS X=cx Y=cy` / `AROT RPL=a` / `ATRANS X=-cx Y=-cy`
//!   (about the origin only `AROT RPL=a`). Both rotate in the plane selected at the block
//!   (RPL= in the active plane), so the plane need not be known here (but for a G68 without a centre).
//! - `G51 X cx Y cy P f` (or `I J K`, a factor each) → `ATRANS` to the centre, `ASCALE` of
//!   the axes whose centre G51 names, `ATRANS` back.
//! - `G51.1 X a` → `ATRANS X=a` / `AMIRROR X0` / `ATRANS X=-a`: mirrored about X = a.
//! - `G69`, `G50`, `G50.1` → the same three instructions undoing the mode in force
//!   (`AROT RPL=-a`, `ASCALE X=1/f`, the mirror again), which keeps any shift exactly;
//!   where none is in force, nothing.
//! - A G68 in G68 mode replaces angle and centre (FANUC, Haas): where the programmable
//!   frame holds nothing but the rotation (`ModalScan::frame_base_empty`), a bare `TRANS`
//!   empties it first, whichever G68 was in force; otherwise the known one is undone first.
//!   A G69 where paths or section calls disagree only on which of the program's G68s (or
//!   none) is in force ([`ROT_ANY`]) is the bare `TRANS` over an empty frame, else NC497.
//!
//! One mode at a time: FANUC applies mirror, scaling and rotation in that order whatever
//! order they are commanded in, Sinumerik's additive frames in the order written, so a
//! second mode while one is in force is refused (a G68 over a G68 aside, above). The mode
//! in force at a cancel must be known from the program's text on every path (the modal
//! scan, `State::rot`), and its values must be constants, except a G68's: a word of user
//! variables is saved at the G68 in `NCTRANS_G68_<axis>` (DEF REAL), which the cancel
//! reads, so the G69 turns back by the values the rotation was set with, as FANUC's. A
//! called program starts with no mode in force where every call of it in the job is made so
//! (`modal::frame_calls`); the programmable frame it writes stays in force after its return
//! as FANUC's modes survive M99 (no `SAVE` on the PROC), and a caller knows its modes after
//! the call only where the callee cancels what it set on every path to its ends. A G68
//! without a centre turns about the tool position (`$P_EP` of the plane's axes, saved) where
//! the plane is known (`planes`) and the tool surely stands on the increment grid. A mode set
//! or cancelled in a called program otherwise (the caller's is not known here), a G68
//! without a centre elsewhere or without an angle (parameter 5410), a G51 without the
//! centre of each axis it scales or a factor, a G50.1 that leaves an axis of its G51.1
//! mirrored, and any of them under G91 are refused (NC497). A cancel of a mode not in force
//! (G50 under G51.1) changes nothing, as on FANUC.

use super::modal::{ModalScan, ROT_ANY};
use super::words::scale;
use super::*;

/// What [`split`] makes of a block.
pub type Out = super::frames::Split;

/// A mode as constants: the centre (axis letter, mm) and what it does there.
enum Mode {
    /// The centre and the angle: constants, or the variables ([`saved`]) that hold the
    /// value of an expression at the G68.
    Rotate(Vec<(u8, Expr)>, Expr),
    Scale(Vec<(u8, f64, f64)>),
    Mirror(Vec<(u8, f64)>),
}

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

fn has_point(e: &Expr) -> bool {
    match &e.kind {
        ExprKind::Num(n) => n.point,
        ExprKind::Unary(_, a) => has_point(a),
        _ => false,
    }
}

/// The Siemens variable that holds a G68 word `l` of an expression: the value at the G68,
/// which its cancel turns back by whatever the FANUC variables hold then.
fn saved(l: u8) -> String {
    format!("NCTRANS_G68_{}", l as char)
}

/// Whether `e` reads a variable.
fn reads_var(e: &Expr) -> bool {
    matches!(e.kind, ExprKind::Var(_)) || e.children().into_iter().any(reads_var)
}

/// Whether `e` reads only user variables and numbers (a system variable read at the G68
/// may have another value where the translation saves it).
fn plain(e: &Expr) -> bool {
    let own = match &e.kind {
        ExprKind::Var(v) => {
            matches!(v.kind, VarKind::Hash(n) if (1..=33).contains(&n) || (100..=199).contains(&n) || (500..=999).contains(&n))
        }
        ExprKind::Num(_) | ExprKind::Unary(..) | ExprKind::Binary(..) | ExprKind::Func(..) => true,
        _ => false,
    };
    own && e.children().into_iter().all(plain)
}

/// The mode a G68, G51 or G51.1 block (`g`) sets, as constants in mm, degrees and factors
/// (a G68 also by expressions, as the variables that save them; `exprs` gets each with its
/// variable's name).
/// `at`: the program's modes and where the block starts (a G68 without a centre takes the
/// tool position there).
fn mode_of(
    ctx: &Ctx,
    items: &[Item],
    g: u32,
    (modal, lo): (&ModalScan, u32),
    saves: &mut Vec<(String, Expr)>,
) -> Result<Mode, &'static str> {
    let inch = modal.inch_at(lo);
    let mut centre: Vec<(u8, f64)> = Vec::new();
    let mut extra: Vec<(u8, f64)> = Vec::new();
    let mut exprs: Vec<(u8, Expr)> = Vec::new();
    for it in items {
        match letter_of(it) {
            Some((b'G', _)) if g_of(it) == Some(g) || matches!(g_of(it), Some(900 | 170 | 180 | 190)) => {}
            Some((l, e)) if g == 680 && b"XYZR".contains(&l) && literal(e).is_none() => {
                if !plain(e) {
                    return Err("a centre or angle that reads a system variable");
                }
                if reads_var(e) {
                    saves.push((saved(l), e.clone()));
                    exprs.push((l, named(&saved(l), e.span)));
                } else {
                    // A constant expression (`R[90./3]`) is the same at the cancel.
                    exprs.push((l, e.clone()));
                }
            }
            Some((l, e)) if b"XYZ".contains(&l) || (g == 680 && l == b'R') || (g == 510 && b"PIJK".contains(&l)) => {
                let Some(v) = literal(e) else { return Err("a centre or factor that is not a constant") };
                let v = if has_point(e) {
                    v
                } else if l == b'R' {
                    // An angle counts the metric increment in either unit.
                    scale(ctx.opts, v, false, true)
                } else if b"PIJK".contains(&l) {
                    // Scale factors without a point: 0.001 (parameter 5400#7 SCR = 0).
                    v * 0.001
                } else {
                    let Some(inch) = inch else {
                        return Err("a centre without a decimal point where the unit depends on the path taken");
                    };
                    scale(ctx.opts, v, inch, false)
                };
                if b"XYZ".contains(&l) {
                    centre.push((l, v));
                } else {
                    extra.push((l, v));
                }
            }
            _ => return Err("a frame G code with other words than its centre, its value and G90"),
        }
    }
    match g {
        680 => {
            let span = items.first().map_or(Span::default(), |it| it.span);
            let mut all: Vec<(u8, Expr)> = centre.iter().map(|&(l, v)| (l, num(v, span))).collect();
            all.extend(extra.iter().filter(|e| e.0 == b'R').map(|&(l, v)| (l, num(v, span))));
            all.extend(exprs);
            let Some(a) = all.iter().find(|e| e.0 == b'R').map(|e| e.1.clone()) else {
                return Err("G68 without R (the angle is then machine parameter 5410)");
            };
            let mut centre: Vec<(u8, Expr)> = all.into_iter().filter(|e| e.0 != b'R').collect();
            // No centre for an axis of the plane: the tool position at the G68 is the centre
            // (F-ROT1), FANUC's block end position (`#5001`.., `$P_EP`), saved for the
            // sequence and its cancel. Both read it in the local system the rotation turns
            // in: the G52 shift (its TRANS) or a caller's frame under it moves it as it moves
            // the tool (docs/semantics.md, "Rotation"). The plane must be known at the block
            // on every path (`planes`): its two axes are the centre's.
            if centre.len() < 2 {
                let at = modal.planes.before(lo);
                let Some(axes) = modal.planes.of_block(lo, items).and_then(plane_axes) else {
                    return Err("G68 without its centre where the plane (G17/G18/G19) depends on the path taken or on the caller (the tool position in the plane's two axes is then the centre)");
                };
                if centre.iter().any(|e| !axes.iter().any(|a| a.0 == e.0)) {
                    return Err("G68 with a centre word outside the plane's two axes");
                }
                // FANUC turns about the tool position as it is; the Sinumerik frame value
                // is rounded to the input increment: exact only for a position on that grid.
                let off = axes.iter().any(|a| !centre.iter().any(|e| e.0 == a.0) && at.grid & plane_bit(a.0) == 0);
                if off {
                    return Err("G68 without its centre where the tool may stand off the 0.001 grid (after a rotated, scaled or polar move, a reference return, G53, a probe move, an offset write, a change of G20/G21, or a call that may make one; FANUC turns about that exact position, a Sinumerik frame value is rounded to the increment)");
                }
                for (l, n) in axes {
                    if centre.iter().all(|e| e.0 != l) {
                        let at = Expr::new(ExprKind::Var(Box::new(VarRef { kind: VarKind::Hash(n), span })), span);
                        saves.push((saved(l), at));
                        centre.push((l, named(&saved(l), span)));
                    }
                }
            }
            centre.sort_by_key(|e| e.0);
            if centre.len() != 2 {
                return Err("G68 without its centre in both axes of the plane (the tool position is then the centre)");
            }
            Ok(Mode::Rotate(centre, a))
        }
        510 => {
            let p = extra.iter().find(|e| e.0 == b'P').map(|e| e.1);
            let mut axes = Vec::new();
            for &(l, c) in &centre {
                let own = extra.iter().find(|e| e.0 == b"IJK"[(l - b'X') as usize]).map(|e| e.1);
                match own.or(p) {
                    Some(f) if f != 0.0 => axes.push((l, c, f)),
                    _ => return Err("G51 without a factor (not 0) for an axis it scales"),
                }
            }
            if axes.is_empty() {
                return Err("G51 without the centre of the axes it scales");
            }
            Ok(Mode::Scale(axes))
        }
        _ => {
            if centre.is_empty() {
                return Err("G51.1 without an axis");
            }
            Ok(Mode::Mirror(centre))
        }
    }
}

/// The two axes of plane `g` (×10) with the FANUC variable of each one's block end position.
fn plane_axes(g: u32) -> Option<[(u8, u32); 2]> {
    match g {
        170 => Some([(b'X', 5001), (b'Y', 5002)]),
        180 => Some([(b'Z', 5003), (b'X', 5001)]),
        190 => Some([(b'Y', 5002), (b'Z', 5003)]),
        _ => None,
    }
}

fn plane_bit(l: u8) -> u8 {
    match l {
        b'X' => 1,
        b'Y' => 2,
        _ => 4,
    }
}

fn is_zero(e: &Expr) -> bool {
    literal(e) == Some(0.0)
}

/// `e`, or its negation (a number negated, an expression as `-(e)`).
fn signed(e: &Expr, sign: f64) -> Expr {
    match literal(e) {
        Some(v) => num(sign * v, e.span),
        None if sign < 0.0 => Expr::new(ExprKind::Unary(UnOp::Neg, Box::new(e.clone())), e.span),
        None => e.clone(),
    }
}

fn shift(centre: &[(u8, Expr)], sign: f64, span: Span) -> Vec<Word> {
    centre
        .iter()
        .filter(|c| !is_zero(&c.1))
        .map(|(l, v)| Word { addr: Addr::Letter(*l), value: WordValue::Expr(signed(v, sign)), span })
        .collect()
}

/// The instructions that set `mode` (`undo`: that take it back).
fn sequence(mode: &Mode, undo: bool, span: Span) -> Vec<Stmt> {
    let (centre, inner): (Vec<(u8, Expr)>, Stmt) = match mode {
        Mode::Rotate(c, a) => {
            let a = signed(a, if undo { -1.0 } else { 1.0 });
            let rpl = Word { addr: Addr::Name("RPL".into()), value: WordValue::Expr(a), span };
            (c.clone(), frame("AROT", vec![rpl], span))
        }
        Mode::Scale(axes) => {
            let words = axes
                .iter()
                .map(|&(l, _, f)| {
                    // The inverse as a number where it has a short decimal form (1/0.5 = 2).
                    let inv = 1.0 / f;
                    let short = (inv * 1e6).round() / 1e6 == inv;
                    let v = match (undo, short) {
                        (false, _) => num(f, span),
                        (true, true) => num(inv, span),
                        (true, false) => bin(BinOp::Div, num(1.0, span), num(f, span)),
                    };
                    Word { addr: Addr::Letter(l), value: WordValue::Expr(v), span }
                })
                .collect();
            (axes.iter().map(|&(l, c, _)| (l, num(c, span))).collect(), frame("ASCALE", words, span))
        }
        Mode::Mirror(c) => {
            // The value of a mirror word is not read; 0 as the manuals write it.
            let words =
                c.iter().map(|&(l, _)| Word { addr: Addr::Letter(l), value: WordValue::Expr(num(0.0, span)), span });
            (c.iter().map(|&(l, v)| (l, num(v, span))).collect(), frame("AMIRROR", words.collect(), span))
        }
    };
    let about_origin = centre.iter().all(|c| is_zero(&c.1));
    let mut out = Vec::new();
    if !about_origin {
        out.push(frame("ATRANS", shift(&centre, 1.0, span), span));
    }
    out.push(inner);
    if !about_origin {
        out.push(frame("ATRANS", shift(&centre, -1.0, span), span));
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

/// The instructions that undo the mode of key `k` in force (none where it is not the mode
/// `set` a cancel ends: FANUC then changes nothing), for the block `b`.
fn undo_known(
    ctx: &mut Ctx,
    modal: &ModalScan,
    k: u32,
    set: u32,
    b: &Block,
    span: Span,
) -> Result<Vec<Stmt>, Box<Out>> {
    let Some((lo, items)) = modal.g68_block(k) else {
        return Err(Box::new(refused(
            ctx,
            span,
            "a frame cancel where the mode in force is not known",
            "cancel in the main program",
        )));
    };
    if !g_codes(items).contains(&set) {
        // A cancel of another mode than the one in force: FANUC changes nothing.
        return Ok(Vec::new());
    }
    match mode_of(ctx, items, set, (modal, lo), &mut Vec::new()) {
        Ok(Mode::Mirror(c)) => {
            // G50.1 cancels the axes it names: exactly those G51.1 mirrored.
            let named: Vec<u8> =
                b.items.iter().filter_map(letter_of).map(|(l, _)| l).filter(|l| b"XYZ".contains(l)).collect();
            // Cancelling an axis that is not mirrored changes nothing; one left
            // mirrored would need a mirror of its own.
            if c.iter().any(|x| !named.contains(&x.0)) {
                return Err(Box::new(refused(
                    ctx,
                    span,
                    "G50.1 that cancels other axes than its G51.1 mirrored",
                    "cancel every mirrored axis in one G50.1: `G50.1 X0 Y0`",
                )));
            }
            Ok(sequence(&Mode::Mirror(c), true, span))
        }
        Ok(mode) => Ok(sequence(&mode, true, span)),
        Err(_) => {
            Err(Box::new(refused(ctx, span, "a cancel of a mode that is not translated", "see the mode's error")))
        }
    }
}

const SETS: [u32; 3] = [680, 510, 511];
const CANCELS: [u32; 3] = [690, 500, 501];

/// Translates a block with G68/G69, G51/G50 or G51.1/G50.1 (`gs`); `Err(b)` hands any
/// other block back.
pub fn split(ctx: &mut Ctx, b: Block, span: Span, modal: &ModalScan, gs: &[u32]) -> Result<Out, Block> {
    let codes: Vec<u32> = gs.iter().copied().filter(|g| SETS.contains(g) || CANCELS.contains(g)).collect();
    let Some(&g) = codes.first() else { return Err(b) };
    let first = b.items.first().map_or(span.lo, |it| it.span.lo);
    if codes.len() > 1 && codes.iter().all(|c| CANCELS.contains(c)) && modal.rot_before(first) == Some(0) {
        // The safety line `G00 G17 G40 G49 G50 G69 G80 G90` where no mode is in force: each
        // cancel changes nothing, so the block is what it is with its first cancel alone.
        let mut b = b;
        let mut kept = false;
        b.items.retain(|it| match g_of(it) {
            Some(c) if CANCELS.contains(&c) => {
                let keep = c == g && !kept;
                kept |= keep;
                keep
            }
            _ => true,
        });
        let rest: Vec<u32> = gs.iter().copied().filter(|c| !CANCELS.contains(c) || *c == g).collect();
        return split(ctx, b, span, modal, &rest);
    }
    if codes.len() > 1 {
        return Ok(refused(
            ctx,
            span,
            "two frame G codes (G68/G69, G51/G50, G51.1/G50.1) in one block",
            "write each in a block of its own",
        ));
    }
    let in_force = modal.rot_before(first);
    let empty_base = modal.frame_base_empty(span.lo);
    if SETS.contains(&g) {
        // A G68 in G68 mode replaces the rotation: the one in force goes first.
        let replaced = match in_force {
            Some(0) => Vec::new(),
            Some(k) if g == 680 && k & 3 == 1 && empty_base => vec![frame("TRANS", Vec::new(), span)],
            Some(k) if g == 680 && k != ROT_ANY && k & 3 == 1 => match undo_known(ctx, modal, k, g, &b, span) {
                Ok(undo) => undo,
                Err(out) => return Ok(*out),
            },
            Some(ROT_ANY) if g == 680 => {
                return Ok(refused(
                    ctx,
                    span,
                    "G68 where a G68 may be in force, which one depends on the path taken or on the call of the section, over a G52 shift or a caller's frame (Sinumerik can neither turn it back nor write the frame anew)",
                    "cancel the rotation (G69) before each G68, or clear the G52 shift (G52 X0 Y0 Z0) in the main program",
                ))
            }
            _ => {
                return Ok(refused(
                    ctx,
                    span,
                    "G68, G51 or G51.1 while another of them may be in force (in a called program: at a call of it, or it is not called in the job)",
                    "cancel each mode (G69, G50, G50.1) before the next, and before each call of a program that sets one",
                ))
            }
        };
        if modal.incremental_at(span.lo) != Some(false) || gs.contains(&910) {
            return Ok(refused(
                ctx,
                span,
                "G68, G51 or G51.1 where G91 may be in force (their centre reads incrementally)",
                "write it under G90: `G90 G68 X.. Y.. R..`",
            ));
        }
        let mut saves = Vec::new();
        return Ok(match mode_of(ctx, &b.items, g, (modal, span.lo), &mut saves) {
            Err(what) => {
                // The message names the G code first (a marked line under --unsupported warn).
                let label = match g {
                    680 => "G68",
                    510 => "G51",
                    _ => "G51.1",
                };
                let what = if what.starts_with('G') { what.to_string() } else { format!("{label}: {what}") };
                refused(ctx, span, &what, "write the mode with constants, alone in its block: `G68 X.. Y.. R..`")
            }
            Ok(mode) => {
                let mut meta = b.meta;
                meta.span = span;
                let mut after = Vec::new();
                // The block's modal words first (the plane a rotation is in), numbered as
                // the source block so that a jump to it runs the whole frame.
                let modes: Vec<Item> =
                    b.items.iter().filter(|it| matches!(g_of(it), Some(900 | 170 | 180 | 190))).cloned().collect();
                if !modes.is_empty() || meta.number.is_some() || meta.label.is_some() || !meta.comments.is_empty() {
                    after.push(block_stmt(meta, modes));
                }
                // The old rotation undone before the new one's values are saved (its
                // cancel may read the saved values of the G68 it replaces).
                after.extend(replaced);
                for (name, e) in saves {
                    let plan = &mut ctx.progs[ctx.cur];
                    if !plan.defs.iter().any(|d| d.0 == name) {
                        plan.defs.push((name.clone(), DataType::Real));
                    }
                    after.push(plain_block(vec![assign(named_ref(&name, e.span), e, span)], span));
                }
                after.extend(sequence(&mode, false, span));
                Out { before: Vec::new(), block: None, after }
            }
        });
    }
    // A cancel: undo the mode in force, if any.
    let set = SETS[CANCELS.iter().position(|&c| c == g).unwrap_or(0)];
    let undo = match in_force {
        Some(0) => Vec::new(),
        // Some rotation of the program or none; G50 and G50.1 cancel neither.
        Some(ROT_ANY) if g != 690 => Vec::new(),
        // The frame written anew: empty, which is what it was under the rotation.
        Some(ROT_ANY) if empty_base => vec![frame("TRANS", Vec::new(), span)],
        Some(ROT_ANY) => {
            return Ok(refused(
                ctx,
                span,
                "G69 where a G68 may be in force, which one depends on the path taken or on the call of the section, over a G52 shift or a caller's frame (Sinumerik can neither turn it back nor write the frame anew)",
                "cancel the rotation on each path in the block that follows its G68, or clear the G52 shift (G52 X0 Y0 Z0) in the main program",
            ))
        }
        Some(k) => match undo_known(ctx, modal, k, set, &b, span) {
            Ok(undo) => undo,
            Err(out) => return Ok(*out),
        },
        None => {
            return Ok(refused(
                ctx,
                span,
                "G69, G50 or G50.1 where the mode in force depends on the path taken, or follows a call of a program that may leave one in force, or in a called program some call of which is made in a mode (which one it cancels is not known here)",
                "cancel a mode in the program that set it, on a path where it is in force",
            ))
        }
    };
    let mut b = b;
    // G50.1's axis words name the axes cancelled: no motion.
    b.items.retain(|it| g_of(it) != Some(g) && !(g == 501 && letter_of(it).is_some_and(|(l, _)| b"XYZ".contains(&l))));
    let mut undo = undo;
    if !undo.is_empty() && (b.meta.number.is_some() || b.meta.label.is_some()) {
        // A jump to the block runs the cancel too: the number and label go first.
        let meta = BlockMeta { number: b.meta.number.take(), label: b.meta.label.take(), span, ..BlockMeta::default() };
        undo.insert(0, block_stmt(meta, Vec::new()));
    }
    let rest = if b.items.is_empty() && b.meta.number.is_none() && b.meta.comments.is_empty() && b.meta.label.is_none()
    {
        None
    } else {
        Some(b)
    };
    Ok(Out { before: undo, block: rest, after: Vec::new() })
}
