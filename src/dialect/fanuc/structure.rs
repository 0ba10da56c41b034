//! The structurer: one program's blocks become a tree. `WHILE[..]DOm … ENDm` and `DOm … ENDm`
//! become `StmtKind::Do`, with the FANUC rules checked (ids 1..3, ranges nest and do not
//! cross, at most three levels); then every `GOTO n` must find an `N n` in the same program.

use super::block::Line;
use crate::diag::Diagnostic;
use crate::dialect::ParseOptions;
use crate::ir::visit::{child_bodies, metas};
use crate::ir::{BlockMeta, DoStmt, Expr, ItemKind, ProgName, Program, Stmt, StmtKind, Target};
use crate::span::{FileId, Span};
use std::collections::HashSet;

/// One program being read: its tree is built block by block, so a million-block file never
/// holds a second copy of its blocks.
pub struct ProgramLines {
    pub name: Option<ProgName>,
    pub head: Option<BlockMeta>,
    pub span: Span,
    /// Inside `G10 L50` … `G11`.
    pub param_mode: bool,
    /// N numbers of blocks that failed to parse (still valid GOTO targets).
    known: Vec<u32>,
    top: Vec<Stmt>,
    /// Open DO loops, outermost first.
    stack: Vec<Open>,
    /// END ids whose DO was closed early by a crossed range: their END is already reported.
    crossed: Vec<u64>,
    diags: Vec<Diagnostic>,
    file: FileId,
    max_nesting: usize,
    /// Streaming: statements are taken out as they finish; what the final GOTO check
    /// needs from them is kept here.
    streamed: Option<Streamed>,
    /// A block read for an index only had words but got no items (so the program is not
    /// only comments; see [`ProgramLines::push_skeleton`]).
    skeleton_words: bool,
}

#[derive(Default)]
struct Streamed {
    drained: bool,
    numbers: crate::dialect::runs::Runs,
    count: u64,
    targets: Vec<crate::ir::SeqNo>,
}

struct Open {
    meta: BlockMeta,
    id: u64,
    id_span: Span,
    cond: Option<Expr>,
    body: Vec<Stmt>,
}

fn close(o: Open, end: BlockMeta) -> Stmt {
    Stmt {
        span: o.meta.span.to(end.span),
        kind: StmtKind::Do(Box::new(DoStmt { head: o.meta, id: o.id.min(255) as u8, cond: o.cond, body: o.body, end })),
    }
}

impl ProgramLines {
    pub fn new(name: Option<ProgName>, head: Option<BlockMeta>, span: Span, file: FileId, opts: &ParseOptions) -> Self {
        ProgramLines {
            name,
            head,
            span,
            param_mode: false,
            known: Vec::new(),
            top: Vec::new(),
            stack: Vec::new(),
            crossed: Vec::new(),
            diags: Vec::new(),
            file,
            max_nesting: opts.semantics.max_loop_nesting as usize,
            streamed: None,
            skeleton_words: false,
        }
    }

    /// Switches to streaming (see [`ProgramLines::drain`]).
    pub fn stream(&mut self) {
        self.streamed.get_or_insert_with(Streamed::default);
    }

    fn drained(&self) -> bool {
        self.streamed.as_ref().is_some_and(|s| s.drained)
    }

    pub fn at_top(&self) -> bool {
        self.stack.is_empty()
    }

    /// Takes the finished top-level statements. Comment blocks before the first `O` are
    /// held back until it is known whether they are that program's title.
    pub fn drain(&mut self) -> Vec<Stmt> {
        if !self.stack.is_empty() || self.top.is_empty() || (self.name.is_none() && self.only_comments()) {
            return Vec::new();
        }
        let top = std::mem::take(&mut self.top);
        self.note_drained(&top);
        top
    }

    /// [`ProgramLines::drain`] into `out`; when `out` is empty the two vectors trade
    /// places, so a stream of one-block statements allocates no new vector per block.
    pub fn drain_into(&mut self, out: &mut Vec<Stmt>) {
        if !self.stack.is_empty() || self.top.is_empty() || (self.name.is_none() && self.only_comments()) {
            return;
        }
        let from = out.len();
        if from == 0 {
            std::mem::swap(&mut self.top, out);
        } else {
            out.append(&mut self.top);
        }
        self.note_drained(&out[from..]);
    }

    /// Remembers what the final GOTO check needs from drained statements.
    fn note_drained(&mut self, top: &[Stmt]) {
        let s = self.streamed.get_or_insert_with(Streamed::default);
        s.drained = true;
        let (runs, count) = (&mut s.numbers, &mut s.count);
        goto_facts_into(
            top,
            &mut |n| {
                runs.push(n, *count, Span::default());
                *count += 1;
            },
            &mut s.targets,
        );
    }

    pub fn is_empty(&self) -> bool {
        !self.drained() && self.top.is_empty() && self.stack.is_empty() && self.known.is_empty()
    }

    /// Only comment blocks so far (a title before the first `O`).
    pub fn only_comments(&self) -> bool {
        !self.drained()
            && !self.skeleton_words
            && self.known.is_empty()
            && self.stack.is_empty()
            && self.top.iter().all(|s| match &s.kind {
                StmtKind::Block(b) => b.items.is_empty() && b.meta.number.is_none(),
                _ => false,
            })
    }

    pub fn extend_span(&mut self, s: Span) {
        self.span = self.span.to(s);
    }

    pub fn note_number(&mut self, n: u32) {
        self.known.push(n);
    }

    fn add(&mut self, s: Stmt) {
        match self.stack.last_mut() {
            Some(o) => o.body.push(s),
            None => self.top.push(s),
        }
    }

    /// Whether a plain block read now would be drained at once, right after it is added
    /// (see [`ProgramLines::push_drained`]): no loop is open, nothing waits, the program has
    /// a name (so nothing is held back as a title) and it is streamed.
    pub fn drains_at_once(&self) -> bool {
        self.stack.is_empty() && self.top.is_empty() && self.name.is_some() && self.streamed.is_some()
    }

    /// What [`ProgramLines::push`] of a plain block `span`, numbered `number`, with plain
    /// words only (no GOTO), and then [`ProgramLines::drain_into`] leave behind when
    /// [`ProgramLines::drains_at_once`]: the span grown, the number noted as drained. The
    /// statement itself the caller has built.
    pub fn push_drained(&mut self, span: Span, number: Option<u32>) {
        self.extend_span(span);
        let s = self.streamed.get_or_insert_with(Streamed::default);
        s.drained = true;
        if let Some(n) = number {
            s.numbers.push(n, s.count, Span::default());
            s.count += 1;
        }
    }

    /// [`ProgramLines::push_skeleton`] of a plain block with or without `words`, then a
    /// drain, when [`ProgramLines::drains_at_once`]: [`ProgramLines::push_drained`] (the
    /// statement is not made).
    #[inline]
    pub fn push_drained_skeleton(&mut self, span: Span, number: Option<u32>, words: bool) {
        self.skeleton_words |= words;
        self.push_drained(span, number);
    }

    /// Adds a plain block read for an index only (see `fast::skeleton`): its items were
    /// not built, `words` says whether it had any. Items of a plain block matter here only
    /// as "not a comment block" (they hold no GOTO), which `words` stands for.
    pub fn push_skeleton(&mut self, meta: BlockMeta, words: bool) {
        self.skeleton_words |= words;
        self.push(Line::Block(crate::ir::Block { meta, items: Vec::new() }));
    }

    /// Adds one block, opening or closing loops.
    pub fn push(&mut self, line: Line) {
        self.extend_span(line.meta().span);
        let file = self.file;
        match line {
            Line::Block(b) => {
                let span = b.meta.span;
                self.add(Stmt { kind: StmtKind::Block(b), span });
            }
            Line::Program { .. } => {}
            Line::DoHead { meta, id, id_span, cond } => {
                let max = self.max_nesting;
                if !(1..=3).contains(&id) {
                    self.diags.push(
                        Diagnostic::error("NC230", format!("DO{id}: loop numbers are 1, 2 and 3"))
                            .primary(file, id_span, "not 1, 2 or 3")
                            .note("the control raises alarm 126 for any other loop number")
                            .hint("use DO1, DO2 or DO3 (numbers may be reused by loops that do not overlap)"),
                    );
                } else if self.stack.len() >= max {
                    let outer = self.stack.first().map_or(meta.span, |o| o.meta.span);
                    self.diags.push(
                        Diagnostic::error("NC235", format!("more than {max} nested DO loops"))
                            .primary(file, meta.span, format!("loop level {}", self.stack.len() + 1))
                            .secondary(file, outer, "outermost loop")
                            .note(format!("FANUC nests at most {max} DO loops in one program"))
                            .hint("move the inner loop into a macro called with G65, or use IF…GOTO"),
                    );
                }
                self.stack.push(Open { meta, id, id_span, cond, body: Vec::new() });
            }
            Line::DoEnd { meta, id, id_span } => self.end(meta, id, id_span),
        }
    }

    fn end(&mut self, meta: BlockMeta, id: u64, id_span: Span) {
        let file = self.file;
        let Some(pos) = self.stack.iter().rposition(|o| o.id == id) else {
            if let Some(k) = self.crossed.iter().position(|&c| c == id) {
                self.crossed.remove(k);
                self.add(plain(meta));
                return;
            }
            if let Some(o) = self.stack.pop() {
                // END2 while DO1 is the open loop: report once and let it close DO1.
                self.diags.push(
                    Diagnostic::error("NC231", format!("END{id} closes DO{}", o.id))
                        .primary(file, id_span, format!("END{id} here"))
                        .secondary(file, o.id_span, format!("the open loop is DO{}", o.id))
                        .note("END must carry the number of the innermost open DO")
                        .hint(format!("write END{}", o.id)),
                );
                let s = close(o, meta);
                self.add(s);
                return;
            }
            self.diags.push(
                Diagnostic::error("NC234", format!("END{id} without DO{id}"))
                    .primary(file, id_span, format!("no open DO{id}"))
                    .note("every ENDm closes the loop opened by the nearest `WHILE[…]DOm` or `DOm` before it")
                    .hint(format!("add `WHILE[…]DO{id}` (or `DO{id}`) before this block, or delete END{id}")),
            );
            self.add(plain(meta));
            return;
        };
        if pos + 1 < self.stack.len() {
            // Crossed ranges: DO1 … DO2 … END1 … END2.
            let inner = &self.stack[pos + 1];
            self.diags.push(
                Diagnostic::error("NC232", format!("END{id} crosses the range of DO{}", inner.id))
                    .primary(file, id_span, format!("closes DO{id} while DO{} is open", inner.id))
                    .secondary(file, self.stack[pos].id_span, format!("DO{id} starts here"))
                    .secondary(file, inner.id_span, format!("DO{} starts inside it", inner.id))
                    .note("DO ranges must nest: the loop opened last closes first")
                    .hint(format!("close DO{} with END{} before END{id}", inner.id, inner.id)),
            );
            while self.stack.len() > pos + 1 {
                let Some(o) = self.stack.pop() else { break };
                self.crossed.push(o.id);
                let head = o.meta.clone();
                let s = close(o, head);
                self.add(s);
            }
        }
        if let Some(o) = self.stack.pop() {
            let s = close(o, meta);
            self.add(s);
        }
    }
}

/// Closes what is still open and checks the jump targets of a finished program.
pub fn build(mut p: ProgramLines, ignored: &[(u32, Span)]) -> (Program, Vec<Diagnostic>) {
    let file = p.file;
    while let Some(o) = p.stack.pop() {
        p.diags.push(
            Diagnostic::error("NC233", format!("DO{} without END{}", o.id, o.id))
                .primary(file, o.id_span, "this loop is never closed")
                .note("the control raises an alarm when it reaches the end of the program inside a loop")
                .hint(format!("add `END{}` after the last block of the loop", o.id)),
        );
        let head = o.meta.clone();
        let s = close(o, head);
        p.add(s);
    }
    let mut diags = std::mem::take(&mut p.diags);
    check_gotos(&p.top, &p.known, p.streamed.as_ref(), file, ignored, &mut diags);
    let mut span = p.span;
    if let Some(h) = &p.head {
        span = span.to(h.span);
    }
    for s in &p.top {
        span = span.to(s.span);
    }
    (Program { name: p.name, head: p.head, params: vec![], save: false, body: p.top, span }, diags)
}

fn plain(meta: BlockMeta) -> Stmt {
    let span = meta.span;
    Stmt { kind: StmtKind::Block(crate::ir::Block { meta, items: vec![] }), span }
}

/// The N numbers of `body` (in order) and its literal GOTO targets.
fn goto_facts(body: &[Stmt]) -> (Vec<u32>, Vec<crate::ir::SeqNo>) {
    let mut numbers = Vec::new();
    let mut targets = Vec::new();
    goto_facts_into(body, &mut |n| numbers.push(n), &mut targets);
    (numbers, targets)
}

/// [`goto_facts`] without collecting the numbers (streaming hands each to `number`), in
/// the order `walk_stmts` visits them.
fn goto_facts_into<F: FnMut(u32)>(body: &[Stmt], number: &mut F, targets: &mut Vec<crate::ir::SeqNo>) {
    for s in body {
        match &s.kind {
            // A plain block (nearly all of them) without building the list of its metas.
            StmtKind::Block(b) => {
                if let Some(n) = &b.meta.number {
                    number(n.value);
                }
                for it in &b.items {
                    if let ItemKind::Goto(g) = &it.kind {
                        if let Target::Number(n) = &g.target {
                            targets.push(n.clone());
                        }
                    }
                }
            }
            other => {
                for m in metas(other) {
                    if let Some(n) = &m.number {
                        number(n.value);
                    }
                }
                for child in child_bodies(other) {
                    goto_facts_into(child, number, targets);
                }
            }
        }
    }
}

/// Every literal `GOTO n` needs a block `Nn` in the same program.
fn check_gotos(
    body: &[Stmt],
    known: &[u32],
    streamed: Option<&Streamed>,
    file: FileId,
    ignored: &[(u32, Span)],
    diags: &mut Vec<Diagnostic>,
) {
    let (found, mut targets) = goto_facts(body);
    let numbers: HashSet<u32> = known.iter().copied().chain(found).collect();
    if let Some(s) = streamed {
        // Targets from drained statements come first: they are earlier in the file.
        targets.splice(0..0, s.targets.iter().cloned());
    }
    for t in targets {
        if numbers.contains(&t.value) || streamed.is_some_and(|s| s.numbers.first_from(t.value, 0).is_some()) {
            continue;
        }
        if let Some((_, s)) = ignored.iter().find(|(n, _)| *n == t.value) {
            // Such programs run on real machines until that path is taken: the jump is the
            // control's alarm when it executes (the evaluator's no-target alarm), not a reason
            // to refuse the file.
            diags.push(
                Diagnostic::warning("NC254", format!("N{} is only after the closing `%`", t.value))
                    .primary(file, t.span, "this jump alarms when it is taken")
                    .secondary(file, *s, "this block is after the closing `%`")
                    .note("the control does not read anything after the second `%` (alarm 128 when the jump runs)")
                    .hint(format!("move N{} before the closing `%`", t.value)),
            );
            continue;
        }
        let mut d = Diagnostic::error("NC236", format!("no block N{} in this program", t.value)).primary(
            file,
            t.span,
            "jump target not found",
        );
        {
            d = d
                .note("GOTO searches only the current program (alarm 128 if the number is missing)")
                .hint(format!("add a block starting with N{}, or jump to an existing N number", t.value));
        }
        diags.push(d);
    }
}
