//! The check's compare of grid moves (the evaluator's fast path hands the checker moves
//! as integers, `GridMove`) against its compare of events: pairs of generated programs,
//! equal and diverging at chosen events (around the checker's batch boundaries too), are
//! checked with the fast path on and off, in one thread and in two (the second run's
//! thread always has the fast path on, so that mixes grid moves with events), and every
//! way must give the same verdict, diagnostics and diff.

use nctrans::check::{self, Side, Verdict};
use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::eval::machine::set_fast_path;
use nctrans::eval::{NoCallees, RunOptions};
use nctrans::span::SourceDb;
use std::fmt::Write as _;
#[path = "support/rng.rs"]
mod rng;
use rng::Rng;

/// A coordinate: on the grid, or off it (five decimals, an inch program's values).
fn num(r: &mut Rng) -> String {
    let sign = if r.below(3) == 0 { "-" } else { "" };
    match r.below(6) {
        0 => format!("{sign}{}.{:05}", r.below(500), r.below(100_000)),
        1 => format!("{sign}{}.", r.below(500)),
        _ => format!("{sign}{}.{:03}", r.below(500), r.below(1000)),
    }
}

/// The blocks of a straight-line program: moves (rapid and feed, a few axes), modal
/// codes, feeds; sometimes a block the general path runs (a spindle start, an offset).
fn blocks(r: &mut Rng, fanuc: bool, n: usize) -> Vec<String> {
    let mut out = vec![if fanuc { "G21 G90 G17 F500." } else { "G71 G90 G17 F500" }.to_string()];
    for _ in 0..n {
        let mut b = String::new();
        match r.below(40) {
            0 => b.push_str(if fanuc { "G20 " } else { "G70 " }),
            1 => b.push_str(if fanuc { "G21 " } else { "G71 " }),
            2 => b.push_str("M3 S1000 "),
            3 if !fanuc => b.push_str("TRANS X1.5 Y-2.25\n"),
            3 => b.push_str("G10 L2 P1 X1.5 Y-2.25\n"),
            _ => {}
        }
        let rapid = r.below(5) == 0;
        b.push_str(if rapid { "G0" } else { "G1" });
        for axis in ["X", "Y", "Z", "A"] {
            // A in rapids only: a feed move with A under G20 has no settled feed (NC662).
            if r.below(3) != 0 && (rapid || axis != "A") {
                let _ = write!(b, " {axis}{}", num(r));
            }
        }
        if r.below(4) == 0 {
            let _ = write!(b, " F{}", 100 + r.below(2000));
        }
        out.push(b);
    }
    out
}

fn text(blocks: &[String], fanuc: bool) -> String {
    let mut t = String::from(if fanuc { "%\nO1000\n" } else { "" });
    for b in blocks {
        t.push_str(b);
        t.push('\n');
    }
    t.push_str(if fanuc { "M30\n%\n" } else { "M30\n" });
    t
}

/// Verdict, diagnostics and diff of checking `a` against `b`, as text.
fn check_text(a: &(String, bool), b: &(String, bool), one_thread: bool) -> String {
    let mut db = SourceDb::new();
    let names = [if a.1 { "a.nc" } else { "a.mpf" }, if b.1 { "b.nc" } else { "b.mpf" }];
    let ids = [db.add(names[0], a.0.clone()), db.add(names[1], b.0.clone())];
    let side = |id: usize, fanuc: bool| {
        let d = if fanuc { Dialect::Fanuc } else { Dialect::Sinumerik };
        let parsed = nctrans::parse(&db, id, d, &ParseOptions::for_dialect(d));
        Side { unit: parsed.unit, callees: Box::new(NoCallees), run: RunOptions::default() }
    };
    let (sa, sb) = (side(ids[0], a.1), side(ids[1], b.1));
    let r = if one_thread { check::in_one_thread(|| check::check(&db, sa, sb)) } else { check::check(&db, sa, sb) };
    let mut s = format!("{:?}\n{}", r.verdict, r.diff);
    for d in &r.diags {
        let labels: Vec<_> = d.labels.iter().map(|l| (l.file, l.span, l.message.clone())).collect();
        let _ = writeln!(s, "{:?} {} {} {labels:?} {:?}", d.severity, d.code, d.message, d.notes);
    }
    s
}

/// The whole trace of one program, as text lines.
fn trace(p: &(String, bool)) -> Vec<(String, nctrans::eval::Event)> {
    let mut db = SourceDb::new();
    let id = db.add(if p.1 { "p.nc" } else { "p.mpf" }, p.0.clone());
    let d = if p.1 { Dialect::Fanuc } else { Dialect::Sinumerik };
    let parsed = nctrans::parse(&db, id, d, &ParseOptions::for_dialect(d));
    let mut sink = nctrans::eval::VecSink::default();
    nctrans::eval::run(&mut db, &parsed.unit, &mut NoCallees, &RunOptions::default(), &mut sink);
    sink.events.into_iter().map(|(e, _)| (nctrans::eval::trace::text_line(&e), e)).collect()
}

/// What a check of `a` against `b` must find, from their whole traces: the first event
/// that differs, and the diff's two sides (three events of context before and after).
fn expected(a: &(String, bool), b: &(String, bool)) -> Option<(u64, Vec<String>, Vec<String>)> {
    let (ta, tb) = (trace(a), trace(b));
    let k = (0..ta.len().max(tb.len())).find(|&i| match (ta.get(i), tb.get(i)) {
        (Some(x), Some(y)) => !check::same_event(&x.1, &y.1),
        _ => true,
    })?;
    let side = |t: &[(String, nctrans::eval::Event)]| {
        let mut v: Vec<String> = t[k.saturating_sub(3)..(k + 4).min(t.len())].iter().map(|x| x.0.clone()).collect();
        if k >= t.len() {
            v.push("<end of trace>".into());
        }
        v
    };
    Some((k as u64, side(&ta), side(&tb)))
}

/// The old (`-`) and new (`+`) sides of a unified diff.
fn diff_sides(diff: &str) -> (Vec<String>, Vec<String>) {
    let (mut old, mut new) = (Vec::new(), Vec::new());
    for l in diff.lines().filter(|l| !l.starts_with("---") && !l.starts_with("+++") && !l.starts_with("@@")) {
        let (c, rest) = l.split_at(1.min(l.len()));
        match c {
            "-" => old.push(rest.to_string()),
            "+" => new.push(rest.to_string()),
            _ => {
                old.push(rest.to_string());
                new.push(rest.to_string());
            }
        }
    }
    (old, new)
}

/// Checks the pair every way; asserts the same result, and the verdict and diff the
/// whole traces give; returns the result.
fn every_way(a: &(String, bool), b: &(String, bool)) -> String {
    let first = same_every_way(a, b);
    match expected(a, b) {
        None => assert!(first.starts_with("Equivalent"), "{first}"),
        Some((k, old, new)) => {
            assert!(first.starts_with(&format!("{:?}", Verdict::Diverged { index: k })), "{first}");
            let diff = first.split_once('\n').map_or("", |x| x.1);
            let (o, n) = diff_sides(diff.split("Error NC500").next().unwrap_or(""));
            assert_eq!((o, n), (old, new), "{first}");
        }
    }
    first
}

fn same_every_way(a: &(String, bool), b: &(String, bool)) -> String {
    let mut results = Vec::new();
    for fast in [true, false] {
        set_fast_path(fast);
        for one in [true, false] {
            results.push((fast, one, check_text(a, b, one)));
        }
    }
    set_fast_path(true);
    let (_, _, first) = &results[0];
    for (fast, one, r) in &results[1..] {
        assert_eq!(r, first, "fast path {fast}, one thread {one}\nprogram a:\n{}\nprogram b:\n{}", a.0, b.0);
    }
    first.clone()
}

#[test]
fn grid_moves_check_like_events() {
    let mut r = Rng(2024);
    let (mut equal, mut diverged) = (0, 0);
    for i in 0..40 {
        let fanuc = i % 2 == 0;
        // Long enough to cross the checker's batches (1024 events) now and then.
        let n = if i % 5 == 0 { 2100 } else { 40 };
        let base = blocks(&mut r, fanuc, n);
        let mut other = base.clone();
        // Where the second program differs (or does not).
        let at = match i % 8 {
            0 => None,
            1 => Some(1),
            2 => Some(n.min(1023)),
            3 => Some(n.min(1025)),
            4 => Some(n),
            _ => Some(1 + r.below(n as u64) as usize),
        };
        match (at, i % 3) {
            (None, _) => {}
            (Some(k), 0) => other[k] = format!("G1 X{} F800", num(&mut r)),
            (Some(k), 1) => {
                other.remove(k);
            }
            (Some(k), _) => other.insert(k, "G0 Z7.5".to_string()),
        }
        let a = (text(&base, fanuc), fanuc);
        // The same program in the other dialect's spelling is not needed: one dialect
        // compared with itself exercises the compare; both dialects are covered by `i`.
        let b = (text(&other, fanuc), fanuc);
        let res = every_way(&a, &b);
        if res.starts_with("Equivalent") {
            equal += 1;
        } else if res.starts_with("Diverged") {
            diverged += 1;
            assert!(res.contains("NC500"), "{res}");
        }
    }
    assert!(equal >= 5 && diverged >= 20, "equal {equal}, diverged {diverged}");
}

#[test]
fn a_grid_move_within_the_tolerance_of_an_event_agrees() {
    // FANUC `X1.` and Siemens `X1.0000004` (rounded to the grid by the machine: the same
    // position) and a divergence by one thousandth, between the two dialects.
    let a = ("%\nO1\nG21 G90 G1 X1. Y2.5 F300.\nG0 Z5.\nM30\n%\n".to_string(), true);
    let b = ("G71 G90 G1 X1.0000004 Y2.5 F300\nG0 Z5\nM30\n".to_string(), false);
    let same = every_way(&a, &b);
    assert!(same.starts_with(&format!("{:?}", Verdict::Equivalent { events: 3 })), "{same}");
    let c = ("G71 G90 G1 X1.001 Y2.5 F300\nG0 Z5\nM30\n".to_string(), false);
    let diff = every_way(&a, &c);
    assert!(diff.starts_with(&format!("{:?}", Verdict::Diverged { index: 0 })), "{diff}");
    assert!(diff.contains("`move linear X=1 Y=2.5 f=300` vs `move linear X=1.001 Y=2.5 f=300`"), "{diff}");
}

#[test]
fn divergences_at_the_batch_edges_show_their_context() {
    // One move per block: block k (after the first) is event k - 1. The checker gets the
    // second trace in batches of 1024 events: divergences and ends on both sides of the
    // edges between them.
    let mut r = Rng(5);
    for fanuc in [false, true] {
        let base = blocks_of_moves(&mut r, fanuc, 2100);
        for k in [1023usize, 1024, 1025, 2047, 2048, 2049] {
            let a = (text(&base, fanuc), fanuc);
            let mut changed = base.clone();
            changed[k + 1] = "G1 X-999.5 F700".to_string();
            every_way(&a, &(text(&changed, fanuc), fanuc));
            let cut = (text(&base[..k + 1], fanuc), fanuc);
            every_way(&a, &cut);
            every_way(&cut, &a);
        }
    }
    // Moves that differ in the feed only, or in rapid against feed motion.
    for (x, y) in [("G1 X1 F300", "G1 X1 F301"), ("G0 X1", "G1 X1 F300"), ("G1 X1 Y2 F300", "G1 X1 Z2 F300")] {
        let a = (format!("G71 G90\n{x}\nM30\n"), false);
        let b = (format!("G71 G90\n{y}\nM30\n"), false);
        let res = every_way(&a, &b);
        assert!(res.starts_with(&format!("{:?}", Verdict::Diverged { index: 0 })), "{res}");
    }
}

/// A first block and `n` plain moves, each one event.
fn blocks_of_moves(r: &mut Rng, fanuc: bool, n: usize) -> Vec<String> {
    let mut out = vec![if fanuc { "G21 G90 G17 F500." } else { "G71 G90 G17 F500" }.to_string()];
    for _ in 0..n {
        out.push(format!("G1 X{} Y{}", num(r), num(r)));
    }
    out
}
