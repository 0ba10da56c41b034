//! The one streamed straight-line translation driver, for every target: the source is read
//! once (`stream::scan_words`), each finished statement and each plain line's words are
//! handed to the target as they come, and the target writes its text into a `stream::Out`.
//! What is the same for every target is here: which blocks send the file to the whole path
//! (a statement that is not straight, a tool change or compensation word, a second
//! program), the block count and the end of the scan. What differs is the [`Target`]: its
//! straight-block test, its fast writer (`lower::to_<name>::fast_write`), what it writes
//! before the first block (its header handling) and after the last
//! (`stream::target::<name>`). Verification is `stream::verify` for every target.

use super::lines::NotStreamable;
use super::{Index, PlainWord, ProgressFn, WordsSink};
use crate::dialect::{Dialect, ParseOptions};
use crate::ir::{BlockMeta, Stmt};
use crate::read::RawBlock;
use std::path::Path;

/// Why a file is not translated as a stream (the caller translates it whole).
#[derive(Debug)]
pub enum Fallback {
    NotStreamable(NotStreamable),
    /// Not a straight-line program (the first block that is not, as a reason).
    NotStraight(String),
    /// The source has diagnostics (rendered by the whole-file path).
    Diagnostics,
}

/// What a target supplies to the straight-line stream (see the module comment). Generic,
/// so each target's calls are its own code (no dynamic dispatch per block).
pub(crate) trait Target {
    /// The dialect of the source read.
    const SOURCE: Dialect;
    /// Why a program with a tool change or compensation word is read whole.
    const COMP: &'static str;
    /// Whether a statement's translation depends on no other block; `Err` names what it has
    /// instead, for the "read whole" note.
    const STRAIGHT: fn(&Stmt) -> Result<(), String>;
    /// Whether the translation has stopped (it is then discarded), and why.
    fn stopped(&self) -> bool;
    fn stop(&mut self) -> &mut Option<Fallback>;
    /// A straight statement of the program.
    fn stmt(&mut self, s: &Stmt);
    /// The words of a plain line of the program (constant letter words, no label, no tool
    /// compensation word), written when the fast writer takes them; `false` (nothing
    /// changed) asks for the line as a statement ([`Target::stmt`]).
    fn plain(&mut self, meta: &BlockMeta, words: &[PlainWord], line: &RawBlock<'_>) -> bool;
}

/// Whether a word of a `T::SOURCE` program sends a straight stream to the whole path.
#[inline]
fn comp_word<T: Target>(w: &PlainWord) -> bool {
    let fanuc = T::SOURCE == Dialect::Fanuc;
    crate::lower::comp_flow::stream_relevant_word(w.letter, Some(w.value), fanuc, !fanuc)
}

/// The target as the first scan's sink: plain lines through its fast writer straight from
/// their words, the rest (and what it declines) as statements.
struct Sink<'t, T> {
    t: &'t mut T,
    blocks: u64,
}

impl<T: Target> WordsSink for Sink<'_, T> {
    fn active(&self) -> bool {
        !self.t.stopped()
    }

    /// A stopped translation is discarded: the rest of the file need not be read.
    fn abandon(&self) -> bool {
        true
    }

    fn stmt(&mut self, prog: usize, s: &Stmt) {
        if self.t.stopped() {
            return;
        }
        if prog != 0 {
            *self.t.stop() = Some(Fallback::NotStraight("more than one program".into()));
            return;
        }
        if let Err(why) = (T::STRAIGHT)(s) {
            *self.t.stop() = Some(Fallback::NotStraight(why));
            return;
        }
        self.blocks += 1;
        self.t.stmt(s);
    }

    fn plain(&mut self, prog: usize, meta: &BlockMeta, words: &[PlainWord], line: &RawBlock<'_>) -> bool {
        if self.t.stopped() {
            return true;
        }
        if words.iter().any(comp_word::<T>) {
            *self.t.stop() = Some(Fallback::NotStraight(T::COMP.into()));
            return true;
        }
        // A second program's line comes again as a statement, which stops.
        if prog != 0 || !self.t.plain(meta, words, line) {
            return false;
        }
        self.blocks += 1;
        true
    }
}

/// Reads `path` once, handing its blocks to `t`: the source's index and the number of
/// blocks translated. `Err` when `t` stopped or the source has diagnostics; what the
/// target writes after the last block is its caller's.
pub(crate) fn run<T: Target>(
    path: &Path,
    popts: &ParseOptions,
    t: &mut T,
    progress: Option<ProgressFn<'_>>,
) -> Result<(Index, u64), Fallback> {
    let mut sink = Sink { t, blocks: 0 };
    let r = super::scan_words_path(path, 0, T::SOURCE, popts, &mut sink, progress);
    let blocks = sink.blocks;
    let index = r.map_err(Fallback::NotStreamable)?;
    if let Some(f) = t.stop().take() {
        return Err(f);
    }
    if !index.diags.is_empty() {
        return Err(Fallback::Diagnostics);
    }
    Ok((index, blocks))
}
