//! The command line's streaming path: `parse --summary`, `run` and `check` on files of 8 MB
//! and more (or with `--stream`) read them as a stream in constant memory, with a progress
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
use std::sync::Arc;
use std::time::Instant;

/// Files this large are streamed without `--stream`.
pub const AUTO_BYTES: u64 = 8 * 1024 * 1024;
/// Files this large get a progress line on a terminal.
const PROGRESS_BYTES: u64 = 10 * 1024 * 1024;

/// Whether to stream `path`: asked for, or large (in any encoding).
pub fn wanted(path: &Path, input: &super::InputOpts) -> bool {
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
            None => Some((encoding_rs::UTF_8, stream::to_sinumerik::has_bom(self.original).ok()?)),
        }
    }

    /// The source's first line ending (of the decoded text).
    pub fn line_ending(&self) -> Option<nctrans::read::LineEnding> {
        match &self.copy {
            Some(c) => Some(c.detected.line_ending),
            None => stream::to_sinumerik::first_line_ending(self.original).ok(),
        }
    }
}

/// Renders progress on stderr (`\r`-updated), at most ten times a second.
pub struct ProgressLine {
    what: &'static str,
    start: Instant,
    last: Option<Instant>,
    on: bool,
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
fn dialect_of(path: &Path, from: Option<Dialect>) -> Option<Dialect> {
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
/// scanned again from a decoded copy (in `src`). The scan's diagnostics are rendered from
/// excerpts of the file (it is not loaded); `Err` when they hold an error, as for a file
/// read whole.
fn scan(src: &mut Source, from: Option<Dialect>, file: usize) -> Option<Result<Index, ExitCode>> {
    let ix = loop {
        let path = src.path();
        let dialect = dialect_of(path, from)?;
        let (input, size) = stream::open(path).ok()?;
        let mut line = ProgressLine::new("reading", size);
        let mut report = |p: Progress| line.update(p);
        let opts = ParseOptions::for_dialect(dialect);
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

/// `nctrans parse --summary` streamed.
pub fn parse_summary(
    path: &Path,
    from: Option<Dialect>,
    forced: Option<&'static encoding_rs::Encoding>,
) -> Option<ExitCode> {
    let mut src = Source::new(path, forced)?;
    let ix = match scan(&mut src, from, 0)? {
        Ok(ix) => ix,
        Err(code) => return Some(code),
    };
    let text = format!(
        "{}: {} program(s), {} blocks, {} warning(s)\n",
        path.display(),
        ix.programs.len(),
        ix.blocks,
        ix.diags.len()
    );
    Some(if std::io::stdout().lock().write_all(text.as_bytes()).is_err() {
        ExitCode::from(2)
    } else {
        ExitCode::SUCCESS
    })
}

/// Run options from the file's header lines and `--set`.
fn run_options(ix: &Index, name: &Path, eval: &super::EvalOpts) -> Result<nctrans::eval::RunOptions, ExitCode> {
    super::run_options(&ix.header, &name.display().to_string(), eval)
}

/// `nctrans run` streamed.
pub fn run(
    path: &Path,
    from: Option<Dialect>,
    eval: &super::EvalOpts,
    format: nctrans::eval::Format,
    quiet: bool,
    forced: Option<&'static encoding_rs::Encoding>,
) -> Option<ExitCode> {
    use nctrans::eval::{self, Ending};
    let mut src = Source::new(path, forced)?;
    let ix = match scan(&mut src, from, 0)? {
        Ok(ix) => ix,
        Err(code) => return Some(code),
    };
    let opts = match run_options(&ix, path, eval) {
        Ok(o) => o,
        Err(code) => return Some(code),
    };
    let mut db = SourceDb::new();
    let main_id = db.add(path.display().to_string(), String::new());
    let size = ix.size;
    let pager = std::rc::Rc::new(stream::paged::Pager::new(Arc::new(ix)));
    let progress_on = ProgressLine::new("running", size).on;
    if progress_on {
        let mut l = ProgressLine::new("running", size);
        pager.set_progress(Box::new(move |p| l.update(p)));
    }
    let p2 = std::rc::Rc::clone(&pager);
    let line_of = move |o: eval::Origin| (o.file == main_id).then(|| p2.line_of(o.span.lo)).flatten();
    let mut callees = eval::DirCallees { semantics: None };
    let (outcome, write_error) = if quiet {
        (eval::run_stream(&mut db, pager, &mut callees, &opts, &mut eval::NullSink), None)
    } else {
        let out = std::io::BufWriter::with_capacity(1 << 16, std::io::stdout().lock());
        let mut sink = eval::WriterSink::new(out, format, Box::new(line_of));
        sink.block_lines = Some(main_id);
        let o = eval::run_stream(&mut db, pager, &mut callees, &opts, &mut sink);
        let err = sink.error.take().or_else(|| sink.out.flush().err());
        (o, err)
    };
    if progress_on {
        eprint!("\r{:70}\r", "");
    }
    eprint!("{}", nctrans::excerpt::render(&db, &outcome.diags, &[(main_id, src.path())]));
    if let Some(e) = write_error {
        eprintln!("error: writing the trace: {e}");
        return Some(ExitCode::from(2));
    }
    Some(match outcome.ending {
        Ending::End(_) | Ending::Stopped => ExitCode::SUCCESS,
        Ending::Error => ExitCode::from(1),
        Ending::Alarm { .. } => ExitCode::from(3),
        Ending::Limit { .. } => ExitCode::from(4),
    })
}

/// One side of `nctrans check`: streamed when wanted and possible, with what it reads (the
/// file, or a decoded copy of a legacy-encoded one: the caller keeps it until the check has
/// run, and renders the check's diagnostics from its [`Source::path`]).
pub fn side<'a>(
    db: &mut SourceDb,
    path: &'a Path,
    from: Option<Dialect>,
    eval: &super::EvalOpts,
    forced: Option<&'static encoding_rs::Encoding>,
) -> Option<Result<(nctrans::check::Runner, Source<'a>), ExitCode>> {
    let file = db.len();
    let mut src = Source::new(path, forced)?;
    let ix = match scan(&mut src, from, file)? {
        Ok(ix) => ix,
        Err(code) => return Some(Err(code)),
    };
    let opts = match run_options(&ix, path, eval) {
        Ok(o) => o,
        Err(code) => return Some(Err(code)),
    };
    db.add(path.display().to_string(), String::new());
    let callees = Box::new(nctrans::eval::DirCallees { semantics: None });
    Some(Ok((stream::runner(Arc::new(ix), callees, opts), src)))
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
pub fn segmented_why(f: &stream::translate::Fallback) -> String {
    use stream::translate::Fallback;
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

/// `nctrans --to fanuc IN [-o OUT]` streamed (with verification unless `--no-verify`);
/// `None` when the input is not streamed or not a straight-line program (then the caller
/// translates it whole; a partial output is removed first). A source in a legacy encoding
/// streams from a decoded copy; an output in another encoding than UTF-8 is written as
/// UTF-8 first, verified from there (as the whole path verifies its text), then encoded.
pub fn translate(
    a: &super::translate_cli::TranslateArgs,
    c: &nctrans::config::Config,
    input: &Path,
) -> Option<ExitCode> {
    let size = std::fs::metadata(input).ok()?.len();
    if !(a.stream || size >= AUTO_BYTES) {
        return None;
    }
    if nctrans::dialect::empty::may_be_program_less(input) {
        return None;
    }
    let mut src = Source::new(input, c.input_encoding)?;
    loop {
        match translate_from(a, c, &src, size) {
            Ok(code) => return code,
            Err(why) => src.transcoded(&why)?,
        }
    }
}

/// [`translate`] from `src`; `Err` when the source is found not to be UTF-8 (nothing is
/// left written: the caller streams again from a decoded copy).
fn translate_from(
    a: &super::translate_cli::TranslateArgs,
    c: &nctrans::config::Config,
    src: &Source,
    size: u64,
) -> Result<Option<ExitCode>, NotStreamable> {
    use stream::translate::{self as st, Fallback};
    let (input, path) = (src.original, src.path());
    if dialect_of(path, None) != Some(Dialect::Sinumerik) {
        return Ok(None);
    }
    let (Some(eol), Some((enc, bom))) = (src.line_ending(), src.encoding()) else {
        return Ok(None);
    };
    let out_enc = c.output_encoding.unwrap_or(enc);
    let opts = match super::translate_cli::options(c, input, eol) {
        Ok(o) => o,
        Err(e) => {
            eprintln!("error: {e}");
            return Ok(Some(ExitCode::from(2)));
        }
    };
    // Without -o the output goes through a temporary file, so a program found not to be
    // straight-line part way can still be translated whole, and verification can read it.
    // So does a special target (`-o /dev/null`, see `is_special`), copied into at the end.
    let special = a.output.as_deref().filter(|p| is_special(p));
    let to_stdout = a.output.is_none();
    let stem = input.file_stem().and_then(|s| s.to_str()).unwrap_or("out");
    let scratch = std::env::temp_dir().join(format!("nctrans-{}-{stem}.nc", std::process::id()));
    let out: &Path = match a.output.as_deref() {
        Some(o) if special.is_none() => o,
        _ => &scratch,
    };
    let ext = out.extension().and_then(|e| e.to_str()).unwrap_or("");
    let tmp = out.with_extension(format!("{ext}.nctrans-tmp"));
    // Output not in UTF-8: the stream writes UTF-8 into a scratch file, encoded into `tmp`
    // when finished and read back from there by verification.
    let utf8 = (out_enc != encoding_rs::UTF_8).then(|| transcode::TempFile::new(&format!("{stem}.utf8.nc")));
    let write_to: &Path = utf8.as_ref().map_or(&tmp, |u| u.path());
    // A byte-order mark is kept, as the whole-file path keeps it (only in UTF-8).
    let direct_bom = bom && utf8.is_none();
    let mut w = match create_temp(write_to) {
        Ok(w) => w,
        Err(code) => return Ok(Some(code)),
    };
    if direct_bom && w.write_all(b"\xEF\xBB\xBF").is_err() {
        let _ = std::fs::remove_file(write_to);
        return Ok(None);
    }
    let mut line = ProgressLine::new("translating", size);
    let mut report = |p: Progress| line.update(p);
    let r = st::to_fanuc(path, &opts, &mut w, Some(&mut report));
    line.done();
    drop(w);
    // The files read, which the output must not be (the callees beside the input, too).
    let mut read = vec![input.to_path_buf()];
    // Not straight-line: segmented (the macro part whole, its runs of straight blocks
    // streamed), else the whole-file path.
    let (index, inputs) = match r {
        Ok(d) => (d.index, None),
        Err(Fallback::NotStraight(why)) => {
            let mut w = match create_temp(write_to) {
                Ok(w) => w,
                Err(code) => return Ok(Some(code)),
            };
            let started = !direct_bom || w.write_all(b"\xEF\xBB\xBF").is_ok();
            let mut line = ProgressLine::new("translating", size);
            let mut report = |p: Progress| line.update(p);
            // Calls of subprograms beside the input are taken when the verifier's callees
            // (`DirCallees`: beside the file it reads, default semantics) are the ones the
            // whole path loads.
            let sem = c.sinumerik_semantics() == nctrans::dialect::Semantics::default_for(Dialect::Sinumerik);
            let mut load = |u: &nctrans::ir::Unit| callees_beside(input, c, u, &mut read);
            let r = if !started {
                Err(None)
            } else if path == input && sem {
                stream::segmented::to_fanuc_with_subs(path, &opts, &mut load, &mut w, Some(&mut report)).map_err(Some)
            } else {
                stream::segmented::to_fanuc_with_notes(path, &opts, &mut w, Some(&mut report)).map_err(Some)
            };
            line.done();
            drop(w);
            match r {
                Ok((d, notes)) => {
                    // The translation's notes, as the whole path renders them (lines read
                    // from the file, or its decoded copy).
                    if !notes.is_empty() {
                        let mut db = SourceDb::new();
                        db.add(input.display().to_string(), String::new());
                        eprint!("{}", nctrans::excerpt::render(&db, &notes, &[(0, path)]));
                    }
                    (d.index, Some(d.inputs))
                }
                Err(f) => {
                    let _ = std::fs::remove_file(write_to);
                    let seg_why = match f {
                        Some(Fallback::NotStraight(w)) => w,
                        Some(Fallback::NotStreamable(e @ NotStreamable::NotUtf8 { .. })) => return Err(e),
                        Some(f) => segmented_why(&f),
                        None => why,
                    };
                    note_read_whole(input, size, &seg_why);
                    return Ok(None);
                }
            }
        }
        Err(f) => {
            let _ = std::fs::remove_file(write_to);
            return match f {
                Fallback::NotStreamable(e @ NotStreamable::NotUtf8 { .. }) => Err(e),
                _ => Ok(None),
            };
        }
    };
    if let Some(u) = &utf8 {
        if let Err(code) = encode_output(u.path(), out_enc, bom, &tmp) {
            return Ok(Some(code));
        }
    }
    if let Err(code) = super::out_guard::check(out, &read, true, "-o") {
        let _ = std::fs::remove_file(&tmp);
        return Ok(Some(code));
    }
    if let Err(e) = std::fs::rename(&tmp, out) {
        eprintln!("error: cannot write {}: {e}", out.display());
        return Ok(Some(ExitCode::from(2)));
    }
    if to_stdout {
        if let Err(e) = copy_to_stdout(out) {
            let _ = std::fs::remove_file(out);
            eprintln!("error: cannot write: {e}");
            return Ok(Some(ExitCode::from(2)));
        }
    }
    if let Some(t) = special {
        if let Err(e) = copy_into(out, t) {
            let _ = std::fs::remove_file(out);
            eprintln!("error: cannot write {}: {e}", t.display());
            return Ok(Some(ExitCode::from(2)));
        }
    }
    let read_back = utf8.as_ref().map_or(out, |u| u.path());
    let code = verify_streamed(c, (input, path), (out, read_back), index, inputs, size);
    if to_stdout || special.is_some() {
        let _ = std::fs::remove_file(out);
    }
    Ok(Some(code))
}

/// The subprograms a segmented skeleton `unit` calls, found beside `input` and loaded as the
/// whole path loads them (`translate_cli`: transitively, file ids from 1 up), for
/// `segmented::to_fanuc_with_subs`. Declines (the whole path takes the program) a callee
/// not found, one with any diagnostic, one that is not one program named as its file, one
/// beside a main program file of the same name (the verifier's `DirCallees` could take
/// that), and callees calling other than by a constant name.
fn callees_beside(
    input: &Path,
    c: &nctrans::config::Config,
    unit: &nctrans::ir::Unit,
    read: &mut Vec<std::path::PathBuf>,
) -> Result<Vec<nctrans::ir::Unit>, stream::translate::Fallback> {
    use super::translate_cli::find_beside;
    use nctrans::ir::ProgName;
    use stream::translate::Fallback;
    let no = |why: &str| Fallback::NotStraight(why.into());
    let mut db = SourceDb::new();
    db.add(input.display().to_string(), String::new());
    let popts = ParseOptions { semantics: c.sinumerik_semantics() };
    let dir = input.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or_else(|| Path::new("."));
    let files: Vec<std::path::PathBuf> = std::fs::read_dir(dir)
        .map_err(|_| no("a folder that cannot be listed"))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .collect();
    super::translate_cli::callees(unit, |callee| {
        let path = find_beside(input, callee).ok_or_else(|| no("a call of a program not found beside it"))?;
        let mpf = files.iter().any(|f| {
            f.file_stem().and_then(|s| s.to_str()).is_some_and(|s| s.eq_ignore_ascii_case(callee))
                && f.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("mpf"))
        });
        if mpf {
            return Err(no("a call of a name that is also a main program beside it"));
        }
        let bytes = std::fs::read(&path).map_err(|_| no("a subprogram that cannot be read"))?;
        read.push(path.clone());
        let l = nctrans::load(&mut db, &path.display().to_string(), &bytes, None);
        let p = nctrans::parse(&db, l.file, Dialect::Sinumerik, &popts);
        let named = matches!(&p.unit.programs[..], [one] if matches!(&one.name, Some(ProgName::Name(n)) if n.eq_ignore_ascii_case(callee)));
        if !p.diags.is_empty() || !named || !stream::segmented::calls_plain(&p.unit) {
            return Err(no(
                "a subprogram with diagnostics, or not one PROC named as its file, or a call of another kind",
            ));
        }
        Ok(Some(p.unit))
    })
}

/// Verifies a streamed translation. Each file is given as its name and the path to read
/// (a decoded copy of a legacy source; the UTF-8 text of an output written in another
/// encoding).
fn verify_streamed(
    c: &nctrans::config::Config,
    input: (&Path, &Path),
    out: (&Path, &Path),
    index: Index,
    inputs: Option<Vec<nctrans::eval::Input>>,
    size: u64,
) -> ExitCode {
    if !c.verify {
        return ExitCode::SUCCESS;
    }
    let mut line = ProgressLine::new("reading back", size);
    let mut report = |p: Progress| line.update(p);
    let v = stream::translate::verify(index, out.1, c.max_steps, inputs.unwrap_or_default(), Some(&mut report));
    line.done();
    if !v.diags.is_empty() {
        let mut db = SourceDb::new();
        db.add(input.0.display().to_string(), String::new());
        db.add(out.0.display().to_string(), String::new());
        // Subprograms the source's run called (read whole, rendered from their text).
        for (name, text) in &v.callees {
            db.add(name.clone(), text.clone());
        }
        eprint!("{}", nctrans::excerpt::render(&db, &v.diags, &[(0, input.1), (1, out.1)]));
    }
    eprint!("{}", v.diff);
    eprintln!("{}", v.summary);
    if v.equivalent {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    }
}
