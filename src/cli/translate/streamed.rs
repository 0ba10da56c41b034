//! The single-file translation as a stream, for an input of 8 MB and more (or `--stream`):
//! a straight-line program is translated chunk by chunk into the output, a program with a
//! macro part segmented (the macro part whole, its runs of straight blocks streamed), then
//! verified with both programs streamed. Anything else is declined (`None`), and the
//! caller translates the file whole.

use super::job::{self, Request};
use super::TranslateArgs;
use crate::cli::stream::{self as cs, ProgressLine, Source};
use nctrans::check::Verdict;
use nctrans::diag;
use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::ir::Unit;
use nctrans::span::SourceDb;
use nctrans::stream::lines::NotStreamable;
use nctrans::stream::transcode;
use nctrans::stream::{self, Fallback, Index, Progress, ProgressFn};
use nctrans::translate::to_sinumerik::{Options, UnsupportedPolicy};
use std::collections::BTreeSet;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// `nctrans --to fanuc IN [-o OUT]` streamed (with verification unless `--no-verify`);
/// `None` when the input is not streamed or not a straight-line program (then the caller
/// translates it whole; a partial output is removed first). A source in a legacy encoding
/// streams from a decoded copy; an output in another encoding than UTF-8 is written as
/// UTF-8 first, verified from there (as the whole path verifies its text), then encoded.
pub fn to_fanuc(a: &TranslateArgs, c: &nctrans::config::Config, input: &Path) -> Option<ExitCode> {
    streamed(input, a.stream, c.input_encoding, &|src, size| to_fanuc_from(a, c, src, size))
}

/// A streamed translation from one source: its exit code (`None`: translate it whole), or
/// `Err` when the source is found not to be UTF-8.
type Attempt = Result<Option<ExitCode>, NotStreamable>;

/// The one way into a streamed translation, either target: `input` is streamed when it is
/// large (or `forced`) and not possibly program-less; `from` translates from the file, and
/// again from a decoded copy when it finds the file not UTF-8. `None`: translate it whole.
fn streamed(
    input: &Path,
    forced: bool,
    encoding: Option<&'static encoding_rs::Encoding>,
    from: &dyn Fn(&Source, u64) -> Attempt,
) -> Option<ExitCode> {
    let size = std::fs::metadata(input).ok()?.len();
    if !(forced || size >= cs::AUTO_BYTES) {
        return None;
    }
    if nctrans::dialect::empty::may_be_program_less(input) {
        return None;
    }
    let mut src = Source::new(input, encoding)?;
    loop {
        match from(&src, size) {
            Ok(code) => return code,
            Err(why) => src.transcoded(&why)?,
        }
    }
}

/// Translates `input` (of `size` bytes) into a fresh `write_to` by the straight-line stream,
/// then, when the program is not straight-line, by the segmented one (the macro part whole,
/// its runs of straight blocks streamed), each with a progress line and (`bom`) a byte-order
/// mark first. `Err` is what the caller returns: declined (`Ok(None)`: nothing is left
/// written; a note says why when the segmented stream declines too), a temporary file that
/// cannot be made, or a source found not to be UTF-8.
fn straight_else_segmented<T>(
    (input, size): (&Path, u64),
    write_to: &Path,
    bom: bool,
    straight: impl FnOnce(&mut dyn Write, ProgressFn<'_>) -> Result<T, Fallback>,
    segmented: impl FnOnce(&mut dyn Write, ProgressFn<'_>) -> Result<T, Fallback>,
) -> Result<T, Attempt> {
    let gone = |a: Attempt| {
        let _ = std::fs::remove_file(write_to);
        Err(a)
    };
    let why = match into_file(write_to, size, bom, straight) {
        Err(code) => return Err(Ok(Some(code))),
        Ok(Some(Ok(t))) => return Ok(t),
        Ok(Some(Err(Fallback::NotStraight(why)))) => why,
        Ok(Some(Err(Fallback::NotStreamable(e @ NotStreamable::NotUtf8 { .. })))) => return gone(Err(e)),
        Ok(None | Some(Err(_))) => return gone(Ok(None)),
    };
    let why = match into_file(write_to, size, bom, segmented) {
        Err(code) => return Err(Ok(Some(code))),
        Ok(Some(Ok(t))) => return Ok(t),
        Ok(Some(Err(Fallback::NotStreamable(e @ NotStreamable::NotUtf8 { .. })))) => return gone(Err(e)),
        Ok(Some(Err(f))) => cs::segmented_why(&f),
        Ok(None) => why,
    };
    cs::note_read_whole(input, size, &why);
    gone(Ok(None))
}

/// One streamed translator `f` into a fresh `write_to` (`bom`: a byte-order mark first) with
/// a progress line; `Ok(None)` when the mark cannot be written.
fn into_file<T>(
    write_to: &Path,
    size: u64,
    bom: bool,
    f: impl FnOnce(&mut dyn Write, ProgressFn<'_>) -> Result<T, Fallback>,
) -> Result<Option<Result<T, Fallback>>, ExitCode> {
    let mut w = cs::create_temp(write_to)?;
    if bom && w.write_all(b"\xEF\xBB\xBF").is_err() {
        return Ok(None);
    }
    let mut line = ProgressLine::new("translating", size);
    let mut report = |p: Progress| line.update(p);
    let r = f(&mut w, &mut report);
    line.done();
    drop(w);
    Ok(Some(r))
}

/// [`to_fanuc`] from `src`; `Err` when the source is found not to be UTF-8 (nothing is
/// left written: the caller streams again from a decoded copy).
fn to_fanuc_from(a: &TranslateArgs, c: &nctrans::config::Config, src: &Source, size: u64) -> Attempt {
    use stream::target::fanuc as st;
    let (input, path) = (src.original, src.path());
    if cs::dialect_of(path, None) != Some(Dialect::Sinumerik) {
        return Ok(None);
    }
    let (Some(eol), Some((enc, bom))) = (src.line_ending(), src.encoding()) else {
        return Ok(None);
    };
    let out_enc = c.output_encoding.unwrap_or(enc);
    let opts = match job::fanuc_options(c, input, eol) {
        Ok(o) => o,
        Err(e) => {
            eprintln!("error: {e}");
            return Ok(Some(ExitCode::from(2)));
        }
    };
    // Without -o the output goes through a temporary file, so a program found not to be
    // straight-line part way can still be translated whole, and verification can read it.
    // So does a special target (`-o /dev/null`, see `is_special`), copied into at the end.
    let special = a.output.as_deref().filter(|p| cs::is_special(p));
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
    // The files read, which the output must not be (the callees beside the input, too).
    let mut read = vec![input.to_path_buf()];
    // Calls of subprograms beside the input are taken when the verifier's callees
    // (`DirCallees`: beside the file it reads, default semantics) are the ones the whole
    // path loads.
    let sem = c.sinumerik_semantics() == nctrans::dialect::Semantics::default_for(Dialect::Sinumerik);
    let straight = |w: &mut dyn Write, p: ProgressFn<'_>| {
        st::to_fanuc(path, &opts, w, Some(p)).map(|d| (d.index, None, Vec::new()))
    };
    let segmented = |w: &mut dyn Write, p: ProgressFn<'_>| {
        let mut load = |u: &nctrans::ir::Unit| to_fanuc_callees(input, c, u, &mut read);
        let r = if path == input && sem {
            stream::segmented::fanuc::to_fanuc_with_subs(path, &opts, &mut load, w, Some(p))
        } else {
            stream::segmented::fanuc::to_fanuc_with_notes(path, &opts, w, Some(p))
        };
        r.map(|(d, notes)| (d.index, Some(d.inputs), notes))
    };
    let r = straight_else_segmented((input, size), write_to, direct_bom, straight, segmented);
    let (index, inputs, notes) = match r {
        Ok(done) => done,
        Err(attempt) => return attempt,
    };
    // The translation's notes, as the whole path renders them (lines read from the file,
    // or its decoded copy).
    if !notes.is_empty() {
        let mut db = SourceDb::new();
        db.add(input.display().to_string(), String::new());
        eprint!("{}", nctrans::excerpt::render(&db, &notes, &[(0, path)]));
    }
    if let Some(u) = &utf8 {
        if let Err(code) = cs::encode_output(u.path(), out_enc, bom, &tmp) {
            return Ok(Some(code));
        }
    }
    if let Err(code) = crate::cli::out_guard::check(out, &read, true, "-o") {
        let _ = std::fs::remove_file(&tmp);
        return Ok(Some(code));
    }
    if let Err(e) = std::fs::rename(&tmp, out) {
        eprintln!("error: cannot write {}: {e}", out.display());
        return Ok(Some(ExitCode::from(2)));
    }
    if to_stdout {
        if let Err(e) = cs::copy_to_stdout(out) {
            let _ = std::fs::remove_file(out);
            eprintln!("error: cannot write: {e}");
            return Ok(Some(ExitCode::from(2)));
        }
    }
    if let Some(t) = special {
        if let Err(e) = cs::copy_into(out, t) {
            let _ = std::fs::remove_file(out);
            eprintln!("error: cannot write {}: {e}", t.display());
            return Ok(Some(ExitCode::from(2)));
        }
    }
    let read_back = utf8.as_ref().map_or(out, |u| u.path());
    let code = verify_to_fanuc(c, (input, path), (out, read_back), index, inputs, size);
    if to_stdout || special.is_some() {
        let _ = std::fs::remove_file(out);
    }
    Ok(Some(code))
}

/// The subprograms a segmented skeleton `unit` calls, found beside `input` and loaded as the
/// whole path loads them (`job::callees`: transitively, file ids from 1 up), for
/// `segmented::to_fanuc_with_subs`. Declines (the whole path takes the program) a callee
/// not found, one with any diagnostic, one that is not one program named as its file, one
/// beside a main program file of the same name (the verifier's `DirCallees` could take
/// that), and callees calling other than by a constant name.
fn to_fanuc_callees(
    input: &Path,
    c: &nctrans::config::Config,
    unit: &nctrans::ir::Unit,
    read: &mut Vec<std::path::PathBuf>,
) -> Result<Vec<nctrans::ir::Unit>, stream::Fallback> {
    use super::job::find_beside;
    use nctrans::ir::ProgName;
    use stream::Fallback;
    let no = |why: &str| Fallback::NotStraight(why.into());
    let mut db = SourceDb::new();
    db.add(input.display().to_string(), String::new());
    let popts = ParseOptions { semantics: c.sinumerik_semantics() };
    let dir = input.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or_else(|| Path::new("."));
    let files: Vec<std::path::PathBuf> = std::fs::read_dir(dir)
        .map_err(|_| no("a folder that cannot be listed"))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .collect();
    job::callees(unit, |callee| {
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
        if !p.diags.is_empty() || !named || !stream::segmented::fanuc::calls_plain(&p.unit) {
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
fn verify_to_fanuc(
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
    let v = stream::verify::verify(index, out.1, c.max_steps, inputs.unwrap_or_default(), Some(&mut report));
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

/// `--to sinumerik` as a stream, for an input of 8 MB and more (or `--stream`) that is a
/// straight-line program: translated chunk by chunk into the output, then verified with
/// both programs streamed. `None` when it is not (then it is translated whole; a partial
/// output is removed first). Prints what the whole path prints; diagnostics point into
/// files that are not loaded, so they are shown compactly with their line.
/// A source in a legacy encoding streams from a decoded UTF-8 copy, and its translation is
/// written as UTF-8 first, verified from there, then encoded (as the whole path encodes).
pub fn to_sinumerik(args: &TranslateArgs, req: &Request, opts: &Options) -> Option<ExitCode> {
    // An output folder the stream creates is removed again when the whole path takes over
    // (which creates it only for a translation it writes).
    let made = req.out.filter(|o| o.to_string_lossy().ends_with('/') && !o.exists());
    let code = streamed(req.file, args.stream, req.encoding, &|src, size| to_sinumerik_from(req, opts, src, size));
    if let (None, Some(dir)) = (&code, made) {
        let _ = std::fs::remove_dir(dir);
    }
    code
}

/// [`to_sinumerik`] from `src`; `Err` when the source is found not to be UTF-8 (nothing is
/// left written: the caller streams again from a decoded copy).
fn to_sinumerik_from(req: &Request, opts: &Options, src: &Source, size: u64) -> Attempt {
    use nctrans::stream::target::sinumerik as sts;
    let path = src.path();
    let (Some(eol), Some((enc, bom))) = (src.line_ending(), src.encoding()) else {
        return Ok(None);
    };
    let stem = req.file.file_stem().and_then(|s| s.to_str()).unwrap_or("out");
    // Written to a temporary file and renamed: a program found not to be straight-line part
    // way is then translated whole; standard output gets a copy of the finished file.
    let is_dir = |o: &Path| o.is_dir() || o.to_string_lossy().ends_with('/');
    // A special target (`-o /dev/null`, see `cs::is_special`) is copied into at the end.
    let special = req.out.filter(|o| cs::is_special(o));
    let tmp = match req.out.filter(|_| special.is_none()) {
        None => std::env::temp_dir().join(format!("nctrans-{}-{stem}.mpf", std::process::id())),
        Some(o) if is_dir(o) => {
            if let Err(e) = std::fs::create_dir_all(o) {
                eprintln!("error: cannot create {}: {e}", o.display());
                return Ok(Some(ExitCode::from(2)));
            }
            o.join(format!(".nctrans-{}-{stem}.tmp", std::process::id()))
        }
        Some(o) => o.with_extension(format!("{}.nctrans-tmp", o.extension().and_then(|e| e.to_str()).unwrap_or(""))),
    };
    // A source not in UTF-8 (so the output neither): the stream writes UTF-8 into a
    // scratch file, encoded into `tmp` when finished and read back from there.
    let utf8 = (enc != encoding_rs::UTF_8).then(|| transcode::TempFile::new(&format!("{stem}.utf8.mpf")));
    let write_to: &Path = utf8.as_ref().map_or(&tmp, |u| u.path());
    let with_subs = special.is_none();
    // The FANUC units translated whole (the skeleton, the callees) and their files.
    let mut fanuc: (SourceDb, Vec<Unit>) = (SourceDb::new(), Vec::new());
    // The files read (the input, the callees beside it): no output may be one of them.
    let mut read = vec![req.file.to_path_buf()];
    let straight =
        |w: &mut dyn Write, p: ProgressFn<'_>| sts::to_sinumerik(path, opts, eol, w, Some(p)).map(|d| (d, Vec::new()));
    // Calls of subprograms (after the main program, or beside the file as the whole path
    // finds them) are taken when the files are written as `write_files` writes them: to a
    // file, a folder or stdout (not a special target).
    let segmented = |w: &mut dyn Write, p: ProgressFn<'_>| {
        use nctrans::stream::segmented::sinumerik as seg;
        if !with_subs {
            return seg::to_sinumerik(path, opts, eol, w, Some(p)).map(|d| (d, Vec::new()));
        }
        let mut load = |u: &Unit| {
            let units = to_sinumerik_callees(req, opts, u, &mut read, &mut fanuc.0)?;
            fanuc.1 = std::iter::once(u.clone()).chain(units.iter().cloned()).collect();
            Ok(units)
        };
        seg::to_sinumerik_with_subs(path, opts, eol, &mut load, w, Some(p))
    };
    let (done, subs) = match straight_else_segmented((req.file, size), write_to, false, straight, segmented) {
        Ok(done) => done,
        Err(attempt) => return attempt,
    };
    if let Some(u) = &utf8 {
        if let Err(code) = cs::encode_output(u.path(), enc, bom, &tmp) {
            return Ok(Some(code));
        }
    }
    let mut db = SourceDb::new();
    db.add(req.file.display().to_string(), String::new());
    eprint!("{}", nctrans::excerpt::render(&db, &done.diags, &[(0, path)]));
    let out = match req.out.filter(|_| special.is_none()) {
        None => tmp.clone(),
        Some(o) if is_dir(o) => o.join(&done.file_name),
        Some(o) => o.to_path_buf(),
    };
    if let Some(o) = req.out.filter(|_| special.is_none()) {
        let dir = job::out_place(o).1;
        let mut paths = vec![out.clone()];
        paths.extend(subs.iter().map(|f| dir.join(&f.name)));
        if let Err(code) = crate::cli::out_guard::check_all(paths.iter().map(PathBuf::as_path), &read, req.force) {
            let _ = std::fs::remove_file(&tmp);
            return Ok(Some(code));
        }
    }
    if let Err(e) = std::fs::rename(&tmp, &out) {
        let _ = std::fs::remove_file(&tmp);
        eprintln!("error: cannot write {}: {e}", out.display());
        return Ok(Some(ExitCode::from(2)));
    }
    if let Some(t) = special {
        if let Err(e) = cs::copy_into(&out, t) {
            let _ = std::fs::remove_file(&out);
            eprintln!("error: cannot write {}: {e}", t.display());
            return Ok(Some(ExitCode::from(2)));
        }
        eprintln!("wrote {}", t.display());
    } else if req.out.is_none() {
        let copied = if subs.is_empty() {
            cs::copy_to_stdout(&out)
        } else {
            job::main_to_stdout(&out, &done.file_name, eol, (enc, bom))
        };
        if copied.is_err() {
            let _ = std::fs::remove_file(&out);
            return Ok(Some(ExitCode::from(2)));
        }
        if let Err(code) = job::write_subs(req, &subs, eol, (enc, bom)) {
            let _ = std::fs::remove_file(&out);
            return Ok(Some(code));
        }
    } else {
        eprintln!("wrote {}", out.display());
        if let Err(code) = job::write_subs(req, &subs, eol, (enc, bom)) {
            return Ok(Some(code));
        }
    }
    let warned = done.diags.iter().any(|d| d.code.starts_with("NC3") || nctrans::unfinished::is_marked(d));
    let mut code = ExitCode::SUCCESS;
    if req.verify {
        // Shown under the name the whole path gives the translation.
        let out_dir = match req.out {
            Some(o) if is_dir(o) => o.display().to_string(),
            Some(o) => o.parent().map_or_else(String::new, |p| p.display().to_string()),
            None => "<stdout>".to_string(),
        };
        let shown = if out_dir.is_empty() { done.file_name.clone() } else { format!("{out_dir}/{}", done.file_name) };
        let read_back = utf8.as_ref().map_or(out.as_path(), |u| u.path());
        // The subprograms are served to the Siemens run from memory, under the names the
        // whole path's verifier shows them (`translate::to_sinumerik::verify::Emitted`).
        let files = subs
            .iter()
            .map(|f| {
                let shown = if out_dir.is_empty() { f.name.clone() } else { format!("{out_dir}/{}", f.name) };
                (f.program.clone(), shown, f.text.clone())
            })
            .collect();
        let emitted = nctrans::translate::to_sinumerik::verify::Emitted { files, semantics: opts.target.clone() };
        let back = (read_back, shown.as_str(), Box::new(emitted) as _);
        // As the whole path: each macro called by G65/G66 also runs alone, with its
        // callers' arguments and each of them vacant (`translate::called`).
        let called = || {
            let units: Vec<&Unit> = fanuc.1.iter().collect();
            let files = (subs.as_slice(), &done.symbols);
            nctrans::translate::called::single_file_runs(&fanuc.0, &units, files, opts, &out_dir, req.max_steps)
        };
        code = verify_to_sinumerik((req.file, path), back, done.index, req.max_steps, opts, size, &called);
    }
    if req.out.is_none() || special.is_some() {
        let _ = std::fs::remove_file(&out);
    }
    if warned && opts.unsupported == UnsupportedPolicy::Warn {
        eprintln!("error: unsupported constructs were written as marked comments");
        return Ok(Some(ExitCode::from(1)));
    }
    Ok(Some(code))
}

/// Verifies a streamed translation: the output read back as Sinumerik (streamed), both
/// programs run streamed side by side, with each one's `nctrans: set` header inputs; the
/// output's callees come from `out_callees` (the translated subprograms).
fn verify_to_sinumerik(
    (input, input_read): (&Path, &Path),
    (out, shown, out_callees): (&Path, &str, Box<dyn nctrans::eval::CalleeSource + Send>),
    source: nctrans::stream::Index,
    max_steps: u64,
    opts: &Options,
    size: u64,
    called: &dyn Fn() -> Vec<(String, nctrans::check::CheckReport)>,
) -> ExitCode {
    use nctrans::eval::{header_inputs, DirCallees, RunOptions};
    use nctrans::stream::verify::{self as sv, ReadBack, StreamSide};
    let mut line = ProgressLine::new("reading back", size);
    let mut report = |p: nctrans::stream::Progress| line.update(p);
    let popts = ParseOptions { semantics: opts.target.clone() };
    let back = sv::read_back(out, 1, Dialect::Sinumerik, &popts, Some(&mut report));
    line.done();
    let mut db = SourceDb::new();
    db.add(input.display().to_string(), String::new());
    db.add(shown.to_string(), String::new());
    let streamed = [(0, input_read), (1, out)];
    let back = match back {
        Ok(b) => b,
        Err(ReadBack::Diags(mut diags)) => {
            diags.push(
                diag::Diagnostic::error("NC372", "the translation does not read back as Sinumerik")
                    .note("this is a gap in nctrans's writer, not in the program")
                    .hint("report it with the program"),
            );
            eprint!("{}", nctrans::excerpt::render(&db, &diags, &streamed));
            return job::verdict(Verdict::Failed, "");
        }
        Err(ReadBack::Unreadable(e)) => {
            eprintln!("error: {} cannot be read back: {e}", out.display());
            return job::verdict(Verdict::Failed, "");
        }
    };
    let (in_a, in_b) = match (header_inputs(&source.header), header_inputs(&back.header)) {
        (Ok(a), Ok(b)) => (a, b),
        (Err(e), _) | (_, Err(e)) => {
            let d = diag::Diagnostic::error("NC407", format!("bad `nctrans: set` header line: {e}"));
            eprint!("{}", nctrans::excerpt::render(&db, &[d], &streamed));
            return job::verdict(Verdict::Failed, "");
        }
    };
    let run = |inputs, sem: &nctrans::dialect::Semantics| RunOptions {
        inputs,
        max_steps,
        semantics: Some(sem.clone()),
        ..RunOptions::default()
    };
    let a = StreamSide {
        index: source,
        name: input.display().to_string(),
        callees: Box::new(DirCallees { semantics: Some(opts.source.clone()) }),
        run: run(in_a, &opts.source),
    };
    let b = StreamSide { index: back, name: shown.to_string(), callees: out_callees, run: run(in_b, &opts.target) };
    let report = sv::compare(a, b);
    eprint!("{}", nctrans::excerpt::render(&report.db, &report.diags, &streamed));
    if !matches!(report.verdict, Verdict::Equivalent { .. }) {
        return job::verdict(report.verdict, &report.diff);
    }
    let mut runs = vec![(String::new(), report)];
    runs.extend(called());
    crate::cli::called::combined(nctrans::translate::called::combine(runs), &|db, diags| {
        nctrans::excerpt::render(db, diags, &[(0, input_read)])
    })
}

/// The callees of a streamed skeleton `unit` (the main program's macro part and the other
/// programs of the file) beside the input, loaded as [`job::load_job`] loads them (file ids
/// from 1 up); declines a call of a program found nowhere and a callee with diagnostics.
/// `db` gets the input (file 0, without its text) and the callee files.
fn to_sinumerik_callees(
    req: &Request,
    opts: &Options,
    unit: &Unit,
    read: &mut Vec<PathBuf>,
    db: &mut SourceDb,
) -> Result<Vec<Unit>, nctrans::stream::Fallback> {
    use nctrans::stream::Fallback;
    *db = SourceDb::new();
    db.add(req.file.display().to_string(), String::new());
    let db = &mut *db;
    let dir = job::beside(req.file);
    let popts = ParseOptions { semantics: opts.source.clone() };
    let (mut units, mut diags) = (vec![unit.clone()], Vec::new());
    let missing =
        job::load_callees(db, &mut units, &dir, req.encoding, &popts, &mut diags, (read, &mut BTreeSet::new()));
    if !missing.is_empty() {
        return Err(Fallback::NotStraight("a call of a program found neither in the file nor beside it".into()));
    }
    if !diags.is_empty() {
        return Err(Fallback::NotStraight("a called program with diagnostics".into()));
    }
    units.remove(0);
    Ok(units)
}
