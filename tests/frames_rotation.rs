//! Frames that turn, scale and mirror (issue #20, trace v2): what the evaluator reports for
//! FANUC G68/G69 and Siemens ROT/AROT, SCALE, MIRROR (positions the tool really reaches),
//! what it refuses where the controls differ, the translations both ways, and planted wrong
//! translations (rotation sign, centre, mirror axis, scale factor) caught.

use nctrans::check::Verdict;
use nctrans::dialect::{Dialect, ParseOptions, Semantics};
use nctrans::eval::{self, RunOptions, VecSink};
use nctrans::ir::Unit;
use nctrans::span::SourceDb;

#[path = "support/frame_check.rs"]
mod frame_check;
use frame_check::*;

#[test]
fn g68_rotates_moves_increments_and_arcs_about_its_centre() {
    let t = trace(
        "O1\nG17 G90 G54 G0 X0 Y0\nG68 X10. Y10. R90.\nG1 X20. Y10. F100.\nG91 X5.\nG90 G2 X20. Y15. R5.\nG69\nG0 X0 Y0\nM30\n",
        Dialect::Fanuc,
    );
    assert_eq!(
        t,
        "work_offset 1\nmove rapid X=0 Y=0 f=-\nmove linear X=10 Y=20 f=100\nmove linear X=10 Y=25 f=100\n\
         arc cw XY X=5 Y=20 center X=5 Y=25 f=100\nmove rapid X=0 Y=0 f=-\nend M30 steps=8"
    );
    // An X-only move in the turned system moves both machine axes.
    let t = trace("O1\nG0 X0 Y0\nG68 X0 Y0 R90.\nG0 X10. Y0\nX20.\nM30\n", Dialect::Fanuc);
    assert!(t.contains("move rapid X=0 Y=10 f=-\nmove rapid X=0 Y=20 f=-"), "{t}");
    // Without a centre: where the tool stands; without a decimal point R is in 0.001°.
    let t = trace("O1\nG0 X5. Y5.\nG68 R90000\nG0 X6. Y5.\nM30\n", Dialect::Fanuc);
    assert!(t.contains("move rapid X=5 Y=6 f=-"), "{t}");
}

#[test]
fn g68_under_g91_adds_the_angle_only_with_parameter_5400_rin() {
    let prog = "O1\nG0 X0 Y0\nG68 X0 Y0 R30.\nG91 G68 X0 Y0 R60.\nG90 G0 X10. Y0\nM30\n";
    // Default RIN = 0: R is absolute; the centre under G91 is refused either way.
    assert!(trace(prog, Dialect::Fanuc).ends_with("error NC490"));
    // In G68 mode a new G68 replaces the rotation (about the tool position without a centre).
    let prog = "O1\nG0 X0 Y0\nG68 X0 Y0 R30.\nG0 X0 Y0\nG91 G68 R60.\nG90 G0 X10. Y0\nM30\n";
    assert!(trace(prog, Dialect::Fanuc).contains("move rapid X=5 Y=8.660254 f=-"), "{}", trace(prog, Dialect::Fanuc));
    let prog = "O1\nG0 X0 Y0\nG68 X0 Y0 R30.\nG69\nG91 G68 R90.\nG90 G0 X10. Y0\nM30\n";
    let abs = trace(prog, Dialect::Fanuc);
    assert!(abs.contains("move rapid X=0 Y=10 f=-"), "{abs}");
    let mut sem = Semantics::default_for(Dialect::Fanuc);
    sem.rotation_angle_incremental = true;
    let opts = RunOptions { semantics: Some(sem), ..RunOptions::default() };
    let prog = "O1\nG0 X0 Y0\nG68 X0 Y0 R30.\nG91 G68 X0 Y0 R60.\nG90 G0 X10. Y0\nM30\n";
    assert!(trace_with(prog, Dialect::Fanuc, &opts).ends_with("error NC490"));
    let prog = "O1\nG0 X0 Y0\nG90 G68 X0 Y0 R30.\nG0 X0 Y0\nG91 G68 R60.\nG90 G0 X10. Y0\nM30\n";
    let inc = trace_with(prog, Dialect::Fanuc, &opts);
    assert!(inc.contains("move rapid X=0 Y=10 f=-"), "{inc}");
}

#[test]
fn where_the_controls_differ_under_a_rotation_is_refused() {
    let f = |body: &str| trace(&format!("O1\nG0 X0 Y0\nG68 X10. Y10. R30.\n{body}M30\n"), Dialect::Fanuc);
    // The first move after G68 / G69: incremental (FANUC takes the G68 position as the
    // centre), or leaving a plane axis out.
    assert!(f("G91 X5.\n").ends_with("error NC494"));
    assert!(f("G0 X5.\n").ends_with("error NC494"));
    assert!(f("G0 X5. Y5.\nG69\nG91 X1.\n").ends_with("error NC494"));
    // Plane selection, G52, reference returns and offsets in G68 mode.
    for body in ["G18\n", "G52 X1.\n", "G91 G28 Z0\n", "G55\n"] {
        assert!(f(body).ends_with("error NC491"), "{body}: {}", f(body));
    }
    // A hole as the first move after G68 leaving a plane axis out (cycles_rotated.rs has the rest).
    assert!(f("G81 X1. Z-5. R2. F100.\n").ends_with("error NC496"));
    assert!(f("G0 X0 Y0\n#1=#5001\n").ends_with("error NC400"));
    assert!(trace("O1\nG68 X0 Y0 R30. I0 J0 K1\nM30\n", Dialect::Fanuc).ends_with("error NC490"));
    // An arc out of the rotation's plane (Siemens may change the plane under a frame).
    let t = trace("G0 X0 Y0 Z0\nROT RPL=30\nG0 X0 Y0 Z0\nG18 G2 Z0 X10 CR=5 F100\nM30\n", Dialect::Sinumerik);
    assert!(t.ends_with("error NC495"), "{t}");
}

#[test]
fn siemens_rot_arot_compose_with_trans_in_the_turned_system() {
    let t = trace(
        "G17 G90 G0 X0 Y0\nTRANS X10 Y10\nAROT RPL=90\nG0 X5 Y0\nATRANS X5\nG0 X0 Y0\nROT Z90\nG0 X5 Y0\nTRANS\nG0 X0 Y0\nM30\n",
        Dialect::Sinumerik,
    );
    assert_eq!(
        t,
        "move rapid X=0 Y=0 f=-\nmove rapid X=10 Y=15 f=-\nmove rapid X=10 Y=15 f=-\nmove rapid X=0 Y=5 f=-\n\
         move rapid X=0 Y=0 f=-\nend M30 steps=11"
    );
    // ROT RPL= rotates in the active plane: G18 turns Z towards X.
    let t = trace("G18 G0 X0 Z0\nROT RPL=90\nG0 Z10 X0\nM30\n", Dialect::Sinumerik);
    assert!(t.contains("move rapid X=10 Z=0 f=-"), "{t}");
    // The programmable frame survives a work offset change.
    let t = trace("$P_UIFR[2,X,TR]=100\nG54\nG0 X0 Y0\nROT RPL=90\nG55\nG0 X10 Y0\nM30\n", Dialect::Sinumerik);
    assert!(t.contains("move rapid X=100 Y=10 f=-"), "{t}");
    assert!(trace("ROT X30 Y10\nM30\n", Dialect::Sinumerik).ends_with("error NC492"));
}

#[test]
fn mirroring_reverses_arcs_and_scaling_scales_radii_and_increments() {
    let t = trace("G0 X0 Y0\nMIRROR X0\nG0 X10 Y0\nG2 X0 Y10 CR=10 F100\nM30\n", Dialect::Sinumerik);
    assert!(t.contains("move rapid X=-10 Y=0 f=-\narc ccw XY X=0 Y=10 center X=-10 Y=10 f=100"), "{t}");
    let t = trace(
        "G0 X0 Y0\nSCALE X2 Y2\nG0 X10 Y0\nG91 G1 X5 F100\nG90 G3 X0 Y15 I=AC(0) J=AC(0)\nM30\n",
        Dialect::Sinumerik,
    );
    assert!(
        t.contains("move rapid X=20 Y=0 f=-\nmove linear X=30 Y=0 f=100\narc ccw XY X=0 Y=30 center X=0 Y=0 f=100"),
        "{t}"
    );
    // Unequal factors in an arc's plane: the controls differ.
    let t = trace("G0 X0 Y0\nSCALE X2 Y3\nG0 X10 Y0\nG3 X0 Y10 CR=10 F100\nM30\n", Dialect::Sinumerik);
    assert!(t.ends_with("error NC495"), "{t}");
    // ATRANS after SCALE is scaled too; a bare MIRROR clears the frame.
    let t = trace("SCALE X2\nATRANS X5\nG0 X0 Y0\nMIRROR\nG0 X0 Y0\nM30\n", Dialect::Sinumerik);
    assert!(t.contains("move rapid X=10 Y=0 f=-\nmove rapid X=0 Y=0 f=-"), "{t}");
}

const F_POCKET: &str = "O1\nG17 G90 G54 G0 X0 Y0 Z5.\nG68 X40. Y30. R30.\nG0 X30. Y20.\nG1 Z-2. F150.\nG91 X20. F300.\nY20.\nX-20.\nY-20.\nG90 G0 Z5.\nG69\nG0 X0 Y0\nM30\n";
const S_POCKET: &str = "G17 G90 G54 G0 X0 Y0 Z5\nATRANS X40 Y30\nAROT RPL=30\nATRANS X-40 Y-30\nG0 X30 Y20\nG1 Z-2 F150\nG91 X20 F300\nY20\nX-20\nY-20\nG90 G0 Z5\nTRANS\nG0 X0 Y0\nM30\n";

#[test]
fn a_rotation_about_a_centre_agrees_and_planted_differences_are_caught() {
    assert!(equivalent(F_POCKET, S_POCKET));
    for (from, to) in [("RPL=30", "RPL=-30"), ("ATRANS X40 Y30", "ATRANS X30 Y40"), ("ATRANS X-40 Y-30\n", "")] {
        assert!(!equivalent(F_POCKET, &S_POCKET.replacen(from, to, 1)), "{from} → {to}");
    }
    // A mirror axis and a scale factor.
    let f = "O1\nG0 X0 Y0\nG0 X10. Y5.\nM30\n";
    assert!(equivalent(f, "G0 X0 Y0\nG0 X10 Y5\nM30\n"));
    assert!(!equivalent("O1\nG0 X0 Y0\nG0 X-10. Y5.\nM30\n", "G0 X0 Y0\nMIRROR Y0\nG0 X10 Y5\nM30\n"));
    assert!(equivalent("O1\nG0 X0 Y0\nG0 X-10. Y5.\nM30\n", "G0 X0 Y0\nMIRROR X0\nG0 X10 Y5\nM30\n"));
    assert!(!equivalent("O1\nG0 X0 Y0\nG0 X20. Y10.\nM30\n", "G0 X0 Y0\nSCALE X2 Y3\nG0 X10 Y5\nM30\n"));
}

mod translation {
    use super::*;

    #[test]
    fn g68_about_a_centre_becomes_atrans_arot_atrans_and_g69_undoes_it() {
        let out = f_to_s(F_POCKET).unwrap();
        for line in [
            "ATRANS X40 Y30\nAROT RPL=30\nATRANS X-40 Y-30\nG0 X30 Y20\n",
            "G0 Z5\nATRANS X40 Y30\nAROT RPL=-30\nATRANS X-40 Y-30\nG0 X0 Y0\n",
        ] {
            assert!(out.contains(line), "{line:?} missing in\n{out}");
        }
        // About the origin: AROT alone; a G69 with no rotation in force: nothing.
        let out = f_to_s("O1\nG69\nG0 X0 Y0\nG68 X0 Y0 R45.\nG0 X10. Y0\nG69 G0 X0 Y0\nM30\n").unwrap();
        assert!(out.contains("G0 X0 Y0\nAROT RPL=45\nG0 X10 Y0\nAROT RPL=-45\nG0 X0 Y0\n"), "{out}");
        // In a loop: the G68 of each pass is the one G69 undoes.
        let out =
            f_to_s("O1\nG0 X0 Y0\n#1=0\nWHILE[#1LT3]DO1\nG68 X5. Y5. R90.\nG0 X10. Y5.\nG69\n#1=#1+1\nEND1\nM30\n");
        assert!(out.is_ok(), "{out:?}");
    }

    #[test]
    fn g68_and_g69_without_an_exact_counterpart_are_refused() {
        let nc497 = Err(vec!["NC497".to_string()]);
        // No centre: the tool position, over a G52 shift and in G18 too (tests/g68_planes.rs);
        // refused where the plane depends on the path taken.
        let out = f_to_s("O1\nG52 X5. Y0 Z0\nG68 R30.\nM30\n").unwrap();
        assert!(out.contains("TRANS X5\nNCTRANS_G68_X=$P_EP[X]"), "{out}");
        let out = f_to_s("O1\nG18\nG68 R30.\nM30\n").unwrap();
        assert!(out.contains("NCTRANS_G68_Z=$P_EP[Z]\nNCTRANS_G68_X=$P_EP[X]"), "{out}");
        let by_path = "O1\nIF[#1EQ1]GOTO10\nG18\nN10 G68 R30.\nM30\n";
        assert_eq!(f_to_s(by_path), nc497, "no centre where the plane depends on the path");
        assert_eq!(f_to_s("O1\nG68 X0 Y0\nM30\n"), nc497, "no angle");
        assert_eq!(f_to_s("O1\nG91 G68 X0 Y0 R30.\nM30\n"), nc497, "under G91");
        assert_eq!(f_to_s("O1\nG68 X0 Y0 R#1\nM30\n"), nc497, "not a constant");
        // G68 in G68 mode replaces the rotation: the frame written anew (frames_rotation_replace).
        let out = f_to_s("O1\nG68 X0 Y0 R30.\nG68 X0 Y0 R60.\nM30\n").unwrap();
        assert!(out.contains("AROT RPL=30\nTRANS\nAROT RPL=60\n"), "{out}");
        // A G69 whose rotation depends on the path: bare TRANS over an empty frame; over a
        // G52 shift, which the frame holds too, refused.
        let path = "O1\nIF[#1EQ1]GOTO10\nG68 X0 Y0 R30.\nN10 G69\nM30\n";
        let out = f_to_s(path).unwrap();
        assert!(out.contains("AROT RPL=30\nN10 LBL_10:\nTRANS\nM30"), "{out}");
        let shifted = "O1\nG52 X5. Y0 Z0\nIF[#1EQ1]GOTO10\nG68 X0 Y0 R30.\nN10 G69\nG52 X0 Y0 Z0\nM30\n";
        assert_eq!(f_to_s(shifted), nc497, "the rotation at G69 depends on the path, over a shift");
    }

    #[test]
    fn trans_then_arot_becomes_g52_and_g68_and_rot_cancels_first() {
        let s = "G17 G90 G54 G0 X0 Y0 Z5\nTRANS X40 Y30\nAROT RPL=30\nG0 X-10 Y-10\nG1 Z-2 F150\nG1 X10 F300\nY10\nG0 Z5\nTRANS\nG0 X0 Y0\nROT RPL=-15\nG0 X20 Y0\nROT\nG0 X0 Y0\nM30\n";
        let out = s_to_f(s).unwrap();
        for line in [
            "G69\nG52 X40. Y30. Z0.\nG68 X0. Y0. R30.\n",
            "G00 Z5.\nG69\nG52 X0. Y0. Z0.\n",
            "G69\nG52 X0. Y0. Z0.\nG68 X0. Y0. R-15.\nG00 X20. Y0.\nG69\nG52 X0. Y0. Z0.\n",
        ] {
            assert!(out.contains(line), "{line:?} missing in\n{out}");
        }
        let nc498 = Err(vec!["NC498".to_string()]);
        assert_eq!(s_to_f("ROT RPL=30\nAROT RPL=10\nM30\n"), nc498, "AROT on another rotation");
        assert_eq!(s_to_f("G17\nG18\nROT RPL=30\nM30\n"), nc498, "not one plane");
        // One plane from the first blocks on: G68 in it (tests/frames_more.rs).
        assert!(s_to_f("G18\nROT RPL=30\nM30\n").unwrap().contains("G68 Z0. X0. R30."));
        assert_eq!(s_to_f("ROT X30\nM30\n"), nc498, "in space");
        assert_eq!(s_to_f("G0 X0\nAROT RPL=30\nM30\n").map(|_| ()), Ok(()), "at the start of a main program");
    }

    #[test]
    fn exact_stop_contouring_and_feed_modes_translate_both_ways() {
        let out = f_to_s("O1\nG09 G1 X1. F100.\nG61\nG1 X2.\nG64\nG95 G1 X3. F0.1\nG94\nM30\n").unwrap();
        assert!(out.contains("G9 G1 X1 F100\nG60\nG1 X2\nG64\nG95 G1 X3 F0.1\nG94\n"), "{out}");
        let out = s_to_f("G9 G1 X1 F100\nG60\nG1 X2\nG64\nG95 G1 X3 F0.1\nG94\nM30\n").unwrap();
        assert!(out.contains("G09 G01 X1. F100.\nG61\nG01 X2.\nG64\nG95 G01 X3. F0.1\nG94\n"), "{out}");
    }

    #[test]
    fn g74_under_g91_does_not_write_g91_again() {
        let out = s_to_f("G0 Z5\nG91\nG74 Z1=0\nG90 G0 X0\nM30\n").unwrap();
        assert!(out.contains("G91\nG28 Z0.\nG90 G00 X0.\n"), "{out}");
        let out = s_to_f("G0 Z5\nG74 Z1=0\nM30\n").unwrap();
        assert!(out.contains("G91 G28 Z0.\nG90\n"), "{out}");
    }

    #[test]
    fn planted_wrong_rotations_are_caught() {
        let good = f_to_s(F_POCKET).unwrap();
        for (from, to) in
            [("RPL=30", "RPL=-30"), ("ATRANS X40 Y30", "ATRANS X40 Y-30"), ("AROT RPL=-30", "AROT RPL=30")]
        {
            assert!(good.contains(from), "{from:?} not in\n{good}");
            let bad = good.replacen(from, to, 1);
            assert!(!equivalent(F_POCKET, &bad), "planted {from:?} → {to:?} not caught\n{bad}");
        }
        let s = "G0 X0 Y0\nTRANS X40 Y30\nAROT RPL=30\nG0 X10 Y0\nTRANS\nG0 X0 Y0\nM30\n";
        let good = s_to_f(s).unwrap();
        for (from, to) in [("R30.", "R-30."), ("G52 X40. Y30.", "G52 X30. Y40."), ("G68 X0. Y0.", "G68 X40. Y30.")] {
            assert!(good.contains(from), "{from:?} not in\n{good}");
            let bad = good.replacen(from, to, 1);
            assert!(!equivalent(&bad, s), "planted {from:?} → {to:?} not caught\n{bad}");
        }
    }
}

#[test]
fn fanuc_mirror_and_scaling_and_their_order() {
    let t = trace(
        "O1\nG0 X10. Y10.\nG51.1 X0\nG0 X10. Y10.\nG2 X20. Y10. R5. F100.\nG50.1 X0\nG0 X10. Y10.\nM30\n",
        Dialect::Fanuc,
    );
    assert!(
        t.contains(
            "move rapid X=-10 Y=10 f=-\narc ccw XY X=-20 Y=10 center X=-15 Y=10 f=100\nmove rapid X=10 Y=10 f=-"
        ),
        "{t}"
    );
    // P without a decimal point counts 0.001; only the axes whose centre G51 names scale.
    let t = trace(
        "O1\nG0 X0 Y0 Z10.\nG51 X5. Y5. P2000\nG0 X10. Y10. Z1.\nG91 G1 X5. F100.\nG90 G50\nG0 X0 Y0\nM30\n",
        Dialect::Fanuc,
    );
    assert!(
        t.contains("move rapid X=15 Y=15 Z=1 f=-\nmove linear X=25 Y=15 Z=1 f=100\nmove rapid X=0 Y=0 Z=1 f=-"),
        "{t}"
    );
    // I J: a factor each (unequal factors refuse arcs in their plane).
    let t = trace("O1\nG0 X0 Y0\nG51 X0 Y0 I2. J3.\nG0 X1. Y1.\nG2 X3. Y1. R1. F100.\nM30\n", Dialect::Fanuc);
    assert!(t.contains("move rapid X=2 Y=3 f=-") && t.ends_with("error NC495"), "{t}");
    // Scaling, then a rotation whose centre scales too.
    let t = trace("O1\nG0 X0 Y0\nG51 X0 Y0 P2.\nG68 X10. Y10. R90.\nG0 X20. Y10.\nG69\nG50\nM30\n", Dialect::Fanuc);
    assert!(t.contains("move rapid X=20 Y=40 f=-"), "{t}");
    // Out of the order mirror, scaling, rotation; coordinate codes in the modes.
    assert!(trace("O1\nG51 X0 Y0 P2.\nG51.1 X0\nM30\n", Dialect::Fanuc).ends_with("error NC491"));
    assert!(trace("O1\nG68 X0 Y0 R9.\nG51 X0 Y0 P2.\nM30\n", Dialect::Fanuc).ends_with("error NC491"));
    assert!(trace("O1\nG51.1 X0\nG52 X5.\nM30\n", Dialect::Fanuc).ends_with("error NC491"));
    assert!(trace("O1\nG51 P2.\nM30\n", Dialect::Fanuc).ends_with("error NC490"), "no centre");
}

mod scale_and_mirror_translation {
    use super::*;
    use nctrans::read::LineEnding;
    use nctrans::translate::to_sinumerik::{translate as to_sinumerik, Options};
    use nctrans::translate::{self, to_fanuc::TranslateOptions};

    fn f_to_s(fanuc: &str) -> Result<String, Vec<String>> {
        let mut db = SourceDb::new();
        let id = db.add("p.nc", fanuc);
        let p = nctrans::parse(&db, id, Dialect::Fanuc, &ParseOptions::for_dialect(Dialect::Fanuc));
        let t = to_sinumerik(&[&p.unit], &Options::default(), LineEnding::Lf);
        if t.has_errors() {
            let mut codes: Vec<String> = t.diags.iter().map(|d| d.code.to_string()).collect();
            codes.dedup();
            return Err(codes);
        }
        let r = nctrans::translate::to_sinumerik::verify::verify_with(&db, id, &p.unit, &t, "out", 100_000);
        let text: String = t.files.iter().map(|x| x.text.clone()).collect();
        assert!(matches!(r.verdict, Verdict::Equivalent { .. }), "{:?}\n{}\n{text}", r.verdict, r.diff);
        Ok(text)
    }

    fn s_to_f(siemens: &str) -> Result<String, Vec<String>> {
        let mut db = SourceDb::new();
        let s = load(&mut db, siemens, Dialect::Sinumerik);
        let t = translate::to_fanuc::to_fanuc(&s, &[], &TranslateOptions::default());
        if !t.ok() {
            let mut codes: Vec<String> = t.diags.iter().map(|d| d.code.to_string()).collect();
            codes.dedup();
            return Err(codes);
        }
        let v = translate::to_fanuc::verify(&mut db, &s, &[], &t.clone().into(), "out.nc", 100_000);
        assert!(v.equivalent, "{}\n{}\n{}", v.summary, v.rendered, t.text);
        Ok(t.text)
    }

    const F: &str = "O1\nG17 G90 G0 X0 Y0 Z5.\nG0 X10. Y10.\nG2 X20. Y10. R5. F100.\nG51.1 X40.\nG0 X10. Y10.\nG2 X20. Y10. R5.\nG50.1 X0\nG51 X5. Y5. P1500\nG0 X10. Y10.\nG3 X20. Y10. R5.\nG50\nG0 X0 Y0\nM30\n";

    #[test]
    fn g51_1_and_g51_become_amirror_and_ascale_about_their_centre() {
        let out = f_to_s(F).unwrap();
        for line in [
            "ATRANS X40\nAMIRROR X0\nATRANS X-40\nG0 X10 Y10\n",
            "ATRANS X40\nAMIRROR X0\nATRANS X-40\nATRANS X5 Y5\nASCALE X1.5 Y1.5\nATRANS X-5 Y-5\n",
            "ATRANS X5 Y5\nASCALE X=1/1.5 Y=1/1.5\nATRANS X-5 Y-5\nG0 X0 Y0\n",
        ] {
            assert!(out.contains(line), "{line:?} missing in\n{out}");
        }
        for (from, to) in
            [("AMIRROR X0", "AMIRROR Y0"), ("ASCALE X1.5 Y1.5", "ASCALE X2 Y1.5"), ("ATRANS X40\n", "ATRANS X20\n")]
        {
            assert!(out.contains(from), "{from:?} not in\n{out}");
            assert!(!equivalent(F, &out.replacen(from, to, 1)), "planted {from:?} → {to:?} not caught");
        }
        // Modes one after the other, each cancelled by its own code.
        let seq = "O1\nG0 X0 Y0\nG51 X0 Y0 P2.\nG0 X5. Y0\nG50\nG68 X0 Y0 R90.\nG0 X5. Y0\nG69\nG51.1 Y0\nG0 X5. Y5.\nG50.1 Y0\nG0 X0 Y0\nM30\n";
        let out = f_to_s(seq).unwrap();
        assert!(
            out.contains("ASCALE X=0.5 Y=0.5\nAROT RPL=90\n") || out.contains("ASCALE X0.5 Y0.5\nAROT RPL=90\n"),
            "{out}"
        );
        let nc497 = vec!["NC497".to_string()];
        assert_eq!(f_to_s("O1\nG51.1 X0 Y0\nG50.1 X0\nM30\n").unwrap_err(), nc497, "partial cancel");
        assert_eq!(f_to_s("O1\nG51.1 X0\nG68 X0 Y0 R5.\nM30\n").unwrap_err(), nc497, "two modes");
        assert_eq!(f_to_s("O1\nG51 X0 Y0 P#1\nM30\n").unwrap_err(), nc497, "not a constant");
    }

    #[test]
    fn mirror_and_scale_become_g51_1_and_g51_and_planted_errors_are_caught() {
        let s = "G17 G90 G0 X0 Y0 Z5\nMIRROR X0\nG0 X10 Y10\nG2 X20 Y10 CR=5 F100\nTRANS X50 Y0\nAMIRROR Y0\nG0 X10 Y10\nTRANS\nSCALE X1.5 Y1.5\nG0 X10 Y10\nG3 X20 Y10 CR=5\nMIRROR\nG0 X0 Y0\nM30\n";
        let out = s_to_f(s).unwrap();
        for line in [
            "G50\nG50.1 X0. Y0. Z0.\nG52 X0. Y0. Z0.\nG51.1 X0.\n",
            "G52 X50. Y0. Z0.\nG51.1 Y0.\n",
            "G51 X0. Y0. I1.5 J1.5\n",
        ] {
            assert!(out.contains(line), "{line:?} missing in\n{out}");
        }
        for (from, to) in [("G51.1 X0.", "G51.1 Y0."), ("I1.5 J1.5", "I1.5 J2."), ("G51.1 Y0.", "G51.1 Y5.")] {
            assert!(out.contains(from), "{from:?} not in\n{out}");
            assert!(!equivalent(&out.replacen(from, to, 1), s), "planted {from:?} → {to:?} not caught");
        }
        assert_eq!(s_to_f("SCALE X=R1\nM30\n").unwrap_err(), vec!["NC498".to_string()]);
        assert_eq!(s_to_f("MIRROR X0\nAROT RPL=5\nM30\n").unwrap_err(), vec!["NC498".to_string()]);
    }
}

/// One called Siemens program, by name.
struct OneCallee(&'static str, &'static str);

impl eval::CalleeSource for OneCallee {
    fn find(
        &mut self,
        db: &mut SourceDb,
        _caller: nctrans::span::FileId,
        d: Dialect,
        name: &eval::CalleeName,
    ) -> Result<Option<Unit>, nctrans::diag::Diagnostic> {
        match name {
            eval::CalleeName::Name(n) if n == self.0 => {
                let id = db.add(format!("{n}.SPF"), self.1);
                Ok(Some(nctrans::parse(db, id, d, &ParseOptions::for_dialect(d)).unit))
            }
            _ => Ok(None),
        }
    }
}

#[test]
fn the_programmable_frame_survives_a_return_and_proc_save_restores_it() {
    let run = |sub: &'static str| {
        let mut db = SourceDb::new();
        let unit = load(&mut db, "G0 X0 Y0\nTRANS X10\nAROT RPL=90\nPOCK\nG0 X5 Y0\nM30\n", Dialect::Sinumerik);
        let mut sink = VecSink::default();
        let mut callees = OneCallee("POCK", sub);
        let out = eval::run(&mut db, &unit, &mut callees, &RunOptions::default(), &mut sink);
        assert!(!nctrans::diag::has_errors(&out.diags), "{}", nctrans::diag::render(&db, &out.diags));
        sink.events.iter().map(|(e, _)| eval::trace::text_line(e)).collect::<Vec<_>>().join("\n")
    };
    // The subprogram's ROT RPL=0 deletes the frame; with SAVE the caller's comes back.
    let kept = run("PROC POCK SAVE\nROT RPL=0\nG0 X5 Y0\nRET\n");
    assert!(kept.ends_with("move rapid X=5 Y=0 f=-\nmove rapid X=10 Y=5 f=-\nend M30 steps=9"), "{kept}");
    let lost = run("PROC POCK\nROT RPL=0\nG0 X5 Y0\nRET\n");
    assert!(lost.ends_with("move rapid X=5 Y=0 f=-\nmove rapid X=5 Y=0 f=-\nend M30 steps=9"), "{lost}");
}
