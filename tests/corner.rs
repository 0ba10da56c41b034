//! Chamfers and roundings between two moves (issue 21): FANUC `,C`/`,R`, Siemens `CHR=`,
//! `CHF=`, `RND=`, `RNDM=`. Both evaluators write the shortened moves and the chamfer line or
//! the tangent arc; the translation respells them both ways (proven); planted wrong corners
//! are caught by the check; corners that cannot be made are refused with their diagnostic.

#[path = "support/proven.rs"]
mod proven;
use nctrans::check::Verdict;
use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::eval::{NoCallees, RunOptions, VecSink};
use nctrans::read::LineEnding;
use nctrans::span::SourceDb;
use nctrans::translate::to_sinumerik::{self as ts, Options};
use nctrans::translate::{self, to_fanuc::TranslateOptions};
use proven::{check_pair, parse, proven_to_fanuc, STEPS};

/// The text trace of a program and the codes of its run's errors.
fn run(text: &str, d: Dialect) -> (Vec<String>, Vec<&'static str>) {
    let mut db = SourceDb::new();
    let u = parse(&mut db, "t", text, d);
    let mut sink = VecSink::default();
    let opts = RunOptions { max_steps: STEPS, ..RunOptions::default() };
    let out = nctrans::eval::run(&mut db, &u, &mut NoCallees, &opts, &mut sink);
    let lines = sink.events.iter().map(|(e, _)| nctrans::eval::trace::text_line(e)).collect();
    (lines, out.diags.iter().filter(|d| d.is_error()).map(|d| d.code).collect())
}

fn trace(text: &str, d: Dialect) -> Vec<String> {
    let (t, errs) = run(text, d);
    assert!(errs.is_empty(), "{errs:?}\n{t:?}");
    t
}

fn fanuc(body: &str) -> String {
    format!("%\nO1\nG17 G21 G90\nG00 X0. Y0.\n{body}M30\n%\n")
}

fn siemens(body: &str) -> String {
    format!("G17 G71 G90\nG0 X0 Y0\n{body}M30\n")
}

/// Siemens → FANUC, proven: the program's lines.
fn to_fanuc(src: &str) -> Vec<String> {
    proven_to_fanuc(src, &TranslateOptions::default())
}

fn to_fanuc_codes(src: &str) -> Vec<&'static str> {
    let mut db = SourceDb::new();
    let u = parse(&mut db, "in.mpf", src, Dialect::Sinumerik);
    let t = translate::to_fanuc::to_fanuc(&u, &[], &TranslateOptions::default());
    assert!(!t.ok(), "translated:\n{}", t.text);
    t.diags.iter().filter(|d| d.is_error()).map(|d| d.code).collect()
}

/// FANUC → Sinumerik, proven: the program's lines.
fn to_sinumerik(src: &str) -> Vec<String> {
    let mut db = SourceDb::new();
    let id = db.add("in.nc", src);
    let u = nctrans::parse(&db, id, Dialect::Fanuc, &ParseOptions::for_dialect(Dialect::Fanuc)).unit;
    let tr = ts::translate(&[&u], &Options::default(), LineEnding::Lf);
    assert!(!tr.has_errors(), "not translated:\n{}", nctrans::diag::render(&db, &tr.diags));
    let rep = nctrans::translate::to_sinumerik::verify::verify_with(&db, id, &u, &tr, "out", STEPS);
    assert!(matches!(rep.verdict, Verdict::Equivalent { .. }), "{:?}\n{}", rep.verdict, rep.diff);
    let main = tr.main().expect("main file");
    main.text.lines().filter(|l| !l.starts_with("; Translated by")).map(str::to_string).collect()
}

#[test]
fn a_chamfer_and_a_rounding_between_lines_in_both_dialects() {
    let f = fanuc("G01 X60. ,C5. F500.\nY40. ,R8.\nX0.\n");
    let want = [
        "move rapid X=0 Y=0 f=-",
        "move linear X=55 Y=0 f=500",
        "move linear X=60 Y=5 f=500",
        "move linear X=60 Y=32 f=500",
        "arc ccw XY X=52 Y=40 center X=52 Y=32 f=500",
        "move linear X=0 Y=40 f=500",
        "end M30 steps=6",
    ];
    assert_eq!(trace(&f, Dialect::Fanuc), want);
    let s = siemens("G1 X60 CHR=5 F500\nY40 RND=8\nX0\n");
    assert_eq!(trace(&s, Dialect::Sinumerik), want);
    // CHF is the chamfer's own length: at a right angle the leg is CHF/√2 (the value first
    // rounded to the 0.001 mm increment, as every length: 7.071 gives 4.999952).
    let s = siemens("G1 X60 CHF=7.0710678 F500\nY40\n");
    let t = trace(&s, Dialect::Sinumerik);
    assert_eq!(t[1..3], ["move linear X=55.000048 Y=0 f=500", "move linear X=60 Y=4.999952 f=500"]);
    // A right turn rounds clockwise; G18 works in Z and X.
    let t = trace(&fanuc("G01 X60. ,R8. F500.\nY-40.\n"), Dialect::Fanuc);
    assert_eq!(t[2], "arc cw XY X=60 Y=-8 center X=52 Y=-8 f=500");
    let t = trace(&fanuc("G18 G01 X0. Z0. F100.\nZ-30. ,R5.\nX20.\n"), Dialect::Fanuc);
    assert!(t.contains(&"arc cw ZX X=5 Y=0 Z=-30 center Z=-25 X=5 f=100".to_string()), "{t:?}");
}

#[test]
fn modal_rounding_rounds_every_corner_until_rndm_0() {
    let s = siemens("G1 X60 RNDM=2 F500\nY40\nX0 RNDM=0\nY0\n");
    let t = trace(&s, Dialect::Sinumerik);
    let arcs = t.iter().filter(|l| l.starts_with("arc")).count();
    assert_eq!(arcs, 2, "{t:?}");
    // The same as RND= on each of those blocks.
    let each = siemens("G1 X60 RND=2 F500\nY40 RND=2\nX0\nY0\n");
    assert_eq!(t, trace(&each, Dialect::Sinumerik));
}

#[test]
fn corners_translate_both_ways_as_a_respelling() {
    let f = fanuc("G01 X60. ,C5. F500.\nY40. ,R8.\nX0. ,C2\nY0.\n");
    let s = to_sinumerik(&f);
    // `,C2` without a decimal point is 0.002 mm (the X rule).
    assert!(s.contains(&"G1 X60 CHR=5 F500".to_string()) && s.contains(&"Y40 RND=8".to_string()), "{s:?}");
    assert!(s.contains(&"X0 CHR=0.002".to_string()), "{s:?}");
    let s = siemens("G1 X60 CHR=5 F500\nY40 RND=8\nX0 RNDM=1.5\nY0\nX10 RNDM=0\nY-10\n");
    let f = to_fanuc(&s);
    for l in ["G01 X60. ,C5. F500.", "Y40. ,R8.", "X0. ,R1.5", "Y0. ,R1.5", "X10.", "Y-10."] {
        assert!(f.contains(&l.to_string()), "{l}: {f:?}");
    }
}

#[test]
fn what_the_translation_cannot_carry_is_refused() {
    // CHF: the leg needs the corner's angle.
    assert_eq!(to_fanuc_codes(&siemens("G1 X60 CHF=4 F500\nY40\n")), ["NC572"]);
    // RNDM where the program does not run straight through its stretch.
    let jumps = siemens("G1 X60 RNDM=2 F500\nY40\nGOTOF END\nX0\nEND:\nY0 RNDM=0\n");
    assert!(to_fanuc_codes(&jumps).contains(&"NC576"));
    let structure = siemens("G1 X60 RNDM=2 F500\nIF R1==0\nY40\nENDIF\nX0 RNDM=0\n");
    assert!(to_fanuc_codes(&structure).contains(&"NC576"));
    let computed = siemens("R1=2\nG1 X60 RNDM=R1 F500\nY40\nX0 RNDM=0\n");
    assert!(to_fanuc_codes(&computed).contains(&"NC576"));
}

#[test]
fn a_planted_wrong_corner_is_caught() {
    let f = fanuc("G01 X60. ,C5. F500.\nY40. ,R8.\nX0.\n");
    let right = siemens("G1 X60 CHR=5 F500\nY40 RND=8\nX0\n");
    assert!(matches!(check_pair(&right, &f), Verdict::Equivalent { .. }));
    for wrong in [
        "G1 X60 CHR=4 F500\nY40 RND=8\nX0\n",    // the chamfer's size
        "G1 X60 CHR=5 F500\nY40 RND=8.01\nX0\n", // the radius
        "G1 X60 CHF=5 F500\nY40 RND=8\nX0\n",    // chamfer length for leg
        "G1 X60 RND=5 F500\nY40 CHR=8\nX0\n",    // chamfer and rounding swapped
        "G1 X60 F500\nY40 RND=8\nX0\n",          // the chamfer left out
    ] {
        let v = check_pair(&siemens(wrong), &f);
        assert!(matches!(v, Verdict::Diverged { .. }), "{wrong}: {v:?}");
    }
}

#[test]
fn corners_that_cannot_be_made_are_refused_with_their_reason() {
    let cases: &[(&str, &str)] = &[
        // Longer than a leg, in line, a rapid or an arc next to it.
        ("G01 X4. ,C5. F500.\nY40.\n", "NC574"),
        ("G01 X40. ,R5. F500.\nY2.\n", "NC574"),
        ("G01 X40. ,R5. F500.\nX80.\n", "NC574"),
        ("G00 X40. ,C5.\nG01 Y40. F500.\n", "NC574"),
        ("G02 X40. Y0. R20. ,R5. F500.\nG01 Y40.\n", "NC574"),
        ("G01 X40. ,R5. F500.\nG03 X60. Y20. R20.\n", "NC573"),
        // The next block is not the move: a function alone, a macro statement, the end.
        ("G01 X40. ,C5. F500.\nM08\nY40.\n", "NC573"),
        ("G01 X40. ,C5. F500.\n#1=2.\nY40.\n", "NC573"),
        ("G01 X40. ,C5. F500. M09\nY40.\n", "NC574"),
        ("G01 X40. ,C5. F500.\n", "NC573"),
        // Out of the plane, another feed.
        ("G01 X40. Z-2. ,C5. F500.\nY40.\n", "NC574"),
        ("G01 X40. ,C5. F500.\nY40. Z-2.\n", "NC574"),
        ("G01 X40. ,C5. F500.\nY40. F400.\n", "NC575"),
        // A corner word without a move, two in one block, a work offset selected with it.
        ("G01 F500. ,C5.\nX40.\n", "NC574"),
        ("G01 X40. ,C5. ,R2. F500.\nY40.\n", "NC574"),
        ("G55 G01 X40. ,C5. F500.\nY40.\n", "NC574"),
    ];
    for (body, code) in cases {
        let (t, errs) = run(&fanuc(body), Dialect::Fanuc);
        assert_eq!(errs, [*code], "{body}: {t:?}");
    }
    // A line with nothing but a comment or a sequence number commands nothing: passed over.
    let (t, errs) = run(&fanuc("G01 X40. ,C5. F500.\n(FINISH)\nN100\nY40.\n"), Dialect::Fanuc);
    assert!(errs.is_empty() && t.contains(&"move linear X=40 Y=5 f=500".to_string()), "{errs:?} {t:?}");
    // Siemens: the same rules, and a corner feed of its own is not modelled.
    let (_, errs) = run(&siemens("G1 X4 CHR=5 F500\nY40\n"), Dialect::Sinumerik);
    assert_eq!(errs, ["NC574"]);
    let (_, errs) = run(&siemens("G1 X40 RND=5 FRC=100 F500\nY40\n"), Dialect::Sinumerik);
    assert_eq!(errs, ["NC575"]);
    let (_, errs) = run(&siemens("G1 X40 RNDM=2 F500\nY40 RND=3\nX0\n"), Dialect::Sinumerik);
    assert_eq!(errs, ["NC574"]);
}

#[test]
fn tool_radius_compensation_events_are_those_of_the_sharp_contour() {
    let body = |c: &str, r: &str| {
        format!("T1 M06\nG43 H01 Z5.\nG01 Z-2. F300.\nG41 D01 X10. Y0.\nX60.{c}\nY40.{r}\nX10.\nG40 X0. Y-10.\nG49\n")
    };
    let comp = |t: Vec<String>| t.into_iter().filter(|l| l.starts_with("comp")).collect::<Vec<_>>();
    let sharp = comp(trace(&fanuc(&body("", "")), Dialect::Fanuc));
    let cut = trace(&fanuc(&body(" ,C5.", " ,R8.")), Dialect::Fanuc);
    assert!(cut.iter().any(|l| l.starts_with("arc")), "{cut:?}");
    assert_eq!(comp(cut), sharp);
}

#[test]
fn a_streamed_run_and_translation_keep_the_corners() {
    let dir = std::env::temp_dir().join(format!("nctrans-corner-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let src = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("corpus/in/fanuc/corner-chamfer-round-plate.nc");
    let input = dir.join("plate.nc");
    std::fs::copy(&src, &input).expect("copy");
    let bin = env!("CARGO_BIN_EXE_nctrans");
    let out = |args: &[&str]| {
        let o = std::process::Command::new(bin).args(args).output().expect("nctrans runs");
        (
            o.status.success(),
            String::from_utf8_lossy(&o.stdout).into_owned(),
            String::from_utf8_lossy(&o.stderr).into_owned(),
        )
    };
    let p = input.to_str().unwrap_or_default();
    let (ok, whole, _) = out(&["run", p]);
    let (ok2, streamed, err) = out(&["run", "--stream", p]);
    assert!(ok && ok2, "{err}");
    assert_eq!(whole, streamed);
    assert!(whole.contains("arc ccw XY X=70 Y=50 Z=-4 center X=70 Y=40 f=450"), "{whole}");
    let o = dir.join("plate.mpf");
    let (ok, _, err) = out(&["--to", "sinumerik", "--stream", p, "-o", o.to_str().unwrap_or_default(), "--force"]);
    assert!(ok && err.contains("equivalent"), "{err}");
    let text = std::fs::read_to_string(&o).unwrap_or_default();
    assert!(text.contains("X80 CHR=6") && text.contains("Y50 RND=10"), "{text}");
    // Modal rounding over a long stretch: the streamed translation writes plain blocks one
    // by one, so it hands the file to the whole-file path, which spreads the `,R`.
    let mut big = String::from("G17 G71 G90\nG0 X0 Y0\nG1 X10 Y0 RNDM=1 F500\n");
    for i in 1..5000 {
        big += &format!("X{} Y{}\n", 10 + 10 * i, if i % 2 == 1 { 10 } else { 0 });
    }
    big += "X50010 Y-20 RNDM=0\nM30\n";
    let input = dir.join("big.mpf");
    std::fs::write(&input, big).expect("write");
    let o = dir.join("big.nc");
    let (ok, _, err) =
        out(&["--to", "fanuc", "--stream", input.to_str().unwrap_or_default(), "-o", o.to_str().unwrap_or_default()]);
    assert!(ok && err.contains("equivalent"), "{err}");
    let text = std::fs::read_to_string(&o).unwrap_or_default();
    assert_eq!(text.matches(",R1.").count(), 5000);
    let _ = std::fs::remove_dir_all(&dir);
}
