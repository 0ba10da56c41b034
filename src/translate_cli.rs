//! `nctrans --to fanuc IN [-o OUT] …`: the translation mode of the command line. Loads the
//! Siemens program and the subprograms it calls (beside it), translates, writes the output,
//! then verifies it by parsing it back as FANUC and comparing both runs' traces.

use nctrans::batch::library::ProgKey;
use nctrans::config::{Comments, Config, LineEnds, Unsupported};
use nctrans::dialect::fanuc::emit::CommentMode;
use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::ir::Unit;
use nctrans::passes::varmap;
use nctrans::passes::UnsupportedPolicy;
use nctrans::span::SourceDb;
use nctrans::translate::{self, TranslateOptions};
use nctrans::{diag, read};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(clap::Args, Debug)]
pub struct TranslateArgs {
    /// Translate the input to this dialect: fanuc, or sinumerik (alias siemens).
    #[arg(long, value_parser = parse_dialect)]
    pub to: Option<Dialect>,
    /// The program to translate.
    pub input: Option<PathBuf>,
    /// Dialect of the input (default: from its extension, .mpf/.spf or .nc/.tap, else its
    /// content); needed to read a file as the dialect its extension does not say.
    #[arg(long, value_parser = parse_dialect)]
    pub from: Option<Dialect>,
    /// Write the translation here (default: standard output).
    #[arg(short = 'o', long)]
    pub output: Option<PathBuf>,
    /// Do not run both programs to prove the translation.
    #[arg(long)]
    pub no_verify: bool,
    /// What an untranslatable construct does: error (default) or warn (a marked comment line).
    #[arg(long, default_value = "error", value_parser = ["error", "warn"])]
    pub unsupported: String,
    /// Variable mapping overrides: to FANUC 'R0-R99=#100', 'R5=#600', 'NAME=#150'; to Sinumerik '#500-#599=R100' (repeatable).
    #[arg(long = "var-map", value_name = "MAP")]
    pub var_map: Vec<String>,
    /// Tool name → FANUC tool number: NAME=n (repeatable).
    #[arg(long = "tool-map", value_name = "NAME=N")]
    pub tool_map: Vec<String>,
    /// Program map: to FANUC NAME=9001 (name → O number); to Sinumerik 9010=PROBE_X (repeatable).
    #[arg(long = "program-map", value_name = "NAME=N")]
    pub program_map: Vec<String>,
    /// O number of the main program.
    #[arg(long)]
    pub program_number: Option<u32>,
    /// Comments: keep, ascii (transliterated) or drop.
    #[arg(long, default_value = "keep", value_parser = ["keep", "ascii", "drop"])]
    pub comments: String,
    /// Number every block with this step (N10, N20, …).
    #[arg(long, value_name = "STEP")]
    pub number_blocks: Option<u32>,
    /// The target accepts compound conditions [[a] AND [b]].
    #[arg(long)]
    pub compound_conditions: bool,
    /// To Sinumerik: write each macro only for the calls seen (drops the defaults of the
    /// arguments they all give; a caller added later may not get them).
    #[arg(long)]
    pub specialise_callers: bool,
    /// Step limit of each verification run (blocks executed).
    #[arg(long, default_value_t = nctrans::eval::DEFAULT_MAX_STEPS)]
    pub max_steps: u64,
    /// Encoding of the input (utf-8, gbk, shift_jis, windows-1250, iso-8859-1, …; key
    /// input.encoding); detected when omitted.
    #[arg(long = "encoding", visible_alias = "input-encoding", value_name = "ENCODING", value_parser = parse_encoding)]
    pub input_encoding: Option<&'static encoding_rs::Encoding>,
    /// Translate and verify as a stream in constant memory (automatic for inputs of 8 MB
    /// and more; straight-line programs only, others are read whole). In a batch: every
    /// straight-line program of the folder, whatever its size.
    #[arg(long)]
    pub stream: bool,
}

fn parse_dialect(s: &str) -> Result<Dialect, String> {
    Dialect::from_name(s).ok_or_else(|| format!("unknown dialect '{s}' (expected sinumerik, siemens or fanuc)"))
}

fn parse_encoding(s: &str) -> Result<&'static encoding_rs::Encoding, String> {
    encoding_rs::Encoding::for_label(s.as_bytes()).ok_or_else(|| format!("unknown encoding '{s}'"))
}

fn fail(msg: String) -> ExitCode {
    eprintln!("error: {msg}");
    ExitCode::from(2)
}

/// Runs the translation mode. `None` when the arguments do not ask for it.
/// `c` is the project configuration with the given flags already applied over it.
pub fn run(a: &TranslateArgs, c: &Config) -> Option<ExitCode> {
    let to = a.to.or(c.to)?;
    let Some(input) = &a.input else {
        return Some(fail("--to needs an input file: nctrans --to fanuc IN.MPF".into()));
    };
    if to != Dialect::Fanuc {
        return Some(fail(format!("translation to {} is not available in this build", to.name())));
    }
    if let Err(code) = crate::cli_dialect::check_direction(input, a.from, to) {
        return Some(code);
    }
    Some(to_fanuc(a, c, input))
}

fn to_fanuc(a: &TranslateArgs, c: &Config, input: &Path) -> ExitCode {
    // Refused before anything is read: -o onto the input, or onto an existing file without --force.
    if let Some(o) = a.output.as_deref() {
        if let Err(code) = crate::out_guard::check(o, &[input.to_path_buf()], c.force, "-o") {
            return code;
        }
    }
    if let Some(code) = crate::stream_cli::translate(a, c, input) {
        return code;
    }
    let bytes = match std::fs::read(input) {
        Ok(b) => b,
        Err(e) => return fail(format!("cannot read {}: {e}", input.display())),
    };
    let mut db = SourceDb::new();
    let name = input.display().to_string();
    let loaded = nctrans::load(&mut db, &name, &bytes, c.input_encoding);
    // `run` has checked the direction: the input is read as Sinumerik.
    let dialect = Dialect::Sinumerik;
    // Global user data and macros from the library's definition files.
    let mut source_sem = c.sinumerik_semantics();
    let gud = nctrans::gud::apply(&mut source_sem, &mut db, input, None, &c.definitions);
    eprint!("{}", diag::render(&db, &gud));
    if diag::has_errors(&gud) {
        return ExitCode::from(1);
    }
    let popts = ParseOptions { semantics: source_sem.clone() };
    let parsed = nctrans::parse(&db, loaded.file, dialect, &popts);
    eprint!("{}", diag::render(&db, &parsed.diags));
    if diag::has_errors(&parsed.diags) {
        return ExitCode::from(1);
    }
    // Subprograms it calls, found beside it (NAME.SPF, any case), transitively.
    let mut inputs = vec![input.to_path_buf()];
    let subs = callees(&parsed.unit, |callee| {
        let Some(path) = find_beside(input, callee) else { return Ok(None) };
        let Ok(bytes) = std::fs::read(&path) else { return Ok(None) };
        inputs.push(path.clone());
        let l = nctrans::load(&mut db, &path.display().to_string(), &bytes, None);
        let p = nctrans::parse(&db, l.file, Dialect::Sinumerik, &popts);
        eprint!("{}", diag::render(&db, &p.diags));
        if diag::has_errors(&p.diags) {
            return Err(ExitCode::from(1));
        }
        Ok(Some(p.unit))
    });
    let subs = match subs {
        Ok(s) => s,
        Err(code) => return code,
    };
    let mut opts = match options(c, input, loaded.line_ending) {
        Ok(o) => o,
        Err(e) => return fail(e),
    };
    opts.source = source_sem;
    let sub_refs: Vec<&Unit> = subs.iter().collect();
    let t = translate::to_fanuc(&parsed.unit, &sub_refs, &opts);
    eprint!("{}", diag::render(&db, &t.diags));
    if diag::has_errors(&t.diags) && opts.unsupported == UnsupportedPolicy::Error {
        eprintln!("error: not translated ({} construct(s) cannot be expressed on FANUC)", t.unsupported.max(1));
        return ExitCode::from(1);
    }
    let out_bytes = read::encode(&t.text, c.output_encoding.unwrap_or(loaded.encoding), loaded.bom);
    if let Some(Err(code)) = a.output.as_deref().map(|o| crate::out_guard::check(o, &inputs, c.force, "-o")) {
        return code;
    }
    if let Err(e) = write_output(a.output.as_deref(), &out_bytes) {
        return fail(e);
    }
    if t.unsupported > 0 || diag::has_errors(&t.diags) {
        eprintln!("not verified: the output is unfinished (it alarms on its first line)");
        eprintln!("error: the output is incomplete: {} construct(s) marked UNSUPPORTED", t.unsupported);
        return ExitCode::from(1);
    }
    if !c.verify {
        return ExitCode::SUCCESS;
    }
    let out_name = a.output.as_ref().map_or("<translation>.nc".to_string(), |p| p.display().to_string());
    let v = translate::verify(&mut db, &parsed.unit, &sub_refs, &t, &out_name, c.max_steps);
    eprint!("{}", v.rendered);
    eprintln!("{}", v.summary);
    if v.equivalent {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    }
}

/// Translation options from the configuration (flags already applied over `nctrans.toml`).
pub(crate) fn options(c: &Config, input: &Path, eol: read::LineEnding) -> Result<TranslateOptions, String> {
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
    let stem = input.file_stem().and_then(|s| s.to_str()).unwrap_or("MAIN").to_ascii_uppercase();
    Ok(TranslateOptions {
        unsupported: match c.unsupported {
            Unsupported::Warn => UnsupportedPolicy::Warn,
            Unsupported::Error => UnsupportedPolicy::Error,
        },
        var_rules,
        tool_map: c.tools.clone(),
        program_map,
        program_number: c.program_number,
        comments: match c.comments {
            Comments::Ascii => CommentMode::Ascii,
            Comments::Drop => CommentMode::Drop,
            Comments::Keep => CommentMode::Keep,
        },
        number_blocks: (c.number_blocks > 0).then_some(c.number_blocks),
        line_ending: match c.line_ends {
            LineEnds::Keep => eol,
            LineEnds::Lf => read::LineEnding::Lf,
            LineEnds::CrLf => read::LineEnding::CrLf,
            LineEnds::Cr => read::LineEnding::Cr,
        },
        compound_conditions: c.fanuc.compound_conditions,
        target: c.fanuc_semantics(),
        source: c.sinumerik_semantics(),
        main_name: stem,
        main_is_sub: input.extension().is_some_and(|e| e.eq_ignore_ascii_case("spf")),
        source_name: input.file_name().and_then(|s| s.to_str()).unwrap_or("").to_string(),
    })
}

/// Writes through a temporary file and a rename, so a failed run never leaves half a program.
fn write_output(path: Option<&Path>, bytes: &[u8]) -> Result<(), String> {
    use std::io::Write;
    match path {
        None => std::io::stdout().lock().write_all(bytes).map_err(|e| format!("cannot write: {e}")),
        // A device or FIFO (`-o /dev/null`) is written into: a rename would replace it.
        Some(p) if crate::stream_cli::is_special(p) => std::fs::OpenOptions::new()
            .write(true)
            .open(p)
            .and_then(|mut f| f.write_all(bytes))
            .map_err(|e| format!("cannot write {}: {e}", p.display())),
        Some(p) => {
            let tmp = p.with_extension(format!("{}.nctrans-tmp", p.extension().and_then(|e| e.to_str()).unwrap_or("")));
            std::fs::write(&tmp, bytes).map_err(|e| format!("cannot write {}: {e}", tmp.display()))?;
            std::fs::rename(&tmp, p).map_err(|e| format!("cannot write {}: {e}", p.display()))
        }
    }
}

/// The programs `unit` calls by name, transitively, each name once: `load` gives a callee's
/// unit (`None`: skipped), whose calls are followed in turn; its first `Err` stops.
pub(crate) fn callees<E>(unit: &Unit, mut load: impl FnMut(&str) -> Result<Option<Unit>, E>) -> Result<Vec<Unit>, E> {
    let mut subs = Vec::new();
    let mut todo = nctrans::ir::visit::called_names(unit);
    let mut seen: Vec<String> = Vec::new();
    while let Some(callee) = todo.pop() {
        if seen.contains(&callee) {
            continue;
        }
        let sub = load(&callee)?;
        seen.push(callee);
        if let Some(u) = sub {
            todo.extend(nctrans::ir::visit::called_names(&u));
            subs.push(u);
        }
    }
    Ok(subs)
}

pub(crate) fn find_beside(input: &Path, name: &str) -> Option<PathBuf> {
    let dir = input.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or_else(|| Path::new("."));
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir).ok()?.filter_map(|e| e.ok().map(|e| e.path())).collect();
    files.sort();
    files.into_iter().find(|f| {
        let stem = f.file_stem().and_then(|s| s.to_str()).unwrap_or("");
        let ext = f.extension().and_then(|s| s.to_str()).unwrap_or("").to_ascii_lowercase();
        stem.eq_ignore_ascii_case(name) && ext == "spf"
    })
}
