//! FANUC corpus programs with CAM runs inserted (shared by the segmented FANUC → Sinumerik
//! tests): the runs go after some of the first program's top-level statements, none before
//! the first, so the head and `nctrans: set` lines stay on top.

#![allow(dead_code)]

use crate::rng::Rng;
use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::read::LineEnding;
use nctrans::span::SourceDb;

/// `text` with a run from `run` (given the file's line end) after each statement picked
/// (each with `percent` chance); `None` when none is picked, the program does not parse or
/// `run` gives none.
pub fn with_runs(
    text: &str,
    r: &mut Rng,
    percent: u64,
    mut run: impl FnMut(&mut Rng, LineEnding) -> Option<String>,
) -> Option<String> {
    let mut db = SourceDb::new();
    let loaded = nctrans::load(&mut db, "x.nc", text.as_bytes(), None);
    let parsed = nctrans::parse(&db, loaded.file, Dialect::Fanuc, &ParseOptions::for_dialect(Dialect::Fanuc));
    let p = parsed.unit.programs.first()?;
    let decoded = &db.get(loaded.file).text;
    let mut ends: Vec<usize> = p
        .body
        .iter()
        .skip(1)
        .filter(|_| r.chance(percent))
        .filter_map(|s| {
            let hi = s.span.hi as usize;
            let at = decoded.get(hi..)?.find(['\n', '\r'])? + hi;
            Some(decoded.get(at..)?.find(|c| c != '\r' && c != '\n').map_or(decoded.len(), |k| k + at))
        })
        .collect();
    ends.dedup();
    if ends.is_empty() {
        return None;
    }
    let mut out = String::new();
    let mut from = 0;
    for at in ends {
        out.push_str(&decoded[from..at]);
        out.push_str(&run(r, loaded.line_ending)?);
        from = at;
    }
    out.push_str(&decoded[from..]);
    Some(out)
}
