//! The trace position on the 0.001 grid: per axis, the integer the trace writes a
//! coordinate from ([`grid_of`] of its `clean` value), remembered with the bits of the
//! position it belongs to. A literal move sets it from the integer its word rounded to,
//! so that nearly every move of a metric program reaches the writer as integers
//! ([`GridMove`]) without a float being rounded or tested again.

use super::{clean, is_decimal_scale, Machine, Motion};
use crate::eval::numfmt::{grid_of, GRID_LIMIT};
use crate::eval::trace::GridMove;

/// The length `q / 1000` (`round_to_decimal`'s result: `q as f64` is never `-0`), and
/// `q` when it is under [`GRID_LIMIT`].
#[inline(always)]
fn milli_length(q: i64) -> (f64, Option<i64>) {
    (q as f64 / 1000.0, (q.unsigned_abs() < GRID_LIMIT).then_some(q))
}

/// A grid entry for positions off the grid (no `n` with [`grid_of`]).
const OFF_GRID: i64 = i64::MIN;

/// `grid_of` of `x` (`clean`ed with `cleaned`), or [`OFF_GRID`]. Out of line: a literal move set the entries it
/// changed, so [`Machine::grid_move`] rarely works one out (inlined, its constants were
/// loaded for every move).
#[cold]
#[inline(never)]
fn grid_value(x: f64, cleaned: bool) -> i64 {
    grid_of(if cleaned { clean(x) } else { x }).unwrap_or(OFF_GRID)
}

/// The bound under which a position sum is exact enough for [`Machine::set_grid`]:
/// 10⁸ thousandths (100 m).
const SUM_LIMIT: u64 = 100_000_000;

/// The grid state of a [`Machine`]: per axis the bits of the position its grid value
/// belongs to, and the move handed to sinks, kept from move to move and written in place
/// (its `to` holds every axis's grid value or [`OFF_GRID`]: a pure function of the
/// bits, so never stale; 0 for the axes not positioned yet).
#[derive(Clone, Debug)]
pub(super) struct Grid {
    bits: [u64; 9],
    /// The feed's bits and grid value (its own value, not `clean`ed).
    feed: (u64, i64),
    /// `seen` when `gm.mask` was worked out from it.
    seen: [bool; 9],
    gm: GridMove,
    /// The bits of the `inc_mm` for which a length rounds to the 0.001 grid in
    /// millimetres ([`Machine::milli_lengths`]; `None`: for none), worked out once: the
    /// increment slots are set by [`Machine::new`] only.
    milli_inc: Option<u64>,
}

impl Grid {
    /// The grid state of a new machine: every position is `0.0`, whose grid value is 0.
    pub(super) fn new(inc_mm: f64) -> Grid {
        let inc = 1.0 / inc_mm;
        let ok = inc_mm > 0.0 && is_decimal_scale(inc) && inc == 1000.0;
        Grid {
            bits: [0f64.to_bits(); 9],
            feed: (0f64.to_bits(), 0),
            seen: [false; 9],
            gm: GridMove { rapid: true, mask: 0, to: [0; 9], f: None, line: 0 },
            milli_inc: ok.then_some(inc_mm.to_bits()),
        }
    }
}

impl Machine {
    /// Whether [`Machine::length_of`] of a linear (`[0]`) and of a rotary (`[1]`) axis
    /// word rounds to the 0.001 grid in millimetres (its slot holds the increment, a
    /// decimal scale of 1000, no inch conversion): what [`Machine::length_grid`] needs,
    /// worked out once per block (the slot's part once per machine: [`Grid::new`]).
    #[inline(always)]
    pub(super) fn milli_lengths(&self) -> [bool; 2] {
        let ok = self.grid.milli_inc == Some(self.inc_mm.to_bits());
        [ok && !self.modal.inch, ok]
    }
    /// [`Machine::length_of`], and the count `q` of thousandths it rounded to (the
    /// length is `q / 1000`, `|q| <` [`GRID_LIMIT`]) when it rounded to the
    /// 0.001 mm grid in millimetres (`milli`: [`Machine::milli_lengths`] for the axis).
    /// `known`: the word's [`LitWord::milli`], `decimal_count(x, 1000.0)` when its reader
    /// worked it out from the digits, which then is not worked out again.
    ///
    /// [`LitWord::milli`]: crate::dialect::lit::LitWord::milli
    #[inline(always)]
    pub(super) fn length_grid(&self, milli: bool, bare: bool, x: f64, known: i32, rotary: bool) -> (f64, Option<i64>) {
        // The count the reader worked out (nearly every CAM word): `length_of`'s way for
        // the word, `round_to_decimal(x, 1000.0)`, is `known / 1000` then.
        if milli && known != crate::dialect::lit::NO_MILLI && !(bare && self.scaling) {
            return milli_length(i64::from(known));
        }
        self.length_grid_rest(milli, bare, x, rotary)
    }

    /// [`Machine::length_grid`] for a word without a known count, out of line: inlined,
    /// its loop invariants (the scale, `inc_mm / 1000`) were worked out for every block.
    #[inline(never)]
    fn length_grid_rest(&self, milli: bool, bare: bool, x: f64, rotary: bool) -> (f64, Option<i64>) {
        if milli {
            // `length_of`'s way for this word: the increment `inc_mm`, rounded by
            // `round_to_decimal(v, 1000.0)`.
            let v = if bare && self.scaling { x * self.inc_mm } else { x };
            if let Some(q) = crate::eval::value::decimal_count(v, 1000.0) {
                return milli_length(q);
            }
        }
        (self.length_of(bare, x, rotary), None)
    }

    /// Remembers that the feed `f` is written from `n` (`grid_of(f) == Some(n)`).
    #[inline(always)]
    pub(super) fn set_feed_grid(&mut self, f: f64, n: i64) {
        debug_assert_eq!(grid_of(f), Some(n), "f = {f:e}");
        self.grid.feed = (f.to_bits(), n);
    }

    /// Remembers that axis `i`, now at `t` = the word's length `q / 1000` (as
    /// `round_to_decimal` gives it, `|q| <` [`GRID_LIMIT`]) plus the active offset `off`,
    /// is written from `q + o`, where `off` = `o / 1000`.
    ///
    /// Why that is `grid_of(clean(t))`: with `off == 0.0`, `t` is `q / 1000` itself (a
    /// double never `-0` plus a zero) and `clean` keeps it (`t × 10⁹` is within 0.25 of
    /// the integer `q × 10⁶`). Otherwise, with `|q|, |o| < 10⁸`, `t` is within three
    /// roundings of 2⁻⁵³ × 2·10⁵ of `(q + o) / 1000`, so `t × 10⁹` is within 0.1 of the
    /// integer `(q + o) × 10⁶` (exact, under 2⁵³), which `clean` rounds to and divides:
    /// the double nearest to `(q + o) / 1000`. Other sums are not remembered.
    #[inline(always)]
    pub(super) fn set_grid(&mut self, i: usize, t: f64, q: i64, off: f64) {
        let n = if off == 0.0 {
            q
        } else {
            match grid_of(off) {
                Some(o) if q.unsigned_abs() < SUM_LIMIT && o.unsigned_abs() < SUM_LIMIT => q + o,
                _ => return,
            }
        };
        debug_assert!(n.unsigned_abs() < GRID_LIMIT);
        debug_assert_eq!(grid_of(clean(t)), Some(n), "t = {t:e}, q = {q}, off = {off:e}");
        if let (Some(b), Some(to)) = (self.grid.bits.get_mut(i), self.grid.gm.to.get_mut(i)) {
            (*b, *to) = (t.to_bits(), n);
        }
    }

    /// The move just made as a [`GridMove`] (the event [`Machine::move_event`] gives, on
    /// the grid), `None` when a coordinate or the feed is off the grid. The move is the
    /// machine's own, updated in place (building one per move zeroed and copied it).
    #[inline]
    pub fn grid_move(&mut self) -> Option<&mut GridMove> {
        let rapid = self.modal.motion == Motion::Rapid;
        let g = &mut self.grid;
        // The axes positioned so far as a bit set, worked out again only when they change.
        if g.seen != self.seen {
            let mut mask = 0u16;
            for (i, &seen) in self.seen.iter().enumerate() {
                mask |= u16::from(seen) << i;
                if !seen {
                    // Not reached while `seen` only grows; keeps `to`'s zeros if it did not.
                    (g.bits[i], g.gm.to[i]) = (0f64.to_bits(), 0);
                }
            }
            (g.seen, g.gm.mask) = (self.seen, mask);
        }
        let mut left = g.gm.mask;
        while left != 0 {
            let i = left.trailing_zeros() as usize;
            left &= left - 1;
            let (Some(&x), Some(b), Some(n)) = (self.pos.get(i), g.bits.get_mut(i), g.gm.to.get_mut(i)) else {
                return None;
            };
            let bits = x.to_bits();
            if *b != bits {
                (*b, *n) = (bits, grid_value(x, true));
            }
            if *n == OFF_GRID {
                return None;
            }
        }
        g.gm.f = if rapid {
            None
        } else {
            let x = self.feed?;
            let bits = x.to_bits();
            if g.feed.0 != bits {
                g.feed = (bits, grid_value(x, false));
            }
            if g.feed.1 == OFF_GRID {
                return None;
            }
            Some((x, g.feed.1))
        };
        g.gm.rapid = rapid;
        Some(&mut g.gm)
    }
}
