//! FANUC drilling cycles → Sinumerik: a G81/G82/G83/G73/G84/G74/G85/G88/G89 block and the
//! hole blocks after it become `MCALL CYCLEnn(…)`, a `G0` positioning block per hole and
//! `MCALL`; a hole without a position (only Z or R) is a direct `CYCLEnn(…)` call. Exact only:
//! - RFP = R, SDIS = 0 (so CYCLE83's infeeds count from R as G83's Q does), DP = Z; under
//!   G91 R counts from the initial level and Z from R, so RFP = `$P_EP[Z]` + R and
//!   DP = RFP + Z (the positions stay incremental moves);
//! - G99 → RTP = R; G98 → RTP = the Z end point at the MCALL (`$P_EP[Z]`, the initial level);
//!   a G98 (or new G91 R) after a G99 hole, where the tool stands at R, reads the initial
//!   level from `NCTRANS_CYC_Z`, set to `$P_EP[Z]` where the cycle began;
//! - P (ms) → DTB (s); Q → FDPR; G85's feed → FFR = RFF = `$P_F`;
//! - tapping (`tapping.rs`): `M29 S` + G84/G74 → CYCLE84, G84/G74 alone → CYCLE840;
//!   G88 → CYCLE88 with SDIR the spindle's direction.
//!
//! Everything else in a cycle is refused (NC428, tapping NC483–NC485) naming what differs:
//! G76/G87 (the shift direction is a FANUC machine parameter; G87 bores upward), G86 (every
//! Sinumerik boring cycle that stops the spindle also stops the program), another plane, a
//! cycle that spans structures or labels, and repeats K/L that are not a constant. The rules are in
//! docs/translation-fanuc-to-sinumerik.md.

use super::*;

mod loops;

/// The cycle data of the sequence, as FANUC expressions in millimetres.
#[derive(Clone, Default)]
struct Data {
    g: u32,
    r: Option<Expr>,
    z: Option<Expr>,
    q: Option<Expr>,
    p: Option<Expr>,
    g99: bool,
    /// The F word of the sequence (the pitch of rigid tapping is F/S).
    f: Option<Expr>,
    /// The spindle, feed mode and M29 when the cycle began (tapping).
    tap: tapping::TapState,
    /// R, Z given under G91: R from the initial level, Z from the R plane.
    r_inc: bool,
    z_inc: bool,
    /// The variable holding the initial level, once a G98 after a G99 hole needed it.
    initial: Option<String>,
}

/// Where the initial level is kept when the tool no longer stands at it.
const INITIAL: &str = "NCTRANS_CYC_Z";

/// Lowers the drilling cycles of every block list of the program.
pub fn lower(ctx: &mut Ctx, body: Vec<Stmt>) -> Vec<Stmt> {
    let mut any = false;
    let mut planes = false;
    visit_blocks(&body, &mut |b| {
        let gs = g_codes(&b.items);
        any |= gs.iter().copied().any(cycle_g);
        // M29 belongs to a tapping cycle: alone it is refused here, not written as an M code.
        any |= b.items.iter().any(|it| matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'M') && word_expr(w).and_then(literal) == Some(29.0)));
        planes |= gs.iter().any(|g| matches!(g, 180 | 190));
    });
    if !any {
        return body;
    }
    let top = ctx.plan().role == Role::Main;
    let mut closable = BTreeMap::new();
    loops::closable_bodies(ctx, &body, &mut closable);
    let mut nested = Vec::with_capacity(body.len());
    for s in body {
        match s.kind {
            StmtKind::Block(_) => nested.push(s),
            _ => nested.extend(map_bodies(vec![s], &mut |b| {
                let open = b.first().and_then(|f| closable.get(&f.span).copied());
                lower_list(ctx, b, planes, false, open)
            })),
        }
    }
    lower_list(ctx, nested, planes, top, None)
}

fn cycle_g(g: u32) -> bool {
    matches!(g, 730 | 740 | 760 | 810..=890)
}

fn visit_blocks(body: &[Stmt], f: &mut dyn FnMut(&Block)) {
    for s in body {
        match &s.kind {
            StmtKind::Block(b) => f(b),
            StmtKind::If(i) => {
                visit_blocks(&i.then_body, f);
                if let Some(e) = &i.else_part {
                    visit_blocks(&e.body, f);
                }
            }
            StmtKind::While(w) => visit_blocks(&w.body, f),
            StmtKind::Loop(l) => visit_blocks(&l.body, f),
            StmtKind::For(x) => visit_blocks(&x.body, f),
            StmtKind::Repeat(r) => visit_blocks(&r.body, f),
            StmtKind::Do(d) => visit_blocks(&d.body, f),
        }
    }
}

/// The numeric value of a word in the block at `lo`: a literal without a decimal point is in
/// least increments of the unit in force there (G20/G21); `None` where that unit depends on
/// the path taken or on the caller (the value cannot be written exactly).
fn length(ctx: &Ctx, e: &Expr, lo: u32) -> Option<Expr> {
    fn bare(e: &Expr) -> bool {
        match &e.kind {
            ExprKind::Num(n) => !n.point,
            ExprKind::Unary(UnOp::Neg, a) => bare(a),
            _ => false,
        }
    }
    match literal(e) {
        Some(v) if bare(e) => {
            ctx.modal.inch_at(lo).map(|inch| num(super::words::scale(ctx.opts, v, inch, false), e.span))
        }
        _ => Some(e.clone()),
    }
}

const UNIT_UNKNOWN: &str =
    "a drilling-cycle value without a decimal point where the unit (G20/G21) depends on the path taken or on the caller";
const UNIT_HINT: &str = "write the value with a decimal point";
const INC_UNKNOWN: &str = "a drilling-cycle R or Z where G90/G91 depends on the path taken or on the caller";
const INC_HINT: &str = "program G90 or G91 in the cycle block";

fn word_expr(w: &Word) -> Option<&Expr> {
    match &w.value {
        WordValue::Expr(e) => Some(e),
        _ => None,
    }
}

fn block(items: Vec<Item>, span: Span) -> Stmt {
    plain_block(items, span)
}

/// After `MCALL`: the motion mode the cycle held (`back`) written again where it is not G0,
/// the one the positioning blocks leave; not known: refused.
fn motion_back(ctx: &mut Ctx, back: Option<u32>, span: Span, hint: &str, out: &mut Vec<Stmt>) {
    match back {
        Some(0) => {}
        Some(m) => out.push(block(vec![super::words::g_word(m, span)], span)),
        None => refuse(ctx, span, "the motion mode after a drilling cycle", hint, out),
    }
}

fn refuse(ctx: &mut Ctx, span: Span, what: &str, hint: &str, out: &mut Vec<Stmt>) {
    out.extend(ctx.refuse("NC428", span, &format!("{what}: not translated to Sinumerik"), what, hint));
}

/// `open`: the list is a loop body whose pass may end with the cycle active, with the motion
/// mode before the loop ([`closable_bodies`]).
fn lower_list(ctx: &mut Ctx, body: Vec<Stmt>, planes: bool, top: bool, open: Option<Option<u32>>) -> Vec<Stmt> {
    let mut out = Vec::with_capacity(body.len());
    let mut active: Option<Data> = None;
    // Before the list's first cycle: whether a block moved or a structure ran (a pass's
    // cycle from the pass before would drill there on FANUC), and the mode G80 gives back.
    let mut cycle_seen = false;
    let mut moved_before = false;
    let mut held: Option<u32> = None;
    // The motion mode before the cycle (G0 at the top of a main program): the positioning
    // blocks write G0, so another mode is written again after the cycle.
    let mut motion: Option<u32> = if top { Some(0) } else { None };
    let mut after_g99_hole = false;
    // Where the running cycle's output begins (the tool still at the initial level).
    let mut start_at = 0;
    let mut tap = tapping::TapState::start(top);
    for s in body {
        let span = s.span;
        let StmtKind::Block(mut b) = s.kind else {
            // A loop of hole positions under the cycle (a bolt circle): the MCALL in force
            // drills each, as FANUC's cycle does (`loops::holes_only`).
            if let Some(d) = active.as_ref().filter(|d| unsupported_kind(d.g).is_none()) {
                if let Some(kept) = loops::holes_only(&s, (b'X', b'Y')) {
                    // Under G99 the tool stands at R after a pass's hole, or at the initial
                    // level if no pass ran: new data after it takes the level where the cycle
                    // began (see `call_item`), right either way.
                    after_g99_hole |= d.g99;
                    out.push(kept);
                    continue;
                }
            }
            moved_before |= !cycle_seen;
            if active.take().is_some() {
                refuse(
                    ctx,
                    span,
                    "a drilling cycle that stays active into a structure",
                    "cancel it with G80 before",
                    &mut out,
                );
            }
            motion = None;
            tap.forget();
            out.push(s);
            continue;
        };
        let gs = g_codes(&b.items);
        let new_cycle = gs.iter().copied().find(|g| cycle_g(*g));
        let motion_g = gs.iter().copied().find(|g| matches!(g, 0 | 10 | 20 | 30));
        if b.meta.label.is_some() && active.is_none() {
            // A jump target: the blocks above it in the text are not the only way here, so
            // the spindle, feed mode and motion mode they set are not known at it.
            if tap.rigid.is_some() {
                out.extend(ctx.refuse(
                    "NC590",
                    span,
                    "a jump target between M29 and its tapping cycle: not translated to Sinumerik",
                    "a jump target between M29 and its tapping cycle",
                    "program M29 S… right before G84/G74, after the label",
                ));
            }
            tap.forget();
            motion = None;
        }
        if active.is_none() && new_cycle.is_none() {
            if let Some(m) = motion_g {
                motion = Some(m);
            }
            let armed = tap.rigid.is_some();
            tap.observe(&mut b);
            let moves = b
                .items
                .iter()
                .any(|it| matches!(&it.kind, ItemKind::Word(w) if matches!(w.addr.as_str(), "X" | "Y" | "Z")));
            moved_before |= !cycle_seen
                && (b.items.iter().any(|it| matches!(it.kind, ItemKind::Call(_) | ItemKind::Return { .. }))
                    || b.items.iter().any(|it| {
                        matches!(&it.kind, ItemKind::Word(w)
                        if matches!(w.addr.as_str(), "X" | "Y" | "Z" | "A" | "B" | "C" | "U" | "V" | "W"))
                    }));
            if armed && moves {
                // FANUC's M29 arms the tapping cycle that follows it; a move between them is
                // not a form the translation knows.
                refuse(
                    ctx,
                    span,
                    "a move between M29 and its tapping cycle",
                    "program M29 S… right before G84/G74",
                    &mut out,
                );
                tap.rigid = None;
            }
            out.push(Stmt { kind: StmtKind::Block(b), span });
            continue;
        }
        if b.meta.label.is_some() && active.is_some() {
            refuse(
                ctx,
                span,
                "a jump target inside a drilling cycle",
                "cancel the cycle (G80) before the label",
                &mut out,
            );
        }
        if planes {
            refuse(ctx, span, "a drilling cycle in a program that selects G18/G19", "drill in G17", &mut out);
            out.push(Stmt { kind: StmtKind::Block(b), span });
            active = None;
            continue;
        }
        // Cancel: G80 or a motion code ends the MCALL before the block's own words.
        let cancel = gs.contains(&800) || motion_g.is_some();
        if cancel && new_cycle.is_none() {
            // G80 (or G00–G03) also ends rigid tapping mode.
            tap.rigid = None;
            b.items.retain(|it| !matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'G') && word_expr(w).and_then(literal) == Some(80.0)));
            // The mode G80 gives back: the one before the cycle in this list, else what the
            // program's flow knows there (a called program: its callers' one mode).
            let back = motion.or_else(|| ctx.modal.motion_at(span.lo));
            if active.take().is_some() {
                if b.items.is_empty() {
                    // `G80` alone: the block becomes the `MCALL` (which stands alone).
                    b.items.push(Item { kind: ItemKind::ModalCallOff, span });
                    if let Some(m) = back.filter(|m| *m != 0) {
                        out.push(Stmt { kind: StmtKind::Block(b), span });
                        out.push(block(vec![super::words::g_word(m, span)], span));
                        continue;
                    }
                    if back.is_none() {
                        refuse(
                            ctx,
                            span,
                            "the motion mode after a drilling cycle",
                            "program G00 or G01 after G80",
                            &mut out,
                        );
                    }
                    out.push(Stmt { kind: StmtKind::Block(b), span });
                    after_g99_hole = false;
                    continue;
                }
                // `MCALL` stands alone in its block: the motion mode goes in a block of its own.
                out.push(block(vec![Item { kind: ItemKind::ModalCallOff, span }], span));
                if motion_g.is_none() {
                    motion_back(ctx, back, span, "program G00 or G01 after G80", &mut out);
                }
            }
            if let Some(m) = motion_g {
                motion = Some(m);
            }
            out.push(Stmt { kind: StmtKind::Block(b), span });
            after_g99_hole = false;
            continue;
        }
        if b.items.iter().any(|it| matches!(it.kind, ItemKind::End { .. })) {
            if active.take().is_some() {
                out.push(block(vec![Item { kind: ItemKind::ModalCallOff, span }], span));
            }
            out.push(Stmt { kind: StmtKind::Block(b), span });
            continue;
        }
        tap.observe_modes(&b.items);
        let mut d = active.clone().unwrap_or_default();
        let starting = active.is_none();
        if starting && b.meta.label.is_some() {
            // The jump lands before the cycle's F/S and MCALL, not on its first hole.
            let mut at = Block::default();
            at.meta.label = b.meta.label.take();
            at.meta.number = b.meta.number.take();
            at.meta.span = b.meta.span;
            out.push(Stmt { kind: StmtKind::Block(at), span });
        }
        if let Some(g) = new_cycle {
            d.g = g;
        }
        if starting {
            if !cycle_seen {
                held = motion.or_else(|| ctx.modal.held_at(span.lo)).or(open.flatten());
            }
            cycle_seen = true;
            start_at = out.len();
            after_g99_hole = false;
            d.tap = tap.clone();
            if let Some(&(_, at)) = tap.rigid.as_ref().filter(|_| !matches!(d.g, 840 | 740)) {
                refuse(
                    ctx,
                    at,
                    "M29 (rigid tapping) before a cycle that is not G84/G74",
                    "program M29 S… right before the tapping cycle",
                    &mut out,
                );
            }
            // The cycle took the M29 (its data keeps it).
            tap.rigid = None;
        }
        // G90/G91 where the block's R and Z are read (the block's own G91 included).
        let incremental = ctx.modal.incremental_at(span.lo);
        let mut changed = starting || new_cycle.is_some();
        let (mut pos, mut drill_word, mut other, mut count) = (Vec::new(), false, Vec::new(), None::<Expr>);
        let mut feed = false;
        for it in std::mem::take(&mut b.items) {
            let ItemKind::Word(w) = &it.kind else {
                other.push(it);
                continue;
            };
            let Some(e) = word_expr(w) else {
                refuse(ctx, it.span, "an AC()/IC() word in a drilling cycle", "write the value plainly", &mut out);
                continue;
            };
            match w.addr.as_str() {
                "G" => match literal(e).map(|v| (v * 10.0).round() as u32) {
                    Some(980) => {
                        d.g99 = false;
                        changed = true;
                    }
                    Some(990) => {
                        d.g99 = true;
                        changed = true;
                    }
                    Some(g) if cycle_g(g) => {}
                    _ => other.push(it.clone()),
                },
                "X" | "Y" => {
                    pos.push(it.clone());
                    drill_word = true;
                }
                letter @ ("Z" | "R") => {
                    let Some(v) = length(ctx, e, span.lo) else {
                        refuse(ctx, it.span, UNIT_UNKNOWN, UNIT_HINT, &mut out);
                        continue;
                    };
                    let Some(inc) = incremental else {
                        refuse(ctx, it.span, INC_UNKNOWN, INC_HINT, &mut out);
                        continue;
                    };
                    if letter == "Z" {
                        (d.z, d.z_inc) = (Some(v), inc);
                    } else {
                        (d.r, d.r_inc) = (Some(v), inc);
                    }
                    drill_word = true;
                    changed = true;
                }
                "Q" => {
                    let Some(v) = length(ctx, e, span.lo) else {
                        refuse(ctx, it.span, UNIT_UNKNOWN, UNIT_HINT, &mut out);
                        continue;
                    };
                    d.q = Some(v);
                    changed = true;
                }
                "P" => {
                    d.p = Some(e.clone());
                    changed = true;
                }
                "K" | "L" => count = Some(e.clone()),
                "F" => {
                    feed = true;
                    d.f = Some(e.clone());
                    other.push(it.clone());
                }
                "M" if literal(e) == Some(29.0) => refuse(
                    ctx,
                    it.span,
                    "M29 in a drilling-cycle block",
                    "program M29 S… in its own block before the tapping cycle",
                    &mut out,
                ),
                _ => other.push(it.clone()),
            }
        }
        active = Some(d.clone());
        if let Some(why) = unsupported_kind(d.g) {
            // Every block of the cycle is refused, so no hole turns into a plain move.
            refuse(ctx, span, why.0, why.1, &mut out);
            continue;
        }
        // G85 carries the feed in its arguments: a new F is a new MCALL.
        // So does rigid tapping (its pitch is F/S).
        changed |= feed && matches!(d.g, 850 | 840 | 740);
        if changed && after_g99_hole && (!d.g99 || d.r_inc) && d.initial.is_none() {
            // The new call counts from the initial level, but the tool stands at R: keep
            // the level where the cycle began, before its first hole.
            let plan = &mut ctx.progs[ctx.cur];
            if !plan.defs.iter().any(|def| def.0 == INITIAL) {
                plan.defs.push((INITIAL.into(), DataType::Real));
            }
            let save = assign(named_ref(INITIAL, span), var_expr(VarKind::Hash(5003), span), span);
            out.insert(start_at.min(out.len()), block(vec![save], span));
            d.initial = Some(INITIAL.into());
            active = Some(d.clone());
        }
        let repeats = match &count {
            None => 1,
            Some(e) => match literal(e) {
                Some(k) if (0.0..=99.0).contains(&k) && k.fract() == 0.0 => k as usize,
                _ => {
                    refuse(
                        ctx,
                        span,
                        "a repeat count K/L that is not a constant from 0 to 99",
                        "write the holes as blocks",
                        &mut out,
                    );
                    1
                }
            },
        };
        let mcall = drill_word && (changed || starting);
        // F and S go before an MCALL (its arguments may read them); the block number, the
        // comments and the other words ride on the first hole.
        let (lead, rest): (Vec<Item>, Vec<Item>) = other
            .into_iter()
            .partition(|it| mcall && matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'F') || w.addr.is(b'S')));
        if !lead.is_empty() {
            let at = feed_slot(&out, &d, starting, &lead);
            out.insert(at, block(lead, span));
        }
        b.items = rest;
        if !drill_word || repeats == 0 {
            if !b.items.is_empty() || b.meta.number.is_some() || !b.meta.comments.is_empty() {
                out.push(Stmt { kind: StmtKind::Block(b), span });
            }
            if drill_word && mcall {
                // `K0`/`L0`: the data is stored and no hole drilled here; the MCALL defines
                // the call the next position makes, and drills nothing itself.
                pending(ctx, &mut out, &active, span, after_g99_hole);
            } else if !drill_word && changed && !starting {
                // New data without a hole: the next hole drills with it.
                pending(ctx, &mut out, &active, span, after_g99_hole);
            }
            continue;
        }
        if mcall {
            if let Some(call) = call_item(ctx, &d, CallKind::Mcall, span, after_g99_hole, &mut out) {
                out.push(block(vec![call], span));
            }
        }
        for k in 0..repeats {
            let mut hole = if k == 0 { std::mem::take(&mut b) } else { Block::default() };
            if pos.is_empty() {
                if let Some(call) = call_item(ctx, &d, CallKind::Named, span, after_g99_hole, &mut out) {
                    hole.items.push(call);
                }
            } else {
                hole.items.insert(0, super::words::g_word(0, span));
                hole.items.extend(pos.iter().cloned());
            }
            hole.meta.span = span;
            out.push(Stmt { kind: StmtKind::Block(hole), span });
        }
        if repeats > 0 {
            after_g99_hole = d.g99;
        }
    }
    if active.is_some() && !top {
        let span = out.last().map_or(Span::default(), |s| s.span);
        if open.is_some() && !moved_before {
            // The pass ends its cycle as the block after the loop would (see `closable_bodies`).
            out.push(block(vec![Item { kind: ItemKind::ModalCallOff, span }], span));
            motion_back(ctx, held, span, "program G00 or G01 before the loop", &mut out);
        } else {
            let hint = if open.is_some() {
                "cancel it with G80, or start the pass with its cycle block (no move before it)"
            } else {
                "cancel it with G80"
            };
            refuse(ctx, span, "a drilling cycle still active at the end of a block list", hint, &mut out);
        }
    }
    if let Some((_, at)) = tap.rigid {
        refuse(ctx, at, "M29 without a tapping cycle after it", "program G84/G74 right after M29 S…", &mut out);
    }
    drop_unused_mcalls(&mut out);
    out
}

/// `MCALL CYCLEnn(a)`, direct `CYCLEnn(a)` calls only, `MCALL`: a cycle that drilled only
/// where the tool stood (`G84 G98 Z.. R..` then `G80`). The modal call fires after motion
/// blocks alone, and there are none before it is cancelled, so it is left out: the direct
/// calls drill the same holes, as a programmer would write them.
fn drop_unused_mcalls(out: &mut Vec<Stmt>) {
    fn only(s: &Stmt) -> Option<&[Item]> {
        match &s.kind {
            StmtKind::Block(b) if b.meta.label.is_none() && b.meta.number.is_none() && b.meta.comments.is_empty() => {
                Some(&b.items)
            }
            _ => None,
        }
    }
    fn call(it: &Item) -> Option<&Call> {
        match &it.kind {
            ItemKind::Call(c) => Some(c),
            _ => None,
        }
    }
    let mut i = 0;
    while i < out.len() {
        let define = only(&out[i]).and_then(|items| match items {
            [it] => call(it).filter(|c| c.kind == CallKind::Mcall).cloned(),
            _ => None,
        });
        let Some(define) = define else {
            i += 1;
            continue;
        };
        // The direct calls of the same cycle, each in a block without axis words.
        let direct = |s: &Stmt| match &s.kind {
            StmtKind::Block(b) => {
                b.meta.label.is_none()
                    && b.items.iter().any(|it| {
                        call(it).is_some_and(|c| {
                            c.kind == CallKind::Named && c.target == define.target && c.args == define.args
                        })
                    })
                    && b.items.iter().all(|it| match &it.kind {
                        ItemKind::Call(_) => true,
                        ItemKind::Word(w) => !matches!(w.addr, Addr::Letter(l) if b"XYZABCUVWIJK".contains(&l)),
                        _ => false,
                    })
            }
            _ => false,
        };
        let mut j = i + 1;
        while j < out.len() && direct(&out[j]) {
            j += 1;
        }
        let cancel = j > i + 1
            && j < out.len()
            && only(&out[j]).is_some_and(|items| matches!(items, [it] if matches!(it.kind, ItemKind::ModalCallOff)));
        if cancel {
            out.remove(j);
            out.remove(i);
        } else {
            i += 1;
        }
    }
}

/// Where the F of a starting rigid tapping cycle goes: before the block that held its
/// `M29 S` when that block is the last one written and sets only S. The speed then stays
/// right before the CYCLE84, the form the Sinumerik → FANUC translation takes back into
/// `M29 S`, so translating the translation back and forth gives it again (with the F after
/// the S, that translation moves the F in front of `M29 S` and the next pass reorders).
fn feed_slot(out: &[Stmt], d: &Data, starting: bool, lead: &[Item]) -> usize {
    let end = out.len();
    let sets_s = |it: &Item| matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'S'));
    let Some((_, at)) = d.tap.rigid.as_ref() else { return end };
    if !starting || !matches!(d.g, 840 | 740) || lead.iter().any(sets_s) {
        return end;
    }
    match out.last() {
        Some(Stmt { kind: StmtKind::Block(b), span })
            if span.contains(*at) && !b.items.is_empty() && b.items.iter().all(sets_s) =>
        {
            end - 1
        }
        _ => end,
    }
}

/// New cycle data in a block without a hole: written as an MCALL at once (the next hole
/// block then drills with it).
fn pending(ctx: &mut Ctx, out: &mut Vec<Stmt>, d: &Option<Data>, span: Span, after_g99: bool) {
    if let Some(d) = d {
        if let Some(call) = call_item(ctx, d, CallKind::Mcall, span, after_g99, out) {
            out.push(block(vec![call], span));
        }
    }
}

/// The cycles without an exact Sinumerik counterpart, and why.
fn unsupported_kind(g: u32) -> Option<(&'static str, &'static str)> {
    Some(match g {
        760 => (
            "fine boring G76",
            "G76 shifts by Q in a direction set by a FANUC machine parameter, CYCLE86 lifts off by RPA/RPO/RPAP given in the program: write CYCLE86 by hand with the machine's shift",
        ),
        870 => (
            "back boring G87",
            "G87 positions below the part and bores upward; no Sinumerik standard cycle does (CYCLE87 bores downward and stops the program)",
        ),
        860 => (
            "boring G86",
            "G86 stops the spindle and rapids out; every Sinumerik boring cycle that stops the spindle also stops the program (CYCLE87/CYCLE88) or orients it and lifts off (CYCLE86)",
        ),
        _ => return None,
    })
}

/// `a + b`, written `a - x` for a negative number `b = -x`.
fn plus(a: Expr, b: Expr) -> Expr {
    match literal(&b) {
        Some(0.0) => a,
        Some(x) if x < 0.0 => bin(BinOp::Sub, a, num(-x, b.span)),
        _ => bin(BinOp::Add, a, b),
    }
}

/// `CYCLEnn(RTP, RFP, SDIS, DP, …)` for the data `d`.
fn call_item(
    ctx: &mut Ctx,
    d: &Data,
    kind: CallKind,
    span: Span,
    after_g99: bool,
    out: &mut Vec<Stmt>,
) -> Option<Item> {
    let (Some(r), Some(z)) = (d.r.clone(), d.z.clone()) else {
        refuse(ctx, span, "a drilling cycle without R or Z", "program R and Z in the cycle block", out);
        return None;
    };
    // Under G91 (FANUC canned cycle rules) R is the distance from the initial level, the
    // drilling-axis position at the MCALL (`$P_EP[Z]`), and Z the distance from the R plane.
    let initial = || match &d.initial {
        Some(name) => named(name, span),
        None => var_expr(VarKind::Hash(5003), span),
    };
    let after_g99 = after_g99 && d.initial.is_none();
    if !d.g99 && after_g99 {
        refuse(ctx, span, "G98 after a G99 hole in one drilling cycle", "start the cycle again after G80", out);
        return None;
    }
    if d.r_inc && after_g99 {
        refuse(
            ctx,
            span,
            "new incremental cycle data (G91) after a G99 hole: the initial level they count from is not where the tool stands",
            "start the cycle again after G80, or program R and Z in G90",
            out,
        );
        return None;
    }
    let r = if d.r_inc { plus(initial(), r) } else { r };
    let z = if d.z_inc { plus(r.clone(), z) } else { z };
    let rtp = if d.g99 { r.clone() } else { initial() };
    let v = |e: Expr| Arg::Value(e);
    let none = || Arg::Omitted(span);
    let zero = || Arg::Value(int(0, span));
    let dtb = || match &d.p {
        Some(p) => match literal(p) {
            Some(ms) => Arg::Value(num(ms.round() / 1000.0, span)),
            None => Arg::Value(bin(BinOp::Div, p.clone(), int(1000, span))),
        },
        None => Arg::Value(int(0, span)),
    };
    let mut args = vec![v(rtp), v(r), zero(), v(z)];
    let name = match d.g {
        810 => "CYCLE81",
        820 => {
            args.extend([none(), dtb()]);
            "CYCLE82"
        }
        830 | 730 => {
            let Some(q) = d.q.clone() else {
                refuse(ctx, span, "G73/G83 without Q", "program the infeed Q", out);
                return None;
            };
            let vari = if d.g == 830 { 1 } else { 0 };
            args.extend([
                none(),
                none(),
                v(q),
                zero(),
                zero(),
                zero(),
                Arg::Value(int(1, span)),
                Arg::Value(int(vari, span)),
            ]);
            "CYCLE83"
        }
        850 => {
            let f = || var_expr(VarKind::Hash(4109), span);
            args.extend([none(), zero(), v(f()), v(f())]);
            "CYCLE85"
        }
        890 => {
            args.extend([none(), dtb()]);
            "CYCLE89"
        }
        880 => {
            // G88: dwell, spindle stop, program stop; CYCLE88 the same, SDIR the spindle's.
            match d.tap.spindle {
                Some(sdir @ (3 | 4)) => {
                    args.extend([none(), dtb(), v(int(i64::from(sdir), span))]);
                    "CYCLE88"
                }
                _ => {
                    refuse(
                        ctx,
                        span,
                        "boring G88 where the spindle is not known to turn",
                        "program M3 or M4 before the cycle: CYCLE88 needs its direction (SDIR)",
                        out,
                    );
                    return None;
                }
            }
        }
        840 | 740 if d.tap.rigid.is_some() && ctx.modal.inch_at(span.lo) != Some(false) => {
            // CYCLE84 takes the lead as PIT, whose unit under G70/G700 the sources at hand
            // do not settle (the Sinumerik run refuses it likewise).
            let what = "rigid tapping in inch (G20), or where G20/G21 is not known";
            out.extend(ctx.refuse(
                "NC591",
                span,
                &format!("{what}: not translated to Sinumerik"),
                what,
                "CYCLE84's pitch PIT under G70/G700 is not modelled: tap in G21, or translate this cycle by hand",
            ));
            return None;
        }
        840 | 740 => {
            let t = tapping::Tap { g: d.g, f: d.f.as_ref(), state: &d.tap };
            match tapping::call_args(&t, span) {
                Ok((name, rest)) => {
                    args.extend([none(), dtb()]);
                    args.extend(rest);
                    name
                }
                Err((code, what, hint)) => {
                    out.extend(ctx.refuse(code, span, &format!("{what}: not translated to Sinumerik"), &what, hint));
                    return None;
                }
            }
        }
        _ => return None,
    };
    let call = Call { kind, target: CallTarget::Name(name.into()), args, repeat: None };
    Some(Item { kind: ItemKind::Call(Box::new(call)), span })
}
