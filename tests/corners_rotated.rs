//! Chamfers and roundings under a frame that only turns and shifts (Siemens ROT/AROT with
//! TRANS, FANUC G68 with G52): the corner is the same figure in the workpiece coordinates
//! as in the programmed ones, so both runs make it and translations prove equivalent. A
//! frame that scales keeps the corner refused (NC574); mirrors: tests/corners_scaled.rs.

mod eval_support;

use eval_support::{nctrans, scratch_dir, write};

const SIE: &str = "G17 G90 G54 G71\nT4 M6\nD1\nS3000 M3\nTRANS X50 Y40\nAROT RPL=30\nG0 X0 Y0 Z5\n\
G1 Z-2 F150\nG1 X15 Y5 F600\nG1 Y-5 CHR=1.5\nG1 X-15\nG1 Y5 RND=2\nG1 X15\nG0 Z50\nTRANS\nM30\n";

const FAN: &str = "%\nO1000\nG17 G90 G54 G21\nT4 M06\nG43 H4 Z50.\nS3000 M03\nG52 X50. Y40.\nG68 X0. Y0. R30.\n\
G00 X0. Y0. Z5.\nG01 Z-2. F150.\nG01 X15. Y5. F600.\nG01 Y-5. ,C1.5\nG01 X-15.\nG01 Y5. ,R2.\nG01 X15.\n\
G00 Z50.\nG69\nG52 X0. Y0.\nM30\n%\n";

#[test]
fn rotated_corners_run_and_translate_both_ways() {
    let d = scratch_dir("corners-rotated", "both");
    let sie = write(&d, "ROT.MPF", SIE);
    let fan = write(&d, "O1000.nc", FAN);
    let (code, trace, err) = nctrans(&["run", &sie]);
    assert_eq!(code, 0, "{err}");
    assert!(trace.contains("arc"), "the rounding is an arc: {trace}");
    for (src, to) in [(&sie, "fanuc"), (&fan, "sinumerik")] {
        let (code, _, err) = nctrans(&["--to", to, src]);
        assert_eq!(code, 0, "{src}: {err}");
        assert!(err.contains("equivalent"), "{src}: {err}");
    }
}

#[test]
fn another_corner_size_under_the_rotation_is_caught() {
    let d = scratch_dir("corners-rotated", "planted");
    let sie = write(&d, "ROT.MPF", SIE);
    let (code, out, err) = nctrans(&["--to", "fanuc", &sie]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains(",R2.") && out.contains(",C1.5"), "{out}");
    for planted in [out.replace(",R2.", ",R3."), out.replace(",C1.5", ""), out.replace("R30.", "R-30.")] {
        let bad = write(&d, "BAD.nc", &planted);
        let (code, verdict, err) = nctrans(&["check", &sie, &bad]);
        assert_ne!(code, 0, "{verdict}{err}");
        assert!(format!("{verdict}{err}").contains("diverge"), "{verdict}{err}");
    }
}

#[test]
fn a_corner_under_scaling_stays_refused() {
    let d = scratch_dir("corners-rotated", "scaled");
    for (name, frame) in [("SCALED.MPF", "ASCALE X2 Y2"), ("ROTATED_SCALED.MPF", "AROT RPL=30\nASCALE X2 Y2")] {
        let src = write(&d, name, &SIE.replace("AROT RPL=30", frame));
        let (code, _, err) = nctrans(&["run", &src]);
        assert_ne!(code, 0, "{name}: {err}");
        assert!(err.contains("NC574"), "{name}: {err}");
    }
}
