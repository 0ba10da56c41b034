//! Where a jump may land (`lower::landings`): only the labels and block numbers a program's
//! jumps name are places where another state may arrive. A Siemens program numbered
//! `N10 N20 …` that never jumps translates its frames as an unnumbered one does (it was
//! NC498); a block a jump does land on still refuses; a `CASE` is a jump to the known-value
//! analysis of the drilling cycles (it was not, and a cycle argument set on one arm only was
//! taken as known: the proof diverged blaming nctrans).

mod eval_support;

use eval_support::{nctrans, scratch_file};

const NUMBERED: &str = "N10 G17 G90 G54 G71 G94\nN20 T1 M6\nN30 S2500 M3 D1\nN40 G0 X0 Y0 Z100\n\
N60 TRANS X50 Y40\nN70 AROT RPL=30\nN80 G0 X10 Y0\nN85 G1 Z-2 F100\nN90 G1 X20 Y0\nN95 G0 Z5\n";

#[test]
fn block_numbers_nothing_jumps_to_do_not_stop_a_frame_translation() {
    let text = format!("{NUMBERED}N100 TRANS\nN110 G0 X0 Y0 Z100\nN120 M30\n");
    let src = scratch_file("landings", "mpf", &text);
    let (code, out, err) = nctrans(&[&src, "--to", "fanuc"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
    assert!(out.contains("G68 X0. Y0. R30."), "{out}");
}

#[test]
fn a_block_a_jump_lands_on_still_refuses() {
    // N70 is the target of a loop: the AROT may add to the rotation of the pass before.
    let text = format!("R1=0\n{NUMBERED}R1=R1+1\nIF R1<3 GOTOB N70\nN100 TRANS\nN110 G0 X0 Y0 Z100\nN120 M30\n");
    let src = scratch_file("landings", "mpf", &text);
    let (code, _, err) = nctrans(&[&src, "--to", "fanuc"]);
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("NC498"), "{err}");
}

#[test]
fn a_case_is_a_jump_to_the_known_values() {
    let text = "G17 G90 G71 G54\nT1 D1 M6\nS2000 M3 F150\nR1=10\nCASE R5 OF 1 GOTOF LA DEFAULT GOTOF LB\n\
LA: R1=20\nLB: G0 X0 Y0 Z30\nMCALL CYCLE81(R1,0,2,-15)\nX20 Y20\nMCALL\nG0 Z100\nM30\n";
    let src = scratch_file("landings", "mpf", text);
    let (code, _, err) = nctrans(&[&src, "--to", "fanuc"]);
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("NC660") && err.contains("R1 is set to 20 here on one path"), "{err}");
    assert!(!err.contains("bug in nctrans"), "{err}");
}
