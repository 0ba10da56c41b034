//! Which Siemens comparisons compare two integers, so FANUC's exact comparison gives the
//! Siemens result and the relative-tolerance form (`passes::exprs`) is not needed.
//!
//! Siemens compares within `1e-12·max(|a|,|b|)`. Two integers that differ differ by at least
//! 1, which that tolerance reaches only beyond 1e12: below it, the exact comparison is the
//! same. A comparison is written plainly when both sides are provably integral there:
//! integer constants, INT/BOOL/CHAR variables, FIX/ROUND/ROUNDUP results, `+ - *` of those
//! (as before), and now also *counters*: R parameters and REAL variables that provably hold
//! an integer below 1e12 wherever the comparison reads them.
//!
//! A variable is a counter when (greatest fixpoint over all programs of the translation):
//! every assignment to it, anywhere, is an integer constant below 1e9, a copy or negation of
//! a counter, or a counter plus or minus an integer constant of at most 1000 (so reaching 1e12
//! takes a billion assignments), each read counter being definitely set at the assignment;
//! it is never written indirectly (`R[i]=` makes every R parameter unknown), never passed as
//! a call argument (a by-reference parameter could write it), and no call leaves the set of
//! programs translated together. "Definitely set" at a point: the variable is assigned by a
//! plain block (no `/` skip) or a DEF or a FOR head among the statements at the top of the
//! program that come before the first jump (no path can reach a later point without passing
//! it), or among the top-level statements after it since the last one a jump may enter (a
//! label or an N number, also nested), or the point is inside a FOR over the variable. Anything else (PROC parameters, R
//! parameters a caller or the previous run left, system variables) keeps the exact form.
//!
//! The same on a grid (issue 17 item 10): values that are all multiples of g = 2^-k (k ≤ 6)
//! are exact in binary and differ, when they differ, by at least g; with every bound above
//! scaled by g the tolerance stays below g. A REAL stepped by 0.5, or an integer counter
//! against 2.5 (half a step of the 1/2 grid from its nearest values), compares plainly.
//! [`exact_differences`] asks the same of the Siemens programs FANUC → Sinumerik writes
//! (`a-b op 0` → `a op b`), where only labelled blocks are jump targets.

use crate::ir::*;
use crate::span::Span;
use std::collections::{BTreeMap, BTreeSet};

/// A scalar variable: an R parameter or a named one.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Key {
    R(u32),
    Name(String),
}

fn key(v: &VarRef) -> Option<Key> {
    match &v.kind {
        VarKind::R(n) => Some(Key::R(*n)),
        VarKind::Named { name, indices } if indices.is_empty() => Some(Key::Name(name.clone())),
        _ => None,
    }
}

const MAX_START: f64 = 1e9;
const MAX_STEP: f64 = 1000.0;

/// Declared types of one program's names (DEF and PROC parameters).
pub type Types = BTreeMap<String, DataType>;

/// A comparison met in the walk, with what was definitely set where it stands.
struct Seen {
    span: Span,
    a: Expr,
    b: Expr,
    set: BTreeSet<Key>,
    prog: usize,
}

struct Assign {
    target: Key,
    value: Expr,
    set: BTreeSet<Key>,
}

#[derive(Default)]
struct Walk {
    assigns: Vec<Assign>,
    cmps: Vec<Seen>,
    /// The numbers of `"L"<<n` calls, as `n == 0` seen where the call stands.
    calls: Vec<Seen>,
    /// Keys that can never be counters (passed as arguments, arrays, indirect targets).
    spoiled: BTreeSet<Key>,
    /// An indirect R write or a call out of the set: no R parameter is a counter.
    all_r_spoiled: bool,
}

/// The finest grid tried: multiples of 2^-MAX_K (1/64).
const MAX_K: i32 = 6;

/// Values that are multiples of `g` = 2^-k (k = 0: the integers). Such values below 2^40·g
/// add and subtract exactly in IEEE doubles, and two that differ differ by at least `g`.
/// Every bound of the integer rule is scaled by `g`: a grid counter starts below 1e9·g and
/// steps by at most 1000·g, so it reaches 1e12·g (where the tolerance 1e-12·max could reach
/// `g`) only after a billion assignments, as an integer counter reaches 1e12.
#[derive(Clone, Copy)]
struct Grid {
    g: f64,
}

impl Grid {
    fn all() -> impl Iterator<Item = Grid> {
        (0..=MAX_K).map(|k| Grid { g: 2f64.powi(-k) })
    }
    fn on(self, v: f64) -> bool {
        (v / self.g).fract() == 0.0
    }
    fn start(self, v: f64) -> bool {
        self.on(v) && v.abs() < MAX_START * self.g
    }
    fn step(self, v: f64) -> bool {
        self.on(v) && v.abs() <= MAX_STEP * self.g
    }
    fn value(self, v: f64) -> bool {
        self.on(v) && v.abs() < 1e12 * self.g
    }
}

/// The walk of every program and, per grid, its counters (greatest fixpoint).
fn counters(progs: &[(&Program, &Types)], names: &BTreeSet<String>, labels_only: bool) -> (Walk, Vec<BTreeSet<Key>>) {
    let mut w = Walk::default();
    for (i, (p, _)) in progs.iter().enumerate() {
        // A jump reaches a block by its label, or by its N number when a jump names one
        // (or is computed); with `labels_only` a program whose jumps all name labels has
        // only its labelled blocks as targets.
        let numbers = !labels_only || jumps_to_numbers(&p.body);
        // `base`: set by the prefix (before the first jump), so at every later point;
        // `set`: also by the top-level blocks since the last possible jump target.
        let mut base = BTreeSet::new();
        let mut prefix = true;
        let mut set = BTreeSet::new();
        for s in &p.body {
            if prefix && has_jump(s) {
                prefix = false;
            }
            if !prefix && is_target(s, numbers) {
                set = base.clone();
            }
            w.stmt(s, i, &mut set.clone(), names);
            definitely_sets(s, &mut set);
            if prefix {
                base = set.clone();
            }
        }
    }
    let mut all: BTreeSet<Key> = w.assigns.iter().map(|a| a.target.clone()).collect();
    all.retain(|k| !(w.spoiled.contains(k) || (w.all_r_spoiled && matches!(k, Key::R(_)))));
    let per_grid = Grid::all()
        .map(|grid| {
            let mut counters = all.clone();
            loop {
                let before = counters.len();
                let drop: Vec<Key> = w
                    .assigns
                    .iter()
                    .filter(|a| counters.contains(&a.target) && !counter_value(&a.value, &counters, &a.set, grid))
                    .map(|a| a.target.clone())
                    .collect();
                for k in drop {
                    counters.remove(&k);
                }
                if counters.len() == before {
                    break counters;
                }
            }
        })
        .collect();
    (w, per_grid)
}

/// For every program (in order), the spans of the relative comparisons whose two sides are
/// provably on one grid (integers, or multiples of 1/2 … 1/64) below its bound where they
/// stand: there the exact comparison gives the Siemens result (Sinumerik → FANUC).
pub fn exact_comparisons(progs: &[(&Program, &Types)], names: &BTreeSet<String>) -> Vec<BTreeSet<Span>> {
    let (w, counters) = counters(progs, names, false);
    proven(&w, progs, |c| {
        let types = progs[c.prog].1;
        Grid::all()
            .zip(&counters)
            .any(|(g, k)| integral(&c.a, k, &c.set, types, g) && integral(&c.b, k, &c.set, types, g))
    })
}

/// For every program (in order), the spans of the Siemens comparisons `a-b op 0` (the
/// exact form FANUC → Sinumerik writes for FANUC's `a op b`) whose `a` and `b` are provably
/// on one grid below its bound where they stand: there `a op b` under the Siemens tolerance
/// is FANUC's exact result. `progs` are translated Siemens programs, whose jumps name
/// labels: a block is a jump target by its label only, unless a jump of its program names
/// an N number (the segmented stream's skeleton then has the same targets as the whole
/// program: its runs hold no label, jump or assignment).
pub fn exact_differences(progs: &[(&Program, &Types)], names: &BTreeSet<String>) -> Vec<BTreeSet<Span>> {
    let (w, counters) = counters(progs, names, true);
    proven(&w, progs, |c| {
        let types = progs[c.prog].1;
        let zero = matches!(&c.b.kind, ExprKind::Num(n) if n.value == 0.0);
        let ExprKind::Binary(BinOp::Sub, x, y) = &c.a.kind else { return false };
        zero && Grid::all()
            .zip(&counters)
            .any(|(g, k)| integral(x, k, &c.set, types, g) && integral(y, k, &c.set, types, g))
    })
}

/// The number `n` of a call of the program named `"L"<<n` (the prefix in any case).
pub fn built_l_number(t: &CallTarget) -> Option<&Expr> {
    match t {
        CallTarget::Computed(Expr { kind: ExprKind::Binary(BinOp::Concat, a, n), .. }) => {
            matches!(&a.kind, ExprKind::Str(s) if s.eq_ignore_ascii_case("L")).then_some(&**n)
        }
        _ => None,
    }
}

/// For every program (in order), the spans of the numbers `n` of its `CALL "L"<<n` that are
/// provably integers below 1e12 where the call stands (the integer grid of
/// [`exact_comparisons`]): `<<` writes them as digits alone, the `k` of program `L<k>`.
pub fn integral_call_numbers(progs: &[(&Program, &Types)], names: &BTreeSet<String>) -> Vec<BTreeSet<Span>> {
    let (w, counters) = counters(progs, names, false);
    let mut out = vec![BTreeSet::new(); progs.len()];
    let integers = Grid { g: 1.0 };
    for c in &w.calls {
        if integral(&c.a, &counters[0], &c.set, progs[c.prog].1, integers) {
            out[c.prog].insert(c.span);
        }
    }
    out
}

/// The spans of the comparisons `ok` proves, per program; two comparisons with one span (a
/// pass may synthesise one) count only when both are proven.
fn proven(w: &Walk, progs: &[(&Program, &Types)], ok: impl Fn(&Seen) -> bool) -> Vec<BTreeSet<Span>> {
    let mut out = vec![BTreeSet::new(); progs.len()];
    let mut unproven: BTreeSet<Span> = BTreeSet::new();
    for c in &w.cmps {
        if ok(c) {
            out[c.prog].insert(c.span);
        } else {
            unproven.insert(c.span);
        }
    }
    for s in &mut out {
        s.retain(|sp| !unproven.contains(sp));
    }
    out
}

/// An assignment's value keeps its target a counter on `grid`.
fn counter_value(e: &Expr, counters: &BTreeSet<Key>, set: &BTreeSet<Key>, grid: Grid) -> bool {
    let counter = |e: &Expr| match &e.kind {
        ExprKind::Var(v) => key(v).is_some_and(|k| counters.contains(&k) && set.contains(&k)),
        _ => false,
    };
    let step = |e: &Expr| matches!(&e.kind, ExprKind::Num(n) if grid.step(n.value));
    match &e.kind {
        ExprKind::Num(n) => grid.start(n.value),
        ExprKind::Var(_) => counter(e),
        ExprKind::Unary(UnOp::Neg, a) => counter(a),
        ExprKind::Binary(BinOp::Add, a, b) => (counter(a) && step(b)) || (step(a) && counter(b)),
        ExprKind::Binary(BinOp::Sub, a, b) => counter(a) && step(b),
        _ => false,
    }
}

/// `e` is on `grid` below its bound wherever it is read (the exprs pass's rule plus counters).
fn integral(e: &Expr, counters: &BTreeSet<Key>, set: &BTreeSet<Key>, types: &Types, grid: Grid) -> bool {
    match &e.kind {
        ExprKind::Num(n) => grid.value(n.value),
        // A machine signal other than a PLC real holds whole numbers below 2^31 (the run
        // refuses any other value: `eval::signals`).
        ExprKind::Var(v) if matches!(&v.kind, VarKind::System { name, .. } if name != "A_DBR" && crate::dialect::signals::is_siemens_signal(name)) => {
            grid.on(1.0) && grid.value(2_147_483_648.0)
        }
        ExprKind::Var(v) => match key(v) {
            Some(k) => {
                // INT is 32 bits: below 2^31, under 1e12·g for every grid tried.
                let typed = matches!(&k, Key::Name(n) if matches!(types.get(n), Some(DataType::Int | DataType::Bool | DataType::Char)));
                typed || (counters.contains(&k) && set.contains(&k))
            }
            None => false,
        },
        ExprKind::Unary(UnOp::Neg, a) => integral(a, counters, set, types, grid),
        // Sums and differences of two values below 1e12·g stay below 2e12·g, where the
        // tolerance is still below 2g but two values g apart could meet it: allow one
        // level only when a side is a small constant.
        ExprKind::Binary(BinOp::Add | BinOp::Sub, a, b) => {
            let small = |x: &Expr| matches!(&x.kind, ExprKind::Num(n) if grid.on(n.value) && n.value.abs() <= MAX_START * grid.g);
            (integral(a, counters, set, types, grid) && small(b))
                || (small(a) && integral(b, counters, set, types, grid))
        }
        _ => false,
    }
}

/// The keys a top-level statement of the prefix sets on every path through it.
fn definitely_sets(s: &Stmt, set: &mut BTreeSet<Key>) {
    match &s.kind {
        StmtKind::Block(b) if b.meta.skip.is_none() => {
            for it in &b.items {
                match &it.kind {
                    ItemKind::Assign { target, .. } => set.extend(key(target)),
                    ItemKind::Def(d) => {
                        set.extend(d.vars.iter().filter(|v| v.dims.is_empty()).map(|v| Key::Name(v.name.clone())))
                    }
                    _ => {}
                }
            }
        }
        StmtKind::For(f) => set.extend(key(&f.var)),
        _ => {}
    }
}

/// A statement a jump may enter: a label (or, with `numbers`, an N number) on it or inside it.
fn is_target(s: &Stmt, numbers: bool) -> bool {
    let mut found = false;
    crate::ir::visit::walk_stmts(std::slice::from_ref(s), &mut |s| {
        found |= crate::ir::visit::metas(&s.kind).iter().any(|m| m.label.is_some() || (numbers && m.number.is_some()));
    });
    found
}

/// Whether a jump of `body` names an N number or is computed (then any numbered block may
/// be its target).
fn jumps_to_numbers(body: &[Stmt]) -> bool {
    fn names_number(it: &Item) -> bool {
        let goto = |g: &Goto| !matches!(g.target, Target::Label(_));
        match &it.kind {
            ItemKind::Goto(g) => goto(g),
            ItemKind::Case(c) => c.arms.iter().any(|a| goto(&a.goto)) || c.default.as_ref().is_some_and(goto),
            ItemKind::IfThen { then, .. } => names_number(then),
            _ => false,
        }
    }
    let mut found = false;
    crate::ir::visit::walk_stmts(body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            found |= b.items.iter().any(names_number);
        }
    });
    found
}

fn has_jump(s: &Stmt) -> bool {
    let mut found = false;
    crate::ir::visit::walk_stmts(std::slice::from_ref(s), &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            found |= b.items.iter().any(item_jumps);
        }
    });
    found
}

fn item_jumps(it: &Item) -> bool {
    match &it.kind {
        ItemKind::Goto(_) | ItemKind::Case(_) | ItemKind::RepeatSection(_) => true,
        ItemKind::IfThen { then, .. } => item_jumps(then),
        _ => false,
    }
}

impl Walk {
    fn stmt(&mut self, s: &Stmt, prog: usize, set: &mut BTreeSet<Key>, names: &BTreeSet<String>) {
        match &s.kind {
            StmtKind::Block(b) => {
                for it in &b.items {
                    self.item(it, prog, set, names);
                }
            }
            StmtKind::If(i) => {
                self.cond(&i.cond, prog, set);
                self.body(&i.then_body, prog, set, names);
                if let Some(e) = &i.else_part {
                    self.body(&e.body, prog, set, names);
                }
            }
            StmtKind::While(w) => {
                self.cond(&w.cond, prog, set);
                self.body(&w.body, prog, set, names);
            }
            StmtKind::Loop(l) => self.body(&l.body, prog, set, names),
            StmtKind::Repeat(r) => {
                self.body(&r.body, prog, set, names);
                self.cond(&r.until, prog, set);
            }
            StmtKind::Do(d) => {
                if let Some(c) = &d.cond {
                    self.cond(c, prog, set);
                }
                self.body(&d.body, prog, set, names);
            }
            StmtKind::For(f) => {
                self.cond(&f.from, prog, set);
                self.cond(&f.to, prog, set);
                let Some(k) = key(&f.var) else {
                    self.spoil_target(&f.var);
                    self.body(&f.body, prog, set, names);
                    return;
                };
                self.assigns.push(Assign { target: k.clone(), value: f.from.clone(), set: set.clone() });
                let mut inner = set.clone();
                inner.insert(k.clone());
                let v = Expr::new(ExprKind::Var(Box::new(f.var.clone())), f.var.span);
                // The FOR's own test `v <= to` (its span is the statement's, see exprs).
                self.cmps.push(Seen { span: s.span, a: v.clone(), b: f.to.clone(), set: inner.clone(), prog });
                let step = Expr::new(
                    ExprKind::Binary(BinOp::Add, Box::new(v), Box::new(Expr::num(1.0, false, s.span))),
                    s.span,
                );
                self.assigns.push(Assign { target: k, value: step, set: inner.clone() });
                self.body(&f.body, prog, &inner, names);
            }
        }
    }

    fn body(&mut self, body: &[Stmt], prog: usize, set: &BTreeSet<Key>, names: &BTreeSet<String>) {
        for s in body {
            self.stmt(s, prog, &mut set.clone(), names);
        }
    }

    fn item(&mut self, it: &Item, prog: usize, set: &BTreeSet<Key>, names: &BTreeSet<String>) {
        match &it.kind {
            ItemKind::Assign { target, value } => {
                self.cond(value, prog, set);
                match key(target) {
                    Some(k) => self.assigns.push(Assign { target: k, value: value.clone(), set: set.clone() }),
                    None => self.spoil_target(target),
                }
            }
            ItemKind::Def(d) => {
                for v in &d.vars {
                    let k = Key::Name(v.name.clone());
                    if !v.dims.is_empty() {
                        self.spoiled.insert(k);
                        continue;
                    }
                    let value = match &v.init {
                        Some(Init::Value(e)) => e.clone(),
                        None => Expr::num(0.0, false, v.span),
                        Some(_) => {
                            self.spoiled.insert(k);
                            continue;
                        }
                    };
                    self.assigns.push(Assign { target: k, value, set: set.clone() });
                }
            }
            ItemKind::Call(c) => {
                // `CALL "L"<<n` reaches an `L<k>` program of the translation (the callers load
                // every one beside them) or none, which stops the run.
                if let Some(n) = built_l_number(&c.target) {
                    let zero = Expr::num(0.0, false, n.span);
                    self.calls.push(Seen { span: n.span, a: n.clone(), b: zero, set: set.clone(), prog });
                }
                let known = built_l_number(&c.target).is_some()
                    || match &c.target {
                        // WORKPIECE and the like only set up the simulation (dropped, NC322);
                        // the standard cycles the translation writes as FANUC words
                        // (drilling cycles, CYCLE832) keep their data in their own
                        // variables, not in R parameters.
                        CallTarget::Name(n) => {
                            let n = n.to_ascii_uppercase();
                            names.contains(&n)
                                || super::words::SIMULATION_ONLY.contains(&n.as_str())
                                || n == "CYCLE832"
                                // FGROUP only names the feed's axes.
                                || n == "FGROUP"
                                || crate::dialect::sinumerik::cycles::cycle_of(&n).is_some()
                        }
                        _ => false,
                    };
                if !known {
                    self.all_r_spoiled = true;
                }
                for a in &c.args {
                    if let Arg::Value(e) = a {
                        if let ExprKind::Var(v) = &e.kind {
                            self.spoil_target(v);
                        }
                    }
                }
                for e in crate::ir::visit::item_exprs(it) {
                    self.cond(e, prog, set);
                }
            }
            ItemKind::IfThen { cond, then } => {
                self.cond(cond, prog, set);
                self.item(then, prog, set, names);
            }
            _ => {
                for e in crate::ir::visit::item_exprs(it) {
                    self.cond(e, prog, set);
                }
            }
        }
    }

    fn spoil_target(&mut self, v: &VarRef) {
        match &v.kind {
            VarKind::RIndirect(_) | VarKind::HashIndirect(_) => self.all_r_spoiled = true,
            VarKind::Named { name, .. } => {
                self.spoiled.insert(Key::Name(name.clone()));
            }
            VarKind::R(n) => {
                self.spoiled.insert(Key::R(*n));
            }
            _ => {}
        }
    }

    /// Records every relative comparison inside `e`.
    fn cond(&mut self, e: &Expr, prog: usize, set: &BTreeSet<Key>) {
        let mut stack = vec![e];
        while let Some(e) = stack.pop() {
            match &e.kind {
                ExprKind::Cmp(_, Tolerance::Relative, a, b) => {
                    self.cmps.push(Seen { span: e.span, a: (**a).clone(), b: (**b).clone(), set: set.clone(), prog });
                    stack.push(a);
                    stack.push(b);
                }
                ExprKind::Cmp(_, _, a, b) | ExprKind::Binary(_, a, b) => {
                    stack.push(a);
                    stack.push(b);
                }
                ExprKind::Unary(_, a) => stack.push(a),
                ExprKind::Func(_, args) => stack.extend(args.iter()),
                _ => {}
            }
        }
    }
}
