//! Sinumerik → FANUC on the CEAD examples: every example that uses only translatable
//! constructs translates and verifies; the others are refused, never written wrong.

use crate::tool_names::tool_map;
use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::span::SourceDb;
use nctrans::translate::{self, to_fanuc::TranslateOptions};
use std::path::PathBuf;

/// Every CEAD example that uses only translatable constructs translates and verifies.
#[test]
fn cead_examples_translate_and_verify() {
    let dir = crate::external("cead-sinumerik/examples");
    let rd = std::fs::read_dir(&dir).expect("readable folder");
    let mut files: Vec<PathBuf> =
        rd.filter_map(|e| e.ok().map(|e| e.path())).filter(|p| p.extension().is_some_and(|e| e == "mpf")).collect();
    files.sort();
    let (mut ok, mut refused, mut failures) = (0, 0, Vec::new());
    for path in files {
        let bytes = std::fs::read(&path).unwrap_or_default();
        let mut db = SourceDb::new();
        let loaded = nctrans::load(&mut db, &path.display().to_string(), &bytes, None);
        let text = db.get(loaded.file).text.clone();
        let parsed =
            nctrans::parse(&db, loaded.file, Dialect::Sinumerik, &ParseOptions::for_dialect(Dialect::Sinumerik));
        if nctrans::diag::has_errors(&parsed.diags) {
            refused += 1;
            continue;
        }
        let opts = TranslateOptions { tool_map: tool_map(&text), ..TranslateOptions::default() };
        let t = translate::to_fanuc::to_fanuc(&parsed.unit, &[], &opts);
        if !t.ok() {
            refused += 1;
            continue;
        }
        let v = translate::to_fanuc::verify(&mut db, &parsed.unit, &[], &t.clone().into(), "cead.nc", 200_000);
        if v.equivalent || v.summary.starts_with("not verified: a run") {
            ok += usize::from(v.equivalent);
            refused += usize::from(!v.equivalent);
        } else {
            failures.push(format!("{}: {}\n{}", path.display(), v.summary, v.rendered));
        }
    }
    eprintln!("CEAD examples: {ok} translated and verified, {refused} refused or not runnable");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
