//! A Siemens cutting edge selected before the M6 of a preselected tool (`Comp::held`): its
//! `comp` event goes out before the first event that could show its length, from the file
//! of the block that selected it (a called program may be running by then).

use super::Interp;
use crate::eval::trace::{Event, Origin};

impl Interp<'_> {
    /// After a block: where a newly held edge was selected.
    pub(super) fn note_held(&mut self) {
        if let Some((_, s)) = &self.m.comp.held {
            if self.held_file.map(|h| h.0) != Some(*s) {
                self.held_file = Some((*s, self.file()));
            }
        }
    }

    /// Before `ev` goes out: the held edge's event, if `ev` could show its length
    /// (`Machine::release_held`).
    pub(super) fn release_held(&mut self, ev: &Event) {
        if self.m.comp.held.is_none() {
            return;
        }
        if let Some((h, span)) = self.m.release_held(ev) {
            let file = match self.held_file {
                Some((s, f)) if s == span => f,
                _ => self.file(),
            };
            self.emit_at(Event::Comp(Box::new(h)), Origin { file, span });
        }
    }
}
