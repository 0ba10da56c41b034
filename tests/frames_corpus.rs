//! The frame programs of the corpus (issue #20): a rotated pocket, a mirrored pair of slots
//! with a scaled copy, and a bolt circle in polar coordinates, each written in both
//! dialects. Each pair is proven equivalent, each committed translation against its source,
//! and wrong translations planted in the committed outputs (rotation sign, centre, mirror
//! axis, scale factor, angle) are caught.

use nctrans::check::{self, Side, Verdict};
use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::eval::{NoCallees, RunOptions};
use nctrans::ir::Unit;
use nctrans::span::SourceDb;
use std::path::PathBuf;

fn read(rel: &str) -> String {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(rel);
    std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

fn load(db: &mut SourceDb, name: &str, text: &str, d: Dialect) -> Unit {
    let id = db.add(name, text);
    let p = nctrans::parse(db, id, d, &ParseOptions::for_dialect(d));
    assert!(!nctrans::diag::has_errors(&p.diags), "{name} does not parse:\n{}", nctrans::diag::render(db, &p.diags));
    p.unit
}

fn verdict(fanuc: &str, siemens: &str) -> Verdict {
    let mut db = SourceDb::new();
    let f = load(&mut db, "f.nc", fanuc, Dialect::Fanuc);
    let s = load(&mut db, "s.mpf", siemens, Dialect::Sinumerik);
    let side = |u: Unit| Side { unit: u, callees: Box::new(NoCallees), run: RunOptions::default() };
    check::check(&db, side(f), side(s)).verdict
}

fn equivalent(fanuc: &str, siemens: &str) -> bool {
    matches!(verdict(fanuc, siemens), Verdict::Equivalent { .. })
}

/// (FANUC source, Sinumerik source, its FANUC → Sinumerik output, its Sinumerik → FANUC output)
const PAIRS: &[(&str, &str, &str, &str)] = &[
    ("g68-rotated-pocket.nc", "rot-rotated-pocket.mpf", "g68-rotated-pocket/O_2101.MPF", "rot-rotated-pocket.mpf.nc"),
    (
        "g51-1-mirrored-pair.nc",
        "mirror-mirrored-pair.mpf",
        "g51-1-mirrored-pair/O_2102.MPF",
        "mirror-mirrored-pair.mpf.nc",
    ),
    ("g16-bolt-circle.nc", "polar-bolt-circle.mpf", "g16-bolt-circle/O_2103.MPF", "polar-bolt-circle.mpf.nc"),
];

fn files(k: usize) -> [String; 4] {
    let (f, s, fs, sf) = PAIRS[k];
    [
        read(&format!("corpus/in/fanuc/{f}")),
        read(&format!("corpus/in/sinumerik/{s}")),
        read(&format!("corpus/out/sinumerik/{fs}")),
        read(&format!("corpus/out/fanuc/{sf}")),
    ]
}

#[test]
fn each_pair_and_each_committed_translation_is_equivalent() {
    for (k, (fname, _, fsname, sfname)) in PAIRS.iter().enumerate() {
        let [f, s, f_s, s_f] = files(k);
        assert!(equivalent(&f, &s), "{fname}: {:?}", verdict(&f, &s));
        assert!(equivalent(&f, &f_s), "{fsname}: {:?}", verdict(&f, &f_s));
        assert!(equivalent(&s_f, &s), "{sfname}: {:?}", verdict(&s_f, &s));
    }
}

#[test]
fn wrong_translations_planted_in_the_committed_outputs_are_caught() {
    let plant = |k: usize, to_sinumerik: bool, from: &str, to: &str| {
        let [f, s, f_s, s_f] = files(k);
        let (good, bad_of) = if to_sinumerik { (f_s, true) } else { (s_f, false) };
        assert!(good.contains(from), "{from:?} not in the committed output of {}", PAIRS[k].0);
        let bad = good.replacen(from, to, 1);
        let caught = if bad_of { !equivalent(&f, &bad) } else { !equivalent(&bad, &s) };
        assert!(caught, "planted {from:?} → {to:?} in {} not caught", PAIRS[k].0);
    };
    // Rotation sign and centre, both ways.
    plant(0, true, "AROT RPL=30", "AROT RPL=-30");
    plant(0, true, "ATRANS X60 Y40", "ATRANS X40 Y60");
    plant(0, false, "G68 X0. Y0. R30.", "G68 X0. Y0. R-30.");
    plant(0, false, "G52 X60. Y40. Z0.", "G52 X40. Y60. Z0.");
    // Mirror axis and scale factor.
    plant(1, true, "AMIRROR X0", "AMIRROR Y0");
    plant(1, true, "ASCALE X0.5 Y0.5", "ASCALE X0.5 Y0.25");
    plant(1, false, "G51.1 X0.", "G51.1 Y0.");
    plant(1, false, "I0.5 J0.5", "I0.5 J1.");
    // The pole and an angle of the bolt circle.
    plant(2, true, "G0 RP=40 AP=120", "G0 RP=40 AP=-120");
    plant(2, true, "TRANS X75 Y60", "TRANS X60 Y75");
    plant(2, false, "SIN[240.]", "SIN[-240.]");
}

#[test]
fn the_sinumerik_sequences_come_back_as_the_fanuc_modes() {
    use nctrans::translate::{self, to_fanuc::TranslateOptions};
    for (k, lines) in [
        (0, &["G68 X60. Y40. R30.\n", "G00 Z50.\nG69\n"][..]),
        (1, &["G51.1 X100.\n", "G50.1 X0.\n", "G51 X100. Y80. I0.5 J0.5\n", "G00 Z5.\nG50\n"][..]),
    ] {
        let [_, _, f_s, _] = files(k);
        let mut db = SourceDb::new();
        let s = load(&mut db, "back.mpf", &f_s, Dialect::Sinumerik);
        let t = translate::to_fanuc::to_fanuc(&s, &[], &TranslateOptions::default());
        assert!(t.ok(), "{}", nctrans::diag::render(&db, &t.diags));
        let v = translate::to_fanuc::verify(&mut db, &s, &[], &t.clone().into(), "back.nc", 100_000);
        assert!(v.equivalent, "{}\n{}", v.summary, t.text);
        for line in lines {
            assert!(t.text.contains(line), "{line:?} missing in\n{}", t.text);
        }
    }
}
