//! Sinumerik `ATRANS` (adds to the programmable frame) to FANUC: the shift of each axis is
//! kept in a variable that the TRANS before it sets and each ATRANS raises, and `G52` is
//! written from them, so a contour repeated with `ATRANS X30` in a loop lands where the
//! Sinumerik one does. Under a rotation (AROT/ROT in G17) the ATRANS shifts along the turned
//! axes: the variables take the turned shift (quarter turns, or constants G52 holds exactly)
//! and the rotation is written again around the G52 (`frame_chain.rs`). A called program
//! that sets its own frame first translates too. Where a TRANS does not come first, the
//! angle is not known, the turned shift is not one G52 holds, with SCALE/MIRROR,
//! incremental moves, SAVE, or in a called program that adds to its caller's frame, it is
//! refused (NC577) with the reason.

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

/// A frame on a fixture at (10, 10) turned by `angle`, then `ATRANS X5 Y3`, a contour.
fn turned(angle: &str) -> String {
    format!(
        "G17 G90 G54 G71\nT1 M6\nD1\nG0 Z5\nTRANS X10 Y10\nAROT RPL={angle}\nATRANS X5 Y3\n\
         G0 X0 Y0\nG1 Z-1 F100\nG1 X8 Y0\nG1 X8 Y4\nG0 Z5\nTRANS\nG0 X0 Y0\nM30\n"
    )
}

fn translate(d: &std::path::Path, name: &str, text: &str) -> (String, String, String) {
    let src = write(d, name, text);
    let (code, out, err) = nctrans(&["--to", "fanuc", &src]);
    assert_eq!(code, 0, "{name}: {err}\n{out}");
    assert!(err.contains("equivalent"), "{name}: {err}");
    (src, out, err)
}

fn caught(d: &std::path::Path, src: &str, bad: &str) {
    let b = write(d, "BAD.nc", bad);
    let (code, verdict, err) = nctrans(&["check", src, &b]);
    assert_ne!(code, 0, "{verdict}{err}");
    assert!(format!("{verdict}{err}").contains("diverge"), "{verdict}{err}");
}

#[test]
fn atrans_after_a_rotation_shifts_along_the_turned_axes_and_is_proven() {
    let d = scratch_dir("atrans", "turned");
    // The turned shift of (5, 3) in the unrotated system, at each angle.
    for (angle, x, y) in [
        ("90", "#1=#1-3.", "#2=#2+5."),
        ("-90", "#1=#1+3.", "#2=#2-5."),
        ("180", "#1=#1-5.", "#2=#2-3."),
        ("270", "#1=#1+3.", "#2=#2-5."),
        ("450", "#1=#1-3.", "#2=#2+5."),
    ] {
        let name = format!("TURN{}.MPF", angle.replace('-', "M"));
        let (src, out, _) = translate(&d, &name, &turned(angle));
        assert!(out.contains(x) && out.contains(y), "{angle}: {out}");
        // The rotation is cancelled around the new G52 and written again about its origin.
        assert!(out.contains("G69\nG52 X#1 Y#2 Z#3\nG68 X0. Y0. R#4"), "{angle}: {out}");
        assert!(out.contains("(NCTRANS: ROT/AROT ANGLE = #4)"), "{out}");
        // Planted: the ATRANS applied along the unrotated axes, or with the wrong sign.
        let unrotated = out.replace(x, "#1=#1+5.").replace(y, "#2=#2+3.");
        caught(&d, &src, &unrotated);
        let flipped = if x.contains('-') { x.replace('-', "+") } else { x.replace('+', "-") };
        let sign = out.replace(x, &flipped);
        caught(&d, &src, &sign);
    }
}

#[test]
fn rot_then_atrans_and_shifts_given_by_expressions() {
    let d = scratch_dir("atrans", "rot");
    // ROT deletes the TRANS: the shifts start at 0 and the angle at the ROT's.
    let text = "DEF REAL STEP\nG17 G90 G54\nROT RPL=-90\nSTEP=12.5\nATRANS X=STEP Y=2*STEP\nG0 X0 Y0 Z5\n\
                G1 X10 Y0 F100\nROT\nG0 X0 Y0\nM30\n";
    let (src, out, _) = translate(&d, "ROTEXPR.MPF", text);
    assert!(out.contains("G52 X0. Y0. Z0.\nG68 X0. Y0. R#"), "{out}");
    caught(&d, &src, &out.replace("G68 X0. Y0. R#", "G68 X0. Y0. R-#"));
}

#[test]
fn atrans_then_arot_then_atrans_chains_in_order() {
    let d = scratch_dir("atrans", "chain");
    // The first ATRANS is unrotated (a plain addition, no G68); the second turns with AROT.
    let text = "G17 G90 G54\nTRANS X10 Y10\nATRANS X5\nAROT RPL=90\nATRANS X5\nG0 X0 Y0 Z5\n\
                G1 X10 Y0 F100\nG1 X10 Y5\nAROT RPL=90\nATRANS X2 Y1\nG0 X0 Y0\nG1 X4 Y0\nTRANS\nG0 X0 Y0\nM30\n";
    let (src, out, _) = translate(&d, "CHAIN.MPF", text);
    let first = out.find("#1=#1+5.").expect("first ATRANS");
    let g68 = out.find("G68").expect("G68");
    assert!(first < g68, "{out}");
    assert!(out.contains("#2=#2+5."), "{out}");
    // At 180°: (2, 1) → (-2, -1).
    assert!(out.contains("#1=#1-2.") && out.contains("#2=#2-1."), "{out}");
    caught(&d, &src, &out.replacen("#2=#2+5.", "#1=#1+5.", 1));
}

#[test]
fn atrans_in_a_subprogram_that_sets_its_own_frame_is_proven() {
    let d = scratch_dir("atrans", "sub");
    let main = write(&d, "FIXTURE.MPF", "G17 G90 G54 G71\nT1 M6\nD1\nG0 X0 Y0 Z5\nPOCK\nG0 X0 Y0\nM30\n");
    let sub = "PROC POCK\nG17 G90\nTRANS X50 Y20\nAROT RPL=90\nATRANS X10\nG0 X0 Y0\nG1 Z-2 F100\n\
               G1 X5 Y0\nG0 Z5\nRET\n";
    write(&d, "POCK.SPF", sub);
    let (code, out, err) = nctrans(&["--to", "fanuc", &main]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
    assert!(out.contains("G65 P9000") && out.contains("G68 X0. Y0. R#"), "{out}");
    // It may be called under a G68 (its leading TRANS deletes the whole frame on Siemens):
    // the translation cancels that first.
    assert!(out.contains("G69\nG52 X50. Y20. Z0."), "{out}");
    // A main program whose chain calls a geometry subprogram without frames.
    let main2 = write(
        &d,
        "ROWS.MPF",
        "DEF INT NK\nG17 G90 G54\nTRANS X100 Y40\nAROT RPL=90\nFOR NK=1 TO 3\nG0 X0 Y0 Z5\nSLOT\nATRANS X20\nENDFOR\nTRANS\nG0 X0 Y0\nM30\n",
    );
    write(&d, "SLOT.SPF", "PROC SLOT\nG1 Z-1 F100\nG1 X8 Y0\nG0 Z5\nRET\n");
    let (code, out, err) = nctrans(&["--to", "fanuc", &main2]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent") && out.contains("#2=#2+20."), "{err}{out}");
}

#[test]
fn atrans_under_a_rotation_that_cannot_be_exact_is_refused_with_its_reason() {
    let d = scratch_dir("atrans", "refused-turned");
    let loop_arot =
        "DEF INT NK\nG17 G90 G54\nTRANS X10\nFOR NK=1 TO 4\nAROT RPL=90\nATRANS X5\nG0 X0 Y0\nENDFOR\nM30\n";
    let cases: Vec<(&str, String, &str)> = vec![
        ("THIRTY.MPF", turned("30"), "rounds to its 0.001 input increment"),
        ("LOOPROT.MPF", loop_arot.into(), "angle is not known at translation"),
        ("VARANGLE.MPF", turned("R1"), "angle is not known at translation"),
        (
            "PATHS.MPF",
            turned("90").replace("AROT RPL=90\n", "IF R1>0\nAROT RPL=90\nELSE\nAROT RPL=180\nENDIF\n"),
            "angle is not known at translation",
        ),
        ("SCALED.MPF", turned("90").replace("G0 X0 Y0\nM30", "SCALE X2\nG0 X0 Y0\nM30"), "SCALE, MIRROR"),
        ("G18.MPF", turned("90").replace("G0 X0 Y0\nM30", "G18\nG0 X0 Y0\nM30"), "G18 or G19"),
        ("NOTFIRST.MPF", turned("90").replace("TRANS X10 Y10\nAROT", "AROT"), "first frame instruction"),
    ];
    for (name, text, why) in cases {
        let src = write(&d, name, &text);
        let (code, _, err) = nctrans(&["--to", "fanuc", &src]);
        assert_ne!(code, 0, "{name}: {err}");
        assert!(err.contains("NC577") && err.contains(why), "{name}: {err}");
    }
    // A called program that adds to the frame its caller left; a SAVE one (Siemens restores
    // the caller's frame at its end); a caller whose chain calls a program with frames.
    let cases = [
        ("ADDS", "PROC ADDS\nG17 G90\nAROT RPL=90\nATRANS X5\nG0 X0 Y0\nRET\n", "does not set its own frame first"),
        ("SAVED", "PROC SAVED SAVE\nG17 G90\nTRANS X5\nAROT RPL=90\nATRANS X5\nG0 X0 Y0\nRET\n", "SAVE"),
    ];
    for (sub, text, why) in cases {
        let main = write(&d, &format!("M{sub}.MPF"), &format!("G17 G90 G54\nTRANS X10\nG0 X0 Y0 Z5\n{sub}\nM30\n"));
        write(&d, &format!("{sub}.SPF"), text);
        let (code, _, err) = nctrans(&["--to", "fanuc", &main]);
        assert_ne!(code, 0, "{sub}: {err}");
        assert!(err.contains("NC577") && err.contains(why), "{sub}: {err}");
    }
    let main = write(&d, "CALLSFRAMES.MPF", "G17 G90 G54\nTRANS X10\nAROT RPL=90\nSHIFTS\nATRANS X5\nG0 X0 Y0\nM30\n");
    write(&d, "SHIFTS.SPF", "PROC SHIFTS\nG17 G90\nTRANS X3\nRET\n");
    let (code, _, err) = nctrans(&["--to", "fanuc", &main]);
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("NC577") && err.contains("subprogram that has frame instructions"), "{err}");
}

/// Angle sums are brought into G68's range by remainder: a huge literal angle (where a step
/// of 360 changes nothing) ends in a refusal, not a hang; a sum past 360 still turns the same.
#[test]
fn a_huge_rotation_angle_is_refused_without_hanging_and_a_sum_past_360_is_reduced() {
    let d = scratch_dir("atrans", "huge-angle");
    let src = write(
        &d,
        "HUGE.MPF",
        "G17 G90 G54\nTRANS X10 Y10\nAROT RPL=90\nAROT RPL=100000000000000000000000\nATRANS X5\nG0 X0 Y0\nTRANS\nM30\n",
    );
    let (code, _, err) = nctrans(&["--to", "fanuc", &src]);
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("NC577"), "{err}");
    let (_, out, _) = translate(&d, "SUM.MPF", &turned("270\nAROT RPL=180"));
    assert!(out.contains("R90.") || out.contains("=90."), "450 is written as 90: {out}");
}
