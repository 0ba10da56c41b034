//! Block numbers as arithmetic runs: CAM output numbers its blocks `N10 N20 N30 …`, so a
//! million numbered blocks are one run, and an index of numbers follows the irregular
//! (macro) part of a program rather than its length.

use crate::span::Span;

/// One run: numbers `n0 + dn·k` at positions `at0 + dat·k`, for `k < count`.
#[derive(Clone, Copy, Debug)]
struct Run {
    n0: u32,
    dn: i64,
    at0: u64,
    dat: u64,
    count: u64,
    /// Span of the first number of the run (later ones are not kept).
    span0: Span,
}

impl Run {
    fn n(&self, k: u64) -> i64 {
        i64::from(self.n0) + self.dn * k as i64
    }

    fn at(&self, k: u64) -> u64 {
        self.at0 + self.dat * k
    }

    /// The `k`s where this run holds `n`: all of them (`dn == 0`), one, or none.
    fn ks(&self, n: u32) -> Option<(u64, u64)> {
        let d = i64::from(n) - i64::from(self.n0);
        if self.dn == 0 {
            return (d == 0).then_some((0, self.count - 1));
        }
        if d % self.dn != 0 {
            return None;
        }
        let k = d / self.dn;
        (k >= 0 && (k as u64) < self.count).then_some((k as u64, k as u64))
    }
}

/// Numbers and their positions (block ordinals or op indices), pushed in increasing
/// position order.
#[derive(Clone, Debug, Default)]
pub struct Runs {
    runs: Vec<Run>,
}

impl Runs {
    pub fn push(&mut self, n: u32, at: u64, span: Span) {
        if let Some(r) = self.runs.last_mut() {
            if r.count == 1 && at > r.at0 {
                r.dn = i64::from(n) - i64::from(r.n0);
                r.dat = at - r.at0;
                r.count = 2;
                return;
            }
            if r.n(r.count) == i64::from(n) && r.at(r.count) == at {
                r.count += 1;
                return;
            }
        }
        self.runs.push(Run { n0: n, dn: 0, at0: at, dat: 0, count: 1, span0: span });
    }

    /// How many runs are kept (the index's size).
    pub fn len(&self) -> usize {
        self.runs.len()
    }

    pub fn is_empty(&self) -> bool {
        self.runs.is_empty()
    }

    fn place(r: &Run, k: u64) -> (u64, Span) {
        (r.at(k), if k == 0 { r.span0 } else { Span::default() })
    }

    /// The first position holding `n` at or after `from`.
    pub fn first_from(&self, n: u32, from: u64) -> Option<(u64, Span)> {
        let mut best: Option<(u64, Span)> = None;
        for r in &self.runs {
            let Some((lo, hi)) = r.ks(n) else { continue };
            // Smallest k in lo..=hi with at(k) >= from.
            let k = if r.at(lo) >= from {
                lo
            } else if r.dat == 0 {
                continue;
            } else {
                let need = (from - r.at0).div_ceil(r.dat);
                if need > hi {
                    continue;
                }
                need.max(lo)
            };
            let p = Runs::place(r, k);
            if best.is_none_or(|b| p.0 < b.0) {
                best = Some(p);
            }
        }
        best
    }

    /// The last position holding `n` at or before `to`.
    pub fn last_to(&self, n: u32, to: u64) -> Option<(u64, Span)> {
        let mut best: Option<(u64, Span)> = None;
        for r in &self.runs {
            let Some((lo, hi)) = r.ks(n) else { continue };
            if r.at(lo) > to {
                continue;
            }
            let k = if r.at(hi) <= to || r.dat == 0 { hi } else { ((to - r.at0) / r.dat).min(hi) };
            let p = Runs::place(r, k);
            if best.is_none_or(|b| p.0 > b.0) {
                best = Some(p);
            }
        }
        best
    }

    /// A few places of `n` that decide a jump check: the first, the last one at or before
    /// `at` and the first one at or after it (without duplicates, in position order).
    pub fn places(&self, n: u32, at: u64) -> Vec<(u64, Span)> {
        let mut v: Vec<(u64, Span)> =
            [self.first_from(n, 0), self.last_to(n, at), self.first_from(n, at)].into_iter().flatten().collect();
        v.sort_by_key(|p| p.0);
        v.dedup_by_key(|p| p.0);
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cam_numbering_is_one_run() {
        let mut r = Runs::default();
        for k in 0..100_000u64 {
            r.push(10 + 10 * k as u32, 3 + k, Span::default());
        }
        assert_eq!(r.len(), 1);
        assert_eq!(r.first_from(500, 0).map(|p| p.0), Some(3 + 49));
        assert_eq!(r.first_from(500, 60), None);
        assert_eq!(r.last_to(500, 60).map(|p| p.0), Some(52));
        assert_eq!(r.last_to(505, 60), None);
    }

    #[test]
    fn repeated_and_irregular_numbers() {
        let mut r = Runs::default();
        for (n, at) in [(1, 0), (1, 2), (1, 4), (7, 5), (3, 9), (1, 11)] {
            r.push(n, at, Span::new(at as u32, at as u32 + 1));
        }
        assert_eq!(r.first_from(1, 3).map(|p| p.0), Some(4));
        assert_eq!(r.first_from(1, 5).map(|p| p.0), Some(11));
        assert_eq!(r.last_to(1, 10).map(|p| p.0), Some(4));
        assert_eq!(r.last_to(3, 10).map(|p| p.0), Some(9));
        assert_eq!(r.places(1, 5).iter().map(|p| p.0).collect::<Vec<_>>(), vec![0, 4, 11]);
        assert_eq!(r.first_from(2, 0), None);
    }
}
