//! Where each FANUC variable lives on the Siemens control.
//!
//! Defaults (each overridable by `--var-map '#from-#to=Rn'`, rules applied first):
//! - `#500..#799` → `R0..R299` (the inverse of the Siemens→FANUC default `Rn` → `#(500+n)`,
//!   so round trips keep their R numbers), `#100..#199` → `R100..R199` ([`DEFAULT_RULES`]).
//! - Any other common variable the program uses (and any default that would land on an R
//!   number already taken) gets the lowest free R number, with a warning naming it. Under
//!   `[fanuc] series = "haas-ngc"` that includes the NGC-only general-purpose variables
//!   (`#10000..#10099`, `#10200..#10499`, `#10700..#10799`): global, kept on power off and
//!   vacant until written, as `#500` is, so they live on R parameters the same way.
//! - A computed `#[…]` goes through the same rules at run time ([`dispatch_ranges`]): every
//!   number of a rule's range whose R number is its own (a direct access of it goes there,
//!   or nothing else is there) is reached as `R[i-from+Rn]`, so `#[550+#1*2]` with #1 = 2
//!   is the R parameter `#554` is. Where two ranges' R numbers overlap (`#600..#699` and
//!   `#100..#199` by default), the ranges the job's variables and computed indices point
//!   at come first, then a range on its own numbers (`#100..#199`). Any other number
//!   raises `SETAL(64115)` (FANUC alarm 115's image).
//! - Is-set flags of tracked common variables take free R numbers from the top down.
//! - Locals `#1..#33`: in a main program `DEF REAL LOCn`; in a G65 macro `PROC` parameters
//!   `ARG_<letter>` for argument locals and `DEF REAL LOCn` for the rest; in an M98
//!   subprogram `VAR REAL LOCn` parameters (the caller's variables by reference). Flags are
//!   `<name>_SET` (BOOL) beside them.
//!
//! An explicit rule that runs past the last R parameter, or two variables on one R number,
//! is an error (NC350/NC351).

use super::calls::{arg_name, spec1_letter};
use super::vacancy::Info;
use super::*;

/// The value name of local `n` in a program.
pub fn local_name(plan: &ProgPlan, n: u32) -> String {
    match plan.params.iter().find(|p| p.local == n && !p.flag) {
        Some(p) => p.name.clone(),
        None => format!("LOC{n}"),
    }
}

/// The is-set flag name of local `n` in a program.
pub fn flag_name(plan: &ProgPlan, n: u32) -> String {
    match plan.params.iter().find(|p| p.local == n && p.flag) {
        Some(p) => p.name.clone(),
        None => format!("{}_SET", local_name(plan, n)),
    }
}

/// The common variables the job names (`common`: which numbers are commons on the source
/// control), each with where it is first used.
fn used_commons(programs: &[(FileId, &Program)], common: fn(u32) -> bool) -> BTreeMap<u32, (FileId, Span)> {
    let mut used = BTreeMap::new();
    for (file, p) in programs {
        let visit = |e: &Expr, file: FileId, used: &mut BTreeMap<u32, (FileId, Span)>| {
            let mut stack = vec![e];
            while let Some(x) = stack.pop() {
                if let ExprKind::Var(v) = &x.kind {
                    if let VarKind::Hash(n) = v.kind {
                        if common(n) {
                            used.entry(n).or_insert((file, v.span));
                        }
                    }
                }
                stack.extend(x.children());
            }
        };
        crate::ir::visit::walk_stmts(&p.body, &mut |s| match &s.kind {
            StmtKind::Block(b) => {
                for it in block_items(b) {
                    if let ItemKind::Assign { target, .. } = &it.kind {
                        if let VarKind::Hash(n) = target.kind {
                            if common(n) {
                                used.entry(n).or_insert((*file, target.span));
                            }
                        }
                    }
                    for e in crate::ir::visit::item_exprs(it) {
                        visit(e, *file, &mut used);
                    }
                }
            }
            StmtKind::Do(d) => {
                if let Some(c) = &d.cond {
                    visit(c, *file, &mut used);
                }
            }
            _ => {}
        });
    }
    used
}

/// Which numbers are common variables on the job's source control.
fn common_test(ctx: &Ctx) -> fn(u32) -> bool {
    if ctx.opts.source.haas_ngc {
        |n| crate::dialect::fanuc::haas_vars::common(n, true)
    } else {
        |n| crate::dialect::fanuc::haas_vars::common(n, false)
    }
}

/// Builds the variable map and completes every program's parameters and DEFs.
pub fn build(ctx: &mut Ctx, programs: &[(FileId, &Program)], info: &Info) {
    let count = ctx.opts.target.r_param_count;
    let used = used_commons(programs, common_test(ctx));
    let mut taken: BTreeMap<u32, u32> = BTreeMap::new(); // R → FANUC variable
    let mut pending: Vec<u32> = Vec::new();
    for (&n, &(file, span)) in &used {
        let rule = ctx.opts.var_map.iter().find(|r| r.from <= n && n <= r.to);
        let Some(rule) = rule else {
            pending.push(n);
            continue;
        };
        let r = rule.r_start + (n - rule.from);
        if r >= count {
            ctx.diags.push(
                Diagnostic::error(
                    "NC350",
                    format!("--var-map puts #{n} on R{r}, past the last R parameter R{}", count - 1),
                )
                .primary(file, span, format!("#{n} used here"))
                .note(format!("rule #{}-#{}=R{}", rule.from, rule.to, rule.r_start))
                .hint("start the rule at a lower R number or split it"),
            );
            continue;
        }
        if let Some(other) = taken.get(&r) {
            ctx.diags.push(
                Diagnostic::error("NC351", format!("#{n} and #{other} would both be R{r}"))
                    .primary(file, span, format!("#{n} used here"))
                    .hint("give the two ranges --var-map rules that do not overlap"),
            );
            continue;
        }
        taken.insert(r, n);
        ctx.commons.insert(n, r);
    }
    let default_r = default_r;
    let mut leftovers = Vec::new();
    for &n in &pending {
        match default_r(n) {
            Some(r) if r < count && !taken.contains_key(&r) => {
                taken.insert(r, n);
                ctx.commons.insert(n, r);
            }
            _ => leftovers.push(n),
        }
    }
    for n in leftovers {
        let (file, span) = used[&n];
        let flag_place = |r: &u32| ctx.opts.flag_places.values().any(|p| p == r);
        match (0..count)
            .find(|r| !taken.contains_key(r) && !flag_place(r) && !pending.iter().any(|&m| default_r(m) == Some(*r)))
        {
            Some(r) => {
                taken.insert(r, n);
                ctx.commons.insert(n, r);
                ctx.diags.push(
                    Diagnostic::warning("NC360", format!("#{n} has no default R parameter; it is R{r}"))
                        .primary(file, span, "used here")
                        .note(if n >= 10000 {
                            "a Haas NGC general-purpose variable without a legacy number (kept on power off, as #500..#999 are): \
                             only #100..#199 and #500..#799 have default R parameters"
                        } else {
                            "#100..#199 map to R100..R199 and #500..#799 to R0..R299 by default"
                        })
                        .hint(format!("choose the place with --var-map '#{n}=R<k>'")),
                );
            }
            None => ctx.diags.push(
                Diagnostic::error("NC350", format!("no R parameter is left for #{n}"))
                    .primary(file, span, "used here")
                    .hint("raise the R parameter count of the target profile or map fewer variables"),
            ),
        }
    }
    let pinned = &ctx.opts.flag_places;
    let reserved = |r: &u32| pinned.values().any(|p| p == r);
    for &n in &info.commons {
        let place = match pinned.get(&n) {
            Some(&r) if r < count && !taken.contains_key(&r) => Some(r),
            _ => (0..count).rev().find(|r| !taken.contains_key(r) && !reserved(r)),
        };
        match place {
            Some(r) => {
                taken.insert(r, n);
                ctx.common_flags.insert(n, r);
            }
            None => {
                let (file, span) = used.get(&n).copied().unwrap_or((0, Span::default()));
                ctx.diags.push(
                    Diagnostic::error("NC350", format!("no R parameter is left for the is-set flag of #{n}"))
                        .primary(file, span, "its vacancy is tested")
                        .hint("raise the R parameter count of the target profile"),
                );
            }
        }
    }
    for plan in &mut ctx.progs {
        plan_locals(plan);
    }
    ctx.index_bases = index_bases(programs, common_test(ctx));
}

/// The highest R parameter nothing of the job is placed on (the end flag of `ends`), below
/// the is-set flags, which are placed from the top down.
pub fn free_r(ctx: &Ctx) -> Option<u32> {
    let taken = |r: u32| {
        ctx.commons.values().any(|&x| x == r)
            || ctx.common_flags.values().any(|&x| x == r)
            || ctx.opts.flag_places.values().any(|&x| x == r)
    };
    (0..ctx.opts.target.r_param_count).rev().find(|&r| !taken(r))
}

/// The first numbers of the Haas NGC general-purpose ranges without a legacy number
/// (`dialect::fanuc::haas_vars::ngc_only`).
const NGC_ONLY: [u32; 3] = [10000, 10200, 10700];

fn ngc_end(lo: u32) -> u32 {
    match lo {
        10200 => 10499,
        _ => lo + 99,
    }
}

/// The default rules `(from, to, R start)`, in the order they are applied.
pub const DEFAULT_RULES: &[(u32, u32, u32)] = &[(500, 799, 0), (100, 199, 100)];

/// The default R number of `#n` (the first default rule that holds it).
fn default_r(n: u32) -> Option<u32> {
    DEFAULT_RULES.iter().find(|r| r.0 <= n && n <= r.1).map(|r| r.2 + (n - r.0))
}

/// The constant term of an index (`550` of `#[550+#1*2]`), when it has one.
pub(super) fn constant_term(e: &Expr) -> Option<f64> {
    match &e.kind {
        ExprKind::Num(n) => Some(n.value),
        ExprKind::Binary(BinOp::Add, a, b) => match (constant_term(a), constant_term(b)) {
            (Some(x), Some(y)) => Some(x + y),
            (x, y) => x.or(y),
        },
        ExprKind::Binary(BinOp::Sub, a, b) => match (constant_term(a), literal(b)) {
            (Some(x), Some(y)) => Some(x - y),
            (x, _) => x,
        },
        _ => None,
    }
}

/// [`Ctx::index_bases`] of the job.
fn index_bases(programs: &[(FileId, &Program)], common: fn(u32) -> bool) -> BTreeSet<u32> {
    let mut bases = BTreeSet::new();
    let mut see = |x: &Expr| {
        if let Some(c) = constant_term(x) {
            let c = c.round();
            if (0.0..=f64::from(u32::MAX)).contains(&c) && common(c as u32) {
                bases.insert(c as u32);
            }
        }
    };
    for (_, p) in programs {
        crate::ir::visit::walk_stmts(&p.body, &mut |s| {
            let StmtKind::Block(b) = &s.kind else { return };
            for it in block_items(b) {
                if let ItemKind::Assign { target, .. } = &it.kind {
                    if let VarKind::HashIndirect(x) = &target.kind {
                        see(x);
                    }
                }
                let mut stack: Vec<&Expr> = crate::ir::visit::item_exprs(it);
                while let Some(e) = stack.pop() {
                    if let ExprKind::Var(v) = &e.kind {
                        if let VarKind::HashIndirect(x) = &v.kind {
                            see(x);
                        }
                    }
                    stack.extend(e.children());
                }
            }
        });
    }
    bases
}

/// The variable ranges a computed `#[…]` reaches at run time, `(from, to, R of from)`, each
/// a run of numbers whose R parameter is the one a direct access uses, no two numbers
/// sharing an R number. A number goes by its rule (the first `--var-map` rule that holds it,
/// else [`DEFAULT_RULES`]), as direct access does; a variable of the job goes where the map
/// put it (its rule's place, or alone where a collision or NC360 put it). Where numbers the
/// job never names would share an R number (`#620` and `#120` on R120 by default), one gets
/// it: an explicit rule's, else one in a hundred (`#6xx`, `#1xx`) the job's variables or
/// computed indices use, else one on its own number, else the earlier rule's; the others
/// are left out (`SETAL(64115)` at run time). Tracked variables (is-set flags) are in: the
/// computed access keeps their flags (`exprs::runtime_indirect`).
pub fn dispatch_ranges(ctx: &Ctx) -> Vec<(u32, u32, u32)> {
    let count = ctx.opts.target.r_param_count;
    let explicit = ctx.opts.var_map.len();
    let rules: Vec<(u32, u32, u32)> =
        ctx.opts.var_map.iter().map(|r| (r.from, r.to, r.r_start)).chain(DEFAULT_RULES.iter().copied()).collect();
    let hundreds: BTreeSet<u32> = ctx.commons.keys().chain(&ctx.index_bases).map(|n| n / 100).collect();
    let owner: BTreeMap<u32, u32> = ctx.commons.iter().map(|(&n, &r)| (r, n)).collect();
    let flag_r: BTreeSet<u32> = ctx.common_flags.values().chain(ctx.opts.flag_places.values()).copied().collect();
    // R number → (preference, number): the candidate that gets it (lowest preference).
    let mut best: BTreeMap<u32, ((u8, u8, usize), u32)> = BTreeMap::new();
    // The NGC-only numbers have no default rule: only a `--var-map` rule over them (or a
    // place of the job's own variable, below) makes them reachable.
    let ngc: &[u32] = if ctx.opts.source.haas_ngc { &NGC_ONLY } else { &[] };
    let numbers = (100..=999u32).chain(ngc.iter().flat_map(|&lo| lo..=ngc_end(lo)));
    for n in numbers {
        let Some(k) = rules.iter().position(|r| r.0 <= n && n <= r.1) else { continue };
        let (from, _, r0) = rules[k];
        let Some(r) = r0.checked_add(n - from) else { continue };
        if r >= count || flag_r.contains(&r) {
            continue;
        }
        let pref = match ctx.commons.get(&n) {
            Some(&m) if m == r => (0, 0, k),
            Some(_) => continue,
            None if owner.contains_key(&r) => continue,
            None => {
                (if k < explicit { 1 } else { 2 }, u8::from(!hundreds.contains(&(n / 100))) * 2 + u8::from(n != r), k)
            }
        };
        if best.get(&r).is_none_or(|b| pref < b.0) {
            best.insert(r, (pref, n));
        }
    }
    // Runs of consecutive numbers with one offset (number → R).
    let mut chosen: Vec<(u32, u32)> = best.iter().map(|(&r, &(_, n))| (n, r)).collect();
    chosen.sort_unstable();
    let mut out: Vec<(u32, u32, u32)> = Vec::new();
    for (n, r) in chosen {
        match out.last_mut() {
            Some(last) if last.1 + 1 == n && last.2 + (n - last.0) == r => last.1 = n,
            _ => out.push((n, n, r)),
        }
    }
    // A variable placed off its rule (a collision, or no rule: NC360) is reached where it is.
    for (&n, &r) in &ctx.commons {
        if best.get(&r).is_none_or(|b| b.1 != n) {
            out.push((n, n, r));
        }
    }
    out.sort_unstable();
    // Such variables placed side by side (`#10200`, `#10201` on R2, R3) are one run.
    let mut merged: Vec<(u32, u32, u32)> = Vec::with_capacity(out.len());
    for (from, to, r) in out {
        match merged.last_mut() {
            Some(last) if last.1 + 1 == from && last.2 + (from - last.0) == r => last.1 = to,
            _ => merged.push((from, to, r)),
        }
    }
    merged
}

fn plan_locals(plan: &mut ProgPlan) {
    let locals: Vec<u32> = plan.locals.iter().copied().collect();
    let tracked = plan.tracked.clone();
    let mut values = Vec::new();
    let mut flags = Vec::new();
    let mut defs = Vec::new();
    for &n in &locals {
        let flagged = tracked.contains(&n);
        match plan.role {
            Role::Main => {
                defs.push((format!("LOC{n}"), DataType::Real));
                if flagged {
                    defs.push((format!("LOC{n}_SET"), DataType::Bool));
                }
            }
            Role::Macro => {
                // Argument locals become parameters: every spec-I letter the macro uses, and
                // any local a caller fills (spec II sets included).
                if spec1_letter(n).is_some() || plan.given_by_callers(n) {
                    let name = arg_name(n);
                    if flagged {
                        flags.push(ParamSpec { local: n, flag: true, name: format!("{name}_SET"), by_ref: false });
                    }
                    values.push(ParamSpec { local: n, flag: false, name, by_ref: false });
                } else {
                    defs.push((format!("LOC{n}"), DataType::Real));
                    if flagged {
                        defs.push((format!("LOC{n}_SET"), DataType::Bool));
                    }
                }
            }
            Role::Sub => {
                values.push(ParamSpec { local: n, flag: false, name: format!("LOC{n}"), by_ref: true });
                if flagged {
                    flags.push(ParamSpec { local: n, flag: true, name: format!("LOC{n}_SET"), by_ref: true });
                }
            }
        }
    }
    values.extend(flags);
    if plan.returns_to {
        values.push(ParamSpec { local: 0, flag: false, name: super::calls::RET_PARAM.into(), by_ref: true });
    }
    plan.params = values;
    plan.defs = defs;
}

impl ProgPlan {
    /// Whether some call site in the job fills local `n` (spec II letters included).
    pub fn given_by_callers(&self, n: u32) -> bool {
        self.given.contains(&n)
    }
}

/// The Siemens variable for FANUC `#n` read or written in the current program, or `None`
/// when it is a system variable (handled by `words::system_var`).
pub fn map_hash(ctx: &Ctx, n: u32, span: Span) -> Option<VarKind> {
    match n {
        1..=33 => Some(VarKind::Named { name: local_name(ctx.plan(), n), indices: vec![] }),
        100..=999 => Some(ctx.commons.get(&n).map_or(VarKind::R(n), |r| VarKind::R(*r))),
        // An NGC-only variable is placed when the job uses it (`build`).
        _ if ctx.opts.source.haas_ngc && crate::dialect::fanuc::haas_vars::ngc_only(n) => {
            ctx.commons.get(&n).map(|r| VarKind::R(*r))
        }
        _ => {
            let _ = span;
            None
        }
    }
}
