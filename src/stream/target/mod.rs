//! The targets of the straight-line stream (`stream::straight`): what each target supplies to
//! the one driver (its straight-block test, its fast writer from `lower::to_<name>::fast_write`,
//! its header and the end of its file) and its entry. A new target adds a module here that
//! implements `straight::Target`.
//!
//! Owns: [`fanuc`] (Sinumerik source → FANUC) and [`sinumerik`] (FANUC source → Sinumerik,
//! with the program plan its chunks are lowered with, which the segmented stream shares),
//! and [`RunWriter`], a target's fast writer of blocks with the mode it carries, which the
//! segmented stream drives. May use what `stream` may use, and `stream::straight`.

pub mod fanuc;
pub mod sinumerik;

use crate::ir::{BlockMeta, Stmt};
use crate::read::RawBlock;
use crate::stream::PlainWord;

/// A target's fast writer of run blocks, with the one mode it carries from block to block
/// (FANUC: the length and feed units; Sinumerik: the arc mode).
pub(crate) trait RunWriter {
    type Mode: Copy;
    /// A run starts in `m`.
    fn start(&mut self, m: Self::Mode);
    /// Appends a plain line's translation; `false`: nothing appended, the mode unchanged
    /// (the line comes again as a statement).
    fn plain(&mut self, meta: &BlockMeta, words: &[PlainWord], line: &RawBlock<'_>, out: &mut Vec<u8>) -> bool;
    /// Appends a run block's translation; `Err` (the mode running into it): nothing
    /// appended, the mode is the one after the block (it is translated alone).
    fn block(&mut self, s: &Stmt, out: &mut Vec<u8>) -> Result<(), Self::Mode>;
}
