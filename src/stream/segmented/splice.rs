//! The output cursor of both segmented writers (`segmented::fanuc::write`, FANUC output,
//! and `segmented::sinumerik::writer`, Sinumerik output): a translated skeleton's text
//! written with each placeholder line replaced by its run, whose blocks the writer appends
//! to its [`Out`] as the writing scan reads them.

use crate::stream::Out;
use std::io::Write;

/// What [`Splice::enter`] found.
pub(crate) enum Entered {
    /// Still in the run being written.
    InRun,
    /// Run `k` starts: the skeleton up to its placeholder is written.
    Run(usize),
    /// No placeholder is left for it (the file changed since the skeleton scan).
    NoPlace,
}

pub(crate) struct Splice<'a> {
    /// The translated skeleton.
    text: &'a str,
    /// The byte range of each placeholder line in `text`, in order.
    places: Vec<(usize, usize)>,
    /// How far `text` is written.
    pos: usize,
    /// The next run.
    next: usize,
    in_run: bool,
    out: Out<'a>,
}

/// The writers write a run's blocks to the output as to any other (`Out::buf`).
impl<'a> std::ops::Deref for Splice<'a> {
    type Target = Out<'a>;
    fn deref(&self) -> &Out<'a> {
        &self.out
    }
}

impl<'a> std::ops::DerefMut for Splice<'a> {
    fn deref_mut(&mut self) -> &mut Out<'a> {
        &mut self.out
    }
}

impl<'a> Splice<'a> {
    pub(crate) fn new(text: &'a str, places: Vec<(usize, usize)>, out: &'a mut dyn Write) -> Splice<'a> {
        Splice { text, places, pos: 0, next: 0, in_run: false, out: Out::new(out) }
    }

    /// A run block comes: at a run's first, the skeleton up to its placeholder is written.
    pub(crate) fn enter(&mut self) -> Entered {
        if self.in_run {
            return Entered::InRun;
        }
        self.in_run = true;
        let Some(&(lo, hi)) = self.places.get(self.next) else { return Entered::NoPlace };
        self.copy_to(lo);
        self.pos = hi;
        self.next += 1;
        Entered::Run(self.next - 1)
    }

    /// A block that is not a run block: the run being written, if any, has ended.
    pub(crate) fn leave(&mut self) {
        self.in_run = false;
    }

    fn copy_to(&mut self, to: usize) {
        if let Some(s) = self.text.get(self.pos..to) {
            self.out.buf.extend_from_slice(s.as_bytes());
        }
        self.pos = to;
    }

    /// Every placeholder met: the rest of the skeleton is written and the output flushed.
    /// `Err` when a run was not met (the caller discards the output) or writing failed.
    pub(crate) fn finish(mut self) -> Result<(), crate::stream::Fallback> {
        if self.next != self.places.len() {
            return Err(crate::stream::Fallback::Diagnostics);
        }
        self.copy_to(self.text.len());
        self.out.finish()
    }
}
