//! FANUC modal information reads (issue 20, "positions read back"): what the evaluator reads
//! for `#4001..` and where it refuses (NC549), and the translation to Sinumerik of
//! `#4001`/`#4003`/`#4006`/`#4014` as the constant the program itself selected, proven on the
//! probing macro's paths; planted wrong constants are caught, and reads whose value is only
//! known at run time are refused by name.

mod eval_support;

use eval_support::{nctrans, run_bare, scratch_dir, write};
use std::path::PathBuf;

fn scratch(name: &str) -> PathBuf {
    scratch_dir("modal-reads-tests", name)
}

fn run(file: &str) -> (String, String) {
    run_bare(file, &[])
}

/// The work offset group reads 54..59 for G54..G59; an extended offset (G54.1 Pn) and
/// `#4130` (its P) are refused by name: no source read gives their values.
#[test]
fn the_work_offset_group_reads_back_and_the_extended_offsets_are_refused() {
    let d = scratch("eval");
    let f = write(&d, "a.nc", "G55\n#1=#4014\nG57\n#2=#4014\nG0 X#1 Y#2\nM30\n");
    assert!(run(&f).0.contains("move rapid X=55 Y=57 f=-"), "{}", run(&f).0);
    for (name, text, what) in [
        ("b.nc", "G54.1 P2\n#1=#4014\nM30\n", "#4014 read under the extended work offset G54.1 P2"),
        ("c.nc", "G55\n#1=#4130\nM30\n", "#4130 (the P number of the additional work offset G54.1)"),
    ] {
        let f = write(&d, name, text);
        let (_, err) = run(&f);
        assert!(err.contains("NC549") && err.contains(what), "{name}: {err}");
    }
    // Back to G54..G59 after an extended offset: read again.
    let f = write(&d, "e.nc", "G54.1 P2\nG56\n#1=#4014\nG0 X#1\nM30\n");
    assert!(run(&f).0.contains("move rapid X=56 f=-"), "{}", run(&f).0);
}

/// The corpus probing macro checks G90, G21 and G56 and keeps the motion mode it found:
/// each read becomes the constant the program selected, and the translation is proven on
/// the path where both sides touch and where either misses.
#[test]
fn the_mode_checking_probe_macro_translates_and_is_proven_on_its_paths() {
    let d = scratch("web");
    let src = "corpus/in/fanuc/probe-web-modes.nc";
    let out = d.join("out");
    let (code, _, err) = nctrans(&[src, "--to", "sinumerik", "-o", &format!("{}/", out.display())]);
    assert_eq!(code, 0, "{err}");
    let mpf = out.join("PROBE_WEB_MODES.MPF");
    let text = std::fs::read_to_string(&mpf).expect("translation written");
    for line in ["IF 90<>90 GOTOF LBL_910", "IF 21<>21 GOTOF LBL_910", "R120=56", "R121=1", "R122=21"] {
        assert!(text.contains(line), "`{line}` not in:\n{text}");
    }
    let mpf = mpf.to_string_lossy().into_owned();
    for probes in [&[][..], &["miss"][..], &["X=-12.47", "miss"][..]] {
        let mut args = vec!["check", src, &mpf];
        for p in probes {
            args.extend(["--probe", p]);
        }
        let (code, out, err) = nctrans(&args);
        assert_eq!(code, 0, "{probes:?}: {out}{err}");
        assert!(out.starts_with("equivalent"), "{probes:?}: {out}");
    }
    // Planted wrong constants: another offset, G91 for G90, G00 for G01.
    for (what, from, to) in [
        ("the work offset", "R120=56", "R120=55"),
        ("G90/G91", "IF 90<>90 GOTOF", "IF 91<>90 GOTOF"),
        ("the units", "IF 21<>21 GOTOF", "IF 20<>21 GOTOF"),
        ("the motion mode", "R121=1", "R121=0"),
        ("the tool", "R122=21", "R122=20"),
    ] {
        let bad = write(&d, "BAD.MPF", &text.replacen(from, to, 1));
        let (code, out, _) = nctrans(&["check", src, &bad]);
        assert_eq!(code, 1, "{what}: a wrong translation passed: {out}");
        assert!(out.starts_with("diverged"), "{what}: {out}");
    }
}

/// Where the program has not selected the mode itself on every path, or the block selects
/// one of the same group, or a called program may change it, there is no exact counterpart.
#[test]
fn reads_whose_mode_is_not_known_before_the_run_are_refused_by_name() {
    let d = scratch("refused");
    let cases = [
        (
            "a.nc",
            "O1\n#1=#4003\nM30\n",
            "#4003 (G90/G91 of the preceding block) read where the program has not set it itself",
        ),
        ("b.nc", "O1\nG90 G0 X0\nIF [#1 GT 0] GOTO 10\nG91\nN10 #2=#4003\nM30\n", "#4003"),
        ("c.nc", "O1\nG90 G0 X0\nG91 X#4003\nM30\n", "read in a block that sets it"),
        ("d.nc", "O1\nG90 G54 G0 X0\nM98 P2\n#1=#4014\nM30\nO2\nG55\nM99\n", "#4014 (the work offset"),
        ("e.nc", "O1\nG21 G0 X0\n#1=#4006\nG#1\nM30\n", ""),
        // Under G66 the macro runs after each move: G90 of a later block does not hold.
        ("f.nc", "O1\nG90 G0 X0\nG66 P9000\nG90 X10.\nG67\n#1=#4003\nM30\nO9000\nG91\nM99\n", "#4003"),
    ];
    for (name, text, what) in cases {
        let f = write(&d, name, text);
        let (code, _, err) = nctrans(&[&f, "--to", "sinumerik", "-o", &format!("{}/", d.join(name).display())]);
        assert_ne!(code, 0, "{name} translated");
        if name == "e.nc" {
            // The read folds (21); the computed G code has no Siemens form.
            assert!(!err.contains("NC549") && err.contains("NC363"), "{name}: {err}");
        } else {
            assert!(err.contains("NC549") && err.contains(what), "{name}: {err}");
        }
    }
}

/// D, H and T read back as FANUC's numbers (`#4107` is the register D5, where the Siemens
/// edge is D1 of tool 5), so a tool's length read through `#[11000+#4120]` is its edge
/// data; proven, and the value `$P_TOOL` would give (1) is caught.
#[test]
fn d_h_and_t_reads_become_the_numbers_the_program_wrote() {
    let d = scratch("dht");
    let src = write(
        &d,
        "t.nc",
        "O1\n(nctrans: set #11005=100.)\nT5 M6\nG0 X0 Y0\nG43 H5 Z50.\nG41 D5 G1 X10. F100.\n#1=#4107\n\
         #2=#[11000+#4120]+#4111\nG40 G1 X20.\nG0 Y#1 Z#2\nG49\nM30\n",
    );
    let out = d.join("out");
    let (code, _, err) = nctrans(&[&src, "--to", "sinumerik", "-o", &format!("{}/", out.display())]);
    assert_eq!(code, 0, "{err}");
    let mpf = out.join("P_T.MPF");
    let text = std::fs::read_to_string(&mpf).expect("translation written");
    assert!(text.contains("LOC1=5\n") && text.contains("LOC2=$TC_DP3[5,1]+5\n"), "{text}");
    let bad = write(&d, "BAD.MPF", &text.replacen("LOC1=5\n", "LOC1=$P_TOOL\n", 1));
    let (code, out, _) = nctrans(&["check", &src, &bad]);
    assert_eq!(code, 1, "the edge number passed for the register: {out}");
    // A loop condition sees every pass: G91 inside the loop leaves G90/G91 unknown there.
    let w = write(&d, "w.nc", "O1\nG90 G0 X0\n#1=0\nWHILE [#4003 EQ 90] DO1\n#1=#1+1\nG91\nEND1\nG90 X#1\nM30\n");
    let (_, _, err) = nctrans(&[&w, "--to", "sinumerik", "-o", &format!("{}/", d.join("w").display())]);
    assert!(err.contains("NC549") && err.contains("#4003"), "{err}");
    // A tool selected on one path only.
    let t = write(&d, "u.nc", "O1\nIF [#1 GT 0] GOTO 10\nT5 M6\nN10 #2=#4120\nM30\n");
    let (_, _, err) = nctrans(&[&t, "--to", "sinumerik", "-o", &format!("{}/", d.join("u").display())]);
    assert!(err.contains("NC549") && err.contains("#4120 (the T number"), "{err}");
}

/// Siemens → FANUC: `$P_TOOLNO` and `$P_TOOL` become the tool changed to and the edge
/// selected where the program did so on every path (FANUC's `#4120`/`#4107` hold other
/// things); proven, a wrong constant is caught, and a read where paths disagree stays NC342.
#[test]
fn the_active_tool_and_edge_read_back_on_fanuc_as_the_numbers_written() {
    let d = scratch("to-fanuc");
    let src = write(&d, "PT.MPF", "G90 G710\nT5 M6 D1\nR1=$P_TOOLNO\nR2=$P_TOOL\nG0 X=R1 Y=R2\nM30\n");
    let nc = d.join("pt.nc");
    let (code, out, err) = nctrans(&[&src, "--to", "fanuc", "-o", &nc.to_string_lossy()]);
    assert_eq!(code, 0, "{out}{err}");
    let text = std::fs::read_to_string(&nc).expect("translation written");
    assert!(text.contains("#501=5.\n#502=1.\n"), "{text}");
    let bad = write(&d, "bad.nc", &text.replacen("#501=5.", "#501=6.", 1));
    let (code, out, _) = nctrans(&["check", &src, &bad]);
    assert_eq!(code, 1, "a wrong tool passed: {out}");
    // Another tool on one path (a jump over the tool change), or in a loop's later passes.
    for (name, text) in [
        ("PU.MPF", "G90 G710\nIF R9>0 GOTOF SKIP1\nT5 M6 D1\nSKIP1:\nR1=$P_TOOLNO\nM30\n"),
        ("PW.MPF", "G90 G710\nT5 M6 D1\nWHILE R9<2\nR1=$P_TOOLNO\nT6 M6 D1\nR9=R9+1\nENDWHILE\nM30\n"),
    ] {
        let f = write(&d, name, text);
        let (_, _, err) = nctrans(&[&f, "--to", "fanuc", "-o", &d.join(format!("{name}.nc")).to_string_lossy()]);
        assert!(err.contains("NC342") && err.contains("$P_TOOLNO"), "{name}: {err}");
    }
}
