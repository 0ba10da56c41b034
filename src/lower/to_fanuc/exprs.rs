//! Expressions → FANUC expressions with exactly the Siemens result.
//!
//! - `ROUNDUP(x)` (ceiling) → `u=FIX[x]`, `IF[x GT u] THEN u=u+1` (FANUC `FUP` rounds away from
//!   zero: FUP[-1.2] = -2, ROUNDUP(-1.2) = -1).
//! - `ATAN2(y,x)`, `ASIN(x)` with NAT=0 (FANUC ranges 0..360 and 270..90) → the FANUC function
//!   into a temporary, then `IF[t GT 180] THEN t=t-360` (90 for ASIN). `ACOS` has one range.
//! - `a MOD b` → `a-FIX[a/b]*b` (sign of the dividend), `a DIV b` → `FIX[a/b]`, `POT(x)` → `x*x`,
//!   `MINVAL/MAXVAL/BOUND` → a temporary and `IF … THEN`.
//! - `TRUNC` → `FIX`; `ROUND` stays integer rounding but never inside an address (FANUC rounds
//!   to the address increment there), so it goes through a temporary in words.
//! - Siemens logical `AND/OR/XOR/NOT` and comparisons used as values → `t=0`, `IF [c] t=1`
//!   (never FANUC bitwise operators); `B_AND/B_OR/B_XOR` → FANUC bitwise `AND/OR/XOR`.
//! - The relative-equality rule: a Siemens comparison of two values that are not both
//!   integral (and neither is the constant 0) compares the difference with
//!   `tol = 1e-12·max(|a|,|b|)`, written `[ABS[a]+ABS[b]+ABS[ABS[a]-ABS[b]]]*0.0000005*0.000001`
//!   (FANUC has no MAX and at most 8 digits per number), as the evaluator's Siemens rule:
//!   `a==b` → `ABS[a-b] LE tol`, `a<>b` → `ABS[a-b] GT tol`, `a<b` → `b-a GT tol`,
//!   `a<=b` → `a-b LE tol`, `a>b` → `a-b GT tol`, `a>=b` → `b-a LE tol`.
//! - Bracket depth: every expression is fitted into FANUC's 5 bracket levels by moving
//!   subexpressions into temporaries.
//!
//! Statements an expression needs run before the statement that uses it; a WHILE whose
//! condition needs some becomes a LOOP that tests at its top.

use super::*;
use crate::dialect::fanuc::emit::depth;

const MAX_DEPTH: i32 = 5;

pub fn run(ctx: &mut Ctx, prog: &mut Program, info: &ProgInfo) {
    let body = std::mem::take(&mut prog.body);
    prog.body = Lower { ctx, info }.body(body);
}

pub(crate) struct Lower<'a> {
    pub ctx: &'a mut Ctx,
    pub info: &'a ProgInfo,
}

/// `(ASIN(x)+360) MOD 360`, `(ATAN2(y,x)+360) MOD 360`: the FANUC → Sinumerik spelling of
/// FANUC's NAT=0 ranges (0..360, 270..90), which are FANUC's `ASIN[x]`, `ATAN[y]/[x]` as
/// they are (up to one rounding of the `+360`), so a round trip gives the FANUC function back
/// instead of wrapping the range correction once more.
fn fanuc_range(e: &Expr) -> Option<(Func, Vec<Expr>)> {
    let is_360 = |x: &Expr| matches!(&x.kind, ExprKind::Num(n) if n.value == 360.0);
    let ExprKind::Binary(BinOp::Mod, a, m) = &e.kind else { return None };
    let ExprKind::Binary(BinOp::Add, f, k) = &a.kind else { return None };
    if !is_360(m) || !is_360(k) {
        return None;
    }
    match &f.kind {
        ExprKind::Func(Func::Asin, args) if args.len() == 1 => Some((Func::FanucAsin, args.clone())),
        ExprKind::Func(Func::Atan2, args) if args.len() == 2 => Some((Func::FanucAtan2, args.clone())),
        _ => None,
    }
}

/// Pushes `pre` before `stmt`, moving the jump target of `meta` in front of them.
fn with_pre(out: &mut Vec<Stmt>, meta: &mut BlockMeta, mut pre: Vec<Stmt>) {
    if pre.is_empty() {
        return;
    }
    out.extend(take_target(meta));
    if let Some(k) = meta.skip {
        for s in &mut pre {
            if let StmtKind::Block(b) = &mut s.kind {
                b.meta.skip = Some(k);
            }
        }
    }
    out.extend(pre);
}

impl Lower<'_> {
    fn body(&mut self, body: Vec<Stmt>) -> Vec<Stmt> {
        let mut out = Vec::with_capacity(body.len());
        for s in body {
            self.stmt(s, &mut out);
        }
        out
    }

    fn stmt(&mut self, s: Stmt, out: &mut Vec<Stmt>) {
        let span = s.span;
        match s.kind {
            StmtKind::Block(mut b) => {
                let mut pre = Vec::new();
                let items = std::mem::take(&mut b.items);
                b.items = items.into_iter().map(|it| self.item(it, &mut pre)).collect();
                with_pre(out, &mut b.meta, pre);
                out.push(Stmt { kind: StmtKind::Block(b), span });
            }
            StmtKind::If(mut i) => {
                let mut pre = Vec::new();
                i.cond = self.cond(i.cond, &mut pre);
                i.then_body = self.body(std::mem::take(&mut i.then_body));
                if let Some(e) = &mut i.else_part {
                    e.body = self.body(std::mem::take(&mut e.body));
                }
                with_pre(out, &mut i.head, pre);
                out.push(Stmt { kind: StmtKind::If(i), span });
            }
            StmtKind::While(w) => {
                let w = *w;
                let mut pre = Vec::new();
                let cond = self.cond(w.cond, &mut pre);
                let mut body = self.body(w.body);
                if pre.is_empty() {
                    let w = WhileStmt { head: w.head, cond, body, end: w.end };
                    out.push(Stmt { kind: StmtKind::While(Box::new(w)), span });
                } else {
                    // The condition's statements must run before every test: test at the top
                    // of an endless loop and leave it with a jump.
                    let exit = self.ctx.label(w.end.span);
                    let cspan = cond.span;
                    let not = Expr::new(ExprKind::Unary(UnOp::Not, Box::new(cond)), cspan);
                    pre.push(block_stmt(vec![goto_item(&exit, Some(not), cspan)], cspan));
                    pre.append(&mut body);
                    let l = LoopStmt { head: w.head, body: pre, end: w.end };
                    out.push(Stmt { kind: StmtKind::Loop(Box::new(l)), span });
                    out.push(label_stmt(exit));
                }
            }
            StmtKind::Loop(mut l) => {
                l.body = self.body(std::mem::take(&mut l.body));
                out.push(Stmt { kind: StmtKind::Loop(l), span });
            }
            StmtKind::For(f) => {
                // `v=a`, then a WHILE on `v <= b` (b evaluated on every pass, compared with
                // Siemens' tolerance) whose body ends with `v=v+1` carrying the ENDFOR block.
                let f = *f;
                let var = f.var.clone();
                let init = meta_stmt(f.head, vec![assign_item(&var, f.from, var.span)]);
                self.stmt(init, out);
                let v = var_expr(&var);
                let cond =
                    Expr::new(ExprKind::Cmp(CmpOp::Le, Tolerance::Relative, Box::new(v.clone()), Box::new(f.to)), span);
                let mut body = f.body;
                body.push(meta_stmt(f.end, vec![assign_item(&var, bin(BinOp::Add, v, num(1.0, span)), span)]));
                let empty = BlockMeta { span, ..BlockMeta::default() };
                let w = WhileStmt { head: empty.clone(), cond, body, end: empty };
                self.stmt(Stmt { kind: StmtKind::While(Box::new(w)), span }, out);
            }
            StmtKind::Repeat(mut r) => {
                r.body = self.body(std::mem::take(&mut r.body));
                let mut pre = Vec::new();
                r.until = self.cond(r.until, &mut pre);
                r.body.extend(pre);
                out.push(Stmt { kind: StmtKind::Repeat(r), span });
            }
            StmtKind::Do(mut d) => {
                d.body = self.body(std::mem::take(&mut d.body));
                out.push(Stmt { kind: StmtKind::Do(d), span });
            }
        }
    }

    fn item(&mut self, it: Item, pre: &mut Vec<Stmt>) -> Item {
        let span = it.span;
        let kind = match it.kind {
            ItemKind::Assign { target, value } => {
                let target = self.varref(*target, pre);
                let value = self.assigned(&target, value, pre);
                ItemKind::Assign { target: Box::new(target), value }
            }
            ItemKind::Word(mut w) => {
                if let WordValue::Expr(e) = w.value {
                    let e = self.value(e, MAX_DEPTH, pre);
                    let e = self.no_round(e, pre);
                    w.value = WordValue::Expr(self.fit(e, MAX_DEPTH - 1, pre));
                }
                ItemKind::Word(w)
            }
            ItemKind::Goto(mut g) => {
                if let Some(c) = g.cond.take() {
                    g.cond = Some(self.cond(c, pre));
                }
                ItemKind::Goto(g)
            }
            ItemKind::Case(mut c) => {
                let sel = self.value(c.selector, MAX_DEPTH, pre);
                c.selector = self.atom(sel, pre);
                ItemKind::Case(c)
            }
            ItemKind::Call(mut c) => {
                for a in &mut c.args {
                    if let Arg::Letter { value, .. } | Arg::Value(value) = a {
                        let v = self.value(std::mem::replace(value, num(0.0, span)), MAX_DEPTH, pre);
                        let v = self.no_round(v, pre);
                        *value = self.fit(v, MAX_DEPTH - 1, pre);
                    }
                }
                if let Some(r) = c.repeat.take() {
                    let r = self.value(r, MAX_DEPTH, pre);
                    c.repeat = Some(self.fit(r, MAX_DEPTH - 1, pre));
                }
                // `G65 P<n>` of `CALL "L"<<n` (`words::built`).
                if let CallTarget::Computed(e) = &mut c.target {
                    let v = self.value(std::mem::replace(e, num(0.0, span)), MAX_DEPTH, pre);
                    *e = self.fit(v, MAX_DEPTH - 1, pre);
                }
                ItemKind::Call(c)
            }
            k => k,
        };
        Item { kind, span }
    }

    /// The value stored into `target`, converted as Siemens converts on assignment: INT and
    /// CHAR round, BOOL is 1 for any non-zero value.
    fn assigned(&mut self, target: &VarRef, value: Expr, pre: &mut Vec<Stmt>) -> Expr {
        let ty = match &target.kind {
            VarKind::Named { name, .. } => self.info.types.get(name).map(|t| t.0),
            _ => None,
        };
        let span = value.span;
        let v = match ty {
            // A constant is already known to be TRUE or FALSE (`LOC2_SET=0` is `#102=0.`).
            Some(DataType::Bool) if matches!(value.kind, ExprKind::Num(_)) => {
                let ExprKind::Num(n) = &value.kind else { unreachable!() };
                num(if n.value != 0.0 { 1.0 } else { 0.0 }, span)
            }
            Some(DataType::Bool) if !is_logical(&value) => {
                let c = Expr::new(
                    ExprKind::Cmp(CmpOp::Ne, Tolerance::Exact, Box::new(value), Box::new(num(0.0, span))),
                    span,
                );
                self.value(c, MAX_DEPTH, pre)
            }
            Some(DataType::Int | DataType::Char) => {
                let v = self.value(value, MAX_DEPTH, pre);
                if self.integral(&v) {
                    v
                } else {
                    func(Func::FanucRound, vec![v], span)
                }
            }
            _ => self.value(value, MAX_DEPTH, pre),
        };
        self.fit(v, MAX_DEPTH, pre)
    }

    fn varref(&mut self, v: VarRef, pre: &mut Vec<Stmt>) -> VarRef {
        let span = v.span;
        let kind = match v.kind {
            VarKind::RIndirect(e) => {
                let e = self.value(*e, MAX_DEPTH, pre);
                VarKind::RIndirect(Box::new(self.fit(e, MAX_DEPTH - 1, pre)))
            }
            VarKind::Named { name, indices } => {
                let indices = indices
                    .into_iter()
                    .map(|i| {
                        let i = self.value(i, MAX_DEPTH, pre);
                        self.fit(i, MAX_DEPTH - 3, pre)
                    })
                    .collect();
                VarKind::Named { name, indices }
            }
            k => k,
        };
        VarRef { kind, span }
    }

    /// A value expression in FANUC form (before variable mapping).
    pub(crate) fn value(&mut self, e: Expr, budget: i32, pre: &mut Vec<Stmt>) -> Expr {
        let v = self.val(e, pre);
        self.fit(v, budget, pre)
    }

    fn val(&mut self, e: Expr, pre: &mut Vec<Stmt>) -> Expr {
        let span = e.span;
        if is_logical(&e) {
            return self.logical_value(e, pre);
        }
        if let Some((f, args)) = fanuc_range(&e).filter(|_| !self.ctx.nat) {
            let args: Vec<Expr> = args.into_iter().map(|a| self.val(a, pre)).collect();
            return func(f, args, span);
        }
        match e.kind {
            ExprKind::Num(_) | ExprKind::Vacant => e,
            ExprKind::Str(_) | ExprKind::Ident(_) => {
                self.ctx.unsupported("NC314", span, "a string value", "FANUC variables hold numbers only");
                num(0.0, span)
            }
            ExprKind::Var(v) => Expr::new(ExprKind::Var(Box::new(self.varref(*v, pre))), span),
            ExprKind::Unary(UnOp::Neg, x) => {
                let x = self.val(*x, pre);
                match x.kind {
                    ExprKind::Num(n) => Expr::num(-n.value, n.point, span),
                    _ => Expr::new(ExprKind::Unary(UnOp::Neg, Box::new(x)), span),
                }
            }
            ExprKind::Unary(op, _) => {
                let what = if op == UnOp::BitNot { "B_NOT" } else { "NOT" };
                self.ctx.unsupported("NC330", span, what, "FANUC has no bitwise complement; use an explicit formula");
                num(0.0, span)
            }
            ExprKind::Binary(op, a, b) => {
                let a = self.val(*a, pre);
                let b = self.val(*b, pre);
                match op {
                    BinOp::IntDiv => func(Func::Trunc, vec![bin(BinOp::Div, a, b)], span),
                    BinOp::Mod => {
                        let a = self.atom(a, pre);
                        let b = self.atom(b, pre);
                        let q = func(Func::Trunc, vec![bin(BinOp::Div, a.clone(), b.clone())], span);
                        bin(BinOp::Sub, a, bin(BinOp::Mul, q, b))
                    }
                    BinOp::BitAnd => bin(BinOp::FanucBitAnd, a, b),
                    BinOp::BitOr => bin(BinOp::FanucBitOr, a, b),
                    BinOp::BitXor => bin(BinOp::FanucBitXor, a, b),
                    BinOp::Concat => {
                        self.ctx.unsupported("NC314", span, "string concatenation <<", "FANUC has no strings");
                        num(0.0, span)
                    }
                    op => bin(op, a, b),
                }
            }
            ExprKind::Func(Func::GetSelT, _) => {
                // FANUC #4120 is the last T word; whether GETSELT returns it (the T number,
                // not the name or duplo tool management chose) is in no source read here.
                let why = "no source read here says what tool management returns for the preselected tool, so FANUC's \
                           #4120 (the last T word) is not proven its counterpart; keep the T number in a variable where \
                           the program selects the tool, or select it by name with --tool-map";
                let what = "GETSELT(…) (the tool tool management preselected for the spindle)";
                self.ctx.unsupported("NC508", span, what, why);
                num(0.0, span)
            }
            ExprKind::Func(Func::GetT, args) => self.gett(&args, span),
            ExprKind::Func(f, _) if f.is_string() => {
                let what = format!("string function {}(…)", crate::dialect::sinumerik::emit::func_name(f));
                self.ctx.unsupported("NC506", span, &what, "FANUC variables hold numbers only; it has no strings");
                num(0.0, span)
            }
            ExprKind::Func(f, args) => {
                let args: Vec<Expr> = args.into_iter().map(|a| self.val(a, pre)).collect();
                self.function(f, args, span, pre)
            }
            ExprKind::Cmp(..) => self.logical_value(e, pre),
        }
    }

    /// `GETT("NAME")`: the T number the tool map gives the name, as a constant (the map is the
    /// set-up's, as for `T="NAME"`); a duplo number or a computed name has no constant.
    fn gett(&mut self, args: &[Expr], span: Span) -> Expr {
        let name = match args {
            [Expr { kind: ExprKind::Str(n), .. }] => n.clone(),
            [Expr { kind: ExprKind::Str(n), .. }, _] => {
                let what = format!("GETT(\"{n}\", duplo) (which replacement tool of that name)");
                let hint = "the tool map holds one T number per name: write GETT(\"NAME\") or give each replacement tool its own name";
                self.ctx.unsupported("NC526", span, &what, hint);
                return num(0.0, span);
            }
            _ => {
                let hint = "write the tool name as a string constant: GETT(\"NAME\")";
                self.ctx.unsupported("NC525", span, "GETT(…) of a computed name", hint);
                return num(0.0, span);
            }
        };
        match self.ctx.tools.get(&name) {
            Some(&n) => {
                self.ctx.tools_used.insert(name, n);
                num(f64::from(n), span)
            }
            None => {
                let msg = format!("GETT(\"{name}\"): tool \"{name}\" has no FANUC tool number");
                let hint = format!(
                    "give the T number the machine has this tool under: --tool-map {name}=<number>, \
                     or `\"{name}\" = <number>` under [tools] in nctrans.toml (nctrans never chooses one)"
                );
                self.ctx.error("NC525", span, &msg, &hint);
                self.ctx.unsupported += 1;
                num(0.0, span)
            }
        }
    }

    fn function(&mut self, f: Func, mut args: Vec<Expr>, span: Span, pre: &mut Vec<Stmt>) -> Expr {
        let want = match f {
            Func::Atan2 | Func::MinVal | Func::MaxVal | Func::Pow | Func::FanucAtan2 => 2,
            Func::Bound => 3,
            _ => 1,
        };
        if args.len() != want {
            self.ctx.unsupported("NC331", span, &format!("{f:?} with {} arguments", args.len()), "");
            return num(0.0, span);
        }
        let c = |v: f64| num(v, span);
        match f {
            Func::AxName => {
                let why = "FANUC addresses are fixed letters; an axis cannot be chosen by name at run time";
                self.ctx.unsupported("NC632", span, "AXNAME(…)", why);
                num(0.0, span)
            }
            Func::Round => func(Func::FanucRound, args, span),
            Func::Acos => func(Func::FanucAcos, args, span),
            Func::Asin if self.ctx.nat => func(Func::FanucAsin, args, span),
            Func::Atan2 if self.ctx.nat => func(Func::FanucAtan2, args, span),
            Func::Asin | Func::Atan2 => {
                let (ff, limit) = if f == Func::Asin { (Func::FanucAsin, 90.0) } else { (Func::FanucAtan2, 180.0) };
                let t = self.ctx.temp(span);
                let v = self.fit(func(ff, args, span), MAX_DEPTH, pre);
                pre.push(block_stmt(vec![assign_item(&t, v, span)], span));
                let tv = var_expr(&t);
                let cond = cmp(CmpOp::Gt, tv.clone(), c(limit));
                pre.push(block_stmt(vec![if_then(cond, &t, bin(BinOp::Sub, tv.clone(), c(360.0)), span)], span));
                tv
            }
            Func::RoundUp => {
                let x = self.atom(args.remove(0), pre);
                let u = self.ctx.temp(span);
                pre.push(block_stmt(vec![assign_item(&u, func(Func::Trunc, vec![x.clone()], span), span)], span));
                let uv = var_expr(&u);
                let cond = cmp(CmpOp::Gt, x, uv.clone());
                pre.push(block_stmt(vec![if_then(cond, &u, bin(BinOp::Add, uv.clone(), c(1.0)), span)], span));
                uv
            }
            Func::Pot => {
                let x = self.atom(args.remove(0), pre);
                bin(BinOp::Mul, x.clone(), x)
            }
            Func::MinVal | Func::MaxVal => {
                let b = self.atom(args.remove(1), pre);
                let t = self.spill(args.remove(0), pre);
                let op = if f == Func::MinVal { CmpOp::Lt } else { CmpOp::Gt };
                let ExprKind::Var(tv) = &t.kind else { return t };
                let tv = (**tv).clone();
                pre.push(block_stmt(vec![if_then(cmp(op, b.clone(), t.clone()), &tv, b, span)], span));
                t
            }
            Func::Bound => {
                let x = args.remove(2);
                let mx = self.atom(args.remove(1), pre);
                let mn = self.atom(args.remove(0), pre);
                let t = self.spill(x, pre);
                let ExprKind::Var(tv) = &t.kind else { return t };
                let tv = (**tv).clone();
                pre.push(block_stmt(vec![if_then(cmp(CmpOp::Lt, t.clone(), mn.clone()), &tv, mn, span)], span));
                pre.push(block_stmt(vec![if_then(cmp(CmpOp::Gt, t.clone(), mx.clone()), &tv, mx, span)], span));
                t
            }
            f => func(f, args, span),
        }
    }

    /// A Siemens logical value (comparison, AND/OR/XOR/NOT) as a number: `t=0`, then `t=1`
    /// when the condition holds (lowered to IF-THEN or IF-GOTO by the structure pass).
    fn logical_value(&mut self, e: Expr, pre: &mut Vec<Stmt>) -> Expr {
        let span = e.span;
        let c = self.cond(e, pre);
        let t = self.ctx.temp(span);
        pre.push(block_stmt(vec![assign_item(&t, num(0.0, span), span)], span));
        let then_body = vec![block_stmt(vec![assign_item(&t, num(1.0, span), span)], span)];
        let head = BlockMeta { span, ..BlockMeta::default() };
        let i = IfStmt { head: head.clone(), cond: c, then_body, else_part: None, end: head };
        pre.push(Stmt { kind: StmtKind::If(Box::new(i)), span });
        var_expr(&t)
    }

    /// A condition: a tree of logical AND/OR/XOR/NOT over exact comparisons of FANUC values.
    pub(crate) fn cond(&mut self, e: Expr, pre: &mut Vec<Stmt>) -> Expr {
        let span = e.span;
        match e.kind {
            ExprKind::Binary(op @ (BinOp::And | BinOp::Or | BinOp::Xor), a, b) => {
                let a = self.cond(*a, pre);
                let b = self.cond(*b, pre);
                Expr::new(ExprKind::Binary(op, Box::new(a), Box::new(b)), span)
            }
            ExprKind::Unary(UnOp::Not, a) => {
                let a = self.cond(*a, pre);
                Expr::new(ExprKind::Unary(UnOp::Not, Box::new(a)), span)
            }
            ExprKind::Cmp(op, tol, a, b) => {
                let a = self.val(*a, pre);
                let b = self.val(*b, pre);
                self.compare(op, tol, a, b, span, pre)
            }
            _ => {
                let v = self.val(e, pre);
                let v = self.fit(v, MAX_DEPTH - 2, pre);
                Expr::new(ExprKind::Cmp(CmpOp::Ne, Tolerance::Exact, Box::new(v), Box::new(num(0.0, span))), span)
            }
        }
    }

    fn compare(&mut self, op: CmpOp, tol: Tolerance, a: Expr, b: Expr, span: Span, pre: &mut Vec<Stmt>) -> Expr {
        let exact = tol == Tolerance::Exact
            || is_zero(&a)
            || is_zero(&b)
            || (self.integral(&a) && self.integral(&b))
            || self.info.exact_cmps.contains(&span);
        let mk = |op, x: Expr, y: Expr| Expr::new(ExprKind::Cmp(op, Tolerance::Exact, Box::new(x), Box::new(y)), span);
        if exact {
            // `a-b>0` (as FANUC → Sinumerik writes FANUC's `a GT b`): the Siemens tolerance
            // around 0 admits only 0, and IEEE `a-b` is 0 only when a = b and keeps the sign,
            // so it is FANUC's exact `a GT b`: the plain form, and a round trip gives back
            // what it was given. Not for EQ/NE/GE/LE, where FANUC tells a vacant operand
            // from 0 (or may: the manuals disagree on GE and LE) and `a-b` never is vacant.
            let (a, b) = match (op, a, b) {
                (CmpOp::Lt | CmpOp::Gt, Expr { kind: ExprKind::Binary(BinOp::Sub, x, y), .. }, z) if is_zero(&z) => {
                    (*x, *y)
                }
                (_, a, b) => (a, b),
            };
            // Room for the condition's own bracket and one compound level.
            let a = self.fit(a, MAX_DEPTH - 2, pre);
            let b = self.fit(b, MAX_DEPTH - 2, pre);
            return mk(op, a, b);
        }
        let a = self.atom(a, pre);
        let b = self.atom(b, pre);
        let abs = |x: &Expr| match &x.kind {
            ExprKind::Num(n) => num(n.value.abs(), x.span),
            _ => func(Func::Abs, vec![x.clone()], x.span),
        };
        // max(|a|,|b|) = (|a| + |b| + ||a|-|b||) / 2; the 1/2 is folded into the constant.
        let sum = bin(BinOp::Add, abs(&a), abs(&b));
        let spread = func(Func::Abs, vec![bin(BinOp::Sub, abs(&a), abs(&b))], span);
        let twice_max = match (&a.kind, &b.kind) {
            (ExprKind::Num(_), ExprKind::Num(_)) => num(2.0 * a_max(&a, &b), span),
            _ => bin(BinOp::Add, sum, spread),
        };
        let tolx = bin(BinOp::Mul, bin(BinOp::Mul, twice_max, num(0.0000005, span)), num(0.000001, span));
        let diff = |x: &Expr, y: &Expr| bin(BinOp::Sub, x.clone(), y.clone());
        match op {
            CmpOp::Eq => mk(CmpOp::Le, func(Func::Abs, vec![diff(&a, &b)], span), tolx),
            CmpOp::Ne => mk(CmpOp::Gt, func(Func::Abs, vec![diff(&a, &b)], span), tolx),
            CmpOp::Lt => mk(CmpOp::Gt, diff(&b, &a), tolx),
            CmpOp::Le => mk(CmpOp::Le, diff(&a, &b), tolx),
            CmpOp::Gt => mk(CmpOp::Gt, diff(&a, &b), tolx),
            CmpOp::Ge => mk(CmpOp::Le, diff(&b, &a), tolx),
        }
    }

    /// True when `e` always has an integer value (so Siemens' tolerance cannot matter).
    fn integral(&self, e: &Expr) -> bool {
        match &e.kind {
            ExprKind::Num(n) => n.value.fract() == 0.0,
            ExprKind::Var(v) => match &v.kind {
                VarKind::Named { name, .. } => {
                    matches!(self.info.types.get(name), Some((DataType::Int | DataType::Bool | DataType::Char, _)))
                }
                _ => false,
            },
            ExprKind::Unary(UnOp::Neg, x) => self.integral(x),
            ExprKind::Binary(BinOp::Add | BinOp::Sub | BinOp::Mul, a, b) => self.integral(a) && self.integral(b),
            ExprKind::Func(Func::Trunc | Func::FanucRound | Func::Round | Func::FanucFup, _) => true,
            _ => false,
        }
    }

    /// `e` as a constant or a plain variable, moving it into a temporary otherwise.
    pub(crate) fn atom(&mut self, e: Expr, pre: &mut Vec<Stmt>) -> Expr {
        if is_atom(&e) {
            e
        } else {
            self.spill(e, pre)
        }
    }

    /// `e` stored in a fresh temporary; returns the temporary.
    pub(crate) fn spill(&mut self, e: Expr, pre: &mut Vec<Stmt>) -> Expr {
        let span = e.span;
        let e = self.fit(e, MAX_DEPTH, pre);
        let t = self.ctx.temp(span);
        pre.push(block_stmt(vec![assign_item(&t, e, span)], span));
        var_expr(&t)
    }

    /// ROUND inside an address rounds to the address increment on FANUC: compute it first.
    fn no_round(&mut self, e: Expr, pre: &mut Vec<Stmt>) -> Expr {
        if !contains_round(&e) {
            return e;
        }
        match e.kind {
            ExprKind::Func(Func::FanucRound, _) => self.spill(e, pre),
            ExprKind::Unary(op, x) => Expr::new(ExprKind::Unary(op, Box::new(self.no_round(*x, pre))), e.span),
            ExprKind::Binary(op, a, b) => {
                let a = self.no_round(*a, pre);
                let b = self.no_round(*b, pre);
                Expr::new(ExprKind::Binary(op, Box::new(a), Box::new(b)), e.span)
            }
            ExprKind::Func(f, args) => {
                let args = args.into_iter().map(|a| self.no_round(a, pre)).collect();
                Expr::new(ExprKind::Func(f, args), e.span)
            }
            _ => self.spill(e, pre),
        }
    }

    /// Fits `e` into `budget` bracket levels by moving the deepest parts into temporaries.
    pub(crate) fn fit(&mut self, e: Expr, budget: i32, pre: &mut Vec<Stmt>) -> Expr {
        let budget = budget.max(0);
        if depth(&e) as i32 <= budget {
            return e;
        }
        if budget == 0 {
            return self.spill(e, pre);
        }
        let span = e.span;
        let e = match e.kind {
            ExprKind::Binary(op, a, b) => {
                let ca = crate::dialect::fanuc::emit::operand_bracketed(op, &a, false) as i32;
                let cb = crate::dialect::fanuc::emit::operand_bracketed(op, &b, true) as i32;
                let a = self.fit(*a, budget - ca, pre);
                let b = self.fit(*b, budget - cb, pre);
                Expr::new(ExprKind::Binary(op, Box::new(a), Box::new(b)), span)
            }
            ExprKind::Unary(op, x) => Expr::new(ExprKind::Unary(op, Box::new(self.fit(*x, budget - 1, pre))), span),
            ExprKind::Func(f, args) => {
                let args = args.into_iter().map(|a| self.fit(a, budget - 1, pre)).collect();
                Expr::new(ExprKind::Func(f, args), span)
            }
            ExprKind::Cmp(op, tol, a, b) => {
                let a = self.fit(*a, budget - 1, pre);
                let b = self.fit(*b, budget - 1, pre);
                Expr::new(ExprKind::Cmp(op, tol, Box::new(a), Box::new(b)), span)
            }
            kind => Expr::new(kind, span),
        };
        if depth(&e) as i32 <= budget {
            e
        } else {
            self.spill(e, pre)
        }
    }
}

pub fn is_logical(e: &Expr) -> bool {
    matches!(
        e.kind,
        ExprKind::Cmp(..) | ExprKind::Unary(UnOp::Not, _) | ExprKind::Binary(BinOp::And | BinOp::Or | BinOp::Xor, _, _)
    )
}

pub fn is_atom(e: &Expr) -> bool {
    match &e.kind {
        ExprKind::Num(_) | ExprKind::Vacant => true,
        ExprKind::Var(v) => {
            matches!(v.kind, VarKind::Hash(_) | VarKind::R(_))
                || matches!(&v.kind, VarKind::Named { indices, .. } if indices.is_empty())
        }
        _ => false,
    }
}

fn a_max(a: &Expr, b: &Expr) -> f64 {
    let v = |e: &Expr| match &e.kind {
        ExprKind::Num(n) => n.value.abs(),
        _ => 0.0,
    };
    v(a).max(v(b))
}

fn is_zero(e: &Expr) -> bool {
    matches!(&e.kind, ExprKind::Num(n) if n.value == 0.0)
}

fn contains_round(e: &Expr) -> bool {
    matches!(e.kind, ExprKind::Func(Func::FanucRound, _)) || e.children().into_iter().any(contains_round)
}

#[cfg(test)]
mod tests {
    use super::super::build::*;
    use super::*;

    fn lower_value(e: Expr) -> (Vec<Stmt>, Expr) {
        let mut ctx = Ctx::new(0, UnsupportedPolicy::Error);
        let info = ProgInfo::default();
        let mut pre = Vec::new();
        let v = Lower { ctx: &mut ctx, info: &info }.value(e, MAX_DEPTH, &mut pre);
        (pre, v)
    }

    #[test]
    fn roundup_is_a_ceiling_not_fup() {
        let (pre, v) = lower_value(func(Func::RoundUp, vec![r(1)], sp()));
        assert_eq!(pre.len(), 2);
        assert!(matches!(v.kind, ExprKind::Var(_)));
        let text = format!("{pre:?}");
        assert!(text.contains("Trunc") && !text.contains("FanucFup"));
    }

    #[test]
    fn mod_uses_fix_and_div_truncates() {
        let (_, v) = lower_value(bin(BinOp::Mod, r(1), r(2)));
        assert!(matches!(v.kind, ExprKind::Binary(BinOp::Sub, _, _)));
        let (_, v) = lower_value(bin(BinOp::IntDiv, r(1), r(2)));
        assert!(matches!(v.kind, ExprKind::Func(Func::Trunc, _)));
    }

    #[test]
    fn logical_and_never_becomes_bitwise() {
        let (pre, v) = lower_value(bin(BinOp::And, r(1), r(2)));
        assert!(matches!(v.kind, ExprKind::Var(_)));
        assert!(!format!("{pre:?}").contains("FanucBit"));
    }

    #[test]
    fn relative_equality_uses_the_tolerance_unless_integral() {
        let mut ctx = Ctx::new(0, UnsupportedPolicy::Error);
        let info = ProgInfo::default();
        let mut pre = Vec::new();
        let mut l = Lower { ctx: &mut ctx, info: &info };
        let c = l.cond(cmp_rel(CmpOp::Eq, r(1), n(0.5)), &mut pre);
        assert!(matches!(c.kind, ExprKind::Cmp(CmpOp::Le, Tolerance::Exact, _, _)));
        let c = l.cond(cmp_rel(CmpOp::Eq, r(1), n(0.0)), &mut pre);
        assert!(matches!(c.kind, ExprKind::Cmp(CmpOp::Eq, Tolerance::Exact, _, _)));
    }

    #[test]
    fn deep_expressions_are_split_into_temporaries() {
        let mut e = r(1);
        for _ in 0..8 {
            e = func(Func::Sin, vec![bin(BinOp::Add, e, n(1.0))], sp());
        }
        let (pre, v) = lower_value(e);
        assert!(!pre.is_empty());
        assert!(depth(&v) <= 5);
    }
}
