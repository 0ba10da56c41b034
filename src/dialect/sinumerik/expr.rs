//! Expressions: the flat `expr` pair (prefix operators, operands, infix operators) folded with
//! the Siemens precedence table (sources S1, S13 of `docs/semantics.md`) into IR, without recursion on operator
//! chains. Parentheses and calls recurse, but the driver caps their nesting before pest runs.

use super::errors::HINT;
use super::names;
use super::parse::Lower;
use super::Rule;
use crate::diag::Diagnostic;
use crate::dialect::limits::{self, MAX_EXPR_DEPTH};
use crate::ir::*;
use crate::span::Span;
use pest::iterators::Pair;

/// An infix operator and its binding power (higher binds tighter). All are left-associative.
#[derive(Clone, Copy)]
enum Op {
    Bin(BinOp),
    Cmp(CmpOp),
}

/// Level 2 (`* / DIV MOD`) down to level 11 (comparisons) of the Siemens table; level 1
/// (`NOT`, `B_NOT`, and the sign) is applied to single operands.
fn infix(rule: Rule) -> Option<(Op, u8)> {
    Some(match rule {
        Rule::op_mul => (Op::Bin(BinOp::Mul), 10),
        Rule::op_div => (Op::Bin(BinOp::Div), 10),
        Rule::op_intdiv => (Op::Bin(BinOp::IntDiv), 10),
        Rule::op_mod => (Op::Bin(BinOp::Mod), 10),
        Rule::op_add => (Op::Bin(BinOp::Add), 9),
        Rule::op_sub => (Op::Bin(BinOp::Sub), 9),
        Rule::op_band => (Op::Bin(BinOp::BitAnd), 8),
        Rule::op_bxor => (Op::Bin(BinOp::BitXor), 7),
        Rule::op_bor => (Op::Bin(BinOp::BitOr), 6),
        Rule::op_and => (Op::Bin(BinOp::And), 5),
        Rule::op_xor => (Op::Bin(BinOp::Xor), 4),
        Rule::op_or => (Op::Bin(BinOp::Or), 3),
        Rule::op_concat => (Op::Bin(BinOp::Concat), 2),
        Rule::op_eq => (Op::Cmp(CmpOp::Eq), 1),
        Rule::op_ne => (Op::Cmp(CmpOp::Ne), 1),
        Rule::op_gt => (Op::Cmp(CmpOp::Gt), 1),
        Rule::op_ge => (Op::Cmp(CmpOp::Ge), 1),
        Rule::op_lt => (Op::Cmp(CmpOp::Lt), 1),
        Rule::op_le => (Op::Cmp(CmpOp::Le), 1),
        _ => return None,
    })
}

fn combine(op: Op, a: Expr, b: Expr) -> Expr {
    let span = a.span.to(b.span);
    let kind = match op {
        Op::Bin(o) => ExprKind::Binary(o, Box::new(a), Box::new(b)),
        Op::Cmp(c) => ExprKind::Cmp(c, Tolerance::Relative, Box::new(a), Box::new(b)),
    };
    Expr::new(kind, span)
}

fn reduce(vals: &mut Vec<(Expr, u32)>, ops: &mut Vec<(Op, u8)>) -> u32 {
    if let (Some((op, _)), Some((b, db)), Some((a, da))) = (ops.pop(), vals.pop(), vals.pop()) {
        let d = 1 + da.max(db);
        vals.push((combine(op, a, b), d));
        return d;
    }
    0
}

impl Lower<'_, '_> {
    /// An `expr` pair → IR, by operator precedence (shunting-yard, left-associative).
    pub fn expr(&mut self, p: Pair<'_, Rule>) -> Expr {
        let whole = self.span(&p);
        let mut vals: Vec<(Expr, u32)> = Vec::new();
        let mut ops: Vec<(Op, u8)> = Vec::new();
        let mut prefixes: Vec<(UnOp, u32)> = Vec::new();
        let mut deepest = 0;
        for q in p.into_inner() {
            let rule = q.as_rule();
            if let Some((op, prec)) = infix(rule) {
                while ops.last().is_some_and(|&(_, top)| top >= prec) {
                    deepest = deepest.max(reduce(&mut vals, &mut ops));
                }
                ops.push((op, prec));
            } else {
                match rule {
                    Rule::op_not => prefixes.push((UnOp::Not, self.span(&q).lo)),
                    Rule::op_bnot => prefixes.push((UnOp::BitNot, self.span(&q).lo)),
                    Rule::op_neg => prefixes.push((UnOp::Neg, self.span(&q).lo)),
                    Rule::op_plus => {}
                    _ => {
                        let mut e = self.operand(q);
                        let mut d = limits::depth(&e);
                        // Innermost prefix first: `NOT -x` is `NOT (-x)`.
                        while let Some((op, lo)) = prefixes.pop() {
                            if d > MAX_EXPR_DEPTH {
                                break;
                            }
                            let span = Span::new(lo, e.span.hi);
                            e = Expr::new(ExprKind::Unary(op, Box::new(e)), span);
                            d += 1;
                        }
                        deepest = deepest.max(d);
                        vals.push((e, d));
                    }
                }
            }
            if deepest > MAX_EXPR_DEPTH || vals.len() > MAX_EXPR_DEPTH as usize {
                self.error(limits::too_deep(self.file(), whole, HINT));
                return Expr::num(0.0, false, whole);
            }
        }
        while !ops.is_empty() {
            deepest = deepest.max(reduce(&mut vals, &mut ops));
            // Stop as soon as it is too deep, so no deeper tree is ever built.
            if deepest > MAX_EXPR_DEPTH {
                self.error(limits::too_deep(self.file(), whole, HINT));
                return Expr::num(0.0, false, whole);
            }
        }
        vals.pop().map_or_else(|| Expr::num(0.0, false, whole), |(e, _)| e)
    }

    /// One operand pair → IR.
    pub fn operand(&mut self, q: Pair<'_, Rule>) -> Expr {
        let span = self.span(&q);
        match q.as_rule() {
            Rule::number => {
                let (v, point) = self.number_text(q.as_str(), span).unwrap_or((0.0, false));
                Expr::num(v, point, span)
            }
            Rule::hex_const | Rule::bin_const => {
                let t = q.as_str();
                let radix = if q.as_rule() == Rule::hex_const { 16 } else { 2 };
                let digits = &t[2..t.len() - 1];
                match u32::from_str_radix(digits, radix) {
                    Ok(v) => Expr::num(f64::from(v), false, span),
                    Err(_) => {
                        self.error(
                            Diagnostic::error("NC132", "constant does not fit in 32 bits")
                                .primary(self.file(), span, "too many digits")
                                .hint("Sinumerik INT values have 32 bits: at most 'HFFFFFFFF'"),
                        );
                        Expr::num(0.0, false, span)
                    }
                }
            }
            Rule::true_kw => Expr::num(1.0, false, span),
            Rule::false_kw => Expr::num(0.0, false, span),
            Rule::string => {
                let text = q.into_inner().next().map(|t| t.as_str().to_string()).unwrap_or_default();
                Expr::new(ExprKind::Str(text), span)
            }
            Rule::paren => match q.into_inner().find(|x| x.as_rule() == Rule::expr) {
                Some(e) => {
                    // The parentheses belong to the expression's span, so spans nest.
                    let inner = self.expr(e);
                    Expr { span, ..inner }
                }
                None => Expr::num(0.0, false, span),
            },
            Rule::func_call => self.func_call(q, span),
            Rule::r_param | Rule::r_indirect | Rule::sys_var | Rule::named_var => {
                let v = self.var(q);
                Expr::new(ExprKind::Var(Box::new(v)), span)
            }
            _ => Expr::num(0.0, false, span),
        }
    }

    fn func_call(&mut self, q: Pair<'_, Rule>, span: Span) -> Expr {
        let mut it = q.into_inner();
        let name_pair = it.next();
        let name = name_pair.as_ref().map(|n| n.as_str().to_ascii_uppercase()).unwrap_or_default();
        let name_span = name_pair.as_ref().map_or(span, |n| self.span(n));
        let args = match it.find(|x| x.as_rule() == Rule::arg_list) {
            Some(a) => self.args(a),
            None => Vec::new(),
        };
        let Some(b) = names::builtin(&name) else {
            let (msg, hint) = if name == "AC" || name == "IC" {
                (
                    format!("{name}(…) must be the whole value of an address"),
                    "write it alone after the address, e.g. `X=IC(R1+5)`".to_string(),
                )
            } else {
                (
                    format!("unknown function {name}"),
                    "the functions are SIN COS TAN ASIN ACOS ATAN2 SQRT ABS TRUNC ROUND ROUNDUP LN EXP POT MINVAL MAXVAL BOUND, and for strings STRLEN TOUPPER TOLOWER INDEX RINDEX SUBSTR NUMBER ISNUMBER; arrays use `[ ]`".to_string(),
                )
            };
            self.error(
                Diagnostic::error("NC123", msg).primary(self.file(), name_span, "not a function here").hint(hint),
            );
            return Expr::num(0.0, false, span);
        };
        let mut exprs = Vec::with_capacity(args.len());
        let mut omitted = false;
        for a in args {
            match a {
                Arg::Value(e) => exprs.push(e),
                _ => omitted = true,
            }
        }
        let substr_to_end = (b.func == Func::Substr && exprs.len() == 2)
            || (b.func == Func::GetT && exprs.len() == 1)
            || (b.func == Func::Sprint && !exprs.is_empty());
        if omitted || (exprs.len() != b.arity && !substr_to_end) {
            let want = match b.arity {
                1 => "one argument".to_string(),
                n => format!("{n} arguments"),
            };
            self.error(
                Diagnostic::error("NC124", format!("{name} takes {want}"))
                    .primary(self.file(), span, format!("called with {} argument(s)", exprs.len()))
                    .hint(format!("give {name} exactly {want}, none left empty")),
            );
        }
        Expr::new(ExprKind::Func(b.func, exprs), span)
    }

    /// The slots of an `arg_list`: values, and omitted entries between commas. A single
    /// empty slot is an empty list (`NAME()`).
    pub fn args(&mut self, p: Pair<'_, Rule>) -> Vec<Arg> {
        let slots: Vec<Pair<'_, Rule>> = p.into_inner().filter(|s| s.as_rule() == Rule::arg_slot).collect();
        if slots.len() == 1 && slots[0].as_str().trim().is_empty() {
            return Vec::new();
        }
        let mut out = Vec::with_capacity(slots.len());
        for s in slots {
            let span = self.span(&s);
            match s.into_inner().next() {
                Some(e) => out.push(Arg::Value(self.expr(e))),
                None => out.push(Arg::Omitted(span)),
            }
        }
        out
    }

    /// A variable pair (`r_param`, `r_indirect`, `sys_var`, `named_var`) → IR.
    pub fn var(&mut self, q: Pair<'_, Rule>) -> VarRef {
        let span = self.span(&q);
        match q.as_rule() {
            Rule::r_param => self.r_param(&q.as_str()[1..], span),
            Rule::r_indirect => {
                let e = match q.into_inner().find(|x| x.as_rule() == Rule::expr) {
                    Some(e) => self.expr(e),
                    None => Expr::num(0.0, false, span),
                };
                VarRef { kind: VarKind::RIndirect(Box::new(e)), span }
            }
            Rule::sys_var => {
                let mut it = q.into_inner();
                let name = it.next().map(|n| n.as_str().to_ascii_uppercase()).unwrap_or_default();
                let indices = match it.find(|x| x.as_rule() == Rule::subscripts) {
                    Some(s) => self.subscripts(s, true),
                    None => Vec::new(),
                };
                VarRef { kind: VarKind::System { name, indices }, span }
            }
            _ => {
                let mut it = q.into_inner();
                let name = it.next().map(|n| n.as_str().to_ascii_uppercase()).unwrap_or_default();
                let indices = match it.find(|x| x.as_rule() == Rule::subscripts) {
                    Some(s) => self.subscripts(s, names::axis_indexed(&name)),
                    None => Vec::new(),
                };
                VarRef { kind: VarKind::Named { name, indices }, span }
            }
        }
    }

    /// A FOR counter: `R1` or a name.
    pub fn simple_var(&mut self, q: &Pair<'_, Rule>) -> VarRef {
        let span = self.span(q);
        let name = q.as_str().to_ascii_uppercase();
        match q.as_rule() {
            Rule::r_param => self.r_param(&name[1..], span),
            _ => VarRef { kind: VarKind::Named { name, indices: vec![] }, span },
        }
    }

    /// Subscripts `[e, …]`. With `idents`, a bare name (axis `X`, frame component `TR`) is an
    /// identifier, not a variable.
    pub fn subscripts(&mut self, s: Pair<'_, Rule>, idents: bool) -> Vec<Expr> {
        let mut out = Vec::new();
        for e in s.into_inner().filter(|x| x.as_rule() == Rule::expr) {
            let ex = self.expr(e);
            let ex = match ex.kind {
                ExprKind::Var(v) if idents => match v.kind {
                    VarKind::Named { name, indices } if indices.is_empty() && !self.st.declared.contains_key(&name) => {
                        Expr::new(ExprKind::Ident(name), ex.span)
                    }
                    VarKind::R(n) => {
                        // `R1` as an axis index is still the R parameter.
                        Expr::new(ExprKind::Var(Box::new(VarRef { kind: VarKind::R(n), span: v.span })), ex.span)
                    }
                    other => Expr::new(ExprKind::Var(Box::new(VarRef { kind: other, span: v.span })), ex.span),
                },
                kind => Expr { kind, span: ex.span },
            };
            out.push(ex);
        }
        out
    }
}
