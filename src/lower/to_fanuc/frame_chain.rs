//! Sinumerik → FANUC: a programmable frame chained from TRANS, ATRANS, ROT and AROT in the
//! plane G17, followed in macro variables (docs/translation.md, "Coordinate systems").
//!
//! Each additive instruction acts in the coordinate system the ones before made: an
//! `ATRANS X5` after `AROT RPL=30` shifts along the turned X. FANUC's G52 shifts the
//! unrotated local system and G68 turns about a point of it, so the translation keeps the
//! frame as its origin in the unrotated system (one variable per axis, as `frames.rs` does
//! for a plain ATRANS) and its angle (one more), and writes the whole frame again after each
//! change:
//!
//! - `TRANS X a Y b` → the shifts a, b (0 for the unnamed axes), the angle 0, `G69`,
//!   `G52 X a Y b Z0`; `ROT RPL=r` → the shifts 0, the angle r, `G69`, `G52 X0 Y0 Z0`,
//!   `G68 X0 Y0 R#a`; bare `TRANS`/`ROT` → the shifts and the angle 0, `G69`, `G52` of 0.
//! - `AROT RPL=r` → the angle raised by r, `G68 X0 Y0 R#a` (about the origin of the shifted
//!   system: G52 moves the centre of G68; a G68 in G68 mode replaces the rotation).
//! - `ATRANS X dx Y dy Z dz` → the shift of X raised by `dx·cos a − dy·sin a`, of Y by
//!   `dx·sin a + dy·cos a`, of Z by dz (a rotation in G17 leaves Z), then `G69`, `G52` from
//!   the variables, `G68 X0 Y0 R#a` (FANUC's G52 under G68 is not modelled: the rotation is
//!   cancelled around it). The increments are worked out here from the angle in force,
//!   which must be one constant on every path (`walk`): at a quarter turn they are ±dx,
//!   ±dy (any expressions); at another angle only constants whose turned value G52 holds
//!   (it rounds its words to the 0.001 input increment, the Siemens frame does not).
//!
//! Where no rotation can be in force (a main program's blocks before its first ROT/AROT
//! after the last TRANS, no jump target between) the G69/G68 are left out and the ATRANS
//! adds plainly. Only where the program's frame instructions are these four, in G17 (a
//! called program writes G17 itself in its leading blocks), the first of them an absolute
//! TRANS or ROT in the leading blocks (so the caller's frame does not matter: every
//! instruction after it builds on one the program set), without incremental moves, not in
//! a SAVE subprogram, and every subprogram it calls leaves the frame alone; elsewhere an
//! ATRANS is refused (NC577) with the reason.

use super::frames::{g, letter, point};
use super::*;

/// What the chain analysis found for one program.
#[derive(Clone, Debug, Default)]
pub struct Chain {
    /// The program's frame is followed here (every frame block is this module's).
    pub on: bool,
    /// The program has an additive ATRANS and a rotation but its frame cannot be followed:
    /// why (each ATRANS is refused with it).
    pub refuse: Option<&'static str>,
    /// The frame's state before each frame block, by the start of its span.
    at: BTreeMap<u32, St>,
}

/// The temporary holding the angle of the chained rotation.
fn angle_var(span: Span) -> VarRef {
    VarRef { kind: VarKind::Named { name: format!("{TEMP_PREFIX}ROT_ANGLE"), indices: vec![] }, span }
}

/// The rotation angle of a `ROT`/`AROT` in G17: `RPL=a` or `Z a` alone.
fn angle(words: &[Word]) -> Option<&Expr> {
    match words {
        [w] if matches!(&w.addr, Addr::Name(n) if n.as_ref() == "RPL") || w.addr.is(b'Z') => match &w.value {
            WordValue::Expr(e) => Some(e),
            _ => None,
        },
        _ => None,
    }
}

fn frame_of(b: &Block) -> Option<(&str, &[Word], Span)> {
    match b.items.as_slice() {
        [Item { kind: ItemKind::Frame { op, words }, span }] => Some((op.as_str(), words.as_slice(), *span)),
        _ => None,
    }
}

fn g_is(it: &Item, v: f64) -> bool {
    matches!(&it.kind, ItemKind::Word(Word { addr: Addr::Letter(b'G'), value: WordValue::Expr(Expr { kind: ExprKind::Num(n), .. }), .. }) if n.value == v)
}

/// The chain analysis of `body` (`main`: not a called program; `axes`: `frames::trans_axes`).
/// `seqs`: the program's sequences about a centre (`frame_seq`), whose ATRANS blocks need
/// no chain (where the program has no other ATRANS, they keep their translation).
pub fn plan(
    body: &[Stmt],
    main: bool,
    axes: u16,
    callees: &BTreeMap<String, Callee>,
    seqs: &super::frame_seq::Seqs,
    save: bool,
) -> Chain {
    let mut additive = false;
    let mut rotation = false;
    let mut calls_frames = false;
    let mut why: Option<&'static str> = None;
    let mut note = |w: &'static str| {
        why.get_or_insert(w);
    };
    crate::ir::visit::walk_stmts(body, &mut |s| {
        let StmtKind::Block(b) = &s.kind else { return };
        for it in &b.items {
            if g_is(it, 18.0) || g_is(it, 19.0) {
                note("in a program that selects G18 or G19 (the chained rotation is followed in G17 only)");
            }
            match &it.kind {
                ItemKind::Frame { op, words } => {
                    if b.items.len() != 1 {
                        note("with a frame instruction sharing its block with other words");
                    }
                    match op.as_str() {
                        "ATRANS" if super::frames::g92_words(words).is_none() => {
                            additive |= !seqs.takes(it.span.lo);
                        }
                        "ATRANS" => note("with the G92 form ATRANS X=$P_EP[X]-v in the program"),
                        "TRANS" => {}
                        "ROT" if words.is_empty() => {}
                        "AROT" if words.is_empty() => note("with an AROT without an angle"),
                        "ROT" | "AROT" => {
                            rotation = true;
                            if angle(words).is_none() {
                                note("with a rotation in space (about X or Y, or about several axes)");
                            }
                        }
                        _ => note("with SCALE, MIRROR (or their additive forms) in the program: a scaled or mirrored ATRANS shift is not followed"),
                    }
                    if b.meta.skip.is_some() {
                        note("with a frame instruction in a skippable block (/)");
                    }
                }
                ItemKind::Call(c) => {
                    let frames = match &c.target {
                        CallTarget::Name(n) => {
                            let n = n.to_ascii_uppercase();
                            match callees.get(&n) {
                                Some(c) => c.effect.frames,
                                None => crate::dialect::sinumerik::cycles::cycle_of(&n).is_none(),
                            }
                        }
                        _ => true,
                    };
                    if frames {
                        calls_frames = true;
                        note("in a program calling a subprogram that has frame instructions (or is not among those translated): the frame it leaves is not followed");
                    }
                }
                _ => {}
            }
        }
    });
    // Without a rotation the plain ATRANS of `frames.rs` does (it needs no angle), except in
    // a SAVE subprogram or beside a call that may change the frame, refused below.
    if !additive || !(rotation || save || calls_frames) {
        return Chain::default();
    }
    if save {
        note("in a PROC … SAVE subprogram: Siemens reactivates the caller's programmable frame at its end, the FANUC translation restores the modal groups only, not G52 and G68");
    }
    if axes & (1 << 15) != 0 {
        note("in a program with incremental moves (G91, IC()): after a frame change the controls travel an increment differently");
    }
    // The leading blocks: a G17 (a called program's plane is its caller's) and the first
    // frame instruction, absolute, before any jump, label, call or structure.
    let mut g17 = main;
    let mut lead = false;
    for s in body {
        let StmtKind::Block(b) = &s.kind else { break };
        if b.meta.label.is_some()
            || b.items.iter().any(|it| {
                matches!(
                    it.kind,
                    ItemKind::Goto(_)
                        | ItemKind::IfThen { .. }
                        | ItemKind::Call(_)
                        | ItemKind::Case(_)
                        | ItemKind::RepeatSection(_)
                )
            })
        {
            break;
        }
        g17 |= b.items.iter().any(|it| g_is(it, 17.0));
        if let Some((op, words, _)) = frame_of(b) {
            lead = op == "TRANS" || (op == "ROT" && (words.is_empty() || angle(words).is_some()));
            break;
        }
    }
    if !lead {
        note(if main {
            "where the program's first frame instruction is not a TRANS or ROT in its leading blocks (before any jump, label, call or structure)"
        } else {
            "in a called program that does not set its own frame first (a TRANS or ROT in its leading blocks): it adds to the frame its caller left, which the translation does not follow into called programs"
        });
    }
    if !g17 {
        note("in a called program that does not select G17 in its leading blocks (its plane is the caller's)");
    }
    if let Some(w) = why {
        return Chain { refuse: Some(w), ..Chain::default() };
    }
    let jumps = crate::lower::landings::Landings::of(body);
    let mut chain = Chain { on: true, ..Chain::default() };
    // A called program may start under its caller's G68 (its first TRANS or ROT cancels it).
    let start = if main { St { angle: Some(0.0), g68: false } } else { St::UNKNOWN };
    walk(body, start, &jumps, &mut chain.at);
    chain
}

/// The frame's state before a block: the angle in force where it is the same on every path
/// (a constant), and whether G68 may be in force.
#[derive(Clone, Copy, Debug, PartialEq)]
struct St {
    angle: Option<f64>,
    g68: bool,
}

impl St {
    const UNKNOWN: St = St { angle: None, g68: true };

    fn merge(self, o: St) -> St {
        St { angle: self.angle.filter(|a| o.angle == Some(*a)), g68: self.g68 || o.g68 }
    }
}

/// The state after `body` from `s`, noting the state before each frame block in `at`.
fn walk(body: &[Stmt], mut s: St, jumps: &crate::lower::landings::Landings, at: &mut BTreeMap<u32, St>) -> St {
    for st in body {
        match &st.kind {
            StmtKind::Block(b) => {
                if jumps.at(&b.meta) {
                    s = St::UNKNOWN; // a jump may land here from anywhere
                }
                let Some((op, words, span)) = frame_of(b) else { continue };
                at.insert(span.lo, s);
                let r = angle(words).and_then(crate::lower::literal);
                s = match op {
                    "TRANS" => St { angle: Some(0.0), g68: false },
                    "ROT" if words.is_empty() => St { angle: Some(0.0), g68: false },
                    "ROT" => St { angle: r, g68: true },
                    "AROT" => St { angle: s.angle.zip(r).map(|(a, r)| a + r), g68: true },
                    _ => s,
                };
            }
            StmtKind::If(i) => {
                let t = walk(&i.then_body, s, jumps, at);
                let e = match &i.else_part {
                    Some(e) => walk(&e.body, s, jumps, at),
                    None => s,
                };
                s = t.merge(e);
            }
            kind => {
                // A loop: its head holds what every pass brings, found by passes over the
                // body until the state stays (the angle becomes unknown at the first change).
                let bodies = crate::ir::visit::child_bodies(kind);
                for _ in 0..4 {
                    let mut scratch = BTreeMap::new();
                    let after = bodies.iter().fold(s, |x, b| walk(b, x, jumps, &mut scratch));
                    let merged = s.merge(after);
                    if merged == s {
                        break;
                    }
                    s = merged;
                }
                for b in &bodies {
                    walk(b, s, jumps, at);
                }
            }
        }
    }
    s
}

/// The cosine and sine of `deg`, exact at the quarter turns.
fn cos_sin(deg: f64) -> (f64, f64) {
    let (s, c) = deg.to_radians().sin_cos();
    let snap = |x: f64| [-1.0, 0.0, 1.0].into_iter().find(|k| (x - k).abs() < 1e-12).unwrap_or(x);
    (snap(c), snap(s))
}

/// The increments of the X and Y shifts (unrotated) of an `ATRANS X dx Y dy` in state `st`.
/// At a quarter turn they are ±dx, ±dy (any expressions); at another angle only constants
/// whose turned shift FANUC's G52 holds exactly (a multiple of its 0.001 input increment:
/// G52 rounds its words to it, Siemens keeps the exact value); `Err`: why not.
fn increments(dx: Option<Expr>, dy: Option<Expr>, st: St, span: Span) -> Result<(Option<Expr>, Option<Expr>), String> {
    if !st.g68 || (dx.is_none() && dy.is_none()) {
        return Ok((dx, dy));
    }
    let Some(a) = st.angle else {
        return Err("under a rotation whose angle is not known at translation (it changes in a loop, depends on a variable, or differs between the paths taken): the shift along the turned axes is not a value FANUC's G52 is known to hold".into());
    };
    let (c, s) = cos_sin(a);
    let quarter = [c, s].iter().all(|x| [-1.0, 0.0, 1.0].contains(x));
    if quarter {
        // c·p + k·q with c, k in {-1, 0, 1}.
        let comb = |p: &Option<Expr>, cp: f64, q: &Option<Expr>, cq: f64| {
            let terms: Vec<(bool, Expr)> = [(p, cp), (q, cq)]
                .into_iter()
                .filter(|(e, k)| e.is_some() && *k != 0.0)
                .filter_map(|(e, k)| e.clone().map(|e| (k > 0.0, e)))
                .collect();
            let first = terms.iter().position(|t| t.0)?;
            let mut sum = terms[first].1.clone();
            for (i, (plus, e)) in terms.iter().enumerate() {
                if i != first {
                    sum = bin(if *plus { BinOp::Add } else { BinOp::Sub }, sum, e.clone());
                }
            }
            Some(sum)
        };
        let comb = |p: &Option<Expr>, cp: f64, q: &Option<Expr>, cq: f64| {
            // All terms negative: the negated sum.
            comb(p, cp, q, cq).or_else(|| comb(p, -cp, q, -cq).map(|e| neg(e, span)))
        };
        return Ok((comb(&dx, c, &dy, -s), comb(&dx, s, &dy, c)));
    }
    let lit = |e: &Option<Expr>| e.as_ref().map_or(Some(0.0), crate::lower::literal);
    let (Some(x), Some(y)) = (lit(&dx), lit(&dy)) else {
        return Err(format!("with a shift that is not a constant under a rotation of {a}° (not a quarter turn): whether FANUC's G52 holds the turned shift exactly is not known at translation"));
    };
    let (u, v) = (c * x - s * y, s * x + c * y);
    let held = |w: f64| ((w * 1000.0).round() - w * 1000.0).abs() < 1e-6;
    if !(held(u) && held(v)) {
        return Err(format!(
            "under a rotation of {a}°: the shift along the turned axes is X{u:.6} Y{v:.6} in the unrotated system, which FANUC's G52 rounds to its 0.001 input increment"
        ));
    }
    let r = |w: f64| (w * 1000.0).round() / 1000.0;
    Ok((Some(point(r(u), span)), Some(point(r(v), span))))
}

/// `v + d`, written `v - e` where d is `-e` (a negative constant too).
fn add(v: Expr, d: Expr) -> Expr {
    match d.kind {
        ExprKind::Unary(UnOp::Neg, e) => bin(BinOp::Sub, v, *e),
        ExprKind::Num(n) if n.value < 0.0 => bin(BinOp::Sub, v, Expr::num(-n.value, true, d.span)),
        kind => bin(BinOp::Add, v, Expr { kind, span: d.span }),
    }
}

fn neg(e: Expr, span: Span) -> Expr {
    Expr::new(ExprKind::Unary(UnOp::Neg, Box::new(e)), span)
}

fn set(var: &VarRef, v: Expr, span: Span) -> Stmt {
    block_stmt(vec![assign_item(var, v, span)], span)
}

fn refuse(ctx: &mut Ctx, span: Span, why: &str) -> Vec<Stmt> {
    let what = format!("ATRANS (adds to the programmable frame) {why}");
    let hint = "in G17 and G90, set the frame with TRANS or ROT first in the program's leading blocks, then AROT RPL= by constants and ATRANS (under a turn other than a quarter one only shifts FANUC's G52 holds); no SCALE or MIRROR, no frames in the subprograms it calls";
    ctx.unsupported("NC577", span, &what, hint).into_iter().collect()
}

/// The FANUC statements of a frame block of a program whose frame is followed ([`Chain::on`]),
/// or the refusal of an ATRANS where it cannot be ([`Chain::refuse`]); `None`: not one.
pub fn block(ctx: &mut Ctx, b: &mut Block, chain: &Chain, abs: Option<bool>, axes: u16) -> Option<Vec<Stmt>> {
    let (op, words, fspan) = frame_of(b)?;
    if let Some(why) = chain.refuse {
        let additive = op == "ATRANS" && super::frames::g92_words(words).is_none();
        return additive.then(|| refuse(ctx, fspan, why));
    }
    if !chain.on {
        return None;
    }
    if abs != Some(true) {
        let what = format!(
            "{op} of a chained frame (TRANS, ROT, AROT, ATRANS followed in variables) where G90 is not known to be in force (FANUC reads G52 under G91 as incremental)"
        );
        return Some(
            ctx.unsupported("NC577", fspan, &what, "select G90 before the frame instructions").into_iter().collect(),
        );
    }
    if let Some(w) = words.iter().find(|w| {
        !matches!(w.value, WordValue::Expr(_))
            || (op.ends_with("TRANS") && !matches!(w.addr, Addr::Letter(l) if b"XYZABCUVW".contains(&l)))
    }) {
        let what = format!("{op} with a word that is not a plain axis value");
        return Some(
            ctx.unsupported("NC577", w.span, &what, "write the shift or angle as a plain value").into_iter().collect(),
        );
    }
    let span = fspan;
    let st = chain.at.get(&fspan.lo).copied().unwrap_or(St::UNKNOWN);
    let rotated = st.g68;
    let a = angle_var(span);
    let shift = |l: u8| super::frames::shift_var(l, span);
    let axis_letters: Vec<u8> =
        b"XYZABCUVW".iter().enumerate().filter(|(i, _)| axes & (1 << i) != 0).map(|(_, &l)| l).collect();
    let value = |l: u8| {
        words.iter().rev().find(|w| w.addr.is(l)).and_then(|w| match &w.value {
            WordValue::Expr(e) => Some(e.clone()),
            _ => None,
        })
    };
    let mut out = Vec::new();
    let g52_of_vars = |span: Span| {
        let mut items = vec![g(52.0, span)];
        items.extend(axis_letters.iter().map(|&l| letter(l, var_expr(&shift(l)), span)));
        items
    };
    let g68 = |span: Span| {
        vec![
            g(68.0, span),
            letter(b'X', point(0.0, span), span),
            letter(b'Y', point(0.0, span), span),
            letter(b'R', var_expr(&a), span),
        ]
    };
    let mut items: Vec<Vec<Item>> = Vec::new();
    match op {
        "TRANS" | "ROT" => {
            let r = if op == "ROT" { angle(words).cloned() } else { None };
            let mut g52 = vec![g(52.0, span)];
            for &l in &axis_letters {
                let v = if op == "TRANS" { value(l).unwrap_or_else(|| point(0.0, span)) } else { point(0.0, span) };
                out.push(set(&shift(l), v.clone(), span));
                g52.push(letter(l, v, span));
            }
            out.push(set(&a, r.clone().unwrap_or_else(|| point(0.0, span)), span));
            if rotated {
                items.push(vec![g(69.0, span)]);
            }
            items.push(g52);
            if r.is_some() {
                items.push(g68(span));
            }
        }
        "AROT" => {
            let r = angle(words)?.clone();
            // A sum known here is written as its value, within G68's -360..360 (the same
            // rotation); else the variable adds at run time.
            // (By remainder, not by steps of 360: a huge literal angle would never end.)
            let known =
                st.angle.zip(crate::lower::literal(&r)).map(|(x, r)| x + r).filter(|v| v.is_finite()).map(|v| {
                    match v % 360.0 {
                        _ if v.abs() <= 360.0 => v,
                        0.0 => 360.0 * v.signum(),
                        rest => rest,
                    }
                });
            out.push(set(&a, known.map_or_else(|| add(var_expr(&a), r), |v| point(v, span)), span));
            items.push(g68(span));
        }
        _ => {
            // ATRANS: the shift along the turned X and Y, in the unrotated system.
            let incs = match increments(value(b'X'), value(b'Y'), st, span) {
                Ok(v) => v,
                Err(why) => return Some(refuse(ctx, fspan, &why)),
            };
            for &l in &axis_letters {
                let inc = match l {
                    b'X' => incs.0.clone(),
                    b'Y' => incs.1.clone(),
                    _ => value(l),
                };
                if let Some(d) = inc {
                    out.push(set(&shift(l), add(var_expr(&shift(l)), d), span));
                }
            }
            if rotated {
                items.push(vec![g(69.0, span)]);
            }
            items.push(g52_of_vars(span));
            if rotated {
                items.push(g68(span));
            }
        }
    }
    // The first statement keeps the block's number, label and comments: a jump to it runs
    // the whole frame change.
    let meta = std::mem::take(&mut b.meta);
    let mut rest = items.into_iter().map(|it| block_stmt(it, span));
    out.extend(rest.by_ref());
    if let Some(Stmt { kind: StmtKind::Block(first), .. }) = out.first_mut() {
        first.meta = meta;
    }
    Some(out)
}
