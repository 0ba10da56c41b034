//! The two modes the words pass follows through a Siemens program (G90/G91, read by
//! AC()/IC() words; the length and feed units, read by F words and calls), known where
//! every path to a block agrees on them. In straight text they follow the G codes block by
//! block; where paths meet they are merged, and a mode the paths disagree on is unknown:
//! after an IF (both branches), at the head of a loop (entry and every later pass, to a
//! fixed point), after a block that may be skipped (`/`), and at a jump target when a
//! mode word lies between a jump and its target. An unknown G90/G91 is read at run time
//! (`#4003`); unknown units decline F words and calls until a unit word (G70, G71, G700,
//! G710: each sets lengths and feeds, [`super::units`]) sets them again.

use super::const_g;
use super::effects::{Effect, UnitEffect, ABS};
use super::units::{FeedConv, Units};
use crate::ir::{Item, ItemKind, Stmt, StmtKind, Target};
use crate::lower::to_fanuc::Callee;
use std::collections::{BTreeMap, HashMap, HashSet};

/// The length and feed units, as far as every path agrees on them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum UnitState {
    Known(Units),
    /// A subprogram's start: lengths and feeds in one unit, the caller's (calls are
    /// declined where the two differ, so this holds for every translated caller).
    Caller,
    /// Paths disagree (or a callee's units on return depend on its path): F words and
    /// calls are declined until a unit word.
    Unknown,
}

/// How an F word is written.
pub(super) enum Feed {
    Static(FeedConv),
    Unknown,
}

impl UnitState {
    pub(super) fn g(&mut self, v: f64) {
        // Each unit word sets lengths and feeds whatever held before (G70/G71 read F in
        // the basic system), so it makes any state known.
        let mut u = Units::default();
        if u.g(v) {
            *self = UnitState::Known(u);
        }
    }

    pub(super) fn feed(self) -> Feed {
        match self {
            UnitState::Known(u) => Feed::Static(u.feed()),
            UnitState::Caller => Feed::Static(FeedConv::Same),
            UnitState::Unknown => Feed::Unknown,
        }
    }

    /// The units after a call of a subprogram with `effect`, from these (one unit).
    fn after_call(&mut self, effect: &Effect) {
        if effect.save {
            return;
        }
        *self = match (effect.units, *self) {
            (UnitEffect::None, s) => s,
            (UnitEffect::Both(u), _) => UnitState::Known(u),
            (UnitEffect::Unknown, _) => UnitState::Unknown,
        };
    }

    /// Lengths and feeds surely in one unit (what a called subprogram assumes at its start).
    pub(super) fn one_unit(self) -> bool {
        matches!(self.feed(), Feed::Static(FeedConv::Same))
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Modes {
    /// `Some(true)` G90, `Some(false)` G91, `None` unknown (a subprogram inherits its caller's).
    pub abs: Option<bool>,
    pub units: UnitState,
}

impl Modes {
    /// What holds where paths with `self` and `other` meet.
    pub(super) fn merge(self, other: Modes) -> Modes {
        Modes {
            abs: if self.abs == other.abs { self.abs } else { None },
            units: if self.units == other.units { self.units } else { UnitState::Unknown },
        }
    }

    /// A constant G word.
    pub(super) fn g(&mut self, v: f64) {
        if v == 90.0 || v == 91.0 {
            self.abs = Some(v == 90.0);
        } else {
            self.units.g(v);
        }
    }

    /// After a call of a subprogram with `effect`.
    pub(super) fn call(&mut self, effect: &Effect) {
        self.abs = effect.abs_after(self.abs);
        self.units.after_call(effect);
    }
}

/// A jump target: a label or an N value.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
enum Key {
    Label(String),
    Number(u32),
}

/// The jump targets where a mode is reset to unknown: a jump reaches them past a word
/// that sets it (every labelled or numbered block, for a computed jump).
#[derive(Default)]
pub(super) struct Resets {
    abs: HashSet<Key>,
    units: HashSet<Key>,
    all_abs: bool,
    all_units: bool,
}

fn callee_effect(it: &Item, callees: &BTreeMap<String, Callee>) -> Option<Effect> {
    match &it.kind {
        ItemKind::Call(c) => match &c.target {
            crate::ir::CallTarget::Name(n) => callees.get(&n.to_ascii_uppercase()).map(|c| c.effect),
            _ => None,
        },
        _ => None,
    }
}

/// Which modes the items of a block may set: (G90/G91, units).
fn sets(items: &[Item], callees: &BTreeMap<String, Callee>) -> (bool, bool) {
    let (mut abs, mut units) = (false, false);
    for it in items {
        if let Some(v) = const_g(it) {
            abs |= v == 90.0 || v == 91.0;
            units |= Units::default().g(v);
        }
        if let Some(e) = callee_effect(it, callees) {
            abs |= e.leaves() & ABS != 0;
            units |= !e.save && e.units != UnitEffect::None;
        }
    }
    (abs, units)
}

impl Resets {
    pub(super) fn of(body: &[Stmt], callees: &BTreeMap<String, Callee>) -> Resets {
        let mut at = 0usize;
        let (mut abs_at, mut units_at) = (Vec::new(), Vec::new());
        let mut targets: Vec<(Key, usize)> = Vec::new();
        let mut jumps: Vec<(Key, usize)> = Vec::new();
        let mut computed = false;
        crate::ir::visit::walk_stmts(body, &mut |s| {
            at += 1;
            for m in crate::ir::visit::metas(&s.kind) {
                if let Some(l) = &m.label {
                    targets.push((Key::Label(l.name.to_ascii_uppercase()), at));
                }
                if let Some(n) = &m.number {
                    targets.push((Key::Number(n.value), at));
                }
            }
            let StmtKind::Block(b) = &s.kind else { return };
            let (a, u) = sets(&b.items, callees);
            if a {
                abs_at.push(at);
            }
            if u {
                units_at.push(at);
            }
            let mut jump = |t: &Target| match t {
                Target::Label(l) => jumps.push((Key::Label(l.name.to_ascii_uppercase()), at)),
                Target::Number(n) => jumps.push((Key::Number(n.value), at)),
                Target::Computed(_) => computed = true,
            };
            for it in &b.items {
                match &it.kind {
                    ItemKind::Goto(g) => jump(&g.target),
                    ItemKind::Case(c) => {
                        c.arms.iter().for_each(|a| jump(&a.goto.target));
                        if let Some(d) = &c.default {
                            jump(&d.target);
                        }
                    }
                    _ => {}
                }
            }
        });
        let mut r = Resets {
            all_abs: computed && !abs_at.is_empty(),
            all_units: computed && !units_at.is_empty(),
            ..Resets::default()
        };
        let mut at_key: HashMap<&Key, Vec<usize>> = HashMap::new();
        for (k, p) in &targets {
            at_key.entry(k).or_default().push(*p);
        }
        // Positions come in walk order, sorted: whether one lies between a jump and its
        // target (the jump's own block included, the target's not) is a binary search.
        let between = |set: &[usize], from: usize, to: usize| {
            let (lo, hi) = (from.min(to), from.max(to));
            let i = set.partition_point(|&p| p < lo);
            set[i..].iter().take_while(|&&p| p <= hi).any(|&p| p != to)
        };
        for (key, from) in &jumps {
            for &to in at_key.get(key).map_or(&[][..], |v| v.as_slice()) {
                if between(&abs_at, *from, to) {
                    r.abs.insert(key.clone());
                }
                if between(&units_at, *from, to) {
                    r.units.insert(key.clone());
                }
            }
        }
        r
    }

    /// The modes at a statement with these metas (a jump target resets what a jump to it
    /// may bring changed).
    pub(super) fn apply(&self, metas: &[&crate::ir::BlockMeta], m: &mut Modes) {
        for meta in metas {
            let keys = meta
                .label
                .iter()
                .map(|l| Key::Label(l.name.to_ascii_uppercase()))
                .chain(meta.number.iter().map(|n| Key::Number(n.value)));
            let any = meta.label.is_some() || meta.number.is_some();
            let (mut abs, mut units) = (self.all_abs && any, self.all_units && any);
            for k in keys {
                abs |= self.abs.contains(&k);
                units |= self.units.contains(&k);
            }
            if abs {
                m.abs = None;
            }
            if units {
                m.units = UnitState::Unknown;
            }
        }
    }

    /// The modes after `body` from `m`, as the words pass follows them (no translation).
    pub(super) fn fold(&self, body: &[Stmt], mut m: Modes, callees: &BTreeMap<String, Callee>) -> Modes {
        for s in body {
            self.apply(&crate::ir::visit::metas(&s.kind), &mut m);
            match &s.kind {
                StmtKind::Block(b) => {
                    let before = m;
                    for it in &b.items {
                        if let Some(v) = const_g(it) {
                            m.g(v);
                        }
                        if let Some(e) = callee_effect(it, callees) {
                            m.call(&e);
                        }
                    }
                    if b.meta.skip.is_some() {
                        m = m.merge(before);
                    }
                }
                StmtKind::If(i) => {
                    let t = self.fold(&i.then_body, m, callees);
                    let e = i.else_part.as_ref().map_or(m, |e| self.fold(&e.body, m, callees));
                    m = t.merge(e);
                }
                kind => m = self.loop_entry(loop_body(kind), m, callees),
            }
        }
        m
    }

    /// The modes at the head of a loop entered with `m`, which hold after it too: `m`
    /// merged with what each pass leaves, to a fixed point (each mode can only become
    /// unknown, so two rounds settle it). A loop that holds loops takes the coarser rule
    /// (every mode its body may set is unknown), so that nested loops cost one walk each
    /// rather than rounds multiplied through the nesting.
    pub(super) fn loop_entry(&self, body: &[Stmt], m: Modes, callees: &BTreeMap<String, Callee>) -> Modes {
        let mut nested = false;
        let (mut abs, mut units) = (false, false);
        crate::ir::visit::walk_stmts(body, &mut |s| match &s.kind {
            StmtKind::Block(b) => {
                let (a, u) = sets(&b.items, callees);
                abs |= a;
                units |= u;
            }
            StmtKind::If(_) => {}
            _ => nested = true,
        });
        if nested {
            return Modes {
                abs: if abs { None } else { m.abs },
                units: if units { UnitState::Unknown } else { m.units },
            };
        }
        let mut e = m;
        for _ in 0..4 {
            let n = e.merge(self.fold(body, e, callees));
            if n == e {
                break;
            }
            e = n;
        }
        e
    }
}

/// The body of a loop statement (empty for a block or an IF).
pub(super) fn loop_body(kind: &StmtKind) -> &[Stmt] {
    match kind {
        StmtKind::While(w) => &w.body,
        StmtKind::Loop(l) => &l.body,
        StmtKind::For(f) => &f.body,
        StmtKind::Repeat(r) => &r.body,
        StmtKind::Do(d) => &d.body,
        StmtKind::Block(_) | StmtKind::If(_) => &[],
    }
}
