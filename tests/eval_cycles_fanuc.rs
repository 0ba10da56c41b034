//! FANUC drilling cycles in the evaluator (G73–G89, G98/G99, G80, K repeats, G91): one
//! `cycle` event per hole with the rules of docs/semantics.md ("Drilling cycles").

mod eval_support;

use eval_support::*;

/// Runs `src` from a scratch file of its own (the tests run in parallel).
fn run(src: &str) -> Ran {
    static N: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let k = N.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    run_text(&format!("cycle-{k}.nc"), src, &[])
}

fn trace(src: &str) -> Vec<String> {
    bare_lines(&run(src))
}

/// The trace without the positioning moves to the holes (pinned by
/// `each_hole_is_positioned_by_a_rapid_at_the_level_the_tool_stands_at`).
fn holes(src: &str) -> Vec<String> {
    let t = trace(src);
    let mut out = Vec::new();
    for (k, l) in t.iter().enumerate() {
        let before_hole = t.get(k + 1).is_some_and(|n| n.starts_with("cycle "));
        if !(before_hole && l.starts_with("move rapid")) {
            out.push(l.clone());
        }
    }
    out
}

/// The error diagnostics' codes of a run that stopped with an evaluator error.
fn error_codes(src: &str) -> Vec<String> {
    let ran = run(src);
    ran.outcome.diags.iter().filter(|d| d.is_error()).map(|d| d.code.to_string()).collect()
}

const HEAD: &str = "O1\nG21 G17 G90\nG0 X0 Y0 Z50.\n";

fn prog(body: &str) -> String {
    format!("{HEAD}{body}M30\n")
}

#[test]
fn each_hole_is_positioned_by_a_rapid_at_the_level_the_tool_stands_at() {
    let t = trace(&prog("G99 G81 X10. Y10. Z-5. R2. F100.\nG98 X20.\nX30.\nZ-6.\nG80\n"));
    assert_eq!(t[1], "move rapid X=10 Y=10 Z=50 f=-");
    // After a G99 hole the tool moves on at the R plane, after a G98 hole at the initial level.
    assert_eq!(t[3], "move rapid X=20 Y=10 Z=2 f=-");
    assert_eq!(t[5], "move rapid X=30 Y=10 Z=50 f=-");
    // A block without plane words drills where the tool is: no positioning.
    assert_eq!(t[7], "cycle drill X=30 Y=10 r=2 bottom=-6 peck=- dwell=- retract=initial f=100");
}

#[test]
fn g98_returns_to_the_initial_level_and_g99_to_r() {
    let t = holes(&prog("G98 G81 X10. Y10. Z-5. R2. F100.\nG99 X20.\nG80\nG0 X0\n"));
    assert_eq!(t[1], "cycle drill X=10 Y=10 r=2 bottom=-5 peck=- dwell=- retract=initial f=100");
    assert_eq!(t[2], "cycle drill X=20 Y=10 r=2 bottom=-5 peck=- dwell=- retract=r f=100");
    // After the last hole the tool stands over it at the R plane (G99).
    assert_eq!(t[3], "move rapid X=0 Y=10 Z=2 f=-");
}

#[test]
fn g98_from_an_initial_level_at_the_r_plane_returns_to_r() {
    // The tool stands at R when the cycle mode begins: G98 and G99 end every hole there,
    // and the event names the level as the Sinumerik reader does (RTP = RFP + SDIS: `r`).
    let t = holes(&prog("G0 Z2.\nG98 G81 X10. Y10. Z-5. R2. F100.\nX20.\nG80\nG0 X0\n"));
    assert_eq!(t[2], "cycle drill X=10 Y=10 r=2 bottom=-5 peck=- dwell=- retract=r f=100");
    assert_eq!(t[3], "cycle drill X=20 Y=10 r=2 bottom=-5 peck=- dwell=- retract=r f=100");
    assert_eq!(t[4], "move rapid X=0 Y=10 Z=2 f=-");
    // A hair above R is another level: still the initial one.
    let t = holes(&prog("G0 Z2.001\nG98 G81 X10. Y10. Z-5. R2. F100.\nG80\n"));
    assert_eq!(t[2], "cycle drill X=10 Y=10 r=2 bottom=-5 peck=- dwell=- retract=initial f=100");
}

#[test]
fn cycle_data_is_modal_and_a_block_without_axis_words_drills_nothing() {
    let t = holes(&prog("G99 G83 X10. Y10. Z-20. R2. Q5. F80.\nF120.\nM8\nY20.\nZ-25.\nG80\n"));
    assert_eq!(t[1], "cycle peck X=10 Y=10 r=2 bottom=-20 peck=5 dwell=- retract=r f=80");
    assert_eq!(t[2], "coolant on");
    // F was taken by the block without axis words; R, Z, Q stayed.
    assert_eq!(t[3], "cycle peck X=10 Y=20 r=2 bottom=-20 peck=5 dwell=- retract=r f=120");
    // Only the depth changed: the same position, drilled again.
    assert_eq!(t[4], "cycle peck X=10 Y=20 r=2 bottom=-25 peck=5 dwell=- retract=r f=120");
    assert_eq!(t.len(), 6);
}

#[test]
fn g91_measures_r_from_the_initial_level_and_z_from_r_and_repeats_move() {
    let t = holes(&prog("G91 G99 G81 X10. Z-7. R-48. K3 F100.\nG90 G80\nG0 X0\n"));
    for (k, x) in ["10", "20", "30"].iter().enumerate() {
        assert_eq!(t[1 + k], format!("cycle drill X={x} Y=0 r=2 bottom=-5 peck=- dwell=- retract=r f=100"));
    }
    assert_eq!(t[4], "move rapid X=0 Y=0 Z=2 f=-");
}

#[test]
fn k_repeats_the_same_hole_under_g90_and_k0_only_stores_the_data() {
    let t = holes(&prog("G81 X10. Y5. Z-5. R2. F100. K0\nX11. K2\nG80\n"));
    assert_eq!(t.len(), 4, "{t:?}");
    // K0 neither drills nor positions.
    assert_eq!(t[1], "cycle drill X=11 Y=0 r=2 bottom=-5 peck=- dwell=- retract=initial f=100");
    assert_eq!(t[1], t[2]);
}

#[test]
fn a_motion_code_cancels_the_cycle_and_its_data() {
    let t = holes(&prog("G81 X10. Y10. Z-5. R2. F100.\nG1 X20.\nX30.\nG81 X40.\n"));
    assert_eq!(t[2], "move linear X=20 Y=10 Z=50 f=100");
    assert_eq!(t[3], "move linear X=30 Y=10 Z=50 f=100");
    // The depth and R plane went with the cycle.
    assert_eq!(error_codes(&prog("G81 X10. Y10. Z-5. R2. F100.\nG0 X20.\nG81 X40. R2.\n")), vec!["NC420"]);
    assert_eq!(error_codes(&prog("G81 X10. Y10. Z-5. F100.\n")), vec!["NC421"]);
    assert_eq!(error_codes(&prog("G0 G81 X10. Y10. Z-5. R2. F100.\n")), vec!["NC416"]);
}

#[test]
fn peck_cycles_without_q_alarm_like_the_control() {
    for src in ["G83 X10. Y10. Z-20. R2. F80.\n", "G73 X10. Y10. Z-20. R2. Q0 F80.\n"] {
        let t = holes(&prog(src));
        assert!(t.last().is_some_and(|l| l.starts_with("alarm 45 ")), "{t:?}");
    }
    let t = holes(&prog("G73 X10. Y10. Z-20. R2. Q2.5 F80.\nG80\n"));
    assert_eq!(t[1], "cycle chip_break X=10 Y=10 r=2 bottom=-20 peck=2.5 dwell=- retract=initial f=80");
    // Beside the alarm a warning says what was missing, at the Q0 (or the block).
    let ran = run(&prog("G83 X10. Y10. Z-20. R2. Q0 F80.\n"));
    let d = ran.outcome.diags.iter().find(|d| d.code == "NC524").expect("NC524");
    assert!(d.message.contains("G83 with Q0") && d.message.contains("alarm PS0045"), "{}", d.message);
    // The label is on the Q0 word (columns 25–26 of its line).
    let q0 = prog("G83 X10. Y10. Z-20. R2. Q0 F80.\n").find("Q0").expect("Q0") as u32;
    assert_eq!(d.labels.first().map(|l| (l.span.lo, l.span.hi)), Some((q0, q0 + 2)), "{d:?}");
    let ran = run(&prog("G73 X10. Y10. Z-20. R2. F80.\n"));
    assert!(ran.outcome.diags.iter().any(|d| d.code == "NC524" && d.message.contains("G73 with no Q")));
}

/// A bottom at or above the R plane (Z above R, G90 or G91, either return level) is refused
/// with the levels and a hint; G87 starts below the part and is not.
#[test]
fn a_bottom_not_below_the_r_plane_is_refused_precisely() {
    for src in [
        "G99 G81 X10. Y10. Z5. R2. F80.\n",
        "G98 G83 X10. Y10. Z2. R2. Q1. F80.\n",
        "G91 G99 G81 X10. Y10. Z5. R-48. F80.\n",
    ] {
        assert_eq!(error_codes(&prog(src)), ["NC522"], "{src}");
        // No hole and no positioning before the refusal.
        assert!(!trace(&prog(src)).iter().any(|l| l.contains("X=10")), "{src}");
    }
    let ran = run(&prog("G99 G81 X10. Y10. Z5. R2. F80.\n"));
    let d = ran.outcome.diags.iter().find(|d| d.code == "NC522").expect("NC522");
    assert!(d.message.contains("(at Z=5) is not below the R plane (at Z=2)"), "{}", d.message);
    assert!(d.notes.iter().any(|n| n.contains("program Z below R")), "{d:?}");
    let t = holes(&prog("G87 X10. Y10. Z-5. R-20. Q1. F80.\nG80\n"));
    assert!(t[1].starts_with("cycle back_bore X=10 Y=10 r=-20 bottom=-5"), "{t:?}");
}

#[test]
fn p_is_a_dwell_in_milliseconds_where_the_cycle_has_one() {
    let t = holes(&prog(
        "G82 X1. Y1. Z-3. R1. P500 F50.\nG80\nG81 X2. Y2. Z-3. R1. P500 F50.\nG80\nG82 X3. Z-3. R1. F50.\n",
    ));
    assert_eq!(t[1], "cycle dwell_drill X=1 Y=1 r=1 bottom=-3 peck=- dwell=0.5 retract=initial f=50");
    assert_eq!(t[2], "cycle drill X=2 Y=2 r=1 bottom=-3 peck=- dwell=- retract=initial f=50");
    // G82 without P (the P of before went with G80) is the motion of G81: reported as it.
    assert_eq!(t[3], "cycle drill X=3 Y=2 r=1 bottom=-3 peck=- dwell=- retract=initial f=50");
}

#[test]
fn the_decimal_point_rule_applies_to_r_z_and_q() {
    let t = holes(&prog("G83 X10. Y10. Z-20000 R2000 Q5000 F80.\nG80\n"));
    assert_eq!(t[1], "cycle peck X=10 Y=10 r=2 bottom=-20 peck=5 dwell=- retract=initial f=80");
}

#[test]
fn every_kind_is_named_and_g87_returns_to_the_initial_level() {
    let src = prog(
        "G99 G85 X1. Y0 Z-5. R2. F100.\nG86 X2.\nG89 X3. P200\nG76 X4. Q0.5 P100\nM29 S500\nG84 X5.\nG74 X6.\n\
         G87 X7. Z5. R-20.\nG88 X8. Z-5. R2. P300\nG80\n",
    );
    let t = holes(&src);
    let kinds: Vec<&str> = t.iter().filter_map(|l| l.strip_prefix("cycle ")?.split(' ').next()).collect();
    assert_eq!(kinds, ["bore", "bore_stop", "bore_dwell", "fine_bore", "tap", "tap_left", "back_bore", "bore_stop"]);
    // P stays from G76 (modal), and G87 returns to the initial level under G99.
    assert!(t.iter().any(|l| l == "cycle back_bore X=7 Y=0 r=-20 bottom=5 peck=- dwell=0.1 retract=initial f=100"));
    // G76: Q is the shift at the bottom, not an infeed.
    assert!(t.iter().any(|l| l == "cycle fine_bore X=4 Y=0 r=2 bottom=-5 peck=- dwell=0.1 retract=r f=100"));
    // G88 halts at the bottom for the operator to retract by hand.
    let g88 = t.iter().position(|l| l.starts_with("cycle bore_stop X=8")).expect("G88 hole");
    assert_eq!(t[g88 + 1], "stop");
}

#[test]
fn the_work_offset_moves_the_holes_and_the_planes() {
    let t = holes(&prog("#5221=100.\n#5223=-10.\nG54 G81 X10. Y10. Z-5. R2. F100.\nG80\nG0 X0\n"));
    let hole = t.iter().find(|l| l.starts_with("cycle")).expect("a hole");
    assert_eq!(hole, "cycle drill X=110 Y=10 r=-8 bottom=-15 peck=- dwell=- retract=initial f=100");
}

#[test]
fn the_cycle_group_reads_back_in_4009() {
    let src = "G99 G83 X1. Y1. Z-5. R1. Q1. F50.\n#100=#4009\n#101=#4010\nG80\n#102=#4009\n\
               IF[#100NE83]GOTO9\nIF[#101NE99]GOTO9\nIF[#102NE80]GOTO9\n#3006=1(OK)\nN9";
    assert!(holes(&prog(src)).iter().any(|l| l == "stop \"OK\""));
}

#[test]
fn no_feed_alarms_and_other_axes_are_refused() {
    let t = holes("O1\nG0 X0 Y0 Z50.\nG81 X10. Y10. Z-5. R2.\nM30\n");
    assert!(t.last().is_some_and(|l| l.starts_with("alarm 11 ")), "{t:?}");
    assert_eq!(error_codes(&prog("G81 X10. Y10. Z-5. R2. F100.\nA90.\n")), vec!["NC417"]);
    assert_eq!(error_codes(&prog("G81 X10. Y10. Z-5. R2. F100. K10000\n")), vec!["NC419"]);
    assert_eq!(error_codes(&prog("G83 X10. Y10. Z-5. R2. Q-1. F100.\n")), vec!["NC418"]);
}
