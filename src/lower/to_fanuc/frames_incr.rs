//! Sinumerik → FANUC: which incremental moves after a TRANS (FANUC `G52`) the two controls
//! travel alike (docs/translation.md, "Coordinate systems and reference points").
//!
//! The first incremental move of an axis after its frame changed travels the change too on
//! Siemens (MD42440 FRAME_OFFSET_INCR_PROG = 1, `Semantics::incremental_travels_offset`); on
//! FANUC after `G52` it travels the increment only. Once the axis has been programmed in the
//! new frame the two agree again. So an axis is *stale* from a frame instruction that changes
//! its shift (TRANS, which becomes G52; ROT, SCALE, MIRROR, which delete the shift) until a
//! block programs it absolutely (a G90 word, `AC()`), and a possibly incremental word of a
//! stale axis (G91 or G90/G91 not known, `IC()`) is refused, NC445, naming the frame
//! instruction. Everything else translates: the proof runs both and compares.
//!
//! The flow is followed conservatively: IF branches and loop passes meet (an axis stale on one
//! path is stale), a block a jump may land on (`Landings`) meets every state a jump of the
//! program leaves, a `REPEAT` meets every state of the program, a skippable block both ways.
//! A called program is summarised ([`summary`], kept in its `Effect`): the axes it may move
//! incrementally before programming them itself (by the mode it is called in), and those its
//! own frame instructions leave stale at its end; a call where such an axis is stale is
//! refused, and a callee not among those translated may move any axis.

use super::words::effects::Effect;
use super::*;
use crate::lower::landings::Landings;

/// The start of the refusal of a segmented stream's run (a placeholder) where an axis is
/// stale: its blocks are not looked into, so the stream reads such a program whole.
pub const STAND_IN: &str = "motion blocks not looked into";

const AXES: &[u8; 9] = b"XYZABCUVW";
const ALL: u16 = (1 << 9) - 1;

/// What changes each frame instruction makes to the flow (`Plan`), where the lowering looks
/// up each block.
#[derive(Clone, Debug, Default)]
pub struct Plan {
    /// The refusals by the start of the item (or stand-in block) they stand at.
    refused: BTreeMap<u32, Refusal>,
}

#[derive(Clone, Debug)]
struct Refusal {
    at: Span,
    axis: u8,
    /// The frame instruction (or call) after which the axis is not yet programmed again.
    cause: Span,
    cause_call: bool,
    what: What,
}

#[derive(Clone, Debug)]
enum What {
    Word,
    Call(String),
    UnknownCall,
    StandIn,
}

/// The flow's state before a block.
#[derive(Clone, Copy, Debug, PartialEq)]
struct St {
    /// Some path reaches here.
    live: bool,
    /// Axes whose shift changed since they were last programmed.
    stale: u16,
    /// Per stale axis, what changed it, and whether that was a call.
    cause: [(Span, bool); 9],
    /// Axes not programmed since the program was entered (what a caller's frame may leave).
    entry: u16,
    /// The shift of each axis where it is one known value.
    shift: [Option<f64>; 9],
    /// G90 (`Some(true)`), G91, or not known.
    abs: Option<bool>,
    /// A modal call (MCALL) of a subprogram may be in force: its effect, `None` unknown.
    mcall: Option<Option<Effect>>,
}

impl St {
    const DEAD: St = St {
        live: false,
        stale: 0,
        cause: [(Span::new(0, 0), false); 9],
        entry: 0,
        shift: [None; 9],
        abs: None,
        mcall: None,
    };

    fn merge(self, o: St) -> St {
        if !self.live {
            return o;
        }
        if !o.live {
            return self;
        }
        let mut cause = self.cause;
        for (i, c) in cause.iter_mut().enumerate() {
            if self.stale & (1 << i) == 0 && o.stale & (1 << i) != 0 {
                *c = o.cause[i];
            }
        }
        let mut shift = self.shift;
        for (s, o) in shift.iter_mut().zip(o.shift) {
            if *s != o {
                *s = None;
            }
        }
        let mcall = match (self.mcall, o.mcall) {
            (a, b) if a == b => a,
            (None, b) => b,
            (a, None) => a,
            _ => Some(None),
        };
        St {
            live: true,
            stale: self.stale | o.stale,
            cause,
            entry: self.entry | o.entry,
            shift,
            abs: self.abs.filter(|a| o.abs == Some(*a)),
            mcall,
        }
    }

    fn make_stale(&mut self, bits: u16, cause: Span, call: bool) {
        for i in 0..9 {
            if bits & (1 << i) != 0 && self.stale & (1 << i) == 0 {
                self.cause[i] = (cause, call);
            }
        }
        self.stale |= bits;
    }
}

struct Walk<'a> {
    jumps: Landings,
    known: &'a dyn Fn(&str) -> Option<Effect>,
    /// What may arrive at a landing: the merge of the states at every jump of the program.
    jumped: St,
    /// The merge of the state after every block (a REPEAT section may end at any).
    anywhere: St,
    /// Both, as this pass finds them.
    next_jumped: St,
    next_anywhere: St,
    /// The states where the program ends or returns.
    exits: St,
    /// Passes over a loop's body that look for its head's state note nothing.
    scratch: bool,
    refused: BTreeMap<u32, Refusal>,
    /// Axes moved (maybe) incrementally while not yet programmed since entry.
    incr_first: u16,
    /// Each loop's head (by its statement's address) for the entry states met this pass.
    memo: std::collections::HashMap<usize, Vec<(St, St)>>,
}

/// The name under which the `known` lookups give what any of the translated programs may
/// do ([`any_callee`]): the target of a call whose name is computed at run time.
pub const ANY_CALLEE: &str = "*";

/// What any of `effects` may do (for a call that may reach each), `None` without any.
pub fn any_callee<'a>(effects: impl Iterator<Item = &'a Effect>) -> Option<Effect> {
    effects.copied().reduce(|a, b| Effect {
        sets: a.leaves() | b.leaves(),
        save: false,
        frames: a.frames || b.frames,
        incr_first: [a.incr_first[0] | b.incr_first[0], a.incr_first[1] | b.incr_first[1]],
        stale_exit: a.stale_exit | b.stale_exit,
        abs_exit: [0, 1].map(|k| a.abs_after_call(k).filter(|x| b.abs_after_call(k) == Some(*x))),
        ..a
    })
}

/// The plan of a program being lowered (`main`: its frame starts without a shift, in G90).
pub fn plan(body: &[Stmt], main: bool, callees: &BTreeMap<String, Callee>) -> Plan {
    let any = any_callee(callees.values().map(|c| &c.effect));
    let known = |n: &str| if n == ANY_CALLEE { any } else { callees.get(n).map(|c| c.effect) };
    let start = St {
        live: true,
        shift: if main { [Some(0.0); 9] } else { [None; 9] },
        abs: if main { Some(true) } else { None },
        ..St::DEAD
    };
    let w = analyse(body, start, &known);
    Plan { refused: w.refused }
}

/// A called program's summary for its callers (kept in its `Effect`).
#[derive(Clone, Copy, Debug, Default)]
pub struct Summary {
    /// The axes it may move incrementally before programming them, called in G90 and in G91.
    pub incr_first: [u16; 2],
    /// The axes its own frame instructions (or its callees') leave stale at its end.
    pub stale_exit: u16,
    /// G90/G91 at its end, called in G90 and in G91.
    pub abs_exit: [Option<bool>; 2],
}

/// The [`Summary`] of a called program (`save`: `PROC … SAVE`).
pub fn summary(body: &[Stmt], save: bool, known: &dyn Fn(&str) -> Option<Effect>) -> Summary {
    let mut first = [0; 2];
    let mut abs_exit = [None; 2];
    let mut exit = 0;
    let mut frames = false;
    crate::ir::visit::walk_stmts(body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            frames |= b.items.iter().any(|it| matches!(it.kind, ItemKind::Frame { .. }));
        }
    });
    for (k, abs) in [true, false].into_iter().enumerate() {
        let start = St { live: true, entry: ALL, abs: Some(abs), ..St::DEAD };
        let w = analyse(body, start, known);
        first[k] = w.incr_first;
        exit |= w.exits.stale;
        abs_exit[k] = w.exits.abs;
    }
    // SAVE restores the caller's frame at the end: every axis the callee moved under its
    // own frame has a shift change to travel.
    if save && frames {
        exit = ALL;
    }
    Summary { incr_first: first, stale_exit: exit, abs_exit }
}

fn analyse<'a>(body: &[Stmt], start: St, known: &'a dyn Fn(&str) -> Option<Effect>) -> Walk<'a> {
    let mut w = Walk {
        jumps: Landings::of(body),
        known,
        jumped: St::DEAD,
        anywhere: St::DEAD,
        next_jumped: St::DEAD,
        next_anywhere: St::DEAD,
        exits: St::DEAD,
        scratch: false,
        refused: BTreeMap::new(),
        incr_first: 0,
        memo: Default::default(),
    };
    // Each pass can only make the states at the jumps and blocks more stale or less known:
    // the lattice is small, so this reaches its fixed point.
    for _ in 0..96 {
        w.next_jumped = St::DEAD;
        w.next_anywhere = St::DEAD;
        w.exits = St::DEAD;
        w.refused.clear();
        w.incr_first = 0;
        w.memo.clear();
        let end = w.body(body, start);
        w.exits = w.exits.merge(end);
        let j = w.jumped.merge(w.next_jumped);
        let a = w.anywhere.merge(w.next_anywhere);
        if j == w.jumped && a == w.anywhere {
            break;
        }
        w.jumped = j;
        w.anywhere = a;
    }
    w
}

impl Walk<'_> {
    fn body(&mut self, body: &[Stmt], mut s: St) -> St {
        for st in body {
            s = match &st.kind {
                StmtKind::Block(b) => self.block(b, s),
                StmtKind::If(i) => {
                    let t = self.body(&i.then_body, s);
                    let e = match &i.else_part {
                        Some(e) => self.body(&e.body, s),
                        None => s,
                    };
                    t.merge(e)
                }
                kind => {
                    // A loop: its head holds what every pass brings (to a fixed point), which
                    // is also its exit. Heads are kept per entry state within a pass, so
                    // nested loops are walked once per state, not once per round outside.
                    let key = st as *const Stmt as usize;
                    let bodies = crate::ir::visit::child_bodies(kind);
                    let known = self.memo.get(&key).and_then(|v| v.iter().find(|(e, _)| *e == s)).map(|(_, h)| *h);
                    let head = match known {
                        Some(h) => h,
                        None => {
                            let scratch = std::mem::replace(&mut self.scratch, true);
                            let mut head = s;
                            for _ in 0..96 {
                                let after = bodies.iter().fold(head, |x, b| self.body(b, x));
                                let merged = head.merge(after);
                                if merged == head {
                                    break;
                                }
                                head = merged;
                            }
                            self.scratch = scratch;
                            self.memo.entry(key).or_default().push((s, head));
                            head
                        }
                    };
                    if !self.scratch {
                        // The walk that notes the refusals.
                        let after = bodies.iter().fold(head, |x, b| self.body(b, x));
                        head.merge(after)
                    } else {
                        head
                    }
                }
            };
        }
        s
    }

    fn refuse(&mut self, key: u32, at: Span, bits: u16, s: &St, what: What) {
        if self.scratch {
            return;
        }
        let Some(i) = (0..9).find(|i| bits & (1 << i) != 0) else { return };
        let (cause, cause_call) = s.cause[i];
        self.refused.entry(key).or_insert(Refusal { at, axis: AXES[i], cause, cause_call, what });
    }

    fn block(&mut self, b: &Block, mut s: St) -> St {
        if self.jumps.at(&b.meta) {
            s = s.merge(self.jumped);
        }
        if !s.live {
            return s;
        }
        let before = s;
        if super::stand_in(&b.meta).is_some() {
            // A run of a segmented stream: its blocks may move any axis either way.
            if s.stale != 0 {
                self.refuse(b.meta.span.lo, b.meta.span, s.stale, &s, What::StandIn);
            }
            if !self.scratch {
                self.incr_first |= s.entry;
            }
        }
        let mut machine = false;
        let mut moves = false;
        for it in &b.items {
            match &it.kind {
                ItemKind::Word(w) if w.addr.is(b'G') => match &w.value {
                    WordValue::Expr(e) => match crate::lower::literal(e) {
                        Some(90.0) => s.abs = Some(true),
                        Some(91.0) => s.abs = Some(false),
                        Some(53.0 | 153.0 | 74.0 | 75.0) => machine = true,
                        Some(g) if [70.0, 71.0, 700.0, 710.0].contains(&g) => {
                            // A shift keeps its programmed number in another unit only if 0.
                            for v in s.shift.iter_mut() {
                                *v = v.filter(|v| *v == 0.0);
                            }
                        }
                        Some(_) => {}
                        None => s.abs = None,
                    },
                    _ => s.abs = None,
                },
                ItemKind::Instruction { name } if name == "SUPA" => machine = true,
                _ => {}
            }
        }
        for it in &b.items {
            if let ItemKind::Frame { op, words } = &it.kind {
                frame(op, words, it.span, &mut s);
            }
        }
        for it in &b.items {
            moves |= self.item_words(it, it.span.lo, machine, &mut s);
        }
        if moves && s.mcall.is_some() {
            if let Some(e) = s.mcall {
                // The modal call runs after the motion block.
                self.call_effect(e, None, b.meta.span.lo, b.meta.span, true, &mut s);
            }
        }
        for it in &b.items {
            self.item_flow(it, it.span.lo, &mut s, false);
        }
        if b.meta.skip.is_some() {
            s = s.merge(before);
        }
        self.next_anywhere = self.next_anywhere.merge(s);
        s
    }

    /// The axis words of `it` (in an IF of the block: maybe); whether it moves an axis.
    fn item_words(&mut self, it: &Item, key: u32, machine: bool, s: &mut St) -> bool {
        match &it.kind {
            ItemKind::Word(w) => {
                let bits = axis_bits(&w.addr);
                if bits == 0 {
                    return false;
                }
                if machine {
                    // Machine coordinates for the block: absolute, but not in the frame.
                    return true;
                }
                let inc = match &w.value {
                    WordValue::Ic(_) => Some(true),
                    WordValue::Ac(_) => Some(false),
                    WordValue::Expr(_) => s.abs.map(|a| !a),
                    WordValue::Rotary(..) => return true, // refused elsewhere (NC630)
                };
                let one = bits.count_ones() == 1;
                if inc != Some(false) {
                    if s.stale & bits != 0 {
                        self.refuse(key, w.span, s.stale & bits, s, What::Word);
                    }
                    if !self.scratch {
                        self.incr_first |= s.entry & bits;
                    }
                }
                // Moved: the axis is in the new frame from here on (an incremental move of a
                // stale one is refused above, once).
                if one {
                    s.stale &= !bits;
                    s.entry &= !bits;
                }
                true
            }
            ItemKind::IfThen { then, .. } => {
                let mut t = *s;
                let moved = self.item_words(then, key, machine, &mut t);
                *s = s.merge(t);
                moved
            }
            ItemKind::IfBlock { items, .. } => {
                let mut t = *s;
                let mut moved = false;
                for i in items {
                    moved |= self.item_words(i, key, machine, &mut t);
                }
                *s = s.merge(t);
                moved
            }
            _ => false,
        }
    }

    /// Calls, jumps, returns of `it` (`cond`: in an IF of the block).
    fn item_flow(&mut self, it: &Item, key: u32, s: &mut St, cond: bool) {
        match &it.kind {
            ItemKind::Call(c) => self.call(c, key, it.span, s),
            ItemKind::ModalCallOff => s.mcall = None,
            ItemKind::Goto(g) => {
                self.next_jumped = self.next_jumped.merge(*s);
                // GOTOC may go on when the target is missing.
                if !cond && g.cond.is_none() && !g.missing_continues {
                    *s = St::DEAD;
                }
            }
            ItemKind::Case(_) => self.next_jumped = self.next_jumped.merge(*s),
            ItemKind::RepeatSection(_) => {
                self.next_jumped = self.next_jumped.merge(*s);
                *s = s.merge(self.anywhere);
            }
            ItemKind::Return { .. } | ItemKind::End { .. } => {
                self.exits = self.exits.merge(*s);
                if !cond {
                    *s = St::DEAD;
                }
            }
            ItemKind::IfThen { then, .. } => {
                let mut t = *s;
                self.item_flow(then, key, &mut t, true);
                *s = s.merge(t);
            }
            ItemKind::IfBlock { items, .. } => {
                let mut t = *s;
                for i in items {
                    self.item_flow(i, key, &mut t, true);
                }
                *s = s.merge(t);
            }
            _ => {}
        }
    }

    fn call(&mut self, c: &Call, key: u32, span: Span, s: &mut St) {
        let effect = match &c.target {
            CallTarget::Name(n) => {
                let n = n.to_ascii_uppercase();
                if harmless(&n) {
                    return;
                }
                (self.known)(&n).map(|e| (e, n))
            }
            // A name computed at run time: one of the programs translated (any other is
            // refused where the call is written, NC303).
            _ => (self.known)(ANY_CALLEE).map(|e| (e, "a program named at run time".to_string())),
        };
        if c.kind == CallKind::Mcall {
            s.mcall = Some(effect.map(|(e, _)| e));
            return;
        }
        let repeated = c.repeat.is_some();
        match effect {
            Some((e, n)) => self.call_effect(Some(e), Some(n), key, span, repeated, s),
            None => self.call_effect(None, None, key, span, repeated, s),
        }
    }

    /// The call of a program with effect `e` (`None`: not known) at `span`; `repeated`: it
    /// may run again right after itself (P=n, a modal call).
    fn call_effect(
        &mut self,
        e: Option<Effect>,
        name: Option<String>,
        key: u32,
        span: Span,
        repeated: bool,
        s: &mut St,
    ) {
        let Some(e) = e else {
            if s.stale != 0 {
                self.refuse(key, span, s.stale, s, What::UnknownCall);
            }
            if !self.scratch {
                self.incr_first |= s.entry;
            }
            // A program not translated is refused at the call (NC303): the flow after it
            // does not matter then.
            s.shift = [None; 9];
            s.abs = None;
            return;
        };
        let first = match s.abs {
            Some(true) => e.incr_first[0],
            Some(false) => e.incr_first[1],
            None => e.incr_first[0] | e.incr_first[1],
        };
        let mut stale = *s;
        if repeated {
            stale.make_stale(e.stale_exit, span, true);
        }
        if first & stale.stale != 0 {
            let what = name.map_or(What::UnknownCall, What::Call);
            self.refuse(key, span, first & stale.stale, &stale, what);
        }
        if !self.scratch {
            self.incr_first |= s.entry & first;
        }
        s.make_stale(e.stale_exit, span, true);
        s.entry &= !e.stale_exit;
        if e.frames {
            s.shift = [None; 9];
        }
        s.abs = e.abs_after(s.abs);
    }
}

/// Calls that move no axis (drilling cycles write absolute levels and drill where the tool
/// stands) or are dropped.
fn harmless(n: &str) -> bool {
    crate::dialect::sinumerik::cycles::cycle_of(n).is_some()
        || n == "FGROUP"
        || n == "CYCLE832"
        || super::words::SIMULATION_ONLY.contains(&n)
}

/// A frame instruction: the shifts it sets, and the axes whose shift changes.
fn frame(op: &str, words: &[Word], span: Span, s: &mut St) {
    let new: [Option<f64>; 9] = match op {
        // TRANS replaces the frame: an axis it does not name has no shift.
        "TRANS" => std::array::from_fn(|i| match words.iter().rev().find(|w| w.addr.is(AXES[i])) {
            Some(Word { value: WordValue::Expr(e), .. }) => crate::lower::literal(e),
            Some(_) => None,
            None => Some(0.0),
        }),
        // These delete the programmable frame, its shift with it.
        "ROT" | "SCALE" | "MIRROR" => [Some(0.0); 9],
        // It adds to the named axes (refused in a program with incremental moves, NC577).
        "ATRANS" => {
            let named = words
                .iter()
                .fold(0, |m, w| m | if matches!(w.addr, Addr::Letter(_)) { axis_bits(&w.addr) } else { ALL });
            s.make_stale(named, span, false);
            s.entry &= !named;
            s.shift = std::array::from_fn(|i| if named & (1 << i) != 0 { None } else { s.shift[i] });
            return;
        }
        _ => return,
    };
    let changed = (0..9).filter(|&i| new[i].is_none() || s.shift[i] != new[i]).fold(0u16, |m, i| m | (1 << i));
    s.make_stale(changed, span, false);
    s.entry &= !changed;
    s.shift = new;
}

/// The axes a word's address names: one, every one for an axis chosen at run time, none
/// for another address.
fn axis_bits(a: &Addr) -> u16 {
    match a {
        Addr::Letter(l) => AXES.iter().position(|c| c == l).map_or(0, |i| 1 << i),
        Addr::Axis(e) => match &e.kind {
            ExprKind::Ident(n) if n.len() == 1 => axis_bits(&Addr::Letter(n.as_bytes()[0].to_ascii_uppercase())),
            _ => ALL,
        },
        Addr::Name(_) => 0,
    }
}

/// The refusal standing at block `b`, if any (NC445 at the move or call, the frame
/// instruction beside it).
pub fn refuse(ctx: &mut Ctx, b: &Block, plan: &Plan) -> Option<Vec<Stmt>> {
    if plan.refused.is_empty() {
        return None;
    }
    let r = std::iter::once(b.meta.span.lo)
        .chain(b.items.iter().map(|it| it.span.lo))
        .find_map(|k| plan.refused.get(&k))?
        .clone();
    let a = r.axis as char;
    let tail = "a Sinumerik incremental move after a frame change also travels the change of the shift (MD42440), \
                a FANUC one after G52 travels the increment only";
    let what = match &r.what {
        What::Word => format!(
            "an incremental move of {a} (G91 or IC()) before {a} is programmed absolutely after its shift changed: {tail}"
        ),
        What::Call(n) => format!(
            "a call of {n}, which may move {a} incrementally before programming it absolutely, where {a} is not programmed again after its shift changed: {tail}"
        ),
        What::UnknownCall => format!(
            "a call of a program not among those translated (it may move {a} incrementally) where {a} is not programmed again after its shift changed: {tail}"
        ),
        What::StandIn => format!("{STAND_IN} where {a} is not programmed again after its shift changed: {tail}"),
    };
    let hint =
        format!("program {a} absolutely (G90, or {a}=AC(…)) after the frame change, before moving it incrementally");
    let mark = ctx.unsupported("NC445", r.at, &what, &hint);
    if let Some(d) = ctx.diags.pop() {
        let label = if r.cause_call {
            format!("this call may leave the shift of {a} changed")
        } else {
            format!("the shift of {a} changes here")
        };
        let file = ctx.file;
        ctx.diags.push(d.secondary(file, r.cause, label));
    }
    Some(mark.into_iter().collect())
}
