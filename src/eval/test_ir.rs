//! Small IR builders for the evaluator's unit tests (no parser needed).

use crate::dialect::Dialect;
use crate::ir::*;
use crate::span::Span;

pub fn sp() -> Span {
    Span::new(0, 1)
}
pub fn n(v: f64) -> Expr {
    Expr::num(v, false, sp())
}
/// A literal with a decimal point.
pub fn p(v: f64) -> Expr {
    Expr::num(v, true, sp())
}
pub fn vacant() -> Expr {
    Expr::new(ExprKind::Vacant, sp())
}
pub fn var(kind: VarKind) -> Expr {
    Expr::new(ExprKind::Var(Box::new(VarRef { kind, span: sp() })), sp())
}
pub fn hash(k: u32) -> Expr {
    var(VarKind::Hash(k))
}
pub fn r(k: u32) -> Expr {
    var(VarKind::R(k))
}
pub fn named(s: &str) -> Expr {
    var(VarKind::Named { name: s.into(), indices: vec![] })
}
pub fn vref(kind: VarKind) -> VarRef {
    VarRef { kind, span: sp() }
}
pub fn bin(op: BinOp, a: Expr, b: Expr) -> Expr {
    Expr::new(ExprKind::Binary(op, Box::new(a), Box::new(b)), sp())
}
pub fn neg(a: Expr) -> Expr {
    Expr::new(ExprKind::Unary(UnOp::Neg, Box::new(a)), sp())
}
pub fn cmp(op: CmpOp, tol: Tolerance, a: Expr, b: Expr) -> Expr {
    Expr::new(ExprKind::Cmp(op, tol, Box::new(a), Box::new(b)), sp())
}
pub fn func(f: Func, args: Vec<Expr>) -> Expr {
    Expr::new(ExprKind::Func(f, args), sp())
}
pub fn item(kind: ItemKind) -> Item {
    Item { kind, span: sp() }
}
pub fn word(addr: &str, e: Expr) -> Item {
    let a = if addr.len() == 1 { Addr::Letter(addr.as_bytes()[0]) } else { Addr::Name(addr.into()) };
    item(ItemKind::Word(Word { addr: a, value: WordValue::Expr(e), span: sp() }))
}
pub fn word_v(addr: &str, v: WordValue) -> Item {
    let a = if addr.len() == 1 { Addr::Letter(addr.as_bytes()[0]) } else { Addr::Name(addr.into()) };
    item(ItemKind::Word(Word { addr: a, value: v, span: sp() }))
}
pub fn assign(kind: VarKind, e: Expr) -> Item {
    item(ItemKind::Assign { target: Box::new(vref(kind)), value: e })
}
pub fn goto(search: Search, target: Target, cond: Option<Expr>) -> Item {
    item(ItemKind::Goto(Box::new(Goto { search, target, cond, missing_continues: false })))
}
pub fn num_target(k: u32) -> Target {
    Target::Number(SeqNo { value: k, span: sp() })
}
pub fn label_target(s: &str) -> Target {
    Target::Label(Label { name: s.into(), span: sp() })
}
pub fn end() -> Item {
    item(ItemKind::End { code: EndCode::M30 })
}

/// A block from items; blocks get distinct spans so that warnings are per block.
pub struct B {
    pub meta: BlockMeta,
    pub items: Vec<Item>,
}
pub fn blk(items: Vec<Item>) -> B {
    B { meta: BlockMeta::default(), items }
}
impl B {
    pub fn n(mut self, k: u32) -> B {
        self.meta.number = Some(SeqNo { value: k, span: sp() });
        self
    }
    pub fn label(mut self, s: &str) -> B {
        self.meta.label = Some(Label { name: s.into(), span: sp() });
        self
    }
    pub fn stmt(self) -> Stmt {
        Stmt { kind: StmtKind::Block(Block { meta: self.meta, items: self.items }), span: sp() }
    }
}
pub fn s(items: Vec<Item>) -> Stmt {
    blk(items).stmt()
}
pub fn meta() -> BlockMeta {
    BlockMeta::default()
}
pub fn while_(cond: Expr, body: Vec<Stmt>) -> Stmt {
    Stmt { kind: StmtKind::While(Box::new(WhileStmt { head: meta(), cond, body, end: meta() })), span: sp() }
}
pub fn do_(cond: Option<Expr>, body: Vec<Stmt>) -> Stmt {
    Stmt { kind: StmtKind::Do(Box::new(DoStmt { head: meta(), id: 1, cond, body, end: meta() })), span: sp() }
}

/// Gives every block its own span (offset = index) so that diagnostics can tell them apart.
fn respan(body: &mut [Stmt], next: &mut u32) {
    for st in body {
        match &mut st.kind {
            StmtKind::Block(b) => {
                b.meta.span = Span::new(*next, *next + 1);
                *next += 1;
            }
            StmtKind::While(w) => {
                w.head.span = Span::new(*next, *next + 1);
                *next += 1;
                respan(&mut w.body, next);
            }
            StmtKind::Do(w) => {
                w.head.span = Span::new(*next, *next + 1);
                *next += 1;
                respan(&mut w.body, next);
            }
            _ => {}
        }
    }
}

pub fn program(name: Option<ProgName>, mut body: Vec<Stmt>) -> Program {
    let mut next = 0;
    respan(&mut body, &mut next);
    Program { name, head: None, params: vec![], save: false, body, span: sp() }
}
pub fn unit(d: Dialect, programs: Vec<Program>) -> Unit {
    Unit { dialect: d, file: 0, programs }
}
