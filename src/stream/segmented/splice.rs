//! The output cursor of both segmented writers (`segmented::fanuc::write`, FANUC output,
//! and `segmented::sinumerik::writer`, Sinumerik output): a translated skeleton's text
//! written with each placeholder line replaced by its run, whose blocks the writer appends
//! to its [`Out`] as the writing scan reads them.

use crate::stream::Out;
use std::io::Write;

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
    /// The scan does not match the skeleton's (the file changed), or a block translated
    /// alone has diagnostics: the output is discarded.
    pub(crate) bad: bool,
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
        Splice { text, places, pos: 0, next: 0, in_run: false, out: Out::new(out), bad: false }
    }

    /// A run block comes: at a run's first, the skeleton up to its placeholder is written and
    /// the run's index returned (none left for it: the file changed since the skeleton scan).
    pub(crate) fn enter(&mut self) -> Option<usize> {
        if self.in_run {
            return None;
        }
        self.in_run = true;
        let Some(&(lo, hi)) = self.places.get(self.next) else {
            self.bad = true;
            return None;
        };
        self.copy_to(lo);
        self.pos = hi;
        self.next += 1;
        Some(self.next - 1)
    }

    /// Whether the output is still to be written (not discarded, no write failed).
    pub(crate) fn live(&self) -> bool {
        !self.bad && self.out.io.is_none()
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

/// The byte ranges of the placeholder lines of a translated skeleton with `runs` runs, in
/// order, for both targets: each line ends in `open`, `k`, `close` and `eol`, after a line
/// head the target's `head` accepts (its comment opener, the placeholder's N number and
/// mode words); with `carriers`, a line of the same `k` right after a placeholder is
/// replaced with it (FANUC's carriers of N numbers, `segmented::fanuc::carry_numbers`).
/// `None` when the text holds the marker anywhere else.
pub(crate) fn placeholders(
    text: &str,
    (runs, eol): (usize, &str),
    (open, close): (&str, &str),
    head: impl Fn(&str) -> bool,
    carriers: bool,
) -> Option<Vec<(usize, usize)>> {
    let mut v: Vec<(usize, usize)> = Vec::with_capacity(runs);
    let mut from = 0;
    while let Some(at) = text[from..].find(open).map(|k| k + from) {
        // The line start: after the last LF, or CR (a file with CR line ends).
        let lo = text[..at].rfind(['\n', '\r']).map_or(0, |k| k + 1);
        if !head(&text[lo..at]) {
            return None;
        }
        let after = at + open.len();
        let k = match v.len().checked_sub(1) {
            Some(l) if carriers && v[l].1 == lo && text[after..].starts_with(&format!("{l}{close}{eol}")) => l,
            _ => v.len(),
        };
        let tail = format!("{k}{close}{eol}");
        if !text[after..].starts_with(&tail) {
            return None;
        }
        let hi = after + tail.len();
        match v.get_mut(k) {
            Some(p) => p.1 = hi,
            None => v.push((lo, hi)),
        }
        from = hi;
    }
    (v.len() == runs).then_some(v)
}
