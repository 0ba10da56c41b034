//! M30/M2 in a called program, both ways: FANUC ends the whole run there, Siemens returns to
//! the caller. Each translation is proven by the product's own verification, and a planted
//! wrong one (the end left as it was, or a bare return) is shown to be caught.

#[path = "support/proven.rs"]
mod proven;

use nctrans::check::Verdict;
use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::read::LineEnding;
use nctrans::span::SourceDb;
use nctrans::translate::to_fanuc::TranslateOptions;
use nctrans::translate::to_sinumerik::{verify::verify, Options, Translation};

/// A main program, a subprogram that calls another, and the inner one ending the run with
/// M02 when #1 is 1 (else it returns): the end must reach the main program, two calls up.
const FANUC: &str = "%\nO0001\nG0 G90 X0 Y0\n#1=1\nM98 P10\nG0 X50\nM30\n\
O0010\nG1 X10 F100\nM98 P20\nG1 X30\nM99\n\
O0020\nG1 Y10 F100\nIF [#1 EQ 1] GOTO 100\nG1 Y20\nM99\nN100 G1 Y5\nM02\n%\n";

fn to_sinumerik(src: &str) -> (SourceDb, nctrans::span::FileId, nctrans::ir::Unit, Translation) {
    let mut db = SourceDb::new();
    let loaded = nctrans::load(&mut db, "m.nc", src.as_bytes(), None);
    let parsed = nctrans::parse(&db, loaded.file, Dialect::Fanuc, &ParseOptions::for_dialect(Dialect::Fanuc));
    let tr = nctrans::translate::to_sinumerik::translate(&[&parsed.unit], &Options::default(), LineEnding::Lf);
    assert!(!tr.has_errors(), "{}", nctrans::diag::render(&db, &tr.diags));
    (db, loaded.file, parsed.unit, tr)
}

fn file_text<'a>(tr: &'a Translation, name: &str) -> &'a str {
    &tr.files.iter().find(|f| f.name == name).unwrap_or_else(|| panic!("no {name}")).text
}

#[test]
fn fanuc_end_in_a_nested_subprogram_ends_the_run_on_sinumerik() {
    let (db, file, unit, tr) = to_sinumerik(FANUC);
    let v = verify(&db, file, &unit, &tr, "");
    assert!(matches!(v.verdict, Verdict::Equivalent { .. }), "{:?}", v.verdict);
    let inner = file_text(&tr, "O_0020.SPF");
    assert!(inner.lines().any(|l| l.ends_with("=2 M2")), "{inner}");
    // With #1 = 0 the inner program returns, the flag stays clear and the run goes on.
    let (db0, file0, unit0, tr0) = to_sinumerik(&FANUC.replace("#1=1", "#1=0"));
    let v0 = verify(&db0, file0, &unit0, &tr0, "");
    assert!(matches!(v0.verdict, Verdict::Equivalent { .. }), "{:?}", v0.verdict);
}

#[test]
fn a_bare_return_or_a_siemens_m2_in_the_subprogram_is_caught() {
    let (db, file, unit, tr) = to_sinumerik(FANUC);
    let inner = file_text(&tr, "O_0020.SPF").to_string();
    let flag = inner.lines().find(|l| l.ends_with("=2 M2")).expect("the flag block").to_string();
    for planted in ["RET", "M2"] {
        let mut bad = tr.clone();
        let f = bad.files.iter_mut().find(|f| f.name == "O_0020.SPF").expect("inner");
        f.text = inner.replace(&flag, planted);
        let v = verify(&db, file, &unit, &bad, "");
        assert!(matches!(v.verdict, Verdict::Diverged { .. }), "{planted}: {:?}", v.verdict);
    }
}

const MAIN: &str = "G0 G90 X0 Y0\nSUBA\nG0 X50\nM30\n";
const SUB: &str = "PROC SUBA\nG1 X10 F100\nIF R1==0\nM30\nENDIF\nG1 X20\nM2\n";

#[test]
fn sinumerik_end_in_a_subprogram_returns_on_fanuc() {
    let mut db = SourceDb::new();
    let main = proven::parse(&mut db, "MAIN.MPF", MAIN, Dialect::Sinumerik);
    let sub = proven::parse(&mut db, "SUBA.SPF", SUB, Dialect::Sinumerik);
    let opts = TranslateOptions::default();
    let t = nctrans::translate::to_fanuc::to_fanuc(&main, &[&sub], &opts);
    assert!(t.ok(), "{}", nctrans::diag::render(&db, &t.diags));
    let (head, callee) = t.text.split_once("(SUBA)").expect("the subprogram");
    assert!(head.contains("M30") && !callee.contains("M30") && !callee.contains("M02"), "{}", t.text);
    let v = nctrans::translate::to_fanuc::verify(&mut db, &main, &[&sub], &t.clone().into(), "out.nc", proven::STEPS);
    assert!(v.equivalent, "{}\n{}\n{}", v.summary, v.rendered, t.text);
    // M30 left as M30 in the subprogram ends the FANUC run early: caught.
    let mut bad = t.clone();
    bad.text = format!("{head}(SUBA){}", callee.replacen("M99", "M30", 1));
    let v = nctrans::translate::to_fanuc::verify(&mut db, &main, &[&sub], &bad.into(), "bad.nc", proven::STEPS);
    assert!(!v.equivalent, "the planted M30 was not caught:\n{}", t.text);
}

#[test]
fn a_repeated_call_of_a_program_that_ends_the_run_is_refused() {
    let src = "%\nO0001\nG0 G90 X0 Y0\nM98 P10 L2\nM30\nO0010\nG1 X10 F100\nM30\n%\n";
    let mut db = SourceDb::new();
    let loaded = nctrans::load(&mut db, "m.nc", src.as_bytes(), None);
    let parsed = nctrans::parse(&db, loaded.file, Dialect::Fanuc, &ParseOptions::for_dialect(Dialect::Fanuc));
    let tr = nctrans::translate::to_sinumerik::translate(&[&parsed.unit], &Options::default(), LineEnding::Lf);
    assert!(tr.has_errors());
    assert!(tr.diags.iter().any(|d| d.code == "NC596"), "{}", nctrans::diag::render(&db, &tr.diags));
}

/// In a batch a program may be both called (by another file) and run on its own: each
/// file's proof runs it as a main program. Its `M30` must end that run as `M30` too, not
/// as the bare return a called program would make (`end RET` against `end M30`).
#[test]
fn a_called_program_that_ends_the_run_also_verifies_as_a_main_program_in_a_batch() {
    use std::process::Command;
    let dir = std::env::temp_dir().join(format!("nctrans-end-batch-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("in")).expect("scratch");
    std::fs::write(dir.join("in/O0010.nc"), "%\nO0010\nG0 G90 X0 Y0\nM98 P20\nG0 X50.\nM30\n%\n").unwrap();
    std::fs::write(dir.join("in/O0020.nc"), "%\nO0020\nG1 X10. Y5. F100.\nM30\n%\n").unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_nctrans"))
        .args(["--to", "sinumerik", "-o"])
        .arg(dir.join("out"))
        .arg(dir.join("in"))
        .output()
        .expect("batch");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stdout}\n{stderr}");
    assert!(stdout.contains("every file verified") && !stderr.contains("NC500"), "{stdout}\n{stderr}");
    let sub = std::fs::read_dir(dir.join("out"))
        .expect("out")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .find(|p| p.to_string_lossy().contains("0020"))
        .expect("the called program's output");
    let text = std::fs::read_to_string(&sub).unwrap();
    assert!(text.lines().any(|l| l.ends_with("=30 M30")), "{text}");
    let _ = std::fs::remove_dir_all(&dir);
}
