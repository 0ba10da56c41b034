//! FANUC → Sinumerik tool compensation: `G43 H` / `G49` and `G41/G42 D` / `G40` become the
//! cutting edge of the tool in the spindle (`D1`, `D0`) and `G41/G42/G40`, through the
//! offset map (`passes::crate::dialect::offsets::OffsetMap`; by default H n and D n are edge D1 of tool
//! n). A register is accepted where it provably belongs to the tool in the spindle: the
//! same number, or the same variable unchanged since the tool change (`T#33 M06` …
//! `G43 H#33`).
//!
//! A tool change becomes `T… M6 D0`: FANUC applies no length until the next G43 H, and
//! D0 keeps Sinumerik from taking the edge MD20270 chooses. Refused (NC471–NC474): a tool
//! change while G43 or G41/G42 is on (FANUC keeps the old register for the new tool,
//! Sinumerik takes the new tool's edge), an H or D that is not the tool's under the map,
//! G44, G41/G42 while G49 (a Siemens edge brings its length with its radius), D0 or a
//! register change under G41/G42. A call keeps the state where the called program (and
//! what it calls) has no tool or compensation word (`ProgPlan::tools`, the shared summary);
//! after any other call the next refusal names it (NC520), a G66 modal call of such a
//! program is NC521.

use super::*;
use crate::eval::trace::Side;
use crate::lower::comp_flow::{self, const_expr, FlowState, K};

/// A T, H or D value: a constant or a FANUC variable.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Val {
    Num(f64),
    Var(u32),
}

fn val(e: &Expr) -> Option<Val> {
    if let Some(v) = const_expr(e) {
        return Some(Val::Num(v));
    }
    match &e.kind {
        ExprKind::Var(v) => match v.kind {
            VarKind::Hash(n) => Some(Val::Var(n)),
            _ => None,
        },
        _ => None,
    }
}

/// What a program applies: the length register and the radius side and register.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Applied {
    len: Option<Val>,
    rad: Option<(Side, Val)>,
}

#[derive(Clone, Debug, PartialEq)]
struct St {
    sel: K<Option<Val>>,
    tool: K<Option<Val>>,
    /// FANUC group 08 (430, 440, 490), group 07 side, modal H and D.
    len_g: K<i64>,
    side: K<Option<Side>>,
    h: K<Val>,
    d: K<Val>,
    /// The FANUC trace state as last translated, and the Siemens edge written for it.
    applied: K<Applied>,
    edge: K<u32>,
    /// A tool change under G43 whose new length the next block selects: the tool change's
    /// span, the body (its address) and index of its translated block, which takes the edge.
    pending: Option<(Span, usize, usize, Span)>,
    /// The last call that made the state unknown (a program that may change the tool or
    /// the compensation, or one not in the job): its span and Siemens name, for the
    /// refusal that follows.
    call: Option<(Span, String)>,
}

impl FlowState for St {
    fn unknown() -> Self {
        St {
            sel: K::Unknown,
            tool: K::Unknown,
            len_g: K::Unknown,
            side: K::Unknown,
            h: K::Unknown,
            d: K::Unknown,
            applied: K::Unknown,
            edge: K::Unknown,
            pending: None,
            call: None,
        }
    }
    fn merge(&self, o: &Self) -> Self {
        St {
            sel: self.sel.merge(&o.sel),
            tool: self.tool.merge(&o.tool),
            len_g: self.len_g.merge(&o.len_g),
            side: self.side.merge(&o.side),
            h: self.h.merge(&o.h),
            d: self.d.merge(&o.d),
            applied: self.applied.merge(&o.applied),
            edge: self.edge.merge(&o.edge),
            pending: self.pending.or(o.pending),
            call: self.call.clone().or_else(|| o.call.clone()),
        }
    }
    fn watches_every_block(&self) -> bool {
        self.pending.is_some()
    }
}

const CODE: &str = "NC471";
const MAP_CODE: &str = "NC472";
const CHANGE_CODE: &str = "NC473";
const G44_CODE: &str = "NC474";
const CALL_CODE: &str = "NC520";
const MODAL_CALL_CODE: &str = "NC521";

/// Runs on the body of program `ctx.cur` (after `cycles::lower`, before `words::lower`).
pub fn lower(ctx: &mut Ctx, body: Vec<Stmt>) -> Vec<Stmt> {
    if !comp_flow::relevant(&body, true) {
        return body;
    }
    let mut st = if ctx.plan().role == Role::Main {
        let zero = Val::Num(0.0);
        St {
            sel: K::Known(None),
            tool: K::Known(None),
            len_g: K::Known(490),
            side: K::Known(None),
            h: K::Known(zero),
            d: K::Known(zero),
            applied: K::Known(Applied { len: None, rad: None }),
            edge: K::Known(0),
            pending: None,
            call: None,
        }
    } else {
        St::unknown()
    };
    let jumping = comp_flow::jumps(&body);
    let mut step = |st: &mut St, b: Block, live: bool, out: &mut Vec<Stmt>| block(ctx, st, b, live, out);
    let mut body = comp_flow::walk(body, &mut st, jumping, true, &mut step, true);
    if let Some((span, ..)) = st.pending {
        refuse_change(ctx, true, span, &mut body);
    }
    body
}

fn refuse_change(ctx: &mut Ctx, live: bool, span: Span, out: &mut Vec<Stmt>) {
    let msg = "a tool change while G43 H or G41/G42 is in force cannot be translated to Sinumerik";
    let hint = "FANUC keeps the old H and D for the new tool until the next G43 H / G41 D, Sinumerik takes the new \
                tool's edge at M6: select the new length (G43 H / G49) in the block right after the tool change, or \
                cancel with G49 (and G40) before it";
    refuse(ctx, live, CHANGE_CODE, span, msg, hint, out);
}

/// Whether a block only positions in the plane or sets the spindle, coolant, feed or the
/// work offset, with nothing that moves Z, reads a position, calls or touches the tool and
/// its compensation: between a tool change and its `G43 H` such blocks act alike whichever
/// length is selected.
fn keeps_z(b: &Block) -> bool {
    b.items.iter().all(|it| {
        let ItemKind::Word(w) = &it.kind else { return false };
        let WordValue::Expr(e) = &w.value else { return false };
        let Addr::Letter(l) = w.addr else { return false };
        match l {
            b'G' => const_expr(e).is_some_and(|g| {
                [0.0, 1.0, 17.0, 54.0, 55.0, 56.0, 57.0, 58.0, 59.0, 80.0, 90.0, 91.0, 94.0].contains(&g)
            }),
            b'M' => const_expr(e).is_some_and(|m| [3.0, 4.0, 5.0, 7.0, 8.0, 9.0].contains(&m)),
            b'X' | b'Y' | b'F' | b'S' => !reads_system(e),
            _ => false,
        }
    })
}

/// Whether an expression reads a system variable (`#1000` and up: positions among them).
fn reads_system(e: &Expr) -> bool {
    let mut stack = vec![e];
    while let Some(x) = stack.pop() {
        if matches!(&x.kind, ExprKind::Var(v) if !matches!(v.kind, VarKind::Hash(n) if n < 1000)) {
            return true;
        }
        stack.extend(x.children());
    }
    false
}

/// Whether a block only selects a length (G43 H / G49 / H, no tool change, no radius words).
fn length_only(b: &Block) -> bool {
    let mut length = false;
    for it in &b.items {
        if let ItemKind::Word(w) = &it.kind {
            let g = match &w.value {
                WordValue::Expr(e) => const_expr(e),
                _ => None,
            };
            match w.addr {
                Addr::Letter(b'H') => length = true,
                Addr::Letter(b'G') if matches!(g, Some(v) if v == 43.0 || v == 49.0) => length = true,
                Addr::Letter(b'G') if matches!(g, Some(v) if (40.0..50.0).contains(&v)) => return false,
                Addr::Letter(b'D' | b'T') => return false,
                Addr::Letter(b'M') if g == Some(6.0) => return false,
                _ => {}
            }
        }
    }
    length
}

fn refuse(ctx: &mut Ctx, live: bool, code: &'static str, span: Span, msg: &str, hint: &str, out: &mut Vec<Stmt>) {
    if live {
        let what = msg.trim_end_matches(" cannot be translated to Sinumerik");
        out.extend(ctx.refuse(code, span, msg, what, hint));
    }
}

fn word(letter: u8, v: f64, span: Span) -> Item {
    Item { kind: ItemKind::Word(Word { addr: Addr::Letter(letter), value: WordValue::Expr(num(v, span)), span }), span }
}

/// A write to FANUC variable `n` forgets every value read from it.
fn forget(st: &mut St, n: u32) {
    let hit = |v: &Val| *v == Val::Var(n);
    if st.sel.known().is_some_and(|v| v.as_ref().is_some_and(hit)) {
        st.sel = K::Unknown;
    }
    if st.tool.known().is_some_and(|v| v.as_ref().is_some_and(hit)) {
        st.tool = K::Unknown;
    }
    for x in [&mut st.h, &mut st.d] {
        if x.known().is_some_and(hit) {
            *x = K::Unknown;
        }
    }
    if let K::Known(a) = &st.applied {
        if a.len.as_ref().is_some_and(hit) || a.rad.as_ref().is_some_and(|r| hit(&r.1)) {
            st.applied = K::Unknown;
        }
    }
}

/// What the calls of a block do to the tool and the compensation.
enum Calls {
    None,
    /// Every call is of a program that touches neither, or a drilling cycle.
    Keep,
    /// A call (span, name) of a program that may change them or that is not in the job;
    /// `modal`: a G66 modal call (`MCALL`), run again after every move.
    Change(Span, String, bool),
}

fn calls_of(ctx: &Ctx, b: &Block) -> Calls {
    let mut calls = Calls::None;
    for it in &b.items {
        let ItemKind::Call(c) = &it.kind else { continue };
        let harmless = match &c.target {
            CallTarget::Name(n) if crate::dialect::sinumerik::cycles::cycle_of(&n.to_ascii_uppercase()).is_some() => {
                true
            }
            // The high-speed settings a Haas G187 or a FANUC G05.1 became (lookahead.rs):
            // CYCLE832 sets the path dynamics, never the tool or its edge.
            CallTarget::Name(n) if n.eq_ignore_ascii_case("CYCLE832") => true,
            CallTarget::Name(n) => ctx.progs.iter().any(|p| p.name.eq_ignore_ascii_case(n) && !p.tools),
            _ => false,
        };
        if harmless {
            if matches!(calls, Calls::None) {
                calls = Calls::Keep;
            }
        } else {
            let name = match &c.target {
                // The FANUC program the Siemens call stands for.
                CallTarget::Name(n) => match ctx.progs.iter().find(|p| p.name.eq_ignore_ascii_case(n)) {
                    Some(ProgPlan { number: Some(o), .. }) => format!("O{o}"),
                    _ => n.clone(),
                },
                CallTarget::Number(n) => format!("O{n:04}"),
                CallTarget::Computed(_) => "a computed program".into(),
            };
            return Calls::Change(it.span, name, c.kind == CallKind::Mcall);
        }
    }
    calls
}

/// A block, and after it what its calls do: a call of a program that keeps the tool and
/// the compensation keeps the state but for the values read from variables (an M98
/// subprogram shares the caller's locals, any program the common variables); any other
/// call leaves nothing known.
fn block(ctx: &mut Ctx, st: &mut St, b: Block, live: bool, out: &mut Vec<Stmt>) {
    let calls = calls_of(ctx, &b);
    if let Calls::Change(span, name, true) = &calls {
        let msg = format!(
            "a G66 modal call of {name}, which may change the tool or the compensation, in a program with tool \
             compensation cannot be translated to Sinumerik"
        );
        let hint = "the call runs again after every move, where the translation cannot follow the tool and its \
                    edge: take the tool and compensation words out of the macro, or call it with G65";
        refuse(ctx, live, MODAL_CALL_CODE, *span, &msg, hint, out);
    }
    block_words(ctx, st, b, live, out);
    if st.tool.known().is_some() && st.applied.known().is_some() {
        st.call = None;
    }
    match calls {
        Calls::None => {}
        Calls::Keep => forget_vars(st),
        Calls::Change(span, name, _) => {
            let pending = st.pending.take();
            *st = St::unknown();
            st.pending = pending;
            st.call = Some((span, name));
        }
    }
}

/// Forgets every value read from a variable (a call may write any).
fn forget_vars(st: &mut St) {
    let mut vars = Vec::new();
    let mut note = |v: Option<&Val>| {
        if let Some(Val::Var(n)) = v {
            vars.push(*n);
        }
    };
    note(st.sel.known().and_then(Option::as_ref));
    note(st.tool.known().and_then(Option::as_ref));
    note(st.h.known());
    note(st.d.known());
    if let K::Known(a) = &st.applied {
        note(a.len.as_ref());
        note(a.rad.as_ref().map(|r| &r.1));
    }
    for n in vars {
        forget(st, n);
    }
}

/// When the state is unknown because of a call (`St::call`): the refusal names the call,
/// NC520, instead of the general one. Returns whether it reported.
fn refuse_after_call(ctx: &mut Ctx, st: &St, live: bool, span: Span, what: &str, out: &mut Vec<Stmt>) -> bool {
    let Some((call, name)) = st.call.clone() else { return false };
    let msg = format!("{what} after the call of {name} cannot be translated to Sinumerik");
    let hint = format!(
        "{name} (or a program it calls) may change the tool or the compensation, or is not in the job: select \
         the tool and its compensation again after the call (T… M06, G43 H…, G41 D…), or take the tool and \
         compensation words out of {name}"
    );
    let before = ctx.diags.len();
    refuse(ctx, live, CALL_CODE, span, &msg, &hint, out);
    if ctx.diags.len() > before {
        let file = ctx.file();
        if let Some(d) = ctx.diags.pop() {
            ctx.diags.push(d.secondary(file, call, "this call may change the tool or the compensation"));
        }
    }
    true
}

fn block_words(ctx: &mut Ctx, st: &mut St, b: Block, live: bool, out: &mut Vec<Stmt>) {
    let span = b.meta.span;
    if let Some((pspan, addr, idx, bspan)) = st.pending {
        if b.items.is_empty() {
            out.push(Stmt { span, kind: StmtKind::Block(b) });
            return;
        }
        let here = out as *const Vec<Stmt> as usize == addr && out.get(idx).is_some_and(|s| s.span == bspan);
        if here && keeps_z(&b) {
            // Positioning in XY before the new length (`G54`, `M8`, `G0 X.. Y..`): the old
            // H on FANUC, the new edge on Sinumerik, and Z does not move under either. The
            // check compares the length where Z first moves (`check::DeferLength`).
            out.push(Stmt { span, kind: StmtKind::Block(b) });
            return;
        }
        st.pending = None;
        if here && length_only(&b) {
            return after_change(ctx, st, b, live, out, idx, pspan);
        }
        refuse_change(ctx, live, pspan, out);
    }
    for it in &b.items {
        if let ItemKind::Assign { target, .. } = &it.kind {
            match target.kind {
                VarKind::Hash(n) => forget(st, n),
                // Any FANUC variable. The other targets are the translation's own (is-set
                // flags, `$P_UIFR` of a G10), which hold no T, H or D.
                VarKind::HashIndirect(_) => *st = St::unknown(),
                _ => {}
            }
        }
    }
    if !comp_flow::relevant_items(&b.items, true) {
        out.push(Stmt { span, kind: StmtKind::Block(b) });
        return;
    }
    let mut m6 = None;
    let mut g_rad = None;
    let mut g44 = false;
    for it in &b.items {
        let ItemKind::Word(w) = &it.kind else { continue };
        let WordValue::Expr(e) = &w.value else { continue };
        let Addr::Letter(l) = w.addr else { continue };
        match l {
            b'T' => st.sel = val(e).map_or(K::Unknown, |v| K::Known(Some(v))),
            b'M' if const_expr(e) == Some(6.0) => m6 = Some(w.span),
            b'H' => st.h = val(e).map_or(K::Unknown, K::Known),
            b'D' => st.d = val(e).map_or(K::Unknown, K::Known),
            b'G' => match const_expr(e).map(|g| (g * 10.0).round() as i64) {
                Some(430 | 490) => st.len_g = K::Known((const_expr(e).unwrap_or(0.0) * 10.0).round() as i64),
                Some(440) => {
                    let msg = "G44 (negative tool length offset) cannot be translated to Sinumerik";
                    refuse(
                        ctx,
                        live,
                        G44_CODE,
                        w.span,
                        msg,
                        "Sinumerik adds the edge's length; use G43 with a negated offset",
                        out,
                    );
                    st.len_g = K::Unknown;
                    g44 = true;
                }
                Some(400) => {
                    st.side = K::Known(None);
                    g_rad = Some(w.span);
                }
                Some(410) => {
                    st.side = K::Known(Some(Side::Left));
                    g_rad = Some(w.span);
                }
                Some(420) => {
                    st.side = K::Known(Some(Side::Right));
                    g_rad = Some(w.span);
                }
                _ => {}
            },
            _ => {}
        }
    }
    let touches = b.items.iter().any(|it| {
        matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'H') || w.addr.is(b'D')
            || (w.addr.is(b'G') && matches!(&w.value, WordValue::Expr(e) if const_expr(e).is_some_and(|g| (40.0..50.0).contains(&g)))))
    });
    if m6.is_none() && !touches {
        // A tool selection alone changes nothing the trace sees.
        out.push(Stmt { span, kind: StmtKind::Block(b) });
        return;
    }
    let mut add: Vec<Item> = Vec::new();
    let mut refused = g44;
    if let Some(ms) = m6 {
        let length_on = matches!(st.applied, K::Known(Applied { len: Some(_), rad: None }));
        if length_on && !touches {
            // FANUC keeps the old H until the next block selects the new one: the edge goes
            // into this block once that block is seen.
            st.tool = st.sel.clone();
            finish(b, add, live, out);
            if out.last().is_some_and(|s| s.span == span) {
                st.pending = Some((ms, out as *const Vec<Stmt> as usize, out.len() - 1, span));
            }
            return;
        }
        let on = |a: &K<Applied>| !matches!(a, K::Known(Applied { len: None, rad: None }));
        if on(&st.applied) {
            if st.applied != K::Unknown || !refuse_after_call(ctx, st, live, ms, "a tool change", out) {
                refuse_change(ctx, live, ms, out);
            }
            refused = true;
        }
        st.tool = st.sel.clone();
        // No length until the next G43 H, as on FANUC (MD20270 would select an edge).
        add.push(word(b'D', 0.0, ms));
        st.edge = K::Known(0);
    }
    // What FANUC applies after the block.
    // G49 and G40 are off whatever H and D are (a subprogram's safety line knows them).
    let zero = |v: &Val| *v == Val::Num(0.0);
    let len = match (&st.len_g, &st.h) {
        (K::Known(490), _) => Some(None),
        (K::Known(g), K::Known(h)) => Some((*g == 430 && !zero(h)).then_some(*h)),
        _ => None,
    };
    let rad = match (&st.side, &st.d) {
        (K::Known(None), _) => Some(None),
        (K::Known(Some(s)), K::Known(d)) => Some((!zero(d)).then_some((*s, *d))),
        _ => None,
    };
    let target = len.zip(rad).map(|(len, rad)| Applied { len, rad });
    let Some(tg) = target else {
        if g44 {
            st.applied = K::Unknown;
            finish(b, add, live, out);
            return;
        }
        if !refuse_after_call(ctx, st, live, span, "tool compensation", out) {
            let msg = "tool compensation where the G43/G49, G40/G41/G42 or H/D in force depends on the path taken or \
                       on a call cannot be translated to Sinumerik";
            let hint = "program G43 H / G49 and G41 D / G40 on every path before this block";
            refuse(ctx, live, CODE, span, msg, hint, out);
        }
        st.applied = K::Unknown;
        finish(b, add, live, out);
        return;
    };
    if refused {
        // Reported once for the block.
        st.applied = K::Known(tg);
        finish(b, add, live, out);
        return;
    }
    let prev = if m6.is_some() { Some(Applied { len: None, rad: None }) } else { st.applied.known().copied() };
    if prev.map(|p| p.len) != Some(tg.len) {
        if prev.is_some_and(|p| p.rad.is_some()) {
            let msg = "a change of G43 H / G49 under G41/G42 cannot be translated to Sinumerik";
            refuse(
                ctx,
                live,
                CODE,
                span,
                msg,
                "change the length compensation with G40 in force: a Siemens edge carries length and radius together",
                out,
            );
        }
        match tg.len {
            None => {
                add.push(word(b'D', 0.0, span));
                st.edge = K::Known(0);
            }
            Some(h) => match edge_of(ctx, st, h) {
                Ok(e) => {
                    add.push(word(b'D', f64::from(e), span));
                    st.edge = K::Known(e);
                }
                Err(msg) => {
                    if st.tool != K::Unknown || !refuse_after_call(ctx, st, live, span, "G43 H", out) {
                        refuse(ctx, live, MAP_CODE, span, &msg, &map_hint(st), out);
                    }
                    st.edge = K::Unknown;
                }
            },
        }
    }
    if prev.map(|p| p.rad) != Some(tg.rad) {
        match (prev.and_then(|p| p.rad), tg.rad) {
            (_, None) if g_rad.is_some() => {}
            (None, None) => {}
            (_, None) => {
                let msg = "D0 under G41/G42 cannot be translated to Sinumerik";
                refuse(ctx, live, CODE, span, msg, "cancel radius compensation with G40", out);
            }
            (Some((_, d1)), Some((_, d2))) if d1 != d2 => {
                let msg = "a change of the radius register D under G41/G42 cannot be translated to Sinumerik";
                refuse(ctx, live, CODE, span, msg, "cancel radius compensation with G40 first", out);
            }
            (_, Some((_, d))) => {
                let ok = match (&st.edge, st.tool.known()) {
                    (K::Known(0), _) => Err("G41/G42 while G49 cannot be translated to Sinumerik: its edge would bring a length".to_string()),
                    (K::Known(e), Some(Some(t))) => match (t, d) {
                        (Val::Num(t), Val::Num(dv)) => match ctx.opts.source.offsets.registers(*t as u32, *e) {
                            Some((_, rd)) if f64::from(rd) == dv => Ok(()),
                            _ => Err(format!("radius register D{} is not the one of edge D{e} of tool {t} under the offset map", dv)),
                        },
                        (t, d) if *t == d && *e == 1 => Ok(()),
                        _ => Err("a radius register D that is not provably the one of the tool in the spindle cannot be translated to Sinumerik".to_string()),
                    },
                    _ => Err("G41/G42 where the tool or its edge is not known cannot be translated to Sinumerik".to_string()),
                };
                let unknown = st.edge == K::Unknown || st.tool == K::Unknown;
                if let Err(msg) = ok {
                    if !unknown || !refuse_after_call(ctx, st, live, span, "G41/G42 D", out) {
                        refuse(ctx, live, MAP_CODE, span, &msg, &map_hint(st), out);
                    }
                }
                if g_rad.is_none() {
                    let msg = "radius compensation that starts without G41/G42 in the block cannot be translated to Sinumerik";
                    refuse(ctx, live, CODE, span, msg, "write G41/G42 with the D word", out);
                }
            }
        }
    }
    st.applied = K::Known(tg);
    finish(b, add, live, out);
}

/// The block after a tool change under G43 that selects the new length: the edge goes into
/// the tool change's block (`out[at]`), where Sinumerik changes it, and nothing in between
/// made an event.
fn after_change(ctx: &mut Ctx, st: &mut St, b: Block, live: bool, out: &mut Vec<Stmt>, at: usize, m6: Span) {
    for it in &b.items {
        let ItemKind::Word(w) = &it.kind else { continue };
        let WordValue::Expr(e) = &w.value else { continue };
        match w.addr {
            Addr::Letter(b'H') => st.h = val(e).map_or(K::Unknown, K::Known),
            Addr::Letter(b'G') if const_expr(e) == Some(43.0) => st.len_g = K::Known(430),
            Addr::Letter(b'G') if const_expr(e) == Some(49.0) => st.len_g = K::Known(490),
            _ => {}
        }
    }
    let len = match (&st.len_g, &st.h) {
        (K::Known(430), K::Known(h)) if *h != Val::Num(0.0) => Some(*h),
        (K::Known(_), K::Known(_)) => None,
        _ => {
            if !refuse_after_call(ctx, st, live, m6, "a tool change", out) {
                refuse_change(ctx, live, m6, out);
            }
            st.applied = K::Unknown;
            return finish(b, vec![], live, out);
        }
    };
    let edge = match len {
        None => Ok(0),
        Some(h) => edge_of(ctx, st, h),
    };
    match edge {
        Ok(e) => {
            if live {
                if let Some(Stmt { kind: StmtKind::Block(tb), .. }) = out.get_mut(at) {
                    let pos = tb
                        .items
                        .iter()
                        .rposition(|it| matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'M') || w.addr.is(b'T')))
                        .map_or(tb.items.len(), |i| i + 1);
                    tb.items.insert(pos, word(b'D', f64::from(e), m6));
                }
            }
            st.edge = K::Known(e);
        }
        Err(msg) => {
            if st.tool != K::Unknown || !refuse_after_call(ctx, st, live, b.meta.span, "G43 H", out) {
                refuse(ctx, live, MAP_CODE, b.meta.span, &msg, &map_hint(st), out);
            }
            st.edge = K::Unknown;
        }
    }
    st.applied = K::Known(Applied { len, rad: None });
    finish(b, vec![], live, out);
}

/// The block without its H, D, G43 and G49 words, with the Siemens edge words.
fn finish(mut b: Block, add: Vec<Item>, live: bool, out: &mut Vec<Stmt>) {
    if !live {
        return;
    }
    b.items.retain(|it| match &it.kind {
        ItemKind::Word(w) if w.addr.is(b'H') || w.addr.is(b'D') => false,
        ItemKind::Word(w) if w.addr.is(b'G') => {
            !matches!(&w.value, WordValue::Expr(e) if matches!(const_expr(e), Some(g) if g == 43.0 || g == 49.0))
        }
        _ => true,
    });
    // The last edge word wins (a tool change's D0, then the G43's edge).
    let last = add.last().cloned();
    if let Some(d) = last {
        // After the tool change (`T6 M6 D0`), else after the G codes (`G0 D1 Z50`).
        let m6 = b.items.iter().any(|it| matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'M') && matches!(&w.value, WordValue::Expr(e) if const_expr(e) == Some(6.0))));
        let after = |w: &Word| w.addr.is(b'G') || (m6 && (w.addr.is(b'T') || w.addr.is(b'M')));
        let at = b.items.iter().rposition(|it| matches!(&it.kind, ItemKind::Word(w) if after(w))).map_or(0, |i| i + 1);
        b.items.insert(at.min(b.items.len()), d);
    }
    let span = b.meta.span;
    if !b.items.is_empty() || crate::lower::meta_is_marked(&b.meta) {
        out.push(Stmt { span, kind: StmtKind::Block(b) });
    }
}

fn map_hint(st: &St) -> String {
    let tool = match st.tool.known() {
        Some(Some(Val::Num(t))) => format!("{t}"),
        Some(None) => {
            return "change the tool (T… M06) in this program before G43 H / G41 D: the register is the tool's".into()
        }
        _ => "n".into(),
    };
    format!(
        "by default H n and D n are edge D1 of tool n (here tool {tool}); name other registers under [offsets] in \
         nctrans.toml (`\"{tool}.2\" = \"H…,D…\"`)"
    )
}

/// The edge of the tool in the spindle whose length register is `h`.
fn edge_of(ctx: &Ctx, st: &St, h: Val) -> Result<u32, String> {
    match st.tool.known() {
        Some(Some(Val::Num(t))) => match h {
            Val::Num(hv) if hv.fract() == 0.0 && hv > 0.0 => ctx
                .opts
                .source
                .offsets
                .edge_of_h(*t as u32, hv as u32)
                .ok_or_else(|| format!("H{hv} is not a length register of tool {t} under the offset map")),
            _ => Err(format!("a computed H is not provably a length register of tool {t}")),
        },
        Some(Some(t)) if *t == h => Ok(1),
        Some(Some(_)) => Err("an H that is not provably the tool's (the same variable as its T) cannot be translated to Sinumerik".into()),
        Some(None) => Err("G43 H without a tool in the spindle (no M06 before it) cannot be translated to Sinumerik".into()),
        None => Err("G43 H where the tool in the spindle depends on the path taken or on a call cannot be translated to Sinumerik".into()),
    }
}
