//! A third dialect added from outside the crate (issue 18): the ISO subset of
//! `iso_dialect/iso.rs`, described with `nctrans::dialect::Spec` and nothing else, is read,
//! translated to and from both built-ins through the generic entry
//! (`translate::generic::translate_between`), and every translation is proven by the generic
//! verify (read back, both sides run, traces compared). A planted wrong translation
//! diverges; a construct plain G-code cannot express is refused with its span.

#[path = "iso_dialect/iso.rs"]
mod iso;

use iso::Iso;
use nctrans::dialect::spec::detect;
use nctrans::dialect::{Dialect, ParseOptions, Spec};
use nctrans::ir::Unit;
use nctrans::span::SourceDb;
use nctrans::translate::generic::{builtin, translate_between, verify_between};
use nctrans::translate::{self, Options, Translation};

/// A machinist's plain program: metric, a face pass and a full circle, an incremental step.
const ISO: &str = "%\n(FACE AND CIRCLE)\nN10 G21 G17 G90\nN20 S1200 M3\nN30 G0 X0 Y0 Z5\n\
N40 G1 Z-1 F100\nN50 G1 X40 Y0 F250\nN60 G2 X60 Y20 R20\nN70 G3 X40 Y40 I-20 J0\n\
N80 G91 G1 Y-10\nN90 G90 G0 Z5\nN100 M5\nN110 M30\n%\n";

const FANUC: &str = "%\nO0100 (POCKET)\nN10 G21 G17 G90\nN20 S800 M3\nN30 G0 X10 Y0 Z5.\n\
N40 G1 Z-2. F120.\nN50 G1 X30. Y0\nN60 G2 X40. Y10. I0 J10.\nN70 G91 G1 X-5.\nN80 G90 G0 Z5.\nN90 M5\nN100 M30\n%\n";

const SINUMERIK: &str = "; CONTOUR\nN10 G17 G90 G71\nN20 S1500 M3\nN30 G0 X0 Y0 Z5\nN40 G1 Z-1.5 F90\n\
N50 G1 X25 Y5\nN60 G2 X35 Y15 CR=10\nN70 G3 X25 Y25 I=-10 J=0\nN80 G0 Z5\nN90 M5\nN100 M30\n";

fn read(db: &mut SourceDb, name: &str, text: &str, spec: &dyn Spec) -> Unit {
    let file = db.add(name, text.to_string());
    let parsed = spec.parse(db.get(file), file, &ParseOptions { semantics: spec.semantics() });
    assert!(parsed.diags.is_empty(), "{}", nctrans::diag::render(db, &parsed.diags));
    assert!(nctrans::ir::visit::check_spans(&parsed.unit, text.len() as u32).is_empty());
    parsed.unit
}

fn proven(db: &mut SourceDb, unit: &Unit, from: &dyn Spec, to: &dyn Spec) -> Translation {
    let t = translate_between(&[unit], from, to, &Options::default());
    assert!(t.ok(), "{}", nctrans::diag::render(db, &t.diags));
    let v = verify_between(db, &[unit], from, to, &t, "out", 100_000);
    assert!(v.equivalent, "{} -> {}: {}\n{}\n{}", from.name(), to.name(), v.summary, v.rendered, t.text());
    assert!(v.summary.starts_with("equivalent ("), "{}", v.summary);
    t
}

#[test]
fn the_iso_reader_builds_ir_with_spans() {
    let mut db = SourceDb::new();
    let unit = read(&mut db, "face.iso", ISO, &Iso);
    assert_eq!(unit.dialect, Dialect::Fanuc);
    let dump = nctrans::ir::dump::dump(&unit);
    assert!(dump.contains("word R 20"), "{dump}");
    assert!(dump.contains("end M30"), "{dump}");
    assert!(dump.contains("comment \"FACE AND CIRCLE\""), "{dump}");
}

#[test]
fn iso_to_fanuc_is_proven_and_writes_points() {
    let mut db = SourceDb::new();
    let unit = read(&mut db, "face.iso", ISO, &Iso);
    let t = proven(&mut db, &unit, &Iso, builtin(Dialect::Fanuc));
    // ISO reads `X40` as 40 mm; FANUC would read it as 0.040 mm, so it is written `X40.`.
    assert!(t.text().contains("X40."), "{}", t.text());
    assert!(t.text().contains("O0001"), "{}", t.text());
    assert_eq!(t.target(), Dialect::Fanuc);
}

#[test]
fn iso_to_sinumerik_is_proven() {
    let mut db = SourceDb::new();
    let unit = read(&mut db, "face.iso", ISO, &Iso);
    let t = proven(&mut db, &unit, &Iso, builtin(Dialect::Sinumerik));
    assert_eq!(t.target(), Dialect::Sinumerik);
    assert!(t.text().contains("X40"), "{}", t.text());
    // To itself: the same model and profile, written again as it was read.
    let t = proven(&mut db, &unit, &Iso, &Iso);
    assert_eq!(t.text(), ISO);
}

#[test]
fn fanuc_to_iso_is_proven_and_restates_increments() {
    let mut db = SourceDb::new();
    let unit = read(&mut db, "pocket.nc", FANUC, builtin(Dialect::Fanuc));
    let t = proven(&mut db, &unit, builtin(Dialect::Fanuc), &Iso);
    // FANUC `X10` is ten increments of 0.001 mm: plain G-code writes the length.
    assert!(t.text().contains("N30 G0 X0.01 Y0 Z5"), "{}", t.text());
    assert!(t.files[0].name.ends_with(".iso"), "{}", t.files[0].name);
}

#[test]
fn sinumerik_to_iso_is_proven() {
    let mut db = SourceDb::new();
    let unit = read(&mut db, "contour.mpf", SINUMERIK, builtin(Dialect::Sinumerik));
    let t = proven(&mut db, &unit, builtin(Dialect::Sinumerik), &Iso);
    assert!(t.text().contains("R10"), "{}", t.text());
    // The header of the translation it went through (which names FANUC) is not copied.
    assert!(!t.text().contains("FANUC"), "{}", t.text());
    // The output reads back as ISO and back again to Sinumerik, still proven.
    let back = read(&mut db, "contour.iso", t.text(), &Iso);
    proven(&mut db, &back, &Iso, builtin(Dialect::Sinumerik));
}

#[test]
fn a_planted_wrong_coordinate_diverges_both_ways() {
    let mut db = SourceDb::new();
    let unit = read(&mut db, "face.iso", ISO, &Iso);
    let fanuc = builtin(Dialect::Fanuc);
    let mut t = translate_between(&[&unit], &Iso, fanuc, &Options::default());
    t.files[0].text = t.files[0].text.replace("X60.", "X61.");
    let v = verify_between(&mut db, &[&unit], &Iso, fanuc, &t, "out", 100_000);
    assert!(!v.equivalent);
    assert!(v.summary.starts_with("diverged"), "{}", v.summary);
    assert!(v.rendered.contains("NC500"), "{}", v.rendered);

    let src = read(&mut db, "pocket.nc", FANUC, fanuc);
    let mut t = translate_between(&[&src], fanuc, &Iso, &Options::default());
    assert!(t.text().contains("X40 Y10"), "{}", t.text());
    t.files[0].text = t.files[0].text.replace("X40 Y10", "X40 Y10.5");
    let v = verify_between(&mut db, &[&src], fanuc, &Iso, &t, "out", 100_000);
    assert!(v.summary.starts_with("diverged"), "{}", v.summary);
}

#[test]
fn what_plain_g_code_cannot_express_is_refused_at_its_span() {
    let mut db = SourceDb::new();
    let text = "N10 G90 G0 X0 Y0\nR1=5\nG1 X=R1 F100\nM30\n";
    let unit = read(&mut db, "var.mpf", text, builtin(Dialect::Sinumerik));
    let t = translate_between(&[&unit], builtin(Dialect::Sinumerik), &Iso, &Options::default());
    assert!(t.has_errors() && t.files.is_empty());
    let rendered = nctrans::diag::render(&db, &t.diags);
    assert!(rendered.contains("NC519") && rendered.contains("a variable assignment has no ISO spelling"), "{rendered}");
    assert!(rendered.contains("var.mpf:2:1"), "{rendered}");
    let v = verify_between(&mut db, &[&unit], builtin(Dialect::Sinumerik), &Iso, &t, "out", 100_000);
    assert!(!v.equivalent && v.summary.contains("refused"), "{}", v.summary);

    let text = "%\nO1\n#1=0\nWHILE[#1LT2]DO1\nG91 G1 X1. F100.\n#1=#1+1\nEND1\nM30\n%\n";
    let unit = read(&mut db, "loop.nc", text, builtin(Dialect::Fanuc));
    let t = translate_between(&[&unit], builtin(Dialect::Fanuc), &Iso, &Options::default());
    let rendered = nctrans::diag::render(&db, &t.diags);
    assert!(rendered.contains("a control structure has no ISO spelling"), "{rendered}");
    assert!(rendered.contains("loop.nc:3:1"), "{rendered}");
}

#[test]
fn bad_iso_input_is_a_diagnostic_with_its_place() {
    let mut db = SourceDb::new();
    let file = db.add("bad.iso", "G1 X10\nG1 Y\nT1 M6\n(open\n".to_string());
    let parsed = Iso.parse(db.get(file), file, &ParseOptions { semantics: Iso.semantics() });
    let rendered = nctrans::diag::render(&db, &parsed.diags);
    assert_eq!(parsed.diags.len(), 3, "{rendered}");
    assert!(rendered.contains("bad.iso:2:4") && rendered.contains("`Y` without a number"), "{rendered}");
    assert!(rendered.contains("`T1` is not in the ISO subset"), "{rendered}");
    assert!(rendered.contains("a comment without `)`"), "{rendered}");
}

#[test]
fn detection_and_the_built_in_pairs() {
    let specs: [&dyn Spec; 3] = [&Iso, builtin(Dialect::Fanuc), builtin(Dialect::Sinumerik)];
    assert_eq!(detect(&specs, "a.iso", "").map(|s| s.name()), Some("iso"));
    assert_eq!(detect(&specs, "a.txt", ISO).map(|s| s.name()), Some("iso"));
    assert_eq!(detect(&specs, "a.txt", "#1=2\nG1 X#1\n").map(|s| s.name()), Some("fanuc"));
    assert_eq!(detect(&specs, "a.txt", "R1=2\nIF R1==2 GOTOF A\n").map(|s| s.name()), Some("sinumerik"));
    // A pair of built-ins takes their own translation and proof unchanged.
    let mut db = SourceDb::new();
    let unit = read(&mut db, "c.mpf", SINUMERIK, builtin(Dialect::Sinumerik));
    let t = proven(&mut db, &unit, builtin(Dialect::Sinumerik), builtin(Dialect::Fanuc));
    assert_eq!(t.text(), translate::translate(&[&unit], Dialect::Fanuc, &Options::default()).text());
}

#[test]
fn cut_and_garbled_iso_input_never_panics() {
    let variants: Vec<String> = (0..ISO.len())
        .filter(|&i| ISO.is_char_boundary(i))
        .flat_map(|i| {
            [ISO[..i].to_string(), format!("{}é{}", &ISO[..i], &ISO[i..]), format!("{}){}", &ISO[..i], &ISO[i..])]
        })
        .collect();
    for text in variants {
        let mut db = SourceDb::new();
        let file = db.add("cut.iso", text.clone());
        let parsed = Iso.parse(db.get(file), file, &ParseOptions { semantics: Iso.semantics() });
        let _ = nctrans::diag::render(&db, &parsed.diags);
        assert!(nctrans::ir::visit::check_spans(&parsed.unit, text.len() as u32).is_empty(), "{text}");
        if !nctrans::diag::has_errors(&parsed.diags) {
            let fanuc = builtin(Dialect::Fanuc);
            let t = translate_between(&[&parsed.unit], &Iso, fanuc, &Options::default());
            let v = verify_between(&mut db, &[&parsed.unit], &Iso, fanuc, &t, "out", 10_000);
            // Every prefix that reads is a whole program: its translation is proven.
            assert!(v.equivalent, "{}\n{}\n{text}", v.summary, v.rendered);
        }
    }
}

/// A described dialect that runs as Siemens: the built-in Sinumerik's reader, writer and
/// lowering under another name, so the generic path (not the built-in pair's) carries it.
struct Shadow;

impl Spec for Shadow {
    fn name(&self) -> &str {
        "shadow"
    }
    fn extensions(&self) -> &[&str] {
        &["shd"]
    }
    fn sniff(&self, text: &str) -> u32 {
        builtin(Dialect::Sinumerik).sniff(text)
    }
    fn runs_as(&self) -> Dialect {
        Dialect::Sinumerik
    }
    fn semantics(&self) -> nctrans::dialect::Semantics {
        builtin(Dialect::Sinumerik).semantics()
    }
    fn parse(
        &self,
        src: &nctrans::span::SourceFile,
        file: nctrans::span::FileId,
        o: &ParseOptions,
    ) -> nctrans::dialect::Parsed {
        builtin(Dialect::Sinumerik).parse(src, file, o)
    }
    fn lower(&self, u: &Unit, s: &nctrans::dialect::Semantics) -> Result<Unit, Vec<nctrans::diag::Diagnostic>> {
        builtin(Dialect::Sinumerik).lower(u, s)
    }
    fn emit(&self, u: &Unit, e: nctrans::read::LineEnding) -> nctrans::dialect::Written {
        builtin(Dialect::Sinumerik).emit(u, e)
    }
}

#[test]
fn a_dialect_that_runs_as_siemens_goes_through_the_generic_path() {
    let mut db = SourceDb::new();
    let src = "R1=2\nWHILE R1<4\nG1 X=R1*10 F100\nR1=R1+1\nENDWHILE\nM30\n";
    let unit = read(&mut db, "w.shd", src, &Shadow);
    // To the built-in of its own model: lowered and written by the target description.
    let t = proven(&mut db, &unit, &Shadow, builtin(Dialect::Sinumerik));
    assert!(t.text().contains("WHILE R1<4"), "{}", t.text());
    // To FANUC: bridged by the Sinumerik → FANUC translation, proven with its alignment.
    let t = proven(&mut db, &unit, &Shadow, builtin(Dialect::Fanuc));
    assert!(t.text().contains("WHILE"), "{}", t.text());
    // FANUC IR cannot become Siemens IR for a described target: refused, not guessed.
    let fanuc = read(&mut db, "f.nc", FANUC, builtin(Dialect::Fanuc));
    let t = translate_between(&[&fanuc], builtin(Dialect::Fanuc), &Shadow, &Options::default());
    assert!(t.files.is_empty());
    assert_eq!(t.diags.iter().map(|d| d.code).collect::<Vec<_>>(), vec!["NC516"]);
    // Units read by another description are not taken as this one's.
    let t = translate_between(&[&fanuc], &Shadow, &Iso, &Options::default());
    assert_eq!(t.diags.iter().map(|d| d.code).collect::<Vec<_>>(), vec!["NC516"]);
}
