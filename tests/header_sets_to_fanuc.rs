//! A Siemens program's `nctrans: set` header lines in a translation to FANUC: the proof runs
//! the source with them (as `run` does), and the output carries them in its own variable
//! names, so `run` and `check` of the written file start from the same inputs.

mod eval_support;

use eval_support::{nctrans, scratch_dir, write};

const SRC: &str = "; nctrans: set R1=5 R2=2 R77=1\nIF R1==0 GOTOF SKIP\nG0 X=R1 Z=-R2\nSKIP:\nM30\n";

#[test]
fn the_proof_takes_the_header_and_the_output_carries_it_in_fanuc_names() {
    let d = scratch_dir("header-sets-tests", "mapped");
    let src = write(&d, "HDR.MPF", SRC);
    let out = d.join("hdr.nc").to_string_lossy().into_owned();
    let (code, _, err) = nctrans(&["--to", "fanuc", &src, "-o", &out]);
    assert_eq!(code, 0, "{err}");
    // The path the header selects (R1=5) is the one proven: the move is compared.
    assert!(err.contains("equivalent (2 events)"), "{err}");
    assert!(!err.contains("NC404"), "the header's R1 is set in the proof: {err}");
    let text = std::fs::read_to_string(&out).unwrap();
    let line = text.lines().find(|l| l.contains("nctrans: set")).expect("header line kept");
    // R77, which the program never uses, has no FANUC home and is left out.
    assert!(line.contains("#501=5") && line.contains("=2") && !line.contains('R'), "{line}");
    let (code, trace, err) = nctrans(&["run", &out]);
    assert_eq!(code, 0, "{err}");
    assert!(trace.contains("move rapid X=5 Z=-2"), "{trace}");
    let (code, verdict, err) = nctrans(&["check", &src, &out]);
    assert_eq!(code, 0, "{verdict}{err}");
    assert!(format!("{verdict}{err}").contains("equivalent"), "{verdict}{err}");
}

/// `--stream` writes the same bytes as the whole translation: the header line stays out of
/// the streamed runs, so it is written in FANUC names on both paths. A program of straight
/// blocks only, and one with a macro part (the segmented stream).
#[test]
fn the_streamed_output_carries_the_header_in_fanuc_names_too() {
    let d = scratch_dir("header-sets-tests", "streamed");
    let straight = "; nctrans: set R1=5\nG0 X10 Y5\nG1 X20 F100\nM30\n";
    for (name, src) in [("STRAIGHT.MPF", straight), ("MACRO.MPF", SRC)] {
        let src = write(&d, name, src);
        let whole = d.join(format!("{name}.whole.nc")).to_string_lossy().into_owned();
        let streamed = d.join(format!("{name}.stream.nc")).to_string_lossy().into_owned();
        let (code, _, err) = nctrans(&["--to", "fanuc", &src, "-o", &whole]);
        assert_eq!(code, 0, "{err}");
        let (code, _, err) = nctrans(&["--to", "fanuc", "--stream", &src, "-o", &streamed]);
        assert_eq!(code, 0, "{err}");
        let (w, s) = (std::fs::read_to_string(&whole).unwrap(), std::fs::read_to_string(&streamed).unwrap());
        assert_eq!(w, s, "{name}: streamed and whole outputs differ");
        // The straight program uses no R1: the line has nothing the output could take.
        let expected = if name == "MACRO.MPF" { "nctrans: set #501=5" } else { "G01 X20. F100." };
        let set_line = w.lines().find(|l| l.contains("nctrans: set")).unwrap_or("");
        assert!(w.contains(expected) && !set_line.contains('R'), "{name}: {w}");
    }
}

/// A main program whose header sets one of its own DEF variables (with a start value and
/// without one) beside an R parameter.
const DEF_SRC: &str = "; nctrans: set DEPTH=5 STEP=4 R1=3\nDEF REAL DEPTH=2\nDEF REAL STEP\nG90 G1 X0 Y0 Z0 F100\nG1 X=R1 Z=-DEPTH\nG1 Z=-STEP\nM30\n";

#[test]
fn an_input_naming_a_def_is_left_out_of_the_proof_and_said_so() {
    // `run` gives the DEF the input; the FANUC program assigns the start value in its body,
    // so the proof runs both with the start value (was: "diverged … a bug in nctrans").
    let d = scratch_dir("header-sets-tests", "def");
    let src = write(&d, "DEFSET.MPF", DEF_SRC);
    let out = d.join("defset.nc").to_string_lossy().into_owned();
    let (code, _, err) = nctrans(&["--to", "fanuc", &src, "-o", &out]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("warning[NC661]") && err.contains("the input DEPTH=5 is not used"), "{err}");
    assert!(err.contains("DEF REAL DEPTH=2"), "the warning points at the DEF: {err}");
    assert!(err.contains("equivalent (") && err.contains("not used: the inputs DEPTH=5 STEP=4"), "{err}");
    // STEP, a DEF without a start value (0), likewise. The R parameter's input is still
    // proven and carried; the DEFs' are not written.
    let text = std::fs::read_to_string(&out).unwrap();
    let line = text.lines().find(|l| l.contains("nctrans: set")).expect("header line kept");
    assert!(line.contains("#501=3") && !line.contains("=5") && !line.contains("=4"), "{line}");
    let (code, verdict, err) = nctrans(&["check", &src, &out]);
    assert_eq!(code, 0, "{verdict}{err}");
    assert!(
        verdict.contains("equivalent (") && verdict.contains("not used: the inputs DEPTH=5 STEP=4"),
        "{verdict}{err}"
    );
}

#[test]
fn a_planted_wrong_start_value_is_still_caught() {
    let d = scratch_dir("header-sets-tests", "def-planted");
    let src = write(&d, "DEFSET.MPF", DEF_SRC);
    let (code, good, err) = nctrans(&["--to", "fanuc", &src]);
    assert_eq!(code, 0, "{err}");
    assert!(good.contains("=2.\n"), "{good}");
    let bad = write(&d, "bad.nc", &good.replacen("=2.\n", "=5.\n", 1));
    let (code, verdict, err) = nctrans(&["check", &src, &bad]);
    assert_ne!(code, 0, "a wrong start value was not caught: {verdict}{err}");
    assert!(verdict.contains("diverged"), "{verdict}");
}
