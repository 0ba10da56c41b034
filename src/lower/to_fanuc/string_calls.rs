//! Siemens `CALL PROG_VAR` (the program name in a STRING variable) to FANUC, where the name
//! is known at translation time: a scalar STRING variable written exactly once, with a
//! constant text (its DEF initial value, or one assignment on the program's top level), in
//! a program without jumps (no `GOTO…`, `CASE`, section repetition: none can pass the
//! assignment or come back before it), and used only as call targets, is the call of that
//! program by name (`DEF STRING[32] PN="L100"` … `CALL PN` is `CALL "L100"`), and the variable
//! goes (FANUC has no strings). The callee then translates as any named call: its O number,
//! its arguments. Any other use of such a variable stays as it was (NC310, NC303).

use crate::ir::*;

/// The STRING variables of `p` that only name a called program, each with the name.
fn known(p: &Program) -> Vec<(String, String)> {
    let mut strings: Vec<(String, Option<String>)> = Vec::new();
    let mut jumps = false;
    crate::ir::visit::walk_stmts(&p.body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            for it in &b.items {
                match &it.kind {
                    ItemKind::Def(d) if matches!(d.ty, DataType::String(_)) && d.scope.is_none() => {
                        for v in d.vars.iter().filter(|v| v.dims.is_empty()) {
                            let init = match &v.init {
                                Some(Init::Value(Expr { kind: ExprKind::Str(t), .. })) => Some(t.clone()),
                                _ => None,
                            };
                            strings.push((v.name.clone(), init));
                        }
                    }
                    ItemKind::Goto(_) | ItemKind::Case(_) | ItemKind::RepeatSection(_) => jumps = true,
                    _ => {}
                }
            }
        }
    });
    if jumps || strings.is_empty() {
        return Vec::new();
    }
    let mut out = Vec::new();
    for (name, init) in strings {
        let mut writes: Vec<Option<String>> = init.iter().cloned().map(Some).collect();
        let (mut calls, mut other_uses, mut nested_write) = (0, 0, false);
        // Top-level assignments (one block of the program body).
        for s in &p.body {
            if let StmtKind::Block(b) = &s.kind {
                for it in &b.items {
                    if let ItemKind::Assign { target, value } = &it.kind {
                        if is_var(target, &name) {
                            writes.push(match &value.kind {
                                ExprKind::Str(t) => Some(t.clone()),
                                _ => None,
                            });
                        }
                    }
                }
            }
        }
        crate::ir::visit::walk_stmts(&p.body, &mut |s| {
            if let StmtKind::Block(b) = &s.kind {
                for it in &b.items {
                    match &it.kind {
                        ItemKind::Call(c) if matches!(&c.target, CallTarget::Computed(e) if is_use(e, &name)) => {
                            calls += 1;
                        }
                        ItemKind::Assign { target, value } if is_var(target, &name) => {
                            other_uses += uses(value, &name);
                        }
                        _ => {
                            other_uses +=
                                crate::ir::visit::item_exprs(it).iter().map(|e| uses(e, &name)).sum::<usize>();
                        }
                    }
                }
            }
        });
        // Assignments inside structures are writes the top-level count did not see.
        let mut all_writes = 0;
        crate::ir::visit::walk_stmts(&p.body, &mut |s| {
            if let StmtKind::Block(b) = &s.kind {
                all_writes += b
                    .items
                    .iter()
                    .filter(|it| matches!(&it.kind, ItemKind::Assign { target, .. } if is_var(target, &name)))
                    .count();
            }
        });
        nested_write |= all_writes + usize::from(init.is_some()) != writes.len();
        if let [Some(text)] = writes.as_slice() {
            if calls > 0 && other_uses == 0 && !nested_write && before_uses(p, &name, init.is_some()) {
                out.push((name, text.to_ascii_uppercase()));
            }
        }
    }
    out
}

fn is_var(v: &VarRef, name: &str) -> bool {
    matches!(&v.kind, VarKind::Named { name: n, indices } if indices.is_empty() && n == name)
}

fn is_use(e: &Expr, name: &str) -> bool {
    matches!(&e.kind, ExprKind::Var(v) if is_var(v, name))
}

fn uses(e: &Expr, name: &str) -> usize {
    usize::from(is_use(e, name)) + e.children().into_iter().map(|c| uses(c, name)).sum::<usize>()
}

/// The one write comes before every call in the top-level order (a DEF initial value always does).
fn before_uses(p: &Program, name: &str, by_init: bool) -> bool {
    if by_init {
        return true;
    }
    let mut assigned = false;
    for s in &p.body {
        let mut call_here = false;
        crate::ir::visit::walk_stmts(std::slice::from_ref(s), &mut |x| {
            if let StmtKind::Block(b) = &x.kind {
                call_here |= b.items.iter().any(
                    |it| matches!(&it.kind, ItemKind::Call(c) if matches!(&c.target, CallTarget::Computed(e) if is_use(e, name))),
                );
            }
        });
        if let StmtKind::Block(b) = &s.kind {
            for it in &b.items {
                match &it.kind {
                    ItemKind::Assign { target, .. } if is_var(target, name) => assigned = true,
                    ItemKind::Call(c)
                        if matches!(&c.target, CallTarget::Computed(e) if is_use(e, name)) && !assigned =>
                    {
                        return false;
                    }
                    _ => {}
                }
            }
        } else if call_here && !assigned {
            return false;
        }
    }
    true
}

/// `p` with every call through a known STRING variable made a call by name, and the variable
/// (its DEF and its assignment) gone; `None` when there is none.
pub fn resolve(p: &Program) -> Option<Program> {
    let normal = super::prog_vars::execstring_as_call(p);
    let p = normal.as_ref().unwrap_or(p);
    let known = known(p);
    if known.is_empty() {
        return normal;
    }
    let mut p = p.clone();
    let name_of = |n: &str| known.iter().find(|(k, _)| k == n).map(|(_, v)| v.clone());
    p.body = crate::lower::map_bodies(std::mem::take(&mut p.body), &mut |list| {
        list.into_iter()
            .filter_map(|mut s| {
                if let StmtKind::Block(b) = &mut s.kind {
                    let had = b.items.len();
                    b.items.retain_mut(|it| match &mut it.kind {
                        ItemKind::Def(d) => {
                            d.vars.retain(|v| name_of(&v.name).is_none() || !v.dims.is_empty());
                            !d.vars.is_empty()
                        }
                        ItemKind::Assign { target, .. } => {
                            !matches!(&target.kind, VarKind::Named { name, indices } if indices.is_empty() && name_of(name).is_some())
                        }
                        ItemKind::Call(c) => {
                            if let CallTarget::Computed(Expr { kind: ExprKind::Var(v), .. }) = &c.target {
                                if let VarKind::Named { name, .. } = &v.kind {
                                    if let Some(t) = name_of(name) {
                                        c.target = CallTarget::Name(t);
                                    }
                                }
                            }
                            true
                        }
                        _ => true,
                    });
                    let meta = &b.meta;
                    if had > 0 && b.items.is_empty() && meta.label.is_none() && meta.number.is_none() && meta.comments.is_empty() {
                        return None;
                    }
                }
                Some(s)
            })
            .collect()
    });
    Some(p)
}

/// The names a unit calls, with the calls through known STRING variables resolved: the
/// subprograms a translation to FANUC loads beside its input.
pub fn called_names(unit: &Unit) -> Vec<String> {
    let resolved: Vec<Program> = unit.programs.iter().map(|p| resolve(p).unwrap_or_else(|| p.clone())).collect();
    let u = Unit { programs: resolved, ..unit.clone() };
    let mut names = crate::ir::visit::called_names(&u);
    for n in super::prog_vars::written_names(unit) {
        if !names.contains(&n) {
            names.push(n);
        }
    }
    names
}

/// Whether `unit` calls a program named `"L"<<n` (built at run time).
pub fn calls_built_l(unit: &Unit) -> bool {
    let mut found = false;
    for p in &unit.programs {
        crate::ir::visit::walk_stmts(&p.body, &mut |s| {
            if let StmtKind::Block(b) = &s.kind {
                found |= b.items.iter().any(|it| match &it.kind {
                    ItemKind::Call(c) => super::integral::built_l_number(&c.target).is_some(),
                    ItemKind::IfThen { then, .. } => {
                        matches!(&then.kind, ItemKind::Call(c) if super::integral::built_l_number(&c.target).is_some())
                    }
                    _ => false,
                });
            }
        });
    }
    found
}
