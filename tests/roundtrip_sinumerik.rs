//! Round trips through the FANUC → Sinumerik translation, proven by running both ends:
//! FANUC corpus → Sinumerik → FANUC, and Sinumerik corpus → FANUC → Sinumerik. The program
//! at the end must give the original's trace (`check`), so a round trip can only pass if
//! both directions kept the meaning.

use nctrans::check::{self, Side, Verdict};
use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::eval::{DirCallees, RunOptions};
use nctrans::ir::Unit;
use nctrans::span::SourceDb;
use nctrans::translate::to_sinumerik::{translate, Options};
use nctrans::translate::{to_fanuc, TranslateOptions};
use std::path::PathBuf;

const STEPS: u64 = 1_000_000;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn cases(dir: &str) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(root().join(dir))
        .map(|rd| rd.filter_map(|e| e.ok()).map(|e| e.path()).filter(|p| p.is_file()).collect())
        .unwrap_or_default();
    v.sort();
    v
}

fn parse(db: &mut SourceDb, name: &str, text: &str, d: Dialect) -> Option<Unit> {
    let id = db.add(name, text);
    let p = nctrans::parse(db, id, d, &ParseOptions::for_dialect(d));
    (!nctrans::diag::has_errors(&p.diags)).then_some(p.unit)
}

/// Serves translated subprograms from memory.
struct Mem(Vec<Unit>);

impl nctrans::eval::CalleeSource for Mem {
    fn find(
        &mut self,
        _db: &mut SourceDb,
        _caller: nctrans::span::FileId,
        _dialect: Dialect,
        name: &nctrans::eval::CalleeName,
    ) -> Result<Option<Unit>, nctrans::diag::Diagnostic> {
        let found = self.0.iter().find(|u| {
            u.programs.iter().any(|p| match (&p.name, name) {
                (Some(nctrans::ir::ProgName::Name(a)), nctrans::eval::CalleeName::Name(b)) => a.eq_ignore_ascii_case(b),
                (Some(nctrans::ir::ProgName::Number(a)), nctrans::eval::CalleeName::Number(b)) => a == b,
                _ => false,
            })
        });
        Ok(found.cloned())
    }
}

/// `exclude`: what the first leg knowingly drops (a Siemens MSG kept as a FANUC comment does
/// not come back as a message), left out of the comparison as that leg's own check does.
fn compare(db: &SourceDb, a: Unit, b: Unit, b_callees: Vec<Unit>, exclude: check::Exclude) -> Verdict {
    let sa = Side {
        unit: a,
        callees: Box::new(DirCallees { semantics: None }),
        run: RunOptions { max_steps: STEPS, ..RunOptions::default() },
    };
    let sb = Side {
        unit: b,
        callees: Box::new(Mem(b_callees)),
        run: RunOptions { max_steps: STEPS, ..RunOptions::default() },
    };
    check::check_excluding(db, sa, sb, exclude).verdict
}

/// FANUC → Sinumerik → FANUC.
fn fanuc_round_trip(path: &PathBuf) -> Result<Verdict, String> {
    let bytes = std::fs::read(path).map_err(|e| e.to_string())?;
    let mut db = SourceDb::new();
    let loaded = nctrans::load(&mut db, &path.display().to_string(), &bytes, None);
    let p = nctrans::parse(&db, loaded.file, Dialect::Fanuc, &ParseOptions::for_dialect(Dialect::Fanuc));
    if nctrans::diag::has_errors(&p.diags) {
        return Err("does not parse".into());
    }
    let s = translate(&[&p.unit], &Options::default(), loaded.line_ending);
    if s.has_errors() {
        return Err("not translatable to Sinumerik".into());
    }
    let mut units = Vec::new();
    for f in &s.files {
        units.push(parse(&mut db, &f.name, &f.text, Dialect::Sinumerik).ok_or("Sinumerik output does not parse")?);
    }
    let main = s.files.iter().position(|f| f.main).unwrap_or(0);
    let subs: Vec<&Unit> = units.iter().enumerate().filter(|(i, _)| *i != main).map(|(_, u)| u).collect();
    let opts = TranslateOptions { main_is_sub: !s.files[main].main, ..TranslateOptions::default() };
    let back = to_fanuc(&units[main], &subs, &opts);
    if !back.ok() {
        return Err(format!(
            "not translatable back to FANUC: {}",
            back.diags.iter().filter(|d| d.is_error()).map(|d| d.message.clone()).collect::<Vec<_>>().join("; ")
        ));
    }
    let b = parse(&mut db, "back.nc", &back.text, Dialect::Fanuc).ok_or("FANUC output does not parse")?;
    Ok(compare(&db, p.unit, b, vec![], check::Exclude::default()))
}

/// Sinumerik → FANUC → Sinumerik.
fn sinumerik_round_trip(path: &PathBuf) -> Result<Verdict, String> {
    let bytes = std::fs::read(path).map_err(|e| e.to_string())?;
    let mut db = SourceDb::new();
    let loaded = nctrans::load(&mut db, &path.display().to_string(), &bytes, None);
    let p = nctrans::parse(&db, loaded.file, Dialect::Sinumerik, &ParseOptions::for_dialect(Dialect::Sinumerik));
    if nctrans::diag::has_errors(&p.diags) {
        return Err("does not parse".into());
    }
    if p.unit.programs.first().is_some_and(|x| !x.params.is_empty()) {
        return Err("a PROC run on its own".into());
    }
    let f = to_fanuc(&p.unit, &[], &TranslateOptions::default());
    if !f.ok() {
        return Err("not translatable to FANUC".into());
    }
    let fu = parse(&mut db, "mid.nc", &f.text, Dialect::Fanuc).ok_or("FANUC output does not parse")?;
    let s = translate(&[&fu], &Options::default(), loaded.line_ending);
    if s.has_errors() {
        return Err(format!(
            "not translatable back to Sinumerik: {}",
            s.diags.iter().filter(|d| d.is_error()).map(|d| d.message.clone()).collect::<Vec<_>>().join("; ")
        ));
    }
    let mut units = Vec::new();
    for o in &s.files {
        units.push(parse(&mut db, &o.name, &o.text, Dialect::Sinumerik).ok_or("Sinumerik output does not parse")?);
    }
    let main = s.files.iter().position(|o| o.main).unwrap_or(0);
    let b = units.remove(main);
    Ok(compare(&db, p.unit, b, units, nctrans::translate::EXCLUDE))
}

fn run_all(dir: &str, f: fn(&PathBuf) -> Result<Verdict, String>) -> (usize, Vec<String>, Vec<String>) {
    let mut ok = 0;
    let mut diverged = Vec::new();
    let mut skipped = Vec::new();
    for c in cases(dir) {
        let name = c.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        match f(&c) {
            Ok(Verdict::Equivalent { .. }) => ok += 1,
            Ok(Verdict::Inconclusive { reason }) => skipped.push(format!("{name}: inconclusive: {reason}")),
            Ok(v) => diverged.push(format!("{name}: {v:?}")),
            Err(why) => skipped.push(format!("{name}: {why}")),
        }
    }
    (ok, diverged, skipped)
}

#[test]
fn fanuc_corpus_round_trips_through_sinumerik() {
    let (ok, diverged, skipped) = run_all("corpus/in/fanuc", fanuc_round_trip);
    println!("FANUC → Sinumerik → FANUC: {ok} equivalent; not round-tripped:\n  {}", skipped.join("\n  "));
    assert!(diverged.is_empty(), "round trips that changed meaning:\n{}", diverged.join("\n"));
    assert!(ok >= 70, "only {ok} FANUC corpus programs round-trip");
}

#[test]
fn sinumerik_corpus_round_trips_through_fanuc() {
    let (ok, diverged, skipped) = run_all("corpus/in/sinumerik", sinumerik_round_trip);
    println!("Sinumerik → FANUC → Sinumerik: {ok} equivalent; not round-tripped:\n  {}", skipped.join("\n  "));
    assert!(diverged.is_empty(), "round trips that changed meaning:\n{}", diverged.join("\n"));
    assert!(ok >= 68, "only {ok} Sinumerik corpus programs round-trip");
}

/// One Sinumerik → FANUC step on text (one main program, no subprograms).
fn s_to_f(text: &str) -> Option<String> {
    let mut db = SourceDb::new();
    let u = parse(&mut db, "rt.mpf", text, Dialect::Sinumerik)?;
    if u.programs.len() != 1 || !u.programs[0].params.is_empty() {
        return None;
    }
    let f = to_fanuc(&u, &[], &TranslateOptions::default());
    f.ok().then_some(f.text)
}

/// One FANUC → Sinumerik step on text (the translation must be one file).
fn f_to_s(text: &str) -> Option<String> {
    let mut db = SourceDb::new();
    let u = parse(&mut db, "rt.nc", text, Dialect::Fanuc)?;
    let s = translate(&[&u], &Options::default(), nctrans::read::LineEnding::Lf);
    (!s.has_errors() && s.files.len() == 1).then(|| s.files[0].text.clone())
}

/// Issue 17 item 10: translating a translation back and forth reaches a fixed point (no
/// tolerance formula growing `…*5EX-7*0.000001`, no header comments piling up): a
/// translation translated back and forth twice gives the same text as once more, both
/// ways, on every corpus program that round-trips as one file. (The first round trip may
/// still rename variables: a FANUC main program's local `#1` becomes `DEF REAL LOC1`, which
/// goes to the common `#100`, which comes back as `R100`, which stays `#600`/`R100`.)
#[test]
fn round_trips_reach_a_fixed_point() {
    let mut fixed = 0;
    let mut moved = Vec::new();
    for dir in ["corpus/in/sinumerik", "corpus/in/fanuc"] {
        for c in cases(dir) {
            let Ok(bytes) = std::fs::read(&c) else { continue };
            let mut db = SourceDb::new();
            let loaded = nctrans::load(&mut db, "x", &bytes, None);
            let text = db.get(loaded.file).text.clone();
            let siemens = dir.ends_with("sinumerik");
            // t1 = the translation, t2 = it translated back, and so on.
            let step = |t: &str, n: usize| if (n % 2 == 1) == siemens { s_to_f(t) } else { f_to_s(t) };
            let mut t = vec![text];
            for n in 1..=7 {
                match step(&t[n - 1], n) {
                    Some(x) => t.push(x),
                    None => break,
                }
            }
            if t.len() < 8 {
                continue;
            }
            let name = c.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
            let first_diff = |a: &str, b: &str| {
                let d = a.lines().zip(b.lines()).find(|(x, y)| x != y);
                d.map_or_else(
                    || format!("lengths {} / {}", a.lines().count(), b.lines().count()),
                    |(x, y)| format!("`{x}` then `{y}`"),
                )
            };
            if t[6] != t[4] || t[7] != t[5] {
                moved.push(format!("{name} (text): {} | {}", first_diff(&t[4], &t[6]), first_diff(&t[5], &t[7])));
            } else {
                fixed += 1;
            }
        }
    }
    assert!(moved.is_empty(), "{} round trips still change the text:\n{}", moved.len(), moved.join("\n"));
    assert!(fixed >= 100, "only {fixed} corpus programs round-trip as one file");
}
