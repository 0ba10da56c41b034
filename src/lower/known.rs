//! Values known at translation: the variables (R parameters, a program's own scalar
//! variables) that hold one constant on every path to a place of a program, found by a
//! forward walk over its blocks, IFs, loops and jumps ([`comp_flow::walk`], the walk the
//! compensation translations share), for a lowering that must decide at translation what
//! the source decides at run time (the drilling cycles' retract plane, peck mode, dwell).
//!
//! Exact and conservative: a variable is known only after an assignment of a value worked
//! out here (a number, or +, −, ×, / of known values), and only where every path that
//! reaches the place agrees on that value. It becomes unknown where an assignment's value is
//! not known, where paths with different values meet (an IF, a loop head, a jump target, a
//! block that may be skipped), where a call may write it (the target says which: an R
//! parameter is global, a variable passed may be a VAR parameter), at a REPEAT (a section run
//! again), at `EXECSTRING`. A variable the target's rules say can change outside the program
//! (global user data, an input, what an interrupt writes) is never known. Each unknown keeps
//! the place that made it so, for the refusal to name.

use crate::ir::*;
use crate::lower::comp_flow::{self, FlowState};
use crate::span::Span;
use std::collections::BTreeMap;

/// A variable followed: an R parameter or a scalar named variable (upper case).
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Key {
    R(u32),
    Named(String),
}

impl Key {
    /// The key of a plain variable reference (no subscripts, no computed number).
    pub fn of(v: &VarRef) -> Option<Key> {
        match &v.kind {
            VarKind::R(n) => Some(Key::R(*n)),
            VarKind::Named { name, indices } if indices.is_empty() => Some(Key::Named(name.to_ascii_uppercase())),
            _ => None,
        }
    }

    /// As the source writes it (`R1`, `_RTP`).
    pub fn name(&self) -> String {
        match self {
            Key::R(n) => format!("R{n}"),
            Key::Named(n) => n.clone(),
        }
    }
}

/// The place that made a variable unknown, and what happens there.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub struct Why {
    pub span: Span,
    pub what: String,
}

#[derive(Clone, Debug, PartialEq)]
enum Fact {
    /// The value, and where it was set (the first such place in the text).
    Value(f64, Span),
    Unknown(Why),
}

/// What is known before a block. A variable without an entry is not known, and nothing
/// in the program says why (it was never set here: its value comes from before).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Known {
    vars: BTreeMap<Key, Fact>,
}

impl FlowState for Known {
    fn unknown() -> Self {
        Known::default()
    }

    fn merge(&self, other: &Self) -> Self {
        let mut vars = BTreeMap::new();
        for (k, a) in &self.vars {
            let Some(b) = other.vars.get(k) else { continue };
            let m = match (a, b) {
                (Fact::Value(x, s), Fact::Value(y, t)) if x == y => Fact::Value(*x, (*s).min(*t)),
                (Fact::Value(x, s), Fact::Value(y, t)) => {
                    // The later assignment is the place named, the other value with it.
                    let ((late, lv), (_, ev)) = if s > t { ((*s, *x), (*t, *y)) } else { ((*t, *y), (*s, *x)) };
                    Fact::Unknown(Why {
                        span: late,
                        what: format!("is set to {} here on one path to it and {} on another", show(lv), show(ev)),
                    })
                }
                (Fact::Unknown(w), Fact::Unknown(v)) => Fact::Unknown(w.min(v).clone()),
                (Fact::Unknown(w), _) | (_, Fact::Unknown(w)) => Fact::Unknown(w.clone()),
            };
            vars.insert(k.clone(), m);
        }
        Known { vars }
    }

    fn watches_every_block(&self) -> bool {
        true
    }
}

/// A number as a message shows it (`10`, `2.5`).
pub fn show(v: f64) -> String {
    format!("{v}")
}

/// Why a value could not be worked out.
#[derive(Clone, Debug, PartialEq)]
pub enum Miss {
    /// The variable is not known there: the place that made it so, or `None` (never set on
    /// some path: its value comes from before the program, its caller or a jump).
    Var(Key, Option<Why>),
    /// A form this analysis does not evaluate (a system variable, a function, a subscript).
    Expr,
}

impl Known {
    /// The value of `key` here.
    pub fn value(&self, key: &Key) -> Result<f64, Miss> {
        match self.vars.get(key) {
            Some(Fact::Value(v, _)) => Ok(*v),
            Some(Fact::Unknown(w)) => Err(Miss::Var(key.clone(), Some(w.clone()))),
            None => Err(Miss::Var(key.clone(), None)),
        }
    }

    /// The value of `e` here: numbers, known variables, −, +, −, ×, / (a division by 0 is
    /// the control's alarm, not a value).
    pub fn eval(&self, e: &Expr) -> Result<f64, Miss> {
        let v = match &e.kind {
            ExprKind::Num(n) => n.value,
            ExprKind::Var(v) => self.value(&Key::of(v).ok_or(Miss::Expr)?)?,
            ExprKind::Unary(UnOp::Neg, a) => -self.eval(a)?,
            ExprKind::Binary(op, a, b) => {
                let (x, y) = (self.eval(a)?, self.eval(b)?);
                match op {
                    BinOp::Add => x + y,
                    BinOp::Sub => x - y,
                    BinOp::Mul => x * y,
                    BinOp::Div if y != 0.0 => x / y,
                    _ => return Err(Miss::Expr),
                }
            }
            _ => return Err(Miss::Expr),
        };
        if v.is_finite() {
            Ok(v)
        } else {
            Err(Miss::Expr)
        }
    }

    fn set(&mut self, key: Key, f: Fact) {
        self.vars.insert(key, f);
    }

    fn kill_where(&mut self, pred: &dyn Fn(&Key) -> bool, why: &Why) {
        for (k, f) in self.vars.iter_mut() {
            if pred(k) {
                *f = Fact::Unknown(why.clone());
            }
        }
    }

    /// Unknown from here on, with `why`; a key not yet set stays without an entry (it was not
    /// known before either).
    fn kill(&mut self, key: &Key, why: &Why) {
        if let Some(f) = self.vars.get_mut(key) {
            *f = Fact::Unknown(why.clone());
        }
    }
}

/// What a call may write.
pub struct CallWrites {
    /// The keys the target calls global ([`Rules::global`]: R parameters, VAR parameters of
    /// this program), and why (for the message: "R parameters are global").
    pub globals: Option<&'static str>,
    /// Per argument, in order: whether the callee may write the variable passed (a VAR
    /// parameter, or a callee not known here).
    pub by_ref: Vec<bool>,
}

/// What the target says about its variables and calls.
pub struct Rules<'a> {
    /// Whether `key` is followed at all (else never known: global user data, an input).
    pub tracked: &'a dyn Fn(&Key) -> bool,
    /// Whether a called program may write `key` without it being passed.
    pub global: &'a dyn Fn(&Key) -> bool,
    /// What a call may write; `None`: nothing (a drilling cycle, which takes its data by value).
    pub call: &'a dyn Fn(&Call) -> Option<CallWrites>,
}

/// The state before each item `want` picks (by the item's span), in the live walk of `body`
/// from nothing known (a main program's R parameters hold what an earlier run left, a
/// called program's variables what its caller passed).
pub fn analyse(body: &[Stmt], rules: &Rules, want: &dyn Fn(&Item) -> bool) -> BTreeMap<Span, Known> {
    let mut at = BTreeMap::new();
    let jumping = comp_flow::jumps(body) || repeats(body);
    let mut st = Known::default();
    let mut step = |st: &mut Known, b: Block, live: bool, out: &mut Vec<Stmt>| {
        if live {
            // Two items with one span (a macro's text used twice) get what both agree on.
            for it in b.items.iter().filter(|it| want(it)) {
                let k = at.get(&it.span).map_or_else(|| st.clone(), |old: &Known| old.merge(st));
                at.insert(it.span, k);
            }
        }
        let before = st.clone();
        for it in &b.items {
            transfer(it, st, rules);
        }
        if b.meta.skip.is_some() {
            *st = st.merge(&before);
        }
        out.push(crate::lower::meta_stmt(b.meta, b.items));
    };
    comp_flow::walk(body.to_vec(), &mut st, jumping, false, &mut step, true);
    at
}

/// Whether `body` has a REPEAT (its sections are run again: the walk must know its labels).
fn repeats(body: &[Stmt]) -> bool {
    let mut any = false;
    crate::ir::visit::walk_stmts(body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            any |= b.items.iter().any(|it| matches!(it.kind, ItemKind::RepeatSection(_)));
        }
    });
    any
}

/// The variables `e` reads (plain ones), in order.
pub fn reads(e: &Expr, out: &mut Vec<Key>) {
    if let ExprKind::Var(v) = &e.kind {
        if let Some(k) = Key::of(v) {
            out.push(k);
        }
    }
    for c in e.children() {
        reads(c, out);
    }
}

fn transfer(it: &Item, st: &mut Known, rules: &Rules) {
    let why = |what: &str| Why { span: it.span, what: what.to_string() };
    match &it.kind {
        ItemKind::Assign { target, value } => match Key::of(target) {
            Some(k) if (rules.tracked)(&k) => {
                let f = match st.eval(value) {
                    Ok(v) => Fact::Value(v, it.span),
                    Err(_) => Fact::Unknown(why("is set here to a value not known at translation")),
                };
                st.set(k, f);
            }
            Some(_) => {}
            None => match &target.kind {
                // A computed R number may be any R parameter (or what a VAR parameter is).
                VarKind::RIndirect(_) | VarKind::HashIndirect(_) => st.kill_where(
                    &|k| matches!(k, Key::R(_)) || (rules.global)(k),
                    &why("may be set here (an R parameter with a computed number)"),
                ),
                VarKind::Named { name, .. } => {
                    let name = name.to_ascii_uppercase();
                    st.kill_where(&|k| *k == Key::Named(name.clone()), &why("may be set here (an element of it)"))
                }
                _ => {}
            },
        },
        ItemKind::Call(c) => {
            let Some(w) = (rules.call)(c) else { return };
            if let Some(reason) = w.globals {
                st.kill_where(rules.global, &why(&format!("may be written by the call here ({reason})")));
            }
            for (k, a) in c.args.iter().enumerate() {
                let e = match a {
                    Arg::Value(e) | Arg::Letter { value: e, .. } => e,
                    Arg::Omitted(_) => continue,
                };
                if w.by_ref.get(k).copied().unwrap_or(true) {
                    let mut keys = Vec::new();
                    reads(e, &mut keys);
                    for key in keys {
                        st.kill(&key, &why("is passed to the call here, which may write it (a VAR parameter)"));
                    }
                }
            }
        }
        ItemKind::Instruction { name } if name.to_ascii_uppercase().starts_with("EXEC") => {
            st.kill_where(&|_| true, &why("may be set by the EXECSTRING/EXECTAILOR here (text known only at run time)"))
        }
        ItemKind::RepeatSection(_) => {
            st.kill_where(&|_| true, &why("may change at the REPEAT here (a section run again)"))
        }
        ItemKind::Print(p) => {
            if let Some(k) = p.status.as_deref().and_then(Key::of) {
                st.kill(&k, &why("is set by the WRITE here (its error variable)"));
            }
        }
        ItemKind::IfThen { then, .. } => {
            let mut taken = st.clone();
            transfer(then, &mut taken, rules);
            *st = st.merge(&taken);
        }
        ItemKind::IfBlock { items, .. } => {
            let mut taken = st.clone();
            for i in items {
                transfer(i, &mut taken, rules);
            }
            *st = st.merge(&taken);
        }
        _ => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn num(v: f64) -> Expr {
        crate::lower::num(v, Span::new(0, 0))
    }

    fn r(n: u32, at: u32) -> VarRef {
        VarRef { kind: VarKind::R(n), span: Span::new(at, at + 1) }
    }

    fn assign(n: u32, v: Expr, at: u32) -> Stmt {
        let s = Span::new(at, at + 1);
        crate::lower::block_stmt(vec![crate::lower::assign_item(&r(n, at), v, s)], s)
    }

    fn word_z(e: Expr, at: u32) -> Stmt {
        let s = Span::new(at, at + 1);
        let w = Word { addr: Addr::Letter(b'Z'), value: WordValue::Expr(e), span: s };
        crate::lower::block_stmt(vec![crate::lower::item(ItemKind::Word(w), s)], s)
    }

    fn tracked(_: &Key) -> bool {
        true
    }

    fn global(k: &Key) -> bool {
        matches!(k, Key::R(_))
    }

    fn call(_: &Call) -> Option<CallWrites> {
        Some(CallWrites { globals: Some("R parameters are global"), by_ref: vec![] })
    }

    fn at_z(body: &[Stmt]) -> Known {
        let rules = Rules { tracked: &tracked, global: &global, call: &call };
        let at = analyse(body, &rules, &|it| matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'Z')));
        at.into_values().next().expect("the Z block")
    }

    #[test]
    fn a_constant_and_a_sum_of_constants_are_known() {
        let sum = crate::lower::bin(BinOp::Add, crate::lower::var_expr(&r(1, 0)), num(2.0));
        let body = vec![assign(1, num(10.0), 1), assign(2, sum, 2), word_z(num(0.0), 3)];
        let k = at_z(&body);
        assert_eq!(k.value(&Key::R(1)), Ok(10.0));
        assert_eq!(k.value(&Key::R(2)), Ok(12.0));
        assert!(matches!(k.value(&Key::R(3)), Err(Miss::Var(_, None))));
    }

    #[test]
    fn an_if_that_sets_another_value_makes_it_unknown_naming_the_place() {
        let s = Span::new(5, 6);
        let iff = Stmt {
            kind: StmtKind::If(Box::new(IfStmt {
                head: BlockMeta::default(),
                cond: num(1.0),
                then_body: vec![assign(1, num(20.0), 7)],
                else_part: None,
                end: BlockMeta::default(),
            })),
            span: s,
        };
        let body = vec![assign(1, num(10.0), 1), iff, word_z(num(0.0), 9)];
        let k = at_z(&body);
        let Err(Miss::Var(_, Some(w))) = k.value(&Key::R(1)) else { panic!("known: {k:?}") };
        assert_eq!(w.span, Span::new(7, 8));
        assert!(w.what.contains("20") && w.what.contains("10"), "{}", w.what);
    }

    #[test]
    fn a_loop_that_changes_it_makes_it_unknown() {
        let inc = crate::lower::bin(BinOp::Add, crate::lower::var_expr(&r(1, 0)), num(1.0));
        let lp = Stmt {
            kind: StmtKind::Loop(Box::new(LoopStmt {
                head: BlockMeta::default(),
                body: vec![assign(1, inc, 4)],
                end: BlockMeta::default(),
            })),
            span: Span::new(3, 6),
        };
        let body = vec![assign(1, num(10.0), 1), lp, word_z(num(0.0), 9)];
        assert!(at_z(&body).value(&Key::R(1)).is_err());
    }

    #[test]
    fn a_call_makes_the_globals_unknown() {
        let s = Span::new(4, 5);
        let call = Call { kind: CallKind::Named, target: CallTarget::Name("SUB".into()), args: vec![], repeat: None };
        let body = vec![
            assign(1, num(10.0), 1),
            crate::lower::block_stmt(vec![crate::lower::item(ItemKind::Call(Box::new(call)), s)], s),
            word_z(num(0.0), 9),
        ];
        let Err(Miss::Var(_, Some(w))) = at_z(&body).value(&Key::R(1)) else { panic!() };
        assert_eq!(w.span, s);
    }
}
