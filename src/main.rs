//! The `nctrans` command line: the only code that prints. Parses arguments, calls the
//! library, renders diagnostics with codespan-reporting.

use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};
use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::span::SourceDb;
use nctrans::{diag, ir};
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

mod batch_cli;
mod check_cli;
mod cli_dialect;
mod cli_profile;
mod cli_sinumerik;
mod out_guard;
mod stream_cli;
mod translate_cli;

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
    translate: translate_cli::TranslateArgs,
    /// Batch mode: a folder in (`nctrans --to fanuc -o out/ programs/`).
    #[command(flatten)]
    batch: batch_cli::BatchArgs,
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
        maps: check_cli::MapOpts,
    },
    /// Write a commented project configuration (nctrans.toml) with every key at its default.
    Init {
        /// Where to write it (default: ./nctrans.toml); an existing file is never overwritten.
        path: Option<PathBuf>,
    },
}

#[derive(clap::Args)]
struct EvalOpts {
    /// Set a variable before the run: R1=5, '#24=10.', NAME=3 (repeatable; overrides the
    /// file's `nctrans: set` header lines).
    #[arg(long = "set", value_name = "VAR=VALUE")]
    set: Vec<String>,
    /// Stop after this many blocks (the run is then inconclusive).
    #[arg(long, default_value_t = nctrans::eval::DEFAULT_MAX_STEPS)]
    max_steps: u64,
    /// Where a probe move (FANUC G31, Siemens MEAS=/MEAW=) touches, as a fraction of the move
    /// in (0, 1]; without it every probe move reaches its end point.
    #[arg(long, value_name = "FRACTION", value_parser = parse_fraction)]
    probe_contact: Option<f64>,
}

fn parse_fraction(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(f) if f > 0.0 && f <= 1.0 => Ok(f),
        _ => Err(format!("'{s}' is not a fraction in (0, 1] (e.g. 0.5: the probe touches halfway)")),
    }
}

#[derive(clap::Args)]
struct InputOpts {
    /// Encoding of the input (utf-8, gbk, shift_jis, windows-1250, iso-8859-1, …); detected when
    /// omitted.
    #[arg(long, visible_alias = "input-encoding", value_name = "ENCODING", value_parser = parse_encoding)]
    encoding: Option<&'static encoding_rs::Encoding>,
    /// Read the file as a stream in constant memory (automatic for files of 8 MB and more).
    #[arg(long)]
    stream: bool,
}

fn parse_dialect(s: &str) -> Result<Dialect, String> {
    Dialect::from_name(s).ok_or_else(|| format!("unknown dialect '{s}' (expected sinumerik, siemens or fanuc)"))
}

fn parse_encoding(s: &str) -> Result<&'static encoding_rs::Encoding, String> {
    encoding_rs::Encoding::for_label(s.as_bytes())
        .ok_or_else(|| format!("unknown encoding '{s}' (try utf-8, gbk, shift_jis, windows-1250, iso-8859-1)"))
}

fn main() -> ExitCode {
    // The matches are kept so batch mode can tell flags given from defaults (flags win over
    // nctrans.toml only when given).
    let matches = Cli::command().get_matches();
    let cli = match Cli::from_arg_matches(&matches) {
        Ok(c) => c,
        Err(e) => e.exit(),
    };
    let Some(command) = cli.command else {
        if let Some(code) = batch_cli::run(&cli.translate, &cli.batch, &matches) {
            return code;
        }
        if cli.translate.to.is_some() || cli.translate.input.is_some() {
            // Single-file translation reads the project configuration like a batch does;
            // its `to` stands for `--to`.
            let config = match batch_cli::configure(&cli.translate, &cli.batch, &matches) {
                Ok(c) => c,
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::from(2);
                }
            };
            if config.to == Some(Dialect::Sinumerik) {
                return cli_sinumerik::run(&cli.translate, &config);
            }
            if let Some(code) = translate_cli::run(&cli.translate, &config) {
                return code;
            }
        }
        eprintln!("error: give a subcommand (parse, …) or --to fanuc IN; see --help");
        return ExitCode::from(2);
    };
    match command {
        Command::Parse { file, from, summary, input } => cmd_parse(&file, from, summary, &input),
        Command::Run { file, from, eval, format, quiet, expand_cycles, input } => {
            cmd_run(&file, from, &eval, format, (quiet, expand_cycles), &input)
        }
        Command::Check { a, b, from_a, from_b, eval, input, maps } => {
            cmd_check(&a, &b, (from_a, from_b), &eval, &input, &maps)
        }
        Command::Init { path } => batch_cli::init(path.as_deref()),
    }
}

fn read_file(path: &PathBuf) -> Result<Vec<u8>, ExitCode> {
    std::fs::read(path).map_err(|e| {
        eprintln!("error: cannot read {}: {e}", path.display());
        ExitCode::from(2)
    })
}

fn cmd_parse(path: &PathBuf, from: Option<Dialect>, summary: bool, input: &InputOpts) -> ExitCode {
    if summary && stream_cli::wanted(path, input) {
        if let Some(code) = stream_cli::parse_summary(path, from, input.encoding) {
            return code;
        }
    }
    let bytes = match read_file(path) {
        Ok(b) => b,
        Err(code) => return code,
    };
    let mut db = SourceDb::new();
    let name = path.display().to_string();
    let loaded = nctrans::load(&mut db, &name, &bytes, input.encoding);
    let dialect = from.unwrap_or_else(|| nctrans::detect_dialect(&name, &db.get(loaded.file).text));
    let sem = match cli_profile::semantics(&mut db, path, dialect) {
        Ok(s) => s,
        Err(code) => return code,
    };
    let parsed = nctrans::parse(&db, loaded.file, dialect, &ParseOptions { semantics: sem });
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

fn parse_format(s: &str) -> Result<nctrans::eval::Format, String> {
    match s {
        "text" => Ok(nctrans::eval::Format::Text),
        "jsonl" => Ok(nctrans::eval::Format::Jsonl),
        _ => Err(format!("unknown trace format '{s}' (expected text or jsonl)")),
    }
}

/// Loads and parses one program for a run; prints its diagnostics.
fn load_for_run(
    db: &mut SourceDb,
    path: &PathBuf,
    from: Option<Dialect>,
    eval: &EvalOpts,
    input: &InputOpts,
) -> Result<(ir::Unit, nctrans::eval::RunOptions), ExitCode> {
    let bytes = read_file(path)?;
    let name = path.display().to_string();
    let loaded = nctrans::load(db, &name, &bytes, input.encoding);
    let dialect = from.unwrap_or_else(|| nctrans::detect_dialect(&name, &db.get(loaded.file).text));
    // The project's profile (nctrans.toml) and the library's definition files.
    let sem = cli_profile::semantics(db, path, dialect)?;
    let parsed = nctrans::parse(db, loaded.file, dialect, &ParseOptions { semantics: sem.clone() });
    eprint!("{}", diag::render(db, &parsed.diags));
    if diag::has_errors(&parsed.diags) {
        return Err(ExitCode::from(1));
    }
    let mut opts = run_options(&db.get(loaded.file).text, &name, eval)?;
    opts.semantics = Some(sem);
    Ok((parsed.unit, opts))
}

/// Run options from a program's `nctrans: set` header lines, then `--set` (which wins).
fn run_options(header: &str, name: &str, eval: &EvalOpts) -> Result<nctrans::eval::RunOptions, ExitCode> {
    let mut inputs = nctrans::eval::header_inputs(header).map_err(|e| {
        eprintln!("error: {name}: bad `nctrans: set` header: {e}");
        ExitCode::from(2)
    })?;
    for s in &eval.set {
        let i = nctrans::eval::parse_input(s).map_err(|e| {
            eprintln!("error: --set {e}");
            ExitCode::from(2)
        })?;
        inputs.retain(|h| h.target != i.target);
        inputs.push(i);
    }
    Ok(nctrans::eval::RunOptions {
        max_steps: eval.max_steps,
        inputs,
        semantics: None,
        probe_contact: eval.probe_contact,
        expand_cycles: None,
    })
}

fn cmd_run(
    path: &PathBuf,
    from: Option<Dialect>,
    eval: &EvalOpts,
    format: nctrans::eval::Format,
    (quiet, expand_cycles): (bool, bool),
    input: &InputOpts,
) -> ExitCode {
    use nctrans::eval::{self, Ending};
    // The streamed run writes `cycle` events only; an expanded run reads the whole file.
    if !expand_cycles && stream_cli::wanted(path, input) {
        if let Some(code) = stream_cli::run(path, from, eval, format, quiet, input.encoding) {
            return code;
        }
    }
    let mut db = SourceDb::new();
    let (unit, mut opts) = match load_for_run(&mut db, path, from, eval, input) {
        Ok(x) => x,
        Err(code) => return code,
    };
    if expand_cycles {
        // The retract amounts are machine data: the profile's, when the folder has one.
        let project = std::path::Path::new(nctrans::config::FILE_NAME);
        let config = if project.is_file() {
            match nctrans::config::Config::load(project) {
                Ok(c) => c,
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::from(2);
                }
            }
        } else {
            nctrans::config::Config::default()
        };
        opts.expand_cycles = Some(config.cycle_retracts(unit.dialect));
    }
    let main_file = db.get(unit.file).clone();
    let main_id = unit.file;
    let line_of = move |o: eval::Origin| (o.file == main_id).then(|| main_file.line_col(o.span.lo).0);
    let out = std::io::BufWriter::new(std::io::stdout().lock());
    let mut callees = eval::DirCallees { semantics: opts.semantics.clone() };
    let (outcome, write_error) = if quiet {
        (eval::run(&mut db, &unit, &mut callees, &opts, &mut eval::NullSink), None)
    } else {
        let mut sink = eval::WriterSink::new(out, format, Box::new(line_of));
        let o = eval::run(&mut db, &unit, &mut callees, &opts, &mut sink);
        let err = sink.error.take().or_else(|| sink.out.flush().err());
        (o, err)
    };
    eprint!("{}", diag::render(&db, &outcome.diags));
    if let Some(e) = write_error {
        eprintln!("error: writing the trace: {e}");
        return ExitCode::from(2);
    }
    match outcome.ending {
        Ending::End(_) | Ending::Stopped => ExitCode::SUCCESS,
        Ending::Error => ExitCode::from(1),
        Ending::Alarm { .. } => ExitCode::from(3),
        Ending::Limit { .. } => ExitCode::from(4),
    }
}

fn cmd_check(
    a: &PathBuf,
    b: &PathBuf,
    (from_a, from_b): (Option<Dialect>, Option<Dialect>),
    eval: &EvalOpts,
    input: &InputOpts,
    maps: &check_cli::MapOpts,
) -> ExitCode {
    use nctrans::check::{self, Side};
    let names = match maps.names() {
        Ok(n) => n,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    if let Some(names) = &names {
        return check_as_translation(a, b, (from_a, from_b), eval, input, names);
    }
    let mut db = SourceDb::new();
    // Each side is streamed when it is large (or --stream), else read whole. A streamed
    // side's source (a decoded copy for a legacy encoding) lives until the check has run.
    let mut streamed: Vec<(usize, stream_cli::Source)> = Vec::new();
    let mut runners = Vec::new();
    for (path, from) in [(a, from_a), (b, from_b)] {
        let id = db.len();
        let side = stream_cli::wanted(path, input)
            .then(|| stream_cli::side(&mut db, path, from, eval, input.encoding))
            .flatten();
        let runner = match side {
            Some(Ok((r, src))) => {
                streamed.push((id, src));
                r
            }
            Some(Err(code)) => return code,
            None => match load_for_run(&mut db, path, from, eval, input) {
                Ok((unit, run)) => {
                    let callees = Box::new(nctrans::eval::DirCallees { semantics: run.semantics.clone() });
                    Side { unit, callees, run }.runner()
                }
                Err(code) => return code,
            },
        };
        runners.push(runner);
    }
    let (Some(rb), Some(ra)) = (runners.pop(), runners.pop()) else {
        return ExitCode::from(2);
    };
    let report = check::check_runners(&db, ra, rb);
    let render: Vec<(usize, &std::path::Path)> = streamed.iter().map(|(id, src)| (*id, src.path())).collect();
    eprint!("{}", nctrans::excerpt::render(&report.db, &report.diags, &render));
    check_verdict(&report)
}

/// Prints a check's verdict; its exit code.
fn check_verdict(report: &nctrans::check::CheckReport) -> ExitCode {
    use nctrans::check::Verdict;
    // The trace holds programmed positions: a program that ran a compensation word (D, H,
    // G40..G49) may apply another length or radius than the other, unseen (issue 17 item 6).
    let compensates = report.diags.iter().any(|d| d.code == nctrans::eval::machine::COMPENSATION_NOTE);
    let diff = &report.diff;
    match &report.verdict {
        Verdict::Equivalent { events } if compensates => {
            println!(
                "inconclusive: {events} trace events agree, but tool compensation (D, H, G40..G49) is not compared"
            );
            ExitCode::from(4)
        }
        Verdict::Equivalent { events } => {
            println!("{}", report.excluded.equivalent(&format!("{events} trace events agree")));
            ExitCode::SUCCESS
        }
        Verdict::Diverged { index } => {
            println!("diverged at trace event {}", index + 1);
            print!("{diff}");
            ExitCode::from(1)
        }
        Verdict::Inconclusive { reason } => {
            println!("inconclusive: {reason}");
            ExitCode::from(4)
        }
        Verdict::Failed => {
            println!("failed: a program could not be evaluated");
            ExitCode::from(1)
        }
    }
}

/// `check` with a translation's maps (`--tool-map`, `--map`): both sides read whole, a
/// Siemens side compared with a FANUC one aligned as the translation's verification aligns
/// it (see `check_cli`).
fn check_as_translation(
    a: &PathBuf,
    b: &PathBuf,
    (from_a, from_b): (Option<Dialect>, Option<Dialect>),
    eval: &EvalOpts,
    input: &InputOpts,
    names: &check_cli::Names,
) -> ExitCode {
    use nctrans::check::{self, Side};
    let mut db = SourceDb::new();
    let mut sides = Vec::new();
    for (path, from) in [(a, from_a), (b, from_b)] {
        match load_for_run(&mut db, path, from, eval, input) {
            Ok(side) => sides.push(side),
            Err(code) => return code,
        }
    }
    let dialects: Vec<Dialect> = sides.iter().map(|(u, _)| u.dialect).collect();
    let cross = dialects[0] != dialects[1];
    let runners: Vec<_> = sides
        .into_iter()
        .map(|(unit, mut run)| {
            let unit = match unit.dialect {
                Dialect::Sinumerik if cross => names.align(&unit),
                Dialect::Fanuc if cross => {
                    names.fanuc_inputs(&mut run.inputs);
                    unit
                }
                _ => unit,
            };
            let callees = Box::new(nctrans::eval::DirCallees { semantics: run.semantics.clone() });
            Side { unit, callees, run }.runner()
        })
        .collect();
    let mut runners = runners.into_iter();
    let (Some(ra), Some(rb)) = (runners.next(), runners.next()) else {
        return ExitCode::from(2);
    };
    // Compared as the translation's verification compares: a Siemens first side's messages
    // shown without a stop are what a FANUC translation keeps as comments.
    let exclude = if cross && dialects[0] == Dialect::Sinumerik {
        nctrans::translate::EXCLUDE
    } else {
        check::Exclude::default()
    };
    let report = check::check_runners_excluding(&db, ra, rb, exclude);
    eprint!("{}", diag::render(&report.db, &report.diags));
    check_verdict(&report)
}
