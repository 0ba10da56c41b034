//! The Sinumerik length and feed units the words pass follows, one definition for the
//! whole-file translator and the streamed routes that mirror it.
//!
//! Sinumerik G700/G710 set the unit of lengths AND feeds; G70/G71 set lengths only and read
//! F in the basic system (MD10240, metric here) whatever G700/G710 came before (828D
//! function manual G2, 7.3), as `eval::machine::modal` runs them. So each of the four sets
//! the whole state, and the states are metric (G71, G710), inch (G700) and inch lengths
//! with metric feeds (G70); metric lengths with inch feeds needs an inch basic system,
//! which no profile models. FANUC G20/G21 (what all four become) set both, so the FANUC
//! feed unit is the length unit: an F word is converted where the Sinumerik feed unit
//! differs from it.

/// Length and feed units in textual order (`true`: inch).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Units {
    pub inch: bool,
    pub inch_feed: bool,
}

/// What an F word (a feed, not a dwell) becomes in the FANUC block.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FeedConv {
    /// Units agree: F as written.
    Same,
    /// Lengths inch, feeds metric (G70, after any unit word): `F[v/25.4]`.
    PerInch,
    /// Lengths metric, feeds inch (an inch basic system under G71; not reached on the
    /// metric one): `F[v*25.4]`.
    PerMm,
}

impl Units {
    /// Applies a constant G code; `true` when it is one of G70, G71, G700, G710.
    #[inline(always)]
    pub fn g(&mut self, v: f64) -> bool {
        if v == 70.0 {
            *self = Units { inch: true, inch_feed: false };
        } else if v == 71.0 {
            *self = Units::default();
        } else if v == 700.0 {
            *self = Units { inch: true, inch_feed: true };
        } else if v == 710.0 {
            *self = Units::default();
        } else {
            return false;
        }
        true
    }

    #[inline(always)]
    pub fn feed(self) -> FeedConv {
        match (self.inch, self.inch_feed) {
            (true, false) => FeedConv::PerInch,
            (false, true) => FeedConv::PerMm,
            _ => FeedConv::Same,
        }
    }

    /// The G code that sets this state from any other (for a block that carries the state
    /// into a translation of its own: a placeholder, a block translated alone).
    pub fn words(self) -> &'static [f64] {
        debug_assert!(self.inch || !self.inch_feed, "metric lengths with inch feeds: no unit word sets it");
        match (self.inch, self.inch_feed) {
            (true, true) => &[700.0],
            (true, false) => &[70.0],
            (false, _) => &[710.0],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every sequence of up to three unit codes from every start state: the state after
    /// `words()` of the start and the sequence equals the state after the sequence, and the
    /// rules are the evaluator's (`eval::machine::modal::Modal::g` on the Sinumerik side).
    #[test]
    fn units_follow_the_evaluator_and_words_set_any_state() {
        use crate::eval::machine::Modal as EvalModal;
        let codes = [70.0, 71.0, 700.0, 710.0];
        let starts = [(false, false), (true, false), (true, true)];
        for (inch, inch_feed) in starts {
            let start = Units { inch, inch_feed };
            for a in codes {
                for b in codes {
                    let mut u = start;
                    for from in starts {
                        let mut from_any = Units { inch: from.0, inch_feed: from.1 };
                        for &w in start.words() {
                            assert!(from_any.g(w));
                        }
                        assert_eq!(from_any, start);
                    }
                    let mut e = EvalModal {
                        motion: crate::eval::machine::Motion::Rapid,
                        plane: crate::eval::trace::Plane::XY,
                        absolute: true,
                        inch,
                        inch_feed,
                        per_rev: false,
                    };
                    for v in [a, b] {
                        assert!(u.g(v));
                        assert!(e.g(false, crate::eval::machine::g_index(v)));
                    }
                    assert_eq!((u.inch, u.inch_feed), (e.inch, e.inch_feed), "{start:?} {a} {b}");
                }
            }
        }
        assert!(!Units::default().g(90.0));
        assert_eq!(Units { inch: true, inch_feed: false }.feed(), FeedConv::PerInch);
        assert_eq!(Units { inch: false, inch_feed: true }.feed(), FeedConv::PerMm);
        // G70 after G700: feeds metric again (the state G70 gives from anywhere).
        let mut u = Units::default();
        assert!(u.g(700.0) && u.g(70.0));
        assert_eq!(u, Units { inch: true, inch_feed: false });
        assert!(u.g(700.0) && u.g(71.0));
        assert_eq!(u.feed(), FeedConv::Same);
    }
}
