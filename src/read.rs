//! Reading: bytes to text (any encoding, losslessly), text to blocks (any line end), and
//! the normalisation of full-width and look-alike characters with warnings that point at
//! the original text.

use crate::diag::Diagnostic;
use crate::span::{FileId, Span};
use encoding_rs::Encoding;
use std::borrow::Cow;

/// The line ending a file uses, remembered so output can match it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LineEnding {
    Lf,
    CrLf,
    Cr,
}

impl LineEnding {
    pub fn as_str(self) -> &'static str {
        match self {
            LineEnding::Lf => "\n",
            LineEnding::CrLf => "\r\n",
            LineEnding::Cr => "\r",
        }
    }
}

/// A decoded file.
#[derive(Clone, Debug)]
pub struct Decoded {
    pub text: String,
    pub encoding: &'static Encoding,
    /// The file started with a UTF-8 byte-order mark (dropped from `text`).
    pub bom: bool,
    pub line_ending: LineEnding,
}

/// Decodes a file. `forced` is `--encoding`; otherwise UTF-8 when the bytes are valid
/// UTF-8, else the legacy encoding chardetng guesses (GBK, Shift-JIS, windows-1250, …).
/// If the guess cannot decode every byte, windows-1252 is used, which maps every byte to a
/// character and back, so no comment byte is ever lost.
pub fn decode(bytes: &[u8], forced: Option<&'static Encoding>) -> Decoded {
    let (bom, body) = match bytes.strip_prefix(b"\xEF\xBB\xBF") {
        Some(rest) => (true, rest),
        None => (false, bytes),
    };
    let encoding = match forced {
        Some(e) => e,
        None if std::str::from_utf8(body).is_ok() => encoding_rs::UTF_8,
        None => {
            let mut det = chardetng::EncodingDetector::new(chardetng::Iso2022JpDetection::Deny);
            det.feed(body, true);
            det.guess(None, chardetng::Utf8Detection::Deny)
        }
    };
    let (text, encoding) = match encoding.decode_without_bom_handling_and_without_replacement(body) {
        Some(t) if round_trips(&t, encoding, body) => (t.into_owned(), encoding),
        _ => {
            let (t, _) = encoding_rs::WINDOWS_1252.decode_without_bom_handling(body);
            (t.into_owned(), encoding_rs::WINDOWS_1252)
        }
    };
    let line_ending = detect_line_ending(&text);
    Decoded { text, encoding, bom, line_ending }
}

/// Some legacy codecs decode two byte sequences to the same character; only accept an
/// encoding that gives back the exact bytes.
fn round_trips(text: &str, enc: &'static Encoding, bytes: &[u8]) -> bool {
    if enc == encoding_rs::UTF_8 {
        return true;
    }
    let (back, _, unmappable) = enc.encode(text);
    !unmappable && back.as_ref() == bytes
}

/// Encodes text for output in the file's original encoding.
pub fn encode(text: &str, enc: &'static Encoding, bom: bool) -> Vec<u8> {
    let (bytes, _, _) = enc.encode(text);
    let mut out = Vec::with_capacity(bytes.len() + 3);
    if bom && enc == encoding_rs::UTF_8 {
        out.extend_from_slice(b"\xEF\xBB\xBF");
    }
    out.extend_from_slice(&bytes);
    out
}

/// The line ending used first in the text (LF when there is none).
pub fn detect_line_ending(text: &str) -> LineEnding {
    let b = text.as_bytes();
    match b.iter().position(|&c| c == b'\n' || c == b'\r') {
        Some(i) if b[i] == b'\r' && b.get(i + 1) == Some(&b'\n') => LineEnding::CrLf,
        Some(i) if b[i] == b'\r' => LineEnding::Cr,
        _ => LineEnding::Lf,
    }
}

/// Whether the text looks like binary data rather than a program (NUL bytes, or many
/// control characters). Returns the offset of the first offending character.
pub fn binary_garbage(text: &str) -> Option<u32> {
    let mut controls = 0usize;
    let mut first = None;
    for (i, c) in text.char_indices() {
        let bad = c == '\0' || (c.is_control() && !matches!(c, '\n' | '\r' | '\t' | '\x0c' | '\x1a'));
        if bad {
            controls += 1;
            first.get_or_insert(i as u32);
            if c == '\0' {
                return first;
            }
        }
    }
    let chars = text.len().max(1);
    if controls * 20 > chars || controls > 64 {
        first
    } else {
        None
    }
}

/// One physical line of the file: a block before dialect-specific splitting.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RawBlock<'a> {
    /// The line without its line end.
    pub text: &'a str,
    /// Byte offset of `text` in the file.
    pub start: u32,
    /// 1-based line number.
    pub line: u32,
}

/// Splits text into lines on LF, CR LF and lone CR.
pub fn blocks(text: &str) -> Blocks<'_> {
    Blocks { text, pos: 0, line: 0 }
}

pub struct Blocks<'a> {
    text: &'a str,
    pos: usize,
    line: u32,
}

impl<'a> Iterator for Blocks<'a> {
    type Item = RawBlock<'a>;

    fn next(&mut self) -> Option<RawBlock<'a>> {
        if self.pos >= self.text.len() {
            return None;
        }
        let rest = &self.text.as_bytes()[self.pos..];
        let end = find2(rest, b'\n', b'\r').unwrap_or(rest.len());
        let start = self.pos;
        let mut next = start + end;
        if next < self.text.len() {
            next += if rest[end] == b'\r' && rest.get(end + 1) == Some(&b'\n') { 2 } else { 1 };
        }
        self.pos = next;
        self.line += 1;
        Some(RawBlock { text: &self.text[start..start + end], start: start as u32, line: self.line })
    }
}

/// Eight bytes as one word (the slice has exactly eight).
#[inline]
fn word8(c: &[u8]) -> u64 {
    c.try_into().map_or(0, u64::from_le_bytes)
}

const LO: u64 = 0x0101_0101_0101_0101;
const HI: u64 = 0x8080_8080_8080_8080;

/// The end of the first line of `b` (the index of its first CR or LF, else `b.len()`), and
/// whether every byte before it is plain: printable ASCII, tab, form feed or SUB. Such a
/// line is valid UTF-8 and holds no control character that the binary-data check counts.
/// Eight bytes are tested at a time (a word with no byte below 0x20 and none at or above
/// 0x7F cannot hold a line end or anything that is not plain); only words that may, are
/// looked at byte by byte.
pub fn line_end(b: &[u8]) -> (usize, bool) {
    let mut plain = true;
    let mut chunks = b.chunks_exact(8);
    let mut at = 0;
    for c in &mut chunks {
        let w = word8(c);
        // Some byte < 0x20 (the classic "has less than" test), or some byte >= 0x7F.
        let special = (w.wrapping_sub(LO * 0x20) & !w & HI) | ((w.wrapping_add(LO) | w) & HI);
        if special != 0 {
            // The lowest flagged byte is flagged rightly (a borrow or carry only reaches the
            // bytes above it): when it is the line end, as at the end of nearly every line,
            // that is all (the bytes before it are plain).
            let k = (special.trailing_zeros() / 8) as usize;
            let x = (w >> (8 * k)) as u8;
            if x == b'\n' || x == b'\r' {
                return (at + k, plain);
            }
            for (k, &x) in c.iter().enumerate().skip(k) {
                match x {
                    b'\n' | b'\r' => return (at + k, plain),
                    b'\t' | 0x0c | 0x1a | 0x20..=0x7e => {}
                    _ => plain = false,
                }
            }
        }
        at += 8;
    }
    for (k, &x) in chunks.remainder().iter().enumerate() {
        match x {
            b'\n' | b'\r' => return (at + k, plain),
            b'\t' | 0x0c | 0x1a | 0x20..=0x7e => {}
            _ => plain = false,
        }
    }
    (b.len(), plain)
}

/// A plain line as a dialect's index-only reader found it straight in the read buffer
/// (`sinumerik::skeleton_bytes`, `fanuc::skeleton_bytes`), all offsets into the line: its
/// text is `len` bytes, all plain (see [`line_end`]), followed by a CR or LF; its block is
/// `lo..hi`; its block number, when it has one, is `number.0` written at `number.1..number.2`;
/// `words` tells whether it has words besides the number.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SkelLine {
    pub len: usize,
    pub lo: usize,
    pub hi: usize,
    pub number: Option<(u32, usize, usize)>,
    pub words: bool,
}

/// The table of a byte automaton for [`run_automaton`]: `step(state, byte)` for every one of
/// `$rows` states and every byte, at `state << 8 | byte`, as the next state's row
/// (`next << 8`). A macro, not a function: a `static` table is built in a const block, which
/// cannot call the dialects' `step` through a function pointer.
macro_rules! automaton_table {
    ($rows:expr, $step:ident) => {{
        let mut t = [0u16; $rows * 256];
        let mut s = 0;
        while s < $rows {
            let mut c = 0;
            while c < 256 {
                t[s * 256 + c] = ($step(s as u8, c as u8) as u16) << 8;
                c += 1;
            }
            s += 1;
        }
        t
    }};
}
pub(crate) use automaton_table;

/// Runs a byte automaton (the dialects' `skeleton_bytes`) over `b` from row `row`: `step`
/// holds at `row | byte` the next state's row (`state << 8`), or a value at or above
/// `stop` where the automaton stops. Gives where it stopped and the value there, or `None`
/// when `b` ends first. `ROWS` is a power of two, so a masked index needs no bounds check;
/// eight bytes are stepped at a time while there are (no bounds check per byte either).
#[inline(always)]
pub fn run_automaton<const ROWS: usize>(
    step: &[u16; ROWS],
    b: &[u8],
    mut row: usize,
    stop: u16,
) -> Option<(usize, u16)> {
    let mut chunks = b.chunks_exact(8);
    let mut at = 0;
    for chunk in &mut chunks {
        for (k, &c) in chunk.iter().enumerate() {
            let next = step[(row | usize::from(c)) & (ROWS - 1)];
            if next >= stop {
                return Some((at + k, next));
            }
            row = usize::from(next);
        }
        at += 8;
    }
    for (k, &c) in chunks.remainder().iter().enumerate() {
        let next = step[(row | usize::from(c)) & (ROWS - 1)];
        if next >= stop {
            return Some((at + k, next));
        }
        row = usize::from(next);
    }
    None
}

/// The index of the first `x` or `y` in `b` (eight bytes at a time).
pub fn find2(b: &[u8], x: u8, y: u8) -> Option<usize> {
    let (sx, sy) = (LO * u64::from(x), LO * u64::from(y));
    let zero = |v: u64| v.wrapping_sub(LO) & !v & HI != 0;
    let mut chunks = b.chunks_exact(8);
    let mut at = 0;
    for c in &mut chunks {
        let w = word8(c);
        if zero(w ^ sx) || zero(w ^ sy) {
            return c.iter().position(|&v| v == x || v == y).map(|k| at + k);
        }
        at += 8;
    }
    chunks.remainder().iter().position(|&v| v == x || v == y).map(|k| at + k)
}

/// `s.trim_start()`, byte by byte while the text is ASCII (the Unicode tables are asked
/// only from the first non-ASCII character on).
pub fn trim_start(s: &str) -> &str {
    let b = s.as_bytes();
    let mut i = 0;
    while i < b.len() && ascii_space(b[i]) {
        i += 1;
    }
    match b.get(i) {
        Some(c) if *c >= 0x80 => s[i..].trim_start(),
        _ => &s[i..],
    }
}

/// `s.trim_end()`, byte by byte while the text is ASCII.
pub fn trim_end(s: &str) -> &str {
    let b = s.as_bytes();
    let mut j = b.len();
    while j > 0 && ascii_space(b[j - 1]) {
        j -= 1;
    }
    match j.checked_sub(1).map(|k| b[k]) {
        Some(c) if c >= 0x80 => s[..j].trim_end(),
        _ => &s[..j],
    }
}

/// `s.trim()` (see [`trim_start`]).
pub fn trim(s: &str) -> &str {
    trim_end(trim_start(s))
}

/// The ASCII characters `char::is_whitespace` accepts (vertical tab included).
fn ascii_space(c: u8) -> bool {
    matches!(c, b' ' | b'\t' | b'\n' | 0x0b | 0x0c | b'\r')
}

/// Whether `b` has a letter O or o (eight bytes at a time).
fn has_letter_o(b: &[u8]) -> bool {
    let mut chunks = b.chunks_exact(8);
    for c in &mut chunks {
        // Setting bit 5 maps exactly `O` and `o` to `o`; then look for a zero byte.
        let v = (word8(c) | (LO * 0x20)) ^ (LO * u64::from(b'o'));
        if v.wrapping_sub(LO) & !v & HI != 0 {
            return true;
        }
    }
    chunks.remainder().iter().any(|&c| c | 0x20 == b'o')
}

/// The fast readers' digit run: skips the ASCII digits of `b` from `i` and returns where
/// they end; with `values`, each is appended to `mant` (wrapping: callers bound the digit
/// count before they use the value). Inlined, so `values` is a constant at each caller.
#[inline(always)]
pub fn digit_run(b: &[u8], mut i: usize, values: bool, mant: &mut u64) -> usize {
    while i < b.len() {
        let d = b[i].wrapping_sub(b'0');
        if d > 9 {
            break;
        }
        if values {
            *mant = mant.wrapping_mul(10).wrapping_add(u64::from(d));
        }
        i += 1;
    }
    i
}

/// The value of a plain decimal literal: ASCII digits with at most one point and at least
/// one digit (`12`, `-` and exponents excluded: `1.5`, `.5`, `7.`), or `None` for any
/// other text. Exactly `s.parse::<f64>()` for such text: when the digits, read as a whole
/// number, are below 2^53 and at most 22 follow the point, the number and the power of ten
/// are both exact doubles and one IEEE division rounds their quotient correctly (Clinger's
/// fast path); longer literals are left to the standard parser.
pub fn decimal(s: &str) -> Option<f64> {
    let b = s.as_bytes();
    let mut mant: u64 = 0;
    let mut digits = 0usize;
    let mut frac: Option<usize> = None;
    for (i, &c) in b.iter().enumerate() {
        match c {
            b'0'..=b'9' => {
                // Leading zeros do not count towards the 19 digits a u64 holds.
                if mant != 0 || c != b'0' {
                    digits += 1;
                }
                if digits <= 19 {
                    mant = mant.wrapping_mul(10).wrapping_add(u64::from(c - b'0'));
                }
            }
            b'.' if frac.is_none() => frac = Some(i),
            _ => return None,
        }
    }
    let k = frac.map_or(0, |p| b.len() - p - 1);
    if b.len() == usize::from(frac.is_some()) {
        return None;
    }
    if digits <= 15 {
        // digits <= 15: mant < 10^15 < 2^53.
        if let Some(v) = scaled(mant, k) {
            return Some(v);
        }
    }
    s.parse().ok()
}

/// `mant / 10^k`, correctly rounded, when that is one exact division: `mant` below 2^53
/// and `k` at most 22 (else `None`). Equal to parsing the decimal literal whose digits
/// are `mant` with `k` of them after the point.
#[inline]
pub fn scaled(mant: u64, k: usize) -> Option<f64> {
    if mant >= 1 << 53 {
        return None;
    }
    POW10.get(k).map(|p| mant as f64 / p)
}

/// 10^0 ..= 10^22: every one an exact double.
const POW10: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20,
    1e21, 1e22,
];

/// [`scaled`] for the fast readers: the same value, the conversion done as a signed one
/// (one instruction; below 2^53 it gives what `as f64` gives).
#[inline(always)]
pub fn exact(mant: u64, k: usize) -> Option<f64> {
    if mant >= 1 << 53 {
        return None;
    }
    let v = mant as i64 as f64;
    // A whole number (`F800`, `G1`) needs no division (x / 1 is x): a division waits
    // several times as long as any other step of a word.
    if k == 0 {
        return Some(v);
    }
    POW10.get(k).map(|p| v / p)
}

/// [`exact`] for a literal the caller knows to be short (the quick readers': at most 14
/// digits, so below 2^53, and at most seven after the point): the same conversion and the
/// same division, without the checks.
#[inline(always)]
pub fn exact_short(mant: u64, k: usize) -> f64 {
    debug_assert!(mant < 1 << 53 && k < 8);
    let v = mant as i64 as f64;
    if k == 0 {
        v
    } else {
        v / POW10[k & 7]
    }
}

/// How a dialect writes comments, so normalisation leaves comment text untouched.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CommentStyle {
    /// Siemens: `;` to the end of the line; `"…"` strings are also left alone.
    Semicolon,
    /// FANUC: `( … )`.
    Parens,
}

/// A block ready for the grammar: ASCII-normalised text and the way back to the original.
#[derive(Clone, Debug)]
pub struct Normalised<'a> {
    pub text: Cow<'a, str>,
    /// Byte offset in the file of the start of the raw block.
    pub start: u32,
    /// For a changed block: the file offset of every byte of `text` (plus one past the end).
    map: Option<Vec<u32>>,
    /// Full-width characters replaced, as file spans (merged runs).
    pub full_width: Vec<Span>,
    /// Letter O read as digit 0 in a G word (`GO`, `G0O`), as file spans.
    pub letter_o: Vec<Span>,
}

impl<'a> Normalised<'a> {
    /// What [`normalise`] gives for a line it leaves as it is, without looking at the line:
    /// for a caller that knows so (an ASCII line, whose reader declines every letter O in
    /// code: on ASCII text normalising changes only a letter O in a G word).
    pub fn unchanged(raw: &RawBlock<'a>) -> Normalised<'a> {
        Normalised { text: Cow::Borrowed(raw.text), start: raw.start, map: None, full_width: vec![], letter_o: vec![] }
    }
}

impl Normalised<'_> {
    /// A block whose text was rewritten after normalising (Siemens macros): `map` gives the
    /// file offset of every byte of `text` plus one past the end; the warnings stay.
    pub fn rewritten(&self, text: String, map: Vec<u32>) -> Normalised<'static> {
        debug_assert_eq!(map.len(), text.len() + 1);
        Normalised {
            text: Cow::Owned(text),
            start: self.start,
            map: Some(map),
            full_width: self.full_width.clone(),
            letter_o: self.letter_o.clone(),
        }
    }

    /// File offset of byte `pos` of the normalised text.
    #[inline]
    pub fn offset(&self, pos: usize) -> u32 {
        match &self.map {
            Some(m) => m[pos.min(m.len() - 1)],
            None => self.start + pos as u32,
        }
    }

    /// File span of the normalised byte range `lo..hi`.
    #[inline]
    pub fn span(&self, lo: usize, hi: usize) -> Span {
        if self.map.is_none() {
            // Unchanged text (nearly every block): offsets are the file's, shifted.
            let from = self.start + lo as u32;
            return Span::new(from, if hi > lo { self.start + hi as u32 } else { from });
        }
        if hi > lo {
            // The end is one past the last byte: map the last byte and step over it, so a
            // full-width character ends where it ends in the file.
            let last = self.offset(hi - 1);
            let width = match &self.map {
                Some(m) => m.get(hi).copied().unwrap_or(last + 1).max(last + 1) - last,
                None => 1,
            };
            Span::new(self.offset(lo), last + width)
        } else {
            let o = self.offset(lo);
            Span::new(o, o)
        }
    }

    /// Warnings for what normalisation changed (NC110 full-width, NC111 letter O).
    pub fn warnings(&self, file: FileId) -> Vec<Diagnostic> {
        let mut v = Vec::new();
        if let (Some(first), Some(last)) = (self.full_width.first(), self.full_width.last()) {
            v.push(
                Diagnostic::warning("NC110", "full-width characters read as ASCII")
                    .primary(file, first.to(*last), "written in full-width form")
                    .note("no control accepts full-width characters; they were read as their ASCII forms")
                    .hint("retype the block in ASCII (half-width) characters"),
            );
        }
        for s in &self.letter_o {
            v.push(
                Diagnostic::warning("NC111", "letter O in a G word read as digit 0")
                    .primary(file, *s, "letter O here")
                    .hint("write the digit zero: G0, G00"),
            );
        }
        v
    }
}

/// Normalises one block: full-width ASCII forms (U+FF01..U+FF5E) and the ideographic space
/// become ASCII outside comments and strings; a letter O inside a G word becomes 0.
pub fn normalise<'a>(raw: &RawBlock<'a>, style: CommentStyle) -> Normalised<'a> {
    // ASCII lines (nearly all of a CAM program) are checked at memory speed.
    let needs_width =
        !raw.text.is_ascii() && raw.text.chars().any(|c| ('\u{FF01}'..='\u{FF5E}').contains(&c) || c == '\u{3000}');
    let mut n =
        Normalised { text: Cow::Borrowed(raw.text), start: raw.start, map: None, full_width: vec![], letter_o: vec![] };
    if needs_width {
        let mut out = String::with_capacity(raw.text.len());
        let mut map = Vec::with_capacity(raw.text.len() + 1);
        let mut state = Zone::Code;
        for (i, c) in raw.text.char_indices() {
            let off = raw.start + i as u32;
            let ascii = match c {
                '\u{FF01}'..='\u{FF5E}' => char::from_u32(c as u32 - 0xFEE0),
                '\u{3000}' => Some(' '),
                _ => None,
            };
            // Delimiters count in either form; contents of comments and strings stay as written.
            let seen = ascii.unwrap_or(c);
            let convert = match state {
                Zone::Code => true,
                Zone::Paren => seen == ')',
                Zone::Quote => seen == '"',
                Zone::Line => false,
            };
            let ch = match (convert, ascii) {
                (true, Some(a)) => {
                    push_merged(&mut n.full_width, Span::new(off, off + c.len_utf8() as u32));
                    a
                }
                _ => c,
            };
            state = next_zone(state, ch, convert, style);
            for _ in 0..ch.len_utf8() {
                map.push(off);
            }
            out.push(ch);
        }
        map.push(raw.start + raw.text.len() as u32);
        if !n.full_width.is_empty() {
            n.text = Cow::Owned(out);
            n.map = Some(map);
        }
    }
    fix_letter_o(&mut n, style);
    n
}

#[derive(Clone, Copy, PartialEq)]
enum Zone {
    Code,
    Paren,
    Quote,
    Line,
}

fn next_zone(state: Zone, ch: char, converted: bool, style: CommentStyle) -> Zone {
    match (state, ch, style) {
        (Zone::Code, '(', CommentStyle::Parens) => Zone::Paren,
        (Zone::Code, ';', CommentStyle::Semicolon) => Zone::Line,
        (Zone::Code, '"', CommentStyle::Semicolon) => Zone::Quote,
        (Zone::Paren, ')', _) if converted => Zone::Code,
        (Zone::Quote, '"', _) if converted => Zone::Code,
        (s, _, _) => s,
    }
}

fn push_merged(spans: &mut Vec<Span>, s: Span) {
    match spans.last_mut() {
        Some(last) if last.hi == s.lo => last.hi = s.hi,
        _ => spans.push(s),
    }
}

/// `GO X…`, `GO1`, `G0O`: a G followed by digits and letter O's (at least one O), standing
/// alone as a word. `GOTO`, `GOTOF` and names like `GOAL` are left alone (a letter follows).
fn fix_letter_o(n: &mut Normalised<'_>, style: CommentStyle) {
    let bytes = n.text.as_bytes();
    // Nearly every block has no letter O at all: nothing to look for.
    if !has_letter_o(bytes) {
        return;
    }
    let mut hits: Vec<(usize, usize)> = Vec::new();
    let mut zone = Zone::Code;
    let mut i = 0;
    while i < bytes.len() {
        let c = bytes[i];
        if zone != Zone::Code {
            zone = next_zone(zone, c as char, true, style);
            i += 1;
            continue;
        }
        let prev_word = i > 0 && (bytes[i - 1].is_ascii_alphanumeric() || bytes[i - 1] == b'_' || bytes[i - 1] == b'$');
        if (c == b'G' || c == b'g') && !prev_word {
            let mut j = i + 1;
            let mut has_o = false;
            while j < bytes.len() && (bytes[j].is_ascii_digit() || bytes[j] == b'O' || bytes[j] == b'o') {
                has_o |= !bytes[j].is_ascii_digit();
                j += 1;
            }
            let ends = j == bytes.len() || !(bytes[j].is_ascii_alphabetic() || bytes[j] == b'_');
            if has_o && ends {
                hits.push((i + 1, j));
            }
            i = j.max(i + 1);
            continue;
        }
        zone = next_zone(zone, c as char, true, style);
        i += 1;
    }
    if hits.is_empty() {
        return;
    }
    let mut text = n.text.to_string().into_bytes();
    for &(lo, hi) in &hits {
        for b in &mut text[lo..hi] {
            if *b == b'O' || *b == b'o' {
                *b = b'0';
            }
        }
        let s = n.span(lo, hi);
        n.letter_o.push(s);
    }
    // Only ASCII letters were replaced by ASCII digits: still valid UTF-8.
    n.text = Cow::Owned(String::from_utf8(text).unwrap_or_default());
}

#[cfg(test)]
#[path = "read_tests.rs"]
mod tests;
