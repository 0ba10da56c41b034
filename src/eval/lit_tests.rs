//! The compact literal blocks ([`super::lit`]) against the IR they replace: every corpus
//! program and many generated ones run both ways and must give the same trace, event
//! origins, per-block positions, ending, steps and diagnostics.

use super::numfmt::tests::Rng;
use super::trace::{text_line, Axes, Event, Origin, TraceSink};
use super::{header_inputs, run, DirCallees, RunOptions};
use crate::dialect::lit;
use crate::dialect::ParseOptions;
use crate::span::SourceDb;
use std::fmt::Write;

#[derive(Default)]
struct Record(String);

impl TraceSink for Record {
    fn event(&mut self, ev: &Event, origin: Origin) {
        let _ = writeln!(self.0, "{}  {:?}", text_line(ev), origin);
    }
    fn wants_blocks(&self) -> bool {
        true
    }
    fn block_done(&mut self, origin: Origin, pos: &Axes) {
        let _ = writeln!(self.0, "  block {origin:?} {pos:?}");
    }
}

/// Everything a run gives, as text.
fn run_text(name: &str, text: &str) -> String {
    let mut db = SourceDb::new();
    let loaded = crate::load(&mut db, name, text.as_bytes(), None);
    let dialect = crate::detect_dialect(name, text);
    let parsed = crate::parse(&db, loaded.file, dialect, &ParseOptions::for_dialect(dialect));
    if crate::diag::has_errors(&parsed.diags) {
        return "parse error".into();
    }
    let inputs = header_inputs(text).unwrap_or_default();
    let opts = RunOptions { max_steps: 100_000, inputs, ..Default::default() };
    let mut sink = Record::default();
    let out = run(&mut db, &parsed.unit, &mut DirCallees { semantics: None }, &opts, &mut sink);
    let mut s = sink.0;
    let _ = writeln!(s, "{:?} steps={}", out.ending, out.steps);
    for d in &out.diags {
        let labels: Vec<_> = d.labels.iter().map(|l| (l.file, l.span)).collect();
        let _ = writeln!(s, "{:?} {} {} {labels:?}", d.severity, d.code, d.message);
    }
    s
}

/// Runs `text` with and without the compact blocks; returns how many events it made.
fn same_both_ways(name: &str, text: &str) -> usize {
    let fast = run_text(name, text);
    let ir = lit::without(|| run_text(name, text));
    assert_eq!(fast, ir, "{name} runs differently with compact blocks:\n{text}");
    fast.lines().count()
}

#[test]
fn corpus_programs_run_the_same_with_compact_blocks() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut count = 0;
    for d in ["fanuc", "sinumerik"] {
        let Ok(rd) = std::fs::read_dir(root.join("corpus/in").join(d)) else { continue };
        let mut files: Vec<_> = rd.filter_map(|e| e.ok()).map(|e| e.path()).collect();
        files.sort();
        for f in files {
            let Ok(bytes) = std::fs::read(&f) else { continue };
            let rel = f.strip_prefix(root).unwrap_or(&f).to_string_lossy().replace('\\', "/");
            // Decoded as the harness does (legacy encodings too).
            let mut db = SourceDb::new();
            let loaded = crate::load(&mut db, &rel, &bytes, None);
            let text = db.get(loaded.file).text.clone();
            same_both_ways(&rel, &text);
            count += 1;
        }
    }
    assert!(count > 50 || !root.join("corpus/in").exists(), "only {count} corpus programs ran");
}

/// A random number as a CAM post writes it: sign, digits, maybe a point and decimals.
fn num(r: &mut Rng, fanuc: bool) -> String {
    let sign = if r.next().is_multiple_of(3) { "-" } else { "" };
    let int = r.next() % [1, 10, 100, 1000][(r.next() % 4) as usize];
    match r.next() % 4 {
        // FANUC without a point: the decimal-point rule applies.
        0 if fanuc => format!("{sign}{int}"),
        0 => format!("{sign}{int}."),
        1 => format!("{sign}{int}.{}", r.next() % 10),
        _ => format!("{sign}{int}.{:04}", r.next() % 10_000),
    }
}

/// One random block: mostly motion, with the modal codes, M functions, arcs and odd
/// forms that change what a block of literals does.
fn block(r: &mut Rng, fanuc: bool) -> String {
    let mut b = String::new();
    if r.next().is_multiple_of(4) {
        let _ = write!(b, "N{} ", r.next() % 1000);
    }
    let pick = |r: &mut Rng, xs: &[&str]| xs[(r.next() % xs.len() as u64) as usize].to_string();
    // Arcs and dwells stop a run when malformed, so they come whole and rarely.
    if r.next().is_multiple_of(25) {
        let arc = pick(r, &["G2", "G3", "G4", "G2 G17", "G3 G18"]);
        let (x, y) = (num(r, fanuc), num(r, fanuc));
        return match (arc.as_str(), fanuc) {
            ("G4", true) => format!("{b}G4 X{}", num(r, true).trim_start_matches('-')),
            ("G4", false) => format!("{b}G4 F{}", num(r, false).trim_start_matches('-')),
            (a, true) => format!("{b}{a} X{x} Y{y} Z{x} R5000."),
            (a, false) => format!("{b}{a} X{x} Y{y} Z{x} CR=5000"),
        };
    }
    let g_common = ["G0", "G1", "G1", "G1", "G17", "G18", "G19", "G90", "G91", "G54", "G64", "G40"];
    let g_dialect: &[&str] = if fanuc {
        &["G20", "G21", "G53", "G55", "G31", "G10 L2 P1", "G94", "G95"]
    } else {
        &["G70", "G71", "G700", "G710", "G500", "G94", "G95"]
    };
    for _ in 0..(r.next() % 3) {
        b.push_str(&if r.next().is_multiple_of(3) { pick(r, g_dialect) } else { pick(r, &g_common) });
        b.push(' ');
    }
    // One rotary letter: a feed move of a rotary axis is refused in several modes (NC662),
    // which would end too many runs early; B and C come in the read-backs below.
    let letters =
        ["X", "Y", "Z", "X", "Y", "Z", "A", "X", "Y", "F", "F", "I", "J", "K", "R", "S", "P", "D", "H", "E", "Q"];
    for _ in 0..(r.next() % 6) {
        let l = pick(r, &letters);
        if !fanuc && r.next().is_multiple_of(12) && matches!(l.as_str(), "X" | "Y" | "Z") {
            let f = if r.next().is_multiple_of(2) { "AC" } else { "IC" };
            let _ = write!(b, "{l}={f}({}) ", num(r, fanuc));
        } else if !fanuc && l == "R" {
            let _ = write!(b, "CR={} ", num(r, fanuc).trim_start_matches('-'));
        } else {
            let _ = write!(b, "{l}{} ", num(r, fanuc));
        }
    }
    if r.next().is_multiple_of(5) {
        b.push_str(&pick(r, &["M3", "M4", "M5", "M6", "M7", "M8", "M9", "M1", "M0", "M41", "T1 M6", "T2", "S500"]));
    }
    if r.next().is_multiple_of(10) {
        b.push_str(if fanuc { " (COMMENT)" } else { " ; comment" });
    }
    if fanuc && r.next().is_multiple_of(15) {
        // The state literal blocks leave (last N and M, positions), read back.
        b.push_str(&pick(r, &["\nG1 A#4114", "\nG1 B#4113", "\nG1 C#5001", "\nG1 A#5022", "\n#1=#4001 G#1"]));
    }
    b.trim_end().to_string()
}

#[test]
fn generated_programs_run_the_same_with_compact_blocks() {
    let mut r = Rng(2024);
    let mut events = 0;
    for i in 0..400 {
        let fanuc = i % 2 == 0;
        let mut text = String::from(if fanuc { "%\nO1000\nG21 G90 F500.\n" } else { "G71 G90 F500\n" });
        for _ in 0..40 {
            text.push_str(&block(&mut r, fanuc));
            text.push('\n');
        }
        text.push_str(if fanuc { "M30\n%\n" } else { "M30\n" });
        events += same_both_ways(if fanuc { "gen.nc" } else { "gen.mpf" }, &text);
    }
    // The programs must run far enough to say something (not all stop at an error).
    assert!(events > 12_000, "only {events} trace lines");
}
