//! The literal fast path: a compact block of G0/G1-style modal codes, axis words and F
//! (nearly every block of CAM output) run straight on the machine state, without the
//! general path's word vector, G/M lists and event vector. It decides every block it takes
//! exactly as [`Machine::apply`] does (the same [`Modal::g`], [`Machine::length_of`],
//! [`Machine::axis_target`] and trace position), and takes only blocks whose general run
//! raises no warning, alarm or error and emits at most one move; anything else is left,
//! untouched, to the general path. `src/eval/fast_tests.rs` and `tests/eval_fast.rs`
//! run programs both ways and compare the traces byte for byte.

use super::{AbsInc, Machine, Motion};
use crate::dialect::lit::{LitBlock, NO_MILLI};
use crate::eval::numfmt::GRID_LIMIT;
use crate::eval::trace::{axis_index, Event};
use crate::span::Span;
use std::cell::Cell;

thread_local! {
    /// Off: every literal block takes the general path (the differential tests).
    static OFF: Cell<bool> = const { Cell::new(false) };
}

/// Turns the literal fast path on or off for runs on this thread (for the differential
/// tests; it is on by default).
#[doc(hidden)]
pub fn set_fast_path(on: bool) {
    OFF.with(|o| o.set(!on));
}

/// Whether the literal fast path is on for this thread.
#[inline]
pub fn fast_path_on() -> bool {
    !OFF.with(|o| o.get())
}

/// What [`Machine::apply_lit`] did with a block it took: the span of the move it made
/// (its event is [`Machine::move_event`]), if any.
pub type LitDone = Option<Span>;

impl Machine {
    /// Runs a literal block when it needs nothing but modal G codes ([`Modal::g`]), axis
    /// words and F, and its general run would neither fail nor warn: `None` (the machine
    /// untouched) otherwise.
    ///
    /// [`Modal::g`]: super::Modal::g
    pub fn apply_lit(&mut self, b: &LitBlock) -> Option<LitDone> {
        // Decide first, without touching the machine: every way out below is `None`.
        // In a drilling cycle mode an axis word is a hole (`eval::cycles`); under a frame
        // that turns, a move is [`Machine::framed_motion`]'s.
        if self.cycle.active.is_some()
            || self.cycle.mcall.is_some()
            || self.framed
            || self.polar
            || self.corners.active()
        {
            return None;
        }
        let mut modal = self.modal;
        let mut any_g = false;
        let mut feed_word: Option<(f64, i32)> = None;
        // The axis words: the axes as bits, and the index of each one's word; a block
        // naming an axis twice is left to the general path (the later word wins there).
        let mut word_of = [0u8; 9];
        let mut seen_axes = 0u16;
        let words = b.words();
        // The block's span as the general path folds it from its words (from the first
        // word's span on: a word's span is never empty, so never the fold's empty start).
        let mut span = words.first().map_or(Span::default(), |w| w.span);
        for (k, w) in words.iter().enumerate() {
            span = span.to(w.span);
            match w.letter {
                // G1 in G1 mode (nearly every G word of CAM output) changes nothing: the
                // modal state is then not written back.
                b'G' if w.value == 1.0 && modal.motion == Motion::Linear => {}
                b'G' => {
                    any_g = true;
                    // G1 without rounding its value.
                    let gi = if w.value == 1.0 { 10 } else { super::g_index(w.value) };
                    if !modal.g(self.fanuc, gi) {
                        return None;
                    }
                }
                b'F' => feed_word = Some((w.value, w.milli)),
                c => {
                    let i = axis_index(c)?;
                    if seen_axes & (1 << i) != 0 {
                        return None;
                    }
                    seen_axes |= 1 << i;
                    *word_of.get_mut(i)? = k as u8;
                }
            }
        }
        if seen_axes != 0 {
            match modal.motion {
                Motion::Rapid => {}
                // The alarm of a feed move without any feed is the general path's.
                // A rotary axis or (Siemens) an axis outside FGROUP: `path_feed`'s, there.
                Motion::Linear if seen_axes & self.fgroup.watch != 0 => return None,
                Motion::Linear if feed_word.is_some() || self.feed.is_some() => {}
                _ => return None,
            }
        }
        // Commit, in the general path's order: modal codes, F, then the axes.
        if any_g {
            self.modal = modal;
        }
        if let Some((x, q)) = feed_word {
            let f = self.feed_value(x);
            self.feed = Some(f);
            self.fgroup.feed_inch = self.modal.inch_feed;
            // The feed's grid value from its digits when it is the word's own value on
            // the grid: `grid_of(f)` is `q` exactly when `f` is the double nearest to
            // `q / 1000` (see `numfmt::grid_of`), which the division tests.
            if f == x && q != NO_MILLI && u64::from(q.unsigned_abs()) < GRID_LIMIT && f64::from(q) / 1000.0 == f {
                self.set_feed_grid(f, i64::from(q));
            }
        }
        if seen_axes == 0 {
            return Some(None);
        }
        let milli = self.milli_lengths();
        let bare_scaled = self.fanuc && self.scaling;
        // Lengths in millimetres on the 0.001 grid for every axis (`milli[0]` implies
        // `milli[1]`), absolute: with a count of thousandths, a plain mode and no
        // decimal-point rule to apply (a point, or no rule), nearly every CAM block's axes.
        let plain = milli[0] && self.modal.absolute;
        // Each axis's target reads that axis's state only, so the axes can be written at
        // once and in any order (here by axis).
        let mut left = seen_axes;
        while left != 0 {
            let i = left.trailing_zeros() as usize;
            left &= left - 1;
            let Some(w) = word_of.get(i).and_then(|&k| words.get(usize::from(k))) else { break };
            let (v, q, absolute) =
                if plain && w.mode == AbsInc::Plain && w.milli != NO_MILLI && (w.point || !bare_scaled) {
                    // What the general way below gives for such a word, without its choices.
                    let (v, q) = self.length_grid(true, false, w.value, w.milli, false);
                    (v, q, true)
                } else {
                    let rotary = (3..6).contains(&i);
                    let (v, q) =
                        self.length_grid(milli[usize::from(rotary)], bare_scaled && !w.point, w.value, w.milli, rotary);
                    let absolute = match w.mode {
                        AbsInc::Ac => true,
                        AbsInc::Ic => false,
                        AbsInc::Plain => self.modal.absolute,
                    };
                    (v, q, absolute)
                };
            let off = self.active_offset(i % 9);
            // An absolute target is the word's length plus the offset (`target_from`'s
            // way without G53), and on the grid when both are.
            let t = if absolute { v + off } else { self.target_from(i, v, w.mode, false, off) };
            self.applied[i % 9] = off;
            self.seen[i % 9] = true;
            self.pos[i % 9] = t;
            if let (true, Some(q)) = (absolute, q) {
                self.set_grid(i % 9, t, q, off);
            }
        }
        Some(Some(span))
    }

    /// The move event of a block [`Machine::apply_lit`] moved in (built where it is sent,
    /// not passed back through the fast path's result: it is 170 bytes).
    #[inline]
    pub fn move_event(&self) -> Event {
        let rapid = self.modal.motion == Motion::Rapid;
        Event::Move { rapid, to: self.trace_pos(), f: if rapid { None } else { self.feed }, probe: false }
    }
}
