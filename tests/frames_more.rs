//! Leftovers of issue #20: Siemens blocks mixing absolute and incremental axis words
//! translated to FANUC through the block-end position `#5001+`, FANUC `G10 L20` and `G92`
//! translated to Sinumerik, each proven by running both, with planted wrong translations
//! (sign, axis, offset number, missing shift) caught and the forms without an exact
//! counterpart refused with their reason.

use nctrans::dialect::Dialect;

#[path = "support/frame_check.rs"]
mod frame_check;
use frame_check::*;

/// Each `(from, to)` replaced once in `good` (which must hold it) gives a program that
/// `differs` from the source.
fn planted(good: &str, plants: &[(&str, &str)], differs: impl Fn(&str) -> bool) {
    for (from, to) in plants {
        assert!(good.contains(from), "{from:?} not in\n{good}");
        let bad = good.replacen(from, to, 1);
        assert!(differs(&bad), "planted {from:?} → {to:?} not caught\n{bad}");
    }
}

mod mixed_absolute_incremental {
    use super::*;

    const SLOTS: &str = "G17 G90 G54 G0 X2 Y3 Z5\nG1 Z-2 F200\nG1 X=IC(40) Y=AC(10)\nG91 X-10 Y=AC(30) Z=IC(1)\nX=AC(5) Y-5\nG90 G2 X=IC(10) Y=AC(25) CR=5\nG0 Z5\nM30\n";

    #[test]
    fn the_block_keeps_its_mode_and_writes_the_other_words_from_the_block_end_position() {
        let out = s_to_f(SLOTS).unwrap();
        for line in [
            "G01 X[#5001+40.] Y10.\n",
            "G91 X-10. Y[30.-#5002] Z1.\n",
            "X[5.-#5001] Y-5.\n",
            "G90 G02 X[#5001+10.] Y25. R5.\n",
        ] {
            assert!(out.contains(line), "{line:?} missing in\n{out}");
        }
        // No switch blocks: the mode in force stays.
        assert!(!out.contains("G#"), "{out}");
    }

    #[test]
    fn where_g90_g91_is_not_known_the_block_is_written_in_g90_and_the_mode_restored() {
        let s = "R1=1\nG90 G0 X0 Y0\nIF R1==1\nG91\nENDIF\nG1 X=IC(1) Y=AC(2) F100\nG90 X3\nM30\n";
        let out = s_to_f(s).unwrap();
        assert!(out.contains("#1=#4003\nG90 G01 X[#5001+1.] Y2. F100.\nG#1\n"), "{out}");
        // A plain axis word there has no known meaning.
        let s = "R1=1\nG90 G0 X0 Y0\nIF R1==1\nG91\nENDIF\nG1 X1 Y=AC(2) F100\nM30\n";
        assert_eq!(s_to_f(s), Err(vec!["NC313".to_string()]));
    }

    #[test]
    fn planted_wrong_rewrites_are_caught() {
        let good = s_to_f(SLOTS).unwrap();
        let plants = [
            ("X[#5001+40.]", "X[#5001-40.]"),
            ("X[#5001+40.]", "X[#5002+40.]"),
            ("Y[30.-#5002]", "Y[#5002-30.]"),
            ("X[5.-#5001]", "X5."),
            ("G90 G02 X[#5001+10.]", "G90 G02 X10."),
        ];
        planted(&good, &plants, |bad| !equivalent(bad, SLOTS));
    }

    #[test]
    fn where_the_block_end_position_does_not_give_the_rewrite_it_is_refused() {
        let nc313 = Err(vec!["NC313".to_string()]);
        assert_eq!(s_to_f("G0 X0 Y0\nROT RPL=10\nG0 X=IC(1) Y=AC(2)\nM30\n"), nc313, "under a rotation");
        assert_eq!(s_to_f("G0 X0 Y0\nSUPA X=IC(1) Y=AC(2)\nM30\n"), nc313, "machine coordinates");
        assert_eq!(s_to_f("G0 X0 U0\nG91 U=AC(1) X2\nM30\n"), nc313, "no block-end variable for U");
        assert_eq!(s_to_f("G0 X0 Y0\nG1 X1 E=IC(2) F100\nM30\n"), nc313, "not an axis");
        // #5001 is read before the block's own G20/G21 acts.
        assert_eq!(s_to_f("G700 G0 X1 Y1\nG710 G0 X=IC(3) Y=AC(4)\nM30\n"), nc313, "a unit word in the block");
        let s = "G0 X1 Y1\n$P_UIFR[2,Y,TR]=50\nG55 X=IC(2) Y=AC(1)\nM30\n";
        assert_eq!(s_to_f(s), nc313, "an offset selection in the block");
        // Inch throughout: #5001 reads inches as the words are.
        let out = s_to_f("G700 G90 G0 X1 Y1\nG1 X=IC(0.5) Y=AC(2) F10\nM30\n").unwrap();
        assert!(out.contains("G01 X[#5001+0.5] Y2. F10.\n"), "{out}");
    }
}

mod extended_offset_writes {
    use super::*;

    const F: &str = "O1\nG90 G54 G0 X0 Y0\nG10 L20 P1 X10. Y20.\nG91 G10 L20 P1 X5.\nG90 G54.1 P1\nG0 X1. Y1.\nG54\nG10 L20 P2 X3. Y-4.\nG54.1 P2\nG0 X1. Y1.\nM30\n";

    #[test]
    fn g10_l20_becomes_a_write_of_frame_6_plus_n() {
        let out = f_to_s(F).unwrap();
        for line in [
            "$P_UIFR[7,X,TR]=10\n$P_UIFR[7,Y,TR]=20\n",
            "G91\n$P_UIFR[7,X,TR]=$P_UIFR[7,X,TR]+5\n",
            "G507\n",
            "$P_UIFR[8,X,TR]=3\n$P_UIFR[8,Y,TR]=-4\nG508\n",
        ] {
            assert!(out.contains(line), "{line:?} missing in\n{out}");
        }
    }

    #[test]
    fn planted_wrong_offset_numbers_and_values_are_caught() {
        let good = f_to_s(F).unwrap();
        let plants = [
            ("$P_UIFR[7,X,TR]=10", "$P_UIFR[8,X,TR]=10"),
            ("$P_UIFR[8,Y,TR]=-4", "$P_UIFR[8,Y,TR]=4"),
            ("$P_UIFR[7,X,TR]=$P_UIFR[7,X,TR]+5", "$P_UIFR[7,X,TR]=5"),
            ("G508", "G507"),
        ];
        planted(&good, &plants, |bad| !equivalent(F, bad));
    }

    #[test]
    fn siemens_frames_5_and_6_are_the_g58_g59_offsets() {
        let s = "G0 X0 Y0\n$P_UIFR[5,X,TR]=10\n$P_UIFR[6,Y,TR]=-5\nG505\nG0 X1 Y1\nG506\nG0 X1 Y1\nG54\nM30\n";
        let out = s_to_f(s).unwrap();
        assert!(out.contains("#5301=10.\n#5322=-5.\nG58\n"), "{out}");
        planted(&out, &[("#5301=10.", "#5281=10."), ("#5322=-5.", "#5321=-5.")], |bad| !equivalent(bad, s));
    }

    #[test]
    fn g10_l20_without_an_exact_form_is_refused() {
        assert_eq!(f_to_s("O1\nG10 L20 P#1 X1.\nM30\n"), Err(vec!["NC545".to_string()]), "computed P");
        assert_eq!(f_to_s("O1\nG10 L20 P49 X1.\nM30\n"), Err(vec!["NC545".to_string()]), "no such offset");
        // Under an extended offset the write may be to the active one, which needs a
        // re-selection the scan does not follow.
        let s = "O1\nG54.1 P1\nG10 L20 P1 X1.\nG0 X0\nM30\n";
        assert_eq!(f_to_s(s), Err(vec!["NC546".to_string()]));
    }
}

mod coordinate_system_setting {
    use super::*;

    const F: &str = "O1\nG90 G54 G0 X10. Y20. Z50.\nG10 L2 P2 X100. Y50.\nG92 X0 Y0\nG0 X5. Y5.\nG55\nG0 X1. Y1.\nG54\nG92 Z5.\nG1 Z-2. F100.\nG28 Z10.\nG53 X0\nG0 X0 Y0\nM30\n";

    #[test]
    fn g92_becomes_a_shift_of_the_programmable_frame_from_the_end_position() {
        let out = f_to_s(F).unwrap();
        for line in ["ATRANS X=$P_EP[X] Y=$P_EP[Y]\nG0 X5 Y5\n", "ATRANS Z=$P_EP[Z]-5\n"] {
            assert!(out.contains(line), "{line:?} missing in\n{out}");
        }
    }

    #[test]
    fn planted_wrong_shifts_are_caught() {
        let good = f_to_s(F).unwrap();
        let plants = [
            ("ATRANS Z=$P_EP[Z]-5", "ATRANS Z=$P_EP[Z]+5"),
            ("ATRANS X=$P_EP[X] Y=$P_EP[Y]", "ATRANS X=$P_EP[Y] Y=$P_EP[X]"),
            ("ATRANS X=$P_EP[X] Y=$P_EP[Y]\n", ""),
            ("ATRANS Z=$P_EP[Z]-5", "TRANS Z=$P_EP[Z]-5"),
        ];
        planted(&good, &plants, |bad| !equivalent(F, bad));
    }

    #[test]
    fn g92_where_the_frame_would_differ_is_refused() {
        let nc547 = Err(vec!["NC547".to_string()]);
        let g92 = |body: &str| f_to_s(&format!("O1\nG0 X10. Y20.\n{body}M30\n"));
        assert_eq!(g92("G92 X0 Y0\nG91 G0 X1.\n"), nc547, "incremental moves");
        assert_eq!(g92("G92 X0 Y0\nG52 X5.\nG0 X1.\n"), nc547, "G52 in the program");
        assert_eq!(g92("G92 X0 Y0\nG68 X0 Y0 R30.\nG0 X1.\nG69\n"), nc547, "G68 in the program");
        assert_eq!(g92("G92 X0 Y0 F100.\n"), nc547, "other words");
        assert_eq!(g92("G92 U0\n"), nc547, "axis U");
    }
}

mod return_from_reference {
    use super::*;

    #[test]
    fn g29_goes_through_the_intermediate_point_to_the_point_given() {
        let t = trace(
            "O1\nG90 G0 X10. Y20. Z50.\nG1 Z5. F100.\nG28 Z30.\nG29 Z-2.\nG91 G28 X0 Y0\nG29 X5. Y0\nG90 G0 X0\nM30\n",
            Dialect::Fanuc,
        );
        assert_eq!(
            t,
            "move rapid X=10 Y=20 Z=50 f=-\nmove linear X=10 Y=20 Z=5 f=100\nmove rapid X=10 Y=20 Z=30 f=-\n\
             home point=1 axes=Z via Z=30\nmove rapid X=10 Y=20 Z=30 f=-\nmove rapid X=10 Y=20 Z=-2 f=-\n\
             home point=1 axes=XY via X=10 Y=20\nmove rapid X=10 Y=20 Z=-2 f=-\nmove rapid X=15 Y=20 Z=-2 f=-\n\
             move rapid X=0 Y=20 Z=-2 f=-\nend M30 steps=8"
        );
        // No intermediate point, or an offset changed since the G28: not modelled.
        assert!(trace("O1\nG0 X1.\nG29 Z5.\nM30\n", Dialect::Fanuc).ends_with("error NC548"));
        assert!(trace("O1\nG0 Z1.\nG28 Z10.\nG29\nM30\n", Dialect::Fanuc).ends_with("error NC548"));
        let t = trace("O1\nG0 X1.\nG28 Z10.\nG10 L2 P1 Z5.\nG29 Z5.\nM30\n", Dialect::Fanuc);
        assert!(t.ends_with("error NC548"), "{t}");
        // Under a rotation, as G28.
        let t = trace("O1\nG0 X0 Y0\nG28 Z10.\nG68 X0 Y0 R30.\nG29 Z5.\nM30\n", Dialect::Fanuc);
        assert!(t.ends_with("error NC491"), "{t}");
    }

    const F: &str = "O1\nG90 G0 X10. Y20. Z50.\nG1 Z5. F100.\nG28 Z30.\nM6 T2\nN20 G29 Z-2.\nG1 X15.\nG28 X0 Y40.\nG91 G29 X5. Y0\nG90 G0 X0\nM30\n";

    #[test]
    fn g29_becomes_the_two_rapid_moves_where_the_intermediate_point_is_known() {
        let out = f_to_s(F).unwrap();
        for line in ["N20 G0 Z30\nG0 Z-2\nG1\n", "G0 X=AC(0) Y=AC(40)\nG0 G91 X5 Y0\nG1\n"] {
            assert!(out.contains(line), "{line:?} missing in\n{out}");
        }
        let nc548 = Err(vec!["NC548".to_string()]);
        assert_eq!(f_to_s("O1\nG0 Z5.\nG91 G28 Z0\nG29 Z5.\nM30\n"), nc548, "the point is where the tool stood");
        assert_eq!(f_to_s("O1\nG0 Z5.\nG28 Z9.\nG20\nG29 Z.5\nM30\n"), nc548, "a unit change since");
        assert_eq!(f_to_s("O1\nG0 Z5.\nG28 Z9.\nG55\nG29 Z5.\nM30\n"), nc548, "an offset change since");
        let path = "O1\nG0 Z5.\nIF[#1EQ1]GOTO10\nG28 Z9.\nN10 G29 Z5.\nM30\n";
        assert_eq!(f_to_s(path), nc548, "the G28 depends on the path");
    }

    #[test]
    fn planted_missing_or_wrong_intermediate_points_are_caught() {
        let good = f_to_s(F).unwrap();
        let plants = [("N20 G0 Z30\n", "N20\n"), ("N20 G0 Z30\n", "N20 G0 Z31\n"), ("G0 X=AC(0) Y=AC(40)\n", "")];
        planted(&good, &plants, |bad| !equivalent(F, bad));
    }
}

mod back_to_fanuc {
    use super::*;

    #[test]
    fn the_g92_and_g10_l20_forms_come_back() {
        let s = "G0 X50 Y40 Z100\nATRANS X=$P_EP[X] Y=$P_EP[Y]-5\nG0 X10 Y10\n$P_UIFR[9,X,TR]=200\n$P_UIFR[9,X,TR]=$P_UIFR[9,X,TR]+5\nG509\nG0 X10 Y10\nG54\nG0 X0 Y0\nM30\n";
        let out = s_to_f(s).unwrap();
        for line in ["G92 X0. Y5.\n", "G10 L20 P3 X200.\nG91 G10 L20 P3 X5.\nG90\n", "G54.1 P3\n"] {
            assert!(out.contains(line), "{line:?} missing in\n{out}");
        }
        let plants = [
            ("G92 X0. Y5.", "G92 X0. Y-5."),
            ("G10 L20 P3 X200.", "G10 L20 P2 X200."),
            ("G91 G10 L20 P3 X5.", "G10 L20 P3 X5."),
        ];
        planted(&out, &plants, |bad| !equivalent(bad, s));
        // The G92 form only where FANUC keeps the shift as Sinumerik does.
        let nc445 = Err(vec!["NC445".to_string()]);
        assert_eq!(s_to_f("G0 X5\nATRANS X=$P_EP[X]\nTRANS Y5\nM30\n"), nc445, "another frame instruction");
        assert_eq!(s_to_f("G0 X5\nATRANS X=$P_EP[X]\nG1 X=IC(1) F100\nM30\n"), nc445, "incremental moves");
        assert_eq!(s_to_f("G0 X5\nATRANS X=$P_EP[Y]\nM30\n"), Err(vec!["NC577".to_string()]), "another axis");
    }
}

/// The corpus programs of these constructs: each committed translation is equivalent to its
/// source, and wrong translations planted in it are caught.
mod corpus {
    use super::*;
    use std::path::PathBuf;

    fn read(rel: &str) -> String {
        let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(rel);
        std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
    }

    #[test]
    fn the_fixture_program_and_its_committed_sinumerik_form() {
        let f = read("corpus/in/fanuc/g92-g29-fixture-zero.nc");
        let s = read("corpus/out/sinumerik/g92-g29-fixture-zero/O_2104.MPF");
        assert!(equivalent(&f, &s), "{:?}", verdict(&f, &s));
        let plants = [
            ("Z=$P_EP[Z]-50", "Z=$P_EP[Z]+50"),
            ("ATRANS X=$P_EP[X] Y=$P_EP[Y] Z=$P_EP[Z]-50", "ATRANS Z=$P_EP[Z]-50"),
            ("G0 Z40 ; BACK OVER THE SLOT\n", ""),
            ("G0 Z40 ; BACK OVER THE SLOT", "G0 Z45"),
            ("$P_UIFR[9,X,TR]=200", "$P_UIFR[8,X,TR]=200"),
            ("G509", "G508"),
        ];
        planted(&s, &plants, |bad| !equivalent(&f, bad));
    }

    #[test]
    fn the_stepped_slot_and_its_committed_fanuc_form() {
        let s = read("corpus/in/sinumerik/ac-ic-stepped-slot.mpf");
        let f = read("corpus/out/fanuc/ac-ic-stepped-slot.mpf.nc");
        assert!(equivalent(&f, &s), "{:?}", verdict(&f, &s));
        let plants = [
            ("G01 X40. Z[#5003-2.]", "G01 X40. Z[#5003+2.]"),
            ("G01 X40. Z[#5003-2.]", "G01 X40. Z-2."),
            ("X0. Z[#5003-2.]", "X0. Z[#5001-2.]"),
            ("G91 X40. Y-#5002", "G91 X40. Y#5002 Z#5003"),
        ];
        planted(&f, &plants, |bad| !equivalent(bad, &s));
    }
}

mod rotation_in_other_planes {
    use super::*;

    const S18: &str = "G18 G90 G0 X0 Y0 Z0\nTRANS X10 Z5\nAROT RPL=30\nG1 Z10 X0 F100\nG2 Z10 X10 CR=5\nTRANS\nG0 X0 Z0\nROT Y45\nG0 Z10 X0\nROT\nM30\n";

    #[test]
    fn a_program_in_one_plane_rotates_in_it_on_fanuc() {
        let out = s_to_f(S18).unwrap();
        for line in ["G52 X10. Y0. Z5.\nG68 Z0. X0. R30.\n", "G68 Z0. X0. R45.\nG00 Z10. X0.\n"] {
            assert!(out.contains(line), "{line:?} missing in\n{out}");
        }
        let out = s_to_f("G19 G90 G0 X0 Y0 Z0\nROT RPL=30\nG1 Y10 Z0 F100\nROT\nM30\n").unwrap();
        assert!(out.contains("G68 Y0. Z0. R30.\nG01 Y10. Z0. F100.\n"), "{out}");
        let plants = [("G68 Z0. X0. R30.", "G68 Z0. X0. R-30."), ("G68 Z0. X0. R45.", "G68 X0. Y0. R45.")];
        let good = s_to_f(S18).unwrap();
        planted(&good, &plants, |bad| !equivalent(bad, S18));
    }

    #[test]
    fn where_the_plane_at_the_rotation_is_not_known_it_is_refused() {
        let nc498 = Err(vec!["NC498".to_string()]);
        assert_eq!(s_to_f("G17 G0 X0 Y0\nG18\nROT RPL=30\nM30\n"), nc498, "two planes");
        assert_eq!(s_to_f("G0 X0 Y0\nN10 G18\nROT RPL=30\nM30\n"), nc498, "G18 on a jump target");
        assert_eq!(s_to_f("ROT RPL=30\nG18\nM30\n"), nc498, "before the G18");
        assert_eq!(s_to_f("G18\nROT Z30\nM30\n"), nc498, "about an axis of the plane");
    }
}
