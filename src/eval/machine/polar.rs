//! Polar coordinates (trace v2): FANUC G16/G15 (the plane's first axis word is the
//! radius, the second the angle, about the workpiece zero) and Siemens G110/G111/G112
//! poles with `AP=`/`RP=`. A polar block's words are turned into the Cartesian words of
//! the plane before the block runs, so moves, arcs and drilling cycles read them as any
//! other (docs/semantics.md, "Polar coordinates").

use super::frames::error;
use super::{g_index, AbsInc, Fault, Machine, Plane, Span, WordVal, WV};
use std::borrow::Cow;

/// The Siemens pole: its plane and its two coordinates there (programmed coordinates, mm);
/// the stored polar angle and radius since it was set.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Pole {
    pub at: Option<(Plane, f64, f64)>,
    pub ap: Option<f64>,
    pub rp: Option<f64>,
}

const LETTERS: &[u8; 3] = b"XYZ";

fn num_of(w: &WordVal) -> Option<f64> {
    match w.val {
        WV::Num(x) => Some(x),
        WV::Str(_) => None,
    }
}

/// The plane a block selects (its last G17/G18/G19), which its polar words are read in.
fn block_plane(gs: &[i64]) -> Option<Plane> {
    gs.iter().rev().find_map(|g| match g {
        170 => Some(Plane::XY),
        180 => Some(Plane::ZX),
        190 => Some(Plane::YZ),
        _ => None,
    })
}

impl Machine {
    /// A plain value in the unit in force (mm, or inch) of the length `mm`.
    fn in_unit(&self, mm: f64) -> f64 {
        if self.modal.inch {
            mm / 25.4
        } else {
            mm
        }
    }

    /// A word's value read as written (decimal-point rule, not rounded), in the unit.
    fn raw(&self, w: &WordVal, x: f64, rotary: bool) -> f64 {
        let inc = crate::dialect::semantics::input_increment(self.inc_mm, self.modal.inch, rotary);
        if w.bare && self.scaling {
            x * inc
        } else {
            x
        }
    }

    fn synth(addr: u8, v: f64, span: Span) -> WordVal {
        let addr: &'static str = match addr {
            b'X' => "X",
            b'Y' => "Y",
            _ => "Z",
        };
        WordVal { addr: Cow::Borrowed(addr), val: WV::Num(v), mode: AbsInc::Ac, bare: false, literal: false, span }
    }

    /// The block's words with its polar coordinates made Cartesian (`None`: nothing polar).
    pub(super) fn polar_words(&mut self, words: &[WordVal]) -> Result<Option<Vec<WordVal>>, Fault> {
        let mut gs = Vec::new();
        for w in words {
            if w.addr.as_ref() == "G" {
                if let Some(x) = num_of(w) {
                    gs.push(g_index(x));
                }
            }
        }
        if self.fanuc {
            let was = self.polar;
            if gs.contains(&160) {
                self.polar = true;
            }
            if gs.contains(&150) {
                self.polar = false;
            }
            if !self.polar {
                return Ok(None);
            }
            // The block that selects G16 selects its plane too ("G17 G16").
            let plane = block_plane(&gs).unwrap_or(self.modal.plane);
            let gs: Vec<i64> = gs.into_iter().filter(|g| was || !matches!(g, 170 | 180 | 190)).collect();
            return self.fanuc_polar(words, &gs, plane);
        }
        let plane = block_plane(&gs).unwrap_or(self.modal.plane);
        self.siemens_polar(words, &gs, plane)
    }

    fn fanuc_polar(&mut self, words: &[WordVal], gs: &[i64], plane: Plane) -> Result<Option<Vec<WordVal>>, Fault> {
        // These read their axis words as Cartesian in G16 mode (or are not modelled in it).
        if gs
            .iter()
            .any(|g| matches!(g, 100 | 520 | 920 | 530 | 680 | 510 | 511 | 501 | 280 | 290 | 300 | 170 | 180 | 190))
        {
            let span = words.iter().find(|w| w.addr.as_ref() == "G").map_or(Span::default(), |w| w.span);
            if gs.iter().any(|g| matches!(g, 280 | 290 | 300 | 170 | 180 | 190)) {
                return Err(error(
                    "NC499",
                    "a reference return or plane selection in G16 mode is not modelled".into(),
                    span,
                    "cancel the polar coordinates with G15 before it",
                ));
            }
            return Ok(None);
        }
        let (u, v, _) = plane.axes();
        let find = |i: usize| words.iter().rposition(|w| w.addr.as_bytes() == [LETTERS[i]]);
        let (ri, ai) = (find(u), find(v));
        if ri.is_none() && ai.is_none() {
            return Ok(None);
        }
        let span = words
            .iter()
            .filter(|w| ri.is_some_and(|k| w.span == words[k].span) || ai.is_some_and(|k| w.span == words[k].span))
            .fold(Span::default(), |s, w| if s == Span::default() { w.span } else { s.to(w.span) });
        let absolute = if gs.contains(&910) { false } else { gs.contains(&900) || self.modal.absolute };
        let (Some(ri), Some(ai)) = (ri, ai) else {
            return Err(error(
                "NC499",
                "a polar block (G16) without both the radius and the angle is not modelled (the controls keep different values)".into(),
                span,
                "write the radius and the angle in every polar block: `G16 … X50. Y45.`",
            ));
        };
        let (rw, aw) = (&words[ri], &words[ai]);
        if !absolute || rw.mode != AbsInc::Plain || aw.mode != AbsInc::Plain {
            return Err(error(
                "NC499",
                "polar coordinates (G16) under G91 are not modelled (the origin is then the current position)".into(),
                span,
                "program polar coordinates under G90, about the workpiece zero (a G52 shift moves it)",
            ));
        }
        let (Some(rx), Some(ax)) = (num_of(rw), num_of(aw)) else { return Ok(None) };
        let r = self.raw(rw, rx, false);
        let a = self.raw(aw, ax, true).to_radians();
        let mut out: Vec<WordVal> =
            words.iter().enumerate().filter(|(k, _)| *k != ri && *k != ai).map(|(_, w)| w.clone()).collect();
        out.push(Self::synth(LETTERS[u], r * a.cos(), rw.span));
        out.push(Self::synth(LETTERS[v], r * a.sin(), aw.span));
        Ok(Some(out))
    }

    fn siemens_polar(&mut self, words: &[WordVal], gs: &[i64], plane: Plane) -> Result<Option<Vec<WordVal>>, Fault> {
        let (u, v, _) = plane.axes();
        let pole_g = gs.iter().copied().find(|g| matches!(g, 1100 | 1110 | 1120));
        let named = |a: &str| words.iter().rposition(|w| w.addr.as_ref() == a);
        let (api, rpi) = (named("AP"), named("RP"));
        if let Some(g) = pole_g {
            let span = words.iter().find(|w| w.addr.as_ref() == "G").map_or(Span::default(), |w| w.span);
            if api.is_some() || rpi.is_some() {
                return Err(error(
                    "NC499",
                    "a pole given in polar coordinates (G110/G111/G112 AP= RP=) is not modelled".into(),
                    span,
                    "give the pole in Cartesian coordinates: `G111 X.. Y..`",
                ));
            }
            // The pole's own block does not move; its words are the pole (G90/G91 do not
            // apply to them).
            let base = match g {
                1110 => (0.0, 0.0),
                1100 => {
                    let w = [0, 1, 2].map(|i| self.pos[i] - self.active_offset(i));
                    let p = self.xf.invert(w).unwrap_or(w);
                    (p[u], p[v])
                }
                _ => match self.pole.at {
                    Some((pl, a, b)) if pl == plane => (a, b),
                    Some(_) => {
                        return Err(error(
                            "NC499",
                            "G112 in another plane than its pole".into(),
                            span,
                            "set the pole again with G111",
                        ))
                    }
                    None => (0.0, 0.0),
                },
            };
            let coord = |i: usize| {
                words
                    .iter()
                    .rev()
                    .find(|w| w.addr.as_bytes() == [LETTERS[i]])
                    .and_then(|w| num_of(w).map(|x| self.length(w, x, false)))
            };
            if words.iter().any(|w| w.addr.len() == 1 && b"ABCUVW".contains(&w.addr.as_bytes()[0]))
                || coord(3 - u - v).is_some()
            {
                return Err(error(
                    "NC499",
                    "a pole with a third axis (cylinder coordinates) is not modelled".into(),
                    span,
                    "give the pole in the plane's two axes",
                ));
            }
            let pole = (base.0 + coord(u).unwrap_or(0.0), base.1 + coord(v).unwrap_or(0.0));
            self.pole = Pole { at: Some((plane, pole.0, pole.1)), ap: None, rp: None };
            // Nothing else of the block is modelled with a pole: its axis words are spent.
            let rest: Vec<WordVal> = words
                .iter()
                .filter(|w| !(w.addr.len() == 1 && b"XYZ".contains(&w.addr.as_bytes()[0])))
                .cloned()
                .collect();
            return Ok(Some(rest));
        }
        if api.is_none() && rpi.is_none() {
            return Ok(None);
        }
        let span = api.or(rpi).map_or(Span::default(), |k| words[k].span);
        let (pu, pv) = match self.pole.at {
            Some((pl, a, b)) if pl == plane => (a, b),
            None => (0.0, 0.0),
            Some(_) => {
                return Err(error(
                    "NC499",
                    "AP=/RP= in another plane than the pole's".into(),
                    span,
                    "set the pole again with G111 after G17/G18/G19",
                ))
            }
        };
        if words.iter().any(|w| w.addr.as_bytes() == [LETTERS[u]] || w.addr.as_bytes() == [LETTERS[v]]) {
            return Err(error(
                "NC499",
                "AP=/RP= with an axis of the plane in the same block".into(),
                span,
                "write the point either polar or Cartesian",
            ));
        }
        let incremental = gs.contains(&910) || (!gs.contains(&900) && !self.modal.absolute);
        let value = |k: Option<usize>, rotary: bool, last: Option<f64>| -> Result<Option<f64>, Fault> {
            let Some(k) = k else { return Ok(last) };
            let w = &words[k];
            let Some(x) = num_of(w) else { return Ok(last) };
            let x = if rotary { x } else { self.length(w, x, false) };
            match w.mode {
                AbsInc::Ac => Ok(Some(x)),
                AbsInc::Ic => Ok(Some(last.unwrap_or(0.0) + x)),
                AbsInc::Plain if incremental => Err(error(
                    "NC499",
                    "AP=/RP= under G91 are not modelled".into(),
                    w.span,
                    "program polar coordinates under G90 (an increment of the angle: AP=IC(..))",
                )),
                AbsInc::Plain => Ok(Some(x)),
            }
        };
        let ap = value(api, true, self.pole.ap)?;
        let rp = value(rpi, false, self.pole.rp)?;
        let (Some(ap), Some(rp)) = (ap, rp) else {
            return Err(error(
                "NC499",
                "a polar move without an angle or a radius since the pole was set".into(),
                span,
                "write AP= and RP= after each G110/G111/G112 and plane change",
            ));
        };
        self.pole.ap = Some(ap);
        self.pole.rp = Some(rp);
        let a = ap.to_radians();
        let mut out: Vec<WordVal> = words
            .iter()
            .enumerate()
            .filter(|(k, _)| Some(*k) != api && Some(*k) != rpi)
            .map(|(_, w)| w.clone())
            .collect();
        let arc = gs.iter().any(|g| matches!(g, 20 | 30))
            || (!gs.iter().any(|g| matches!(g, 0 | 10))
                && matches!(self.modal.motion, super::Motion::Cw | super::Motion::Ccw));
        let has_centre = words.iter().any(|w| matches!(w.addr.as_ref(), "I" | "J" | "K" | "CR" | "AR"));
        if arc && !has_centre {
            // A polar arc runs about the pole.
            for (i, c) in [(u, pu), (v, pv)] {
                let addr: &'static str = ["I", "J", "K"][i];
                out.push(WordVal {
                    addr: Cow::Borrowed(addr),
                    val: WV::Num(self.in_unit(c)),
                    mode: AbsInc::Ac,
                    bare: false,
                    literal: false,
                    span,
                });
            }
        }
        out.push(Self::synth(LETTERS[u], self.in_unit(pu + rp * a.cos()), span));
        out.push(Self::synth(LETTERS[v], self.in_unit(pv + rp * a.sin()), span));
        Ok(Some(out))
    }
}
