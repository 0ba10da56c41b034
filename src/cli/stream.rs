//! What the commands share to stream: `parse --summary`, `run`, `check` and the single-file
//! translation on files of 8 MB and more (or with `--stream`) read them as a stream in
//! constant memory, with a progress
//! line on a terminal for files over 10 MB. A file in a legacy encoding (detected, or
//! forced with `--encoding`) streams from a decoded UTF-8 copy (`stream::transcode`).
//! Anything the stream cannot do exactly as the whole-file path falls back to that path.

use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::span::SourceDb;
use nctrans::stream::lines::NotStreamable;
use nctrans::stream::transcode::{self, TempCopy};
use nctrans::stream::{self, lines, Index, Progress};
use std::io::{IsTerminal, Write};
use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

/// Files this large are streamed without `--stream`.
pub const AUTO_BYTES: u64 = 8 * 1024 * 1024;
/// Files this large get a progress line on a terminal.
const PROGRESS_BYTES: u64 = 10 * 1024 * 1024;

/// Whether to stream `path`: asked for, or large (in any encoding).
pub fn wanted(path: &Path, input: &super::args::InputOpts) -> bool {
    (input.stream || std::fs::metadata(path).is_ok_and(|m| m.len() >= AUTO_BYTES))
        // A file that may hold no program is read whole, which reports it (NC145).
        && !nctrans::dialect::empty::may_be_program_less(path)
}

/// What a stream reads for `path`: the file itself, or (legacy encodings) a decoded UTF-8
/// copy, removed when this is dropped. Spans, lines and columns are the same in both
/// (offsets into the decoded text), so diagnostics render from [`Source::path`].
pub struct Source<'a> {
    pub original: &'a Path,
    pub copy: Option<TempCopy>,
    /// `--encoding`.
    forced: Option<&'static encoding_rs::Encoding>,
}

impl<'a> Source<'a> {
    /// The file itself when `forced` is not a legacy encoding (a UTF-8 file costs nothing
    /// extra), else a decoded copy; `None` when it cannot be made.
    pub fn new(path: &'a Path, forced: Option<&'static encoding_rs::Encoding>) -> Option<Source<'a>> {
        let copy = if transcode::needs_copy(forced) { transcode::copy(path, forced).ok()? } else { None };
        Some(Source { original: path, copy, forced })
    }

    /// After a stream of the file itself stopped at a line that is not UTF-8: a decoded
    /// copy to stream instead (`None` when there is one already, or it cannot be made).
    pub fn transcoded(&mut self, why: &NotStreamable) -> Option<()> {
        if self.copy.is_some() || !matches!(why, NotStreamable::NotUtf8 { .. }) {
            return None;
        }
        self.copy = Some(transcode::copy(self.original, self.forced).ok()??);
        Some(())
    }

    /// The path to read.
    pub fn path(&self) -> &Path {
        self.copy.as_ref().map_or(self.original, |c| c.path())
    }

    /// The source's encoding and byte-order mark, as `read::decode` decides them.
    pub fn encoding(&self) -> Option<(&'static encoding_rs::Encoding, bool)> {
        match &self.copy {
            Some(c) => Some((c.detected.encoding, c.detected.bom)),
            None => Some((encoding_rs::UTF_8, stream::lines::has_bom(self.original).ok()?)),
        }
    }

    /// The source's first line ending (of the decoded text).
    pub fn line_ending(&self) -> Option<nctrans::read::LineEnding> {
        match &self.copy {
            Some(c) => Some(c.detected.line_ending),
            None => stream::lines::first_line_ending(self.original).ok(),
        }
    }
}

/// Renders progress on stderr (`\r`-updated), at most ten times a second.
pub struct ProgressLine {
    what: &'static str,
    start: Instant,
    last: Option<Instant>,
    pub on: bool,
}

impl ProgressLine {
    pub fn new(what: &'static str, size: u64) -> ProgressLine {
        ProgressLine {
            what,
            start: Instant::now(),
            last: None,
            on: size > PROGRESS_BYTES && std::io::stderr().is_terminal(),
        }
    }

    pub fn update(&mut self, p: Progress) {
        if !self.on || self.last.is_some_and(|t| t.elapsed().as_millis() < 100) {
            return;
        }
        self.last = Some(Instant::now());
        let secs = self.start.elapsed().as_secs_f64().max(1e-3);
        let frac = p.done as f64 / p.total.max(1) as f64;
        let eta = if frac > 0.0 { secs / frac - secs } else { 0.0 };
        eprint!(
            "\r{}: {:.0}/{:.0} MB ({:.0}%), {:.0} blocks/s, ETA {:.0} s   ",
            self.what,
            p.done as f64 / 1e6,
            p.total as f64 / 1e6,
            frac * 100.0,
            p.blocks as f64 / secs,
            eta
        );
    }

    pub fn done(&self) {
        if self.on && self.last.is_some() {
            eprint!("\r{:70}\r", "");
        }
    }
}

/// The dialect from `--from`, the extension, else the first lines of the file.
pub fn dialect_of(path: &Path, from: Option<Dialect>) -> Option<Dialect> {
    if let Some(d) = from {
        return Some(d);
    }
    let name = path.display().to_string();
    if let Some(d) = path.extension().and_then(|e| e.to_str()).and_then(Dialect::from_extension) {
        return Some(d);
    }
    let (input, _) = stream::open(path).ok()?;
    let mut l = lines::Lines::new(input).ok()?;
    let mut head = String::new();
    for _ in 0..400 {
        match l.next_line() {
            Ok(Some(x)) => {
                head.push_str(x.text);
                head.push('\n');
            }
            _ => break,
        }
    }
    Some(nctrans::detect_dialect(&name, &head))
}

/// First scan (for the index only) with a progress line; `None` when the file cannot be
/// streamed exactly (the caller then reads it whole). A file found not to be UTF-8 is
/// scanned again from a decoded copy (in `src`). The file is read with the profile the
/// whole-file path reads it with (`profile::semantics`: the project's, for a Siemens
/// program with its library's global user data and macros, found beside the original
/// file), which the index keeps (`Index::opts`) for its runs. The scan's diagnostics are
/// rendered from excerpts of the file (it is not loaded); `Err` when they hold an error, as
/// for a file read whole (so do the definition files').
pub fn scan(src: &mut Source, from: Option<Dialect>, file: usize) -> Option<Result<Index, ExitCode>> {
    let mut profile: Option<(Dialect, ParseOptions)> = None;
    let ix = loop {
        let path = src.path();
        let dialect = dialect_of(path, from)?;
        let opts = match &profile {
            Some((d, o)) if *d == dialect => o.clone(),
            _ => match super::profile::streamed(src.original, dialect) {
                Ok(semantics) => {
                    profile = Some((dialect, ParseOptions { semantics }));
                    profile.as_ref().map(|p| p.1.clone())?
                }
                Err(code) => return Some(Err(code)),
            },
        };
        let (input, size) = stream::open(path).ok()?;
        let mut line = ProgressLine::new("reading", size);
        let mut report = |p: Progress| line.update(p);
        let r = stream::scan_index(input, size, path, file, dialect, &opts, stream::CHUNK_OPS, Some(&mut report));
        line.done();
        match r {
            Ok(ix) => break ix,
            Err(why) => src.transcoded(&why)?,
        }
    };
    // NC102: a structure left open at the end; its full diagnostics need the whole file.
    if ix.diags.iter().any(|d| d.code == "NC102") {
        return None;
    }
    if !ix.diags.is_empty() {
        let mut db = SourceDb::new();
        while db.len() < file {
            db.add("", String::new());
        }
        db.add(src.original.display().to_string(), String::new());
        eprint!("{}", nctrans::excerpt::render(&db, &ix.diags, &[(file, src.path())]));
        if nctrans::diag::has_errors(&ix.diags) {
            return Some(Err(ExitCode::from(1)));
        }
    }
    Some(Ok(ix))
}

/// Run options from the file's header lines and `--set`.
pub fn run_options(
    ix: &Index,
    name: &Path,
    eval: &super::args::EvalOpts,
) -> Result<nctrans::eval::RunOptions, ExitCode> {
    super::args::run_options(&ix.header, &name.display().to_string(), eval)
}

/// Creates the temporary output of a streamed translation (renamed when it is finished).
pub fn create_temp(tmp: &Path) -> Result<std::io::BufWriter<std::fs::File>, ExitCode> {
    match std::fs::File::create(tmp) {
        Ok(f) => Ok(std::io::BufWriter::with_capacity(1 << 16, f)),
        Err(e) => {
            eprintln!("error: cannot write {}: {e}", tmp.display());
            Err(ExitCode::from(2))
        }
    }
}

/// Says why a large file is read whole after all (a small one says nothing: it was only
/// streamed because `--stream` asked for it).
/// Encodes a finished UTF-8 translation (`utf8`) into `tmp` in the output encoding (with a
/// byte-order mark when `bom`, UTF-8 only); on failure `tmp` is removed and the error shown.
pub fn encode_output(utf8: &Path, enc: &'static encoding_rs::Encoding, bom: bool, tmp: &Path) -> Result<(), ExitCode> {
    let mut w = create_temp(tmp)?;
    if let Err(e) = transcode::encode_to(utf8, enc, bom, &mut w).and_then(|_| w.flush()) {
        let _ = std::fs::remove_file(tmp);
        eprintln!("error: cannot write {}: {e}", tmp.display());
        return Err(ExitCode::from(2));
    }
    Ok(())
}

/// Why the segmented route declined, for [`note_read_whole`] (after "it has").
pub fn segmented_why(f: &stream::Fallback) -> String {
    use stream::Fallback;
    match f {
        Fallback::NotStraight(w) => w.clone(),
        Fallback::Diagnostics => "warnings or errors to show".into(),
        Fallback::NotStreamable(e) => format!("a line the stream cannot take ({e})"),
    }
}

pub fn note_read_whole(input: &Path, size: u64, why: &str) {
    if size >= AUTO_BYTES {
        eprintln!(
            "note: {} is read whole: it has {why} (only straight-line programs and simple macro parts stream)",
            input.display()
        );
    }
}

/// Copies a finished output file to standard output.
/// Whether `-o` names something that is neither a regular file nor a folder (`/dev/null`,
/// a FIFO, a terminal): such a target is written into, never replaced by renaming a finished
/// file over it (that would put a regular file in its place, `/dev/null` included), and the
/// translation is kept in a temporary file until then, for verification to read back.
pub fn is_special(p: &Path) -> bool {
    std::fs::metadata(p).is_ok_and(|m| !m.is_file() && !m.is_dir())
}

/// Copies the finished file `path` into the special target `to` (see [`is_special`]).
pub fn copy_into(path: &Path, to: &Path) -> std::io::Result<()> {
    let mut f = std::fs::File::open(path)?;
    let mut t = std::fs::OpenOptions::new().write(true).open(to)?;
    std::io::copy(&mut f, &mut t).and_then(|_| t.flush())
}

pub fn copy_to_stdout(path: &Path) -> std::io::Result<()> {
    let mut f = std::fs::File::open(path)?;
    let mut so = std::io::stdout().lock();
    std::io::copy(&mut f, &mut so).and_then(|_| so.flush())
}
