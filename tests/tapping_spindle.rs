//! Rigid tapping and the spindle (issue 19): from a stopped spindle (M5 before `M29 S`,
//! CYCLE84 with SDAC 5) both controls tap at the tapping speed and leave the spindle stopped,
//! so a row of holes is translated both ways and proven; a planted wrong SDAC, a missing M5
//! or a wrong pitch is caught; rigid tapping from a turning spindle stays refused, naming
//! what no source settles (FANUC's M29 with the spindle turning and its state after the
//! cycle), and the FANUC run warns where its trace rests on that (NC592).

mod eval_support;

use eval_support::*;

fn scratch(ext: &str, text: &str) -> String {
    scratch_file("tspin", ext, text)
}

/// The tool's length from its edge on both sides (G43 H1 / D1), so the heads compare equal.
const F_HEAD: &str = "%\nO1\nG21 G17 G90 G94\nG54 G0 X0 Y0\nT1 M6\nG43 H1\nG0 Z50.\n";
const S_HEAD: &str = "G17 G90 G94 G54\nG0 X0 Y0\nT1 D1 M6\nG0 Z50\n";

fn fanuc(body: &str) -> String {
    format!("{F_HEAD}{body}M30\n%\n")
}

fn sinumerik(body: &str) -> String {
    format!("{S_HEAD}{body}M30\n")
}

/// Translates and asserts it verified; the output's lines.
fn translate(src: &str, ext: &str, to: &str) -> Vec<String> {
    let p = scratch(ext, src);
    let (code, out, err) = nctrans(&[&p, "--to", to]);
    assert_eq!(code, 0, "{src}\n{out}\n{err}");
    assert!(err.contains("equivalent"), "{err}");
    out.lines().map(str::to_string).collect()
}

fn refused(src: &str, ext: &str, to: &str) -> String {
    let p = scratch(ext, src);
    let (code, _, err) = nctrans(&[&p, "--to", to]);
    assert_ne!(code, 0, "{src}\n{err}");
    err
}

fn check(a: (&str, &str), b: (&str, &str)) -> (i32, String) {
    let (pa, pb) = (scratch(a.1, a.0), scratch(b.1, b.0));
    let (code, out, _) = nctrans(&["check", &pa, &pb]);
    (code, out)
}

/// A machinist's row: the spindle started for the approach, stopped before M29, tapped,
/// started again after G80.
const F_ROW: &str =
    "S500 M3\nG0 Z20.\nM5\nM29 S500\nG98 G84 X10. Y10. Z-16. R5. F625.\nX20.\nX30.\nG80\nS500 M3\nG0 Z50.\nM5\n";

#[test]
fn a_row_tapped_from_a_stopped_spindle_is_proven_both_ways() {
    let t = translate(&fanuc(F_ROW), "nc", "sinumerik");
    let k = t.iter().position(|l| l.starts_with("MCALL CYCLE84(")).expect("CYCLE84");
    // SDAC 5: the spindle stays stopped after each hole, as FANUC's does.
    assert_eq!(t[k], "MCALL CYCLE84($P_EP[Z],5,0,-16,,0,5,,1.25,,500)", "{t:?}");
    assert!(t[..k].iter().any(|l| l.contains("M5")), "the stop before the cycle stays: {t:?}");
    // And back: the same M5 before M29 S500.
    let back = translate(&format!("{}\n", t.join("\n")), "mpf", "fanuc");
    let m = back.iter().position(|l| l == "M29 S500").expect("M29");
    assert!(back[..m].iter().any(|l| l == "M05"), "{back:?}");
    assert!(back[m + 1].starts_with("G98 G84 X10. Y10. Z-16. R5."), "{back:?}");
    // A Sinumerik row written the same way.
    let s = sinumerik(
        "S500 M3\nG0 Z20\nM5\nF625\nMCALL CYCLE84(20, 0, 5, -16, , , 5, 8, , , 500)\nX10 Y10\nX20\nX30\nMCALL\nS500 M3\nG0 Z50\nM5\n",
    );
    let t = translate(&s, "mpf", "fanuc");
    assert!(t.iter().any(|l| l == "M29 S500"), "{t:?}");
    assert!(t.iter().any(|l| l.starts_with("G98 G84 X10. Y10. Z-16. R5.")), "{t:?}");
}

#[test]
fn a_planted_wrong_sdac_a_missing_m5_or_a_wrong_pitch_is_caught() {
    let f = fanuc(F_ROW);
    let row = |stop: &str, sdac: u8, pit: &str| {
        sinumerik(&format!(
            "S500 M3\nG0 Z20\n{stop}MCALL CYCLE84(20, 0, 5, -16, , , {sdac}, , {pit}, , 500)\nX10 Y10\nX20\nX30\nMCALL\nS500 M3\nG0 Z50\nM5\n"
        ))
    };
    let (code, out) = check((&f, "nc"), (&row("M5\n", 5, "1.25"), "mpf"));
    assert_eq!(code, 0, "the right translation does not check:\n{out}");
    for (what, bad) in [
        // The spindle started again after each hole: the Sinumerik run refuses a state
        // after the cycle other than the one before it, so the pair is not proven.
        ("SDAC", row("M5\n", 3, "1.25")),
        // No M5: the FANUC spindle stops before M29, this one keeps turning.
        ("missing M5", row("", 3, "1.25")),
        ("pitch", row("M5\n", 5, "1.5")),
    ] {
        let (code, out) = check((&f, "nc"), (&bad, "mpf"));
        assert_ne!(code, 0, "a wrong {what} was not caught:\n{out}");
    }
    // The missing M5 is a divergence the trace shows: the spindle event.
    let (_, out) = check((&f, "nc"), (&row("", 3, "1.25"), "mpf"));
    assert!(out.contains("spindle"), "{out}");
}

#[test]
fn rigid_tapping_from_a_turning_spindle_stays_refused_naming_the_difference() {
    let to_s = |body: &str| refused(&fanuc(body), "nc", "sinumerik");
    let err = to_s("S500 M3\nM29 S500\nG98 G84 X10. Y10. Z-16. R5. F625.\nX20.\nG80\n");
    assert!(err.contains("NC484") && err.contains("turning M3 before M29"), "{err}");
    assert!(err.contains("not settled") && err.contains("M5 before M29"), "{err}");
    let err = to_s("S500 M4\nM29 S500\nG98 G74 X10. Y10. Z-16. R5. F625.\nG80\n");
    assert!(err.contains("NC484") && err.contains("turning M4"), "{err}");
    // Reached by a jump: the state before M29 is not known.
    let err = to_s("M5\nGOTO10\nN5 S500 M3\nN10 M29 S500\nG98 G84 X10. Y10. Z-16. R5. F625.\nG80\n");
    assert!(err.contains("NC484") && err.contains("not known here"), "{err}");

    let to_f = |body: &str| refused(&sinumerik(body), "mpf", "fanuc");
    let err = to_f("S500 M3\nMCALL CYCLE84(50, 0, 5, -16, , , 3, 8, , , 500)\nX10 Y10\nX20\nMCALL\n");
    assert!(err.contains("NC487") && err.contains("turning M3 before it"), "{err}");
    let err = to_f("S500 M4\nMCALL CYCLE84(50, 0, 5, -16, , , 4, -8, , , 500)\nX10 Y10\nMCALL\n");
    assert!(err.contains("NC487") && err.contains("turning M4"), "{err}");
    // Stopped before but started after each hole.
    let err = to_f("M5\nMCALL CYCLE84(50, 0, 5, -16, , , 3, 8, , , 500)\nX10 Y10\nMCALL\n");
    assert!(err.contains("NC487") && err.contains("SDAC 3"), "{err}");
}

#[test]
fn the_fanuc_run_warns_where_its_trace_rests_on_an_unsettled_spindle() {
    let warned = |body: &str| {
        let r = run_text("tspin-warn.nc", &fanuc(body), &[]);
        r.outcome.diags.iter().filter(|d| d.code == "NC592").count()
    };
    // Once per cycle, however many holes.
    assert_eq!(warned("S500 M3\nM29 S500\nG98 G84 X10. Y10. Z-16. R5. F625.\nX20.\nX30.\nG80\n"), 1);
    assert_eq!(
        warned("S500 M3\nM29 S500\nG98 G84 X10. Y10. Z-16. R5. F625.\nG80\nM29 S500\nG84 X20. Y10. Z-16. R5.\nG80\n"),
        2
    );
    // The settled forms: a stopped spindle, floating tapping.
    assert_eq!(warned(F_ROW), 0);
    assert_eq!(warned("S500 M3\nG98 G84 X10. Y10. Z-16. R5. F625.\nG80\n"), 0);
}

/// `check` of programs whose traces rest on that assumption is never "equivalent".
#[test]
fn a_check_resting_on_a_rigid_tap_from_a_turning_spindle_is_inconclusive() {
    let a = scratch("nc", &fanuc("S500 M3\nM29 S500\nG98 G84 X10. Y10. Z-16. R5. F625.\nX20.\nG80\n"));
    let (code, out, err) = nctrans(&["check", &a, &a]);
    assert_eq!(code, 4, "{out}{err}");
    assert!(out.contains("inconclusive") && out.contains("NC592"), "{out}{err}");
    // From a stopped spindle the same check is equivalent.
    let b = scratch("nc", &fanuc(F_ROW));
    let (code, out, err) = nctrans(&["check", &b, &b]);
    assert_eq!(code, 0, "{out}{err}");
}
