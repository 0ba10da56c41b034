//! A library macro is written for every possible caller, not for the calls one batch sees:
//! its defaults for arguments (`IF [#11 EQ #0] THEN #11=1.`) stay, and its verification runs
//! it with the arguments its callers pass and again with each of them vacant. Only
//! `--specialise-callers` (or `translate.specialise_callers` in nctrans.toml) writes it for
//! the calls seen.

use std::path::{Path, PathBuf};
use std::process::Command;

const MAIN: &str = "%\nO1000 (SLOT ROUGHING)\nG90 G0 X0 Y0 Z5.\nG65 P9100 H2. D5.\nG65 P9100 H3. D1.\nM30\n%\n";
const MACRO: &str = "%\nO9100 (STEP MACRO)\nIF [#11 EQ #0] THEN #11=1.\nIF [#7 EQ #0] GOTO 900\n\
G1 X#11 Y#7 F100.\nM99\nN900 #3000=1(D MISSING)\nM99\n%\n";

fn library(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("nctrans-macro-defaults-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("in")).expect("dir");
    std::fs::write(dir.join("in/O1000.nc"), MAIN).expect("write");
    std::fs::write(dir.join("in/O9100.nc"), MACRO).expect("write");
    dir
}

/// Runs a batch to Sinumerik in `dir`; returns the macro's output and its report summary.
fn batch(dir: &Path, extra: &[&str]) -> (String, String) {
    let mut args = vec!["--to", "sinumerik", "in", "-o", "out", "--report", "r.json"];
    args.extend(extra);
    let out = Command::new(env!("CARGO_BIN_EXE_nctrans")).args(&args).current_dir(dir).output().expect("run");
    let text = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    assert_eq!(out.status.code(), Some(0), "{text}");
    assert!(text.contains("every file verified"), "{text}");
    let spf = std::fs::read_to_string(dir.join("out/O_9100.spf")).expect("macro written");
    let report = std::fs::read_to_string(dir.join("r.json")).expect("report");
    let line = report.lines().find(|l| l.contains("\"path\": \"O9100.nc\"")).expect("macro's record").to_string();
    (spf, line)
}

#[test]
fn a_library_macro_keeps_its_defaults_and_is_verified_with_each_argument_vacant() {
    let dir = library("plain");
    let (spf, record) = batch(&dir, &[]);
    assert!(spf.contains("IF NOT ARG_H_SET\n  ARG_H=1 ARG_H_SET=1\nENDIF\n"), "{spf}");
    assert!(spf.contains("IF NOT ARG_D_SET GOTOF LBL_900\n"), "{spf}");
    // Two call sites, and each with H or D vacant: six runs.
    assert!(record.contains("equivalent (10 events in 6 runs)"), "{record}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn specialise_callers_writes_the_macro_for_the_calls_seen() {
    let dir = library("flag");
    let (spf, record) = batch(&dir, &["--specialise-callers"]);
    assert!(!spf.contains("ARG_H=1") && !spf.contains("IF 0"), "{spf}");
    assert!(record.contains("equivalent (4 events in 2 runs)"), "{record}");
    let _ = std::fs::remove_dir_all(&dir);
    // The same from the project configuration.
    let dir = library("config");
    std::fs::write(dir.join("nctrans.toml"), "[translate]\nspecialise_callers = true\n").expect("write");
    let (spf, _) = batch(&dir, &[]);
    assert!(!spf.contains("ARG_H=1") && !spf.contains("IF 0"), "{spf}");
    let _ = std::fs::remove_dir_all(&dir);
}
