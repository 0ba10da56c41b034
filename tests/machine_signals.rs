//! Machine signals (docs/semantics.md, Machine signals): Siemens PLC data and NCK inputs
//! (`$A_DBB[n]`, `$A_IN[n]` …) and FANUC interface signals (`#1000..#1015`, `#1032`,
//! `#1100..#1115`, `#1132`). A run reads them from its inputs or refuses naming the input to
//! give (NC578); translation both ways goes through the set-up's wiring (`[signals]`),
//! proven; a planted wrong variable is caught by `check`; no wiring, a write, or a value the
//! other side cannot carry is refused by name.

use std::path::{Path, PathBuf};
use std::process::Command;

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("nctrans-signals-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn nctrans(cwd: &Path, args: &[&str]) -> (bool, String) {
    let o = Command::new(env!("CARGO_BIN_EXE_nctrans")).current_dir(cwd).args(args).output().unwrap();
    (o.status.success(), format!("{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr)))
}

const WIRING: &str = "[signals]\n\"$A_DBB[17]\" = \"#1001\"\n\"$A_DBB[18]\" = \"#1002\"\n\"$A_IN[1]\" = \"#1000\"\n";

/// A chuck check as grinding libraries write it: clamped and not released, else stop.
const CHUCK: &str = "\
; nctrans: set $A_DBB[17]=1 $A_DBB[18]=0 $A_IN[1]=1
G17 G90 G71
WHILE $A_IN[1]==0
G4 F1
ENDWHILE
IF ($A_DBB[17]==1) AND ($A_DBB[18]==0) GOTOF CLAMPED
MSG(\"CHUCK NOT CLAMPED\")
M0
CLAMPED:
S1800 M3
G0 X10 Y0 Z2
G1 Z-1 F150
X40
G0 Z20 M5
M30
";

#[test]
fn a_run_reads_a_signal_it_is_given_and_refuses_one_it_is_not() {
    let d = dir("run");
    let body: String = CHUCK.lines().skip(1).map(|l| format!("{l}\n")).collect();
    std::fs::write(d.join("chuck.mpf"), &body).unwrap();
    let (ok, out) = nctrans(&d, &["run", "chuck.mpf"]);
    assert!(!ok && out.contains("NC578") && out.contains("$A_IN[1]") && out.contains("--set '$A_IN[1]=…'"), "{out}");
    let (ok, out) = nctrans(&d, &["run", "chuck.mpf", "--set", "$A_IN[1]=1", "--set", "$A_DBB[17]=0"]);
    assert!(!ok && out.contains("NC578") && out.contains("$A_DBB[18]"), "{out}");
    let sets = ["--set", "$A_IN[1]=1", "--set", "$A_DBB[17]=0", "--set", "$A_DBB[18]=0"];
    let (ok, out) = nctrans(&d, &[&["run", "chuck.mpf"][..], &sets].concat());
    assert!(ok && out.contains("stop \"CHUCK NOT CLAMPED\""), "{out}");
    let (ok, out) = nctrans(&d, &["run", "chuck.mpf", "--set", "$A_DBB[17]=256"]);
    assert!(!ok && out.contains("NC597") && out.contains("0..255"), "{out}");
    // FANUC: the bits and the 16 at once agree.
    std::fs::write(
        d.join("ui.nc"),
        "%\nO1000\nIF [#1002 EQ 1] GOTO 10\n#3000=1(UI2 OFF)\nN10 #100=#1032\nG0 X#100\nM30\n%\n",
    )
    .unwrap();
    let (ok, out) = nctrans(&d, &["run", "ui.nc", "--set", "#1032=4"]);
    assert!(ok && out.contains("X=4"), "{out}");
    let (ok, out) = nctrans(&d, &["run", "ui.nc", "--set", "#1002=1"]);
    assert!(!ok && out.contains("NC578") && out.contains("#1032"), "{out}");
    let (ok, out) = nctrans(&d, &["run", "ui.nc", "--set", "#1002=2"]);
    assert!(!ok && out.contains("NC597"), "{out}");
}

#[test]
fn writes_are_read_only_or_not_compared() {
    let d = dir("writes");
    std::fs::write(d.join("w.nc"), "%\nO1000\n#1103=1\nG0 X#1103\nM30\n%\n").unwrap();
    let (ok, out) = nctrans(&d, &["run", "w.nc"]);
    assert!(ok && out.contains("NC579") && out.contains("X=1"), "{out}");
    let (ok, out) = nctrans(&d, &["check", "w.nc", "w.nc"]);
    assert!(ok && out.contains("1 signal write not compared"), "{out}");
    std::fs::write(d.join("r.nc"), "%\nO1000\n#1003=1\nM30\n%\n").unwrap();
    let (ok, out) = nctrans(&d, &["run", "r.nc"]);
    assert!(!ok && out.contains("read-only"), "{out}");
    // Translation refuses a write in both directions, wired or not.
    std::fs::write(d.join("nctrans.toml"), "[signals]\n\"$A_OUT[3]\" = \"#1103\"\n").unwrap();
    let (ok, out) = nctrans(&d, &["--to", "sinumerik", "w.nc", "-o", "w.mpf"]);
    assert!(!ok && out.contains("NC579"), "{out}");
    std::fs::write(d.join("w.mpf"), "$A_OUT[3]=1\nM30\n").unwrap();
    let (ok, out) = nctrans(&d, &["--to", "fanuc", "w.mpf", "-o", "w2.nc"]);
    assert!(!ok && out.contains("NC579") && out.contains("$A_OUT[3]"), "{out}");
}

#[test]
fn the_chuck_check_translates_both_ways_and_a_wrong_variable_is_caught() {
    let d = dir("both");
    std::fs::write(d.join("nctrans.toml"), WIRING).unwrap();
    std::fs::write(d.join("chuck.mpf"), CHUCK).unwrap();
    let (ok, out) = nctrans(&d, &["--to", "fanuc", "chuck.mpf", "-o", "chuck.nc"]);
    assert!(ok && out.contains("equivalent"), "{out}");
    let nc = std::fs::read_to_string(d.join("chuck.nc")).unwrap();
    for want in ["(nctrans: set #1001=1 #1002=0 #1000=1)", "WHILE [#1000 EQ 0.] DO1", "#1001 NE 1.", "#1002 EQ 0."] {
        assert!(nc.contains(want), "missing {want}:\n{nc}");
    }
    let (ok, out) = nctrans(&d, &["check", "chuck.mpf", "chuck.nc"]);
    assert!(ok && out.contains("equivalent"), "{out}");
    // Planted: the clamp read from the released switch's variable.
    let bad = nc.replace("#1001 NE 1.", "#1002 NE 1.");
    std::fs::write(d.join("bad.nc"), &bad).unwrap();
    let (ok, out) = nctrans(&d, &["check", "chuck.mpf", "bad.nc"]);
    assert!(!ok && out.contains("diverge"), "{out}");
    // Planted: a variable no input gives is refused, not read as 0.
    std::fs::write(d.join("bad2.nc"), nc.replace("#1001 NE 1.", "#1005 NE 1.")).unwrap();
    let (ok, out) = nctrans(&d, &["check", "chuck.mpf", "bad2.nc"]);
    assert!(!ok && out.contains("NC578") && out.contains("#1005"), "{out}");
    // `--set` in either dialect's names reaches both sides through the wiring.
    for set in ["$A_DBB[17]=0", "#1001=0"] {
        let (ok, out) = nctrans(&d, &["check", "chuck.mpf", "chuck.nc", "--set", set]);
        assert!(ok && out.contains("equivalent (8 trace events agree)"), "{set}: {out}");
    }
    // And back: the FANUC program to Siemens, the signals the wiring names.
    let (ok, out) = nctrans(&d, &["--to", "sinumerik", "chuck.nc", "-o", "back.mpf"]);
    assert!(ok && out.contains("equivalent"), "{out}");
    let back = std::fs::read_to_string(d.join("back.mpf")).unwrap();
    for want in ["; nctrans: set $A_DBB[17]=1 $A_DBB[18]=0 $A_IN[1]=1", "WHILE $A_IN[1]==0", "$A_DBB[17]<>1"] {
        assert!(back.contains(want), "missing {want}:\n{back}");
    }
}

#[test]
fn without_a_wiring_the_refusal_names_the_key() {
    let d = dir("none");
    std::fs::write(d.join("a.mpf"), "IF $A_DBB[2]==1 GOTOF SKIP\nG0 X1\nSKIP:\nM30\n").unwrap();
    let (ok, out) = nctrans(&d, &["--to", "fanuc", "a.mpf", "-o", "a.nc"]);
    assert!(!ok && out.contains("NC342") && out.contains("[signals] \"$A_DBB[2]\" = \"#1000\""), "{out}");
    std::fs::write(d.join("b.nc"), "%\nO1000\nIF [#1004 EQ 1] GOTO 10\nG0 X1.\nN10 M30\n%\n").unwrap();
    let (ok, out) = nctrans(&d, &["--to", "sinumerik", "b.nc", "-o", "b.mpf"]);
    assert!(!ok && out.contains("NC365") && out.contains("[signals]") && out.contains("\"#1004\""), "{out}");
    // Inside a synchronized action: refused as before, wiring or not.
    std::fs::write(d.join("nctrans.toml"), "[signals]\n\"$A_DBB[2]\" = \"#1002\"\n").unwrap();
    std::fs::write(d.join("s.mpf"), "WHEN $A_DBB[2]==1 DO DELDTG(X)\nG1 X10 F100\nM30\n").unwrap();
    let (ok, out) = nctrans(&d, &["--to", "fanuc", "s.mpf", "-o", "s.nc"]);
    assert!(!ok && out.contains("NC631"), "{out}");
}

#[test]
fn a_value_the_other_side_cannot_carry_is_refused() {
    let d = dir("range");
    std::fs::write(d.join("nctrans.toml"), "[signals]\n\"$A_DBB[0]\" = \"#1000\"\n").unwrap();
    // A byte copied on a bit: only its comparisons with 0 or 1 carry over.
    std::fs::write(d.join("c.mpf"), "; nctrans: set $A_DBB[0]=1\nR1=$A_DBB[0]\nM30\n").unwrap();
    let (ok, out) = nctrans(&d, &["--to", "fanuc", "c.mpf", "-o", "c.nc"]);
    assert!(!ok && out.contains("NC597") && out.contains("$A_DBB[0]") && out.contains("0 or 1"), "{out}");
    // A signed word on the 16 unsigned inputs.
    std::fs::write(d.join("nctrans.toml"), "[signals]\n\"$A_DBW[4]\" = \"#1032\"\n").unwrap();
    std::fs::write(d.join("w.mpf"), "; nctrans: set $A_DBW[4]=3\nIF $A_DBW[4]>2 GOTOF SKIP\nG0 X1\nSKIP:\nM30\n")
        .unwrap();
    let (ok, out) = nctrans(&d, &["--to", "fanuc", "w.mpf", "-o", "w.nc"]);
    assert!(!ok && out.contains("NC597") && out.contains("$A_DBW[4]"), "{out}");
    // A wiring the values rule out is refused when nctrans.toml is read.
    std::fs::write(d.join("nctrans.toml"), "[signals]\n\"$A_DBR[8]\" = \"#1001\"\n").unwrap();
    let (ok, out) = nctrans(&d, &["--to", "fanuc", "c.mpf", "-o", "c.nc"]);
    assert!(!ok && out.contains("$A_DBR[8]") && out.contains("whole numbers"), "{out}");
    std::fs::write(d.join("nctrans.toml"), "[signals]\n\"$A_IN[1]\" = \"#1101\"\n").unwrap();
    let (ok, out) = nctrans(&d, &["--to", "fanuc", "c.mpf", "-o", "c.nc"]);
    assert!(!ok && out.contains("interface input"), "{out}");
    // Two entries over the same bits: the word and one of its bits.
    let both = "[signals]\n\"$A_DBB[0]\" = \"#1032\"\n\"$A_IN[1]\" = \"#1000\"\n";
    std::fs::write(d.join("nctrans.toml"), both).unwrap();
    let (ok, out) = nctrans(&d, &["--to", "fanuc", "c.mpf", "-o", "c.nc"]);
    assert!(!ok && out.contains("16 bits"), "{out}");
}

#[test]
fn a_batch_translates_with_the_wiring_and_its_map_keeps_it() {
    let d = dir("batch");
    std::fs::create_dir_all(d.join("lib")).unwrap();
    std::fs::write(d.join("lib/chuck.mpf"), CHUCK).unwrap();
    std::fs::write(d.join("nctrans.toml"), WIRING).unwrap();
    let (ok, out) = nctrans(&d, &["--to", "fanuc", "-o", "out", "lib"]);
    assert!(ok && out.contains("every file verified"), "{out}");
    let map = std::fs::read_to_string(d.join("out/nctrans-map.toml")).unwrap();
    assert!(map.contains("[signals]\n\"$A_DBB[17]\" = \"#1001\""), "{map}");
    let first = std::fs::read_to_string(d.join("out/chuck.nc")).unwrap();
    // A rerun with the map alone (no nctrans.toml) reads the same signals.
    std::fs::remove_file(d.join("nctrans.toml")).unwrap();
    let (ok, out) = nctrans(&d, &["--to", "fanuc", "-o", "out", "lib", "--force"]);
    assert!(ok && out.contains("every file verified"), "{out}");
    assert_eq!(std::fs::read_to_string(d.join("out/chuck.nc")).unwrap(), first);
}

#[test]
fn a_haas_target_and_the_32_outputs_at_once_are_refused() {
    let d = dir("haas");
    std::fs::write(d.join("nctrans.toml"), format!("[fanuc]\nseries = \"haas\"\n{WIRING}")).unwrap();
    std::fs::write(d.join("chuck.mpf"), CHUCK).unwrap();
    let (ok, out) = nctrans(&d, &["--to", "fanuc", "chuck.mpf", "-o", "chuck.nc"]);
    assert!(!ok && out.contains("NC597") && out.contains("on a Haas control"), "{out}");
    // Which outputs #1133 covers is in no source read here: unmodelled, as before.
    let d = dir("w1133");
    std::fs::write(d.join("w.nc"), "%\nO1000\n#1133=5\nM30\n%\n").unwrap();
    let (ok, out) = nctrans(&d, &["run", "w.nc"]);
    assert!(!ok && out.contains("NC400") && out.contains("#1133"), "{out}");
}
