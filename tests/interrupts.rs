//! Interrupts (issue 21): Siemens `SETINT`/`ENABLE`/`DISABLE`/`CLRINT` and FANUC `M96`/`M97`
//! run where a test input (`--interrupt N@K`, `nctrans: interrupt`) switches the input, and
//! translate both ways where the profile says the machine has FANUC's custom macro interrupt.

use std::path::{Path, PathBuf};
use std::process::Command;

fn workdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("nctrans-interrupts-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

fn nctrans(dir: &Path, args: &[&str]) -> (String, String, bool) {
    let out = Command::new(env!("CARGO_BIN_EXE_nctrans")).current_dir(dir).args(args).output().expect("run nctrans");
    (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
        out.status.success(),
    )
}

const MAIN: &str = "G0 X0 Y0 Z10\nSETINT(1) PRIO=1 RETRACT\nG1 X10 F100\nG1 X20\nG1 X30\nM30\n";
const RETRACT: &str = "PROC RETRACT\nG0 Z50\nM17\n";
const PROFILE: &str = "[fanuc]\nmacro_interrupt = true\n";

fn siemens(dir: &Path, main: &str) {
    std::fs::write(dir.join("part.mpf"), main).expect("write main");
    std::fs::write(dir.join("RETRACT.SPF"), RETRACT).expect("write routine");
}

/// The lines of a text trace without the `@line` suffix.
fn moves(trace: &str) -> Vec<String> {
    trace.lines().map(|l| l.split("  @").next().unwrap_or("").trim().to_string()).collect()
}

#[test]
fn the_routine_runs_after_the_kth_motion_only_when_the_input_switches() {
    let dir = workdir("run");
    siemens(&dir, MAIN);
    let (out, err, ok) = nctrans(&dir, &["run", "part.mpf"]);
    assert!(ok, "{err}");
    assert!(!out.contains("Z=50"), "{out}");
    assert!(err.contains("NC566") && err.contains("never switches"), "{err}");
    let (out, err, ok) = nctrans(&dir, &["run", "part.mpf", "--interrupt", "1@2"]);
    assert!(ok, "{err}");
    let m = moves(&out);
    assert_eq!(m[1], "move linear X=10 Y=0 Z=10 f=100", "{out}");
    assert_eq!(m[2], "move rapid X=10 Y=0 Z=50 f=-", "{out}");
    assert_eq!(m[3], "move linear X=20 Y=0 Z=50 f=100", "{out}");
    assert!(!err.contains("NC566"), "{err}");
    // The header line does the same.
    siemens(&dir, &format!("; nctrans: interrupt 1@3\n{MAIN}"));
    let (out, _, _) = nctrans(&dir, &["run", "part.mpf"]);
    assert_eq!(moves(&out)[3], "move rapid X=20 Y=0 Z=50 f=-", "{out}");
}

#[test]
fn disable_stops_it_firing_and_enable_brings_it_back() {
    let dir = workdir("disable");
    let main = "G0 X0 Y0 Z10\nSETINT(1) PRIO=1 RETRACT\nDISABLE(1)\nG1 X10 F100\nENABLE(1)\nG1 X20\nM30\n";
    siemens(&dir, main);
    let (out, err, ok) = nctrans(&dir, &["run", "part.mpf", "--interrupt", "1@2"]);
    assert!(ok, "{err}");
    assert!(!out.contains("Z=50"), "{out}");
    assert!(err.contains("NC642") && err.contains("disabled"), "{err}");
    let (out, _, _) = nctrans(&dir, &["run", "part.mpf", "--interrupt", "1@3"]);
    assert!(out.contains("move rapid X=20 Y=0 Z=50"), "{out}");
    let cleared = "G0 X0 Y0 Z10\nSETINT(1) PRIO=1 RETRACT\nCLRINT(1)\nG1 X10 F100\nM30\n";
    siemens(&dir, cleared);
    let (out, err, _) = nctrans(&dir, &["run", "part.mpf", "--interrupt", "1@2"]);
    assert!(!out.contains("Z=50") && err.contains("no routine is assigned"), "{out}{err}");
}

#[test]
fn a_bad_interrupt_argument_is_a_clear_cli_error() {
    let dir = workdir("cli");
    siemens(&dir, MAIN);
    for bad in ["1", "9@2", "1@0", "1@x"] {
        let (_, err, ok) = nctrans(&dir, &["run", "part.mpf", "--interrupt", bad]);
        assert!(!ok && err.contains("--interrupt"), "{bad}: {err}");
    }
    siemens(&dir, &format!("; nctrans: interrupt 1@\n{MAIN}"));
    let (_, err, ok) = nctrans(&dir, &["run", "part.mpf"]);
    assert!(!ok && err.contains("bad `nctrans: interrupt` header"), "{err}");
}

#[test]
fn without_the_profile_flag_the_translation_is_refused_with_nc566() {
    let dir = workdir("refuse");
    siemens(&dir, MAIN);
    let (_, err, ok) = nctrans(&dir, &["--to", "fanuc", "part.mpf"]);
    assert!(!ok && err.contains("NC566") && err.contains("macro_interrupt"), "{err}");
}

#[test]
fn liftfast_and_a_second_input_are_refused() {
    let dir = workdir("liftfast");
    std::fs::write(dir.join("nctrans.toml"), PROFILE).expect("profile");
    siemens(&dir, &MAIN.replace("RETRACT\n", "RETRACT LIFTFAST\n"));
    let (_, err, ok) = nctrans(&dir, &["--to", "fanuc", "part.mpf"]);
    assert!(!ok && err.contains("NC639") && err.contains("LIFTFAST"), "{err}");
    let (_, err, ok) = nctrans(&dir, &["run", "part.mpf", "--interrupt", "1@2"]);
    assert!(!ok && err.contains("NC639"), "{err}");
    siemens(&dir, &MAIN.replace("SETINT(1)", "SETINT(2)"));
    let (_, err, ok) = nctrans(&dir, &["--to", "fanuc", "part.mpf"]);
    assert!(!ok && err.contains("NC640") && err.contains("one signal"), "{err}");
}

#[test]
fn siemens_to_fanuc_is_proven_with_the_interrupt_fired_and_wrong_ones_are_caught() {
    let dir = workdir("to-fanuc");
    std::fs::write(dir.join("nctrans.toml"), PROFILE).expect("profile");
    siemens(&dir, &format!("; nctrans: interrupt 1@2\n{MAIN}"));
    let (out, err, ok) = nctrans(&dir, &["--to", "fanuc", "part.mpf", "-o", "part.nc"]);
    assert!(ok, "{out}{err}");
    assert!(err.contains("equivalent (6 events)"), "{err}");
    let text = std::fs::read_to_string(dir.join("part.nc")).expect("output");
    assert!(text.contains("M96 P9000") && text.contains("O9000 (RETRACT)"), "{text}");
    // check applies the same switch to both programs.
    let (out, err, ok) = nctrans(&dir, &["check", "part.mpf", "part.nc", "--interrupt", "1@3"]);
    assert!(ok && out.contains("equivalent"), "{out}{err}");
    // Planted: the interrupt enabled one motion later fires at another point.
    let late = text.replacen("M96 P9000\n", "", 1).replacen("G01 X20.\n", "G01 X20.\nM96 P9000\n", 1);
    std::fs::write(dir.join("late.nc"), &late).expect("write");
    let (out, err, ok) = nctrans(&dir, &["check", "part.mpf", "late.nc"]);
    assert!(!ok && out.contains("diverge") || err.contains("diverge"), "{out}{err}");
    // Planted: the wrong routine.
    let wrong = text.replace("M96 P9000", "M96 P9001").replace("%\n", "") + "O9001\nG00 Z60.\nM99\n%\n";
    std::fs::write(dir.join("wrong.nc"), format!("%\n{wrong}")).expect("write");
    let (out, err, ok) = nctrans(&dir, &["check", "part.mpf", "wrong.nc"]);
    assert!(!ok && (out.contains("Z=60") || err.contains("Z=60")), "{out}{err}");
    // No switch: the verdict says what was not compared.
    siemens(&dir, MAIN);
    let (_, err, ok) = nctrans(&dir, &["--to", "fanuc", "part.mpf", "-o", "quiet.nc"]);
    assert!(ok && err.contains("1 interrupt routine not compared"), "{err}");
}

#[test]
fn fanuc_to_siemens_is_proven_with_the_interrupt_fired() {
    let dir = workdir("to-sinumerik");
    std::fs::write(dir.join("nctrans.toml"), PROFILE).expect("profile");
    let src = "O1000\n(nctrans: interrupt 1@2)\nG21\nG0 X0. Y0. Z10.\nM96 P9000\nG1 X10. F100.\nG1 X20.\nM97\n\
               G1 X30.\nM30\nO9000\nG21\nG0 Z50.\nM99\n";
    std::fs::write(dir.join("part.nc"), src).expect("write");
    let (out, err, ok) = nctrans(&dir, &["run", "part.nc", "--interrupt", "1@4"]);
    assert!(ok && !out.contains("Z=50") && err.contains("disabled"), "{out}{err}");
    let (_, err, ok) = nctrans(&dir, &["--to", "sinumerik", "part.nc", "-o", "out/"]);
    assert!(ok && err.contains("equivalent"), "{err}");
    let main = std::fs::read_to_string(dir.join("out/PART.MPF")).expect("main");
    assert!(main.contains("SETINT(1) PRIO=1 O_9000") && main.contains("DISABLE(1)"), "{main}");
    // Without the flag M96 is a machine-specific M code: nothing is read as an interrupt.
    std::fs::remove_file(dir.join("nctrans.toml")).expect("rm");
    let (out, err, _) = nctrans(&dir, &["run", "part.nc"]);
    assert!(!out.contains("Z=50") && err.contains("M96 is machine-specific"), "{out}{err}");
}

#[test]
fn reposa_in_a_routine_is_refused() {
    let dir = workdir("reposa");
    std::fs::write(dir.join("part.mpf"), MAIN).expect("write main");
    std::fs::write(dir.join("RETRACT.SPF"), "PROC RETRACT\nG0 Z50\nREPOSA\nM17\n").expect("write routine");
    let (_, err, ok) = nctrans(&dir, &["run", "part.mpf", "--interrupt", "1@2"]);
    assert!(!ok && err.contains("NC639") && err.contains("REPOS"), "{err}");
}
