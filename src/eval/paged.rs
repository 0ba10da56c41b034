//! What the evaluator reads a streamed program through: pages of flattened ops (one index
//! chunk each) from a [`PagedSource`]. The source that re-reads the file is
//! `stream::paged::Pager`; the evaluator sees only this interface, so `eval` does not depend
//! on `stream` (the rule in `eval/mod.rs`).

use super::flow::Op;
use crate::diag::Diagnostic;
use crate::dialect::Dialect;
use crate::ir::{Program, Search};
use crate::span::{FileId, Span};
use std::rc::Rc;

/// One chunk's ops, and its lines for line numbers.
pub struct Page {
    pub(crate) prog: usize,
    pub(crate) base: usize,
    pub(crate) ops: Vec<Op>,
    pub(crate) lo: u64,
    pub(crate) hi: u64,
    /// (text offset, line number) of every line of the chunk.
    pub(crate) lines: Vec<(u32, u32)>,
}

impl Page {
    /// The page's ops (from op index `base`).
    pub fn ops(&self) -> &[Op] {
        &self.ops
    }

    pub fn get(&self, pc: usize) -> Option<&Op> {
        self.ops.get(pc.wrapping_sub(self.base))
    }
}

/// The programs of a file read page by page.
pub trait PagedSource: std::fmt::Debug {
    fn dialect(&self) -> Dialect;
    fn file(&self) -> FileId;
    /// How many programs the file holds.
    fn programs(&self) -> usize;
    /// Program `prog`'s header (name, parameters, SAVE; its body is not kept).
    fn program(&self, prog: usize) -> &Program;
    /// (op index, upper-case name) of every label of program `prog`.
    fn labels(&self, prog: usize) -> &[(usize, String)];
    /// The span of program `prog`'s last op (where a run falls off the end).
    fn last_span(&self, prog: usize) -> Span;
    /// The page holding op `pc` of program `prog`, or `None` past its end.
    fn page(&self, prog: usize, pc: usize) -> Result<Option<Rc<Page>>, Diagnostic>;
    /// Jump search for block number `n` from op `from` (see `Code::find`).
    fn find_number(&self, prog: usize, from: usize, search: Search, n: u32) -> Option<usize>;
    /// The first op with number `n` at or after `from`, then from the top.
    fn find_number_from(&self, prog: usize, from: usize, n: u32) -> Option<usize>;
}
