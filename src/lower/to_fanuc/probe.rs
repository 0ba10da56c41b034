//! Siemens measuring blocks on FANUC: `MEAS=1 G1 X.. F..` (probe 1, rising edge, the rest
//! of the move deleted at the trigger) is `G31 X.. F..` (skip signal 1, a G1 move that stops
//! where the signal arrives). The measured values do not carry over: Siemens keeps
//! `$AA_MW`/`$AA_MM` from the last probe that switched and tells it by `$AC_MEA`, FANUC has
//! no such flag and writes the end point into `#5061+` on a miss, so those reads stay
//! refused (NC342, `varmap`). MEAW (the move goes on to its end point), the falling edge and
//! probe 2 have no G31 form (NC540); a measuring block without G1 in it is refused too
//! (NC541), since G31 does not say which motion mode holds after it.
//!
//! The one form of reading the measurement that FANUC has, right after the measuring block
//! (STOPRE between allowed): `IF $AC_MEA[1]==1 T=$AA_MW[X] ELSE T=$AA_IW[X] ENDIF` for an axis
//! of the block is `T=#5061` (the trigger point on a hit, the end point on a miss, on both
//! controls); it is what the FANUC → Sinumerik translation writes, so a round trip comes back.
//! The same `+R` in both branches (the FANUC → Sinumerik keep of Z under G43 adds the edge's
//! length) is `T=#5061+R`, which `probe_length` settles against the G43 H at the G31.
//!
//! Runs around [`super::words`]: [`take`] removes the `MEAS=` word (words would refuse the
//! address) and the block's `G1`, remembering the block; [`put`] then writes `G31` into it,
//! with a `G1` block after it so the motion mode after the block is G1 as on Siemens (after,
//! not before: a jump to the block's label or N number must meet it too).

use super::*;
use std::collections::BTreeMap;

/// Removes `MEAS=1` and `G1` from every measuring block; the spans of those blocks.
pub fn take(ctx: &mut Ctx, prog: &mut Program) -> Vec<Span> {
    let mut found = Vec::new();
    let own = own_names(&prog.body);
    let body = std::mem::take(&mut prog.body);
    prog.body = crate::lower::map_bodies(body, &mut |list: Vec<Stmt>| {
        let mut out = Vec::with_capacity(list.len());
        // The axes of the measuring block just taken, while only STOPRE blocks follow it.
        let mut after: Option<Vec<usize>> = None;
        for mut s in list {
            // The DEF of a translation's own skip variable (its reads become `#5061+`).
            if own_write(&s, &own).is_some_and(|v| crate::lower::literal(v) == Some(0.0)) {
                continue;
            }
            if let Some(axes) = &after {
                if is_stopre(&s) {
                    out.push(s);
                    continue;
                }
                if let Some(kept) = skip_idiom(&s, axes) {
                    // The Z keeps, for the length the G43 H at the G31 adds (`probe_length`).
                    if let Some(&meas) = found.last() {
                        for k in kept.iter().filter(|k| is_z_keep(k)) {
                            ctx.z_keeps.push((meas, k.span));
                        }
                    }
                    for k in &kept {
                        if let (Some(v), Some(&meas)) = (own_write(k, &own), found.last()) {
                            own_keep(ctx, meas, v, "#5063");
                        }
                    }
                    out.extend(kept.into_iter().filter(|k| own_write(k, &own).is_none()));
                    continue;
                }
                // An axis the block does not move: FANUC keeps where it stands, as `$AA_IW`.
                if let Some(v) = own_write(&s, &own).filter(|v| kept_axis(v, "AA_IW").is_some()) {
                    if let Some(&meas) = found.last() {
                        own_keep(ctx, meas, v, "AA_IW");
                    }
                    continue;
                }
                after = None;
            }
            if let StmtKind::Block(b) = &mut s.kind {
                if let Some(at) = b.items.iter().position(measuring_word) {
                    let isp = b.items[at].span;
                    let ok = match &b.items[at].kind {
                        ItemKind::Word(w) => {
                            let meaw = matches!(&w.addr, Addr::Name(n) if n.eq_ignore_ascii_case("MEAW"));
                            let one = matches!(&w.value, WordValue::Expr(e) if crate::lower::literal(e) == Some(1.0));
                            !meaw && one
                        }
                        _ => false,
                    };
                    let g1 = b.items.iter().position(|it| g_of(it) == Some(1.0));
                    if !ok {
                        out.extend(ctx.unsupported(
                            "NC540",
                            isp,
                            "a measuring word other than MEAS=1 (MEAW goes on to the end point; the falling edge and probe 2 have no G31 form)",
                            "probe with MEAS=1 (FANUC G31: skip signal 1, the move stops at the signal)",
                        ));
                        // The whole block is refused (a marked comment under warn).
                        continue;
                    } else if g1.is_none() {
                        out.extend(ctx.unsupported(
                            "NC541",
                            isp,
                            "a measuring block (MEAS=1) without G1 in it",
                            "write G1 in the measuring block: MEAS=1 G1 X.. F..",
                        ));
                        continue;
                    } else {
                        let g1 = g1.unwrap_or(0);
                        let (hi, lo) = if g1 > at { (g1, at) } else { (at, g1) };
                        b.items.remove(hi);
                        b.items.remove(lo);
                        found.push(s.span);
                        after = Some(b.items.iter().filter_map(axis_of).collect());
                    }
                }
            }
            out.push(s);
        }
        out
    });
    if !own.is_empty() {
        let mut z_reads = Vec::new();
        crate::lower::map_exprs(&mut prog.body, &mut |e: &mut Expr| own_reads(e, &own, &mut z_reads));
        ctx.own_z_reads = z_reads;
    }
    found
}

/// The translation's own skip variables (`NCTRANS_SKIP_X`, written by the FANUC → Sinumerik
/// translation and reserved for it) and their axes, where every write of them is its DEF
/// (0) or a kept skip position of that axis (`$AA_MW`/`$AA_IW`): their reads are `#5061+`.
fn own_names(body: &[Stmt]) -> BTreeMap<String, usize> {
    let mut names = BTreeMap::new();
    let mut bad = std::collections::BTreeSet::new();
    let mut stack: Vec<&Stmt> = body.iter().collect();
    while let Some(s) = stack.pop() {
        match &s.kind {
            StmtKind::Block(b) => {
                for it in &b.items {
                    let ItemKind::Assign { target, value } = &it.kind else { continue };
                    let VarKind::Named { name, indices } = &target.kind else { continue };
                    let Some(axis) = name.strip_prefix("NCTRANS_SKIP_").and_then(|a| AXES.iter().position(|x| *x == a))
                    else {
                        continue;
                    };
                    let kept = [kept_axis(value, "AA_MW"), kept_axis(value, "AA_IW")].contains(&Some(axis));
                    if indices.is_empty() && (kept || crate::lower::literal(value) == Some(0.0)) {
                        names.insert(name.clone(), axis);
                    } else {
                        bad.insert(name.clone());
                    }
                }
            }
            StmtKind::If(i) => {
                stack.extend(i.then_body.iter());
                if let Some(e) = &i.else_part {
                    stack.extend(e.body.iter());
                }
            }
            StmtKind::While(w) => stack.extend(w.body.iter()),
            StmtKind::Loop(l) => stack.extend(l.body.iter()),
            StmtKind::For(x) => stack.extend(x.body.iter()),
            StmtKind::Repeat(r) => stack.extend(r.body.iter()),
            StmtKind::Do(d) => stack.extend(d.body.iter()),
        }
    }
    names.retain(|n, _| !bad.contains(n));
    names
}

/// `$NAME[axis]` or `$NAME[axis]+R` (the keep of Z under G43 adds the edge's length): the axis.
fn kept_axis(e: &Expr, name: &str) -> Option<usize> {
    match &e.kind {
        ExprKind::Binary(BinOp::Add, x, _) => sys_axis(x, name),
        _ => sys_axis(e, name),
    }
}

/// Records a dropped keep of the translation's own Z skip variable (`value`, written after the
/// measuring block `meas`; `skip`: its `#5063` form or its Siemens one): its `+R`, which
/// `probe_length` proves is the length FANUC's `#5063` holds.
fn own_keep(ctx: &mut Ctx, meas: Span, value: &Expr, skip: &str) {
    let z =
        |e: &Expr| sys_axis(e, skip) == Some(2) || matches!(&e.kind, ExprKind::Var(v) if v.kind == VarKind::Hash(5063));
    match &value.kind {
        ExprKind::Binary(BinOp::Add, x, r) if z(x) => ctx.own_z_keeps.push((meas, Some((**r).clone()))),
        _ if z(value) => ctx.own_z_keeps.push((meas, None)),
        _ => {}
    }
}

/// The value `s` writes to one of `own`, when it is a block of that one assignment.
fn own_write<'a>(s: &'a Stmt, own: &BTreeMap<String, usize>) -> Option<&'a Expr> {
    let StmtKind::Block(b) = &s.kind else { return None };
    match b.items.as_slice() {
        [Item { kind: ItemKind::Assign { target, value }, .. }] if !crate::lower::meta_is_marked(&b.meta) => {
            matches!(&target.kind, VarKind::Named { name, .. } if own.contains_key(name)).then_some(value)
        }
        _ => None,
    }
}

fn own_reads(e: &mut Expr, own: &BTreeMap<String, usize>, z: &mut Vec<Span>) {
    if let ExprKind::Var(v) = &mut e.kind {
        if let VarKind::Named { name, indices } = &v.kind {
            if let (Some(&a), true) = (own.get(name), indices.is_empty()) {
                v.kind = VarKind::Hash(5061 + a as u32);
                if a == 2 {
                    z.push(v.span);
                }
            }
            return;
        }
    }
    match &mut e.kind {
        ExprKind::Var(v) => match &mut v.kind {
            VarKind::System { indices, .. } | VarKind::Named { indices, .. } => {
                indices.iter_mut().for_each(|x| own_reads(x, own, z))
            }
            VarKind::HashIndirect(x) | VarKind::RIndirect(x) => own_reads(x, own, z),
            _ => {}
        },
        ExprKind::Binary(_, a, b) | ExprKind::Cmp(_, _, a, b) => {
            own_reads(a, own, z);
            own_reads(b, own, z);
        }
        ExprKind::Unary(_, a) => own_reads(a, own, z),
        ExprKind::Func(_, args) => args.iter_mut().for_each(|x| own_reads(x, own, z)),
        _ => {}
    }
}

fn measuring_word(it: &Item) -> bool {
    matches!(&it.kind, ItemKind::Word(Word { addr: Addr::Name(n), .. })
        if n.eq_ignore_ascii_case("MEAS") || n.eq_ignore_ascii_case("MEAW"))
}

fn g_of(it: &Item) -> Option<f64> {
    match &it.kind {
        ItemKind::Word(Word { addr: Addr::Letter(b'G'), value: WordValue::Expr(e), .. }) => crate::lower::literal(e),
        _ => None,
    }
}

fn g_word(v: f64, span: Span) -> Item {
    item(ItemKind::Word(Word { addr: Addr::Letter(b'G'), value: WordValue::Expr(num(v, span)), span }), span)
}

/// Writes `G31` into the blocks [`take`] found (`G1` in a block of its own after each).
pub fn put(prog: &mut Program, blocks: &[Span]) {
    if blocks.is_empty() {
        return;
    }
    let body = std::mem::take(&mut prog.body);
    prog.body = crate::lower::map_bodies(body, &mut |list: Vec<Stmt>| {
        let mut out = Vec::with_capacity(list.len());
        let mut list = list.into_iter().peekable();
        while let Some(mut s) = list.next() {
            if let StmtKind::Block(b) = &mut s.kind {
                if blocks.contains(&s.span) {
                    b.items.insert(0, g_word(31.0, s.span));
                    let span = s.span;
                    out.push(s);
                    // Not where the next block selects the motion mode itself (a round
                    // trip would add a block each time).
                    if !list.peek().is_some_and(selects_motion) {
                        out.push(block_stmt(vec![g_word(1.0, span)], span));
                    }
                    continue;
                }
            }
            out.push(s);
        }
        out
    });
}

const AXES: [&str; 6] = ["X", "Y", "Z", "A", "B", "C"];

/// A block that selects G0, G1, G2 or G3 itself.
pub(crate) fn selects_motion(s: &Stmt) -> bool {
    matches!(&s.kind, StmtKind::Block(b) if b.meta.skip.is_none() && b.items.iter().any(|it| matches!(g_of(it), Some(g) if [0.0, 1.0, 2.0, 3.0].contains(&g))))
}

/// The axis (X Y Z A B C, index) an address word positions.
fn axis_of(it: &Item) -> Option<usize> {
    match &it.kind {
        ItemKind::Word(Word { addr: Addr::Letter(l), .. }) => AXES.iter().position(|a| a.as_bytes()[0] == *l),
        _ => None,
    }
}

fn is_stopre(s: &Stmt) -> bool {
    matches!(&s.kind, StmtKind::Block(b) if !b.items.is_empty() && b.items.iter().all(|it| matches!(it.kind, ItemKind::Stopre)))
}

/// `$NAME[axis]` with one axis index: the axis.
fn sys_axis(e: &Expr, name: &str) -> Option<usize> {
    let ExprKind::Var(v) = &e.kind else { return None };
    let VarKind::System { name: n, indices } = &v.kind else { return None };
    if !n.eq_ignore_ascii_case(name) || indices.len() != 1 {
        return None;
    }
    let id = match &indices[0].kind {
        ExprKind::Ident(s) => s.clone(),
        ExprKind::Var(v) => match &v.kind {
            VarKind::Named { name, indices } if indices.is_empty() => name.clone(),
            _ => return None,
        },
        _ => return None,
    };
    AXES.iter().position(|a| a.eq_ignore_ascii_case(&id))
}

/// `$AC_MEA[1]==1` (or `$AC_MEA[1]-1==0`, the form the FANUC → Sinumerik translation writes).
fn probe_switched(c: &Expr) -> bool {
    let is_mea = |e: &Expr| {
        matches!(&e.kind, ExprKind::Var(v) if matches!(&v.kind, VarKind::System { name, indices }
            if name.eq_ignore_ascii_case("AC_MEA") && indices.len() == 1 && crate::lower::literal(&indices[0]) == Some(1.0)))
    };
    let ExprKind::Cmp(CmpOp::Eq, _, a, b) = &c.kind else { return false };
    match (&a.kind, crate::lower::literal(b)) {
        (_, Some(v)) if v == 1.0 && is_mea(a) => true,
        (ExprKind::Binary(BinOp::Sub, x, one), Some(0.0)) => is_mea(x) && crate::lower::literal(one) == Some(1.0),
        _ => false,
    }
}

/// A keep `T=#5063` (or `T=#5063+R`) that [`skip_idiom`] wrote.
fn is_z_keep(s: &Stmt) -> bool {
    let z = |e: &Expr| matches!(&e.kind, ExprKind::Var(v) if v.kind == VarKind::Hash(5063));
    matches!(&s.kind, StmtKind::Block(b) if matches!(b.items.as_slice(),
        [Item { kind: ItemKind::Assign { value, .. }, .. }]
            if z(value) || matches!(&value.kind, ExprKind::Binary(BinOp::Add, x, _) if z(x))))
}

/// One assignment `T=$NAME[axis]` (or `T=$NAME[axis]+R`) in a block of its own: the
/// target, the axis and R.
fn kept(s: &Stmt, name: &str) -> Option<(VarRef, usize, Option<Expr>)> {
    let StmtKind::Block(b) = &s.kind else { return None };
    match b.items.as_slice() {
        [Item { kind: ItemKind::Assign { target, value }, .. }] if !crate::lower::meta_is_marked(&b.meta) => {
            if let Some(a) = sys_axis(value, name) {
                return Some(((**target).clone(), a, None));
            }
            // The FANUC → Sinumerik translation's keep of Z under G43 adds the edge's length.
            let ExprKind::Binary(BinOp::Add, x, r) = &value.kind else { return None };
            Some(((**target).clone(), sys_axis(x, name)?, Some((**r).clone())))
        }
        _ => None,
    }
}

/// Right after a measuring block, `IF $AC_MEA[1]==1 T=$AA_MW[a] ELSE T=$AA_IW[a] ENDIF`
/// keeps in T what FANUC keeps in `#5061+a` (the trigger point on a hit, the end point on a
/// miss) for an axis `a` of the block: the assignments `T=#5061+a`; with the same `+R` in
/// both branches (read once, at the keep, on both controls), `T=#5061+a+R`. `None`: not
/// that form.
fn skip_idiom(s: &Stmt, axes: &[usize]) -> Option<Vec<Stmt>> {
    let StmtKind::If(i) = &s.kind else { return None };
    let else_body = &i.else_part.as_ref()?.body;
    if !probe_switched(&i.cond) || i.then_body.is_empty() || i.then_body.len() != else_body.len() {
        return None;
    }
    let mut out = Vec::new();
    for (t, e) in i.then_body.iter().zip(else_body) {
        let (target, a, r) = kept(t, "AA_MW")?;
        let (target2, a2, r2) = kept(e, "AA_IW")?;
        let same = |x: &Option<Expr>, y: &Option<Expr>| match (x, y) {
            (None, None) => true,
            (Some(x), Some(y)) => crate::ir::dump::expr(x) == crate::ir::dump::expr(y),
            _ => false,
        };
        if target.kind != target2.kind || a != a2 || !axes.contains(&a) || !same(&r, &r2) {
            return None;
        }
        let span = t.span;
        let skip = var_expr(&VarRef { kind: VarKind::Hash(5061 + a as u32), span });
        let skip = match r {
            Some(r) => bin(BinOp::Add, skip, r),
            None => skip,
        };
        out.push(block_stmt(vec![assign_item(&target, skip, span)], span));
    }
    Some(out)
}
