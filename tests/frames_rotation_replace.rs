//! A G68 commanded while a G68 is in force, and a G69 where which rotation is in force is
//! not known from the text (issue 20): on FANUC the new G68 replaces angle and centre and
//! G69 ends whichever rotation there is (docs/semantics.md, "Rotation, scaling and
//! mirroring"); the Sinumerik translation writes the programmable frame anew (bare TRANS)
//! where it holds nothing else, or turns the known rotation back first, and planted wrong
//! angles and centres are caught.

#[path = "support/frame_check.rs"]
mod frame_check;
use frame_check::*;
use nctrans::dialect::Dialect;

#[test]
fn a_g68_in_g68_mode_replaces_angle_and_centre() {
    // About X10 Y0 by 90°, then about the origin by 90°: X5 Y0 is at X0 Y5 (the two
    // composed would put it at X5 Y10 or X5 Y-10).
    let t = trace("O1\nG0 X0 Y0\nG68 X10. Y0 R90.\nG0 X5. Y0\nG68 X0 Y0 R90.\nG0 X5. Y0\nM30\n", Dialect::Fanuc);
    assert!(t.contains("move rapid X=10 Y=-5 f=-\nmove rapid X=0 Y=5 f=-"), "{t}");
    // The angle of the second is its own, not the sum: 30° then 60° turns X10 by 60°.
    let t = trace("O1\nG0 X0 Y0\nG68 X0 Y0 R30.\nG0 X10. Y0\nG68 X0 Y0 R60.\nG0 X10. Y0\nM30\n", Dialect::Fanuc);
    assert!(t.contains("move rapid X=5 Y=8.660254 f=-"), "{t}");
    // G69 after both: no rotation at all.
    let t = trace(
        "O1\nG0 X0 Y0\nG68 X5. Y5. R30.\nG0 X10. Y0\nG68 X0 Y0 R60.\nG0 X10. Y0\nG69\nG0 X10. Y0\nM30\n",
        Dialect::Fanuc,
    );
    assert!(t.ends_with("move rapid X=10 Y=0 f=-\nend M30 steps=8"), "{t}");
}

/// A fan of slots: one G68 a pass of the loop, the first pass in none, the others in the
/// last pass's rotation.
const FAN: &str = "O1\nG17 G90 G0 X0 Y0 Z5.\n#1=-30.\nWHILE [#1 LE 30.] DO1\nG68 X20. Y10. R#1\nG0 X45. Y10.\n\
G1 X60. F250.\n#1=#1+15.\nEND1\nG69\nG0 X0 Y0\nM30\n";

#[test]
fn a_g68_in_a_loop_writes_the_frame_anew_and_planted_errors_are_caught() {
    let out = f_to_s(FAN).unwrap();
    let turn = "  TRANS\n  NCTRANS_G68_R=LOC1\n  ATRANS X20 Y10\n  AROT RPL=NCTRANS_G68_R\n  ATRANS X-20 Y-10\n";
    assert!(out.contains(turn), "{out}");
    assert!(out.contains("ENDWHILE\nTRANS\nG0 X0 Y0\n"), "{out}");
    for (from, to) in [
        // The rotation's sign, its centre, the reset before each pass, the cancel.
        ("AROT RPL=NCTRANS_G68_R", "AROT RPL=-NCTRANS_G68_R"),
        ("ATRANS X20 Y10\n", "ATRANS X20 Y5\n"),
        ("ATRANS X-20 Y-10\n", "ATRANS X-10 Y-10\n"),
        ("WHILE LOC1<=30\n  TRANS\n", "WHILE LOC1<=30\n"),
        ("ENDWHILE\nTRANS\n", "ENDWHILE\n"),
    ] {
        let planted = out.replacen(from, to, 1);
        assert_ne!(planted, out, "{from:?} not in\n{out}");
        assert!(!equivalent(FAN, &planted), "planted {from:?} → {to:?} not caught");
    }
}

/// Over a G52 shift the frame holds the shift too: a known G68 is turned back first.
const SHIFTED: &str = "O1\nG17 G90 G0 X0 Y0 Z5.\nG52 X100. Y0 Z0\nG68 X0 Y0 R10.\nG0 X20. Y0\n\
G68 X5. Y5. R-20.\nG0 X20. Y0\nG69\nG0 X0 Y0\nG52 X0 Y0 Z0\nG0 X0 Y0\nM30\n";

#[test]
fn a_known_g68_under_a_shift_is_turned_back_before_the_next() {
    let out = f_to_s(SHIFTED).unwrap();
    let replace = "AROT RPL=-10\nATRANS X5 Y5\nAROT RPL=-20\nATRANS X-5 Y-5\nG0 X20 Y0\n";
    assert!(out.contains(replace), "{out}");
    for (from, to) in
        [("AROT RPL=-10\n", "AROT RPL=10\n"), ("AROT RPL=-10\n", ""), ("ATRANS X5 Y5\n", "ATRANS X5 Y0\n")]
    {
        let planted = out.replacen(from, to, 1);
        assert_ne!(planted, out, "{from:?} not in\n{out}");
        assert!(!equivalent(SHIFTED, &planted), "planted {from:?} → {to:?} not caught");
    }
}

#[test]
fn where_the_rotation_in_force_is_not_known_and_the_frame_holds_more_it_is_refused() {
    let nc497 = Err(vec!["NC497".to_string()]);
    // The loop's G68 over a G52 shift: which rotation to turn back is not known.
    let shifted =
        FAN.replacen("#1=-30.\n", "G52 X5. Y0 Z0\n#1=-30.\n", 1).replacen("G0 X0 Y0\nM30", "G52 X0 Y0 Z0\nM30", 1);
    assert_eq!(f_to_s(&shifted), nc497, "loop over a shift");
    // A G68 or G69 in a program no call reaches, before any G52: the caller's mode.
    assert_eq!(f_to_s("O2\nG0 X0. Y0.\nG69\nG0 X1. Y1.\nM99\n"), nc497, "a cancel of the caller's mode");
}

#[test]
fn after_a_g52_no_rotation_is_in_force() {
    // In a program no call reaches, the G69 after its G52 (a TRANS on Sinumerik, and on
    // FANUC refused under a rotation) cancels nothing.
    let f = "O2\nG17 G90\nG52 X-45. Y15. Z0.\nG0 X0. Y0.\nG69\nG0 X10. Y0.\nG52 X0. Y0. Z0.\nM99\n";
    let out = f_to_s(f).unwrap();
    assert!(out.contains("TRANS X-45 Y15\nG0 X0 Y0\nG0 X10 Y0\n"), "{out}");
}

/// The committed library translations (corpus/in/library-fanuc/O01640, O01641) against their
/// sources under the library's Haas profile: each agrees, and a planted wrong rotation
/// (sign, centre, a reset left out) does not.
#[test]
fn the_library_translations_agree_and_planted_rotations_are_caught() {
    let root = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let lib = root.join("corpus/in/library-fanuc");
    let tmp = std::env::temp_dir().join(format!("nctrans-frames-replace-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    let check = |src: &str, text: &str| {
        let planted = tmp.join(format!("{src}.mpf"));
        std::fs::write(&planted, text).unwrap();
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_nctrans"))
            .args(["check", &format!("{src}.nc")])
            .arg(&planted)
            .current_dir(&lib)
            .output()
            .expect("run nctrans");
        out.status.success()
    };
    let cases: [(&str, &[(&str, &str)]); 2] = [
        (
            "O01640",
            &[
                ("AROT RPL=225", "AROT RPL=-225"),
                ("AROT RPL=NCTRANS_G68_R", "AROT RPL=-NCTRANS_G68_R"),
                ("N200 ; ONE SPOT OF THE CIRCLE, THE FRAME TURNED BY #1\nTRANS\n", "N200\n"),
                ("G0 Z2\nTRANS\nG0 X0 Y0\n", "G0 Z2\nG0 X0 Y0\n"),
            ],
        ),
        (
            "O01641",
            &[
                ("ATRANS X20 Y10\n", "ATRANS X10 Y20\n"),
                ("AROT RPL=-10\nATRANS X5 Y5\n", "ATRANS X5 Y5\n"),
                ("ATRANS X5 Y5\nAROT RPL=-20", "ATRANS X5 Y0\nAROT RPL=-20"),
            ],
        ),
    ];
    for (src, plants) in cases {
        let text =
            std::fs::read_to_string(root.join(format!("corpus/out/library-sinumerik-from-fanuc/files/P_{src}.mpf")))
                .expect("committed output");
        assert!(check(src, &text), "{src}: the committed output does not agree");
        for (from, to) in plants {
            let planted = text.replacen(from, to, 1);
            assert_ne!(planted, text, "{src}: {from:?} not in\n{text}");
            assert!(!check(src, &planted), "{src}: planted {from:?} → {to:?} not caught");
        }
    }
    let _ = std::fs::remove_dir_all(&tmp);
}
