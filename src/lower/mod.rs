//! Lowering: what the IR must become to be expressible in a target dialect, one folder per
//! target (`to_fanuc/`, `to_sinumerik/`, each ordering its own passes in its `mod.rs`), and
//! here, once, what every target shares: the small IR builders and walkers, the refusal of
//! tool compensation ([`compensation`]), the recognition of nctrans's own headers
//! ([`own_header`]), bare literal lengths restated for another profile, with the letters
//! they are on ([`restate`]), and the variables known at translation ([`known`]).
//!
//! May use: `ir`, `dialect` (spellings and `Semantics` facts), `eval` (facts the evaluator
//! owns: refusal reasons, modal tables), `diag`, `span`, `read` (the source line the fast
//! writers, `to_*/fast_write`, copy digits from). Never `stream`, `check` or the
//! translators above it: lowering is IR → IR and is driven from above. A target folder may
//! use this module, never its sibling target.

#[cfg(test)]
pub(crate) mod build;
pub mod comp_flow;
pub mod hole_loops;
pub mod known;
pub mod landings;
pub mod own_header;
pub mod restate;
pub mod signals;
pub mod to_fanuc;
pub mod to_sinumerik;

use crate::ir::*;
use crate::span::Span;

// ---- small builders shared by the passes ----

pub fn num(v: f64, span: Span) -> Expr {
    Expr::num(v, v.fract() != 0.0, span)
}

pub fn var_expr(v: &VarRef) -> Expr {
    Expr::new(ExprKind::Var(Box::new(v.clone())), v.span)
}

pub fn bin(op: BinOp, a: Expr, b: Expr) -> Expr {
    let span = a.span.to(b.span);
    Expr::new(ExprKind::Binary(op, Box::new(a), Box::new(b)), span)
}

pub fn cmp(op: CmpOp, a: Expr, b: Expr) -> Expr {
    let span = a.span.to(b.span);
    Expr::new(ExprKind::Cmp(op, Tolerance::Exact, Box::new(a), Box::new(b)), span)
}

pub fn func(f: Func, args: Vec<Expr>, span: Span) -> Expr {
    Expr::new(ExprKind::Func(f, args), span)
}

pub fn item(kind: ItemKind, span: Span) -> Item {
    Item { kind, span }
}

pub fn assign_item(target: &VarRef, value: Expr, span: Span) -> Item {
    item(ItemKind::Assign { target: Box::new(target.clone()), value }, span)
}

/// A statement holding one block with the given items and a fresh (empty) meta.
pub fn block_stmt(items: Vec<Item>, span: Span) -> Stmt {
    let meta = BlockMeta { span, ..BlockMeta::default() };
    Stmt { kind: StmtKind::Block(Block { meta, items }), span }
}

pub fn meta_stmt(meta: BlockMeta, items: Vec<Item>) -> Stmt {
    let span = meta.span;
    Stmt { kind: StmtKind::Block(Block { meta, items }), span }
}

/// An empty block carrying `label` (a jump target).
pub fn label_stmt(label: Label) -> Stmt {
    let span = label.span;
    let meta = BlockMeta { span, label: Some(label), ..BlockMeta::default() };
    Stmt { kind: StmtKind::Block(Block { meta, items: vec![] }), span }
}

/// A jump to `label` (unique by construction, so the search direction does not matter).
pub fn goto_item(label: &Label, cond: Option<Expr>, span: Span) -> Item {
    item(
        ItemKind::Goto(Box::new(Goto {
            search: Search::ForwardThenBackward,
            target: Target::Label(label.clone()),
            cond,
            missing_continues: false,
        })),
        span,
    )
}

/// `IF [cond] THEN target = value`.
pub fn if_then(cond: Expr, target: &VarRef, value: Expr, span: Span) -> Item {
    item(ItemKind::IfThen { cond, then: Box::new(assign_item(target, value, span)) }, span)
}

/// True when a block meta carries something a jump or a reader could need.
pub fn meta_is_marked(m: &BlockMeta) -> bool {
    m.number.is_some() || m.label.is_some() || !m.comments.is_empty() || m.skip.is_some()
}

/// Splits off what makes a block a jump target (number, label) into an empty block, so that
/// statements inserted before it still run when a jump lands there.
pub fn take_target(meta: &mut BlockMeta) -> Option<Stmt> {
    if meta.number.is_none() && meta.label.is_none() {
        return None;
    }
    let m = BlockMeta {
        span: meta.span,
        skip: None,
        number: meta.number.take(),
        label: meta.label.take(),
        comments: vec![],
    };
    Some(meta_stmt(m, vec![]))
}

// ---- walkers shared by the passes ----

/// Applies `f` to every statement list in `body` (children first), letting a pass rewrite
/// blocks into several statements.
pub fn map_bodies(body: Vec<Stmt>, f: &mut dyn FnMut(Vec<Stmt>) -> Vec<Stmt>) -> Vec<Stmt> {
    let inner: Vec<Stmt> = body
        .into_iter()
        .map(|mut s| {
            match &mut s.kind {
                StmtKind::Block(_) => {}
                StmtKind::If(i) => {
                    i.then_body = map_bodies(std::mem::take(&mut i.then_body), f);
                    if let Some(e) = &mut i.else_part {
                        e.body = map_bodies(std::mem::take(&mut e.body), f);
                    }
                }
                StmtKind::While(w) => w.body = map_bodies(std::mem::take(&mut w.body), f),
                StmtKind::Loop(l) => l.body = map_bodies(std::mem::take(&mut l.body), f),
                StmtKind::For(x) => x.body = map_bodies(std::mem::take(&mut x.body), f),
                StmtKind::Repeat(r) => r.body = map_bodies(std::mem::take(&mut r.body), f),
                StmtKind::Do(d) => d.body = map_bodies(std::mem::take(&mut d.body), f),
            }
            s
        })
        .collect();
    f(inner)
}

/// Rewrites every expression of a statement tree in place (conditions, item expressions,
/// nested IF-THEN items), outermost first is not guaranteed: `f` sees each root expression.
pub fn map_exprs(body: &mut [Stmt], f: &mut dyn FnMut(&mut Expr)) {
    for s in body.iter_mut() {
        match &mut s.kind {
            StmtKind::Block(b) => {
                for it in &mut b.items {
                    item_exprs_mut(it, f);
                }
            }
            StmtKind::If(i) => {
                f(&mut i.cond);
                map_exprs(&mut i.then_body, f);
                if let Some(e) = &mut i.else_part {
                    map_exprs(&mut e.body, f);
                }
            }
            StmtKind::While(w) => {
                f(&mut w.cond);
                map_exprs(&mut w.body, f);
            }
            StmtKind::Loop(l) => map_exprs(&mut l.body, f),
            StmtKind::For(x) => {
                f(&mut x.from);
                f(&mut x.to);
                map_exprs(&mut x.body, f);
            }
            StmtKind::Repeat(r) => {
                f(&mut r.until);
                map_exprs(&mut r.body, f);
            }
            StmtKind::Do(d) => {
                if let Some(c) = &mut d.cond {
                    f(c);
                }
                map_exprs(&mut d.body, f);
            }
        }
    }
}

/// The root expressions of one item, mutably (the mirror of `ir::visit::item_exprs`, plus
/// the indices of assignment targets).
pub fn item_exprs_mut(it: &mut Item, f: &mut dyn FnMut(&mut Expr)) {
    fn word(w: &mut Word, f: &mut dyn FnMut(&mut Expr)) {
        match &mut w.value {
            WordValue::Expr(e) | WordValue::Ac(e) | WordValue::Ic(e) | WordValue::Rotary(_, e) => f(e),
        }
    }
    fn goto(g: &mut Goto, f: &mut dyn FnMut(&mut Expr)) {
        if let Some(c) = &mut g.cond {
            f(c);
        }
        if let Target::Computed(e) = &mut g.target {
            f(e);
        }
    }
    match &mut it.kind {
        ItemKind::Assign { target, value } => {
            varref_exprs_mut(target, f);
            f(value);
        }
        ItemKind::Word(w) => word(w, f),
        ItemKind::Goto(g) => goto(g, f),
        ItemKind::IfThen { cond, then } => {
            f(cond);
            item_exprs_mut(then, f);
        }
        ItemKind::IfBlock { cond, items } => {
            f(cond);
            for i in items {
                item_exprs_mut(i, f);
            }
        }
        ItemKind::SyncAction(a) => {
            if let Some((_, e)) = &mut a.id {
                f(e);
            }
            if let Some((_, e)) = &mut a.trigger {
                f(e);
            }
            for i in &mut a.actions {
                item_exprs_mut(i, f);
            }
        }
        ItemKind::Case(c) => {
            f(&mut c.selector);
            for a in &mut c.arms {
                f(&mut a.value);
                goto(&mut a.goto, f);
            }
            if let Some(d) = &mut c.default {
                goto(d, f);
            }
        }
        ItemKind::Call(c) => {
            if let CallTarget::Computed(e) = &mut c.target {
                f(e);
            }
            for a in &mut c.args {
                match a {
                    Arg::Value(e) | Arg::Letter { value: e, .. } => f(e),
                    Arg::Omitted(_) => {}
                }
            }
            if let Some(r) = &mut c.repeat {
                f(r);
            }
        }
        ItemKind::Return { to } => {
            if let Some(e) = to {
                f(e);
            }
        }
        ItemKind::Def(d) => {
            for v in &mut d.vars {
                if let Some(Init::Value(e)) = &mut v.init {
                    f(e);
                }
            }
        }
        ItemKind::Alarm { number, .. } => f(number),
        ItemKind::Message { text: Some(e) } => f(e),
        ItemKind::ParamWrite(p) => {
            f(&mut p.number);
            if let Some(a) = &mut p.axis {
                f(a);
            }
            if let Some(b) = &mut p.bit {
                f(b);
            }
            f(&mut p.value);
        }
        ItemKind::RepeatSection(r) => {
            if let Some(c) = &mut r.count {
                f(c);
            }
        }
        ItemKind::Frame { words, .. } => {
            for w in words {
                word(w, f);
            }
        }
        ItemKind::Print(p) => {
            if let Some(s) = &mut p.status {
                varref_exprs_mut(s, f);
            }
            if let Some(e) = &mut p.file {
                f(e);
            }
            for part in &mut p.parts {
                match part {
                    PrintPart::Field { value: e, .. } | PrintPart::Str(e) => f(e),
                    PrintPart::Text(_) => {}
                }
            }
        }
        ItemKind::Message { text: None }
        | ItemKind::Extern(_)
        | ItemKind::ModalCallOff
        | ItemKind::Instruction { .. }
        | ItemKind::End { .. }
        | ItemKind::StopMessage { .. }
        | ItemKind::Stopre => {}
    }
}

fn varref_exprs_mut(v: &mut VarRef, f: &mut dyn FnMut(&mut Expr)) {
    match &mut v.kind {
        VarKind::HashIndirect(e) | VarKind::RIndirect(e) => f(e),
        VarKind::Named { indices, .. } | VarKind::System { indices, .. } => {
            for e in indices {
                f(e);
            }
        }
        VarKind::Hash(_) | VarKind::R(_) => {}
    }
}
/// The direct sub-expressions of `e`, mutably (a variable's indices included).
pub fn children_mut(e: &mut Expr) -> Vec<&mut Expr> {
    match &mut e.kind {
        ExprKind::Num(_) | ExprKind::Vacant | ExprKind::Str(_) | ExprKind::Ident(_) => vec![],
        ExprKind::Var(v) => match &mut v.kind {
            VarKind::HashIndirect(x) | VarKind::RIndirect(x) => vec![x.as_mut()],
            VarKind::Named { indices, .. } | VarKind::System { indices, .. } => indices.iter_mut().collect(),
            _ => vec![],
        },
        ExprKind::Unary(_, a) => vec![a.as_mut()],
        ExprKind::Binary(_, a, b) | ExprKind::Cmp(_, _, a, b) => vec![a.as_mut(), b.as_mut()],
        ExprKind::Func(_, args) => args.iter_mut().collect(),
    }
}

/// Every item of a block, each followed by the item an IF-THEN in it guards.
pub fn block_items(b: &Block) -> impl Iterator<Item = &Item> {
    b.items.iter().flat_map(|it| {
        let then = match &it.kind {
            ItemKind::IfThen { then, .. } => Some(&**then),
            _ => None,
        };
        std::iter::once(it).chain(then)
    })
}

/// The numeric value of a literal.
pub fn literal(e: &Expr) -> Option<f64> {
    match &e.kind {
        ExprKind::Num(n) => Some(n.value),
        ExprKind::Unary(UnOp::Neg, a) => literal(a).map(|v| -v),
        _ => None,
    }
}

/// The G code numbers (×10 to keep `G54.1` as 541) written in a block.
pub fn g_codes(items: &[Item]) -> Vec<u32> {
    items
        .iter()
        .filter_map(|it| match &it.kind {
            ItemKind::Word(w) if w.addr.is(b'G') => match &w.value {
                WordValue::Expr(e) => literal(e).map(|v| (v * 10.0).round() as u32),
                _ => None,
            },
            _ => None,
        })
        .collect()
}

/// The axes (bit i: `XYZABCUVW`\[i\]) any `G52` of `body` may leave shifted: a word other
/// than a literal 0.
pub fn g52_axes(body: &[Stmt]) -> u16 {
    let mut bits = 0;
    crate::ir::visit::walk_stmts(body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            if g_codes(&b.items).contains(&520) {
                for it in &b.items {
                    if let ItemKind::Word(Word { addr: Addr::Letter(l), value: WordValue::Expr(e), .. }) = &it.kind {
                        if literal(e) != Some(0.0) {
                            bits |= b"XYZABCUVW".iter().position(|c| c == l).map_or(0, |i| 1 << i);
                        }
                    }
                }
            }
        }
    });
    bits
}

/// Whether every X, Y, Z word of a block is a literal 0 (`G101 X0.`, `G51.1 X0`).
pub fn xyz_words_zero(items: &[Item]) -> bool {
    items.iter().all(|it| match &it.kind {
        ItemKind::Word(w) if matches!(w.addr, Addr::Letter(b'X' | b'Y' | b'Z')) => match &w.value {
            WordValue::Expr(e) => literal(e) == Some(0.0),
            _ => false,
        },
        _ => true,
    })
}

/// Rewrites the G words of a block by `map` (the G code ×10, as [`g_codes`] gives it → the
/// code to write), keeping their spans: one control's spelling of a meaning into another's.
pub fn respell_g(items: &mut [Item], map: &[(u32, f64)]) {
    for it in items {
        if let ItemKind::Word(w) = &mut it.kind {
            if let (true, WordValue::Expr(e)) = (w.addr.is(b'G'), &mut w.value) {
                let g = literal(e).map(|v| (v * 10.0).round() as u32);
                if let Some(&(_, to)) = map.iter().find(|(from, _)| Some(*from) == g) {
                    *e = Expr::num(to, to.fract() != 0.0, e.span);
                }
            }
        }
    }
}
