//! The feed of moves with a rotary axis, and the Siemens feed group (`FGROUP`): the trace's
//! `f` is the speed along every axis that moves, degrees counted as mm (docs/semantics.md,
//! "Feed of moves with rotary axes and FGROUP"). A Siemens X+A move under the default group
//! (F along X only, A dragged along) is no longer "equivalent" to the same words on FANUC:
//! refused at translation; a FANUC 4-axis program gets `FGROUP(X,Y,Z,A)` and is proven; a
//! planted translation without it, or with the wrong axes, is caught by `check`.

#[path = "support/cli_run.rs"]
mod cli_run;

use cli_run::{nctrans, workdir};

fn dir(name: &str, files: &[(&str, &str)]) -> std::path::PathBuf {
    let d = workdir("rotary_feed", name);
    for (f, text) in files {
        std::fs::write(d.join(f), text).unwrap();
    }
    d
}

/// The `f=` of each move line of a text trace.
fn feeds(trace: &str) -> Vec<String> {
    trace
        .lines()
        .filter(|l| l.starts_with("move linear") || l.starts_with("arc"))
        .filter_map(|l| l.split_whitespace().find(|w| w.starts_with("f=")).map(str::to_string))
        .collect()
}

const BUG: &str = "G90 G1 X0 Y0 Z0 A0 F100\nG1 X10 A90 F100\nM30\n";

#[test]
fn the_siemens_default_group_drags_the_rotary_axis_and_the_trace_says_so() {
    let d = dir("default", &[("rot.mpf", BUG)]);
    let (trace, err, code) = nctrans(&d, &["run", "rot.mpf"]);
    assert_eq!(code, 0, "{err}");
    // F along X only: 10 mm at 100 mm/min while the path of X and A is 90.55 "mm".
    assert_eq!(feeds(&trace), ["f=100", "f=905.538514"], "{trace}");
}

#[test]
fn the_bug_is_refused_at_translation_naming_the_move_and_the_group() {
    let d = dir("refused", &[("rot.mpf", BUG)]);
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "rot.mpf", "-o", "rot.nc"]);
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("error[NC664]: the feed of this move of X, A"), "{err}");
    assert!(err.contains("the default feed group (X, Y, Z)"), "{err}");
    assert!(err.contains("write FGROUP(X,Y,Z,A) before the move"), "{err}");
    assert!(!err.contains("equivalent"), "{err}");
    assert!(!d.join("rot.nc").exists());
    // Under an explicit group the same move is named with the FGROUP.
    let src = "G90 G1 X0 Y0 Z0 A0 F100\nFGROUP(X)\nG1 X10 Y5 F100\nM30\n";
    let d = dir("refused-group", &[("g.mpf", src)]);
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "g.mpf", "-o", "g.nc"]);
    assert_ne!(code, 0, "{err}");
    assert!(
        err.contains("NC664") && err.contains("under FGROUP(X)") && err.contains("the feed group set here"),
        "{err}"
    );
}

#[test]
fn a_move_not_known_at_translation_is_caught_by_the_proof() {
    // The position comes from a variable: the translation cannot tell, the proof does.
    let src = "R1=90\nG90 G1 X0 Y0 Z0 A0 F100\nG1 X10 A=R1 F100\nM30\n";
    let d = dir("proof", &[("p.mpf", src)]);
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "p.mpf", "-o", "p.nc"]);
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("NC500") && err.contains("f=905.538514") && err.contains("f=100"), "{err}");
}

#[test]
fn fgroup_with_every_moving_axis_translates_to_plain_fanuc_words() {
    let src = "G90 G1 X0 Y0 Z0 A0 F100\nFGROUP(X,Y,Z,A)\nG1 X10 A90 F100\nA180\nFGROUP()\nG1 X0 F200\nM30\n";
    let d = dir("exact", &[("e.mpf", src)]);
    let (trace, err, code) = nctrans(&d, &["run", "e.mpf"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(feeds(&trace), ["f=100", "f=100", "f=100", "f=200"], "{trace}");
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "e.mpf", "-o", "e.nc"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent ("), "{err}");
    let out = std::fs::read_to_string(d.join("e.nc")).unwrap();
    assert!(!out.contains("FGROUP"), "{out}");
    assert!(out.contains("G01 X10. A90. F100."), "{out}");
}

#[test]
fn fgroup_z_with_z_only_moves_runs_and_translates() {
    // The grinding library's form: the feed refers to Z, and only Z moves.
    let src = "G90 G0 X5 Z2\nFGROUP(Z)\nG1 Z-10 F50\nG1 Z2 F300\nFGROUP()\nG1 X0 F100\nM30\n";
    let d = dir("z", &[("z.mpf", src)]);
    let (trace, err, code) = nctrans(&d, &["run", "z.mpf"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(feeds(&trace), ["f=50", "f=300", "f=100"], "{trace}");
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "z.mpf", "-o", "z.nc"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent ("), "{err}");
}

#[test]
fn fgroup_takes_axnames_and_axis_variables() {
    let src = "DEF AXIS AV\nAV=AXNAME(\"A\")\nG90 G1 X0 A0 F100\nFGROUP(X,AV)\nG1 X10 A10\nFGROUP(AXNAME(\"X\"))\nG1 X20 A20\nM30\n";
    let d = dir("axnames", &[("n.mpf", src)]);
    let (trace, err, code) = nctrans(&d, &["run", "n.mpf"]);
    assert_eq!(code, 0, "{err}");
    // Under FGROUP(X,A) F runs along both; under FGROUP(X) A is dragged: √2 · F.
    assert_eq!(feeds(&trace), ["f=100", "f=100", "f=141.421356"], "{trace}");
    let src = "FGROUP(X1)\nM30\n";
    let d = dir("bad-axis", &[("b.mpf", src)]);
    let (_, err, code) = nctrans(&d, &["run", "b.mpf"]);
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("error[NC663]") && err.contains("X1"), "{err}");
    // The bare word: not said to be FGROUP().
    let d = dir("bare", &[("b.mpf", "FGROUP(X)\nFGROUP\nG1 X1 Y1 F100\nM30\n")]);
    let (_, err, code) = nctrans(&d, &["run", "b.mpf"]);
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("error[NC663]: FGROUP without parentheses"), "{err}");
}

#[test]
fn feeds_no_source_settles_are_refused_in_run() {
    let cases = [
        // FGROUP(Z) and a move of X only: none of the group's axes moves.
        ("nogroup.mpf", "FGROUP(Z)\nG1 X10 F100\nM30\n"),
        // A rotary axis under feed per revolution.
        ("g95.mpf", "M3 S1000\nG95 G1 X1 A10 F0.1\nM30\n"),
        // FANUC: a linear and a rotary axis together under G20.
        ("g20.nc", "%\nO1\nG20 G1 X1. A10. F10.\nM30\n%\n"),
        // A rotary axis in an arc.
        ("arc.nc", "%\nO1\nG1 X0 Y0 F100.\nG2 X10. Y0 R5. A10.\nM30\n%\n"),
    ];
    for (name, src) in cases {
        let d = dir("refused-run", &[(name, src)]);
        let (_, err, code) = nctrans(&d, &["run", name]);
        assert_ne!(code, 0, "{name}: {err}");
        assert!(err.contains("error[NC662]"), "{name}: {err}");
    }
    // On a Haas the rotary feed rests on Settings 34/79.
    let d = dir("haas", &[("h.nc", "%\nO1\nG1 X1. A10. F100.\nM30\n%\n")]);
    std::fs::write(d.join("nctrans.toml"), "[fanuc]\nseries = \"haas\"\n").unwrap();
    let (_, err, code) = nctrans(&d, &["run", "h.nc"]);
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("NC662") && err.contains("Setting 34"), "{err}");
}

#[test]
fn a_rotary_axis_alone_moves_at_f_degrees_per_minute() {
    // FANUC and Siemens: F of a rotary axis alone is degrees/min, also under inch units.
    let d = dir(
        "alone",
        &[
            ("a.nc", "%\nO1\nG20 G1 A90. F15.\nG21 G1 A0 F100.\nM30\n%\n"),
            ("a.mpf", "G700 G1 A90 F15\nG710 G1 A0 F100\nM30\n"),
        ],
    );
    for f in ["a.nc", "a.mpf"] {
        let (trace, err, code) = nctrans(&d, &["run", f]);
        assert_eq!(code, 0, "{f}: {err}");
        assert_eq!(feeds(&trace), ["f=15", "f=100"], "{f}: {trace}");
    }
    let (_, err, code) = nctrans(&d, &["check", "a.nc", "a.mpf"]);
    assert_eq!(code, 0, "{err}");
}

const FANUC_4AX: &str = "%
O2000
G21 G90 G17
G0 X0 Y0 Z5. A0
G1 Z-1. F200.
G1 X20. A90. F150.
G1 Y10. A180.
A270.
G1 X0 Y0 A360. F300.
G0 Z5.
M30
%
";

#[test]
fn a_fanuc_four_axis_program_gets_its_fgroup_and_is_proven() {
    let d = dir("to-sinumerik", &[("p.nc", FANUC_4AX)]);
    let (_, err, code) = nctrans(&d, &["--to", "sinumerik", "p.nc", "-o", "out"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent ("), "{err}");
    let out = std::fs::read_to_string(d.join("out")).unwrap_or_else(|_| {
        let f = std::fs::read_dir(d.join("out")).unwrap().next().unwrap().unwrap().path();
        std::fs::read_to_string(f).unwrap()
    });
    assert_eq!(out.matches("FGROUP(").count(), 1, "{out}");
    assert!(out.contains("FGROUP(X,Y,Z,A)"), "{out}");
    let (trace, _, _) = nctrans(&d, &["run", "p.nc"]);
    assert_eq!(feeds(&trace), ["f=200", "f=150", "f=150", "f=150", "f=300"], "{trace}");
}

#[test]
fn a_planted_translation_without_fgroup_or_with_the_wrong_axes_is_caught() {
    let d = dir("planted", &[("p.nc", FANUC_4AX)]);
    let (_, err, code) = nctrans(&d, &["--to", "sinumerik", "p.nc", "-o", "good.mpf"]);
    assert_eq!(code, 0, "{err}");
    let good = std::fs::read_to_string(d.join("good.mpf")).unwrap();
    let (_, err, code) = nctrans(&d, &["check", "p.nc", "good.mpf"]);
    assert_eq!(code, 0, "{err}");
    for (name, bad) in [
        ("missing.mpf", good.replace("FGROUP(X,Y,Z,A)\n", "")),
        ("wrong.mpf", good.replace("FGROUP(X,Y,Z,A)", "FGROUP(X,Y,Z)")),
        ("partial.mpf", good.replace("FGROUP(X,Y,Z,A)", "FGROUP(X,A)")),
    ] {
        assert_ne!(bad, good, "{name}");
        std::fs::write(d.join(name), &bad).unwrap();
        let (_, err, code) = nctrans(&d, &["check", "p.nc", name]);
        assert_ne!(code, 0, "{name}: {err}");
        assert!(err.contains("NC500") || err.contains("NC662"), "{name}: {err}");
    }
}

#[test]
fn fgref_turns_the_rotary_axis_degrees_into_the_arc_at_its_radius() {
    // FGROUP(X,A) with FGREF[A]=10: F is the tangential speed at 10 mm, so A alone turns at
    // 100 / (10·π/180) = 572.96 degrees/min; in inch (G700) the radius is in inch.
    let src = "G90 G71 G0 X0 A0\nFGROUP(X,A)\nFGREF[A]=10\nG1 A90 F100\nG1 X10 A180\nM30\n";
    let d = dir("fgref", &[("r.mpf", src)]);
    let (trace, err, code) = nctrans(&d, &["run", "r.mpf"]);
    assert_eq!(code, 0, "{err}");
    // X10 A90 more: group path sqrt(10² + (90·10·π/180)²) = 18.62 mm at 100 mm/min, while
    // every axis (degrees as mm) is sqrt(10² + 90²) = 90.55: f = 100 · 90.55 / 18.62.
    assert_eq!(feeds(&trace), ["f=572.957795", "f=486.300689"], "{trace}");
    let inch = "G90 G700 G0 X0 A0\nFGROUP(X,A)\nFGREF[A]=1\nG1 A90 F100\nM30\n";
    let d = dir("fgref-inch", &[("r.mpf", inch)]);
    let (trace, err, code) = nctrans(&d, &["run", "r.mpf"]);
    assert_eq!(code, 0, "{err}");
    assert!(trace.contains("move linear"), "{trace}");
    // A linear axis has no reference radius; outside the group it is not settled.
    for (name, src, what) in [
        ("fgref-x", "FGREF[X]=10\nM30\n", "belongs to a rotary axis"),
        ("fgref-out", "G90 G0 X0 A0\nFGREF[A]=10\nG1 A90 F100\nM30\n", "not in the feed group"),
    ] {
        let d = dir(name, &[("r.mpf", src)]);
        let (_, err, code) = nctrans(&d, &["run", "r.mpf"]);
        assert_ne!(code, 0, "{name}: {err}");
        assert!(err.contains(what), "{name}: {err}");
    }
}

#[test]
fn fgref_is_refused_for_fanuc_with_its_reason() {
    let src = "G90 G0 X0 A0\nFGROUP(X,A)\nFGREF[A]=10\nG1 A90 F100\nM30\n";
    let d = dir("fgref-fanuc", &[("r.mpf", src)]);
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "r.mpf", "-o", "r.nc"]);
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("error[NC619]") && err.contains("FGREF (the reference radius"), "{err}");
    assert!(!err.contains("NC341") && !err.contains("NC314"), "one diagnostic: {err}");
}
