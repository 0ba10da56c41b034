//! Sinumerik drilling cycles → FANUC (runs after `words`, which keeps `CYCLEnn` calls and
//! `MCALL` for it): `MCALL CYCLE81/82/83/84/840/85/87/88/89(…)` and its positioning blocks
//! become a FANUC cycle block (the first hole, with G98/G99, the cycle code, Z, R, Q, P, F),
//! hole blocks and G80; a direct call becomes a cycle block without a position (it drills
//! where the tool is) and G80. Exact only (the `cycle` events and the moves between the holes
//! must agree):
//! - R = RFP + SDIS, Z = DP (or RFP − DPR); RTP = R → G99; RTP = the level the tool stands
//!   at (its last Z in this block list) → G98, an RTP between that level and R first
//!   positions Z there (`G0 Z<RTP>`, the approach the Sinumerik cycle makes: a direct call
//!   where the tool is, under MCALL after the first hole's plane position);
//! - DTB (s) → P (ms); CYCLE83 FDPR → Q with VARI 1 → G83, VARI 0 → G73 (SDIS 0, DAM 0);
//! - tapping and boring (`cycles_tap.rs`): CYCLE84 → `M29 S` + G84/G74, CYCLE840 → G84/G74,
//!   CYCLE85 → G85/G89 with F (the feed before written back after G80), CYCLE87/88 → G88;
//! - the positioning blocks must be G0 moves of the plane axes: FANUC positions by rapid;
//! - an argument that is a variable known at translation (`cycles_known.rs`) decides the
//!   cycle as its value; the words keep the variable where FANUC takes it as it is.
//!
//! Refused with a reason (NC390–NC396, tapping NC486–NC488): CYCLE86, arguments the FANUC
//! cycle has no place for, an RTP that is neither, positions that are not plain rapids, and a
//! cycle open across a structure; NC660 an argument reading a variable not known at the call.
//! Rules: docs/translation.md.

use super::*;
use crate::dialect::sinumerik::cycles::{cycle_of, SieCycle};
use crate::lower::{literal, map_bodies};

/// Lowers the drilling cycles of every block list of `prog`.
pub fn run(ctx: &mut Ctx, prog: &mut Program, info: &ProgInfo) {
    let vals = super::cycles_known::vals(ctx, prog, info);
    let body = std::mem::take(&mut prog.body);
    let top = !info.is_sub;
    // A main program that never selects G91 (nor calls a program that could) is in G90
    // everywhere, inside its loops and IFs too (G90 is the start-up mode, as for `top`).
    let abs_everywhere = top && !may_select_incremental(&body);
    let mut nested = Vec::with_capacity(body.len());
    for s in body {
        match s.kind {
            StmtKind::Block(_) => nested.push(s),
            _ => nested.extend(map_bodies(vec![s], &mut |b| list(ctx, b, false, abs_everywhere, &vals))),
        }
    }
    prog.body = list(ctx, nested, top, abs_everywhere, &vals);
}

/// Whether a block of `body` may select G91: a G91 word, a G word computed at run time, or
/// a call of a program (its G91 outlives the return) other than a drilling cycle.
fn may_select_incremental(body: &[Stmt]) -> bool {
    fn item(it: &Item) -> bool {
        match &it.kind {
            ItemKind::Word(w) if w.addr.as_str() == "G" => !matches!(g_of(w), Some(g) if g != 91.0),
            ItemKind::Call(_) => cycle_call(it).is_none(),
            ItemKind::IfThen { then, .. } => item(then),
            ItemKind::Word(_) => false,
            ItemKind::Instruction { name } => name.to_ascii_uppercase().starts_with("EXECSTRING"),
            _ => false,
        }
    }
    let mut found = false;
    crate::ir::visit::walk_stmts(body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            found |= b.items.iter().any(item);
        }
    });
    found
}

/// The FANUC cycle a Sinumerik call makes: its G code and words after the position.
struct Fanuc {
    g: f64,
    retract: f64,
    words: Vec<(u8, Expr)>,
    /// `G0 Z<RTP>` first.
    approach: Option<f64>,
    /// Tapping: `M29 S…` before the cycle block, the F written back after G80.
    m29: Option<Expr>,
    restore: Option<f64>,
}

fn word(letter: u8, e: Expr, span: Span) -> Item {
    item(ItemKind::Word(Word { addr: Addr::Letter(letter), value: WordValue::Expr(e), span }), span)
}

fn gw(v: f64, span: Span) -> Item {
    word(b'G', Expr::num(v, v.fract() != 0.0, span), span)
}

fn mm(v: f64, span: Span) -> Expr {
    Expr::num(v, true, span)
}

fn g_of(w: &Word) -> Option<f64> {
    match &w.value {
        WordValue::Expr(e) if w.addr.is(b'G') => literal(e),
        _ => None,
    }
}

fn cycle_call(it: &Item) -> Option<(&Call, SieCycle)> {
    match &it.kind {
        ItemKind::Call(c) => match &c.target {
            CallTarget::Name(n) => cycle_of(&n.to_ascii_uppercase()).map(|k| (&**c, k)),
            _ => None,
        },
        _ => None,
    }
}

fn refuse(ctx: &mut Ctx, code: &'static str, span: Span, what: &str, hint: &str, out: &mut Vec<Stmt>) {
    out.extend(ctx.unsupported(code, span, what, hint));
}

/// The argument `name` of the call: `Some(expr)`, or `None` when empty or missing.
pub(super) fn arg<'a>(c: &'a Call, k: SieCycle, name: &str) -> Option<&'a Expr> {
    let i = k.params().iter().position(|p| *p == name)?;
    match c.args.get(i)? {
        Arg::Value(e) => Some(e),
        _ => None,
    }
}

/// The argument `name` as a number: 0 when empty, `None` when not a number (the call has
/// its arguments known at translation written as numbers, `cycles_known`).
pub(super) fn constant(c: &Call, k: SieCycle, name: &str) -> Option<f64> {
    match arg(c, k, name) {
        None => Some(0.0),
        Some(e) => literal(e),
    }
}

/// Plans the FANUC cycle of a call made where the tool stands at `level` (its last Z):
/// `c` with its arguments known at translation as numbers (what decides the cycle), `orig`
/// as written (the words keep its variables: `R[R2+R3]` where RFP and SDIS are variables).
fn plan(
    c: &Call,
    orig: &Call,
    k: SieCycle,
    level: Option<f64>,
    st: &super::cycles_tap::SieState,
) -> Result<Fanuc, (&'static str, String, &'static str)> {
    let bad = |code, what: String, hint| Err((code, what, hint));
    let (g, allowed): (f64, &[&str]) = match k {
        SieCycle::C81 => (81.0, &[]),
        SieCycle::C82 => (82.0, &["DTB"]),
        SieCycle::C83 => (0.0, &["FDEP", "FDPR", "VARI", "DAM", "FRF"]),
        SieCycle::C89 => (89.0, &["DTB"]),
        SieCycle::C84 => (84.0, &["DTB", "SDAC", "MPIT", "PIT", "SST"]),
        SieCycle::C840 => (84.0, &["DTB", "SDR", "SDAC", "ENC", "MPIT", "PIT"]),
        SieCycle::C85 => (85.0, &["DTB", "FFR", "RFF"]),
        SieCycle::C87 => (88.0, &["SDIR"]),
        SieCycle::C88 => (88.0, &["DTB", "SDIR"]),
        other => {
            let why = match other {
                SieCycle::C86 => {
                    "CYCLE86 lifts the tool off by RPA/RPO/RPAP after its oriented stop; FANUC's G76 shifts by Q in a direction set by a machine parameter, not in the program"
                }
                _ => "no FANUC cycle makes this motion",
            };
            return bad(
                "NC390",
                format!("{} (no exact FANUC cycle: {why})", other.name()),
                "write the holes as a FANUC cycle by hand",
            );
        }
    };
    for (i, p) in k.params().iter().enumerate() {
        let set = match c.args.get(i) {
            Some(Arg::Value(e)) => literal(e) != Some(0.0),
            _ => false,
        };
        if set && !["RTP", "RFP", "SDIS", "DP", "DPR"].contains(p) && !allowed.contains(p) {
            return bad("NC391", format!("{} with {p}", k.name()), "FANUC's cycle has no place for it: leave it empty");
        }
    }
    // `$P_EP[Z]`: the level the tool stands at (how the FANUC → Sinumerik translation
    // writes G98's initial level).
    let at_tool = arg(c, k, "RTP").is_some_and(is_tool_level);
    let level = if at_tool { Some(f64::NAN) } else { level };
    let rtp_value = if at_tool { Some(f64::NAN) } else { constant(c, k, "RTP") };
    let (Some(rtp), Some(rfp), Some(sdis)) = (rtp_value, constant(c, k, "RFP"), constant(c, k, "SDIS")) else {
        return bad(
            "NC392",
            format!("{} with RTP, RFP or SDIS known only at run time", k.name()),
            "write them as numbers",
        );
    };
    if !at_tool && rtp < rfp {
        return bad("NC392", format!("{} drilling upwards (RTP below RFP)", k.name()), "");
    }
    let r = rfp + sdis.abs();
    // RFP as the words write it: the variable where the program gave one.
    let rfp_w = |span: Span| kept(orig, k, "RFP").unwrap_or_else(|| mm(rfp, span));
    let z = match arg(c, k, "DPR").filter(|e| literal(e) != Some(0.0)) {
        Some(dpr) => match (literal(dpr), kept(orig, k, "RFP")) {
            (Some(d), None) => mm(rfp - d.abs(), dpr.span),
            (Some(d), Some(v)) => bin(BinOp::Sub, v, mm(d.abs(), dpr.span)),
            (None, _) => bin(BinOp::Sub, rfp_w(dpr.span), func(Func::Abs, vec![dpr.clone()], dpr.span)),
        },
        None => match kept(orig, k, "DP").or_else(|| arg(c, k, "DP").cloned()) {
            Some(e) => literal(&e).map_or_else(|| e.clone(), |v| mm(v, e.span)),
            None => mm(0.0, Span::default()),
        },
    };
    let mut words = vec![(b'Z', z), (b'R', r_word(orig, k, rfp, sdis, r))];
    let mut g = g;
    let (mut m29, mut restore, mut feed_word) = (None, None, None);
    if matches!(k, SieCycle::C84 | SieCycle::C840 | SieCycle::C85 | SieCycle::C87 | SieCycle::C88) {
        let t = if matches!(k, SieCycle::C84 | SieCycle::C840) {
            super::cycles_tap::plan(c, k, st)?
        } else {
            super::cycles_tap::plan_boring(c, k, st)?
        };
        g = t.g;
        m29 = t.m29;
        restore = t.restore.filter(|prev| t.f.as_ref().and_then(literal) != Some(*prev));
        feed_word = t.f;
    }
    if k == SieCycle::C83 {
        if sdis != 0.0
            || constant(c, k, "DAM") != Some(0.0)
            || !matches!(constant(c, k, "FRF"), Some(x) if x == 0.0 || x == 1.0)
        {
            return bad(
                "NC391",
                "CYCLE83 with SDIS, DAM or FRF set".into(),
                "G83/G73 count Q from R with equal infeeds",
            );
        }
        let q = match (arg(c, k, "FDPR").filter(|e| literal(e) != Some(0.0)), arg(c, k, "FDEP")) {
            (Some(e), _) => match (literal(e), kept(orig, k, "FDPR")) {
                // The program's variable where its value is the infeed as it is.
                (Some(v), Some(w)) if v > 0.0 => w,
                (Some(v), _) => mm(v.abs(), e.span),
                (None, _) => e.clone(),
            },
            (None, Some(e)) => {
                let e = kept(orig, k, "FDEP").unwrap_or_else(|| e.clone());
                match (literal(&e), kept(orig, k, "RFP")) {
                    (Some(v), None) => mm(rfp - v, e.span),
                    (_, _) => bin(BinOp::Sub, rfp_w(e.span), e.clone()),
                }
            }
            (None, None) => return bad("NC391", "CYCLE83 without FDEP or FDPR".into(), "give the infeed"),
        };
        words.push((b'Q', q));
        g = match constant(c, k, "VARI") {
            Some(1.0) => 83.0,
            Some(0.0) => 73.0,
            _ => return bad("NC392", "CYCLE83 with VARI known only at run time".into(), "write VARI as 0 or 1"),
        };
    }
    if allowed.contains(&"DTB") {
        match constant(c, k, "DTB") {
            Some(s) if ((s * 1000.0).round() - s * 1000.0).abs() < 1e-9 => {
                if s != 0.0 {
                    words.push((b'P', Expr::num((s * 1000.0).round(), false, Span::default())));
                }
            }
            _ => {
                return bad(
                    "NC392",
                    format!("{} with a dwell DTB not a whole number of milliseconds", k.name()),
                    "FANUC's P counts milliseconds",
                )
            }
        }
    }
    let same = |a: f64, b: f64| (a - b).abs() < 1e-9;
    let (retract, approach) = if at_tool {
        (98.0, None)
    } else if same(rtp, r) {
        (99.0, None)
    } else {
        match level {
            Some(p) if same(p, rtp) => (98.0, None),
            Some(p) if (p > rtp && rtp > r) => (98.0, Some(rtp)),
            _ => {
                return bad(
                    "NC393",
                    format!(
                        "{}: RTP is neither RFP + SDIS nor a level between the tool's last Z and RFP + SDIS",
                        k.name()
                    ),
                    "position the tool at RTP (G0 Z…) before the cycle, or give RTP = RFP + SDIS",
                )
            }
        }
    };
    // F last, as a programmer writes the cycle block.
    if let Some(f) = feed_word {
        words.push((b'F', f));
    }
    Ok(Fanuc { g, retract, words, approach, m29, restore })
}

/// The argument `name` as written where it is not a number (a variable the words keep).
fn kept(orig: &Call, k: SieCycle, name: &str) -> Option<Expr> {
    arg(orig, k, name).filter(|e| literal(e).is_none()).cloned()
}

/// The R word: RFP + |SDIS| as a number, or with the program's variables where it gave
/// them (`R[R2+R3]`; `R3` alone where RFP is 0), their values known to give `r`.
fn r_word(orig: &Call, k: SieCycle, rfp: f64, sdis: f64, r: f64) -> Expr {
    let span = Span::default();
    let (rv, sv) = (kept(orig, k, "RFP"), kept(orig, k, "SDIS"));
    if rv.is_none() && sv.is_none() {
        return mm(r, span);
    }
    let rfp_e = rv.unwrap_or_else(|| mm(rfp, span));
    let sdis_e = match sv {
        Some(e) if sdis < 0.0 => func(Func::Abs, vec![e.clone()], e.span),
        Some(e) => e,
        None => mm(sdis.abs(), span),
    };
    match (literal(&rfp_e) == Some(0.0), literal(&sdis_e) == Some(0.0)) {
        (true, _) => sdis_e,
        (_, true) => rfp_e,
        _ => bin(BinOp::Add, rfp_e, sdis_e),
    }
}

/// A structure whose blocks are only rapid X/Y positions (`G0 X=… Y=…`, or X/Y under G0)
/// and assignments, with no label, number or skip: its hole blocks without their G0 (which
/// would end FANUC's cycle); `None` for any other statement.
fn holes_in(s: &Stmt, motion: Option<f64>) -> Option<Stmt> {
    let is_hole = |b: &Block| {
        let words = b.items.iter().all(|it| match &it.kind {
            ItemKind::Word(w) => w.addr.is(b'X') || w.addr.is(b'Y') || (w.addr.is(b'G') && g_of(w) == Some(0.0)),
            _ => false,
        });
        words && positions(b, motion) == Ok(true)
    };
    let strip = |b: &mut Block| b.items.retain(|it| !matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'G')));
    crate::lower::hole_loops::rewritten(s, &is_hole, &strip)
}

/// The block's plane positions if it is a plain rapid of X/Y (and M, F, S, comments).
fn positions(b: &Block, motion: Option<f64>) -> Result<bool, &'static str> {
    let mut moved = false;
    let mut g0 = motion == Some(0.0);
    for it in &b.items {
        match &it.kind {
            ItemKind::Word(w) => match w.addr.as_str() {
                "X" | "Y" => moved = true,
                "G" => match g_of(w) {
                    Some(0.0) => g0 = true,
                    _ => return Err("a G code in a hole block"),
                },
                "M" | "F" | "S" => {}
                _ => return Err("a word other than X, Y, M, F, S in a hole block"),
            },
            _ => return Err("a statement other than words in a hole block"),
        }
    }
    if moved && !g0 {
        return Err("a hole positioned by a feed move (FANUC positions by rapid)");
    }
    Ok(moved)
}

fn list(
    ctx: &mut Ctx,
    body: Vec<Stmt>,
    top: bool,
    abs_everywhere: bool,
    vals: &super::cycles_known::Vals,
) -> Vec<Stmt> {
    let mut out = Vec::with_capacity(body.len());
    let mut level: Option<f64> = None;
    let mut motion: Option<f64> = if top { Some(0.0) } else { None };
    let mut abs: Option<bool> = if top || abs_everywhere { Some(true) } else { None };
    // The MCALL in force and whether its first hole was written.
    let mut active: Option<(Fanuc, bool, Span)> = None;
    // The block number and comments of an MCALL block, written on its first hole.
    let mut carry: Option<BlockMeta> = None;
    // An MCALL of a cycle that was refused: its MCALL cancel is not a second error.
    let mut refused_mcall = false;
    // A subprogram's modal call (G66) is in force.
    let mut g66 = false;
    let mut tap = super::cycles_tap::SieState::start(top);
    let mut zshift = super::cycles_frames::Shift::start(top);
    for s in body {
        let span = s.span;
        zshift.pass(&s);
        let StmtKind::Block(mut b) = s.kind else {
            // A loop of hole positions under the MCALL (a bolt circle): FANUC's cycle in force
            // drills at each of them (`holes_in`); a cycle not yet opened is stored first with
            // K0 (L0 on a Haas), which positions and drills nothing, where the tool already
            // stands at RTP (else the first hole's approach would move Z before X/Y).
            if let Some((f, first, _)) =
                active.as_mut().filter(|a| a.0.m29.is_none() && (a.1 || a.0.approach.is_none()))
            {
                if let Some(kept) = holes_in(&s, motion) {
                    if !*first {
                        let mut items = vec![gw(f.retract, span), gw(f.g, span)];
                        items.extend(f.words.iter().map(|(l, e)| word(*l, e.clone(), span)));
                        items.push(word(if ctx.haas { b'L' } else { b'K' }, Expr::num(0.0, false, span), span));
                        match carry.take() {
                            Some(m) => out.push(meta_stmt(BlockMeta { span, ..m }, items)),
                            None => out.push(block_stmt(items, span)),
                        }
                        *first = true;
                    }
                    out.push(kept);
                    continue;
                }
            }
            if active.take().is_some() {
                refuse(
                    ctx,
                    "NC394",
                    span,
                    "a drilling cycle (MCALL) open into a structure",
                    "end it with MCALL before",
                    &mut out,
                );
            }
            level = None;
            motion = None;
            // A G91 (or a call) inside the structure may outlive it.
            if !abs_everywhere && may_select_incremental(std::slice::from_ref(&s)) {
                abs = None;
            }
            tap = super::cycles_tap::SieState::default();
            out.push(s);
            continue;
        };
        // A subprogram's modal call (`MCALL NAME(…)`, now G66): Siemens' next MCALL replaces
        // it, where FANUC would nest a second one (or call it at each hole of a cycle).
        if b.items.iter().any(|it| matches!(&it.kind, ItemKind::Call(c) if c.kind == CallKind::G66)) {
            if g66 || active.is_some() {
                refuse(
                    ctx,
                    "NC318",
                    span,
                    "an MCALL while another modal call is in force",
                    "end the first with MCALL",
                    &mut out,
                );
                continue;
            }
            g66 = true;
        }
        let call = b.items.iter().find_map(|it| cycle_call(it).map(|(c, k)| (c.clone(), k, it.span)));
        if g66 && call.as_ref().is_some_and(|c| c.0.kind == CallKind::Mcall) {
            refuse(
                ctx,
                "NC318",
                span,
                "a drilling cycle's MCALL while a subprogram's modal call is in force",
                "end it with MCALL first",
                &mut out,
            );
            continue;
        }
        let off = b.items.iter().any(|it| matches!(it.kind, ItemKind::ModalCallOff));
        if let Some((orig, k, cspan)) = call {
            b.items.retain(|it| cycle_call(it).is_none());
            observe_words(&mut tap, &b.items);
            let mcall = orig.kind == CallKind::Mcall;
            zshift.positioned(&b.items);
            if !mcall && zshift.turned() {
                super::cycles_frames::first_hole(ctx, span, &mut out);
                continue;
            }
            if abs != Some(true) {
                refuse(
                    ctx,
                    "NC395",
                    span,
                    "a drilling cycle where G90 is not known to be active",
                    "program G90 before",
                    &mut out,
                );
                continue;
            }
            let f = match vals.resolve(&orig, k, cspan) {
                Ok(c) => plan(&c, &orig, k, level, &tap).map(|f| (f, c)).map_err(|(a, b, h)| (a, b, h, None)),
                Err(r) => Err(r),
            };
            let (f, c) = match f {
                Ok(f) => f,
                Err((code, what, hint, at)) => {
                    refuse(ctx, code, span, &what, hint, &mut out);
                    // The place that makes the variable unknown, beside the call.
                    if let Some((at, label)) = at {
                        if let Some(d) = ctx.diags.pop() {
                            let file = ctx.file;
                            ctx.diags.push(d.secondary(file, at, label));
                        }
                    }
                    refused_mcall |= mcall;
                    continue;
                }
            };
            let mut meta = None;
            if b.items.is_empty() && b.meta.label.is_none() {
                meta = Some(std::mem::take(&mut b.meta));
            } else {
                out.push(Stmt { kind: StmtKind::Block(b), span });
            }
            if motion != Some(0.0) {
                out.push(block_stmt(vec![gw(0.0, span)], span));
                motion = Some(0.0);
            }
            // A direct call approaches RTP where the tool is; under MCALL the Sinumerik cycle
            // positions the plane axes first and then approaches, so the first hole does.
            if let (Some(z), false) = (f.approach, mcall) {
                out.push(block_stmt(vec![gw(0.0, span), word(b'Z', mm(z, span), span)], span));
            }
            if mcall {
                active = Some((f, false, span));
                carry = meta;
            } else {
                // A direct call drills where the tool is: the cycle block without a position.
                let mut items = vec![gw(f.retract, span), gw(f.g, span)];
                items.extend(f.words.iter().map(|(l, e)| word(*l, e.clone(), span)));
                if let Some(s) = &f.m29 {
                    take_speed_block(&mut out, s);
                    out.push(m29_block(s, span));
                }
                match meta {
                    Some(m) => out.push(meta_stmt(BlockMeta { span, ..m }, items)),
                    None => out.push(block_stmt(items, span)),
                }
                out.push(block_stmt(cancel_items(&f, span), span));
            }
            // Every hole ends at RTP.
            if !arg(&c, k, "RTP").is_some_and(is_tool_level) {
                level = constant(&c, k, "RTP");
            }
            continue;
        }
        if off {
            b.items.retain(|it| !matches!(it.kind, ItemKind::ModalCallOff));
            match active.take() {
                Some((f, first, _)) => {
                    if first {
                        let mut items = cancel_items(&f, span);
                        items.append(&mut b.items);
                        b.items = items;
                    }
                }
                None if std::mem::take(&mut refused_mcall) => {}
                // The end of a subprogram's modal call (`words` wrote it as G66): G67.
                None if std::mem::take(&mut g66) => b.items.push(Item { kind: ItemKind::ModalCallOff, span }),
                None => refuse(
                    ctx,
                    "NC318",
                    span,
                    "MCALL cancel",
                    "the MCALL it ends is not in this block list: end a modal call where it began",
                    &mut out,
                ),
            }
            out.push(Stmt { kind: StmtKind::Block(b), span });
            continue;
        }
        if let Some((f, first, _)) = &mut active {
            // A rotation between the holes (cycles_frames.rs): the next hole opens the cycle again.
            if let Some(keeps) = zshift.frame_block(&b) {
                super::cycles_frames::across(ctx, keeps, first, cancel_items(f, span), span, &mut out);
                f.approach = None;
                out.push(Stmt { kind: StmtKind::Block(b), span });
                continue;
            }
            // `M29 S…` right before the first cycle block.
            let mut rigid = None;
            match positions(&b, motion) {
                Err(why) => {
                    refuse(ctx, "NC396", span, why, "under MCALL, position the holes with G0 X… Y…", &mut out);
                    continue;
                }
                _ if f.m29.is_some()
                    && b.items.iter().any(|it| matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'F'))) =>
                {
                    refuse(
                        ctx,
                        "NC487",
                        span,
                        "an F in a hole block of CYCLE84",
                        "CYCLE84 taps at pitch × SST whatever F is, FANUC's G84 at F: program F after MCALL",
                        &mut out,
                    );
                    continue;
                }
                Ok(false) => {}
                Ok(true) if !zshift.positioned(&b.items) => {
                    super::cycles_frames::first_hole(ctx, span, &mut out);
                    continue;
                }
                Ok(true) => {
                    b.items.retain(|it| !matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'G')));
                    if !*first {
                        rigid = f.m29.clone();
                        let mut items = vec![gw(f.retract, span), gw(f.g, span)];
                        items.append(&mut b.items);
                        items.extend(f.words.iter().map(|(l, e)| word(*l, e.clone(), span)));
                        b.items = items;
                        *first = true;
                        if let Some(m) = carry.take() {
                            if b.meta.number.is_none() || m.number.is_none() {
                                b.meta.number = b.meta.number.take().or(m.number);
                                let mut comments = m.comments;
                                comments.append(&mut b.meta.comments);
                                b.meta.comments = comments;
                            } else {
                                // Both numbered: the MCALL's number stays a block (a jump may
                                // name it).
                                out.push(meta_stmt(m, vec![]));
                            }
                        }
                        if let Some(z) = f.approach {
                            // The first hole: positioned at the tool's level, then Z to RTP
                            // (FANUC's initial level), then the cycle block drills there.
                            let meta = std::mem::take(&mut b.meta);
                            let (pos, rest): (Vec<Item>, Vec<Item>) =
                                std::mem::take(&mut b.items).into_iter().partition(is_plane_position);
                            out.push(meta_stmt(BlockMeta { span, ..meta }, pos));
                            out.push(block_stmt(vec![gw(0.0, span), word(b'Z', mm(z, span), span)], span));
                            b.items = rest;
                        }
                    }
                }
            }
            if let Some(s) = rigid {
                take_speed_block(&mut out, &s);
                out.push(m29_block(&s, span));
            }
            observe_words(&mut tap, &b.items);
            out.push(Stmt { kind: StmtKind::Block(b), span });
            continue;
        }
        // A frame block's Z is no position (cycles_frames.rs).
        let kept = zshift.frame_block(&b).map(|keeps| level.filter(|_| keeps));
        for it in &b.items {
            if let ItemKind::Word(w) = &it.kind {
                match (w.addr.as_str(), g_of(w)) {
                    ("G", Some(v)) if [0.0, 1.0, 2.0, 3.0].contains(&v) => motion = Some(v),
                    ("G", Some(90.0)) => abs = Some(true),
                    ("G", Some(91.0)) => abs = Some(false),
                    (l, _) if matches!(l, "M" | "G" | "F") => {
                        let v = match &w.value {
                            WordValue::Expr(e) => literal(e),
                            _ => None,
                        };
                        tap.observe(l, v);
                    }
                    ("Z", _) => {
                        level = match (&w.value, abs) {
                            (WordValue::Expr(e), Some(true)) => vals.z(w, e),
                            _ => None,
                        }
                    }
                    _ => {}
                }
            }
        }
        if let Some(l) = kept {
            level = l;
        }
        zshift.positioned(&b.items);
        if b.items.iter().any(|it| !matches!(it.kind, ItemKind::Word(_))) {
            // An assignment, a call …: the tool's level may have changed.
            level = None;
        }
        if b.items.iter().any(|it| matches!(it.kind, ItemKind::Call(_))) {
            tap = super::cycles_tap::SieState::default();
        }
        out.push(Stmt { kind: StmtKind::Block(b), span });
    }
    if let Some((_, _, span)) = active {
        if !top {
            refuse(
                ctx,
                "NC394",
                span,
                "a drilling cycle (MCALL) still open at the end of a block list",
                "end it with MCALL",
                &mut out,
            );
        }
    }
    out
}

/// The spindle, feed-mode and F words of a block, for the tapping and boring plans.
fn observe_words(tap: &mut super::cycles_tap::SieState, items: &[Item]) {
    for it in items {
        if let ItemKind::Word(w) = &it.kind {
            let v = match &w.value {
                WordValue::Expr(e) => literal(e),
                _ => None,
            };
            tap.observe(w.addr.as_str(), v);
        }
    }
}

/// A Sinumerik `S<sst>` just before rigid tapping (only S and F blocks between) is the
/// speed `M29 S<sst>` sets in FANUC: its S word goes (and the block, when nothing else is in
/// it), so a translation translated back does not gain an S block each time.
fn take_speed_block(out: &mut Vec<Stmt>, sst: &Expr) {
    let Some(v) = literal(sst) else { return };
    for k in (0..out.len()).rev() {
        let StmtKind::Block(b) = &mut out[k].kind else { return };
        let words_only =
            b.items.iter().all(|it| matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'S') || w.addr.is(b'F')));
        if !words_only || b.meta.label.is_some() {
            return;
        }
        let at = b.items.iter().position(|it| matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'S') && matches!(&w.value, WordValue::Expr(e) if literal(e) == Some(v))));
        if let Some(i) = at {
            b.items.remove(i);
            if b.items.is_empty() && b.meta.number.is_none() && b.meta.comments.is_empty() {
                out.remove(k);
            }
            return;
        }
    }
}

/// `M29 S<sst>`: rigid tapping for the cycle block after it.
fn m29_block(sst: &Expr, span: Span) -> Stmt {
    block_stmt(vec![word(b'M', Expr::num(29.0, false, span), span), word(b'S', sst.clone(), span)], span)
}

/// `G80`, and after rigid tapping the feed the program had before (G84's F is modal).
fn cancel_items(f: &Fanuc, span: Span) -> Vec<Item> {
    let mut items = vec![gw(80.0, span)];
    if let Some(prev) = f.restore {
        items.push(word(b'F', mm(prev, span), span));
    }
    items
}

/// Whether `e` is `$P_EP[Z]`, the programmed end point of the drilling axis.
fn is_tool_level(e: &Expr) -> bool {
    match &e.kind {
        ExprKind::Var(v) => match &v.kind {
            VarKind::System { name, indices } => {
                name.eq_ignore_ascii_case("P_EP")
                    && matches!(indices.as_slice(), [i] if matches!(&i.kind, ExprKind::Ident(a) if a.eq_ignore_ascii_case("Z")))
            }
            _ => false,
        },
        _ => false,
    }
}

/// An X or Y word of a hole block: where the hole is in the plane.
fn is_plane_position(it: &Item) -> bool {
    matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'X') || w.addr.is(b'Y'))
}
