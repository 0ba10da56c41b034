//! Address words and Siemens-only items → their FANUC forms.
//!
//! `CR=` → `R`; `G4 F` → `G04 X` (seconds); `G70/G700` → `G20`, `G71/G710` → `G21` (F words
//! are converted where the Sinumerik feed unit differs from the length unit: under G70/G71
//! F is in the basic system, metric, [`units`]); `AC()/IC()` → the block in G90/G91 with a switch back after it; `T="NAME"` → a number from the tool map; `MSG("…")` → a comment, or with
//! the `M0` block that follows it `#3006=1(…)`; `SETAL(n)` → `#3000`; calls of translated
//! subprograms → `G65 P…` with one argument letter per parameter ([`param_letters`]);
//! `WORKPIECE`/`STOPRE` dropped with a note; frames, section repetition, modal calls and
//! unknown cycles are unsupported.

use super::*;
use calls::call;
pub use calls::param_letters;
use modes::{Feed, Modes, Resets, UnitState};
use units::{FeedConv, Units};

pub mod effects;
mod mixed;
mod modes;
mod sysunits;
pub mod units;

/// G codes with the same number and meaning on both controls.
pub const SAME_G: &[u32] = &[0, 1, 2, 3, 4, 9, 17, 18, 19, 40, 41, 42, 53, 54, 55, 56, 57, 64, 90, 91, 94, 95];
const AXES: &[u8] = b"XYZABCUVW";
/// Siemens instructions that only change dynamics (acceleration, feed control): dropped.
const DYNAMICS_ONLY: &[&str] = &["SOFT", "BRISK", "DRIVE", "FFWON", "FFWOF", "CFC", "CFTCP", "CFIN"];
/// Calls that only set up the HMI simulation: dropped.
pub const SIMULATION_ONLY: &[&str] = &["WORKPIECE"];

struct Modal {
    s: Modes,
    /// Jump targets where modes are reset.
    resets: Resets,
    /// The axes a TRANS becomes a G52 of (`frames::trans_axes`).
    trans_axes: u16,
    /// What the program's rotations allow (`rotation::plan`).
    rot: super::rotation::Plan,
    /// The poles of its polar moves (`polar::poles`).
    poles: super::polar::Poles,
    /// Its additive frame sequences (`frame_seq::seqs`).
    seqs: super::frame_seq::Seqs,
    /// Its frame chained from TRANS, ATRANS, ROT, AROT (`frame_chain::plan`).
    chain: super::frame_chain::Chain,
    /// A called program (its caller's frame, a G52 among them, is not known here).
    is_sub: bool,
    /// The incremental moves after a frame change the controls travel differently
    /// (`frames_incr::plan`).
    incr: super::frames_incr::Plan,
}

impl Modal {
    /// Where paths meet, one with the modes here and one with `other`: what they agree
    /// on from here on. Where they disagree on the units, those no longer follow the text
    /// (the streamed translators, whose runs convert F words in text order, decline then;
    /// G90/G91 is read by AC()/IC() words only, all in the skeleton they translate here).
    fn meet(&mut self, ctx: &mut Ctx, other: Modes) {
        if other.units != self.s.units {
            ctx.units_inexact = true;
        }
        self.s = self.s.merge(other);
    }
}

pub fn run(ctx: &mut Ctx, prog: &mut Program, info: &ProgInfo) {
    let trans_axes = super::frames::trans_axes(&prog.body);
    let seqs = super::frame_seq::seqs(&prog.body, !info.is_sub);
    let chain =
        super::frame_chain::plan(&prog.body, !info.is_sub, trans_axes, &ctx.callees, &seqs, info.is_sub && prog.save);
    let mut m = Modal {
        s: Modes {
            abs: if info.is_sub { None } else { Some(true) },
            units: if info.is_sub { UnitState::Caller } else { UnitState::Known(Units::default()) },
        },
        resets: Resets::of(&prog.body, &ctx.callees),
        trans_axes,
        rot: super::rotation::plan(&prog.body, !info.is_sub),
        poles: super::polar::poles(&prog.body, !info.is_sub),
        // A followed chain writes every frame block itself.
        seqs: if chain.on { Default::default() } else { seqs },
        chain,
        is_sub: info.is_sub,
        incr: super::frames_incr::plan(&prog.body, !info.is_sub, &ctx.callees),
    };
    // The groups a SAVE subprogram sets (its callees' included), read before its G codes
    // become FANUC ones.
    let saves = if info.is_sub && prog.save {
        effects::effect_of(prog, &|n| ctx.callees.get(n).map(|c| c.effect)).sets
    } else {
        0
    };
    let body = std::mem::take(&mut prog.body);
    prog.body = body_pass(ctx, body, &mut m);
    if saves != 0 {
        save::restore_on_return(ctx, prog, saves);
    }
}

fn body_pass(ctx: &mut Ctx, body: Vec<Stmt>, m: &mut Modal) -> Vec<Stmt> {
    let mut out: Vec<Stmt> = Vec::with_capacity(body.len());
    let mut it = body.into_iter().peekable();
    while let Some(mut s) = it.next() {
        let mut at = m.s;
        m.resets.apply(&crate::ir::visit::metas(&s.kind), &mut at);
        m.meet(ctx, at);
        match &mut s.kind {
            StmtKind::Block(b) => {
                if let Some(run) = super::stand_in(&b.meta) {
                    // The units its run's blocks start in, in the whole program.
                    let units = match m.s.units {
                        UnitState::Known(u) => Some(u),
                        _ => None,
                    };
                    ctx.stand_in_units.push((run, units));
                }
                // MSG("…") directly followed by a block holding only M0: one stop with a message.
                if let Some(text) = msg_text(b) {
                    if let Some(StmtKind::Block(next)) = it.peek().map(|n| &n.kind) {
                        if is_lone_m0(next) {
                            let span = b.meta.span;
                            let mut meta = std::mem::take(&mut b.meta);
                            if let Some(StmtKind::Block(nb)) = it.next().map(|n| n.kind) {
                                meta.comments.extend(nb.meta.comments);
                            }
                            out.push(meta_stmt(meta, vec![item(ItemKind::StopMessage { text: Some(text) }, span)]));
                            continue;
                        }
                    }
                }
                let mut b = std::mem::take(b);
                let before = m.s;
                let skip = b.meta.skip.is_some();
                // The block's expressions are evaluated before its own unit words act.
                if let Err(mark) = sys_units(ctx, m, &mut b.items, b.meta.span) {
                    out.extend(mark);
                    continue;
                }
                block_pass(ctx, b, m, &mut out);
                if skip {
                    // A block that may be skipped: both ways meet after it.
                    m.meet(ctx, before);
                }
                continue;
            }
            StmtKind::If(i) => {
                out.extend(sys_units_expr(ctx, m, &mut i.cond));
                let entry = m.s;
                i.then_body = body_pass(ctx, std::mem::take(&mut i.then_body), m);
                let then_end = m.s;
                m.s = entry;
                if let Some(e) = &mut i.else_part {
                    e.body = body_pass(ctx, std::mem::take(&mut e.body), m);
                }
                m.meet(ctx, then_end);
            }
            kind => {
                // A loop's head holds what every pass may bring; so does its exit.
                let entry = m.resets.loop_entry(modes::loop_body(kind), m.s, &ctx.callees);
                m.meet(ctx, entry);
                let entry = m.s;
                match kind {
                    StmtKind::While(w) => {
                        out.extend(sys_units_expr(ctx, m, &mut w.cond));
                        w.body = body_pass(ctx, std::mem::take(&mut w.body), m)
                    }
                    StmtKind::Loop(l) => l.body = body_pass(ctx, std::mem::take(&mut l.body), m),
                    StmtKind::For(f) => {
                        out.extend(sys_units_expr(ctx, m, &mut f.from));
                        out.extend(sys_units_expr(ctx, m, &mut f.to));
                        f.body = body_pass(ctx, std::mem::take(&mut f.body), m)
                    }
                    StmtKind::Repeat(r) => {
                        r.body = body_pass(ctx, std::mem::take(&mut r.body), m);
                        out.extend(sys_units_expr(ctx, m, &mut r.until));
                    }
                    StmtKind::Do(d) => d.body = body_pass(ctx, std::mem::take(&mut d.body), m),
                    StmtKind::Block(_) | StmtKind::If(_) => {}
                }
                m.meet(ctx, entry);
            }
        }
        out.push(s);
    }
    out
}

/// Length system variables in `items` scaled where the Siemens unit (the feeds') and the
/// FANUC one (the lengths') differ ([`sysunits`]); a marker where the units are not known.
fn sys_units(ctx: &mut Ctx, m: &Modal, items: &mut [Item], span: Span) -> Result<(), Vec<Stmt>> {
    if !items.iter().any(sysunits::uses_lengths) {
        return Ok(());
    }
    match m.s.units.feed() {
        Feed::Static(conv) => {
            items.iter_mut().for_each(|it| sysunits::item(it, conv));
            Ok(())
        }
        Feed::Unknown => Err(unknown_sys_units(ctx, span)),
    }
}

/// [`sys_units`] of a condition or loop bound.
fn sys_units_expr(ctx: &mut Ctx, m: &Modal, e: &mut Expr) -> Vec<Stmt> {
    if !sysunits::reads(e) {
        return vec![];
    }
    match m.s.units.feed() {
        Feed::Static(conv) => {
            sysunits::expr(e, conv);
            vec![]
        }
        Feed::Unknown => unknown_sys_units(ctx, e.span),
    }
}

fn unknown_sys_units(ctx: &mut Ctx, span: Span) -> Vec<Stmt> {
    let what = "a length system variable ($AA_IW, $AA_IM, $P_EP, $P_UIFR) or $P_F where the units (G70/G71/G700/G710) depend on the path taken or on a call";
    unsup(ctx, "NC376", span, what, "write G700 or G710 before it, after the IF, loop, jump target or call")
}

pub fn msg_text(b: &Block) -> Option<String> {
    match b.items.as_slice() {
        [Item { kind: ItemKind::Message { text: Some(Expr { kind: ExprKind::Str(t), .. }) }, .. }] => Some(t.clone()),
        _ => None,
    }
}

pub fn is_lone_m0(b: &Block) -> bool {
    b.meta.number.is_none()
        && b.meta.label.is_none()
        && matches!(b.items.as_slice(), [Item { kind: ItemKind::Word(w), .. }]
            if w.addr.is(b'M') && const_of(&w.value) == Some(0.0))
}

fn const_of(v: &WordValue) -> Option<f64> {
    match v {
        WordValue::Expr(Expr { kind: ExprKind::Num(n), .. }) => Some(n.value),
        _ => None,
    }
}

/// The value of an item that is a constant G word.
fn const_g(it: &Item) -> Option<f64> {
    match &it.kind {
        ItemKind::Word(w) if w.addr.is(b'G') => const_of(&w.value),
        _ => None,
    }
}

fn block_pass(ctx: &mut Ctx, mut b: Block, m: &mut Modal, out: &mut Vec<Stmt>) {
    // An incremental move (or call) the controls travel differently after a TRANS.
    if let Some(mark) = super::frames_incr::refuse(ctx, &b, &m.incr) {
        out.extend(mark);
        return;
    }
    // G111 and AP=/RP= (polar.rs); ROT/AROT (rotation.rs); TRANS, SUPA/G153, G505..,
    // G74/G75 (frames.rs).
    if let Some(stmts) = super::polar::block(ctx, &mut b, &m.poles) {
        out.extend(stmts);
        return;
    }
    // A followed chain writes every frame block (it has no sequences then); else the
    // sequences take theirs and the chain refuses the other ATRANS where it says why.
    if let Some(stmts) = super::frame_seq::block(&mut b, &m.seqs) {
        out.extend(stmts);
        return;
    }
    if let Some(stmts) = super::frame_chain::block(ctx, &mut b, &m.chain, m.s.abs, m.trans_axes) {
        out.extend(stmts);
        return;
    }
    if let Some(stmts) = super::rotation::block(ctx, &mut b, &m.rot, m.s.abs, m.trans_axes, out) {
        out.extend(stmts);
        return;
    }
    if let Some(stmts) = super::frames::block(ctx, &mut b, m.s.abs, m.trans_axes, !m.is_sub, out) {
        out.extend(stmts);
        return;
    }
    let items = std::mem::take(&mut b.items);
    let mut kept: Vec<Item> = Vec::new();
    let mut after: Vec<Stmt> = Vec::new();
    let mut before: Vec<Stmt> = Vec::new();
    let has_words = items.iter().any(|i| matches!(i.kind, ItemKind::Word(_)));
    if has_words {
        let words: Vec<Word> = items
            .iter()
            .filter_map(|i| match &i.kind {
                ItemKind::Word(w) => Some(w.clone()),
                _ => None,
            })
            .collect();
        let has_call = items.iter().any(|i| matches!(i.kind, ItemKind::Call(_)));
        match words_pass(ctx, words, m, has_call, b.meta.span) {
            Ok((ws, pre, post)) => {
                before.extend(pre);
                kept.extend(ws.into_iter().map(|w| {
                    let span = w.span;
                    item(ItemKind::Word(w), span)
                }));
                after.extend(post);
            }
            Err(mark) => {
                out.extend(mark);
                return;
            }
        }
    }
    for it in items {
        let span = it.span;
        match it.kind {
            ItemKind::Word(_) => {}
            ItemKind::Message { text: None } => {}
            ItemKind::Message { text: Some(Expr { kind: ExprKind::Str(t), .. }) } => {
                ctx.note(
                    "NC320",
                    span,
                    "MSG becomes a comment",
                    "FANUC shows no message without stopping; MSG followed by M0 would become #3006=1(…)",
                );
                b.meta.comments.push(Comment { text: format!("MSG: {t}"), span });
            }
            ItemKind::Message { text: Some(e) } => {
                // As a fixed message does: a comment, here the text's formula as written in
                // Siemens (FANUC cannot build text at run time; the value is not shown).
                ctx.note(
                    "NC320",
                    span,
                    "MSG with a computed text becomes a comment of its formula",
                    "FANUC shows no message without stopping and cannot build text; the values are not shown",
                );
                let formula = crate::dialect::sinumerik::emit::expr(&e);
                b.meta.comments.push(Comment { text: format!("MSG: {formula}"), span });
            }
            ItemKind::Alarm { style: AlarmStyle::Setal, number, .. } => match &number.kind {
                // User alarms: SETAL(65000+k) ↔ #3000=k (alarm 3000+k), as the checker pairs them.
                ExprKind::Num(n) if (65000.0..=65999.0).contains(&n.value) && n.value.fract() == 0.0 => {
                    let v = n.value as u64;
                    let k = v - 65000;
                    kept.push(item(
                        ItemKind::Alarm {
                            style: AlarmStyle::FanucMacro,
                            number: num(k as f64, number.span),
                            text: Some(format!("SETAL {v}")),
                        },
                        span,
                    ));
                }
                _ => after.extend(ctx.unsupported(
                    "NC315",
                    number.span,
                    "SETAL with a computed number or one outside 65000..65999",
                    "use a user alarm SETAL(65000+k); it becomes #3000=k",
                )),
            },
            ItemKind::Stopre => ctx.note(
                "NC321",
                span,
                "STOPRE dropped",
                "FANUC waits for motion by itself before reading position variables",
            ),
            ItemKind::Call(c) => {
                if let Some(s) = call(ctx, *c, span, m, &mut kept) {
                    after.push(s);
                }
            }
            ItemKind::Frame { op, .. } => after.extend(ctx.unsupported(
                "NC316",
                span,
                &format!("frame instruction {op}"),
                "FANUC has no programmable frames; use G52/G68 by hand",
            )),
            ItemKind::RepeatSection(_) => after.extend(ctx.unsupported(
                "NC317",
                span,
                "program-section repetition (REPEAT label P=n)",
                "rewrite the section as a FOR loop",
            )),
            ItemKind::Instruction { name } if (name == "FFWON" || name == "FFWOF") && !ctx.haas => {
                before.extend(super::lookahead::feed_forward(ctx, name == "FFWON", span))
            }
            ItemKind::Instruction { name } if DYNAMICS_ONLY.contains(&name.as_str()) => ctx.note(
                "NC323",
                span,
                &format!("{name} dropped"),
                "it changes acceleration or feed control only, not the programmed path",
            ),
            ItemKind::Instruction { name } if crate::eval::instructions::is_interrupt(&name) => {
                match super::interrupt::lower(ctx, &name, span) {
                    Ok(items) => kept.extend(items),
                    Err(mark) => after.extend(mark),
                }
            }
            // M99 P<n> would be the counterpart for one level, but what RET's arguments mean
            // and where the control finds the target are unsourced (the note says so).
            ItemKind::Instruction { name } if crate::dialect::sinumerik::is_ret_with_target(&name) => {
                after.extend(ctx.unsupported(
                    "NC507",
                    span,
                    &format!("{name} (a return that resumes at a label or block of a caller)"),
                    "FANUC M99 Pn resumes at Nn of the caller only; rewrite it as RET and a jump in the caller",
                ));
                if let Some(d) = ctx.diags.pop() {
                    ctx.diags.push(d.note(crate::dialect::sinumerik::RET_TARGET_UNSOURCED));
                }
            }
            // The device is the set-up's (extdev.ini), and the run stops at it (NC586) so no
            // WRITE to it is ever proven; FANUC's POPEN opens the device its parameters name.
            ItemKind::Instruction { name } if crate::eval::print::is_external_device(&name) => {
                after.extend(ctx.unsupported(
                    "NC586",
                    span,
                    &format!("{name} (opens or closes an external device for WRITE)"),
                    "FANUC POPEN/PCLOS open the output device set by the control's parameters, not a named one:                      set up the device on the FANUC control and write the output with POPEN, DPRNT and PCLOS by hand",
                ))
            }
            ItemKind::Instruction { name } => after.extend(ctx.unsupported(
                "NC312",
                span,
                &format!("instruction {name}"),
                "no FANUC code has the same meaning",
            )),
            // Kept for the drilling cycles (`passes::cycles`), which refuse any other.
            ItemKind::ModalCallOff => kept.push(Item { kind: ItemKind::ModalCallOff, span }),
            ItemKind::Extern(e) => ctx.note(
                "NC637",
                span,
                &format!("EXTERN {} dropped", e.name),
                "it only declares the parameters of a called subprogram; FANUC calls declare nothing",
            ),
            ItemKind::Assign { target, value } if super::frames::extended_frame(&target).is_some() => {
                match super::frames::g10_l20(ctx, &target, value, m.s.abs, span) {
                    Ok(stmts) => after.extend(stmts),
                    Err(mark) => after.extend(mark),
                }
            }
            ItemKind::Print(p) => after.extend(super::print::lower(ctx, *p, span)),
            ItemKind::SyncAction(a) => after.extend(ctx.unsupported(
                "NC631",
                span,
                &crate::eval::refuse::sync_name(&a),
                crate::eval::refuse::SYNC_WHY,
            )),
            kind => kept.push(Item { kind, span }),
        }
    }
    // A numbered block whose words all became a block of their own (`N60 CYCLE832(…)` →
    // `G05.1 Q1`, `N80 FFWON`) carries them, as a programmer writes it: a jump to N80 then
    // runs them (it landed below a block written before it), a `/` skips them with it.
    if kept.is_empty() && meta_is_marked(&b.meta) {
        let side = match (before.len(), after.is_empty()) {
            (1, true) => Some(&mut before),
            (0, false) => Some(&mut after),
            _ => None,
        };
        if let Some(side) = side {
            if let Some(Stmt { kind: StmtKind::Block(first), .. }) = side.first() {
                let plain = first.meta.number.is_none() && first.meta.label.is_none() && first.meta.skip.is_none();
                if plain && first.meta.comments.is_empty() && !first.items.is_empty() {
                    if let StmtKind::Block(first) = side.remove(0).kind {
                        kept = first.items;
                    }
                }
            }
        }
    }
    let drop_empty = kept.is_empty() && !meta_is_marked(&b.meta);
    out.extend(before);
    if !drop_empty {
        b.items = kept;
        out.push(Stmt { span: b.meta.span, kind: StmtKind::Block(b) });
    }
    out.extend(after);
}

type WordsOut = (Vec<Word>, Vec<Stmt>, Vec<Stmt>);

/// `M2` / `S1` as a spindle-addressed word (`M2=3`): its letter and spindle number.
fn spindle_word(n: &str) -> Option<(u8, u32)> {
    let (l, k) = n.split_at_checked(1)?;
    let letter = match l {
        "M" => b'M',
        "S" => b'S',
        _ => return None,
    };
    (!k.is_empty() && k.bytes().all(|b| b.is_ascii_digit())).then(|| k.parse().ok().map(|k| (letter, k)))?
}

/// Translates the NC words of one block. Returns the words, blocks to run before and after
/// (the G90/G91 switch), or the marker of an unsupported word.
fn words_pass(
    ctx: &mut Ctx,
    words: Vec<Word>,
    m: &mut Modal,
    has_call: bool,
    span: Span,
) -> Result<WordsOut, Vec<Stmt>> {
    let dwell = words.iter().any(|w| w.addr.is(b'G') && const_of(&w.value) == Some(4.0));
    // Modal G words of this block apply to its own axis words.
    for w in &words {
        if w.addr.is(b'G') {
            if let Some(v) = const_of(&w.value) {
                m.s.g(v);
            }
        }
    }
    let mut out = Vec::with_capacity(words.len());
    let mut explicit: Option<bool> = None;
    let mut mixed = false;
    let mut plain_axis = false;
    // Per word of `out`: `Some(true)` AC(), `Some(false)` IC(), `None` otherwise.
    let mut forms: Vec<Option<bool>> = Vec::with_capacity(words.len());
    for mut w in words {
        let wspan = w.span;
        match &w.addr {
            Addr::Name(n) if n.as_ref() == "CR" => w.addr = Addr::Letter(b'R'),
            // `,C` / `,R`: the same meaning, spelt by the writer (`corners`).
            Addr::Name(n) if matches!(n.as_ref(), "CHR" | "RND") => {}
            Addr::Axis(_) if ctx.axis_reported.contains(&wspan) => return Err(vec![]), // `axis_vars` said why
            Addr::Axis(_) => {
                let what = "AX[…] (an axis chosen by name at run time)";
                return Err(unsup(
                    ctx,
                    "NC635",
                    wspan,
                    what,
                    "FANUC addresses are fixed letters; write the axis letter",
                ));
            }
            Addr::Name(n) if spindle_word(n).is_some_and(|(_, k)| k == ctx.master_spindle) => {
                // `M1=3`, `S1=1000`: the master spindle by number is the FANUC spindle.
                w.addr = Addr::Letter(n.as_bytes()[0]);
            }
            Addr::Name(n) if spindle_word(n).is_some() => {
                let what = format!("{n}= (a word of spindle {}, not the master spindle)", &n[1..]);
                let hint = "the FANUC profile has one spindle, the Siemens master spindle (spindle 1)";
                return Err(unsup(ctx, "NC505", wspan, &what, hint));
            }
            Addr::Name(n) => {
                let what = format!("address {n}=");
                return Err(unsup(ctx, "NC312", wspan, &what, "no FANUC address has this meaning"));
            }
            Addr::Letter(_) => {}
        }
        let letter = match w.addr {
            Addr::Letter(l) => l,
            Addr::Name(_) | Addr::Axis(_) => b'?',
        };
        let is_axis = AXES.contains(&letter);
        match &w.value {
            WordValue::Rotary(m, _) => {
                let what = format!("{}={}(…) rotary-axis positioning", w.addr.as_str(), m.name());
                return Err(unsup(ctx, "NC630", wspan, &what, crate::eval::refuse::ROTARY_WHY));
            }
            WordValue::Ac(_) | WordValue::Ic(_) if !is_axis => {
                let what = format!("{}=AC()/IC() on a non-axis address", letter as char);
                return Err(unsup(ctx, "NC313", wspan, &what, "write the arc centre incrementally"));
            }
            WordValue::Ac(_) | WordValue::Ic(_) => {
                let abs = matches!(w.value, WordValue::Ac(_));
                if explicit.is_some_and(|e| e != abs) {
                    mixed = true;
                }
                explicit = Some(abs);
            }
            WordValue::Expr(_) if is_axis => plain_axis = true,
            WordValue::Expr(_) => {}
        }
        let form = match &w.value {
            WordValue::Ac(_) => Some(true),
            WordValue::Ic(_) => Some(false),
            _ => None,
        };
        if let WordValue::Ac(e) | WordValue::Ic(e) = &w.value {
            w.value = WordValue::Expr(e.clone());
        }
        // `S=ROUND(x)`: FANUC rounds the spindle speed half away from zero itself, as ROUND
        // does (the FANUC → Sinumerik translation writes it so).
        if letter == b'S' {
            if let WordValue::Expr(Expr { kind: ExprKind::Func(Func::Round, args), .. }) = &mut w.value {
                if args.len() == 1 {
                    let x = args.remove(0);
                    w.value = WordValue::Expr(x);
                }
            }
        }
        match letter {
            b'G' => match const_of(&w.value) {
                Some(v) if v == 70.0 || v == 700.0 => w.value = WordValue::Expr(num(20.0, wspan)),
                Some(v) if v == 71.0 || v == 710.0 => w.value = WordValue::Expr(num(21.0, wspan)),
                Some(v) if v.fract() == 0.0 && SAME_G.contains(&(v as u32)) => {}
                // Exact stop mode, modal: Siemens G60 is FANUC G61 (G9, one block, and G64
                // contouring are spelt alike).
                Some(60.0) => w.value = WordValue::Expr(num(61.0, wspan)),
                // Smoothing within the machine's axis tolerances: FANUC's cutting mode G64
                // keeps the path through the corners; the run counts the corners as not
                // compared (`eval::machine::lookahead::smoothing`). G641's rounding by a
                // programmed distance ADIS has no FANUC form.
                Some(642.0) => {
                    w.value = WordValue::Expr(num(64.0, wspan));
                    ctx.note(
                        "NC620",
                        wspan,
                        "G642 becomes G64",
                        "FANUC's cutting mode does not smooth the corners within axis tolerances as G642 does; the corners are not compared",
                    );
                }
                Some(v) => {
                    let what = format!("G{v}");
                    return Err(unsup(ctx, "NC311", wspan, &what, "no FANUC G code has the same meaning"));
                }
                None => {
                    return Err(unsup(ctx, "NC311", wspan, "a computed G code", "write the G code as a constant"));
                }
            },
            b'F' if dwell => w.addr = Addr::Letter(b'X'),
            b'S' if dwell => {
                return Err(unsup(
                    ctx,
                    "NC319",
                    wspan,
                    "G4 S (dwell in revolutions)",
                    "write the dwell in seconds (G4 F)",
                ));
            }
            b'F' => {
                let op = match m.s.units.feed() {
                    Feed::Static(FeedConv::Same) => None,
                    Feed::Static(FeedConv::PerInch) => Some(BinOp::Div),
                    Feed::Static(FeedConv::PerMm) => Some(BinOp::Mul),
                    Feed::Unknown => {
                        let what = "a feed where the units (G70/G71/G700/G710) depend on the path taken or on a call";
                        let hint = "write G700 or G710 before the F word, after the IF, loop, jump target or call";
                        return Err(unsup(ctx, "NC324", wspan, what, hint));
                    }
                };
                if let (Some(op), WordValue::Expr(e)) = (op, &w.value) {
                    w.value = WordValue::Expr(bin(op, e.clone(), num(25.4, wspan)));
                }
            }
            b'T' => {
                if let WordValue::Expr(Expr { kind: ExprKind::Str(name), span }) = &w.value {
                    match ctx.tools.get(name) {
                        Some(&n) => {
                            ctx.tools_used.insert(name.clone(), n);
                            w.value = WordValue::Expr(num(n as f64, *span));
                        }
                        None => {
                            // Never chosen here: a T number selects a pocket and its offsets.
                            let msg = format!("tool \"{name}\" has no FANUC tool number");
                            let hint = format!(
                                "give the T number the machine has this tool under: --tool-map {name}=<number>, \
                                 or `\"{name}\" = <number>` under [tools] in nctrans.toml (nctrans never chooses one)"
                            );
                            ctx.error("NC301", *span, &msg, &hint);
                            ctx.unsupported += 1;
                            w.value = WordValue::Expr(num(0.0, *span));
                        }
                    }
                }
            }
            _ => {}
        }
        forms.push(form);
        out.push(w);
    }
    let (mut pre, mut post) = (vec![], vec![]);
    if let Some(mut abs) = explicit {
        if mixed || (plain_axis && m.s.abs != Some(abs)) {
            abs = mixed::rewrite(ctx, &mut out, &forms, m, plain_axis, has_call, span)?;
        }
        if m.s.abs != Some(abs) {
            // Switch for this block, then back to the mode in force. The block's own G90/G91
            // words are in `m.s.abs` already (the restore block sets that mode) and must go:
            // FANUC takes the last G code of a group in a block, so they would undo the switch.
            out.retain(|w| !(w.addr.is(b'G') && matches!(const_of(&w.value), Some(v) if v == 90.0 || v == 91.0)));
            let g = |v: f64| Word { addr: Addr::Letter(b'G'), value: WordValue::Expr(num(v, span)), span };
            out.insert(0, g(if abs { 90.0 } else { 91.0 }));
            let restore = match m.s.abs {
                Some(prev) => WordValue::Expr(num(if prev { 90.0 } else { 91.0 }, span)),
                None => {
                    let t = ctx.temp(span);
                    let sys = VarRef { kind: VarKind::Hash(4003), span };
                    pre.push(block_stmt(vec![assign_item(&t, var_expr(&sys), span)], span));
                    WordValue::Expr(var_expr(&t))
                }
            };
            let w = Word { addr: Addr::Letter(b'G'), value: restore, span };
            post.push(block_stmt(vec![item(ItemKind::Word(w), span)], span));
        }
    }
    Ok((out, pre, post))
}

fn unsup(ctx: &mut Ctx, code: &'static str, span: Span, what: &str, hint: &str) -> Vec<Stmt> {
    ctx.unsupported(code, span, what, hint).into_iter().collect()
}

mod built;
mod calls;
mod prog_call;
mod save;
#[cfg(test)]
mod tests;
