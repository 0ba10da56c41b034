//! The literal fast path of the evaluator (`Machine::apply_lit`) against the general path
//! it shortcuts: every corpus program and thousands of generated straight-line programs
//! (both dialects, in memory and streamed) run with the fast path on and off, and their
//! text and jsonl traces, per-block positions, endings, steps and diagnostics must be
//! identical byte for byte.

use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::eval::machine::set_fast_path;
use nctrans::eval::trace::{Axes, Format, GridMove, Origin, WriterSink};
use nctrans::eval::{self, Event, Outcome, RunOptions, TraceSink};
use nctrans::span::SourceDb;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
#[path = "support/rng.rs"]
mod rng;
use rng::Rng;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Writes the trace in both formats (with the span's start as the `line`) and the
/// position after every block.
struct Both {
    text: WriterSink<'static, Vec<u8>>,
    json: WriterSink<'static, Vec<u8>>,
    blocks: String,
}

impl Both {
    fn new() -> Both {
        let line = |o: Origin| Some(o.span.lo as usize * 1000 + o.span.hi as usize % 1000 + o.file * 7);
        Both {
            text: WriterSink::new(Vec::new(), Format::Text, Box::new(line)),
            json: WriterSink::new(Vec::new(), Format::Jsonl, Box::new(line)),
            blocks: String::new(),
        }
    }
}

impl TraceSink for Both {
    fn event(&mut self, ev: &Event, origin: Origin) {
        self.text.event(ev, origin);
        self.json.event(ev, origin);
    }
    // The writers' own grid move (the fast path's way to them) against their `event`
    // (the general path's).
    fn grid_move(&mut self, m: &GridMove, origin: Origin) {
        self.text.grid_move(m, origin);
        self.json.grid_move(m, origin);
    }
    fn wants_blocks(&self) -> bool {
        true
    }
    // The writers hand over their last lines here (without it their outputs stay short).
    fn finish(&mut self) {
        self.text.finish();
        self.json.finish();
    }
    fn block_done(&mut self, origin: Origin, pos: &Axes) {
        let _ = writeln!(self.blocks, "{origin:?} {pos:?}");
    }
}

/// Everything a run gives, as text.
fn report(sink: Both, out: &Outcome) -> String {
    let mut s = String::from_utf8_lossy(&sink.text.out).into_owned();
    s.push_str(&String::from_utf8_lossy(&sink.json.out));
    s.push_str(&sink.blocks);
    let _ = writeln!(s, "{:?} steps={}", out.ending, out.steps);
    for d in &out.diags {
        let labels: Vec<_> = d.labels.iter().map(|l| (l.file, l.span)).collect();
        let _ = writeln!(s, "{:?} {} {} {labels:?}", d.severity, d.code, d.message);
    }
    s
}

/// Runs the program in `path` from memory.
fn run_mem(path: &Path) -> String {
    let Ok(bytes) = std::fs::read(path) else { return "unreadable".into() };
    let mut db = SourceDb::new();
    let name = path.to_string_lossy().replace('\\', "/");
    let loaded = nctrans::load(&mut db, &name, &bytes, None);
    let text = db.get(loaded.file).text.clone();
    let dialect = nctrans::detect_dialect(&name, &text);
    let parsed = nctrans::parse(&db, loaded.file, dialect, &ParseOptions::for_dialect(dialect));
    if nctrans::diag::has_errors(&parsed.diags) {
        return "parse error".into();
    }
    let inputs = eval::header_inputs(&text).unwrap_or_default();
    let opts = RunOptions { max_steps: 200_000, inputs, ..Default::default() };
    let mut sink = Both::new();
    let out = eval::run(&mut db, &parsed.unit, &mut eval::DirCallees { semantics: None }, &opts, &mut sink);
    report(sink, &out)
}

/// Runs the program in `path` streamed (its literal blocks come from the re-read, not
/// from the IR); `None` when it cannot stream.
fn run_streamed(path: &Path, dialect: Dialect) -> Option<String> {
    let opts = ParseOptions::for_dialect(dialect);
    let ix = nctrans::stream::scan_index_path(path, 0, dialect, &opts, None).ok()?;
    let mut db = SourceDb::new();
    db.add(path.display().to_string(), String::new());
    let run = RunOptions { max_steps: 200_000, ..Default::default() };
    let runner = nctrans::stream::runner(std::sync::Arc::new(ix), Box::new(eval::DirCallees { semantics: None }), run);
    let mut sink = Both::new();
    let out = runner.run(&mut db, &mut sink);
    Some(report(sink, &out))
}

/// Runs `f` with the fast path off, then on; asserts equal results; returns the trace.
fn same(what: &str, f: impl Fn() -> String) -> String {
    set_fast_path(false);
    let general = f();
    set_fast_path(true);
    let fast = f();
    if fast != general {
        let first = fast.lines().zip(general.lines()).position(|(a, b)| a != b);
        let show = |s: &str| first.and_then(|i| s.lines().nth(i)).unwrap_or("(shorter)").to_string();
        panic!("{what}: the fast path differs\n  fast:    {}\n  general: {}", show(&fast), show(&general));
    }
    fast
}

#[test]
fn corpus_programs_run_the_same_with_the_fast_path() {
    let mut count = 0;
    for top in ["corpus/in", "corpus/err"] {
        for d in ["fanuc", "sinumerik"] {
            let Ok(rd) = std::fs::read_dir(root().join(top).join(d)) else { continue };
            let mut files: Vec<_> = rd.filter_map(|e| e.ok()).map(|e| e.path()).filter(|p| p.is_file()).collect();
            files.sort();
            for f in files {
                same(&f.display().to_string(), || run_mem(&f));
                count += 1;
            }
        }
    }
    assert!(count > 50 || !root().join("corpus/in").exists(), "only {count} corpus programs ran");
}

/// A number as CAM posts and people write it: sign, digits, with or without a point,
/// up to five decimals (off the 0.001 grid too), large and tiny values.
fn num(r: &mut Rng, fanuc: bool) -> String {
    let sign = if r.below(3) == 0 { "-" } else { "" };
    let int = r.next() % [1, 10, 100, 1000, 100_000][r.below(5) as usize];
    match r.below(10) {
        // 0..=15 digits (1 at least), 0..=6 of them after the point: the compact words'
        // thousandths worked out from the digits (`dialect::lit::thousandths`), up to where they
        // are not and the value is rounded instead.
        7 | 8 => {
            let digits = 1 + r.below(15) as usize;
            let frac = r.below(digits.min(6) as u64 + 1) as usize;
            let mut d: String = (0..digits).map(|_| char::from(b'0' + r.below(10) as u8)).collect();
            if frac > 3 && r.below(2) == 0 {
                // A tie of the thousandth, or next to one.
                let at = digits - frac + 3;
                let mut tail = r.pick(&["5", "49999999", "50000001", "4", "6"]).to_string();
                while tail.len() < frac - 3 {
                    tail.push('0');
                }
                tail.truncate(frac - 3);
                d.replace_range(at.., &tail);
            }
            if fanuc && frac == 0 && r.below(2) == 0 {
                return format!("{sign}{d}");
            }
            format!("{sign}{}.{}", &d[..digits - frac], &d[digits - frac..])
        }
        9 => format!(
            "{sign}{}",
            r.pick(&["0.0005", "1.2345", "0.00049999", "0.0015", "999.9995", "0.00050001", "2.0025"])
        ),
        0 if fanuc => format!("{sign}{int}"),
        0 => format!("{sign}{int}."),
        1 => format!("{sign}{int}.{}", r.below(10)),
        2 => format!("{sign}{int}.{:05}", r.below(100_000)),
        3 => format!("{sign}.{:03}", r.below(1000)),
        4 => format!("{sign}{int}.{:03}5", r.below(1000)),
        _ => format!("{sign}{int}.{:04}", r.below(10_000)),
    }
}

/// One straight-line block, mostly what the fast path takes, sometimes what it must
/// leave to the general path (M, S, arcs, offsets, warnings, duplicate words).
fn block(r: &mut Rng, fanuc: bool) -> String {
    let mut b = String::new();
    if r.below(4) == 0 {
        let _ = write!(b, "N{} ", r.below(10_000));
    }
    let common = ["G0", "G1", "G1", "G1", "G90", "G91", "G17", "G18", "G94", "G95"];
    let units: &[&str] = if fanuc {
        &["G20", "G21", "G21", "G54", "G55"]
    } else {
        &["G70", "G71", "G700", "G710", "G71", "G54", "G500"]
    };
    for _ in 0..r.below(3) {
        let g = if r.below(4) == 0 { r.pick(units) } else { r.pick(&common) };
        b.push_str(g);
        b.push(' ');
    }
    let rare = if fanuc {
        ["G64", "M3 S1000", "M8", "G2 X1. Y1. R5.", "G10 L2 P2 X7.5 Y-2.25 Z1.", "T1 M6", "G4 X1.", "M1", "G40"]
    } else {
        ["G64", "M3 S1000", "M8", "G2 X1 Y1 CR=5", "TRANS X7.5 Y-2.25", "T1 M6", "G4 F1", "M1", "ATRANS Z.5"]
    };
    if r.below(30) == 0 {
        b.push_str(r.pick(&rare));
        b.push(' ');
    }
    // Rotary and U, V, W axes mostly in rapids: a feed move of them has a feed of its own
    // (`machine::path_feed`, always the general path) and is refused in many modes.
    let letters = if r.below(5) == 0 {
        b.push_str("G0 ");
        &["X", "Y", "Z", "A", "B", "C", "U", "V", "W"][..]
    } else if r.below(20) == 0 {
        &["X", "Y", "Z", "A", "B", "C", "U", "V", "W", "F"][..]
    } else {
        &["X", "Y", "Z", "X", "Y", "Z", "F"][..]
    };
    for _ in 0..r.below(6) {
        let l = r.pick(letters);
        if !fanuc && l != "F" && r.below(10) == 0 {
            let f = if r.below(2) == 0 { "AC" } else { "IC" };
            let _ = write!(b, "{l}={f}({}) ", num(r, fanuc));
        } else if l == "F" {
            let _ = write!(b, "F{} ", num(r, fanuc).trim_start_matches('-'));
        } else {
            let _ = write!(b, "{l}{} ", num(r, fanuc));
        }
    }
    if r.below(12) == 0 {
        b.push_str(if fanuc { "(NOTE)" } else { "; note" });
    }
    b.trim_end().to_string()
}

/// A generated program: sometimes without any feed before the first G1 (the alarm).
fn program(r: &mut Rng, fanuc: bool, blocks: usize) -> String {
    let mut text = String::from(if fanuc { "%\nO1000\n" } else { "" });
    match r.below(3) {
        0 => {}
        1 => text.push_str(if fanuc { "G21 G90 F500.\n" } else { "G71 G90 F500\n" }),
        _ => text.push_str(if fanuc { "G90 G0 X0 Y0 Z5.\n" } else { "G90 G0 X0 Y0 Z5\n" }),
    }
    for _ in 0..blocks {
        text.push_str(&block(r, fanuc));
        text.push('\n');
    }
    text.push_str(if fanuc { "M30\n%\n" } else { "M30\n" });
    text
}

#[test]
fn generated_straight_line_programs_run_the_same_with_the_fast_path() {
    let dir = root().join("target/eval-fast-tests");
    std::fs::create_dir_all(&dir).expect("scratch dir");
    let mut r = Rng(77);
    let (mut moves, mut streamed) = (0, 0);
    for i in 0..600 {
        let fanuc = i % 2 == 0;
        let text = program(&mut r, fanuc, 60);
        let path = dir.join(if fanuc { "gen.nc" } else { "gen.mpf" });
        std::fs::write(&path, &text).expect("scratch file");
        let dialect = if fanuc { Dialect::Fanuc } else { Dialect::Sinumerik };
        let trace = same(&format!("generated program\n{text}"), || run_mem(&path));
        moves += trace.lines().filter(|l| l.starts_with("move")).count();
        if i % 3 == 0 {
            if let Some(t) = run_streamed(&path, dialect) {
                streamed += 1;
                let again =
                    same(&format!("streamed program\n{text}"), || run_streamed(&path, dialect).unwrap_or_default());
                assert_eq!(t, again);
            }
        }
    }
    // The programs must move a lot (not all stop at their first alarm), and stream.
    assert!(moves > 10_000, "only {moves} moves");
    assert!(streamed > 100, "only {streamed} programs streamed");
}

/// The text trace of a streamed run with real line numbers (`@line` from the text), the
/// writer taking the lines its moves carry (`block_lines`) or looking every one up.
fn streamed_text(path: &Path, dialect: Dialect, block_lines: bool) -> Option<Vec<u8>> {
    let text = std::fs::read_to_string(path).ok()?;
    let opts = ParseOptions::for_dialect(dialect);
    let ix = nctrans::stream::scan_index_path(path, 0, dialect, &opts, None).ok()?;
    let mut db = SourceDb::new();
    let file = db.add(path.display().to_string(), String::new());
    let run = RunOptions { max_steps: 200_000, ..Default::default() };
    let runner = nctrans::stream::runner(std::sync::Arc::new(ix), Box::new(eval::DirCallees { semantics: None }), run);
    let line = move |o: Origin| {
        (o.file == file).then(|| text.as_bytes()[..o.span.lo as usize].iter().filter(|&&c| c == b'\n').count() + 1)
    };
    let mut sink = WriterSink::new(Vec::new(), Format::Text, Box::new(line));
    if block_lines {
        sink.block_lines = Some(file);
    }
    runner.run(&mut db, &mut sink);
    Some(sink.out)
}

#[test]
fn lines_carried_by_streamed_blocks_are_the_lines_of_their_spans() {
    // Where the stream's re-read gives its blocks their lines, the writer takes them (and,
    // in a debug build, asserts each is the one looked up): the traces must be the same.
    let dir = root().join("target/eval-fast-tests");
    std::fs::create_dir_all(&dir).expect("scratch dir");
    let mut r = Rng(91);
    for i in 0..40 {
        let fanuc = i % 2 == 0;
        let text = program(&mut r, fanuc, 80);
        let path = dir.join(if fanuc { "lines.nc" } else { "lines.mpf" });
        std::fs::write(&path, &text).expect("scratch file");
        let dialect = if fanuc { Dialect::Fanuc } else { Dialect::Sinumerik };
        let looked_up = streamed_text(&path, dialect, false);
        assert_eq!(streamed_text(&path, dialect, true), looked_up, "{text}");
    }
}
