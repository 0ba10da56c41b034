//! The `nctrans` command line: the only code that prints. Parses arguments, calls the
//! library, renders diagnostics with codespan-reporting.

mod cli_sinumerik;

use clap::{Parser, Subcommand};
use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::span::SourceDb;
use nctrans::{diag, ir};
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "nctrans",
    version,
    about = "Translate CNC macro programs between Siemens Sinumerik and FANUC Macro B, verified by running both"
)]
#[command(args_conflicts_with_subcommands = true)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    #[command(flatten)]
    translate: TranslateArgs,
}

/// `nctrans --to <dialect> FILE`: translate, then verify by running both.
#[derive(clap::Args)]
struct TranslateArgs {
    /// Target dialect: sinumerik (alias siemens) for a FANUC input.
    #[arg(long, value_parser = parse_dialect)]
    to: Option<Dialect>,
    /// The program to translate.
    file: Option<PathBuf>,
    /// Write the output here (a file for the main program, or a directory) instead of stdout.
    #[arg(short = 'o', long = "output")]
    output: Option<PathBuf>,
    #[command(flatten)]
    sinumerik: cli_sinumerik::SinumerikArgs,
    #[command(flatten)]
    input: InputOpts,
}

#[derive(Subcommand)]
enum Command {
    /// Parse a program and print its IR as a stable text dump.
    Parse {
        file: PathBuf,
        /// Source dialect (default: from the extension, .mpf/.spf or .nc/.tap, else the content).
        #[arg(long, value_parser = parse_dialect)]
        from: Option<Dialect>,
        /// Print only a one-line summary (programs, blocks, diagnostics) instead of the IR.
        #[arg(long)]
        summary: bool,
        #[command(flatten)]
        input: InputOpts,
    },
}

#[derive(clap::Args)]
struct InputOpts {
    /// Encoding of the input (utf-8, gbk, shift_jis, windows-1250, iso-8859-1, …); detected when omitted.
    #[arg(long, value_parser = parse_encoding)]
    encoding: Option<&'static encoding_rs::Encoding>,
}

fn parse_dialect(s: &str) -> Result<Dialect, String> {
    Dialect::from_name(s).ok_or_else(|| format!("unknown dialect '{s}' (expected sinumerik, siemens or fanuc)"))
}

fn parse_encoding(s: &str) -> Result<&'static encoding_rs::Encoding, String> {
    encoding_rs::Encoding::for_label(s.as_bytes())
        .ok_or_else(|| format!("unknown encoding '{s}' (try utf-8, gbk, shift_jis, windows-1250, iso-8859-1)"))
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Some(Command::Parse { file, from, summary, input }) => cmd_parse(&file, from, summary, &input),
        None => cmd_translate(&cli.translate),
    }
}

fn cmd_translate(t: &TranslateArgs) -> ExitCode {
    let (Some(to), Some(file)) = (t.to, &t.file) else {
        eprintln!("error: give a command (nctrans --help) or translate with: nctrans --to sinumerik FILE");
        return ExitCode::from(2);
    };
    match to {
        Dialect::Sinumerik => cli_sinumerik::run(&cli_sinumerik::Request {
            file,
            out: t.output.as_deref(),
            encoding: t.input.encoding,
            args: &t.sinumerik,
        }),
        Dialect::Fanuc => {
            eprintln!("error: --to fanuc is not in this build");
            ExitCode::from(2)
        }
    }
}

fn read_file(path: &PathBuf) -> Result<Vec<u8>, ExitCode> {
    std::fs::read(path).map_err(|e| {
        eprintln!("error: cannot read {}: {e}", path.display());
        ExitCode::from(2)
    })
}

fn cmd_parse(path: &PathBuf, from: Option<Dialect>, summary: bool, input: &InputOpts) -> ExitCode {
    let bytes = match read_file(path) {
        Ok(b) => b,
        Err(code) => return code,
    };
    let mut db = SourceDb::new();
    let name = path.display().to_string();
    let loaded = nctrans::load(&mut db, &name, &bytes, input.encoding);
    let dialect = from.unwrap_or_else(|| nctrans::detect_dialect(&name, &db.get(loaded.file).text));
    let parsed = nctrans::parse(&db, loaded.file, dialect, &ParseOptions::for_dialect(dialect));
    eprint!("{}", diag::render(&db, &parsed.diags));
    if diag::has_errors(&parsed.diags) {
        return ExitCode::from(1);
    }
    let text = if summary {
        format!(
            "{}: {} program(s), {} blocks, {} warning(s)\n",
            name,
            parsed.unit.programs.len(),
            ir::visit::count_blocks(&parsed.unit),
            parsed.diags.len()
        )
    } else {
        ir::dump::dump(&parsed.unit)
    };
    let mut out = std::io::stdout().lock();
    if out.write_all(text.as_bytes()).is_err() {
        return ExitCode::from(2);
    }
    ExitCode::SUCCESS
}
