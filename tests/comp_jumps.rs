//! Tool compensation across jumps: a jump target starts in what the blocks before it and
//! every jump to it agree on, so a loop written with a label and `GOTOB` (FANUC `GOTO`)
//! keeps the edge or the H register known after it; where a jump brings another edge the
//! state is unknown there, and a compensation word that depends on it is refused.

mod eval_support;

use eval_support::{nctrans, nctrans_in, scratch_dir, write};

/// A roughing loop with a label and a backward jump, the edge selected before it, D0 after.
const SIE: &str = "G17 G90 G54 G71\nT4 M6\nD1\nS3000 M3\nG0 X0 Y0 Z5\nR1=0\nLOOP1:\nR1=R1-2\nG1 Z=R1 F150\n\
G1 X20\nG1 X0\nIF R1>-6 GOTOB LOOP1\nG0 Z50 D0\nM30\n";

const FAN: &str = "%\nO1000\nG17 G90 G54 G21\nT4 M06\nG43 H4 Z50.\nS3000 M03\nG00 X0. Y0. Z5.\n#1=0.\n\
N10 #1=#1-2.\nG01 Z#1 F150.\nX20.\nX0.\nIF [#1 GT -6.] GOTO 10\nG00 G49 Z50.\nM30\n%\n";

#[test]
fn a_label_loop_keeps_the_edge_known_to_fanuc() {
    let d = scratch_dir("comp-jumps", "sie");
    let src = write(&d, "ROUGH.MPF", SIE);
    let (code, out, err) = nctrans(&["--to", "fanuc", &src]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
    assert!(out.contains("G43 H4") && out.contains("G49"), "{out}");
}

#[test]
fn a_goto_loop_keeps_the_length_known_to_sinumerik() {
    let d = scratch_dir("comp-jumps", "fan");
    let src = write(&d, "O1000.nc", FAN);
    let (code, out, err) = nctrans(&["--to", "sinumerik", &src]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
    assert!(out.contains("D0"), "{out}");
}

#[test]
fn a_jump_that_brings_another_edge_leaves_the_target_unknown() {
    let d = scratch_dir("comp-jumps", "mixed");
    // The backward jump comes from after D0: at LOOP1 the edge is D1 or D0.
    let text = SIE.replace("IF R1>-6 GOTOB LOOP1\nG0 Z50 D0\n", "G0 Z50 D0\nIF R1>-6 GOTOB LOOP1\nG0 Z60 D1\n");
    let src = write(&d, "ROUGH.MPF", &text);
    let (code, _, err) = nctrans(&["--to", "fanuc", &src]);
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("NC470"), "{err}");
}

/// A Haas `M97` local subprogram becomes a section the program jumps to and repeats
/// (`GOTOF` … `REPEAT … P=2` … `GOTOB`): the state after it is what the section's end
/// leaves, so the `G49` after the call knows the length compensation in force.
const HAAS: &str = "%\nO01000 (BRACKET)\nG20 G17 G40 G49 G80 G90\nT1 M06\nG00 G90 G54 X-0.5 Y-0.5 S4000 M03\n\
G43 H01 Z1. M08\nG01 Z-0.25 F20.\nG41 D01 X0. Y0. F30.\nG01 Y2.\nG01 X3.\nG40 G01 X3.5 Y2.5\nG00 Z1. M09\n\
M97 P100 L2\nG53 G49 Z0. M05\nM30\nN100\nG00 X1.75 Y1.25\nG01 Z-0.1 F10.\nG00 Z1.\nM99\n%\n";

#[test]
fn a_haas_local_subprogram_keeps_the_length_known_after_its_call() {
    let d = scratch_dir("comp-jumps", "haas");
    std::fs::write(d.join("nctrans.toml"), "[fanuc]\nseries = \"haas-ngc\"\n").unwrap();
    let src = write(&d, "O01000.nc", HAAS);
    let (code, out, err) = nctrans_in(&d, &["--to", "sinumerik", &src]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
    assert!(out.contains("REPEAT") && out.contains("D0"), "{out}");
    // The section cancels the length itself: after the call that is known, too.
    let other = write(&d, "O01001.nc", &HAAS.replace("N100\nG00 X1.75", "N100\nG49 Z2.\nG00 X1.75"));
    let (code, _, err) = nctrans_in(&d, &["--to", "sinumerik", &other]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
}
