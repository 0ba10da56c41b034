//! Segmented streaming translation (FANUC → Sinumerik with a macro part): where it does not
//! decline, its output is byte-identical to the whole-file translation (warnings too) and
//! its streamed verification gives the same verdict as the whole-file verification.
//! Inputs: every corpus FANUC program with runs of generated CAM blocks put between its
//! top-level statements, and generated programs (macro prologue/epilogue, IF..GOTO,
//! WHILE..DO, jumps to N numbers of CAM blocks forward and backward, duplicate N numbers,
//! G2/G3 by R around macro statements and loops, LF and CRLF). What it must decline, it
//! declines; the CLI then translates whole with the same output.

#[path = "support/fanuc_runs.rs"]
mod fanuc_runs;
#[path = "support/rng.rs"]
mod rng;

use nctrans::check::Verdict;
use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::eval::{header_inputs, DirCallees, NoCallees, RunOptions};
use nctrans::read::LineEnding;
use nctrans::span::SourceDb;
use nctrans::stream::segmented::sinumerik as segmented;
use nctrans::stream::verify::{self as sv, StreamSide};
use nctrans::stream::Fallback;
use nctrans::translate::to_sinumerik::{self as ts, Options};
use rng::Rng;
use std::path::{Path, PathBuf};
use std::process::Command;

const MAX_STEPS: u64 = 200_000;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn scratch(name: &str) -> PathBuf {
    let d = root().join("target/stream-segmented-sin").join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("dir");
    d
}

fn opts() -> Options {
    Options { main_name: "CAMPART".into(), ..Options::default() }
}

/// What happened to one program.
#[derive(Debug)]
enum Outcome {
    Declined(String),
    /// Identical; the verdict.
    Same(Verdict),
}

/// The streamed check of a written translation (both programs streamed).
fn streamed_check(path: &Path, out: &Path, o: &Options) -> Verdict {
    let popts = ParseOptions { semantics: o.source.clone() };
    let src = nctrans::stream::scan_path(path, 0, Dialect::Fanuc, &popts, &mut |_, _| {}, None).expect("scan");
    let Ok(back) = sv::read_back(out, 1, Dialect::Sinumerik, &ParseOptions { semantics: o.target.clone() }, None)
    else {
        return Verdict::Failed;
    };
    let (Ok(in_a), Ok(in_b)) = (header_inputs(&src.header), header_inputs(&back.header)) else {
        return Verdict::Failed;
    };
    let run = |inputs, sem: &nctrans::dialect::Semantics| RunOptions {
        inputs,
        max_steps: MAX_STEPS,
        semantics: Some(sem.clone()),
        probe_contact: None,
        probes: Vec::new(),
        interrupts: Vec::new(),
        expand_cycles: None,
    };
    let a = StreamSide {
        run: run(in_a, &o.source),
        index: src,
        name: path.display().to_string(),
        callees: Box::new(DirCallees { semantics: Some(o.source.clone()) }),
    };
    let b = StreamSide {
        run: run(in_b, &o.target),
        index: back,
        name: out.display().to_string(),
        callees: Box::new(NoCallees),
    };
    sv::compare(a, b).verdict
}

/// Translates `path` whole and segmented; when segmented does not decline, asserts the
/// same bytes, the same warnings and the same verdict.
fn compare(path: &Path) -> Outcome {
    let o = opts();
    let bytes = std::fs::read(path).expect("read");
    let mut db = SourceDb::new();
    let loaded = nctrans::load(&mut db, &path.display().to_string(), &bytes, None);
    let parsed = nctrans::parse(&db, loaded.file, Dialect::Fanuc, &ParseOptions { semantics: o.source.clone() });
    let tr = ts::translate(&[&parsed.unit], &o, loaded.line_ending);
    let mut out = Vec::new();
    let seg = match segmented::to_sinumerik(path, &o, loaded.line_ending, &mut out, None) {
        Ok(s) => s,
        Err(Fallback::NotStraight(why)) => return Outcome::Declined(why),
        Err(f) => return Outcome::Declined(format!("{f:?}")),
    };
    let name = path.display();
    assert!(!tr.has_errors(), "{name}: segmented took a program the whole translation refuses");
    let main = tr.main().expect("main");
    let whole = nctrans::read::encode(&main.text, loaded.encoding, loaded.bom);
    if out != whole {
        let (g, w) = (String::from_utf8_lossy(&out), String::from_utf8_lossy(&whole));
        let at = g.bytes().zip(w.bytes()).take_while(|(a, b)| a == b).count();
        let cut = |s: &str| s[at.saturating_sub(300).min(s.len())..(at + 300).min(s.len())].to_string();
        panic!("{name}: segmented differs at byte {at}:\n--- whole ---\n{}\n--- segmented ---\n{}", cut(&w), cut(&g));
    }
    assert_eq!(seg.diags, tr.diags, "{name}");
    assert_eq!(seg.file_name, main.name, "{name}");
    assert_eq!(&seg.symbols, tr.symbols.sinumerik(), "{name}");
    let out_path = path.with_extension("seg.mpf");
    std::fs::write(&out_path, &out).expect("write");
    let profiles =
        nctrans::translate::to_sinumerik::verify::Profiles { fanuc: o.source.clone(), sinumerik: o.target.clone() };
    let w = nctrans::translate::to_sinumerik::verify::verify_profiled(
        &db,
        loaded.file,
        &parsed.unit,
        &tr,
        "",
        MAX_STEPS,
        &profiles,
    );
    let v = streamed_check(path, &out_path, &o);
    assert_eq!(v, w.verdict, "{name}: streamed / whole verdicts");
    Outcome::Same(v)
}

/// A coordinate as CAM output writes it (without a point it counts 0.001 mm).
fn coord(r: &mut Rng) -> String {
    let v = r.below(20_000) as f64 / 1000.0 - 10.0;
    match r.below(4) {
        0 => format!("{}", (v * 1000.0).round() as i64),
        1 => format!("{v:.1}"),
        2 => format!("{v:.4}"),
        _ => format!("{}.", v.round() as i64),
    }
}

/// A run of `n` CAM blocks (lines joined by `eol`, each ended): straight moves, arcs by R
/// (a radius that fits any chord in the ±10 mm box, so every arc is valid wherever a jump
/// comes from), R-only arc blocks while an arc mode is on (as the text has it), feeds, N
/// numbers from `ns` (some repeat), a comment now and then. `arc` is the text's arc mode.
fn cam_run(r: &mut Rng, n: usize, eol: &str, arc: &mut bool, ns: &mut Vec<u32>) -> String {
    let mut t = String::new();
    for _ in 0..n {
        let mut line = String::new();
        if r.chance(15) {
            let v = 1 + r.below(60) as u32;
            ns.push(v);
            line.push_str(&format!("N{v} "));
        }
        let radius = format!("R{}{}.{}", if r.chance(20) { "-" } else { "" }, 15 + r.below(15), r.below(1000));
        match r.below(10) {
            0..=3 => {
                line.push_str(&format!("G1 X{} Y{} Z{}", coord(r), coord(r), coord(r)));
                *arc = false;
            }
            4 | 5 => {
                line.push_str(&format!("G{} X{} Y{} {radius}", 2 + r.below(2), coord(r), coord(r)));
                *arc = true;
            }
            6 if *arc => line.push_str(&format!("X{} Y{} {radius}", coord(r), coord(r))),
            6 => line.push_str(&format!("X{} Z{}", coord(r), coord(r))),
            7 => {
                line.push_str(&format!("G0 Z{}", coord(r)));
                *arc = false;
            }
            8 => line.push_str(&format!("F{}.", 100 + r.below(900))),
            // What the fast path leaves to the passes: a dwell (tool compensation is refused).
            9 if r.chance(30) => line.push_str(r.pick(&["G4 P200", "G4 X0.5"])),
            _ => line.push_str(&format!("(PASS {})", r.below(99))),
        }
        if r.chance(5) && !line.starts_with('N') {
            line.insert(0, '/');
        }
        t.push_str(&line);
        t.push_str(eol);
    }
    t
}

/// [`cam_run`] of fewer than `max` blocks.
fn cam_upto(r: &mut Rng, max: u64, eol: &str, arc: &mut bool, ns: &mut Vec<u32>) -> String {
    let n = r.below(max) as usize;
    cam_run(r, n, eol, arc, ns)
}

/// A generated macro program with CAM runs between its statements.
fn generated(seed: u64, eol: &str) -> String {
    let mut r = Rng(seed);
    let mut t = format!("%{eol}O{} (GEN {seed}){eol}", 1000 + seed % 8000);
    if r.chance(50) {
        t.push_str(&format!("(nctrans: set #1=2. #100=3.){eol}"));
    }
    t.push_str(&format!("#100=[#100+1]{eol}#101=2.5{eol}"));
    if r.chance(30) {
        t.push_str(&format!("G0 Z20.{eol}"));
    }
    t.push_str(&format!("G21 G17 G90 G94{eol}G0 X0. Y0. Z5.{eol}"));
    let mut arc = false;
    let mut ns: Vec<u32> = Vec::new();
    let mut counter = 130;
    for _ in 0..2 + r.below(6) {
        t.push_str(&cam_upto(&mut r, 25, eol, &mut arc, &mut ns));
        match r.below(9) {
            0 => t.push_str(&format!("#102=#101*{}+#100{eol}", r.below(9))),
            1 | 2 if !ns.is_empty() => {
                // A jump to an N number written so far (backward, once: a counter) or later.
                let n = ns[r.index(ns.len())];
                counter += 1;
                t.push_str(&format!("#{counter}=#{counter}+1{eol}IF[#{counter}LT2]GOTO{n}{eol}"));
            }
            3 => {
                // A forward jump to an N of the next run (the target is written there).
                let n = 61 + r.below(20) as u32;
                t.push_str(&format!("IF[#100GT{}]GOTO{n}{eol}", r.below(5)));
                t.push_str(&cam_upto(&mut r, 6, eol, &mut arc, &mut ns));
                t.push_str(&format!("N{n} G1 X{} Y0.{eol}", coord(&mut r)));
                ns.push(n);
                arc = false;
            }
            4 => {
                let g = 2 + r.below(2);
                t.push_str(&format!(
                    "#1=0{eol}WHILE[#1LT2]DO1{eol}G{g} X{} Y{} R20.{eol}#1=#1+1{eol}END1{eol}",
                    coord(&mut r),
                    coord(&mut r)
                ));
                arc = true;
            }
            5 => {
                t.push_str(&format!("G1 X#101 Y#100{eol}"));
                arc = false;
            }
            6 => {
                t.push_str(&format!("G{} X#101 Y1. R25.{eol}", 2 + r.below(2)));
                arc = true;
            }
            7 => t.push_str(&format!("IF[#101GT1.]THEN#103=#101{eol}")),
            _ => t.push_str(&format!("G4 P{}{eol}", r.below(500))),
        }
    }
    t.push_str(&cam_upto(&mut r, 25, eol, &mut arc, &mut ns));
    t.push_str(&format!("#104=#100+#101{eol}M30{eol}%{eol}"));
    t
}

#[test]
fn generated_macro_programs_translate_segmented_to_the_whole_translation() {
    let dir = scratch("generated");
    let (mut same, mut equivalent, mut declined) = (0, 0, Vec::new());
    for seed in 1..=160u64 {
        let eol = if seed % 3 == 0 { "\r\n" } else { "\n" };
        let path = dir.join(format!("g{seed}.nc"));
        std::fs::write(&path, generated(seed, eol)).expect("write");
        match compare(&path) {
            Outcome::Same(v) => {
                same += 1;
                equivalent += usize::from(matches!(v, Verdict::Equivalent { .. }));
            }
            Outcome::Declined(why) => declined.push((seed, why)),
        }
    }
    assert!(same >= 150, "{same} segmented; declined: {declined:?}");
    assert!(equivalent >= 140, "{equivalent} of {same} equivalent");
}

#[test]
fn corpus_programs_with_cam_runs_translate_segmented_to_the_whole_translation() {
    let Ok(rd) = std::fs::read_dir(root().join("corpus/in/fanuc")) else {
        println!("note: corpus/in/fanuc not found; skipped");
        return;
    };
    let dir = scratch("corpus");
    let mut files: Vec<PathBuf> = rd.filter_map(|e| e.ok()).map(|e| e.path()).collect();
    files.sort();
    let (mut same, mut declined) = (Vec::new(), 0);
    for f in files {
        let Ok(text) = std::fs::read_to_string(&f) else { continue };
        let name = f.file_name().map(|n| n.to_string_lossy().to_string()).unwrap_or_default();
        // One generator per file, seeded by its name, so a corpus file added later does not
        // change the runs inserted into the others.
        let mut r = Rng(name.bytes().fold(7u64, |h, b| h.wrapping_mul(31).wrapping_add(u64::from(b))));
        // The arc mode and the N numbers used run on from one inserted run to the next.
        let (mut arc, mut ns) = (false, Vec::new());
        let runs =
            fanuc_runs::with_runs(&text, &mut r, 60, |r, eol| Some(cam_upto(r, 31, eol.as_str(), &mut arc, &mut ns)));
        for (k, t) in [Some(text.clone()), runs].into_iter().flatten().enumerate() {
            let path = dir.join(format!("{k}-{name}"));
            std::fs::write(&path, t).expect("write");
            match compare(&path) {
                Outcome::Same(_) => same.push(format!("{k}-{name}")),
                Outcome::Declined(_) => declined += 1,
            }
        }
    }
    for name in ["1-if-goto.nc", "1-local-variables.nc", "1-pitfall-goto-duplicate-n.nc"] {
        assert!(same.iter().any(|s| s == name), "{name} not segmented; segmented: {same:?}");
    }
    assert!(same.len() >= 60 && declined >= 20, "{} segmented, {declined} declined: {same:?}", same.len());
}

#[test]
fn what_needs_the_whole_program_declines() {
    let dir = scratch("declined");
    let cam = "G1 X1. Y2.\nG2 X3. Y1. R20.\nX1. Y1. R20.\n";
    let cases = [
        ("computed goto", format!("O1\nG0 X0.\n{cam}#1=10\nGOTO#1\nN10 {cam}M30\n")),
        ("m98", format!("O1\nG0 X0.\n{cam}#1=1\nM98 P2\n{cam}M30\nO2\nG0 X1.\nM99\n")),
        ("g65", format!("O1\nG0 X0.\n{cam}G65 P9010 A1.\n{cam}M30\n")),
        ("g10", format!("O1\nG0 X0.\n{cam}G10 L2 P1 X10.\n{cam}#1=1\nM30\n")),
        ("m99", format!("O1\nG0 X0.\n{cam}#1=1\n{cam}M99\n")),
        ("work offset", format!("O1\nG0 X0.\n{cam}#5221=1.\n{cam}M30\n")),
        ("two programs", format!("O1\nG0 X0.\n{cam}#1=1\nM30\nO2\n{cam}#1=1\nM30\n")),
        ("marker", format!("O1\nG0 X0.\n{cam}#1=1 (NCTRANS SEGMENT 0)\n{cam}M30\n")),
        ("marker after text", format!("O1\nG0 X0.\n{cam}#1=1 (中NCTRANS SEGMENT 0)\n{cam}M30\n")),
        // (`IF[..]THEN G2 …` is a Haas conditional block since issue 21, read and translated.)
        ("if-then two statements", format!("O1\nG0 X0.\n{cam}IF[#1EQ#0]THEN #2=1 GOTO7\nN7 {cam}M30\n")),
        ("r after a run's arc", format!("O1\nG0 X0.\nG2 X1. Y1. R20.\nIF[#1EQ#0]GOTO7\nN7 X2. R20.\n{cam}M30\n")),
        ("error", format!("O1\nG0 X0.\n{cam}#1=1\nG68 X0 Y0 R45.\n{cam}M30\n")),
    ];
    for (what, text) in cases {
        let path = dir.join("p.nc");
        std::fs::write(&path, &text).expect("write");
        let mut out = Vec::new();
        let r = segmented::to_sinumerik(&path, &opts(), LineEnding::Lf, &mut out, None);
        assert!(r.is_err(), "{what} segmented:\n{}", String::from_utf8_lossy(&out));
    }
}

fn cli(args: &[&str]) -> (Option<i32>, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_nctrans")).args(args).output().expect("runs");
    (out.status.code(), String::from_utf8_lossy(&out.stderr).to_string())
}

#[test]
fn cli_streams_macro_programs_segmented_and_falls_back_whole_on_what_it_declines() {
    let dir = scratch("cli");
    let mut r = Rng(3);
    let mut ns = Vec::new();
    let mut arc = false;
    let run = cam_run(&mut r, 200, "\n", &mut arc, &mut ns);
    let seg = format!("%\nO7\n#100=5\nG21 G90 G0 X0. Y0.\n{run}#101=#100*2\n{run}M30\n%\n");
    let declined = format!("%\nO7\n#100=5\nG21 G90 G0 X0. Y0.\n{run}#1=1\nGOTO#1\nN1 {run}M30\n%\n");
    for (name, text) in [("seg.nc", seg), ("whole.nc", declined)] {
        let input = dir.join(name);
        std::fs::write(&input, text).expect("write");
        let (a, b) = (dir.join(format!("{name}.stream.mpf")), dir.join(format!("{name}.whole.mpf")));
        let i = input.display().to_string();
        let (ca, ea) = cli(&["--to", "sinumerik", "--stream", &i, "-o", &a.display().to_string()]);
        let (cb, eb) = cli(&["--to", "sinumerik", &i, "-o", &b.display().to_string()]);
        assert_eq!(std::fs::read(&a).expect("stream out"), std::fs::read(&b).expect("whole out"), "{name}");
        assert_eq!(ca, cb, "{name}: {ea}\n{eb}");
        let last = |e: &str| e.lines().last().unwrap_or("").to_string();
        assert_eq!(last(&ea), last(&eb), "{name}");
        assert!(last(&ea).starts_with("equivalent"), "{name}: {ea}");
    }
}

#[test]
fn arc_modes_run_from_the_macro_part_into_runs_and_back() {
    let dir = scratch("arcs");
    let head = "%\nO5\n#101=2.\nG21 G17 G90\nG0 X0. Y0.\n";
    let cases = [
        // The arc mode of a loop body runs into the run after the loop.
        "#1=0\nWHILE[#1LT2]DO1\nG2 X1. Y1. R20.\n#1=#1+1\nEND1\nX2. Y2. R20.\nX3. Y1. R20.\n#1=1\n",
        // A macro block with G3 sets it; one with G1 clears it.
        "G3 X#101 Y1. R25.\nX1. Y2. R25.\nG1 X#101\nG2 X2. Y1. R20.\nY3. R20.\n",
        // Set in a run, across a macro statement and a jump target, into the next run.
        "G1 X1.\nG2 X2. Y2. R20.\n#102=#101+1\nIF[#102GT5.]GOTO7\nX1. Y1. R20.\nN7 G2 Y1. R20.\nX1. R20.\nG0 Z5.\n#103=1\n",
    ];
    for (k, body) in cases.iter().enumerate() {
        for eol in ["\n", "\r\n"] {
            let path = dir.join(format!("a{k}-{}.nc", eol.len()));
            std::fs::write(&path, format!("{head}{body}M30\n%\n").replace('\n', eol)).expect("write");
            let o = compare(&path);
            assert!(matches!(o, Outcome::Same(Verdict::Equivalent { .. })), "case {k}: {o:?}");
        }
    }
}

/// Runs whose translations pass the in-memory part of the spill (64 KiB) go through its
/// temporary file, with blocks the fast path declines (translated alone after the scan and
/// put in at their places) and arc modes running between the runs and the macro part.
#[test]
fn large_runs_through_the_spill_file() {
    let dir = scratch("spill");
    for (k, eol) in ["\n", "\r\n"].into_iter().enumerate() {
        let mut r = Rng(0x5B11_0002 + k as u64);
        let mut t = format!("%{eol}O2{k}00 (SPILL){eol}#100=1{eol}G21 G17 G90 G94{eol}G0 X0. Y0. Z5.{eol}");
        let (mut arc, mut ns) = (false, Vec::new());
        for j in 0..4 {
            t.push_str(&cam_run(&mut r, 1500, eol, &mut arc, &mut ns));
            t.push_str(&format!("#10{j}=#100+{j}{eol}G1 X#100 Y{j}.{eol}"));
            arc = false;
        }
        t.push_str(&format!("M30{eol}%{eol}"));
        assert!(t.len() > 100_000, "{}", t.len());
        let path = dir.join(format!("spill{k}.nc"));
        std::fs::write(&path, &t).expect("write");
        match compare(&path) {
            Outcome::Same(_) => {}
            Outcome::Declined(why) => panic!("spill{k} declined: {why}"),
        }
    }
}
