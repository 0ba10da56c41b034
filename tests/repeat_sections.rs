//! Siemens program-section repetition (`REPEAT`, `REPEATB`, `ENDLABEL`): what the evaluator
//! runs (the section, its passes, ENDLABEL ending it, REPEATB's label below), the FANUC
//! translation (the section copied into a counted loop, proven), a planted wrong count caught
//! by `nctrans check`, and each form the copy cannot make exact refused with its own code.

#[path = "support/cli_run.rs"]
mod cli_run;

use cli_run::{nctrans, workdir};
use std::path::Path;

fn write(d: &Path, name: &str, text: &str) {
    std::fs::write(d.join(name), text).unwrap();
}

/// The X values of the moves `nctrans run` prints, in order.
fn xs(d: &Path, name: &str) -> Vec<String> {
    let (out, err, code) = nctrans(d, &["run", name]);
    assert_eq!(code, 0, "{err}");
    out.lines()
        .filter(|l| l.starts_with("move "))
        .filter_map(|l| l.split_whitespace().find(|w| w.starts_with("X=")).map(str::to_string))
        .collect()
}

#[test]
fn section_repetition_runs_the_section_from_the_repeat() {
    let d = workdir("repeat-sections", "run");
    // P=2: the section (its label's block included, the REPEAT not) twice more; no P: once.
    write(&d, "two.mpf", "G91 G1 F100\nAA: X1\nX10\nREPEAT AA P=2\nREPEAT AA\nG90\nM30\n");
    let x = xs(&d, "two.mpf");
    // AA, X10 | twice again | then REPEAT AA repeats AA..(REPEAT AA P=2): AA, X10 and that
    // REPEAT's two passes again.
    let steps = ["X=1", "X=11", "X=12", "X=22", "X=23", "X=33", "X=34", "X=44", "X=45", "X=55", "X=56", "X=66"];
    assert_eq!(x, steps);
    // ENDLABEL ends the section: the block after it is not repeated.
    write(
        &d,
        "end.mpf",
        "G91 G1 F100\nAA: X1\nENDLABEL: X2\nX100\nREPEAT AA P=1\nBB: X1000\nENDLABEL: X3\nREPEAT BB\nG90\nM30\n",
    );
    let x = xs(&d, "end.mpf");
    assert_eq!(x, ["X=1", "X=3", "X=103", "X=104", "X=106", "X=1106", "X=1109", "X=2109", "X=2112"]);
    // REPEATB finds its label below it too, and runs only that block.
    write(&d, "b.mpf", "G91 G1 F100\nREPEATB LATER P=2\nX100\nLATER: X1\nG90\nM30\n");
    assert_eq!(xs(&d, "b.mpf"), ["X=1", "X=2", "X=102", "X=103"]);
}

#[test]
fn section_repetition_translates_into_a_counted_loop_and_checks_equivalent() {
    let d = workdir("repeat-sections", "translate");
    let src = "DEF INT NP\nG17 G90 G54 G71\nT1 M6\nD1\nG0 X0 Y0 Z5 S2000 M3\nNP=2\n\
               SLOT: G91 G1 Z-7 F100 ; plunge\nG1 X20 F300\nG0 Z7\nG0 X-20 Y8\nG90\n\
               REPEAT SLOT P=3 ; three more slots\nREPEAT SLOT P=NP\nG0 Z100\nM30\n";
    write(&d, "slots.mpf", src);
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "slots.mpf", "-o", "slots.nc"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
    let text = std::fs::read_to_string(d.join("slots.nc")).unwrap();
    for line in [
        "(REPEAT SECTION FROM SLOT, 3 TIMES: three more slots)",
        "WHILE [#1 LE 3.] DO1",
        "#1=#1+1.",
        "(REPEAT SECTION FROM SLOT, P=NP TIMES)",
        "#1=ROUND[#100]",
        "WHILE [#1 GT 0.] DO1",
        "#1=#1-1.",
    ] {
        assert!(text.lines().any(|l| l.trim() == line), "missing `{line}` in\n{text}");
    }
    // The label stays on the original block only.
    assert_eq!(text.matches("(SLOT:)").count(), 1, "{text}");
    // A planted wrong count: two passes where three run.
    let planted = text.replace("WHILE [#1 LE 3.] DO1", "WHILE [#1 LE 2.] DO1");
    assert_ne!(planted, text);
    write(&d, "planted.nc", &planted);
    let (out, err, code) = nctrans(&d, &["check", "slots.mpf", "planted.nc"]);
    assert_ne!(code, 0, "a pass too few must diverge: {out}{err}");
    // The counted-down form: one pass more.
    let planted = text.replace("#1=ROUND[#100]", "#1=ROUND[#100]+1.");
    assert_ne!(planted, text);
    write(&d, "planted2.nc", &planted);
    let (out, err, code) = nctrans(&d, &["check", "slots.mpf", "planted2.nc"]);
    assert_ne!(code, 0, "a pass too many must diverge: {out}{err}");
    let (out, err, code) = nctrans(&d, &["check", "slots.mpf", "slots.nc"]);
    assert_eq!(code, 0, "{out}{err}");
}

#[test]
fn nested_repetitions_deep_loops_and_jumps_from_outside_stay_exact() {
    let d = workdir("repeat-sections", "nested");
    // A REPEAT inside a repeated section is copied again; inside three FOR/WHILE levels the
    // counter loop is a label/GOTO loop; a GOTO from outside lands in the original section.
    let src = "DEF INT II, JJ, KK\nG90 G1 F100\nR1=0\nGOTOF CUT\nPASS: G1 X=R1\nCUT: G1 Y=R1\nR1=R1+1\n\
               REPEATB CUT P=2\nREPEAT PASS P=2\nFOR II=1 TO 2\nFOR JJ=1 TO 2\nWHILE KK<1\nKK=KK+1\n\
               STEP: G1 X=II*10+JJ Y=KK\nREPEAT STEP P=2\nENDWHILE\nKK=0\nENDFOR\nENDFOR\nM30\n";
    write(&d, "nest.mpf", src);
    let (out, err, code) = nctrans(&d, &["--to", "fanuc", "nest.mpf"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
    assert!(out.contains("WHILE [#2 LE 2.] DO2"), "the nested copy counts on its own counter:\n{out}");
    assert!(!out.contains("DO4"), "{out}");
    assert!(out.contains("IF [#1 GT 2.] GOTO"), "the fourth level is a GOTO loop:\n{out}");
}

fn refused(name: &str, text: &str, code: &str) {
    let d = workdir("repeat-sections", name);
    write(&d, "p.mpf", text);
    let (_, err, rc) = nctrans(&d, &["--to", "fanuc", "p.mpf", "-o", "p.nc"]);
    assert_ne!(rc, 0, "{name}: {err}");
    assert!(err.contains(&format!("error[{code}]")), "{name}: expected {code} in {err}");
    assert!(err.contains("hint:") || code == "NC659", "{name}: a refusal says what to do: {err}");
    assert!(!err.contains("NC317"), "{name}: {err}");
}

#[test]
fn copies_that_would_not_be_exact_are_refused_with_their_codes() {
    let s = "LA: G1 X1 F100\n";
    refused("goto", &format!("{s}IF R1>2 GOTOF OUT\nR1=R1+1\nREPEAT LA P=2\nOUT: M30\n"), "NC657");
    refused("case", &format!("{s}CASE R1 OF 1 GOTOF OUT DEFAULT GOTOF OUT\nREPEAT LA P=2\nOUT: M30\n"), "NC657");
    refused("ret", &format!("PROC RR\n{s}RET\nREPEAT LA P=2\nM17\n"), "NC657");
    refused("m30", &format!("{s}M30\nREPEAT LA P=2\n"), "NC657");
    refused("across", &format!("{s}IF R1==0\nLB: G1 X2\nENDIF\nREPEAT LA LB\nM30\n"), "NC658");
    refused("first-in-if", &format!("{s}IF R1==0\nREPEAT LA\nENDIF\nM30\n"), "NC658");
    refused("into-if", &format!("{s}IF R1==0\nG1 X2\nREPEAT LA P=2\nENDIF\nM30\n"), "NC658");
    refused("order", "LB: G1 X1 F100\nLA: G1 X2\nREPEAT LA LB\nM30\n", "NC658");
    refused("p0", &format!("{s}REPEAT LA P=0\nM30\n"), "NC658");
    refused("p-fraction", &format!("{s}REPEAT LA P=1.5\nM30\n"), "NC658");
    refused("skip", &format!("{s}/REPEAT LA P=2\nM30\n"), "NC658");
    refused("self", "G1 X1 F100\nLL: REPEAT LL P=2\nM30\n", "NC659");
    refused("self-end", &format!("{s}LB: REPEAT LA LB P=2\nM30\n"), "NC659");
    refused("cycle", &format!("{s}REPEATB LB P=2\nLB: REPEAT LA P=2\nM30\n"), "NC659");
    let deep = format!("G91\n{s}{}G90\nM30\n", "REPEAT LA\n".repeat(5));
    refused("deep", &deep, "NC659");
    // Four levels are copied (each REPEAT's section holds the REPEATs above it).
    let d = workdir("repeat-sections", "four");
    write(&d, "p.mpf", &format!("G91\n{s}{}G90\nM30\n", "REPEAT LA\n".repeat(4)));
    let (_, err, rc) = nctrans(&d, &["--to", "fanuc", "p.mpf", "-o", "p.nc"]);
    assert_eq!(rc, 0, "{err}");
}

#[test]
fn copies_beyond_the_bound_are_refused() {
    // A long section (no REPEAT in it) repeated fifty times: the copies pass 100000 statements.
    let mut src = String::from("G91 G1 F100\nLA: X1\n");
    src.push_str(&"X1\n".repeat(2100));
    src.push_str("LB: X1\n");
    src.push_str(&"REPEAT LA LB\n".repeat(50));
    src.push_str("G90\nM30\n");
    refused("bound", &src, "NC659");
}

#[test]
fn a_streamed_translation_takes_the_whole_path_for_a_repeat() {
    // The segmented stream would copy a section holding a placeholder of straight blocks:
    // it declines, and `--stream` gives the whole translation's bytes.
    let d = workdir("repeat-sections", "stream");
    let mut src = String::from("G90 G1 F100\nLA: X1\n");
    for k in 0..300 {
        src.push_str(&format!("X{} Y{}\n", k % 7, k % 5));
    }
    src.push_str("LB: X2\nREPEAT LA LB P=2\nM30\n");
    write(&d, "cam.mpf", &src);
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "cam.mpf", "-o", "whole.nc"]);
    assert_eq!(code, 0, "{err}");
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "--stream", "cam.mpf", "-o", "streamed.nc"]);
    assert_eq!(code, 0, "{err}");
    let whole = std::fs::read_to_string(d.join("whole.nc")).unwrap();
    assert_eq!(whole, std::fs::read_to_string(d.join("streamed.nc")).unwrap());
    // The section once in the text and once in the loop: k = 34, 69, … 279 give X6 Y4.
    assert_eq!(whole.matches("X6. Y4.").count(), 2 * 8, "{whole}");
}
