//! Test builders: small hand-made IR for the pass and writer unit tests.

use super::*;

pub fn sp() -> Span {
    Span::new(0, 0)
}

pub fn n(v: f64) -> Expr {
    Expr::num(v, v.fract() != 0.0, sp())
}

pub fn rv(k: u32) -> VarRef {
    VarRef { kind: VarKind::R(k), span: sp() }
}

pub fn r(k: u32) -> Expr {
    var_expr(&rv(k))
}

pub fn hv(k: u32) -> VarRef {
    VarRef { kind: VarKind::Hash(k), span: sp() }
}

pub fn h(k: u32) -> Expr {
    var_expr(&hv(k))
}

pub fn named(name: &str) -> VarRef {
    VarRef { kind: VarKind::Named { name: name.into(), indices: vec![] }, span: sp() }
}

pub fn assign(target: VarRef, value: Expr) -> Item {
    assign_item(&target, value, sp())
}

pub fn word_item(letter: u8, value: Expr) -> Item {
    item(ItemKind::Word(Word { addr: Addr::Letter(letter), value: WordValue::Expr(value), span: sp() }), sp())
}

pub fn ret_item() -> Item {
    item(ItemKind::Return { to: None }, sp())
}

pub fn cmp_rel(op: CmpOp, a: Expr, b: Expr) -> Expr {
    Expr::new(ExprKind::Cmp(op, Tolerance::Relative, Box::new(a), Box::new(b)), sp())
}

pub fn block(items: Vec<Item>) -> Stmt {
    block_stmt(items, sp())
}

pub fn program(body: Vec<Stmt>) -> Program {
    Program { name: None, head: None, params: vec![], save: false, body, span: sp() }
}

pub fn if_stmt(cond: Expr, then_body: Vec<Stmt>, else_body: Option<Vec<Stmt>>) -> Stmt {
    let m = BlockMeta::default();
    let else_part = else_body.map(|body| ElsePart { head: m.clone(), body });
    Stmt { kind: StmtKind::If(Box::new(IfStmt { head: m.clone(), cond, then_body, else_part, end: m })), span: sp() }
}

pub fn while_stmt(cond: Expr, body: Vec<Stmt>) -> Stmt {
    let m = BlockMeta::default();
    Stmt { kind: StmtKind::While(Box::new(WhileStmt { head: m.clone(), cond, body, end: m })), span: sp() }
}

/// `N10 assign`, `L - ` (labelled, no items), `- word`: a block's number/label and item kinds.
pub fn shape(s: &Stmt) -> String {
    match &s.kind {
        StmtKind::Block(b) => {
            let head = match (&b.meta.number, &b.meta.label) {
                (Some(n), _) => format!("N{}", n.value),
                (None, Some(_)) => "L -".into(),
                _ => "-".into(),
            };
            let kinds: Vec<&str> = b
                .items
                .iter()
                .map(|i| match i.kind {
                    ItemKind::Assign { .. } => "assign",
                    ItemKind::Word(_) => "word",
                    ItemKind::Goto(_) => "goto",
                    ItemKind::IfThen { .. } => "ifthen",
                    ItemKind::Return { .. } => "return",
                    _ => "other",
                })
                .collect();
            format!("{head} {}", kinds.join(" "))
        }
        StmtKind::Do(_) => "do".into(),
        _ => "structure".into(),
    }
}

/// The addresses of a block's words, space separated.
pub fn shape_words(s: &Stmt) -> String {
    match &s.kind {
        StmtKind::Block(b) => b
            .items
            .iter()
            .filter_map(|i| match &i.kind {
                ItemKind::Word(w) => Some(w.addr.as_str().to_string()),
                _ => None,
            })
            .collect::<Vec<_>>()
            .join(" "),
        _ => String::new(),
    }
}
