//! M30/M2 in a called FANUC program: FANUC ends the whole run there, Siemens returns to the
//! caller (docs/semantics.md, "M2/M30 in a subprogram"). The called program sets a global
//! end flag (an R parameter the variable map leaves free) to the end code before its end, which
//! stays (returning when called, ending the run when the file runs as a main program); after
//! each call of a program that can end the run, the caller tests the flag and ends with the
//! same code (which in a called program returns again), so the end reaches the main
//! program. The main program clears the flag at its start (R parameters outlive a run).

use super::*;

/// FANUC program numbers whose call may end the run, with the end codes it may end with.
pub fn ending(programs: &[(FileId, &Program)], progs: &[ProgPlan]) -> BTreeMap<u32, BTreeSet<u8>> {
    let mut out: BTreeMap<u32, BTreeSet<u8>> = BTreeMap::new();
    loop {
        let mut changed = false;
        for ((_, p), plan) in programs.iter().zip(progs) {
            let (Some(n), false) = (plan.number, plan.role == Role::Main) else { continue };
            let mut codes = BTreeSet::new();
            crate::ir::visit::walk_stmts(&p.body, &mut |s| {
                if let StmtKind::Block(b) = &s.kind {
                    for it in block_items(b) {
                        match &it.kind {
                            ItemKind::End { code } => {
                                codes.insert(code_number(*code));
                            }
                            ItemKind::Call(c) => {
                                if let Some(more) = called(c).and_then(|m| out.get(&m)) {
                                    codes.extend(more.iter().copied());
                                }
                            }
                            _ => {}
                        }
                    }
                }
            });
            if !codes.is_empty() && out.get(&n) != Some(&codes) {
                out.insert(n, codes);
                changed = true;
            }
        }
        if !changed {
            return out;
        }
    }
}

fn code_number(c: EndCode) -> u8 {
    match c {
        EndCode::M30 => 30,
        EndCode::M2 => 2,
    }
}

fn called(c: &Call) -> Option<u32> {
    match (c.kind, &c.target) {
        (CallKind::M98 | CallKind::G65 | CallKind::G66, CallTarget::Number(n)) => Some(*n),
        _ => None,
    }
}

fn flag(r: u32, span: Span) -> Expr {
    var_expr(VarKind::R(r), span)
}

fn flag_is(r: u32, code: u8, span: Span) -> Expr {
    Expr::new(
        // The flag only ever holds 0, 2 or 30: Siemens' relative equality is exact on them,
        // so the test reads as written (`IF R299==30`), not in the exact difference form.
        ExprKind::Cmp(CmpOp::Eq, Tolerance::Relative, Box::new(flag(r, span)), Box::new(int(code.into(), span))),
        span,
    )
}

/// Rewrites the body of program `ctx.cur` (FANUC IR, before `gotos`): ends in a called
/// program become flag-and-return, calls of ending programs get their test.
pub fn lower(ctx: &mut Ctx, body: Vec<Stmt>) -> Vec<Stmt> {
    let Some(r) = ctx.end_flag else { return body };
    let main = ctx.plan().role == Role::Main;
    let ends = ctx.end_codes.clone();
    let mut refused: Vec<(Span, &'static str)> = Vec::new();
    let mut body = map_bodies(body, &mut |list| {
        let mut out = Vec::with_capacity(list.len());
        for mut s in list {
            let span = s.span;
            let mut codes: BTreeSet<u8> = BTreeSet::new();
            if let StmtKind::Block(b) = &mut s.kind {
                let mut items = Vec::with_capacity(b.items.len());
                for it in std::mem::take(&mut b.items) {
                    match &it.kind {
                        ItemKind::End { code } if !main => {
                            let v = int(code_number(*code).into(), it.span);
                            items.push(assign(VarRef { kind: VarKind::R(r), span: it.span }, v, it.span));
                            // The end itself stays: called, a Siemens M30/M2 returns (like
                            // M17); run as a main program (a batch proves each file alone),
                            // it ends the run as the FANUC one does.
                            items.push(it);
                        }
                        ItemKind::Call(c) => {
                            if let Some(more) = called(c).and_then(|m| ends.get(&m)) {
                                if c.kind == CallKind::G66 {
                                    refused.push((it.span, "a modal call (G66)"));
                                } else if c.repeat.is_some() {
                                    refused.push((it.span, "a repeated call (L)"));
                                }
                                codes.extend(more.iter().copied());
                            }
                            items.push(it);
                        }
                        ItemKind::IfThen { then, .. }
                            if matches!(then.kind, ItemKind::Call(_) | ItemKind::End { .. }) =>
                        {
                            if !main || matches!(then.kind, ItemKind::Call(_)) {
                                refused.push((it.span, "a conditional call or end (IF … THEN)"));
                            }
                            items.push(it);
                        }
                        _ => items.push(it),
                    }
                }
                b.items = items;
            }
            out.push(s);
            for code in codes {
                // The same end in a main or a called program: called, it returns again.
                let end = if code == 2 { EndCode::M2 } else { EndCode::M30 };
                let then = Item { kind: ItemKind::End { code: end }, span };
                out.push(if_stmt(flag_is(r, code, span), vec![plain_block(vec![then], span)], None, span));
            }
        }
        out
    });
    for (span, what) in refused {
        let msg = format!("{what} of a program that can end the run (M30/M2 in a called program)");
        ctx.error(
            "NC596",
            span,
            msg,
            "calls a program that may end the run",
            "call it with a plain M98 or G65 without L",
        );
    }
    if main {
        let span = body.first().map_or(Span::default(), |s| s.span);
        let clear = plain_block(vec![assign(VarRef { kind: VarKind::R(r), span }, int(0, span), span)], span);
        body.insert(0, clear);
    }
    body
}
