//! FANUC → Sinumerik: a drilling cycle stored with `L0` (or defined by a first hole) and left
//! in force over a WHILE loop that computes the hole positions, the classic macro bolt
//! circle: the MCALL in force drills at each `G0 X… Y…` of the loop, as FANUC's cycle drills
//! at each position block; a loop that does anything else under the cycle stays refused
//! (NC428). Also `G81 … L0` followed by plain position blocks (its MCALL was left out, so
//! the translation drilled nothing and the proof failed).

mod eval_support;

use eval_support::{nctrans, nctrans_in, scratch_dir, write};

fn bolt_circle(mode: &str, body: &str) -> String {
    format!(
        "%\nO2000 (BOLT CIRCLE)\nG17 G21 G90 G40 G80\nG54 G00 X0. Y0. Z50. S2000 M03\n#1=6 (HOLES)\n#2=40. (PCD RADIUS)\n\
#3=15. (START ANGLE)\n#4=0\n{mode} G81 Z-10. R2. F200. L0\nWHILE [#4 LT #1] DO1\n#5=#3+#4*360./#1\n{body}#4=#4+1\nEND1\n\
G80\nG00 Z100. M05\nM30\n%\n"
    )
}

const HOLE: &str = "X[#2*COS[#5]] Y[#2*SIN[#5]]\n";

#[test]
fn a_bolt_circle_loop_under_a_stored_cycle_is_one_mcall() {
    let d = scratch_dir("cycles-bolt-circle", "loop");
    for mode in ["G98", "G99"] {
        let src = write(&d, &format!("O2000{mode}.nc"), &bolt_circle(mode, HOLE));
        let (code, out, err) = nctrans(&["--to", "sinumerik", &src]);
        assert_eq!(code, 0, "{mode}: {err}");
        assert!(err.contains("equivalent ("), "{mode}: {err}");
        let out_file = write(&d, &format!("O2000{mode}.MPF"), &out);
        let (code, trace, err) = nctrans(&["run", &out_file]);
        assert_eq!(code, 0, "{err}");
        assert_eq!(trace.matches("cycle drill").count(), 6, "{mode}: six holes: {trace}");
        let lines: Vec<&str> = out.lines().map(str::trim).collect();
        let mcall = lines.iter().position(|l| l.starts_with("MCALL CYCLE81(")).expect("MCALL");
        let looped = lines.iter().position(|l| l.starts_with("WHILE")).expect("WHILE");
        assert!(mcall < looped, "{out}");
        assert!(lines.contains(&"G0 X=LOC2*COS(LOC5) Y=LOC2*SIN(LOC5)"), "{out}");
        assert_eq!(lines.iter().filter(|l| **l == "MCALL").count(), 1, "{out}");
    }
}

#[test]
fn a_planted_wrong_depth_in_the_bolt_circle_is_caught() {
    let d = scratch_dir("cycles-bolt-circle", "planted");
    let src = write(&d, "O2000.nc", &bolt_circle("G98", HOLE));
    let (code, good, err) = nctrans(&["--to", "sinumerik", &src]);
    assert_eq!(code, 0, "{err}");
    let bad = write(&d, "BAD.MPF", &good.replacen(",-10)", ",-12)", 1));
    assert_ne!(bad, good);
    let (code, verdict, err) = nctrans(&["check", &src, &bad]);
    assert_ne!(code, 0, "a wrong depth was not caught: {verdict}{err}");
    assert!(verdict.contains("diverged"), "{verdict}");
}

#[test]
fn a_loop_that_does_more_than_position_under_the_cycle_is_refused() {
    let d = scratch_dir("cycles-bolt-circle", "refused");
    for (name, body) in [
        ("Z", "X[#2*COS[#5]] Y[#2*SIN[#5]] Z-12.\n"),
        ("M", "X[#2*COS[#5]] Y[#2*SIN[#5]]\nM08\n"),
        ("G", "G01 X[#2*COS[#5]] Y[#2*SIN[#5]]\n"),
    ] {
        let src = write(&d, &format!("O2000{name}.nc"), &bolt_circle("G98", body));
        let (code, _, err) = nctrans(&["--to", "sinumerik", &src]);
        assert_ne!(code, 0, "{name}: {err}");
        assert!(err.contains("NC428") && err.contains("stays active into a structure"), "{name}: {err}");
    }
}

#[test]
fn a_stored_cycle_before_plain_positions_defines_its_mcall() {
    let d = scratch_dir("cycles-bolt-circle", "stored");
    let src = write(
        &d,
        "O2001.nc",
        "%\nO2001\nG17 G21 G90\nG00 X0. Y0. Z50.\nG98 G81 Z-10. R2. F200. L0\nX10. Y10.\nX20.\nG80\nM30\n%\n",
    );
    let (code, out, err) = nctrans(&["--to", "sinumerik", &src]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent (6 events)"), "{err}");
    assert!(out.contains("MCALL CYCLE81($P_EP[Z],2,0,-10)\nG0 X10 Y10\nG0 X20\nMCALL\n"), "{out}");
}

/// Sinumerik → FANUC, the same bolt circle: an MCALL over a FOR loop of `G0 X=… Y=…`.
fn mcall_circle(level: &str, body: &str) -> String {
    format!(
        "DEF INT HOLE\nDEF REAL PCD_R=45\nG17 G90 G54 G71 G40\nT1 D1 M6\nS2200 M3 F180\nG0 X0 Y0 Z{level}\n\
MCALL CYCLE81(20,0,2,-12)\nFOR HOLE=0 TO 5\n{body}ENDFOR\nMCALL\nG0 Z100 M5\nM30\n"
    )
}

const SIE_HOLE: &str = "  G0 X=PCD_R*COS(30+HOLE*60) Y=PCD_R*SIN(30+HOLE*60)\n";

#[test]
fn an_mcall_over_a_loop_of_positions_is_a_stored_fanuc_cycle() {
    let d = scratch_dir("cycles-bolt-circle", "mcall");
    let src = write(&d, "FLANGE.MPF", &mcall_circle("20", SIE_HOLE));
    let (code, out, err) = nctrans(&["--to", "fanuc", &src]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent ("), "{err}");
    let lines: Vec<&str> = out.lines().collect();
    let stored = lines.iter().position(|l| *l == "G98 G81 Z-12. R2. K0").expect("the stored cycle");
    let looped = lines.iter().position(|l| l.starts_with("WHILE")).expect("WHILE");
    assert!(stored < looped && lines.contains(&"G80"), "{out}");
    // The holes stay positions: a G00 in them would end FANUC's cycle.
    assert!(!lines.iter().any(|l| l.starts_with("G00 X[")), "{out}");
    let nc = write(&d, "flange.nc", &out);
    let (code, trace, err) = nctrans(&["run", &nc]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(trace.matches("cycle drill").count(), 6, "{trace}");
    // A planted wrong depth is caught.
    let bad = write(&d, "bad.nc", &out.replacen("Z-12. R2. K0", "Z-13. R2. K0", 1));
    let (code, verdict, _) = nctrans(&["check", &src, &bad]);
    assert_ne!(code, 0, "{verdict}");
    assert!(verdict.contains("diverged"), "{verdict}");
    // A Haas stores it with L0.
    std::fs::write(d.join("nctrans.toml"), "[fanuc]\nseries = \"haas\"\n").unwrap();
    let (code, out, err) = nctrans_in(&d, &["--to", "fanuc", "FLANGE.MPF"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.lines().any(|l| l == "G98 G81 Z-12. R2. L0"), "{out}");
}

#[test]
fn an_mcall_loop_that_does_more_or_starts_above_rtp_is_refused() {
    let d = scratch_dir("cycles-bolt-circle", "mcall-refused");
    for (name, level, body) in [
        ("Z", "20", "  G0 X=PCD_R*COS(HOLE*60) Y=PCD_R*SIN(HOLE*60) Z30\n"),
        ("F", "20", "  G1 X=PCD_R*COS(HOLE*60) Y=PCD_R*SIN(HOLE*60)\n"),
        // Above RTP the first hole positions X/Y there and then lowers to RTP: a stored
        // FANUC cycle would start at the tool's level.
        ("ABOVE", "50", SIE_HOLE),
    ] {
        let src = write(&d, &format!("{name}.MPF"), &mcall_circle(level, body));
        let (code, _, err) = nctrans(&["--to", "fanuc", &src]);
        assert_ne!(code, 0, "{name}: {err}");
        assert!(err.contains("NC394") && err.contains("open into a structure"), "{name}: {err}");
    }
}
