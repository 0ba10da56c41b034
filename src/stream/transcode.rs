//! Streaming files in legacy encodings (GBK, Shift-JIS, windows-1252, cp1250, …): the
//! encoding is decided exactly as `read::decode` decides it, but in passes over the file in
//! chunks; the text is then decoded into a temporary UTF-8 copy that the stream reads in
//! place of the source, and a UTF-8 output is encoded back at the end.
//!
//! Spans of the whole-file path are byte offsets into the DECODED text (BOM dropped), so a
//! stream over the copy gives the same spans, lines and columns; diagnostics are rendered
//! from the copy. The copy costs about the file's size on disk (in the system temp folder)
//! and is removed when its [`TempCopy`] is dropped. UTF-8 files never get here.

use super::lines::{has_bom, NotStreamable};
use crate::read::LineEnding;
use encoding_rs::{CoderResult, DecoderResult, EncoderResult, Encoding};
use std::fs::File;
use std::io::{self, Read, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU32, Ordering};

/// Bytes read per chunk.
const CHUNK: usize = 64 * 1024;
const BOM: &[u8] = b"\xEF\xBB\xBF";

/// What `read::decode` decides for a file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Detected {
    pub encoding: &'static Encoding,
    /// The file starts with a UTF-8 byte-order mark (dropped from the decoded text).
    pub bom: bool,
    pub line_ending: LineEnding,
}

/// Calls `f` with the file's body (after a UTF-8 BOM) in chunks of `chunk` bytes, then
/// once with an empty slice and `last`. Returns whether there was a BOM.
fn chunks(path: &Path, chunk: usize, f: &mut dyn FnMut(&[u8], bool) -> io::Result<()>) -> io::Result<bool> {
    let mut file = File::open(path)?;
    let mut head = [0u8; 3];
    let mut got = 0;
    while got < 3 {
        let n = file.read(&mut head[got..])?;
        if n == 0 {
            break;
        }
        got += n;
    }
    let bom = &head[..got] == BOM;
    if !bom {
        for piece in head[..got].chunks(chunk.max(1)) {
            f(piece, false)?;
        }
    }
    let mut buf = vec![0u8; chunk.max(1)];
    loop {
        let n = file.read(&mut buf)?;
        if n == 0 {
            break;
        }
        f(&buf[..n], false)?;
    }
    f(&[], true)?;
    Ok(bom)
}

/// The first line ending in text fed piece by piece (as `read::detect_line_ending`).
#[derive(Default)]
struct EolFinder {
    found: Option<LineEnding>,
    cr: bool,
}

impl EolFinder {
    fn feed(&mut self, b: &[u8]) {
        if self.found.is_some() {
            return;
        }
        if self.cr {
            if let Some(&c) = b.first() {
                self.found = Some(if c == b'\n' { LineEnding::CrLf } else { LineEnding::Cr });
            }
            return;
        }
        match b.iter().position(|&c| c == b'\n' || c == b'\r') {
            Some(i) if b[i] == b'\n' => self.found = Some(LineEnding::Lf),
            Some(i) => match b.get(i + 1) {
                Some(&b'\n') => self.found = Some(LineEnding::CrLf),
                Some(_) => self.found = Some(LineEnding::Cr),
                None => self.cr = true,
            },
            None => {}
        }
    }

    fn end(&self) -> LineEnding {
        match (self.found, self.cr) {
            (Some(e), _) => e,
            (None, true) => LineEnding::Cr,
            (None, false) => LineEnding::Lf,
        }
    }
}

fn bad(msg: &str) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidData, msg.to_string())
}

/// [`detect_chunked`] with the default chunk size.
pub fn detect(path: &Path, forced: Option<&'static Encoding>) -> Result<Detected, NotStreamable> {
    detect_chunked(path, forced, CHUNK)
}

/// What `read::decode(bytes, forced)` decides for the file, in bounded memory: a pass for
/// UTF-8 validity and chardetng's guess (when not forced), a pass decoding without
/// replacement and re-encoding to check the bytes come back, else windows-1252.
#[doc(hidden)]
pub fn detect_chunked(path: &Path, forced: Option<&'static Encoding>, chunk: usize) -> Result<Detected, NotStreamable> {
    let encoding = match forced {
        Some(e) => e,
        None => {
            let mut det = chardetng::EncodingDetector::new(chardetng::Iso2022JpDetection::Deny);
            let mut valid = true;
            let mut carry: Vec<u8> = Vec::new();
            let mut eol = EolFinder::default();
            chunks(path, chunk, &mut |b, last| {
                det.feed(b, last);
                eol.feed(b);
                if valid {
                    carry.extend_from_slice(b);
                    match std::str::from_utf8(&carry) {
                        Ok(_) => carry.clear(),
                        // An incomplete sequence at the end may finish in the next chunk.
                        Err(e) if e.error_len().is_none() && !last => {
                            carry.drain(..e.valid_up_to());
                        }
                        Err(_) => valid = false,
                    }
                }
                Ok(())
            })?;
            if valid {
                let bom = has_bom(path)?;
                return Ok(Detected { encoding: encoding_rs::UTF_8, bom, line_ending: eol.end() });
            }
            det.guess(None, chardetng::Utf8Detection::Deny)
        }
    };
    if let Some(line_ending) = round_trip(path, encoding, chunk)? {
        let bom = has_bom(path)?;
        return Ok(Detected { encoding, bom, line_ending });
    }
    // windows-1252 maps every byte and keeps ASCII: the line ending is the bytes' own.
    let mut eol = EolFinder::default();
    let bom = chunks(path, chunk, &mut |b, _| {
        eol.feed(b);
        Ok(())
    })?;
    Ok(Detected { encoding: encoding_rs::WINDOWS_1252, bom, line_ending: eol.end() })
}

/// Whether the body decodes in `enc` without replacement and encodes back to the same
/// bytes (`read::round_trips`); the decoded text's first line ending when it does.
fn round_trip(path: &Path, enc: &'static Encoding, chunk: usize) -> io::Result<Option<LineEnding>> {
    let mut dec = enc.new_decoder_without_bom_handling();
    // `Encoding::encode` writes in the output encoding (UTF-16 text comes out as UTF-8).
    let mut encoder = enc.output_encoding().new_encoder();
    let check = enc != encoding_rs::UTF_8;
    let mut pending: Vec<u8> = Vec::new(); // source bytes not yet matched
    let mut ahead: Vec<u8> = Vec::new(); // re-encoded bytes not yet matched
    let mut text = vec![0u8; chunk.max(16) * 3 + 16];
    let mut back = vec![0u8; chunk.max(16) * 3 + 16];
    let mut eol = EolFinder::default();
    let mut ok = true;
    let r = chunks(path, chunk, &mut |b, last| {
        if !ok {
            return Ok(());
        }
        if check {
            pending.extend_from_slice(b);
        }
        let mut src = b;
        loop {
            let (res, read, written) = dec.decode_to_utf8_without_replacement(src, &mut text, last);
            src = &src[read..];
            if let DecoderResult::Malformed(..) = res {
                ok = false;
                return Ok(());
            }
            let s = std::str::from_utf8(&text[..written]).map_err(|_| bad("decoder wrote bad UTF-8"))?;
            eol.feed(s.as_bytes());
            if check {
                let mut s = s;
                loop {
                    let done_all = last && src.is_empty() && matches!(res, DecoderResult::InputEmpty);
                    let (er, r, w) = encoder.encode_from_utf8_without_replacement(s, &mut back, done_all);
                    s = &s[r..];
                    if let EncoderResult::Unmappable(_) = er {
                        ok = false;
                        return Ok(());
                    }
                    ahead.extend_from_slice(&back[..w]);
                    let n = ahead.len().min(pending.len());
                    if ahead[..n] != pending[..n] {
                        ok = false;
                        return Ok(());
                    }
                    ahead.drain(..n);
                    pending.drain(..n);
                    if matches!(er, EncoderResult::InputEmpty) {
                        break;
                    }
                }
            }
            if matches!(res, DecoderResult::InputEmpty) {
                break;
            }
        }
        Ok(())
    });
    r?;
    Ok((ok && pending.is_empty() && ahead.is_empty()).then(|| eol.end()))
}

/// Writes the file's text, decoded as `det` says, as UTF-8 without a BOM into `out`.
pub fn decode_to(path: &Path, det: &Detected, out: &mut dyn Write) -> io::Result<()> {
    let mut dec = det.encoding.new_decoder_without_bom_handling();
    let mut text = vec![0u8; CHUNK * 3 + 16];
    chunks(path, CHUNK, &mut |b, last| {
        let mut src = b;
        loop {
            let (res, read, written, _) = dec.decode_to_utf8(src, &mut text, last);
            src = &src[read..];
            out.write_all(&text[..written])?;
            if matches!(res, CoderResult::InputEmpty) {
                return Ok(());
            }
        }
    })?;
    Ok(())
}

/// Encodes the UTF-8 file `utf8` into `out` in `enc` (as `read::encode`: unmappable
/// characters as numeric character references, a BOM only for UTF-8 output, when `bom`).
/// A byte-order mark at the start of `utf8` is not text (a stream that keeps its source's
/// mark wrote it): it is dropped.
pub fn encode_to(utf8: &Path, enc: &'static Encoding, bom: bool, out: &mut dyn Write) -> io::Result<()> {
    // `read::encode` asks for UTF-8 itself: UTF-16 text is written as UTF-8 without one.
    if bom && enc == encoding_rs::UTF_8 {
        out.write_all(BOM)?;
    }
    let enc = enc.output_encoding();
    let mut encoder = enc.new_encoder();
    let mut carry: Vec<u8> = Vec::new();
    let mut back = vec![0u8; CHUNK * 4 + 64];
    let mut file = File::open(utf8)?;
    let mut buf = vec![0u8; CHUNK];
    let mut start = true;
    loop {
        let n = file.read(&mut buf)?;
        let last = n == 0;
        carry.extend_from_slice(&buf[..n]);
        if start {
            if carry.len() < BOM.len() && !last && BOM.starts_with(&carry) {
                continue;
            }
            if carry.starts_with(BOM) {
                carry.drain(..BOM.len());
            }
            start = false;
        }
        let upto = match std::str::from_utf8(&carry) {
            Ok(s) => s.len(),
            Err(e) if e.error_len().is_none() && !last => e.valid_up_to(),
            Err(_) => return Err(bad("the translation is not UTF-8")),
        };
        let s = std::str::from_utf8(&carry[..upto]).map_err(|_| bad("the translation is not UTF-8"))?;
        let mut s = s;
        loop {
            let (res, r, w, _) = encoder.encode_from_utf8(s, &mut back, last);
            s = &s[r..];
            out.write_all(&back[..w])?;
            if matches!(res, CoderResult::InputEmpty) {
                break;
            }
        }
        carry.drain(..upto);
        if last {
            return Ok(());
        }
    }
}

/// A decoded UTF-8 copy of a file, in a folder of its own under the system temp folder,
/// under the file's own name (its extension tells the dialect). Removed on drop.
#[derive(Debug)]
pub struct TempCopy {
    dir: PathBuf,
    path: PathBuf,
    pub detected: Detected,
}

impl TempCopy {
    /// The copy's path (read it in place of the source).
    pub fn path(&self) -> &Path {
        &self.path
    }
}

impl Drop for TempCopy {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.path);
        let _ = std::fs::remove_dir(&self.dir);
    }
}

/// Whether a stream of `path` needs a decoded copy before it starts: when `forced` names a
/// legacy encoding (UTF-8 files are streamed as they are; one that turns out not to be
/// UTF-8 stops with `NotUtf8`, and the caller then asks for a [`copy`]).
pub fn needs_copy(forced: Option<&'static Encoding>) -> bool {
    forced.is_some_and(|e| e != encoding_rs::UTF_8)
}

static SEQ: AtomicU32 = AtomicU32::new(0);

/// A temporary file in the system temp folder (for a UTF-8 translation that is encoded
/// when finished), removed when dropped. The file is not created here.
#[derive(Debug)]
pub struct TempFile(PathBuf);

impl TempFile {
    /// A fresh name ending in `name`.
    pub fn new(name: &str) -> TempFile {
        let n = SEQ.fetch_add(1, Ordering::Relaxed);
        TempFile(std::env::temp_dir().join(format!("nctrans-{}-{n}-{name}", std::process::id())))
    }

    pub fn path(&self) -> &Path {
        &self.0
    }
}

impl Drop for TempFile {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
    }
}

/// Detects the file's encoding and decodes it into a [`TempCopy`]. `Ok(None)` when the
/// file is UTF-8 after all (stream the file itself).
pub fn copy(path: &Path, forced: Option<&'static Encoding>) -> Result<Option<TempCopy>, NotStreamable> {
    let detected = detect(path, forced)?;
    if detected.encoding == encoding_rs::UTF_8 {
        return Ok(None);
    }
    let name = path.file_name().map_or_else(|| "input".into(), |n| n.to_os_string());
    let base = std::env::temp_dir();
    let dir = loop {
        let d = base.join(format!("nctrans-{}-{}.dec", std::process::id(), SEQ.fetch_add(1, Ordering::Relaxed)));
        match std::fs::create_dir(&d) {
            Ok(()) => break d,
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => continue,
            Err(e) => return Err(e.into()),
        }
    };
    let copy = TempCopy { path: dir.join(name), dir, detected };
    let mut w = io::BufWriter::with_capacity(1 << 16, File::create(&copy.path)?);
    decode_to(path, &copy.detected, &mut w)?;
    w.flush()?;
    Ok(Some(copy))
}
