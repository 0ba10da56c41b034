//! Leftovers of issue #20: FANUC G68/G51/G51.1/G16 in called programs translated to
//! Sinumerik where every call of the program is made without a mode in force
//! (`modal::frame_calls`): a G65 macro that rotates a pocket about a centre and cancels
//! the rotation before M99 runs alike on both controls, a planted wrong rotation sign or
//! centre is caught, and the calls whose modes are not known are refused with NC497.

use nctrans::check::Verdict;
use nctrans::dialect::Dialect;
use nctrans::read::LineEnding;
use nctrans::span::SourceDb;
use nctrans::translate::to_sinumerik::{translate as to_sinumerik, verify::verify_with, Options};

#[path = "support/frame_check.rs"]
mod frame_check;

const STEPS: u64 = 100_000;

/// A machinist's job: the main program mills a pocket rotated by 30° about X60 Y40 through
/// a G65 macro, a second one by 120°, then rotates a move of its own.
const JOB: &str = "%\nO2110 (POCKETS ROTATED BY A MACRO)\nG17 G21 G40 G49 G80 G90\nG54 G00 X0. Y0. Z50.\n\
G65 P9110 A20. B10.\nG65 P9111 A15. B8.\nG00 X0. Y0.\nG68 X10. Y10. R45.\nG01 X30. Y10. F200.\nG69\n\
G00 X0. Y0. Z50.\nM30\n\
O9110 (POCKET ROTATED 30 DEG ABOUT X60 Y40)\nG90 G68 X60. Y40. R30.\nG00 X[60.+#1] Y40.\nZ2.\n\
G01 Z-3. F100.\nY[40.+#2]\nX[60.-#1]\nY[40.-#2]\nX[60.+#1]\nY40.\nG00 Z50.\nG69\nG00 X60. Y40.\nM99\n\
O9111 (POCKET ROTATED 120 DEG ABOUT X60 Y40)\nG90 G68 X60. Y40. R120.\nG00 X[60.+#1] Y40.\nZ2.\n\
G01 Z-3. F100.\nY[40.+#2]\nX[60.-#1]\nY40.\nG00 Z50.\nG69\nG00 X60. Y40.\nM99\n%\n";

/// The translation's files and whether it is proven equivalent; `Err`: the error codes.
fn translate(fanuc: &str) -> Result<Vec<(String, String)>, Vec<&'static str>> {
    translate_with(fanuc, &Options::default())
}

fn translate_with(fanuc: &str, opts: &Options) -> Result<Vec<(String, String)>, Vec<&'static str>> {
    let j = frame_check::parse_job(fanuc);
    let t = to_sinumerik(&[&j.unit], opts, LineEnding::Lf);
    if t.has_errors() {
        let mut codes: Vec<&'static str> = t.diags.iter().filter(|d| d.is_error()).map(|d| d.code).collect();
        codes.dedup();
        return Err(codes);
    }
    let r = verify_with(&j.db, j.id, &j.unit, &t, "out", STEPS);
    let files: Vec<(String, String)> = t.files.iter().map(|f| (f.name.clone(), f.text.clone())).collect();
    assert!(matches!(r.verdict, Verdict::Equivalent { .. }), "{:?}\n{}\n{files:?}", r.verdict, r.diff);
    Ok(files)
}

/// Whether the translation of `fanuc` with `from` replaced by `to` in its file `name`
/// still runs like the source.
fn planted_equivalent(fanuc: &str, name: &str, from: &str, to: &str) -> bool {
    planted_with(fanuc, &Options::default(), name, from, to)
}

fn planted_with(fanuc: &str, opts: &Options, name: &str, from: &str, to: &str) -> bool {
    let j = frame_check::parse_job(fanuc);
    let mut t = to_sinumerik(&[&j.unit], opts, LineEnding::Lf);
    let f = t.files.iter_mut().find(|f| f.name == name).unwrap_or_else(|| panic!("no file {name}"));
    assert!(f.text.contains(from), "{from:?} not in\n{}", f.text);
    f.text = f.text.replacen(from, to, 1);
    let r = verify_with(&j.db, j.id, &j.unit, &t, "out", STEPS);
    matches!(r.verdict, Verdict::Equivalent { .. })
}

fn file<'a>(files: &'a [(String, String)], name: &str) -> &'a str {
    &files.iter().find(|f| f.0 == name).unwrap_or_else(|| panic!("no {name} in {files:?}")).1
}

#[test]
fn a_macro_that_rotates_a_pocket_and_cancels_translates_and_runs_alike() {
    let files = translate(JOB).expect("translated");
    let m = file(&files, "O_9110.SPF");
    for line in ["ATRANS X60 Y40\nAROT RPL=30\nATRANS X-60 Y-40\n", "ATRANS X60 Y40\nAROT RPL=-30\nATRANS X-60 Y-40\n"]
    {
        assert!(m.contains(line), "{line:?} missing in\n{m}");
    }
    // The caller knows its modes after both calls: its own G68/G69 translate.
    let main = &files[0].1;
    assert!(main.contains("AROT RPL=45") && main.contains("AROT RPL=-45"), "{main}");
}

#[test]
fn a_wrong_rotation_sign_or_centre_in_the_macro_is_caught() {
    for (from, to) in
        [("AROT RPL=30", "AROT RPL=-30"), ("ATRANS X60 Y40", "ATRANS X40 Y60"), ("AROT RPL=-30", "AROT RPL=30")]
    {
        assert!(!planted_equivalent(JOB, "O_9110.SPF", from, to), "planted {from:?} → {to:?} not caught");
    }
}

#[test]
fn a_rotation_left_in_force_at_m99_stays_in_force_in_the_caller_on_both() {
    // O9110 leaves G68 on: the caller's moves after the call run rotated on FANUC, and the
    // frame the PROC wrote stays on Sinumerik (no SAVE).
    let job = "%\nO1\nG17 G21 G90 G54 G00 X0. Y0. Z50.\nG65 P9110\nG01 X80. Y40. F100.\nG00 X0. Y0.\nM30\n\
O9110\nG90 G68 X60. Y40. R30.\nG00 X70. Y40.\nM99\n%\n";
    translate(job).expect("translated");
    // The caller cannot cancel what it does not know is in force.
    let cancel = job.replace("G00 X0. Y0.\nM30", "G69\nG00 X0. Y0.\nM30");
    assert_eq!(translate(&cancel).unwrap_err(), ["NC497"]);
}

#[test]
fn calls_whose_modes_are_not_known_are_refused() {
    // A call made while G68 is in force: the macro's G68 would replace it on FANUC.
    let in_mode = JOB.replace("G65 P9110 A20. B10.", "G68 X0. Y0. R10.\nG65 P9110 A20. B10.\nG69");
    assert_eq!(translate(&in_mode).unwrap_err(), ["NC497"]);
    // A macro no call in the job reaches (translated alone) does not know its caller's mode.
    let alone = "%\nO9110\nG90 G68 X60. Y40. R30.\nG00 X70. Y40.\nG69\nG00 X0. Y0.\nM99\n%\n";
    assert_eq!(translate(alone).unwrap_err(), ["NC497"]);
    // A centre from the macro's arguments, which may be vacant: the word is then left out
    // and the tool position is the centre, which every call of the macro in the job makes in
    // G17 with the tool on the grid, so the vacant case turns about `$P_EP` (tests/g68_planes.rs).
    let args = JOB.replace("G90 G68 X60. Y40. R30.", "G90 G68 X#24 Y#25 R30.");
    let files = translate(&args).expect("translated");
    assert!(file(&files, "O_9110.SPF").contains("NCTRANS_G68_X=$P_EP[X]"), "{files:?}");
    // A system variable read by the G68 is refused.
    let sys = JOB.replace("G90 G68 X60. Y40. R30.", "G90 G68 X#5001 Y40. R30.");
    assert!(translate(&sys).unwrap_err().contains(&"NC497"));
}

#[test]
fn mirror_scaling_and_polar_coordinates_in_a_subprogram_follow_the_same_rule() {
    let job = "%\nO1\nG17 G21 G90 G54 G00 X0. Y0. Z50.\nM98 P9120\nG00 X0. Y0.\nM98 P9121\nG00 X0. Y0.\nM30\n\
O9120\nG90 G51.1 X50.\nG00 X70. Y10.\nG01 X80. Y20. F100.\nG50.1 X0.\nG00 X0. Y0.\nM99\n\
O9121\nG90 G51 X50. Y50. P500\nG00 X70. Y10.\nG01 X80. Y20. F100.\nG50\nG00 X0. Y0.\nM99\n%\n";
    let files = translate(job).expect("translated");
    assert!(file(&files, "O_9120.SPF").contains("AMIRROR X0"), "{files:?}");
    assert!(file(&files, "O_9121.SPF").contains("ASCALE X0.5 Y0.5"), "{files:?}");
    // A subprogram that leaves G16 on: the caller's next move is not known to be polar.
    let polar = "%\nO1\nG17 G21 G90 G54 G00 X0. Y0. Z50.\nM98 P9122\nG00 X40. Y30.\nM30\n\
O9122\nG90 G16\nG00 X40. Y30.\nM99\n%\n";
    assert_eq!(translate(polar).unwrap_err(), ["NC497"]);
}

/// The machinist's macro: a pocket rotated by R about X Y, all given by the G65 call.
const ARGS_JOB: &str = "%\nO2111\nG17 G21 G40 G49 G80 G90\nG54 G00 X0. Y0. Z50.\n\
G65 P9112 X60. Y40. R30. A20. B10.\nG65 P9112 X60. Y40. R120. A20. B10.\nG00 X0. Y0.\nM30\n\
O9112\nG90 G68 X#24 Y#25 R#18\nG00 X[#24+#1] Y#25\nZ2.\nG01 Z-3. F100.\nY[#25+#2]\nX[#24-#1]\n\
Y[#25-#2]\nX[#24+#1]\nY#25\nG00 Z50.\nG69\nG00 X#24 Y#25\nM99\n%\n";

#[test]
fn a_macro_rotating_by_its_arguments_translates_for_the_calls_seen() {
    // With the macro written for the calls of the job, the arguments are surely given: the
    // G68 words are saved at the G68 and its G69 turns back by the saved values.
    let opts = Options { specialise_callers: true, ..Options::default() };
    let files = translate_with(ARGS_JOB, &opts).expect("translated");
    let m = file(&files, "O_9112.SPF");
    for line in [
        "NCTRANS_G68_R=ARG_R\n",
        "AROT RPL=NCTRANS_G68_R\n",
        "ATRANS X=NCTRANS_G68_X Y=NCTRANS_G68_Y\n",
        "AROT RPL=-NCTRANS_G68_R\n",
    ] {
        assert!(m.contains(line), "{line:?} missing in\n{m}");
    }
    for (from, to) in [
        ("AROT RPL=NCTRANS_G68_R", "AROT RPL=-NCTRANS_G68_R"),
        ("NCTRANS_G68_X=ARG_X", "NCTRANS_G68_X=ARG_Y"),
        ("AROT RPL=-NCTRANS_G68_R", "AROT RPL=NCTRANS_G68_R"),
    ] {
        assert!(!planted_with(ARGS_JOB, &opts, "O_9112.SPF", from, to), "planted {from:?} → {to:?} not caught");
    }
}

#[test]
fn a_rotation_by_variables_is_undone_by_the_values_it_was_set_with() {
    // #1 changes between G68 and G69: FANUC's G69 cancels the rotation in force whatever
    // #1 holds then; the translation turns back by the saved angle.
    let p = "%\nO1\nG17 G21 G90 G54 G00 X0. Y0. Z50.\n#1=30.\n#2=60.\nG68 X#2 Y40. R[#1*2]\n\
G01 X80. Y40. F100.\n#1=50.\n#2=0.\nG69\nG00 X0. Y0.\nG68 X#2 Y0. R#1\nG01 X20. Y0.\nG69\nG00 X0. Y0.\nM30\n%\n";
    let files = translate(p).expect("translated");
    let main = &files[0].1;
    assert!(main.contains("NCTRANS_G68_R=LOC1*2\n"), "{main}");
    for (from, to) in [
        ("AROT RPL=-NCTRANS_G68_R", "AROT RPL=-LOC1*2"),
        // The shift back of the first G69 (the first ATRANS back is at the G68, where #2
        // still holds the centre).
        ("AROT RPL=-NCTRANS_G68_R\nATRANS X=-NCTRANS_G68_X", "AROT RPL=-NCTRANS_G68_R\nATRANS X=-LOC2"),
    ] {
        assert!(!planted_equivalent(p, &files[0].0, from, to), "planted {from:?} → {to:?} not caught");
    }
}

#[test]
fn the_corpus_job_matches_its_committed_translation_and_plants_are_caught() {
    let root = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let src = std::fs::read_to_string(root.join("corpus/in/fanuc/g68-macro-rotated-pockets.nc")).expect("source");
    let files = translate(&src).expect("translated");
    for (name, text) in &files {
        let committed = root.join("corpus/out/sinumerik/g68-macro-rotated-pockets").join(name);
        let committed = std::fs::read_to_string(&committed).unwrap_or_else(|e| panic!("{}: {e}", committed.display()));
        // The committed file's header names the input path; the programs follow it.
        let body = |t: &str| t.lines().filter(|l| !l.starts_with("; Translated by")).collect::<Vec<_>>().join("\n");
        assert_eq!(body(&committed), body(text), "{name}");
    }
    for (name, from, to) in [
        ("O_9120.SPF", "AROT RPL=30", "AROT RPL=-30"),
        ("O_9120.SPF", "ATRANS X-60 Y-40", "ATRANS X-40 Y-60"),
        ("O_2120.MPF", "AROT RPL=NCTRANS_G68_R", "AROT RPL=-NCTRANS_G68_R"),
        ("O_2120.MPF", "NCTRANS_G68_R=LOC10", "NCTRANS_G68_R=LOC10+120"),
    ] {
        assert!(!planted_equivalent(&src, name, from, to), "planted {from:?} → {to:?} in {name} not caught");
    }
}

/// Sinumerik → FANUC: the ATRANS / AROT / ATRANS rotation about a centre in the one plane
/// G18 or G19 a main program selects first.
mod sequences_in_other_planes {
    use super::*;
    use nctrans::translate::{self, to_fanuc::TranslateOptions};

    use super::frame_check;

    fn s_to_f(siemens: &str) -> Result<String, Vec<&'static str>> {
        let mut db = SourceDb::new();
        let s = frame_check::load(&mut db, siemens, Dialect::Sinumerik);
        let t = translate::to_fanuc::to_fanuc(&s, &[], &TranslateOptions::default());
        if !t.ok() {
            let mut codes: Vec<&'static str> = t.diags.iter().filter(|d| d.is_error()).map(|d| d.code).collect();
            codes.dedup();
            return Err(codes);
        }
        let v = translate::to_fanuc::verify(&mut db, &s, &[], &t.clone().into(), "out.nc", STEPS);
        assert!(v.equivalent, "{}\n{}\n{}", v.summary, v.rendered, t.text);
        Ok(t.text)
    }

    const G18: &str = "G18 G90 G54 G0 X0 Y0 Z0\nATRANS X20 Z10\nAROT RPL=30\nATRANS X-20 Z-10\n\
G1 X40 Z10 F100\nG2 X20 Z30 CR=20\nATRANS X20 Z10\nAROT RPL=-30\nATRANS X-20 Z-10\nG0 X0 Z0\nM30\n";
    const G19: &str = "G19 G90 G54 G0 X0 Y0 Z0\nATRANS Y15 Z5\nAROT RPL=45\nATRANS Y-15 Z-5\n\
G1 Y40 Z5 F100\nATRANS Y15 Z5\nAROT RPL=-45\nATRANS Y-15 Z-5\nG0 Y0 Z0\nM30\n";

    #[test]
    fn a_rotation_about_a_centre_in_g18_or_g19_becomes_g68_in_that_plane() {
        for (src, g68) in [(G18, "G68 Z10. X20. R30.\n"), (G19, "G68 Y15. Z5. R45.\n")] {
            let out = s_to_f(src).expect("translated");
            assert!(out.contains(g68) && out.contains("G69\n"), "{g68:?} missing in\n{out}");
            for (from, to) in [
                (g68.to_string(), g68.replace("R", "R-")),
                (g68.to_string(), g68.replace("Z10. X20.", "Z20. X10.").replace("Y15. Z5.", "Y5. Z15.")),
            ] {
                let bad = out.replacen(&from, &to, 1);
                assert!(!frame_check::equivalent(&bad, src), "planted {from:?} → {to:?} not caught\n{bad}");
            }
        }
    }

    #[test]
    fn where_the_plane_is_not_known_the_sequence_stays_refused() {
        // Two planes in the program: the plane of the block is not known from its text.
        let mixed = G18.replace("G0 X0 Z0\nM30", "G17\nG0 X0 Y0\nM30");
        assert!(s_to_f(&mixed).is_err());
        // Before the plane word (the program starts in G17 there).
        let before = "G90 G54 G0 X0 Y0 Z0\nATRANS X20 Z10\nAROT RPL=30\nATRANS X-20 Z-10\nG18\nG1 X40 Z10 F100\nM30\n";
        assert!(s_to_f(before).is_err());
    }
}

#[test]
fn a_constant_expression_in_g68_is_written_as_it_stands() {
    let p = "%\nO1\nG17 G21 G90 G54 G00 X0. Y0. Z50.\nG68 X10. Y0. R[90./3.]\nG01 X80. Y40. F100.\nG69\nG00 X0. Y0.\nM30\n%\n";
    let files = translate(p).expect("translated");
    let main = &files[0].1;
    assert!(main.contains("AROT RPL=90/3\n") && main.contains("AROT RPL=-(90/3)\n"), "{main}");
    assert!(!main.contains("NCTRANS_G68"), "{main}");
}
