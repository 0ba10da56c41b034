//! More modal information reads (issues 20 and 21): Siemens `$P_GG[1]` (G0..G3 as 1..4) run
//! and translated to FANUC as the constant the program selected, the other groups refused
//! naming them; FANUC `#4113` (M) and `#4114` (N) run and translated to Sinumerik as the
//! constant, `#4102`, `#4115`, `#4130` refused by name; `GETSELT` refused with what is not
//! settled. Planted wrong translations are caught by the check.

mod eval_support;

use eval_support::{nctrans, run_bare, scratch_dir, write};
use std::path::PathBuf;

fn scratch(name: &str) -> PathBuf {
    scratch_dir("modal-reads-more-tests", name)
}

fn run(file: &str) -> (String, String) {
    run_bare(file, &[])
}

/// `$P_GG[1]` reads the internal number of the active G0..G3; the groups whose numbering
/// no source gives are refused naming the group (6 and 7: tests/modal_reads_groups.rs).
#[test]
fn p_gg_of_group_1_runs_and_the_other_groups_are_refused_by_name() {
    let d = scratch("eval");
    let f = write(
        &d,
        "A.MPF",
        "G90 G71\nG0 X0\nR1=$P_GG[1]\nG1 X1 F100\nR2=$P_GG[1]\nG2 X2 I0.5\nR3=$P_GG[1]\nG3 X3 I0.5\n\
         R4=$P_GG[1]\nG0 X=R1 Y=R2 Z=R3\nG0 X=R4\nM30\n",
    );
    let (out, err) = run(&f);
    assert!(out.contains("move rapid X=1 Y=2 Z=3 f=-") && out.contains("move rapid X=4 "), "{out}{err}");
    for (n, what) in [(14, "group 14: G90/G91"), (13, "group 13: the units"), (8, "group 8: the work offset"), (2, "")]
    {
        let f = write(&d, "B.MPF", &format!("G90 G71\nG0 X0\nR1=$P_GG[{n}]\nM30\n"));
        let (_, err) = run(&f);
        assert!(err.contains("NC656") && err.contains(&format!("$P_GG[{n}]")) && err.contains(what), "{n}: {err}");
    }
    // Read-only.
    let f = write(&d, "C.MPF", "G90 G71\n$P_GG[1]=2\nM30\n");
    assert!(run(&f).0.contains("$P_GG is read-only"), "{}", run(&f).0);
}

/// The corpus guard checks G1 before it cuts: `$P_GG[1]` becomes the 2 the program selected,
/// proven; a planted G0 (1) or G2 (3) is caught.
#[test]
fn the_motion_mode_guard_translates_to_fanuc_and_is_proven() {
    let d = scratch("guard");
    let src = "corpus/in/sinumerik/motion-mode-guard.mpf";
    let nc = d.join("guard.nc");
    let (code, out, err) = nctrans(&[src, "--to", "fanuc", "-o", &nc.to_string_lossy()]);
    assert_eq!(code, 0, "{out}{err}");
    let text = std::fs::read_to_string(&nc).expect("translation written");
    assert!(text.contains("#520=2. "), "{text}");
    let (code, out, _) = nctrans(&["check", src, &nc.to_string_lossy()]);
    assert_eq!(code, 0, "{out}");
    for wrong in ["#520=1. ", "#520=3. "] {
        let bad = write(&d, "bad.nc", &text.replacen("#520=2. ", wrong, 1));
        let (code, out, _) = nctrans(&["check", src, &bad]);
        assert_eq!(code, 1, "{wrong} passed: {out}");
        assert!(out.starts_with("diverged"), "{wrong}: {out}");
    }
    // Directly in a jump condition, too.
    let f = write(&d, "J.MPF", "G90 G71\nG1 X1 F100\nIF $P_GG[1]==2 GOTOF LIN\nG0 X5\nLIN:\nG0 X9\nM30\n");
    let nc = d.join("j.nc");
    let (code, out, err) = nctrans(&[&f, "--to", "fanuc", "-o", &nc.to_string_lossy()]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(std::fs::read_to_string(&nc).unwrap().contains("IF [2. EQ 2.] GOTO"));
    let (code, out, _) = nctrans(&["check", &f, &nc.to_string_lossy()]);
    assert_eq!(code, 0, "{out}");
}

/// Where the program has not selected G0..G3 on every path, in a block that sets group 1,
/// after a call or cycle, in a structured condition, or for another group: NC342 naming it.
#[test]
fn p_gg_reads_without_an_exact_fanuc_value_are_refused() {
    let d = scratch("refused");
    let g1 = "$P_GG[1] (G0..G3 as 1..4) read where the program has not selected";
    let cases = [
        ("A.MPF", "G90 G71\nR1=$P_GG[1]\nM30\n", g1),
        ("B.MPF", "G90 G71\nIF R9>0 GOTOF SK1\nG0 X0\nSK1:\nR1=$P_GG[1]\nM30\n", g1),
        ("C.MPF", "G90 G71\nG1 X0 F100\nG0 R1=$P_GG[1]\nM30\n", g1),
        ("D.MPF", "G90 G71\nG1 X0 F100\nCYCLE81(10,0,2,-5)\nR1=$P_GG[1]\nM30\n", g1),
        ("E.MPF", "G90 G71\nG1 X0 F100\nIF $P_GG[1]==2\nG0 X1\nENDIF\nM30\n", g1),
        ("F.MPF", "G90 G71\nG1 X0 F100\nR1=$P_GG[14]\nM30\n", "$P_GG[14] (group 14: G90/G91) (no source"),
        ("G.MPF", "G90 G71\nG1 X0 F100\nR2=1\nR1=$P_GG[R2]\nM30\n", "computed group number"),
        // A skippable block, a thread (group 1 numbers G33 otherwise), a loop's later passes.
        ("H.MPF", "G90 G71\nG1 X0 F100\n/G0 X1\nR1=$P_GG[1]\nM30\n", g1),
        ("I.MPF", "G90 G71\nG1 X0 F100\nG33 Z-5 K1\nR1=$P_GG[1]\nM30\n", g1),
        ("K.MPF", "G90 G71\nG1 X0 F100\nWHILE R9<2\nR1=$P_GG[1]\nG0 X1\nR9=R9+1\nENDWHILE\nM30\n", g1),
    ];
    for (name, text, what) in cases {
        let f = write(&d, name, text);
        let (code, out, err) = nctrans(&[&f, "--to", "fanuc", "-o", &d.join(format!("{name}.nc")).to_string_lossy()]);
        assert_ne!(code, 0, "{name} translated: {out}");
        assert!(err.contains("NC342") && err.contains(what), "{name}: {err}");
    }
}

/// `#4113` is the M code and `#4114` the sequence number of the preceding block; the corpus
/// macro checks the coolant M8 and keeps N40: both become constants, proven, and planted
/// wrong ones are caught.
#[test]
fn m_and_n_reads_run_and_translate_as_the_constants_written() {
    let d = scratch("mn");
    let f = write(&d, "a.nc", "O1\nG0 X0 M3 S100\nN20 M8\n#1=#4113\n#2=#4114\nG0 X#1 Y#2\nM30\n");
    assert!(run(&f).0.contains("move rapid X=8 Y=20 f=-"), "{}", run(&f).0);
    let src = "corpus/in/fanuc/coolant-check-m-code.nc";
    let out = d.join("out");
    let (code, _, err) = nctrans(&[src, "--to", "sinumerik", "-o", &format!("{}/", out.display())]);
    assert_eq!(code, 0, "{err}");
    let mpf = out.join("COOLANT_CHECK_M_CODE.MPF");
    let text = std::fs::read_to_string(&mpf).expect("translation written");
    assert!(text.contains("IF 8<>8 GOTOF LBL_910") && text.contains("R130=40 "), "{text}");
    let (code, out, _) = nctrans(&["check", src, &mpf.to_string_lossy()]);
    assert_eq!(code, 0, "{out}");
    for (from, to) in [("IF 8<>8", "IF 9<>8"), ("R130=40 ", "R130=41 ")] {
        let bad = write(&d, "BAD.MPF", &text.replacen(from, to, 1));
        let (code, out, _) = nctrans(&["check", src, &bad]);
        assert_eq!(code, 1, "{to} passed: {out}");
    }
}

/// M or N not known on every path, two M codes in one block, the read block's own N; and
/// `#4102`, `#4115`, `#4130`, whose values no source settles (run and translation alike).
#[test]
fn m_n_b_o_reads_without_a_settled_value_are_refused_by_name() {
    let d = scratch("mn-refused");
    let cases = [
        ("a.nc", "O1\nIF [#9 GT 0] GOTO 10\nM8\nN10 #1=#4113\nM30\n", "#4113 (the M code"),
        ("b.nc", "O1\nM3 M8 S100\n#1=#4113\nM30\n", "#4113 (the M code"),
        ("c.nc", "O1\nN10 G0 X0\nN20 #1=#4114\nM30\n", "#4114 (the sequence number N"),
        ("d.nc", "O1\nM8\nM98 P2\n#1=#4113\nM30\nO2\nM9\nM99\n", "#4113"),
        ("h.nc", "O1\nM8\n/M9\n#1=#4113\nM30\n", "#4113"),
        ("i.nc", "O1\nM8\nG0 X#4113 M9\nM30\n", "read in a block that sets it"),
        ("e.nc", "O1\nG0 X0\n#1=#4102\nM30\n", "#4102 (the B code"),
        ("f.nc", "O1\nG0 X0\n#1=#4115\nM30\n", "#4115 (the program number"),
        ("g.nc", "O1\nG55\n#1=#4130\nM30\n", "#4130 (the P number"),
    ];
    for (name, text, what) in cases {
        let f = write(&d, name, text);
        let (code, _, err) = nctrans(&[&f, "--to", "sinumerik", "-o", &format!("{}/", d.join(name).display())]);
        assert_ne!(code, 0, "{name} translated");
        assert!(err.contains("NC549") && err.contains(what), "{name}: {err}");
    }
    for (name, what) in [("e.nc", "#4102"), ("f.nc", "#4115")] {
        let (_, err) = run(&d.join(name).to_string_lossy());
        assert!(err.contains("NC549") && err.contains(what), "{name}: {err}");
    }
}

/// GETSELT: what tool management returns for the preselected tool, and whether FANUC's
/// `#4120` is it, is in no source read here: refused in the run and to FANUC, saying so.
#[test]
fn getselt_stays_refused_with_what_is_not_settled() {
    let d = scratch("getselt");
    let f = write(&d, "G.MPF", "DEF INT _T[1]\nT5\nR1=GETSELT(_T,1)\nM30\n");
    let (_, err) = run(&f);
    assert!(err.contains("NC508") && err.contains("preselected for the spindle"), "{err}");
    let (code, _, err) = nctrans(&[&f, "--to", "fanuc", "-o", &d.join("g.nc").to_string_lossy()]);
    assert_ne!(code, 0);
    assert!(err.contains("NC508") && err.contains("#4120 (the last T word) is not proven"), "{err}");
}
