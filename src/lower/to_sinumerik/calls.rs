//! Programs and calls: which FANUC program becomes an `.MPF` or an `.SPF` and with which
//! `PROC` parameters (planning), and the lowering of G65/G66/G67/M98/M99 and `G10 L2`.
//!
//! - `G65 P9010 A1. X2.` → `O_9010(1.0, 2.0, …)`: one REAL parameter per argument local
//!   (`ARG_A`, `ARG_X`, spec-II sets `ARG_I3`…), then one BOOL is-set flag per argument
//!   whose vacancy the macro observes. An omitted letter is an omitted actual parameter, so
//!   the callee sees value 0 and flag FALSE: exactly FANUC's vacant.
//! - `M98 P3 L2` → `O_0003(LOC1, LOC24, …) P2`: the subprogram shares the caller's locals on
//!   FANUC, so it takes every local it (or its own M98 callees) uses as a `VAR` parameter and
//!   the caller passes its own variables by reference.
//! - `G66` → `MCALL NAME(…)`, `G67` → `MCALL`, `M99` → `RET` (also in a main program, where
//!   the trace spec ends the run on M99 as on RET).
//! - `G10 L2 Pp X.. Y..` → `$P_UIFR[p,X,TR]=…` (added to the old value under G91) and a
//!   re-selection of the work offset active at that point so the new value takes effect;
//!   `G10 L20 Pn` (extended offset n) → `$P_UIFR[6+n,X,TR]=…` where G54..G59 is in force.

use super::*;

/// The VAR parameter through which a program ending in `M99 P<n>` passes n back.
pub const RET_PARAM: &str = "NCTRANS_RET";
/// The caller's variable that receives it.
pub const RET_CODE: &str = "NCTRANS_RC";

/// `M99 P<n>` returns to block n of the caller: after a call of such a program the caller
/// clears its return code before the call and afterwards jumps on it like a computed GOTO
/// (`IF[NCTRANS_RC NE 0] GOTO NCTRANS_RC`, resolved by `gotos` from this point).
pub fn lower_return_jumps(ctx: &mut Ctx, body: Vec<Stmt>) -> Vec<Stmt> {
    let mut used = false;
    let main = ctx.plan().role == Role::Main;
    let out = map_bodies(body, &mut |list| {
        let mut out = Vec::with_capacity(list.len());
        for mut s in list {
            let span = s.span;
            // `M99 P<n>` in a main program continues at its own block n: a GOTO.
            if let (true, StmtKind::Block(b)) = (main, &mut s.kind) {
                for it in &mut b.items {
                    if let ItemKind::Return { to: Some(to) } = &it.kind {
                        let target = match literal(to) {
                            Some(v) if v >= 1.0 && v.fract() == 0.0 && v <= 99_999.0 => {
                                Target::Number(SeqNo { value: v as u32, span: to.span })
                            }
                            _ => Target::Computed(to.clone()),
                        };
                        let g = Goto { search: Search::ForwardThenWrap, target, cond: None, missing_continues: false };
                        it.kind = ItemKind::Goto(Box::new(g));
                    }
                }
            }
            let target = match &s.kind {
                StmtKind::Block(b) => b.items.iter().find_map(|it| match &it.kind {
                    ItemKind::Call(c) if matches!(c.kind, CallKind::G65 | CallKind::M98) => match c.target {
                        CallTarget::Number(n) => Some(n),
                        _ => None,
                    },
                    _ => None,
                }),
                _ => None,
            };
            let returns = target.and_then(|n| ctx.program_by_number(n)).is_some_and(|i| ctx.progs[i].returns_to);
            if !returns {
                out.push(s);
                continue;
            }
            used = true;
            out.push(plain_block(vec![assign(named_ref(RET_CODE, span), int(0, span), span)], span));
            out.push(s);
            let cond = Expr::new(
                ExprKind::Cmp(CmpOp::Ne, Tolerance::Exact, Box::new(named(RET_CODE, span)), Box::new(int(0, span))),
                span,
            );
            let g = Goto {
                search: Search::ForwardThenWrap,
                target: Target::Computed(named(RET_CODE, span)),
                cond: Some(cond),
                missing_continues: false,
            };
            out.push(plain_block(vec![Item { kind: ItemKind::Goto(Box::new(g)), span }], span));
        }
        out
    });
    if used {
        let plan = &mut ctx.progs[ctx.cur];
        if !plan.defs.iter().any(|(n, _)| n == RET_CODE) {
            plan.defs.push((RET_CODE.to_string(), DataType::Real));
        }
    }
    out
}

/// FANUC argument letter of local `n` under argument specification I, if any.
pub fn spec1_letter(n: u32) -> Option<char> {
    Some(match n {
        1 => 'A',
        2 => 'B',
        3 => 'C',
        4 => 'I',
        5 => 'J',
        6 => 'K',
        7 => 'D',
        8 => 'E',
        9 => 'F',
        11 => 'H',
        13 => 'M',
        17 => 'Q',
        18 => 'R',
        19 => 'S',
        20 => 'T',
        21 => 'U',
        22 => 'V',
        23 => 'W',
        24 => 'X',
        25 => 'Y',
        26 => 'Z',
        _ => return None,
    })
}

/// PROC parameter name of argument local `n`: `ARG_X` (spec I) or `ARG_I3` (spec II set 3).
pub fn arg_name(n: u32) -> String {
    match spec1_letter(n) {
        Some(c) => format!("ARG_{c}"),
        None => {
            let k = n.saturating_sub(4);
            let letter = ['I', 'J', 'K'][(k % 3) as usize];
            format!("ARG_{letter}{}", k / 3 + 1)
        }
    }
}

struct CallSite {
    caller: usize,
    callee: u32,
    kind: CallKind,
    span: Span,
}

fn collect_calls(body: &[Stmt], out: &mut Vec<(CallKind, u32, Vec<u32>, Span)>) {
    fn item(it: &Item, out: &mut Vec<(CallKind, u32, Vec<u32>, Span)>) {
        match &it.kind {
            ItemKind::Call(c) => {
                if let CallTarget::Number(n) = c.target {
                    let given = c
                        .args
                        .iter()
                        .filter_map(|a| match a {
                            Arg::Letter { var, value, .. } if !matches!(value.kind, ExprKind::Vacant) => {
                                Some(u32::from(*var))
                            }
                            _ => None,
                        })
                        .collect();
                    out.push((c.kind, n, given, it.span));
                }
            }
            ItemKind::IfThen { then, .. } => item(then, out),
            _ => {}
        }
    }
    crate::ir::visit::walk_stmts(body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            for it in &b.items {
                item(it, out);
            }
        }
    });
}

/// Locals `#1..#33` referenced directly in a program body.
pub fn direct_locals(body: &[Stmt]) -> (BTreeSet<u32>, bool) {
    let mut set = BTreeSet::new();
    let mut writes = false;
    fn expr(e: &Expr, set: &mut BTreeSet<u32>) {
        if let ExprKind::Var(v) = &e.kind {
            if let VarKind::Hash(n @ 1..=33) = v.kind {
                set.insert(n);
            }
        }
        for c in e.children() {
            expr(c, set);
        }
    }
    fn item(it: &Item, set: &mut BTreeSet<u32>, writes: &mut bool) {
        if let ItemKind::Assign { target, .. } = &it.kind {
            match target.kind {
                VarKind::Hash(n @ 1..=33) => {
                    set.insert(n);
                    *writes = true;
                }
                VarKind::HashIndirect(_) => *writes = true,
                _ => {}
            }
        }
        if let ItemKind::IfThen { then, .. } = &it.kind {
            item(then, set, writes);
        }
        for e in crate::ir::visit::item_exprs(it) {
            expr(e, set);
        }
    }
    crate::ir::visit::walk_stmts(body, &mut |s| match &s.kind {
        StmtKind::Block(b) => {
            for it in &b.items {
                item(it, &mut set, &mut writes);
            }
        }
        StmtKind::Do(d) => {
            if let Some(c) = &d.cond {
                expr(c, &mut set);
            }
        }
        _ => {}
    });
    (set, writes)
}

fn has_item(body: &[Stmt], pred: &dyn Fn(&ItemKind) -> bool) -> bool {
    let mut found = false;
    crate::ir::visit::walk_stmts(body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            found |= b.items.iter().any(|it| pred(&it.kind));
        }
    });
    found
}

/// Decides role, name and locals of every program (parameters are completed by the
/// variable map once the vacancy analysis knows which flags exist).
pub fn plan_programs(ctx: &mut Ctx, programs: &[(FileId, &Program)]) {
    let mut sites: Vec<CallSite> = Vec::new();
    let mut given: BTreeMap<u32, BTreeSet<u32>> = BTreeMap::new();
    for (i, (_, p)) in programs.iter().enumerate() {
        let mut calls = Vec::new();
        collect_calls(&p.body, &mut calls);
        for (kind, n, g, span) in calls {
            given.entry(n).or_default().extend(g);
            sites.push(CallSite { caller: i, callee: n, kind, span });
        }
    }
    let tools = tool_effects(programs);
    for (i, (file, p)) in programs.iter().enumerate() {
        let number = match &p.name {
            Some(ProgName::Number(n)) => Some(*n),
            _ => None,
        };
        let called: Vec<&CallSite> = sites.iter().filter(|s| Some(s.callee) == number).collect();
        let by_macro = called.iter().any(|s| matches!(s.kind, CallKind::G65 | CallKind::G66));
        let by_m98 = called.iter().any(|s| s.kind == CallKind::M98);
        let ends_with_m99 = has_item(&p.body, &|k| matches!(k, ItemKind::Return { .. }))
            && !has_item(&p.body, &|k| matches!(k, ItemKind::End { .. }));
        let role = if by_m98 && !by_macro {
            Role::Sub
        } else if by_macro || (ends_with_m99 && called.is_empty()) {
            Role::Macro
        } else {
            Role::Main
        };
        let name = match number {
            Some(n) => ctx.opts.program_map.get(&n).cloned().unwrap_or_else(|| {
                if role == Role::Main && i == 0 && ctx.opts.main_name != "MAIN" {
                    ctx.opts.main_name.clone()
                } else {
                    format!("O_{n:04}")
                }
            }),
            None => ctx.opts.main_name.clone(),
        };
        let (locals, writes_locals) = direct_locals(&p.body);
        ctx.progs.push(ProgPlan {
            file: *file,
            number,
            name: name.to_ascii_uppercase(),
            role,
            params: Vec::new(),
            locals,
            tracked: BTreeSet::new(),
            sure_words: BTreeSet::new(),
            given: number.and_then(|n| given.get(&n)).cloned().unwrap_or_default(),
            writes_locals,
            returns_to: role != Role::Main && has_item(&p.body, &|k| matches!(k, ItemKind::Return { to: Some(_) })),
            defs: Vec::new(),
            start_inch: None,
            sets_units: super::modal::sets_units(&p.body),
            start_incremental: None,
            start_motion: None,
            sets_distance: super::modal::sets_distance(&p.body),
            sets_g90: super::modal::has_g(&p.body, &[900]),
            tools: number.and_then(|n| tools.get(&n).copied()).unwrap_or(true),
            // Set once the units are known (`modal::frame_calls`).
            start_clear: false,
            leaves_frames: false,
            leaves_polar: false,
            // Set with the job's planes (`planes::start_planes`).
            start_plane: super::planes::At::UNKNOWN,
            sets_plane: (false, false),
            // Set when the idiom is found (`save_idiom`).
            save: false,
        });
        if by_m98 && by_macro {
            ctx.cur = i;
            let span = called.first().map_or(p.span, |s| s.span);
            let caller = called.first().map_or(i, |s| s.caller);
            let file = ctx.progs[caller].file;
            ctx.diags.push(
                Diagnostic::error("NC352", format!("O{} is called both by M98 and by G65/G66", number.unwrap_or(0)))
                    .primary(file, span, "one of the calls")
                    .note(
                        "M98 shares the caller's locals, G65 gives the macro its own; one Siemens PROC cannot do both",
                    )
                    .hint("call the program one way only, or copy it under a second O number"),
            );
        }
    }
    // M98 subprograms use their callers' locals: the locals of a program include those of
    // the subprograms it runs with M98 (to pass them by reference).
    let edges: Vec<(usize, usize)> = sites
        .iter()
        .filter(|s| s.kind == CallKind::M98)
        .filter_map(|s| ctx.progs.iter().position(|p| p.number == Some(s.callee)).map(|c| (s.caller, c)))
        .collect();
    for _ in 0..ctx.progs.len() + 1 {
        let mut changed = false;
        for &(a, b) in &edges {
            let add: Vec<u32> = ctx.progs[b].locals.difference(&ctx.progs[a].locals).copied().collect();
            if !add.is_empty() {
                ctx.progs[a].locals.extend(add);
                changed = true;
            }
            if ctx.progs[b].writes_locals && !ctx.progs[a].writes_locals {
                ctx.progs[a].writes_locals = true;
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    // Macro arguments given by callers are parameters even if the macro does not read them
    // directly (an M98 callee might).
    for p in &mut ctx.progs {
        if p.role == Role::Macro {
            if let Some(g) = p.number.and_then(|n| given.get(&n)) {
                p.locals.extend(g.iter().copied());
            }
        }
    }
}

/// Lowers calls, returns and offset writes of the current program.
pub fn lower(ctx: &mut Ctx, body: Vec<Stmt>) -> Vec<Stmt> {
    let modal = std::mem::take(&mut ctx.modal);
    let out = lower_with(ctx, body, &modal);
    ctx.modal = modal;
    out
}

fn lower_with(ctx: &mut Ctx, body: Vec<Stmt>, modal: &super::words::ModalScan) -> Vec<Stmt> {
    map_bodies(body, &mut |list| {
        let mut out = Vec::with_capacity(list.len());
        for s in list {
            match s.kind {
                StmtKind::Block(b) => lower_block(ctx, b, s.span, modal, &mut out),
                kind => out.push(Stmt { kind, span: s.span }),
            }
        }
        out
    })
}

/// Which numbered programs of the job may change the tool or the compensation (the shared
/// summary, `comp_flow::tool_effects`). `M97` runs blocks of the calling program itself;
/// a computed `P#1` may run anything.
fn tool_effects(programs: &[(FileId, &Program)]) -> BTreeMap<u32, bool> {
    use crate::lower::comp_flow::{self, CallRuns};
    let numbered: Vec<(u32, &Program)> = programs
        .iter()
        .filter_map(|(_, p)| match &p.name {
            Some(ProgName::Number(n)) => Some((*n, *p)),
            _ => None,
        })
        .collect();
    let runs = |c: &Call| match (&c.kind, &c.target) {
        (CallKind::M97, _) => CallRuns::Harmless,
        _ if super::dispatch::stops(c) => CallRuns::Harmless,
        (_, CallTarget::Number(n)) => CallRuns::Program(*n),
        _ => CallRuns::Unknown,
    };
    comp_flow::tool_effects(&numbered, true, &runs)
}

/// `POPEN`, `PCLOS`, `DPRNT[…]`, `BPRNT[…]` as the FANUC reader keeps them.
fn is_data_output(name: &str) -> bool {
    matches!(name, "POPEN" | "PCLOS") || name.starts_with("DPRNT[") || name.starts_with("BPRNT[")
}

fn lower_block(ctx: &mut Ctx, mut b: Block, span: Span, modal: &super::words::ModalScan, out: &mut Vec<Stmt>) {
    if g_codes(&b.items).contains(&100) {
        lower_g10(ctx, b, span, modal, out);
        return;
    }
    let mut items = Vec::with_capacity(b.items.len());
    let mut ret_after: Option<Span> = None;
    for it in std::mem::take(&mut b.items) {
        match it.kind {
            ItemKind::Call(c) if c.kind == CallKind::M97 => {
                if let Some(st) = ctx.unsupported(
                    "NC636",
                    it.span,
                    "Haas `M97 P<n>` (a local subprogram at block N<n> of the same program)",
                    "Siemens calls whole programs only: move the blocks from N<n> to their M99 into a subprogram \
                     and call it with M98",
                ) {
                    out.push(st);
                }
            }
            ItemKind::Print(p) => items.extend(super::print::lower(ctx, *p, it.span, out)),
            ItemKind::Instruction { name } if name == "POPEN" || name == "PCLOS" => {
                out.push(super::print::channel_comment(&name, it.span));
                // The note a Sinumerik → FANUC translation put on its POPEN says nothing here.
                b.meta.comments.retain(|c| !super::print::is_write_note(&c.text));
            }
            ItemKind::Instruction { name } if crate::eval::instructions::is_interrupt(&name) => {
                match super::interrupt::lower(ctx, &name, it.span) {
                    Ok(item) => items.push(item),
                    Err(Some(st)) => out.push(st),
                    Err(None) => {}
                }
            }
            ItemKind::Instruction { name } if is_data_output(&name) => {
                let what = format!("FANUC external output `{name}`");
                let hint = "BPRNT is binary; a DPRNT is translated (to WRITE) when it holds letters, digits, \
                            + - / and * alone: write the output by hand";
                if let Some(st) = ctx.unsupported("NC510", it.span, &what, hint) {
                    out.push(st);
                }
            }
            ItemKind::Call(c) => match lower_call(ctx, *c, it.span, modal.inch_at(span.lo)) {
                Ok(item) => items.push(item),
                Err(Some(stmt)) => out.push(stmt),
                Err(None) => {}
            },
            ItemKind::Return { to: Some(to) } if ctx.plan().returns_to => {
                // Tell the caller where to continue, then return.
                // RET stands in a block of its own after the one (and its label) that sets it.
                items.push(assign(named_ref(RET_PARAM, it.span), to, it.span));
                ret_after = Some(it.span);
            }
            ItemKind::Return { to: Some(_) } => {
                if let Some(st) = ctx.unsupported(
                    "NC354",
                    it.span,
                    "`M99 P<n>` (return to a block number of the caller)",
                    "return with M99 and jump in the caller with IF/GOTO",
                ) {
                    out.push(st);
                }
            }
            ItemKind::ParamWrite(_) => {
                if let Some(st) = ctx.unsupported(
                    "NC355",
                    it.span,
                    "`G10 L50` parameter write",
                    "set the machine datum by hand or write the machine data ($MN_/$MC_/$MA_) on the Siemens control",
                ) {
                    out.push(st);
                }
            }
            kind => items.push(Item { kind, span: it.span }),
        }
    }
    // MCALL (cancel) stands alone on Siemens.
    if items.len() > 1 && items.iter().any(|it| matches!(it.kind, ItemKind::ModalCallOff)) {
        let (off, rest): (Vec<Item>, Vec<Item>) =
            items.into_iter().partition(|it| matches!(it.kind, ItemKind::ModalCallOff));
        out.push(plain_block(off, span));
        items = rest;
    }
    // A G10 L50 / G11 frame block keeps nothing Siemens can use.
    let g = g_codes(&items);
    if g.contains(&110) {
        items.retain(|it| !matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'G')));
    }
    if items.is_empty() && b.meta.comments.is_empty() && b.meta.label.is_none() && b.meta.number.is_none() {
        return;
    }
    b.items = items;
    out.push(Stmt { kind: StmtKind::Block(b), span });
    if let Some(rs) = ret_after {
        out.push(plain_block(vec![Item { kind: ItemKind::Return { to: None }, span: rs }], rs));
    }
}

/// `inch`: the unit (G20/G21) of the call block, for arguments written without a decimal point.
fn lower_call(ctx: &mut Ctx, c: Call, span: Span, inch: Option<bool>) -> Result<Item, Option<Stmt>> {
    let n =
        match &c.target {
            CallTarget::Number(n) => *n,
            CallTarget::Computed(_) => return Err(ctx.unsupported(
                "NC356",
                span,
                "a call with a computed program number (`P#1`) that is not one number on every path to it, nor one \
                 of a few known ones (an input, a value a call may change, the main program's number)",
                "set the number from constants before the call (`#1=9010`, `IF [..] THEN #1=9020`), the call alone \
                 in its block, its arguments with a decimal point; or call each program by its number behind IF/GOTO",
            )),
            CallTarget::Name(_) => return Ok(Item { kind: ItemKind::Call(Box::new(c)), span }),
        };
    let Some(callee) = ctx.program_by_number(n) else {
        // Under the warn policy the call becomes a marked line: the run then reaches the
        // same point as FANUC does before it would miss the program.
        let hint = if ctx.opts.after_end.contains(&n) {
            format!(
                "O{n:04} is in the file, but after the closing `%`, where the control stops reading (NC237): move it before that `%`"
            )
        } else {
            format!("put O{n:04} in the same file, or beside it as O{n:04}.nc")
        };
        return Err(ctx.refuse(
            "NC353",
            span,
            &format!("the called program O{n} was not found"),
            &format!("call of the missing program O{n}"),
            &hint,
        ));
    };
    let cplan = ctx.progs[callee].clone();
    let mut args = Vec::new();
    let value_of = |local: u32| -> Option<&Expr> {
        // FANUC: the later-written letter wins for a shared variable.
        c.args.iter().rev().find_map(|a| match a {
            Arg::Letter { var, value, .. } if u32::from(*var) == local && !matches!(value.kind, ExprKind::Vacant) => {
                Some(value)
            }
            _ => None,
        })
    };
    let letter_of = |local: u32| -> Option<u8> {
        c.args.iter().rev().find_map(|a| match a {
            Arg::Letter { var, letter, .. } if u32::from(*var) == local => Some(*letter),
            _ => None,
        })
    };
    match c.kind {
        CallKind::G65 | CallKind::G66 => {
            for p in cplan.params.iter().filter(|p| p.local != 0) {
                let arg = match (value_of(p.local), p.flag) {
                    (None, _) => Arg::Omitted(span),
                    (Some(v), false) => {
                        let mut v = v.clone();
                        if let (ExprKind::Num(num), Some(l)) = (&mut v.kind, letter_of(p.local)) {
                            if !num.point && super::words::scaled_letter(l) && super::words::scales_bare(ctx.opts) {
                                let rotary = super::words::rotary_letter(l);
                                let Some(inch) = inch.or(rotary.then_some(false)) else {
                                    return Err(bare_in_unknown_unit(ctx, v.span));
                                };
                                num.value = super::words::scale(ctx.opts, num.value, inch, rotary);
                                num.point = true;
                            }
                        }
                        Arg::Value(v)
                    }
                    (Some(v), true) => Arg::Value(super::vacancy::flag_of_value(ctx, v)),
                };
                args.push(arg);
            }
            if let Some(r) = &c.repeat {
                if literal(r) != Some(1.0) && cplan.writes_locals {
                    return Err(ctx.unsupported(
                        "NC357",
                        span,
                        "`G65 … L<n>` repeating a macro that changes its own locals",
                        "FANUC keeps the macro's locals between repetitions; a Siemens PROC starts afresh: \
                         call the macro in a WHILE loop instead",
                    ));
                }
            }
        }
        CallKind::M98 => {
            for p in cplan.params.iter().filter(|p| p.local != 0) {
                let e = if p.flag {
                    super::vacancy::local_flag_expr(ctx, p.local, span)
                } else {
                    var_expr(VarKind::Hash(p.local), span)
                };
                args.push(Arg::Value(e));
            }
        }
        _ => {}
    }
    if cplan.returns_to {
        args.push(Arg::Value(named(RET_CODE, span)));
    }
    while matches!(args.last(), Some(Arg::Omitted(_))) {
        args.pop();
    }
    let kind = if c.kind == CallKind::G66 { CallKind::Mcall } else { CallKind::Named };
    let repeat = c.repeat.filter(|r| literal(r) != Some(1.0));
    if kind == CallKind::Mcall && repeat.is_some() {
        return Err(ctx.unsupported("NC357", span, "`G66 … L<n>`", "repeat inside the macro instead"));
    }
    Ok(Item { kind: ItemKind::Call(Box::new(Call { kind, target: CallTarget::Name(cplan.name), args, repeat })), span })
}

/// `G10 L2 Pp X.. Y.. Z..` → `$P_UIFR[p,AX,TR]=v` writes plus the re-selection of the active
/// work offset; `G10 L20 Pn` → `$P_UIFR[6+n,AX,TR]` (G507.. is G54.1 P1..), where G54..G59 is
/// known to be in force (so the written offset is not). Other `G10` forms are unsupported.
fn lower_g10(ctx: &mut Ctx, b: Block, span: Span, modal: &super::words::ModalScan, out: &mut Vec<Stmt>) {
    let word_val = |a: u8| {
        b.items.iter().find_map(|it| match &it.kind {
            ItemKind::Word(w) if w.addr.is(a) => match &w.value {
                WordValue::Expr(e) => Some(e.clone()),
                _ => None,
            },
            _ => None,
        })
    };
    let l = word_val(b'L').and_then(|e| literal(&e));
    if let Some(field) = l.filter(|_| !ctx.opts.source.haas).and_then(crate::eval::tool_data::g10_field) {
        let (p, r) = (word_val(b'P'), word_val(b'R'));
        let inc = match g_codes(&b.items) {
            gs if gs.contains(&910) => Some(true),
            gs if gs.contains(&900) => Some(false),
            _ => modal.incremental_at(span.lo),
        };
        g10_modal_words(&b, span, out);
        out.extend(super::tool_data::g10(ctx, field, p, r, inc, b.meta.clone(), span));
        return;
    }
    let extended = l == Some(20.0);
    if l != Some(2.0) && !extended {
        let what = if l == Some(50.0) { "`G10 L50` parameter write" } else { "this `G10` data setting" };
        if let Some(st) = ctx.unsupported(
            if l == Some(50.0) { "NC355" } else { "NC358" },
            span,
            what,
            "only `G10 L2 P1..6` and `G10 L20 P1..48` (work offsets) translate; set other data on the Siemens control",
        ) {
            out.push(st);
        }
        return;
    }
    let p = word_val(b'P').and_then(|e| literal(&e)).unwrap_or(-1.0);
    let frame = match p as i64 {
        // `G10 L20 Pn`: extended offset n (G54.1 Pn), Siemens G50(6+n) ($P_UIFR[6+n]).
        1..=48 if extended && p.fract() == 0.0 => 6 + p as i64,
        _ if extended => {
            if let Some(st) = ctx.unsupported(
                "NC545",
                span,
                "`G10 L20` with a P other than a constant 1..48",
                "write the extended offset number as a constant: `G10 L20 P3 X..`",
            ) {
                out.push(st);
            }
            return;
        }
        1..=4 if p.fract() == 0.0 => p as i64,
        5 | 6 if p.fract() == 0.0 => p as i64, // G58/G59 → G505/G506 ($P_UIFR[5], [6])
        _ => {
            if let Some(st) = ctx.unsupported(
                "NC358",
                span,
                "`G10 L2` with a P other than 1..6 (external offset or computed)",
                "write $P_UIFR[1..6,axis,TR] for G54..G59 (G505/G506)",
            ) {
                out.push(st);
            }
            return;
        }
    };
    let gs = g_codes(&b.items);
    let incremental = if gs.contains(&910) {
        true
    } else if gs.contains(&900) {
        false
    } else {
        match modal.incremental_at(span.lo) {
            Some(inc) => inc,
            None => {
                if let Some(st) = ctx.unsupported(
                    "NC374",
                    span,
                    "`G10 L2` where G90/G91 depends on the path taken or on the caller",
                    "write G90 or G91 in the G10 block",
                ) {
                    out.push(st);
                }
                return;
            }
        }
    };
    g10_modal_words(&b, span, out);
    let mut first = true;
    for it in &b.items {
        let ItemKind::Word(w) = &it.kind else { continue };
        let Addr::Letter(a) = w.addr else { continue };
        if !matches!(a, b'X' | b'Y' | b'Z' | b'A' | b'B' | b'C' | b'U' | b'V' | b'W') {
            continue;
        }
        let WordValue::Expr(e) = &w.value else { continue };
        let mut v = e.clone();
        if let ExprKind::Num(n) = &mut v.kind {
            if !n.point && super::words::scales_bare(ctx.opts) {
                let rotary = super::words::rotary_letter(a);
                let Some(inch) = modal.inch_at(span.lo).or(rotary.then_some(false)) else {
                    out.extend(bare_in_unknown_unit(ctx, v.span));
                    return;
                };
                n.value = super::words::scale(ctx.opts, n.value, inch, rotary);
                n.point = true;
            }
        }
        let axis = (a as char).to_string();
        let target = VarRef {
            kind: VarKind::System {
                name: "P_UIFR".into(),
                indices: vec![
                    int(frame, w.span),
                    Expr::new(ExprKind::Ident(axis), w.span),
                    Expr::new(ExprKind::Ident("TR".into()), w.span),
                ],
            },
            span: w.span,
        };
        let value = if incremental { bin(BinOp::Add, var_expr(target.kind.clone(), w.span), v) } else { v };
        let mut meta = BlockMeta { span, ..BlockMeta::default() };
        if first {
            meta = b.meta.clone();
            first = false;
        }
        out.push(block_stmt(meta, vec![assign(target, value, w.span)]));
    }
    // Writing $P_UIFR does not activate it: re-select the offset active here, if it is
    // the one written (FANUC: a write to another offset acts at its next selection).
    let g = match modal.offset_at(span.lo) {
        // G54..G59 in force: the extended offset written is not (the scan knows no G54.1 P).
        Some(_) if extended => return,
        None if extended => {
            if let Some(st) = ctx.unsupported(
                "NC546",
                span,
                "`G10 L20` where an extended offset (G54.1 Pn) may be in force (FANUC acts on a write to the active one at once; Sinumerik needs its G50x selected again, and which one is active is not followed here)",
                "write the extended offsets under G54..G59 (e.g. `G54`, then `G10 L20 P1 X..`), then select `G54.1 P1`",
            ) {
                out.push(st);
            }
            return;
        }
        Some(g) if i64::from(g / 10) - 53 != frame => return,
        Some(580) => 5050,
        Some(590) => 5060,
        Some(g) => g,
        None => {
            out.extend(super::words::unknown_offset(ctx, span));
            return;
        }
    };
    out.push(plain_block(vec![super::words::g_word(g, span)], span));
}

/// A value written without a decimal point where the unit (G20/G21) it counts in is not known.
fn bare_in_unknown_unit(ctx: &mut Ctx, span: Span) -> Option<Stmt> {
    ctx.refuse(
        "NC375",
        span,
        "a value without a decimal point where the unit (G20/G21) depends on the path taken or on the caller",
        "a value without a decimal point",
        "write the value with a decimal point, or select G20/G21 before it (in a subprogram: in the subprogram)",
    )
}

/// The modal G codes written in a G10 block (G90/G91 …), which stay in force for later
/// blocks: a block of their own before what the G10 becomes.
fn g10_modal_words(b: &Block, span: Span, out: &mut Vec<Stmt>) {
    let modal_words: Vec<Item> = b
        .items
        .iter()
        .filter(|it| matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'G')))
        .filter(|it| !g_codes(std::slice::from_ref(it)).contains(&100))
        .cloned()
        .collect();
    if !modal_words.is_empty() {
        out.push(plain_block(modal_words, span));
    }
}
