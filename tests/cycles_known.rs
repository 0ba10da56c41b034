//! Sinumerik drilling cycles whose arguments are variables known at translation (issue 19):
//! an R parameter or a DEF variable that holds one constant on every path to the call is
//! that constant where the FANUC cycle is decided (G98/G99, the R plane, the peck mode), and
//! the words keep the variables; one that an IF, a loop, a jump, a call or an input may
//! change is refused (NC660) naming the variable and the place; a translation planted wrong
//! in the R plane is caught by `nctrans check`.

mod eval_support;

use eval_support::{nctrans, nctrans_in, scratch_dir, scratch_file, write};

const HEAD: &str = "G17 G90 G71 G54\nT1 D1 M6\nS2000 M3 F150\n";
const HOLES: &str = "X20 Y20\nX-20 Y20\nMCALL\nG0 Z100\nM30\n";

fn program(vars: &str, call: &str) -> String {
    format!("{vars}{HEAD}G0 X0 Y0 Z10\nMCALL {call}\n{HOLES}")
}

/// The verified FANUC translation's lines.
fn to_fanuc(text: &str) -> Vec<String> {
    let src = scratch_file("cycknown", "mpf", text);
    let (code, out, err) = nctrans(&[&src, "--to", "fanuc"]);
    assert_eq!(code, 0, "{out}\n{err}");
    assert!(err.contains("equivalent"), "{err}");
    out.lines().filter(|l| !l.starts_with('(') && !l.starts_with('%')).map(str::to_string).collect()
}

/// The refusal's text (NC660).
fn refused(text: &str) -> String {
    let src = scratch_file("cycknown", "mpf", text);
    let (code, _, err) = nctrans(&[&src, "--to", "fanuc"]);
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("NC660"), "{err}");
    err
}

#[test]
fn def_variables_with_start_values_decide_the_cycle_and_stay_in_the_words() {
    let t = to_fanuc(&program("DEF REAL _RTP=10, _RFP=0, _SDIS=2, _DP=-15\n", "CYCLE81(_RTP,_RFP,_SDIS,_DP)"));
    assert!(t.iter().any(|l| l == "G98 G81 X20. Y20. Z#103 R[#101+#102]"), "{t:?}");
    // RTP = RFP + SDIS: G99.
    let t = to_fanuc(&program("DEF REAL _RTP=2, _RFP=0, _SDIS=2\n", "CYCLE81(_RTP,_RFP,_SDIS,-15)"));
    assert!(t.iter().any(|l| l.starts_with("G99 G81 X20. Y20. Z-15. R[#101+#102]")), "{t:?}");
}

#[test]
fn r_parameters_set_before_the_call_are_known() {
    let t = to_fanuc(&program("R1=10 R2=0 R3=2\n", "CYCLE81(R1,R2,R3,-15)"));
    assert!(t.iter().any(|l| l.starts_with("G98 G81 X20. Y20. Z-15. R[#")), "{t:?}");
    // A value computed from known ones; a jump over blocks that leave it alone.
    let t = to_fanuc(&program("R2=0 R3=2 R1=R2+4*R3+2\nGOTOF ON\nR7=1\nON:\n", "CYCLE81(R1,R2,R3,-15)"));
    assert!(t.iter().any(|l| l.contains("G98 G81")), "{t:?}");
}

#[test]
fn a_value_set_in_an_if_branch_is_refused_naming_the_assignment() {
    let err = refused(&program("R1=10 R2=0 R3=2\nIF R5>0\nR1=20\nENDIF\n", "CYCLE81(R1,R2,R3,-15)"));
    assert!(err.contains("RTP = R1") && err.contains("set to 20 here on one path to it and 10 on another"), "{err}");
    assert!(err.contains("3 │ R1=20"), "the assignment is labelled: {err}");
}

#[test]
fn a_value_changed_in_a_loop_or_by_a_jump_is_refused() {
    let err =
        refused(&program("R1=10 R2=0 R3=2 R4=0\nWHILE R4<2\nR3=R3+1\nR4=R4+1\nENDWHILE\n", "CYCLE81(R1,R2,R3,-15)"));
    assert!(err.contains("SDIS = R3") && err.contains("R3=R3+1"), "{err}");
    let err = refused(&program("R1=10 R2=0 R3=2\nIF R5>0 GOTOF ON\nR1=20\nON:\n", "CYCLE81(R1,R2,R3,-15)"));
    assert!(err.contains("RTP = R1"), "{err}");
}

#[test]
fn a_called_program_that_may_write_an_r_parameter_makes_them_unknown() {
    let d = scratch_dir("cycknown", "calls");
    write(&d, "SETR.SPF", "PROC SETR\nR3=5\nM17\n");
    write(&d, "NOSET.SPF", "PROC NOSET\nG0 X0 Y0\nM17\n");
    let main = write(&d, "MAIN.MPF", &program("R1=10 R2=0 R3=2\nSETR\n", "CYCLE81(R1,R2,R3,-15)"));
    let (code, _, err) = nctrans(&[&main, "--to", "fanuc"]);
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("NC660") && err.contains("may be written by the call here"), "{err}");
    // One that writes none leaves them known.
    let main = write(&d, "MAIN2.MPF", &program("R1=10 R2=0 R3=2\nNOSET\n", "CYCLE81(R1,R2,R3,-15)"));
    let (code, out, err) = nctrans(&[&main, "--to", "fanuc"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent") && out.contains("G98 G81"), "{out}\n{err}");
}

#[test]
fn an_input_set_by_the_header_is_never_known() {
    let err = refused(&program(
        "; nctrans: set _RTP=20\nDEF REAL _RTP=10, _RFP=0, _SDIS=2\n",
        "CYCLE81(_RTP,_RFP,_SDIS,-15)",
    ));
    assert!(err.contains("_RTP is set by the program's `nctrans: set` header line"), "{err}");
}

#[test]
fn a_peck_and_a_tapping_cycle_take_their_mode_and_pitch_from_variables() {
    let t = to_fanuc(&program(
        "DEF REAL _RTP=3, _RFP=3, _FDPR=6\nDEF INT _VARI=0\n",
        "CYCLE83(_RTP,_RFP,0,-30,,,_FDPR,0,0,0,1,_VARI)",
    ));
    assert!(t.iter().any(|l| l == "G99 G73 X20. Y20. Z-30. R#101 Q#102"), "{t:?}");
    let tap = "G17 G90 G71 G54\nT1 D1 M6\nM5\nR10=8 R11=400\nG0 X0 Y0 Z30\nMCALL CYCLE84(30,0,5,-16,,0,5,R10,,0,R11)\nX25 Y0\nMCALL\nM30\n";
    let t = to_fanuc(tap);
    assert!(t.iter().any(|l| l == "G98 G84 X25. Y0. Z-16. R5. F500."), "{t:?}");
}

#[test]
fn a_planted_wrong_r_plane_is_caught_by_check() {
    let text = program("R1=10 R2=0 R3=2\n", "CYCLE81(R1,R2,R3,-15)");
    let src = scratch_file("cycknown", "mpf", &text);
    let (code, good, err) = nctrans(&[&src, "--to", "fanuc"]);
    assert_eq!(code, 0, "{err}");
    let from = "R[#502+#503]";
    assert!(good.contains(from), "{good}");
    for to in ["R[#501+#503]", "R[#502-#503]", "R[#502+#503+1.]"] {
        let bad = scratch_file("cycknown", "nc", &good.replacen(from, to, 1));
        let (code, report, _) = nctrans(&["check", &src, &bad]);
        assert_ne!(code, 0, "a wrong R plane {to} was not caught:\n{report}");
        assert!(report.contains("diverged"), "{to}: {report}");
    }
}

#[test]
fn a_subprograms_parameter_is_known_only_once_it_sets_it() {
    let d = scratch_dir("cycknown", "params");
    let main = "G17 G90 G71 G54\nT1 D1 M6\nS2000 M3 F150\nR1=10\nDRILL(-12, R1)\nG0 Z100\nM30\n";
    let sub = |set: &str| {
        format!(
            "PROC DRILL(REAL DEPTH, REAL RTPV)\nDEF REAL _RFP=0, _SDIS=2\n{set}G90 G0 X0 Y0 Z=RTPV\nMCALL CYCLE81(RTPV,_RFP,_SDIS,DEPTH)\nX20 Y20\nMCALL\nM17\n"
        )
    };
    write(&d, "DRILL.SPF", &sub(""));
    let m = write(&d, "MAIN.MPF", main);
    let (code, _, err) = nctrans(&[&m, "--to", "fanuc"]);
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("RTPV is not set in this program on every path to the call"), "{err}");
    write(&d, "DRILL.SPF", &sub("RTPV=10\n"));
    let (code, out, err) = nctrans(&[&m, "--to", "fanuc"]);
    assert_eq!(code, 0, "{err}");
    // The depth stays the parameter (a word's value), the R plane its variables.
    assert!(out.contains("G98 G81 X20. Y20. Z#1 R[#3+#4]") && err.contains("equivalent"), "{out}\n{err}");
}

#[test]
fn r_parameters_are_never_known_where_an_interrupt_routine_may_run() {
    let d = scratch_dir("cycknown", "interrupt");
    write(&d, "nctrans.toml", "[fanuc]\nmacro_interrupt = true\n");
    write(&d, "LIFT.SPF", "PROC LIFT SAVE\nR1=50\nM17\n");
    write(&d, "ARM.SPF", "PROC ARM\nSETINT(1) PRIO=1 LIFT\nM17\n");
    // Set up here, or by a called program (it stays armed after the return).
    for (name, setup) in [("OWN.MPF", "SETINT(1) PRIO=1 LIFT\n"), ("CALLED.MPF", "ARM\n")] {
        write(&d, name, &program(&format!("{setup}R1=10 R2=0 R3=2\n"), "CYCLE81(R1,R2,R3,-15)"));
        let (code, _, err) = nctrans_in(&d, &[name, "--to", "fanuc"]);
        assert_ne!(code, 0, "{name}: {err}");
        assert!(err.contains("NC660") && err.contains("interrupt routine"), "{name}: {err}");
    }
}
