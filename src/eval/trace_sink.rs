//! Where the trace goes: the sink trait the evaluator writes every event to, the move on
//! the 0.001 grid a writer may format fast, and the two plain sinks.

use super::*;

/// Where an event comes from: never compared, used for diagnostics.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Origin {
    pub file: FileId,
    pub span: Span,
}

/// A straight move whose coordinates and feed are on the 0.001 grid (nearly every move
/// of a metric CAM program), given as the integers [`crate::eval::numfmt::grid_of`] finds for
/// the values of its [`Event::Move`]: a writer formats them without looking at a float.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridMove {
    pub rapid: bool,
    /// Bit `i`: axis `i` ([`AXES`]) has a position.
    pub mask: u16,
    /// Per axis in `mask`: the position is `to[i] / 1000` (the double nearest to it);
    /// 0 for the axes not in `mask` (so that two moves compare as whole arrays).
    pub to: [i64; 9],
    /// The feed (`None` for a rapid move) and its `grid_of`.
    pub f: Option<(f64, i64)>,
    /// The 1-based line of the block that moved when known (0: not known); not part of
    /// the event (see [`WriterSink::block_lines`]).
    pub line: u32,
}

impl GridMove {
    /// The move as an event: the same event the general path emits.
    pub fn event(&self) -> Event {
        let mut to = [None; 9];
        for (i, slot) in to.iter_mut().enumerate() {
            if self.mask & (1 << i) != 0 {
                *slot = Some(self.to[i] as f64 / 1000.0);
            }
        }
        Event::Move { rapid: self.rapid, to, f: self.f.map(|f| f.0), probe: false }
    }
}

/// Receives the trace as it is produced; nothing is collected by the evaluator.
pub trait TraceSink {
    fn event(&mut self, ev: &Event, origin: Origin);
    /// A move on the grid: the same as `event(&m.event(), origin)` (the default), which a
    /// writer may do faster.
    fn grid_move(&mut self, m: &GridMove, origin: Origin) {
        self.event(&m.event(), origin);
    }
    /// Called after every executed block with the current position (workpiece frame,
    /// millimetres); for per-block comparisons. Default: nothing.
    fn block_done(&mut self, _origin: Origin, _pos: &Axes) {}
    /// Whether [`TraceSink::block_done`] is wanted (it costs a little per block); asked
    /// once per run, so the answer must not change during it.
    fn wants_blocks(&self) -> bool {
        false
    }
    /// Polled once per block: `true` ends the run early ([`crate::eval::Ending::Stopped`]),
    /// e.g. when the checker has seen enough.
    fn wants_stop(&self) -> bool {
        false
    }
    /// Called once when the run has ended (after its last event): a writer hands over
    /// what it still holds. Default: nothing.
    fn finish(&mut self) {}
}

/// Discards the trace.
#[derive(Default)]
pub struct NullSink;

impl TraceSink for NullSink {
    fn event(&mut self, _ev: &Event, _origin: Origin) {}
    fn grid_move(&mut self, _m: &GridMove, _origin: Origin) {}
}

/// Collects the trace (tests and the checker's context window; not for long runs).
#[derive(Default)]
pub struct VecSink {
    pub events: Vec<(Event, Origin)>,
}

impl TraceSink for VecSink {
    fn event(&mut self, ev: &Event, origin: Origin) {
        self.events.push((ev.clone(), origin));
    }
}
