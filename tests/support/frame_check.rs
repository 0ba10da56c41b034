//! What the frame tests share: reading a program, its trace as text lines, and whether a
//! FANUC and a Sinumerik program run alike.
#![allow(dead_code)]

use nctrans::check::{self, Side, Verdict};
use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::eval::{self, NoCallees, RunOptions, VecSink};
use nctrans::ir::Unit;
use nctrans::read::LineEnding;
use nctrans::span::SourceDb;
use nctrans::translate::to_sinumerik::{translate as to_sinumerik, Options};
use nctrans::translate::{self, to_fanuc::TranslateOptions};

/// A FANUC job read for a translation test: its sources, the file and the unit.
pub struct Job {
    pub db: SourceDb,
    pub id: nctrans::span::FileId,
    pub unit: Unit,
}

/// Reads `fanuc` as file `job.nc`, which must parse without errors.
pub fn parse_job(fanuc: &str) -> Job {
    let mut db = SourceDb::new();
    let id = db.add("job.nc", fanuc);
    let p = nctrans::parse(&db, id, Dialect::Fanuc, &ParseOptions::for_dialect(Dialect::Fanuc));
    assert!(!nctrans::diag::has_errors(&p.diags), "{}", nctrans::diag::render(&db, &p.diags));
    Job { db, id, unit: p.unit }
}

pub fn load(db: &mut SourceDb, text: &str, d: Dialect) -> Unit {
    let name = if d == Dialect::Fanuc { "t.nc" } else { "t.mpf" };
    let id = db.add(name, text);
    let p = nctrans::parse(db, id, d, &ParseOptions::for_dialect(d));
    assert!(!nctrans::diag::has_errors(&p.diags), "does not parse:\n{}", nctrans::diag::render(db, &p.diags));
    p.unit
}

/// The trace in its text form under `opts`, one event a line; an error ends it with
/// `error CODE`.
pub fn trace_with(text: &str, d: Dialect, opts: &RunOptions) -> String {
    let mut db = SourceDb::new();
    let unit = load(&mut db, text, d);
    let mut sink = VecSink::default();
    let out = eval::run(&mut db, &unit, &mut NoCallees, opts, &mut sink);
    let mut s: Vec<String> = sink.events.iter().map(|(e, _)| eval::trace::text_line(e)).collect();
    if let Some(e) = out.diags.iter().find(|d| d.severity == nctrans::diag::Severity::Error) {
        s.push(format!("error {}", e.code));
    }
    s.join("\n")
}

/// [`trace_with`] the default options.
pub fn trace(text: &str, d: Dialect) -> String {
    trace_with(text, d, &RunOptions::default())
}

pub fn verdict(fanuc: &str, siemens: &str) -> Verdict {
    let mut db = SourceDb::new();
    let f = load(&mut db, fanuc, Dialect::Fanuc);
    let s = load(&mut db, siemens, Dialect::Sinumerik);
    let side = |u: Unit| Side { unit: u, callees: Box::new(NoCallees), run: RunOptions::default() };
    check::check(&db, side(f), side(s)).verdict
}

pub fn equivalent(fanuc: &str, siemens: &str) -> bool {
    matches!(verdict(fanuc, siemens), Verdict::Equivalent { .. })
}

pub const STEPS: u64 = 100_000;

/// The FANUC translation of a Siemens program, proven equivalent; `Err`: the codes of
/// its refusal.
pub fn s_to_f(siemens: &str) -> Result<String, Vec<String>> {
    let mut db = SourceDb::new();
    let s = load(&mut db, siemens, Dialect::Sinumerik);
    let t = translate::to_fanuc::to_fanuc(&s, &[], &TranslateOptions::default());
    if !t.ok() {
        let mut codes: Vec<String> = t.diags.iter().map(|d| d.code.to_string()).collect();
        codes.dedup();
        return Err(codes);
    }
    let v = translate::to_fanuc::verify(&mut db, &s, &[], &t.clone().into(), "out.nc", STEPS);
    assert!(v.equivalent, "{}\n{}\n{}", v.summary, v.rendered, t.text);
    Ok(t.text)
}

/// The Sinumerik translation of a FANUC program, proven equivalent.
pub fn f_to_s(fanuc: &str) -> Result<String, Vec<String>> {
    let mut db = SourceDb::new();
    let id = db.add("p.nc", fanuc);
    let p = nctrans::parse(&db, id, Dialect::Fanuc, &ParseOptions::for_dialect(Dialect::Fanuc));
    let t = to_sinumerik(&[&p.unit], &Options::default(), LineEnding::Lf);
    if t.has_errors() {
        let mut codes: Vec<String> = t.diags.iter().map(|d| d.code.to_string()).collect();
        codes.dedup();
        return Err(codes);
    }
    let r = nctrans::translate::to_sinumerik::verify::verify_with(&db, id, &p.unit, &t, "out", STEPS);
    let text: String = t.files.iter().map(|x| x.text.clone()).collect();
    assert!(matches!(r.verdict, Verdict::Equivalent { .. }), "{:?}\n{}\n{text}", r.verdict, r.diff);
    Ok(text)
}
