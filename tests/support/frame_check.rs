//! What the frame tests share: reading a program, its trace as text lines, and whether a
//! FANUC and a Sinumerik program run alike.
#![allow(dead_code)]

use nctrans::check::{self, Side, Verdict};
use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::eval::{self, NoCallees, RunOptions, VecSink};
use nctrans::ir::Unit;
use nctrans::span::SourceDb;

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
