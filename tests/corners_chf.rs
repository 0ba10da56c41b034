//! Siemens `CHF=` → FANUC `,C` where the corner is known at translation: the leg
//! CHF / (2·cos(turn/2)) is written where FANUC, which rounds `,C` to its 0.001 mm increment,
//! makes the same chamfer (proven); every other CHF is refused (NC572) saying why: a position
//! not known, an arc, or a leg off the increment grid with the CHR= a programmer can write.

#[path = "support/proven.rs"]
mod proven;
use nctrans::check::Verdict;
use nctrans::dialect::Dialect;
use nctrans::span::SourceDb;
use nctrans::translate::{self, to_fanuc::TranslateOptions};
use proven::{check_pair, parse, proven_to_fanuc};

/// The brief's plate corner: a rounding at (0,40), the chamfer at (60,40) turning 90°.
fn plate(chamfer: &str) -> String {
    format!(
        "G17 G90 G54 G71 G94 G40\nT1 D1 M6\nS4000 M3\nG0 X-20 Y-20 Z50\nG1 Z-3 F300\nG41 G1 X0 Y0 F800\n\
         G1 Y40 RND=5\nG1 X60 {chamfer}\nG1 Y0\nG40 G1 X-20 Y-20\nG0 Z50\nM30\n"
    )
}

fn siemens(body: &str) -> String {
    format!("G17 G71 G90\nG0 X0 Y0\n{body}M30\n")
}

fn to_fanuc(src: &str) -> Vec<String> {
    proven_to_fanuc(src, &TranslateOptions::default())
}

/// The refusal: the error codes and the rendered diagnostics.
fn refused(src: &str) -> (Vec<&'static str>, String) {
    let mut db = SourceDb::new();
    let u = parse(&mut db, "in.mpf", src, Dialect::Sinumerik);
    let t = translate::to_fanuc::to_fanuc(&u, &[], &TranslateOptions::default());
    assert!(!t.ok(), "translated:\n{}", t.text);
    let codes = t.diags.iter().filter(|d| d.is_error()).map(|d| d.code).collect();
    (codes, nctrans::diag::render(&db, &t.diags))
}

fn the_c(lines: &[String]) -> Vec<String> {
    lines.iter().filter(|l| l.contains(",C")).cloned().collect()
}

#[test]
fn a_right_angle_whose_leg_lies_on_the_grid_translates_and_is_proven() {
    // 8.119 / (2·cos 45°) = 5.74100004…: within 1e-7 mm of 5.741.
    let out = to_fanuc(&plate("CHF=8.119"));
    assert_eq!(the_c(&out), ["G01 X60. ,C5.741"], "{out:#?}");
    assert!(out.iter().any(|l| l == "G01 Y40. ,R5."), "{out:#?}");
}

#[test]
fn the_briefs_right_angle_is_refused_with_the_leg_and_the_chr_that_fanuc_can_make() {
    // 3 / (2·cos 45°) = 2.1213203…: FANUC's `,C2.121` (and `,C2.1213203`, rounded to the
    // same) would cut the chamfer 0.0003 mm off the Siemens one.
    let (codes, text) = refused(&plate("CHF=3"));
    assert_eq!(codes, ["NC572"]);
    assert!(text.contains("turns 90°") && text.contains("2.1213203"), "{text}");
    assert!(text.contains("0.001 mm") && text.contains("CHR=2.121"), "{text}");
    // The hint's CHR is a chamfer FANUC makes: it translates and is proven.
    assert_eq!(the_c(&to_fanuc(&plate("CHR=2.121"))), ["G01 X60. ,C2.121"]);
}

#[test]
fn a_45_degree_corner() {
    // From +X into the diagonal: a 45° turn, leg = 7.792 / (2·cos 22.5°) = 4.21700001….
    let out = to_fanuc(&siemens("G1 X20 CHF=7.792 F500\nX40 Y20\nY40\n"));
    assert_eq!(the_c(&out), ["G01 X20. ,C4.217 F500."], "{out:#?}");
    // Another length at the same corner is off the grid: refused, naming the angle.
    let (codes, text) = refused(&siemens("G1 X20 CHF=2 F500\nX40 Y20\nY40\n"));
    assert_eq!(codes, ["NC572"]);
    assert!(text.contains("turns 45°"), "{text}");
}

#[test]
fn a_120_degree_corner() {
    // (-10.864, 18.817) is within 3e-8 mm of the 120° direction times 21.728: the leg is CHF.
    let out = to_fanuc(&siemens("G1 X20 CHF=2 F500\nX9.136 Y18.817\nX0 Y0\n"));
    assert_eq!(the_c(&out), ["G01 X20. ,C2. F500."], "{out:#?}");
    // A hexagon's 8.66 for 5·√3 is 0.00025 mm off: the turn is 120.0016°, the leg 2.0000…
    // too far from 2 for the proof's 1e-6: refused, saying so.
    let (codes, text) = refused(&siemens("G1 X10 CHF=2 F500\nX5 Y8.66\nX0 Y0\n"));
    assert_eq!(codes, ["NC572"]);
    assert!(text.contains("turns 120.00") && text.contains("CHR=2"), "{text}");
}

#[test]
fn a_move_to_a_variable_end_point_is_refused_saying_so() {
    let (codes, text) = refused(&siemens("G1 X60 CHF=8.119 F500\nY=R5\nX0\n"));
    assert_eq!(codes, ["NC572"]);
    assert!(text.contains("the end point of the move after it is not known at translation"), "{text}");
    assert!(text.contains("R5 is not set in this program"), "{text}");
    // The same R parameter with one value is known: the corner is made.
    let out = to_fanuc(&siemens("R5=40\nG1 X60 CHF=8.119 F500\nY=R5\nX0\n"));
    assert_eq!(the_c(&out), ["G01 X60. ,C5.741 F500."], "{out:#?}");
}

#[test]
fn a_frame_change_or_a_jump_target_between_is_named() {
    let (codes, text) = refused(&siemens("G1 X10 F500\nTRANS X5\nX60 CHF=8.119\nY40\n"));
    assert_eq!(codes, ["NC572"]);
    assert!(text.contains("positions are not followed across TRANS"), "{text}");
    let (codes, text) = refused(&siemens("G1 X10 F500\nBACK:\nX60 CHF=8.119\nY40\nX10 Y0\nGOTOB BACK\n"));
    assert_eq!(codes, ["NC572"]);
    assert!(text.contains("jump target"), "{text}");
}

#[test]
fn a_contour_in_a_depth_loop_is_known_from_its_own_moves() {
    // Z comes from the loop's variable; the chamfer's three points are the body's literals.
    let src = "G17 G71 G90\nG0 X0 Y0 Z5\nR1=-1\nWHILE R1>=-3\nG1 Z=R1 F500\nG1 X0 Y0\nG1 X60 CHF=8.119\nY40\nX0\n\
               R1=R1-1\nENDWHILE\nG0 Z5\nM30\n";
    let out = to_fanuc(src);
    assert_eq!(the_c(&out), ["G01 X60. ,C5.741"], "{out:#?}");
    // Where the body's first move is the corner's, its start depends on the pass: refused.
    let src = "G17 G71 G90\nG0 X0 Y0 Z5\nR1=-1\nWHILE R1>=-3\nG1 X60 CHF=8.119 F500\nY40\nX0 Y0\n\
               R1=R1-1\nENDWHILE\nM30\n";
    let (codes, text) = refused(src);
    assert_eq!(codes, ["NC572"]);
    assert!(text.contains("where the move to the corner starts is not known"), "{text}");
}

#[test]
fn a_chamfer_next_to_an_arc_stays_refused() {
    // The run models corners between two lines only (NC574 there): no leg is written.
    let (codes, text) = refused(&siemens("G1 X20 F500\nG3 X40 Y20 CR=20 CHF=2\nG1 Y40\n"));
    assert_eq!(codes, ["NC572"]);
    assert!(text.contains("is an arc (G2/G3)"), "{text}");
    let (codes, text) = refused(&siemens("G1 X20 CHF=2 F500\nG2 X40 Y-20 CR=20\nG1 Y-40\n"));
    assert_eq!(codes, ["NC572"]);
    assert!(text.contains("the move after the corner is an arc"), "{text}");
}

#[test]
fn a_corner_that_is_no_corner_stays_refused() {
    let (codes, text) = refused(&siemens("G1 X20 CHF=2 F500\nX40\n"));
    assert_eq!(codes, ["NC572"]);
    assert!(text.contains("in line or turn straight back"), "{text}");
}

#[test]
fn a_planted_wrong_leg_is_caught_by_the_check() {
    let src = plate("CHF=8.119");
    let mut db = SourceDb::new();
    let u = parse(&mut db, "in.mpf", &src, Dialect::Sinumerik);
    let t = translate::to_fanuc::to_fanuc(&u, &[], &TranslateOptions::default());
    assert!(t.ok() && t.text.contains(",C5.741"), "{}", t.text);
    assert!(matches!(check_pair(&src, &t.text), Verdict::Equivalent { .. }));
    // The chamfer's length as the leg, and the leg's nearest neighbour on the grid.
    for wrong in [",C8.119", ",C5.742"] {
        let planted = t.text.replace(",C5.741", wrong);
        assert!(matches!(check_pair(&src, &planted), Verdict::Diverged { .. }), "{wrong}");
    }
}

/// A streamed translation writes a run of plain blocks next to the chamfer one by one (a
/// stand-in in the skeleton, whose positions the pass does not see): the corner is not
/// taken as known there, the stream falls back to the whole translation, and both write
/// the same `,C`.
#[test]
fn a_streamed_translation_writes_the_same_leg() {
    let dir = std::env::temp_dir().join(format!("nctrans-corners-chf-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch");
    let src = dir.join("seg.mpf");
    let text = "G17 G71 G90\nG0 X0 Y0\nR1=2\nG1 X10 F500\nX20\nX30\nX60 CHF=8.119\nY40\nY50\nY60\nIF R1>1\nG0 Z5\nENDIF\nM30\n";
    std::fs::write(&src, text).expect("write");
    let run = |extra: &[&str], out: &str| {
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_nctrans"))
            .args(extra)
            .args(["--to", "fanuc", "--force"])
            .arg(&src)
            .arg("-o")
            .arg(dir.join(out))
            .output()
            .expect("run nctrans");
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        std::fs::read_to_string(dir.join(out)).expect("output")
    };
    let whole = run(&[], "whole.nc");
    assert!(whole.contains("X60. ,C5.741"), "{whole}");
    assert_eq!(run(&["--stream"], "streamed.nc"), whole);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn def_variables_inch_and_the_zx_plane_are_followed() {
    let out = to_fanuc("DEF REAL LEN=8.119, WID=60\nG17 G71 G90\nG0 X0 Y0\nG1 X=WID CHF=LEN F500\nY40\nX0\nM30\n");
    assert_eq!(the_c(&out).len(), 1, "{out:#?}");
    assert!(the_c(&out)[0].contains(",C5.741"), "{out:#?}");
    // Inch: the leg 0.5741 in lies on FANUC's 0.0001 in grid.
    let out = to_fanuc("G17 G70 G90\nG0 X0 Y0\nG1 X2 CHF=0.8119 F20\nY4\nX0\nM30\n");
    assert!(the_c(&out).iter().any(|l| l.contains(",C0.5741")), "{out:#?}");
    let out = to_fanuc("G18 G71 G90\nG0 X0 Z0\nG1 Z60 CHF=8.119 F500\nX40\nZ0\nM30\n");
    assert_eq!(the_c(&out), ["G01 Z60. ,C5.741 F500."], "{out:#?}");
}
