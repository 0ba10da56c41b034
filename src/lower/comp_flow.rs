//! What both compensation translations share (`comp_to_fanuc`, `to_sinumerik::comp`): the
//! H ↔ T/D mapping, values known or not on every path, and a walk over a program body that
//! carries a state through blocks, structures and jump targets.
//!
//! The mapping (docs/translation.md, "Tool compensation"): by default FANUC length register
//! H n and radius register D n belong to cutting edge D1 of tool n; `[offsets]` in
//! nctrans.toml (`"6.2" = "H26,D46"`) names the registers of any other edge. A
//! register the mapping does not give is refused, never guessed.

use crate::ir::*;
use std::collections::BTreeMap;

/// A block handed to a [`walk`]'s step: the state, the block, whether the step is live, and
/// where its statements go.
pub type Step<'a, S> = dyn FnMut(&mut S, Block, bool, &mut Vec<Stmt>) + 'a;

/// A value known on every path here, or not.
#[derive(Clone, Debug, PartialEq)]
pub enum K<T> {
    Known(T),
    Unknown,
}

impl<T: Clone + PartialEq> K<T> {
    pub fn merge(&self, other: &K<T>) -> K<T> {
        if self == other {
            self.clone()
        } else {
            K::Unknown
        }
    }

    pub fn known(&self) -> Option<&T> {
        match self {
            K::Known(t) => Some(t),
            K::Unknown => None,
        }
    }
}

/// A state a walk carries through a program.
pub trait FlowState: Clone + PartialEq {
    /// Nothing known (a jump target, the start of a subprogram).
    fn unknown() -> Self;
    /// What two paths meeting here agree on.
    fn merge(&self, other: &Self) -> Self;
    /// Whether every block must be seen now, also inside structures without compensation
    /// words (a tool change waiting for its length: any block in between matters).
    fn watches_every_block(&self) -> bool {
        false
    }
}

/// The constant value of a word, if it is one.
pub fn const_word(w: &Word) -> Option<f64> {
    match &w.value {
        WordValue::Expr(e) => const_expr(e),
        _ => None,
    }
}

pub fn const_expr(e: &Expr) -> Option<f64> {
    match &e.kind {
        ExprKind::Num(n) => Some(n.value),
        ExprKind::Unary(UnOp::Neg, x) => const_expr(x).map(|v| -v),
        _ => None,
    }
}

/// Whether a constant letter word is one the compensation translation reads: D, H (FANUC),
/// T, G40–G49, M6. The streamed translators translate a program with one whole (the
/// translation carries the tool and the compensation from block to block).
pub fn relevant_word(letter: u8, value: Option<f64>, fanuc: bool) -> bool {
    match letter {
        b'D' | b'T' => true,
        b'H' => fanuc,
        // A computed G code is no compensation code: the Sinumerik → FANUC words pass writes
        // `G#…` only to restore G90/G91, and FANUC `G#1` is refused by the words pass.
        b'G' => value.is_some_and(|g| (40.0..50.0).contains(&g)),
        b'M' => value.is_none_or(|m| m == 6.0),
        _ => false,
    }
}

/// Whether a constant letter word makes a streamed translation read the program whole: a
/// compensation word (D, FANUC H, G40–G49), and M6 where `m6` (Sinumerik → FANUC, and the
/// segmented FANUC → Sinumerik path). A T word alone changes nothing the translation writes.
/// The straight FANUC → Sinumerik stream takes M6 blocks through the passes (`T1 M6 D0`):
/// without a compensation word in the program the length is off at every tool change.
pub fn stream_relevant_word(letter: u8, value: Option<f64>, fanuc: bool, m6: bool) -> bool {
    match letter {
        b'T' => false,
        b'M' => m6 && relevant_word(letter, value, fanuc),
        _ => relevant_word(letter, value, fanuc),
    }
}

/// [`stream_relevant_word`] of a block's words.
pub fn stream_relevant_items(items: &[Item], fanuc: bool, m6: bool) -> bool {
    items.iter().any(|it| match &it.kind {
        ItemKind::Word(Word { addr: Addr::Letter(l), value, .. }) => {
            let v = match value {
                WordValue::Expr(e) => const_expr(e),
                _ => None,
            };
            stream_relevant_word(*l, v, fanuc, m6)
        }
        ItemKind::IfThen { then, .. } => stream_relevant_items(std::slice::from_ref(then), fanuc, m6),
        _ => false,
    })
}

/// Whether a body holds a block with [`stream_relevant_items`].
pub fn stream_relevant(body: &[Stmt], fanuc: bool, m6: bool) -> bool {
    let mut any = false;
    crate::ir::visit::walk_stmts(body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            any |= stream_relevant_items(&b.items, fanuc, m6);
        }
    });
    any
}

/// Whether `items` hold a word the compensation translation reads ([`relevant_word`]).
pub fn relevant_items(items: &[Item], fanuc: bool) -> bool {
    items.iter().any(|it| match &it.kind {
        ItemKind::Word(w) => match w.addr {
            Addr::Letter(l) => relevant_word(l, const_word(w), fanuc),
            _ => false,
        },
        ItemKind::IfThen { then, .. } => relevant_items(std::slice::from_ref(then), fanuc),
        _ => false,
    })
}

/// Whether a body holds a block with [`relevant_items`].
pub fn relevant(body: &[Stmt], fanuc: bool) -> bool {
    let mut any = false;
    crate::ir::visit::walk_stmts(body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            any |= relevant_items(&b.items, fanuc);
        }
    });
    any
}

/// What a call runs, as far as the tool and the compensation go: a program among those
/// translated (looked up in the summary), nothing that touches them (a drilling cycle, a
/// Haas `M97` local subprogram whose blocks are the caller's own, data output), or a
/// program not known here.
pub enum CallRuns<K> {
    Program(K),
    Harmless,
    Unknown,
}

/// Whether `items` make a call that may change the tool or the compensation, given what
/// each called program does (`tools(k)`: `None` for a program not in the summary).
fn calls_touch<K>(items: &[Item], runs: &dyn Fn(&Call) -> CallRuns<K>, tools: &dyn Fn(&K) -> Option<bool>) -> bool {
    items.iter().any(|it| match &it.kind {
        ItemKind::Call(c) => match runs(c) {
            CallRuns::Program(k) => tools(&k) != Some(false),
            CallRuns::Harmless => false,
            CallRuns::Unknown => true,
        },
        ItemKind::IfThen { then, .. } => calls_touch(std::slice::from_ref(then), runs, tools),
        ItemKind::IfBlock { items, .. } => calls_touch(items, runs, tools),
        _ => false,
    })
}

/// The one summary of what a subprogram does to the tool and the compensation (both
/// directions read it: `Effect::tools` Sinumerik → FANUC, `ProgPlan::tools` FANUC →
/// Sinumerik): whether `p` may change them, by a word the translation reads
/// ([`relevant_items`]: T, D, FANUC H, G40–G49, M6) or by a call of a program that may or
/// that is not among those translated.
pub fn program_tools<K>(
    p: &Program,
    fanuc: bool,
    runs: &dyn Fn(&Call) -> CallRuns<K>,
    tools: &dyn Fn(&K) -> Option<bool>,
) -> bool {
    program_touches(p, &|items| relevant_items(items, fanuc), runs, tools)
}

/// Whether `p` has a block `touches` (or a call of a program that may touch, by
/// `effects(k)`, or that is not known): the walk behind [`program_tools`], for any mode a
/// translation follows through calls (the tool here, the frame modes in
/// `to_sinumerik::modal::frame_calls`).
pub fn program_touches<K>(
    p: &Program,
    touches: &dyn Fn(&[Item]) -> bool,
    runs: &dyn Fn(&Call) -> CallRuns<K>,
    effects: &dyn Fn(&K) -> Option<bool>,
) -> bool {
    let mut any = false;
    crate::ir::visit::walk_stmts(&p.body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            any |= touches(&b.items) || calls_touch(&b.items, runs, effects);
        }
    });
    any
}

/// [`program_tools`] of every program of `progs` (keyed by how calls name them), followed
/// through calls among them to a fixed point: every program starts as harmless and a pass
/// only turns programs into tool changers, so at most one pass per program plus one.
pub fn tool_effects<K: Ord + Clone>(
    progs: &[(K, &Program)],
    fanuc: bool,
    runs: &dyn Fn(&Call) -> CallRuns<K>,
) -> BTreeMap<K, bool> {
    touch_effects(progs, &|items| relevant_items(items, fanuc), runs)
}

/// [`program_touches`] of every program of `progs`, followed through calls to a fixed
/// point as [`tool_effects`] does.
pub fn touch_effects<K: Ord + Clone>(
    progs: &[(K, &Program)],
    touches: &dyn Fn(&[Item]) -> bool,
    runs: &dyn Fn(&Call) -> CallRuns<K>,
) -> BTreeMap<K, bool> {
    let mut map: BTreeMap<K, bool> = progs.iter().map(|(k, _)| (k.clone(), false)).collect();
    for _ in 0..=progs.len() {
        // Two programs under one name (reported elsewhere) count as one that does both.
        let mut next: BTreeMap<K, bool> = BTreeMap::new();
        for (k, p) in progs {
            let t = program_touches(p, touches, runs, &|c| map.get(c).copied());
            *next.entry(k.clone()).or_default() |= t;
        }
        if next == map {
            break;
        }
        map = next;
    }
    map
}

/// Whether a body jumps (a GOTO anywhere): its labels and N numbers are then places where
/// paths meet.
pub fn jumps(body: &[Stmt]) -> bool {
    crate::lower::landings::Landings::of(body).any()
}

/// Walks `body` with the state `st`, handing every block to `step` (`live`: false while a
/// loop's or a jump target's state is found, when `step` must neither report nor change
/// anything that stays). Structures without a relevant word are passed over; a loop body
/// starts in what its entry and its end agree on; a jump target (when the body jumps)
/// starts in what the blocks before it and every jump to it agree on, found by walking the
/// body again until the targets' states hold (a jump whose target is computed, or states
/// that do not settle, make every target know nothing).
pub fn walk<S: FlowState>(
    body: Vec<Stmt>,
    st: &mut S,
    jumping: bool,
    fanuc: bool,
    step: &mut Step<'_, S>,
    live: bool,
) -> Vec<Stmt> {
    if !jumping {
        return walk_in(body, st, &mut Jumps::None, fanuc, step, live);
    }
    let mut jumps = Jumps::Blind;
    if resolvable(&body) {
        let (mut at, mut ends): (BTreeMap<String, S>, BTreeMap<String, S>) = Default::default();
        for _ in 0..5 {
            let mut probe = st.clone();
            let mut pass =
                Jumps::Known { at: at.clone(), seen: BTreeMap::new(), ends: ends.clone(), ends_seen: BTreeMap::new() };
            walk_in(body.clone(), &mut probe, &mut pass, fanuc, step, false);
            let Jumps::Known { seen, ends_seen, .. } = pass else { break };
            let (next_at, next_ends) = (joined(&at, seen), joined(&ends, ends_seen));
            if next_at == at && next_ends == ends {
                jumps = Jumps::Known { at, seen: BTreeMap::new(), ends, ends_seen: BTreeMap::new() };
                break;
            }
            (at, ends) = (next_at, next_ends);
        }
    }
    walk_in(body, st, &mut jumps, fanuc, step, live)
}

/// `old` with the states of `new` merged in, key by key.
fn joined<S: FlowState>(old: &BTreeMap<String, S>, new: BTreeMap<String, S>) -> BTreeMap<String, S> {
    let mut out = old.clone();
    for (k, v) in new {
        let m = out.get(&k).map_or_else(|| v.clone(), |o| o.merge(&v));
        out.insert(k, m);
    }
    out
}

/// How a walk treats jump targets.
enum Jumps<S> {
    /// The body does not jump.
    None,
    /// Every labelled or numbered block may be a target from anywhere: it knows nothing.
    Blind,
    /// The states at the targets (by [`meta_keys`]) and those this walk's jumps carry; the
    /// states after each labelled block (where a `REPEAT` section ends and the run goes on
    /// after the REPEAT) and those this walk leaves there.
    Known {
        at: BTreeMap<String, S>,
        seen: BTreeMap<String, S>,
        ends: BTreeMap<String, S>,
        ends_seen: BTreeMap<String, S>,
    },
}

impl<S: FlowState> Jumps<S> {
    /// The state at a statement whose lines carry `metas`, arriving with `st`.
    fn arrive(&self, metas: &[&BlockMeta], st: &mut S) {
        match self {
            Jumps::None => {}
            Jumps::Blind => {
                if metas.iter().any(|m| m.label.is_some() || m.number.is_some()) {
                    *st = st.merge(&S::unknown());
                }
            }
            Jumps::Known { at, .. } => {
                for m in metas {
                    for k in meta_keys(m) {
                        if let Some(s) = at.get(&k) {
                            *st = st.merge(s);
                        }
                    }
                }
            }
        }
    }

    /// A jump to each of `keys` leaves with `st`.
    fn leave(&mut self, keys: &[String], st: &S) {
        if let Jumps::Known { seen, .. } = self {
            for k in keys {
                let m = seen.get(k).map_or_else(|| st.clone(), |old| old.merge(st));
                seen.insert(k.clone(), m);
            }
        }
    }

    /// The block found by `keys` ran, leaving `st`; then its `REPEAT` (if any) runs its section
    /// (from the start label, or the one labelled block) and goes on after it with what the
    /// section's end leaves (merged with `st` where the count may be 0).
    fn after_block(&mut self, keys: Vec<String>, repeat: Option<&RepeatSection>, st: &mut S) {
        let Jumps::Known { ends, ends_seen, .. } = self else { return };
        for k in keys {
            let m = ends_seen.get(&k).map_or_else(|| st.clone(), |old| old.merge(st));
            ends_seen.insert(k, m);
        }
        let Some(r) = repeat else { return };
        let start = format!("L:{}", r.start.name.to_ascii_uppercase());
        let end = if r.single {
            Some(start.clone())
        } else {
            r.end.as_ref().map(|l| format!("L:{}", l.name.to_ascii_uppercase()))
        };
        let once = r.count.as_ref().is_none_or(|c| matches!(crate::lower::literal(c), Some(n) if n >= 1.0));
        // No end label: the section ends right before the REPEAT, where `st` stands.
        let after = end.and_then(|e| ends.get(&e).cloned());
        self.leave(&[start], st);
        if let Some(after) = after {
            *st = if once { after } else { after.merge(st) };
        }
    }
}

/// The keys a block is found by as a jump target: its label and its N number.
fn meta_keys(m: &BlockMeta) -> Vec<String> {
    let mut out = Vec::new();
    if let Some(l) = &m.label {
        out.push(format!("L:{}", l.name.to_ascii_uppercase()));
    }
    if let Some(n) = &m.number {
        out.push(format!("N:{}", n.value));
    }
    out
}

fn goto_key(g: &Goto) -> Option<String> {
    match &g.target {
        Target::Label(l) => Some(format!("L:{}", l.name.to_ascii_uppercase())),
        Target::Number(n) => Some(format!("N:{}", n.value)),
        Target::Computed(_) => None,
    }
}

/// The jumps of one item (`None` in the list for a target not known before the run).
fn item_gotos(it: &Item, out: &mut Vec<Option<String>>) {
    match &it.kind {
        ItemKind::Goto(g) => out.push(goto_key(g)),
        ItemKind::IfThen { then, .. } => item_gotos(then, out),
        ItemKind::IfBlock { items, .. } => items.iter().for_each(|i| item_gotos(i, out)),
        ItemKind::Case(c) => {
            out.extend(c.arms.iter().map(|a| goto_key(&a.goto)));
            out.extend(c.default.iter().map(goto_key));
        }
        _ => {}
    }
}

/// The jump targets of every block of `body` (its structures too).
fn body_gotos(body: &[Stmt]) -> Vec<Option<String>> {
    let mut out = Vec::new();
    crate::ir::visit::walk_stmts(body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            for it in &b.items {
                item_gotos(it, &mut out);
            }
        }
    });
    out
}

/// Whether every way into a labelled block of `body` is a jump of `body` naming its target
/// (a `REPEAT` jumps to its section's start and on from its end, [`Jumps::after_block`]): no
/// computed target, no return to a label (`M99 P…`, `RET("…")`) and no call of a program,
/// which may return to one of this body's blocks (drilling cycles and CYCLE832 return where
/// they were called).
fn resolvable(body: &[Stmt]) -> bool {
    fn other_entry(it: &Item) -> bool {
        match &it.kind {
            ItemKind::Return { to: Some(_) } => true,
            ItemKind::Call(c) => !matches!(&c.target, CallTarget::Name(n)
                if n.eq_ignore_ascii_case("CYCLE832")
                    || crate::dialect::sinumerik::cycles::cycle_of(&n.to_ascii_uppercase()).is_some()),
            ItemKind::IfThen { then, .. } => other_entry(then),
            ItemKind::IfBlock { items, .. } => items.iter().any(other_entry),
            _ => false,
        }
    }
    let mut other = false;
    crate::ir::visit::walk_stmts(body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            other |= b.items.iter().any(other_entry);
        }
    });
    !other && body_gotos(body).iter().all(Option::is_some)
}

fn walk_in<S: FlowState>(
    body: Vec<Stmt>,
    st: &mut S,
    jumps: &mut Jumps<S>,
    fanuc: bool,
    step: &mut Step<'_, S>,
    live: bool,
) -> Vec<Stmt> {
    let mut out = Vec::with_capacity(body.len());
    for s in body {
        jumps.arrive(&crate::ir::visit::metas(&s.kind), st);
        let span = s.span;
        let mut s = match s.kind {
            StmtKind::Block(b) => {
                let mut gotos = Vec::new();
                for it in &b.items {
                    item_gotos(it, &mut gotos);
                }
                // Only a walk that knows its targets needs the block's keys and REPEAT.
                let (keys, repeat) = match jumps {
                    Jumps::Known { .. } => (
                        meta_keys(&b.meta),
                        b.items.iter().find_map(|it| match &it.kind {
                            ItemKind::RepeatSection(r) => Some((**r).clone()),
                            _ => None,
                        }),
                    ),
                    _ => (Vec::new(), None),
                };
                step(st, b, live, &mut out);
                jumps.leave(&gotos.into_iter().flatten().collect::<Vec<_>>(), st);
                jumps.after_block(keys, repeat.as_ref(), st);
                continue;
            }
            kind => Stmt { kind, span },
        };
        if !relevant(std::slice::from_ref(&s), fanuc) && !st.watches_every_block() {
            // Nothing in it changes the state: its jumps leave with the state here.
            let gotos: Vec<String> = body_gotos(std::slice::from_ref(&s)).into_iter().flatten().collect();
            jumps.leave(&gotos, st);
            out.push(s);
            continue;
        }
        match &mut s.kind {
            StmtKind::If(i) => {
                let entry = st.clone();
                i.then_body = walk_in(std::mem::take(&mut i.then_body), st, jumps, fanuc, step, live);
                let then_end = std::mem::replace(st, entry);
                if let Some(e) = &mut i.else_part {
                    e.body = walk_in(std::mem::take(&mut e.body), st, jumps, fanuc, step, live);
                }
                *st = st.merge(&then_end);
            }
            kind => {
                if let Some(body) = loop_body(kind) {
                    // The state at the loop head: what the entry and every pass's end agree on.
                    let mut head = st.clone();
                    for _ in 0..3 {
                        let mut probe = head.clone();
                        walk_in(body.clone(), &mut probe, jumps, fanuc, step, false);
                        let next = head.merge(&probe);
                        if next == head {
                            break;
                        }
                        head = next;
                    }
                    let mut probe = head.clone();
                    walk_in(body.clone(), &mut probe, jumps, fanuc, step, false);
                    if head.merge(&probe) != head {
                        head = S::unknown();
                    }
                    *st = head.clone();
                    *body = walk_in(std::mem::take(body), st, jumps, fanuc, step, live);
                    // A loop may run no pass (WHILE, FOR) or leave at its test.
                    *st = head.merge(st);
                }
            }
        }
        out.push(s);
    }
    out
}

fn loop_body(kind: &mut StmtKind) -> Option<&mut Vec<Stmt>> {
    match kind {
        StmtKind::While(w) => Some(&mut w.body),
        StmtKind::Loop(l) => Some(&mut l.body),
        StmtKind::For(f) => Some(&mut f.body),
        StmtKind::Repeat(r) => Some(&mut r.body),
        StmtKind::Do(d) => Some(&mut d.body),
        StmtKind::If(_) | StmtKind::Block(_) => None,
    }
}

/// Whether `e` reads one of the system variables `names` (`$P_GG`, any indices).
pub fn reads_system(e: &Expr, names: &[&str]) -> bool {
    if let ExprKind::Var(v) = &e.kind {
        if let VarKind::System { name, .. } = &v.kind {
            if names.iter().any(|n| name.eq_ignore_ascii_case(n)) {
                return true;
            }
        }
    }
    e.children().into_iter().any(|c| reads_system(c, names))
}

/// Folds the reads of a value the program itself settled (a system variable FANUC has no
/// counterpart of, `$P_TOOLNO`, `$P_GG[1]`): walks `prog` from nothing known with `apply`
/// (the state after a block's items, and whether they touch what is read), and in each live
/// block that does not touch it replaces each read of one of `names` whose `value` (from its
/// name, upper case, its indices and the state) is known by that number. Nothing is walked
/// unless the program reads one of `names`.
pub fn fold_reads<S: FlowState>(
    prog: &mut Program,
    names: &[&str],
    apply: fn(&[Item], S) -> (S, bool),
    value: fn(&str, &[Expr], &S) -> Option<f64>,
) {
    let mut any = false;
    crate::ir::visit::walk_stmts(&prog.body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            any |=
                b.items.iter().any(|it| crate::ir::visit::item_exprs(it).into_iter().any(|e| reads_system(e, names)));
        }
    });
    if !any {
        return;
    }
    fn fold<S>(e: &mut Expr, names: &[&str], value: fn(&str, &[Expr], &S) -> Option<f64>, st: &S) {
        if let ExprKind::Var(v) = &e.kind {
            if let VarKind::System { name, indices } = &v.kind {
                let upper = name.to_ascii_uppercase();
                if names.contains(&upper.as_str()) {
                    if let Some(x) = value(&upper, indices, st) {
                        *e = crate::lower::num(x, e.span);
                    }
                }
                return;
            }
        }
        for c in crate::lower::children_mut(e) {
            fold(c, names, value, st);
        }
    }
    let jumping = jumps(&prog.body);
    let body = std::mem::take(&mut prog.body);
    let mut st = S::unknown();
    let mut step = |st: &mut S, mut b: Block, live: bool, out: &mut Vec<Stmt>| {
        let (after, touches) = apply(&b.items, st.clone());
        // In a block that sets the value itself, which one the read sees is not settled.
        if live && !touches {
            for it in &mut b.items {
                crate::lower::item_exprs_mut(it, &mut |e: &mut Expr| fold(e, names, value, st));
            }
        }
        *st = if b.meta.skip.is_some() { after.merge(st) } else { after };
        out.push(crate::lower::meta_stmt(b.meta, b.items));
    };
    prog.body = walk(body, &mut st, jumping, false, &mut step, true);
}
