//! Sinumerik drilling cycles in the evaluator (CYCLE81–CYCLE89, CYCLE840, MCALL), and the
//! checker comparing their `cycle` events with FANUC's: equal programs of the two controls
//! agree, and a planted difference in depth, R plane, peck, dwell, retract or feed diverges.

mod eval_support;

use eval_support::*;
use std::process::Command;

static N: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);

fn scratch(ext: &str, text: &str) -> String {
    scratch_file("scycle", ext, text)
}

fn run(src: &str) -> Ran {
    let k = N.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    run_text(&format!("scycle-run-{k}.mpf"), src, &[])
}

/// The setting-up every test program starts with (G54 is the first event, `work_offset 1`).
const HEAD: &str = "G17 G90 G54\nT1 M6 D1\nS1000 M3\nG0 X0 Y0 Z50\nF100\n";

fn prog(body: &str) -> String {
    format!("{HEAD}{body}M30\n")
}

fn trace(body: &str) -> Vec<String> {
    // The tool's edge (a `comp` event at the tool change) is not what these tests look at.
    bare_lines(&run(&prog(body))).into_iter().filter(|l| !l.starts_with("comp ")).collect()
}

fn cycles(body: &str) -> Vec<String> {
    trace(body).into_iter().filter(|l| l.starts_with("cycle ")).collect()
}

fn error_codes(body: &str) -> Vec<String> {
    run(&prog(body)).outcome.diags.iter().filter(|d| d.is_error()).map(|d| d.code.to_string()).collect()
}

#[test]
fn a_direct_call_drills_where_the_tool_is_and_mcall_after_every_move() {
    let t = trace("G0 X10 Y10\nCYCLE81(50, 0, 2, -5)\nMCALL CYCLE81(50, 0, 2, -5)\nX20\nY20\nMCALL\nX30\n");
    assert_eq!(t[5], "cycle drill X=10 Y=10 r=2 bottom=-5 peck=- dwell=- retract=initial f=100");
    assert_eq!(t[6], "move rapid X=20 Y=10 Z=50 f=-");
    assert_eq!(t[7], "cycle drill X=20 Y=10 r=2 bottom=-5 peck=- dwell=- retract=initial f=100");
    assert_eq!(t[9], "cycle drill X=20 Y=20 r=2 bottom=-5 peck=- dwell=- retract=initial f=100");
    // MCALL alone ends it: the last move drills nothing.
    assert_eq!(t[10], "move rapid X=30 Y=20 Z=50 f=-");
    assert_eq!(t[11], "end M30 steps=13");
}

#[test]
fn dpr_wins_over_dp_and_empty_arguments_are_zero() {
    let c = cycles("CYCLE82(50, 10, 1, -99, 6, 0.5)\nCYCLE81(50, , 2, -5)\n");
    assert_eq!(c[0], "cycle dwell_drill X=0 Y=0 r=11 bottom=4 peck=- dwell=0.5 retract=initial f=100");
    assert_eq!(c[1], "cycle drill X=0 Y=0 r=2 bottom=-5 peck=- dwell=- retract=initial f=100");
}

#[test]
fn the_retraction_plane_sets_the_retract_level() {
    // RTP = RFP + SDIS: back to the R plane.
    let t = trace("CYCLE81(2, 0, 2, -5)\nG0 X5\n");
    assert_eq!(t[4], "cycle drill X=0 Y=0 r=2 bottom=-5 peck=- dwell=- retract=r f=100");
    assert_eq!(t[5], "move rapid X=5 Y=0 Z=2 f=-");
    // RTP between the tool and the R plane: approached first, then the tool's level.
    let t = trace("CYCLE81(10, 0, 2, -5)\n");
    assert_eq!(t[4], "move rapid X=0 Y=0 Z=10 f=-");
    assert_eq!(t[5], "cycle drill X=0 Y=0 r=2 bottom=-5 peck=- dwell=- retract=initial f=100");
    // RTP above the tool: the cycle returns through the start level to RTP.
    let t = trace("CYCLE81(80, 0, 2, -5)\n");
    assert_eq!(t[4], "cycle drill X=0 Y=0 r=2 bottom=-5 peck=- dwell=- retract=initial f=100");
    assert_eq!(t[5], "move rapid X=0 Y=0 Z=80 f=-");
}

#[test]
fn every_cycle_has_its_kind() {
    let c = cycles(
        "CYCLE81(50, 0, 2, -5)\nCYCLE82(50, 0, 2, -5, , 0.3)\nCYCLE83(50, 0, 0, -20, , , 4, 0, 0, 0, 1, 1)\n\
         CYCLE83(50, 0, 0, -20, , -3, , , , , , 0)\nCYCLE84(50, 0, 2, -16, , 0, 3, 8, , 0, 400)\n\
         CYCLE84(50, 0, 2, -16, , , , , -1.5, , 200)\nCYCLE840(50, 0, 2, -16, , , 4, 3, 1)\n\
         CYCLE85(50, 0, 2, -22, , 0, 70, 70)\nCYCLE86(50, 0, 2, -25, , 0.1, 3, 0.2, 0, 0, 0)\n\
         CYCLE87(50, 0, 2, -12, , 3)\nCYCLE88(50, 0, 2, -12, , 1, 3)\nCYCLE89(50, 0, 2, -8, , 0.4)\n",
    );
    let end = "retract=initial";
    assert_eq!(c[0], format!("cycle drill X=0 Y=0 r=2 bottom=-5 peck=- dwell=- {end} f=100"));
    assert_eq!(c[1], format!("cycle dwell_drill X=0 Y=0 r=2 bottom=-5 peck=- dwell=0.3 {end} f=100"));
    assert_eq!(c[2], format!("cycle peck X=0 Y=0 r=0 bottom=-20 peck=4 dwell=- {end} f=100"));
    assert_eq!(c[3], format!("cycle chip_break X=0 Y=0 r=0 bottom=-20 peck=3 dwell=- {end} f=100"));
    // M8 (1.25 mm) at SST 400: 500 mm/min; PIT -1.5: left hand.
    assert_eq!(c[4], format!("cycle tap X=0 Y=0 r=2 bottom=-16 peck=- dwell=- {end} f=500 tapping=rigid"));
    assert_eq!(c[5], format!("cycle tap_left X=0 Y=0 r=2 bottom=-16 peck=- dwell=- {end} f=300 tapping=rigid"));
    // CYCLE840 without encoder: the programmed feed, the hand from M3, SDR 4 out.
    assert_eq!(c[6], format!("cycle tap X=0 Y=0 r=2 bottom=-16 peck=- dwell=- {end} f=100 tapping=floating"));
    assert_eq!(c[7], format!("cycle bore X=0 Y=0 r=2 bottom=-22 peck=- dwell=- {end} f=70"));
    assert_eq!(c[8], format!("cycle fine_bore X=0 Y=0 r=2 bottom=-25 peck=- dwell=0.1 {end} f=100"));
    assert_eq!(c[9], format!("cycle bore_stop X=0 Y=0 r=2 bottom=-12 peck=- dwell=- {end} f=100"));
    assert_eq!(c[10], format!("cycle bore_stop X=0 Y=0 r=2 bottom=-12 peck=- dwell=1 {end} f=100"));
    assert_eq!(c[11], format!("cycle bore_dwell X=0 Y=0 r=2 bottom=-8 peck=- dwell=0.4 {end} f=100"));
    // CYCLE87/88 stop at the bottom.
    let t = trace("CYCLE87(50, 0, 2, -12, , 3)\n");
    assert_eq!(t[5], "stop");
}

#[test]
fn settings_the_event_cannot_show_are_refused() {
    assert_eq!(error_codes("CYCLE81(50, 0, 2, -5, , 1)\n"), ["NC423"]); // _GMODE
    assert_eq!(error_codes("CYCLE81(50, 0, 2, -5, , 0, 0, 0, 9)\n"), ["NC424"]);
    assert_eq!(error_codes("CYCLE81(50, 0, 2, 5)\n"), ["NC425"]);
    assert_eq!(error_codes("CYCLE81(1, 0, 2, -5)\n"), ["NC422"]);
    assert_eq!(error_codes("CYCLE83(50, 0, 2, -20, , , 4, 0, 0, 0, 1, 1)\n"), ["NC426"]);
    assert_eq!(error_codes("CYCLE83(50, 0, 0, -20, , , 4, 1, 0, 0, 1, 1)\n"), ["NC423"]); // DAM
    assert_eq!(error_codes("CYCLE83(50, 0, 0, -20, , , , , , , , 1)\n"), ["NC427"]);
    // FDEP given as 0 and FDPR 0, DAM 0: still no first drilling depth.
    assert_eq!(error_codes("CYCLE83(50, 0, 0, -20, , 0, 0, 0, 0, 0, 1, 1)\n"), ["NC427"]);
    assert_eq!(error_codes("CYCLE84(50, 0, 2, -16, , 0, 3, , , 0, 400)\n"), ["NC427"]);
    assert_eq!(error_codes("CYCLE85(50, 0, 2, -22, , 0, 70, 200)\n"), ["NC423"]);
    assert_eq!(error_codes("CYCLE86(50, 0, 2, -25, , 0.1, 4)\n"), ["NC423"]);
    let t = bare_lines(&run("G0 X0 Y0 Z50\nCYCLE81(50, 0, 2, -5)\nM30\n"));
    assert!(t.last().is_some_and(|l| l.starts_with("alarm 10860 ")), "{t:?}");
}

fn check(fanuc: &str, siemens: &str) -> (i32, String) {
    let a = scratch("nc", fanuc);
    let b = scratch("mpf", siemens);
    let out = Command::new(env!("CARGO_BIN_EXE_nctrans")).args(["check", &a, &b]).output().expect("run nctrans");
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stdout).into_owned())
}

const F_HEAD: &str = "%\nO1\nG17 G90 G54\nT1 M6\nG43 H1\nS1000 M3\nG0 X0 Y0 Z50.\nF100.\n";

/// FANUC and Sinumerik forms of the same holes: each pair agrees.
const PAIRS: &[(&str, &str)] = &[
    ("G98 G81 X10. Y10. Z-5. R2.\nX20.\nG80\n", "MCALL CYCLE81(50, 0, 2, -5)\nX10 Y10\nX20\nMCALL\n"),
    ("G99 G81 X10. Y10. Z-5. R2.\nX20.\nG80\n", "MCALL CYCLE81(2, 0, 2, -5)\nX10 Y10\nX20\nMCALL\n"),
    ("G98 G82 X10. Y10. Z-5. R2. P300\nG80\n", "G0 X10 Y10\nCYCLE82(50, 0, 2, -5, , 0.3)\n"),
    ("G98 G83 X10. Y10. Z-20. R0 Q4.\nG80\n", "G0 X10 Y10\nCYCLE83(50, 0, 0, -20, , , 4, 0, 0, 0, 1, 1)\n"),
    ("G98 G73 X10. Y10. Z-20. R0 Q3.\nG80\n", "G0 X10 Y10\nCYCLE83(50, 0, 0, -20, , , 3, , , , , 0)\n"),
    (
        // Rigid tapping from a stopped spindle (from a turning one FANUC's is not settled, NC592).
        "M05\nM29 S400\nG98 G84 X10. Y10. Z-16. R2. F500.\nG80\n",
        "M5\nS400\nG0 X10 Y10\nCYCLE84(50, 0, 2, -16, , , 5, 8, , , 400)\nF500\n",
    ),
    (
        "M05\nM29 S400\nG98 G74 X10. Y10. Z-16. R2. F500.\nG80\n",
        "M5\nS400\nG0 X10 Y10\nCYCLE84(50, 0, 2, -16, , , 5, , -1.25, , 400)\nF500\n",
    ),
    ("G98 G84 X10. Y10. Z-16. R2. F500.\nG80\n", "G0 X10 Y10\nF500\nCYCLE840(50, 0, 2, -16, , , 4, 3, 1)\n"),
    ("G98 G85 X10. Y10. Z-22. R2. F70.\nG80\n", "G0 X10 Y10\nCYCLE85(50, 0, 2, -22, , 0, 70, 70)\nF70\n"),
    ("G98 G89 X10. Y10. Z-8. R2. P400\nG80\n", "G0 X10 Y10\nCYCLE89(50, 0, 2, -8, , 0.4)\n"),
    ("G98 G88 X10. Y10. Z-12. R2. P1000\nG80\n", "G0 X10 Y10\nCYCLE88(50, 0, 2, -12, , 1, 3)\n"),
    ("G98 G88 X10. Y10. Z-12. R2.\nG80\n", "G0 X10 Y10\nCYCLE87(50, 0, 2, -12, , 3)\n"),
];

fn pair_texts(f: &str, s: &str) -> (String, String) {
    (format!("{F_HEAD}{f}M30\n%\n"), prog(s))
}

#[test]
fn fanuc_and_sinumerik_forms_of_the_same_holes_agree() {
    for (f, s) in PAIRS {
        let (a, b) = pair_texts(f, s);
        let (code, out) = check(&a, &b);
        assert_eq!(code, 0, "FANUC:\n{a}\nSinumerik:\n{b}\n{out}");
    }
}

#[test]
fn a_planted_difference_in_any_field_diverges() {
    let fanuc = format!("{F_HEAD}G99 G83 X10. Y10. Z-20. R0 Q4. F120.\nG80\nM30\n%\n");
    let good = prog("G0 X10 Y10\nF120\nCYCLE83(0, 0, 0, -20, , , 4, 0, 0, 0, 1, 1)\n");
    assert_eq!(check(&fanuc, &good).0, 0);
    let planted = [
        ("depth", "G0 X10 Y10\nF120\nCYCLE83(0, 0, 0, -21, , , 4, 0, 0, 0, 1, 1)\n"),
        ("R plane", "G0 X10 Y10\nF120\nCYCLE83(0.5, 0.5, 0, -20, , , 4, 0, 0, 0, 1, 1)\n"),
        ("peck", "G0 X10 Y10\nF120\nCYCLE83(0, 0, 0, -20, , , 5, 0, 0, 0, 1, 1)\n"),
        ("kind", "G0 X10 Y10\nF120\nCYCLE83(0, 0, 0, -20, , , 4, 0, 0, 0, 1, 0)\n"),
        ("retract", "G0 X10 Y10\nF120\nCYCLE83(50, 0, 0, -20, , , 4, 0, 0, 0, 1, 1)\n"),
        ("feed", "G0 X10 Y10\nF100\nCYCLE83(0, 0, 0, -20, , , 4, 0, 0, 0, 1, 1)\n"),
    ];
    for (what, body) in planted {
        let (code, out) = check(&fanuc, &prog(body));
        assert_ne!(code, 0, "a wrong {what} was not caught:\n{out}");
        assert!(out.contains("differ") || out.contains("diverge"), "{what}: {out}");
    }
    // Dwell: CYCLE82 against G82.
    let fanuc = format!("{F_HEAD}G98 G82 X10. Y10. Z-5. R2. P300\nG80\nM30\n%\n");
    assert_ne!(check(&fanuc, &prog("G0 X10 Y10\nCYCLE82(50, 0, 2, -5, , 0.4)\n")).0, 0);
}

/// A cycle without DP and DPR drills to DP=0 (an empty argument is 0), with a warning at the
/// call; a DP or DPR written, even 0, is no warning.
#[test]
fn a_cycle_without_a_depth_runs_to_dp_0_with_a_warning() {
    let ran = run(&prog("CYCLE81(50, 0, 2)\n"));
    assert!(matches!(ran.outcome.ending, nctrans::eval::Ending::End { .. }), "{:?}", ran.outcome.ending);
    let warned: Vec<_> = ran.outcome.diags.iter().filter(|d| d.code == "NC523").collect();
    assert_eq!(warned.len(), 1, "{:?}", ran.outcome.diags);
    assert!(warned[0].message.contains("CYCLE81 without a final drilling depth"), "{}", warned[0].message);
    assert!(bare_lines(&ran).iter().any(|l| l.starts_with("cycle drill X=0 Y=0 r=2 bottom=0 ")));
    for written in ["CYCLE81(50, 0, 2, 0)\n", "CYCLE81(50, 0, 2, , 5)\n", "MCALL CYCLE81(50, 0, 2, -5)\nX1\nMCALL\n"] {
        let ran = run(&prog(written));
        assert!(!ran.outcome.diags.iter().any(|d| d.code == "NC523"), "{written}: {:?}", ran.outcome.diags);
    }
    // Under MCALL the warning stands once, at the MCALL.
    let ran = run(&prog("MCALL CYCLE82(50, 0, 2)\nX1\nX2\nMCALL\n"));
    assert_eq!(ran.outcome.diags.iter().filter(|d| d.code == "NC523").count(), 1, "{:?}", ran.outcome.diags);
}
