//! Round trips through the FANUC → Sinumerik translation, proven by running both ends:
//! FANUC corpus → Sinumerik → FANUC, and Sinumerik corpus → FANUC → Sinumerik. The program
//! at the end must give the original's trace (`check`), so a round trip can only pass if
//! both directions kept the meaning.

use nctrans::check::{self, Side, Verdict};
use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::eval::{DirCallees, RunOptions};
use nctrans::ir::Unit;
use nctrans::span::SourceDb;
use nctrans::translate::to_fanuc::{to_fanuc, TranslateOptions};
use nctrans::translate::to_sinumerik::{translate, Options};
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
    Ok(compare(&db, p.unit, b, units, nctrans::translate::to_fanuc::EXCLUDE))
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

/// Issue 17 item 10: a round trip does not grow. A translation translated back and forth
/// (the first round trip, t1 → t2 → t3) and that once more (the second, t3 → t4 → t5) write
/// the same programs byte for byte (t4 = t2, t5 = t3), both ways, on every corpus program
/// that round-trips as one file; and no text carries two nctrans headers (a translation
/// translated back drops the old header, never stacks it). Only the header lines that say
/// where each variable went may name other FANUC numbers, and one renaming is on purpose:
/// a main program's DEF variable (an is-set flag `LOC2_SET`, say) goes to a free common
/// from #100 up, which comes back as R100, and R parameters go to the retained #500+n
/// (FANUC clears #100–#199 at reset, Siemens keeps every R parameter), so `#100` becomes
/// `#600` once and then stays: such a program must be the same up to that renaming.
/// Programs whose second round trip is equivalent but not the same text, and why.
const NOT_A_FIXED_POINT: &[(&str, &str)] = &[(
    "g52-pockets-g28-tool-changes.nc",
    // The first FANUC text's `G91 G28 Z0.` (a G74 under G90, its G91 saved and given back)
    // is modal on FANUC, so it comes back as `G91` / `G74 Z1=0`; that G74 under a known G91
    // is then `G91` / `G28 Z0.` (translatable since TRANS with incremental moves is).
    "G91 G28 Z0. written again as G91 / G28 Z0.",
)];

#[test]
fn the_second_round_trip_is_the_first_byte_for_byte() {
    let mut same = 0;
    let mut grown = Vec::new();
    for dir in ["corpus/in/sinumerik", "corpus/in/fanuc"] {
        for c in cases(dir) {
            let Ok(bytes) = std::fs::read(&c) else { continue };
            let mut db = SourceDb::new();
            let loaded = nctrans::load(&mut db, "x", &bytes, None);
            let siemens = dir.ends_with("sinumerik");
            let step = |t: &str, n: usize| if (n % 2 == 1) == siemens { s_to_f(t) } else { f_to_s(t) };
            let mut t = vec![db.get(loaded.file).text.clone()];
            for n in 1..=5 {
                match step(&t[n - 1], n) {
                    Some(x) => t.push(x),
                    None => break,
                }
            }
            if t.len() < 6 {
                continue;
            }
            let name = c.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
            if NOT_A_FIXED_POINT.iter().any(|(n, _)| *n == name) {
                continue;
            }
            // The text without the variable-map lines of nctrans's header.
            let body = |x: &str| -> String {
                x.lines()
                    .filter(|l| {
                        let map = l.starts_with(";   #") && l.contains(" = ");
                        let fanuc = l.starts_with("(NCTRANS: ")
                            && (l.contains(" = #") || l.starts_with("(NCTRANS: TEMPORARIES"));
                        !(map || fanuc)
                    })
                    .collect::<Vec<_>>()
                    .join("\n")
            };
            let headers = |x: &str| {
                x.lines()
                    .filter(|l| l.starts_with("; Translated by nctrans") || l.starts_with("(NCTRANS: SINUMERIK"))
                    .count()
            };
            if let Some(n) = (1..6).find(|&n| headers(&t[n]) > 1) {
                grown.push(format!("{name}: two headers in step {n}:\n{}", t[n]));
            } else if (body(&t[4]) != body(&t[2]) || body(&t[5]) != body(&t[3]))
                && !(names_a_def_variable(&t[2], &t[3], siemens)
                    && renamed(&body(&t[4])) == renamed(&body(&t[2]))
                    && renamed(&body(&t[5])) == renamed(&body(&t[3])))
            {
                let (a, b) =
                    if body(&t[4]) != body(&t[2]) { (body(&t[2]), body(&t[4])) } else { (body(&t[3]), body(&t[5])) };
                let d = a.lines().zip(b.lines()).find(|(x, y)| x != y);
                grown.push(format!("{name}: {d:?} (lines {} / {})", a.lines().count(), b.lines().count()));
            } else {
                same += 1;
            }
        }
    }
    assert!(grown.is_empty(), "{} second round trips differ from the first:\n{}", grown.len(), grown.join("\n"));
    assert!(same >= 100, "only {same} corpus programs round-trip as one file");
}

/// Whether the FANUC text of a first round trip (`t2` from a FANUC program, else `t3`) puts
/// a Siemens DEF variable on a common from #100 to #199 (its `(NCTRANS: NAME = #1xx)` line).
fn names_a_def_variable(t2: &str, t3: &str, siemens: bool) -> bool {
    let fanuc = if siemens { t3 } else { t2 };
    fanuc.lines().any(|l| {
        let Some(rest) = l.strip_prefix("(NCTRANS: ") else { return false };
        let Some((name, n)) = rest.trim_end_matches(')').split_once(" = #") else { return false };
        let numbered =
            |p: &str| name.strip_prefix(p).is_some_and(|d| !d.is_empty() && d.bytes().all(|b| b.is_ascii_digit()));
        let named = !numbered("R") && !numbered("LOC");
        named && n.parse::<u32>().is_ok_and(|n| (100..200).contains(&n))
    })
}

/// `text` with every FANUC variable number and R parameter renamed in order of first
/// appearance (`#600` → `#v1`): two texts the same but for a renaming read the same.
fn renamed(text: &str) -> String {
    let mut names: Vec<String> = Vec::new();
    let mut out = String::new();
    let b = text.as_bytes();
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        let word_start = i == 0 || !b[i - 1].is_ascii_alphanumeric();
        if (c == b'#' || (c == b'R' && word_start)) && i + 1 < b.len() && b[i + 1].is_ascii_digit() {
            let mut j = i + 1;
            while j < b.len() && b[j].is_ascii_digit() {
                j += 1;
            }
            let tok = &text[i..j];
            let k = names.iter().position(|n| n == tok).unwrap_or_else(|| {
                names.push(tok.to_string());
                names.len() - 1
            });
            out.push_str(&format!("{}v{k}", c as char));
            i = j;
        } else {
            out.push(c as char);
            i += 1;
        }
    }
    out
}
