//! Tapping both ways: FANUC rigid tapping (`M29 S` + G84/G74) ↔ Sinumerik CYCLE84, floating
//! G84/G74 ↔ CYCLE840 without an encoder; the hand from the G code / the pitch's sign / the
//! spindle direction as each control defines it; pitch = F/S per minute, F per revolution.
//! Every translation is verified by running both; a planted wrong pitch, hand or rigid /
//! floating choice is caught; CYCLE840's direction parameters are checked as the manual says.

mod eval_support;

use eval_support::*;

fn scratch(ext: &str, text: &str) -> String {
    scratch_file("ttap", ext, text)
}

/// Spindle stopped after the tool change (rigid tapping needs it so); the tool's length from
/// its edge on both sides (G43 H1 / D1), so the heads compare equal in `check`.
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

#[test]
fn rigid_g84_and_g74_become_cycle84_with_the_pitch_and_speed() {
    let t = translate(&fanuc("M29 S400\nG98 G84 X10. Y10. Z-16. R5. F500.\nX20.\nG80\n"), "nc", "sinumerik");
    assert!(t.iter().any(|l| l == "MCALL CYCLE84($P_EP[Z],5,0,-16,,0,5,,1.25,,400)"), "{t:?}");
    assert!(t.iter().any(|l| l.contains("S400")), "the tapping speed stays the modal S: {t:?}");
    assert!(!t.iter().any(|l| l.contains("M29")), "{t:?}");
    // G74: the pitch is negative (left hand); a lead that is not a round quotient stays F/S.
    let t = translate(&fanuc("M29 S300\nG99 G74 X10. Y10. Z-16. R5. F500.\nG80\n"), "nc", "sinumerik");
    assert!(t.iter().any(|l| l == "MCALL CYCLE84(5,5,0,-16,,0,5,,-(500/300),,300)"), "{t:?}");
    // Per revolution the lead is F itself.
    let t = translate(&fanuc("G95\nM29 S400\nG98 G84 X10. Y10. Z-16. R5. F1.25\nG80\nG94\n"), "nc", "sinumerik");
    assert!(t.iter().any(|l| l == "MCALL CYCLE84($P_EP[Z],5,0,-16,,0,5,,1.25,,400)"), "{t:?}");
}

#[test]
fn floating_g84_and_g74_become_cycle840_without_an_encoder() {
    let t = translate(&fanuc("S300 M3\nG98 G84 X10. Y10. Z-16. R5. P200 F450.\nG80\n"), "nc", "sinumerik");
    assert!(t.iter().any(|l| l == "MCALL CYCLE840($P_EP[Z],5,0,-16,,0.2,4,3,1)"), "{t:?}");
    let t = translate(&fanuc("S300 M4\nG99 G74 X10. Y10. Z-16. R5. F450.\nG80\n"), "nc", "sinumerik");
    assert!(t.iter().any(|l| l == "MCALL CYCLE840(5,5,0,-16,,0,3,4,1)"), "{t:?}");
}

#[test]
fn fanuc_tapping_the_sinumerik_side_cannot_match_is_refused() {
    let to_s = |body: &str| refused(&fanuc(body), "nc", "sinumerik");
    assert!(to_s("S300 M4\nG84 X10. Y10. Z-16. R5. F450.\nG80\n").contains("NC484"));
    assert!(to_s("G84 X10. Y10. Z-16. R5. F450.\nG80\n").contains("spindle stopped"));
    assert!(to_s("S400 M3\nM29 S400\nG84 X10. Y10. Z-16. R5. F500.\nG80\n").contains("NC484"));
    // One refused cycle, however many holes it drills: one diagnostic.
    let err = to_s("S400 M3\nM29 S400\nG84 X10. Y10. Z-16. R5. F500.\nX20.\nX30.\nG80\n");
    assert_eq!(err.matches("error[NC484]").count(), 1, "{err}");
    assert!(to_s("M29\nG84 X10. Y10. Z-16. R5. F500.\nG80\n").contains("NC483"));
    assert!(to_s("M29 S400\nG81 X10. Y10. Z-16. R5. F500.\nG80\n").contains("M29"));
    assert!(to_s("G84 X10. Y10. Z-16. R5. F500. M29\nG80\n").contains("M29 in a drilling-cycle block"));
}

#[test]
fn cycle84_and_cycle840_become_fanuc_tapping() {
    let t =
        translate(&sinumerik("MCALL CYCLE84(50, 0, 5, -16, , , 5, 8, , , 400)\nX10 Y10\nX20\nMCALL\n"), "mpf", "fanuc");
    let k = t.iter().position(|l| l == "M29 S400").expect("M29 before the cycle");
    assert_eq!(t[k + 1], "G98 G84 X10. Y10. Z-16. R5. F500.");
    let t = translate(
        &sinumerik("F200\nMCALL CYCLE84(5, 0, 5, -16, , , 5, -10, , , 200)\nX10 Y10\nMCALL\nG1 X0\n"),
        "mpf",
        "fanuc",
    );
    assert!(t.iter().any(|l| l == "G99 G74 X10. Y10. Z-16. R5. F300."), "{t:?}");
    // G84's F is modal in FANUC: the feed before the cycle is written again.
    assert!(t.iter().any(|l| l == "G80 F200."), "{t:?}");
    let t = translate(
        &sinumerik("S300 M3\nF450\nMCALL CYCLE840(50, 0, 5, -16, , 0.2, 4, 3, 1)\nX10 Y10\nMCALL\n"),
        "mpf",
        "fanuc",
    );
    assert!(t.iter().any(|l| l == "G98 G84 X10. Y10. Z-16. R5. P200"), "{t:?}");
    let t = translate(&sinumerik("S300 M4\nF450\nCYCLE840(50, 0, 5, -16, , , 3, 4, 1)\n"), "mpf", "fanuc");
    assert!(t.iter().any(|l| l == "G98 G74 Z-16. R5."), "{t:?}");
}

#[test]
fn sinumerik_tapping_fanuc_cannot_say_is_refused() {
    let to_f = |body: &str| refused(&sinumerik(body), "mpf", "fanuc");
    // With an encoder the feed follows the spindle (G33): no FANUC cycle does that.
    assert!(to_f("S300 M3\nCYCLE840(50, 0, 5, -16, , , 0, 3, 0, , 1.5)\n").contains("NC488"));
    // Without an encoder but with a pitch the feed is pitch × S, not FANUC's modal F.
    assert!(to_f("S300 M3\nF450\nCYCLE840(50, 0, 5, -16, , , 4, 3, 1, , 1.5)\n").contains("NC488"));
    // Rigid tapping with the spindle turning.
    assert!(to_f("S300 M3\nCYCLE84(50, 0, 5, -16, , , 3, 8, , , 400)\n").contains("NC487"));
    // An oriented start (POSS) and a retract speed (SST1) have no FANUC word.
    assert!(to_f("CYCLE84(50, 0, 5, -16, , , 5, 8, , 90, 400)\n").contains("NC391"));
}

#[test]
fn floating_tapping_from_the_r_plane_with_a_computed_speed_is_verified() {
    // A shop template's shape: the speed computed from a cutting speed and a diameter, the
    // tool put at the R plane, then G98 (back to the initial level, which is R).
    let src = fanuc(
        "#2=6.\n#3=3.\n#4=1.5\n#5=12.\n#10=#2*1000./3.14159/#5\nS#10 M3\nG0 Z#3\n\
         G84 G98 Z-20. F[#10*#4] R#3\nG80 Z#3\n",
    );
    let t = translate(&src, "nc", "sinumerik");
    // One hole where the tool stands, then G80: a direct call, no MCALL around it.
    let k = t.iter().position(|l| l.starts_with("CYCLE840(")).expect("a CYCLE840");
    assert_eq!(t[k], "CYCLE840($P_EP[Z],LOC3,0,-20,,0,4,3,1)", "{t:?}");
    assert!(!t.iter().any(|l| l.starts_with("MCALL")), "{t:?}");
    // The trace names the level the tool returns to: R, on both sides.
    let r = run_text("ttap-rplane.nc", &src, &[]);
    let holes: Vec<String> = bare_lines(&r).into_iter().filter(|l| l.starts_with("cycle tap ")).collect();
    assert_eq!(holes.len(), 1);
    assert!(holes[0].contains(" r=3 ") && holes[0].contains("retract=r "), "{holes:?}");
    // Planted: from a tool standing above R, G98 goes back up; a translation that stops at
    // R (RTP = RFP + SDIS) is caught at the retract level.
    let high = fanuc("S300 M3\nG0 Z10.\nG98 G84 X10. Y10. Z-16. R5. F450.\nG80\n");
    let good = sinumerik("S300 M3\nG0 Z10\nF450\nMCALL CYCLE840(10, 5, 0, -16, , , 4, 3, 1)\nX10 Y10\nMCALL\n");
    assert_eq!(check((&high, "nc"), (&good, "mpf")).0, 0);
    let bad = sinumerik("S300 M3\nG0 Z10\nF450\nMCALL CYCLE840(5, 5, 0, -16, , , 4, 3, 1)\nX10 Y10\nMCALL\n");
    let (code, out) = check((&high, "nc"), (&bad, "mpf"));
    assert_ne!(code, 0, "a wrong retract level was not caught:\n{out}");
    assert!(out.contains("retract=initial") && out.contains("retract=r"), "{out}");
}

/// A Haas NGC translation to Sinumerik: its exit code, output and messages.
fn haas(src: &str) -> (i32, String, String) {
    let cfg = scratch("toml", "[fanuc]\nseries = \"haas-ngc\"\n");
    let p = scratch("nc", src);
    nctrans(&[&p, "--to", "sinumerik", "--config", &cfg])
}

fn errors(err: &str) -> Vec<String> {
    err.lines().filter_map(|l| l.strip_prefix("error[")).map(|l| l[..5].to_string()).collect()
}

#[test]
fn a_haas_m97_tapping_body_is_analysed_from_its_callers() {
    // The tapping of a Haas template's local subprogram (after M30, reached by M97 only):
    // its speed and planes are set in the body before the cycle, so the spindle turns M3
    // there and no word needs a vacancy test: it translates (M97 as a REPEAT section) and
    // is proven.
    let body = "#1=-25.\n#2=500.\n#3=5.\n#4=1.\nS[#2] M03\nG00 Z[#3] M08\n\
                G84 G98 Z[#1] F[#2*#4] R[#3]\nG80 Z[#3] M09\nM99\n";
    let src = format!("{F_HEAD}M97 P15\nM30\nN15\n{body}%\n");
    let (code, out, err) = haas(&src);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
    assert!(out.contains("\nCYCLE840(") && !out.contains("MCALL") && !out.contains("_SET"), "{out}");
    // A body that may leave #3 vacant: after the call the caller's R#3 is not known to be
    // set, and its cycle is refused (the vacant R would drop the word on the control).
    let src =
        format!("{F_HEAD}#3=5.\nS300 M3\nM97 P15\nG0 Z#3\nG84 G98 Z-16. F450. R#3\nG80\nM30\nN15\n#3=#0\nM99\n%\n");
    let (code, _, err) = haas(&src);
    assert_ne!(code, 0, "{err}");
    assert!(errors(&err).contains(&"NC428".to_string()), "{err}");
}

#[test]
fn a_jump_target_forgets_the_spindle_and_lands_before_the_cycle() {
    // Reached by the jump with M4, by the text above it with M3: the direction is not known
    // at N10 (before, CYCLE840 was written for M3 and its MCALL stood before the label, so
    // the jump skipped it).
    let err =
        refused(&fanuc("S300 M4\nGOTO10\nN5 S300 M3\nN10 G98 G84 X10. Y10. Z-16. R5. F450.\nG80\n"), "nc", "sinumerik");
    assert!(err.contains("NC484") && err.contains("not known"), "{err}");
    // Set again at the target: known, and the label comes before the cycle's F and MCALL.
    let t = translate(
        &fanuc("S300 M4\nGOTO10\nN5 S300 M4\nN10 G0 M3\nG98 G84 X10. Y10. Z-16. R5. F450.\nG80\n"),
        "nc",
        "sinumerik",
    );
    assert!(t.iter().any(|l| l.starts_with("MCALL CYCLE840(") && l.ends_with(",4,3,1)")), "{t:?}");
    let t = translate(
        &fanuc("S300 M3\nGOTO10\nN5 S300 M3\nN10 G98 G81 X10. Y10. Z-16. R5. F450.\nG80 G0\n"),
        "nc",
        "sinumerik",
    );
    let (l, m) = (t.iter().position(|l| l == "N10 LBL_10:"), t.iter().position(|l| l.starts_with("MCALL CYCLE81(")));
    assert!(l.is_some() && l < m && t[l.unwrap() + 1] == "F450", "{t:?}");
    // M29 armed above a jump target: what the jump brings is not rigid tapping.
    let err = refused(&fanuc("GOTO10\nM29 S400\nN10 G98 G84 X10. Y10. Z-16. R5. F500.\nG80\n"), "nc", "sinumerik");
    assert!(err.contains("NC590"), "{err}");
}

#[test]
fn cycle840_direction_parameters_are_checked_as_the_manual_says() {
    let codes = |body: &str| {
        let r = run_text("ttap-eval.mpf", &sinumerik(body), &[]);
        r.outcome.diags.iter().filter(|d| d.is_error()).map(|d| d.code.to_string()).collect::<Vec<_>>()
    };
    // Without an encoder the cycle cannot reverse by itself: SDR is needed.
    assert_eq!(codes("S300 M3\nF450\nCYCLE840(50, 0, 5, -16, , , 0, 3, 1)\n"), ["NC480"]);
    // SDR the same as the spindle's direction: the tap would not come out.
    assert_eq!(codes("S300 M3\nF450\nCYCLE840(50, 0, 5, -16, , , 3, 3, 1)\n"), ["NC481"]);
    assert_eq!(codes("S300 M3\nF450\nCYCLE840(50, 0, 5, -16, , , 4, 4, 1)\n"), ["NC482"]);
    // Without an encoder a given pitch sets the feed from the speed (pitch × S).
    let r = run_text("ttap-eval2.mpf", &sinumerik("S300 M3\nF450\nCYCLE840(50, 0, 5, -16, , , 4, 3, 1, , 1.5)\n"), &[]);
    let t = bare_lines(&r);
    assert!(t.iter().any(|l| l.starts_with("cycle tap ") && l.ends_with("f=450 tapping=floating")), "{t:?}");
}

#[test]
fn a_planted_wrong_pitch_hand_or_holder_is_caught() {
    let f = fanuc("M29 S400\nG98 G84 X10. Y10. Z-16. R5. F500.\nG80\n");
    let good = sinumerik("MCALL CYCLE84(50, 0, 5, -16, , , 5, , 1.25, , 400)\nX10 Y10\nMCALL\n");
    assert_eq!(check((&f, "nc"), (&good, "mpf")).0, 0);
    for (what, bad) in [
        ("pitch", "MCALL CYCLE84(50, 0, 5, -16, , , 5, , 1.5, , 400)\nX10 Y10\nMCALL\n"),
        ("hand", "MCALL CYCLE84(50, 0, 5, -16, , , 5, , -1.25, , 400)\nX10 Y10\nMCALL\n"),
    ] {
        let (code, out) = check((&f, "nc"), (&sinumerik(bad), "mpf"));
        assert_ne!(code, 0, "a wrong {what} was not caught:\n{out}");
    }
    // The same feed, the same spindle, another holder: rigid against floating.
    let rigid = fanuc("S400 M3\nM29 S400\nG98 G84 X10. Y10. Z-16. R5. F500.\nG80\n");
    let floating = fanuc("S400 M3\nG98 G84 X10. Y10. Z-16. R5. F500.\nG80\n");
    let (code, out) = check((&rigid, "nc"), (&floating, "nc"));
    assert_ne!(code, 0, "{out}");
    assert!(out.contains("tapping=rigid") && out.contains("tapping=floating"), "{out}");
    let rigid = sinumerik("S400 M3\nF500\nMCALL CYCLE84(50, 0, 5, -16, , , 3, 8, , , 400)\nX10 Y10\nMCALL\n");
    let floating = sinumerik("S400 M3\nF500\nMCALL CYCLE840(50, 0, 5, -16, , , 4, 3, 1)\nX10 Y10\nMCALL\n");
    assert_eq!(check((&floating, "mpf"), (&floating, "mpf")).0, 0);
    let (code, out) = check((&rigid, "mpf"), (&floating, "mpf"));
    assert_ne!(code, 0, "{out}");
}

#[test]
fn m29_must_arm_the_tapping_cycle_right_after_it() {
    let to_s = |body: &str| refused(&fanuc(body), "nc", "sinumerik");
    assert!(to_s("M29 S400\nG0 X5.\nG84 X10. Y10. Z-16. R5. F500.\nG80\n").contains("a move between M29"));
    assert!(to_s("M29 S400\n").contains("M29 without a tapping cycle"));
    // G80 ends rigid tapping: the next G84 is floating (CYCLE840), which needs the spindle.
    let t = translate(
        &fanuc("M29 S400\nG98 G84 X10. Y10. Z-16. R5. F500.\nG80\nS400 M3\nG98 G84 X20. Y10. Z-16. R5.\nG80\nM5\n"),
        "nc",
        "sinumerik",
    );
    assert!(t.iter().any(|l| l.starts_with("MCALL CYCLE84(")), "{t:?}");
    assert!(t.iter().any(|l| l.starts_with("MCALL CYCLE840(")), "{t:?}");
}

#[test]
fn the_feed_before_a_rigid_cycle_is_followed_through_hole_blocks() {
    // An F in a hole block of another cycle is the feed the rigid cycle's F must give back.
    let t = translate(
        &sinumerik(
            "F100\nMCALL CYCLE81(50, 0, 2, -5)\nX10 Y10 F150\nMCALL\nMCALL CYCLE84(50, 0, 5, -16, , , 5, 8, , , 400)\nX20 Y10\nMCALL\nG1 X0\n",
        ),
        "mpf",
        "fanuc",
    );
    assert!(t.iter().any(|l| l == "G80 F150."), "{t:?}");
}

#[test]
fn the_speed_block_before_cycle84_becomes_the_m29_block() {
    // `S400` just before the cycle is the speed M29 S400 sets; the modal F already is the
    // tapping feed, so the cycle block needs none (and a round trip does not grow).
    let t = translate(
        &sinumerik("F500\nS400\nMCALL CYCLE84(50, 0, 5, -16, , , 5, 8, , , 400)\nX10 Y10\nMCALL\n"),
        "mpf",
        "fanuc",
    );
    let k = t.iter().position(|l| l == "M29 S400").expect("M29");
    assert_eq!(t[k - 1], "F500.", "{t:?}");
    assert_eq!(t[k + 1], "G98 G84 X10. Y10. Z-16. R5.", "{t:?}");
    assert_eq!(t.iter().filter(|l| l.contains("S400")).count(), 1, "{t:?}");
}

#[test]
fn the_speed_of_m29_stays_right_before_cycle84_so_a_round_trip_comes_back() {
    // The cycle's F goes before the S of M29 S: the S right before CYCLE84 is the form the
    // way back takes into `M29 S` again, so the round trip is a fixed point.
    let t = translate(&fanuc("M29 S400\nG98 G84 X10. Y10. Z-16. R5. F500.\nG80\n"), "nc", "sinumerik");
    let k = t.iter().position(|l| l.starts_with("MCALL CYCLE84(")).expect("CYCLE84");
    assert_eq!((t[k - 2].as_str(), t[k - 1].as_str()), ("F500", "S400"), "{t:?}");
    let back = translate(&format!("{}\n", t.join("\n")), "mpf", "fanuc");
    let again = translate(&format!("{}\n", back.join("\n")), "nc", "sinumerik");
    let body = |x: &[String]| x.iter().filter(|l| !l.starts_with(';')).cloned().collect::<Vec<_>>();
    assert_eq!(body(&again), body(&t));
}

#[test]
fn rigid_tapping_in_inch_is_refused_until_the_unit_of_pit_is_settled() {
    // FANUC G20 rigid tapping: F/S is a lead in inch, which CYCLE84 would take as PIT.
    let inch = "%\nO1\nG20 G17 G90 G94\nG54 G0 X0 Y0\nT1 M6\nG43 H1\nG0 Z2.\nM29 S500\nG84 X1. Y1. Z-0.5 R0.2 F25.\nG80\nM30\n%\n";
    let err = refused(inch, "nc", "sinumerik");
    assert!(err.contains("NC591") && err.contains("inch"), "{err}");
    // The Sinumerik run refuses a PIT under G700 (and G70), not a metric MPIT.
    let pit = "G700 G17 G90 G94 G54\nG0 X0 Y0\nT1 D1 M6\nG0 Z2\nCYCLE84(2, 0.2, 0, -0.5, , , , , 0.05, , 500)\nM30\n";
    let r = run_text("ttap-inch.mpf", pit, &[]);
    let why: Vec<String> = r.outcome.diags.iter().map(|d| format!("{} {}", d.code, d.message)).collect();
    assert!(why.iter().any(|d| d.starts_with("NC423") && d.contains("PIT under G70/G700")), "{why:?}");
    let mpit = "G700 G17 G90 G94 G54\nG0 X0 Y0\nT1 D1 M6\nG0 Z2\nCYCLE84(2, 0.2, 0, -0.5, , , , 6, , , 500)\nM30\n";
    let r = run_text("ttap-mpit.mpf", mpit, &[]);
    assert!(!r.outcome.diags.iter().any(|d| d.code == "NC423"), "{:?}", r.outcome.diags);
}

// ---- The spindle around rigid tapping ----
// Rigid tapping and the spindle (issue 19): from a stopped spindle (M5 before `M29 S`,
// CYCLE84 with SDAC 5) both controls tap at the tapping speed and leave the spindle stopped,
// so a row of holes is translated both ways and proven; a planted wrong SDAC, a missing M5
// or a wrong pitch is caught; rigid tapping from a turning spindle stays refused, naming
// what no source settles (FANUC's M29 with the spindle turning and its state after the
// cycle), and the FANUC run warns where its trace rests on that (NC592).

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
