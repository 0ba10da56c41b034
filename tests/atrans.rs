//! Sinumerik `ATRANS` (adds to the programmable frame) to FANUC: the shift of each axis is
//! kept in a variable that the TRANS before it sets and each ATRANS raises, and `G52` is
//! written from them, so a contour repeated with `ATRANS X30` in a loop lands where the
//! Sinumerik one does. Where a TRANS does not come first, or with rotation, incremental
//! moves or in a called program, it is refused (NC577).

mod eval_support;

use eval_support::{nctrans, scratch_dir, write};

const ROW: &str = "; FOUR POCKETS IN A ROW\nDEF INT NP\nG17 G90 G54 G71\nTRANS X10 Y20\nT1 M6\nD1\n\
G0 Z5 S2000 M3\nFOR NP=1 TO 4\n  G0 X0 Y0\n  G1 Z-2 F100\n  G1 X20 F300\n  G1 Y10\n  G1 X0\n  G1 Y0\n  G0 Z5\n\
  ATRANS X30\nENDFOR\nTRANS\nG0 Z100\nM30\n";

#[test]
fn atrans_in_a_loop_translates_with_shift_variables_and_is_proven() {
    let d = scratch_dir("atrans", "row");
    let src = write(&d, "ROW.MPF", ROW);
    let (code, out, err) = nctrans(&["--to", "fanuc", &src]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
    assert!(out.contains("#1=#1+30.") && out.contains("G52 X#1 Y#2 Z#3"), "{out}");
    assert!(out.contains("(NCTRANS: TRANS/ATRANS SHIFT X = #1)"), "{out}");
    // A planted step of 20 instead of 30, or the ATRANS as an absolute G52: caught.
    for bad in [out.replace("#1=#1+30.", "#1=#1+20."), out.replace("G52 X#1 Y#2 Z#3", "G52 X30. Y20. Z0.")] {
        let b = write(&d, "BAD.nc", &bad);
        let (code, verdict, err) = nctrans(&["check", &src, &b]);
        assert_ne!(code, 0, "{verdict}{err}");
        assert!(format!("{verdict}{err}").contains("diverge"), "{verdict}{err}");
    }
}

#[test]
fn atrans_without_a_leading_trans_or_with_rotation_is_refused() {
    let d = scratch_dir("atrans", "refused");
    let cases = [
        ("NOTRANS.MPF", ROW.replace("TRANS X10 Y20\n", "")),
        ("ROTATED.MPF", ROW.replace("ATRANS X30\n", "ATRANS X30\n  AROT RPL=5\n")),
        ("INCREMENTAL.MPF", ROW.replace("G1 X0\n", "G91 G1 X-20\nG90\n")),
    ];
    for (name, text) in cases {
        let src = write(&d, name, &text);
        let (code, _, err) = nctrans(&["--to", "fanuc", &src]);
        assert_ne!(code, 0, "{name}: {err}");
        assert!(err.contains("NC577") || err.contains("NC445") || err.contains("NC498"), "{name}: {err}");
    }
    // In a called program the shifts its caller set are not known.
    let main = write(&d, "CALLER.MPF", "G17 G90 G54\nTRANS X10\nSTEP\nM30\n");
    write(&d, "STEP.SPF", "PROC STEP\nATRANS X30\nG0 X0 Y0\nRET\n");
    let (code, _, err) = nctrans(&["--to", "fanuc", &main]);
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("NC577") && err.contains("called program"), "{err}");
}
