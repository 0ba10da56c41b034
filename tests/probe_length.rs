//! FANUC skip positions under tool length compensation (issue 20 with the tool data of
//! issue 21): `#5063` includes the length offset in force at the G31 (G43 +, G44 −, geometry
//! plus wear of the H register), read where the run is given the register; otherwise, and
//! where the axis or unit is not settled, refused by name (NC534). The translations refuse
//! what would differ between the two controls (NC550 to Sinumerik, NC551 to FANUC).

mod eval_support;

use eval_support::{nctrans, run_bare, scratch_dir, write};
use std::path::PathBuf;

fn scratch(name: &str) -> PathBuf {
    scratch_dir("probe-length-tests", name)
}

fn run(file: &str, extra: &[&str]) -> (String, String) {
    run_bare(file, extra)
}

const SET: [&str; 4] = ["--set", "#11001=100.", "--set", "#10001=-0.5"];

#[test]
fn the_skip_position_includes_the_length_offset_at_the_g31() {
    let d = scratch("eval");
    // G43: Z holds the trigger point plus geometry and wear; X and Y are not offset.
    let f = write(
        &d,
        "a.nc",
        "G0 X3. Y4.\nG43 H1 Z10.\nG31 Z0 F100.\n#1=#5063\n#2=#5061\n#3=#5062\nG49\nG0 X#1 Y[#2+#3]\nM30\n",
    );
    let mut args = SET.to_vec();
    args.extend(["--probe", "Z=2.5"]);
    let (t, err) = run(&f, &args);
    assert!(t.contains("move rapid X=102 Y=7 Z=2.5 f=-"), "{t}{err}");
    // A miss: the end point, with the offset.
    let mut args = SET.to_vec();
    args.extend(["--probe", "miss"]);
    assert!(run(&f, &args).0.contains("move rapid X=99.5 Y=7 Z=0 f=-"), "{}", run(&f, &args).0);
    // G44 subtracts it.
    let g = write(&d, "b.nc", "G0 X0\nG44 H1 Z10.\nG31 Z0 F100.\n#1=#5063\nG49\nG0 X#1\nM30\n");
    assert!(run(&g, &SET).0.contains("move rapid X=-99.5 Z=0 f=-"), "{}", run(&g, &SET).0);
    // The offset in force at the G31: a later write to the register does not change it.
    let h = write(&d, "c.nc", "G0 X0\nG43 H1 Z10.\nG31 Z0 F100.\nG10 L10 P1 R50.\n#1=#5063\nG49\nG0 X#1\nM30\n");
    assert!(run(&h, &SET).0.contains("move rapid X=99.5 Z=0 f=-"), "{}", run(&h, &SET).0);
    // H0 is offset 0; a G31 under G49 holds none.
    let k = write(
        &d,
        "d.nc",
        "G0 X0\nG43 H0 Z10.\nG31 Z0 F100.\n#1=#5063\nG49\nG31 Z1. F100.\n#2=#5063\nG0 X[#1+#2]\nM30\n",
    );
    assert!(run(&k, &[]).0.contains("move rapid X=1 Z=1 f=-"), "{}", run(&k, &[]).0);
}

#[test]
fn what_the_run_does_not_know_is_refused_by_name() {
    let d = scratch("refused");
    let cases = [
        (
            "a.nc",
            "G0 X0\nG43 H1 Z10.\nG31 Z0 F100.\n#1=#5063\nM30\n",
            &[][..],
            "with the length of H1 not given (--set '#11001=…')",
        ),
        (
            "b.nc",
            "G0 X0\nG43 H1 Z10.\nG31 Z0 F100.\n#1=#5063\nM30\n",
            &["--set", "#11001=100."][..],
            "(--set '#10001=…')",
        ),
        ("c.nc", "G18 G0 X0\nG43 H1 Z10.\nG31 Z0 F100.\n#1=#5061\nM30\n", &SET[..], "outside G17"),
        ("d.nc", "G20 G0 X0\nG43 H1 Z1.\nG31 Z0 F10.\n#1=#5063\nM30\n", &SET[..], "under G20"),
    ];
    for (name, text, extra, what) in cases {
        let f = write(&d, name, text);
        let (_, err) = run(&f, extra);
        assert!(err.contains("NC534") && err.contains("#506") && err.contains(what), "{name}: {err}");
    }
}

/// The corpus Z touch-off under G43 runs on both of its paths; its translation to Sinumerik
/// adds H21's edge length to the kept Z (tests/probe_skip_length.rs); where G43 is not known
/// on every path to the G31, refused (NC550).
#[test]
fn a_g31_under_unsettled_length_compensation_does_not_translate_to_sinumerik() {
    let d = scratch("to-sinumerik");
    let src = "corpus/in/fanuc/probe-face-z-g43.nc";
    assert!(run(src, &[]).0.contains("move rapid X=0 Y=0 Z=9.93 f=-"), "{}", run(src, &[]).0);
    assert!(run(src, &["--probe", "miss"]).0.contains("alarm 3001"), "{}", run(src, &["--probe", "miss"]).0);
    let (code, out_s, err) = nctrans(&[src, "--to", "sinumerik", "-o", &format!("{}/", d.join("a").display())]);
    assert_eq!(code, 0, "{out_s}{err}");
    // A called program probes in its caller's mode: refused unless it sets the offset itself.
    let called = "O1\nG43 H1 Z10.\nM98 P2\nM30\nO2\nG31 Z0 F100.\n#1=#5063\nM99\n";
    let f = write(&d, "b.nc", called);
    let (_, _, err) = nctrans(&[&f, "--to", "sinumerik", "-o", &format!("{}/", d.join("b").display())]);
    assert!(err.contains("NC550") && err.contains("not set on every path"), "{err}");
    // Under G49 on every path: translated and proven.
    let ok = "O1\nT1 M6\nG0 X0 Y0\nG43 H1 Z10.\nG49\nG31 Z0 F100.\n#1=#5063\nG0 X#1\nM30\n";
    let f = write(&d, "c.nc", ok);
    let out = d.join("c");
    let (code, out_s, err) = nctrans(&[&f, "--to", "sinumerik", "-o", &format!("{}/", out.display())]);
    assert_eq!(code, 0, "{out_s}{err}");
    // A G43 on one path only.
    let one = "O1\nT1 M6\nG0 X0 Y0\nIF [#1 GT 0] GOTO 10\nG43 H1 Z10.\nN10 G31 Z0 F100.\n#2=#5063\nM30\n";
    let f = write(&d, "e.nc", one);
    let (_, _, err) = nctrans(&[&f, "--to", "sinumerik", "-o", &format!("{}/", d.join("e").display())]);
    assert!(err.contains("NC550"), "{err}");
}

/// Siemens → FANUC: the kept Z measurement becomes `#5063`, which under the `G43 H` an edge
/// becomes includes the length; the H at the G31 known, it is taken off
/// (tests/probe_skip_length.rs); refused where the edge is not known, translated with D0.
#[test]
fn the_kept_z_measurement_under_an_unknown_edge_does_not_translate_to_fanuc() {
    let d = scratch("to-fanuc");
    let text = "DEF REAL ZS\nG90 G17 G710\nG54\nT1 M6 D1\nG0 X0 Y0 Z50\nIF R1>0 GOTOF SKIP\nD2\nSKIP:\n\
                MEAS=1 G1 Z0 F100\nSTOPRE\nIF $AC_MEA[1]==1\n  ZS=$AA_MW[Z]\nELSE\n  ZS=$AA_IW[Z]\nENDIF\nG0 X=ZS\nM30\n";
    let f = write(&d, "A.MPF", text);
    let (code, _, err) = nctrans(&[&f, "--to", "fanuc", "-o", &d.join("a.nc").to_string_lossy()]);
    assert_ne!(code, 0);
    assert!(err.contains("NC551") && err.contains("the measured Z position (#5063)"), "{err}");
    let plain = text.replace("IF R1>0 GOTOF SKIP\nD2\nSKIP:\n", "");
    let f = write(&d, "B.MPF", &plain.replace("T1 M6 D1", "T1 M6 D0"));
    let (code, out, err) = nctrans(&[&f, "--to", "fanuc", "-o", &d.join("b.nc").to_string_lossy()]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("equivalent") || err.contains("equivalent"), "{out}{err}");
}
