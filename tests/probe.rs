//! Probing (issue 20): the `--probe` test inputs, the values each control keeps of a
//! probing move, and the translations of G31 / MEAS=1, proven on the path where the probe
//! touches and the one where it misses; planted wrong translations (wrong axis, machine
//! instead of workpiece coordinates) are caught.

mod eval_support;

use eval_support::{nctrans, scratch_dir, write};
use std::path::PathBuf;

fn scratch(name: &str) -> PathBuf {
    scratch_dir("probe-tests", name)
}

fn trace(file: &str, extra: &[&str]) -> (String, String) {
    let mut args = vec!["run", file];
    args.extend_from_slice(extra);
    let (_, out, err) = nctrans(&args);
    let lines: Vec<&str> = out.lines().map(|l| l.split("  @").next().unwrap_or("")).collect();
    (lines.join("\n"), err)
}

#[test]
fn a_probe_input_stops_the_move_and_fanuc_keeps_the_skip_position() {
    let d = scratch("fanuc-skip");
    let f = write(&d, "p.nc", "G90 G0 X0 Y0\nG31 X10. Y10. F100.\n#1=#5061\n#2=#5062\nG1 X[#1+100.] Y[#2+100.]\nM30\n");
    let (t, _) = trace(&f, &["--probe", "X=2.5"]);
    assert!(t.contains("move linear X=2.5 Y=2.5 f=100 probe"), "{t}");
    assert!(t.contains("move linear X=102.5 Y=102.5 f=100\n"), "{t}");
    // A miss: the end point, and #5061 holds it (FANUC).
    let (t, _) = trace(&f, &["--probe", "miss"]);
    assert!(t.contains("move linear X=10 Y=10 f=100 probe"), "{t}");
    assert!(t.contains("move linear X=110 Y=110 f=100\n"), "{t}");
    // Off the line: a precise error.
    let (_, err) = trace(&f, &["--probe", "X=2.5,Y=3"]);
    assert!(err.contains("NC530") && err.contains("does not lie on this probing move"), "{err}");
    let (_, err) = trace(&f, &["--probe", "X=12"]);
    assert!(err.contains("NC530"), "{err}");
    let (_, err) = trace(&f, &["--probe", "Z=1"]);
    assert!(err.contains("NC530") && err.contains("names no axis"), "{err}");
}

#[test]
fn siemens_keeps_measured_values_only_when_the_probe_switches() {
    let d = scratch("siemens-meas");
    let text = "G54\nG0 X0 Y0\nMEAS=1 G1 X10 F100\nR1=$AC_MEA[1]\nR2=$AA_MW[X]\nR3=$AA_MM[X]\nR4=$AA_MW[Y]\n\
                G1 X=R1 Y=R2 Z=R3\nG1 X=R4\nMEAW=1 G1 X20\nR5=$AA_MW[X]\nG1 Y=R5\nM30\n";
    let f = write(&d, "m.mpf", text);
    let (t, _) = trace(&f, &["--probe", "X=4", "--probe", "X=12"]);
    assert!(t.contains("move linear X=4 Y=0 f=100 probe"), "{t}");
    assert!(t.contains("move linear X=1 Y=4 Z=4 f=100\n"), "{t}");
    // MEAW goes on to the end point; the measured value is the trigger point.
    assert!(t.contains("move linear X=20 Y=4 Z=4 f=100 probe"), "{t}");
    assert!(t.contains("move linear X=20 Y=12 Z=4 f=100\n"), "{t}");
    // A miss: $AC_MEA[1] is 0 and $AA_MW keeps its old value (0 here).
    let (t, _) = trace(&f, &["--probe", "miss"]);
    assert!(t.contains("move linear X=0 Y=0 Z=0 f=100\n"), "{t}");
}

#[test]
fn probing_blocks_the_evaluator_does_not_model_are_errors() {
    let d = scratch("unmodelled");
    let f = write(&d, "a.nc", "G0 X0\nG31 P2 X10. F100.\nM30\n");
    assert!(trace(&f, &[]).1.contains("NC532"));
    let f = write(&d, "b.mpf", "G0 X0\nMEAS=1 X10\nM30\n");
    assert!(trace(&f, &[]).1.contains("NC533"));
    let f = write(&d, "c.mpf", "G1 X0 F100\nMEAS=3 X10\nM30\n");
    assert!(trace(&f, &[]).1.contains("NC531"));
    let f = write(&d, "d.nc", "G0 X0\nG31.1 X10. F100.\nM30\n");
    assert!(trace(&f, &[]).1.contains("NC403"));
}

/// The FANUC bore-probing corpus macro, translated, is equivalent on every path its
/// logic takes; a wrong axis or machine coordinates in the translation are caught.
#[test]
fn the_bore_probing_macro_translates_and_is_proven_on_both_paths() {
    let d = scratch("bore");
    let src = "corpus/in/fanuc/probe-bore-g55.nc";
    let out = d.join("out");
    let (code, _, err) = nctrans(&[src, "--to", "sinumerik", "-o", &format!("{}/", out.display())]);
    assert_eq!(code, 0, "{err}");
    let mpf = out.join("PROBE_BORE_G55.MPF");
    let text = std::fs::read_to_string(&mpf).expect("translation written");
    assert!(text.contains("MEAS=1 G1 X=R110 F100"), "{text}");
    assert!(text.contains("NCTRANS_SKIP_X=$AA_MW[X]"), "{text}");
    let mpf = mpf.to_string_lossy().into_owned();
    // The header's trigger points, then a miss at each of the four probing moves.
    let hits = ["X=-225.01", "X=-275.01", "Y=-154.98", "Y=-204.98"];
    let mut cases: Vec<Vec<&str>> = vec![hits.to_vec()];
    for k in 0..4 {
        let mut c = hits[..k].to_vec();
        c.push("miss");
        cases.push(c);
    }
    for probes in &cases {
        let mut args = vec!["check", src, &mpf];
        for p in probes {
            args.extend(["--probe", p]);
        }
        let (code, out, err) = nctrans(&args);
        assert_eq!(code, 0, "{probes:?}: {out}{err}");
        assert!(out.starts_with("equivalent"), "{probes:?}: {out}");
    }
    // Planted wrong translations.
    for (what, from, to) in [
        ("machine coordinates", "NCTRANS_SKIP_X=$AA_MW[X]", "NCTRANS_SKIP_X=$AA_MM[X]"),
        ("the wrong axis", "NCTRANS_SKIP_Y=$AA_MW[Y]", "NCTRANS_SKIP_Y=$AA_MW[X]"),
        ("the end point on a hit", "NCTRANS_SKIP_X=$AA_MW[X]", "NCTRANS_SKIP_X=$AA_IW[X]+0.01"),
        ("the stale value on a miss", "ELSE\n  NCTRANS_SKIP_X=$AA_IW[X]", "ELSE\n  NCTRANS_SKIP_X=$AA_MW[X]"),
    ] {
        assert!(text.contains(from), "{what}: `{from}` not in the translation");
        let bad = write(&d, "BAD.MPF", &text.replacen(from, to, 1));
        let probes: &[&str] = if what.contains("miss") { &["--probe", "miss"] } else { &[] };
        let mut args = vec!["check", src, &bad];
        args.extend_from_slice(probes);
        let (code, out, _) = nctrans(&args);
        assert_eq!(code, 1, "{what}: a wrong translation passed: {out}");
        assert!(out.starts_with("diverged"), "{what}: {out}");
    }
}

#[test]
fn a_siemens_surface_probe_translates_to_g31_on_both_paths() {
    let d = scratch("surface");
    let src = "corpus/in/sinumerik/probe-surface-z.mpf";
    let out = d.join("out.nc");
    let out_s = out.to_string_lossy().into_owned();
    let (code, _, err) = nctrans(&[src, "--to", "fanuc", "-o", &out_s]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&out).expect("written");
    assert!(text.contains("G31 Z140. F150.\nG01\n"), "{text}");
    for probes in [vec![], vec!["--probe", "miss"], vec!["--probe", "Z=160"]] {
        let mut args = vec!["check", src, &out_s];
        args.extend(probes.iter().copied());
        let (code, out, err) = nctrans(&args);
        assert_eq!(code, 0, "{probes:?}: {out}{err}");
    }
    // The measured values and the trigger flag have no FANUC counterpart.
    let (code, _, err) = nctrans(&["corpus/in/sinumerik/probe-bore-measured.mpf", "--to", "fanuc"]);
    assert_eq!(code, 1);
    assert!(err.contains("NC342") && err.contains("$AA_MW") && err.contains("$AC_MEA"), "{err}");
}

#[test]
fn constructs_without_a_counterpart_are_refused_by_name() {
    let d = scratch("refused");
    let cases = [
        ("a.mpf", "G0 X0\nMEAW=1 G1 X10 F100\nM30\n", "NC540"),
        ("b.mpf", "G1 X0 F100\nMEAS=1 X10\nM30\n", "NC541"),
        ("c.mpf", "G1 X0 F100\nMEAS=2 G1 X10\nM30\n", "NC540"),
    ];
    for (name, text, code) in cases {
        let f = write(&d, name, text);
        let (rc, _, err) = nctrans(&[&f, "--to", "fanuc"]);
        assert_eq!(rc, 1, "{name}");
        assert!(err.contains(code), "{name}: {err}");
    }
    let cases = [
        // The skip position of a caller's (or no) G31.
        ("d.nc", "G0 X0\n#1=#5061\nG31 X10. F100.\nM30\n", "NC536"),
        ("e.nc", "G0 X0\nG31 X10. F100.\nN10 #1=#5061\nG31 Y10.\nGOTO 10\nM30\n", ""),
        ("f.nc", "G0 X0\nIF [#2 EQ 1] GOTO 10\nG31 X10. F100.\nN10 #1=#5061\nM30\n", "NC536"),
        ("g.nc", "G0 X0\nG31 P1 X10. F100.\nM30\n", "NC538"),
        ("h.nc", "G0 X0\nIF [#2 EQ 1] GOTO 10\nG1 X1. F100.\nN10 G31 X10. F100.\nM30\n", "NC537"),
        ("i.nc", "G0 X0\nG31 X10. F100.\n#1=#5067\nM30\n", "NC536"),
    ];
    for (name, text, code) in cases {
        let f = write(&d, name, text);
        let (rc, out, err) = nctrans(&[&f, "--to", "sinumerik", "--no-verify"]);
        if code.is_empty() {
            assert_eq!(rc, 0, "{name}: {err}");
            assert!(out.contains("MEAS=1 G1 Y10\nSTOPRE\n") || out.contains("MEAS=1 G1 Y10"), "{name}: {out}");
        } else {
            assert_eq!(rc, 1, "{name}: {out}");
            assert!(err.contains(code), "{name}: {err}");
        }
    }
}

/// FANUC's current and skip positions include the tool length offset, Siemens machine
/// positions the tool length; where the run is not given the length, such reads under
/// compensation are refused by name (and so the translations are never called equivalent
/// where the real values differ); with it, tests/position_reads_length.rs.
#[test]
fn position_reads_that_would_hold_a_tool_length_are_refused() {
    let d = scratch("comp-reads");
    let cases = [
        ("a.nc", "G0 X0\nG43 H1 Z10.\n#1=#5043\nM30\n", "#5043 read under G43/G44"),
        ("b.nc", "G0 X0\nG43 H1 Z10.\n#1=#5023\nM30\n", "#5023 read under G43/G44"),
        ("c.nc", "G0 X0\nG43 H1 Z10.\nG31 Z0 F100.\nG49\n#1=#5063\nM30\n", "#5063 read under G43/G44"),
        ("d.mpf", "T1 M6 D1\nG0 X0\nR1=$AA_IM[Z]\nM30\n", "$AA_IM read under a cutting edge"),
        ("e.mpf", "G0 X0 Y0\nG41 G1 X10 F100\nR1=$AA_IW[X]\nM30\n", "$AA_IW read under G41/G42"),
    ];
    for (name, text, what) in cases {
        let f = write(&d, name, text);
        let (_, err) = trace(&f, &[]);
        assert!(err.contains("NC534") && err.contains(what), "{name}: {err}");
    }
    // The programmed end point holds no offset: #5001 and $P_EP read under compensation.
    let f = write(&d, "f.nc", "G0 X0\nG43 H1 Z10.\n#1=#5003\nG0 X#1\nM30\n");
    assert!(trace(&f, &[]).0.contains("move rapid X=10 Z=10 f=-"));
}

/// Back to FANUC: the kept-skip-position form the translation writes (hit: `$AA_MW`, miss:
/// `$AA_IW`, right after the measuring block) is `#5061+`, so the bore macro comes back and
/// is proven on both paths; the same form for an axis the block does not move, or with the
/// branches swapped, is not that meaning and stays refused.
#[test]
fn the_kept_skip_position_reads_back_as_5061() {
    let d = scratch("round-trip");
    let mpf = "corpus/out/sinumerik/probe-bore-g55/O_1000.MPF";
    let nc = d.join("back.nc").to_string_lossy().into_owned();
    let (code, out, err) = nctrans(&[mpf, "--to", "fanuc", "-o", &nc]);
    assert_eq!(code, 0, "{out}{err}");
    let text = std::fs::read_to_string(&nc).expect("written");
    assert!(text.contains("G31 X#610 F100.\nG01\n#601=#5061\n"), "{text}");
    for probes in [vec![], vec!["--probe", "X=-225.01", "--probe", "miss"]] {
        let mut args = vec!["check", "corpus/in/fanuc/probe-bore-g55.nc", &nc];
        args.extend(probes.iter().copied());
        let (code, out, err) = nctrans(&args);
        assert_eq!(code, 0, "{probes:?}: {out}{err}");
    }
    let form = |then: &str, other: &str| {
        format!("G0 X0 Y0\nMEAS=1 G1 X10 F100\nSTOPRE\nIF $AC_MEA[1]==1\nR1={then}\nELSE\nR1={other}\nENDIF\nG0 Y=R1\nM30\n")
    };
    let f = write(&d, "ok.mpf", &form("$AA_MW[X]", "$AA_IW[X]"));
    let (code, out, err) = nctrans(&[&f, "--to", "fanuc"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("G31 X10. F100.\nG01\n#501=#5061\n"), "{out}");
    for (name, then, other) in [("y.mpf", "$AA_MW[Y]", "$AA_IW[Y]"), ("swap.mpf", "$AA_IW[X]", "$AA_MW[X]")] {
        let f = write(&d, name, &form(then, other));
        let (code, _, err) = nctrans(&[&f, "--to", "fanuc"]);
        assert_eq!(code, 1, "{name}");
        assert!(err.contains("NC342"), "{name}: {err}");
    }
}
