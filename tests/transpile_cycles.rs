//! Drilling cycles FANUC → Sinumerik: each translatable cycle becomes `MCALL CYCLEnn(…)`,
//! positions and `MCALL`, proven by running both; the cycles without an exact counterpart
//! are refused (NC428) naming the difference; and a translation planted wrong in any field
//! of the cycle (depth, R plane, peck, dwell, retract, feed) is caught by `nctrans check`.

mod eval_support;

use eval_support::{nctrans, root, scratch_file};

fn scratch(ext: &str, text: &str) -> String {
    scratch_file("tcycle", ext, text)
}

const HEAD: &str = "%\nO1\nG21 G17 G90\nG54 G0 X0 Y0\nT1 M6\nS1000 M3\nG0 Z50.\n";

fn fanuc(body: &str) -> String {
    format!("{HEAD}{body}M30\n%\n")
}

/// The verified translation's program lines (without the header comment).
fn translate(body: &str) -> Vec<String> {
    let src = scratch("nc", &fanuc(body));
    let (code, out, err) = nctrans(&[&src, "--to", "sinumerik"]);
    assert_eq!(code, 0, "{out}\n{err}");
    assert!(err.contains("equivalent"), "{err}");
    out.lines().filter(|l| !l.starts_with(';')).map(str::to_string).collect()
}

fn refused(body: &str) -> String {
    let src = scratch("nc", &fanuc(body));
    let (code, _, err) = nctrans(&[&src, "--to", "sinumerik"]);
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("NC428"), "{err}");
    err
}

#[test]
fn g81_under_g98_and_g99_becomes_mcall_cycle81() {
    let t = translate("G98 G81 X10. Y10. Z-5. R2. F100.\nX20.\nG99 Y20.\nG80\n");
    let from = t.iter().position(|l| l == "F100").expect("the feed before the MCALL");
    assert_eq!(
        t[from + 1..from + 7],
        ["MCALL CYCLE81($P_EP[Z],2,0,-5)", "G0 X10 Y10", "G0 X20", "MCALL CYCLE81(2,2,0,-5)", "G0 Y20", "MCALL",]
    );
}

#[test]
fn each_translatable_cycle_has_its_form() {
    let cases = [
        ("G98 G82 X10. Y10. Z-5. R2. P300 F100.\nG80\n", "MCALL CYCLE82($P_EP[Z],2,0,-5,,0.3)"),
        ("G98 G83 X10. Y10. Z-20. R1. Q4. F100.\nG80\n", "MCALL CYCLE83($P_EP[Z],1,0,-20,,,4,0,0,0,1,1)"),
        ("G98 G73 X10. Y10. Z-20. R1. Q2. F100.\nG80\n", "MCALL CYCLE83($P_EP[Z],1,0,-20,,,2,0,0,0,1,0)"),
        ("G99 G85 X10. Y10. Z-20. R2. F70.\nG80\n", "MCALL CYCLE85(2,2,0,-20,,0,$P_F,$P_F)"),
        ("G99 G89 X10. Y10. Z-8. R2. P400 F60.\nG80\n", "MCALL CYCLE89(2,2,0,-8,,0.4)"),
        // The decimal-point rule: Z-5000 is 5 mm, Q2000 2 mm.
        ("G98 G83 X10. Y10. Z-5000 R1000 Q2000 F100.\nG80\n", "MCALL CYCLE83($P_EP[Z],1,0,-5,,,2,0,0,0,1,1)"),
    ];
    for (body, call) in cases {
        let t = translate(body);
        assert!(t.iter().any(|l| l == call), "{body}: {t:?}");
    }
}

#[test]
fn a_variable_stays_an_expression_and_a_hole_without_position_is_a_direct_call() {
    let t = translate("#1=-12.\nG98 G81 X10. Y10. Z#1 R2. F100.\nZ[#1-3.]\nG80\n");
    assert!(
        t.iter().any(|l| l.starts_with("MCALL CYCLE81($P_EP[Z],2,0,") && l != "MCALL CYCLE81($P_EP[Z],2,0,-12)"),
        "{t:?}"
    );
    assert!(t.iter().any(|l| l.starts_with("CYCLE81($P_EP[Z],2,0,")), "{t:?}");
}

#[test]
fn repeats_become_position_blocks() {
    let t = translate("G99 G81 X10. Y10. Z-5. R2. F100. K3\nG80\n");
    assert_eq!(t.iter().filter(|l| *l == "G0 X10 Y10").count(), 3, "{t:?}");
}

#[test]
fn cycles_without_an_exact_counterpart_are_refused_naming_the_difference() {
    assert!(refused("G76 X10. Y10. Z-10. R2. Q0.2 F50.\nG80\n").contains("machine parameter"));
    assert!(refused("G86 X10. Y10. Z-10. R2. F50.\nG80\n").contains("also stops the program"));
    // G88 and CYCLE85/87/88 translate now: tests/transpile_boring.rs.
    // G91 cycle data translates now: tests/transpile_cycle_increments.rs.
    // G98 after G99 holes translates now: tests/transpile_cycle_increments.rs.
}

#[test]
fn a_translation_planted_wrong_in_any_field_is_caught() {
    let body = "G98 G83 X10. Y10. Z-20. R1. Q4. F120.\nX20.\nG80\nG99 G82 X30. Y10. Z-5. R2. P300\nG80\n";
    let src = scratch("nc", &fanuc(body));
    let out = scratch("mpf", "");
    let (code, _, err) = nctrans(&[&src, "--to", "sinumerik", "-o", &out, "--force"]);
    assert_eq!(code, 0, "{err}");
    let good = std::fs::read_to_string(&out).expect("translation");
    assert_eq!(nctrans(&["check", &src, &out]).0, 0);
    let plants = [
        ("depth", "CYCLE83($P_EP[Z],1,0,-20,", "CYCLE83($P_EP[Z],1,0,-21,"),
        ("R plane", "CYCLE83($P_EP[Z],1,0,-20,", "CYCLE83($P_EP[Z],1.5,0,-20,"),
        ("peck", ",,,4,0,0,0,1,1)", ",,,5,0,0,0,1,1)"),
        ("kind", ",,,4,0,0,0,1,1)", ",,,4,0,0,0,1,0)"),
        ("dwell", "CYCLE82(2,2,0,-5,,0.3)", "CYCLE82(2,2,0,-5,,0.4)"),
        ("retract", "CYCLE82(2,2,0,-5,,0.3)", "CYCLE82(10,2,0,-5,,0.3)"),
        ("feed", "F120", "F110"),
    ];
    for (what, from, to) in plants {
        assert!(good.contains(from), "{what}: {good}");
        let bad = scratch("mpf", &good.replacen(from, to, 1));
        let (code, report, _) = nctrans(&["check", &src, &bad]);
        assert_ne!(code, 0, "a wrong {what} was not caught:\n{report}");
        assert!(report.contains("diverged"), "{what}: {report}");
    }
}

const S_HEAD: &str = "G17 G90 G54\nT1 M6 D1\nS1000 M3\nG0 X0 Y0 Z50\nF100\n";

/// The verified FANUC translation of a Sinumerik program's body.
fn to_fanuc(body: &str) -> Vec<String> {
    let src = scratch("mpf", &format!("{S_HEAD}{body}M30\n"));
    let (code, out, err) = nctrans(&[&src, "--to", "fanuc"]);
    assert_eq!(code, 0, "{out}\n{err}");
    assert!(err.contains("equivalent"), "{err}");
    out.lines().filter(|l| !l.starts_with('(') && !l.starts_with('%')).map(str::to_string).collect()
}

fn refused_to_fanuc(body: &str) -> String {
    let src = scratch("mpf", &format!("{S_HEAD}{body}M30\n"));
    let (code, _, err) = nctrans(&[&src, "--to", "fanuc"]);
    assert_ne!(code, 0, "{err}");
    err
}

#[test]
fn mcall_cycles_become_a_fanuc_cycle_block_holes_and_g80() {
    let t = to_fanuc("MCALL CYCLE81(50, 0, 2, -5)\nG0 X10 Y10\nX20\nMCALL\n");
    let k = t.iter().position(|l| l.starts_with("G98 G81")).expect("cycle block");
    assert_eq!(t[k..k + 3], ["G98 G81 X10. Y10. Z-5. R2.", "X20.", "G80"]);
    // RTP = RFP + SDIS: G99; DTB in ms; CYCLE83 chip breaking is G73.
    let t = to_fanuc("MCALL CYCLE82(2, 0, 2, -5, , 0.3)\nG0 X10 Y10\nMCALL\n");
    assert!(t.iter().any(|l| l == "G99 G82 X10. Y10. Z-5. R2. P300"), "{t:?}");
    let t = to_fanuc("G0 X5 Y5\nCYCLE83(50, 1, 0, -20, , , 2, 0, 0, 0, 1, 0)\n");
    assert!(t.iter().any(|l| l == "G98 G73 Z-20. R1. Q2."), "{t:?}");
    // RTP between the tool and the R plane: positioned there first.
    let t = to_fanuc("G0 X5 Y5\nCYCLE89(10, 0, 2, -8, , 0.4)\n");
    let k = t.iter().position(|l| l == "G00 Z10.").expect("approach");
    assert_eq!(t[k + 1], "G98 G89 Z-8. R2. P400");
    // RTP the tool's level, which is the R plane: G98 from the R plane, the same holes.
    let t = to_fanuc("G0 Z2\nMCALL CYCLE81($P_EP[Z], 0, 2, -5)\nG0 X10 Y10\nX20\nMCALL\n");
    assert!(t.iter().any(|l| l == "G98 G81 X10. Y10. Z-5. R2."), "{t:?}");
}

#[test]
fn an_mcall_cycle_with_rtp_below_the_tool_positions_the_first_hole_then_approaches() {
    // The Sinumerik cycle goes to the hole at the tool's level, then down to RTP; FANUC's
    // initial level must be RTP, so the first hole is positioned, Z goes to RTP, and the
    // cycle block drills there (it once approached RTP at the previous position: caught).
    let body = "MCALL CYCLE81(10, 0, 2, -15)\nX10 Y10\nX30 Y10\nX30 Y30\nMCALL\n";
    let t = to_fanuc(body);
    let k = t.iter().position(|l| l == "X10. Y10.").expect("first hole positioned");
    assert_eq!(t[k..k + 6], ["X10. Y10.", "G00 Z10.", "G98 G81 Z-15. R2.", "X30. Y10.", "X30. Y30.", "G80"]);
    let src = scratch("mpf", &format!("{S_HEAD}{body}M30\n"));
    let good = scratch("nc", "");
    let (code, _, err) = nctrans(&[&src, "--to", "fanuc", "-o", &good, "--force"]);
    assert_eq!(code, 0, "{err}");
    let good = std::fs::read_to_string(&good).expect("translation");
    let early = good.replacen("X10. Y10.\nG00 Z10.\n", "G00 Z10.\nX10. Y10.\n", 1);
    assert_ne!(early, good);
    let (code, report, _) = nctrans(&["check", &src, &scratch("nc", &early)]);
    assert_ne!(code, 0, "an approach before the first hole was not caught:\n{report}");
}

#[test]
fn sinumerik_cycles_without_an_exact_fanuc_form_are_refused() {
    // Rigid tapping with the spindle turning (S_HEAD has M3): tests/transpile_tapping.rs.
    assert!(refused_to_fanuc("CYCLE84(50, 0, 2, -16, , , 3, 8, , , 400)\n").contains("NC487"));
    assert!(refused_to_fanuc("CYCLE82(50, 0, 2, -5, , 0.0005)\n").contains("NC392"));
    assert!(refused_to_fanuc("CYCLE81(80, 0, 2, -5)\n").contains("NC393"));
    assert!(refused_to_fanuc("MCALL CYCLE81(50, 0, 2, -5)\nG1 X10 Y10\nMCALL\n").contains("NC396"));
    assert!(refused_to_fanuc("CYCLE83(50, 0, 0, -20, , , 4, 1, 0, 0, 1, 1)\n").contains("NC391"));
}

#[test]
fn a_fanuc_translation_planted_wrong_is_caught() {
    let src = scratch(
        "mpf",
        &format!("{S_HEAD}MCALL CYCLE83(50, 1, 0, -20, , , 4, 0, 0, 0, 1, 1)\nG0 X10 Y10\nX20\nMCALL\nM30\n"),
    );
    let out = scratch("nc", "");
    let (code, _, err) = nctrans(&[&src, "--to", "fanuc", "-o", &out, "--force"]);
    assert_eq!(code, 0, "{err}");
    let good = std::fs::read_to_string(&out).expect("translation");
    assert!(good.contains("G98 G83 X10. Y10. Z-20. R1. Q4."), "{good}");
    for (what, to) in [
        ("depth", "G98 G83 X10. Y10. Z-21. R1. Q4."),
        ("R plane", "G98 G83 X10. Y10. Z-20. R1.5 Q4."),
        ("peck", "G98 G83 X10. Y10. Z-20. R1. Q3."),
        ("kind", "G98 G73 X10. Y10. Z-20. R1. Q4."),
        ("retract", "G99 G83 X10. Y10. Z-20. R1. Q4."),
        ("feed", "G98 G83 X10. Y10. Z-20. R1. Q4. F90."),
    ] {
        let bad = scratch("nc", &good.replacen("G98 G83 X10. Y10. Z-20. R1. Q4.", to, 1));
        let (code, report, _) = nctrans(&["check", &src, &bad]);
        assert_ne!(code, 0, "a wrong {what} was not caught:\n{report}");
    }
}

#[test]
fn a_streamed_translation_reads_a_cycle_program_whole() {
    // The streamed writer takes plain blocks one by one; hole blocks depend on the cycle
    // before them, so a program with a drilling cycle is translated whole, the same.
    let src = root().join("corpus/in/fanuc/cycle-g82-counterbore.nc").to_string_lossy().into_owned();
    let whole = nctrans(&[&src, "--to", "sinumerik"]);
    let streamed = nctrans(&[&src, "--to", "sinumerik", "--stream"]);
    assert_eq!(whole.0, 0, "{}", whole.2);
    assert_eq!(streamed.0, 0, "{}", streamed.2);
    assert_eq!(streamed.1, whole.1);
}

/// `G80` with other words after a cycle entered from G01: the `MCALL` stands alone (a G
/// code beside it does not read back), the motion mode follows in a block of its own.
#[test]
fn g80_with_other_words_writes_mcall_alone_and_the_motion_mode_after_it() {
    let t = translate("G01 X0. F100.\nG98 G83 X45. Y60. Z-45. R1. Q6. F180.\nG80 M9\n");
    let at = t.iter().position(|l| l == "MCALL").expect("MCALL alone");
    assert_eq!(t[at..at + 3], ["MCALL", "G1", "M9"], "{t:?}");
}
