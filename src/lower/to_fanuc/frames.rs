//! Sinumerik → FANUC: programmable translation, machine coordinates, settable offsets past
//! G57 and reference-point approach (docs/translation.md, "Coordinate systems").
//!
//! - `TRANS X.. Y..` → `G52` naming X, Y, Z and every other axis any TRANS of the program
//!   names, the unnamed ones 0: TRANS replaces the whole programmable frame, G52 only the
//!   axes it names. Bare `TRANS` → `G52 X0 Y0 Z0`. Under G91 (or where it may be in force)
//!   written `G90 G52 ..` and the mode selected again after it: FANUC reads G52 under G91 as
//!   incremental. Incremental moves after it: `frames_incr.rs`. `ATRANS` adds to the frame, whose
//!   value FANUC cannot read back: the translation keeps the shift of each axis in a
//!   variable (set by the TRANS before, raised by each ATRANS) and writes `G52` from them,
//!   where every ATRANS follows a TRANS on every path ([`ATRANS_READY`]), in a main program
//!   (or a called one whose own leading TRANS sets the frame: its caller's does not matter)
//!   with no rotation, scale or mirror and no incremental move; elsewhere refused (NC577).
//!   Under a rotation `frame_chain.rs` follows the frame (and refuses where it cannot).
//! - `SUPA` and `G153` → `G53` in the same block.
//! - `G505`/`G506` → `G58`/`G59`, `G507`.. → `G54.1 P1`.. (the trace numbers both alike).
//! - `G74 Z1=0` → `G91 G28 Z0` (the intermediate point is where the tool stands, as for
//!   G74), then `G90` again where the program is absolute (under G91 only `G28 Z0`);
//!   `G75 FP=k` → `G91 G30 P(k+1)`.

use super::*;

const AXES: &[u8; 9] = b"XYZABCUVW";

/// A `G` word (`G52`, `G68`) of the FANUC blocks the frame translation writes.
pub(super) fn g(v: f64, span: Span) -> Item {
    item(ItemKind::Word(Word { addr: Addr::Letter(b'G'), value: WordValue::Expr(num(v, span)), span }), span)
}

/// An address word `l` with value `v`.
pub(super) fn letter(l: u8, v: Expr, span: Span) -> Item {
    item(ItemKind::Word(Word { addr: Addr::Letter(l), value: WordValue::Expr(v), span }), span)
}

/// A number written with its decimal point (a length, an angle).
pub(super) fn point(v: f64, span: Span) -> Expr {
    Expr::num(v, true, span)
}

fn const_g(it: &Item) -> Option<f64> {
    match &it.kind {
        ItemKind::Word(Word { addr: Addr::Letter(b'G'), value: WordValue::Expr(e), .. }) => match &e.kind {
            ExprKind::Num(n) => Some(n.value),
            _ => None,
        },
        _ => None,
    }
}

/// [`trans_axes`] bit: the program adds to its frame (`ATRANS`, not the G92 form) and may:
/// its frame instructions are TRANS and ATRANS only, and the first of them in the text is a
/// TRANS in a top-level block that no jump, label or structure comes before, so every
/// ATRANS finds the shifts that TRANS set.
pub const ATRANS_READY: u16 = 1 << 13;

/// The temporary holding the programmable shift of axis `l` (a local of the main program).
pub(super) fn shift_var(l: u8, span: Span) -> VarRef {
    VarRef { kind: VarKind::Named { name: format!("{TEMP_PREFIX}SHIFT_{}", l as char), indices: vec![] }, span }
}

/// Whether `body` has an additive ATRANS and every one finds the shifts of a TRANS before it
/// ([`ATRANS_READY`]).
fn atrans_ready(body: &[Stmt]) -> bool {
    let mut additive = false;
    let mut others = false;
    crate::ir::visit::walk_stmts(body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            for it in &b.items {
                if let ItemKind::Frame { op, words } = &it.kind {
                    match op.as_str() {
                        "TRANS" => {}
                        "ATRANS" if g92_words(words).is_none() => additive = true,
                        _ => others = true,
                    }
                }
            }
        }
    });
    if !additive || others {
        return false;
    }
    for s in body {
        let StmtKind::Block(b) = &s.kind else { return false };
        if b.meta.label.is_some()
            || b.items
                .iter()
                .any(|it| matches!(it.kind, ItemKind::Goto(_) | ItemKind::IfThen { .. } | ItemKind::Call(_)))
        {
            return false;
        }
        if let Some(op) = b.items.iter().find_map(|it| match &it.kind {
            ItemKind::Frame { op, .. } => Some(op.as_str()),
            _ => None,
        }) {
            return op == "TRANS";
        }
    }
    false
}

/// The axes any TRANS of `body` names, with X, Y and Z; bit 15: the program has an
/// incremental word (G91 or IC()), after which TRANS and G52 differ; bit 14: it has a
/// frame instruction other than the `ATRANS X=$P_EP[X]-v` form of G92 ([`g92_words`]).
pub fn trans_axes(body: &[Stmt]) -> u16 {
    let mut bits = 0b111;
    crate::ir::visit::walk_stmts(body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            for it in &b.items {
                if const_g(it) == Some(91.0) || matches!(&it.kind, ItemKind::Word(Word { value: WordValue::Ic(_), .. }))
                {
                    bits |= 1 << 15;
                }
                if let ItemKind::Frame { op, words } = &it.kind {
                    if op != "ATRANS" || g92_words(words).is_none() {
                        bits |= 1 << 14;
                    }
                    for w in words {
                        if let Addr::Letter(l) = w.addr {
                            bits |= AXES.iter().position(|&c| c == l).map_or(0, |i| 1 << i);
                        }
                    }
                }
            }
        }
    });
    if atrans_ready(body) {
        bits |= ATRANS_READY;
    }
    bits
}

/// `SUPA` → `G53` in its block (before the block is split: it stays with its words).
pub fn supa_as_g53(b: &mut Block) {
    for it in b.items.iter_mut() {
        if matches!(&it.kind, ItemKind::Instruction { name } if name == "SUPA") {
            *it = g(53.0, it.span);
        }
    }
}

/// Rewrites `G153` in place and moves a `G505..` selection into a block of its own
/// in `out` (it bypasses the words pass, where G58/G59 are Siemens codes of another
/// meaning); `Some(stmts)`: the block became these (TRANS, G74, G75, or a refusal).
pub fn block(
    ctx: &mut Ctx,
    b: &mut Block,
    abs: Option<bool>,
    axes: u16,
    main: bool,
    out: &mut Vec<Stmt>,
) -> Option<Vec<Stmt>> {
    let (mut k, mut moved) = (0, false);
    while k < b.items.len() {
        let span = b.items[k].span;
        match (&b.items[k].kind, const_g(&b.items[k])) {
            (_, Some(153.0)) => b.items[k] = g(53.0, span),
            (_, Some(v)) if (505.0..=554.0).contains(&v) && v.fract() == 0.0 => {
                let sel = if v < 507.0 {
                    vec![g(v - 447.0, span)]
                } else {
                    vec![g(54.1, span), letter(b'P', num(v - 506.0, span), span)]
                };
                out.push(block_stmt(sel, span));
                b.items.remove(k);
                moved = true;
                continue;
            }
            _ => {}
        }
        k += 1;
    }
    if moved && b.items.is_empty() && b.meta.number.is_none() && b.meta.comments.is_empty() && b.meta.label.is_none() {
        return Some(Vec::new());
    }
    let span = b.meta.span;
    if let [Item { kind: ItemKind::Frame { op, words }, span: fspan }] = b.items.as_slice() {
        if op == "ATRANS" && g92_words(words).is_none() {
            return Some(atrans(ctx, &mut b.meta, words, *fspan, abs, axes, main));
        }
        if op == "ATRANS" {
            let g92 = g92_words(words)?;
            if !main || axes & (3 << 14) != 0 || abs != Some(true) {
                return Some(refuse(
                    ctx,
                    *fspan,
                    "ATRANS X=$P_EP[X]-v (FANUC G92) in a called program, under G91, or in a program with other frame instructions or incremental moves (FANUC G52 keeps the G92 shift where TRANS replaces it; after a frame change a Sinumerik incremental move also travels it)",
                    "set the coordinate system in a main program that has no other frames, in G90",
                ));
            }
            let mut items = vec![g(92.0, span)];
            items.extend(g92.into_iter().map(|(l, v, s)| letter(l, v, s)));
            let meta = std::mem::take(&mut b.meta);
            return Some(vec![meta_stmt(meta, items)]);
        }
        if op != "TRANS" {
            return None; // the words pass refuses the others (NC316)
        }
        // An incremental move after it is refused where the controls travel it differently
        // (`frames_incr`: an axis not programmed absolutely since its shift changed). The
        // TRANS values are the shift whatever G90/G91 (the Siemens run agrees); FANUC reads
        // G52's words under G91 incrementally, so where G91 may be in force the G52 is
        // written under G90 and the mode in force selected again after it.
        if words.iter().any(|w| matches!(w.value, WordValue::Rotary(..))) {
            return Some(refuse(
                ctx,
                *fspan,
                "a rotary positioning form (ACP, ACN, DC …) in a TRANS",
                "a shift is a plain value: write TRANS with the value alone",
            ));
        }
        let mut items = vec![g(52.0, span)];
        let mut shifts = Vec::new();
        let restore = match abs {
            Some(true) => None,
            Some(false) => Some(num(91.0, span)),
            None => {
                let t = ctx.temp(span);
                let sys = VarRef { kind: VarKind::Hash(4003), span };
                shifts.push(block_stmt(vec![assign_item(&t, crate::lower::var_expr(&sys), span)], span));
                Some(crate::lower::var_expr(&t))
            }
        };
        if restore.is_some() {
            items.insert(0, g(90.0, span));
        }
        for (i, &l) in AXES.iter().enumerate() {
            if axes & (1 << i) == 0 {
                continue;
            }
            let v = words.iter().rev().find(|w| w.addr.is(l)).map(|w| match &w.value {
                // Refused above: a rotary positioning form is no shift value.
                WordValue::Expr(e) | WordValue::Ac(e) | WordValue::Ic(e) | WordValue::Rotary(_, e) => e.clone(),
            });
            let v = v.unwrap_or_else(|| point(0.0, *fspan));
            if axes & ATRANS_READY != 0 {
                // The shifts an ATRANS after it adds to.
                shifts.push(block_stmt(vec![assign_item(&shift_var(l, *fspan), v.clone(), *fspan)], *fspan));
            }
            items.push(letter(l, v, *fspan));
        }
        let meta = std::mem::take(&mut b.meta);
        shifts.push(meta_stmt(meta, items));
        if let Some(mode) = restore {
            shifts.push(block_stmt(vec![letter(b'G', mode, span)], span));
        }
        return Some(shifts);
    }
    let gs: Vec<f64> = b.items.iter().filter_map(const_g).collect();
    let home = if gs.contains(&74.0) {
        74.0
    } else if gs.contains(&75.0) {
        75.0
    } else {
        return None;
    };
    // G91 only where the program is absolute: written again under G91 it would pile up
    // over round trips (`G91` then `G91 G28 Z0`).
    let mut items = vec![g(91.0, span), g(if home == 74.0 { 28.0 } else { 30.0 }, span)];
    if abs == Some(false) {
        items.remove(0);
    }
    for it in &b.items {
        let ok = match &it.kind {
            ItemKind::Word(w) => match &w.addr {
                Addr::Letter(b'G') => const_g(it) == Some(home),
                Addr::Name(n) if n.as_ref() == "FP" && home == 75.0 => {
                    let k = match &w.value {
                        WordValue::Expr(Expr { kind: ExprKind::Num(k), .. }) => k.value,
                        _ => 0.0,
                    };
                    if !(1.0..=4.0).contains(&k) || k.fract() != 0.0 {
                        return Some(refuse(ctx, w.span, "G75 without a constant FP=1..4", "write FP=1 to FP=4"));
                    }
                    items.insert(usize::from(abs != Some(false)) + 1, letter(b'P', num(k + 1.0, w.span), w.span));
                    true
                }
                Addr::Name(n) => match n.as_bytes() {
                    [c, b'1'] if AXES.contains(c) => {
                        items.push(letter(*c, point(0.0, w.span), w.span));
                        true
                    }
                    _ => false,
                },
                _ => false,
            },
            _ => false,
        };
        if !ok {
            return Some(refuse(
                ctx,
                it.span,
                "G74/G75 with other words than the machine axes (and FP=): the approach stands alone in its block \
                 (\"G75 requires a separate block\", Siemens 802D programming manual §10.3.6; G74 is held to the same \
                 rule, which no source relaxes)",
                "write the approach alone in its block (`G74 Z1=0`) and the other words in a block of their own",
            ));
        }
    }
    if abs.is_none() {
        return Some(refuse(
            ctx,
            span,
            "G74/G75 where G90/G91 depends on the caller or the path taken",
            "select G90 or G91 before the reference point approach",
        ));
    }
    let meta = std::mem::take(&mut b.meta);
    let mut out = vec![meta_stmt(meta, items)];
    if abs == Some(true) {
        out.push(block_stmt(vec![g(90.0, span)], span));
    }
    Some(out)
}

/// `ATRANS X.. Y..` (adds to the frame): each named axis's shift variable raised by its
/// value, then `G52` of every axis from the variables (`#1=#1+50.`, `G52 X#1 Y#2 Z#3`).
fn atrans(
    ctx: &mut Ctx,
    meta: &mut BlockMeta,
    words: &[Word],
    fspan: Span,
    abs: Option<bool>,
    axes: u16,
    main: bool,
) -> Vec<Stmt> {
    let why = if !main && axes & ATRANS_READY == 0 {
        Some("in a called program that does not set its own frame first (a TRANS in its leading blocks): it adds to the frame its caller left, which the translation does not follow into called programs")
    } else if axes & (1 << 15) != 0 || abs != Some(true) {
        Some("in a program with incremental moves (after a frame change a Sinumerik incremental move also travels the shift, a FANUC one after G52 does not)")
    } else if axes & ATRANS_READY == 0 {
        Some("where a TRANS does not come first on every path, or with ROT, SCALE or MIRROR in the program (FANUC's G52 shifts the unrotated coordinates)")
    } else if words
        .iter()
        .any(|w| !matches!(w.value, WordValue::Expr(_)) || !matches!(w.addr, Addr::Letter(l) if AXES.contains(&l)))
    {
        Some("with a word that is not an axis shift value")
    } else {
        None
    };
    if let Some(why) = why {
        let what = format!("ATRANS (adds to the programmable frame) {why}");
        let hint = "program a TRANS first, in the main program's leading blocks, and keep the program in G90 without ROT, SCALE or MIRROR";
        return ctx.unsupported("NC577", fspan, &what, hint).into_iter().collect();
    }
    let mut out = Vec::new();
    for w in words {
        let (Addr::Letter(l), WordValue::Expr(e)) = (&w.addr, &w.value) else { continue };
        let var = shift_var(*l, w.span);
        let sum = crate::lower::bin(BinOp::Add, crate::lower::var_expr(&var), e.clone());
        out.push(block_stmt(vec![assign_item(&var, sum, w.span)], w.span));
    }
    let mut items = vec![g(52.0, meta.span)];
    for (i, &l) in AXES.iter().enumerate() {
        if axes & (1 << i) != 0 {
            items.push(letter(l, crate::lower::var_expr(&shift_var(l, fspan)), fspan));
        }
    }
    out.push(meta_stmt(std::mem::take(meta), items));
    out
}

fn refuse(ctx: &mut Ctx, span: Span, what: &str, hint: &str) -> Vec<Stmt> {
    ctx.unsupported("NC445", span, what, hint).into_iter().collect()
}

/// The words of `ATRANS X=$P_EP[X]-v Y=$P_EP[Y] ..` (what FANUC → Sinumerik writes for
/// `G92 X v Y0`): each axis's new coordinate v, or `None` for another ATRANS.
pub fn g92_words(words: &[Word]) -> Option<Vec<(u8, Expr, Span)>> {
    let end_of = |e: &Expr, l: u8| match &e.kind {
        ExprKind::Var(v) => match &v.kind {
            VarKind::System { name, indices } if name.eq_ignore_ascii_case("P_EP") => match indices.as_slice() {
                [Expr { kind: ExprKind::Ident(a), .. }] => a.eq_ignore_ascii_case(&(l as char).to_string()),
                _ => false,
            },
            _ => false,
        },
        _ => false,
    };
    let mut out = Vec::new();
    for w in words {
        let Addr::Letter(l) = w.addr else { return None };
        if !b"XYZABC".contains(&l) {
            return None;
        }
        let WordValue::Expr(e) = &w.value else { return None };
        let v = match &e.kind {
            _ if end_of(e, l) => point(0.0, w.span),
            ExprKind::Binary(BinOp::Sub, a, v) if end_of(a, l) => (**v).clone(),
            _ => return None,
        };
        out.push((l, v, w.span));
    }
    (!out.is_empty()).then_some(out)
}

/// A write of `$P_UIFR[n,X,TR]` for an extended frame (n 7..54, `G50n`, FANUC G54.1 P(n-6)):
/// the P number and the axis letter.
pub fn extended_frame(target: &VarRef) -> Option<(u32, u8)> {
    let VarKind::System { name, indices } = &target.kind else { return None };
    if !name.eq_ignore_ascii_case("P_UIFR") {
        return None;
    }
    let [n, a, c] = indices.as_slice() else { return None };
    let n = match &n.kind {
        ExprKind::Num(n) if (7.0..=54.0).contains(&n.value) && n.value.fract() == 0.0 => n.value as u32,
        _ => return None,
    };
    let ident = |e: &Expr| match &e.kind {
        ExprKind::Ident(s) => Some(s.to_ascii_uppercase()),
        ExprKind::Var(v) => match &v.kind {
            VarKind::Named { name, indices } if indices.is_empty() => Some(name.to_ascii_uppercase()),
            _ => None,
        },
        _ => None,
    };
    let axis = ident(a).filter(|s| s.len() == 1 && b"XYZABC".contains(&s.as_bytes()[0]))?;
    (ident(c).as_deref() == Some("TR")).then(|| (n - 6, axis.as_bytes()[0]))
}

/// `$P_UIFR[n,X,TR]=v` (n 7..54) → `G10 L20 P(n-6) X v`, written under G90 (the mode in
/// force is switched for the block where it is G91). Sinumerik stores the frame until `G50n`
/// selects it, FANUC applies a write to the active offset at once: where the program writes
/// the active one and moves before selecting it again, the check finds the difference.
pub fn g10_l20(
    ctx: &mut Ctx,
    target: &VarRef,
    value: Expr,
    abs: Option<bool>,
    span: Span,
) -> Result<Vec<Stmt>, Vec<Stmt>> {
    let Some((p, l)) = extended_frame(target) else { return Ok(Vec::new()) };
    let Some(abs) = abs else {
        return Err(refuse(
            ctx,
            span,
            "a write of an extended frame ($P_UIFR[7..54]) where G90/G91 depends on the path taken or on the caller (FANUC G10 under G91 adds to the offset)",
            "select G90 or G91 before the write",
        ));
    };
    // `$P_UIFR[n,X,TR]=$P_UIFR[n,X,TR]+d` (what G91 G10 L20 becomes): the G91 form.
    let (add, value) = match value.kind {
        ExprKind::Binary(BinOp::Add, a, d) if matches!(&a.kind, ExprKind::Var(v) if extended_frame(v) == Some((p, l))) => {
            (true, *d)
        }
        kind => (false, Expr { kind, span: value.span }),
    };
    let mut items = vec![g(10.0, span), letter(b'L', num(20.0, span), span), letter(b'P', num(p as f64, span), span)];
    items.push(letter(l, value, span));
    if abs != add {
        return Ok(vec![block_stmt(items, span)]);
    }
    items.insert(0, g(if add { 91.0 } else { 90.0 }, span));
    Ok(vec![block_stmt(items, span), block_stmt(vec![g(if abs { 90.0 } else { 91.0 }, span)], span)])
}
