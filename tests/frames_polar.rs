//! Polar coordinates (issue #20, trace v2): FANUC G16/G15 and Siemens G110/G111/G112 with
//! AP=/RP= give the positions the tool really reaches, a bolt circle drilled both ways
//! agrees, what the controls do differently is refused, and the translations both ways
//! are proven (a planted wrong angle or pole is caught).

use nctrans::check::Verdict;
use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::span::SourceDb;

#[path = "support/frame_check.rs"]
mod frame_check;
use frame_check::*;

pub const F_BOLTS: &str = "O1\nG17 G90 G54 G0 X0 Y0 Z10.\nG52 X50. Y40.\nG16\nG0 X30. Y0\nG81 X30. Y0 Z-5. R2. F100.\nX30. Y90.\nX30. Y180.\nX30. Y270.\nG80\nG15\nG52 X0 Y0 Z0\nG0 X0 Y0\nM30\n";
pub const S_BOLTS: &str = "G17 G90 G54 G0 X0 Y0 Z10\nG111 X50 Y40\nG0 AP=0 RP=30 F100\nMCALL CYCLE81(10,0,2,-5)\nG0 AP=0 RP=30\nAP=90\nAP=IC(90)\nAP=270\nMCALL\nG0 X0 Y0\nM30\n";

#[test]
fn g16_reads_radius_and_angle_about_the_local_zero() {
    let t =
        trace("O1\nG0 X0 Y0\nG52 X10.\nG16\nG0 X20. Y90.\nG1 X10. Y180. F100.\nG15\nG0 X0 Y0\nM30\n", Dialect::Fanuc);
    assert_eq!(t, "move rapid X=0 Y=0 f=-\nmove rapid X=10 Y=20 f=-\nmove linear X=0 Y=0 f=100\nmove rapid X=10 Y=0 f=-\nend M30 steps=8");
    // The plane in the block that selects G16; the angle without a decimal point counts 0.001°.
    assert!(trace("O1\nG17 G16 G0 X10. Y90.\nM30\n", Dialect::Fanuc).contains("move rapid X=0 Y=10 f=-"));
    assert!(trace("O1\nG16\nG17\nM30\n", Dialect::Fanuc).ends_with("error NC499"));
    assert!(trace("O1\nG18 G16 G0 Z10. X90.\nM30\n", Dialect::Fanuc).contains("move rapid X=10 Z=0 f=-"));
    assert!(trace("O1\nG16\nG0 X10. Y90000\nM30\n", Dialect::Fanuc).contains("move rapid X=0 Y=10 f=-"));
    // Under G91 the origin is the current position; a block with one of the two words: refused.
    assert!(trace("O1\nG16\nG91 G0 X10. Y90.\nM30\n", Dialect::Fanuc).ends_with("error NC499"));
    assert!(trace("O1\nG16\nG0 Y90.\nM30\n", Dialect::Fanuc).ends_with("error NC499"));
    assert!(trace("O1\nG16\nG91 G28 Z0\nM30\n", Dialect::Fanuc).ends_with("error NC499"));
}

#[test]
fn siemens_poles_and_stored_polar_values() {
    let t = trace(
        "G0 X10 Y0\nG111 X10 Y10\nG0 AP=90 RP=5\nAP=IC(90)\nG110 X1 Y0\nG0 AP=0 RP=2\nG112 X1 Y1\nG0 AP=0 RP=1\nM30\n",
        Dialect::Sinumerik,
    );
    assert_eq!(
        t,
        "move rapid X=10 Y=0 f=-\nmove rapid X=10 Y=15 f=-\nmove rapid X=5 Y=10 f=-\nmove rapid X=8 Y=10 f=-\nmove rapid X=8 Y=11 f=-\nend M30 steps=9"
    );
    // A polar arc runs about the pole; without a pole the workpiece zero is one.
    let t = trace("G0 X10 Y0\nG3 AP=90 RP=10 F100\nM30\n", Dialect::Sinumerik);
    assert!(t.contains("arc ccw XY X=0 Y=10 center X=0 Y=0 f=100"), "{t}");
    assert!(trace("G111 X0 Y0\nG0 AP=30\nM30\n", Dialect::Sinumerik).ends_with("error NC499"), "no radius yet");
    assert!(trace("G91 G0 AP=30 RP=5\nM30\n", Dialect::Sinumerik).ends_with("error NC499"));
    assert!(trace("G111 AP=30 RP=5\nM30\n", Dialect::Sinumerik).ends_with("error NC499"));
}

#[test]
fn a_bolt_circle_agrees_and_a_planted_angle_or_pole_is_caught() {
    assert!(equivalent(F_BOLTS, S_BOLTS));
    assert!(!equivalent(F_BOLTS, &S_BOLTS.replace("AP=270", "AP=-270")));
    assert!(!equivalent(F_BOLTS, &S_BOLTS.replace("G111 X50 Y40", "G111 X40 Y50")));
}

mod translation {
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

    #[test]
    fn g16_becomes_a_pole_at_the_workpiece_zero_and_rp_ap_words() {
        let out = f_to_s(F_BOLTS).unwrap();
        for line in ["TRANS X50 Y40\nG111 X0 Y0\nG0 RP=30 AP=0\n", "G0 RP=30 AP=270\nMCALL\n"] {
            assert!(out.contains(line), "{line:?} missing in\n{out}");
        }
        for (from, to) in [("AP=90", "AP=-90"), ("RP=30 AP=180", "RP=20 AP=180")] {
            assert!(!equivalent(F_BOLTS, &out.replacen(from, to, 1)), "planted {from:?} → {to:?} not caught");
        }
        let nc497 = vec!["NC497".to_string()];
        assert_eq!(f_to_s("O1\nG16\nM98 P100\nM30\nO100\nG0 X1. Y1.\nM99\n").unwrap_err(), nc497, "a call in G16");
        assert_eq!(f_to_s("O1\nG18\nG17 G16\nG0 X1. Y1.\nM30\n").unwrap_err(), nc497, "G18 in the program");
        assert_eq!(f_to_s("O1\nIF[#1EQ1]GOTO5\nG16\nN5 G0 X1. Y1.\nM30\n").unwrap_err(), nc497, "path-dependent");
    }

    #[test]
    fn ap_rp_become_cartesian_points_about_the_pole() {
        let out = s_to_f(S_BOLTS).unwrap();
        for line in ["G00 F100. X[50.+30.*COS[0.]] Y[40.+30.*SIN[0.]]\n", "X[50.+30.*COS[180.]] Y[40.+30.*SIN[180.]]\n"]
        {
            assert!(out.contains(line), "{line:?} missing in\n{out}");
        }
        for (from, to) in [("SIN[90.]", "SIN[-90.]"), ("50.+30.*COS[270.]", "40.+30.*COS[270.]")] {
            assert!(out.contains(from), "{from:?} not in\n{out}");
            assert!(!equivalent(&out.replacen(from, to, 1), S_BOLTS), "planted {from:?} → {to:?} not caught");
        }
        let nc498 = vec!["NC498".to_string()];
        assert_eq!(s_to_f("G111 X1 Y1\nG0 AP=IC(R1) RP=5\nM30\n").unwrap_err(), nc498, "IC on an unknown angle");
        assert_eq!(s_to_f("G110 X1 Y1\nG0 AP=5 RP=5\nM30\n").unwrap_err(), nc498, "a relative pole");
        assert_eq!(s_to_f("G0 X0 Y0\nG2 AP=90 RP=5 F100\nM30\n").unwrap_err(), nc498, "a polar arc");
        assert!(
            s_to_f("G111 X1 Y1\nR1=0\nWHILE R1<3\nG0 AP=R1*90 RP=5\nR1=R1+1\nENDWHILE\nM30\n").is_err(),
            "pole in a loop not known"
        );
    }
}

#[test]
fn g92_sets_the_current_position_and_moves_every_offset_in_parallel() {
    let t = trace(
        "O1\nG10 L2 P2 X100.\nG54 G0 X10. Y5.\nG92 X0 Y0\nG0 X1. Y1.\nG55\nG0 X0 Y0\nG91 X1.\nM30\n",
        Dialect::Fanuc,
    );
    assert_eq!(
        t,
        "work_offset 1\nmove rapid X=10 Y=5 f=-\nmove rapid X=11 Y=6 f=-\nwork_offset 2\nmove rapid X=110 Y=5 f=-\nmove rapid X=111 Y=5 f=-\nend M30 steps=8"
    );
    // Only the named axes; under G91, with a G52 shift or under a rotation: refused.
    assert!(trace("O1\nG0 X10. Y5.\nG92 X0\nG0 X1. Y1.\nM30\n", Dialect::Fanuc).contains("move rapid X=11 Y=1 f=-"));
    assert!(trace("O1\nG91 G92 X0\nM30\n", Dialect::Fanuc).ends_with("error NC491"));
    assert!(trace("O1\nG52 X5.\nG92 X0\nM30\n", Dialect::Fanuc).ends_with("error NC491"));
    assert!(trace("O1\nG68 X0 Y0 R9.\nG92 X0\nM30\n", Dialect::Fanuc).ends_with("error NC491"));
}

#[test]
fn g10_l20_writes_the_extended_offsets_and_g29_needs_an_intermediate_point() {
    let t =
        trace("O1\nG10 L20 P2 X100. Y5.\nG54.1 P2\nG0 X0 Y0\nG91 G10 L20 P2 X1.\nG90 G0 X0 Y0\nM30\n", Dialect::Fanuc);
    assert_eq!(t, "work_offset 8\nmove rapid X=100 Y=5 f=-\nwork_offset 8\nmove rapid X=101 Y=5 f=-\nend M30 steps=6");
    assert!(trace("O1\nG10 L20 P49 X1.\nM30\n", Dialect::Fanuc).contains("alarm"));
    // G29 runs (tests/frames_more.rs); without a G28 before it there is no intermediate point.
    assert!(trace("O1\nG29 X0 Y0\nM30\n", Dialect::Fanuc).ends_with("error NC548"));
}
