//! `nctrans --to DIALECT IN [-o OUT] …`: the single-file translation of the command line.
//! Loads the program and the callees found beside it, translates, writes the output, then
//! verifies it by reading it back and comparing both programs' traces.
//!
//! Owns: the translation flags ([`TranslateArgs`]), the one driver for every target (here),
//! what a translation reads and writes and what differs per target (`job`) and the streamed
//! translation of a large file (`streamed`). May use: the library, and
//! `cli::{called, dialect, out_guard, stream}`.

pub(crate) mod job;
mod streamed;

use super::args::{fail, parse_dialect};
use job::Request;
use nctrans::config::Config;
use nctrans::diag;
use nctrans::dialect::Dialect;
use nctrans::ir::Unit;
use nctrans::translate;
use std::path::PathBuf;
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
    /// A STRING global user datum the machine's set-up fixes: NAME=VALUE, e.g. AXIS_HORI=Z
    /// (repeatable; `[variables] fixed`). Runs assume it, AXNAME(NAME) translates to that axis.
    #[arg(long = "fixed", value_name = "NAME=VALUE")]
    pub fixed: Vec<String>,
    /// Program map: to FANUC NAME=9001 (name → O number); to Sinumerik 9010=PROBE_X (repeatable).
    #[arg(long = "program-map", value_name = "NAME=N")]
    pub program_map: Vec<String>,
    /// To FANUC: a program named L<k> is O<k>, so `CALL "L"<<R1` is `G65 P#n` (key
    /// programs.l_numbers).
    #[arg(long = "l-numbers")]
    pub l_numbers: bool,
    /// H/D registers of cutting edges: a TOML file with an [offsets] table ("6.2" = "H26,D46");
    /// replaces the [offsets] of nctrans.toml.
    #[arg(long = "offset-map", value_name = "FILE")]
    pub offset_map: Option<PathBuf>,
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
    Some(translate_file(a, c, to))
}

/// `nctrans --to DIALECT IN`: the same steps for every target; what differs (the options,
/// how the files are read and written, what is refused, how the verdict is shown) is the
/// target's choice in `job`. `--program-map` reads `NAME=9001` to FANUC, `9010=PROBE_X` to
/// Sinumerik.
fn translate_file(a: &TranslateArgs, c: &Config, to: Dialect) -> ExitCode {
    let Some(input) = a.input.as_deref() else {
        return fail(job::needs_input(to));
    };
    if let Err(code) = super::dialect::check_direction(input, a.from, to) {
        return code;
    }
    if let Some(flag) = job::foreign_flag(a, to) {
        return fail(format!("{flag} applies to --to fanuc only"));
    }
    let req = Request {
        file: input,
        out: a.output.as_deref(),
        encoding: c.input_encoding,
        force: c.force,
        verify: c.verify,
        max_steps: c.max_steps,
    };
    // -o naming the main file: refused before anything is read when it is the input, or an
    // existing file without --force (files written into a folder are checked once named).
    if let Some(o) = req.out.filter(|o| !job::out_place(o).0) {
        if let Err(code) = super::out_guard::check(o, &[input.to_path_buf()], c.force, "-o") {
            return code;
        }
    }
    let mut opts = match job::options(a, c, input, to) {
        Ok(o) => o,
        Err(e) => return fail(e),
    };
    if let Some(code) = streamed::translate(to, &req, a.stream, c, &opts.sinumerik) {
        return code;
    }
    let mut job = match job::load(&req, c, &opts, to) {
        Ok(j) => j,
        Err(code) => return code,
    };
    eprint!("{}", diag::render(&job.db, &job.warnings));
    job::complete(&mut opts, c, &job, to);
    let units: Vec<&Unit> = job.units.iter().collect();
    let t = translate::translate(&units, to, &opts);
    eprint!("{}", diag::render(&job.db, &t.diags));
    if let Some(why) = job::refused(&t, &opts, to) {
        eprintln!("error: {why}");
        return ExitCode::from(1);
    }
    if let Err(code) = job::write(&req, &t, &job, c, to) {
        return code;
    }
    if let Some(lines) = job::unfinished(&t, &opts, to) {
        // An unfinished program (it alarms on its first line) is never verified, so never
        // called equivalent.
        for l in lines {
            eprintln!("{l}");
        }
        return ExitCode::from(1);
    }
    if !req.verify {
        return ExitCode::SUCCESS;
    }
    job::verify(&mut job, &t, &req, &opts, to)
}
