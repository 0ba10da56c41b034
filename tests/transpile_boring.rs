//! Boring both ways where the motion is the same: FANUC G85 ↔ CYCLE85 (FFR = RFF), G89 ↔
//! CYCLE89 and CYCLE85 with a dwell, G88 ↔ CYCLE88 (and CYCLE87, no dwell) with SDIR the
//! spindle's direction; where it differs (G86 stops the spindle without a program stop, G76
//! and CYCLE86 shift by machine data or by program, G87 bores upward) the translation is an
//! error naming the difference. Each translation is verified; planted wrong dwells and
//! feeds are caught.

mod eval_support;

use eval_support::{nctrans, scratch_file};

fn scratch(ext: &str, text: &str) -> String {
    scratch_file("tbore", ext, text)
}

fn fanuc(body: &str) -> String {
    format!("%\nO1\nG21 G17 G90 G94\nG54 G0 X0 Y0\nT1 M6\nG0 Z50.\n{body}M30\n%\n")
}

fn sinumerik(body: &str) -> String {
    format!("G17 G90 G94 G54\nG0 X0 Y0\nT1 D1 M6\nG0 Z50\n{body}M30\n")
}

fn translate(src: &str, ext: &str, to: &str) -> (String, Vec<String>) {
    let p = scratch(ext, src);
    let out_ext = if to == "fanuc" { "nc" } else { "mpf" };
    let out = scratch(out_ext, "");
    let (code, _, err) = nctrans(&[&p, "--to", to, "-o", &out, "--force"]);
    assert_eq!(code, 0, "{src}\n{err}");
    assert!(err.contains("equivalent"), "{err}");
    let text = std::fs::read_to_string(&out).expect("translation");
    (p, text.lines().map(str::to_string).collect())
}

fn refused(src: &str, ext: &str, to: &str) -> String {
    let p = scratch(ext, src);
    let (code, _, err) = nctrans(&[&p, "--to", to]);
    assert_ne!(code, 0, "{src}\n{err}");
    err
}

/// `nctrans check` of `src` against its translation with `from` replaced by `to`.
fn planted(src: &str, lines: &[String], ext: &str, from: &str, to: &str) -> i32 {
    let text = lines.join("\n") + "\n";
    assert!(text.contains(from), "{from} not in\n{text}");
    let bad = scratch(ext, &text.replacen(from, to, 1));
    nctrans(&["check", src, &bad]).0
}

#[test]
fn g88_becomes_cycle88_with_the_spindle_direction() {
    let (src, t) = translate(&fanuc("S450 M3\nG98 G88 X10. Y10. Z-12. R2. P1000 F50.\nX20.\nG80\n"), "nc", "sinumerik");
    assert!(t.iter().any(|l| l == "MCALL CYCLE88($P_EP[Z],2,0,-12,,1,3)"), "{t:?}");
    assert_ne!(
        planted(&src, &t, "mpf", "CYCLE88($P_EP[Z],2,0,-12,,1,3)", "CYCLE88($P_EP[Z],2,0,-12,,1.5,3)"),
        0,
        "dwell"
    );
    let (_, t) = translate(&fanuc("S450 M4\nG99 G88 X10. Y10. Z-12. R2. F50.\nG80\n"), "nc", "sinumerik");
    assert!(t.iter().any(|l| l == "MCALL CYCLE88(2,2,0,-12,,0,4)"), "{t:?}");
    let err = refused(&fanuc("G98 G88 X10. Y10. Z-12. R2. F50.\nG80\n"), "nc", "sinumerik");
    assert!(err.contains("NC428") && err.contains("not known to turn"), "{err}");
}

#[test]
fn boring_cycles_whose_motion_differs_are_refused_naming_the_difference() {
    let to_s = |body: &str| refused(&fanuc(&format!("S450 M3\n{body}G80\n")), "nc", "sinumerik");
    let e = to_s("G98 G86 X10. Y10. Z-12. R2. F50.\n");
    assert!(e.contains("G86 stops the spindle and rapids out"), "{e}");
    let e = to_s("G98 G76 X10. Y10. Z-12. R2. Q0.2 F50.\n");
    assert!(e.contains("machine parameter") && e.contains("CYCLE86"), "{e}");
    let e = to_s("G98 G87 X10. Y10. Z-2. R-14. Q1. F50.\n");
    assert!(e.contains("bores upward"), "{e}");
    let e = refused(&sinumerik("S450 M3\nCYCLE86(50, 0, 2, -25, , 0.1, 3, -0.2, 0, 0, 0)\n"), "mpf", "fanuc");
    assert!(e.contains("NC390") && e.contains("RPA/RPO/RPAP"), "{e}");
}

#[test]
fn cycle85_becomes_g85_or_g89_with_its_feed() {
    let (src, t) = translate(
        &sinumerik("S350 M3\nF200\nMCALL CYCLE85(2, 0, 2, -22, , 0, 70, 70)\nX10 Y10\nX20\nMCALL\nG1 X0\n"),
        "mpf",
        "fanuc",
    );
    assert!(t.iter().any(|l| l == "G99 G85 X10. Y10. Z-22. R2. F70."), "{t:?}");
    // G85's F is modal in FANUC: the feed before the cycle comes back after G80.
    assert!(t.iter().any(|l| l == "G80 F200."), "{t:?}");
    assert_ne!(planted(&src, &t, "nc", "R2. F70.", "R2. F80."), 0, "feed");
    assert_ne!(planted(&src, &t, "nc", "G80 F200.", "G80"), 0, "feed after the cycle");
    let (_, t) = translate(&sinumerik("S350 M3\nF200\nCYCLE85(50, 0, 2, -22, , 0.5, 70, 70)\n"), "mpf", "fanuc");
    assert!(t.iter().any(|l| l == "G98 G89 Z-22. R2. P500 F70."), "{t:?}");
    let e = refused(&sinumerik("S350 M3\nF200\nCYCLE85(50, 0, 2, -22, , 0, 70, 200)\n"), "mpf", "fanuc");
    assert!(e.contains("NC391") && e.contains("RFF"), "{e}");
}

#[test]
fn cycle87_and_cycle88_become_g88() {
    let (src, t) =
        translate(&sinumerik("S450 M3\nF50\nMCALL CYCLE88(50, 0, 2, -12, , 1, 3)\nX10 Y10\nMCALL\n"), "mpf", "fanuc");
    assert!(t.iter().any(|l| l == "G98 G88 X10. Y10. Z-12. R2. P1000"), "{t:?}");
    assert_ne!(planted(&src, &t, "nc", "P1000", "P800"), 0, "dwell");
    let (_, t) = translate(&sinumerik("S450 M4\nF50\nCYCLE87(2, 0, 2, -12, , 4)\n"), "mpf", "fanuc");
    assert!(t.iter().any(|l| l == "G99 G88 Z-12. R2."), "{t:?}");
    // SDIR other than the spindle's: the Sinumerik cycle would start it the other way.
    let e = refused(&sinumerik("S450 M3\nF50\nCYCLE87(2, 0, 2, -12, , 4)\n"), "mpf", "fanuc");
    assert!(e.contains("NC391") && e.contains("SDIR"), "{e}");
}
