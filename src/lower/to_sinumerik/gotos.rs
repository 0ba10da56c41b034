//! FANUC jumps → Siemens jumps with the same target.
//!
//! FANUC `GOTO n` searches forward to the end of the program, then from the top, and takes
//! the first block numbered n. The pass resolves every jump to that block at translation
//! time, gives each target block a unique label (`LBL_10`, a second block N10 `LBL_10_2`),
//! and writes `GOTOF` when the target lies after the jump, `GOTOB` otherwise: with unique
//! labels both searches find exactly the block FANUC would. A target on a `WHILE` line gets
//! a label block in front of the loop (jumping there re-enters the loop from its start, as
//! on FANUC); a target on an `END` line gets a label block at the end of the loop body.
//! Jumping out of a loop stays a plain `GOTOF`/`GOTOB` (legal on both controls); jumping
//! into a loop is refused, as FANUC refuses it.
//!
//! Computed `GOTO#1` / `GOTO[expr]` → `CASE(ROUND(expr)) OF n1 GOTOx LBL_n1 …` over every
//! N number of the program, each arm resolved from the jump's own position; a number with
//! no block jumps through `NCTRANS_NO_N` (a STRING holding a label that does not exist), so
//! Siemens raises its own alarm 14080 where FANUC raises 128.

use super::vacancy::resolve;
use super::*;

/// Siemens alarm numbers for FANUC runtime alarms the translation raises itself.
pub const RUNTIME_ALARM_BASE: i64 = 64000;

/// The STRING variable a computed GOTO jumps through when no block has the number.
pub const NO_TARGET: &str = "NCTRANS_NO_N";

#[derive(Default)]
struct Scan {
    numbers: Vec<Option<u32>>,
    /// Enclosing loops (head node, end node) of every node.
    loops: Vec<Vec<(usize, usize)>>,
    /// Node of every GOTO / computed GOTO item, in visit order, with its target.
    gotos: Vec<(usize, Span, GotoKind)>,
}

enum GotoKind {
    Number(u32),
    Computed,
    Other,
}

fn scan(body: &[Stmt], s: &mut Scan, stack: &mut Vec<(usize, usize)>) {
    for st in body {
        match &st.kind {
            StmtKind::Block(b) => {
                let idx = s.numbers.len();
                s.numbers.push(b.meta.number.as_ref().map(|n| n.value));
                s.loops.push(stack.clone());
                for it in &b.items {
                    let mut visit = |it: &Item| {
                        if let ItemKind::Goto(g) = &it.kind {
                            let k = match &g.target {
                                Target::Number(n) => GotoKind::Number(n.value),
                                Target::Computed(_) => GotoKind::Computed,
                                Target::Label(_) => GotoKind::Other,
                            };
                            s.gotos.push((idx, it.span, k));
                        }
                    };
                    visit(it);
                    if let ItemKind::IfThen { then, .. } = &it.kind {
                        visit(then);
                    }
                }
            }
            StmtKind::Do(d) => {
                let head = s.numbers.len();
                s.numbers.push(d.head.number.as_ref().map(|n| n.value));
                s.loops.push(stack.clone());
                // The end index is only known after the body: patch it.
                stack.push((head, usize::MAX));
                let depth = stack.len();
                scan(&d.body, s, stack);
                let end = s.numbers.len();
                s.numbers.push(d.end.number.as_ref().map(|n| n.value));
                s.loops.push(stack.clone());
                stack.truncate(depth - 1);
                for l in s.loops.iter_mut().skip(head) {
                    for r in l.iter_mut() {
                        if *r == (head, usize::MAX) {
                            *r = (head, end);
                        }
                    }
                }
            }
            other => {
                for b in crate::ir::visit::child_bodies(other) {
                    scan(b, s, stack);
                }
            }
        }
    }
}

struct Plan {
    /// Label of every target node.
    labels: BTreeMap<usize, String>,
    /// Per GOTO in visit order: its node.
    goto_nodes: Vec<usize>,
    numbers: Vec<Option<u32>>,
}

/// Lowers every jump of the current program.
pub fn lower(ctx: &mut Ctx, body: Vec<Stmt>) -> Vec<Stmt> {
    let mut s = Scan::default();
    scan(&body, &mut s, &mut Vec::new());
    if s.gotos.is_empty() {
        return body;
    }
    let mut targets: BTreeSet<usize> = BTreeSet::new();
    for (node, span, k) in &s.gotos {
        match k {
            GotoKind::Number(n) => match resolve(&s.numbers, *node, *n) {
                Some(t) => {
                    let inside_ok = s.loops[t].iter().all(|&(h, e)| h < *node && *node <= e);
                    if !inside_ok {
                        ctx.error(
                            "NC367",
                            *span,
                            format!("GOTO {n} jumps into a WHILE/DO loop"),
                            "jumps into the loop",
                            "FANUC forbids jumping into a loop (and so does Siemens); jump to the WHILE block instead",
                        );
                    }
                    targets.insert(t);
                }
                // The control runs the program until the jump is taken (a block after the
                // closing `%` is not read): the jump becomes Siemens' own jump alarm.
                None => ctx.warn(
                    "NC366",
                    *span,
                    format!(
                        "GOTO {n}: the program has no block N{n} (FANUC alarm 128 when it is taken): written as a \
                         jump to a label that does not exist (Siemens alarm 14080)"
                    ),
                    "target not found",
                ),
            },
            GotoKind::Computed => {
                targets.extend((0..s.numbers.len()).filter(|&i| s.numbers[i].is_some()));
            }
            GotoKind::Other => {}
        }
    }
    let mut labels = BTreeMap::new();
    let mut seen: BTreeMap<u32, u32> = BTreeMap::new();
    for (i, n) in s.numbers.iter().enumerate() {
        let Some(n) = n else { continue };
        let k = seen.entry(*n).or_insert(0);
        *k += 1;
        if targets.contains(&i) {
            labels.insert(i, if *k == 1 { format!("LBL_{n}") } else { format!("LBL_{n}_{k}") });
        }
    }
    let plan = Plan { labels, goto_nodes: s.gotos.iter().map(|g| g.0).collect(), numbers: s.numbers };
    let mut counter = 0usize;
    let mut goto_i = 0usize;
    rewrite(ctx, body, &plan, &mut counter, &mut goto_i)
}

fn rewrite(ctx: &mut Ctx, body: Vec<Stmt>, plan: &Plan, counter: &mut usize, goto_i: &mut usize) -> Vec<Stmt> {
    let mut out = Vec::with_capacity(body.len());
    for st in body {
        let span = st.span;
        match st.kind {
            StmtKind::Block(mut b) => {
                let idx = *counter;
                *counter += 1;
                if let Some(l) = plan.labels.get(&idx) {
                    b.meta.label = Some(Label { name: l.clone(), span: b.meta.span });
                }
                let mut extra: Vec<Stmt> = Vec::new();
                let mut items = Vec::with_capacity(b.items.len());
                for it in std::mem::take(&mut b.items) {
                    match it.kind {
                        ItemKind::Goto(g) => {
                            let node = plan.goto_nodes.get(*goto_i).copied().unwrap_or(idx);
                            *goto_i += 1;
                            lower_goto(ctx, *g, it.span, node, plan, &mut items, &mut extra);
                        }
                        ItemKind::IfThen { cond, then } => {
                            if let ItemKind::Goto(g) = then.kind {
                                // IF[c]THEN GOTO n is IF[c]GOTO n.
                                let node = plan.goto_nodes.get(*goto_i).copied().unwrap_or(idx);
                                *goto_i += 1;
                                let mut g = *g;
                                g.cond = Some(cond);
                                lower_goto(ctx, g, it.span, node, plan, &mut items, &mut extra);
                            } else {
                                items.push(Item { kind: ItemKind::IfThen { cond, then }, span: it.span });
                            }
                        }
                        kind => items.push(Item { kind, span: it.span }),
                    }
                }
                b.items = items;
                out.push(Stmt { kind: StmtKind::Block(b), span });
                out.extend(extra);
            }
            StmtKind::Do(mut d) => {
                let head = *counter;
                *counter += 1;
                if let Some(l) = plan.labels.get(&head) {
                    out.push(label_stmt(l, d.head.span));
                }
                d.body = rewrite(ctx, std::mem::take(&mut d.body), plan, counter, goto_i);
                let end = *counter;
                *counter += 1;
                if let Some(l) = plan.labels.get(&end) {
                    d.body.push(label_stmt(l, d.end.span));
                }
                out.push(Stmt { kind: StmtKind::Do(d), span });
            }
            mut kind => {
                match &mut kind {
                    StmtKind::If(i) => {
                        i.then_body = rewrite(ctx, std::mem::take(&mut i.then_body), plan, counter, goto_i);
                        if let Some(e) = &mut i.else_part {
                            e.body = rewrite(ctx, std::mem::take(&mut e.body), plan, counter, goto_i);
                        }
                    }
                    StmtKind::While(w) => w.body = rewrite(ctx, std::mem::take(&mut w.body), plan, counter, goto_i),
                    StmtKind::Loop(l) => l.body = rewrite(ctx, std::mem::take(&mut l.body), plan, counter, goto_i),
                    StmtKind::For(f) => f.body = rewrite(ctx, std::mem::take(&mut f.body), plan, counter, goto_i),
                    StmtKind::Repeat(r) => r.body = rewrite(ctx, std::mem::take(&mut r.body), plan, counter, goto_i),
                    StmtKind::Block(_) | StmtKind::Do(_) => {}
                }
                out.push(Stmt { kind, span });
            }
        }
    }
    out
}

fn jump_to(plan: &Plan, from: usize, target: usize, span: Span) -> Goto {
    let name = plan.labels.get(&target).cloned().unwrap_or_default();
    Goto {
        search: if target > from { Search::Forward } else { Search::Backward },
        target: Target::Label(Label { name, span }),
        cond: None,
        missing_continues: false,
    }
}

fn lower_goto(
    ctx: &mut Ctx,
    g: Goto,
    span: Span,
    node: usize,
    plan: &Plan,
    items: &mut Vec<Item>,
    extra: &mut Vec<Stmt>,
) {
    match g.target {
        Target::Number(n) => match resolve(&plan.numbers, node, n.value) {
            Some(t) => {
                let mut j = jump_to(plan, node, t, n.span);
                j.cond = g.cond;
                items.push(Item { kind: ItemKind::Goto(Box::new(j)), span });
            }
            // No such block (reported): the jump alarms where FANUC's would.
            None => {
                let alarm = plain_block(no_target_jump(ctx, span), span);
                extra.push(match g.cond {
                    None => alarm,
                    Some(c) => if_stmt(c, vec![alarm], None, span),
                });
            }
        },
        Target::Computed(e) => {
            let mut distinct: BTreeSet<u32> = BTreeSet::new();
            distinct.extend(plan.numbers.iter().flatten().copied());
            let arms: Vec<CaseArm> = distinct
                .into_iter()
                .filter_map(|n| {
                    resolve(&plan.numbers, node, n)
                        .map(|t| CaseArm { value: int(i64::from(n), e.span), goto: jump_to(plan, node, t, e.span) })
                })
                .collect();
            let selector = func(Func::FanucRound, vec![e.clone()], e.span);
            // A program without N numbers has no arm: only the missing-target jump remains.
            let case = (!arms.is_empty())
                .then(|| Item { kind: ItemKind::Case(Box::new(Case { selector, arms, default: None })), span });
            let alarm_items = no_target_jump(ctx, span);
            match g.cond {
                None => {
                    // CASE stands in a block of its own (the FANUC block may hold NC words).
                    extra.extend(case.map(|c| plain_block(vec![c], span)));
                    extra.push(plain_block(alarm_items, span));
                }
                Some(c) => {
                    let mut body: Vec<Stmt> = case.into_iter().map(|c| plain_block(vec![c], span)).collect();
                    body.push(plain_block(alarm_items, span));
                    extra.push(if_stmt(c, body, None, span));
                }
            }
        }
        Target::Label(_) => items.push(Item { kind: ItemKind::Goto(Box::new(g)), span }),
    }
}

/// A jump to a label that does not exist, held in a STRING variable, so that Siemens
/// raises its own "jump target not found" (14080), the counterpart of FANUC's alarm 128
/// for a GOTO to a number no block has.
fn no_target_jump(ctx: &mut Ctx, span: Span) -> Vec<Item> {
    let plan = &mut ctx.progs[ctx.cur];
    if !plan.defs.iter().any(|(n, _)| n == NO_TARGET) {
        plan.defs.push((NO_TARGET.to_string(), DataType::String(16)));
    }
    vec![
        assign(named_ref(NO_TARGET, span), Expr::new(ExprKind::Str("NO_SUCH_BLOCK".into()), span), span),
        Item {
            kind: ItemKind::Goto(Box::new(Goto {
                search: Search::Forward,
                target: Target::Label(Label { name: NO_TARGET.into(), span }),
                cond: None,
                missing_continues: false,
            })),
            span,
        },
    ]
}
