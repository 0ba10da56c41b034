//! The checker's view of a tool length selected at the tool change: a `comp` event that
//! changes only the length register, after a `tool` event with nothing between that could
//! move the tool along Z, is compared where the length first matters, the first event after
//! it that could.
//!
//! Why: FANUC keeps the old `H` for the new tool until the program's next `G43 H`, while a
//! Sinumerik tool change takes the new tool's edge at once (`T2 M6 D1`). Between the two a
//! CAM program only positions in XY (`T2 M6`, `S2500 M3`, `G54`, `M8`, `G0 X10. Y10.`, then
//! `G43 Z15. H2`): the tool never moves along Z, so which length was selected there makes no
//! difference to the machine. The deferral passes the length change over exactly such
//! events (spindle, coolant, dwell, a re-selection of the work offset in force, straight
//! moves that leave Z where it is) and stops before anything else, so a move along Z (or
//! an arc, a cycle, a probe move, a reference return, another offset) under the two
//! selections still diverges. The window after the tool change is the same for the length
//! selected in the tool change's block (Siemens) and for one selected blocks later (FANUC
//! `T3 M6`, `S800 M3`, `G43 H3 Z25.`): both are held to the same event. A second length
//! selection in the window replaces the first, which never moved the tool. Both runs go
//! through it, so two traces that differ only in where such a length was selected compare
//! equal, and no other pair does.

use crate::eval::trace::{Axes, CompEv, Event, GridMove, Origin, TraceSink};

/// Index of Z in [`crate::eval::trace::AXES`].
const Z: usize = 2;

/// Passes every event on to `inner`, holding back such a length selection.
pub struct DeferLength<'a> {
    inner: &'a mut dyn TraceSink,
    /// The held `comp` event.
    pending: Option<(Event, Origin)>,
    /// The compensation in force as last seen (held or passed on).
    comp: CompEv,
    /// Since the last tool change nothing has happened that could move the tool along Z.
    window: bool,
    /// Z as the trace last showed it, where known.
    z: Option<f64>,
    /// The work offset last selected.
    offset: Option<u32>,
}

impl<'a> DeferLength<'a> {
    pub fn new(inner: &'a mut dyn TraceSink) -> Self {
        DeferLength { inner, pending: None, comp: CompEv::default(), window: false, z: None, offset: None }
    }

    fn flush(&mut self) {
        if let Some((ev, origin)) = self.pending.take() {
            self.inner.event(&ev, origin);
        }
    }

    /// Whether a move to `z` leaves Z where the trace last showed it.
    fn keeps_z(&self, z: Option<f64>) -> bool {
        matches!((self.z, z), (Some(a), Some(b)) if a == b)
    }

    fn moved(&mut self, z: Option<f64>) {
        if !self.keeps_z(z) {
            self.close();
        }
        self.z = z;
    }

    /// Something that could move the tool along Z: the held length is compared before it.
    fn close(&mut self) {
        self.flush();
        self.window = false;
    }
}

fn z_of(to: &Axes) -> Option<f64> {
    to[Z]
}

impl TraceSink for DeferLength<'_> {
    fn event(&mut self, ev: &Event, origin: Origin) {
        match ev {
            Event::Comp(c) => {
                let length_only = c.radius == self.comp.radius && c.length != self.comp.length;
                self.comp = (**c).clone();
                if self.window && length_only {
                    self.pending = Some((ev.clone(), origin));
                    return;
                }
                self.close();
            }
            Event::Move { to, probe: false, .. } => self.moved(z_of(to)),
            Event::Spindle { .. } | Event::Coolant { .. } | Event::Dwell { .. } => {}
            Event::WorkOffset { n } => {
                if self.offset != Some(*n) {
                    self.close();
                    self.z = None;
                }
                self.offset = Some(*n);
            }
            Event::Home(h) => {
                self.close();
                self.z = z_of(&h.at);
            }
            Event::Arc { to, .. } | Event::Move { to, .. } => {
                self.close();
                self.z = z_of(to);
            }
            _ => {
                self.close();
                self.window = matches!(ev, Event::Tool { .. });
                if !matches!(ev, Event::Tool { .. } | Event::Message { .. } | Event::Stop { .. }) {
                    self.z = None;
                }
            }
        }
        self.inner.event(ev, origin);
    }
    fn grid_move(&mut self, m: &GridMove, origin: Origin) {
        let z = (m.mask & (1 << Z) != 0).then(|| m.to[Z] as f64 / 1000.0);
        self.moved(z);
        self.inner.grid_move(m, origin);
    }
    fn block_done(&mut self, origin: Origin, pos: &Axes) {
        self.inner.block_done(origin, pos);
    }
    fn wants_blocks(&self) -> bool {
        self.inner.wants_blocks()
    }
    fn wants_stop(&self) -> bool {
        self.inner.wants_stop()
    }
    fn finish(&mut self) {
        self.flush();
        self.inner.finish();
    }
}
