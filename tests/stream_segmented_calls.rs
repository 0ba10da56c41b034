//! Segmented streaming of Sinumerik main programs that call subprograms found beside them
//! (`segmented::to_fanuc_with_subs`, and the command line's `--stream`): the output is the
//! whole translation's (main program with its CAM runs, then each subprogram), byte for byte,
//! and the streamed verification gives the whole path's verdict. Declined programs (a callee
//! not found, one with a MSG, a modal call, …) give the whole path's output on the command
//! line.

use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::ir::Unit;
use nctrans::span::SourceDb;
use nctrans::stream::segmented::fanuc as segmented;
use nctrans::stream::Fallback;
use nctrans::translate::{self, to_fanuc::TranslateOptions};
use std::path::{Path, PathBuf};

const MAX_STEPS: u64 = 2_000_000;

fn dir(name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/stream-segmented-calls").join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("dir");
    d
}

/// A deterministic run of `n` CAM blocks (some numbered).
fn cam(seed: &mut u64, n: usize) -> String {
    let mut s = String::new();
    for k in 0..n {
        let mut next = || {
            *seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((*seed >> 33) % 200_000) as f64 / 1000.0 - 100.0
        };
        let (x, y, z) = (next(), next(), next() / 10.0);
        if k % 7 == 3 {
            s.push_str(&format!("N{} ", 1000 + k * 10));
        }
        s.push_str(&format!("G1 X{x:.3} Y{y:.3} Z{z:.4}"));
        if k % 5 == 0 {
            s.push_str(&format!(" F{}", 500 + k % 400));
        }
        s.push('\n');
    }
    s
}

fn opts(path: &Path) -> TranslateOptions {
    TranslateOptions {
        main_name: path.file_stem().and_then(|s| s.to_str()).unwrap_or("MAIN").to_ascii_uppercase(),
        source_name: path.file_name().and_then(|s| s.to_str()).unwrap_or("").to_string(),
        ..TranslateOptions::default()
    }
}

/// The whole path's loading of the callees (`NAME.SPF` beside `main`, transitively) into
/// `db` (file ids from 1 up).
fn load_subs(db: &mut SourceDb, main: &Path, unit: &Unit) -> Option<Vec<Unit>> {
    let popts = ParseOptions::for_dialect(Dialect::Sinumerik);
    let (mut todo, mut seen, mut subs) = (nctrans::ir::visit::called_names(unit), Vec::<String>::new(), Vec::new());
    while let Some(c) = todo.pop() {
        if seen.contains(&c) {
            continue;
        }
        seen.push(c.clone());
        let path = main.with_file_name(format!("{c}.SPF"));
        let bytes = std::fs::read(&path).ok()?;
        let l = nctrans::load(db, &path.display().to_string(), &bytes, None);
        let p = nctrans::parse(db, l.file, Dialect::Sinumerik, &popts);
        if !p.diags.is_empty() {
            return None;
        }
        todo.extend(nctrans::ir::visit::called_names(&p.unit));
        subs.push(p.unit);
    }
    Some(subs)
}

/// Writes the main program and its subprograms into a fresh folder; the main's path.
fn files(name: &str, main: &str, subs: &[(&str, &str)]) -> PathBuf {
    let d = dir(name);
    for (n, text) in subs {
        std::fs::write(d.join(format!("{n}.SPF")), text).expect("write");
    }
    let p = d.join("MAIN.MPF");
    std::fs::write(&p, main).expect("write");
    p
}

/// Whole translation and verdict of `path` (as `cli::translate` does it).
fn whole(path: &Path) -> (String, bool, String) {
    let mut db = SourceDb::new();
    let bytes = std::fs::read(path).expect("read");
    let loaded = nctrans::load(&mut db, &path.display().to_string(), &bytes, None);
    let parsed = nctrans::parse(&db, loaded.file, Dialect::Sinumerik, &ParseOptions::for_dialect(Dialect::Sinumerik));
    let subs = load_subs(&mut db, path, &parsed.unit).expect("subs");
    let refs: Vec<&Unit> = subs.iter().collect();
    let t = translate::to_fanuc::to_fanuc(&parsed.unit, &refs, &opts(path));
    assert!(t.ok(), "{:?}", t.diags);
    let v = translate::to_fanuc::verify(&mut db, &parsed.unit, &refs, &t.clone().into(), "whole.nc", MAX_STEPS);
    (t.text, v.equivalent, v.summary)
}

/// Segmented translation (with the callees loaded as the whole path loads them), written
/// beside the input, and its streamed verdict; `break_at`: text replaced in the output
/// before verifying.
fn streamed(path: &Path, break_at: Option<(&str, &str)>) -> Result<(String, bool, String), Fallback> {
    let mut out = Vec::new();
    let mut load = |u: &Unit| {
        let mut db = SourceDb::new();
        db.add(path.display().to_string(), String::new());
        load_subs(&mut db, path, u).ok_or(Fallback::Diagnostics)
    };
    let (d, notes) = segmented::to_fanuc_with_subs(path, &opts(path), &mut load, &mut out, None)?;
    assert!(notes.is_empty(), "{notes:?}");
    let mut text = String::from_utf8(out).expect("utf8");
    let written = text.clone();
    if let Some((from, to)) = break_at {
        assert!(text.contains(from), "{from}");
        text = text.replacen(from, to, 1);
    }
    let o = path.with_extension("seg.nc");
    std::fs::write(&o, &text).expect("write");
    let v = nctrans::stream::verify::verify(d.index, &o, MAX_STEPS, d.inputs, None);
    Ok((written, v.equivalent, v.summary))
}

/// The command line on `path`, whole then `--stream`: same output, stderr, exit code.
fn cli_same(path: &Path) -> String {
    cli_same_with(path, &[])
}

/// [`cli_same`] with more arguments.
fn cli_same_with(path: &Path, args: &[&str]) -> String {
    let out = path.with_extension("cli.nc");
    let run = |stream: bool| {
        let _ = std::fs::remove_file(&out);
        let mut c = std::process::Command::new(env!("CARGO_BIN_EXE_nctrans"));
        c.args(["--to", "fanuc", "--max-steps", "2000000"]).args(args).arg(path).arg("-o").arg(&out);
        if stream {
            c.arg("--stream");
        }
        let r = c.output().expect("run nctrans");
        (std::fs::read(&out).unwrap_or_default(), String::from_utf8_lossy(&r.stderr).to_string(), r.status.code())
    };
    let (w, s) = (run(false), run(true));
    assert!(w.0 == s.0, "{}: outputs differ", path.display());
    assert_eq!(w.1, s.1, "{}", path.display());
    assert_eq!(w.2, s.2, "{}", path.display());
    s.1
}

/// A test folder: its name, the main program's calls, the subprograms (name, text).
type Set<'a> = (&'a str, Vec<&'a str>, Vec<(&'a str, &'a str)>);

const L100: &str = "PROC L100\nR3=R1*2\nG0 Z=R3\nM17\n";
const POCKET: &str =
    "PROC POCKET(REAL DEPTH, REAL SAFE)\nDEF INT CNT\nCNT=0\nWHILE CNT<2\nG1 Z=-DEPTH F200\nG0 Z=SAFE\nCNT=CNT+1\nENDWHILE\nTOOLCHG\nRET\n";
const TOOLCHG: &str = "PROC TOOLCHG\nG0 Z100\nR2=R2+1\nM17\n";

fn main_with_calls(seed: u64, calls: &[&str]) -> String {
    let mut s = seed;
    let mut text = String::from("; MAIN WITH CALLS\nR1=5 R2=0\nG71 G17 G90 G94\nG0 X0 Y0 Z=R1\n");
    for c in calls {
        text.push_str(&cam(&mut s, 150));
        text.push_str(c);
        text.push('\n');
    }
    text.push_str(&cam(&mut s, 100));
    text.push_str("IF R2<>3 GOTOF N99\nG0 Z=R1+R3\nN99 M30\n");
    text
}

#[test]
fn calls_of_subprograms_stream_as_the_whole_translation() {
    let sets: Vec<Set> = vec![
        ("one-l", vec!["L100"], vec![("L100", L100)]),
        (
            "named-params",
            vec!["POCKET(3.5, R1)", "L100"],
            vec![("L100", L100), ("POCKET", POCKET), ("TOOLCHG", TOOLCHG)],
        ),
        (
            "three",
            vec!["TOOLCHG", "L100", "POCKET(1, 2)", "TOOLCHG"],
            vec![("L100", L100), ("POCKET", POCKET), ("TOOLCHG", TOOLCHG)],
        ),
        // A callee reading an R parameter never set: the warning shows its line, as whole.
        ("unset", vec!["USERSUB", "L100"], vec![("USERSUB", "PROC USERSUB\nG0 Z=R7+10\nM17\n"), ("L100", L100)]),
    ];
    for (k, (name, calls, subs)) in sets.into_iter().enumerate() {
        let path = files(name, &main_with_calls(k as u64 + 7, &calls), &subs);
        let (wt, weq, wsum) = whole(&path);
        let (st, seq, ssum) = streamed(&path, None).unwrap_or_else(|e| panic!("{name} declined: {e:?}"));
        assert!(wt == st, "{name}: texts differ");
        assert!(wt.contains("O9000"), "{name}: no subprogram in the output");
        assert_eq!(weq, seq, "{name}: {wsum} / {ssum}");
        assert!(seq, "{name}: {ssum}");
        let stderr = cli_same(&path);
        assert!(stderr.contains("equivalent"), "{stderr}");
        // Program numbers from `--program-map` (and the rest numbered around them).
        let mapped = cli_same_with(&path, &["--program-map", "L100=9000", "--program-map", "TOOLCHG=8123"]);
        assert!(mapped.contains("equivalent"), "{mapped}");
        if name == "unset" {
            assert!(stderr.contains("USERSUB.SPF:2:") && stderr.contains("NC404"), "{stderr}");
        }
    }
}

/// The streamed verification runs the subprograms of the output file: a broken one fails.
#[test]
fn a_broken_subprogram_in_the_output_fails_the_streamed_verification() {
    let path = files("broken", &main_with_calls(3, &["TOOLCHG"]), &[("TOOLCHG", TOOLCHG)]);
    let (_, ok, sum) = streamed(&path, None).expect("streamed");
    assert!(ok, "{sum}");
    let (_, ok, sum) = streamed(&path, Some(("G00 Z100.", "G00 Z101."))).expect("streamed");
    assert!(!ok && sum.contains("diverged"), "{sum}");
}

#[test]
fn declines_calls_it_does_not_take() {
    let sets: Vec<Set> = vec![
        // A callee not beside the program.
        ("missing", vec!["L100", "NOWHERE"], vec![("L100", L100)]),
        // A MSG in a callee (the whole path's verifier drops it, the streamed one would not).
        ("msg", vec!["MSGSUB"], vec![("MSGSUB", "PROC MSGSUB\nMSG(\"HI\")\nG0 Z50\nM17\n")]),
        // A modal call.
        ("mcall", vec!["MCALL L100", "MCALL"], vec![("L100", L100)]),
        // A callee calling modally.
        ("mcall-sub", vec!["MSUB"], vec![("MSUB", "PROC MSUB\nMCALL L100\nG1 X1\nMCALL\nM17\n"), ("L100", L100)]),
        // A callee without PROC (the whole path's verifier does not find it by name).
        ("no-proc", vec!["NOPROC"], vec![("NOPROC", "G0 Z60\nM17\n")]),
    ];
    for (k, (name, calls, subs)) in sets.into_iter().enumerate() {
        let path = files(name, &main_with_calls(k as u64 + 20, &calls), &subs);
        if name != "no-proc" {
            assert!(streamed(&path, None).is_err(), "{name} was streamed");
        }
        cli_same(&path);
    }
}

/// The command line takes the segmented route for a large main program calling two
/// subprograms (no "read whole" note) and writes what the library writes. Minutes in a debug
/// build: `cargo test --release --test stream_segmented_calls -- --ignored`.
#[test]
#[ignore]
fn cli_streams_a_large_program_with_calls() {
    let mut seed = 11;
    let mut text = String::from("R1=5 R2=0\nG71 G90\n");
    while text.len() < 4_300_000 {
        text.push_str(&cam(&mut seed, 1000));
    }
    text.push_str("L100\n");
    while text.len() < 8_600_000 {
        text.push_str(&cam(&mut seed, 1000));
    }
    text.push_str("POCKET(2, R1)\nM30\n");
    let path = files("large", &text, &[("L100", L100), ("POCKET", POCKET), ("TOOLCHG", TOOLCHG)]);
    let out = path.with_extension("nc");
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_nctrans"))
        .args(["--to", "fanuc"])
        .arg(&path)
        .arg("-o")
        .arg(&out)
        .output()
        .expect("run nctrans");
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{stderr}");
    assert!(!stderr.contains("read whole") && stderr.contains("equivalent"), "{stderr}");
    let (lib, ok, sum) = streamed(&path, None).unwrap_or_else(|e| panic!("declined: {e:?}"));
    assert!(ok, "{sum}");
    assert!(std::fs::read(&out).expect("output") == lib.as_bytes());
}
