//! Sinumerik → FANUC: programmable rotation, scaling and mirroring (docs/translation.md,
//! "Coordinate systems").
//!
//! - `AROT RPL=a` (or `AROT Z a`) right after an absolute frame instruction (`TRANS X..`,
//!   or a bare `TRANS`/`ROT`/…, or at the start of a main program) → `G68 X0 Y0 R a`: a
//!   rotation about the origin of the shifted system, which is where FANUC rotates about
//!   `X0 Y0` under G52 (the TRANS before it becomes G52). Likewise `ASCALE X f Y g` →
//!   `G51 X0 Y0 I.. J..` (constant factors, written with a decimal point) and `AMIRROR X0`
//!   → `G51.1 X0`.
//! - `ROT RPL=a`, `SCALE ..`, `MIRROR ..` (which delete the TRANS) → the cancels, `G52 X0 Y0
//!   Z0 …`, then the FANUC mode as above.
//! - Every absolute frame instruction (`TRANS`, bare `ROT`, `SCALE`, `MIRROR`) of a program
//!   with one of these cancels them first: `G69`, `G50`, `G50.1 X0 Y0 Z0` (each only where
//!   the program uses it) before its `G52` (G52 in these modes is not modelled; a cancel of
//!   a mode not in force changes nothing). One mode at a time: FANUC applies mirror,
//!   scaling and rotation in that order whatever order they come in.
//!
//! "Right after": in the same statement list, with no block between them that a jump could
//! land on (a label or number one of the program's jumps names: `lower::landings`), no call
//! and no structure. A main program whose only plane
//! word is G18 (or G19), written in its leading blocks, rotates in that plane after it:
//! `G68 Z0 X0 R a` (`G68 Y0 Z0`), the angle `RPL=` or about the plane's normal (`ROT Y a`);
//! both controls turn counter-clockwise seen from the normal's positive end (Z towards X in
//! G18). A rotation where the plane is not known so, in a called program (its plane and
//! frame are the caller's), an `AROT` after another rotation, and spatial rotations are
//! refused (NC498).

use super::*;

/// What the program's rotations allow, found once before its blocks are translated.
#[derive(Clone, Debug, Default)]
pub struct Plan {
    /// The program has a ROT/AROT (bit 0), SCALE/ASCALE (bit 1), MIRROR/AMIRROR (bit 2)
    /// with values.
    pub any: u8,
    /// The program never selects G18/G19 and is a main program: G17 at every rotation
    /// (also what `frame_seq.rs` needs for its rotation sequences).
    pub g17: bool,
    /// The span starts of the AROT instructions that follow an absolute one.
    fresh: Vec<u32>,
    /// A main program whose only plane word is G18 (18) or G19 (19), first written in its
    /// leading blocks (before any label, number, jump, call or structure), so that plane is
    /// in force at every block after that first word (its span start).
    plane: Option<(u32, u32)>,
}

fn frame_of(b: &Block) -> Option<(&str, &[Word], Span)> {
    match b.items.as_slice() {
        [Item { kind: ItemKind::Frame { op, words }, span }] => Some((op.as_str(), words.as_slice(), *span)),
        _ => None,
    }
}

fn g_const(it: &Item) -> Option<f64> {
    match &it.kind {
        ItemKind::Word(Word { addr: Addr::Letter(b'G'), value: WordValue::Expr(e), .. }) => match &e.kind {
            ExprKind::Num(n) => Some(n.value),
            _ => None,
        },
        _ => None,
    }
}

fn scan(body: &[Stmt], start: bool, jumps: &crate::lower::landings::Landings, plan: &mut Plan) {
    let mut after_abs = start;
    for s in body {
        let StmtKind::Block(b) = &s.kind else {
            for child in crate::ir::visit::child_bodies(&s.kind) {
                scan(child, false, jumps, plan);
            }
            after_abs = false;
            continue;
        };
        if b.items.iter().any(|it| matches!(g_const(it), Some(v) if v == 18.0 || v == 19.0)) {
            plan.g17 = false;
        }
        if jumps.at(&b.meta) {
            after_abs = false;
        }
        match frame_of(b) {
            Some((op, words, span)) => {
                let rotates = kind(op).is_some() && !words.is_empty();
                plan.any |= kind(op).filter(|_| rotates).unwrap_or(0);
                if op.starts_with('A') && rotates && after_abs {
                    plan.fresh.push(span.lo);
                }
                after_abs = matches!(op, "TRANS" | "ROT" | "SCALE" | "MIRROR")
                    && !rotates
                    && (op == "TRANS" || words.is_empty());
            }
            None => {
                // A standard drilling cycle (a direct call or MCALL) leaves the frame as it is.
                let frame_call = |it: &Item| match &it.kind {
                    ItemKind::Call(c) => !matches!(&c.target, CallTarget::Name(n)
                        if crate::dialect::sinumerik::cycles::cycle_of(&n.to_ascii_uppercase()).is_some()),
                    _ => false,
                };
                if b.items.iter().any(frame_call) {
                    after_abs = false;
                }
            }
        }
    }
}

/// The mode bit of a frame instruction that turns, scales or mirrors ([`Plan::any`]).
fn kind(op: &str) -> Option<u8> {
    match op {
        "ROT" | "AROT" => Some(1),
        "SCALE" | "ASCALE" => Some(2),
        "MIRROR" | "AMIRROR" => Some(4),
        _ => None,
    }
}

/// The cancels of the FANUC modes `any` uses, in the order they must come (G69, G50, G50.1).
fn cancels(any: u8, span: Span) -> Vec<Stmt> {
    let mut out = Vec::new();
    if any & 1 != 0 {
        out.push(block_stmt(vec![g(69.0, span)], span));
    }
    if any & 2 != 0 {
        out.push(block_stmt(vec![g(50.0, span)], span));
    }
    if any & 4 != 0 {
        let zero = |l| letter(l, Expr::num(0.0, true, span), span);
        out.push(block_stmt(vec![g(50.1, span), zero(b'X'), zero(b'Y'), zero(b'Z')], span));
    }
    out
}

/// The FANUC block of a scaling or mirror instruction's words (constants; `Err`: why not).
fn scale_or_mirror(op: &str, words: &[Word], span: Span) -> Result<Vec<Item>, &'static str> {
    let mirror = op.ends_with("MIRROR");
    let mut items = vec![g(if mirror { 51.1 } else { 51.0 }, span)];
    let mut factors = Vec::new();
    for w in words {
        let Some(i) = b"XYZ".iter().position(|&c| w.addr.is(c)) else {
            return Err("a scaling or mirror of other axes than X, Y, Z");
        };
        items.push(letter(b"XYZ"[i], Expr::num(0.0, true, span), span));
        if !mirror {
            let f = match &w.value {
                WordValue::Expr(e) => crate::lower::literal(e),
                _ => None,
            };
            // Written with a decimal point, I J K are the factor itself (without one they
            // would count 0.001, parameter 5400#7 SCR = 0).
            match f {
                Some(k) if k != 0.0 => factors.push((b"IJK"[i], k)),
                _ => return Err("a scale factor that is not a constant (or is 0)"),
            }
        }
    }
    for (l, k) in factors {
        items.push(letter(l, Expr::num(k, true, span), span));
    }
    Ok(items)
}

/// The plan of a program (`main`: not a called one).
pub fn plan(body: &[Stmt], main: bool) -> Plan {
    let mut p = Plan { g17: main, ..Plan::default() };
    scan(body, main, &crate::lower::landings::Landings::of(body), &mut p);
    if main && !p.g17 {
        p.plane = single_plane(body);
    }
    p
}

/// [`Plan::plane`]: the one plane (18 or 19) of every plane word of `body`, and the start of
/// the first, where that one is in the leading blocks.
pub(super) fn single_plane(body: &[Stmt]) -> Option<(u32, u32)> {
    let mut planes = Vec::new();
    crate::ir::visit::walk_stmts(body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            for it in &b.items {
                if let Some(g) = g_const(it).filter(|g| matches!(g, 17.0 | 18.0 | 19.0)) {
                    planes.push(g as u32);
                }
            }
        }
    });
    let p = *planes.first()?;
    if p == 17 || planes.iter().any(|&q| q != p) {
        return None;
    }
    for s in body {
        let StmtKind::Block(b) = &s.kind else { return None };
        if b.meta.number.is_some() || b.meta.label.is_some() || b.meta.skip.is_some() {
            return None;
        }
        if let Some(it) = b.items.iter().find(|it| g_const(it) == Some(p as f64)) {
            return Some((p, it.span.lo));
        }
        if b.items.iter().any(|it| matches!(it.kind, ItemKind::Goto(_) | ItemKind::Call(_) | ItemKind::Case(_))) {
            return None;
        }
    }
    None
}

fn g(v: f64, span: Span) -> Item {
    item(ItemKind::Word(Word { addr: Addr::Letter(b'G'), value: WordValue::Expr(num(v, span)), span }), span)
}

fn letter(l: u8, v: Expr, span: Span) -> Item {
    item(ItemKind::Word(Word { addr: Addr::Letter(l), value: WordValue::Expr(v), span }), span)
}

fn refuse(ctx: &mut Ctx, span: Span, what: &str, hint: &str) -> Vec<Stmt> {
    ctx.unsupported("NC498", span, what, hint).into_iter().collect()
}

/// The angle of a `ROT`/`AROT` in the plane: `RPL=a`, or about the axis `normal` to it
/// (`Z a` in G17).
fn angle(words: &[Word], normal: u8) -> Option<Expr> {
    match words {
        [w] if matches!(&w.addr, Addr::Name(n) if n.as_ref() == "RPL") || w.addr.is(normal) => match &w.value {
            WordValue::Expr(e) => Some(e.clone()),
            _ => None,
        },
        _ => None,
    }
}

/// Translates a frame block this module owns (`Some`: the statements it became), and puts a
/// `G69` into `out` before an absolute frame instruction of a program that rotates.
pub fn block(
    ctx: &mut Ctx,
    b: &mut Block,
    plan: &Plan,
    abs: Option<bool>,
    axes: u16,
    out: &mut Vec<Stmt>,
) -> Option<Vec<Stmt>> {
    let (op, words, fspan) = frame_of(b)?;
    let absolute = matches!(op, "TRANS" | "ROT" | "SCALE" | "MIRROR");
    let rotates = kind(op).is_some() && !words.is_empty();
    if !rotates {
        if absolute {
            out.extend(cancels(plan.any, fspan));
        }
        if absolute && words.is_empty() && op != "TRANS" {
            // A bare ROT/SCALE/MIRROR deletes the whole frame, as a bare TRANS: G52 X0 Y0 Z0.
            if let Some(ItemKind::Frame { op, .. }) = b.items.first_mut().map(|it| &mut it.kind) {
                *op = "TRANS".into();
            }
        }
        return None;
    }
    // The plane of the rotation: G17, or the one plane of the program after its first word.
    // (Scaling and mirroring do not depend on it.)
    let rot = matches!(op, "ROT" | "AROT");
    let plane = match plan.plane.filter(|&(_, lo)| fspan.lo > lo) {
        _ if plan.g17 || !rot => 17,
        Some((p, _)) => p,
        None => return Some(refuse(
            ctx,
            fspan,
            "a rotation in a called program, or in one whose plane (G17/G18/G19) at the rotation is not known from its leading blocks (FANUC G68 rotates in the plane of the block)",
            "rotate in the main program, in the one plane it selects first (G17, or G18/G19 in its first blocks)",
        )),
    };
    // The plane's two axes (G17 X Y, G18 Z X, G19 Y Z) and its normal.
    let (u, v, normal) = match plane {
        18 => (b'Z', b'X', b'Y'),
        19 => (b'Y', b'Z', b'X'),
        _ => (b'X', b'Y', b'Z'),
    };
    let mode = if matches!(op, "ROT" | "AROT") {
        let Some(a) = angle(words, normal) else {
            return Some(refuse(
                ctx,
                fspan,
                "a rotation in space (about X or Y, or about several axes)",
                "rotate in the plane: `ROT RPL=30`",
            ));
        };
        vec![
            g(68.0, fspan),
            letter(u, Expr::num(0.0, true, fspan), fspan),
            letter(v, Expr::num(0.0, true, fspan), fspan),
            letter(b'R', a, fspan),
        ]
    } else {
        match scale_or_mirror(op, words, fspan) {
            Ok(items) => items,
            Err(what) => return Some(refuse(ctx, fspan, what, "scale by constant factors: `SCALE X2 Y2`")),
        }
    };
    let mut stmts = Vec::new();
    if absolute {
        if abs != Some(true) {
            return Some(refuse(
                ctx,
                fspan,
                "ROT where G91 may be in force (its G52 would be read incrementally)",
                "select G90 before the ROT",
            ));
        }
        stmts.extend(cancels(plan.any, fspan));
        let mut g52 = vec![g(52.0, fspan)];
        for (i, &l) in b"XYZABCUVW".iter().enumerate() {
            if axes & (1 << i) != 0 {
                g52.push(letter(l, Expr::num(0.0, true, fspan), fspan));
            }
        }
        stmts.push(block_stmt(g52, fspan));
    } else if !plan.fresh.contains(&fspan.lo) {
        return Some(refuse(
            ctx,
            fspan,
            "AROT, ASCALE or AMIRROR that may add to another rotation, scaling or mirror (FANUC applies them in its own order, and G68 replaces the rotation in force)",
            "program the frame absolute before it: `TRANS X.. Y..` then `AROT RPL=..`",
        ));
    }
    let meta = std::mem::take(&mut b.meta);
    let rot = mode;
    if stmts.is_empty() {
        stmts.push(meta_stmt(meta, rot));
    } else {
        // The first block keeps the number and label: a jump to it runs the whole frame.
        if let Some(Stmt { kind: StmtKind::Block(first), .. }) = stmts.first_mut() {
            let items = std::mem::take(&mut first.items);
            first.meta = meta;
            first.items = items;
        }
        stmts.push(block_stmt(rot, fspan));
    }
    Some(stmts)
}
