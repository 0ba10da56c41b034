//! FANUC expressions → Siemens expressions with exactly FANUC's results.
//!
//! - Variables through the variable map; `#0` (vacant) reads as 0; system variables per
//!   `words::system_var`.
//! - `a AND b` (bitwise on integer parts) → `TRUNC(a) B_AND TRUNC(b)`, same for OR/XOR.
//! - `FIX` → `TRUNC`; `FUP[x]` (away from zero) → `ROUNDUP(x)-TRUNC(x)-ROUNDUP(-x)`, exact
//!   in integer arithmetic; `ACOS` is the same function; `ATAN[y]/[x]`, `ASIN[x]` with NAT=0
//!   (0..360, 270..90) → `(ATAN2(y,x)+360) MOD 360`, `(ASIN(x)+360) MOD 360`.
//! - `POW[a,k]` for a literal k in 0..16 → products (`POT` for 2); `BIN`/`BCD` → digit sums.
//! - Comparisons: FANUC compares exactly, Siemens within 1e-12 relative. `a op b` is written
//!   `a-b op 0` (or `a op 0` when one side is the literal 0): a relative tolerance around 0
//!   admits only 0, and IEEE subtraction is 0 exactly when a = b, so the test is exact.
//! - Precedence is the emitter's job: it parenthesises by Siemens priorities.

use super::*;

/// Lowers every expression of the current program.
pub fn lower(ctx: &mut Ctx, body: Vec<Stmt>) -> Vec<Stmt> {
    map_bodies(body, &mut |list| {
        let mut out = Vec::with_capacity(list.len());
        for mut s in list {
            let mut local: Vec<Stmt> = Vec::new();
            match &mut s.kind {
                StmtKind::Block(b) => {
                    ctx.guard_ok = true;
                    for it in &mut b.items {
                        lower_item(ctx, it, &mut local);
                    }
                    ctx.guard_ok = false;
                }
                StmtKind::If(i) => lower_expr(ctx, &mut i.cond, &mut local),
                StmtKind::While(w) => lower_expr(ctx, &mut w.cond, &mut local),
                StmtKind::Repeat(r) => lower_expr(ctx, &mut r.until, &mut local),
                StmtKind::For(x) => {
                    lower_expr(ctx, &mut x.from, &mut local);
                    lower_expr(ctx, &mut x.to, &mut local);
                }
                StmtKind::Do(d) => {
                    if let Some(c) = &mut d.cond {
                        lower_expr(ctx, c, &mut local);
                    }
                }
                StmtKind::Loop(_) => {}
            }
            out.extend(local);
            out.push(s);
        }
        out
    })
}

fn lower_item(ctx: &mut Ctx, it: &mut Item, marks: &mut Vec<Stmt>) {
    if let ItemKind::Assign { target, value } = &mut it.kind {
        // A computed write keeps the is-set flag of the variable it reaches: the value's
        // flag, taken from the FANUC value before it is lowered.
        let flag = matches!(target.kind, VarKind::HashIndirect(_)).then(|| super::vacancy::flag_of_value(ctx, value));
        map_target(ctx, target, marks, flag);
    }
    if let ItemKind::IfThen { then, .. } = &mut it.kind {
        // (`structures` has made every IF-THEN block an IF statement; this is for any left.)
        lower_item(ctx, then, marks);
    }
    // Assignment targets were handled above; their index expressions and every other
    // expression go through lower_expr.
    let mut f = |e: &mut Expr| lower_expr(ctx, e, marks);
    match &mut it.kind {
        ItemKind::IfThen { cond, .. } => f(cond),
        _ => item_exprs_mut(it, &mut f),
    }
}

/// `write_flag`: for a computed target, the flag of the value written.
fn map_target(ctx: &mut Ctx, target: &mut VarRef, marks: &mut Vec<Stmt>, write_flag: Option<Expr>) {
    let span = target.span;
    match &target.kind {
        VarKind::Hash(n) => {
            let n = *n;
            match super::varmap::map_hash(ctx, n, span).or_else(|| super::words::system_var(n, span)) {
                Some(k) => target.kind = k,
                None => {
                    if let Some(m) = ngc_common(ctx, n, span) {
                        marks.extend(m);
                    } else {
                        let (what, hint) = super::haas_sys::refusal(ctx, n, true)
                            .unwrap_or_else(|| (format!("writing the system variable #{n}"), GENERIC_HINT));
                        let what = if what.starts_with("writing") { what } else { format!("writing {what}") };
                        marks.extend(ctx.unsupported("NC365", span, &what, hint));
                    }
                    target.kind = VarKind::Named { name: format!("NCTRANS_UNSUPPORTED_{n}"), indices: vec![] };
                }
            }
        }
        VarKind::HashIndirect(x) => {
            let mut x = (**x).clone();
            lower_expr(ctx, &mut x, marks);
            if let Some(m) = super::haas_sys::computed(ctx, &x, span) {
                marks.extend(m);
                target.kind = VarKind::Named { name: "NCTRANS_UNSUPPORTED_INDIRECT".into(), indices: vec![] };
                return;
            }
            match runtime_indirect(ctx, x, span, marks, Access::Write(write_flag)) {
                Some(k) => target.kind = k,
                None => {
                    marks.extend(ctx.unsupported(
                        "NC361",
                        span,
                        "an indirect variable `#[…]` whose number is not known before the run",
                        "use it in a plain block (assign it to a variable before the IF or WHILE), or give its range a --var-map rule",
                    ));
                    target.kind = VarKind::Named { name: "NCTRANS_UNSUPPORTED_INDIRECT".into(), indices: vec![] };
                }
            }
        }
        _ => {}
    }
}

/// The hint of a system variable refusal without a description of its own.
const GENERIC_HINT: &str =
    "docs/translation-fanuc-to-sinumerik.md (Variables) lists the system variables that have a Siemens counterpart";

/// FANUC alarm 115 (variable number out of range), as the translation raises it.
const ALARM_INDEX: i64 = super::gotos::RUNTIME_ALARM_BASE + 115;

/// `#[x]` with an index only known at run time → `R[…]` by the variable map's own rules
/// (`varmap::dispatch_ranges`), in a plain block: blocks in front compute the R number into
/// an `INT` temporary, one `IF` per range that needs an offset (`NCTRANS_IX1=NCTRANS_IX1-500`
/// for `#500..` on `R0..`), and raise `SETAL(64115)` for a number no range holds, so the
/// mapping is checked on every run instead of trusted. One range on its own R numbers needs
/// no temporary: `R[ROUND(x)]` after the guard.
fn runtime_indirect(ctx: &mut Ctx, x: Expr, span: Span, marks: &mut Vec<Stmt>, access: Access) -> Option<VarKind> {
    if !ctx.guard_ok {
        return None;
    }
    let ranges = super::varmap::dispatch_ranges(ctx);
    // The tracked variables it may reach, (R number, flag R number).
    let tracked: Vec<(u32, u32)> = ctx
        .common_flags
        .iter()
        .filter_map(|(n, &f)| {
            let r = *ctx.commons.get(n)?;
            ranges.iter().any(|&(from, to, _)| from <= *n && *n <= to).then_some((r, f))
        })
        .collect();
    if ranges.is_empty() {
        return None;
    }
    let idx = func(Func::Round, vec![x], span);
    let cmp = |e: &Expr, op: CmpOp, v: u32| {
        Expr::new(ExprKind::Cmp(op, Tolerance::Relative, Box::new(e.clone()), Box::new(int(i64::from(v), span))), span)
    };
    let outside =
        |e: &Expr, (from, to, _): (u32, u32, u32)| bin(BinOp::Or, cmp(e, CmpOp::Lt, from), cmp(e, CmpOp::Gt, to));
    let inside =
        |e: &Expr, (from, to, _): (u32, u32, u32)| bin(BinOp::And, cmp(e, CmpOp::Ge, from), cmp(e, CmpOp::Le, to));
    let alarm = || {
        plain_block(
            vec![Item {
                kind: ItemKind::Alarm { style: AlarmStyle::Setal, number: int(ALARM_INDEX, span), text: None },
                span,
            }],
            span,
        )
    };
    if let [one @ (from, _, r)] = ranges[..] {
        if from == r {
            marks.push(if_stmt(outside(&idx, one), vec![alarm()], None, span));
            flags(&idx, &tracked, access, span, marks);
            return Some(VarKind::RIndirect(Box::new(idx)));
        }
    }
    // The temporary: one per computed access of the statement (the blocks in front of it
    // are `marks`), the same ones again for the next statement; declared once.
    let k = marks.iter().filter(|m| is_temp_set(m)).count() + 1;
    let name = format!("{IX_TEMP}{k}");
    let plan = &mut ctx.progs[ctx.cur];
    if !plan.defs.iter().any(|d| d.0 == name) {
        plan.defs.push((name.clone(), DataType::Int));
    }
    let t = named(&name, span);
    marks.push(plain_block(vec![crate::lower::assign_item(&named_ref(&name, span), idx, span)], span));
    // Ranges on their own R numbers need no assignment: they are tested last, together.
    let (same, moved): (Vec<_>, Vec<_>) = ranges.iter().copied().partition(|(from, _, r)| from == r);
    let mut tail = match same.split_first() {
        None => vec![alarm()],
        Some((first, rest)) => {
            let cond = rest.iter().fold(outside(&t, *first), |c, &r| bin(BinOp::And, c, outside(&t, r)));
            vec![if_stmt(cond, vec![alarm()], None, span)]
        }
    };
    for range @ (from, _, r) in moved.into_iter().rev() {
        let shift = if r > from {
            bin(BinOp::Add, t.clone(), int(i64::from(r - from), span))
        } else {
            bin(BinOp::Sub, t.clone(), int(i64::from(from - r), span))
        };
        let set = plain_block(vec![crate::lower::assign_item(&named_ref(&name, span), shift, span)], span);
        tail = vec![if_stmt(inside(&t, range), vec![set], Some(tail), span)];
    }
    marks.extend(tail);
    flags(&t, &tracked, access, span, marks);
    Some(VarKind::RIndirect(Box::new(t)))
}

/// A computed variable access.
enum Access {
    Read,
    /// The value's flag.
    Write(Option<Expr>),
}

/// The is-set flags of the tracked variables a computed access with R number `r` may reach:
/// a write sets the flag of the one it reaches to the value's; a read of one that is vacant
/// (its flag FALSE) raises `SETAL(64115)`, as Siemens has no vacant value to read.
fn flags(r: &Expr, tracked: &[(u32, u32)], access: Access, span: Span, marks: &mut Vec<Stmt>) {
    for &(rn, f) in tracked {
        let hit = Expr::new(
            ExprKind::Cmp(CmpOp::Eq, Tolerance::Relative, Box::new(r.clone()), Box::new(int(i64::from(rn), span))),
            span,
        );
        let flag = VarRef { kind: VarKind::R(f), span };
        let body = match &access {
            Access::Write(w) => {
                let value = w.clone().unwrap_or_else(|| int(1, span));
                marks.push(if_stmt(
                    hit,
                    vec![plain_block(vec![crate::lower::assign_item(&flag, value, span)], span)],
                    None,
                    span,
                ));
                continue;
            }
            Access::Read => vec![plain_block(
                vec![Item {
                    kind: ItemKind::Alarm { style: AlarmStyle::Setal, number: int(ALARM_INDEX, span), text: None },
                    span,
                }],
                span,
            )],
        };
        let unset =
            Expr::new(ExprKind::Unary(UnOp::Not, Box::new(Expr::new(ExprKind::Var(Box::new(flag)), span))), span);
        marks.push(if_stmt(bin(BinOp::And, hit, unset), body, None, span));
    }
}

/// The name stem of the temporaries that hold a computed R number.
const IX_TEMP: &str = "NCTRANS_IX";

/// Whether `s` is the block that sets a computed-R-number temporary (`NCTRANS_IX1=ROUND(…)`).
fn is_temp_set(s: &Stmt) -> bool {
    let StmtKind::Block(b) = &s.kind else { return false };
    matches!(b.items.as_slice(), [Item { kind: ItemKind::Assign { target, .. }, .. }]
        if matches!(&target.kind, VarKind::Named { name, .. } if name.starts_with(IX_TEMP)))
}

fn lower_expr(ctx: &mut Ctx, e: &mut Expr, marks: &mut Vec<Stmt>) {
    for c in super::vacancy::children_mut(e) {
        lower_expr(ctx, c, marks);
    }
    let span = e.span;
    let new = match std::mem::replace(&mut e.kind, ExprKind::Vacant) {
        ExprKind::Vacant => Expr::num(0.0, false, span),
        ExprKind::Var(v) => match v.kind {
            VarKind::Hash(0) => Expr::num(0.0, false, span),
            VarKind::Hash(5043) if let Some(r) = super::position_length::read(ctx, v.span) => r.unwrap_or_else(|m| {
                marks.extend(m);
                Expr::num(0.0, false, span)
            }),
            VarKind::Hash(n) => {
                match super::varmap::map_hash(ctx, n, v.span).or_else(|| super::words::system_var(n, v.span)) {
                    Some(k) => var_expr(k, v.span),
                    None if ngc_common(ctx, n, v.span).map(|m| marks.extend(m)).is_some() => {
                        Expr::num(0.0, false, span)
                    }
                    None if let Some(m) = haas_data(ctx, n, v.span) => {
                        marks.extend(m);
                        Expr::num(0.0, false, span)
                    }
                    None if let Some(r) = super::modal_reads::read(ctx, n, v.span) => r.unwrap_or_else(|m| {
                        marks.extend(m);
                        Expr::num(0.0, false, span)
                    }),
                    None => {
                        let (what, hint) = super::haas_sys::refusal(ctx, n, false)
                            .unwrap_or_else(|| (format!("the system variable #{n}"), GENERIC_HINT));
                        marks.extend(ctx.unsupported("NC365", v.span, &what, hint));
                        Expr::num(0.0, false, span)
                    }
                }
            }
            VarKind::HashIndirect(x) if let Some(m) = super::haas_sys::computed(ctx, &x, v.span) => {
                marks.extend(m);
                Expr::num(0.0, false, span)
            }
            VarKind::HashIndirect(x) => match runtime_indirect(ctx, *x, v.span, marks, Access::Read) {
                Some(k) => var_expr(k, v.span),
                None => {
                    marks.extend(ctx.unsupported(
                        "NC361",
                        v.span,
                        "an indirect variable `#[…]` whose number is not known before the run",
                        "use it in a plain block (assign it to a variable before the IF or WHILE), or give its range a --var-map rule",
                    ));
                    Expr::num(0.0, false, span)
                }
            },
            kind => var_expr(kind, v.span),
        },
        ExprKind::Binary(op, a, b) => match op {
            BinOp::FanucBitAnd | BinOp::FanucBitOr | BinOp::FanucBitXor => {
                let sop = match op {
                    BinOp::FanucBitAnd => BinOp::BitAnd,
                    BinOp::FanucBitOr => BinOp::BitOr,
                    _ => BinOp::BitXor,
                };
                bin(sop, int_part(*a), int_part(*b))
            }
            _ => Expr::new(ExprKind::Binary(op, a, b), span),
        },
        // A FANUC comparison is exact; a relative one here was written by a pass for values
        // on which the relative equality is exact (the end flag's 0, 2, 30; `$AC_MEA`'s 0
        // and 1): as written.
        ExprKind::Cmp(op, Tolerance::Relative, a, b) => Expr::new(ExprKind::Cmp(op, Tolerance::Relative, a, b), span),
        ExprKind::Cmp(op, _, a, b) => {
            let zero = |x: &Expr| literal(x) == Some(0.0);
            let (l, r) = if zero(&b) || zero(&a) {
                (*a, *b)
            } else {
                let sp = a.span.to(b.span);
                (bin(BinOp::Sub, *a, *b), Expr::num(0.0, false, sp))
            };
            Expr::new(ExprKind::Cmp(op, Tolerance::Relative, Box::new(l), Box::new(r)), span)
        }
        ExprKind::Func(f, args) => lower_func(ctx, f, args, span, marks),
        kind => Expr::new(kind, span),
    };
    *e = new;
}

/// FANUC's `a op b` written `a-b op 0` (exact under the Siemens tolerance) becomes the plain
/// `a op b` where both sides are provably integers, or multiples of one power of two, below
/// the bound where the tolerance could join two of them (`passes::integral`, run on the
/// translated programs, so on what the Siemens control computes): two such values differ
/// by at least the grid step, far more than 1e-12 of either, so the tolerance changes no
/// result. `LOC1-3<=0` → `LOC1<=3` for a counter stepped by 1.
pub fn plain_comparisons(programs: &mut [(ProgPlan, Program)]) {
    let names: BTreeSet<String> = programs.iter().map(|(plan, _)| plan.name.to_ascii_uppercase()).collect();
    let types: Vec<crate::lower::to_fanuc::integral::Types> =
        programs.iter().map(|(_, p)| p.params.iter().map(|prm| (prm.name.clone(), prm.ty)).collect()).collect();
    let with_types: Vec<(&Program, &crate::lower::to_fanuc::integral::Types)> =
        programs.iter().zip(&types).map(|((_, p), t)| (p, t)).collect();
    let exact = crate::lower::to_fanuc::integral::exact_differences(&with_types, &names);
    for ((_, p), spans) in programs.iter_mut().zip(exact) {
        if !spans.is_empty() {
            plain_in(&mut p.body, &spans);
        }
    }
}

fn plain_in(body: &mut [Stmt], spans: &BTreeSet<Span>) {
    for s in body {
        match &mut s.kind {
            StmtKind::Block(b) => b.items.iter_mut().for_each(|it| plain_item(it, spans)),
            StmtKind::If(i) => plain_expr(&mut i.cond, spans),
            StmtKind::While(w) => plain_expr(&mut w.cond, spans),
            StmtKind::Repeat(r) => plain_expr(&mut r.until, spans),
            StmtKind::Do(d) => {
                if let Some(c) = &mut d.cond {
                    plain_expr(c, spans);
                }
            }
            StmtKind::For(_) | StmtKind::Loop(_) => {}
        }
        for b in crate::ir::visit::child_bodies_mut(&mut s.kind) {
            plain_in(b, spans);
        }
    }
}

fn plain_item(it: &mut Item, spans: &BTreeSet<Span>) {
    match &mut it.kind {
        ItemKind::Assign { value, .. } => plain_expr(value, spans),
        ItemKind::Goto(g) => {
            if let Some(c) = &mut g.cond {
                plain_expr(c, spans);
            }
        }
        ItemKind::IfThen { cond, then } => {
            plain_expr(cond, spans);
            plain_item(then, spans);
        }
        _ => {}
    }
}

fn plain_expr(e: &mut Expr, spans: &BTreeSet<Span>) {
    match &mut e.kind {
        // Only the difference `lower` wrote (its 0 has the span of the difference); a
        // source's own `#1-2. LT 0.` stays as written, so a round trip keeps its form.
        ExprKind::Cmp(_, Tolerance::Relative, a, b)
            if spans.contains(&e.span) && literal(b) == Some(0.0) && b.span == a.span =>
        {
            if let ExprKind::Binary(BinOp::Sub, x, y) = &mut a.kind {
                let (x, y) = (
                    std::mem::replace(&mut **x, Expr::num(0.0, false, e.span)),
                    std::mem::replace(&mut **y, Expr::num(0.0, false, e.span)),
                );
                **a = x;
                **b = y;
            }
        }
        ExprKind::Cmp(_, _, a, b) | ExprKind::Binary(_, a, b) => {
            plain_expr(a, spans);
            plain_expr(b, spans);
        }
        ExprKind::Unary(_, a) => plain_expr(a, spans),
        ExprKind::Func(_, args) => args.iter_mut().for_each(|a| plain_expr(a, spans)),
        _ => {}
    }
}

fn int_part(e: Expr) -> Expr {
    // Already an integer (a truncation, a rounding, a bitwise result): another TRUNC would
    // only pile up on every round trip (`FIX[FIX[x]] AND 3`), and a chain `#1 AND #2 AND …`
    // would nest one TRUNC per operator, past the reader's bracket limit.
    if matches!(
        &e.kind,
        ExprKind::Func(Func::Trunc | Func::Round | Func::RoundUp, _)
            | ExprKind::Binary(BinOp::BitAnd | BinOp::BitOr | BinOp::BitXor, _, _)
    ) {
        return e;
    }
    match literal(&e) {
        Some(v) if v.fract() == 0.0 => e,
        _ => {
            let sp = e.span;
            func(Func::Trunc, vec![e], sp)
        }
    }
}

fn normalise_360(e: Expr, span: Span) -> Expr {
    bin(BinOp::Mod, bin(BinOp::Add, e, int(360, span)), int(360, span))
}

fn neg(e: Expr) -> Expr {
    let sp = e.span;
    Expr::new(ExprKind::Unary(UnOp::Neg, Box::new(e)), sp)
}

fn lower_func(ctx: &mut Ctx, f: Func, mut args: Vec<Expr>, span: Span, marks: &mut Vec<Stmt>) -> Expr {
    let nat = ctx.opts.source.nat;
    let first = args.first().cloned().unwrap_or_else(|| int(0, span));
    match f {
        Func::FanucFup => {
            let x = first;
            bin(
                BinOp::Sub,
                bin(BinOp::Sub, func(Func::RoundUp, vec![x.clone()], span), func(Func::Trunc, vec![x.clone()], span)),
                func(Func::RoundUp, vec![neg(x)], span),
            )
        }
        Func::FanucRound => func(Func::Round, args, span),
        Func::FanucAcos => func(Func::Acos, args, span),
        Func::FanucAsin => {
            let r = func(Func::Asin, args, span);
            if nat {
                r
            } else {
                normalise_360(r, span)
            }
        }
        Func::FanucAtan2 | Func::FanucAtan => {
            if f == Func::FanucAtan {
                args.push(int(1, span));
            }
            let r = func(Func::Atan2, args, span);
            if nat {
                r
            } else {
                normalise_360(r, span)
            }
        }
        Func::Pow => {
            let k = args.get(1).and_then(literal);
            match k {
                Some(k) if k.fract() == 0.0 && (0.0..=16.0).contains(&k) => {
                    let k = k as u32;
                    match k {
                        0 => int(1, span),
                        1 => first,
                        2 => func(Func::Pot, vec![first], span),
                        _ => (1..k).fold(first.clone(), |acc, _| bin(BinOp::Mul, acc, first.clone())),
                    }
                }
                _ => {
                    marks.extend(ctx.unsupported(
                        "NC369",
                        span,
                        "POW with an exponent that is not a literal 0..16",
                        "Siemens has only POT (square); write EXP(b*LN(a)) if a is positive and rounding is acceptable",
                    ));
                    int(0, span)
                }
            }
        }
        Func::Bin => digit_sum(first, 16.0, 10.0, span),
        Func::Bcd => digit_sum(first, 10.0, 16.0, span),
        Func::Adp => {
            marks.extend(ctx.unsupported(
                "NC369",
                span,
                "ADP (add a decimal point to an argument)",
                "pass the argument with a decimal point instead",
            ));
            first
        }
        other => func(other, args, span),
    }
}

/// Re-weights the base-`from` digits of `TRUNC(ABS(x))` by powers of `to` (8 digits): BIN
/// reads BCD nibbles as decimal digits, BCD writes decimal digits as nibbles. For BIN a
/// nibble above 9 is FANUC's alarm 111; the result is then divided by
/// `Π(1-TRUNC(nibble/10))`, which is 1 for valid BCD and 0 otherwise, so the same class of
/// alarm (arithmetic) stops the Siemens run.
fn digit_sum(x: Expr, from: f64, to: f64, span: Span) -> Expr {
    let xi = func(Func::Trunc, vec![func(Func::Abs, vec![x], span)], span);
    let mut acc: Option<Expr> = None;
    let mut valid: Option<Expr> = None;
    for k in 0..8 {
        let div = from.powi(k);
        let scaled = if k == 0 {
            xi.clone()
        } else {
            func(Func::Trunc, vec![bin(BinOp::Div, xi.clone(), num(div, span))], span)
        };
        let digit = bin(BinOp::Mod, scaled, num(from, span));
        if from == 16.0 {
            let ok = bin(
                BinOp::Sub,
                int(1, span),
                func(Func::Trunc, vec![bin(BinOp::Div, digit.clone(), int(10, span))], span),
            );
            valid = Some(match valid {
                None => ok,
                Some(v) => bin(BinOp::Mul, v, ok),
            });
        }
        let term = if k == 0 { digit } else { bin(BinOp::Mul, digit, num(to.powi(k), span)) };
        acc = Some(match acc {
            None => term,
            Some(a) => bin(BinOp::Add, a, term),
        });
    }
    let sum = acc.unwrap_or_else(|| int(0, span));
    match valid {
        Some(v) => bin(BinOp::Div, sum, v),
        None => sum,
    }
}

/// A Haas NGC general-purpose variable without a legacy number (`#10000..#10099`, …) that
/// got no R parameter (`varmap::build` placed every one the job uses, or said NC350 when the
/// R parameters ran out); `None` for any other number.
fn ngc_common(ctx: &mut Ctx, n: u32, span: Span) -> Option<Option<Stmt>> {
    if !(ctx.opts.source.haas_ngc && crate::dialect::fanuc::haas_vars::ngc_only(n)) {
        return None;
    }
    let what = format!("the Haas NGC variable #{n} without an R parameter (none was left for it)");
    let hint = "raise the R parameter count of the target profile, or map fewer variables (--var-map)";
    Some(ctx.unsupported("NC509", span, &what, hint))
}

/// A read of Haas machine data (`#20000+` settings, `#30000+` parameters): the Haas
/// machine's own values, which Siemens machine and setting data do not number alike; `None`
/// for any other variable.
fn haas_data(ctx: &mut Ctx, n: u32, span: Span) -> Option<Option<Stmt>> {
    if !ctx.opts.source.haas {
        return None;
    }
    let (kind, k) = crate::eval::haas_data::machine_data(i64::from(n))?;
    Some(ctx.unsupported(
        crate::eval::haas_data::CODE,
        span,
        &format!("#{n} (Haas {kind} {k}, the machine's own data)"),
        "Sinumerik machine and setting data ($MN_, $MC_, $SC_) are numbered otherwise; give the value the program needs in a variable",
    ))
}
