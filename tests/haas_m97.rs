//! Haas `M97 Pn Lm` local subprograms translated to Sinumerik program-section repetition
//! (`REPEAT <start> <end> P=m` in a trampoline after the sections): a machinist-style program
//! translates and checks equivalent with the Haas NGC profile, a planted wrong count or wrong
//! section is caught by `nctrans check`, and every form the translation cannot make exact is
//! refused with its own code.

#[path = "support/cli_run.rs"]
mod cli_run;

use cli_run::{nctrans, workdir};
use std::path::Path;

const PROFILE: &str = "[fanuc]\nseries = \"haas-ngc\"\n";

/// A shop program: a pocket pass run twice by M97 P100 L2, a counted pattern by `L#5`, a
/// skippable call, local subprograms after M30 (one with a WHILE loop) ending in M99.
const SHOP: &str = "%
O1000 (HAAS M97 SHOP)
G00 G17 G40 G49 G80 G90
G54
T1 M06
S2000 M03
G00 X0. Y0.
M97 P100 L2
G00 X50.
#5=3.
M97 P200 L#5
/ M97 P200
M97 P300
G00 Z50. M09
M30
N100 G91 G01 X10. F300.
Y5.
G90
M99
N200 #1=#1+1.
WHILE [#1 LT 3] DO1
G01 Y#1 F100.
#1=#1+1.
END1
G00 Z5. M99
N300 G01 X#5 F200.
M99
%
";

fn setup(name: &str, text: &str) -> std::path::PathBuf {
    let d = workdir("haas-m97", name);
    std::fs::write(d.join("nctrans.toml"), PROFILE).unwrap();
    std::fs::write(d.join("O1000.nc"), text).unwrap();
    d
}

fn translate(d: &Path) -> (String, String, i32) {
    let (out, err, code) = nctrans(d, &["--to", "sinumerik", "O1000.nc", "-o", "o.mpf"]);
    let text = std::fs::read_to_string(d.join("o.mpf")).unwrap_or_default();
    let _ = out;
    (text, err, code)
}

fn check(d: &Path, text: &str) -> (String, i32) {
    std::fs::write(d.join("planted.mpf"), text).unwrap();
    let (out, err, code) = nctrans(d, &["check", "O1000.nc", "planted.mpf"]);
    (format!("{out}{err}"), code)
}

#[test]
fn local_subprograms_become_section_repetitions_and_check_equivalent() {
    let d = setup("shop", SHOP);
    let (text, err, code) = translate(&d);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
    for line in [
        "GOTOF LSUB_CALL1",
        "LSUB_RET1:",
        "LSUB_100:",
        "LSUB_E1:",
        "REPEAT LSUB_100 LSUB_E1 P=2",
        "GOTOB LSUB_RET1",
        "IF LOC5-0.5<0 GOTOB LSUB_RET2",
        "REPEAT LSUB_200 LSUB_E2 P=ROUND(LOC5)",
        "/ GOTOF LSUB_CALL3",
        "REPEAT LSUB_300 LSUB_E3 P=1",
    ] {
        assert!(text.lines().any(|l| l.trim() == line), "missing `{line}` in\n{text}");
    }
    // No M99/RET is left of the sections, and the trampolines stand after all of them.
    assert!(!text.contains("RET\n") && !text.contains("M99"), "{text}");
    let last_section = text.find("LSUB_E3:").unwrap();
    assert!(text.find("LSUB_CALL1:").unwrap() > last_section, "{text}");
    // The checker agrees with the translation on its own.
    let (out, code) = check(&d, &text);
    assert_eq!(code, 0, "{out}");
}

#[test]
fn a_wrong_repeat_count_or_section_is_caught() {
    let d = setup("planted", SHOP);
    let (text, err, code) = translate(&d);
    assert_eq!(code, 0, "{err}");
    let wrong_count = text.replace("LSUB_E1 P=2", "LSUB_E1 P=1");
    assert_ne!(wrong_count, text);
    let (out, code) = check(&d, &wrong_count);
    assert_ne!(code, 0, "one pass instead of two must diverge: {out}");
    // The section ending one block early (before its `Y5.`).
    let wrong_section: String = text
        .lines()
        .filter(|l| l.trim() != "LSUB_E1:")
        .flat_map(|l| if l.trim() == "Y5" { vec!["LSUB_E1:", l] } else { vec![l] })
        .map(|l| format!("{l}\n"))
        .collect();
    assert_ne!(wrong_section, text);
    let (out, code) = check(&d, &wrong_section);
    assert_ne!(code, 0, "a section without its last move must diverge: {out}");
    // Repeating the other local subprogram.
    let other = text.replace("REPEAT LSUB_100 LSUB_E1", "REPEAT LSUB_300 LSUB_E3");
    let (out, code) = check(&d, &other);
    assert_ne!(code, 0, "the wrong section must diverge: {out}");
}

fn refused(name: &str, text: &str, code: &str) {
    let d = setup(name, text);
    let (_, err, rc) = translate(&d);
    assert_ne!(rc, 0, "{name}: {err}");
    assert!(err.contains(code), "{name}: expected {code} in {err}");
    assert!(!err.contains("NC636"), "{name}: {err}");
}

#[test]
fn forms_that_are_not_exact_are_refused_with_their_codes() {
    let tail = "M30\nN100 G01 X1. F100.\nM99\n";
    refused("missing-n", "O1000\nM97 P100\nM30\nN200 G01 X1. F100.\nM99\n", "NC580");
    refused("duplicate-n", &format!("O1000\nM97 P100\n{tail}N100 X2.\nM99\n"), "NC580");
    refused("other-words", &format!("O1000\nG00 X5. M97 P100\n{tail}"), "NC581");
    refused("in-loop", &format!("O1000\n#1=0\nWHILE[#1 LT 2]DO1\nM97 P100\n#1=#1+1\nEND1\n{tail}"), "NC581");
    refused("nested", "O1000\nM97 P100\nM30\nN100 G01 X1. F100.\nM97 P200\nM99\nN200 G01 Y1.\nM99\n", "NC582");
    refused("goto-out", "O1000\nM97 P100\nM30\nN100 G01 X1. F100.\nGOTO 5\nM99\nN5 M30\n", "NC582");
    refused("m99-p", "O1000\nM97 P100\nN7 M30\nN100 G01 X1. F100.\nM99 P7\n", "NC582");
    refused("m30-inside", "O1000\nM97 P100\nM30\nN100 G01 X1. F100.\nM30\n", "NC582");
    refused("skipped-m99", "O1000\nM97 P100\nM30\nN100 G01 X1. F100.\n/ M99\nM99\n", "NC582");
    refused("falls-in", "O1000\nM97 P100\nG00 X5.\nN100 G01 X1. F100.\nM99\n", "NC583");
    refused("jumped-into", &format!("O1000\nM97 P100\nGOTO 100\n{tail}"), "NC583");
    refused("computed-goto", &format!("O1000\n#2=100.\nM97 P100\nIF[#2 EQ 0]GOTO#2\n{tail}"), "NC583");
    refused("l0", &format!("O1000\nM97 P100 L0\n{tail}"), "NC584");
}

/// A computed count of zero (rounded) runs no pass, on both sides.
#[test]
fn a_computed_count_below_one_runs_no_pass() {
    let d = setup("zero", "O1000\n#5=0.4\nG00 X0 Y0\nM97 P100 L#5\nG00 X9.\nM30\nN100 G01 X1. F100.\nM99\n");
    let (text, err, code) = translate(&d);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
    // The guard jumps back before REPEAT, so no control ever sees P=0.
    assert!(text.contains("IF LOC5-0.5<0 GOTOB LSUB_RET1"), "{text}");
}
