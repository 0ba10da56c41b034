//! `M98 P#1` / `G65 P#1 …` whose number is not one value on every path (after
//! `indirect::resolve`) but one of a few known ones (constants, and sums, differences and
//! products of them, through every path: a value-set propagation over the graph
//! `indirect` uses, at most 16 values): a dispatch over the programs of the job those values
//! name, before any other pass, in FANUC terms every later pass reads as written. FANUC calls
//! the program numbered `ROUND[#1]` (half away from zero, as P is taken); so the block
//! becomes, for each program `k` a value names,
//!
//! ```text
//! IF [ROUND[#1] NE k] GOTO a   M98 Pk   GOTO end   Na …
//! ```
//!
//! then, for `M98` without `L`, the packed form FANUC reads where no program has the number
//! (`P10176` is O0176 once: the count in front of four digits), and last a call of a program
//! no control holds (`NCTRANS_NO_PROG`), whose "program not found" is Siemens' own, as FANUC
//! stops where no program has the number. The tests read the number again each time, but no
//! block runs between them. Each branch is then an ordinary call of a known program (roles,
//! parameters, names as for `M98 P176`). A number that may be any (an input, a variable a
//! call may change), one that may name the main program, a call sharing its block with other
//! words, one with an argument without a decimal point, and a modal `G66 P#1` stay refused
//! by `calls` (NC356).

use super::*;
use std::collections::{BTreeMap, BTreeSet};

/// The program no control holds, called where FANUC finds no program of the number.
pub const NO_PROGRAM: &str = "NCTRANS_NO_PROG";

/// The call of [`NO_PROGRAM`]: it stops the run (program not found), so the analyses that
/// follow modes through calls take nothing from it.
pub fn stops(c: &Call) -> bool {
    matches!(&c.target, CallTarget::Name(n) if n == NO_PROGRAM)
}

/// A block that is only an `M98`/`G65` with a computed number. An argument written without a
/// decimal point is scaled by the unit in force at the call, which the modal scan, keyed by
/// source position, would read after the whole dispatch (after the callees): such a call
/// stays refused.
fn is_dispatched(b: &Block) -> bool {
    let bare = |c: &Call| {
        c.args.iter().any(|a| matches!(a, Arg::Letter { value: Expr { kind: ExprKind::Num(n), .. }, .. } if !n.point))
    };
    matches!(b.items.as_slice(), [Item { kind: ItemKind::Call(c), .. }]
        if matches!(c.target, CallTarget::Computed(_)) && matches!(c.kind, CallKind::M98 | CallKind::G65) && !bare(c))
}

/// The values a variable may hold at a point, as bits of the f64 (at most [`MAX_VALUES`]);
/// a variable absent may hold any value.
type Sets = BTreeMap<u32, BTreeSet<u64>>;

/// More values than this and a variable counts as unknown.
const MAX_VALUES: usize = 16;

fn eval_set(e: &Expr, env: &Sets) -> Option<BTreeSet<u64>> {
    let out: BTreeSet<u64> = match &e.kind {
        ExprKind::Num(n) => [n.value.to_bits()].into(),
        ExprKind::Var(v) => match &v.kind {
            VarKind::Hash(n) => env.get(n)?.clone(),
            _ => return None,
        },
        ExprKind::Unary(UnOp::Neg, a) => {
            eval_set(a, env)?.into_iter().map(|x| (-f64::from_bits(x)).to_bits()).collect()
        }
        ExprKind::Binary(op @ (BinOp::Add | BinOp::Sub | BinOp::Mul), a, b) => {
            let (xs, ys) = (eval_set(a, env)?, eval_set(b, env)?);
            if xs.len() * ys.len() > MAX_VALUES {
                return None;
            }
            let mut out = BTreeSet::new();
            for x in &xs {
                for y in &ys {
                    let (x, y) = (f64::from_bits(*x), f64::from_bits(*y));
                    out.insert(
                        match op {
                            BinOp::Add => x + y,
                            BinOp::Sub => x - y,
                            _ => x * y,
                        }
                        .to_bits(),
                    );
                }
            }
            out
        }
        _ => return None,
    };
    (out.len() <= MAX_VALUES && out.iter().all(|x| f64::from_bits(*x).is_finite())).then_some(out)
}

fn transfer(it: &Item, env: &mut Sets) {
    match &it.kind {
        ItemKind::Assign { target, value } => match &target.kind {
            VarKind::Hash(n) => match eval_set(value, env) {
                Some(v) => {
                    env.insert(*n, v);
                }
                None => {
                    env.remove(n);
                }
            },
            VarKind::HashIndirect(_) => env.clear(),
            _ => {}
        },
        ItemKind::IfThen { then, .. } => {
            let mut after = env.clone();
            transfer(then, &mut after);
            *env = meet(env, &after);
        }
        ItemKind::Call(c) => match c.kind {
            // A macro has its own locals; it can only change commons.
            CallKind::G65 | CallKind::G66 => env.retain(|n, _| *n <= 33),
            _ => env.clear(),
        },
        _ => {}
    }
}

/// Where paths meet: a variable known on both with the values of both.
fn meet(a: &Sets, b: &Sets) -> Sets {
    a.iter()
        .filter_map(|(k, x)| {
            let y = b.get(k)?;
            let u: BTreeSet<u64> = x.union(y).copied().collect();
            (u.len() <= MAX_VALUES).then_some((*k, u))
        })
        .collect()
}

/// The program numbers each computed call of `body` may take (by the call's span), FANUC's
/// rounding applied; `None` where the number may be any.
fn call_values(body: &[Stmt]) -> BTreeMap<(u32, u32), Option<BTreeSet<u32>>> {
    use super::vacancy::{flatten, Node};
    let flat = flatten(body);
    let (ins, settled) = super::forward::run(&flat, Sets::new(), transfer, meet);
    let mut out: BTreeMap<(u32, u32), Option<BTreeSet<u32>>> = BTreeMap::new();
    for (node, env) in flat.nodes.iter().zip(&ins) {
        let Node::Items(items) = node else { continue };
        let Some(mut env) = env.clone().filter(|_| settled) else {
            // Not reached (or not settled): nothing is known there.
            for it in items.iter() {
                if let ItemKind::Call(c) = &it.kind {
                    if matches!(c.target, CallTarget::Computed(_)) {
                        out.insert((it.span.lo, it.span.hi), None);
                    }
                }
            }
            continue;
        };
        for it in items.iter() {
            if let ItemKind::Call(c) = &it.kind {
                if let CallTarget::Computed(e) = &c.target {
                    let values = eval_set(e, &env).map(|vs| {
                        vs.into_iter()
                            .map(|x| crate::eval::value::round_half_away(f64::from_bits(x)).clamp(0.0, 4e9) as u32)
                            .collect()
                    });
                    out.insert((it.span.lo, it.span.hi), values);
                }
            }
            transfer(it, &mut env);
        }
    }
    out
}

/// The program with its computed calls dispatched over the programs of `numbers` (the
/// job's, but the main program) their number can name; `None` when it has none.
/// `main`: the main program's number, which no dispatch calls (a value naming it keeps the
/// call refused).
pub fn expand(p: &Program, numbers: &[u32], main: Option<u32>) -> Option<Program> {
    let mut any = false;
    let mut max_n = 0u32;
    crate::ir::visit::walk_stmts(&p.body, &mut |s| {
        for m in crate::ir::visit::metas(&s.kind) {
            if let Some(n) = &m.number {
                max_n = max_n.max(n.value);
            }
        }
        if let StmtKind::Block(b) = &s.kind {
            any |= is_dispatched(b);
        }
    });
    if !any {
        return None;
    }
    let values = call_values(&p.body);
    let mut next = max_n;
    let mut fresh = move || {
        next += 1;
        next
    };
    let mut p = p.clone();
    p.body = crate::lower::map_bodies(std::mem::take(&mut p.body), &mut |list| {
        let mut out = Vec::with_capacity(list.len());
        for s in list {
            match s.kind {
                StmtKind::Block(b) if is_dispatched(&b) => {
                    let at = b.items.first().map(|it| (it.span.lo, it.span.hi));
                    let known = at.and_then(|k| values.get(&k).cloned().flatten());
                    match known.filter(|vs| main.is_none_or(|m| !vs.contains(&m))) {
                        Some(vs) => out.extend(dispatch(b, s.span, &vs, numbers, &mut fresh)),
                        None => out.push(Stmt { kind: StmtKind::Block(b), span: s.span }),
                    }
                }
                kind => out.push(Stmt { kind, span: s.span }),
            }
        }
        out
    });
    Some(p)
}

fn func(f: Func, args: Vec<Expr>, span: Span) -> Expr {
    Expr::new(ExprKind::Func(f, args), span)
}

fn bin(op: BinOp, a: Expr, b: Expr, span: Span) -> Expr {
    Expr::new(ExprKind::Binary(op, Box::new(a), Box::new(b)), span)
}

fn cmp(op: CmpOp, a: Expr, b: Expr, span: Span) -> Expr {
    Expr::new(ExprKind::Cmp(op, Tolerance::Exact, Box::new(a), Box::new(b)), span)
}

fn goto(n: u32, cond: Option<Expr>, span: Span) -> Item {
    let target = Target::Number(SeqNo { value: n, span });
    let g = Goto { search: Search::ForwardThenWrap, target, cond, missing_continues: false };
    Item { kind: ItemKind::Goto(Box::new(g)), span }
}

fn numbered(n: Option<u32>, items: Vec<Item>, span: Span) -> Stmt {
    let meta = BlockMeta { span, number: n.map(|value| SeqNo { value, span }), ..BlockMeta::default() };
    Stmt { kind: StmtKind::Block(Block { meta, items }), span }
}

/// Builds the blocks in order; each takes the pending jump-target number, the first the
/// original block's meta (its N number, label, comments).
struct Out {
    stmts: Vec<Stmt>,
    meta: Option<BlockMeta>,
    here: Option<u32>,
    span: Span,
}

impl Out {
    fn push(&mut self, items: Vec<Item>) {
        let mut s = numbered(self.here.take(), items, self.span);
        if let (Some(m), StmtKind::Block(blk)) = (self.meta.take(), &mut s.kind) {
            // The original block's own number (a jump target) wins; a pending fresh one is
            // never pending for the first block.
            blk.meta = m;
        }
        self.stmts.push(s);
    }

    /// For each program `k`: `IF [value NE k] GOTO miss`, the call of k, `GOTO end`; with
    /// `complete` (the value is surely one of `numbers`) the last is called without a test.
    fn chain(
        &mut self,
        c: &Call,
        value: &Expr,
        repeat: &Option<Expr>,
        (numbers, complete): (&[u32], bool),
        end: u32,
        fresh: &mut dyn FnMut() -> u32,
    ) {
        let span = self.span;
        for (i, &k) in numbers.iter().enumerate() {
            if complete && i + 1 == numbers.len() {
                let call = Call { target: CallTarget::Number(k), repeat: repeat.clone(), ..c.clone() };
                self.push(vec![Item { kind: ItemKind::Call(Box::new(call)), span }]);
                return;
            }
            let miss = fresh();
            let ne = cmp(CmpOp::Ne, value.clone(), Expr::num(f64::from(k), false, span), span);
            self.push(vec![goto(miss, Some(ne), span)]);
            let call = Call { target: CallTarget::Number(k), repeat: repeat.clone(), ..c.clone() };
            self.push(vec![Item { kind: ItemKind::Call(Box::new(call)), span }]);
            self.push(vec![goto(end, None, span)]);
            self.here = Some(miss);
        }
    }
}

/// `values`: the numbers the call can take; the chains call those of `numbers` they name
/// (directly, or packed for `M98` without `L`), any other goes to the not-found call.
fn dispatch(
    mut b: Block,
    span: Span,
    values: &BTreeSet<u32>,
    numbers: &[u32],
    fresh: &mut dyn FnMut() -> u32,
) -> Vec<Stmt> {
    let Some(Item { kind: ItemKind::Call(c), span: cspan }) = b.items.pop() else { return vec![] };
    let CallTarget::Computed(e) = &c.target else { return vec![] };
    let v = func(Func::FanucRound, vec![e.clone()], e.span);
    let end = fresh();
    let mut out = Out { stmts: Vec::new(), meta: Some(b.meta), here: None, span: cspan };
    let direct: Vec<u32> = values.iter().copied().filter(|k| numbers.contains(k)).collect();
    let packed_ok = c.kind == CallKind::M98 && c.repeat.is_none();
    let packed: Vec<u32> = values
        .iter()
        .filter(|k| packed_ok && **k > 9999 && !numbers.contains(k))
        .map(|k| k % 10000)
        .filter(|k| numbers.contains(k))
        .collect::<BTreeSet<u32>>()
        .into_iter()
        .collect();
    // Every value names a program (directly or packed): no test for the last, no not-found.
    let covered =
        values.iter().all(|k| numbers.contains(k) || (packed_ok && *k > 9999 && numbers.contains(&(k % 10000))));
    out.chain(&c, &v, &c.repeat, (&direct, covered && packed.is_empty()), end, fresh);
    if !packed.is_empty() {
        // Where no program has the number: the count packed in front of four digits.
        let not_found = fresh();
        if !covered {
            out.push(vec![goto(
                not_found,
                Some(cmp(CmpOp::Le, v.clone(), Expr::num(9999.0, false, span), span)),
                span,
            )]);
        }
        let ten_k = || Expr::num(10000.0, false, span);
        let count = func(Func::Trunc, vec![bin(BinOp::Div, v.clone(), ten_k(), span)], span);
        let low = bin(BinOp::Sub, v.clone(), bin(BinOp::Mul, count.clone(), ten_k(), span), span);
        out.chain(&c, &low, &Some(count), (&packed, covered), end, fresh);
        if !covered {
            out.push(vec![]);
            out.here = Some(not_found);
        }
    }
    if !covered {
        let none =
            Call { kind: CallKind::Named, target: CallTarget::Name(NO_PROGRAM.into()), args: vec![], repeat: None };
        out.push(vec![Item { kind: ItemKind::Call(Box::new(none)), span: cspan }]);
    }
    out.here = Some(end);
    out.push(vec![]);
    out.stmts
}
