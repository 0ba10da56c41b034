//! The `nctrans` command line: the only code that prints. Parses arguments, calls the
//! library, renders diagnostics with codespan-reporting, and decides exit codes.
//!
//! Owns: one file per command (`parse`, `run`, `check`, `init`, the single-file translation
//! in `translate/`, the folder translation in `batch`), the arguments they share (`args`),
//! the configuration with the flags applied (`configure`), the streamed side of the
//! commands (`stream`), the output rules (`out_guard`) and the source-dialect check
//! (`dialect`). May use: the library (`nctrans::*`) and clap; the library never uses this.
//! Within it, the commands use the shared modules, never each other.

use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};
use nctrans::dialect::Dialect;
use std::path::PathBuf;
use std::process::ExitCode;

mod args;
mod batch;
mod check;
mod configure;
mod dialect;
mod init;
mod out_guard;
mod parse;
mod profile;
mod run;
mod stream;
mod translate;

use args::{parse_dialect, parse_format, EvalOpts, InputOpts};

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
    /// Translation mode: `nctrans --to fanuc IN [-o OUT] …`.
    #[command(flatten)]
    translate: translate::TranslateArgs,
    /// Batch mode: a folder in (`nctrans --to fanuc -o out/ programs/`).
    #[command(flatten)]
    batch: batch::BatchArgs,
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
    /// Run a program in the bundled evaluator and print its canonical trace.
    Run {
        file: PathBuf,
        /// Source dialect (default: from the extension, else the content).
        #[arg(long, value_parser = parse_dialect)]
        from: Option<Dialect>,
        #[command(flatten)]
        eval: EvalOpts,
        /// Trace format: text (one event per line) or jsonl (one JSON object per event); both are
        /// described in docs/trace-format.md.
        #[arg(long, default_value = "text", value_parser = parse_format)]
        format: nctrans::eval::Format,
        /// Run without printing the trace (for timing).
        #[arg(long)]
        quiet: bool,
        /// Write each drilling cycle as the moves, dwells and spindle events the control makes
        /// (retract amounts from nctrans.toml [fanuc]/[sinumerik]) instead of `cycle` events.
        #[arg(long)]
        expand_cycles: bool,
        #[command(flatten)]
        input: InputOpts,
    },
    /// Run two programs (either dialect) and report whether their traces agree.
    Check {
        a: PathBuf,
        b: PathBuf,
        /// Dialect of A (default: from the extension, else the content).
        #[arg(long, value_parser = parse_dialect)]
        from_a: Option<Dialect>,
        /// Dialect of B.
        #[arg(long, value_parser = parse_dialect)]
        from_b: Option<Dialect>,
        #[command(flatten)]
        eval: EvalOpts,
        #[command(flatten)]
        input: InputOpts,
        #[command(flatten)]
        maps: check::MapOpts,
    },
    /// Write a commented project configuration (nctrans.toml) with every key at its default.
    Init {
        /// Where to write it (default: ./nctrans.toml); an existing file is never overwritten.
        path: Option<PathBuf>,
    },
}

/// Parses the command line and runs the command it names.
pub fn main() -> ExitCode {
    // The matches are kept so batch mode can tell flags given from defaults (flags win over
    // nctrans.toml only when given).
    let matches = Cli::command().get_matches();
    let cli = match Cli::from_arg_matches(&matches) {
        Ok(c) => c,
        Err(e) => e.exit(),
    };
    let Some(command) = cli.command else {
        if let Some(code) = batch::run(&cli.translate, &cli.batch, &matches) {
            return code;
        }
        if cli.translate.to.is_some() || cli.translate.input.is_some() {
            // Single-file translation reads the project configuration like a batch does;
            // its `to` stands for `--to`.
            let config = match configure::configure(&cli.translate, &cli.batch, &matches) {
                Ok(c) => c,
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::from(2);
                }
            };
            if let Some(code) = translate::run(&cli.translate, &config) {
                return code;
            }
        }
        eprintln!("error: give a subcommand (parse, …) or --to fanuc IN; see --help");
        return ExitCode::from(2);
    };
    match command {
        Command::Parse { file, from, summary, input } => parse::parse(&file, from, summary, &input),
        Command::Run { file, from, eval, format, quiet, expand_cycles, input } => {
            run::run(&file, from, &eval, format, (quiet, expand_cycles), &input)
        }
        Command::Check { a, b, from_a, from_b, eval, input, maps } => {
            check::check(&a, &b, (from_a, from_b), &eval, &input, &maps)
        }
        Command::Init { path } => init::init(path.as_deref()),
    }
}
