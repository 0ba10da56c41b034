//! Drilling cycles inside loops and IFs of a Sinumerik main program translate to FANUC when
//! G90 is known there: the program never selects G91 (nor calls a program that could), so
//! the start-up G90 holds everywhere. A G91 inside a loop leaves the mode unknown after it.

mod eval_support;

use eval_support::{nctrans, scratch_dir, write};

/// A bolt circle drilled in a FOR loop, the positions computed from the loop counter.
const LOOPED: &str = "; BOLT CIRCLE IN A LOOP\nDEF REAL PCD=80\nDEF INT CNT\nG17 G90 G54 G71\nT1 M6\nD1\n\
G0 X0 Y0 Z10 S2000 M3\nFOR CNT=0 TO 3\n  G0 X=PCD/2*COS(CNT*90) Y=PCD/2*SIN(CNT*90) Z10\n  CYCLE81(10,0,2,-2)\nENDFOR\n\
IF PCD>50\n  G0 X0 Y0 Z10\n  CYCLE81(10,0,2,-5)\nENDIF\nG0 Z100\nM30\n";

#[test]
fn cycles_in_a_loop_and_an_if_of_a_g90_program_translate_and_verify() {
    let d = scratch_dir("cycles-in-structures", "looped");
    let src = write(&d, "BOLT.MPF", LOOPED);
    let (code, out, err) = nctrans(&["--to", "fanuc", &src]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
    assert_eq!(out.matches("G81").count(), 2, "{out}");
}

#[test]
fn a_g91_inside_the_loop_leaves_the_mode_unknown_at_the_cycle() {
    let d = scratch_dir("cycles-in-structures", "incremental");
    // G91 inside the loop body: the cycle after it in the next pass is under G91 or G90.
    let text = LOOPED.replace("  CYCLE81(10,0,2,-2)\n", "  CYCLE81(10,0,2,-2)\n  G91 G0 X0\n  G90\n");
    let src = write(&d, "BOLT.MPF", &text);
    let (code, _, err) = nctrans(&["--to", "fanuc", &src]);
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("NC395"), "{err}");
}
