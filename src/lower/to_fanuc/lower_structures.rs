//! Structured Siemens control flow → FANUC IF-GOTO, IF-THEN and WHILE-DOm.
//!
//! - `IF c … ELSE … ENDIF` → `IF [not c] GOTO else`, then-part, `GOTO end`, else-part. FANUC has
//!   no ELSE and no NOT: comparisons are inverted (EQ↔NE, GT↔LE, LT↔GE, exact complements also
//!   for vacant operands) and compound conditions follow De Morgan. An IF whose body is one
//!   assignment becomes `IF [c] THEN #i=…`.
//! - `WHILE c` → `WHILE [c] DOm … ENDm` with m the DO nesting depth (1..3, reused); deeper
//!   loops, and loops whose condition is compound, become label/IF-GOTO loops.
//! - `LOOP` → `DOm … ENDm` (or a GOTO loop); `FOR v=a TO b` → `v=a`, a loop on `v LE b` ending
//!   with `v=v+1` (b was evaluated once by the expression pass); `REPEAT … UNTIL c` → a label
//!   and `IF [not c] GOTO top`; `CASE` → a chain of `IF [sel EQ v] GOTO`.
//! - Compound AND/OR conditions → nested IF-GOTO, or `[[a] AND [b]]` when the target accepts it.

use super::*;
use crate::dialect::fanuc::emit::cond_depth;

const MAX_DO: u32 = 3;

pub fn run(ctx: &mut Ctx, prog: &mut Program) {
    let body = std::mem::take(&mut prog.body);
    prog.body = S { ctx }.body(body, 0);
}

struct S<'a> {
    ctx: &'a mut Ctx,
}

/// Where a jump goes, with its Siemens search semantics (resolved by the label pass).
#[derive(Clone)]
struct Tgt {
    target: Target,
    search: Search,
    missing_continues: bool,
}

impl Tgt {
    fn label(l: &Label) -> Tgt {
        Tgt { target: Target::Label(l.clone()), search: Search::ForwardThenBackward, missing_continues: false }
    }
}

fn push(out: &mut Vec<Stmt>, meta: &mut Option<BlockMeta>, items: Vec<Item>, span: Span) {
    match meta.take() {
        Some(m) => out.push(meta_stmt(m, items)),
        None => out.push(block_stmt(items, span)),
    }
}

/// Pushes the construct's leftover head meta (when nothing carried it) as an empty block.
fn flush(out: &mut Vec<Stmt>, meta: Option<BlockMeta>) {
    if let Some(m) = meta {
        if meta_is_marked(&m) {
            out.push(meta_stmt(m, vec![]));
        }
    }
}

fn invert(op: CmpOp) -> CmpOp {
    match op {
        CmpOp::Eq => CmpOp::Ne,
        CmpOp::Ne => CmpOp::Eq,
        CmpOp::Gt => CmpOp::Le,
        CmpOp::Le => CmpOp::Gt,
        CmpOp::Lt => CmpOp::Ge,
        CmpOp::Ge => CmpOp::Lt,
    }
}

/// The condition with NOT pushed to the comparisons (De Morgan); `None` when it holds an XOR.
fn nnf(e: &Expr, neg: bool) -> Option<Expr> {
    match &e.kind {
        ExprKind::Unary(UnOp::Not, a) => nnf(a, !neg),
        ExprKind::Cmp(op, tol, a, b) => {
            let op = if neg { invert(*op) } else { *op };
            Some(Expr::new(ExprKind::Cmp(op, *tol, a.clone(), b.clone()), e.span))
        }
        ExprKind::Binary(op @ (BinOp::And | BinOp::Or), a, b) => {
            let op = match (op, neg) {
                (BinOp::And, false) | (BinOp::Or, true) => BinOp::And,
                _ => BinOp::Or,
            };
            Some(Expr::new(ExprKind::Binary(op, Box::new(nnf(a, neg)?), Box::new(nnf(b, neg)?)), e.span))
        }
        _ => None,
    }
}

impl S<'_> {
    fn body(&mut self, body: Vec<Stmt>, depth: u32) -> Vec<Stmt> {
        let mut out = Vec::with_capacity(body.len());
        for s in body {
            self.stmt(s, depth, &mut out);
        }
        out
    }

    /// A condition FANUC can test in one `IF [..]` or `WHILE [..]`: one comparison, or a
    /// compound one when the target accepts it; `None` when it needs several jumps.
    fn single(&self, c: &Expr, neg: bool) -> Option<Expr> {
        let n = nnf(c, neg)?;
        let ok = match &n.kind {
            ExprKind::Cmp(..) => true,
            _ => self.ctx.compound_conditions,
        };
        (ok && cond_depth(&n) <= 5).then_some(n)
    }

    fn stmt(&mut self, s: Stmt, depth: u32, out: &mut Vec<Stmt>) {
        let span = s.span;
        match s.kind {
            StmtKind::Block(b) => self.block(b, out),
            StmtKind::If(i) => {
                let i = *i;
                if i.else_part.is_none() {
                    if let Some(it) = self.if_then(&i) {
                        out.push(meta_stmt(i.head, vec![it]));
                        flush(out, Some(i.end));
                        return;
                    }
                }
                let end = self.ctx.label(i.end.span);
                let mut head = Some(i.head);
                match i.else_part {
                    None => {
                        self.jump(&i.cond, true, &Tgt::label(&end), &mut head, out);
                        flush(out, head);
                        out.extend(self.body(i.then_body, depth));
                    }
                    Some(e) => {
                        let els = self.ctx.label(e.head.span);
                        self.jump(&i.cond, true, &Tgt::label(&els), &mut head, out);
                        flush(out, head);
                        out.extend(self.body(i.then_body, depth));
                        out.push(block_stmt(vec![goto_item(&end, None, e.head.span)], e.head.span));
                        let mut em = e.head;
                        em.label = Some(els);
                        out.push(meta_stmt(em, vec![]));
                        out.extend(self.body(e.body, depth));
                    }
                }
                let mut em = i.end;
                em.label = Some(end);
                out.push(meta_stmt(em, vec![]));
            }
            StmtKind::While(w) => {
                let w = *w;
                self.looping(w.head, Some(w.cond), w.body, vec![], w.end, depth, out, span);
            }
            StmtKind::Loop(l) => {
                let l = *l;
                self.looping(l.head, None, l.body, vec![], l.end, depth, out, span);
            }
            StmtKind::For(f) => {
                let f = *f;
                let v = var_expr(&f.var);
                out.push(meta_stmt(f.head, vec![assign_item(&f.var, f.from, f.var.span)]));
                let cond = cmp(CmpOp::Le, v.clone(), f.to);
                let inc = meta_stmt(f.end, vec![assign_item(&f.var, bin(BinOp::Add, v, num(1.0, span)), span)]);
                let head = BlockMeta { span, ..BlockMeta::default() };
                let end = BlockMeta { span, ..BlockMeta::default() };
                self.looping(head, Some(cond), f.body, vec![inc], end, depth, out, span);
            }
            StmtKind::Repeat(r) => {
                let r = *r;
                let top = self.ctx.label(r.head.span);
                let mut hm = r.head;
                if hm.label.is_some() {
                    out.push(meta_stmt(hm, vec![]));
                    out.push(label_stmt(top.clone()));
                } else {
                    hm.label = Some(top.clone());
                    out.push(meta_stmt(hm, vec![]));
                }
                out.extend(self.body(r.body, depth));
                let mut em = Some(r.end);
                self.jump(&r.until, true, &Tgt::label(&top), &mut em, out);
                flush(out, em);
            }
            StmtKind::Do(mut d) => {
                d.body = self.body(std::mem::take(&mut d.body), depth + 1);
                out.push(Stmt { kind: StmtKind::Do(d), span });
            }
        }
    }

    /// `IF c` + one assignment → `IF [c] THEN assignment`.
    fn if_then(&self, i: &IfStmt) -> Option<Item> {
        let [Stmt { kind: StmtKind::Block(b), .. }] = i.then_body.as_slice() else { return None };
        if b.meta.number.is_some() || b.meta.label.is_some() || b.meta.skip.is_some() || !b.meta.comments.is_empty() {
            return None;
        }
        let [it @ Item { kind: ItemKind::Assign { .. }, .. }] = b.items.as_slice() else { return None };
        let cond = self.single(&i.cond, false)?;
        Some(item(ItemKind::IfThen { cond, then: Box::new(it.clone()) }, i.head.span))
    }

    #[allow(clippy::too_many_arguments)]
    fn looping(
        &mut self,
        mut head: BlockMeta,
        cond: Option<Expr>,
        body: Vec<Stmt>,
        tail: Vec<Stmt>,
        end: BlockMeta,
        depth: u32,
        out: &mut Vec<Stmt>,
        span: Span,
    ) {
        let single = match &cond {
            None => Some(None),
            Some(c) => self.single(c, false).map(Some),
        };
        if let (true, Some(c)) = (depth < MAX_DO, single) {
            let id = (depth + 1) as u8;
            let mut body = self.body(body, depth + 1);
            body.extend(tail);
            let d = DoStmt { head, id, cond: c, body, end };
            out.push(Stmt { kind: StmtKind::Do(Box::new(d)), span });
            return;
        }
        // A label/GOTO loop: no DO level used.
        let top = self.ctx.label(head.span);
        let exit = self.ctx.label(end.span);
        if head.label.is_some() {
            out.push(meta_stmt(head, vec![]));
            out.push(label_stmt(top.clone()));
        } else {
            head.label = Some(top.clone());
            out.push(meta_stmt(head, vec![]));
        }
        if let Some(c) = &cond {
            self.jump(c, true, &Tgt::label(&exit), &mut None, out);
        }
        out.extend(self.body(body, depth));
        out.extend(tail);
        let mut em = end;
        let back = goto_item(&top, None, em.span);
        let espan = em.span;
        let exit_meta = BlockMeta { span: espan, label: Some(exit), ..BlockMeta::default() };
        em.label = None;
        out.push(meta_stmt(em, vec![back]));
        out.push(meta_stmt(exit_meta, vec![]));
    }

    fn block(&mut self, mut b: Block, out: &mut Vec<Stmt>) {
        let span = b.meta.span;
        let cond_goto = matches!(b.items.as_slice(), [Item { kind: ItemKind::Goto(g), .. }]
            if g.cond.as_ref().is_some_and(|c| !matches!(c.kind, ExprKind::Cmp(..))));
        let case = matches!(b.items.as_slice(), [Item { kind: ItemKind::Case(_), .. }]);
        if !cond_goto && !case {
            out.push(Stmt { kind: StmtKind::Block(b), span });
            return;
        }
        let it = b.items.remove(0);
        let mut meta = Some(b.meta);
        match it.kind {
            ItemKind::Goto(g) => {
                let g = *g;
                let t = Tgt { target: g.target, search: g.search, missing_continues: g.missing_continues };
                if let Some(c) = &g.cond {
                    self.jump(c, false, &t, &mut meta, out);
                }
            }
            ItemKind::Case(c) => {
                let c = *c;
                for arm in c.arms {
                    let t = Tgt {
                        target: arm.goto.target,
                        search: arm.goto.search,
                        missing_continues: arm.goto.missing_continues,
                    };
                    let cond = cmp(CmpOp::Eq, c.selector.clone(), arm.value);
                    self.jump(&cond, false, &t, &mut meta, out);
                }
                if let Some(d) = c.default {
                    let g =
                        Goto { search: d.search, target: d.target, cond: None, missing_continues: d.missing_continues };
                    push(out, &mut meta, vec![item(ItemKind::Goto(Box::new(g)), span)], span);
                }
            }
            _ => {}
        }
        flush(out, meta);
    }

    /// Jumps to `t` when `c` holds (`neg`: when it does not hold).
    fn jump(&mut self, c: &Expr, neg: bool, t: &Tgt, meta: &mut Option<BlockMeta>, out: &mut Vec<Stmt>) {
        let span = c.span;
        if let Some(single) = self.single(c, neg) {
            let g = Goto {
                search: t.search,
                target: t.target.clone(),
                cond: Some(single),
                missing_continues: t.missing_continues,
            };
            push(out, meta, vec![item(ItemKind::Goto(Box::new(g)), span)], span);
            return;
        }
        match &c.kind {
            ExprKind::Unary(UnOp::Not, a) => self.jump(a, !neg, t, meta, out),
            ExprKind::Binary(op @ (BinOp::And | BinOp::Or), a, b) => {
                // "all of" (AND, or NOT OR) needs a skip label; "any of" jumps twice.
                let all = (*op == BinOp::And) != neg;
                let (na, nb) = (neg, neg);
                if all {
                    let skip = self.ctx.label(span);
                    self.jump(a, !na, &Tgt::label(&skip), meta, out);
                    self.jump(b, nb, t, meta, out);
                    out.push(label_stmt(skip));
                } else {
                    self.jump(a, na, t, meta, out);
                    self.jump(b, nb, t, meta, out);
                }
            }
            ExprKind::Binary(BinOp::Xor, a, b) => {
                let a_true = self.ctx.label(span);
                let done = self.ctx.label(span);
                self.jump(a, false, &Tgt::label(&a_true), meta, out);
                self.jump(b, neg, t, meta, out);
                push(out, meta, vec![goto_item(&done, None, span)], span);
                out.push(label_stmt(a_true));
                self.jump(b, !neg, t, meta, out);
                out.push(label_stmt(done));
            }
            _ => {
                // Not a condition (the expression pass makes every leaf a comparison).
                let c = cmp(if neg { CmpOp::Eq } else { CmpOp::Ne }, c.clone(), num(0.0, span));
                self.jump(&c, false, t, meta, out);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::build::*;
    use super::*;

    fn lower(body: Vec<Stmt>, compound: bool) -> Vec<Stmt> {
        let mut ctx = Ctx::new(0, UnsupportedPolicy::Error);
        ctx.compound_conditions = compound;
        let mut prog = program(body);
        run(&mut ctx, &mut prog);
        prog.body
    }

    #[test]
    fn if_else_becomes_inverted_goto() {
        let i = if_stmt(
            cmp(CmpOp::Gt, r(1), n(0.0)),
            vec![block(vec![word_item(b'X', n(1.0))])],
            Some(vec![block(vec![word_item(b'X', n(2.0))])]),
        );
        let out = lower(vec![i], false);
        let shapes: Vec<String> = out.iter().map(shape).collect();
        assert_eq!(shapes, ["- goto", "- word", "- goto", "L - ", "- word", "L - "]);
        assert!(matches!(&out[0].kind, StmtKind::Block(b) if matches!(&b.items[0].kind,
            ItemKind::Goto(g) if matches!(g.cond.as_ref().map(|c| &c.kind), Some(ExprKind::Cmp(CmpOp::Le, ..))))));
    }

    #[test]
    fn single_assignment_if_becomes_if_then() {
        let i = if_stmt(cmp(CmpOp::Eq, r(1), n(1.0)), vec![block(vec![assign(rv(2), n(3.0))])], None);
        let out = lower(vec![i], false);
        assert_eq!(out.iter().map(shape).collect::<Vec<_>>(), ["- ifthen"]);
    }

    #[test]
    fn compound_and_nests_gotos_unless_the_profile_allows_it() {
        let c = bin(BinOp::And, cmp(CmpOp::Gt, r(1), n(0.0)), cmp(CmpOp::Lt, r(2), n(5.0)));
        let mk = || if_stmt(c.clone(), vec![block(vec![word_item(b'X', n(1.0))])], None);
        assert_eq!(
            lower(vec![mk()], false).iter().map(shape).collect::<Vec<_>>(),
            ["- goto", "- goto", "- word", "L - "]
        );
        assert_eq!(lower(vec![mk()], true).iter().map(shape).collect::<Vec<_>>(), ["- goto", "- word", "L - "]);
    }

    #[test]
    fn fourth_nested_while_becomes_a_goto_loop() {
        let mut inner = block(vec![word_item(b'X', n(1.0))]);
        for _ in 0..4 {
            inner = while_stmt(cmp(CmpOp::Lt, r(1), n(5.0)), vec![inner]);
        }
        let out = lower(vec![inner], false);
        let mut ids = Vec::new();
        crate::ir::visit::walk_stmts(&out, &mut |s| {
            if let StmtKind::Do(d) = &s.kind {
                ids.push(d.id);
            }
        });
        assert_eq!(ids, [1, 2, 3]);
    }

    #[test]
    fn repeat_jumps_back_while_the_condition_fails() {
        let rp = Stmt {
            kind: StmtKind::Repeat(Box::new(RepeatStmt {
                head: BlockMeta::default(),
                body: vec![block(vec![word_item(b'X', n(1.0))])],
                end: BlockMeta::default(),
                until: cmp(CmpOp::Ge, r(1), n(3.0)),
            })),
            span: sp(),
        };
        let out = lower(vec![rp], false);
        assert_eq!(out.iter().map(shape).collect::<Vec<_>>(), ["L - ", "- word", "- goto"]);
    }
}
