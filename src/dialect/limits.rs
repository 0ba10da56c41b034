//! The bounds both readers put on one expression, in one place: how many operations may nest
//! in its tree, and how deeply brackets may nest before the grammar runs.
//!
//! Every walk over an expression after the reader (structurers, passes, both emitters, the
//! evaluator, `ir::dump`, `ir::visit`, and the drop of its boxes) recurses once per level,
//! and pest recurses once per nested bracket. These bounds, with [`THREAD_STACK`] for the
//! threads nctrans starts (a spawned thread has only 2 MiB unless told), are what keeps all
//! of them on the stack, in debug builds too. `tests/expr_limits.rs` runs every command on
//! expressions at the limits on half that stack. No real program comes near them: a
//! CAM or hand-written expression has a few dozen operations, and FANUC itself allows five
//! levels of brackets.

use super::Dialect;
use crate::diag::Diagnostic;
use crate::ir::visit::{item_exprs, walk_stmts};
use crate::ir::{Expr, ExprKind, Item, ItemKind, Stmt, StmtKind, VarKind};
use crate::span::{FileId, Span};

/// The most operations that may nest in one expression tree: `1+1+…` with 256 `+` is
/// accepted, with 257 it is NC130. A flat chain of left-associative operators is as deep as
/// it is long, so this is also its length.
pub const MAX_EXPR_DEPTH: u32 = 256;

/// The deepest nesting of `( )` / `[ ]` either reader hands to its grammar (FANUC's own
/// limit, 5 by default, comes from the profile and is never above this).
pub const MAX_NESTING: u32 = 64;

/// The stack of every thread nctrans starts to read, translate or run a program (batch
/// workers, the checker's second run): the main thread's 8 MiB, so what the limits above
/// keep safe on the main thread is safe there too. The deepest walk allowed, a Siemens
/// chain of 256 comparisons lowered for FANUC inside 64 nested structures, takes under
/// 3 MiB in a debug build and a fraction of that optimised; a caller of the library that
/// translates on threads of its own should give them as much. Only address space: pages
/// are used as the stack grows.
pub const THREAD_STACK: usize = 8 << 20;

/// How many operations nest in `e`: 0 for a number or a plain variable, one more for each
/// operator, function, comparison, indirection or subscript above the deepest leaf. Without
/// recursion, so it can measure any tree.
pub fn depth(e: &Expr) -> u32 {
    let mut max = 0;
    let mut stack: Vec<(&Expr, u32)> = vec![(e, 0)];
    while let Some((x, d)) = stack.pop() {
        max = max.max(d);
        match &x.kind {
            ExprKind::Num(_) | ExprKind::Vacant | ExprKind::Str(_) | ExprKind::Ident(_) => {}
            ExprKind::Var(v) => match &v.kind {
                VarKind::Hash(_) | VarKind::R(_) => {}
                VarKind::HashIndirect(a) | VarKind::RIndirect(a) => stack.push((a, d + 1)),
                VarKind::Named { indices, .. } | VarKind::System { indices, .. } => {
                    stack.extend(indices.iter().map(|a| (a, d + 1)));
                }
            },
            ExprKind::Unary(_, a) => stack.push((a, d + 1)),
            ExprKind::Binary(_, a, b) | ExprKind::Cmp(_, _, a, b) => {
                stack.push((a, d + 1));
                stack.push((b, d + 1));
            }
            ExprKind::Func(_, args) => stack.extend(args.iter().map(|a| (a, d + 1))),
        }
    }
    max
}

/// NC130: the expression at `span` has more than [`MAX_EXPR_DEPTH`] nested operations.
/// `hint` names the dialect's intermediate variables.
pub fn too_deep(file: FileId, span: Span, hint: &str) -> Diagnostic {
    Diagnostic::error("NC130", format!("expression nested deeper than {MAX_EXPR_DEPTH} operations"))
        .primary(file, span, "too long to evaluate in one expression")
        .note(format!(
            "nctrans reads at most {MAX_EXPR_DEPTH} nested operations in one expression (a chain `a+b+…` counts each operator)"
        ))
        .hint(hint)
}

/// NC130: brackets nested deeper than [`MAX_NESTING`]; `at` is the first bracket too deep.
pub fn too_nested(file: FileId, at: Span, level: u32, hint: &str) -> Diagnostic {
    Diagnostic::error("NC130", format!("expression nested deeper than {MAX_NESTING} levels"))
        .primary(file, at, format!("level {level}"))
        .hint(hint)
}

/// NC130 for each expression of a translated `body` that the translation made deeper than
/// [`MAX_EXPR_DEPTH`], at its source span: its output would not read back. Checked before
/// the output is written, so the message is about the source, not about nctrans's writer.
pub fn deepened(body: &[Stmt], file: FileId, target: Dialect) -> Vec<Diagnostic> {
    let (name, example) = match target {
        Dialect::Sinumerik => ("Sinumerik", " (an exact FANUC comparison is a difference with 0 there)"),
        Dialect::Fanuc => ("FANUC", ""),
    };
    fn item<'a>(it: &'a Item, out: &mut Vec<&'a Expr>) {
        out.extend(item_exprs(it));
        if let ItemKind::IfThen { then, .. } = &it.kind {
            item(then, out);
        }
    }
    let mut exprs: Vec<&Expr> = Vec::new();
    walk_stmts(body, &mut |s| match &s.kind {
        StmtKind::Block(b) => b.items.iter().for_each(|it| item(it, &mut exprs)),
        StmtKind::If(i) => exprs.push(&i.cond),
        StmtKind::While(w) => exprs.push(&w.cond),
        StmtKind::For(f) => exprs.extend([&f.from, &f.to]),
        StmtKind::Repeat(r) => exprs.push(&r.until),
        StmtKind::Do(d) => exprs.extend(d.cond.as_ref()),
        StmtKind::Loop(_) => {}
    });
    exprs
        .into_iter()
        .filter(|e| depth(e) > MAX_EXPR_DEPTH)
        .map(|e| {
            Diagnostic::error("NC130", format!("in {name} this expression nests more than {MAX_EXPR_DEPTH} operations"))
                .primary(file, e.span, "too long once translated")
                .note(format!(
                    "the translation writes operations the source does not{example}, and nctrans reads at most {MAX_EXPR_DEPTH} nested operations in one expression"
                ))
                .hint("split the expression into several assignments in the source")
        })
        .collect()
}
