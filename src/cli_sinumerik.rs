//! `nctrans --to sinumerik FILE`: the command-line side of the FANUC → Sinumerik translation
//! (part of the binary: it prints). Loads the FANUC file and the callees found beside it,
//! translates, prints or writes the Siemens files, then verifies by running both.

use crate::translate_cli::TranslateArgs;
use nctrans::batch::library::ProgKey;
use nctrans::check::Verdict;
use nctrans::config::Config;
use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::ir::{CallTarget, ItemKind, StmtKind, Unit};
use nctrans::span::SourceDb;
use nctrans::stream::lines::NotStreamable;
use nctrans::stream::transcode;
use nctrans::translate_sinumerik::{self as ts, Options, UnsupportedPolicy, VarMapRule};
use nctrans::{diag, read};
use std::collections::BTreeSet;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Where the input is and where the output goes.
pub struct Request<'a> {
    pub file: &'a Path,
    pub out: Option<&'a Path>,
    pub encoding: Option<&'static encoding_rs::Encoding>,
    /// `--force`: existing output files may be replaced (inputs never).
    pub force: bool,
    /// Whether to verify (`--no-verify`, `batch.verify`), and each run's step limit.
    pub verify: bool,
    pub max_steps: u64,
}

/// The options from the configuration: `nctrans.toml` (or `--config`) with the flags given
/// applied over it (`batch_cli::configure`).
fn options(args: &TranslateArgs, stem: &str, c: &Config) -> Result<Options, String> {
    // The project's profiles (the Haas series, the increment system, R parameters).
    let mut o = Options { source: c.fanuc_semantics(), target: c.sinumerik_semantics(), ..Options::default() };
    // Flag rules come first in the list: the first rule that covers a variable places it.
    for r in &c.var_map_to_sinumerik {
        o.var_map.push(VarMapRule::parse(r)?);
    }
    for (k, v) in &c.programs_to_sinumerik {
        if let (ProgKey::Number(n), ProgKey::Name(name)) = (k, v) {
            o.program_map.insert(*n, name.to_ascii_uppercase());
        }
    }
    o.specialise_callers = c.specialise_callers || args.specialise_callers;
    for m in &args.program_map {
        let (n, name) = m.split_once('=').ok_or_else(|| format!("bad --program-map '{m}' (expected 9010=NAME)"))?;
        let n: u32 =
            n.trim().trim_start_matches(['O', 'o']).parse().map_err(|_| format!("bad program number in '{m}'"))?;
        let name = name.trim().to_ascii_uppercase();
        if !valid_name(&name) {
            return Err(format!(
                "bad Siemens program name '{name}' (letters, digits and _, the first two letters or _)"
            ));
        }
        o.program_map.insert(n, name);
    }
    if args.unsupported == "warn" {
        o.unsupported = UnsupportedPolicy::Warn;
    }
    o.main_name = main_name(stem);
    Ok(o)
}

fn valid_name(s: &str) -> bool {
    let b = s.as_bytes();
    b.len() >= 2
        && b.len() <= 31
        && b[..2].iter().all(|c| c.is_ascii_alphabetic() || *c == b'_')
        && b.iter().all(|c| c.is_ascii_alphanumeric() || *c == b'_')
}

/// A Siemens program name from a file stem: upper case, other characters `_`, and `P_` in
/// front when it would not start with two letters.
pub fn main_name(stem: &str) -> String {
    let mut s: String =
        stem.chars().map(|c| if c.is_ascii_alphanumeric() { c.to_ascii_uppercase() } else { '_' }).collect();
    if !valid_name(&s) {
        s = format!("P_{s}");
    }
    s.truncate(31);
    s
}

/// Program numbers called in a unit.
fn called_numbers(unit: &Unit) -> BTreeSet<u32> {
    let mut set = BTreeSet::new();
    for p in &unit.programs {
        nctrans::ir::visit::walk_stmts(&p.body, &mut |s| {
            if let StmtKind::Block(b) = &s.kind {
                for it in &b.items {
                    let mut items = vec![it];
                    if let ItemKind::IfThen { then, .. } = &it.kind {
                        items.push(then);
                    }
                    if let ItemKind::IfBlock { items: inner, .. } = &it.kind {
                        items.extend(inner);
                    }
                    for it in items {
                        if let ItemKind::Call(c) = &it.kind {
                            // Haas M97 names a block of this program, not a program.
                            if let (CallTarget::Number(n), false) = (&c.target, c.kind == nctrans::ir::CallKind::M97) {
                                set.insert(*n);
                            }
                        }
                    }
                }
            }
        });
    }
    set
}

/// The file beside `dir` that holds FANUC program `n`: `O1234.nc`, `1234.nc`, a name that
/// starts with it (`O01234_PROBE.nc`), or any FANUC file holding the line `O1234`; any case,
/// `.nc`/`.tap`/`.txt`/no extension (`eval::callee_files`).
pub fn find_callee_file(dir: &Path, n: u32) -> Option<PathBuf> {
    nctrans::eval::callee_files::find(dir, None, n, &nctrans::eval::callee_files::fanuc_ext)
}

/// The loaded job: the main unit, the callee units found beside it, and the source DB.
pub struct Job {
    pub db: SourceDb,
    pub units: Vec<Unit>,
    pub loaded: nctrans::Loaded,
    /// The files read: the input, then the callee files (no output may be one of them).
    pub read: Vec<PathBuf>,
    /// The warnings of reading the files (shown before the translation's).
    pub warnings: Vec<diag::Diagnostic>,
    /// Program numbers after a closing `%` in the files read (see `Options::after_end`).
    pub after_end: BTreeSet<u32>,
}

/// Loads `path` and, transitively, the callees it needs that are not in the file itself.
pub fn load_job(
    path: &Path,
    encoding: Option<&'static encoding_rs::Encoding>,
    profile: &nctrans::dialect::Semantics,
) -> Result<Job, (SourceDb, Vec<diag::Diagnostic>)> {
    let mut db = SourceDb::new();
    let bytes = match std::fs::read(path) {
        Ok(b) => b,
        Err(e) => {
            return Err((db, vec![diag::Diagnostic::error("NC102", format!("cannot read {}: {e}", path.display()))]))
        }
    };
    let name = path.display().to_string();
    let loaded = nctrans::load(&mut db, &name, &bytes, encoding);
    let opts = ParseOptions { semantics: profile.clone() };
    let parsed = nctrans::parse(&db, loaded.file, Dialect::Fanuc, &opts);
    let mut diags = parsed.diags;
    let mut after_end: BTreeSet<u32> = parsed.after_end_programs.into_iter().collect();
    let mut units = vec![parsed.unit];
    let dir = beside(path);
    let mut read = vec![path.to_path_buf()];
    load_callees(&mut db, &mut units, &dir, encoding, &opts, &mut diags, (&mut read, &mut after_end));
    if diag::has_errors(&diags) {
        return Err((db, diags));
    }
    // Warnings of reading are shown, not fatal.
    Ok(Job { db, units, loaded, read, warnings: diags, after_end })
}

/// The folder a file is in (`.` for a bare file name, whose parent is empty).
fn beside(path: &Path) -> PathBuf {
    path.parent().filter(|p| !p.as_os_str().is_empty()).map_or_else(|| PathBuf::from("."), Path::to_path_buf)
}

/// Loads, transitively, the callees `units` need that none of them holds, from the files
/// beside them in `dir` (`find_callee_file`), in the order the whole path takes them (each
/// round the wanted numbers ascending); their reading diagnostics go to `diags`, their
/// paths to `read`. Returns the numbers called that were not found.
fn load_callees(
    db: &mut SourceDb,
    units: &mut Vec<Unit>,
    dir: &Path,
    encoding: Option<&'static encoding_rs::Encoding>,
    opts: &ParseOptions,
    diags: &mut Vec<diag::Diagnostic>,
    (read, after_end): (&mut Vec<PathBuf>, &mut BTreeSet<u32>),
) -> BTreeSet<u32> {
    let mut have: BTreeSet<u32> = BTreeSet::new();
    let mut tried: BTreeSet<u32> = BTreeSet::new();
    let mut missing = BTreeSet::new();
    loop {
        for u in units.iter() {
            for p in &u.programs {
                if let Some(nctrans::ir::ProgName::Number(n)) = &p.name {
                    have.insert(*n);
                }
            }
        }
        let want: Vec<u32> = units
            .iter()
            .flat_map(called_numbers)
            .filter(|n| !have.contains(n) && !tried.contains(n))
            .collect::<BTreeSet<u32>>()
            .into_iter()
            .collect();
        if want.is_empty() {
            break;
        }
        for n in want {
            tried.insert(n);
            let Some(p) = find_callee_file(dir, n) else {
                missing.insert(n);
                continue;
            };
            let Ok(bytes) = std::fs::read(&p) else {
                missing.insert(n);
                continue;
            };
            read.push(p.clone());
            let l = nctrans::load(db, &p.display().to_string(), &bytes, encoding);
            let parsed = nctrans::parse(db, l.file, Dialect::Fanuc, opts);
            diags.extend(parsed.diags);
            after_end.extend(parsed.after_end_programs);
            units.push(parsed.unit);
        }
    }
    missing
}

/// The callees of a streamed skeleton `unit` (the main program's macro part and the other
/// programs of the file) beside the input, loaded as [`load_job`] loads them (file ids
/// from 1 up); declines a call of a program found nowhere and a callee with diagnostics.
fn callees_beside(
    req: &Request,
    opts: &Options,
    unit: &Unit,
    read: &mut Vec<PathBuf>,
) -> Result<Vec<Unit>, nctrans::stream::translate::Fallback> {
    use nctrans::stream::translate::Fallback;
    let mut db = SourceDb::new();
    db.add(req.file.display().to_string(), String::new());
    let dir = beside(req.file);
    let popts = ParseOptions { semantics: opts.source.clone() };
    let (mut units, mut diags) = (vec![unit.clone()], Vec::new());
    let missing =
        load_callees(&mut db, &mut units, &dir, req.encoding, &popts, &mut diags, (read, &mut BTreeSet::new()));
    if !missing.is_empty() {
        return Err(Fallback::NotStraight("a call of a program found neither in the file nor beside it".into()));
    }
    if !diags.is_empty() {
        return Err(Fallback::NotStraight("a called program with diagnostics".into()));
    }
    units.remove(0);
    Ok(units)
}

fn encode(text: &str, loaded: &nctrans::Loaded) -> Vec<u8> {
    read::encode(text, loaded.encoding, loaded.bom)
}

/// Runs `nctrans --to sinumerik` (the options are the translation mode's, shared with
/// `--to fanuc`; `--program-map` reads `9010=PROBE_X` in this direction). `config` is the
/// project configuration with the flags given applied over it.
pub fn run(args: &TranslateArgs, config: &Config) -> ExitCode {
    let Some(file) = args.input.as_deref() else {
        eprintln!("error: --to sinumerik needs an input file: nctrans --to sinumerik IN.nc");
        return ExitCode::from(2);
    };
    if let Err(code) = crate::cli_dialect::check_direction(file, args.from, Dialect::Sinumerik) {
        return code;
    }
    let fanuc_only = [
        ("--tool-map", !args.tool_map.is_empty()),
        ("--program-number", args.program_number.is_some()),
        ("--number-blocks", args.number_blocks.is_some()),
        ("--compound-conditions", args.compound_conditions),
        ("--comments", args.comments != "keep"),
    ];
    if let Some((flag, _)) = fanuc_only.iter().find(|(_, given)| *given) {
        eprintln!("error: {flag} applies to --to fanuc only");
        return ExitCode::from(2);
    }
    let force = config.force;
    let req = Request {
        file,
        out: args.output.as_deref(),
        encoding: config.input_encoding,
        force,
        verify: config.verify,
        max_steps: config.max_steps,
    };
    let stem = req.file.file_stem().and_then(|s| s.to_str()).unwrap_or("MAIN");
    // -o naming the main file: refused before anything is read when it is the input, or an
    // existing file without --force (the subprogram files are checked once they are named).
    if let Some(o) = req.out.filter(|o| !out_place(o).0) {
        if let Err(code) = crate::out_guard::check(o, &[file.to_path_buf()], force, "-o") {
            return code;
        }
    }
    let opts = match options(args, stem, config) {
        Ok(o) => o,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    if let Some(code) = streamed(args, &req, &opts) {
        return code;
    }
    let job = match load_job(req.file, req.encoding, &opts.source) {
        Ok(j) => j,
        Err((db, diags)) => {
            eprint!("{}", diag::render(&db, &diags));
            return ExitCode::from(1);
        }
    };
    eprint!("{}", diag::render(&job.db, &job.warnings));
    let mut opts = opts;
    opts.after_end = job.after_end.clone();
    let units: Vec<&Unit> = job.units.iter().collect();
    let tr = ts::translate(&units, &opts, job.loaded.line_ending);
    eprint!("{}", diag::render(&job.db, &tr.diags));
    if tr.has_errors() {
        eprintln!("error: translation failed; nothing written");
        return ExitCode::from(1);
    }
    if let Err(code) = write_files(&req, &tr, &job.loaded, &job.read) {
        return code;
    }
    let warned = tr.diags.iter().any(|d| d.code.starts_with("NC3"));
    if warned && opts.unsupported == UnsupportedPolicy::Warn {
        // An unfinished program (it alarms on its first line) is never verified, so never
        // called equivalent.
        eprintln!(
            "not verified: the output is unfinished (blocks marked NCTRANS UNSUPPORTED; it alarms on its first line)"
        );
        eprintln!("error: unsupported constructs were written as marked comments");
        return ExitCode::from(1);
    }
    let mut code = ExitCode::SUCCESS;
    if req.verify {
        code = verify(&job, &tr, &req, req.max_steps, &opts);
    }
    code
}

/// Where `-o` puts the files: whether it names a folder (an existing one, or written with a
/// trailing slash: every file under its own name), and the folder of the subprograms (a
/// file path names the main program, subprograms go beside it).
fn out_place(o: &Path) -> (bool, PathBuf) {
    let is_dir = o.is_dir() || o.to_string_lossy().ends_with('/');
    let dir = if is_dir { o.to_path_buf() } else { o.parent().map_or_else(|| PathBuf::from("."), Path::to_path_buf) };
    (is_dir, dir)
}

/// The line standard output shows in front of each file when there are several.
fn separator(name: &str, eol: read::LineEnding) -> String {
    format!("; ==== {name} ===={}", eol.as_str())
}

fn write_files(
    req: &Request,
    tr: &ts::Translation,
    loaded: &nctrans::Loaded,
    read: &[PathBuf],
) -> Result<(), ExitCode> {
    match req.out {
        None => {
            let mut out = std::io::stdout().lock();
            let several = tr.files.len() > 1;
            for f in &tr.files {
                let mut text = String::new();
                if several {
                    text.push_str(&separator(&f.name, loaded.line_ending));
                }
                text.push_str(&f.text);
                if out.write_all(&encode(&text, loaded)).is_err() {
                    return Err(ExitCode::from(2));
                }
            }
        }
        Some(o) => {
            let (is_dir, dir) = out_place(o);
            let paths: Vec<PathBuf> =
                tr.files.iter().map(|f| if !is_dir && f.main { o.to_path_buf() } else { dir.join(&f.name) }).collect();
            // Every file checked before the first is written: none is half done.
            crate::out_guard::check_all(paths.iter().map(PathBuf::as_path), read, req.force)?;
            if is_dir {
                if let Err(e) = std::fs::create_dir_all(&dir) {
                    eprintln!("error: cannot create {}: {e}", dir.display());
                    return Err(ExitCode::from(2));
                }
            }
            for (f, path) in tr.files.iter().zip(&paths) {
                write_one(path, &encode(&f.text, loaded))?;
            }
        }
    }
    Ok(())
}

/// Writes one file of `-o` and says so.
fn write_one(path: &Path, bytes: &[u8]) -> Result<(), ExitCode> {
    if let Err(e) = std::fs::write(path, bytes) {
        eprintln!("error: cannot write {}: {e}", path.display());
        return Err(ExitCode::from(2));
    }
    eprintln!("wrote {}", path.display());
    Ok(())
}

/// How the files of a translation are encoded: the source's encoding and byte-order mark.
type Encoded = (&'static encoding_rs::Encoding, bool);

/// The subprogram files of a streamed translation, after its main file, as [`write_files`]
/// writes them (each encoded whole, `enc`): on standard output each after its separator
/// line, else beside the main file (or in the folder).
fn write_subs(req: &Request, subs: &[ts::OutFile], eol: read::LineEnding, enc: Encoded) -> Result<(), ExitCode> {
    match req.out {
        None => {
            let mut out = std::io::stdout().lock();
            for f in subs {
                let text = format!("{}{}", separator(&f.name, eol), f.text);
                if out.write_all(&read::encode(&text, enc.0, enc.1)).is_err() {
                    return Err(ExitCode::from(2));
                }
            }
        }
        Some(o) => {
            let (_, dir) = out_place(o);
            for f in subs {
                write_one(&dir.join(&f.name), &read::encode(&f.text, enc.0, enc.1))?;
            }
        }
    }
    Ok(())
}

/// The main file of a streamed translation with subprograms on standard output, as
/// [`write_files`] writes it: `encode(separator + text)`, which is the separator encoded
/// (with the byte-order mark in front, when there is one) and then the encoded text as
/// written (its own mark left out). The separator is ASCII, so encoding it apart from the
/// text gives the same bytes (every encoder starts and ends in its ASCII state).
fn main_to_stdout(out: &Path, name: &str, eol: read::LineEnding, enc: Encoded) -> std::io::Result<()> {
    let mut so = std::io::stdout().lock();
    so.write_all(&read::encode(&separator(name, eol), enc.0, enc.1))?;
    let mut f = std::io::BufReader::new(std::fs::File::open(out)?);
    if enc.0 == encoding_rs::UTF_8 && enc.1 {
        let mut mark = [0u8; 3];
        std::io::Read::read_exact(&mut f, &mut mark)?;
        if &mark != b"\xEF\xBB\xBF" {
            so.write_all(&mark)?;
        }
    }
    std::io::copy(&mut f, &mut so)?;
    so.flush()
}

/// Runs both programs and reports: "equivalent (N events)" and success, or the first
/// divergence / inconclusive run and failure.
fn verify(job: &Job, tr: &ts::Translation, req: &Request, max_steps: u64, opts: &Options) -> ExitCode {
    let out_dir = match req.out {
        Some(o) if o.is_dir() || o.to_string_lossy().ends_with('/') => o.display().to_string(),
        Some(o) => o.parent().map_or_else(String::new, |p| p.display().to_string()),
        None => "<stdout>".to_string(),
    };
    let main_unit = &job.units[0];
    let profiles = nctrans::verify_sinumerik::Profiles { fanuc: opts.source.clone(), sinumerik: opts.target.clone() };
    let report = nctrans::verify_sinumerik::verify_profiled(
        &job.db,
        job.loaded.file,
        main_unit,
        tr,
        &out_dir,
        max_steps,
        &profiles,
    );
    eprint!("{}", diag::render(&report.db, &report.diags));
    verdict(report.verdict, &report.diff)
}

/// Prints a verification's verdict; success only for "equivalent".
fn verdict(v: Verdict, diff: &str) -> ExitCode {
    match v {
        Verdict::Equivalent { events } => {
            eprintln!("equivalent ({events} events)");
            ExitCode::SUCCESS
        }
        Verdict::Diverged { .. } => {
            if !diff.is_empty() {
                eprintln!("{diff}");
            }
            eprintln!("error: the translation is not equivalent");
            ExitCode::from(1)
        }
        Verdict::Inconclusive { reason } => {
            eprintln!("inconclusive: {reason}");
            ExitCode::from(1)
        }
        Verdict::Failed => {
            eprintln!("error: verification could not run");
            ExitCode::from(1)
        }
    }
}

/// `--to sinumerik` as a stream, for an input of 8 MB and more (or `--stream`) that is a
/// straight-line program: translated chunk by chunk into the output, then verified with
/// both programs streamed. `None` when it is not (then it is translated whole; a partial
/// output is removed first). Prints what the whole path prints; diagnostics point into
/// files that are not loaded, so they are shown compactly with their line.
/// A source in a legacy encoding streams from a decoded UTF-8 copy, and its translation is
/// written as UTF-8 first, verified from there, then encoded (as the whole path encodes).
fn streamed(args: &TranslateArgs, req: &Request, opts: &Options) -> Option<ExitCode> {
    use crate::stream_cli;
    let size = std::fs::metadata(req.file).ok()?.len();
    if !(args.stream || size >= stream_cli::AUTO_BYTES) {
        return None;
    }
    if nctrans::empty::may_be_program_less(req.file) {
        return None;
    }
    let mut src = stream_cli::Source::new(req.file, req.encoding)?;
    // An output folder the stream creates is removed again when the whole path takes over
    // (which creates it only for a translation it writes).
    let made = req.out.filter(|o| o.to_string_lossy().ends_with('/') && !o.exists());
    let code = (|| loop {
        match streamed_from(req, opts, &src, size) {
            Ok(code) => return code,
            Err(why) => src.transcoded(&why)?,
        }
    })();
    if let (None, Some(dir)) = (&code, made) {
        let _ = std::fs::remove_dir(dir);
    }
    code
}

/// [`streamed`] from `src`; `Err` when the source is found not to be UTF-8 (nothing is
/// left written: the caller streams again from a decoded copy).
fn streamed_from(
    req: &Request,
    opts: &Options,
    src: &crate::stream_cli::Source,
    size: u64,
) -> Result<Option<ExitCode>, NotStreamable> {
    use crate::stream_cli::{self, ProgressLine};
    use nctrans::stream::to_sinumerik as sts;
    use nctrans::stream::translate::Fallback;
    let path = src.path();
    let (Some(eol), Some((enc, bom))) = (src.line_ending(), src.encoding()) else {
        return Ok(None);
    };
    let stem = req.file.file_stem().and_then(|s| s.to_str()).unwrap_or("out");
    // Written to a temporary file and renamed: a program found not to be straight-line part
    // way is then translated whole; standard output gets a copy of the finished file.
    let is_dir = |o: &Path| o.is_dir() || o.to_string_lossy().ends_with('/');
    // A special target (`-o /dev/null`, see `stream_cli::is_special`) is copied into at the end.
    let special = req.out.filter(|o| stream_cli::is_special(o));
    let tmp = match req.out {
        None => std::env::temp_dir().join(format!("nctrans-{}-{stem}.mpf", std::process::id())),
        Some(_) if special.is_some() => std::env::temp_dir().join(format!("nctrans-{}-{stem}.mpf", std::process::id())),
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
    let mut w = match stream_cli::create_temp(write_to) {
        Ok(w) => w,
        Err(code) => return Ok(Some(code)),
    };
    let with_subs = special.is_none();
    let mut subs: Vec<ts::OutFile> = Vec::new();
    // The files read (the input, the callees beside it): no output may be one of them.
    let mut read = vec![req.file.to_path_buf()];
    let mut line = ProgressLine::new("translating", size);
    let mut report = |p: nctrans::stream::Progress| line.update(p);
    let r = sts::to_sinumerik(path, opts, eol, &mut w, Some(&mut report));
    line.done();
    drop(w);
    // Not straight-line: segmented (the macro part whole, its runs of straight blocks
    // streamed), else the whole-file path (with a note only when segmented declines too).
    let r = match r {
        Err(Fallback::NotStraight(_)) => {
            let mut w = match stream_cli::create_temp(write_to) {
                Ok(w) => w,
                Err(code) => return Ok(Some(code)),
            };
            let mut line = ProgressLine::new("translating", size);
            let mut report = |p: nctrans::stream::Progress| line.update(p);
            // Calls of subprograms (after the main program, or beside the file as the whole
            // path finds them) are taken when the files are written as `write_files` writes
            // them: to a file, a folder or stdout (not a special target).
            let r = if with_subs {
                let mut load = |u: &Unit| callees_beside(req, opts, u, &mut read);
                sts::segmented::to_sinumerik_with_subs(path, opts, eol, &mut load, &mut w, Some(&mut report)).map(
                    |(d, s)| {
                        subs = s;
                        d
                    },
                )
            } else {
                sts::segmented::to_sinumerik(path, opts, eol, &mut w, Some(&mut report))
            };
            line.done();
            drop(w);
            if let Err(Fallback::NotStreamable(NotStreamable::NotUtf8 { .. })) = &r {
                let _ = std::fs::remove_file(write_to);
                if let Err(Fallback::NotStreamable(e)) = r {
                    return Err(e);
                }
            }
            r.map_err(|f| Fallback::NotStraight(stream_cli::segmented_why(&f)))
        }
        r => r,
    };
    let done = match r {
        Ok(d) => d,
        Err(f) => {
            let _ = std::fs::remove_file(write_to);
            match f {
                Fallback::NotStraight(why) => stream_cli::note_read_whole(req.file, size, &why),
                Fallback::NotStreamable(e @ NotStreamable::NotUtf8 { .. }) => return Err(e),
                _ => {}
            }
            return Ok(None);
        }
    };
    if let Some(u) = &utf8 {
        if let Err(code) = stream_cli::encode_output(u.path(), enc, bom, &tmp) {
            return Ok(Some(code));
        }
    }
    let mut db = SourceDb::new();
    db.add(req.file.display().to_string(), String::new());
    eprint!("{}", nctrans::excerpt::render(&db, &done.diags, &[(0, path)]));
    let out = match req.out {
        None => tmp.clone(),
        Some(_) if special.is_some() => tmp.clone(),
        Some(o) if is_dir(o) => o.join(&done.file_name),
        Some(o) => o.to_path_buf(),
    };
    if let Some(o) = req.out.filter(|_| special.is_none()) {
        let dir = out_place(o).1;
        let mut paths = vec![out.clone()];
        paths.extend(subs.iter().map(|f| dir.join(&f.name)));
        if let Err(code) = crate::out_guard::check_all(paths.iter().map(PathBuf::as_path), &read, req.force) {
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
        if let Err(e) = stream_cli::copy_into(&out, t) {
            let _ = std::fs::remove_file(&out);
            eprintln!("error: cannot write {}: {e}", t.display());
            return Ok(Some(ExitCode::from(2)));
        }
        eprintln!("wrote {}", t.display());
    } else if req.out.is_none() {
        let copied = if subs.is_empty() {
            stream_cli::copy_to_stdout(&out)
        } else {
            main_to_stdout(&out, &done.file_name, eol, (enc, bom))
        };
        if copied.is_err() {
            let _ = std::fs::remove_file(&out);
            return Ok(Some(ExitCode::from(2)));
        }
        if let Err(code) = write_subs(req, &subs, eol, (enc, bom)) {
            let _ = std::fs::remove_file(&out);
            return Ok(Some(code));
        }
    } else {
        eprintln!("wrote {}", out.display());
        if let Err(code) = write_subs(req, &subs, eol, (enc, bom)) {
            return Ok(Some(code));
        }
    }
    let warned = done.diags.iter().any(|d| d.code.starts_with("NC3"));
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
        // whole path's verifier shows them (`verify_sinumerik::Emitted`).
        let files = subs
            .iter()
            .map(|f| {
                let shown = if out_dir.is_empty() { f.name.clone() } else { format!("{out_dir}/{}", f.name) };
                (f.program.clone(), shown, f.text.clone())
            })
            .collect();
        let emitted = nctrans::verify_sinumerik::Emitted { files, semantics: opts.target.clone() };
        let back = (read_back, shown.as_str(), Box::new(emitted) as _);
        code = verify_streamed((req.file, path), back, done.index, req.max_steps, opts, size);
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
fn verify_streamed(
    (input, input_read): (&Path, &Path),
    (out, shown, out_callees): (&Path, &str, Box<dyn nctrans::eval::CalleeSource + Send>),
    source: nctrans::stream::Index,
    max_steps: u64,
    opts: &Options,
    size: u64,
) -> ExitCode {
    use crate::stream_cli::ProgressLine;
    use nctrans::eval::{header_inputs, DirCallees, RunOptions};
    use nctrans::stream::to_sinumerik::{self as sts, ReadBack, StreamSide};
    let mut line = ProgressLine::new("reading back", size);
    let mut report = |p: nctrans::stream::Progress| line.update(p);
    let popts = ParseOptions { semantics: opts.target.clone() };
    let back = sts::read_back(out, 1, Dialect::Sinumerik, &popts, Some(&mut report));
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
            return verdict(Verdict::Failed, "");
        }
        Err(ReadBack::Unreadable(e)) => {
            eprintln!("error: {} cannot be read back: {e}", out.display());
            return verdict(Verdict::Failed, "");
        }
    };
    let (in_a, in_b) = match (header_inputs(&source.header), header_inputs(&back.header)) {
        (Ok(a), Ok(b)) => (a, b),
        (Err(e), _) | (_, Err(e)) => {
            let d = diag::Diagnostic::error("NC407", format!("bad `nctrans: set` header line: {e}"));
            eprint!("{}", nctrans::excerpt::render(&db, &[d], &streamed));
            return verdict(Verdict::Failed, "");
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
    let report = sts::compare(a, b);
    eprint!("{}", nctrans::excerpt::render(&report.db, &report.diags, &streamed));
    verdict(report.verdict, &report.diff)
}
