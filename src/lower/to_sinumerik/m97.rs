//! Haas `M97 Pn Lm` (the local subprogram from block Nn of the same program to its M99, m
//! times, sharing the caller's variables) → Siemens program-section repetition.
//!
//! The blocks stay where they are. The section gets a start label block before Nn
//! (`LSUB_n:`) and an end label block after its M99 block (`LSUB_E1:`), whose M99 is dropped.
//! The call becomes `GOTOF LSUB_CALL1` followed by a return label block `LSUB_RET1:`; at the
//! end of the program a trampoline per call runs `REPEAT LSUB_n LSUB_E1 P=m` and jumps back
//! with `GOTOB LSUB_RET1`. The trampoline stands after every section, so REPEAT finds both
//! labels searching toward the program start (the one search direction docs/semantics.md can
//! cite); with unique labels every search finds the same blocks. A computed count `L#5` is
//! guarded: below one pass (rounded) the trampoline jumps back at once, as the Haas run does.
//!
//! The section must be plain straight flow (structures allowed, no jump, end or call of
//! another local subprogram inside), end in an unconditional, unskippable M99, and be reached
//! only through M97 (the block before Nn ends the program or a section; no GOTO into it), so
//! dropping its M99 changes nothing else. Every other form is refused with NC580–NC584.

use super::modal_flow::Local;
use super::*;

/// What [`prepare`] found: the spans the rewrite after the jump pass places labels at.
#[derive(Default)]
pub struct Plan {
    /// Section start block spans with the label in front of them.
    starts: Vec<(Span, String)>,
    /// M99 block spans with the end label after them.
    ends: Vec<(Span, String)>,
    /// M97 item span → (call number, start label, end label, count).
    calls: Vec<(Span, String, String, Count)>,
    /// The same calls for the modal scan, which follows them into their sections.
    pub locals: Vec<Local>,
}

/// What the checks of [`prepare`] found, before anything is reported or rewritten.
struct Checked {
    plan: Plan,
    /// Top-level indices of the M99 blocks whose M99 is dropped.
    drop_m99: BTreeSet<usize>,
    /// (code, M97 span, what, hint) of each call refused.
    refused: Vec<(&'static str, Span, String, &'static str)>,
}

/// The `M97` calls of `body` that [`prepare`] translates, as the modal scan follows them
/// (for the analyses of a job made on the programs as read).
pub fn locals(body: &[Stmt]) -> Vec<Local> {
    check(body).map(|c| c.plan.locals).unwrap_or_default()
}

/// The start of a top-level block's span (as the modal scan numbers blocks).
fn block_lo(s: &Stmt) -> u32 {
    match &s.kind {
        StmtKind::Block(b) => b.meta.span.lo,
        _ => s.span.lo,
    }
}

#[derive(Clone)]
enum Count {
    Fixed(u64),
    Computed(Expr),
}

/// One local subprogram: top-level indices of its first block and of its M99 block.
struct Section {
    start: usize,
    end: usize,
}

fn number_of(s: &Stmt) -> Option<u32> {
    match &s.kind {
        StmtKind::Block(b) => b.meta.number.as_ref().map(|n| n.value),
        _ => None,
    }
}

/// Every N number of the body (loop heads and ends included), with repeats.
fn all_numbers(body: &[Stmt], out: &mut Vec<u32>) {
    for s in body {
        match &s.kind {
            StmtKind::Block(b) => out.extend(b.meta.number.as_ref().map(|n| n.value)),
            StmtKind::Do(d) => {
                out.extend(d.head.number.as_ref().map(|n| n.value));
                all_numbers(&d.body, out);
                out.extend(d.end.number.as_ref().map(|n| n.value));
            }
            other => {
                for b in crate::ir::visit::child_bodies(other) {
                    all_numbers(b, out);
                }
            }
        }
    }
}

/// Every item of the body, nested ones (`IF … THEN`) included, with whether it stands in a
/// top-level block.
fn all_items<'a>(body: &'a [Stmt], top: bool, out: &mut Vec<(&'a Item, bool)>) {
    for s in body {
        match &s.kind {
            StmtKind::Block(b) => {
                for it in &b.items {
                    out.push((it, top));
                    if let ItemKind::IfThen { then, .. } = &it.kind {
                        out.push((then, false));
                    }
                }
            }
            other => {
                for b in crate::ir::visit::child_bodies(other) {
                    all_items(b, false, out);
                }
            }
        }
    }
}

fn is_m97(it: &Item) -> bool {
    matches!(&it.kind, ItemKind::Call(c) if c.kind == CallKind::M97)
}

/// Why statement `s` (inside a section) leaves straight flow, if it does.
fn leaves(s: &Stmt) -> Option<(&'static str, Span)> {
    let mut items = Vec::new();
    all_items(std::slice::from_ref(s), false, &mut items);
    items.into_iter().find_map(|(it, _)| match &it.kind {
        ItemKind::Goto(_) => Some(("a jump (GOTO)", it.span)),
        ItemKind::Case(_) => Some(("a jump (GOTO)", it.span)),
        ItemKind::Return { to: Some(_) } => Some(("`M99 P<n>`", it.span)),
        ItemKind::Return { to: None } => Some(("an M99 that is not the end of a top-level block", it.span)),
        ItemKind::End { .. } => Some(("a program end (M30/M2)", it.span)),
        ItemKind::Call(c) if c.kind == CallKind::M97 => Some(("a nested `M97`", it.span)),
        _ => None,
    })
}

/// Whether a top-level statement ends straight flow unconditionally (M30, M2, M99).
fn terminal(s: &Stmt) -> bool {
    match &s.kind {
        StmtKind::Block(b) => {
            b.meta.skip.is_none()
                && b.items.iter().any(|it| matches!(it.kind, ItemKind::End { .. } | ItemKind::Return { to: None }))
        }
        _ => false,
    }
}

/// The M99 block that ends the section from top-level index `start`, or why there is none.
fn section_end(body: &[Stmt], start: usize) -> Result<usize, (&'static str, Span)> {
    for (k, s) in body.iter().enumerate().skip(start) {
        if let StmtKind::Block(b) = &s.kind {
            if let Some(pos) = b.items.iter().position(|it| matches!(it.kind, ItemKind::Return { to: None })) {
                if b.meta.skip.is_some() {
                    return Err(("a skippable (`/`) M99 (skipped, the Haas control runs on past it)", b.meta.span));
                }
                if pos + 1 != b.items.len() {
                    return Err(("words after the M99 in its block", b.items[pos + 1].span));
                }
                let rest = Block { meta: b.meta.clone(), items: b.items[..pos].to_vec() };
                let rest = Stmt { kind: StmtKind::Block(rest), span: s.span };
                if let Some(why) = leaves(&rest) {
                    return Err(why);
                }
                return Ok(k);
            }
        }
        if let Some(why) = leaves(s) {
            return Err(why);
        }
    }
    Err(("no M99 before the end of the program", body.last().map_or(Span::default(), |s| s.span)))
}

/// Checks every M97 of the program and drops the M99 of each section it can translate;
/// `None` when the program has no M97. Refused calls are reported and taken out.
pub fn prepare(ctx: &mut Ctx, mut body: Vec<Stmt>) -> (Vec<Stmt>, Option<Plan>) {
    let Some(Checked { plan, drop_m99, refused }) = check(&body) else { return (body, None) };
    for (k, s) in body.iter_mut().enumerate() {
        if let (true, StmtKind::Block(b)) = (drop_m99.contains(&k), &mut s.kind) {
            b.items.retain(|it| !matches!(it.kind, ItemKind::Return { to: None }));
        }
    }
    // Refused calls: the diagnostic, and the call taken out (a marked line under `warn`).
    let spans: Vec<Span> = refused.iter().map(|r| r.1).collect();
    let mut marks = Vec::new();
    for (code, span, what, hint) in refused {
        marks.push((span, ctx.unsupported(code, span, &what, hint)));
    }
    body = map_bodies(body, &mut |list| {
        let mut out = Vec::with_capacity(list.len());
        for mut s in list {
            if let StmtKind::Block(b) = &mut s.kind {
                let before = b.items.len();
                b.items.retain(|it| !spans.contains(&it.span));
                if b.items.len() != before {
                    for (sp, m) in &mut marks {
                        if s.span.lo <= sp.lo && sp.hi <= s.span.hi {
                            out.extend(m.take());
                        }
                    }
                }
            }
            out.push(s);
        }
        out
    });
    (body, Some(plan))
}

/// The checks of every M97 of the program; `None` when it has none.
fn check(body: &[Stmt]) -> Option<Checked> {
    let mut items = Vec::new();
    all_items(body, true, &mut items);
    let m97: Vec<Span> = items.iter().filter(|(it, _)| is_m97(it)).map(|(it, _)| it.span).collect();
    if m97.is_empty() {
        return None;
    }
    let mut numbers = Vec::new();
    all_numbers(body, &mut numbers);
    // Jumps that could land inside a section: by number (checked per section), or computed.
    let computed_jump = items.iter().find_map(|(it, _)| match &it.kind {
        ItemKind::Goto(g) if matches!(g.target, Target::Computed(_)) => Some(it.span),
        ItemKind::Return { to: Some(to) } if literal(to).is_none() => Some(it.span),
        _ => None,
    });
    let jump_targets: Vec<(u32, Span)> = items
        .iter()
        .filter_map(|(it, _)| match &it.kind {
            ItemKind::Goto(g) => match &g.target {
                Target::Number(n) => Some((n.value, it.span)),
                _ => None,
            },
            ItemKind::Return { to: Some(to) } => literal(to).map(|v| (v as u32, it.span)),
            _ => None,
        })
        .collect();
    let mut sections: BTreeMap<u32, Result<Section, (&'static str, &'static str, Span)>> = BTreeMap::new();
    let mut plan = Plan::default();
    let mut drop_m99 = BTreeSet::new();
    let mut refused: Vec<(&'static str, Span, String, &'static str)> = Vec::new();
    let mut calls = Vec::new();
    for (i, s) in body.iter().enumerate() {
        if let StmtKind::Block(b) = &s.kind {
            for it in &b.items {
                if let ItemKind::Call(c) = &it.kind {
                    if c.kind == CallKind::M97 {
                        calls.push((i, it.span, (**c).clone(), b.items.len()));
                    }
                }
            }
        }
    }
    // M97 calls not in a top-level block (inside a loop, IF, or IF … THEN).
    for span in &m97 {
        if !calls.iter().any(|c| c.1 == *span) {
            refused.push((
                "NC581",
                *span,
                "Haas `M97` inside a loop, IF structure or `IF … THEN`".into(),
                "the translation returns from the section by a jump back to the call, which Siemens cannot make into \
                 a structure; put the M97 in a block of its own outside the structure",
            ));
        }
    }
    for (i, span, c, n_items) in calls {
        let CallTarget::Number(n) = c.target else {
            refused.push((
                "NC580",
                span,
                "Haas `M97 P#…` (a computed local subprogram)".into(),
                "REPEAT names its section by labels written in the program; write the block number",
            ));
            continue;
        };
        if n_items != 1 {
            refused.push((
                "NC581",
                span,
                "Haas `M97` in a block with other words".into(),
                "write the other words in a block of their own before the M97",
            ));
            continue;
        }
        let count = match &c.repeat {
            None => Count::Fixed(1),
            Some(e) => {
                match literal(e) {
                    Some(v) if v >= 1.0 && v.fract() == 0.0 && v <= 9999.0 => Count::Fixed(v as u64),
                    Some(_) => {
                        refused.push((
                        "NC584",
                        span,
                        format!("Haas `M97 P{n}` with the count `L` {} (not a whole number of passes from 1)", e_text(e)),
                        "a local subprogram run zero times does nothing: remove the block; otherwise write L1 to L9999",
                    ));
                        continue;
                    }
                    None => Count::Computed(e.clone()),
                }
            }
        };
        let section = sections.entry(n).or_insert_with(|| {
            let hits = numbers.iter().filter(|&&m| m == n).count();
            let Some(start) = body.iter().position(|s| number_of(s) == Some(n)) else {
                let why = if hits == 0 { "no block N{n} in this program" } else { "block N{n} inside a loop or IF" };
                return Err(("NC580", why, span));
            };
            if hits > 1 {
                return Err(("NC580", "more than one block N{n} in this program", body[start].span));
            }
            if start == 0 || !terminal(&body[start - 1]) {
                return Err((
                    "NC583",
                    "the blocks before N{n} run on into it (the block before N{n} is no unconditional M30, M2 or M99)",
                    body[start].span,
                ));
            }
            let end = section_end(body, start).map_err(|(why, sp)| ("NC582", why, sp))?;
            let inside: BTreeSet<u32> = body[start..=end].iter().filter_map(number_of).collect();
            if let Some((_, sp)) = jump_targets.iter().find(|(m, _)| inside.contains(m)) {
                return Err(("NC583", "a jump elsewhere in the program lands inside it", *sp));
            }
            if let Some(sp) = computed_jump {
                return Err(("NC583", "a computed jump elsewhere in the program may land inside it", sp));
            }
            Ok(Section { start, end })
        });
        let (start, end) = match section {
            Ok(s) => (s.start, s.end),
            Err((code, why, sp)) => {
                let why = why.replace("{n}", &n.to_string());
                let what = format!("Haas `M97 P{n}` whose local subprogram is not plain: {why}");
                let _ = sp;
                refused.push((
                    code,
                    span,
                    what,
                    "Siemens repeats a program section by REPEAT between two labels; the section must run from N<n> \
                     straight to one M99, reached only through M97",
                ));
                continue;
            }
        };
        // A call from inside a section would nest a repetition in the section it jumps out of.
        let nested = sections.values().any(|s| matches!(s, Ok(s) if (s.start..=s.end).contains(&i)));
        if nested {
            refused.push((
                "NC581",
                span,
                format!("Haas `M97 P{n}` inside a local subprogram"),
                "the translation jumps out of the running section to repeat another one; call the inner local \
                 subprogram from the main program or make it an M98 subprogram",
            ));
            continue;
        }
        let start_label = format!("LSUB_{n}");
        if !plan.starts.iter().any(|(_, l)| *l == start_label) {
            plan.starts.push((body[start].span, start_label.clone()));
        }
        let end_span = body[end].span;
        let end_label = match plan.ends.iter().find(|(s, _)| *s == end_span) {
            Some((_, l)) => l.clone(),
            None => {
                let l = format!("LSUB_E{}", plan.ends.len() + 1);
                plan.ends.push((end_span, l.clone()));
                l
            }
        };
        drop_m99.insert(end);
        let passes = match &count {
            Count::Fixed(m) => Some(*m),
            Count::Computed(_) => None,
        };
        plan.locals.push(Local {
            call: span.lo,
            start: block_lo(&body[start]),
            end: block_lo(&body[end]),
            count: passes,
        });
        plan.calls.push((span, start_label, end_label, count));
    }
    // A section checked after a call inside it was accepted: refuse that call now.
    let accepted: Vec<Span> = plan.calls.iter().map(|c| c.0).collect();
    for span in accepted {
        let i = body.iter().position(|s| s.span.lo <= span.lo && span.hi <= s.span.hi);
        if let Some(i) = i {
            if sections.values().any(|s| matches!(s, Ok(s) if (s.start..=s.end).contains(&i))) {
                refused.push((
                    "NC581",
                    span,
                    "Haas `M97` inside a local subprogram".into(),
                    "call the inner local subprogram from the main program or make it an M98 subprogram",
                ));
                plan.calls.retain(|c| c.0 != span);
                plan.locals.retain(|l| l.call != span.lo);
            }
        }
    }
    Some(Checked { plan, drop_m99, refused })
}

fn e_text(e: &Expr) -> String {
    match literal(e) {
        Some(v) => format!("{v}"),
        None => "computed".into(),
    }
}

/// After the jump pass: the labels, the calls as jumps to their trampolines, and the
/// trampolines at the end of the program.
pub fn lower(body: Vec<Stmt>, plan: &Plan) -> Vec<Stmt> {
    let mut out = Vec::with_capacity(body.len() + 2 * plan.calls.len());
    let mut tramps = Vec::new();
    // An earlier pass may have split a block into statements with its span: the start label
    // goes before the first of them, the end label after the last.
    let first: BTreeMap<usize, &str> = plan
        .starts
        .iter()
        .filter_map(|(sp, l)| body.iter().position(|s| s.span == *sp).map(|i| (i, l.as_str())))
        .collect();
    let last: BTreeMap<usize, &str> = plan
        .ends
        .iter()
        .filter_map(|(sp, l)| body.iter().rposition(|s| s.span == *sp).map(|i| (i, l.as_str())))
        .collect();
    for (k, mut s) in body.into_iter().enumerate() {
        if let Some(l) = first.get(&k) {
            out.push(label_stmt(l, s.span));
        }
        let end = last.get(&k).map(|l| l.to_string());
        let mut ret = None;
        if let StmtKind::Block(b) = &mut s.kind {
            for it in &mut b.items {
                let Some(i) = plan.calls.iter().position(|c| c.0 == it.span && is_m97(it)) else { continue };
                let (span, start, end_l, count) = &plan.calls[i];
                let span = *span;
                let call = format!("LSUB_CALL{}", i + 1);
                let back = format!("LSUB_RET{}", i + 1);
                it.kind = ItemKind::Goto(Box::new(jump(Search::Forward, &call, None, span)));
                ret = Some(label_stmt(&back, span));
                tramps.push(label_stmt(&call, span));
                let p = match count {
                    Count::Fixed(n) => int(*n as i64, span),
                    Count::Computed(e) => {
                        // Haas rounds the count and runs no pass below one.
                        let low = Expr::new(
                            ExprKind::Cmp(CmpOp::Lt, Tolerance::Exact, Box::new(e.clone()), Box::new(num(0.5, span))),
                            span,
                        );
                        let g = jump(Search::Backward, &back, Some(low), span);
                        tramps.push(plain_block(vec![Item { kind: ItemKind::Goto(Box::new(g)), span }], span));
                        func(Func::FanucRound, vec![e.clone()], span)
                    }
                };
                let rep = RepeatSection {
                    start: Label { name: start.clone(), span },
                    end: Some(Label { name: end_l.clone(), span }),
                    count: Some(p),
                    single: false,
                };
                tramps.push(plain_block(vec![Item { kind: ItemKind::RepeatSection(Box::new(rep)), span }], span));
                let g = jump(Search::Backward, &back, None, span);
                tramps.push(plain_block(vec![Item { kind: ItemKind::Goto(Box::new(g)), span }], span));
            }
        }
        let span = s.span;
        out.push(s);
        out.extend(ret);
        if let Some(l) = end {
            out.push(label_stmt(&l, span));
        }
    }
    out.extend(tramps);
    out
}

fn jump(search: Search, label: &str, cond: Option<Expr>, span: Span) -> Goto {
    Goto { search, target: Target::Label(Label { name: label.to_string(), span }), cond, missing_continues: false }
}
