//! FANUC expressions from grammar pairs: precedence (functions, then `* / AND MOD`, then
//! `+ - OR XOR`), conditions versus values (`AND` between two conditions is logical, between
//! values bitwise), functions with their arity, and variable numbers.

use super::names::{self, FuncSpec};
use super::parse::{literal, Rule, Seg};
use crate::diag::Diagnostic;
use crate::dialect::limits::{self, MAX_EXPR_DEPTH};
use crate::dialect::ParseOptions;
use crate::ir::{BinOp, CmpOp, Expr, ExprKind, Func, Tolerance, UnOp, VarKind, VarRef};
use crate::span::Span;
use pest::iterators::Pair;

pub struct ExprCx<'s, 'a> {
    pub seg: &'s Seg<'a>,
    #[allow(dead_code)]
    pub opts: &'s ParseOptions,
}

impl ExprCx<'_, '_> {
    fn span(&self, p: &Pair<'_, Rule>) -> Span {
        let s = p.as_span();
        self.seg.span(s.start(), s.end())
    }

    fn err(&self, code: &'static str, msg: impl Into<String>, span: Span, label: &str) -> Diagnostic {
        Diagnostic::error(code, msg).primary(self.seg.file, span, label.to_string())
    }

    /// NC130 for the expression at `span` (see [`limits`]).
    fn too_deep(&self, span: Span) -> Diagnostic {
        limits::too_deep(self.seg.file, span, HINT)
    }

    /// `e` if no more than [`MAX_EXPR_DEPTH`] operations nest in it. For the nodes that wrap
    /// bounded operands (brackets, signs, functions, indirection), so each adds one level at
    /// most before it is measured.
    pub fn bounded(&self, e: Expr) -> Result<Expr, Diagnostic> {
        if limits::depth(&e) > MAX_EXPR_DEPTH {
            return Err(self.too_deep(e.span));
        }
        Ok(e)
    }
}

const HINT: &str = "split the calculation into several assignments with intermediate variables (#100…)";

/// Whether an expression is a condition (a comparison, or conditions joined logically).
pub fn is_cond(e: &Expr) -> bool {
    matches!(e.kind, ExprKind::Cmp(..) | ExprKind::Binary(BinOp::And | BinOp::Or | BinOp::Xor, _, _))
}

/// An expression used as a value (assignment, address, argument, index).
pub fn value(cx: &ExprCx<'_, '_>, p: Pair<'_, Rule>) -> Result<Expr, Diagnostic> {
    let e = any(cx, p)?;
    need_value(cx, e, "a value is needed here")
}

fn need_value(cx: &ExprCx<'_, '_>, e: Expr, why: &str) -> Result<Expr, Diagnostic> {
    if is_cond(&e) {
        return Err(cx
            .err("NC171", "a condition is not a value", e.span, why)
            .note("FANUC cannot store or compute with the result of EQ/NE/GT/GE/LT/LE")
            .hint("use the condition in IF[…] or WHILE[…], e.g. `IF[#1 LT 2] THEN #2=1`"));
    }
    Ok(e)
}

/// The bracketed condition of `IF[…]` / `WHILE[…]`.
pub fn condition(cx: &ExprCx<'_, '_>, p: Pair<'_, Rule>) -> Result<Expr, Diagnostic> {
    let e = any(cx, p)?;
    if !is_cond(&e) {
        return Err(cx
            .err("NC171", "a condition is needed here", e.span, "this is a value, not a comparison")
            .note("a FANUC condition compares two values with EQ, NE, GT, GE, LT or LE")
            .hint("write a comparison, e.g. `[#1 NE 0]`"));
    }
    Ok(e)
}

/// Any expression pair (expr, factor-level primaries, bracket, cond).
fn any(cx: &ExprCx<'_, '_>, p: Pair<'_, Rule>) -> Result<Expr, Diagnostic> {
    match p.as_rule() {
        Rule::expr => infix(cx, p),
        Rule::unsigned => {
            let n = literal(p.as_str());
            Ok(Expr::new(ExprKind::Num(n), cx.span(&p)))
        }
        Rule::variable => variable_expr(cx, p),
        Rule::bracket => {
            let span = cx.span(&p);
            let inner = p.into_inner().nth(1);
            match inner {
                Some(c) => {
                    let e = cond(cx, c)?;
                    Ok(Expr { span, ..e })
                }
                None => Err(cx.err("NC199", "empty brackets", span, "here")),
            }
        }
        Rule::cond => cond(cx, p),
        Rule::atan_call => atan(cx, p),
        Rule::func_call => func(cx, p),
        _ => {
            let span = cx.span(&p);
            Err(cx
                .err("NC199", "unexpected expression form", span, "here")
                .hint("please report this block (a bug in nctrans)"))
        }
    }
}

fn cond(cx: &ExprCx<'_, '_>, p: Pair<'_, Rule>) -> Result<Expr, Diagnostic> {
    let mut it = p.into_inner();
    let lhs = match it.next() {
        Some(e) => any(cx, e)?,
        None => return Err(cx.err("NC199", "empty condition", Span::default(), "here")),
    };
    let Some(op) = it.next() else {
        return Ok(lhs);
    };
    let rhs = match it.next() {
        Some(e) => any(cx, e)?,
        None => return Err(cx.err("NC199", "comparison without right side", cx.span(&op), "here")),
    };
    let op_span = cx.span(&op);
    let cmp = match op.as_str().to_ascii_uppercase().as_str() {
        "EQ" => CmpOp::Eq,
        "NE" => CmpOp::Ne,
        "GT" => CmpOp::Gt,
        "GE" => CmpOp::Ge,
        "LT" => CmpOp::Lt,
        _ => CmpOp::Le,
    };
    for side in [&lhs, &rhs] {
        if is_cond(side) {
            return Err(cx
                .err("NC171", "a comparison cannot compare conditions", side.span, "this is a condition")
                .secondary(cx.seg.file, op_span, "compared here")
                .hint("join conditions with AND/OR/XOR in brackets: `[[#1 EQ 1] AND [#2 GT 3]]`"));
        }
    }
    let span = lhs.span.to(rhs.span);
    cx.bounded(Expr::new(ExprKind::Cmp(cmp, Tolerance::Exact, Box::new(lhs), Box::new(rhs)), span))
}

/// `factor (op factor)*` with two precedence levels, left associative. Without recursion,
/// and each term's depth is counted as it is built, so a chain longer than
/// [`MAX_EXPR_DEPTH`] is refused before its tree grows deeper than that.
fn infix(cx: &ExprCx<'_, '_>, p: Pair<'_, Rule>) -> Result<Expr, Diagnostic> {
    let whole = cx.span(&p);
    let mut it = p.into_inner();
    let measured = |e: Expr| -> (u32, Expr) { (limits::depth(&e), e) };
    let (mut depth, mut current) = match it.next() {
        Some(f) => measured(factor(cx, f)?),
        None => return Err(cx.err("NC199", "empty expression", Span::default(), "here")),
    };
    // Add-level operands waiting for the mul-level term to their right, and the operator
    // after each.
    let mut terms: Vec<(Expr, u32)> = Vec::new();
    let mut ops: Vec<Pair<'_, Rule>> = Vec::new();
    while let Some(op) = it.next() {
        let (d, rhs) = match it.next() {
            Some(f) => measured(factor(cx, f)?),
            None => return Err(cx.err("NC199", "operator without operand", cx.span(&op), "here")),
        };
        if op.as_rule() == Rule::mul_op {
            current = binary(cx, &op, current, rhs)?;
            depth = 1 + depth.max(d);
            if depth > MAX_EXPR_DEPTH {
                return Err(cx.too_deep(whole));
            }
        } else {
            terms.push((current, depth));
            ops.push(op);
            (current, depth) = (rhs, d);
        }
    }
    // Fold the add level left to right: a - b + c = (a - b) + c.
    terms.push((current, depth));
    let mut terms = terms.into_iter();
    let Some((mut acc, mut acc_depth)) = terms.next() else {
        return Err(cx.err("NC199", "empty expression", Span::default(), "here"));
    };
    for (op, (t, d)) in ops.iter().zip(terms) {
        acc = binary(cx, op, acc, t)?;
        acc_depth = 1 + acc_depth.max(d);
        if acc_depth > MAX_EXPR_DEPTH {
            return Err(cx.too_deep(whole));
        }
    }
    Ok(acc)
}

fn binary(cx: &ExprCx<'_, '_>, op: &Pair<'_, Rule>, a: Expr, b: Expr) -> Result<Expr, Diagnostic> {
    let word = op.as_str().to_ascii_uppercase();
    let (ca, cb) = (is_cond(&a), is_cond(&b));
    let logical = |l: BinOp, bit: BinOp| -> Result<BinOp, Diagnostic> {
        match (ca, cb) {
            (true, true) => Ok(l),
            (false, false) => Ok(bit),
            _ => {
                let (c, v) = if ca { (&a, &b) } else { (&b, &a) };
                Err(cx
                    .err("NC171", format!("`{word}` joins a condition and a value"), cx.span(op), "here")
                    .secondary(cx.seg.file, c.span, "a condition")
                    .secondary(cx.seg.file, v.span, "a value")
                    .note(format!("`{word}` is bitwise between two values and logical between two conditions"))
                    .hint("put each comparison in its own brackets: `[[#1 EQ 1] AND [#2 GT 3]]`"))
            }
        }
    };
    let bop = match word.as_str() {
        "+" => BinOp::Add,
        "-" => BinOp::Sub,
        "*" => BinOp::Mul,
        "/" => BinOp::Div,
        "MOD" => BinOp::Mod,
        "AND" => logical(BinOp::And, BinOp::FanucBitAnd)?,
        "OR" => logical(BinOp::Or, BinOp::FanucBitOr)?,
        _ => logical(BinOp::Xor, BinOp::FanucBitXor)?,
    };
    if matches!(bop, BinOp::Add | BinOp::Sub | BinOp::Mul | BinOp::Div | BinOp::Mod) {
        for side in [&a, &b] {
            if is_cond(side) {
                return Err(cx
                    .err("NC171", format!("cannot compute `{word}` with a condition"), side.span, "this is a condition")
                    .hint("a comparison can only be used in IF[…]/WHILE[…] or joined with AND/OR/XOR"));
            }
        }
    }
    let span = a.span.to(b.span);
    Ok(Expr::new(ExprKind::Binary(bop, Box::new(a), Box::new(b)), span))
}

fn factor(cx: &ExprCx<'_, '_>, p: Pair<'_, Rule>) -> Result<Expr, Diagnostic> {
    let span = cx.span(&p);
    let mut it = p.into_inner();
    let Some(mut first) = it.next() else {
        return Err(cx.err("NC199", "empty operand", span, "here"));
    };
    let mut neg = None;
    // A run of signs folds to one: an odd number of `-` is a minus (`+ -` is `-`).
    while first.as_rule() == Rule::sign {
        neg = Some((first.as_str() == "-") != neg.unwrap_or(false));
        match it.next() {
            Some(n) => first = n,
            None => return Err(cx.err("NC199", "sign without operand", span, "here")),
        }
    }
    // A sign directly before a literal is part of the number (`-5` is the number −5).
    if first.as_rule() == Rule::unsigned {
        let n = literal(first.as_str());
        let v = if neg == Some(true) { -n.value } else { n.value };
        return Ok(Expr::num(v, n.point, span));
    }
    let e = any(cx, first)?;
    match neg {
        None => Ok(e),
        Some(minus) => {
            let e = need_value(cx, e, "a sign needs a value")?;
            if minus {
                cx.bounded(Expr::new(ExprKind::Unary(UnOp::Neg, Box::new(e)), span))
            } else {
                Ok(Expr { span, ..e })
            }
        }
    }
}

/// `#n` / `#[e]` as a value: `#0` is the vacant value.
fn variable_expr(cx: &ExprCx<'_, '_>, p: Pair<'_, Rule>) -> Result<Expr, Diagnostic> {
    let v = variable_ref(cx, p)?;
    Ok(match v.kind {
        VarKind::Hash(0) => Expr::new(ExprKind::Vacant, v.span),
        _ => Expr::new(ExprKind::Var(Box::new(v.clone())), v.span),
    })
}

/// `#n` / `#[e]` as a variable reference (assignment targets keep `#0` for the caller to reject).
pub fn variable_ref(cx: &ExprCx<'_, '_>, p: Pair<'_, Rule>) -> Result<VarRef, Diagnostic> {
    let span = cx.span(&p);
    let Some(mut inner) = p.into_inner().next() else {
        return Err(cx.err("NC199", "variable without number", span, "here"));
    };
    let mut bit = None;
    if inner.as_rule() == Rule::var_number {
        let mut parts = inner.clone().into_inner();
        if let Some(num) = parts.next() {
            inner = num;
        }
        bit = parts.next();
    }
    if let Some(bit) = bit {
        let text = format!("#{}{}", inner.as_str(), bit.as_str());
        return Err(cx
            .err("NC511", format!("the parameter bit read `{text}` is not read yet"), span, "a bit of a machine parameter")
            .note("on a Haas NGC #30000+ are the machine parameters and `.n` one bit of one; they are machine data, not the program's")
            .hint("read the bit as a number the program is given: #1=… (value of the bit) set with --set"));
    }
    if inner.as_rule() == Rule::bracket {
        let e = value(cx, inner)?;
        if limits::depth(&e) >= MAX_EXPR_DEPTH {
            return Err(cx.too_deep(span));
        }
        return Ok(VarRef { kind: VarKind::HashIndirect(Box::new(e)), span });
    }
    let n = inner.as_str().parse::<u32>().map_err(|_| {
        cx.err("NC177", "variable number too large", span, "no such variable")
            .hint("FANUC variable numbers have at most 8 digits")
    })?;
    check_var_number(cx.seg, n, span)?;
    // Haas NGC: `#10100` is the variable `#100` (the text keeps the NGC number).
    let n = if cx.opts.semantics.haas_ngc { super::haas_vars::legacy(n).unwrap_or(n) } else { n };
    Ok(VarRef { kind: VarKind::Hash(n), span })
}

/// Numbers between the local and common ranges do not exist on any FANUC control.
pub fn check_var_number(seg: &Seg<'_>, n: u32, span: Span) -> Result<(), Diagnostic> {
    if (34..=99).contains(&n) {
        return Err(Diagnostic::error("NC177", format!("there is no variable #{n}"))
            .primary(seg.file, span, "not a FANUC variable")
            .note("locals are #1..#33, commons #100..#199 and #500..#999, system variables #1000 and up (alarm 115 otherwise)")
            .hint("use a local (#1..#33) or a common variable (#100..#199, #500..#999)"));
    }
    Ok(())
}

fn func(cx: &ExprCx<'_, '_>, p: Pair<'_, Rule>) -> Result<Expr, Diagnostic> {
    let span = cx.span(&p);
    let mut it = p.into_inner();
    let Some(name_pair) = it.next() else {
        return Err(cx.err("NC199", "function without name", span, "here"));
    };
    let name = name_pair.as_str().to_ascii_uppercase();
    let name_span = cx.span(&name_pair);
    let mut args = Vec::new();
    for a in it {
        if a.as_rule() == Rule::cond {
            let e = cond(cx, a)?;
            args.push(need_value(cx, e, "function arguments are values")?);
        }
    }
    let Some(FuncSpec { func, arity, .. }) = names::function(&name) else {
        let mut d = cx
            .err("NC165", format!("unknown function `{name}`"), name_span, "not a FANUC function")
            .note(format!("FANUC functions: {}", names::FUNCTION_LIST));
        d = d.hint(names::function_hint(&name));
        return Err(d);
    };
    if args.len() != arity {
        return Err(cx
            .err(
                "NC166",
                format!("`{name}` takes {arity} argument{}, found {}", plural(arity), args.len()),
                span,
                "wrong number of arguments",
            )
            .hint(names::function_usage(&name)));
    }
    cx.bounded(Expr::new(ExprKind::Func(func, args), span))
}

fn plural(n: usize) -> &'static str {
    if n == 1 {
        ""
    } else {
        "s"
    }
}

/// `ATAN[a]/[b]`, `ATAN[a,b]` (both two-argument) and `ATAN[a]`.
fn atan(cx: &ExprCx<'_, '_>, p: Pair<'_, Rule>) -> Result<Expr, Diagnostic> {
    let span = cx.span(&p);
    let mut args = Vec::new();
    let mut comma = false;
    let mut slash = None;
    for a in p.into_inner() {
        match a.as_rule() {
            Rule::cond => {
                let e = cond(cx, a)?;
                args.push(need_value(cx, e, "ATAN arguments are values")?);
            }
            Rule::comma => comma = true,
            Rule::atan_slash => slash = Some(cx.span(&a)),
            _ => {}
        }
    }
    if let (true, Some(s)) = (comma, slash) {
        return Err(cx
            .err("NC166", "ATAN takes two arguments, found three", s, "a third argument")
            .hint("write either `ATAN[y]/[x]` or `ATAN[y,x]`"));
    }
    let f = if args.len() == 2 { Func::FanucAtan2 } else { Func::FanucAtan };
    cx.bounded(Expr::new(ExprKind::Func(f, args), span))
}
