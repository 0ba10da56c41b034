//! FANUC's vacant value on a control that has none.
//!
//! Representation: a FANUC variable whose vacancy the program can observe ("tracked") gets
//! an is-set flag (BOOL `NAME_SET`, or an R parameter for common variables); while the flag
//! is FALSE the value slot holds 0. So arithmetic reads need no change (vacant reads as 0
//! there), and only the three places where FANUC tells vacant from 0 consult the flag:
//! `EQ`/`NE`, copies (`#1=#2` copies vacancy) and address words (`X#24` is dropped when
//! #24 is vacant, so the block is emitted in an `IF NAME_SET … ELSE … ENDIF`).
//!
//! Which variables are tracked comes from a must-analysis over each program's control-flow
//! graph (FANUC GOTO search order included): a variable is "definitely set" at a point when
//! every path to it assigns a non-vacant value. A vacancy-sensitive use of a variable that is
//! not definitely set makes it tracked; tracking then spreads backwards over copies, G65
//! arguments and the locals an M98 subprogram shares with its callers. Untracked variables
//! stay plain R parameters / DEF variables, so ordinary programs read as before.

use super::*;
pub(super) use crate::lower::children_mut;

/// A variable in the whole translation: a local of one program, or a common variable.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Key {
    Local(usize, u32),
    Common(u32),
}

fn key(prog: usize, n: u32) -> Option<Key> {
    match n {
        1..=33 => Some(Key::Local(prog, n)),
        _ if maybe_common(n) => Some(Key::Common(n)),
        _ => None,
    }
}

/// A common variable number (NGC-only ones included: `haas_vars::maybe_common`).
fn maybe_common(n: u32) -> bool {
    crate::dialect::fanuc::haas_vars::maybe_common(n)
}

/// One node of a program's control-flow graph.
pub(super) enum Node<'a> {
    Items(&'a [Item]),
    /// `WHILE[c]DOm` (or bare `DOm`); `exit` is the node after the matching `END`.
    Head {
        cond: Option<&'a Expr>,
        exit: usize,
    },
    End {
        head: usize,
    },
}

/// The flat node list of a program (in text order) with each node's sequence number.
pub(super) struct Flat<'a> {
    pub nodes: Vec<Node<'a>>,
    pub numbers: Vec<Option<u32>>,
    /// Each block node's span start and whether it may be skipped (`/`); `None` for loop
    /// heads and ends.
    pub blocks: Vec<Option<(u32, bool)>>,
    /// Haas `M97 Pn` nodes with their n: the local subprogram is part of this graph.
    pub m97: Vec<(usize, u32)>,
}

pub(super) fn flatten(body: &[Stmt]) -> Flat<'_> {
    let mut f = Flat { nodes: Vec::new(), numbers: Vec::new(), blocks: Vec::new(), m97: Vec::new() };
    flatten_into(body, &mut f);
    f
}

fn flatten_into<'a>(body: &'a [Stmt], f: &mut Flat<'a>) {
    for s in body {
        match &s.kind {
            StmtKind::Block(b) => {
                for it in &b.items {
                    if let ItemKind::Call(c) = &it.kind {
                        if let (CallKind::M97, CallTarget::Number(n)) = (c.kind, &c.target) {
                            f.m97.push((f.nodes.len(), *n));
                        }
                    }
                }
                f.nodes.push(Node::Items(&b.items));
                f.numbers.push(b.meta.number.as_ref().map(|n| n.value));
                f.blocks.push(Some((b.meta.span.lo, b.meta.skip.is_some())));
            }
            StmtKind::Do(d) => {
                let head = f.nodes.len();
                f.nodes.push(Node::Head { cond: d.cond.as_ref(), exit: 0 });
                f.numbers.push(d.head.number.as_ref().map(|n| n.value));
                f.blocks.push(None);
                flatten_into(&d.body, f);
                f.nodes.push(Node::End { head });
                f.numbers.push(d.end.number.as_ref().map(|n| n.value));
                f.blocks.push(None);
                let exit = f.nodes.len();
                if let Node::Head { exit: e, .. } = &mut f.nodes[head] {
                    *e = exit;
                }
            }
            // Siemens structures do not occur in FANUC input; their bodies still count.
            other => {
                for b in crate::ir::visit::child_bodies(other) {
                    flatten_into(b, f);
                }
            }
        }
    }
}

/// FANUC `GOTO n` from node `from`: the first block numbered `n` searching forward to the
/// end of the program, then from the top.
pub(super) fn resolve(numbers: &[Option<u32>], from: usize, n: u32) -> Option<usize> {
    let len = numbers.len();
    (from + 1..len).chain(0..=from.min(len.saturating_sub(1))).find(|&i| numbers[i] == Some(n))
}

/// Successors of node `i` in a program's control-flow graph (FANUC jump semantics).
pub(super) fn succs(flat: &Flat, i: usize) -> Vec<usize> {
    let len = flat.nodes.len();
    let mut out = Vec::new();
    match &flat.nodes[i] {
        Node::Items(items) => {
            let mut fall = true;
            for it in items.iter() {
                match &it.kind {
                    ItemKind::Goto(g) => {
                        match &g.target {
                            Target::Number(n) => out.extend(resolve(&flat.numbers, i, n.value)),
                            Target::Computed(_) => {
                                out.extend((0..len).filter(|&j| flat.numbers[j].is_some()));
                            }
                            Target::Label(_) => {}
                        }
                        if g.cond.is_none() {
                            fall = false;
                            break;
                        }
                    }
                    // Haas `M97 Pn`: the local subprogram runs from block n (its M99
                    // comes back below).
                    ItemKind::Call(c) if c.kind == CallKind::M97 => {
                        if let CallTarget::Number(n) = c.target {
                            out.extend(resolve(&flat.numbers, i, n));
                        }
                    }
                    ItemKind::Return { to } => {
                        // `M99 P<n>` in a main program continues at its block n. For a
                        // called program the edge is not real, but an extra edge only makes
                        // this must-analysis more careful.
                        // An M99 may end a local subprogram: it continues after every M97
                        // (or runs the section again, L times).
                        if to.is_none() {
                            for &(j, n) in &flat.m97 {
                                out.extend((j + 1 < len).then_some(j + 1));
                                out.extend(resolve(&flat.numbers, j, n));
                            }
                        }
                        if let Some(to) = to {
                            match literal(to) {
                                Some(v) if v >= 0.0 && v.fract() == 0.0 => {
                                    out.extend(resolve(&flat.numbers, i, v as u32))
                                }
                                _ => out.extend((0..len).filter(|&j| flat.numbers[j].is_some())),
                            }
                        }
                        fall = false;
                        break;
                    }
                    ItemKind::End { .. } => {
                        fall = false;
                        break;
                    }
                    _ => {}
                }
            }
            if fall && i + 1 < len {
                out.push(i + 1);
            }
        }
        Node::Head { cond, exit } => {
            if i + 1 < len {
                out.push(i + 1);
            }
            if cond.is_some() && *exit < len {
                out.push(*exit);
            }
        }
        Node::End { head } => out.push(*head),
    }
    out
}

/// Whether `e` can never evaluate to vacant given the definitely-set variables `d`.
fn nonvacant(e: &Expr, d: &BTreeSet<u32>) -> bool {
    match &e.kind {
        ExprKind::Vacant => false,
        ExprKind::Unary(UnOp::Neg, a) => nonvacant(a, d),
        ExprKind::Var(v) => match v.kind {
            VarKind::Hash(0) => false,
            VarKind::Hash(n) if (1..=33).contains(&n) || maybe_common(n) => d.contains(&n),
            VarKind::HashIndirect(_) => false,
            _ => true,
        },
        _ => true,
    }
}

/// The variable `cond` tests for vacancy: `#n EQ #0` (either way round).
fn tested_vacant(cond: &Expr) -> Option<u32> {
    let ExprKind::Cmp(CmpOp::Eq, Tolerance::Exact, a, b) = &cond.kind else { return None };
    match (vacancy_var(a), vacancy_var(b)) {
        (Some(n), None) if is_vacant_literal(b) => Some(n),
        (None, Some(n)) if is_vacant_literal(a) => Some(n),
        _ => None,
    }
}

/// What a program may leave vacant in variables it writes (for callers' analyses).
#[derive(Clone, Default)]
struct Summary {
    locals: BTreeSet<u32>,
    commons: BTreeSet<u32>,
    clobbers: bool,
}

/// Tracked common variables (the per-program tracked locals are stored in the plans).
pub struct Info {
    pub commons: BTreeSet<u32>,
}

fn vacant_writes(body: &[Stmt]) -> Summary {
    let mut s = Summary::default();
    let empty = BTreeSet::new();
    fn item(it: &Item, s: &mut Summary, empty: &BTreeSet<u32>) {
        match &it.kind {
            ItemKind::Assign { target, value } if !nonvacant(value, empty) => match target.kind {
                VarKind::Hash(n @ 1..=33) => {
                    s.locals.insert(n);
                }
                VarKind::Hash(n) if maybe_common(n) => {
                    s.commons.insert(n);
                }
                VarKind::HashIndirect(_) => s.clobbers = true,
                _ => {}
            },
            ItemKind::IfThen { then, .. } => item(then, s, empty),
            _ => {}
        }
    }
    crate::ir::visit::walk_stmts(body, &mut |st| {
        if let StmtKind::Block(b) = &st.kind {
            for it in &b.items {
                item(it, &mut s, &empty);
            }
        }
    });
    s
}

struct Analysis {
    numbers: Vec<Option<u32>>,
    summaries: Vec<Summary>,
    seeds: BTreeSet<Key>,
    /// Address words whose variable is definitely set there: (program, span lo, hi).
    sure: BTreeSet<(usize, u32, u32)>,
    edges: Vec<(Key, Key)>,
}

impl Analysis {
    fn callee(&self, n: u32) -> Option<usize> {
        self.numbers.iter().position(|x| *x == Some(n))
    }

    fn kill_call(&self, c: &Call, d: &mut BTreeSet<u32>) {
        // M97 names a block of this program, whose writes the graph follows itself.
        if c.kind == CallKind::M97 {
            return;
        }
        let CallTarget::Number(n) = c.target else {
            d.clear();
            return;
        };
        let Some(i) = self.callee(n) else { return };
        let s = &self.summaries[i];
        if s.clobbers {
            d.clear();
            return;
        }
        d.retain(|v| !s.commons.contains(v));
        if c.kind == CallKind::M98 {
            d.retain(|v| !s.locals.contains(v));
        }
    }

    fn transfer_item(&self, it: &Item, d: &mut BTreeSet<u32>) {
        match &it.kind {
            ItemKind::Assign { target, value } => match target.kind {
                VarKind::Hash(n) => {
                    if nonvacant(value, d) {
                        d.insert(n);
                    } else {
                        d.remove(&n);
                    }
                }
                VarKind::HashIndirect(_) if !nonvacant(value, d) => d.clear(),
                _ => {}
            },
            ItemKind::IfThen { cond, then } => {
                let mut after = d.clone();
                self.transfer_item(then, &mut after);
                // `IF [#n EQ #0] THEN …`: where the test fails, #n is not vacant (FANUC's
                // EQ tells vacant from 0), so a default written this way leaves it set.
                let mut skipped = d.clone();
                skipped.extend(tested_vacant(cond));
                d.clear();
                d.extend(after.intersection(&skipped).copied());
            }
            ItemKind::Call(c) => self.kill_call(c, d),
            _ => {}
        }
    }

    /// Definitely-set variables at the entry of every node (`None`: unreachable).
    fn dataflow(&self, flat: &Flat, entry: BTreeSet<u32>) -> Vec<Option<BTreeSet<u32>>> {
        let len = flat.nodes.len();
        let mut ins: Vec<Option<BTreeSet<u32>>> = vec![None; len];
        if len == 0 {
            return ins;
        }
        ins[0] = Some(entry);
        let succs: Vec<Vec<usize>> = (0..len).map(|i| succs(flat, i)).collect();
        // `IF [#n EQ #0] GOTO …` ending a node: #n is not vacant where it falls through.
        let fall_set: Vec<Option<u32>> = (0..len)
            .map(|i| match &flat.nodes[i] {
                Node::Items(items) => match items.last().map(|it| &it.kind) {
                    Some(ItemKind::Goto(g)) => g.cond.as_ref().and_then(tested_vacant),
                    _ => None,
                },
                _ => None,
            })
            .collect();
        // Sets only shrink, so this terminates; the bound guards against a slow case.
        for _round in 0..(len + 2).min(200) {
            let mut changed = false;
            for i in 0..len {
                let Some(mut d) = ins[i].clone() else { continue };
                if let Node::Items(items) = &flat.nodes[i] {
                    for it in items.iter() {
                        self.transfer_item(it, &mut d);
                    }
                }
                for (k, &s) in succs[i].iter().enumerate() {
                    // The fall-through edge is the last one (`succs`); a jump to the next
                    // node as well meets it there without the refinement.
                    let mut d = d.clone();
                    if k + 1 == succs[i].len() && s == i + 1 {
                        d.extend(fall_set[i]);
                    }
                    let new = match &ins[s] {
                        None => d.clone(),
                        Some(old) => old.intersection(&d).copied().collect(),
                    };
                    if ins[s].as_ref() != Some(&new) {
                        ins[s] = Some(new);
                        changed = true;
                    }
                }
            }
            if !changed {
                return ins;
            }
        }
        // Not settled: assume nothing is definitely set (tracks more, never wrong).
        vec![Some(BTreeSet::new()); len]
    }

    fn uses_expr(&mut self, prog: usize, e: &Expr, d: &BTreeSet<u32>) {
        if let ExprKind::Cmp(CmpOp::Eq | CmpOp::Ne, Tolerance::Exact, a, b) = &e.kind {
            for (x, y) in [(a, b), (b, a)] {
                if let Some(n) = vacancy_var(x) {
                    let other_nonzero = literal(y).is_some_and(|v| v != 0.0);
                    if !d.contains(&n) && !other_nonzero {
                        self.seeds.extend(key(prog, n));
                    }
                }
            }
        }
        for c in e.children() {
            self.uses_expr(prog, c, d);
        }
    }

    fn uses_item(&mut self, prog: usize, it: &Item, d: &BTreeSet<u32>) {
        match &it.kind {
            ItemKind::Word(w) => {
                if let WordValue::Expr(e) = &w.value {
                    if let Some(n) = vacancy_var(e) {
                        if !d.contains(&n) {
                            self.seeds.extend(key(prog, n));
                        } else {
                            self.sure.insert((prog, e.span.lo, e.span.hi));
                        }
                    }
                }
            }
            ItemKind::Assign { target, value } => {
                if let (VarKind::Hash(t), Some(w)) = (&target.kind, vacancy_var(value)) {
                    if !d.contains(&w) {
                        if let (Some(a), Some(b)) = (key(prog, *t), key(prog, w)) {
                            self.edges.push((a, b));
                        }
                    }
                }
            }
            ItemKind::IfThen { then, .. } => self.uses_item(prog, then, d),
            ItemKind::Call(c) => {
                if let (CallKind::G65 | CallKind::G66, CallTarget::Number(n)) = (c.kind, &c.target) {
                    if let Some(callee) = self.callee(*n) {
                        for a in &c.args {
                            if let Arg::Letter { var, value, .. } = a {
                                if let Some(w) = vacancy_var(value) {
                                    if !d.contains(&w) {
                                        if let Some(src) = key(prog, w) {
                                            self.edges.push((Key::Local(callee, u32::from(*var)), src));
                                        }
                                    }
                                }
                            }
                        }
                    }
                }
            }
            _ => {}
        }
        for e in crate::ir::visit::item_exprs(it) {
            self.uses_expr(prog, e, d);
        }
    }
}

/// Macro entry under `--specialise-callers`: the argument locals every call site gives a
/// value that cannot be vacant. Without it nothing is set on entry: a later caller may leave
/// any argument out.
fn macro_entry(progs: &[(FileId, &Program)], number: Option<u32>) -> BTreeSet<u32> {
    let Some(num) = number else { return BTreeSet::new() };
    let mut result: Option<BTreeSet<u32>> = None;
    let empty = BTreeSet::new();
    for (_, p) in progs {
        crate::ir::visit::walk_stmts(&p.body, &mut |s| {
            if let StmtKind::Block(b) = &s.kind {
                for it in &b.items {
                    if let ItemKind::Call(c) = &it.kind {
                        if matches!(c.kind, CallKind::G65 | CallKind::G66) && c.target == CallTarget::Number(num) {
                            let given: BTreeSet<u32> = c
                                .args
                                .iter()
                                .filter_map(|a| match a {
                                    Arg::Letter { var, value, .. } if nonvacant(value, &empty) => Some(u32::from(*var)),
                                    _ => None,
                                })
                                .collect();
                            result = Some(match result.take() {
                                None => given,
                                Some(r) => r.intersection(&given).copied().collect(),
                            });
                        }
                    }
                }
            }
        });
    }
    result.unwrap_or_default()
}

/// Runs the analysis over every program and stores the tracked locals in the plans.
pub fn analyse(ctx: &mut Ctx, programs: &[(FileId, &Program)]) -> Info {
    let numbers: Vec<Option<u32>> = ctx.progs.iter().map(|p| p.number).collect();
    let mut summaries: Vec<Summary> = programs.iter().map(|(_, p)| vacant_writes(&p.body)).collect();
    // Callees' vacant writes reach the caller: commons through any call, locals through M98.
    let mut calls: Vec<(usize, usize, bool)> = Vec::new();
    for (i, (_, p)) in programs.iter().enumerate() {
        crate::ir::visit::walk_stmts(&p.body, &mut |s| {
            if let StmtKind::Block(b) = &s.kind {
                for it in &b.items {
                    if let ItemKind::Call(c) = &it.kind {
                        if let CallTarget::Number(n) = c.target {
                            if let Some(j) = numbers.iter().position(|x| *x == Some(n)) {
                                calls.push((i, j, c.kind == CallKind::M98));
                            }
                        }
                    }
                }
            }
        });
    }
    for _ in 0..programs.len() + 1 {
        let mut changed = false;
        for &(a, b, m98) in &calls {
            let sb = summaries[b].clone();
            let sa = &mut summaries[a];
            let before = (sa.locals.len(), sa.commons.len(), sa.clobbers);
            sa.commons.extend(sb.commons.iter().copied());
            sa.clobbers |= sb.clobbers;
            if m98 {
                sa.locals.extend(sb.locals.iter().copied());
            }
            changed |= before != (sa.locals.len(), sa.commons.len(), sa.clobbers);
        }
        if !changed {
            break;
        }
    }
    let mut an = Analysis { numbers, summaries, seeds: BTreeSet::new(), sure: BTreeSet::new(), edges: Vec::new() };
    for (i, (_, p)) in programs.iter().enumerate() {
        let flat = flatten(&p.body);
        let entry = if ctx.progs[i].role == Role::Macro && ctx.opts.specialise_callers {
            macro_entry(programs, an.numbers[i])
        } else {
            BTreeSet::new()
        };
        let ins = an.dataflow(&flat, entry);
        // Seeds and copy edges, with the state before each item of the node.
        for (j, d) in ins.into_iter().enumerate() {
            let mut d = d.unwrap_or_default();
            match &flat.nodes[j] {
                Node::Items(items) => {
                    for it in items.iter() {
                        an.uses_item(i, it, &d);
                        an.transfer_item(it, &mut d);
                    }
                }
                Node::Head { cond: Some(c), .. } => an.uses_expr(i, c, &d),
                _ => {}
            }
        }
    }
    // M98 subprograms and their callers share locals. Every local a subprogram shares (its
    // own and its M98 callees') is tracked, in it and in each caller: its `PROC` line then
    // depends on it alone, not on what one caller's flow needs, so a batch job translating
    // the subprogram's own file writes the line its callers' jobs call (a caller in another
    // file tracked a local the subprogram never touches: the call passed a flag the PROC
    // did not take).
    for &(a, b, m98) in &calls {
        if m98 {
            for &n in &ctx.progs[b].locals {
                an.seeds.insert(Key::Local(a, n));
                an.seeds.insert(Key::Local(b, n));
            }
        }
    }
    let mut tracked = an.seeds.clone();
    loop {
        let before = tracked.len();
        for (dst, src) in &an.edges {
            if tracked.contains(dst) {
                tracked.insert(*src);
            }
        }
        if tracked.len() == before {
            break;
        }
    }
    for &(p, lo, hi) in &an.sure {
        if let Some(pl) = ctx.progs.get_mut(p) {
            pl.sure_words.insert((lo, hi));
        }
    }
    let mut commons = BTreeSet::new();
    for k in tracked {
        match k {
            Key::Local(p, n) => {
                if let Some(pl) = ctx.progs.get_mut(p) {
                    pl.tracked.insert(n);
                    pl.locals.insert(n);
                }
            }
            Key::Common(n) => {
                commons.insert(n);
            }
        }
    }
    Info { commons }
}

// ---- rewriting ----

/// The flag of FANUC variable `n` in the current program, if it is tracked.
fn flag_ref(ctx: &Ctx, n: u32, span: Span) -> Option<VarRef> {
    match n {
        1..=33 if ctx.plan().tracked.contains(&n) => Some(named_ref(&super::varmap::flag_name(ctx.plan(), n), span)),
        _ if maybe_common(n) => ctx.common_flags.get(&n).map(|r| VarRef { kind: VarKind::R(*r), span }),
        _ => None,
    }
}

/// The flag expression of a value: a tracked variable's flag, 0 for `#0`, else 1.
enum Flag {
    Const(bool),
    Var(VarRef),
}

fn flag_of(ctx: &Ctx, e: &Expr) -> Flag {
    if is_vacant_literal(e) {
        return Flag::Const(false);
    }
    match vacancy_var(e) {
        Some(n) => flag_ref(ctx, n, e.span).map_or(Flag::Const(true), Flag::Var),
        None => Flag::Const(true),
    }
}

fn flag_expr(f: Flag, span: Span) -> Expr {
    match f {
        Flag::Const(b) => int(i64::from(b), span),
        Flag::Var(v) => Expr::new(ExprKind::Var(Box::new(v)), span),
    }
}

/// The is-set flag to pass for a G65 argument value.
pub fn flag_of_value(ctx: &Ctx, v: &Expr) -> Expr {
    flag_expr(flag_of(ctx, v), v.span)
}

/// The caller's flag variable of local `n` (passed by reference to an M98 subprogram).
pub fn local_flag_expr(ctx: &Ctx, n: u32, span: Span) -> Expr {
    match flag_ref(ctx, n, span) {
        Some(v) => Expr::new(ExprKind::Var(Box::new(v)), span),
        None => int(1, span),
    }
}

/// EQ/NE with FANUC's vacant rule, written with the flags.
fn rewrite_cmp(ctx: &Ctx, e: &mut Expr) {
    for c in children_mut(e) {
        rewrite_cmp(ctx, c);
    }
    let span = e.span;
    let ExprKind::Cmp(op @ (CmpOp::Eq | CmpOp::Ne), Tolerance::Exact, a, b) = &e.kind else { return };
    let (fa, fb) = (flag_of(ctx, a), flag_of(ctx, b));
    if matches!((&fa, &fb), (Flag::Const(true), Flag::Const(true))) {
        return;
    }
    let eq = *op == CmpOp::Eq;
    let cmp = || Expr::new(ExprKind::Cmp(*op, Tolerance::Exact, a.clone(), b.clone()), span);
    let new = match (fa, fb) {
        (Flag::Const(x), Flag::Const(y)) => int(i64::from((x == y) == eq), span),
        (Flag::Const(false), Flag::Var(f)) | (Flag::Var(f), Flag::Const(false)) => {
            let f = flag_expr(Flag::Var(f), span);
            if eq {
                not(f)
            } else {
                f
            }
        }
        (Flag::Const(true), Flag::Var(f)) | (Flag::Var(f), Flag::Const(true)) => {
            let f = flag_expr(Flag::Var(f), span);
            if eq {
                bin(BinOp::And, f, cmp())
            } else {
                bin(BinOp::Or, not(f), cmp())
            }
        }
        (Flag::Var(x), Flag::Var(y)) => {
            let differ = bin(BinOp::Xor, flag_expr(Flag::Var(x), span), flag_expr(Flag::Var(y), span));
            if eq {
                bin(BinOp::And, not(differ), cmp())
            } else {
                bin(BinOp::Or, differ, cmp())
            }
        }
    };
    *e = new;
}

/// An assignment plus, for a tracked target, the write of its flag.
fn rewrite_assign(ctx: &Ctx, it: Item) -> Vec<Item> {
    let ItemKind::Assign { target, value } = &it.kind else { return vec![it] };
    let VarKind::Hash(n) = target.kind else { return vec![it] };
    let Some(flag) = flag_ref(ctx, n, target.span) else { return vec![it] };
    let f = flag_of(ctx, value);
    let value = if matches!(f, Flag::Const(false)) { int(0, value.span) } else { value.clone() };
    let fe = flag_expr(f, it.span);
    vec![assign((**target).clone(), value, it.span), assign(flag, fe, it.span)]
}

/// Rewrites the current program: flags on writes, EQ/NE on vacancy, conditional words.
pub fn rewrite(ctx: &mut Ctx, body: Vec<Stmt>) -> Vec<Stmt> {
    let mut body = body;
    map_exprs(&mut body, &mut |e| rewrite_cmp(ctx, e));
    map_bodies(body, &mut |list| {
        let mut out = Vec::with_capacity(list.len());
        for s in list {
            let span = s.span;
            match s.kind {
                StmtKind::Block(b) => rewrite_block(ctx, b, span, &mut out),
                kind => out.push(Stmt { kind, span }),
            }
        }
        out
    })
}

fn rewrite_block(ctx: &mut Ctx, mut b: Block, span: Span, out: &mut Vec<Stmt>) {
    // IF[..]THEN with a tracked target: two assignments, so a real IF block.
    if let [Item { kind: ItemKind::IfThen { cond, then }, span: isp }] = b.items.as_slice() {
        let assigns = rewrite_assign(ctx, (**then).clone());
        if assigns.len() > 1 {
            let inner = plain_block(assigns, *isp);
            let meta = std::mem::take(&mut b.meta);
            if meta.number.is_some() || meta.label.is_some() || !meta.comments.is_empty() || meta.skip.is_some() {
                out.push(block_stmt(meta, vec![]));
            }
            out.push(if_stmt(cond.clone(), vec![inner], None, span));
            return;
        }
    }
    let mut items = Vec::with_capacity(b.items.len());
    for it in std::mem::take(&mut b.items) {
        items.extend(rewrite_assign(ctx, it));
    }
    // Address words whose variable may be vacant: FANUC drops them.
    let cond_words: Vec<usize> = items
        .iter()
        .enumerate()
        .filter_map(|(i, it)| match &it.kind {
            ItemKind::Word(Word { value: WordValue::Expr(e), .. })
                if !ctx.plan().sure_words.contains(&(e.span.lo, e.span.hi)) =>
            {
                vacancy_var(e).and_then(|n| flag_ref(ctx, n, e.span)).map(|_| i)
            }
            _ => None,
        })
        .collect();
    if cond_words.is_empty() {
        b.items = items;
        out.push(Stmt { kind: StmtKind::Block(b), span });
        return;
    }
    if cond_words.len() > 3 {
        if let Some(st) = ctx.unsupported(
            "NC359",
            span,
            "a block with more than 3 address words whose variables may be vacant",
            "test the arguments with IF[#n EQ #0] and write the variants out, or give the arguments a value",
        ) {
            out.push(st);
        }
        return;
    }
    // The number, label and comments stay on a block of their own in front of the IF, so
    // GOTO targets and the comment remain visible.
    let meta = std::mem::take(&mut b.meta);
    if meta.number.is_some() || meta.label.is_some() || !meta.comments.is_empty() || meta.skip.is_some() {
        out.push(block_stmt(meta.clone(), vec![]));
    }
    out.push(variants(ctx, &items, &cond_words, span));
}

fn variants(ctx: &Ctx, items: &[Item], cond: &[usize], span: Span) -> Stmt {
    let Some((&first, rest)) = cond.split_first() else {
        return plain_block(items.to_vec(), span);
    };
    let n = match &items[first].kind {
        ItemKind::Word(Word { value: WordValue::Expr(e), .. }) => vacancy_var(e).unwrap_or(0),
        _ => 0,
    };
    let flag = local_or_common_flag(ctx, n, items[first].span);
    let with = variants(ctx, items, rest, span);
    let without_items: Vec<Item> =
        items.iter().enumerate().filter(|(i, _)| *i != first).map(|(_, it)| it.clone()).collect();
    let rest_shifted: Vec<usize> = rest.iter().map(|&i| if i > first { i - 1 } else { i }).collect();
    let without = variants(ctx, &without_items, &rest_shifted, span);
    let mut else_body = vec![without];
    // A block left without any item still runs its modal G codes on FANUC; an empty one is
    // nothing at all.
    if let StmtKind::Block(b) = &else_body[0].kind {
        if b.items.is_empty() {
            else_body.clear();
        }
    }
    if else_body.is_empty() {
        if_stmt(flag, vec![with], None, span)
    } else {
        if_stmt(flag, vec![with], Some(else_body), span)
    }
}

fn local_or_common_flag(ctx: &Ctx, n: u32, span: Span) -> Expr {
    flag_expr(flag_ref(ctx, n, span).map_or(Flag::Const(true), Flag::Var), span)
}
