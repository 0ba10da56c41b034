//! `nctrans --to fanuc -o out/ programs/` (a folder in, batch mode): the command line of
//! migration batches. Reads `nctrans.toml`, lets the flags win, runs the
//! library's batch engine, renders progress (a live line on a terminal, plain lines
//! otherwise), the summary table and the report, and stops cleanly on Ctrl-C.

use super::args::fail;
use super::configure::configure;
use super::translate::TranslateArgs;
use clap::ArgMatches;
use nctrans::batch::{self, jobs, BatchOptions, FileJob, Progress, Status};
use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// Flags only a batch has.
#[derive(clap::Args, Debug)]
pub struct BatchArgs {
    /// Batch: worker threads (default: the number of cores).
    #[arg(short = 'j', long = "jobs", value_name = "N")]
    pub jobs: Option<usize>,
    /// Replace existing output files (a batch's, or the -o of one file's translation); an
    /// input is never written, even with it.
    #[arg(long)]
    pub force: bool,
    /// Batch: write a per-file report (.json or .csv).
    #[arg(long, value_name = "FILE")]
    pub report: Option<PathBuf>,
    /// Batch: take program, tool and variable names from an earlier run's nctrans-map.toml
    /// (default: the one in the output folder, if any).
    #[arg(long, value_name = "FILE")]
    pub map: Option<PathBuf>,
    /// The project configuration (default: ./nctrans.toml when present).
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
}

/// Runs a batch when the input is a folder; `None` otherwise (single-file translation).
pub fn run(t: &TranslateArgs, b: &BatchArgs, m: &ArgMatches) -> Option<ExitCode> {
    let input = t.input.as_ref().filter(|p| p.is_dir())?;
    if let Some(d) = t.from {
        // Each file of a folder is read as its extension (else its content) says.
        return Some(fail(format!(
            "--from {} applies to a single file: in a batch each file's dialect comes from its extension (else its content)",
            d.name()
        )));
    }
    Some(run_batch(input, t, b, m))
}

fn run_batch(input: &Path, t: &TranslateArgs, b: &BatchArgs, m: &ArgMatches) -> ExitCode {
    let mut c = match configure(t, b, m) {
        Ok(c) => c,
        Err(e) => return fail(e),
    };
    let Some(to) = c.to else { return fail("a batch needs --to") };
    let Some(output) = c.output.clone() else {
        return fail("a folder is translated into a folder: give -o OUT (or batch.output in nctrans.toml)");
    };
    // Pinned names: an earlier run's map, then the configuration over it.
    let map_path = c.map.clone().or_else(|| Some(output.join(batch::MAP_FILE)).filter(|p| p.is_file()));
    let mut pinned = batch::BatchMaps::default();
    if let Some(p) = &map_path {
        let text = match std::fs::read_to_string(p) {
            Ok(t) => t,
            Err(e) => return fail(format!("cannot read {}: {e}", p.display())),
        };
        match batch::maps::from_toml(&text) {
            Ok((maps, target)) if target.is_none_or(|d| d == to) => pinned = maps,
            Ok((_, Some(d))) => {
                return fail(format!("{}: this map is for --to {}, not {}", p.display(), d.name(), to.name()))
            }
            Ok(_) => {}
            Err(e) => return fail(format!("{}: {e}", p.display())),
        }
        eprintln!("using the names in {}", p.display());
    }
    let from_config = nctrans::batch::BatchMaps::from_config(&c, to);
    pinned.programs.extend(from_config.programs);
    pinned.tools.extend(from_config.tools);
    if !from_config.var_rules.is_empty() {
        pinned.var_rules = from_config.var_rules;
    }
    // The offset map: the configuration's (nctrans.toml, --offset-map) when it has one, else
    // the earlier run's; the jobs translate with it and the map file keeps it.
    if !from_config.offsets.edges.is_empty() {
        if let Some(p) = map_path.as_ref().filter(|_| !pinned.offsets.edges.is_empty()) {
            if pinned.offsets != from_config.offsets {
                eprintln!("note: the offset map of the configuration replaces the [offsets] of {}", p.display());
            }
        }
        pinned.offsets = from_config.offsets;
    }
    c.offsets = pinned.offsets.clone();
    // The signal wiring likewise: the configuration's, else the earlier run's.
    if !from_config.signals.is_empty() {
        pinned.signals = from_config.signals;
    }
    c.signals = pinned.signals.clone();
    let settings = match jobs::JobSettings::from_config(&c) {
        Ok(s) => s,
        Err(e) => return fail(e),
    };
    let job: Box<dyn FileJob> = jobs::for_target(to, settings);
    // The report is never written over a program of the library (another spelling, a link).
    if let Some(rp) = &c.report {
        let found = batch::discover::discover(input, Some(&output)).map(|f| f.files).unwrap_or_default();
        let inputs: Vec<PathBuf> = found.into_iter().map(|f| f.abs).collect();
        if let Err(code) = super::out_guard::check(rp, &inputs, true, "--report") {
            return code;
        }
    }
    let mut opts = BatchOptions::new(input, &output, to);
    opts.jobs = if c.jobs == 0 { batch::default_jobs() } else { c.jobs };
    opts.force = c.force;
    opts.verify = c.verify;
    opts.pinned = pinned;
    opts.encoding = c.input_encoding;
    opts.specialise_callers = c.specialise_callers;
    opts.l_numbers = c.l_numbers;
    if t.stream {
        opts.stream_bytes = 0;
    }

    let cancel = Arc::new(AtomicBool::new(false));
    {
        let cancel = cancel.clone();
        // First Ctrl-C: finish the files in hand, report. Second: leave at once (the outputs
        // already written are whole; the staging folder is cleared by the next run).
        let _ = ctrlc::set_handler(move || {
            if cancel.swap(true, Ordering::SeqCst) {
                std::process::exit(130);
            }
        });
    }
    let mut ui = ProgressUi::new();
    let result = match batch::run_batch(opts, job.as_ref(), cancel, &mut |p| ui.show(p)) {
        Ok(r) => r,
        Err(batch::BatchError::Refused { code, message, hint }) => {
            eprintln!("error[{code}]: {message}\n  = hint: {hint}");
            return ExitCode::from(2);
        }
        Err(e) => return fail(e),
    };
    ui.finish();
    print!("{}", batch::report::summary(&result, to.name()));
    if let Some(rp) = &c.report {
        let text = if rp.extension().is_some_and(|e| e.eq_ignore_ascii_case("csv")) {
            batch::report::csv(&result)
        } else {
            batch::report::json(&result, to.name(), &input.display().to_string(), &output.display().to_string())
        };
        let tmp = rp.with_extension("nctrans-tmp");
        if let Err(e) = std::fs::write(&tmp, text).and_then(|_| std::fs::rename(&tmp, rp)) {
            let _ = std::fs::remove_file(&tmp);
            return fail(format!("cannot write the report {}: {e}", rp.display()));
        }
        eprintln!("report written to {}", rp.display());
    }
    if result.cancelled {
        ExitCode::from(130)
    } else if result.all_verified() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    }
}

/// Renders progress: one redrawn line on a terminal, plain lines otherwise.
struct ProgressUi {
    tty: bool,
    drawn: bool,
}

impl ProgressUi {
    fn new() -> ProgressUi {
        ProgressUi { tty: std::io::stderr().is_terminal(), drawn: false }
    }

    fn show(&mut self, p: Progress) {
        let mut err = std::io::stderr().lock();
        match p {
            Progress::Note(s) => {
                self.clear(&mut err);
                let _ = writeln!(err, "note: {s}");
            }
            Progress::Started { total, skipped } => {
                self.clear(&mut err);
                let _ = writeln!(err, "{total} file(s) to translate ({skipped} already in the target dialect)");
            }
            Progress::FileDone { record, done, total, failures, elapsed } => {
                let eta = if done > 0 { elapsed.as_secs_f64() / done as f64 * (total - done) as f64 } else { 0.0 };
                if self.tty {
                    if record.status.is_failure() {
                        self.clear(&mut err);
                        let _ = writeln!(err, "{:<22} {}  {}", record.status.as_str(), record.path, record.summary);
                    }
                    let _ = write!(
                        err,
                        "\r\x1b[2K[{done}/{total}] {failures} failed, ETA {:.0} s  {}",
                        eta.ceil(),
                        record.path
                    );
                    let _ = err.flush();
                    self.drawn = true;
                } else {
                    let _ = writeln!(
                        err,
                        "[{done}/{total}] {:<22} {}  {}",
                        record.status.as_str(),
                        record.path,
                        if record.status == Status::Verified { "" } else { record.summary.as_str() }
                    );
                }
            }
        }
    }

    fn clear(&mut self, err: &mut impl Write) {
        if self.drawn {
            let _ = write!(err, "\r\x1b[2K");
            self.drawn = false;
        }
    }

    fn finish(&mut self) {
        let mut err = std::io::stderr().lock();
        self.clear(&mut err);
    }
}
