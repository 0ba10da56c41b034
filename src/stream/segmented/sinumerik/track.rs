//! The Sinumerik target's part of a segmented skeleton scan (FANUC source): which blocks
//! are run blocks, the arc mode followed in textual order through the runs and through the
//! skeleton alone, what declines a statement of the macro part, and the fast writer of run
//! blocks (see `segmented::sinumerik`).

use crate::dialect::digits::Src;
use crate::ir::{Addr, Block, BlockMeta, Item, ItemKind, Stmt, StmtKind, VarKind, Word, WordValue};
use crate::lower::to_sinumerik::fast_write as fast;
use crate::lower::to_sinumerik::{self as passes, Options};
use crate::read::RawBlock;
use crate::span::Span;
use crate::stream::segmented::driver::{jump_or_call, RunTests, SkelPart, Why};
use crate::stream::segmented::nset::{kept, Keep, MAX_TRACKED_N};
use crate::stream::target::sinumerik::{plain_g, straight};
use crate::stream::target::RunWriter;
use crate::stream::PlainWord;

/// The arc mode after G code `g10` (×10) as `words::lower` follows it.
fn arc_after(arc: bool, g10: u32) -> bool {
    match g10 {
        20 | 30 => true,
        0 | 10 => false,
        _ => arc,
    }
}

/// The arc mode after a block's own G codes.
fn follow_items(arc: bool, items: &[Item]) -> bool {
    passes::g_codes(items).into_iter().fold(arc, arc_after)
}

/// The arc mode after a plain line's G words.
fn follow_words(arc: bool, words: &[PlainWord]) -> bool {
    words.iter().filter(|w| w.letter == b'G').fold(arc, |a, w| arc_after(a, fast::round(w.value * 10.0) as u32))
}

/// Whether an M value is a program end, call or return (never a plain word of a run).
fn special_m(v: f64) -> bool {
    v == 2.0 || v == 30.0 || v == 97.0 || v == 98.0 || v == 99.0
}

/// A block the translation surely keeps as a line with an item, a number or a label (so
/// `take_inputs` stops there): a number, a program end, a constant motion word or a G code
/// the words pass keeps. Anything else counts as not (runs start later).
fn solid(s: &Stmt) -> bool {
    let StmtKind::Block(b) = &s.kind else { return true };
    b.meta.number.is_some()
        || b.items.iter().any(|it| match &it.kind {
            ItemKind::End { .. } => true,
            ItemKind::Word(Word { addr: Addr::Letter(l), value: WordValue::Expr(e), .. }) => {
                let v = crate::lower::literal(e);
                match l {
                    b'G' => v.is_some_and(|v| {
                        matches!((v * 10.0).round() as u32, 0 | 10 | 20 | 30 | 170 | 180 | 190 | 900 | 910 | 940 | 950)
                    }),
                    b'X' | b'Y' | b'Z' | b'A' | b'B' | b'C' | b'F' | b'S' | b'T' | b'D' => v.is_some(),
                    _ => false,
                }
            }
            _ => false,
        })
}

/// What declines an item of the skeleton (see the module comment); its jump target.
fn check_item(it: &Item, calls: bool, targets: &mut Vec<u32>) -> Option<&'static str> {
    if let Some(why) = jump_or_call(it, calls, super::subs::plain_call, targets) {
        return why;
    }
    match &it.kind {
        ItemKind::ModalCallOff if !calls => Some("a call of another program"),
        ItemKind::Return { .. } => Some("M99"),
        ItemKind::ParamWrite(_) => Some("G10"),
        ItemKind::Assign { target, .. } => match target.kind {
            VarKind::Hash(5221..=5340) | VarKind::HashIndirect(_) => Some("a work offset or indirect write"),
            _ => None,
        },
        ItemKind::Word(Word { addr, value: WordValue::Expr(e), .. }) if addr.is(b'G') => {
            // A drilling cycle makes the blocks after it holes: read whole.
            crate::lower::literal(e).and_then(|v| match (v * 10.0).round() as u32 {
                100 | 110 => Some("G10"),
                730 | 740 | 760 | 810..=890 => Some("a drilling cycle"),
                _ => None,
            })
        }
        _ => None,
    }
}

/// Whether a plain line is a run block (else it is to come as a statement), after a
/// `solid` statement or not, with the N values `keep` kept out of runs; the same in every
/// scan (it changes only on statements that are not run blocks).
#[inline]
fn plain_run(solid: bool, keep: &Keep, meta: &BlockMeta, words: &[PlainWord]) -> bool {
    solid
        && meta.label.is_none()
        && !kept(keep, meta)
        && words.iter().all(|w| match w.letter {
            // G0..G3 (plain) without `plain_g`'s rounding: CAM lines are made of them.
            // Not G20: the runs are written metric, and a G20 in the skeleton reads the
            // program whole.
            b'G' => {
                let g = w.value as u32;
                (g <= 3 && f64::from(g) == w.value) || (plain_g(w.value) && w.value != 20.0)
            }
            b'M' => !special_m(w.value),
            _ => true,
        })
}

/// [`plain_run`] of a statement.
fn stmt_run(solid: bool, keep: &Keep, s: &Stmt) -> bool {
    let StmtKind::Block(b) = &s.kind else { return false };
    solid
        && straight(s).is_ok()
        && !crate::lower::to_sinumerik::modal::has_g(std::slice::from_ref(s), &[200])
        && !kept(keep, &b.meta)
        && !b.items.iter().any(|it| matches!(it.kind, ItemKind::End { .. }))
}

/// The writing scan's tests: [`plain_run`] and [`stmt_run`], following `solid` again.
pub(super) struct Class {
    pub(super) solid: bool,
}

impl RunTests for Class {
    #[inline]
    fn plain_run(&self, keep: &Keep, meta: &BlockMeta, words: &[PlainWord]) -> bool {
        plain_run(self.solid, keep, meta, words)
    }

    /// Whether a statement is a run block (else `solid` follows it).
    fn stmt_run(&mut self, keep: &Keep, s: &Stmt) -> bool {
        if stmt_run(self.solid, keep, s) {
            return true;
        }
        self.solid |= solid(s);
        false
    }
}

/// The Sinumerik target's part of the skeleton scan: the arc mode after everything so far
/// (what the words pass has on the whole file) and after the skeleton's statements alone
/// (what it has on the skeleton), and whether a `solid` statement has been seen.
#[derive(Default)]
pub(crate) struct Track {
    solid: bool,
    pub(super) arc: bool,
    own_arc: bool,
}

impl SkelPart for Track {
    type Mode = bool;

    #[inline]
    fn plain_run(&self, keep: &Keep, meta: &BlockMeta, words: &[PlainWord]) -> bool {
        plain_run(self.solid, keep, meta, words)
    }

    fn stmt_run(&mut self, keep: &Keep, s: &Stmt) -> bool {
        stmt_run(self.solid, keep, s)
    }

    #[inline]
    fn mode(&self) -> bool {
        self.arc
    }

    fn follow_plain(&mut self, words: &[PlainWord]) {
        self.arc = follow_words(self.arc, words);
    }

    fn follow_stmt(&mut self, items: &[Item]) {
        self.arc = follow_items(self.arc, items);
    }

    fn placeholder(&mut self, mark: String, span: Span) -> Stmt {
        passes::comment_stmt(mark, span)
    }

    /// The arc mode with the runs and without.
    type Walk = (bool, bool);

    fn walk(&self) -> (bool, bool) {
        (self.arc, self.own_arc)
    }

    fn macro_block((arc, own): &mut (bool, bool), b: &Block, calls: bool, targets: &mut Vec<u32>) -> Why {
        let big = b.meta.number.as_ref().is_some_and(|n| n.value > MAX_TRACKED_N);
        let mut why = big.then_some("an N number above 16777216");
        (*arc, *own) = (follow_items(*arc, &b.items), follow_items(*own, &b.items));
        if arc != own && b.items.iter().any(|it| matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'R'))) {
            why = why.or(Some("an R word in the macro part after an arc mode set in a run"));
        }
        for it in &b.items {
            why = why.or(check_item(it, calls, targets));
            if let ItemKind::IfThen { then, .. } = &it.kind {
                if matches!(then.kind, ItemKind::Word(_)) {
                    why = why.or(Some("IF..THEN with an address word"));
                }
                why = why.or(check_item(then, calls, targets));
            }
        }
        why
    }

    fn walked(&mut self, (arc, own): (bool, bool), s: &Stmt) {
        (self.arc, self.own_arc) = (arc, own);
        self.solid |= solid(s);
    }
}

/// The fast path of run blocks, which carries the arc mode from block to block.
pub(crate) struct Fast<'a> {
    pub(super) opts: &'a Options,
    pub(super) eol: &'static [u8],
    pub(super) arc: bool,
}

impl RunWriter for Fast<'_> {
    type Mode = bool;

    #[inline]
    fn start(&mut self, arc: bool) {
        self.arc = arc;
    }

    #[inline]
    fn plain(&mut self, meta: &BlockMeta, words: &[PlainWord], line: &RawBlock<'_>, out: &mut Vec<u8>) -> bool {
        if fast::plain_words(meta, words, &mut self.arc, self.eol, out) {
            return true;
        }
        let after = follow_words(self.arc, words);
        let mark = out.len();
        let lit = |w: &PlainWord| Some(Src { line, span: w.span, canon: w.canon });
        if fast::block(meta, words, lit, after, Some(false), self.opts, self.eol, out).is_err() {
            // Nothing is kept; the block comes again as a statement.
            out.truncate(mark);
            return false;
        }
        self.arc = after;
        true
    }

    fn block(&mut self, s: &Stmt, out: &mut Vec<u8>) -> Result<(), bool> {
        let before = self.arc;
        let StmtKind::Block(b) = &s.kind else { return Err(before) };
        let after = follow_items(before, &b.items);
        self.arc = after;
        let mark = out.len();
        if fast::block(&b.meta, &b.items, |_| None, after, Some(false), self.opts, self.eol, out).is_err() {
            out.truncate(mark);
            return Err(before);
        }
        Ok(())
    }
}
