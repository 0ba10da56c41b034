//! The one library entry (`translate::translate`, `translate::verify`) gives, for each
//! target, what the work behind it gives, and proves both directions with one call.

use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::ir::Unit;
use nctrans::read::LineEnding;
use nctrans::span::SourceDb;
use nctrans::translate::{self, to_fanuc::TranslateOptions, to_sinumerik, Options};

fn load(db: &mut SourceDb, name: &str, text: &str, d: Dialect) -> Unit {
    let file = db.add(name, text.to_string());
    let parsed = nctrans::parse(db, file, d, &ParseOptions::for_dialect(d));
    assert!(parsed.diags.is_empty(), "{:?}", parsed.diags);
    parsed.unit
}

#[test]
fn to_fanuc_through_the_entry() {
    let mut db = SourceDb::new();
    let src = "R1=2\nWHILE R1<5\nG1 X=R1*2 F100\nR1=R1+1\nENDWHILE\nM30\n";
    let unit = load(&mut db, "w.mpf", src, Dialect::Sinumerik);
    let fanuc = TranslateOptions { line_ending: LineEnding::CrLf, ..TranslateOptions::default() };
    let stage = translate::to_fanuc::to_fanuc(&unit, &[], &fanuc);
    // The entry's line ending is the output's, whatever the FANUC options say.
    let opts = Options { line_ending: LineEnding::CrLf, ..Options::default() };
    let t = translate::translate(&[&unit], Dialect::Fanuc, &opts);
    assert_eq!(t.target(), Dialect::Fanuc);
    assert!(t.ok(), "{:?}", t.diags);
    assert_eq!(t.files.len(), 1);
    assert_eq!(t.text(), stage.text);
    assert!(t.text().contains("\r\n"));
    assert_eq!(t.symbols.fanuc(), &stage.symbol_map);
    assert!(t.symbols.sinumerik().vars.is_empty());
    let v = translate::verify(&mut db, &[&unit], &t, "out.nc", 100_000);
    assert!(v.equivalent, "{}\n{}", v.summary, v.rendered);
}

#[test]
fn to_sinumerik_through_the_entry() {
    let mut db = SourceDb::new();
    let src = "%\nO1\n#500=1\nWHILE[#500LT4]DO1\nG1X#500F100.\n#500=#500+1\nEND1\nM30\n%\n";
    let unit = load(&mut db, "w.nc", src, Dialect::Fanuc);
    let opts = Options::to_sinumerik(to_sinumerik::Options::default(), LineEnding::Lf);
    let t = translate::translate(&[&unit], Dialect::Sinumerik, &opts);
    let stage = to_sinumerik::translate(&[&unit], &opts.sinumerik, LineEnding::Lf);
    assert_eq!(t.target(), Dialect::Sinumerik);
    assert!(t.ok(), "{:?}", t.diags);
    assert_eq!(t.files, stage.files);
    assert!(t.symbols.sinumerik().common(500).is_some());
    let v = translate::verify(&mut db, &[&unit], &t, "out", 100_000);
    assert!(v.equivalent, "{}\n{}", v.summary, v.rendered);
    assert!(v.summary.starts_with("equivalent ("), "{}", v.summary);
}

#[test]
fn a_wrong_translation_is_not_equivalent_for_either_target() {
    let mut db = SourceDb::new();
    let unit = load(&mut db, "w.mpf", "G1 X10 F100\nM30\n", Dialect::Sinumerik);
    let mut t = translate::translate(&[&unit], Dialect::Fanuc, &Options::default());
    t.files[0].text = t.files[0].text.replace("X10.", "X11.");
    let v = translate::verify(&mut db, &[&unit], &t, "bad.nc", 100_000);
    assert!(!v.equivalent && v.summary.starts_with("diverged"), "{}", v.summary);

    let unit = load(&mut db, "w.nc", "%\nO1\nG1X10.F100.\nM30\n%\n", Dialect::Fanuc);
    let mut t = translate::translate(&[&unit], Dialect::Sinumerik, &Options::default());
    t.files[0].text = t.files[0].text.replace("X10", "X11");
    let v = translate::verify(&mut db, &[&unit], &t, "bad", 100_000);
    assert!(!v.equivalent && v.summary.starts_with("diverged"), "{}", v.summary);
    let v = translate::verify(&mut db, &[], &t, "bad", 100_000);
    assert!(!v.equivalent);
}
