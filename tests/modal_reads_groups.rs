//! Siemens `$P_GG[6]` (the plane G17/G18/G19 as 1..3) and `$P_GG[7]` (the radius
//! compensation G40/G41/G42 as 1..3), numbered by the SINUMERIK ONE programming manual's G
//! group tables (docs/semantics.md, Modal information): run, a read in a block that changes
//! the mode seeing the mode before it, the groups without a source refused by name.

mod eval_support;

use eval_support::{nctrans, run_bare, scratch_dir, write};
use std::path::PathBuf;

fn scratch(name: &str) -> PathBuf {
    scratch_dir("modal-reads-groups-tests", name)
}

fn run(file: &str) -> (String, String) {
    run_bare(file, &[])
}

/// Each value of groups 6 and 7, and the read in `G19 R3=$P_GG[6]` / `G42 … R7=$P_GG[7]`
/// seeing the plane and side before the block (as group 1 does).
#[test]
fn plane_and_radius_compensation_groups_run_with_their_list_numbers() {
    let d = scratch("eval");
    let f = write(
        &d,
        "A.MPF",
        "G90 G71\nG0 X0\nR1=$P_GG[6]\nG18\nR2=$P_GG[6]\nG19 R3=$P_GG[6]\nR4=$P_GG[6]\nG17\nR5=$P_GG[7]\n\
         T1 D1\nG41 G1 X10 Y0 F100\nR6=$P_GG[7]\nG42 X20 R7=$P_GG[7]\nR8=$P_GG[7]\nG40 X30\nR9=$P_GG[7]\n\
         G0 X=R1 Y=R2 Z=R3\nG0 X=R4 Y=R5 Z=R6\nG0 X=R7 Y=R8 Z=R9\nM30\n",
    );
    let (out, err) = run(&f);
    for want in ["move rapid X=1 Y=2 Z=2 f=-", "move rapid X=3 Y=1 Z=2 f=-", "move rapid X=2 Y=3 Z=1 f=-"] {
        assert!(out.contains(want), "{want}: {out}{err}");
    }
    // Not a wrong value where the run meets a group without a source: NC656 naming it.
    for (n, what) in [(14, "group 14: G90/G91"), (15, "group 15: the feed type"), (10, "")] {
        let f = write(&d, "B.MPF", &format!("G90 G71\nG0 X0\nR1=$P_GG[{n}]\nM30\n"));
        let (_, err) = run(&f);
        assert!(err.contains("NC656") && err.contains(&format!("$P_GG[{n}]")) && err.contains(what), "{n}: {err}");
        assert!(err.contains("group 6 G17/G18/G19 = 1..3"), "{n}: {err}");
    }
}

/// To FANUC, `$P_GG[6]`/`[7]` become the number of the function the program selected on
/// every path, proven by the check; planted wrong numbers are caught.
#[test]
fn plane_and_compensation_reads_translate_to_fanuc_as_the_constants_selected() {
    let d = scratch("to-fanuc");
    let f = write(
        &d,
        "B.MPF",
        "G90 G71\nT1 M6\nD1\nG18 G1 X0 Z0 F100\nR1=$P_GG[6]\nG42 X10\nR2=$P_GG[7]\nG17 G40 X20\nR3=$P_GG[6]\n\
         R4=$P_GG[7]\nG0 X=R1 Y=R2 Z=R3\nG0 X=R4\nM30\n",
    );
    let nc = d.join("b.nc");
    let (code, out, err) = nctrans(&[&f, "--to", "fanuc", "-o", &nc.to_string_lossy()]);
    assert_eq!(code, 0, "{out}{err}");
    let text = std::fs::read_to_string(&nc).expect("translation written");
    for want in ["#501=2.", "#502=3.", "#503=1.", "#504=1."] {
        assert!(text.contains(want), "{want}: {text}");
    }
    let (code, out, _) = nctrans(&["check", &f, &nc.to_string_lossy()]);
    assert_eq!(code, 0, "{out}");
    for (from, to) in [("#501=2.", "#501=1."), ("#502=3.", "#502=2."), ("#503=1.", "#503=3."), ("#504=1.", "#504=2.")] {
        let bad = write(&d, "bad.nc", &text.replacen(from, to, 1));
        let (code, out, _) = nctrans(&["check", &f, &bad]);
        assert_eq!(code, 1, "{to} passed: {out}");
        assert!(out.starts_with("diverged"), "{to}: {out}");
    }
}

/// Where the plane or side is not selected on every path, or the read's block sets it, or
/// the group has no source: NC342 naming it.
#[test]
fn plane_and_compensation_reads_without_an_exact_fanuc_value_are_refused() {
    let d = scratch("refused");
    let g6 = "$P_GG[6] (G17/G18/G19 as 1..3) read where the program has not selected";
    let g7 = "$P_GG[7] (G40/G41/G42 as 1..3) read where the program has not selected";
    let cases = [
        ("A.MPF", "G90 G71\nR1=$P_GG[6]\nM30\n", g6),
        ("B.MPF", "G90 G71\nG17\nIF R9>0 GOTOF SK1\nG18\nSK1:\nR1=$P_GG[6]\nM30\n", g6),
        ("C.MPF", "G90 G71\nG17\nG18 R1=$P_GG[6]\nM30\n", g6),
        ("D.MPF", "G90 G71\nG40\nR1=$P_GG[7]\nCYCLE81(10,0,2,-5)\nR1=$P_GG[6]\nM30\n", g6),
        ("E.MPF", "G90 G71\nR1=$P_GG[7]\nM30\n", g7),
        ("F.MPF", "G90 G71\nG40\nIF $P_GG[7]==1\nG0 X1\nENDIF\nM30\n", g7),
        ("G.MPF", "G90 G71\nG90\nR1=$P_GG[14]\nM30\n", "$P_GG[14] (group 14: G90/G91) (no source"),
    ];
    for (name, text, what) in cases {
        let f = write(&d, name, text);
        let (code, out, err) = nctrans(&[&f, "--to", "fanuc", "-o", &d.join(format!("{name}.nc")).to_string_lossy()]);
        assert_ne!(code, 0, "{name} translated: {out}");
        assert!(err.contains("NC342") && err.contains(what), "{name}: {err}");
    }
}

/// To Sinumerik, `#4002` and `#4007` read where the program has not set the mode on every
/// path become `$P_GG[6]+16` and `$P_GG[7]+39`, proven on both paths; planted wrong forms
/// are caught. `#4003` (group 14, no source for its numbering) stays NC549, so the probe
/// macro's opening `#3=#4003` does not translate yet.
#[test]
fn fanuc_plane_and_compensation_reads_become_p_gg_where_the_path_decides() {
    let d = scratch("to-sinumerik");
    // The plane depends on the path taken; the subprogram's compensation on its caller.
    for first in ["1", "0"] {
        let src = write(
            &d,
            &format!("c{first}.nc"),
            &format!(
                "O1\nG90 G21 G17 G40 G49\nT1 M6\nG43 H1 Z10\nG41 D1 G1 X5 Y0 F100\nM98 P100\nG40 G0 X0\n#1={first}\n\
                 IF [#1 GT 0] GOTO 10\nG18\nN10 #3=#4002\nG0 X#3 Y#4\nM30\nO100\n#4=#4007\nM99\n"
            ),
        );
        let out = d.join(format!("out{first}"));
        let (code, o, err) = nctrans(&[&src, "--to", "sinumerik", "-o", &format!("{}/", out.display())]);
        assert_eq!(code, 0, "{o}{err}");
        let main = out.join(format!("P_C{first}.MPF"));
        let sub = out.join("O_0100.SPF");
        let text = std::fs::read_to_string(&main).expect("translation written");
        let subtext = std::fs::read_to_string(&sub).expect("translation written");
        assert!(text.contains("=$P_GG[6]+16") && subtext.contains("=$P_GG[7]+39"), "{text}{subtext}");
        let (code, o, _) = nctrans(&["check", &src, &main.to_string_lossy()]);
        assert_eq!(code, 0, "{first}: {o}");
        let planted = [
            (&main, &text, "$P_GG[6]+16", "$P_GG[6]+17"),
            (&main, &text, "$P_GG[6]+16", "17"),
            (&sub, &subtext, "$P_GG[7]+39", "$P_GG[6]+39"),
            (&sub, &subtext, "$P_GG[7]+39", "$P_GG[7]+40"),
        ];
        for (file, good, from, to) in planted {
            std::fs::write(file, good.replacen(from, to, 1)).unwrap();
            let (code, o, _) = nctrans(&["check", &src, &main.to_string_lossy()]);
            std::fs::write(file, good).unwrap();
            // The planted plane is wrong on one path only: where `first` takes the other, it agrees.
            if to == "17" && first == "1" {
                assert_eq!(code, 0, "{first}: {to}: {o}");
                continue;
            }
            assert_eq!(code, 1, "{first}: {to} passed: {o}");
            assert!(o.starts_with("diverged"), "{first} {to}: {o}");
        }
    }
    let probe = write(
        &d,
        "probe.nc",
        "O1\nG90 G21 G17 G40 G94\nG65 P9000\nM30\nO9000\n#3=#4003\nG91 G31 Z-10. F500\n#10=#5063\nG#3\nM99\n",
    );
    let (code, _, err) = nctrans(&[&probe, "--to", "sinumerik", "-o", &format!("{}/", d.join("probe").display())]);
    // `#3=#4003` … `G#3 M99` is the save/restore idiom, taken as PROC … SAVE (tests/save_idiom.rs):
    // the read is no longer refused; the skip position under a caller's G43 still is.
    assert_ne!(code, 0);
    assert!(!err.contains("NC549") && err.contains("NC550"), "{err}");
}
