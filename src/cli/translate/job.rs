//! What a single-file translation reads and writes, for both targets and both paths (whole
//! and streamed): the options from the configuration, the input and the callees found
//! beside it, the output files under the rules of `-o`, and the verdict of the proof. The
//! driver (`super::translate_file`) is one for every target; each choice a target makes
//! differently is one function here that decides by the target (so a new target's arms
//! are the ones the compiler lists).

use super::TranslateArgs;
use nctrans::batch::jobs::JobSettings;
use nctrans::check::Verdict;
use nctrans::config::Config;
use nctrans::dialect::{empty_call, Dialect, ParseOptions};
use nctrans::ir::{CallTarget, ItemKind, StmtKind, Unit};
use nctrans::lower::to_fanuc::varmap;
use nctrans::span::SourceDb;
use nctrans::translate::library::ProgKey;
use nctrans::translate::to_sinumerik::{self as ts, Options, UnsupportedPolicy, VarMapRule};
use nctrans::translate::{self, to_fanuc::TranslateOptions, Translation};
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
/// applied over it (`cli::configure`).
pub fn sinumerik_options(args: &TranslateArgs, stem: &str, c: &Config) -> Result<Options, String> {
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

/// Translation options from the configuration (flags already applied over `nctrans.toml`).
pub fn fanuc_options(c: &Config, input: &Path, eol: read::LineEnding) -> Result<TranslateOptions, String> {
    let mut var_rules = Vec::new();
    for s in &c.var_map_to_fanuc {
        var_rules.extend(varmap::parse_rules(s).map_err(|e| format!("--var-map {e}"))?);
    }
    let program_map = c
        .programs_to_fanuc
        .iter()
        .filter_map(|(k, v)| match (k, v) {
            (ProgKey::Name(s), ProgKey::Number(n)) => Some((s.to_ascii_uppercase(), *n)),
            _ => None,
        })
        .collect();
    Ok(TranslateOptions {
        var_rules,
        tool_map: c.tools.clone(),
        program_map,
        program_number: c.program_number,
        l_numbers: c.l_numbers,
        max_program_number: c.fanuc.max_program_number(),
        ..nctrans::batch::target::fanuc::file_options(&JobSettings::of(c), input, eol)
    })
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
    /// The profile the files were read with (Sinumerik: with the library's definitions).
    pub profile: nctrans::dialect::Semantics,
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
    Ok(Job { db, units, loaded, read, warnings: diags, after_end, profile: profile.clone() })
}

/// The folder a file is in (`.` for a bare file name, whose parent is empty).
pub fn beside(path: &Path) -> PathBuf {
    path.parent().filter(|p| !p.as_os_str().is_empty()).map_or_else(|| PathBuf::from("."), Path::to_path_buf)
}

/// Loads, transitively, the callees `units` need that none of them holds, from the files
/// beside them in `dir` (`find_callee_file`), in the order the whole path takes them (each
/// round the wanted numbers ascending); their reading diagnostics go to `diags`, their
/// paths to `read`; a program-less callee file is NC593 at each call of it instead of its
/// NC145. Returns the numbers called that were not found.
pub fn load_callees(
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
    let mut empties = Vec::new();
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
            if empty_call::is_program_less(&parsed.diags) {
                empties.push((l.file, nctrans::ir::ProgName::Number(n)));
            }
            diags.extend(parsed.diags);
            after_end.extend(parsed.after_end_programs);
            units.push(parsed.unit);
        }
    }
    // A callee file without a program: said at each call of it (NC593).
    let callers: Vec<&Unit> = units.iter().collect();
    empty_call::at_call_sites(db, &callers, &empties, diags);
    missing
}

pub fn encode(text: &str, loaded: &nctrans::Loaded) -> Vec<u8> {
    read::encode(text, loaded.encoding, loaded.bom)
}

/// Where `-o` puts the files: whether it names a folder (an existing one, or written with a
/// trailing slash: every file under its own name), and the folder of the subprograms (a
/// file path names the main program, subprograms go beside it).
pub fn out_place(o: &Path) -> (bool, PathBuf) {
    let is_dir = o.is_dir() || o.to_string_lossy().ends_with('/');
    let dir = if is_dir { o.to_path_buf() } else { o.parent().map_or_else(|| PathBuf::from("."), Path::to_path_buf) };
    (is_dir, dir)
}

/// The line standard output shows in front of each file when there are several.
pub fn separator(name: &str, eol: read::LineEnding) -> String {
    format!("; ==== {name} ===={}", eol.as_str())
}

pub fn write_files(
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
            crate::cli::out_guard::check_all(paths.iter().map(PathBuf::as_path), read, req.force)?;
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
pub fn write_one(path: &Path, bytes: &[u8]) -> Result<(), ExitCode> {
    if let Err(e) = std::fs::write(path, bytes) {
        eprintln!("error: cannot write {}: {e}", path.display());
        return Err(ExitCode::from(2));
    }
    eprintln!("wrote {}", path.display());
    Ok(())
}

/// How the files of a translation are encoded: the source's encoding and byte-order mark.
pub type Encoded = (&'static encoding_rs::Encoding, bool);

/// The subprogram files of a streamed translation, after its main file, as [`write_files`]
/// writes them (each encoded whole, `enc`): on standard output each after its separator
/// line, else beside the main file (or in the folder).
pub fn write_subs(req: &Request, subs: &[ts::OutFile], eol: read::LineEnding, enc: Encoded) -> Result<(), ExitCode> {
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
pub fn main_to_stdout(out: &Path, name: &str, eol: read::LineEnding, enc: Encoded) -> std::io::Result<()> {
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

/// Prints a verification's verdict; success only for "equivalent".
pub fn verdict(v: Verdict, diff: &str) -> ExitCode {
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

/// The folder a proof to Sinumerik shows the files in (as `-o` puts them, or `<stdout>`).
pub fn shown_dir(out: Option<&Path>) -> String {
    match out {
        Some(o) if out_place(o).0 => o.display().to_string(),
        Some(o) => o.parent().map_or_else(String::new, |p| p.display().to_string()),
        None => "<stdout>".to_string(),
    }
}

/// Prints the combined verdict of a FANUC → Sinumerik proof made of several runs (the main
/// program's, each called macro's alone: `translate::called`): the first one not
/// equivalent as [`verdict`] does, named; `render` shows its diagnostics.
pub fn combined(c: translate::called::Combined, render: &dyn Fn(&SourceDb, &[diag::Diagnostic]) -> String) -> ExitCode {
    use translate::called::Combined;
    match c {
        Combined::Equivalent { events, runs, excluded } => {
            eprintln!("{}", Combined::summary(events, runs, &excluded));
            ExitCode::SUCCESS
        }
        Combined::Not(label, report) => {
            if !label.is_empty() {
                // (The main run's are shown.)
                eprint!("{}", render(&report.db, &report.diags));
                eprintln!("in the run{label}:");
            }
            verdict(report.verdict, &report.diff)
        }
    }
}

/// Writes through a temporary file and a rename, so a failed run never leaves half a program.
pub fn write_output(path: Option<&Path>, bytes: &[u8]) -> Result<(), String> {
    use std::io::Write;
    match path {
        None => std::io::stdout().lock().write_all(bytes).map_err(|e| format!("cannot write: {e}")),
        // A device or FIFO (`-o /dev/null`) is written into: a rename would replace it.
        Some(p) if crate::cli::stream::is_special(p) => std::fs::OpenOptions::new()
            .write(true)
            .open(p)
            .and_then(|mut f| f.write_all(bytes))
            .map_err(|e| format!("cannot write {}: {e}", p.display())),
        Some(p) => {
            let tmp = p.with_extension(format!("{}.nctrans-tmp", p.extension().and_then(|e| e.to_str()).unwrap_or("")));
            std::fs::write(&tmp, bytes).map_err(|e| format!("cannot write {}: {e}", tmp.display()))?;
            std::fs::rename(&tmp, p).map_err(|e| {
                // Nothing of a failed write stays behind.
                let _ = std::fs::remove_file(&tmp);
                format!("cannot write {}: {e}", p.display())
            })
        }
    }
}

/// The programs `unit` calls by name, transitively, each name once: `load` gives a callee's
/// unit (`None`: skipped), whose calls are followed in turn; its first `Err` stops. A unit
/// that calls `"L"<<n` also calls every name of `l_names` (the `L<k>` programs beside it,
/// under `--l-numbers`; [`l_names_beside`]).
pub fn callees<E>(
    unit: &Unit,
    l_names: &[String],
    mut load: impl FnMut(&str) -> Result<Option<Unit>, E>,
) -> Result<Vec<Unit>, E> {
    use nctrans::lower::to_fanuc::string_calls::{called_names, calls_built_l};
    let mut subs = Vec::new();
    let mut todo = called_names(unit);
    let mut l_added = calls_built_l(unit);
    if l_added {
        todo.extend(l_names.iter().rev().cloned());
    }
    let mut seen: Vec<String> = Vec::new();
    while let Some(callee) = todo.pop() {
        if seen.contains(&callee) {
            continue;
        }
        let sub = load(&callee)?;
        seen.push(callee);
        if let Some(u) = sub {
            todo.extend(called_names(&u));
            if !l_added && calls_built_l(&u) {
                l_added = true;
                todo.extend(l_names.iter().rev().cloned());
            }
            subs.push(u);
        }
    }
    Ok(subs)
}

/// With `on` (`--l-numbers`), the names of the `L<k>` subprograms beside `input` (`L10.SPF`,
/// any case; DIN names without a leading zero), in number order: the programs a call of
/// `"L"<<n` can reach.
pub fn l_names_beside(input: &Path, on: bool) -> Vec<String> {
    if !on {
        return Vec::new();
    }
    let dir = beside(input);
    let mut found: Vec<(u64, String)> = std::fs::read_dir(dir)
        .map(|rd| {
            rd.filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|f| f.extension().and_then(|x| x.to_str()).is_some_and(|x| x.eq_ignore_ascii_case("spf")))
                .filter_map(|f| {
                    let stem = f.file_stem()?.to_str()?.to_ascii_uppercase();
                    Some((nctrans::translate::to_fanuc::numbers::l_number(&stem)?, stem))
                })
                .collect()
        })
        .unwrap_or_default();
    found.sort();
    found.dedup();
    found.into_iter().map(|(_, s)| s).collect()
}

pub fn find_beside(input: &Path, name: &str) -> Option<PathBuf> {
    let dir = input.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or_else(|| Path::new("."));
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir).ok()?.filter_map(|e| e.ok().map(|e| e.path())).collect();
    files.sort();
    files.into_iter().find(|f| {
        let stem = f.file_stem().and_then(|s| s.to_str()).unwrap_or("");
        let ext = f.extension().and_then(|s| s.to_str()).unwrap_or("").to_ascii_lowercase();
        stem.eq_ignore_ascii_case(name) && ext == "spf"
    })
}

/// How the command line asks for the input it misses.
pub fn needs_input(to: Dialect) -> &'static str {
    match to {
        Dialect::Fanuc => "--to needs an input file: nctrans --to fanuc IN.MPF",
        Dialect::Sinumerik => "--to sinumerik needs an input file: nctrans --to sinumerik IN.nc",
    }
}

/// A flag given that means nothing to `to` (the FANUC writer's own).
pub fn foreign_flag(args: &TranslateArgs, to: Dialect) -> Option<&'static str> {
    if to == Dialect::Fanuc {
        return None;
    }
    let fanuc_only = [
        ("--tool-map", !args.tool_map.is_empty()),
        ("--program-number", args.program_number.is_some()),
        ("--number-blocks", args.number_blocks.is_some()),
        ("--compound-conditions", args.compound_conditions),
        ("--comments", args.comments != "keep"),
    ];
    fanuc_only.iter().find(|(_, given)| *given).map(|(flag, _)| *flag)
}

/// The options of a translation of `input` to `to` from the configuration; the parts that
/// depend on what is read are [`complete`]d once it is.
pub fn options(args: &TranslateArgs, c: &Config, input: &Path, to: Dialect) -> Result<translate::Options, String> {
    Ok(match to {
        Dialect::Fanuc => translate::Options::to_fanuc(fanuc_options(c, input, read::LineEnding::Lf)?),
        Dialect::Sinumerik => {
            let stem = input.file_stem().and_then(|s| s.to_str()).unwrap_or("MAIN");
            translate::Options::to_sinumerik(sinumerik_options(args, stem, c)?, read::LineEnding::Lf)
        }
    })
}

/// The options' parts that depend on the files read: the profile they were read with, the
/// output's line ending (to FANUC as `line_ends` says, to Sinumerik the input's), and the
/// programs after a closing `%`.
pub fn complete(opts: &mut translate::Options, c: &Config, job: &Job, to: Dialect) {
    let eol = job.loaded.line_ending;
    match to {
        Dialect::Fanuc => {
            opts.fanuc.source = job.profile.clone();
            opts.fanuc.line_ending = JobSettings::of(c).line_ending(eol);
            opts.line_ending = opts.fanuc.line_ending;
        }
        Dialect::Sinumerik => {
            opts.sinumerik.after_end = job.after_end.clone();
            opts.line_ending = eol;
        }
    }
}

/// Reads the input (as the dialect `to` is translated from) and the callees found beside
/// it; a failure has been shown, and is the exit code.
pub fn load(req: &Request, c: &Config, opts: &translate::Options, to: Dialect) -> Result<Job, ExitCode> {
    match to {
        Dialect::Fanuc => load_sinumerik(req, c),
        Dialect::Sinumerik => load_job(req.file, req.encoding, &opts.sinumerik.source).map_err(|(db, diags)| {
            eprint!("{}", diag::render(&db, &diags));
            ExitCode::from(1)
        }),
    }
}

/// Loads a Sinumerik `input` with the global user data and macros of the library's
/// definition files, and the subprograms it calls found beside it (`NAME.SPF`, any case),
/// transitively; each file's diagnostics are shown as it is read.
fn load_sinumerik(req: &Request, c: &Config) -> Result<Job, ExitCode> {
    let input = req.file;
    let bytes =
        std::fs::read(input).map_err(|e| crate::cli::args::fail(format!("cannot read {}: {e}", input.display())))?;
    let mut db = SourceDb::new();
    let loaded = nctrans::load(&mut db, &input.display().to_string(), &bytes, c.input_encoding);
    let profile = crate::cli::profile::sinumerik(c, &mut db, input)?;
    let shown = |db: &SourceDb, diags: &[diag::Diagnostic]| {
        eprint!("{}", diag::render(db, diags));
        if diag::has_errors(diags) {
            return Err(ExitCode::from(1));
        }
        Ok(())
    };
    let popts = ParseOptions { semantics: profile.clone() };
    let parsed = nctrans::parse(&db, loaded.file, Dialect::Sinumerik, &popts);
    shown(&db, &parsed.diags)?;
    let mut read = vec![input.to_path_buf()];
    let l_names = l_names_beside(input, c.l_numbers);
    let mut empties = Vec::new();
    let subs = callees::<ExitCode>(&parsed.unit, &l_names, |callee| {
        let Some(path) = find_beside(input, callee) else { return Ok(None) };
        let Ok(bytes) = std::fs::read(&path) else { return Ok(None) };
        read.push(path.clone());
        let l = nctrans::load(&mut db, &path.display().to_string(), &bytes, None);
        let mut p = nctrans::parse(&db, l.file, Dialect::Sinumerik, &popts);
        // A file without a program is said at the calls of it, once all are read (NC593).
        if empty_call::is_program_less(&p.diags) && !p.diags.iter().any(|d| d.is_error() && d.code != "NC145") {
            empties.push((l.file, nctrans::ir::ProgName::Name(callee.to_string())));
            return Ok(Some(p.unit));
        }
        shown(&db, &p.diags)?;
        nctrans::dialect::sinumerik::name_after_file(&mut p.unit, callee);
        Ok(Some(p.unit))
    })?;
    let units: Vec<Unit> = std::iter::once(parsed.unit).chain(subs).collect();
    if !empties.is_empty() {
        let mut diags = Vec::new();
        empty_call::at_call_sites(&db, &units.iter().collect::<Vec<_>>(), &empties, &mut diags);
        shown(&db, &diags)?;
    }
    Ok(Job { db, units, loaded, read, warnings: vec![], after_end: BTreeSet::new(), profile })
}

/// Why nothing is written, when the translation is refused: to FANUC an error under the
/// error policy (under the warn policy the marked output is written), to Sinumerik any error.
pub fn refused(t: &Translation, opts: &translate::Options, to: Dialect) -> Option<String> {
    match to {
        Dialect::Fanuc => (t.has_errors()
            && opts.fanuc.unsupported == nctrans::lower::to_fanuc::UnsupportedPolicy::Error)
            .then(|| format!("not translated ({} construct(s) cannot be expressed on FANUC)", t.unsupported.max(1))),
        Dialect::Sinumerik => t.has_errors().then(|| "translation failed; nothing written".to_string()),
    }
}

/// Writes the translation: to FANUC the one file (in the output encoding, through a
/// temporary file), to Sinumerik each program's file ([`write_files`]).
pub fn write(req: &Request, t: &Translation, job: &Job, c: &Config, to: Dialect) -> Result<(), ExitCode> {
    match to {
        Dialect::Fanuc => {
            let loaded = &job.loaded;
            let bytes = read::encode(t.text(), c.output_encoding.unwrap_or(loaded.encoding), loaded.bom);
            // `-o DIR/` (or an existing folder) takes the file under the input's name, `.nc`.
            let target = req.out.map(|o| match (out_place(o), job.read.first().and_then(|i| i.file_name())) {
                ((true, dir), Some(name)) => dir.join(nctrans::batch::discover::fanuc_output(Path::new(name))),
                _ => o.to_path_buf(),
            });
            if let Some(o) = &target {
                crate::cli::out_guard::check(o, &job.read, c.force, "-o")?;
                if let Some(dir) = o.parent().filter(|d| !d.as_os_str().is_empty() && !d.exists()) {
                    std::fs::create_dir_all(dir)
                        .map_err(|e| crate::cli::args::fail(format!("cannot create {}: {e}", dir.display())))?;
                }
            }
            write_output(target.as_deref(), &bytes).map_err(crate::cli::args::fail)
        }
        Dialect::Sinumerik => write_files(req, t, &job.loaded, &job.read),
    }
}

/// What is shown when the written output is unfinished (constructs marked UNSUPPORTED under
/// the warn policy), which is then not verified.
pub fn unfinished(t: &Translation, opts: &translate::Options, to: Dialect) -> Option<[String; 2]> {
    match to {
        Dialect::Fanuc => (t.unsupported > 0 || t.has_errors()).then(|| {
            [
                "not verified: the output is unfinished (it alarms on its first line)".to_string(),
                format!("error: the output is incomplete: {} construct(s) marked UNSUPPORTED", t.unsupported),
            ]
        }),
        Dialect::Sinumerik => {
            let warned = t.diags.iter().any(|d| d.code.starts_with("NC3") || nctrans::unfinished::is_marked(d));
            (warned && opts.sinumerik.unsupported == UnsupportedPolicy::Warn).then(|| {
                [
                    "not verified: the output is unfinished (blocks marked NCTRANS UNSUPPORTED; it alarms on its first line)"
                        .to_string(),
                    "error: unsupported constructs were written as marked comments".to_string(),
                ]
            })
        }
    }
}

/// Proves the translation and shows the verdict; success only for an equivalence.
pub fn verify(job: &mut Job, t: &Translation, req: &Request, opts: &translate::Options, to: Dialect) -> ExitCode {
    match to {
        Dialect::Fanuc => {
            let out_name = req.out.map_or("<translation>.nc".to_string(), |p| p.display().to_string());
            let units: Vec<&Unit> = job.units.iter().collect();
            let v = translate::verify(&mut job.db, &units, t, &out_name, req.max_steps);
            eprint!("{}", v.rendered);
            eprintln!("{}", v.summary);
            if v.equivalent {
                ExitCode::SUCCESS
            } else {
                ExitCode::from(1)
            }
        }
        Dialect::Sinumerik => {
            let out_dir = shown_dir(req.out);
            let o = &opts.sinumerik;
            let vo = translate::VerifyOptions {
                max_steps: req.max_steps,
                profiles: Some(ts::verify::Profiles { fanuc: o.source.clone(), sinumerik: o.target.clone() }),
                set: &[],
                library: None,
                each_vacant: !o.specialise_callers,
            };
            let units: Vec<&Unit> = job.units.iter().collect();
            let v = translate::verify(&mut job.db, &units, t, &out_dir, vo);
            // The main run's diagnostics, then the verdict of all (a macro called by G65/G66
            // also runs alone, with its callers' arguments and each of them vacant).
            if let Some((_, main)) = v.runs.first() {
                eprint!("{}", diag::render(&main.db, &main.diags));
            }
            let render = |db: &SourceDb, diags: &[diag::Diagnostic]| diag::render(db, diags);
            combined(translate::called::combine(v.runs), &render)
        }
    }
}
