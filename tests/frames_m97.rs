//! Haas `M97` local subprograms under the frame modes (G68 rotation, G16 polar coordinates),
//! FANUC/Haas → Sinumerik: the modes in force at a call run on in its section and the
//! section's modes at its M99 come back to that call, so each translation here is proven
//! equivalent (translate + verify with the Haas NGC profile) and a planted wrong one is
//! caught; a section whose frame code or polar move reads a mode that differs between its
//! calls is still refused (NC497).

#[path = "support/cli_run.rs"]
mod cli_run;

use cli_run::{nctrans, workdir};
use std::path::{Path, PathBuf};

const PROFILE: &str = "[fanuc]\nseries = \"haas-ngc\"\n";

/// Two slots, the same local subprogram milled under a rotation of 30° and one of 150°;
/// a third pass twice under one rotation without a cancel between the calls.
const ROTATED_SLOTS: &str = "%
O1000 (SLOTS UNDER G68 FROM A LOCAL SUB)
G00 G17 G40 G49 G80 G90
G54
T1 M06
S3000 M03
G00 X0. Y0. Z50.
G68 X0. Y0. R30.
M97 P100
G69
G68 X0. Y0. R150.
M97 P100
G69
G68 X10. Y10. R-45.
M97 P100
M97 P100
G69
G00 X0. Y0. Z50.
M30
N100 G00 X40. Y0.
G00 Z2.
G01 Z-3. F200.
G01 X60. F400.
Y8.
X40.
Y0.
G00 Z50.
M99
%
";

/// Bolt circles: a section that selects G16 itself (two radii), and one run in the G16
/// mode its call is made in, three passes turning the angle.
const BOLT_CIRCLES: &str = "%
O1001 (BOLT CIRCLES IN LOCAL SUBS)
G00 G17 G40 G49 G80 G90
#1=0.
#2=0.
G54
T2 M06
S1500 M03
G00 X0. Y0. Z50.
#1=30.
M97 P200
#1=45.
M97 P200
#2=0.
G16
M97 P300 L3
G15
G00 X0. Y0. Z50.
M30
N200 G16
G00 X#1 Y0.
G01 Z-2. F100.
G00 Z2.
G00 X#1 Y120.
G01 Z-2.
G00 Z2.
G15
M99
N300 G00 X60. Y#2
G01 Z-4. F100.
G00 Z2.
#2=#2+120.
M99
%
";

/// A section that cancels the rotation it is called under: a new G68 after the call is
/// made with none in force; and a bolt pattern by a section that sets and cancels its own
/// rotation each pass (`L4`, the angle turned by a variable).
const SECTION_CANCELS: &str = "%
O1002 (LOCAL SUB ENDS THE ROTATION)
G00 G17 G40 G49 G80 G90
#3=0.
G54
T3 M06
S2500 M03
G00 X0. Y0. Z50.
G68 X0. Y0. R60.
M97 P400
G68 X5. Y0. R-30.
G00 X20. Y0.
G01 Z-1. F150.
G00 Z50.
G69
#3=0.
M97 P500 L4
G00 X0. Y0. Z50.
M30
N400 G00 X30. Y0.
G01 Z-2. F150.
G00 Z50.
G69
M99
N500 G68 X0. Y0. R#3
G00 X25. Y0.
G01 Z-2. F150.
G00 Z5.
G69
#3=#3+90.
M99
%
";

fn setup(name: &str, text: &str) -> PathBuf {
    let d = workdir("frames-m97", name);
    std::fs::write(d.join("nctrans.toml"), PROFILE).unwrap();
    std::fs::write(d.join("O1000.nc"), text).unwrap();
    d
}

/// The Sinumerik translation with the verifier's verdict on stderr.
fn translate(d: &Path) -> (String, String, i32) {
    let (_, err, code) = nctrans(d, &["--to", "sinumerik", "O1000.nc", "-o", "o.mpf"]);
    (std::fs::read_to_string(d.join("o.mpf")).unwrap_or_default(), err, code)
}

fn check(d: &Path, text: &str) -> (String, i32) {
    std::fs::write(d.join("planted.mpf"), text).unwrap();
    let (out, err, code) = nctrans(d, &["check", "O1000.nc", "planted.mpf"]);
    (format!("{out}{err}"), code)
}

/// Translates, asserts it verified and that the checker agrees on its own; the text.
fn proven(name: &str, src: &str) -> (PathBuf, String) {
    let d = setup(name, src);
    let (text, err, code) = translate(&d);
    assert_eq!(code, 0, "{name}: {err}");
    assert!(err.contains("equivalent"), "{name}: {err}");
    let (out, code) = check(&d, &text);
    assert_eq!(code, 0, "{name}: {out}\n{text}");
    (d, text)
}

fn has_line(text: &str, line: &str) -> bool {
    text.lines().any(|l| l.trim() == line)
}

#[test]
fn a_section_milled_under_two_rotations_is_proven_and_a_wrong_angle_caught() {
    let (d, text) = proven("rotated", ROTATED_SLOTS);
    for line in ["AROT RPL=30", "AROT RPL=-30", "AROT RPL=150", "AROT RPL=-150", "REPEAT LSUB_100 LSUB_E1 P=1"] {
        assert!(has_line(&text, line), "missing `{line}` in\n{text}");
    }
    // The second G69 turns back by the second angle: planting the first is caught.
    let wrong = text.replacen("AROT RPL=-150", "AROT RPL=-30", 1);
    assert_ne!(wrong, text);
    let (out, code) = check(&d, &wrong);
    assert_ne!(code, 0, "a wrong cancel must diverge: {out}");
    // Dropping the rotation of the second call is caught too.
    let unrotated = text.replacen("AROT RPL=150\n", "", 1);
    assert_ne!(unrotated, text);
    let (out, code) = check(&d, &unrotated);
    assert_ne!(code, 0, "an unrotated section must diverge: {out}");
}

#[test]
fn g16_bolt_circles_in_sections_are_proven_and_a_wrong_angle_caught() {
    let (d, text) = proven("bolts", BOLT_CIRCLES);
    // The section's polar moves in polar words, in either form of the mode.
    for line in ["G0 RP=LOC1 AP=120", "N300 G0 RP=60 AP=LOC2", "REPEAT LSUB_300 LSUB_E2 P=3"] {
        assert!(has_line(&text, line), "missing `{line}` in\n{text}");
    }
    let wrong = text.replacen("AP=120", "AP=210", 1);
    assert_ne!(wrong, text);
    let (out, code) = check(&d, &wrong);
    assert_ne!(code, 0, "a wrong polar angle must diverge: {out}");
}

#[test]
fn a_section_that_cancels_the_frame_leaves_none_in_force_after_its_call() {
    let (d, text) = proven("cancels", SECTION_CANCELS);
    assert!(has_line(&text, "AROT RPL=-60"), "{text}");
    // Without the section's cancel the next rotation would add to 60°: caught.
    let kept = text.replacen("AROT RPL=-60\n", "", 1);
    assert_ne!(kept, text);
    let (out, code) = check(&d, &kept);
    assert_ne!(code, 0, "a rotation left in force must diverge: {out}");
}

fn refused(name: &str, text: &str, code: &str, line: &str) {
    let d = setup(name, text);
    let (_, err, rc) = translate(&d);
    assert_ne!(rc, 0, "{name}: {err}");
    assert!(err.contains(code), "{name}: expected {code} in {err}");
    assert!(err.contains(line), "{name}: expected the refusal at `{line}` in {err}");
}

#[test]
fn a_section_whose_mode_differs_between_its_calls_is_refused() {
    // The section cancels whichever rotation its call is made in, over a G52 shift: the
    // frame cannot be written anew without it, nor turned back by one angle.
    refused(
        "two-rotations-shifted",
        "O1000\nG00 G90 G17 X0. Y0.\nG52 X10. Y0. Z0.\nG68 X0. Y0. R30.\nM97 P100\nG68 X0. Y0. R60.\nM97 P100\n\
         G52 X0. Y0. Z0.\nM30\nN100 G00 X10. Y0.\nG69\nM99\n",
        "NC497",
        "G69",
    );
    // Polar moves in a section called once in G16 mode and once not.
    refused(
        "polar-or-not",
        "O1000\nG00 G90 G17 X0. Y0.\nG16\nM97 P100\nG15\nM97 P100\nM30\nN100 G01 X20. Y45. F100.\nM99\n",
        "NC497",
        "G01 X20. Y45.",
    );
    // A section that leaves a rotation in force, called with a computed count (none or
    // some passes), in a called program (whose frame under the rotation is its caller's).
    refused(
        "computed-count-called",
        "O1000\nG00 G90 G17 X0. Y0.\n#5=2.\nM97 P100 L#5\nG69\nM99\nN100 G68 X0. Y0. R10.\nG00 X10. Y0.\nM99\n",
        "NC497",
        "G69",
    );
}

/// A G69 in a section called under two rotations, and one after a computed count of a
/// section that sets one (no pass or some): over an empty programmable frame the cancel
/// writes the frame anew (bare TRANS), whichever rotation was in force.
#[test]
fn a_g69_undoing_whichever_rotation_writes_the_frame_anew() {
    let (d, text) = proven(
        "two-rotations",
        "O1000\nG00 G90 G17 X0. Y0.\nG68 X0. Y0. R30.\nM97 P100\nG68 X5. Y0. R60.\nM97 P100\nG00 X0. Y0.\nM30\n\
         N100 G00 X10. Y0.\nG69\nG00 X20. Y0.\nM99\n",
    );
    assert!(has_line(&text, "TRANS"), "{text}");
    // Without the reset the second call leaves its rotation: caught.
    let kept = text.replacen("\nTRANS\n", "\n", 1);
    assert_ne!(kept, text);
    let (out, code) = check(&d, &kept);
    assert_ne!(code, 0, "a rotation left in force must diverge: {out}");
    let (d, text) = proven(
        "computed-count",
        "O1000\nG00 G90 G17 X0. Y0.\n#5=2.\nM97 P100 L#5\nG69\nG00 X5. Y0.\nM30\n\
         N100 G68 X0. Y0. R10.\nG00 X10. Y0.\nM99\n",
    );
    assert!(has_line(&text, "TRANS"), "{text}");
    let kept = text.replacen("\nTRANS\n", "\n", 1);
    assert_ne!(kept, text);
    let (out, code) = check(&d, &kept);
    assert_ne!(code, 0, "a rotation left in force must diverge: {out}");
}

/// A section that does not read the mode may be called in different ones: each call comes
/// back with its own.
#[test]
fn a_section_that_does_not_read_the_mode_may_be_called_in_different_ones() {
    proven(
        "mode-free",
        "O1000\nG00 G90 G17 X0. Y0. Z50.\nG68 X0. Y0. R90.\nM97 P100\nG69\nM97 P100\nG00 X0. Y0.\nM30\n\
         N100 G00 X10. Y5.\nG01 Z-1. F100.\nG00 Z50.\nM99\n",
    );
}

/// `G52 Z0.` before any XY shift keeps an XY shift of 0, which TRANS (the whole shift) keeps
/// too; after a section shifted XY it would delete that shift, and is refused (NC442).
#[test]
fn a_g52_that_keeps_only_unshifted_axes_translates() {
    let src = "O1000\nG00 G90 G17 X0. Y0. Z50.\nG52 Z0.\n#1=0.\nM97 P100 L3\nG52 X0. Y0. Z0.\nG00 X0. Y0.\nM30\n\
               N100 G52 X[20.*COS[#1]] Y[20.*SIN[#1]] Z0.\nG00 X0. Y0.\nG01 Z-1. F100.\nG00 Z5.\n#1=#1+120.\nM99\n";
    let (d, text) = proven("g52-z", src);
    assert!(has_line(&text, "TRANS"), "{text}");
    // The section's shift planted without its Y word is caught.
    let wrong = text.replacen(" Y=20*SIN(LOC1)", "", 1);
    assert_ne!(wrong, text);
    let (out, code) = check(&d, &wrong);
    assert_ne!(code, 0, "a shift without its Y must diverge: {out}");
    refused(
        "g52-z-after-xy",
        "O1000\nG00 G90 G17 X0. Y0. Z50.\nM97 P100\nG52 Z0.\nG00 X0. Y0.\nM30\nN100 G52 X5. Y5. Z0.\nG00 X0. Y0.\nM99\n",
        "NC442",
        "G52 Z0.",
    );
}
