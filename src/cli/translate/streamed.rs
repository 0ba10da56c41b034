//! The single-file translation as a stream, for an input of 8 MB and more (or `--stream`):
//! a straight-line program is translated chunk by chunk into the output, a program with a
//! macro part segmented (the macro part whole, its runs of straight blocks streamed), then
//! verified with both programs streamed. Anything else is declined (`None`), and the
//! caller translates the file whole. One path for both targets ([`from`]); what a target
//! does as its own (its streams, its callees, how it shows its output and proves it) is
//! its [`Target`]: [`ToFanuc`], [`ToSinumerik`].

use super::job::{self, Request};
use crate::cli::stream::{self as cs, ProgressLine, Source};
use nctrans::check::Verdict;
use nctrans::config::Config;
use nctrans::diag::{self, Diagnostic};
use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::ir::Unit;
use nctrans::read::LineEnding;
use nctrans::span::SourceDb;
use nctrans::stream::lines::NotStreamable;
use nctrans::stream::transcode;
use nctrans::stream::{self, Fallback, Index, Progress, ProgressFn};
use nctrans::translate::to_sinumerik::{Options, OutFile, UnsupportedPolicy};
use std::collections::BTreeSet;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// `nctrans --to TARGET IN [-o OUT]` streamed (with verification unless `--no-verify`);
/// `None` when the input is not streamed or not a program the streams take (then the
/// caller translates it whole; a partial output is removed first, and an output folder the
/// stream created). A source in a legacy encoding streams from a decoded copy; an output in
/// another encoding than UTF-8 is written as UTF-8 first, verified from there (as the whole
/// path verifies its text), then encoded.
pub fn translate(to: Dialect, req: &Request, stream: bool, c: &Config, opts: &Options) -> Option<ExitCode> {
    // An output folder the stream creates is removed again when the whole path takes over
    // (which creates it only for a translation it writes).
    let made = req.out.filter(|o| o.to_string_lossy().ends_with('/') && !o.exists());
    let code = match to {
        Dialect::Fanuc => streamed(req, stream, &|src, size| from(&ToFanuc { req, c }, req, src, size)),
        Dialect::Sinumerik => streamed(req, stream, &|src, size| from(&ToSinumerik { req, opts }, req, src, size)),
    };
    if let (None, Some(dir)) = (&code, made) {
        let _ = std::fs::remove_dir(dir);
    }
    code
}

/// A streamed translation from one source: its exit code (`None`: translate it whole), or
/// `Err` when the source is found not to be UTF-8.
type Attempt = Result<Option<ExitCode>, NotStreamable>;

/// The one way into a streamed translation, either target: the input is streamed when it
/// is large (or `forced`) and not possibly program-less; `from` translates from the file,
/// and again from a decoded copy when it finds the file not UTF-8. `None`: translate it whole.
fn streamed(req: &Request, forced: bool, from: &dyn Fn(&Source, u64) -> Attempt) -> Option<ExitCode> {
    let input = req.file;
    let size = std::fs::metadata(input).ok()?.len();
    if !(forced || size >= cs::AUTO_BYTES) {
        return None;
    }
    if nctrans::dialect::empty::may_be_program_less(input) {
        return None;
    }
    let mut src = Source::new(input, req.encoding)?;
    loop {
        match from(&src, size) {
            Ok(code) => return code,
            Err(why) => src.transcoded(&why)?,
        }
    }
}

/// What a target's streamed translation does as its own; the rest (where the output is
/// written, the temporary file and its rename, `-o`, a special target and standard output,
/// the order of the steps) is [`from`]'s, the same for every target.
trait Target {
    /// What the streams made (the source's index, the output's name, its diagnostics …).
    type Done;
    /// The extension of the scratch file that stands for standard output or a special target.
    const EXT: &'static str;
    /// Whether `-o` may name a folder (one file per program) and the files written are
    /// named (`wrote …`).
    const FOLDERS: bool;
    /// The output's encoding for a source in `enc`, and whether the stream writes the
    /// source's byte-order mark itself (`false`: it is added, if at all, by the encoding).
    fn out_encoding(&self, enc: &'static encoding_rs::Encoding) -> (&'static encoding_rs::Encoding, bool);
    /// Translates the source (its size, its line ending) into a fresh file (a byte-order mark
    /// first, or not) by [`straight_else_segmented`]; `read` gets the files read beside the
    /// input. `Err` is what [`from`] returns.
    fn translate(
        &self,
        src: (&Source, u64, LineEnding),
        write_to: (&Path, bool),
        read: &mut Vec<PathBuf>,
    ) -> Result<Self::Done, Attempt>;
    /// The translation's diagnostics, the name of its main file (in an output folder), its
    /// other files, and whether it is unfinished (constructs written as marked comments,
    /// `--unsupported warn`: it fails after its proof).
    fn parts<'d>(&self, done: &'d Self::Done) -> (&'d [Diagnostic], &'d str, &'d [OutFile], bool);
    /// Shows the finished main file `out` on standard output (`stdout`), then writes the
    /// other files of `done` where `-o` puts them. `Err`: the exit code, after saying why.
    fn deliver(&self, done: &Self::Done, out: &Path, stdout: bool, encoded: job::Encoded) -> Result<(), ExitCode>;
    /// Proves the translation and shows the verdict: the source (its name, the path it is
    /// read from) against the output (its path, the path its UTF-8 text is read from).
    fn verify(&self, done: Self::Done, input: (&Path, &Path), out: (&Path, &Path), size: u64) -> ExitCode;
}

/// [`translate`] from `src` for target `t`; `Err` when the source is found not to be UTF-8
/// (nothing is left written: the caller streams again from a decoded copy).
fn from<T: Target>(t: &T, req: &Request, src: &Source, size: u64) -> Attempt {
    let (input, path) = (req.file, src.path());
    let (Some(eol), Some((enc, bom))) = (src.line_ending(), src.encoding()) else {
        return Ok(None);
    };
    let (out_enc, stream_bom) = t.out_encoding(enc);
    let stem = input.file_stem().and_then(|s| s.to_str()).unwrap_or("out");
    // The stream writes `tmp`, renamed to the output once it is whole and may be written;
    // standard output (no `-o`) and a special target (`-o /dev/null`, see `cs::is_special`)
    // get a copy of a scratch file, removed at the end.
    let special = req.out.filter(|o| cs::is_special(o));
    let written = req.out.filter(|_| special.is_none());
    let folder = written.filter(|o| T::FOLDERS && job::out_place(o).0);
    let tmp = match (written, folder) {
        (None, _) => std::env::temp_dir().join(format!("nctrans-{}-{stem}.{}", std::process::id(), T::EXT)),
        (_, Some(o)) => {
            if let Err(e) = std::fs::create_dir_all(o) {
                eprintln!("error: cannot create {}: {e}", o.display());
                return Ok(Some(ExitCode::from(2)));
            }
            o.join(format!(".nctrans-{}-{stem}.tmp", std::process::id()))
        }
        (Some(o), None) => {
            o.with_extension(format!("{}.nctrans-tmp", o.extension().and_then(|e| e.to_str()).unwrap_or("")))
        }
    };
    // Output not in UTF-8: the stream writes UTF-8 into a scratch file, encoded into `tmp`
    // when finished and read back from there by verification.
    let utf8 = (out_enc != encoding_rs::UTF_8).then(|| transcode::TempFile::new(&format!("{stem}.utf8.{}", T::EXT)));
    let write_to: &Path = utf8.as_ref().map_or(&tmp, |u| u.path());
    // The files read (the input, the callees beside it): no output may be one of them.
    let mut read = vec![input.to_path_buf()];
    let done = match t.translate((src, size, eol), (write_to, stream_bom && bom && utf8.is_none()), &mut read) {
        Ok(done) => done,
        Err(attempt) => return attempt,
    };
    let (diags, name, subs, unfinished) = t.parts(&done);
    // The translation's diagnostics, as the whole path renders them (lines read from the
    // file, or its decoded copy).
    let mut db = SourceDb::new();
    db.add(input.display().to_string(), String::new());
    eprint!("{}", nctrans::excerpt::render(&db, diags, &[(0, path)]));
    if let Some(u) = &utf8 {
        if let Err(code) = cs::encode_output(u.path(), out_enc, bom, &tmp) {
            return Ok(Some(code));
        }
    }
    let out = match (written, folder) {
        (None, _) => tmp.clone(),
        (_, Some(o)) => o.join(name),
        (Some(o), None) => o.to_path_buf(),
    };
    if let Some(o) = written {
        let dir = job::out_place(o).1;
        let paths: Vec<PathBuf> = std::iter::once(out.clone()).chain(subs.iter().map(|f| dir.join(&f.name))).collect();
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
    if let Some(s) = special {
        if let Err(e) = cs::copy_into(&out, s) {
            let _ = std::fs::remove_file(&out);
            eprintln!("error: cannot write {}: {e}", s.display());
            return Ok(Some(ExitCode::from(2)));
        }
        if T::FOLDERS {
            eprintln!("wrote {}", s.display());
        }
    } else {
        let stdout = req.out.is_none();
        if T::FOLDERS && !stdout {
            eprintln!("wrote {}", out.display());
        }
        if let Err(code) = t.deliver(&done, &out, stdout, (out_enc, bom)) {
            if stdout {
                let _ = std::fs::remove_file(&out);
            }
            return Ok(Some(code));
        }
    }
    let mut code = ExitCode::SUCCESS;
    if req.verify {
        let read_back = utf8.as_ref().map_or(out.as_path(), |u| u.path());
        code = t.verify(done, (input, path), (&out, read_back), size);
    }
    if written.is_none() {
        let _ = std::fs::remove_file(&out);
    }
    if unfinished {
        eprintln!("error: unsupported constructs were written as marked comments");
        return Ok(Some(ExitCode::from(1)));
    }
    Ok(Some(code))
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

/// The Sinumerik → FANUC part of a streamed translation.
struct ToFanuc<'a> {
    req: &'a Request<'a>,
    c: &'a Config,
}

/// What the streams to FANUC made: the source's index, the segmented translation's symbol
/// map (what its proof's runs start with, `translate::to_fanuc::main_proof`), the
/// translation's notes, and the profile the source was read with.
type FanucDone = (Index, Option<nctrans::translate::to_fanuc::SymbolMap>, Vec<Diagnostic>, nctrans::dialect::Semantics);

impl Target for ToFanuc<'_> {
    type Done = FanucDone;
    const EXT: &'static str = "nc";
    const FOLDERS: bool = false;

    fn out_encoding(&self, enc: &'static encoding_rs::Encoding) -> (&'static encoding_rs::Encoding, bool) {
        // A byte-order mark is kept, as the whole-file path keeps it (only in UTF-8).
        (self.c.output_encoding.unwrap_or(enc), true)
    }

    fn translate(
        &self,
        (src, size, eol): (&Source, u64, LineEnding),
        (write_to, bom): (&Path, bool),
        read: &mut Vec<PathBuf>,
    ) -> Result<FanucDone, Attempt> {
        use stream::target::fanuc as st;
        let (c, input, path) = (self.c, self.req.file, src.path());
        if cs::dialect_of(path, None) != Some(Dialect::Sinumerik) {
            return Err(Ok(None));
        }
        let mut opts = match job::fanuc_options(c, input, eol) {
            Ok(o) => o,
            Err(e) => {
                eprintln!("error: {e}");
                return Err(Ok(Some(ExitCode::from(2))));
            }
        };
        // The source is read with the profile the whole path reads it with: its library's
        // global user data and macros (`job::load_sinumerik`), found beside the input.
        opts.source = match crate::cli::profile::sinumerik(c, &mut SourceDb::new(), input) {
            Ok(s) => s,
            Err(code) => return Err(Ok(Some(code))),
        };
        let profile = opts.source.clone();
        // Calls of subprograms beside the input are taken when the verifier's callees
        // (`DirCallees`: beside the file it reads, with that profile) are the ones the whole
        // path loads.
        let straight = |w: &mut dyn Write, p: ProgressFn<'_>| {
            st::to_fanuc(path, &opts, w, Some(p)).map(|d| (d.index, None, Vec::new(), profile.clone()))
        };
        let segmented = |w: &mut dyn Write, p: ProgressFn<'_>| {
            let mut load = |u: &Unit| fanuc_callees(input, &opts.source, c, u, read);
            let r = if path == input {
                stream::segmented::fanuc::to_fanuc_with_subs(path, &opts, &mut load, w, Some(p))
            } else {
                stream::segmented::fanuc::to_fanuc_with_notes(path, &opts, w, Some(p))
            };
            r.map(|(d, notes)| (d.index, Some(d.symbol_map), notes, profile.clone()))
        };
        straight_else_segmented((input, size), write_to, bom, straight, segmented)
    }

    fn parts<'d>(&self, done: &'d FanucDone) -> (&'d [Diagnostic], &'d str, &'d [OutFile], bool) {
        // An unsupported construct is refused on the way to FANUC (the stream declines it).
        (&done.2, "", &[], false)
    }

    fn deliver(&self, _: &FanucDone, out: &Path, stdout: bool, _: job::Encoded) -> Result<(), ExitCode> {
        let copied = if stdout { cs::copy_to_stdout(out) } else { Ok(()) };
        copied.map_err(|e| {
            eprintln!("error: cannot write: {e}");
            ExitCode::from(2)
        })
    }

    /// The output read back as FANUC (streamed), both programs run streamed side by side.
    fn verify(&self, done: FanucDone, input: (&Path, &Path), out: (&Path, &Path), size: u64) -> ExitCode {
        let mut line = ProgressLine::new("reading back", size);
        let mut report = |p: Progress| line.update(p);
        let macro_interrupt = self.c.fanuc_semantics().macro_interrupt;
        // Both runs start, and the output is read back, as the whole path's proof does (a
        // straight-line program has no variables, no inputs: `main_proof` of a map without).
        let map = done.1.unwrap_or_else(|| {
            // What any translation's map holds of the target it was written for.
            let t = self.c.fanuc_semantics();
            let (haas, haas_ngc, macro_interrupt) = (t.haas, t.haas_ngc, t.macro_interrupt);
            nctrans::translate::to_fanuc::SymbolMap { haas, haas_ngc, macro_interrupt, ..Default::default() }
        });
        let p = nctrans::translate::to_fanuc::main_proof(&map, &done.0.header);
        let src = stream::verify::SourceRun {
            semantics: p.source,
            callees: Some(done.3),
            inputs: p.source_inputs,
            output: p.target,
        };
        let (max_steps, b_in) = (self.req.max_steps, p.target_inputs);
        let v = stream::verify::verify_for((done.0, src), out.1, max_steps, b_in, macro_interrupt, Some(&mut report));
        line.done();
        let mut db = SourceDb::new();
        db.add(input.0.display().to_string(), String::new());
        db.add(out.0.display().to_string(), String::new());
        // Subprograms the source's run called (read whole, rendered from their text).
        for (name, text) in &v.callees {
            db.add(name.clone(), text.clone());
        }
        eprint!("{}", nctrans::excerpt::render(&db, &v.diags, &[(0, input.1), (1, out.1)]));
        eprint!("{}", v.diff);
        eprintln!("{}", v.summary);
        ExitCode::from(u8::from(!v.equivalent))
    }
}

/// The subprograms a segmented skeleton `unit` calls, found beside `input` and loaded as the
/// whole path loads them (`job::callees`: transitively, file ids from 1 up), for
/// `segmented::to_fanuc_with_subs`. Declines (the whole path takes the program) a callee
/// not found, one with any diagnostic, one that is not one program named as its file, one
/// beside a main program file of the same name (the verifier's `DirCallees` could take
/// that), and callees calling other than by a constant name.
fn fanuc_callees(
    input: &Path,
    profile: &nctrans::dialect::Semantics,
    c: &Config,
    unit: &Unit,
    read: &mut Vec<PathBuf>,
) -> Result<Vec<Unit>, Fallback> {
    use nctrans::ir::ProgName;
    let no = |why: &str| Fallback::NotStraight(why.into());
    let mut db = SourceDb::new();
    db.add(input.display().to_string(), String::new());
    let popts = ParseOptions { semantics: profile.clone() };
    let dir = input.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or_else(|| Path::new("."));
    let files: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|_| no("a folder that cannot be listed"))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .collect();
    job::callees(unit, &job::l_names_beside(input, c.l_numbers), |callee| {
        let path = job::find_beside(input, callee).ok_or_else(|| no("a call of a program not found beside it"))?;
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

/// The FANUC → Sinumerik part of a streamed translation.
struct ToSinumerik<'a> {
    req: &'a Request<'a>,
    opts: &'a Options,
}

/// What the streams to Sinumerik made: the main file's translation, the subprograms' files
/// and the FANUC units translated whole (the skeleton, the callees) with their files.
struct SinumerikDone {
    main: nctrans::stream::target::sinumerik::Streamed,
    subs: Vec<OutFile>,
    fanuc: (SourceDb, Vec<Unit>),
    eol: LineEnding,
}

impl Target for ToSinumerik<'_> {
    type Done = SinumerikDone;
    const EXT: &'static str = "mpf";
    const FOLDERS: bool = true;

    fn out_encoding(&self, enc: &'static encoding_rs::Encoding) -> (&'static encoding_rs::Encoding, bool) {
        // A source not in UTF-8, so the output neither.
        (enc, false)
    }

    fn translate(
        &self,
        (src, size, eol): (&Source, u64, LineEnding),
        (write_to, bom): (&Path, bool),
        read: &mut Vec<PathBuf>,
    ) -> Result<SinumerikDone, Attempt> {
        use nctrans::stream::target::sinumerik as sts;
        let (req, opts, path) = (self.req, self.opts, src.path());
        let with_subs = !req.out.is_some_and(cs::is_special);
        let mut fanuc: (SourceDb, Vec<Unit>) = (SourceDb::new(), Vec::new());
        let straight = |w: &mut dyn Write, p: ProgressFn<'_>| {
            sts::to_sinumerik(path, opts, eol, w, Some(p)).map(|d| (d, Vec::new()))
        };
        // Calls of subprograms (after the main program, or beside the file as the whole path
        // finds them) are taken when the files are written as `write_files` writes them: to a
        // file, a folder or stdout (not a special target).
        let segmented = |w: &mut dyn Write, p: ProgressFn<'_>| {
            use nctrans::stream::segmented::sinumerik as seg;
            if !with_subs {
                return seg::to_sinumerik(path, opts, eol, w, Some(p)).map(|d| (d, Vec::new()));
            }
            let mut load = |u: &Unit| {
                let units = sinumerik_callees(req, opts, u, read, &mut fanuc.0)?;
                fanuc.1 = std::iter::once(u.clone()).chain(units.iter().cloned()).collect();
                Ok(units)
            };
            seg::to_sinumerik_with_subs(path, opts, eol, &mut load, w, Some(p))
        };
        let (main, subs) = straight_else_segmented((req.file, size), write_to, bom, straight, segmented)?;
        Ok(SinumerikDone { main, subs, fanuc, eol })
    }

    fn parts<'d>(&self, done: &'d SinumerikDone) -> (&'d [Diagnostic], &'d str, &'d [OutFile], bool) {
        let warned = done.main.diags.iter().any(|d| d.code.starts_with("NC3") || nctrans::unfinished::is_marked(d));
        let unfinished = warned && self.opts.unsupported == UnsupportedPolicy::Warn;
        (&done.main.diags, &done.main.file_name, &done.subs, unfinished)
    }

    fn deliver(&self, done: &SinumerikDone, out: &Path, stdout: bool, encoded: job::Encoded) -> Result<(), ExitCode> {
        if stdout {
            let copied = if done.subs.is_empty() {
                cs::copy_to_stdout(out)
            } else {
                job::main_to_stdout(out, &done.main.file_name, done.eol, encoded)
            };
            copied.map_err(|_| ExitCode::from(2))?;
        }
        job::write_subs(self.req, &done.subs, done.eol, encoded)
    }

    /// The output read back as Sinumerik (streamed), both programs run streamed side by
    /// side, with each one's `nctrans: set` header inputs; the output's callees are the
    /// translated subprograms. As the whole path, each macro called by G65/G66 also runs
    /// alone, with its callers' arguments and each of them vacant (`translate::called`).
    fn verify(&self, done: SinumerikDone, input: (&Path, &Path), out: (&Path, &Path), size: u64) -> ExitCode {
        use nctrans::eval::{header_inputs, DirCallees, RunOptions};
        use nctrans::stream::verify::{self as sv, ReadBack, StreamSide};
        use nctrans::translate::called;
        let (opts, max_steps, read_back) = (self.opts, self.req.max_steps, out.1);
        // Shown under the names the whole path gives the translation's files.
        let out_dir = job::shown_dir(self.req.out);
        let shown = |name: &str| if out_dir.is_empty() { name.to_string() } else { format!("{out_dir}/{name}") };
        let mut line = ProgressLine::new("reading back", size);
        let mut report = |p: Progress| line.update(p);
        let popts = ParseOptions { semantics: opts.target.clone() };
        let back = sv::read_back(read_back, 1, Dialect::Sinumerik, &popts, Some(&mut report));
        line.done();
        let mut db = SourceDb::new();
        db.add(input.0.display().to_string(), String::new());
        db.add(shown(&done.main.file_name), String::new());
        let streamed = [(0, input.1), (1, read_back)];
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
                eprintln!("error: {} cannot be read back: {e}", read_back.display());
                return job::verdict(Verdict::Failed, "");
            }
        };
        let (in_a, in_b) = match (header_inputs(&done.main.index.header), header_inputs(&back.header)) {
            (Ok(a), Ok(b)) => (a, b),
            (Err(e), _) | (_, Err(e)) => {
                let d = diag::Diagnostic::error("NC407", format!("bad `nctrans: set` header line: {e}"));
                eprint!("{}", nctrans::excerpt::render(&db, &[d], &streamed));
                return job::verdict(Verdict::Failed, "");
            }
        };
        // Both runs meet the source's interrupt inputs, as the whole path's proof does.
        let interrupts = nctrans::eval::header_interrupts(&done.main.index.header).unwrap_or_default();
        let run = |inputs, sem: &nctrans::dialect::Semantics| RunOptions {
            inputs,
            max_steps,
            semantics: Some(sem.clone()),
            interrupts: interrupts.clone(),
            ..RunOptions::default()
        };
        // The subprograms are served to the Siemens run from memory, under the names the
        // whole path's verifier shows them (`translate::to_sinumerik::verify::Emitted`).
        let files = done.subs.iter().map(|f| (f.program.clone(), shown(&f.name), f.text.clone())).collect();
        let emitted = nctrans::translate::to_sinumerik::verify::Emitted { files, semantics: opts.target.clone() };
        let a = StreamSide {
            index: done.main.index,
            name: input.0.display().to_string(),
            callees: Box::new(DirCallees { semantics: Some(opts.source.clone()) }),
            run: run(in_a, &opts.source),
        };
        let b = StreamSide {
            index: back,
            name: shown(&done.main.file_name),
            callees: Box::new(emitted),
            run: run(in_b, &opts.target),
        };
        let report = sv::compare(a, b);
        eprint!("{}", nctrans::excerpt::render(&report.db, &report.diags, &streamed));
        if !matches!(report.verdict, Verdict::Equivalent { .. }) {
            return job::verdict(report.verdict, &report.diff);
        }
        let profiles = nctrans::translate::to_sinumerik::verify::Profiles {
            fanuc: opts.source.clone(),
            sinumerik: opts.target.clone(),
        };
        let settings = called::RunSettings { out_dir: &out_dir, max_steps, profiles: &profiles, set: &[] };
        let tr = nctrans::translate::to_sinumerik::Translation {
            files: done.subs,
            symbols: nctrans::translate::Symbols::Sinumerik(done.main.symbols),
            diags: Vec::new(),
            unsupported: 0,
        };
        let units: Vec<&Unit> = done.fanuc.1.iter().collect();
        let mut runs = vec![(String::new(), report)];
        runs.extend(called::called_runs(&done.fanuc.0, &units, &tr, &settings, !opts.specialise_callers));
        job::combined(called::combine(runs), &|db, diags| nctrans::excerpt::render(db, diags, &[(0, input.1)]))
    }
}

/// The callees of a streamed skeleton `unit` (the main program's macro part and the other
/// programs of the file) beside the input, loaded as [`job::load_job`] loads them (file ids
/// from 1 up); declines a call of a program found nowhere and a callee with diagnostics.
/// `db` gets the input (file 0, without its text) and the callee files.
fn sinumerik_callees(
    req: &Request,
    opts: &Options,
    unit: &Unit,
    read: &mut Vec<PathBuf>,
    db: &mut SourceDb,
) -> Result<Vec<Unit>, Fallback> {
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
