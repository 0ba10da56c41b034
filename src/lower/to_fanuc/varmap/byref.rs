//! Siemens `VAR` (by-reference) parameters on FANUC: the caller passes the *number* of its
//! variable as the G65 argument, and the callee reads and writes it as `#[#n]`.
//!
//! This is exact only where the caller's variable has a number every call level shares: a
//! common variable (`#100`..`#199`, `#500`..`#999`: R parameters, the main program's DEF
//! variables, an element of an array stored there, global user data at its retained home,
//! or the caller's own VAR parameter, which already is such a number). FANUC locals `#1`..`#33` are one set per call level, so a
//! subprogram's own DEF variable or value parameter (a local) has no number its callee could
//! reach: such an argument is refused (NC381). Aliasing needs no care: the same variable
//! passed twice, or a VAR parameter and a direct use of the same R parameter, are the same
//! `#n`, as on the Siemens control where both name the one variable.
//!
//! The parameter's type and shape must be the variable's (NC382): Siemens converts a value
//! written through the reference to the variable's type, the translation rounds it for the
//! parameter's (`exprs`), and the two agree only when they are the same.

use super::*;

/// A VAR parameter of the program being mapped: the local holding the number, and its
/// dimensions.
pub struct RefParam {
    pub var: u32,
    pub dims: Vec<u32>,
}

/// What `address_of` needs to know about the program whose calls it rewrites.
pub struct Scope<'a> {
    pub map: &'a HashMap<String, (u32, Vec<u32>)>,
    pub refs: &'a HashMap<String, RefParam>,
    pub r_target: &'a dyn Fn(u32) -> u32,
    pub r_offset: Option<u32>,
    pub info: &'a ProgInfo,
    /// The parameters of each callee, by its O number.
    pub callees: &'a HashMap<u32, Vec<Param>>,
}

/// Replaces each argument of a G65 for a VAR parameter by its variable's number. Runs before
/// the variables are rewritten (it reads names); subscripts stay as written for that rewrite.
pub fn rewrite_calls(ctx: &mut Ctx, body: &mut [Stmt], scope: &Scope) {
    for s in body {
        match &mut s.kind {
            StmtKind::Block(b) => {
                for it in &mut b.items {
                    if let ItemKind::Call(c) = &mut it.kind {
                        call(ctx, c, scope);
                    }
                }
            }
            other => {
                for child in crate::ir::visit::child_bodies_mut(other) {
                    rewrite_calls(ctx, child, scope);
                }
            }
        }
    }
}

fn call(ctx: &mut Ctx, c: &mut Call, scope: &Scope) {
    let (CallKind::G65, CallTarget::Number(n)) = (c.kind, &c.target) else { return };
    let Some(params) = scope.callees.get(n) else { return };
    for (k, p) in params.iter().enumerate() {
        if !p.by_ref {
            continue;
        }
        let Some(Arg::Letter { value, .. }) = c.args.get_mut(k) else { continue };
        let ExprKind::Var(v) = &value.kind else {
            // `words` passed only variables; never a value where a number is expected.
            let what = format!("argument for VAR parameter {} that is not a variable", p.name);
            ctx.unsupported("NC380", value.span, &what, "pass an R parameter or a DEF variable");
            continue;
        };
        let v = (**v).clone();
        if let Some(addr) = address_of(ctx, &v, p, scope) {
            *value = addr;
        }
    }
}

/// The number of variable `v` as an expression, after checking it can be passed for `p`.
fn address_of(ctx: &mut Ctx, v: &VarRef, p: &Param, scope: &Scope) -> Option<Expr> {
    let span = v.span;
    let (ty, dims, indexed) = match &v.kind {
        VarKind::R(_) | VarKind::RIndirect(_) => (DataType::Real, vec![], false),
        VarKind::Named { name, indices } => match scope.info.types.get(name) {
            Some((ty, dims)) => (*ty, dims.clone(), !indices.is_empty()),
            // Global user data lives in retained commons every call level shares: its
            // number is passed like a main program's variable's (its home is in `map`).
            None => match super::gud::lookup(&ctx.globals, name) {
                Some(g) => (g.def.ty, g.dims().to_vec(), !indices.is_empty()),
                None => return None, // reported as undeclared by the mapping
            },
        },
        _ => {
            let what = format!("this variable for VAR parameter {}", p.name);
            ctx.unsupported("NC381", span, &what, "pass an R parameter or a DEF variable");
            return None;
        }
    };
    let shape_ok = if p.dims.is_empty() { dims.is_empty() || indexed } else { !indexed && dims == p.dims };
    if ty != p.ty || !shape_ok {
        let shape = |d: &[u32]| {
            if d.is_empty() {
                String::new()
            } else {
                format!("[{}]", d.iter().map(u32::to_string).collect::<Vec<_>>().join(","))
            }
        };
        let given =
            if indexed { format!("an element of {ty}{}", shape(&dims)) } else { format!("{ty}{}", shape(&dims)) };
        let what = format!("{given} passed for VAR parameter {} {}{}", p.name, p.ty, shape(&p.dims));
        let hint = "pass a variable of the parameter's own type and size (Siemens requires it for VAR)";
        ctx.unsupported("NC382", span, &what, hint);
        return None;
    }
    match &v.kind {
        VarKind::R(n) => Some(num((scope.r_target)(*n) as f64, span)),
        VarKind::RIndirect(e) => Some(bin(BinOp::Add, (**e).clone(), num(scope.r_offset.unwrap_or(500) as f64, span))),
        VarKind::Named { name, indices } => {
            if let Some(rp) = scope.refs.get(name) {
                let base = var_expr(&VarRef { kind: VarKind::Hash(rp.var), span });
                return Some(plus_offset(base, &rp.dims, indices, span));
            }
            let (n, dims) = scope.map.get(name)?;
            if *n <= 33 {
                let what = format!("{name}, a local variable of this subprogram, passed for VAR parameter {}", p.name);
                let hint = "FANUC locals #1..#33 belong to one call level: keep the variable in an R parameter \
                            or in the main program, or map it to a common variable with --var-map";
                ctx.unsupported("NC381", span, &what, hint);
                return None;
            }
            let off = linear(dims, indices, span);
            Some(match &off.kind {
                ExprKind::Num(x) => num(f64::from(*n) + x.value, span),
                _ => bin(BinOp::Add, off, num(f64::from(*n), span)),
            })
        }
        _ => None,
    }
}

/// `base` plus the element offset of `indices` (`#7`, `#7+1.`, `#7+[#3*2.+#4]`).
pub fn plus_offset(base: Expr, dims: &[u32], indices: &[Expr], span: Span) -> Expr {
    if indices.is_empty() {
        return base;
    }
    match linear(dims, indices, span) {
        Expr { kind: ExprKind::Num(n), .. } if n.value == 0.0 => base,
        off => bin(BinOp::Add, base, off),
    }
}

/// The row-major element offset of `indices` in an array of `dims`, folded when constant.
pub fn linear(dims: &[u32], indices: &[Expr], span: Span) -> Expr {
    let consts: Option<Vec<f64>> = indices
        .iter()
        .map(|i| match &i.kind {
            ExprKind::Num(n) => Some(n.value),
            _ => None,
        })
        .collect();
    if let Some(c) = consts {
        let mut lin = 0.0;
        for (k, v) in c.iter().enumerate() {
            lin = lin * dims.get(k).copied().unwrap_or(1) as f64 + v;
        }
        if lin >= 0.0 && lin.fract() == 0.0 {
            return num(lin, span);
        }
    }
    let mut it = indices.iter().cloned();
    let mut lin = it.next().unwrap_or_else(|| num(0.0, span));
    for (k, i) in it.enumerate() {
        let d = dims.get(k + 1).copied().unwrap_or(1);
        lin = bin(BinOp::Add, bin(BinOp::Mul, lin, num(d as f64, span)), i);
    }
    lin
}
