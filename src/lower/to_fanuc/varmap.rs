//! Variables → FANUC `#n`.
//!
//! Defaults: `R n` → `#(500+n)` (retained commons, like R parameters); DEF variables of the main
//! program → free common variables from `#100` up (then free ones from `#500`); PROC
//! parameters → the G65 argument locals of their letters; DEF variables of a subprogram and
//! temporaries → free locals `#1..#33` (one set per call level, like Siemens LUDs), then
//! commons. `--var-map` rules override (`R0-R99=#100`, `R5=#600`, `NAME=#150`). Every target
//! is checked: a number outside the commons (`#0`, `#34..#99`, past `#999`, system variables),
//! two variables on one number, or `R[expr]` without one contiguous R mapping are errors.

use super::words::param_letters;
use super::*;
use std::collections::{BTreeSet, HashMap};

mod byref;
mod gud;
use byref::{RefParam, Scope};

/// One `--var-map` rule.
#[derive(Clone, Debug, PartialEq)]
pub enum VarRule {
    /// `Rlo-Rhi=#base`: R n → #(base + n - lo).
    R { lo: u32, hi: u32, base: u32 },
    /// `NAME=#n` for a DEF variable (arrays: the first element).
    Name { name: String, number: u32 },
}

/// Parses `R0-R99=#100`, `R5=#600`, `NAME=#150`; several separated by commas.
pub fn parse_rules(s: &str) -> Result<Vec<VarRule>, String> {
    let mut v = Vec::new();
    for part in s.split(',').map(str::trim).filter(|p| !p.is_empty()) {
        let (lhs, rhs) = part.split_once('=').ok_or_else(|| format!("'{part}': expected SOURCE=#n"))?;
        if lhs.trim_start().starts_with('#') && rhs.trim_start().starts_with(['R', 'r']) {
            return Err(format!(
                "'{part}' maps FANUC variables onto R parameters, a FANUC → Sinumerik rule (--to sinumerik); \
                 to FANUC a rule maps R parameters or variable names onto # variables, like 'R0-R99=#100' or 'COUNT=#150'"
            ));
        }
        let number: u32 = rhs
            .trim()
            .strip_prefix('#')
            .and_then(|n| n.parse().ok())
            .ok_or_else(|| format!("'{part}': the target must be written #n"))?;
        let lhs = lhs.trim().to_ascii_uppercase();
        let r_num = |t: &str| t.strip_prefix('R').and_then(|n| n.parse::<u32>().ok());
        if let Some((a, b)) = lhs.split_once('-') {
            match (r_num(a.trim()), r_num(b.trim())) {
                (Some(lo), Some(hi)) if lo <= hi => v.push(VarRule::R { lo, hi, base: number }),
                _ => return Err(format!("'{part}': expected a range Rlo-Rhi")),
            }
        } else if let Some(n) = r_num(&lhs) {
            v.push(VarRule::R { lo: n, hi: n, base: number });
        } else if lhs.chars().next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_') {
            v.push(VarRule::Name { name: lhs, number });
        } else {
            return Err(format!("'{part}': expected Rn, Rlo-Rhi or a variable name"));
        }
    }
    Ok(v)
}

/// One mapped variable, for the output header and the symbol map.
#[derive(Clone, Debug, PartialEq)]
pub struct Mapped {
    /// The program it belongs to (`None`: global, R parameters).
    pub program: Option<String>,
    /// `R1`, `CNT`, `A[0,1]`, `X (parameter, letter X)`, `temporary`.
    pub source: String,
    pub number: u32,
}

/// A program to map: its body, facts and name.
pub struct Job<'a> {
    pub prog: &'a mut Program,
    pub info: &'a ProgInfo,
    pub name: String,
    /// The file the program's spans point into.
    pub file: crate::span::FileId,
}

fn common(n: u32) -> bool {
    (100..=199).contains(&n) || (500..=999).contains(&n)
}

/// Maps every variable of every program; returns the mapping for the header and symbol map.
pub fn run(ctx: &mut Ctx, jobs: &mut [Job], rules: &[VarRule], r_count: u32) -> Vec<Mapped> {
    // Which R parameters and names are used, in order of first use.
    let mut r_used = BTreeSet::new();
    let mut r_indirect = None;
    let mut names: Vec<Vec<(String, Span)>> = Vec::new();
    for j in jobs.iter_mut() {
        let mut seen: Vec<(String, Span)> = Vec::new();
        visit_vars(&mut j.prog.body, &mut |v| match &v.kind {
            VarKind::R(n) => {
                r_used.insert(*n);
            }
            VarKind::RIndirect(_) => r_indirect = r_indirect.or(Some(v.span)),
            VarKind::Named { name, .. } if !seen.iter().any(|(s, _)| s == name) => seen.push((name.clone(), v.span)),
            _ => {}
        });
        names.push(seen);
    }
    let mut claimed: HashMap<u32, String> = HashMap::new();
    let mut out = Vec::new();
    let claim = |ctx: &mut Ctx, n: u32, who: String, span: Span, claimed: &mut HashMap<u32, String>| {
        if let Some(other) = claimed.get(&n) {
            let msg = format!("{who} and {other} would both be #{n}");
            ctx.error("NC302", span, &msg, "change one of them with --var-map");
            return false;
        }
        claimed.insert(n, who);
        true
    };
    // R parameters.
    let r_target = |n: u32| -> u32 {
        for r in rules {
            if let VarRule::R { lo, hi, base } = r {
                if (*lo..=*hi).contains(&n) {
                    return base + (n - lo);
                }
            }
        }
        500 + n
    };
    let span0 = Span::default();
    let r_offset: Option<u32> = match r_indirect {
        None => None,
        Some(span) => {
            let r_rules: Vec<_> = rules.iter().filter(|r| matches!(r, VarRule::R { .. })).collect();
            match r_rules.as_slice() {
                [] => Some(500),
                [VarRule::R { lo: 0, hi, base }] if *hi + 1 >= r_count => Some(*base),
                _ => {
                    ctx.error(
                        "NC302",
                        span,
                        "R[expr] needs all R parameters mapped as one contiguous range",
                        "use a single rule R0-R<last>=#n",
                    );
                    None
                }
            }
        }
    };
    let r_all: Vec<u32> = match r_offset {
        Some(_) => (0..r_count).chain(r_used.iter().copied().filter(|n| *n >= r_count)).collect(),
        None => r_used.iter().copied().collect(),
    };
    for n in r_all {
        let t = r_target(n);
        let used = r_used.contains(&n);
        if !(common(t) || (ctx.haas_ngc && crate::dialect::fanuc::haas_vars::ngc_only(t))) {
            let why = match crate::dialect::fanuc::haas_vars::legacy(t) {
                // A Haas NGC reads it as the legacy number: R{n} would share it.
                Some(l) if ctx.haas_ngc => format!("on a Haas NGC the same variable as #{l} (its NGC spelling)"),
                _ if t > 999 => "past #999 (system variables)".to_string(),
                _ => "not a common variable".to_string(),
            };
            let msg = format!("R{n} would be #{t}, {why}");
            ctx.error(
                "NC302",
                r_indirect.unwrap_or(span0),
                &msg,
                "map the R parameters elsewhere with --var-map 'R0-R99=#100'",
            );
            continue;
        }
        if claim(ctx, t, format!("R{n}"), span0, &mut claimed) && used {
            out.push(Mapped { program: None, source: format!("R{n}"), number: t });
        }
    }
    if let Some(off) = r_offset {
        out.push(Mapped { program: None, source: format!("R[i] (all R, #{off}+i)"), number: off });
    }
    // Names.
    let mut next_common = 100u32;
    let mut alloc_common = |claimed: &HashMap<u32, String>, size: u32| -> Option<u32> {
        let mut n = next_common;
        while n.saturating_add(size - 1) <= 999 {
            // #100..#199 only where the R parameter of the same number is not used: the
            // FANUC → Sinumerik translation brings both #k and #(500+k) back as Rk, so a
            // round trip would have to move one of them (issue 17 item 10).
            let fits = (n..n + size)
                .all(|k| common(k) && !claimed.contains_key(&k) && !((100..=199).contains(&k) && r_used.contains(&k)));
            if fits {
                next_common = n + size;
                return Some(n);
            }
            n += 1;
        }
        None
    };
    let callees: HashMap<u32, Vec<Param>> = ctx.callees.values().map(|c| (c.number, c.params.clone())).collect();
    // Names a subprogram uses: a main program's DEF variable of that name is visible there.
    let sub_names: BTreeSet<String> = jobs
        .iter()
        .zip(&names)
        .filter(|(j, _)| j.info.is_sub)
        .flat_map(|(_, seen)| seen.iter().map(|(n, _)| n.clone()))
        .collect();
    for (j, seen) in jobs.iter_mut().zip(names) {
        ctx.file = j.file;
        let mut map: HashMap<String, (u32, Vec<u32>)> = HashMap::new();
        let mut refs: HashMap<String, RefParam> = HashMap::new();
        let mut locals = [false; 34];
        locals[0] = true;
        // `LOCn` is what the FANUC → Sinumerik translation calls a main program's local #n:
        // it goes back there (a round trip keeps the program), unless a subprogram sees it
        // or a rule places it.
        if !j.info.is_sub {
            for (name, _) in &seen {
                let Some(k) = name.strip_prefix("LOC").and_then(|d| d.parse::<u32>().ok()) else { continue };
                let scalar_real = matches!(j.info.types.get(name), Some((DataType::Real, d)) if d.is_empty());
                let ruled = rules.iter().any(|r| matches!(r, VarRule::Name { name: n, .. } if n == name));
                if (1..=33).contains(&k)
                    && format!("LOC{k}") == *name
                    && scalar_real
                    && !ruled
                    && !sub_names.contains(name)
                    && !locals[k as usize]
                {
                    locals[k as usize] = true;
                    map.insert(name.clone(), (k, vec![]));
                    out.push(Mapped { program: Some(j.name.clone()), source: name.clone(), number: k });
                }
            }
        }
        if let Some(letters) = param_letters(j.prog.params.len()) {
            for (p, (letter, var)) in j.prog.params.iter().zip(letters) {
                locals[var as usize] = true;
                map.insert(p.name.clone(), (var as u32, vec![]));
                let source = if p.by_ref {
                    refs.insert(p.name.clone(), RefParam { var: var as u32, dims: p.dims.clone() });
                    format!(
                        "{} (VAR parameter, letter {}: the number of the caller's variable)",
                        p.name, letter as char
                    )
                } else {
                    format!("{} (parameter, letter {})", p.name, letter as char)
                };
                out.push(Mapped { program: Some(j.name.clone()), source, number: var as u32 });
            }
        }
        for (name, span) in seen {
            if map.contains_key(&name) {
                continue;
            }
            let temp = name.starts_with(TEMP_PREFIX);
            let dims = match j.info.types.get(&name) {
                Some((_, d)) => d.clone(),
                None if temp => vec![],
                None if gud::lookup(&ctx.globals, &name).is_some() => {
                    let globals = ctx.globals.clone();
                    let Some(g) = gud::lookup(&globals, &name) else { continue };
                    let Some(n) = gud::number(ctx, &g, &name, span, rules) else { continue };
                    let dims = g.dims().to_vec();
                    // One home for the whole translation: a second program using it shares it.
                    let who = format!("global user data {name}");
                    let mut ok = true;
                    for (k, v) in (n..).zip(gud::seeds(&g).unwrap_or_default()) {
                        if claimed.get(&k) == Some(&who) {
                            continue;
                        }
                        ok &= claim(ctx, k, who.clone(), span, &mut claimed);
                        ctx.gud_seeds.push((k, v));
                    }
                    if !ok {
                        continue;
                    }
                    if !out.iter().any(|m: &Mapped| m.program.is_none() && m.number == n) {
                        let size: u32 = crate::ir::elements(&dims);
                        let source = if dims.is_empty() {
                            format!("{name} (global user data)")
                        } else {
                            format!("{name}[…] ({size} elements, global user data)")
                        };
                        out.push(Mapped { program: None, source, number: n });
                    }
                    map.insert(name.clone(), (n, dims));
                    continue;
                }
                None => {
                    let msg = format!("variable {name} is not declared");
                    // Machine builders' libraries declare most names in GUD files (`DEF NCK …` in
                    // MGUD.DEF): those keep their values between programs, so a FANUC
                    // translation would need one library-wide map to retained commons.
                    let hint = format!(
                        "declare it: DEF REAL {name}; or, if it is global user data, put its .DEF file beside the \
                         programs (or in a DEF folder there) or list it in [sinumerik] definitions in nctrans.toml"
                    );
                    ctx.error("NC341", span, &msg, &hint);
                    continue;
                }
            };
            let size: u32 = crate::ir::elements(&dims);
            let rule = rules.iter().find_map(|r| match r {
                VarRule::Name { name: n, number } if *n == name => Some(*number),
                _ => None,
            });
            let local_ok = temp || j.info.is_sub;
            let number = if let Some(n) = rule {
                let last = n.saturating_add(size - 1);
                // Off a Haas NGC the rule's ends are checked, as before; on one the whole
                // table must lie in one range (`gud::fits`: not across the NGC aliases).
                let fits = match ctx.haas_ngc {
                    true => gud::fits(n, last, false, true),
                    false if common(n) && common(last) => Ok(()),
                    false => Err("not a common variable".to_string()),
                };
                let local = j.info.is_sub && n >= 1 && last <= 33;
                if let (Err(why), false) = (fits, local) {
                    let at = if size > 1 && ctx.haas_ngc { format!("#{n}..#{last}") } else { format!("#{n}") };
                    let msg = format!("{name} would be {at}, {why}");
                    ctx.error("NC302", span, &msg, &format!("map it to {}", gud::homes(false, ctx.haas_ngc)));
                    continue;
                }
                Some(n)
            } else if local_ok {
                free_locals(&locals, size).or_else(|| alloc_common(&claimed, size))
            } else {
                alloc_common(&claimed, size)
            };
            let Some(n) = number else {
                ctx.error("NC302", span, &format!("no free variables left for {name}"), "free some with --var-map");
                continue;
            };
            if n <= 33 {
                for k in n..n + size {
                    locals[k as usize] = true;
                }
            } else {
                let mut ok = true;
                for k in n..n + size {
                    ok &= claim(ctx, k, name.clone(), span, &mut claimed);
                }
                if !ok {
                    continue;
                }
                if j.info.is_sub && !temp {
                    ctx.note(
                        "NC340",
                        span,
                        &format!("{name} of {} lives in common variable #{n}", j.name),
                        "the 33 locals are used up; a recursive or re-entrant call would share it",
                    );
                }
            }
            map.insert(name.clone(), (n, dims.clone()));
            let source = if let Some(axis) = name.strip_prefix(TEMP_PREFIX).and_then(|t| t.strip_prefix("SHIFT_")) {
                // The programmable shift ATRANS adds to (`frames::atrans`).
                format!("TRANS/ATRANS SHIFT {axis}")
            } else if name == format!("{TEMP_PREFIX}ROT_ANGLE") {
                // The angle of the chained rotation (`frame_chain`).
                "ROT/AROT ANGLE".to_string()
            } else if temp {
                "temporary".to_string()
            } else if dims.is_empty() {
                name.clone()
            } else {
                format!("{name}[…] ({size} elements)")
            };
            out.push(Mapped { program: Some(j.name.clone()), source, number: n });
        }
        let types = j.info;
        let scope = Scope { map: &map, refs: &refs, r_target: &r_target, r_offset, info: types, callees: &callees };
        byref::rewrite_calls(ctx, &mut j.prog.body, &scope);
        let mut errs: Vec<(Span, String)> = Vec::new();
        visit_vars(&mut j.prog.body, &mut |v| rewrite(v, &map, &refs, &r_target, r_offset, types, &mut errs));
        for (span, msg) in errs {
            ctx.unsupported(
                "NC342",
                span,
                &msg,
                "only $AA_IW, $AA_IM, $P_EP, $P_UIFR[1..6,axis,TR] (and writes of [7..54]), $P_F, $P_S and the part counters have FANUC counterparts",
            );
        }
    }
    out
}

fn free_locals(locals: &[bool; 34], size: u32) -> Option<u32> {
    (1..=33u32).find(|&n| n + size - 1 <= 33 && (n..n + size).all(|k| !locals[k as usize]))
}

fn axis_index(e: &Expr) -> Option<u32> {
    match &e.kind {
        ExprKind::Ident(s) | ExprKind::Str(s) => b"XYZABC".iter().position(|&c| s.as_bytes() == [c]).map(|p| p as u32),
        _ => None,
    }
}

fn system(name: &str, idx: &[Expr]) -> Option<u32> {
    match (name, idx) {
        ("AA_IW", [a]) => Some(5041 + axis_index(a)?),
        ("AA_IM", [a]) => Some(5021 + axis_index(a)?),
        ("P_EP", [a]) => Some(5001 + axis_index(a)?),
        // The F and S last programmed (`feed_reads` refuses the reads where they differ;
        // `words::sysunits` scales `$P_F` under G70).
        ("P_F", []) => Some(4109),
        ("P_S", []) => Some(4119),
        ("AC_ACTUAL_PARTS", []) => Some(3901),
        ("AC_REQUIRED_PARTS", []) => Some(3902),
        ("P_UIFR", [n, a, c]) => {
            let ExprKind::Num(n) = &n.kind else { return None };
            let tr = matches!(&c.kind, ExprKind::Ident(s) if s == "TR");
            // Frames 1..6: G54..G57 and G505/G506, which are FANUC G58/G59 (#5301+, #5321+).
            (tr && (1.0..=6.0).contains(&n.value) && n.value.fract() == 0.0)
                .then(|| 5221 + 20 * (n.value as u32 - 1) + axis_index(a).unwrap_or(99))
                .filter(|&k| k < 5221 + 20 * 6)
        }
        _ => None,
    }
}

fn rewrite(
    v: &mut VarRef,
    map: &HashMap<String, (u32, Vec<u32>)>,
    refs: &HashMap<String, RefParam>,
    r_target: &dyn Fn(u32) -> u32,
    r_offset: Option<u32>,
    info: &ProgInfo,
    errs: &mut Vec<(Span, String)>,
) {
    let span = v.span;
    let kind = std::mem::replace(&mut v.kind, VarKind::Hash(0));
    v.kind = match kind {
        VarKind::R(n) => VarKind::Hash(r_target(n)),
        VarKind::RIndirect(e) => {
            let off = r_offset.unwrap_or(500);
            VarKind::HashIndirect(Box::new(bin(BinOp::Add, *e, num(off as f64, span))))
        }
        VarKind::Named { name, indices } if refs.contains_key(&name) => {
            // A VAR parameter: its local holds the number of the caller's variable.
            let rp = &refs[&name];
            let base = var_expr(&VarRef { kind: VarKind::Hash(rp.var), span });
            let at = byref::plus_offset(base, &rp.dims, &indices, span);
            VarKind::HashIndirect(Box::new(at))
        }
        VarKind::Named { name, indices } => match map.get(&name) {
            None => {
                if !info.types.contains_key(&name) && !name.starts_with(TEMP_PREFIX) {
                    // Reported as undeclared already.
                }
                VarKind::Hash(0)
            }
            Some((n, dims)) if indices.is_empty() || dims.is_empty() => VarKind::Hash(*n),
            Some((n, dims)) => element(*n, dims, indices, span),
        },
        VarKind::System { name, indices } => match system(&name, &indices) {
            Some(n) => VarKind::Hash(n),
            None if name.eq_ignore_ascii_case("P_GG") => {
                errs.push((span, super::modal_reads::refusal(&indices)));
                VarKind::Hash(0)
            }
            None => {
                errs.push((span, format!("system variable ${name}")));
                VarKind::Hash(0)
            }
        },
        k => k,
    };
}

/// Element `indices` of an array stored row-major from `#base`.
fn element(base: u32, dims: &[u32], indices: Vec<Expr>, span: Span) -> VarKind {
    match byref::linear(dims, &indices, span) {
        // A constant offset: `linear` folds only whole, non-negative ones.
        Expr { kind: ExprKind::Num(n), .. } if n.value >= 0.0 && n.value.fract() == 0.0 => {
            VarKind::Hash(base + n.value as u32)
        }
        lin => VarKind::HashIndirect(Box::new(bin(BinOp::Add, lin, num(base as f64, span)))),
    }
}

/// Calls `f` on every variable reference, inner ones (in subscripts) first.
pub fn visit_vars(body: &mut [Stmt], f: &mut dyn FnMut(&mut VarRef)) {
    for s in body {
        match &mut s.kind {
            StmtKind::Block(b) => b.items.iter_mut().for_each(|i| visit_item(i, f)),
            StmtKind::If(i) => {
                visit_expr(&mut i.cond, f);
                visit_vars(&mut i.then_body, f);
                if let Some(e) = &mut i.else_part {
                    visit_vars(&mut e.body, f);
                }
            }
            StmtKind::While(w) => {
                visit_expr(&mut w.cond, f);
                visit_vars(&mut w.body, f);
            }
            StmtKind::Loop(l) => visit_vars(&mut l.body, f),
            StmtKind::For(x) => {
                visit_var(&mut x.var, f);
                visit_expr(&mut x.from, f);
                visit_expr(&mut x.to, f);
                visit_vars(&mut x.body, f);
            }
            StmtKind::Repeat(r) => {
                visit_vars(&mut r.body, f);
                visit_expr(&mut r.until, f);
            }
            StmtKind::Do(d) => {
                if let Some(c) = &mut d.cond {
                    visit_expr(c, f);
                }
                visit_vars(&mut d.body, f);
            }
        }
    }
}

fn visit_item(it: &mut Item, f: &mut dyn FnMut(&mut VarRef)) {
    let goto = |g: &mut Goto, f: &mut dyn FnMut(&mut VarRef)| {
        if let Some(c) = &mut g.cond {
            visit_expr(c, f);
        }
        if let Target::Computed(e) = &mut g.target {
            visit_expr(e, f);
        }
    };
    match &mut it.kind {
        ItemKind::Assign { target, value } => {
            visit_var(target, f);
            visit_expr(value, f);
        }
        ItemKind::Word(w) => match &mut w.value {
            WordValue::Expr(e) | WordValue::Ac(e) | WordValue::Ic(e) | WordValue::Rotary(_, e) => visit_expr(e, f),
        },
        ItemKind::Goto(g) => goto(g, f),
        ItemKind::IfThen { cond, then } => {
            visit_expr(cond, f);
            visit_item(then, f);
        }
        ItemKind::Case(c) => {
            visit_expr(&mut c.selector, f);
            for a in &mut c.arms {
                goto(&mut a.goto, f);
            }
        }
        ItemKind::Call(c) => {
            for a in &mut c.args {
                if let Arg::Value(e) | Arg::Letter { value: e, .. } = a {
                    visit_expr(e, f);
                }
            }
            if let Some(r) = &mut c.repeat {
                visit_expr(r, f);
            }
            if let CallTarget::Computed(e) = &mut c.target {
                visit_expr(e, f);
            }
        }
        ItemKind::Alarm { number, .. } => visit_expr(number, f),
        ItemKind::Message { text: Some(e) } => visit_expr(e, f),
        ItemKind::Return { to: Some(e) } => visit_expr(e, f),
        _ => {}
    }
}

fn visit_var(v: &mut VarRef, f: &mut dyn FnMut(&mut VarRef)) {
    match &mut v.kind {
        VarKind::HashIndirect(e) | VarKind::RIndirect(e) => visit_expr(e, f),
        VarKind::Named { indices, .. } => indices.iter_mut().for_each(|e| visit_expr(e, f)),
        _ => {}
    }
    f(v);
}

fn visit_expr(e: &mut Expr, f: &mut dyn FnMut(&mut VarRef)) {
    match &mut e.kind {
        ExprKind::Var(v) => visit_var(v, f),
        ExprKind::Unary(_, a) => visit_expr(a, f),
        ExprKind::Binary(_, a, b) | ExprKind::Cmp(_, _, a, b) => {
            visit_expr(a, f);
            visit_expr(b, f);
        }
        ExprKind::Func(_, args) => args.iter_mut().for_each(|a| visit_expr(a, f)),
        _ => {}
    }
}

#[cfg(test)]
mod tests {
    use super::super::build::*;
    use super::*;

    fn map(body: Vec<Stmt>, info: ProgInfo, rules: &[VarRule]) -> (Vec<Stmt>, Vec<Mapped>, Ctx) {
        let mut ctx = Ctx::new(0, UnsupportedPolicy::Error);
        let mut prog = program(body);
        let m = {
            let mut jobs = [Job { prog: &mut prog, info: &info, name: "MAIN".into(), file: 0 }];
            run(&mut ctx, &mut jobs, rules, 300)
        };
        (prog.body, m, ctx)
    }

    #[test]
    fn rules_parse() {
        assert_eq!(parse_rules("R0-R99=#100").unwrap_or_default(), vec![VarRule::R { lo: 0, hi: 99, base: 100 }]);
        assert_eq!(
            parse_rules("cnt=#150, R5=#600").unwrap_or_default(),
            vec![VarRule::Name { name: "CNT".into(), number: 150 }, VarRule::R { lo: 5, hi: 5, base: 600 }]
        );
        assert!(parse_rules("R1=100").is_err());
    }

    #[test]
    fn r_defaults_to_500_plus_n_and_def_to_commons() {
        let mut info = ProgInfo::default();
        info.types.insert("CNT".into(), (DataType::Int, vec![]));
        let body = vec![block(vec![assign(rv(1), var_expr(&named("CNT")))])];
        let (_, m, ctx) = map(body, info, &[]);
        assert!(ctx.diags.is_empty(), "{:?}", ctx.diags);
        assert_eq!(m.iter().map(|x| (x.source.as_str(), x.number)).collect::<Vec<_>>(), [("R1", 501), ("CNT", 100)]);
    }

    #[test]
    fn collisions_and_ranges_are_errors() {
        let mut info = ProgInfo::default();
        info.types.insert("CNT".into(), (DataType::Int, vec![]));
        let body = vec![block(vec![assign(rv(5), var_expr(&named("CNT")))])];
        let rules = parse_rules("CNT=#505").unwrap_or_default();
        let (_, _, ctx) = map(body.clone(), info.clone(), &rules);
        assert_eq!(ctx.diags[0].code, "NC302");
        let (_, _, ctx) = map(vec![block(vec![assign(rv(600), n(1.0))])], ProgInfo::default(), &[]);
        assert!(ctx.diags[0].message.contains("past #999"));
        let rules = parse_rules("R5=#1000").unwrap_or_default();
        let (_, _, ctx) = map(body, info, &rules);
        assert!(ctx.diags.iter().any(|d| d.message.contains("#1000")));
    }

    #[test]
    fn indirect_r_keeps_its_offset() {
        let ind = VarRef { kind: VarKind::RIndirect(Box::new(r(1))), span: sp() };
        let (body, _, _) = map(vec![block(vec![assign(ind, n(1.0))])], ProgInfo::default(), &[]);
        let text = format!("{body:?}");
        assert!(text.contains("HashIndirect") && text.contains("value: 500.0"));
    }
}
