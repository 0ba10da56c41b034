//! The first move after a rotation changes, leaving a plane axis out (issue #20). FANUC's
//! reading (the programmed value kept, then turned by the new rotation) and Siemens' (the
//! position worked out again through the new frame) are both run only where they agree: the
//! tool stands on the centre of the rotation, under the same offsets. Elsewhere NC494 as
//! before. A Siemens bolt pattern turned by `ROT` in a loop with its plunge at the centre
//! translates to FANUC proven; a planted wrong rotation sign is caught.

#[path = "support/frame_check.rs"]
mod frame_check;
use frame_check::*;
use nctrans::dialect::Dialect;

#[test]
fn a_plunge_at_the_centre_of_the_rotation_runs() {
    let t =
        trace("O1\nG0 X10. Y10. Z5.\nG68 X10. Y10. R45.\nG1 Z-2. F100.\nG0 Z5.\nG69\nG0 Z10.\nM30\n", Dialect::Fanuc);
    assert!(!t.contains("error"), "{t}");
    assert!(t.contains("move linear X=10 Y=10 Z=-2"), "{t}");
    assert!(t.contains("move rapid X=10 Y=10 Z=10"), "{t}");
}

#[test]
fn off_the_centre_or_after_a_shift_it_stays_refused() {
    // Off the centre the readings part: X50 Y0 kept and turned, or the point stays.
    let t = trace("O1\nG0 X50. Y0 Z5.\nG68 X0 Y0 R30.\nG1 Z-2. F100.\nM30\n", Dialect::Fanuc);
    assert!(t.ends_with("error NC494"), "{t}");
    // At the centre, but a G52 between G69 and the move shifts the programmed value.
    let t = trace("O1\nG0 X0 Y0 Z5.\nG68 X0 Y0 R30.\nG0 X0 Y0\nG69\nG52 X5.\nG0 Z10.\nM30\n", Dialect::Fanuc);
    assert!(t.ends_with("error NC494"), "{t}");
    // A hole at the centre leaves nothing to choose either; off it, NC496 as before.
    let t = trace("O1\nG0 X0 Y0 Z10.\nG68 X0 Y0 R30.\nG81 Z-5. R2. F100.\nG80\nM30\n", Dialect::Fanuc);
    assert!(t.contains("cycle") && !t.contains("error"), "{t}");
}

/// Four slots turned by a quarter each, plunging at the centre after every ROT.
const SLOTS: &str = "\
; 4 SLOTS AT 90 DEG
DEF INT _I
N10 G17 G90 G71 G54
N20 T2 D1 M6
N30 S1800 M3 F200
N40 G0 X0 Y0 Z10
N50 FOR _I=1 TO 4
N60 ROT RPL=_I*90
N70 G1 Z-5
N80 G1 X30 F400
N90 G0 Z10
N100 X0 Y0
N110 ENDFOR
N120 ROT
N130 G0 Z100 M5
N140 M30
";

#[test]
fn a_rot_loop_plunging_at_the_centre_translates_proven() {
    let fanuc = s_to_f(SLOTS).unwrap_or_else(|codes| panic!("refused: {codes:?}"));
    assert!(fanuc.contains("G68 X0. Y0. R[#"), "{fanuc}");
    // Planted: the rotation turned the other way.
    let planted = fanuc.replacen("R[#", "R[-#", 1);
    assert_ne!(planted, fanuc);
    assert!(!equivalent(&planted, SLOTS), "{planted}");
}
