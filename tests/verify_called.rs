//! A macro written for every possible caller is proven so on every path (issue 17 item 9):
//! `nctrans --to sinumerik`, whole or streamed, runs each macro called by G65/G66 alone with
//! its callers' arguments and again with each of them vacant (`verify_called`, the rule the
//! batch uses), so a wrong default or a missing alarm for a vacant argument is caught even
//! when every call seen gives every argument.

use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::ir::Unit;
use nctrans::read::LineEnding;
use nctrans::span::SourceDb;
use nctrans::translate::called::{called_runs, combine, Combined, RunSettings};
use nctrans::translate::to_sinumerik::{Options, OutFile, Translation};
use std::path::PathBuf;
use std::process::Command;

fn corpus_file() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("corpus/in/fanuc/macro-defaults-all-given.nc")
}

/// The macro's default for H, planted wrong: only a run with H vacant sees it.
fn tamper(files: &mut [OutFile]) {
    let f = files.iter_mut().find(|f| f.name == "O_9100.SPF").expect("the macro's file");
    assert!(f.text.contains("ARG_H=1 ARG_H_SET=1"), "{}", f.text);
    f.text = f.text.replace("ARG_H=1 ARG_H_SET=1", "ARG_H=2 ARG_H_SET=1");
}

fn verdict(db: &SourceDb, units: &[&Unit], tr: &Translation) -> Combined {
    let profiles = nctrans::translate::to_sinumerik::verify::Profiles::default();
    let settings = RunSettings { out_dir: "", max_steps: 100_000, profiles: &profiles, set: &[] };
    combine(called_runs(db, units, tr, &settings, true))
}

#[test]
fn a_wrong_default_is_caught_in_the_whole_translation() {
    let bytes = std::fs::read(corpus_file()).expect("corpus file");
    let mut db = SourceDb::new();
    let loaded = nctrans::load(&mut db, "m.nc", &bytes, None);
    let parsed = nctrans::parse(&db, loaded.file, Dialect::Fanuc, &ParseOptions::for_dialect(Dialect::Fanuc));
    let tr = nctrans::translate::to_sinumerik::translate(&[&parsed.unit], &Options::default(), LineEnding::Lf);
    assert!(!tr.has_errors());
    match verdict(&db, &[&parsed.unit], &tr) {
        // Two call sites, then H, D, K vacant in turn for each.
        Combined::Equivalent { runs, .. } => assert_eq!(runs, 8),
        Combined::Not(label, r) => panic!("{label}: {:?}\n{}", r.verdict, r.diff),
    }
    let mut bad = tr.clone();
    tamper(&mut bad.files);
    // The main program's run alone does not see it: every call gives H.
    let main = nctrans::translate::to_sinumerik::verify::verify(&db, loaded.file, &parsed.unit, &bad, "");
    assert!(matches!(main.verdict, nctrans::check::Verdict::Equivalent { .. }), "{:?}", main.verdict);
    match verdict(&db, &[&parsed.unit], &bad) {
        Combined::Not(label, r) => {
            assert!(matches!(r.verdict, nctrans::check::Verdict::Diverged { .. }), "{:?}", r.verdict);
            assert!(label.contains("O_9100 alone") && label.contains("#11 vacant"), "{label}");
        }
        Combined::Equivalent { .. } => panic!("the wrong default was not caught"),
    }
}

#[test]
fn a_wrong_default_is_caught_in_the_streamed_translation() {
    use nctrans::stream::to_sinumerik::segmented::to_sinumerik_with_subs;
    let path = corpus_file();
    let mut skeleton: Vec<Unit> = Vec::new();
    let mut load = |u: &Unit| {
        skeleton.push(u.clone());
        Ok(Vec::new())
    };
    let mut out: Vec<u8> = Vec::new();
    let (done, mut subs) =
        match to_sinumerik_with_subs(&path, &Options::default(), LineEnding::Lf, &mut load, &mut out, None) {
            Ok(r) => r,
            Err(_) => panic!("the file streams"),
        };
    let mut db = SourceDb::new();
    db.add(path.display().to_string(), String::new());
    let units: Vec<&Unit> = skeleton.iter().collect();
    let tr = |files: &[OutFile]| Translation {
        files: files.to_vec(),
        symbols: nctrans::translate::Symbols::Sinumerik(done.symbols.clone()),
        diags: Vec::new(),
        unsupported: 0,
    };
    assert!(matches!(verdict(&db, &units, &tr(&subs)), Combined::Equivalent { runs: 8, .. }));
    tamper(&mut subs);
    assert!(matches!(verdict(&db, &units, &tr(&subs)), Combined::Not(..)), "the wrong default was not caught");
}

fn nctrans(args: &[&str], dir: &std::path::Path) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_nctrans")).args(args).current_dir(dir).output().expect("run");
    (out.status.success(), String::from_utf8_lossy(&out.stdout).into(), String::from_utf8_lossy(&out.stderr).into())
}

#[test]
fn the_verdict_counts_the_runs_whole_and_streamed() {
    let dir = std::env::temp_dir().join(format!("nctrans-verify-called-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("dir");
    std::fs::copy(corpus_file(), dir.join("pocket.nc")).expect("copy");
    for stream in [false, true] {
        let mut args = vec!["--to", "sinumerik", "pocket.nc", "-o", "out/"];
        if stream {
            args.push("--stream");
        }
        let (ok, _, err) = nctrans(&args, &dir);
        assert!(ok, "{err}");
        // The main program, then the macro alone: two call sites, each with H, D, K vacant.
        assert!(err.contains("equivalent (34 events in 9 runs)"), "stream {stream}: {err}");
        let spf = std::fs::read_to_string(dir.join("out/O_9100.SPF")).expect("macro written");
        assert!(spf.contains("IF NOT ARG_H_SET\n  ARG_H=1 ARG_H_SET=1\nENDIF\n"), "{spf}");
        assert!(!spf.contains("IF 0"), "{spf}");
        let _ = std::fs::remove_dir_all(dir.join("out"));
    }
    // Specialised: the defaults are decided for the calls seen, and no vacant run is made.
    let (ok, out, err) = nctrans(&["--to", "sinumerik", "--specialise-callers", "pocket.nc"], &dir);
    assert!(ok, "{err}");
    assert!(out.contains("IF 0\n  ARG_H=1\nENDIF\n"), "{out}");
    assert!(err.contains("equivalent (16 events in 3 runs)"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}
