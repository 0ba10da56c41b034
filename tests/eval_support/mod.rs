//! Shared helpers of the evaluator tests: load, parse and run a program file, and give
//! its trace in the text form (`event  @line`) with the way it ended.

#![allow(dead_code)]

use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::eval::{self, trace, Ending, Event, Origin, RunOptions, TraceSink};
use nctrans::span::SourceDb;
use std::path::{Path, PathBuf};

pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

pub fn bless() -> bool {
    std::env::var_os("NCTRANS_BLESS").is_some_and(|v| v != "0")
}

/// Collects events (with their line) and per-block positions.
#[derive(Default)]
pub struct Collect {
    pub lines: Vec<String>,
    pub events: Vec<Event>,
    pub blocks: Vec<trace::Axes>,
    pub main_text: String,
    pub main_file: usize,
}

impl TraceSink for Collect {
    fn event(&mut self, ev: &Event, origin: Origin) {
        let mut l = trace::text_line(ev);
        if origin.file == self.main_file {
            let line = self.main_text[..(origin.span.lo as usize).min(self.main_text.len())].matches('\n').count() + 1;
            l.push_str(&format!("  @{line}"));
        }
        self.lines.push(l);
        self.events.push(ev.clone());
    }
    fn wants_blocks(&self) -> bool {
        true
    }
    fn block_done(&mut self, _origin: Origin, pos: &trace::Axes) {
        self.blocks.push(*pos);
    }
}

pub struct Ran {
    pub sink: Collect,
    pub outcome: eval::Outcome,
    pub db: SourceDb,
    pub parse_errors: Option<String>,
}

impl Ran {
    /// The trace as committed: events, then each diagnostic's code and message.
    pub fn text(&self) -> String {
        let mut s = String::new();
        for l in &self.sink.lines {
            s.push_str(l);
            s.push('\n');
        }
        if let Ending::Error = self.outcome.ending {
            for d in self.outcome.diags.iter().filter(|d| d.is_error()) {
                s.push_str(&format!("error {}: {}\n", d.code, d.message));
            }
        }
        s
    }
}

/// Runs `path` (dialect from its extension) with the file's header inputs plus `extra`.
pub fn run_file(path: &Path, extra: &[&str], max_steps: u64) -> Ran {
    run_file_expanding(path, extra, max_steps, false)
}

/// [`run_file`], with `expand` as `nctrans run --expand-cycles` with the default profile.
pub fn run_file_expanding(path: &Path, extra: &[&str], max_steps: u64, expand: bool) -> Ran {
    let bytes = std::fs::read(path).expect("readable program");
    let mut db = SourceDb::new();
    let name = path.to_string_lossy().replace('\\', "/");
    let loaded = nctrans::load(&mut db, &name, &bytes, None);
    let text = db.get(loaded.file).text.clone();
    let dialect = nctrans::detect_dialect(&name, &text);
    let parsed = nctrans::parse(&db, loaded.file, dialect, &ParseOptions::for_dialect(dialect));
    let mut sink = Collect { main_text: text.clone(), main_file: loaded.file, ..Default::default() };
    if nctrans::diag::has_errors(&parsed.diags) {
        let rendered = nctrans::diag::render(&db, &parsed.diags);
        let outcome = eval::Outcome { ending: Ending::Error, steps: 0, diags: vec![] };
        return Ran { sink, outcome, db, parse_errors: Some(rendered) };
    }
    let mut inputs = eval::header_inputs(&text).expect("valid header inputs");
    for e in extra {
        inputs.push(eval::parse_input(e).expect("valid input"));
    }
    let expand_cycles = expand.then(|| nctrans::config::Config::default().cycle_retracts(dialect));
    // The header's probe inputs (`nctrans: probe`) too, as `nctrans run` reads them.
    let probes = eval::header_probes(&text).expect("valid header probe inputs");
    let opts = RunOptions { max_steps, inputs, expand_cycles, probes, ..Default::default() };
    let mut callees = eval::DirCallees { semantics: None };
    let outcome = eval::run(&mut db, &parsed.unit, &mut callees, &opts, &mut sink);
    Ran { sink, outcome, db, parse_errors: None }
}

/// Every corpus program, readable and erroneous, of both dialects, in path order.
pub fn corpus_files() -> Vec<PathBuf> {
    let mut v = Vec::new();
    for top in ["corpus/in", "corpus/err"] {
        for (_, d) in dialect_dirs() {
            let Ok(rd) = std::fs::read_dir(root().join(top).join(d)) else { continue };
            v.extend(rd.filter_map(|e| e.ok()).map(|e| e.path()).filter(|p| p.is_file()));
        }
    }
    v.sort();
    v
}

pub fn dialect_dirs() -> [(Dialect, &'static str); 2] {
    [(Dialect::Fanuc, "fanuc"), (Dialect::Sinumerik, "sinumerik")]
}

/// Writes `text` to a scratch file named `name` (the extension picks the dialect) and
/// runs it.
pub fn run_text(name: &str, text: &str, extra: &[&str]) -> Ran {
    let dir = root().join("target/eval-tests");
    std::fs::create_dir_all(&dir).expect("scratch dir");
    let path = dir.join(name);
    std::fs::write(&path, text).expect("scratch file");
    run_file(&path, extra, 1_000_000)
}

/// The trace lines without their `@line` suffix.
pub fn bare_lines(ran: &Ran) -> Vec<String> {
    ran.sink.lines.iter().map(|l| l.split("  @").next().unwrap_or("").to_string()).collect()
}

static SCRATCH: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);

/// A scratch file `target/eval-tests/<prefix>-<k>.<ext>` holding `text` (k counts up in the
/// test binary, so parallel tests never share one); its path.
pub fn scratch_file(prefix: &str, ext: &str, text: &str) -> String {
    let k = SCRATCH.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = root().join("target/eval-tests");
    std::fs::create_dir_all(&dir).expect("scratch dir");
    let p = dir.join(format!("{prefix}-{k}.{ext}"));
    std::fs::write(&p, text).expect("write");
    p.to_string_lossy().to_string()
}

/// An emptied folder `target/<area>/<name>` for one test's files.
pub fn scratch_dir(area: &str, name: &str) -> PathBuf {
    let d = root().join("target").join(area).join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("scratch dir");
    d
}

/// Writes `text` to `dir/name`; its path.
pub fn write(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).expect("write");
    p.to_string_lossy().into_owned()
}

/// Runs the nctrans binary: its exit code, stdout and stderr.
pub fn nctrans(args: &[&str]) -> (i32, String, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_nctrans")).args(args).output().expect("run nctrans");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// `nctrans run FILE EXTRA…`: the trace with each line's `  @…` place cut off, and stderr.
pub fn run_bare(file: &str, extra: &[&str]) -> (String, String) {
    let mut args = vec!["run", file];
    args.extend_from_slice(extra);
    let (_, out, err) = nctrans(&args);
    let lines: Vec<&str> = out.lines().map(|l| l.split("  @").next().unwrap_or("")).collect();
    (lines.join("\n"), err)
}

/// [`nctrans`] run from `dir` (its `nctrans.toml` applies).
pub fn nctrans_in(dir: &std::path::Path, args: &[&str]) -> (i32, String, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_nctrans"))
        .current_dir(dir)
        .args(args)
        .output()
        .expect("run nctrans");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}
