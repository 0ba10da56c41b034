//! Every CEAD Sinumerik example program (`cead-sinumerik/examples` of the external
//! programs) parses. The set of files that are rejected is asserted
//! exactly, with the reason, so a new rejection or a silent change shows up here.

use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::span::SourceDb;
use nctrans::{diag, ir};
use std::path::PathBuf;

/// Files rejected on purpose: (file name, diagnostic code, why). None at present.
const REJECTED: &[(&str, &str, &str)] = &[];

/// Files accepted with a warning: (file name, warning code, why).
const WARNED: &[(&str, &str, &str)] = &[(
    "r_param.mpf",
    "NC133",
    "`DEF REAL R0=0` declares a name that is R parameter R0; every later `R0` is the R parameter",
)];

fn programs() -> Vec<PathBuf> {
    let dir = crate::external("cead-sinumerik/examples");
    let mut v = Vec::new();
    for d in [dir.clone(), dir.join("flattening")] {
        for e in std::fs::read_dir(&d).expect("readable folder").flatten() {
            let p = e.path();
            if p.extension().is_some_and(|x| x == "mpf") {
                v.push(p);
            }
        }
    }
    v.sort();
    v
}

#[test]
fn every_cead_example_parses() {
    let files = programs();
    assert!(files.len() >= 30, "expected the 32 CEAD examples, found {}", files.len());
    let mut rejected = Vec::new();
    let mut warned = Vec::new();
    for f in &files {
        let name = f.file_name().unwrap_or_default().to_string_lossy().to_string();
        let bytes = std::fs::read(f).expect("readable");
        let mut db = SourceDb::new();
        let loaded = nctrans::load(&mut db, &name, &bytes, None);
        let p = nctrans::parse(&db, loaded.file, Dialect::Sinumerik, &ParseOptions::for_dialect(Dialect::Sinumerik));
        let problems = ir::visit::check_spans(&p.unit, db.get(loaded.file).text.len() as u32);
        assert!(problems.is_empty(), "{name}: {problems:?}");
        for d in &p.diags {
            if d.is_error() {
                rejected.push((name.clone(), d.code, diag::render(&db, std::slice::from_ref(d))));
            } else {
                warned.push((name.clone(), d.code));
            }
        }
    }
    let got: Vec<(&str, &str)> = rejected.iter().map(|(n, c, _)| (n.as_str(), *c)).collect();
    let want: Vec<(&str, &str)> = REJECTED.iter().map(|(n, c, _)| (*n, *c)).collect();
    let details: Vec<&str> = rejected.iter().map(|(_, _, r)| r.as_str()).collect();
    assert_eq!(got, want, "rejections changed:\n{}", details.join("\n"));
    let got: Vec<(&str, &str)> = warned.iter().map(|(n, c)| (n.as_str(), *c)).collect();
    let want: Vec<(&str, &str)> = WARNED.iter().map(|(n, c, _)| (*n, *c)).collect();
    assert_eq!(got, want);
}
