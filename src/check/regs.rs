//! Compensation registers compared by their order of first appearance (trace format v2):
//! a translation may rename them (FANUC `H6` ↔ Siemens `"6.1"`) but must keep which
//! moves use the same one. Length and radius registers pair separately: one Siemens edge
//! carries both, while FANUC takes them from two registers (`H6`, `D16`).

use crate::eval::trace::{CompEv, CompReg, Event};
use std::collections::BTreeMap;

/// The pairing of the two runs' registers so far, per kind, both ways.
#[derive(Clone, Debug, Default)]
pub struct Registers {
    length: Pairs,
    radius: Pairs,
}

#[derive(Clone, Debug, Default)]
struct Pairs {
    a_to_b: BTreeMap<CompReg, CompReg>,
    b_to_a: BTreeMap<CompReg, CompReg>,
}

impl Pairs {
    /// Pairs `a` with `b`; `false` when either is paired with another already.
    fn pair(&mut self, a: &CompReg, b: &CompReg) -> bool {
        match (self.a_to_b.get(a), self.b_to_a.get(b)) {
            (Some(x), Some(y)) => x == b && y == a,
            (None, None) => {
                self.a_to_b.insert(a.clone(), b.clone());
                self.b_to_a.insert(b.clone(), a.clone());
                true
            }
            _ => false,
        }
    }
}

/// Two `comp` events alike but for the register names (what `same_event` compares).
pub fn same_shape(a: &CompEv, b: &CompEv) -> bool {
    a.length.is_some() == b.length.is_some()
        && match (&a.radius, &b.radius) {
            (Some((s1, _)), Some((s2, _))) => s1 == s2,
            (None, None) => true,
            _ => false,
        }
}

impl Registers {
    /// For two events that agree otherwise: whether their registers pair consistently
    /// with every earlier pair (recording new ones). Other events always do.
    pub fn agree(&mut self, a: &Event, b: &Event) -> bool {
        // A tool data write names its register as `comp` does: one pairing for both, so a
        // write to another register than the one a move uses is caught.
        if let (Event::ToolData(a), Event::ToolData(b)) = (a, b) {
            let pairs = if a.field.is_length() { &mut self.length } else { &mut self.radius };
            return pairs.pair(&a.register, &b.register);
        }
        let (Event::Comp(a), Event::Comp(b)) = (a, b) else { return true };
        // Checked before recording: a failed radius pair must not leave a length pair.
        let mut next = self.clone();
        let length = match (&a.length, &b.length) {
            (Some(x), Some(y)) => next.length.pair(x, y),
            _ => true,
        };
        let radius = match (&a.radius, &b.radius) {
            (Some((_, x)), Some((_, y))) => next.radius.pair(x, y),
            _ => true,
        };
        if length && radius {
            *self = next;
        }
        length && radius
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::eval::trace::Side;

    fn ev(l: Option<CompReg>, r: Option<(Side, CompReg)>) -> Event {
        Event::Comp(Box::new(CompEv { length: l, radius: r }))
    }

    #[test]
    fn registers_pair_by_first_appearance_and_must_stay_paired() {
        let (f, e) = (CompReg::Fanuc, |s: &str| CompReg::Edge(s.into()));
        let mut r = Registers::default();
        assert!(r.agree(&ev(Some(f(6)), None), &ev(Some(e("6.1")), None)));
        assert!(r.agree(&ev(Some(f(7)), None), &ev(Some(e("7.1")), None)));
        assert!(r.agree(&ev(Some(f(6)), None), &ev(Some(e("6.1")), None)));
        assert!(!r.agree(&ev(Some(f(6)), None), &ev(Some(e("7.1")), None)), "H6 is 6.1");
        assert!(!r.agree(&ev(Some(f(8)), None), &ev(Some(e("6.1")), None)), "6.1 is H6");
        // Radius registers pair on their own: D16 with 6.1 beside H6 with 6.1.
        assert!(r.agree(&ev(Some(f(6)), Some((Side::Left, f(16)))), &ev(Some(e("6.1")), Some((Side::Left, e("6.1"))))));
        assert!(!r.agree(&ev(Some(f(6)), Some((Side::Left, f(6)))), &ev(Some(e("6.1")), Some((Side::Left, e("6.1"))))));
    }
}
