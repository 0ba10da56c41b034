//! The checker's view of `work_offset` events: a selection that repeats the `work_offset`
//! event right before it (nothing in between) says nothing new, since any change of the
//! offset's values shows in the positions that follow. FANUC writes an offset live
//! (`G10 L2`, `#5221=`), Sinumerik needs `$P_UIFR` and a re-selection: a translation
//! may so select once more where the source selected once (docs/semantics.md).

use super::trace::{Axes, Event, GridMove, Origin, TraceSink};

/// Passes every event on to `inner` except such a repeated `work_offset`.
pub struct CollapseWorkOffsets<'a> {
    pub inner: &'a mut dyn TraceSink,
    last: Option<u32>,
}

impl<'a> CollapseWorkOffsets<'a> {
    pub fn new(inner: &'a mut dyn TraceSink) -> Self {
        CollapseWorkOffsets { inner, last: None }
    }
}

impl TraceSink for CollapseWorkOffsets<'_> {
    fn event(&mut self, ev: &Event, origin: Origin) {
        if let Event::WorkOffset { n } = ev {
            if self.last == Some(*n) {
                return;
            }
            self.last = Some(*n);
        } else {
            self.last = None;
        }
        self.inner.event(ev, origin);
    }
    fn grid_move(&mut self, m: &GridMove, origin: Origin) {
        self.last = None;
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
        self.inner.finish();
    }
}
