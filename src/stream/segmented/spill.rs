//! The spill of a one-scan segmented translation: the runs' translations, written as the
//! scan reaches them, kept until the skeleton is translated and its text can go out with
//! each placeholder line replaced by a byte copy of its run (see `segmented`). In memory
//! while it is small, then in a temporary file (about the output's size) that is removed
//! on every path: unlinked right after it is made where the system allows it (Unix), else
//! when the spill is dropped.

use crate::stream::WRITE_BYTES;
use std::fs::File;
use std::io::{Read, Seek, SeekFrom, Write};
use std::path::PathBuf;
use std::sync::atomic::{AtomicU64, Ordering};

/// Spill files made by this process so far (for unique names).
static MADE: AtomicU64 = AtomicU64::new(0);

/// A temporary file, removed when dropped (if it could not be unlinked while open).
struct TempFile {
    file: Option<File>,
    path: Option<PathBuf>,
}

impl TempFile {
    fn new() -> std::io::Result<TempFile> {
        let dir = std::env::temp_dir();
        let nanos = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.subsec_nanos());
        let mut tries = 0;
        loop {
            let k = MADE.fetch_add(1, Ordering::Relaxed);
            let path = dir.join(format!("nctrans-spill-{}-{k}-{nanos}.tmp", std::process::id()));
            match std::fs::OpenOptions::new().read(true).write(true).create_new(true).open(&path) {
                Ok(file) => {
                    // Unlinked while open where that works: nothing is left if the process dies.
                    let path = std::fs::remove_file(&path).is_err().then_some(path);
                    return Ok(TempFile { file: Some(file), path });
                }
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists && tries < 100 => tries += 1,
                Err(e) => return Err(e),
            }
        }
    }
}

impl TempFile {
    fn file(&mut self) -> std::io::Result<&mut File> {
        self.file.as_mut().ok_or_else(|| std::io::Error::other("spill file closed"))
    }
}

impl Drop for TempFile {
    fn drop(&mut self) {
        // Closed first: some systems remove no open file.
        drop(self.file.take());
        if let Some(p) = &self.path {
            let _ = std::fs::remove_file(p);
        }
    }
}

/// Bytes written in order, read back in order once.
#[derive(Default)]
pub(crate) struct Spill {
    /// What is not in the file yet.
    pub(crate) buf: Vec<u8>,
    file: Option<TempFile>,
    /// Bytes in the file.
    flushed: u64,
    /// The first error (the spill is then useless: the caller falls back).
    pub(crate) io: Option<std::io::Error>,
}

impl Spill {
    pub(crate) fn new() -> Spill {
        Spill { buf: Vec::with_capacity(WRITE_BYTES + 4096), ..Spill::default() }
    }

    /// Bytes spilled so far.
    pub(crate) fn len(&self) -> u64 {
        self.flushed + self.buf.len() as u64
    }

    /// Moves the buffer to the file when it is full.
    #[inline]
    pub(crate) fn flush_some(&mut self) {
        if self.buf.len() >= WRITE_BYTES {
            self.flush();
        }
    }

    fn flush(&mut self) {
        if self.io.is_some() {
            self.buf.clear();
            return;
        }
        if self.file.is_none() {
            match TempFile::new() {
                Ok(f) => self.file = Some(f),
                Err(e) => {
                    self.io = Some(e);
                    self.buf.clear();
                    return;
                }
            }
        }
        if let Some(f) = &mut self.file {
            match f.file().and_then(|file| file.write_all(&self.buf)) {
                Ok(()) => self.flushed += self.buf.len() as u64,
                Err(e) => self.io = Some(e),
            }
        }
        self.buf.clear();
    }

    /// A reader of everything spilled, from the start.
    pub(crate) fn reader(mut self) -> std::io::Result<SpillReader> {
        if let Some(e) = self.io.take() {
            return Err(e);
        }
        if self.file.is_some() {
            self.flush();
            if let Some(e) = self.io.take() {
                return Err(e);
            }
        }
        if let Some(f) = &mut self.file {
            f.file()?.seek(SeekFrom::Start(0))?;
        }
        Ok(SpillReader { file: self.file, mem: self.buf, at: 0, chunk: Vec::new() })
    }
}

/// Reads a spill back in order.
pub(crate) struct SpillReader {
    file: Option<TempFile>,
    /// The whole spill when it never reached a file.
    mem: Vec<u8>,
    at: u64,
    chunk: Vec<u8>,
}

impl SpillReader {
    /// Copies the spill's bytes `[self.at, to)` to `out` (through `out`'s own buffering).
    pub(crate) fn copy_to(&mut self, to: u64, out: &mut dyn Write) -> std::io::Result<()> {
        if to < self.at {
            return Err(std::io::Error::other("spill read out of order"));
        }
        let mut left = to - self.at;
        match &mut self.file {
            None => {
                let lo = usize::try_from(self.at).unwrap_or(usize::MAX);
                let hi = usize::try_from(to).unwrap_or(usize::MAX);
                let s = self.mem.get(lo..hi).ok_or_else(|| std::io::Error::other("spill too short"))?;
                out.write_all(s)?;
            }
            Some(f) => {
                if self.chunk.is_empty() {
                    self.chunk.resize(WRITE_BYTES, 0);
                }
                while left > 0 {
                    let n = usize::try_from(left).unwrap_or(usize::MAX).min(self.chunk.len());
                    f.file()?.read_exact(&mut self.chunk[..n])?;
                    out.write_all(&self.chunk[..n])?;
                    left -= n as u64;
                }
            }
        }
        self.at = to;
        Ok(())
    }
}

/// Writes the translated skeleton `text` to `out` with each placeholder line (`places`)
/// replaced by its run's translation from the spill (run `k` from `starts[k]` on), with
/// the texts `inserts` (each: its run, where in the spill, the bytes; in order) put in.
pub(crate) fn assemble(
    text: &str,
    places: &[(usize, usize)],
    spill: Spill,
    starts: &[u64],
    inserts: &[(usize, u64, String)],
    out: &mut dyn Write,
) -> std::io::Result<()> {
    let total = spill.len();
    let mut r = spill.reader()?;
    let mut o = std::io::BufWriter::with_capacity(WRITE_BYTES, &mut *out);
    let mut pos = 0;
    let mut ins = inserts.iter().peekable();
    for (k, &(lo, hi)) in places.iter().enumerate() {
        o.write_all(text.get(pos..lo).unwrap_or_default().as_bytes())?;
        while let Some((_, at, bytes)) = ins.next_if(|i| i.0 == k) {
            r.copy_to(*at, &mut o)?;
            o.write_all(bytes.as_bytes())?;
        }
        r.copy_to(starts.get(k + 1).copied().unwrap_or(total), &mut o)?;
        pos = hi;
    }
    if ins.next().is_some() {
        return Err(std::io::Error::other("a block to put in outside the runs"));
    }
    o.write_all(text.get(pos..).unwrap_or_default().as_bytes())?;
    o.flush()?;
    drop(o);
    out.flush()
}
