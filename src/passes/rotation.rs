//! Sinumerik → FANUC: programmable rotation (docs/translation.md, "Coordinate systems").
//!
//! - `AROT RPL=a` (or `AROT Z a`) right after an absolute frame instruction (`TRANS X..`,
//!   or a bare `TRANS`/`ROT`/…, or at the start of a main program) → `G68 X0 Y0 R a`: a
//!   rotation about the origin of the shifted system, which is where FANUC rotates about
//!   `X0 Y0` under G52 (the TRANS before it becomes G52).
//! - `ROT RPL=a` (which deletes the TRANS) → `G69`, `G52 X0 Y0 Z0 …` where the program has
//!   a TRANS, then `G68 X0 Y0 R a`.
//! - Every absolute frame instruction (`TRANS`, bare `ROT`, `SCALE`, `MIRROR`) of a program
//!   with a rotation cancels it first: `G69` before its `G52` (G52 in G68 mode is not
//!   modelled; G69 without a rotation changes nothing).
//!
//! "Right after": in the same statement list, with no block between them that a jump could
//! land on (a number or a label), no call and no structure. A rotation in a program that
//! selects G18/G19, or in a called program (its plane and frame are the caller's), an
//! `AROT` after another rotation, and spatial rotations are refused (NC498).

use super::*;

/// What the program's rotations allow, found once before its blocks are translated.
#[derive(Clone, Debug, Default)]
pub struct Plan {
    /// The program has a ROT/AROT with values.
    pub any: bool,
    /// The program never selects G18/G19 and is a main program: G17 at every rotation.
    pub g17: bool,
    /// The span starts of the AROT instructions that follow an absolute one.
    fresh: Vec<u32>,
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

fn scan(body: &[Stmt], start: bool, plan: &mut Plan) {
    let mut after_abs = start;
    for s in body {
        let StmtKind::Block(b) = &s.kind else {
            for child in crate::ir::visit::child_bodies(&s.kind) {
                scan(child, false, plan);
            }
            after_abs = false;
            continue;
        };
        if b.items.iter().any(|it| matches!(g_const(it), Some(v) if v == 18.0 || v == 19.0)) {
            plan.g17 = false;
        }
        if b.meta.number.is_some() || b.meta.label.is_some() {
            after_abs = false;
        }
        match frame_of(b) {
            Some((op, words, span)) => {
                let rotates = matches!(op, "ROT" | "AROT") && !words.is_empty();
                plan.any |= rotates;
                if op == "AROT" && after_abs {
                    plan.fresh.push(span.lo);
                }
                after_abs = matches!(op, "TRANS" | "ROT" | "SCALE" | "MIRROR") && !rotates
                    && (op == "TRANS" || words.is_empty());
            }
            None => {
                if b.items.iter().any(|it| matches!(it.kind, ItemKind::Call(_))) {
                    after_abs = false;
                }
            }
        }
    }
}

/// The plan of a program (`main`: not a called one).
pub fn plan(body: &[Stmt], main: bool) -> Plan {
    let mut p = Plan { g17: main, ..Plan::default() };
    scan(body, main, &mut p);
    p
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

/// The angle of a `ROT`/`AROT` in the plane: `RPL=a`, or `Z a` (about the axis normal to
/// G17).
fn angle(words: &[Word]) -> Option<Expr> {
    match words {
        [w] if matches!(&w.addr, Addr::Name(n) if n.as_ref() == "RPL") || w.addr.is(b'Z') => match &w.value {
            WordValue::Expr(e) => Some(e.clone()),
            _ => None,
        },
        _ => None,
    }
}

/// Translates a frame block this module owns (`Some`: the statements it became), and puts a
/// `G69` into `out` before an absolute frame instruction of a program that rotates.
pub fn block(ctx: &mut Ctx, b: &mut Block, plan: &Plan, abs: Option<bool>, axes: u16, out: &mut Vec<Stmt>) -> Option<Vec<Stmt>> {
    let (op, words, fspan) = frame_of(b)?;
    let absolute = matches!(op, "TRANS" | "ROT" | "SCALE" | "MIRROR");
    let rotates = matches!(op, "ROT" | "AROT") && !words.is_empty();
    if !rotates {
        if absolute && plan.any {
            out.push(block_stmt(vec![g(69.0, fspan)], fspan));
        }
        if absolute && words.is_empty() && op != "TRANS" {
            // A bare ROT/SCALE/MIRROR deletes the whole frame, as a bare TRANS: G52 X0 Y0 Z0.
            if let Some(ItemKind::Frame { op, .. }) = b.items.first_mut().map(|it| &mut it.kind) {
                *op = "TRANS".into();
            }
        }
        return None;
    }
    if !plan.g17 {
        return Some(refuse(
            ctx,
            fspan,
            "a rotation in a called program or in one that selects G18/G19 (FANUC G68 rotates in the plane of the block, which is not known here)",
            "rotate in the main program, in G17",
        ));
    }
    let Some(a) = angle(words) else {
        return Some(refuse(
            ctx,
            fspan,
            "a rotation in space (about X or Y, or about several axes)",
            "rotate in the plane: `ROT RPL=30`",
        ));
    };
    let mut stmts = Vec::new();
    if op == "ROT" {
        if abs != Some(true) {
            return Some(refuse(
                ctx,
                fspan,
                "ROT where G91 may be in force (its G52 would be read incrementally)",
                "select G90 before the ROT",
            ));
        }
        stmts.push(block_stmt(vec![g(69.0, fspan)], fspan));
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
            "AROT that may add to another rotation (FANUC G68 replaces the rotation in force)",
            "program the frame absolute before it: `TRANS X.. Y..` then `AROT RPL=..`",
        ));
    }
    let meta = std::mem::take(&mut b.meta);
    let rot = vec![
        g(68.0, fspan),
        letter(b'X', Expr::num(0.0, true, fspan), fspan),
        letter(b'Y', Expr::num(0.0, true, fspan), fspan),
        letter(b'R', a, fspan),
    ];
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
