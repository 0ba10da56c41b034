//! Splits Siemens multi-statement blocks into FANUC one-macro-statement blocks, preserving
//! order, and turns `DEF` declarations into explicit assignments.
//!
//! A Siemens block runs its assignments (and DEF initialisations, messages) in text order,
//! then its NC words as one motion block, then its control item (jump, call, return, end).
//! A word's value is the one at its place in the text: a word written before an assignment
//! in the same block is computed into a temporary at that place.
//! FANUC allows one macro statement per block and no NC words beside an assignment, so each
//! becomes its own block in that order. The first piece keeps the block number and label (a
//! jump to the block must run all pieces), every piece keeps the block-skip slash.

use super::*;

/// Largest array that DEF initialisation writes element by element.
const MAX_ARRAY: u32 = 1000;

pub fn run(ctx: &mut Ctx, prog: &mut Program, info: &mut ProgInfo) {
    for p in &prog.params {
        info.types.insert(p.name.clone(), (p.ty, p.dims.clone()));
    }
    let body = std::mem::take(&mut prog.body);
    prog.body = split_body(ctx, body, info);
    drop_dead_zero_stores(ctx, &mut prog.body);
}

/// Whether `e` reads the named variable `name` (also in subscripts).
fn mentions(e: &Expr, name: &str) -> bool {
    let mut stack = vec![e];
    while let Some(e) = stack.pop() {
        match &e.kind {
            ExprKind::Var(v) => match &v.kind {
                VarKind::Named { name: n, indices } => {
                    if n == name {
                        return true;
                    }
                    stack.extend(indices.iter());
                }
                VarKind::RIndirect(x) | VarKind::HashIndirect(x) => stack.push(x),
                VarKind::System { indices, .. } => stack.extend(indices.iter()),
                _ => {}
            },
            ExprKind::Binary(_, a, b) | ExprKind::Cmp(_, _, a, b) => {
                stack.push(a);
                stack.push(b);
            }
            ExprKind::Unary(_, a) => stack.push(a),
            ExprKind::Func(_, args) => stack.extend(args.iter()),
            _ => {}
        }
    }
    false
}

/// How far a dead `v=0` looks ahead for the store that replaces it (statements).
pub const DEAD_STORE_WINDOW: usize = 64;

/// Removes a top-level `v=0` (a DEF's start value, typically) that a later top-level
/// assignment to `v` replaces before anything can read it: only plain blocks without a
/// jump, call, end or skip between, none of which reads `v`. A DEF variable the program
/// sets at once then reads as one assignment, and a round trip (whose other direction
/// writes the DEF's start value out as `LOC1=0`) does not add one each time.
///
/// A segmented stream's stand-in for a run of straight blocks counts as the run's blocks
/// (`ctx.stand_in_runs`: as many statements of the window, or one that stops the search),
/// so the skeleton keeps the start values the whole program keeps.
fn drop_dead_zero_stores(ctx: &mut Ctx, body: &mut Vec<Stmt>) {
    let zero_store = |s: &Stmt| -> Option<String> {
        let StmtKind::Block(b) = &s.kind else { return None };
        let m = &b.meta;
        if m.label.is_some() || m.number.is_some() || !m.comments.is_empty() || b.items.len() != 1 {
            return None;
        }
        match &b.items[0].kind {
            ItemKind::Assign { target, value: Expr { kind: ExprKind::Num(n), .. } } if n.value == 0.0 => {
                match &target.kind {
                    VarKind::Named { name, indices } if indices.is_empty() => Some(name.clone()),
                    _ => None,
                }
            }
            _ => None,
        }
    };
    let reads = |s: &Stmt, name: &str| {
        let mut found = false;
        let StmtKind::Block(b) = &s.kind else { return true };
        for it in &b.items {
            let mut check = |e: &Expr| found |= mentions(e, name);
            for e in crate::ir::visit::item_exprs(it) {
                check(e);
            }
            if let ItemKind::Assign { target, .. } = &it.kind {
                if let VarKind::Named { indices, .. } = &target.kind {
                    indices.iter().for_each(&mut check);
                }
            }
        }
        found
    };
    let mut dead = Vec::new();
    for i in 0..body.len() {
        let Some(name) = zero_store(&body[i]) else { continue };
        // Jumps passed on the way: each must name a label between the zero store and the
        // store W that replaces it (it then skips only blocks that do not read `v`), never
        // one past W.
        let mut jumps: Vec<&Target> = Vec::new();
        // Statements of the window used so far (a stand-in uses its run's blocks).
        let (mut used, mut last_run) = (0, None);
        for (k, s) in body.iter().enumerate().skip(i + 1) {
            if used == DEAD_STORE_WINDOW {
                break;
            }
            used += 1;
            let StmtKind::Block(b) = &s.kind else {
                // An IF or WHILE that never reads `v` and only assigns and moves (no jump,
                // call or end) lets the search go on past it (`DEF REAL A, B` then
                // `A=4 IF 9<A … ENDIF B=4`: B's start value is dead too).
                if passes_over(s, &name, &reads) {
                    continue;
                }
                break;
            };
            if let Some(run) = super::stand_in(&b.meta) {
                // A segmented stream's stand-in: the search goes through its run's blocks as
                // it does in the whole program (none of which reads or sets anything). A
                // carrier line after it, with the same run's mark, stands for no block.
                match ctx.stand_in_runs.get(run) {
                    _ if last_run == Some(run) => used -= 1,
                    Some(&n) if n != RUN_STOPS_SEARCH => used = used - 1 + usize::from(n),
                    _ => break,
                }
                last_run = Some(run);
                if used > DEAD_STORE_WINDOW {
                    break;
                }
                continue;
            }
            let plain = b.meta.skip.is_none()
                && b.items
                    .iter()
                    .all(|it| matches!(it.kind, ItemKind::Assign { .. } | ItemKind::Word(_) | ItemKind::Goto(_)));
            if !plain {
                break;
            }
            jumps.extend(b.items.iter().filter_map(|it| match &it.kind {
                ItemKind::Goto(g) => Some(&g.target),
                _ => None,
            }));
            let sets = b.items.iter().any(|it| {
                matches!(&it.kind, ItemKind::Assign { target, .. } if matches!(&target.kind, VarKind::Named { name: n, indices } if *n == name && indices.is_empty()))
            });
            if reads(s, &name) {
                break;
            }
            if sets {
                let between = &body[i + 1..=k];
                let lands = |t: &Target| {
                    between.iter().any(|x| {
                        crate::ir::visit::metas(&x.kind).first().is_some_and(|m| match t {
                            Target::Label(l) => m.label.as_ref().is_some_and(|x| x.name == l.name),
                            // A number may stand on several blocks; the search could pass W.
                            Target::Number(_) | Target::Computed(_) => false,
                        })
                    })
                };
                if jumps.iter().all(|t| lands(t)) {
                    dead.push(i);
                }
                break;
            }
        }
    }
    let mut k = 0;
    body.retain(|_| {
        let keep = !dead.contains(&k);
        k += 1;
        keep
    });
}

/// Whether the IF or WHILE statement `s` neither reads `name` (in a condition or a block)
/// nor holds anything but plain blocks of assignments and words.
fn passes_over(s: &Stmt, name: &str, reads: &dyn Fn(&Stmt, &str) -> bool) -> bool {
    let conds: Vec<&Expr> = match &s.kind {
        StmtKind::If(i) => vec![&i.cond],
        StmtKind::While(w) => vec![&w.cond],
        _ => return false,
    };
    if conds.iter().any(|c| mentions(c, name)) {
        return false;
    }
    let mut ok = true;
    for body in crate::ir::visit::child_bodies(&s.kind) {
        for inner in body {
            ok &= match &inner.kind {
                StmtKind::Block(b) => {
                    b.items.iter().all(|it| matches!(it.kind, ItemKind::Assign { .. } | ItemKind::Word(_)))
                        && !reads(inner, name)
                }
                _ => passes_over(inner, name, reads),
            };
        }
    }
    ok
}

fn split_body(ctx: &mut Ctx, body: Vec<Stmt>, info: &mut ProgInfo) -> Vec<Stmt> {
    let mut out = Vec::with_capacity(body.len());
    for mut s in body {
        match &mut s.kind {
            StmtKind::Block(b) => {
                let b = std::mem::take(b);
                split_block(ctx, b, info, &mut out);
                continue;
            }
            StmtKind::If(i) => {
                i.then_body = split_body(ctx, std::mem::take(&mut i.then_body), info);
                if let Some(e) = &mut i.else_part {
                    e.body = split_body(ctx, std::mem::take(&mut e.body), info);
                }
            }
            StmtKind::While(w) => w.body = split_body(ctx, std::mem::take(&mut w.body), info),
            StmtKind::Loop(l) => l.body = split_body(ctx, std::mem::take(&mut l.body), info),
            StmtKind::For(f) => f.body = split_body(ctx, std::mem::take(&mut f.body), info),
            StmtKind::Repeat(r) => r.body = split_body(ctx, std::mem::take(&mut r.body), info),
            StmtKind::Do(d) => d.body = split_body(ctx, std::mem::take(&mut d.body), info),
        }
        out.push(s);
    }
    out
}

fn split_block(ctx: &mut Ctx, mut b: Block, info: &mut ProgInfo, out: &mut Vec<Stmt>) {
    // SUPA is a word of its block on FANUC (G53), not a statement after it.
    super::frames::supa_as_g53(&mut b);
    let mut first: Vec<Item> = Vec::new();
    let mut words: Vec<Item> = Vec::new();
    let mut tail: Vec<Item> = Vec::new();
    let mut marks: Vec<Stmt> = Vec::new();
    let last_assign = b.items.iter().rposition(|i| matches!(i.kind, ItemKind::Assign { .. } | ItemKind::Def(_)));
    for (k, mut it) in b.items.into_iter().enumerate() {
        match it.kind {
            ItemKind::Def(d) => def_items(ctx, *d, it.span, info, &mut first, &mut marks),
            ItemKind::Assign { .. } | ItemKind::Message { .. } => first.push(it),
            ItemKind::Word(ref mut w) => {
                // A word's value is taken where it is written: an assignment later in the
                // block must not change it, so it is computed before that assignment.
                if last_assign.is_some_and(|a| a > k) {
                    let (WordValue::Expr(e) | WordValue::Ac(e) | WordValue::Ic(e) | WordValue::Rotary(_, e)) =
                        &mut w.value;
                    if !matches!(e.kind, ExprKind::Num(_) | ExprKind::Str(_)) {
                        let t = ctx.temp(e.span);
                        let v = std::mem::replace(e, var_expr(&t));
                        first.push(assign_item(&t, v, it.span));
                    }
                }
                words.push(it)
            }
            _ => tail.push(it),
        }
    }
    let mut pieces: Vec<Vec<Item>> = first.into_iter().map(|i| vec![i]).collect();
    if !words.is_empty() {
        pieces.push(words);
    }
    pieces.extend(tail.into_iter().map(|i| vec![i]));
    let span = b.meta.span;
    let skip = b.meta.skip;
    if pieces.is_empty() {
        out.push(meta_stmt(b.meta, vec![]));
        out.extend(marks);
        return;
    }
    let mut meta = Some(b.meta);
    for items in pieces {
        let m = meta.take().unwrap_or(BlockMeta { span, skip, ..BlockMeta::default() });
        out.push(meta_stmt(m, items));
    }
    out.extend(marks);
}

/// `DEF type a=1, b[3]` → `a=1`, `b[0]=0`, `b[1]=0`, `b[2]=0`: Siemens DEF variables start at
/// their initial value or 0 on every run, FANUC variables keep whatever they held.
fn def_items(ctx: &mut Ctx, d: Def, span: Span, info: &mut ProgInfo, out: &mut Vec<Item>, marks: &mut Vec<Stmt>) {
    if let Some(scope) = d.scope {
        // Global user data keeps its value between programs (the HMI often writes it): a
        // FANUC translation would have to map it to retained common variables for the whole
        // library, never initialise it here.
        let kw = if scope == DefScope::Nck { "NCK" } else { "CHAN" };
        let what = format!("global user data definition DEF {kw} {}", d.ty);
        let hint = "FANUC has no declarations; global user data needs a library-wide map to common variables #500+";
        marks.extend(ctx.unsupported("NC634", span, &what, hint));
        return;
    }
    for v in d.vars {
        info.types.insert(v.name.clone(), (d.ty, v.dims.clone()));
        if matches!(d.ty, DataType::String(_) | DataType::Axis | DataType::Frame) {
            // `axis_vars` has said why this AXIS variable is not one known axis.
            if !ctx.axis_reported.contains(&v.span) {
                let what = format!("DEF {} {}", d.ty, v.name);
                let hint = "FANUC variables hold numbers only; rewrite the program without STRING/AXIS/FRAME variables";
                marks.extend(ctx.unsupported("NC310", v.span, &what, hint));
            }
            continue;
        }
        let total: u32 = crate::ir::elements(&v.dims);
        if total > MAX_ARRAY {
            let what = match total {
                u32::MAX => format!("array {} with more than {} elements", v.name, u32::MAX - 1),
                _ => format!("array {} with {total} elements", v.name),
            };
            marks.extend(ctx.unsupported("NC310", v.span, &what, "FANUC has at most a few hundred common variables"));
            continue;
        }
        let values: Vec<Expr> = match &v.init {
            None => vec![num(0.0, v.span); total as usize],
            Some(Init::Value(e)) => vec![e.clone(); total as usize],
            Some(Init::Set(list)) => (0..total as usize)
                .map(|k| list.get(k).cloned().flatten().unwrap_or_else(|| num(0.0, v.span)))
                .collect(),
            Some(Init::Rep { value, count }) => {
                let n = match count.as_ref().map(|c| &c.kind) {
                    None => total as usize,
                    Some(ExprKind::Num(n)) => n.value.max(0.0) as usize,
                    Some(_) => {
                        let what = format!("REP with a computed count in DEF {}", v.name);
                        marks.extend(ctx.unsupported("NC310", v.span, &what, "write the count as a constant"));
                        continue;
                    }
                };
                (0..total as usize).map(|k| if k < n { value.clone() } else { num(0.0, v.span) }).collect()
            }
        };
        for (k, value) in values.into_iter().enumerate() {
            let indices = element_indices(&v.dims, k as u32, v.span);
            let target = VarRef { kind: VarKind::Named { name: v.name.clone(), indices }, span: v.span };
            out.push(assign_item(&target, value, span));
        }
    }
}

/// Row-major subscripts of element `k` of an array with `dims` (empty for a scalar).
fn element_indices(dims: &[u32], k: u32, span: Span) -> Vec<Expr> {
    match dims {
        [] => vec![],
        [_] => vec![num(k as f64, span)],
        [_, n2] => vec![num((k / n2.max(&1)) as f64, span), num((k % n2.max(&1)) as f64, span)],
        _ => {
            let mut rest = k;
            let mut idx = vec![0u32; dims.len()];
            for (i, d) in dims.iter().enumerate().rev() {
                idx[i] = rest % d.max(&1);
                rest /= d.max(&1);
            }
            idx.into_iter().map(|i| num(i as f64, span)).collect()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::build::*;
    use super::*;

    #[test]
    fn assignments_come_before_words_and_control_after() {
        let b = Block {
            meta: BlockMeta { number: Some(SeqNo { value: 10, span: sp() }), ..BlockMeta::default() },
            items: vec![word_item(b'X', r(1)), assign(rv(1), n(0.0)), assign(rv(4), n(1.0)), ret_item()],
        };
        let mut prog = program(vec![Stmt { kind: StmtKind::Block(b), span: sp() }]);
        let mut ctx = Ctx::new(0, UnsupportedPolicy::Error);
        run(&mut ctx, &mut prog, &mut ProgInfo::default());
        let shapes: Vec<String> = prog.body.iter().map(shape).collect();
        // X=R1 is written before the assignments: its value is taken first, into a temporary.
        assert_eq!(shapes, ["N10 assign", "- assign", "- assign", "- word", "- return"]);
    }

    #[test]
    fn def_initialises_every_element() {
        let d = Def {
            scope: None,
            ty: DataType::Real,
            vars: vec![DefVar { name: "A".into(), dims: vec![2, 2], init: None, span: sp() }],
        };
        let b = Block { meta: BlockMeta::default(), items: vec![item(ItemKind::Def(Box::new(d)), sp())] };
        let mut prog = program(vec![Stmt { kind: StmtKind::Block(b), span: sp() }]);
        let mut ctx = Ctx::new(0, UnsupportedPolicy::Error);
        let mut info = ProgInfo::default();
        run(&mut ctx, &mut prog, &mut info);
        assert_eq!(prog.body.len(), 4);
        assert_eq!(info.types.get("A"), Some(&(DataType::Real, vec![2, 2])));
    }

    #[test]
    fn string_def_is_unsupported() {
        let d = Def {
            scope: None,
            ty: DataType::String(10),
            vars: vec![DefVar { name: "S".into(), dims: vec![], init: None, span: sp() }],
        };
        let b = Block { meta: BlockMeta::default(), items: vec![item(ItemKind::Def(Box::new(d)), sp())] };
        let mut prog = program(vec![Stmt { kind: StmtKind::Block(b), span: sp() }]);
        let mut ctx = Ctx::new(0, UnsupportedPolicy::Error);
        run(&mut ctx, &mut prog, &mut ProgInfo::default());
        assert_eq!(ctx.unsupported, 1);
        assert_eq!(ctx.diags[0].code, "NC310");
    }
}
