//! Coordinate systems, frames and reference returns (issue #20, trace v2): what the
//! evaluator reports for FANUC G52/G53/G54.1/G28/G30 and Siemens TRANS/ATRANS/SUPA/G74/G75,
//! that the two dialects' forms of one part agree, and that planted differences (offset
//! number, missing intermediate point, wrong shift sign) are caught.

use nctrans::check::Verdict;
use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::span::SourceDb;

#[path = "support/frame_check.rs"]
mod frame_check;
use frame_check::*;

#[test]
fn g52_shifts_every_work_offset_per_axis_until_cancelled() {
    let t = trace(
        "O1\nG10 L2 P2 X100. Y0 Z0\nG90 G54\nG52 X10. Y5.\nG0 X0 Y0\nG52 Y20.\nG0 X0 Y0\nG55\nG0 X0 Y0\nG52 X0 Y0 Z0\nG0 X0 Y0\nM30\n",
        Dialect::Fanuc,
    );
    assert_eq!(
        t,
        "work_offset 1\nmove rapid X=10 Y=5 f=-\nmove rapid X=10 Y=20 f=-\nwork_offset 2\nmove rapid X=110 Y=20 f=-\n\
         move rapid X=100 Y=0 f=-\nend M30 steps=11"
    );
}

#[test]
fn g52_under_g91_is_refused() {
    assert!(trace("O1\nG91 G52 X10.\nM30\n", Dialect::Fanuc).ends_with("error NC440"));
}

#[test]
fn extended_offsets_and_their_siemens_numbers() {
    assert_eq!(
        trace("O1\nG54.1 P3\nG54 P1\nG59\nM30\n", Dialect::Fanuc),
        "work_offset 9\nwork_offset 7\nwork_offset 6\nend M30 steps=4"
    );
    assert_eq!(
        trace("G500\nG54\nG57\nG505\nG509\nM30\n", Dialect::Sinumerik),
        "work_offset 0\nwork_offset 1\nwork_offset 4\nwork_offset 5\nwork_offset 9\nend M30 steps=6"
    );
    assert!(trace("O1\nG54.1 P49\nM30\n", Dialect::Fanuc).contains("alarm"));
}

#[test]
fn g28_moves_to_the_intermediate_point_then_homes() {
    let t = trace("O1\nG0 X10. Y10. Z100.\nG28 G90 Z50.\nG0 X0\nG91 G28 X0 Y0\nM30\n", Dialect::Fanuc);
    assert_eq!(
        t,
        "move rapid X=10 Y=10 Z=100 f=-\nmove rapid X=10 Y=10 Z=50 f=-\nhome point=1 axes=Z via Z=50\n\
         move rapid X=0 Y=10 Z=0 f=-\nhome point=1 axes=XY via X=0 Y=10\nend M30 steps=5"
    );
    // G28 leaves the motion mode as it was: the next block still feeds.
    let t = trace("O1\nG1 X10. F100.\nG91 G28 Z0\nG90 X20.\nM30\n", Dialect::Fanuc);
    assert!(t.contains("move linear X=20 Z=0 f=100"), "{t}");
}

#[test]
fn g30_points_and_siemens_g75_fixed_points() {
    assert!(trace("O1\nG91 G30 P3 Z0\nM30\n", Dialect::Fanuc).starts_with("home point=3 axes=Z via Z=0"));
    assert!(trace("O1\nG91 G30 Z0\nM30\n", Dialect::Fanuc).starts_with("home point=2 axes=Z"));
    assert!(trace("G75 FP=2 Z1=0\nM30\n", Dialect::Sinumerik).starts_with("home point=3 axes=Z via Z=0"));
    assert!(trace("G75 X1=0 Y1=0\nM30\n", Dialect::Sinumerik).starts_with("home point=2 axes=XY"));
    assert!(trace("G74 Z=0\nM30\n", Dialect::Sinumerik).ends_with("error NC441"));
    assert!(trace("O1\nG30 P5 Z0\nM30\n", Dialect::Fanuc).contains("alarm"));
}

#[test]
fn machine_coordinate_moves_ignore_the_offsets() {
    let t = trace("O1\nG10 L2 P1 X100. Y0 Z-200.\nG54\nG52 X5.\nG0 X0 Z0\nG53 Z0\nM30\n", Dialect::Fanuc);
    assert!(t.contains("move rapid X=105 Z=-200 f=-\nmove rapid X=105 Z=0 f=-"), "{t}");
    let t = trace("$P_UIFR[1,Z,TR]=-200\nG54\nTRANS X5\nG0 X0 Z0\nG0 SUPA Z0\nG153 X0\nM30\n", Dialect::Sinumerik);
    assert!(t.contains("move rapid X=5 Z=-200 f=-\nmove rapid X=5 Z=0 f=-\nmove rapid X=0 Z=0 f=-"), "{t}");
}

#[test]
fn trans_replaces_atrans_adds() {
    let t = trace(
        "TRANS X10 Y10\nG0 X0 Y0\nATRANS X5\nG0 X0 Y0\nTRANS Y1\nG0 X0 Y0\nTRANS\nG0 X0 Y0\nM30\n",
        Dialect::Sinumerik,
    );
    assert_eq!(t, "move rapid X=10 Y=10 f=-\nmove rapid X=15 Y=10 f=-\nmove rapid X=0 Y=1 f=-\nmove rapid X=0 Y=0 f=-\nend M30 steps=9");
}

const F_PART: &str = "O1\nG90 G54\nG0 X0 Y0 Z100.\nG52 X50. Y20.\nG0 X0 Y0\nG1 Z-5. F200.\nG91 G28 Z0\nG90 G52 X0 Y0\nG28 X10. Y10.\nM30\n";
const S_PART: &str = "G90 G54\nG0 X0 Y0 Z100\nTRANS X50 Y20\nG0 X0 Y0\nG1 Z-5 F200\nG74 Z1=0\nTRANS\nG0 X10 Y10\nG74 X1=0 Y1=0\nG1\nM30\n";

#[test]
fn the_two_dialects_forms_of_one_part_agree() {
    assert!(equivalent(F_PART, S_PART), "{:?}", verdict(F_PART, S_PART));
    assert!(equivalent("O1\nG55\nG30 P2 G91 Z0\nM30\n", "G55\nG75 FP=1 Z1=0\nM30\n"));
    assert!(equivalent("O1\nG54.1 P1\nG59\nM30\n", "G507\nG506\nM30\n"));
}

#[test]
fn planted_differences_are_caught() {
    // Wrong offset number.
    assert!(!equivalent("O1\nG54.1 P1\nM30\n", "G508\nM30\n"));
    assert!(!equivalent("O1\nG58\nM30\n", "G57\nM30\n"));
    // Missing intermediate point.
    assert!(!equivalent(F_PART, &S_PART.replace("G0 X10 Y10\n", "")));
    // Wrong shift sign.
    assert!(!equivalent(F_PART, &S_PART.replace("TRANS X50", "TRANS X-50")));
    // Second reference point for the first.
    assert!(!equivalent("O1\nG91 G30 Z0\nM30\n", "G74 Z1=0\nM30\n"));
}

mod translation {
    use super::*;
    use nctrans::read::LineEnding;
    use nctrans::translate::to_sinumerik::{translate as to_sinumerik, Options};
    use nctrans::translate::{self, to_fanuc::TranslateOptions};

    const STEPS: u64 = 100_000;

    /// FANUC → Sinumerik: the text, or the diagnostic codes; verified when translated.
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
        let r = nctrans::translate::to_sinumerik::verify::verify_with(&db, id, &p.unit, &t, "out", STEPS);
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
        let v = translate::to_fanuc::verify(&mut db, &s, &[], &t.clone().into(), "out.nc", STEPS);
        assert!(v.equivalent, "{}\n{}\n{}", v.summary, v.rendered, t.text);
        Ok(t.text)
    }

    #[test]
    fn fanuc_frames_become_trans_supa_g74_g75_and_verify() {
        let out = f_to_s(F_PART).unwrap();
        for line in ["TRANS X50 Y20\n", "G91\nG74 Z1=0\nG90\nTRANS\n", "G0 X10 Y10\nG74 X1=0 Y1=0\nG1\n"] {
            assert!(out.contains(line), "{line:?} missing in\n{out}");
        }
        let out = f_to_s("O1\nG54.1 P2\nG0 X1.\nG58\nG53 Z0\nG91 G30 P3 Z0\nG90\nM30\n").unwrap();
        for line in ["G508\n", "G505\n", "G53 Z0\n", "G75 FP=2 Z1=0\n"] {
            assert!(out.contains(line), "{line:?} missing in\n{out}");
        }
    }

    #[test]
    fn siemens_frames_become_g52_g53_g28_g30_and_verify() {
        let out = s_to_f(S_PART).unwrap();
        for line in ["G52 X50. Y20. Z0.\n", "G91 G28 Z0.\nG90\n", "G52 X0. Y0. Z0.\n", "G91 G28 X0. Y0.\nG90\n"] {
            assert!(out.contains(line), "{line:?} missing in\n{out}");
        }
        let out = s_to_f("G507\nG506\nG0 SUPA Z0\nG153 X0\nG75 FP=1 Z1=0\nM30\n").unwrap();
        for line in ["G54.1 P1\n", "G59\n", "G00 G53 Z0.\n", "G53 X0.\n", "G91 G30 P2 Z0.\n"] {
            assert!(out.contains(line), "{line:?} missing in\n{out}");
        }
    }

    #[test]
    fn spindle_stop_and_coolant_off_beside_a_reference_return_follow_it() {
        // M5 and M9 act after the block's motion: a block of their own after G74 does the same.
        let out = f_to_s("O1\nG0 Z5. S800 M3\nM8\nG28 G91 Z0 M05 M09\nG90\nM30\n").unwrap();
        assert!(out.contains("G74 Z1=0\nM5 M9\n"), "{out}");
        let out = f_to_s("O1\nG0 Z5. S800 M3\nG28 Z10. M5\nM30\n").unwrap();
        assert!(out.contains("G74 Z1=0\nM5\n"), "{out}");
    }

    #[test]
    fn a_reference_return_after_a_drilling_cycle_knows_the_motion_mode_g80_gives_back() {
        // FANUC's cycles are group 09: after G80 the G01 from before the cycle is in force
        // again, so the G28's intermediate point is a G0 move and G1 follows it.
        let prog = "O1\nG0 X0 Y0 Z10. S1000 M3\nG1 Z5. F100.\nG98 G81 X10. Z-5. R2. F80.\nG80\nX20.\nG90 G28 X0. Y0.\nX5.\nM30\n";
        let out = f_to_s(prog).unwrap();
        assert!(out.contains("G0 G90 X0 Y0\nG74 X1=0 Y1=0\nG1\n"), "{out}");
        // A G00/G01 beside G28 sets the motion mode only.
        let out = f_to_s("O1\nG0 X5. Z10.\nG1 Z5. F100.\nG00 G91 G28 Z0.\nX3.\nM30\n").unwrap();
        assert!(out.contains("G0 G91\nG74 Z1=0\nX3\n"), "{out}");
        let out = f_to_s("O1\nG0 X5. Z10.\nG01 G90 G28 X0. Y0. F100.\nX3.\nM30\n");
        assert!(out.is_err(), "an F beside G28 stays refused: {out:?}");
        let out = f_to_s("O1\nG0 X5. Z10.\nG01 G90 G28 X0. Y0.\nX3.\nM30\n").unwrap();
        assert!(out.contains("G0 G90 X0 Y0\nG74 X1=0 Y1=0\nG1\nX3\n"), "{out}");
        // A cycle still in force at the G28 (no G80): the mode it holds is not followed.
        let held = "O1\nG0 X0 Y0 Z10.\nG98 G81 X10. Z-5. R2. F80.\nG90 G28 X0. Y0.\nM30\n";
        assert!(f_to_s(held).is_err());
    }

    #[test]
    fn what_has_no_exact_counterpart_is_refused() {
        // G52 that keeps another axis's shift: TRANS would drop it.
        assert_eq!(f_to_s("O1\nG52 X10.\nG52 Y5.\nM30\n"), Err(vec!["NC442".into()]));
        assert!(f_to_s("O1\nG52 X10. Y0\nG52 X0 Y5.\nM30\n").is_ok());
        // G52 under G91 (the evaluator refuses it too).
        assert_eq!(f_to_s("O1\nG91 G52 X10.\nM30\n").unwrap_err(), vec!["NC442".to_string()]);
        assert_eq!(f_to_s("O1\nG54.1 P#1\nM30\n").unwrap_err(), vec!["NC443".to_string()]);
        assert_eq!(f_to_s("O1\nG28 Z0 S100\nM30\n").unwrap_err(), vec!["NC444".to_string()]);
        // G68.1 is not translated: refused by name (G92 and G29: tests/frames_more.rs); a
        // G69 where no rotation is in force cancels nothing (tests/frames_rotation.rs has
        // rotation, scaling and mirroring).
        let g68_1 = "O1\nG68.1 X0 Y0 Z0 I0 J1 K0 R30.\nM30\n";
        assert_eq!(f_to_s(g68_1).unwrap_err(), vec!["NC446".to_string()]);
        assert!(f_to_s("O1\nG90 G69 G15\nG0 X1.\nM30\n").unwrap().contains("G90\nG0 X1\n"));
        // ATRANS adds to a frame FANUC cannot read; TRANS under G91 is G52 under G90.
        assert_eq!(s_to_f("ATRANS X5\nM30\n").unwrap_err(), vec!["NC577".to_string()]);
        assert!(s_to_f("G91\nTRANS X5\nM30\n").unwrap().contains("G90 G52 X5. Y0. Z0.\nG91\n"));
        assert_eq!(s_to_f("G74 Z1=0 M5\nM30\n").unwrap_err(), vec!["NC445".to_string()]);
        // After a frame change a Sinumerik incremental move also travels the change, a
        // FANUC one does not: an incremental move before the axis is programmed again is
        // refused (tests/frames_incremental.rs).
        assert_eq!(s_to_f("X1\nTRANS X100\nX=IC(1)\nM30\n").unwrap_err(), vec!["NC445".to_string()]);
        assert!(s_to_f("X1\nTRANS X100\nX0\nX=IC(1)\nM30\n").is_ok());
        assert_eq!(f_to_s("O1\nG52 X100. Y0\nG91 X1.\nM30\n").unwrap_err(), vec!["NC442".to_string()]);
    }

    #[test]
    fn planted_wrong_translations_are_caught() {
        let good = f_to_s(F_PART).unwrap();
        for (from, to) in [
            ("TRANS X50 Y20", "TRANS X-50 Y20"),     // shift sign
            ("G0 X10 Y10\n", ""),                    // missing intermediate point
            ("G74 X1=0 Y1=0", "G75 FP=1 X1=0 Y1=0"), // second reference point
            ("G54\n", "G55\n"),                      // offset number
        ] {
            assert!(good.contains(from), "{from:?} not in\n{good}");
            let bad = good.replacen(from, to, 1);
            assert!(!equivalent(F_PART, &bad), "planted {from:?} → {to:?} not caught\n{bad}");
        }
        let good = s_to_f(S_PART).unwrap();
        for (from, to) in [("G52 X50.", "G52 X-50."), ("G00 X10. Y10.\n", ""), ("G54\n", "G54.1 P1\n")] {
            assert!(good.contains(from), "{from:?} not in\n{good}");
            let bad = good.replacen(from, to, 1);
            assert!(!equivalent(&bad, S_PART), "planted {from:?} → {to:?} not caught\n{bad}");
        }
    }
}
