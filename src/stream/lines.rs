//! Reading a file line by line in constant memory: a fixed buffer refilled from the file,
//! lines split on LF, CR LF and lone CR exactly like `read::blocks`, each with its byte
//! offset (after a UTF-8 byte-order mark, like the decoded text) and line number, and a
//! seek to any line start for re-reading.

use std::fs::File;
use std::io::{self, Read, Seek, SeekFrom};

/// Refill size; lines longer than this grow the buffer (up to [`MAX_LINE`]).
const CHUNK: usize = 256 * 1024;
/// A longer line is refused (the whole-file reader handles such files).
pub const MAX_LINE: usize = 16 * 1024 * 1024;

/// Why a file cannot be streamed as it is; the caller falls back to the whole-file path.
#[derive(Debug)]
pub enum NotStreamable {
    Io(io::Error),
    /// A line that is not UTF-8 (legacy encodings are decoded whole).
    NotUtf8 {
        line: u32,
    },
    /// A line longer than [`MAX_LINE`].
    LongLine {
        line: u32,
    },
    /// NUL bytes or many control characters: binary data (diagnosed by the whole path).
    Binary,
    /// Over 4 GiB of text: spans are 32-bit offsets.
    TooLarge,
}

impl std::fmt::Display for NotStreamable {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            NotStreamable::Io(e) => write!(f, "{e}"),
            NotStreamable::NotUtf8 { line } => write!(f, "line {line} is not UTF-8"),
            NotStreamable::LongLine { line } => write!(f, "line {line} is longer than {MAX_LINE} bytes"),
            NotStreamable::Binary => write!(f, "the file holds binary data"),
            NotStreamable::TooLarge => write!(f, "the file is larger than 4 GiB"),
        }
    }
}

impl From<io::Error> for NotStreamable {
    fn from(e: io::Error) -> Self {
        NotStreamable::Io(e)
    }
}

/// Where the bytes come from: a file, or memory (tests).
pub enum Input {
    File(File),
    Mem(io::Cursor<Vec<u8>>),
}

impl Input {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        match self {
            Input::File(f) => f.read(buf),
            Input::Mem(c) => c.read(buf),
        }
    }

    fn seek(&mut self, to: u64) -> io::Result<()> {
        match self {
            Input::File(f) => f.seek(SeekFrom::Start(to)).map(|_| ()),
            Input::Mem(c) => c.seek(SeekFrom::Start(to)).map(|_| ()),
        }
    }
}

/// A line reader with a fixed-size buffer.
pub struct Lines {
    input: Input,
    buf: Vec<u8>,
    /// Valid bytes are `buf[pos..end]`.
    pos: usize,
    end: usize,
    eof: bool,
    /// Text offset (after the BOM) of `buf[pos]`.
    offset: u64,
    line: u32,
    bom: u64,
    /// Control characters seen (for the binary-data check).
    pub controls: u64,
}

/// One line: its text without the line end, its text offset and 1-based number.
pub struct Line<'a> {
    pub text: &'a str,
    pub start: u64,
    pub line: u32,
    /// Offset of the next line (after this one's line end).
    pub next: u64,
    /// Every byte is printable ASCII, a tab, a form feed or SUB (so the text is ASCII).
    pub ascii: bool,
}

/// A line [`Lines::skip_plain`] moved past: as [`Line`], less the text.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Taken {
    pub start: u64,
    pub line: u32,
    pub next: u64,
}

impl Lines {
    /// Opens the input at its start (a UTF-8 byte-order mark is skipped).
    pub fn new(mut input: Input) -> Result<Lines, NotStreamable> {
        input.seek(0)?;
        let mut l =
            Lines { input, buf: vec![0; CHUNK], pos: 0, end: 0, eof: false, offset: 0, line: 0, bom: 0, controls: 0 };
        l.fill(3)?;
        if l.buf[..l.end].starts_with(b"\xEF\xBB\xBF") {
            l.bom = 3;
            l.pos = 3;
        }
        Ok(l)
    }

    /// Whether the file starts with a byte-order mark.
    pub fn bom(&self) -> bool {
        self.bom > 0
    }

    /// Continues reading at text offset `offset`, which must be a line start, as line `line`.
    pub fn seek(&mut self, offset: u64, line: u32) -> Result<(), NotStreamable> {
        self.input.seek(offset + self.bom)?;
        self.pos = 0;
        self.end = 0;
        self.eof = false;
        self.offset = offset;
        self.line = line - 1;
        Ok(())
    }

    /// [`Lines::seek`], but when `offset` is at or after the next line's start and among
    /// the bytes buffered (a re-read of the chunk after the one just read, nearly always),
    /// reading goes on from the buffer: the file is not read again (a page re-read would
    /// otherwise read a whole buffer for a chunk of a fraction of it). The bytes buffered
    /// are the file's from `offset()` on (`fill` only appends to them), so they are what
    /// reading there again would give.
    pub fn seek_near(&mut self, offset: u64, line: u32) -> Result<(), NotStreamable> {
        let ahead = (self.end - self.pos) as u64;
        match offset.checked_sub(self.offset) {
            Some(k) if k <= ahead && line > 0 => {
                self.pos += k as usize;
                self.offset = offset;
                self.line = line - 1;
                Ok(())
            }
            _ => self.seek(offset, line),
        }
    }

    /// Reads until at least `want` bytes are buffered or the input ends.
    fn fill(&mut self, want: usize) -> io::Result<()> {
        if self.pos > 0 {
            self.buf.copy_within(self.pos..self.end, 0);
            self.end -= self.pos;
            self.pos = 0;
        }
        while self.end < want && !self.eof {
            if self.end == self.buf.len() {
                let n = (self.buf.len() * 2).min(MAX_LINE + CHUNK);
                self.buf.resize(n, 0);
            }
            let n = self.input.read(&mut self.buf[self.end..])?;
            if n == 0 {
                self.eof = true;
            }
            self.end += n;
        }
        Ok(())
    }

    /// The next line, or `None` at the end of the input.
    pub fn next_line(&mut self) -> Result<Option<Line<'_>>, NotStreamable> {
        let mut scanned = 0;
        // Whether `buf[pos..pos + scanned]` is plain ASCII (no control characters but tab,
        // form feed and SUB): such a line needs neither a UTF-8 nor a control-character check.
        let mut plain = true;
        let cut = loop {
            let avail = &self.buf[self.pos + scanned..self.end];
            let (i, p) = crate::read::line_end(avail);
            plain &= p;
            if i < avail.len() {
                let at = self.pos + scanned + i;
                // A CR at the end of the buffer may be the first half of CR LF.
                if self.buf[at] == b'\r' && at + 1 == self.end && !self.eof {
                    let keep = at - self.pos;
                    self.fill(self.end - self.pos + CHUNK)?;
                    scanned = keep;
                    continue;
                }
                break Some(at);
            }
            if self.eof {
                break None;
            }
            let have = self.end - self.pos;
            if have > MAX_LINE {
                return Err(NotStreamable::LongLine { line: self.line + 1 });
            }
            scanned = have;
            self.fill(have + CHUNK)?;
        };
        let (text_end, next) = match cut {
            Some(at) => {
                let w = if self.buf[at] == b'\r' && self.buf.get(at + 1) == Some(&b'\n') && at + 1 < self.end {
                    2
                } else {
                    1
                };
                (at, at + w)
            }
            None if self.pos == self.end => return Ok(None),
            None => (self.end, self.end),
        };
        self.line += 1;
        let bytes = &self.buf[self.pos..text_end];
        let text = if plain {
            // SAFETY: `line_end` looked at every byte of `bytes` (they are the bytes before
            // the line end it found, over all refills: `plain` is the AND of its answers)
            // and found each to be a tab, form feed, SUB or in 0x20..=0x7E: all ASCII, and
            // ASCII bytes are valid UTF-8 on their own.
            // This skips a second pass over the line, which costs more than finding its end.
            unsafe { std::str::from_utf8_unchecked(bytes) }
        } else {
            std::str::from_utf8(bytes).map_err(|_| NotStreamable::NotUtf8 { line: self.line })?
        };
        if !plain {
            for c in text.chars() {
                if c == '\0' {
                    return Err(NotStreamable::Binary);
                }
                if c.is_control() && !matches!(c, '\t' | '\x0c' | '\x1a') {
                    self.controls += 1;
                }
            }
            if self.controls > 64 {
                return Err(NotStreamable::Binary);
            }
        }
        let start = self.offset;
        self.offset += (next - self.pos) as u64;
        self.pos = next;
        Ok(Some(Line { text, start, line: self.line, next: self.offset, ascii: plain }))
    }

    /// The buffered bytes from the next line's start on (any number of lines, the last
    /// perhaps cut short): for a reader that takes a line straight from the buffer and then
    /// moves past it with [`Lines::skip_plain`].
    #[inline]
    pub fn ahead(&self) -> &[u8] {
        &self.buf[self.pos..self.end]
    }

    /// Moves past the next line, whose text is the first `len` bytes of [`Lines::ahead`],
    /// all of them plain (see `read::line_end`; the caller has looked), followed by a CR
    /// or LF: what [`Lines::next_line`] would do, without looking at the text again (plain
    /// text is valid UTF-8 with no control character to count). Gives the line as
    /// `next_line` would, less its text. `None`, and nothing moves, when no line end
    /// follows, or it is a CR that a refill might show to be the first half of CR LF.
    #[inline]
    pub fn skip_plain(&mut self, len: usize) -> Option<Taken> {
        let t = self.peek_plain(len)?;
        self.skip_peeked(t);
        Some(t)
    }

    /// What [`Lines::skip_plain`]`(len)` would give, without moving: for a reader that
    /// looks at the line's text (in [`Lines::ahead`]) before it moves past it with
    /// [`Lines::skip_peeked`]. The same conditions (`None` likewise).
    #[inline]
    pub fn peek_plain(&self, len: usize) -> Option<Taken> {
        let at = self.pos + len;
        if at >= self.end {
            return None;
        }
        let w = match self.buf[at] {
            b'\n' => 1,
            b'\r' if at + 1 < self.end => 1 + usize::from(self.buf[at + 1] == b'\n'),
            b'\r' if self.eof => 1,
            _ => return None,
        };
        Some(Taken { start: self.offset, line: self.line + 1, next: self.offset + (len + w) as u64 })
    }

    /// Moves past the line [`Lines::peek_plain`] gave as `t` (nothing moved since): as
    /// [`Lines::skip_plain`] would.
    #[inline]
    pub fn skip_peeked(&mut self, t: Taken) {
        debug_assert_eq!((t.start, t.line), (self.offset, self.line + 1));
        self.pos += (t.next - t.start) as usize;
        self.offset = t.next;
        self.line = t.line;
    }

    /// Text bytes read so far (for progress).
    pub fn offset(&self) -> u64 {
        self.offset
    }
}

/// The line holding text offset `lo` of a file on disk: its number, start offset and text,
/// read line by line from the start (constant memory; for rendering a few diagnostics of a
/// streamed file without loading it).
pub fn line_at(path: &std::path::Path, lo: u32) -> Option<(u32, u64, String)> {
    let (input, _) = super::open(path).ok()?;
    let mut lines = Lines::new(input).ok()?;
    let at = u64::from(lo);
    let mut last = None;
    while let Ok(Some(l)) = lines.next_line() {
        let found = at < l.next || l.next == l.start + l.text.len() as u64;
        last = Some((l.line, l.start, l.text.to_string()));
        if found {
            break;
        }
    }
    last
}

/// The line ending used first in the file (LF when none), as `read::detect_line_ending`
/// finds it in the whole text.
pub fn first_line_ending(path: &std::path::Path) -> Result<crate::read::LineEnding, NotStreamable> {
    let mut f = std::fs::File::open(path)?;
    let mut buf = vec![0u8; 64 * 1024];
    let mut seen = 0usize;
    let mut cr = false;
    loop {
        let n = f.read(&mut buf)?;
        if n == 0 {
            return Ok(if cr { crate::read::LineEnding::Cr } else { crate::read::LineEnding::Lf });
        }
        for &b in &buf[..n] {
            if cr {
                return Ok(if b == b'\n' { crate::read::LineEnding::CrLf } else { crate::read::LineEnding::Cr });
            }
            match b {
                b'\n' => return Ok(crate::read::LineEnding::Lf),
                b'\r' => cr = true,
                _ => {}
            }
        }
        seen += n;
        if seen > MAX_LINE {
            return Err(NotStreamable::LongLine { line: 1 });
        }
    }
}

/// Whether the file starts with a UTF-8 byte-order mark (a translation's output then gets
/// one too).
pub fn has_bom(path: &std::path::Path) -> io::Result<bool> {
    let mut head = Vec::with_capacity(3);
    File::open(path)?.take(3).read_to_end(&mut head)?;
    Ok(head == b"\xEF\xBB\xBF")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn all(bytes: &[u8]) -> Vec<(String, u64, u32)> {
        let mut l = Lines::new(Input::Mem(io::Cursor::new(bytes.to_vec()))).unwrap();
        let mut v = Vec::new();
        while let Some(x) = l.next_line().unwrap() {
            v.push((x.text.to_string(), x.start, x.line));
        }
        v
    }

    #[test]
    fn splits_like_read_blocks() {
        for text in ["a\r\nb\rc\n\nd", "x\n", "\r\r\n\n", "", "one line", "é\r\nü\r"] {
            let want: Vec<_> =
                crate::read::blocks(text).map(|b| (b.text.to_string(), u64::from(b.start), b.line)).collect();
            assert_eq!(all(text.as_bytes()), want, "{text:?}");
        }
    }

    #[test]
    fn long_lines_and_buffer_edges() {
        let mut text = String::new();
        for i in 0..5000 {
            text.push_str(&"X".repeat(i % 700));
            text.push_str(if i % 3 == 0 {
                "\r\n"
            } else if i % 3 == 1 {
                "\r"
            } else {
                "\n"
            });
        }
        text.push_str(&"Y".repeat(CHUNK * 3));
        let want: Vec<_> =
            crate::read::blocks(&text).map(|b| (b.text.to_string(), u64::from(b.start), b.line)).collect();
        assert_eq!(all(text.as_bytes()), want);
    }

    #[test]
    fn bom_offsets_and_seek() {
        let mut l = Lines::new(Input::Mem(io::Cursor::new(b"\xEF\xBB\xBFab\ncd\nef".to_vec()))).unwrap();
        assert!(l.bom());
        assert_eq!(l.next_line().unwrap().map(|x| x.start), Some(0));
        assert_eq!(l.next_line().unwrap().map(|x| (x.text.to_string(), x.start)), Some(("cd".into(), 3)));
        l.seek(3, 2).unwrap();
        assert_eq!(l.next_line().unwrap().map(|x| (x.text.to_string(), x.line)), Some(("cd".into(), 2)));
    }

    #[test]
    fn control_characters_are_counted_like_the_whole_path() {
        // Lines of plain ASCII with tabs, form feeds, SUB, DEL, other controls and
        // multi-byte characters, over buffer refills: the same lines as `read::blocks`
        // and the same count of control characters as a per-character check.
        let mut state = 0x2545_F491_4F6C_DD1Du64;
        let mut next = |n: u64| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state % n
        };
        let pieces = ["G1 X1.5", "\t", "\x0c", "\x1a", "\x7f", "\x01", "\x1b", "é", "注", "\u{85}", "abcdefgh", " "];
        let ends = ["\n", "\r\n", "\r"];
        let mut text = String::new();
        let mut controls = 0u64;
        while text.len() < 3 * CHUNK {
            let p = pieces[next(pieces.len() as u64) as usize];
            if p.chars().any(|c| c.is_control() && !matches!(c, '\t' | '\x0c' | '\x1a')) {
                if controls >= 60 {
                    continue;
                }
                controls += 1;
            }
            text.push_str(p);
            if next(4) == 0 {
                text.push_str(ends[next(3) as usize]);
            }
        }
        let want: Vec<_> =
            crate::read::blocks(&text).map(|b| (b.text.to_string(), u64::from(b.start), b.line)).collect();
        let mut l = Lines::new(Input::Mem(io::Cursor::new(text.as_bytes().to_vec()))).unwrap();
        let mut got = Vec::new();
        while let Some(x) = l.next_line().unwrap() {
            got.push((x.text.to_string(), x.start, x.line));
        }
        assert_eq!(got, want);
        assert_eq!(l.controls, controls);
        assert!(controls > 10);
    }

    #[test]
    fn refuses_what_the_whole_path_must_read() {
        let mut l = Lines::new(Input::Mem(io::Cursor::new(b"ok\n\xff\xfe\n".to_vec()))).unwrap();
        assert!(l.next_line().is_ok());
        assert!(matches!(l.next_line(), Err(NotStreamable::NotUtf8 { line: 2 })));
        let mut l = Lines::new(Input::Mem(io::Cursor::new(b"a\0b".to_vec()))).unwrap();
        assert!(matches!(l.next_line(), Err(NotStreamable::Binary)));
    }
}
