//! Siemens axes named by a value (`AX[e]`, `AXNAME(…)`, `DEF AXIS v`) to FANUC's fixed
//! letters, where the axis is known at translation time: `AXNAME("Z")` and
//! `AXNAME(AXIS_HORI)` of a STRING the set-up fixes (`[variables] fixed`, `Ctx::fixed`) are
//! that axis; a program's own scalar `DEF AXIS v` is one axis when every write of it (its
//! initial value, every assignment anywhere) is that same known axis, a write comes before
//! every read on every path, and it is read only as an axis (`AX[v]`, `POS[v]`, `FGROUP(v)`,
//! another AXIS variable's value). `G1 AX[v]=10` is then the word `Z10` the words pass writes
//! as any Z word; the DEF and the assignments go (so do a local STRING that only copies
//! set-up values and is never read, and an AXIS variable nothing uses). Where the axis is not known the reason is
//! said (NC542: two axes, a parameter, a read before any write; NC543: a global STRING no
//! `[variables] fixed` entry gives, an axis the FANUC profile lacks; NC544: a program writes a
//! fixed value); anything else keeps the general refusal (NC310 for the DEF, NC635 for AX[…]).
//! Runs first in [`super::lower_program`], before `blocks` sees the DEFs.

use super::{Ctx, Span};
use crate::ir::*;
use std::collections::BTreeMap;

/// The axes the FANUC writer spells as address letters (`words::AXES`).
const FANUC_AXES: &[u8] = b"XYZABCUVW";

/// Why an axis is not known: the code and reason to refuse it; `None`: the general refusal.
type Why = Option<(&'static str, String)>;

/// What an axis expression names at translation time.
enum Axis {
    /// The upper-case axis name, with the set-up values it rests on.
    Known(String, Vec<String>),
    /// Not known, and why.
    Unknown(Why),
}

struct Facts<'a> {
    fixed: &'a BTreeMap<String, String>,
    /// STRING global user data (upper-case names).
    gud_strings: Vec<String>,
    params: Vec<String>,
    /// Local AXIS variables resolved so far: name → axis and the set-up values used.
    known: BTreeMap<String, (String, Vec<String>)>,
    /// Local AXIS variables refused, with the code and reason (`None`: general refusal).
    refused: BTreeMap<String, Why>,
    /// Local AXIS variables without initial value that the program neither reads nor
    /// writes: they change nothing the machine does, and go.
    unused: Vec<String>,
    /// Local scalar STRING variables the program never reads, written only with set-up
    /// values (`HORIZONTAL_AX=AXIS_HORI`): copies of axis names nothing uses, gone.
    dead_strings: Vec<String>,
}

fn named(e: &Expr) -> Option<&str> {
    match &e.kind {
        ExprKind::Var(v) => match &v.kind {
            VarKind::Named { name, indices } if indices.is_empty() => Some(name),
            _ => None,
        },
        _ => None,
    }
}

impl Facts<'_> {
    /// Whether a write of `name` writes a value the set-up fixes (NC544).
    fn writes_fixed(&self, name: &str) -> bool {
        self.fixed.contains_key(name) && self.gud_strings.iter().any(|g| g == name)
    }

    fn axis_of(&self, e: &Expr) -> Axis {
        match &e.kind {
            ExprKind::Str(t) => Axis::Known(t.trim().to_ascii_uppercase(), vec![]),
            ExprKind::Ident(t) => Axis::Known(t.to_ascii_uppercase(), vec![]),
            ExprKind::Func(Func::AxName, args) if args.len() == 1 => match &args[0].kind {
                ExprKind::Str(t) => Axis::Known(t.trim().to_ascii_uppercase(), vec![]),
                _ => self.string_value(&args[0]),
            },
            _ => match named(e) {
                Some(n) if self.known.contains_key(n) => {
                    let (a, used) = &self.known[n];
                    Axis::Known(a.clone(), used.clone())
                }
                Some(n) if self.refused.contains_key(n) => {
                    Axis::Unknown(self.refused[n].clone().map(|(c, why)| (c, format!("{n} {why}"))))
                }
                Some(_) => self.string_value(e),
                None => Axis::Unknown(None),
            },
        }
    }

    /// The axis a STRING-valued name gives (`AXNAME(AXIS_HORI)`, `AX[AXIS_HORI]`).
    fn string_value(&self, e: &Expr) -> Axis {
        match named(e) {
            Some(n) if self.fixed.contains_key(n) && self.gud_strings.iter().any(|g| g == n) => {
                Axis::Known(self.fixed[n].trim().to_ascii_uppercase(), vec![n.to_string()])
            }
            Some(n) if self.gud_strings.iter().any(|g| g == n) => Axis::Unknown(Some((
                "NC543",
                format!("{n} is global user data that no [variables] fixed entry gives, so its axis is known only at run time"),
            ))),
            Some(n) if self.params.iter().any(|p| p == n) => Axis::Unknown(Some((
                "NC542",
                format!("{n} is a parameter: each caller chooses the axis"),
            ))),
            _ => Axis::Unknown(None),
        }
    }
}

/// Every item of `body`, nested ones (IF-THEN, sync actions) included, in source order.
fn each_item<'a>(body: &'a [Stmt], f: &mut dyn FnMut(&'a Item)) {
    fn item<'a>(it: &'a Item, f: &mut dyn FnMut(&'a Item)) {
        f(it);
        match &it.kind {
            ItemKind::IfThen { then, .. } => item(then, f),
            ItemKind::IfBlock { items, .. } => items.iter().for_each(|i| item(i, f)),
            ItemKind::SyncAction(a) => a.actions.iter().for_each(|i| item(i, f)),
            _ => {}
        }
    }
    crate::ir::visit::walk_stmts(body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            b.items.iter().for_each(|it| item(it, f));
        }
    });
}

/// The expressions an item reads, its axis addresses included (nested items are their own).
fn item_reads(it: &Item) -> Vec<&Expr> {
    let mut v = crate::ir::visit::item_exprs(it);
    let words: &[Word] = match &it.kind {
        ItemKind::Word(w) => std::slice::from_ref(w),
        ItemKind::Frame { words, .. } => words,
        _ => &[],
    };
    for w in words {
        if let Addr::Axis(e) = &w.addr {
            v.push(e);
        }
    }
    v
}

fn uses(e: &Expr, name: &str) -> usize {
    usize::from(named(e) == Some(name)) + e.children().into_iter().map(|c| uses(c, name)).sum::<usize>()
}

/// Reads of `name` in a statement, with its conditions and nested statements.
fn stmt_uses(s: &Stmt, name: &str) -> usize {
    let mut n = 0;
    crate::ir::visit::walk_stmts(std::slice::from_ref(s), &mut |x| {
        let conds: Vec<&Expr> = match &x.kind {
            StmtKind::Block(_) => vec![],
            StmtKind::If(i) => vec![&i.cond],
            StmtKind::While(w) => vec![&w.cond],
            StmtKind::For(f) => vec![&f.from, &f.to],
            StmtKind::Repeat(r) => vec![&r.until],
            StmtKind::Do(d) => d.cond.iter().collect(),
            StmtKind::Loop(_) => vec![],
        };
        n += conds.iter().map(|c| uses(c, name)).sum::<usize>();
    });
    each_item(std::slice::from_ref(s), &mut |it| n += item_reads(it).iter().map(|e| uses(e, name)).sum::<usize>());
    n
}

fn is_jump(it: &Item) -> bool {
    matches!(it.kind, ItemKind::Goto(_) | ItemKind::Case(_) | ItemKind::RepeatSection(_))
}

fn is_write_of(it: &Item, name: &str) -> bool {
    matches!(&it.kind, ItemKind::Assign { target, .. } if matches!(&target.kind, VarKind::Named { name: n, indices } if n == name && indices.is_empty()))
}

/// Positioning-axis targets whose subscript is an axis (`POS[X]=…`).
const AXIS_INDEXED: [&str; 3] = ["POS", "POSA", "FA"];

/// How many reads of `name` stand where an axis goes.
fn axis_uses(p: &Program, name: &str, axis_vars: &[String]) -> usize {
    let mut n = 0;
    each_item(&p.body, &mut |it| match &it.kind {
        ItemKind::Word(w) => n += usize::from(matches!(&w.addr, Addr::Axis(e) if named(e) == Some(name))),
        ItemKind::Frame { words, .. } => {
            n += words.iter().filter(|w| matches!(&w.addr, Addr::Axis(e) if named(e) == Some(name))).count()
        }
        ItemKind::Assign { target, value } => {
            if let VarKind::Named { name: t, indices } = &target.kind {
                if AXIS_INDEXED.contains(&t.as_str()) && indices.len() == 1 && named(&indices[0]) == Some(name) {
                    n += 1;
                }
                if axis_vars.contains(t) && indices.is_empty() && named(value) == Some(name) {
                    n += 1;
                }
            }
        }
        ItemKind::Call(c) if matches!(&c.target, CallTarget::Name(t) if t.eq_ignore_ascii_case("FGROUP")) => {
            n += c.args.iter().filter(|a| matches!(a, Arg::Value(e) if named(e) == Some(name))).count()
        }
        _ => {}
    });
    n
}

/// Whether a write of `name` comes before every read on every path: a top-level write
/// with no read of it and no jump (which could pass the write) before it.
fn written_first(p: &Program, name: &str) -> Result<(), String> {
    for s in &p.body {
        if let StmtKind::Block(b) = &s.kind {
            for it in &b.items {
                if is_write_of(it, name) {
                    return Ok(());
                }
                if is_jump(it) {
                    return Err("may be read unset: a jump before its first assignment can pass it".into());
                }
                if item_reads(it).iter().any(|e| uses(e, name) > 0) {
                    return Err("may be read unset: it is read before any assignment outside IF, loops or jumps".into());
                }
            }
            continue;
        }
        let mut jump = false;
        each_item(std::slice::from_ref(s), &mut |it| jump |= is_jump(it));
        if jump || stmt_uses(s, name) > 0 {
            return Err(
                "may be read unset: a path reads it (or jumps past its assignment) before any assignment".into()
            );
        }
    }
    Err("may be read unset: no assignment outside IF, loops or jumps comes before its reads".into())
}

/// The one axis a local `DEF AXIS` variable holds, or why there is none.
fn verdict(f: &Facts, p: &Program, v: &DefVar, axis_vars: &[String]) -> Result<(String, Vec<String>), Why> {
    let name = v.name.as_str();
    let mut values: Vec<Expr> = match &v.init {
        Some(Init::Value(e)) => vec![e.clone()],
        _ => vec![],
    };
    let mut other_write = false;
    each_item(&p.body, &mut |it| {
        if let ItemKind::Assign { target, value } = &it.kind {
            if is_write_of(it, name) {
                values.push(value.clone());
            } else if matches!(&target.kind, VarKind::Named { name: n, .. } if n == name) {
                other_write = true;
            }
        }
    });
    crate::ir::visit::walk_stmts(&p.body, &mut |s| {
        other_write |=
            matches!(&s.kind, StmtKind::For(x) if matches!(&x.var.kind, VarKind::Named { name: n, .. } if n == name));
    });
    if other_write {
        return Err(None);
    }
    let mut axes: Vec<String> = Vec::new();
    let mut used = Vec::new();
    for e in &values {
        match f.axis_of(e) {
            Axis::Known(a, u) => {
                if !axes.contains(&a) {
                    axes.push(a);
                }
                used.extend(u);
            }
            Axis::Unknown(Some((code, why))) => {
                return Err(Some((code, format!("is written from a value where {why}"))))
            }
            Axis::Unknown(None) => return Err(None),
        }
    }
    match axes.as_slice() {
        [] => return Err(Some(("NC542", "is never assigned an axis".into()))),
        [_] => {}
        [a, b, ..] => {
            let why = format!("holds two different axes ({a} and {b}), so AX[{name}] names an axis only the run knows");
            return Err(Some(("NC542", why)));
        }
    }
    let total: usize = p.body.iter().map(|s| stmt_uses(s, name)).sum();
    if total != axis_uses(p, name, axis_vars) {
        return Err(None);
    }
    if v.init.is_none() {
        written_first(p, name).map_err(|why| Some(("NC542", why)))?;
    }
    used.sort();
    used.dedup();
    Ok((axes.remove(0), used))
}

/// The FANUC letter of a known axis, or why the FANUC profile has none.
fn letter(axis: &str, used: &[String]) -> Result<u8, (&'static str, String)> {
    match axis.as_bytes() {
        [l] if FANUC_AXES.contains(l) => Ok(*l),
        _ => {
            let from =
                if used.is_empty() { String::new() } else { format!(" (from {}, [variables] fixed)", used.join(", ")) };
            Err(("NC543", format!("axis \"{axis}\"{from} is not an axis of the FANUC profile (X Y Z A B C U V W)")))
        }
    }
}

/// Resolves the axes of `prog` that are known at translation time (see the module text).
pub fn run(ctx: &mut Ctx, prog: &mut Program) {
    let fixed = ctx.fixed.clone();
    let gud_strings: Vec<String> = ctx
        .globals
        .iter()
        .filter(|d| matches!(d.ty, DataType::String(_)))
        .flat_map(|d| d.vars.iter().filter(|v| v.dims.is_empty()).map(|v| v.name.clone()))
        .collect();
    let mut f = Facts {
        fixed: &fixed,
        gud_strings,
        params: prog.params.iter().map(|p| p.name.clone()).collect(),
        known: BTreeMap::new(),
        refused: BTreeMap::new(),
        unused: Vec::new(),
        dead_strings: Vec::new(),
    };
    let mut defs: Vec<DefVar> = Vec::new();
    each_item(&prog.body, &mut |it| {
        if let ItemKind::Def(d) = &it.kind {
            if d.ty == DataType::Axis && d.scope.is_none() {
                defs.extend(d.vars.iter().filter(|v| v.dims.is_empty()).cloned());
            }
        }
    });
    f.dead_strings = dead_strings(&f, prog);
    let axis_vars: Vec<String> = defs.iter().map(|v| v.name.clone()).collect();
    for v in &defs {
        let mut written = false;
        each_item(&prog.body, &mut |it| written |= is_write_of(it, &v.name));
        if v.init.is_none() && !written && prog.body.iter().all(|s| stmt_uses(s, &v.name) == 0) {
            f.unused.push(v.name.clone());
            continue;
        }
        match verdict(&f, prog, v, &axis_vars).and_then(|(a, used)| match letter(&a, &used) {
            Ok(_) => Ok((a, used)),
            Err(r) => Err(Some(r)),
        }) {
            Ok(k) => {
                f.known.insert(v.name.clone(), k);
            }
            Err(why) => {
                if let Some((code, why)) = &why {
                    let what = format!("DEF AXIS {} ({} {why})", v.name, v.name);
                    ctx.unsupported(code, v.span, &what, "FANUC addresses are fixed letters: write the axis letter");
                    ctx.axis_reported.insert(v.span);
                }
                f.refused.insert(v.name.clone(), why);
            }
        }
    }
    for (_, used) in f.known.values() {
        for u in used {
            ctx.fixed_used.insert(u.clone(), fixed[u].clone());
        }
    }
    rewrite(ctx, &f, &mut prog.body);
}

/// The local STRING variables that only copy set-up values (at least once) and are never read.
fn dead_strings(f: &Facts, p: &Program) -> Vec<String> {
    let mut strings: Vec<DefVar> = Vec::new();
    each_item(&p.body, &mut |it| {
        if let ItemKind::Def(d) = &it.kind {
            if matches!(d.ty, DataType::String(_)) && d.scope.is_none() {
                strings.extend(d.vars.iter().filter(|v| v.dims.is_empty()).cloned());
            }
        }
    });
    let copied = |e: &Expr| named(e).is_some_and(|n| f.fixed.contains_key(n) && f.gud_strings.iter().any(|g| g == n));
    strings
        .into_iter()
        .filter(|v| {
            let mut ok = v.init.as_ref().is_none_or(|i| matches!(i, Init::Value(e) if copied(e)));
            let mut writes = usize::from(v.init.is_some());
            each_item(&p.body, &mut |it| {
                if let ItemKind::Assign { target, value } = &it.kind {
                    if matches!(&target.kind, VarKind::Named { name, .. } if *name == v.name) {
                        ok &= is_write_of(it, &v.name) && copied(value);
                        writes += 1;
                    }
                }
            });
            crate::ir::visit::walk_stmts(&p.body, &mut |s| {
                ok &= !matches!(&s.kind, StmtKind::For(x) if matches!(&x.var.kind, VarKind::Named { name, .. } if *name == v.name));
            });
            ok && writes > 0 && p.body.iter().all(|s| stmt_uses(s, &v.name) == 0)
        })
        .map(|v| v.name)
        .collect()
}

/// Besides the assignments that are now axis letters, the writes this pass refused saying
/// why go too (of an AXIS variable refused NC542/NC543, of a fixed value NC544): the
/// translation fails on that refusal, and the general refusals of their values (NC632
/// `AXNAME`, NC314 a string, NC504 a STRING GUD) would only say it again.
fn rewrite(ctx: &mut Ctx, f: &Facts, body: &mut Vec<Stmt>) {
    let gone = |it: &Item| match &it.kind {
        ItemKind::Assign { target, .. } => matches!(&target.kind, VarKind::Named { name, indices }
            if indices.is_empty() && (f.known.contains_key(name) || f.dead_strings.contains(name)
                || f.refused.get(name).is_some_and(Option::is_some) || f.writes_fixed(name))),
        ItemKind::Def(d) => d.vars.is_empty(),
        _ => false,
    };
    body.retain_mut(|s| match &mut s.kind {
        StmtKind::Block(b) => {
            let had = b.items.len();
            for it in &mut b.items {
                item(ctx, f, it);
            }
            b.items.retain(|it| !gone(it));
            // A block that held only what went, with no label, number or comment of its own.
            let m = &b.meta;
            !(had > 0 && b.items.is_empty() && m.label.is_none() && m.number.is_none() && m.comments.is_empty())
        }
        other => {
            for child in crate::ir::visit::child_bodies_mut(other) {
                rewrite(ctx, f, child);
            }
            true
        }
    });
}

fn item(ctx: &mut Ctx, f: &Facts, it: &mut Item) {
    match &mut it.kind {
        ItemKind::Word(w) => word(ctx, f, w),
        ItemKind::Frame { words, .. } => words.iter_mut().for_each(|w| word(ctx, f, w)),
        ItemKind::Def(d) if d.ty == DataType::Axis && d.scope.is_none() => {
            d.vars.retain(|v| !f.known.contains_key(&v.name) && !f.unused.contains(&v.name));
        }
        ItemKind::Def(d) if matches!(d.ty, DataType::String(_)) && d.scope.is_none() => {
            d.vars.retain(|v| !f.dead_strings.contains(&v.name));
        }
        ItemKind::Assign { target, .. } => {
            if let VarKind::Named { name, indices } = &mut target.kind {
                if f.writes_fixed(name) {
                    let what = format!("a write to {name} (a value [variables] fixed says the set-up fixes)");
                    let hint = "no program may write a value the set-up fixes: take it out of [variables] fixed, or the write out of the program";
                    ctx.unsupported(crate::dialect::fixed::WRITTEN, it.span, &what, hint);
                } else if AXIS_INDEXED.contains(&name.as_str()) && indices.len() == 1 {
                    known_ident(ctx, f, &mut indices[0]);
                }
            }
        }
        ItemKind::Call(c) if matches!(&c.target, CallTarget::Name(t) if t.eq_ignore_ascii_case("FGROUP")) => {
            for a in &mut c.args {
                if let Arg::Value(e) = a {
                    known_ident(ctx, f, e);
                }
            }
        }
        ItemKind::IfThen { then, .. } => item(ctx, f, then),
        ItemKind::IfBlock { items, .. } => items.iter_mut().for_each(|i| item(ctx, f, i)),
        ItemKind::SyncAction(a) => a.actions.iter_mut().for_each(|i| item(ctx, f, i)),
        _ => {}
    }
}

/// A known axis as the bare axis name (`POS[Z]`, `FGROUP(Z)`); the construct itself is
/// then translated, or refused, as it is with a written axis.
fn known_ident(ctx: &mut Ctx, f: &Facts, e: &mut Expr) {
    if matches!(e.kind, ExprKind::Ident(_)) {
        return;
    }
    if let Axis::Known(axis, used) = f.axis_of(e) {
        for u in used {
            ctx.fixed_used.insert(u.clone(), f.fixed[&u].clone());
        }
        e.kind = ExprKind::Ident(axis);
    }
}

fn word(ctx: &mut Ctx, f: &Facts, w: &mut Word) {
    let Addr::Axis(e) = &w.addr else { return };
    let span: Span = w.span;
    match f.axis_of(e) {
        Axis::Known(a, used) => match letter(&a, &used) {
            Ok(l) => {
                for u in used {
                    ctx.fixed_used.insert(u.clone(), f.fixed[&u].clone());
                }
                w.addr = Addr::Letter(l);
            }
            Err((code, why)) => refuse(ctx, code, span, &why),
        },
        Axis::Unknown(Some((code, why))) => refuse(ctx, code, span, &why),
        Axis::Unknown(None) => {}
    }
}

fn refuse(ctx: &mut Ctx, code: &'static str, span: Span, why: &str) {
    let what = format!("AX[…] ({why})");
    ctx.unsupported(code, span, &what, "FANUC addresses are fixed letters: write the axis letter");
    ctx.axis_reported.insert(span);
}
