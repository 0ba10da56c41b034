//! FANUC frame codes real programs write that the Sinumerik translation takes as FANUC runs
//! them: the safety line that cancels several frame modes in one block (`G00 G17 G40 G49 G50
//! G69 G80 G90`; where none is in force each cancel changes nothing, where one is, two frame
//! codes in a block stay refused, NC497), and `G68 R a` without a centre (the tool position).

mod eval_support;

use eval_support::{nctrans, scratch_dir, write};

#[test]
fn a_safety_line_with_several_cancels_translates_where_no_mode_is_in_force() {
    let d = scratch_dir("frame-cancels", "safety");
    let src = write(&d, "O1.nc", "%\nO0001\nG00 G17 G40 G49 G50 G69 G80 G90\nG0 X10. Y5.\nM30\n%\n");
    let (code, out, err) = nctrans(&["--to", "sinumerik", &src]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent") && out.contains("G0 G17 G40 G90"), "{out}{err}");
    let inforce = write(&d, "O2.nc", "%\nO0002\nG90 G68 X0 Y0 R30.\nG0 X1. Y1.\nG00 G50 G69\nG0 X1. Y1.\nM30\n%\n");
    let (code, _, err) = nctrans(&["--to", "sinumerik", &inforce]);
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("NC497"), "{err}");
}

/// `G68 R30.` without a centre turns about the tool position at the G68 (the FANUC manual's
/// rule): the Sinumerik sequence saves the programmed position (`$P_EP`) and turns about
/// it, proven; a planted centre at the origin is caught.
#[test]
fn a_g68_without_centre_turns_about_the_tool_position() {
    let d = scratch_dir("frame-cancels", "g68-centre");
    let text =
        "%\nO0003\nG17 G90 G54\nG0 X20. Y10. Z5.\nG68 R30.\nG1 X30. Y10. F100.\nG1 Y20.\nG69\nG0 X0 Y0\nM30\n%\n";
    let src = write(&d, "O3.nc", text);
    let (code, out, err) = nctrans(&["--to", "sinumerik", &src]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent") && out.contains("NCTRANS_G68_X=$P_EP[X]"), "{out}{err}");
    let bad = write(&d, "BAD.mpf", &out.replace("NCTRANS_G68_X=$P_EP[X]", "NCTRANS_G68_X=0"));
    let (code, verdict, err) = nctrans(&["check", &src, &bad]);
    assert_ne!(code, 0, "{verdict}{err}");
    assert!(format!("{verdict}{err}").contains("diverge"), "{verdict}{err}");
}
