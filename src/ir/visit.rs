//! Walking the IR: the span-nesting check every corpus file must pass, and helpers to
//! visit statements and expressions in source order.

use super::*;

/// Calls `f` on every statement of `body`, depth first, in source order.
pub fn walk_stmts<'a>(body: &'a [Stmt], f: &mut dyn FnMut(&'a Stmt)) {
    for s in body {
        f(s);
        for child in child_bodies(&s.kind) {
            walk_stmts(child, f);
        }
    }
}

/// The nested statement lists of a structured statement.
pub fn child_bodies(kind: &StmtKind) -> Vec<&[Stmt]> {
    match kind {
        StmtKind::Block(_) => vec![],
        StmtKind::If(i) => {
            let mut v = vec![i.then_body.as_slice()];
            if let Some(e) = &i.else_part {
                v.push(e.body.as_slice());
            }
            v
        }
        StmtKind::While(w) => vec![w.body.as_slice()],
        StmtKind::Loop(l) => vec![l.body.as_slice()],
        StmtKind::For(f) => vec![f.body.as_slice()],
        StmtKind::Repeat(r) => vec![r.body.as_slice()],
        StmtKind::Do(d) => vec![d.body.as_slice()],
    }
}

/// [`child_bodies`], to change them.
pub fn child_bodies_mut(kind: &mut StmtKind) -> Vec<&mut Vec<Stmt>> {
    match kind {
        StmtKind::Block(_) => vec![],
        StmtKind::If(i) => {
            let IfStmt { then_body, else_part, .. } = &mut **i;
            let mut v = vec![then_body];
            if let Some(e) = else_part {
                v.push(&mut e.body);
            }
            v
        }
        StmtKind::While(w) => vec![&mut w.body],
        StmtKind::Loop(l) => vec![&mut l.body],
        StmtKind::For(f) => vec![&mut f.body],
        StmtKind::Repeat(r) => vec![&mut r.body],
        StmtKind::Do(d) => vec![&mut d.body],
    }
}

/// The block metadata (head, else, end) of a statement, in source order.
pub fn metas(kind: &StmtKind) -> Vec<&BlockMeta> {
    match kind {
        StmtKind::Block(b) => vec![&b.meta],
        StmtKind::If(i) => {
            let mut v = vec![&i.head];
            if let Some(e) = &i.else_part {
                v.push(&e.head);
            }
            v.push(&i.end);
            v
        }
        StmtKind::While(w) => vec![&w.head, &w.end],
        StmtKind::Loop(l) => vec![&l.head, &l.end],
        StmtKind::For(f) => vec![&f.head, &f.end],
        StmtKind::Repeat(r) => vec![&r.head, &r.end],
        StmtKind::Do(d) => vec![&d.head, &d.end],
    }
}

/// Expressions written directly in an item (not those of nested items).
pub fn item_exprs(item: &Item) -> Vec<&Expr> {
    fn word(w: &Word) -> &Expr {
        match &w.value {
            WordValue::Expr(e) | WordValue::Ac(e) | WordValue::Ic(e) | WordValue::Rotary(_, e) => e,
        }
    }
    fn goto<'a>(g: &'a Goto, v: &mut Vec<&'a Expr>) {
        if let Some(c) = &g.cond {
            v.push(c);
        }
        if let Target::Computed(e) = &g.target {
            v.push(e);
        }
    }
    let mut v: Vec<&Expr> = Vec::new();
    match &item.kind {
        ItemKind::Assign { target, value } => {
            v.extend(target.children());
            v.push(value);
        }
        ItemKind::Word(w) => v.push(word(w)),
        ItemKind::Goto(g) => goto(g, &mut v),
        ItemKind::IfThen { cond, .. } | ItemKind::IfBlock { cond, .. } => v.push(cond),
        ItemKind::SyncAction(a) => {
            v.extend(a.id.iter().map(|(_, e)| e));
            v.extend(a.trigger.iter().map(|(_, e)| e));
        }
        ItemKind::Case(c) => {
            v.push(&c.selector);
            for a in &c.arms {
                v.push(&a.value);
                goto(&a.goto, &mut v);
            }
            if let Some(d) = &c.default {
                goto(d, &mut v);
            }
        }
        ItemKind::Call(c) => {
            if let CallTarget::Computed(e) = &c.target {
                v.push(e);
            }
            for a in &c.args {
                match a {
                    Arg::Value(e) | Arg::Letter { value: e, .. } => v.push(e),
                    Arg::Omitted(_) => {}
                }
            }
            if let Some(r) = &c.repeat {
                v.push(r);
            }
        }
        ItemKind::Return { to } => v.extend(to.iter()),
        ItemKind::Def(d) => {
            for var in &d.vars {
                match &var.init {
                    Some(Init::Value(e)) => v.push(e),
                    Some(Init::Set(list)) => v.extend(list.iter().flatten()),
                    Some(Init::Rep { value, count }) => {
                        v.push(value);
                        v.extend(count.iter());
                    }
                    None => {}
                }
            }
        }
        ItemKind::Alarm { number, .. } => v.push(number),
        ItemKind::Message { text } => v.extend(text.iter()),
        ItemKind::ParamWrite(p) => {
            v.push(&p.number);
            v.extend(p.axis.iter());
            v.extend(p.bit.iter());
            v.push(&p.value);
        }
        ItemKind::RepeatSection(r) => v.extend(r.count.iter()),
        ItemKind::Frame { words, .. } => v.extend(words.iter().map(word)),
        ItemKind::Print(p) => {
            if let Some(s) = &p.status {
                v.extend(s.children());
            }
            v.extend(p.file.iter());
            for part in &p.parts {
                match part {
                    PrintPart::Field { value: e, .. } | PrintPart::Str(e) => v.push(e),
                    PrintPart::Text(_) => {}
                }
            }
        }
        ItemKind::ModalCallOff
        | ItemKind::Extern(_)
        | ItemKind::Instruction { .. }
        | ItemKind::End { .. }
        | ItemKind::StopMessage { .. }
        | ItemKind::Stopre => {}
    }
    v
}

/// Checks that every span lies inside the file (`0..len`) and inside its parent's span.
/// Returns one line per violation; empty means the unit is well-formed.
pub fn check_spans(unit: &Unit, len: u32) -> Vec<String> {
    let mut problems = Vec::new();
    let file = Span::new(0, len);
    for p in &unit.programs {
        inside(&mut problems, file, p.span, "program");
        if let Some(h) = &p.head {
            meta_spans(&mut problems, p.span, h);
        }
        for prm in &p.params {
            inside(&mut problems, p.span, prm.span, "param");
        }
        body_spans(&mut problems, p.span, &p.body);
    }
    problems
}

fn inside(problems: &mut Vec<String>, parent: Span, child: Span, what: &str) {
    if child.lo > child.hi || !parent.contains(child) {
        problems.push(format!("{what} span {}..{} not inside {}..{}", child.lo, child.hi, parent.lo, parent.hi));
    }
}

fn meta_spans(problems: &mut Vec<String>, parent: Span, m: &BlockMeta) {
    inside(problems, parent, m.span, "block");
    if let Some(n) = &m.number {
        inside(problems, m.span, n.span, "number");
    }
    if let Some(l) = &m.label {
        inside(problems, m.span, l.span, "label");
    }
    for c in &m.comments {
        inside(problems, m.span, c.span, "comment");
    }
}

fn body_spans(problems: &mut Vec<String>, parent: Span, body: &[Stmt]) {
    for s in body {
        inside(problems, parent, s.span, "statement");
        for m in metas(&s.kind) {
            meta_spans(problems, s.span, m);
        }
        match &s.kind {
            StmtKind::Block(b) => {
                for it in &b.items {
                    item_spans(problems, b.meta.span, it);
                }
            }
            StmtKind::If(i) => expr_spans(problems, i.head.span, &i.cond),
            StmtKind::While(w) => expr_spans(problems, w.head.span, &w.cond),
            StmtKind::For(f) => {
                inside(problems, f.head.span, f.var.span, "variable");
                expr_spans(problems, f.head.span, &f.from);
                expr_spans(problems, f.head.span, &f.to);
            }
            StmtKind::Repeat(r) => expr_spans(problems, r.end.span, &r.until),
            StmtKind::Do(d) => {
                if let Some(c) = &d.cond {
                    expr_spans(problems, d.head.span, c);
                }
            }
            StmtKind::Loop(_) => {}
        }
        for child in child_bodies(&s.kind) {
            body_spans(problems, s.span, child);
        }
    }
}

fn item_spans(problems: &mut Vec<String>, parent: Span, it: &Item) {
    inside(problems, parent, it.span, "item");
    match &it.kind {
        ItemKind::Assign { target, .. } => inside(problems, it.span, target.span, "variable"),
        ItemKind::Word(w) => inside(problems, it.span, w.span, "word"),
        ItemKind::IfThen { then, .. } => item_spans(problems, it.span, then),
        ItemKind::IfBlock { items, .. } => items.iter().for_each(|i| item_spans(problems, it.span, i)),
        ItemKind::Def(d) => {
            for v in &d.vars {
                inside(problems, it.span, v.span, "declaration");
            }
        }
        ItemKind::Frame { words, .. } => {
            for w in words {
                inside(problems, it.span, w.span, "word");
            }
        }
        _ => {}
    }
    for e in item_exprs(it) {
        expr_spans(problems, it.span, e);
    }
}

fn expr_spans(problems: &mut Vec<String>, parent: Span, e: &Expr) {
    inside(problems, parent, e.span, "expression");
    if let ExprKind::Var(v) = &e.kind {
        inside(problems, e.span, v.span, "variable");
    }
    for c in e.children() {
        expr_spans(problems, e.span, c);
    }
}

/// Number of source blocks a unit holds (structure heads, ELSE and ends count as blocks).
/// The names a unit calls by a constant name (upper case, in walk order, repeats kept):
/// the subprograms a translation loads beside its input.
pub fn called_names(unit: &Unit) -> Vec<String> {
    let mut v = Vec::new();
    for p in &unit.programs {
        walk_stmts(&p.body, &mut |s| {
            if let StmtKind::Block(b) = &s.kind {
                for it in &b.items {
                    if let ItemKind::Call(c) = &it.kind {
                        if let CallTarget::Name(n) = &c.target {
                            v.push(n.to_ascii_uppercase());
                        }
                    }
                    // An interrupt routine is a subprogram the program names (`SETINT`).
                    if let ItemKind::Instruction { name } = &it.kind {
                        if let Some(Ok(super::interrupt::IntOp::Assign { routine: ProgName::Name(r), .. })) =
                            super::interrupt::op_of(name)
                        {
                            v.push(r);
                        }
                    }
                }
            }
        });
    }
    v
}

pub fn count_blocks(unit: &Unit) -> usize {
    let mut n = 0;
    for p in &unit.programs {
        n += usize::from(p.head.is_some());
        walk_stmts(&p.body, &mut |s| n += metas(&s.kind).len());
    }
    n
}
