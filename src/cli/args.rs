//! The arguments several commands share (how a program is read, how it is run) and their
//! value parsers, with the loading a run needs (`run` and `check`).

use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::span::SourceDb;
use nctrans::{diag, ir};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(clap::Args, Clone)]
pub struct EvalOpts {
    /// Set a variable before the run: R1=5, '#24=10.', NAME=3 (repeatable; overrides the
    /// file's `nctrans: set` header lines).
    #[arg(long = "set", value_name = "VAR=VALUE")]
    pub set: Vec<String>,
    /// Stop after this many blocks (the run is then inconclusive).
    #[arg(long, default_value_t = nctrans::eval::DEFAULT_MAX_STEPS)]
    pub max_steps: u64,
    /// Where a probe move (FANUC G31, Siemens MEAS=/MEAW=) touches, as a fraction of the move
    /// in (0, 1]; without it every probe move reaches its end point.
    #[arg(long, value_name = "FRACTION", value_parser = parse_fraction)]
    pub probe_contact: Option<f64>,
    /// Where the probe triggers on the next probing move, in run order: X=12.5 (or
    /// X=3,Y=4; trace coordinates, on the programmed line) or `miss` (repeatable; overrides
    /// the file's `nctrans: probe` header lines). Moves beyond the list do not trigger.
    #[arg(long = "probe", value_name = "POINT|miss", value_parser = parse_probe)]
    pub probe: Vec<nctrans::eval::ProbeInput>,
    /// Interrupt input N switches on right after the K-th motion event (move, arc, cycle,
    /// home) of the run: 1@3 (repeatable; overrides the file's `nctrans: interrupt` header
    /// lines). FANUC's one interrupt signal is input 1. Without it no input ever switches.
    #[arg(long = "interrupt", value_name = "N@K", value_parser = parse_interrupt)]
    pub interrupt: Vec<nctrans::eval::InterruptInput>,
}

fn parse_interrupt(s: &str) -> Result<nctrans::eval::InterruptInput, String> {
    nctrans::eval::parse_interrupt(s)
}

fn parse_probe(s: &str) -> Result<nctrans::eval::ProbeInput, String> {
    nctrans::eval::parse_probe(s)
}

fn parse_fraction(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(f) if f > 0.0 && f <= 1.0 => Ok(f),
        _ => Err(format!("'{s}' is not a fraction in (0, 1] (e.g. 0.5: the probe touches halfway)")),
    }
}

#[derive(clap::Args)]
pub struct InputOpts {
    /// Encoding of the input (utf-8, gbk, shift_jis, windows-1250, iso-8859-1, …); detected when
    /// omitted.
    #[arg(long, visible_alias = "input-encoding", value_name = "ENCODING", value_parser = parse_encoding)]
    pub encoding: Option<&'static encoding_rs::Encoding>,
    /// Read the file as a stream in constant memory (automatic for files of 8 MB and more).
    #[arg(long)]
    pub stream: bool,
}

/// Says why a command cannot go on; exit code 2.
pub fn fail(msg: impl std::fmt::Display) -> ExitCode {
    eprintln!("error: {msg}");
    ExitCode::from(2)
}

pub fn parse_dialect(s: &str) -> Result<Dialect, String> {
    Dialect::from_name(s).ok_or_else(|| format!("unknown dialect '{s}' (expected sinumerik, siemens or fanuc)"))
}

pub fn parse_encoding(s: &str) -> Result<&'static encoding_rs::Encoding, String> {
    encoding_rs::Encoding::for_label(s.as_bytes())
        .ok_or_else(|| format!("unknown encoding '{s}' (try utf-8, gbk, shift_jis, windows-1250, iso-8859-1)"))
}

pub fn parse_format(s: &str) -> Result<nctrans::eval::Format, String> {
    match s {
        "text" => Ok(nctrans::eval::Format::Text),
        "jsonl" => Ok(nctrans::eval::Format::Jsonl),
        _ => Err(format!("unknown trace format '{s}' (expected text or jsonl)")),
    }
}

pub fn read_file(path: &PathBuf) -> Result<Vec<u8>, ExitCode> {
    std::fs::read(path).map_err(|e| {
        eprintln!("error: cannot read {}: {e}", path.display());
        ExitCode::from(2)
    })
}

/// Loads and parses one program for a run; prints its diagnostics.
pub fn load_for_run(
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
    let sem = super::profile::semantics(db, path, dialect)?;
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
pub fn run_options(header: &str, name: &str, eval: &EvalOpts) -> Result<nctrans::eval::RunOptions, ExitCode> {
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
    let probes = if eval.probe.is_empty() {
        nctrans::eval::header_probes(header).map_err(|e| {
            eprintln!("error: {name}: bad `nctrans: probe` header: {e}");
            ExitCode::from(2)
        })?
    } else {
        eval.probe.clone()
    };
    let interrupts = if eval.interrupt.is_empty() {
        nctrans::eval::header_interrupts(header).map_err(|e| {
            eprintln!("error: {name}: bad `nctrans: interrupt` header: {e}");
            ExitCode::from(2)
        })?
    } else {
        eval.interrupt.clone()
    };
    Ok(nctrans::eval::RunOptions {
        max_steps: eval.max_steps,
        inputs,
        semantics: None,
        probe_contact: eval.probe_contact,
        probes,
        interrupts,
        expand_cycles: None,
    })
}

/// `check`: both programs meet the same probe inputs, `--probe` or else the first file's
/// `nctrans: probe` header lines (else the second's), so a translation whose header moved
/// is run as its source is.
pub fn shared_probes(eval: &EvalOpts, paths: [&PathBuf; 2]) -> Result<EvalOpts, ExitCode> {
    let mut out = eval.clone();
    // Interrupt inputs the same way: `--interrupt`, else the first file's header lines
    // (else the second's).
    if eval.interrupt.is_empty() {
        for path in paths {
            let ints = nctrans::eval::header_interrupts(&String::from_utf8_lossy(&head_of(path))).map_err(|e| {
                eprintln!("error: {}: bad `nctrans: interrupt` header: {e}", path.display());
                ExitCode::from(2)
            })?;
            if !ints.is_empty() {
                out.interrupt = ints;
                break;
            }
        }
    }
    if !eval.probe.is_empty() {
        return Ok(out);
    }
    for path in paths {
        // Header lines come first: the start of the file is enough (a large file is streamed).
        let mut head = Vec::new();
        if let Ok(f) = std::fs::File::open(path) {
            use std::io::Read;
            let _ = f.take(1 << 16).read_to_end(&mut head);
        }
        let probes = nctrans::eval::header_probes(&String::from_utf8_lossy(&head)).map_err(|e| {
            eprintln!("error: {}: bad `nctrans: probe` header: {e}", path.display());
            ExitCode::from(2)
        })?;
        if !probes.is_empty() {
            out.probe = probes;
            return Ok(out);
        }
    }
    Ok(out)
}

/// The start of a file, where its header lines are (a large file is streamed).
fn head_of(path: &PathBuf) -> Vec<u8> {
    let mut head = Vec::new();
    if let Ok(f) = std::fs::File::open(path) {
        use std::io::Read;
        let _ = f.take(1 << 16).read_to_end(&mut head);
    }
    head
}
