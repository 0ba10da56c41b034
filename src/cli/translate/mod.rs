//! `nctrans --to DIALECT IN [-o OUT] …`: the single-file translation of the command line.
//! Loads the program and the callees found beside it, translates, writes the output, then
//! verifies it by reading it back and comparing both programs' traces.
//!
//! Owns: the translation flags ([`TranslateArgs`]), the choice of the path for a target
//! (here), what a translation reads and writes (`job`) and the streamed translation of a
//! large file (`streamed`). May use: the library, and `cli::{dialect, out_guard, stream}`.

pub(crate) mod job;
mod streamed;

use super::args::{fail, parse_dialect};
use job::Request;
use nctrans::config::Config;
use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::ir::Unit;
use nctrans::lower::to_fanuc::UnsupportedPolicy;
use nctrans::span::SourceDb;
use nctrans::translate;
use nctrans::translate::to_sinumerik as ts;
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

fn parse_encoding(s: &str) -> Result<&'static encoding_rs::Encoding, String> {
    encoding_rs::Encoding::for_label(s.as_bytes()).ok_or_else(|| format!("unknown encoding '{s}'"))
}

/// Runs the translation mode. `None` when the arguments do not ask for it.
/// `c` is the project configuration with the given flags already applied over it.
pub fn run(a: &TranslateArgs, c: &Config) -> Option<ExitCode> {
    let to = a.to.or(c.to)?;
    if to == Dialect::Sinumerik {
        return Some(to_sinumerik(a, c));
    }
    let Some(input) = &a.input else {
        return Some(fail("--to needs an input file: nctrans --to fanuc IN.MPF"));
    };
    if let Err(code) = super::dialect::check_direction(input, a.from, to) {
        return Some(code);
    }
    Some(to_fanuc(a, c, input))
}

fn to_fanuc(a: &TranslateArgs, c: &Config, input: &Path) -> ExitCode {
    // Refused before anything is read: -o onto the input, or onto an existing file without --force.
    if let Some(o) = a.output.as_deref() {
        if let Err(code) = super::out_guard::check(o, &[input.to_path_buf()], c.force, "-o") {
            return code;
        }
    }
    if let Some(code) = streamed::to_fanuc(a, c, input) {
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
    let subs = job::callees(&parsed.unit, |callee| {
        let Some(path) = job::find_beside(input, callee) else { return Ok(None) };
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
    let mut opts = match job::fanuc_options(c, input, loaded.line_ending) {
        Ok(o) => o,
        Err(e) => return fail(e),
    };
    opts.source = source_sem;
    let sub_refs: Vec<&Unit> = subs.iter().collect();
    let units: Vec<&Unit> = std::iter::once(&parsed.unit).chain(sub_refs.iter().copied()).collect();
    let policy = opts.unsupported;
    let t = translate::translate(&units, Dialect::Fanuc, &translate::Options::to_fanuc(opts));
    eprint!("{}", diag::render(&db, &t.diags));
    if diag::has_errors(&t.diags) && policy == UnsupportedPolicy::Error {
        eprintln!("error: not translated ({} construct(s) cannot be expressed on FANUC)", t.unsupported.max(1));
        return ExitCode::from(1);
    }
    let out_bytes = read::encode(t.text(), c.output_encoding.unwrap_or(loaded.encoding), loaded.bom);
    if let Some(Err(code)) = a.output.as_deref().map(|o| super::out_guard::check(o, &inputs, c.force, "-o")) {
        return code;
    }
    if let Err(e) = job::write_output(a.output.as_deref(), &out_bytes) {
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
    let v = translate::verify(&mut db, &units, &t, &out_name, c.max_steps);
    eprint!("{}", v.rendered);
    eprintln!("{}", v.summary);
    if v.equivalent {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    }
}

/// Runs `nctrans --to sinumerik` (the options are the translation mode's, shared with
/// `--to fanuc`; `--program-map` reads `9010=PROBE_X` in this direction). `config` is the
/// project configuration with the flags given applied over it.
fn to_sinumerik(args: &TranslateArgs, config: &Config) -> ExitCode {
    let Some(file) = args.input.as_deref() else {
        eprintln!("error: --to sinumerik needs an input file: nctrans --to sinumerik IN.nc");
        return ExitCode::from(2);
    };
    if let Err(code) = super::dialect::check_direction(file, args.from, Dialect::Sinumerik) {
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
    if let Some(o) = req.out.filter(|o| !job::out_place(o).0) {
        if let Err(code) = super::out_guard::check(o, &[file.to_path_buf()], force, "-o") {
            return code;
        }
    }
    let opts = match job::sinumerik_options(args, stem, config) {
        Ok(o) => o,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    if let Some(code) = streamed::to_sinumerik(args, &req, &opts) {
        return code;
    }
    let job = match job::load_job(req.file, req.encoding, &opts.source) {
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
    let tr = translate::translate(
        &units,
        Dialect::Sinumerik,
        &translate::Options::to_sinumerik(opts.clone(), job.loaded.line_ending),
    );
    eprint!("{}", diag::render(&job.db, &tr.diags));
    if tr.has_errors() {
        eprintln!("error: translation failed; nothing written");
        return ExitCode::from(1);
    }
    if let Err(code) = job::write_files(&req, &tr, &job.loaded, &job.read) {
        return code;
    }
    let warned = tr.diags.iter().any(|d| d.code.starts_with("NC3") || nctrans::unfinished::is_marked(d));
    if warned && opts.unsupported == ts::UnsupportedPolicy::Warn {
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
        code = job::verify(&job, &tr, &req, req.max_steps, &opts);
    }
    code
}
