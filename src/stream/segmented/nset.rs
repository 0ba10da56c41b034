//! The set of N values both segmented translators keep (the numbers jumps name, the numbers
//! of run blocks), a bit per value: one type for both directions.

use crate::ir::BlockMeta;

/// N values above this are not tracked (a block holding one declines).
pub(crate) const MAX_TRACKED_N: u32 = 1 << 24;

/// A set of N values (a bit per value up to [`MAX_TRACKED_N`]).
#[derive(Default, Clone)]
pub(crate) struct NSet(Vec<u64>);

impl NSet {
    pub(crate) fn insert(&mut self, n: u32) {
        let w = (n / 64) as usize;
        if self.0.len() <= w {
            self.0.resize(w + 1, 0);
        }
        self.0[w] |= 1 << (n % 64);
    }

    pub(crate) fn has(&self, n: u32) -> bool {
        self.0.get((n / 64) as usize).is_some_and(|w| w & (1 << (n % 64)) != 0)
    }

    pub(crate) fn meets(&self, o: &NSet) -> bool {
        self.0.iter().zip(&o.0).any(|(a, b)| a & b != 0)
    }
}

/// The blocks a skeleton scan keeps out of runs: those whose N value a jump names, and those
/// in a stretch of the source that a section repetition may copy.
#[derive(Default, Clone)]
pub(crate) struct Keep {
    pub(crate) ns: NSet,
    /// Blocks starting in `lo..hi` (source offsets).
    pub(crate) spans: Option<(u32, u32)>,
}

/// Whether the block of `meta` stays in the skeleton (`keep`).
pub(crate) fn kept(keep: &Keep, meta: &BlockMeta) -> bool {
    meta.number.as_ref().is_some_and(|n| keep.ns.has(n.value))
        || keep.spans.is_some_and(|(lo, hi)| (lo..hi).contains(&meta.span.lo))
}
