//! Flattening a program's IR tree once into linear code with jump targets, so that GOTO
//! into and out of structures behaves like the controls' interpretive search, and the
//! label / N tables that the searches of each [`Search`] kind walk.

use super::paged::{Page, PagedSource};
use crate::diag::Diagnostic;
use crate::dialect::lit::LitBlock;
use crate::ir::{Block, BlockMeta, Expr, Program, Search, Stmt, StmtKind, VarRef, ENDLABEL};
use crate::span::{FileId, Span};
use std::cell::RefCell;
use std::collections::HashMap;
use std::rc::Rc;

/// Deepest structure nesting flattened (the parsers limit it far lower).
const MAX_NESTING: u32 = 256;

/// One executable step. Every op stands for one source block and counts as one step.
#[derive(Clone, Debug)]
pub enum Op {
    /// An NC block.
    Block(Block),
    /// An NC block of constant one-letter words only (see [`LitBlock`]).
    Lit(LitBlock),
    /// A structure block with nothing to do (`LOOP`, `REPEAT`, `ENDIF`, bare `DOm`).
    Nop(Span),
    /// `WHILE`/`IF`/`WHILE[..]DOm` head: continue when `cond` holds, else go to `target`.
    Test { span: Span, cond: Expr, target: usize },
    /// `ENDWHILE`, `ENDLOOP`, `ENDm`, `ELSE` (end of the then-part): go to `target`.
    Jump { span: Span, target: usize },
    /// `UNTIL cond`: back to `target` while `cond` is false.
    Until { span: Span, cond: Expr, target: usize },
    /// `FOR var = from TO to`: assign, then test `var <= to` (else go to `exit`).
    ForHead { span: Span, var: VarRef, from: Expr, to: Expr, exit: usize },
    /// `ENDFOR`: `var += 1`, then back to `body` while `var <= to` (`to` evaluated on
    /// every pass: the documented choice).
    ForEnd { span: Span, var: VarRef, to: Expr, body: usize },
}

impl Op {
    pub fn span(&self) -> Span {
        match self {
            Op::Block(b) => b.meta.span,
            Op::Lit(l) => l.span,
            Op::Nop(s) => *s,
            Op::Test { span, .. }
            | Op::Jump { span, .. }
            | Op::Until { span, .. }
            | Op::ForHead { span, .. }
            | Op::ForEnd { span, .. } => *span,
        }
    }
}

/// What a jump looks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Key {
    Number(u32),
    /// Interned label id (see [`Code::label_id`]).
    Label(u32),
}

/// A flattened program.
#[derive(Debug)]
pub struct Code {
    pub file: FileId,
    pub ops: Vec<Op>,
    /// Op index → the N number and label of its block, for every op that has one.
    marks: Vec<(usize, Option<u32>, Option<u32>)>,
    labels: HashMap<String, u32>,
    /// Resolved jumps: (from, search, key) → destination.
    memo: RefCell<HashMap<(usize, u8, Key), Option<usize>>>,
    /// A streamed program: its pager and program index. `ops` is empty, `marks` holds the
    /// labels only; block numbers are searched in the index's runs.
    paged: Option<(Rc<dyn PagedSource>, usize)>,
}

/// An op borrowed from a program in memory, or held by a page of a streamed one.
pub enum OpRef<'c> {
    Mem(&'c Op),
    Page(Rc<Page>, usize),
}

impl OpRef<'_> {
    pub fn op(&self) -> Option<&Op> {
        match self {
            OpRef::Mem(op) => Some(op),
            OpRef::Page(p, pc) => p.get(*pc),
        }
    }
}

struct Builder {
    /// Op index of `ops[0]` (a chunk of a streamed program starts part way).
    base: usize,
    file: FileId,
    ops: Vec<Op>,
    marks: Vec<(usize, Option<u32>, Option<u32>)>,
    labels: HashMap<String, u32>,
}

impl Builder {
    fn at(&self) -> usize {
        self.base + self.ops.len()
    }

    fn mark(&mut self, meta: &BlockMeta) {
        let at = self.at();
        let n = meta.number.as_ref().map(|n| n.value);
        let l = meta.label.as_ref().map(|l| {
            let next = self.labels.len() as u32;
            *self.labels.entry(l.name.clone()).or_insert(next)
        });
        if n.is_some() || l.is_some() {
            self.marks.push((at, n, l));
        }
    }

    fn push(&mut self, meta: &BlockMeta, op: Op) -> usize {
        self.mark(meta);
        self.ops.push(op);
        self.at() - 1
    }

    fn op_mut(&mut self, at: usize) -> Option<&mut Op> {
        self.ops.get_mut(at.wrapping_sub(self.base))
    }

    fn stmts(&mut self, body: &[Stmt], depth: u32) -> Result<(), Diagnostic> {
        for s in body {
            self.stmt(s, depth)?;
        }
        Ok(())
    }

    fn stmt(&mut self, s: &Stmt, depth: u32) -> Result<(), Diagnostic> {
        if depth > MAX_NESTING {
            return Err(Diagnostic::error("NC411", "control structures nested too deeply")
                .primary(self.file, s.span, "this structure")
                .hint("flatten the nesting into jumps or subprograms"));
        }
        let d = depth + 1;
        match &s.kind {
            StmtKind::Block(b) => {
                let op = LitBlock::of(b).map_or_else(|| Op::Block(b.clone()), Op::Lit);
                self.push(&b.meta, op);
            }
            StmtKind::If(st) => {
                let crate::ir::IfStmt { head, cond, then_body, else_part, end } = &**st;
                let test = self.push(head, Op::Test { span: head.span, cond: cond.clone(), target: 0 });
                self.stmts(then_body, d)?;
                let false_target = if let Some(e) = else_part {
                    let jump = self.push(&e.head, Op::Jump { span: e.head.span, target: 0 });
                    let else_start = self.at();
                    self.stmts(&e.body, d)?;
                    let end_at = self.push(end, Op::Nop(end.span));
                    set_target(self.op_mut(jump), end_at);
                    else_start
                } else {
                    self.push(end, Op::Nop(end.span))
                };
                set_target(self.op_mut(test), false_target);
            }
            StmtKind::While(w) => self.test_loop(&w.head, Some(&w.cond), &w.body, &w.end, d)?,
            StmtKind::Do(w) => self.test_loop(&w.head, w.cond.as_ref(), &w.body, &w.end, d)?,
            StmtKind::Loop(w) => self.test_loop(&w.head, None, &w.body, &w.end, d)?,
            StmtKind::Repeat(st) => {
                let crate::ir::RepeatStmt { head, body, end, until } = &**st;
                let top = self.push(head, Op::Nop(head.span));
                self.stmts(body, d)?;
                self.push(end, Op::Until { span: end.span, cond: until.clone(), target: top });
            }
            StmtKind::For(st) => {
                let crate::ir::ForStmt { head, var, from, to, body, end } = &**st;
                let h = self.push(
                    head,
                    Op::ForHead { span: head.span, var: var.clone(), from: from.clone(), to: to.clone(), exit: 0 },
                );
                self.stmts(body, d)?;
                self.push(end, Op::ForEnd { span: end.span, var: var.clone(), to: to.clone(), body: h + 1 });
                let exit = self.at();
                if let Some(Op::ForHead { exit: e, .. }) = self.op_mut(h) {
                    *e = exit;
                }
            }
        }
        Ok(())
    }

    fn test_loop(
        &mut self,
        head: &BlockMeta,
        cond: Option<&Expr>,
        body: &[Stmt],
        end: &BlockMeta,
        d: u32,
    ) -> Result<(), Diagnostic> {
        let top = match cond {
            Some(c) => self.push(head, Op::Test { span: head.span, cond: c.clone(), target: 0 }),
            None => self.push(head, Op::Nop(head.span)),
        };
        self.stmts(body, d)?;
        self.push(end, Op::Jump { span: end.span, target: top });
        let exit = self.at();
        if cond.is_some() {
            set_target(self.op_mut(top), exit);
        }
        Ok(())
    }
}

/// The ops of one chunk of a streamed program, built statement by statement as the chunk
/// is re-read (see [`ChunkOps`]); jump targets are absolute op indices.
pub struct ChunkOps(Builder);

impl ChunkOps {
    /// Ops from index `base` on, room for `cap`.
    pub fn new(file: FileId, base: usize, cap: usize) -> ChunkOps {
        ChunkOps(Builder { base, file, ops: Vec::with_capacity(cap), marks: Vec::new(), labels: HashMap::new() })
    }

    /// The next top-level statement.
    pub fn stmt(&mut self, s: Stmt) -> Result<(), Diagnostic> {
        match s.kind {
            // Plain blocks (nearly all of a CAM program) move into their op. Marks are
            // not kept: a streamed program's labels and numbers are in its index.
            StmtKind::Block(blk) => {
                self.0.ops.push(match LitBlock::of(&blk) {
                    Some(l) => Op::Lit(l),
                    None => Op::Block(blk),
                });
                Ok(())
            }
            kind => self.0.stmt(&Stmt { kind, span: s.span }, 0),
        }
    }

    /// The next block, to be read straight into its compact form in place (what
    /// [`ChunkOps::stmt`] makes of a plain block whose [`LitBlock::of`] is the block
    /// filled in); `None` when the compact form is off. Undo with [`ChunkOps::unlit`] when
    /// the line is not such a block.
    #[inline(always)]
    pub fn lit(&mut self) -> Option<&mut LitBlock> {
        if !LitBlock::enabled() {
            return None;
        }
        // A constant pushed after the vector has room: it is then written straight from
        // read-only data into its slot. `push` of an op made at run time builds it on the
        // stack and copies it twice (a memmove per re-read line); `resize_with` costs a
        // call and a loop per line.
        const EMPTY: Op = Op::Lit(LitBlock::EMPTY);
        self.0.ops.reserve(1);
        self.0.ops.push(EMPTY);
        match self.0.ops.last_mut() {
            Some(Op::Lit(l)) => Some(l),
            _ => None,
        }
    }

    /// Drops the block [`ChunkOps::lit`] gave last.
    pub fn unlit(&mut self) {
        if let Some(Op::Lit(_)) = self.0.ops.last() {
            self.0.ops.pop();
        }
    }

    pub fn finish(self) -> Vec<Op> {
        self.0.ops
    }
}

fn set_target(op: Option<&mut Op>, to: usize) {
    if let Some(Op::Test { target, .. } | Op::Jump { target, .. } | Op::Until { target, .. }) = op {
        *target = to;
    }
}

fn search_code(s: Search) -> u8 {
    match s {
        Search::Forward => 0,
        Search::Backward => 1,
        Search::ForwardThenBackward => 2,
        Search::ForwardThenWrap => 3,
    }
}

impl Code {
    /// Flattens one program.
    pub fn flatten(file: FileId, prog: &Program) -> Result<Code, Diagnostic> {
        let mut b = Builder { base: 0, file, ops: Vec::new(), marks: Vec::new(), labels: HashMap::new() };
        b.stmts(&prog.body, 0)?;
        Ok(Code { file, ops: b.ops, marks: b.marks, labels: b.labels, memo: RefCell::new(HashMap::new()), paged: None })
    }

    /// A streamed program: ops are read chunk by chunk through `pager` (see `crate::stream`).
    pub fn paged(file: FileId, pager: Rc<dyn PagedSource>, prog: usize) -> Code {
        let mut labels = HashMap::new();
        let mut marks = Vec::new();
        for (at, name) in pager.labels(prog) {
            let next = labels.len() as u32;
            let id = *labels.entry(name.clone()).or_insert(next);
            marks.push((*at, None, Some(id)));
        }
        Code { file, ops: Vec::new(), marks, labels, memo: RefCell::new(HashMap::new()), paged: Some((pager, prog)) }
    }

    /// The op at `pc` and what keeps it alive (a page of a streamed program).
    pub fn op_at(&self, pc: usize) -> Result<Option<OpRef<'_>>, Diagnostic> {
        match &self.paged {
            None => Ok(self.ops.get(pc).map(OpRef::Mem)),
            Some((pager, prog)) => Ok(pager.page(*prog, pc)?.map(|page| OpRef::Page(page, pc))),
        }
    }

    /// The op at `pc` of a program in memory (`None` for a streamed one, whose ops are
    /// in its pages).
    #[inline]
    pub fn mem_op(&self, pc: usize) -> Option<&Op> {
        match &self.paged {
            None => self.ops.get(pc),
            Some(_) => None,
        }
    }

    /// The span of the last op (where a run falls off the end).
    pub fn last_span(&self) -> Span {
        match &self.paged {
            None => self.ops.last().map_or(Span::default(), Op::span),
            Some((pager, prog)) => pager.last_span(*prog),
        }
    }

    /// The interned id of a label name (upper case), if the program has that label.
    pub fn label_id(&self, name: &str) -> Option<u32> {
        self.labels.get(name).copied()
    }

    fn matches(&self, m: &(usize, Option<u32>, Option<u32>), key: Key) -> bool {
        match key {
            Key::Number(n) => m.1 == Some(n),
            Key::Label(l) => m.2 == Some(l),
        }
    }

    /// Finds the destination of a jump from op `from`.
    /// Forward searches start after the jumping block; backward searches start at it (a
    /// block may jump to its own label); FANUC wraps to the top and searches up to and
    /// including the jumping block; the first match in search order wins, which decides
    /// duplicate numbers and labels.
    pub fn find(&self, from: usize, search: Search, key: Key) -> Option<usize> {
        let mk = (from, search_code(search), key);
        if let Some(hit) = self.memo.borrow().get(&mk) {
            return *hit;
        }
        if let (Some((pager, prog)), Key::Number(n)) = (&self.paged, key) {
            let hit = pager.find_number(*prog, from, search, n);
            self.memo.borrow_mut().insert(mk, hit);
            return hit;
        }
        // Marks are sorted by op index.
        let split = self.marks.partition_point(|m| m.0 <= from);
        let fwd = || self.marks[split..].iter().find(|m| self.matches(m, key));
        let bwd = || self.marks[..split].iter().rev().find(|m| self.matches(m, key));
        let head = || self.marks[..split].iter().find(|m| self.matches(m, key));
        let hit = match search {
            Search::Forward => fwd(),
            Search::Backward => bwd(),
            Search::ForwardThenBackward => fwd().or_else(bwd),
            Search::ForwardThenWrap => fwd().or_else(head),
        }
        .map(|m| m.0);
        self.memo.borrow_mut().insert(mk, hit);
        hit
    }

    /// The first op, in program order, carrying sequence number `n` at or after `from`,
    /// then from the top (FANUC `M99 Pn` into the caller).
    pub fn find_number_from(&self, from: usize, n: u32) -> Option<usize> {
        if let Some((pager, prog)) = &self.paged {
            return pager.find_number_from(*prog, from, n);
        }
        let split = self.marks.partition_point(|m| m.0 < from);
        self.marks[split..].iter().chain(self.marks[..split].iter()).find(|m| m.1 == Some(n)).map(|m| m.0)
    }

    /// The op carrying `label`, searched backward from `from` (section repetition).
    pub fn find_label_back(&self, from: usize, label: &str) -> Option<usize> {
        let id = self.label_id(label)?;
        self.find(from, Search::Backward, Key::Label(id))
    }

    /// The first and last op a section repetition at `pc` runs (Siemens `REPEAT`, see
    /// docs/semantics.md, Section repetition), `None` when it runs nothing; `Err` names a
    /// label that is not found. The labels are searched toward the program start from the
    /// REPEAT block; `REPEATB` then also toward the end. `REPEAT L` alone ends at the first
    /// `ENDLABEL` after L that comes before the REPEAT, else at the block before it.
    pub fn section(&self, pc: usize, rs: &crate::ir::RepeatSection) -> Result<Option<(usize, usize)>, String> {
        let label = |name: &str, from: usize, search: Search| {
            self.label_id(name).and_then(|id| self.find(from, search, Key::Label(id)))
        };
        let start = rs.start.name.as_str();
        let s = match self.find_label_back(pc, start) {
            Some(s) => s,
            None if rs.single => label(start, pc, Search::Forward).ok_or_else(|| start.to_string())?,
            None => return Err(start.to_string()),
        };
        let e = if rs.single {
            s
        } else if let Some(l) = &rs.end {
            self.find_label_back(pc, &l.name).ok_or_else(|| l.name.clone())?
        } else {
            if pc == 0 || s >= pc {
                return Ok(None);
            }
            label(ENDLABEL, s, Search::Forward).filter(|&e| e < pc).unwrap_or(pc - 1)
        };
        Ok((e >= s).then_some((s, e)))
    }
}
