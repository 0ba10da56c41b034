//! The output cursor of both segmented writers (`segmented::fanuc::write`, FANUC output,
//! and `segmented::sinumerik::writer`, Sinumerik output): a translated skeleton's text
//! written with each placeholder line replaced by its run, whose blocks the writer appends
//! to [`Splice::buf`] as the writing scan reads them.

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
    pub(crate) buf: Vec<u8>,
    out: &'a mut dyn Write,
    pub(crate) io: Option<std::io::Error>,
}

impl<'a> Splice<'a> {
    pub(crate) fn new(text: &'a str, places: Vec<(usize, usize)>, out: &'a mut dyn Write) -> Splice<'a> {
        Splice {
            text,
            places,
            pos: 0,
            next: 0,
            in_run: false,
            buf: Vec::with_capacity(crate::stream::WRITE_BYTES + 4096),
            out,
            io: None,
        }
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
            self.buf.extend_from_slice(s.as_bytes());
        }
        self.pos = to;
    }

    /// Writes the buffer out once it holds a write's worth.
    #[inline]
    pub(crate) fn flush_some(&mut self) {
        if self.buf.len() >= crate::stream::WRITE_BYTES {
            crate::stream::spill(self.out, &mut self.buf, &mut self.io);
        }
    }

    /// Every placeholder met: the rest of the skeleton is written and the output flushed.
    /// `Err` when a run was not met (the caller discards the output) or writing failed.
    pub(crate) fn finish(mut self) -> Result<(), crate::stream::Fallback> {
        if self.next != self.places.len() {
            return Err(crate::stream::Fallback::Diagnostics);
        }
        self.copy_to(self.text.len());
        crate::stream::spill(self.out, &mut self.buf, &mut self.io);
        crate::stream::finish_output(self.out, self.io)
    }
}
