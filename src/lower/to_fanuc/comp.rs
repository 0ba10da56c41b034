//! Sinumerik → FANUC tool compensation: cutting edges (`D`, a tool change's edge) and
//! `G40/G41/G42` become `G43 H` / `G49` and `G41/G42 D` with the registers of the offset
//! map ([`crate::dialect::offsets::OffsetMap`]; by default edge D1 of tool n is H n and D n).
//!
//! The FANUC words go into the block where the Siemens state changes, so both traces make
//! their `comp` event at the same place (after a tool change, before the block's motion):
//! `D1 G0 Z50` → `G43 H6 G0 Z50.`; a tool change `T6 M6 D1` → `T6 M6` and `G43 H6` in the
//! next line. A tool change without D takes the edge machine data MD20270 chooses: it is
//! translated only when the next block selects the edge itself (`T6 M6` / `D1 …`), so the
//! machine data does not matter. Refused (NC470–NC473): an edge without a known tool, an
//! edge the map gives no registers for, a tool change or `D` change while G41/G42 is on,
//! `D0` under G41/G42, G41/G42 without an edge.
//!
//! A D between a tool's preselection `T1` and its `M6` selects an edge of the tool still in
//! the spindle, which the tool change then replaces with the edge MD20270 chooses (W1
//! §2.1): `T1 D1` / `M6` is translated `T1` / `M06` / `G43 H1` where the profile states
//! MD20270 and it chooses that same edge, and only blocks that cannot show a length
//! (S, F, T, M3/M4/M5, coolant) stand between; otherwise NC567 (a block that may move the
//! old tool's edge) or NC568 (the tool change selects another edge).

use super::*;
use crate::eval::trace::Side;
use crate::lower::comp_flow::{self, const_word, FlowState, K};

/// What the FANUC program applies: the H register (length) and the radius side and D.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Applied {
    len: Option<u32>,
    rad: Option<(Side, u32)>,
}

#[derive(Clone, Debug, PartialEq)]
struct St {
    /// The tool selected by T and the tool in the spindle (`None`: no tool).
    sel: K<Option<u32>>,
    tool: K<Option<u32>>,
    /// The Siemens edge (0: D0) and radius side.
    edge: K<u32>,
    side: K<Option<Side>>,
    /// What the FANUC translation applies so far.
    fanuc: K<Applied>,
    /// A tool change without D whose edge the next block must select (its span, and the
    /// edge of a D programmed before it).
    pending: Option<(Span, Option<u32>)>,
    /// A D programmed after a preselection T and before its M6: its edge and span.
    held: Option<(u32, Span)>,
}

impl FlowState for St {
    fn unknown() -> Self {
        St {
            sel: K::Unknown,
            tool: K::Unknown,
            edge: K::Unknown,
            side: K::Unknown,
            fanuc: K::Unknown,
            pending: None,
            held: None,
        }
    }
    fn merge(&self, o: &Self) -> Self {
        St {
            sel: self.sel.merge(&o.sel),
            tool: self.tool.merge(&o.tool),
            edge: self.edge.merge(&o.edge),
            side: self.side.merge(&o.side),
            fanuc: self.fanuc.merge(&o.fanuc),
            pending: self.pending.or(o.pending),
            held: self.held.or(o.held),
        }
    }
}

const CODE: &str = "NC470";
const MAP_CODE: &str = "NC472";
const CHANGE_CODE: &str = "NC473";
const HELD_CODE: &str = "NC567";
const HELD_EDGE_CODE: &str = "NC568";

/// Runs on one program after the words pass (T numbers are FANUC numbers by then).
pub fn run(ctx: &mut Ctx, prog: &mut Program, info: &ProgInfo) {
    if !comp_flow::relevant(&prog.body, false) {
        return;
    }
    let mut st = if info.is_sub {
        St::unknown()
    } else {
        St {
            sel: K::Known(None),
            tool: K::Known(None),
            edge: K::Known(0),
            side: K::Known(None),
            fanuc: K::Known(Applied { len: None, rad: None }),
            pending: None,
            held: None,
        }
    };
    let jumping = comp_flow::jumps(&prog.body);
    let body = std::mem::take(&mut prog.body);
    let mut step = |st: &mut St, b: Block, live: bool, out: &mut Vec<Stmt>| block(ctx, st, b, live, out);
    prog.body = comp_flow::walk(body, &mut st, jumping, false, &mut step, true);
    if let Some((span, before)) = st.pending {
        refuse_pending(ctx, span, before, true);
    }
}

fn refuse_pending(ctx: &mut Ctx, span: Span, before: Option<u32>, live: bool) {
    if live {
        let msg = match before {
            Some(e) => format!(
                "a tool change without D cannot be translated: the edge it selects is machine data (MD20270); the \
                 D{e} before it is an edge of the tool still in the spindle (840D sl W1 §2.1), not of the new tool"
            ),
            None => {
                "a tool change without D cannot be translated: the edge it selects is machine data (MD20270)".into()
            }
        };
        ctx.error(
            CODE,
            span,
            &msg,
            "program the edge in the tool change block (`T6 M6 D1`) or as the next block (`D1`), or state the \
             machine's MD20270 in nctrans.toml (`[sinumerik] cutting_edge_default = 1`)",
        );
        ctx.unsupported += 1;
    }
}

fn refuse(ctx: &mut Ctx, live: bool, code: &'static str, span: Span, msg: &str, hint: &str) {
    if live {
        ctx.error(code, span, msg, hint);
        ctx.unsupported += 1;
    }
}

fn word(letter: u8, v: f64, span: Span) -> Item {
    item(ItemKind::Word(Word { addr: Addr::Letter(letter), value: WordValue::Expr(num(v, span)), span }), span)
}

fn block(ctx: &mut Ctx, st: &mut St, mut b: Block, live: bool, out: &mut Vec<Stmt>) {
    let span = b.meta.span;
    let relevant = comp_flow::relevant_items(&b.items, false);
    if live
        && b.items
            .iter()
            .any(|it| matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'G') && const_word(w) == Some(31.0)))
    {
        // The length a kept Z measurement takes off (`probe_length`): what FANUC applies in
        // the G31 block, known only where the block changes nothing of it.
        let applied =
            if relevant || st.held.is_some() || st.pending.is_some() { None } else { st.fanuc.known().map(|a| a.len) };
        ctx.skip_lengths.push((span, applied));
    }
    let has_content = !b.items.is_empty();
    if let Some((_, hs)) = st.held {
        let m6_here = b
            .items
            .iter()
            .any(|it| matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'M') && const_word(w) == Some(6.0)));
        if !m6_here && !cannot_show_length(&b) {
            let msg = "a cutting edge D programmed before the tool change (M6) selects an edge of the tool still in \
                       the spindle (840D sl W1 §2.1: D activates an edge \"on the active tool\"), and a block that may \
                       move it comes before the M6";
            refuse(ctx, live, HELD_CODE, hs, msg, "program the D after the M6 (`M6` / `D1`) or in its block (`M6 D1`)");
            st.held = None;
            st.edge = K::Unknown;
        }
    }
    if let Some((p, before)) = st.pending {
        let has_d = b.items.iter().any(|it| matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'D')));
        if !has_d && has_content {
            refuse_pending(ctx, p, before, live);
            // Reported once: FANUC still applies what it did before the tool change.
            st.pending = None;
        }
    }
    if !relevant {
        if b.items.iter().any(|it| matches!(it.kind, ItemKind::Call(_))) && !is_cycle_call(&b) && !calls_only(&b, ctx) {
            // A subprogram may change the tool or the compensation.
            *st = St::unknown();
        }
        out.push(meta_stmt(b.meta, b.items));
        return;
    }
    let (mut t, mut m6, mut d, mut g) = (None, None, None, None);
    for it in &b.items {
        let ItemKind::Word(w) = &it.kind else { continue };
        match w.addr {
            Addr::Letter(b'T') => t = Some((const_word(w), w.span)),
            Addr::Letter(b'M') if const_word(w) == Some(6.0) => m6 = Some(w.span),
            Addr::Letter(b'D') => d = Some((const_word(w), w.span)),
            Addr::Letter(b'G') => match const_word(w) {
                Some(40.0) => g = Some((None, w.span)),
                Some(41.0) => g = Some((Some(Side::Left), w.span)),
                Some(42.0) => g = Some((Some(Side::Right), w.span)),
                _ => {}
            },
            _ => {}
        }
    }
    if let Some((v, _)) = t {
        st.sel = match v {
            Some(v) if v >= 0.0 && v.fract() == 0.0 => K::Known(Some(v as u32)),
            _ => K::Unknown,
        };
    }
    let d_val = match d {
        Some((Some(v), _)) if v >= 0.0 && v.fract() == 0.0 => Some(v as u32),
        Some((_, s)) => {
            refuse(ctx, live, CODE, s, "a computed cutting edge D cannot be translated", "write the edge as a number");
            st.edge = K::Unknown;
            None
        }
        None => None,
    };
    let preselected = matches!((&st.sel, &st.tool), (K::Known(a), K::Known(b)) if a != b);
    if let (true, None, None, Some(e), Some((_, ds)), true) = (preselected, m6, g, d_val, d, cannot_show_length(&b)) {
        // The edge of the tool in the spindle, replaced by the M6 before anything shows it
        // (checked in the blocks up to the M6): FANUC has nothing to write for it.
        st.held = Some((e, ds));
        if live {
            b.items.retain(|it| !matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'D')));
            if !b.items.is_empty() || meta_is_marked(&b.meta) {
                out.push(meta_stmt(b.meta, b.items));
            }
        }
        return;
    }
    let mut pending_now = None;
    let mut refused = false;
    if let Some(ms) = m6 {
        if !matches!(st.side, K::Known(None)) && !matches!(g, Some((None, _))) {
            let msg = "a tool change during cutter radius compensation (G41/G42) cannot be translated";
            refuse(ctx, live, CHANGE_CODE, ms, msg, "cancel it with G40 before the tool change");
            refused = true;
        }
        st.tool = st.sel.clone();
        let held = st.held.take();
        if let (Some((he, hs)), None, Some(e)) = (held, d, ctx.edge_default) {
            if he != e {
                let msg = format!(
                    "the edge D{he} programmed before the tool change is not the edge the tool change selects (D{e}, \
                     the profile's MD20270): D before M6 is an edge of the tool still in the spindle (840D sl W1 §2.1)"
                );
                refuse(
                    ctx,
                    live,
                    HELD_EDGE_CODE,
                    hs,
                    &msg,
                    &format!("program D{he} after the M6 or in its block (`M6 D{he}`)"),
                );
            }
        }
        match d_val {
            Some(e) => st.edge = K::Known(e),
            None if d.is_none() => match ctx.edge_default {
                // The profile states the machine's MD20270.
                Some(e) => st.edge = K::Known(e),
                None => {
                    st.edge = K::Known(crate::eval::machine::comp::CUTTING_EDGE_DEFAULT);
                    pending_now = Some((ms, held.map(|h| h.0)));
                }
            },
            None => {}
        }
    } else if let Some(e) = d_val {
        st.edge = K::Known(e);
    }
    if let Some((side, _)) = g {
        st.side = K::Known(side);
    }
    if m6.is_none() && d.is_none() && g.is_none() {
        // A tool selection alone changes nothing the trace sees.
        out.push(meta_stmt(b.meta, b.items));
        return;
    }
    if m6.is_none() && d.is_none() && matches!(g, Some((None, _))) && st.edge == K::Unknown {
        // G40 where the edge is not known (a subprogram's safety line): FANUC G40 is off
        // whatever the registers; the length stays as unknown as it was.
        if let K::Known(a) = &mut st.fanuc {
            a.rad = None;
        }
        out.push(meta_stmt(b.meta, b.items));
        return;
    }
    // The FANUC state the Siemens one stands for.
    let target = target(ctx, st, &b, live);
    let before = st.fanuc.clone();
    let mut add: Vec<Item> = Vec::new();
    if let (Some(tg), None) = (target, pending_now) {
        let prev = before.known().copied();
        if prev.map(|p| p.len) != Some(tg.len) {
            match tg.len {
                Some(h) => {
                    add.push(word(b'G', 43.0, span));
                    add.push(word(b'H', f64::from(h), span));
                }
                None => add.push(word(b'G', 49.0, span)),
            }
        }
        if prev.map(|p| p.rad) != Some(tg.rad) && !refused {
            match (prev.and_then(|p| p.rad), tg.rad) {
                (_, None) if matches!(g, Some((None, _))) => {}
                (_, None) if prev.is_some_and(|p| p.rad.is_none()) => {}
                (_, None) => {
                    // Unknown before (an edge that was refused, a path or call that decides
                    // it): say so rather than claim G41/G42 is on.
                    let msg = if prev.is_some() {
                        "switching the cutting edge off (D0, a tool change) under G41/G42 cannot be translated"
                    } else {
                        "switching the cutting edge off (D0, a tool change) where G41/G42 may be in force (the \
                         compensation before is not known) cannot be translated"
                    };
                    refuse(ctx, live, CODE, d.map_or(span, |x| x.1), msg, "cancel radius compensation with G40 first");
                }
                (Some((_, d1)), Some((_, d2))) if d1 != d2 => {
                    let msg = "changing the cutting edge under G41/G42 cannot be translated";
                    refuse(ctx, live, CODE, d.map_or(span, |x| x.1), msg, "cancel radius compensation with G40 first");
                }
                (_, Some((_, dr))) if g.is_some() => add.push(word(b'D', f64::from(dr), span)),
                (_, Some(_)) => {
                    let msg = "radius compensation that starts without G41/G42 in the block cannot be translated";
                    refuse(ctx, live, CODE, span, msg, "write G41/G42 in the block that selects the edge");
                }
            }
        }
        st.fanuc = K::Known(tg);
    } else if pending_now.is_none() {
        st.fanuc = K::Unknown;
    }
    st.pending = pending_now;
    if !live {
        return;
    }
    // The Siemens D words go (FANUC D is a radius register); the FANUC words take their place.
    b.items.retain(|it| !matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'D')));
    if add.is_empty() {
        if !b.items.is_empty() || meta_is_marked(&b.meta) {
            out.push(meta_stmt(b.meta, b.items));
        }
        return;
    }
    // A tool change alone: the compensation in a line of its own after it (same order of
    // events; the control does not take G43 with the tool change).
    let alone = m6.is_some()
        && b.items.iter().all(|it| matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'T') || w.addr.is(b'M')));
    if alone {
        out.push(meta_stmt(b.meta, b.items));
        out.push(block_stmt(add, span));
        return;
    }
    let at =
        b.items.iter().rposition(|it| matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'G'))).map_or(0, |i| i + 1);
    b.items.splice(at..at, add);
    out.push(meta_stmt(b.meta, b.items));
}

/// Whether `b` holds only words that change no tool length the trace could show: S, F,
/// T, D, M3/M4/M5 and coolant (they make `spindle` and `coolant` events, which the Siemens
/// run lets a held edge pass, `Machine::release_held`; a D there is held in its turn).
fn cannot_show_length(b: &Block) -> bool {
    b.items.iter().all(|it| match &it.kind {
        ItemKind::Word(w) => match w.addr {
            Addr::Letter(b'S' | b'F' | b'T' | b'D') => true,
            Addr::Letter(b'M') => matches!(const_word(w), Some(x) if [3.0, 4.0, 5.0, 7.0, 8.0, 9.0].contains(&x)),
            _ => false,
        },
        _ => false,
    })
}

/// Whether every call of `b` is of a translated program that changes neither the tool nor
/// the compensation (`Effect::tools`), by name or, after the words pass, by its O number.
fn calls_only(b: &Block, ctx: &Ctx) -> bool {
    let keeps = |c: &Callee| !c.effect.tools;
    b.items.iter().all(|it| match &it.kind {
        ItemKind::Call(c) => match &c.target {
            CallTarget::Name(n) => ctx.callees.get(&n.to_ascii_uppercase()).is_some_and(keeps),
            CallTarget::Number(o) => ctx.callees.values().any(|c| c.number == *o && keeps(c)),
            CallTarget::Computed(_) => false,
        },
        _ => true,
    })
}

fn is_cycle_call(b: &Block) -> bool {
    b.items.iter().all(|it| match &it.kind {
        ItemKind::Call(c) => matches!(&c.target, CallTarget::Name(n) if crate::dialect::sinumerik::cycles::cycle_of(&n.to_ascii_uppercase()).is_some()),
        _ => true,
    })
}

/// The FANUC registers the Siemens state stands for; `None` (reported) where they are not
/// known.
fn target(ctx: &mut Ctx, st: &St, b: &Block, live: bool) -> Option<Applied> {
    let (K::Known(edge), K::Known(side)) = (&st.edge, &st.side) else {
        refuse(
            ctx,
            live,
            CODE,
            b.meta.span,
            "tool compensation where the cutting edge or G40/G41/G42 in force depends on the path taken or on a call \
             cannot be translated",
            "select the tool and its edge (T… M6 D…) on every path before this block",
        );
        return None;
    };
    if *edge == 0 {
        if side.is_some() && live {
            let msg = "G41/G42 without an active cutting edge cannot be translated";
            refuse(ctx, live, CODE, b.meta.span, msg, "select the edge (D1) before G41/G42");
            return None;
        }
        return Some(Applied { len: None, rad: None });
    }
    let tool = match &st.tool {
        K::Known(Some(t)) => *t,
        _ => {
            let msg = "a cutting edge D without a known tool in the spindle cannot be translated";
            refuse(
                ctx,
                live,
                CODE,
                b.meta.span,
                msg,
                "change the tool (T… M6) in this program before selecting its edge",
            );
            return None;
        }
    };
    let Some((h, d)) = ctx.offsets.registers(tool, *edge) else {
        let msg = format!("edge D{edge} of tool {tool} has no FANUC registers in the offset map");
        let hint = format!(
            "name them: `\"{tool}.{edge}\" = \"H…,D…\"` under [offsets] in nctrans.toml \
             (by default only edge D1 of tool n has registers: H n, D n)"
        );
        refuse(ctx, live, MAP_CODE, b.meta.span, &msg, &hint);
        return None;
    };
    Some(Applied { len: Some(h), rad: side.map(|s| (s, d)) })
}
