//! A call through a STRING variable that holds program names (`CALL SHAPE`,
//! `EXECSTRING(SHAPE)`; `lower::to_fanuc::prog_vars` made the variable the O number of the
//! program it names) to FANUC: `G65 P#n`, the same program for every name the variable can
//! hold. Exact when every program it can name takes no parameters (the Siemens call passes
//! none, so they are 0; `G65` without letters would leave them vacant) and leaves the units
//! as they were (the words pass follows the units across calls, which a callee known only at
//! run time would make depend on the path). G90/G91 a candidate leaves changed is merged over
//! the candidates, as where paths meet (an AC()/IC() word then reads `#4003`), and as a
//! direct call of one that changes it leaves it. Anything else is refused (NC558).

use super::*;

fn var_of<'a>(ctx: &'a Ctx, e: &Expr) -> Option<&'a str> {
    let ExprKind::Var(v) = &e.kind else { return None };
    let VarKind::Named { name, indices } = &v.kind else { return None };
    if !indices.is_empty() {
        return None;
    }
    ctx.prog_vars
        .get_key_value(name)
        .map(|(k, _)| k.as_str())
        .or_else(|| ctx.prog_var_why.get_key_value(name).map(|(k, _)| k.as_str()))
}

/// Whether `e` is a variable that holds program names.
pub(super) fn holds_names(ctx: &Ctx, e: &Expr) -> bool {
    var_of(ctx, e).is_some_and(|n| ctx.prog_vars.contains_key(n))
}

/// Why a call through the STRING variable `e` has no FANUC counterpart, if it is one the
/// analysis looked at.
pub(super) fn why_not<'a>(ctx: &'a Ctx, e: &Expr) -> Option<&'a String> {
    var_of(ctx, e).and_then(|n| ctx.prog_var_why.get(n))
}

pub(super) fn refuse(ctx: &mut Ctx, e: &Expr, span: Span) -> Option<Stmt> {
    let name = var_of(ctx, e).unwrap_or_default().to_string();
    let why = why_not(ctx, e).cloned().unwrap_or_default();
    let what = format!("a call through the STRING variable {name}, which cannot become an O number: {why}");
    let hint = "FANUC has no strings: a STRING variable called through becomes the O number of the program it names \
                when every write of it is a literal program name translated together with it (or \"\") and every \
                read a call or an ==/<> comparison with such a name";
    ctx.unsupported("NC559", span, &what, hint)
}

/// Lowers the call through a program-name variable; `None` when it was translated.
pub(super) fn call(ctx: &mut Ctx, c: Call, span: Span, m: &mut Modal, kept: &mut Vec<Item>) -> Option<Stmt> {
    let CallTarget::Computed(target) = c.target else { return None };
    let var = var_of(ctx, &target).unwrap_or_default().to_string();
    let names = ctx.prog_vars.get(&var).cloned().unwrap_or_default();
    let mut after = m.s;
    let mut first = true;
    for name in &names {
        let Some(callee) = ctx.callees.get(name).cloned() else {
            let what = format!("a call through {var}, which can name {name}, a program not translated with it");
            return ctx.unsupported("NC558", span, &what, &format!("translate {name} too: put {name}.SPF beside"));
        };
        let units = callee.effect.units != effects::UnitEffect::None;
        if !callee.params.is_empty() || units {
            let why = if callee.params.is_empty() {
                "leaves the units (G70/G71/G700/G710) changed"
            } else {
                "has parameters (the call passes none: Siemens gives them 0, G65 would leave them vacant)"
            };
            let what = format!("a call through {var}, which can name {name}, which {why}");
            return ctx.unsupported("NC558", span, &what, "call the programs by name (an IF over the names)");
        }
        let mut s = m.s;
        s.call(&callee.effect);
        after = if first { s } else { after.merge(s) };
        first = false;
    }
    if !m.s.units.one_unit() {
        let what = format!("a call through {var} where lengths and feeds are not in one known unit");
        let hint = "set both units with G700 or G710 before the call (a subprogram starts in its caller's units)";
        return ctx.unsupported("NC324", span, &what, hint);
    }
    let g65 = Call { kind: CallKind::G65, target: CallTarget::Computed(target), args: vec![], repeat: c.repeat };
    kept.push(item(ItemKind::Call(Box::new(g65)), span));
    m.s = after;
    None
}
