//! Issue 20: FANUC `G68 R a` without a centre turns about the tool position where the G68
//! is given (F-ROT1, F-ROT2), in the plane selected then. The FANUC run rotates in G18 and
//! G19 about that point and over a G52 shift (the centre is the local position, the shift
//! stays under the rotation); the Sinumerik translation saves `$P_EP` of the plane's two
//! axes and turns about them with ATRANS/AROT RPL=/ATRANS on top of the TRANS the G52
//! became, proven, also in a called program whose callers all call it in one plane.
//! Planted wrong translations (the centre, the sign, the plane) are caught; what stays
//! refused: a plane that depends on the path or the caller, a tool position that may be
//! off the increment grid, and (in the FANUC run) G52 or G92 given under G68 (NC491).

mod eval_support;
#[path = "support/frame_check.rs"]
mod frame_check;

use eval_support::{nctrans, run_text, scratch_dir, write};
use nctrans::check::Verdict;
use nctrans::read::LineEnding;
use nctrans::translate::to_sinumerik::{translate as to_sinumerik, verify::verify_with, Options};

/// A groove on the front face (G18, the XZ plane) turned 30° about where the tool stands.
const G18: &str = "%\nO0181 (G18 GROOVE TURNED ABOUT THE TOOL)\nG18 G21 G90 G54\nG0 X20. Z10. Y5.\n\
G68 R30.\nG1 X30. Z10. F100.\nG1 Z20.\nG69\nG0 X0 Z0\nM30\n%\n";

/// A slot on the side face (G19, the YZ plane) turned -15° about the tool, over a G52 shift.
const G19_G52: &str = "%\nO0191 (G19 SLOT OVER A LOCAL SHIFT)\nG19 G21 G90 G54\nG52 X5. Y10. Z-2.\n\
G0 X0 Y20. Z10.\nG68 R-15.\nG1 Y30. Z10. F200.\nG1 Z0\nG69\nG0 Y0 Z0\nG52 X0 Y0 Z0\nM30\n%\n";

fn lines(text: &str, name: &str) -> Vec<String> {
    let ran = run_text(name, text, &[]);
    assert!(ran.outcome.diags.is_empty(), "{}", ran.text());
    eval_support::bare_lines(&ran)
}

/// The FANUC run: in G18 the centre is the tool's (Z, X) and the turn goes Z towards X; in
/// G19 (Y, Z), Y towards Z, with the local shift added after the rotation.
#[test]
fn the_fanuc_run_turns_about_the_tool_in_g18_and_g19() {
    let g18 = lines(G18, "g68-planes-g18.nc");
    // From (Z10, X20): the step X+10 turns by 30° to X+8.660254, Z-5.
    assert_eq!(g18[2], "move linear X=28.660254 Y=5 Z=5 f=100", "{g18:?}");
    let g19 = lines(G19_G52, "g68-planes-g19.nc");
    // The tool at local (Y20, Z10) is machine (Y30, Z8); the step Y+10 turns by -15°.
    assert_eq!(g19[1], "move rapid X=5 Y=30 Z=8 f=-", "{g19:?}");
    assert_eq!(g19[2], "move linear X=5 Y=39.659258 Z=5.41181 f=200", "{g19:?}");
}

/// `nctrans --to sinumerik` then verify: proven for G18 and for G19 over a G52 shift, the
/// saved position in the plane's axes composed on the TRANS.
#[test]
fn g18_and_g19_without_centre_are_proven() {
    let d = scratch_dir("g68-planes", "proven");
    let src = write(&d, "O181.nc", G18);
    let (code, out, err) = nctrans(&["--to", "sinumerik", &src]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
    for want in ["NCTRANS_G68_Z=$P_EP[Z]", "NCTRANS_G68_X=$P_EP[X]", "ATRANS X=NCTRANS_G68_X Z=NCTRANS_G68_Z"] {
        assert!(out.contains(want), "{want}\n{out}");
    }
    assert!(!out.contains("$P_EP[Y]"), "{out}");
    let src = write(&d, "O191.nc", G19_G52);
    let (code, out, err) = nctrans(&["--to", "sinumerik", &src]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
    let trans = out.find("TRANS X5 Y10 Z-2").expect("the G52 shift");
    let save = out.find("NCTRANS_G68_Y=$P_EP[Y]").expect("the saved centre");
    assert!(trans < save && out.contains("ATRANS Y=NCTRANS_G68_Y Z=NCTRANS_G68_Z"), "{out}");
}

/// Each planted fault in the translation is caught by verify (`check` diverges).
#[test]
fn wrong_centre_sign_or_plane_is_caught() {
    let d = scratch_dir("g68-planes", "planted");
    let cases: [(&str, &str, &str, &str); 5] = [
        // The centre at the zero of the local system, not the tool.
        (G18, "NCTRANS_G68_Z=$P_EP[Z]", "NCTRANS_G68_Z=0", "centre"),
        // The centre in machine terms: the G52 shift added once more.
        (G19_G52, "NCTRANS_G68_Y=$P_EP[Y]", "NCTRANS_G68_Y=$P_EP[Y]+10", "shift"),
        // The turn the other way.
        (G18, "AROT RPL=30", "AROT RPL=-30", "sign"),
        // The rotation in the XY plane (G17 before the frame, G18 after it).
        (G18, "AROT RPL=30", "G17\nAROT RPL=30\nG18", "plane"),
        // The axes of the wrong plane saved (G17's X, Y in a G19 program).
        (G19_G52, "NCTRANS_G68_Z=$P_EP[Z]", "NCTRANS_G68_Z=$P_EP[X]", "axis"),
    ];
    for (src_text, from, to, what) in cases {
        let src = write(&d, &format!("{what}.nc"), src_text);
        let (code, out, err) = nctrans(&["--to", "sinumerik", &src]);
        assert_eq!(code, 0, "{what}: {err}");
        assert!(out.contains(from), "{what}: {from}\n{out}");
        let bad = write(&d, &format!("{what}.mpf"), &out.replacen(from, to, 1));
        let (code, verdict, err) = nctrans(&["check", &src, &bad]);
        assert_ne!(code, 0, "{what}: {verdict}{err}");
        assert!(format!("{verdict}{err}").contains("diverge"), "{what}: {verdict}{err}");
    }
}

/// The job's translation, verified, with one planted change (`from` → `to` in file `name`,
/// none when `from` is empty): `Ok(equivalent, files)`, or the error codes.
/// Whether the job verifies, and its files (name, text).
type Verified = (bool, Vec<(String, String)>);

fn job(fanuc: &str, name: &str, from: &str, to: &str) -> Result<Verified, Vec<&'static str>> {
    let j = frame_check::parse_job(fanuc);
    let mut t = to_sinumerik(&[&j.unit], &Options::default(), LineEnding::Lf);
    if t.has_errors() {
        let mut codes: Vec<&'static str> = t.diags.iter().filter(|d| d.is_error()).map(|d| d.code).collect();
        codes.dedup();
        return Err(codes);
    }
    if !from.is_empty() {
        let f = t.files.iter_mut().find(|f| f.name == name).unwrap_or_else(|| panic!("no file {name}"));
        assert!(f.text.contains(from), "{from:?} not in\n{}", f.text);
        f.text = f.text.replacen(from, to, 1);
    }
    let r = verify_with(&j.db, j.id, &j.unit, &t, "out", 100_000);
    let files = t.files.iter().map(|f| (f.name.clone(), f.text.clone())).collect();
    Ok((matches!(r.verdict, Verdict::Equivalent { .. }), files))
}

fn refusal(fanuc: &str) -> String {
    let j = frame_check::parse_job(fanuc);
    let t = to_sinumerik(&[&j.unit], &Options::default(), LineEnding::Lf);
    assert!(t.has_errors(), "translated:\n{:?}", t.files.iter().map(|f| &f.text).collect::<Vec<_>>());
    t.diags.iter().filter(|d| d.is_error()).map(|d| format!("{} {}\n", d.code, d.message)).collect()
}

/// A subprogram turning a slot about the tool: every call of it is made in G19 over the
/// caller's G52 shift, so it turns in YZ about the local position; the second call after a
/// move of the caller's own that puts the tool back on the grid.
const CALLED: &str = "%\nO0192 (SIDE SLOTS BY A SUBPROGRAM)\nG19 G21 G90 G54\nG52 X5. Y10. Z-2.\n\
G0 X0 Y20. Z10.\nM98 P9192\nG0 Y0 Z0\nM98 P9192\nG52 X0 Y0 Z0\nG17\nM30\n\
O9192 (SLOT TURNED -15 DEG ABOUT THE TOOL)\nG68 R-15.\nG1 Y30. Z10. F200.\nG1 Z0\nG69\nG0 Y20. Z10.\nM99\n%\n";

#[test]
fn a_called_program_turns_in_its_callers_plane() {
    let (ok, files) = job(CALLED, "", "", "").expect("translated");
    assert!(ok, "{files:?}");
    let sub = &files.iter().find(|f| f.0 == "O_9192.SPF").expect("the subprogram").1;
    assert!(sub.contains("NCTRANS_G68_Y=$P_EP[Y]") && sub.contains("NCTRANS_G68_Z=$P_EP[Z]"), "{sub}");
    // Planted: the subprogram turning in XY about X, Y (as if it ran in G17).
    let xy = "NCTRANS_G68_Y=$P_EP[Y]\nNCTRANS_G68_Z=$P_EP[Z]\nATRANS Y=NCTRANS_G68_Y Z=NCTRANS_G68_Z";
    let (ok, _) = job(
        CALLED,
        "O_9192.SPF",
        xy,
        "NCTRANS_G68_Y=$P_EP[Y]\nNCTRANS_G68_Z=$P_EP[Z]\nG17\nATRANS Y=NCTRANS_G68_Y Z=NCTRANS_G68_Z",
    )
    .expect("translated");
    assert!(!ok, "a rotation in the wrong plane was proven");
}

#[test]
fn where_the_plane_or_the_grid_is_not_known_it_stays_refused() {
    // Calls in two planes: the subprogram's plane is not known.
    let two = CALLED.replace("G0 Y0 Z0\nM98 P9192", "G0 Y0 Z0\nG17\nM98 P9192");
    let why = refusal(&two);
    assert!(
        why.contains("NC497") && why.contains("plane (G17/G18/G19) depends on the path taken or on the caller"),
        "{why}"
    );
    // A plane that depends on the path taken.
    let path = "%\nO0193\n#1=1.\nG21 G90 G54\nG0 X20. Y5. Z10.\nIF [#1 GT 0] GOTO 10\nG18\nN10 G68 R30.\n\
G1 X30. Y5. Z10. F100.\nG69\nM30\n%\n";
    let why = refusal(path);
    assert!(why.contains("NC497") && why.contains("plane"), "{why}");
    // In G68 mode after a turned move the tool stands off the 0.001 grid: a new G68 without
    // a centre would turn about a point the Sinumerik frame value rounds.
    let replaced = G18.replace("G1 Z20.\n", "G1 Z20.\nG68 R45.\nG1 X25. Z12.\n");
    let why = refusal(&replaced);
    assert!(why.contains("NC497") && why.contains("off the 0.001 grid"), "{why}");
    // A unit change: a position on the millimetre grid is off the inch grid.
    let unit = "%\nO0196\nG21 G17 G90 G54\nG0 X20. Y10.\nG20\nG68 R30.\nG1 X3. Y1.5 F10.\nG69\nM30\n%\n";
    let why = refusal(unit);
    assert!(why.contains("NC497") && why.contains("off the 0.001 grid"), "{why}");
    // A subprogram that may leave the tool off the grid (it turns a move and returns
    // without one of the caller's after it).
    let off = CALLED.replace("G0 Y0 Z0\nM98 P9192", "M98 P9192");
    let off = off.replace("G69\nG0 Y20. Z10.\nM99", "G69\nM99");
    let why = refusal(&off);
    assert!(why.contains("NC497") && why.contains("off the 0.001 grid"), "{why}");
}

/// The FANUC run: G52 and G92 given while G68 is in force stay refused (NC491), naming what
/// no source settles.
#[test]
fn g52_and_g92_under_g68_stay_refused_in_the_fanuc_run() {
    let g52 = "%\nO0194\nG90 G54 G0 X10. Y10.\nG68 X0 Y0 R30.\nG52 X5. Y5.\nG0 X0 Y0\nG69\nM30\n%\n";
    let ran = run_text("g68-planes-g52.nc", g52, &[]);
    let text = ran.text();
    assert!(text.contains("NC491") && text.contains("rotated or the unrotated axes"), "{text}");
    let g92 = g52.replace("G52 X5. Y5.", "G92 X5. Y5.");
    let ran = run_text("g68-planes-g92.nc", &g92, &[]);
    let text = ran.text();
    assert!(text.contains("NC491") && text.contains("G92 under G68"), "{text}");
}

/// The segmented stream reads a job with a G68 without a centre whole: the plane word in a
/// run (`G18` is a run block) decides its axes, so `--stream` writes what the whole-file
/// translation writes.
#[test]
fn the_stream_writes_the_whole_translation() {
    let d = scratch_dir("g68-planes", "stream");
    let text = "%\nO0195\n#1=5.\nG90 G54\nG18\nG0 X20. Z10. Y5.\nG1 X21. F100.\nIF [#1 GT 2.] GOTO 10\n\
G0 X22.\nN10 G68 R30.\nG1 X30. Z10. F100.\nG69\nG0 X0 Z0\nM30\n%\n";
    let src = write(&d, "O195.nc", text);
    let (code, whole, err) = nctrans(&["--to", "sinumerik", &src]);
    assert_eq!(code, 0, "{err}");
    let (code, streamed, err) = nctrans(&["--to", "sinumerik", "--stream", &src]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(whole, streamed);
    assert!(whole.contains("NCTRANS_G68_Z=$P_EP[Z]"), "{whole}");
}
