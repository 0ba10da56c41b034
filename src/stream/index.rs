//! The first-scan index of a streamed file: per program its head (name, PROC parameters),
//! its chunks (byte ranges of whole top-level statements, with the reader state to resume
//! there and the op index they start at), its labels and its block numbers as runs. Its size
//! follows the macro part of a program: a straight-line CAM program of ten million blocks
//! has one chunk per [`CHUNK_OPS`] ops and one run of N numbers.

use crate::dialect::runs::Runs;
use crate::dialect::{fanuc, sinumerik};
use crate::ir::{BlockMeta, Program, Stmt, StmtKind};
use crate::span::Span;

/// Ops per chunk (a chunk may be longer: it always ends with a whole top-level statement).
pub const CHUNK_OPS: usize = 2048;

/// Reader state at a chunk start.
#[derive(Clone, Debug)]
pub enum Resume {
    Sinumerik(sinumerik::Resume),
    Fanuc(fanuc::Resume),
}

/// Byte range `lo..hi` of the text holding ops `op_base..op_base + ops` of one program.
#[derive(Clone, Debug)]
pub struct Chunk {
    pub lo: u64,
    pub hi: u64,
    /// Line number of the line starting at `lo`.
    pub line: u32,
    pub op_base: usize,
    pub ops: usize,
    pub resume: Resume,
}

/// One program of the file.
#[derive(Clone, Debug)]
pub struct ProgIndex {
    /// Name, head, parameters and span; `body` stays empty.
    pub program: Program,
    pub chunks: Vec<Chunk>,
    pub ops: usize,
    /// Op index → label name (upper case as written), in op order.
    pub labels: Vec<(usize, String)>,
    /// Block numbers by op index.
    pub numbers: Runs,
    /// Span of the last op (where a run falls off the end).
    pub last_span: Span,
    /// The program's index among all programs started while reading (the `prog` that
    /// `stream::scan` hands out with each statement).
    pub raw: usize,
}

impl ProgIndex {
    pub fn new() -> ProgIndex {
        ProgIndex {
            program: Program {
                name: None,
                head: None,
                params: vec![],
                save: false,
                body: vec![],
                span: Span::default(),
            },
            chunks: Vec::new(),
            ops: 0,
            labels: Vec::new(),
            numbers: Runs::default(),
            last_span: Span::default(),
            raw: 0,
        }
    }

    /// Records the ops of one top-level statement, in the order `eval::flow` flattens them.
    pub fn add(&mut self, s: &Stmt) {
        walk_ops(s, &mut |meta| {
            let at = self.ops;
            if let Some(n) = &meta.number {
                self.numbers.push(n.value, at as u64, n.span);
            }
            if let Some(l) = &meta.label {
                self.labels.push((at, l.name.clone()));
            }
            self.last_span = meta.span;
            self.ops += 1;
        });
    }

    /// [`ProgIndex::add`] of a plain block statement (span `span`, number `number`, no label).
    #[inline]
    pub fn add_plain(&mut self, span: Span, number: Option<&crate::ir::SeqNo>) {
        if let Some(n) = number {
            self.numbers.push(n.value, self.ops as u64, n.span);
        }
        self.last_span = span;
        self.ops += 1;
    }

    /// The chunk holding op `pc`.
    pub fn chunk_of(&self, pc: usize) -> Option<usize> {
        let i = self.chunks.partition_point(|c| c.op_base <= pc);
        let i = i.checked_sub(1)?;
        (pc < self.chunks[i].op_base + self.chunks[i].ops).then_some(i)
    }
}

impl Default for ProgIndex {
    fn default() -> Self {
        ProgIndex::new()
    }
}

/// Calls `f` with the block of every op of `s`, in flattening order (one op per block:
/// structure heads, ELSE and ends included).
pub fn walk_ops(s: &Stmt, f: &mut dyn FnMut(&BlockMeta)) {
    match &s.kind {
        StmtKind::Block(b) => f(&b.meta),
        StmtKind::If(st) => {
            f(&st.head);
            st.then_body.iter().for_each(|s| walk_ops(s, f));
            if let Some(e) = &st.else_part {
                f(&e.head);
                e.body.iter().for_each(|s| walk_ops(s, f));
            }
            f(&st.end);
        }
        StmtKind::While(w) => loop_ops(&w.head, &w.body, &w.end, f),
        StmtKind::Do(w) => loop_ops(&w.head, &w.body, &w.end, f),
        StmtKind::Loop(w) => loop_ops(&w.head, &w.body, &w.end, f),
        StmtKind::Repeat(w) => loop_ops(&w.head, &w.body, &w.end, f),
        StmtKind::For(w) => loop_ops(&w.head, &w.body, &w.end, f),
    }
}

fn loop_ops(head: &BlockMeta, body: &[Stmt], end: &BlockMeta, f: &mut dyn FnMut(&BlockMeta)) {
    f(head);
    body.iter().for_each(|s| walk_ops(s, f));
    f(end);
}
