//! Siemens STRING variables that hold program names (issue 21: `SHAPE="D_TRIANGLE"` in one
//! program, `EXECSTRING(SHAPE)` or `CALL SHAPE` in another) to FANUC, which has no strings: a
//! scalar STRING variable, a program's own DEF or global user data (GUD), whose every write in
//! the programs translated together is a literal naming one of them (or ""), and whose every
//! read is a call target or an `==`/`<>` comparison with such a literal, becomes a number: the
//! O number of the program it names, 0 for "" (a Siemens STRING starts as "", a DEF'd INT and a
//! GUD's common start at 0, and no program is O0, so the FANUC call of 0 fails as the Siemens
//! call of "" does). The call is lowered by `words::prog_call` as `G65 P#n`.
//! Anything else about such a variable (a concatenation, a read as text, a write of an
//! expression, a name not among the translated programs) keeps it a STRING, and its call is
//! refused with the reason (NC559).

use crate::ir::*;
use std::collections::{BTreeMap, BTreeSet};

/// A STRING variable: a program's own (by the program's index among those translated
/// together) or global user data.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Key {
    Local(usize, String),
    Gud(String),
}

#[derive(Default)]
struct Uses {
    names: BTreeSet<String>,
    calls: usize,
    why_not: Option<String>,
    /// The variables copied into this one (`SHAPE=WORM_SHAPE`).
    copied_from: BTreeSet<Key>,
}

/// What the analysis found: per program, the variables it sees that hold program names (with
/// the names they can hold), and those called through that cannot (with why).
#[derive(Clone, Debug, Default)]
pub struct Found {
    pub per_prog: Vec<BTreeMap<String, Vec<String>>>,
    pub refused: Vec<BTreeMap<String, String>>,
    /// The GUD names that become numbers.
    pub guds: BTreeSet<String>,
}

fn key_name(k: &Key) -> &str {
    match k {
        Key::Local(_, n) | Key::Gud(n) => n,
    }
}

fn var_name(v: &VarRef) -> Option<&str> {
    match &v.kind {
        VarKind::Named { name, indices } if indices.is_empty() => Some(name),
        _ => None,
    }
}

fn expr_var(e: &Expr) -> Option<&str> {
    match &e.kind {
        ExprKind::Var(v) => var_name(v),
        _ => None,
    }
}

/// `EXECSTRING(e)` as the call it is when its text is a program name: a call whose target is
/// `e` (a literal name: the call of that name). The evaluator runs it so (`eval::calls`).
pub fn execstring_as_call(p: &Program) -> Option<Program> {
    let mut changed = false;
    let mut p = p.clone();
    items_mut(&mut p.body, &mut |it| {
        if let ItemKind::Call(c) = &mut it.kind {
            if c.kind == CallKind::Named
                && matches!(&c.target, CallTarget::Name(n) if n == "EXECSTRING")
                && c.args.len() == 1
            {
                if let Some(Arg::Value(e)) = c.args.pop() {
                    c.target = match &e.kind {
                        ExprKind::Str(t) if crate::dialect::sinumerik::is_program_name_line(t.trim()) => {
                            CallTarget::Name(t.trim().to_ascii_uppercase())
                        }
                        _ => CallTarget::Computed(e),
                    };
                    changed = true;
                }
            }
        }
    });
    changed.then_some(p)
}

/// Every item of `body`, nested structures and IF-THEN items included.
fn items_mut(body: &mut [Stmt], f: &mut dyn FnMut(&mut Item)) {
    fn item(it: &mut Item, f: &mut dyn FnMut(&mut Item)) {
        f(it);
        match &mut it.kind {
            ItemKind::IfThen { then, .. } => item(then, f),
            ItemKind::IfBlock { items, .. } => items.iter_mut().for_each(|i| item(i, f)),
            _ => {}
        }
    }
    for s in body.iter_mut() {
        match &mut s.kind {
            StmtKind::Block(b) => b.items.iter_mut().for_each(|i| item(i, f)),
            k => {
                for b in crate::ir::visit::child_bodies_mut(k) {
                    items_mut(b, f);
                }
            }
        }
    }
}

/// The STRING variables of `progs` (with their names for the O numbers, `translated`) that
/// hold program names; `globals` is the source's global user data.
pub fn find(progs: &[&Program], globals: &[Def], translated: &BTreeSet<String>) -> Found {
    let gud: BTreeSet<String> = globals
        .iter()
        .filter(|d| matches!(d.ty, DataType::String(_)))
        .flat_map(|d| d.vars.iter().filter(|v| v.dims.is_empty()).map(|v| v.name.clone()))
        .collect();
    let mut uses: BTreeMap<Key, Uses> = BTreeMap::new();
    let mut locals: Vec<BTreeSet<String>> = Vec::new();
    for (i, p) in progs.iter().enumerate() {
        // A PROC parameter hides a GUD of its name and holds what its caller passes: never one of these.
        let mut own: BTreeSet<String> = p.params.iter().map(|q| format!("\u{0}{}", q.name)).collect();
        crate::ir::visit::walk_stmts(&p.body, &mut |s| {
            if let StmtKind::Block(b) = &s.kind {
                for it in &b.items {
                    if let ItemKind::Def(d) = &it.kind {
                        if d.scope.is_none() {
                            for v in &d.vars {
                                // Any own DEF hides a GUD of its name; only a scalar STRING can hold a name.
                                if matches!(d.ty, DataType::String(_)) && v.dims.is_empty() {
                                    own.insert(v.name.clone());
                                } else {
                                    own.insert(format!("\u{0}{}", v.name));
                                }
                            }
                        }
                    }
                }
            }
        });
        let key_of = |n: &str| -> Option<Key> {
            if own.contains(n) {
                Some(Key::Local(i, n.to_string()))
            } else if own.contains(&format!("\u{0}{n}")) {
                None
            } else {
                gud.contains(n).then(|| Key::Gud(n.to_string()))
            }
        };
        let mut p = (*p).clone();
        let mut note = |k: Key, f: &mut dyn FnMut(&mut Uses)| f(uses.entry(k).or_default());
        items_mut(&mut p.body, &mut |it| {
            scan_item(it, &key_of, translated, &mut note);
        });
        scan_conds(&p.body, &key_of, translated, &mut note);
        locals.push(own);
    }
    let mut found = Found {
        per_prog: vec![BTreeMap::new(); progs.len()],
        refused: vec![BTreeMap::new(); progs.len()],
        guds: BTreeSet::new(),
    };
    // Names flow along copies (`SHAPE=WORM_SHAPE`), and so do the reasons not to.
    for _ in 0..=uses.len() {
        let mut changed = false;
        let keys: Vec<Key> = uses.keys().cloned().collect();
        for k in &keys {
            for src in uses[k].copied_from.clone() {
                let (names, why) = uses.get(&src).map(|u| (u.names.clone(), u.why_not.clone())).unwrap_or_default();
                let Some(u) = uses.get_mut(k) else { continue };
                let before = (u.names.len(), u.why_not.is_some());
                u.names.extend(names);
                if u.why_not.is_none() {
                    u.why_not = why.map(|w| format!("it is copied from {}, for which {w}", key_name(&src)));
                }
                changed |= before != (u.names.len(), u.why_not.is_some());
            }
        }
        if !changed {
            break;
        }
    }
    // Called through, or copied into one that is.
    let mut relevant: BTreeSet<Key> = uses.iter().filter(|(_, u)| u.calls > 0).map(|(k, _)| k.clone()).collect();
    loop {
        let more: Vec<Key> = relevant
            .iter()
            .flat_map(|k| uses.get(k).map(|u| u.copied_from.iter().cloned().collect::<Vec<_>>()).unwrap_or_default())
            .filter(|s| !relevant.contains(s))
            .collect();
        if more.is_empty() {
            break;
        }
        relevant.extend(more);
    }
    for (key, u) in uses {
        if !relevant.contains(&key) {
            continue;
        }
        let names: Vec<String> = u.names.iter().filter(|n| !n.is_empty()).cloned().collect();
        let targets: Vec<usize> = match &key {
            Key::Local(i, n) => vec![*i].into_iter().filter(|_| locals[*i].contains(n)).collect(),
            Key::Gud(n) => (0..progs.len())
                .filter(|i| !locals[*i].contains(n) && !locals[*i].contains(&format!("\u{0}{n}")))
                .collect(),
        };
        let name = match &key {
            Key::Local(_, n) | Key::Gud(n) => n.clone(),
        };
        let why = u.why_not.clone().or_else(|| {
            (names.is_empty() && u.calls > 0)
                .then(|| format!("{name} is never given a program name in the programs translated together"))
        });
        for i in targets {
            match &why {
                Some(w) => {
                    found.refused[i].insert(name.clone(), w.clone());
                }
                None => {
                    found.per_prog[i].insert(name.clone(), names.clone());
                }
            }
        }
        if why.is_none() {
            if let Key::Gud(n) = key {
                found.guds.insert(n);
            }
        }
    }
    found
}

/// The literal a write or comparison gives, if it names a translated program (or is "").
fn literal(e: &Expr, translated: &BTreeSet<String>) -> Result<String, String> {
    match &e.kind {
        ExprKind::Str(t) => {
            let t = t.trim().to_ascii_uppercase();
            if t.is_empty() || translated.contains(&t) {
                Ok(t)
            } else {
                Err(format!("\"{t}\" names no program translated together with it"))
            }
        }
        ExprKind::Binary(BinOp::Concat, ..) => Err("it is written from a concatenation (`<<`)".into()),
        _ => Err("it is written from an expression, not a literal program name".into()),
    }
}

type Note<'a> = dyn FnMut(Key, &mut dyn FnMut(&mut Uses)) + 'a;

fn scan_item(it: &Item, key_of: &dyn Fn(&str) -> Option<Key>, translated: &BTreeSet<String>, note: &mut Note) {
    match &it.kind {
        ItemKind::Def(d) if d.scope.is_none() => {
            for v in &d.vars {
                if let (Some(k), Some(Init::Value(e))) = (key_of(&v.name), &v.init) {
                    let r = literal(e, translated);
                    note(k, &mut |u| record(u, &r));
                }
            }
            return;
        }
        ItemKind::Assign { target, value } => {
            if let (Some(k), Some(src)) = (var_name(target).and_then(key_of), expr_var(value).and_then(key_of)) {
                note(k, &mut |u| {
                    u.copied_from.insert(src.clone());
                });
                note(src, &mut |_| {});
                return;
            }
            if let Some(k) = var_name(target).and_then(key_of) {
                let r = literal(value, translated);
                note(k, &mut |u| record(u, &r));
                scan_expr(value, key_of, translated, note);
                return;
            }
            if let VarKind::Named { name, .. } = &target.kind {
                if let Some(k) = key_of(name) {
                    note(k, &mut |u| deny(u, "it is written with an index"));
                }
            }
        }
        ItemKind::Call(c) => {
            if let CallTarget::Computed(e) = &c.target {
                if let Some(k) = expr_var(e).and_then(key_of) {
                    let with_args = !c.args.is_empty() || c.repeat.is_some() || c.kind != CallKind::Named;
                    note(k, &mut |u| {
                        u.calls += 1;
                        if with_args {
                            deny(u, "it is called with arguments, a repetition or as a modal call");
                        }
                    });
                    for a in &c.args {
                        if let Arg::Value(x) = a {
                            scan_expr(x, key_of, translated, note);
                        }
                    }
                    return;
                }
            }
        }
        // The nested item is visited on its own (`items_mut`).
        ItemKind::IfThen { cond, .. } | ItemKind::IfBlock { cond, .. } => {
            scan_expr(cond, key_of, translated, note);
            return;
        }
        _ => {}
    }
    for e in crate::ir::visit::item_exprs(it) {
        scan_expr(e, key_of, translated, note);
    }
}

fn record(u: &mut Uses, r: &Result<String, String>) {
    match r {
        Ok(n) => {
            u.names.insert(n.clone());
        }
        Err(w) => deny(u, w),
    }
}

fn deny(u: &mut Uses, why: &str) {
    u.why_not.get_or_insert_with(|| why.to_string());
}

fn scan_conds(body: &[Stmt], key_of: &dyn Fn(&str) -> Option<Key>, translated: &BTreeSet<String>, note: &mut Note) {
    for s in body {
        let conds: Vec<&Expr> = match &s.kind {
            StmtKind::Block(_) => vec![],
            StmtKind::If(i) => vec![&i.cond],
            StmtKind::While(w) => vec![&w.cond],
            StmtKind::Loop(_) => vec![],
            StmtKind::For(x) => vec![&x.from, &x.to],
            StmtKind::Repeat(r) => vec![&r.until],
            StmtKind::Do(d) => d.cond.iter().collect(),
        };
        for c in conds {
            scan_expr(c, key_of, translated, note);
        }
        for b in crate::ir::visit::child_bodies(&s.kind) {
            scan_conds(b, key_of, translated, note);
        }
    }
}

/// A read: allowed only as a side of `==`/`<>` with a literal.
fn scan_expr(e: &Expr, key_of: &dyn Fn(&str) -> Option<Key>, translated: &BTreeSet<String>, note: &mut Note) {
    if let ExprKind::Cmp(CmpOp::Eq | CmpOp::Ne, _, a, b) = &e.kind {
        for (v, lit) in [(a, b), (b, a)] {
            if let Some(k) = expr_var(v).and_then(key_of) {
                let r = match &lit.kind {
                    ExprKind::Str(_) => literal(lit, translated),
                    _ => Err("it is compared with something other than a literal program name".into()),
                };
                note(k, &mut |u| {
                    if let Err(w) = &r {
                        deny(u, w);
                    }
                });
                return scan_expr(lit, key_of, translated, note);
            }
        }
    }
    if let Some(k) = expr_var(e).and_then(key_of) {
        note(k, &mut |u| deny(u, "it is read as text (FANUC variables hold numbers)"));
        return;
    }
    for c in e.children() {
        scan_expr(c, key_of, translated, note);
    }
}

/// `p` (the program `i` of [`find`]'s list) with its program-name variables made numbers:
/// their DEFs INT, every literal written or compared the number `number` gives the name (0
/// for ""). Calls through them keep their computed target for `words::prog_call`.
pub fn rewrite(p: &mut Program, vars: &BTreeMap<String, Vec<String>>, number: &dyn Fn(&str) -> Option<u32>) {
    if vars.is_empty() {
        return;
    }
    let value = |e: &mut Expr| {
        if let ExprKind::Str(t) = &e.kind {
            let t = t.trim().to_ascii_uppercase();
            let n = if t.is_empty() { Some(0) } else { number(&t) };
            if let Some(n) = n {
                *e = crate::lower::num(f64::from(n), e.span);
            }
        }
    };
    let is_ours = |e: &Expr| expr_var(e).is_some_and(|n| vars.contains_key(n));
    let mut cmp = |root: &mut Expr| {
        fn walk(e: &mut Expr, is_ours: &dyn Fn(&Expr) -> bool, value: &dyn Fn(&mut Expr)) {
            // Whole O numbers (or 0) apart by 1 at least: the Siemens tolerance cannot join two.
            if let ExprKind::Cmp(CmpOp::Eq | CmpOp::Ne, tol, a, b) = &mut e.kind {
                if is_ours(a) {
                    value(b);
                    *tol = Tolerance::Exact;
                } else if is_ours(b) {
                    value(a);
                    *tol = Tolerance::Exact;
                }
            }
            match &mut e.kind {
                ExprKind::Unary(_, a) => walk(a, is_ours, value),
                ExprKind::Binary(_, a, b) | ExprKind::Cmp(_, _, a, b) => {
                    walk(a, is_ours, value);
                    walk(b, is_ours, value);
                }
                ExprKind::Func(_, args) => args.iter_mut().for_each(|a| walk(a, is_ours, value)),
                _ => {}
            }
        }
        walk(root, &is_ours, &value);
    };
    crate::lower::map_exprs(&mut p.body, &mut cmp);
    items_mut(&mut p.body, &mut |it| match &mut it.kind {
        // A DEF of several STRINGs not all holding names stays STRING (the varmap refuses it).
        ItemKind::Def(d)
            if d.scope.is_none()
                && matches!(d.ty, DataType::String(_))
                && d.vars.iter().all(|v| vars.contains_key(&v.name) && v.dims.is_empty()) =>
        {
            d.ty = DataType::Int;
            for v in &mut d.vars {
                if let Some(Init::Value(e)) = &mut v.init {
                    value(e);
                }
            }
        }
        ItemKind::Assign { target, value: v } if var_name(target).is_some_and(|n| vars.contains_key(n)) => value(v),
        _ => {}
    });
}

/// `p` with every call through one of its program-name variables `vars` made the calls of
/// every program the variable can name, one after the other: what the effects of `p` on its
/// callers (`words::effects`, which does not follow a computed target) are made of. The groups
/// and tools these set add up, as where the paths of the one call taken meet; the G90/G91 and
/// units a candidate leaves changed are refused at the call (`words::prog_call`, NC558).
pub fn calls_by_name(p: &Program, vars: &BTreeMap<String, Vec<String>>) -> Program {
    let mut p = p.clone();
    if vars.is_empty() {
        return p;
    }
    p.body = crate::lower::map_bodies(std::mem::take(&mut p.body), &mut |list| {
        list.into_iter()
            .map(|mut s| {
                if let StmtKind::Block(b) = &mut s.kind {
                    let items = std::mem::take(&mut b.items);
                    for it in items {
                        let names = match &it.kind {
                            ItemKind::Call(c) => match &c.target {
                                CallTarget::Computed(e) => expr_var(e).and_then(|n| vars.get(n)),
                                _ => None,
                            },
                            _ => None,
                        };
                        match names {
                            Some(names) => b.items.extend(names.iter().map(|n| Item {
                                kind: ItemKind::Call(Box::new(Call {
                                    kind: CallKind::Named,
                                    target: CallTarget::Name(n.clone()),
                                    args: vec![],
                                    repeat: None,
                                })),
                                span: it.span,
                            })),
                            None => b.items.push(it),
                        }
                    }
                }
                s
            })
            .collect()
    });
    p
}

/// The global user data as the FANUC side sees it: the program-name STRINGs are INT.
pub fn globals_as_numbers(globals: &[Def], guds: &BTreeSet<String>) -> Vec<Def> {
    let mut out = Vec::new();
    for d in globals {
        if !matches!(d.ty, DataType::String(_)) || !d.vars.iter().any(|v| guds.contains(&v.name)) {
            out.push(d.clone());
            continue;
        }
        let (ours, rest): (Vec<DefVar>, Vec<DefVar>) = d.vars.iter().cloned().partition(|v| guds.contains(&v.name));
        out.push(Def { scope: d.scope, ty: DataType::Int, vars: ours });
        if !rest.is_empty() {
            out.push(Def { scope: d.scope, ty: d.ty, vars: rest });
        }
    }
    out
}

/// The program names written into STRING variables of `unit` as literals: the programs a
/// call through such a variable can reach, which a translation loads beside its input. Only
/// writes of variables that may be called through count: a program's own STRING called
/// through in that program (`CALL v`, `EXECSTRING(v)`), or a name the program does not declare
/// (global user data, called through in another program); a name is kept only where a program
/// of it may exist (`is_program_name_line`).
pub fn written_names(unit: &Unit) -> Vec<String> {
    let mut out = Vec::new();
    for p in &unit.programs {
        let p = execstring_as_call(p).unwrap_or_else(|| p.clone());
        let mut declared = BTreeSet::new();
        let mut called = BTreeSet::new();
        declared.extend(p.params.iter().map(|q| q.name.clone()));
        let mut q = p.clone();
        items_mut(&mut q.body, &mut |it| match &it.kind {
            ItemKind::Def(d) => declared.extend(d.vars.iter().map(|v| v.name.clone())),
            ItemKind::Call(c) => {
                if let CallTarget::Computed(e) = &c.target {
                    called.extend(expr_var(e).map(str::to_string));
                }
            }
            _ => {}
        });
        let counts = |n: &str| !declared.contains(n) || called.contains(n);
        items_mut(&mut q.body, &mut |it| {
            let lits: Vec<&Expr> = match &it.kind {
                ItemKind::Assign { target, value } if var_name(target).is_some_and(counts) => vec![value],
                ItemKind::Def(d) if matches!(d.ty, DataType::String(_)) => d
                    .vars
                    .iter()
                    .filter(|v| counts(&v.name))
                    .filter_map(|v| match &v.init {
                        Some(Init::Value(e)) => Some(e),
                        _ => None,
                    })
                    .collect(),
                _ => vec![],
            };
            for e in lits {
                if let ExprKind::Str(t) = &e.kind {
                    let t = t.trim().to_ascii_uppercase();
                    if crate::dialect::sinumerik::is_program_name_line(&t) && !out.contains(&t) {
                        out.push(t);
                    }
                }
            }
        });
    }
    out
}
