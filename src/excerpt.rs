//! Rendering diagnostics that point into a file too large to hold in memory (a streamed
//! program): the lines their labels touch are read off disk in one pass, and codespan
//! renders them from that excerpt with the file's real line and column numbers, so a warning
//! at the end of a 400 MB program looks exactly as it does for a small file.

use crate::diag::{self, Diagnostic, Label, MAX_LABEL_LINES};
use crate::span::{FileId, SourceDb};
use crate::stream::lines::{Input, Lines};
use codespan_reporting::files::{Error, Files};
use codespan_reporting::term;
use std::ops::Range;
use std::path::Path;

/// Label ranges past this many are not looked up (a file with a warning on every line
/// renders the first ones; the rest still print their message and place).
const MAX_LABELS: usize = 10_000;

/// The kept lines of one streamed file.
struct Excerpt {
    id: FileId,
    name: String,
    /// The kept lines, concatenated, each with its own line end.
    text: String,
    /// The kept lines, in file order.
    lines: Vec<KeptLine>,
}

/// One kept line: its text offset in the file, number, start in the excerpt and length
/// with its line end.
#[derive(Clone, Copy)]
struct KeptLine {
    start: u64,
    line: u32,
    at: usize,
    len: usize,
}

/// What the pass over the file learns about one label.
#[derive(Clone, Copy)]
struct Reach {
    lo: u64,
    hi: u64,
    /// Line-break characters inside the label (for the same clipping as `diag::render`).
    breaks: usize,
    /// Text end of the label's first line.
    first_end: Option<u64>,
}

impl Excerpt {
    /// Reads `path` once, keeping the lines the `reach`es touch (at most a label's first
    /// `MAX_LABEL_LINES + 2` lines each, so memory follows the diagnostics, not the file),
    /// and fills in what each reach learns; the reaches keep their order.
    fn read(id: FileId, name: String, path: &Path, reach: &mut [Reach]) -> Option<Excerpt> {
        let f = std::fs::File::open(path).ok()?;
        let mut lines = Lines::new(Input::File(f)).ok()?;
        // Reaches by start, as the lines come.
        let mut order: Vec<usize> = (0..reach.len()).collect();
        order.sort_by_key(|&i| reach[i].lo);
        let mut ex = Excerpt { id, name, text: String::new(), lines: Vec::new() };
        // Labels that have started and may still need lines.
        let mut open: Vec<usize> = Vec::new();
        let mut taken = vec![0usize; reach.len()];
        let mut k = 0;
        let mut last: Option<(u64, u32, u64)> = None;
        while let Ok(Some(l)) = lines.next_line() {
            let text_end = l.start + l.text.len() as u64;
            while k < order.len() && reach[order[k]].lo < l.next.max(text_end + 1) {
                open.push(order[k]);
                k += 1;
            }
            let mut keep = false;
            open.retain(|&i| {
                let r = &mut reach[i];
                if r.hi < l.start && r.lo < l.start {
                    return false;
                }
                if taken[i] > MAX_LABEL_LINES + 1 {
                    return false;
                }
                taken[i] += 1;
                keep = true;
                if r.first_end.is_none() {
                    r.first_end = Some(text_end);
                }
                // The line break lies inside the label.
                if text_end >= r.lo && text_end < r.hi {
                    r.breaks += ((l.next - text_end) as usize).min((r.hi - text_end) as usize);
                }
                true
            });
            if keep {
                ex.push(l.start, l.line, l.text, (l.next - text_end) as usize);
            }
            last = Some((l.next, l.line, text_end));
            if k >= reach.len() && open.is_empty() {
                break;
            }
        }
        // A label at the very end of a file that ends with a line break sits on the empty
        // line after it, as in the whole-file rendering.
        if let Some((next, line, text_end)) = last {
            if next > text_end && reach.iter().any(|r| r.lo >= next) {
                ex.push(next, line + 1, "", 0);
            }
        }
        Some(ex)
    }

    /// Keeps a line; `end` is the length of its line end (CR LF, LF or CR: 2, 1 or 0).
    fn push(&mut self, start: u64, line: u32, text: &str, end: usize) {
        let at = self.text.len();
        self.text.push_str(text);
        self.text.push_str(["", "\n", "\r\n"][end.min(2)]);
        self.lines.push(KeptLine { start, line, at, len: self.text.len() - at });
    }

    fn kept(&self, line_index: usize) -> Result<&KeptLine, Error> {
        let i = self.lines.partition_point(|l| (l.line as usize) < line_index + 1);
        self.lines
            .get(i)
            .filter(|l| l.line as usize == line_index + 1)
            .ok_or(Error::LineTooLarge { given: line_index, max: self.lines.last().map_or(0, |l| l.line as usize) })
    }

    /// The excerpt offset of file offset `o` (clamped to the kept line at or before it).
    fn map(&self, o: u64) -> usize {
        let i = self.lines.partition_point(|l| l.start <= o);
        let Some(l) = i.checked_sub(1).map(|i| self.lines[i]) else { return 0 };
        // Past the kept line: a line that was not kept, clamped to the kept line's end.
        (l.at + ((o - l.start) as usize).min(l.len)).min(self.text.len())
    }

    /// The label's range in the excerpt, cut after its first line when it covers more
    /// than `MAX_LABEL_LINES` lines (like `diag::render`).
    fn range(&self, r: &Reach) -> Range<usize> {
        let hi = if r.breaks > MAX_LABEL_LINES { r.first_end.unwrap_or(r.hi).max(r.lo) } else { r.hi };
        let lo = self.map(r.lo);
        lo..self.map(hi).max(lo)
    }
}

/// Files for codespan: excerpts for streamed files, the database for the rest.
struct View<'a> {
    db: &'a SourceDb,
    ex: &'a [Excerpt],
}

impl View<'_> {
    fn excerpt(&self, id: FileId) -> Option<&Excerpt> {
        self.ex.iter().find(|e| e.id == id)
    }
}

impl<'a> Files<'a> for View<'a> {
    type FileId = FileId;
    type Name = &'a str;
    type Source = &'a str;

    fn name(&'a self, id: FileId) -> Result<&'a str, Error> {
        match self.excerpt(id) {
            Some(e) => Ok(&e.name),
            None => self.db.name(id),
        }
    }

    fn source(&'a self, id: FileId) -> Result<&'a str, Error> {
        match self.excerpt(id) {
            Some(e) => Ok(&e.text),
            None => self.db.source(id),
        }
    }

    fn line_index(&'a self, id: FileId, byte_index: usize) -> Result<usize, Error> {
        match self.excerpt(id) {
            // Real line indices, so that codespan marks the gaps between far lines.
            Some(e) => {
                let i = e.lines.partition_point(|l| l.at <= byte_index).saturating_sub(1);
                Ok(e.lines.get(i).map_or(0, |l| l.line as usize - 1))
            }
            None => self.db.line_index(id, byte_index),
        }
    }

    fn line_range(&'a self, id: FileId, line_index: usize) -> Result<Range<usize>, Error> {
        match self.excerpt(id) {
            Some(e) => e.kept(line_index).map(|l| l.at..l.at + l.len),
            None => self.db.line_range(id, line_index),
        }
    }
}

/// Renders `diags` like [`diag::render`], reading the lines of labels in `streamed` files
/// (id, path on disk) from disk instead of the database, whose text for them is empty.
pub fn render(db: &SourceDb, diags: &[Diagnostic], streamed: &[(FileId, &Path)]) -> String {
    let is_streamed = |f: FileId| streamed.iter().any(|s| s.0 == f);
    if !diags.iter().flat_map(|d| &d.labels).any(|l| is_streamed(l.file)) {
        return diag::render(db, diags);
    }
    // One reach per label in a streamed file, in diagnostic order, then one pass per file.
    let mut reach: Vec<(FileId, Reach)> = Vec::new();
    for l in diags.iter().flat_map(|d| &d.labels) {
        if is_streamed(l.file) && reach.len() < MAX_LABELS {
            reach.push((
                l.file,
                Reach { lo: u64::from(l.span.lo), hi: u64::from(l.span.hi), breaks: 0, first_end: None },
            ));
        }
    }
    let mut excerpts = Vec::new();
    for &(id, path) in streamed {
        let idx: Vec<usize> = (0..reach.len()).filter(|&i| reach[i].0 == id).collect();
        let mut mine: Vec<Reach> = idx.iter().map(|&i| reach[i].1).collect();
        if mine.is_empty() {
            continue;
        }
        let name = if id < db.len() { db.get(id).name.clone() } else { path.display().to_string() };
        if let Some(ex) = Excerpt::read(id, name, path, &mut mine) {
            for (&i, r) in idx.iter().zip(mine) {
                reach[i].1 = r;
            }
            excerpts.push(ex);
        }
    }
    let view = View { db, ex: &excerpts };
    let config = term::Config::default();
    let mut out = String::new();
    let mut n = 0;
    for d in diags {
        let mut ranges: Vec<Option<Range<usize>>> = Vec::new();
        let mut complete = true;
        for l in &d.labels {
            ranges.push(if is_streamed(l.file) {
                let r = reach.get(n).map(|r| r.1);
                n += 1;
                match (r, excerpts.iter().find(|e| e.id == l.file)) {
                    (Some(r), Some(e)) => Some(e.range(&r)),
                    _ => {
                        complete = false;
                        None
                    }
                }
            } else {
                None
            });
        }
        let range_of = |l: &Label| -> Range<usize> {
            let i = d.labels.iter().position(|x| std::ptr::eq(x, l)).unwrap_or(0);
            ranges.get(i).cloned().flatten().unwrap_or_else(|| diag::shown_range(db, l))
        };
        let mut one = String::new();
        if complete && term::emit_to_string(&mut one, &config, &view, &d.to_codespan_with(&range_of)).is_ok() {
            out.push_str(&one);
        } else {
            out.push_str(&diag::render(&SourceDb::new(), std::slice::from_ref(d)));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::span::Span;

    /// The excerpt rendering of `diags` over `text` written to a file, and the whole-file one.
    fn both(tag: &str, bytes: &[u8], diags: &[Diagnostic]) -> (String, String) {
        let dir = std::env::temp_dir().join(format!("nctrans-excerpt-{}-{tag}", std::process::id()));
        let _ = std::fs::create_dir_all(&dir);
        let path = dir.join("big.mpf");
        std::fs::write(&path, bytes).unwrap();
        let text = String::from_utf8_lossy(bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes)).into_owned();
        let mut whole = SourceDb::new();
        whole.add("big.mpf", text);
        let mut empty = SourceDb::new();
        empty.add("big.mpf", String::new());
        let a = render(&empty, diags, &[(0, &path)]);
        let b = diag::render(&whole, diags);
        let _ = std::fs::remove_dir_all(&dir);
        (a, b)
    }

    fn at(text: &str, needle: &str) -> Span {
        let lo = text.find(needle).unwrap() as u32;
        Span::new(lo, lo + needle.len() as u32)
    }

    #[test]
    fn excerpts_render_like_the_whole_file() {
        let mut text: String = (1..=3000).map(|i| format!("N{i} G1 X{i} Y-{i}\n")).collect();
        text.push_str("IF R1 > 2\nENDWHILE\n");
        let len = text.len() as u32;
        let d1 = Diagnostic::warning("NC110", "one").primary(0, at(&text, "X17 "), "here").hint("write it so");
        let d2 = Diagnostic::error("NC200", "two").primary(0, at(&text, "ENDWHILE"), "this end").secondary(
            0,
            at(&text, "IF R1"),
            "opened here",
        );
        let d3 = Diagnostic::error("NC306", "whole").primary(0, Span::new(0, len), "the program");
        let d4 =
            Diagnostic::error("NC201", "short").primary(0, Span::new(at(&text, "N5 ").lo, at(&text, "N8 ").lo), "");
        let d5 = Diagnostic::error("NC230", "end").primary(0, Span::new(len, len), "the end");
        let d6 = Diagnostic::warning("NC111", "far").primary(0, at(&text, "N2999 "), "b").secondary(
            0,
            at(&text, "N3 "),
            "a",
        );
        for (i, d) in [d1, d2, d3, d4, d5, d6].into_iter().enumerate() {
            let (a, b) = both(&format!("lf{i}"), text.as_bytes(), std::slice::from_ref(&d));
            assert_eq!(a, b, "diagnostic {i}");
            assert!(a.contains(&d.message), "{a}");
        }
    }

    #[test]
    fn crlf_bom_and_no_final_line_end() {
        let mut body: String = (1..=40).map(|i| format!("N{i} G1 X{i}\r\n")).collect();
        body.push_str("M30");
        let len = body.len() as u32;
        let mut bytes = b"\xEF\xBB\xBF".to_vec();
        bytes.extend_from_slice(body.as_bytes());
        let ds = [
            Diagnostic::warning("NC110", "x").primary(0, at(&body, "X12\r"), "here"),
            Diagnostic::error("NC230", "no end").primary(0, Span::new(len, len), "end"),
            Diagnostic::error("NC306", "many").primary(0, Span::new(at(&body, "N2 ").lo, at(&body, "N30 ").lo), "x"),
            Diagnostic::error("NC201", "few").primary(0, Span::new(at(&body, "N2 ").lo, at(&body, "N4 ").lo), "x"),
        ];
        for (i, d) in ds.iter().enumerate() {
            let (a, b) = both(&format!("crlf{i}"), &bytes, std::slice::from_ref(d));
            assert_eq!(a, b, "diagnostic {i}");
        }
        // All at once, in one pass over the file.
        let (a, b) = both("crlf-all", &bytes, &ds);
        assert_eq!(a, b);
    }
}
