//! Shared by the in-process translation tests: parse a program (its errors fail the test)
//! and translate Siemens → FANUC with the verification that must prove it.

#![allow(dead_code)]

use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::ir::Unit;
use nctrans::span::SourceDb;
use nctrans::translate::{self, to_fanuc::TranslateOptions};

/// The step limit of every run these tests make.
pub const STEPS: u64 = 100_000;

/// `text` read as a program of dialect `d`, added to `db` as `name`.
pub fn parse(db: &mut SourceDb, name: &str, text: &str, d: Dialect) -> Unit {
    let id = db.add(name, text);
    let p = nctrans::parse(db, id, d, &ParseOptions::for_dialect(d));
    assert!(!nctrans::diag::has_errors(&p.diags), "{name}:\n{}", nctrans::diag::render(db, &p.diags));
    p.unit
}

/// Siemens → FANUC with `opts`: the program lines (no `%`, O line or nctrans notes) after
/// the verification proved them equivalent.
pub fn proven_to_fanuc(src: &str, opts: &TranslateOptions) -> Vec<String> {
    let mut db = SourceDb::new();
    let u = parse(&mut db, "in.mpf", src, Dialect::Sinumerik);
    let t = translate::to_fanuc::to_fanuc(&u, &[], opts);
    assert!(t.ok(), "not translated:\n{}", nctrans::diag::render(&db, &t.diags));
    let v = translate::to_fanuc::verify(&mut db, &u, &[], &t.clone().into(), "out.nc", STEPS);
    assert!(v.equivalent, "{}\n{}\n{}", v.summary, v.rendered, t.text);
    t.text
        .lines()
        .filter(|l| *l != "%" && !l.starts_with('O') && !l.starts_with("(NCTRANS"))
        .map(str::to_string)
        .collect()
}

/// The check of a Siemens program `s` against a FANUC one `f`, each run alone.
pub fn check_pair(s: &str, f: &str) -> nctrans::check::Verdict {
    let mut db = SourceDb::new();
    let (s, f) = (parse(&mut db, "a.mpf", s, Dialect::Sinumerik), parse(&mut db, "b.nc", f, Dialect::Fanuc));
    let side = |u: &Unit| nctrans::check::Side {
        unit: u.clone(),
        callees: Box::new(nctrans::eval::NoCallees),
        run: nctrans::eval::RunOptions { max_steps: STEPS, ..nctrans::eval::RunOptions::default() },
    };
    nctrans::check::check(&db, side(&s), side(&f)).verdict
}
