//! The structurer: one program's blocks become a tree. `WHILE[..]DOm … ENDm` and `DOm … ENDm`
//! become `StmtKind::Do`, with the FANUC rules checked (ids 1..3, ranges nest and do not
//! cross, at most three levels); then every `GOTO n` must find an `N n` in the same program.

use super::block::Line;
use crate::diag::Diagnostic;
use crate::dialect::ParseOptions;
use crate::ir::visit::{metas, walk_stmts};
use crate::ir::{BlockMeta, DoStmt, Expr, ItemKind, ProgName, Program, Stmt, StmtKind, Target};
use crate::span::{FileId, Span};
use std::collections::HashSet;

/// The blocks of one program as read, before structuring.
pub struct ProgramLines {
    pub name: Option<ProgName>,
    pub head: Option<BlockMeta>,
    pub span: Span,
    lines: Vec<Line>,
    /// Inside `G10 L50` … `G11`.
    pub param_mode: bool,
    /// N numbers of blocks that failed to parse (still valid GOTO targets).
    known: Vec<u32>,
}

impl ProgramLines {
    pub fn new(name: Option<ProgName>, head: Option<BlockMeta>, span: Span) -> Self {
        ProgramLines { name, head, span, lines: Vec::new(), param_mode: false, known: Vec::new() }
    }

    pub fn is_empty(&self) -> bool {
        self.lines.is_empty() && self.known.is_empty()
    }

    /// Only comment blocks so far (a title before the first `O`).
    pub fn only_comments(&self) -> bool {
        self.known.is_empty()
            && self.lines.iter().all(|l| match l {
                Line::Block(b) => b.items.is_empty() && b.meta.number.is_none(),
                _ => false,
            })
    }

    pub fn push(&mut self, line: Line) {
        self.extend_span(line.meta().span);
        self.lines.push(line);
    }

    pub fn extend_span(&mut self, s: Span) {
        self.span = self.span.to(s);
    }

    pub fn note_number(&mut self, n: u32) {
        self.known.push(n);
    }
}

struct Open {
    meta: BlockMeta,
    id: u64,
    id_span: Span,
    cond: Option<Expr>,
    body: Vec<Stmt>,
}

/// Builds the program tree and checks loops and jump targets.
pub fn build(
    p: ProgramLines,
    file: FileId,
    opts: &ParseOptions,
    ignored: &[(u32, Span)],
) -> (Program, Vec<Diagnostic>) {
    let mut diags = Vec::new();
    let max = opts.semantics.max_loop_nesting as usize;
    let mut top: Vec<Stmt> = Vec::new();
    let mut stack: Vec<Open> = Vec::new();
    // END ids whose DO was closed early by a crossed range: their END is already reported.
    let mut crossed: Vec<u64> = Vec::new();

    fn push(stack: &mut [Open], top: &mut Vec<Stmt>, s: Stmt) {
        match stack.last_mut() {
            Some(o) => o.body.push(s),
            None => top.push(s),
        }
    }

    fn close(o: Open, end: BlockMeta) -> Stmt {
        Stmt {
            span: o.meta.span.to(end.span),
            kind: StmtKind::Do(Box::new(DoStmt {
                head: o.meta,
                id: o.id.min(255) as u8,
                cond: o.cond,
                body: o.body,
                end,
            })),
        }
    }

    for line in p.lines {
        match line {
            Line::Block(b) => {
                let span = b.meta.span;
                push(&mut stack, &mut top, Stmt { kind: StmtKind::Block(b), span });
            }
            Line::Program { .. } => {}
            Line::DoHead { meta, id, id_span, cond } => {
                if !(1..=3).contains(&id) {
                    diags.push(
                        Diagnostic::error("NC230", format!("DO{id}: loop numbers are 1, 2 and 3"))
                            .primary(file, id_span, "not 1, 2 or 3")
                            .note("the control raises alarm 126 for any other loop number")
                            .hint("use DO1, DO2 or DO3 (numbers may be reused by loops that do not overlap)"),
                    );
                } else if stack.len() >= max {
                    diags.push(
                        Diagnostic::error("NC235", format!("more than {max} nested DO loops"))
                            .primary(file, meta.span, format!("loop level {}", stack.len() + 1))
                            .secondary(file, stack[0].meta.span, "outermost loop")
                            .note(format!("FANUC nests at most {max} DO loops in one program"))
                            .hint("move the inner loop into a macro called with G65, or use IF…GOTO"),
                    );
                }
                stack.push(Open { meta, id, id_span, cond, body: Vec::new() });
            }
            Line::DoEnd { meta, id, id_span } => {
                let Some(pos) = stack.iter().rposition(|o| o.id == id) else {
                    if let Some(k) = crossed.iter().position(|&c| c == id) {
                        crossed.remove(k);
                        push(&mut stack, &mut top, plain(meta));
                        continue;
                    }
                    if let Some(o) = stack.pop() {
                        // END2 while DO1 is the open loop: report once and let it close DO1.
                        diags.push(
                            Diagnostic::error("NC231", format!("END{id} closes DO{}", o.id))
                                .primary(file, id_span, format!("END{id} here"))
                                .secondary(file, o.id_span, format!("the open loop is DO{}", o.id))
                                .note("END must carry the number of the innermost open DO")
                                .hint(format!("write END{}", o.id)),
                        );
                        let s = close(o, meta);
                        push(&mut stack, &mut top, s);
                        continue;
                    }
                    diags.push(
                        Diagnostic::error("NC234", format!("END{id} without DO{id}"))
                            .primary(file, id_span, format!("no open DO{id}"))
                            .note("every ENDm closes the loop opened by the nearest `WHILE[…]DOm` or `DOm` before it")
                            .hint(format!("add `WHILE[…]DO{id}` (or `DO{id}`) before this block, or delete END{id}")),
                    );
                    push(&mut stack, &mut top, plain(meta));
                    continue;
                };
                if pos + 1 < stack.len() {
                    // Crossed ranges: DO1 … DO2 … END1 … END2.
                    let inner = &stack[pos + 1];
                    diags.push(
                        Diagnostic::error("NC232", format!("END{id} crosses the range of DO{}", inner.id))
                            .primary(file, id_span, format!("closes DO{id} while DO{} is open", inner.id))
                            .secondary(file, stack[pos].id_span, format!("DO{id} starts here"))
                            .secondary(file, inner.id_span, format!("DO{} starts inside it", inner.id))
                            .note("DO ranges must nest: the loop opened last closes first")
                            .hint(format!("close DO{} with END{} before END{id}", inner.id, inner.id)),
                    );
                    while stack.len() > pos + 1 {
                        let Some(o) = stack.pop() else { break };
                        crossed.push(o.id);
                        let head = o.meta.clone();
                        let s = close(o, head);
                        push(&mut stack, &mut top, s);
                    }
                }
                if let Some(o) = stack.pop() {
                    let s = close(o, meta);
                    push(&mut stack, &mut top, s);
                }
            }
        }
    }
    while let Some(o) = stack.pop() {
        diags.push(
            Diagnostic::error("NC233", format!("DO{} without END{}", o.id, o.id))
                .primary(file, o.id_span, "this loop is never closed")
                .note("the control raises an alarm when it reaches the end of the program inside a loop")
                .hint(format!("add `END{}` after the last block of the loop", o.id)),
        );
        let head = o.meta.clone();
        let s = close(o, head);
        push(&mut stack, &mut top, s);
    }

    check_gotos(&top, &p.known, file, ignored, &mut diags);

    let mut span = p.span;
    if let Some(h) = &p.head {
        span = span.to(h.span);
    }
    for s in &top {
        span = span.to(s.span);
    }
    (Program { name: p.name, head: p.head, params: vec![], save: false, body: top, span }, diags)
}

fn plain(meta: BlockMeta) -> Stmt {
    let span = meta.span;
    Stmt { kind: StmtKind::Block(crate::ir::Block { meta, items: vec![] }), span }
}

/// Every literal `GOTO n` needs a block `Nn` in the same program.
fn check_gotos(body: &[Stmt], known: &[u32], file: FileId, ignored: &[(u32, Span)], diags: &mut Vec<Diagnostic>) {
    let mut numbers: HashSet<u32> = known.iter().copied().collect();
    let mut targets = Vec::new();
    walk_stmts(body, &mut |s| {
        for m in metas(&s.kind) {
            if let Some(n) = &m.number {
                numbers.insert(n.value);
            }
        }
        if let StmtKind::Block(b) = &s.kind {
            for it in &b.items {
                if let ItemKind::Goto(g) = &it.kind {
                    if let Target::Number(n) = &g.target {
                        targets.push(n.clone());
                    }
                }
            }
        }
    });
    for t in targets {
        if numbers.contains(&t.value) {
            continue;
        }
        let mut d = Diagnostic::error("NC236", format!("no block N{} in this program", t.value)).primary(
            file,
            t.span,
            "jump target not found",
        );
        if let Some((_, s)) = ignored.iter().find(|(n, _)| *n == t.value) {
            d = d
                .secondary(file, *s, "this block is after the closing `%`")
                .note("the control does not read anything after the second `%`")
                .hint(format!("move N{} before the closing `%`", t.value));
        } else {
            d = d
                .note("GOTO searches only the current program (alarm 128 if the number is missing)")
                .hint(format!("add a block starting with N{}, or jump to an existing N number", t.value));
        }
        diags.push(d);
    }
}
