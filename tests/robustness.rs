//! Robustness: truncations, byte flips and random splices of every corpus file must never
//! panic or hang the reader and parsers, and every diagnostic must render (its labels lie
//! inside the file). `NCTRANS_FUZZ_ROUNDS` raises the number of mutations per file.

use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::span::SourceDb;
use nctrans::{diag, ir};
use std::path::PathBuf;
use std::sync::mpsc;
use std::time::Duration;

#[path = "support/rng.rs"]
mod rng;
use rng::Rng;

fn corpus_files() -> Vec<(PathBuf, Dialect)> {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let mut v = Vec::new();
    for kind in ["in", "err"] {
        for d in [Dialect::Sinumerik, Dialect::Fanuc] {
            let dir = root.join("corpus").join(kind).join(d.name());
            if let Ok(rd) = std::fs::read_dir(&dir) {
                let mut files: Vec<PathBuf> = rd.filter_map(|e| e.ok()).map(|e| e.path()).collect();
                files.sort();
                v.extend(files.into_iter().map(|p| (p, d)));
            }
        }
    }
    v
}

/// Bytes that tend to break grammars: delimiters, operators, keywords' letters, line ends,
/// a multi-byte character cut in half, NUL.
const NASTY: &[u8] = b"()[]#=;:/%\"'\r\n\t -+*.,0123456789ENOGXRIFDWHLPAB_$\xEF\xBC\x00\xFF";

fn mutate(rng: &mut Rng, base: &[u8], other: &[u8]) -> Vec<u8> {
    let mut b = base.to_vec();
    match rng.index(4) {
        0 => b.truncate(rng.index(b.len() + 1)),
        1 => {
            for _ in 0..1 + rng.index(4) {
                if !b.is_empty() {
                    let i = rng.index(b.len());
                    b[i] = NASTY[rng.index(NASTY.len())];
                }
            }
        }
        2 => {
            let at = rng.index(b.len() + 1);
            let lo = rng.index(other.len() + 1);
            let hi = (lo + rng.index(200)).min(other.len());
            b.splice(at..at, other[lo..hi].iter().copied());
        }
        _ => {
            // Repeat a slice many times: deep nesting and long lines.
            let lo = rng.index(b.len() + 1);
            let hi = (lo + 1 + rng.index(8)).min(b.len());
            let piece = b[lo..hi].to_vec();
            for _ in 0..rng.index(300) {
                b.splice(lo..lo, piece.iter().copied());
            }
        }
    }
    b
}

fn check_one(bytes: &[u8], dialect: Dialect) -> Result<(), String> {
    let mut db = SourceDb::new();
    let loaded = nctrans::load(&mut db, "mutant", bytes, None);
    let parsed = nctrans::parse(&db, loaded.file, dialect, &ParseOptions::for_dialect(dialect));
    let len = db.get(loaded.file).text.len() as u32;
    for d in &parsed.diags {
        for l in &d.labels {
            if l.span.hi > len || l.span.lo > l.span.hi {
                return Err(format!("label {:?} outside the file (len {len}) in {}", l.span, d.message));
            }
        }
    }
    let _ = diag::render(&db, &parsed.diags);
    if !diag::has_errors(&parsed.diags) {
        let problems = ir::visit::check_spans(&parsed.unit, len);
        if !problems.is_empty() {
            return Err(format!("accepted with bad spans: {problems:?}"));
        }
    }
    Ok(())
}

#[test]
fn mutated_corpus_never_panics_or_hangs() {
    let rounds: usize = std::env::var("NCTRANS_FUZZ_ROUNDS").ok().and_then(|s| s.parse().ok()).unwrap_or(24);
    let files = corpus_files();
    let contents: Vec<Vec<u8>> = files.iter().map(|(p, _)| std::fs::read(p).unwrap_or_default()).collect();
    let (tx, rx) = mpsc::channel::<Result<String, String>>();
    let total = files.len() * rounds;
    std::thread::spawn(move || {
        let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
        for (i, (path, dialect)) in files.iter().enumerate() {
            for round in 0..rounds {
                let other = &contents[rng.index(contents.len())];
                let bytes = mutate(&mut rng, &contents[i], other);
                let case = format!("{} round {round}", path.display());
                let outcome = std::panic::catch_unwind(|| check_one(&bytes, *dialect));
                let msg = match outcome {
                    Ok(Ok(())) => Ok(case),
                    Ok(Err(e)) => Err(format!("{case}: {e}\ninput: {:?}", String::from_utf8_lossy(&bytes))),
                    Err(_) => Err(format!("{case}: panicked\ninput: {:?}", String::from_utf8_lossy(&bytes))),
                };
                if tx.send(msg).is_err() {
                    return;
                }
            }
        }
    });
    let mut failures = Vec::new();
    for _ in 0..total {
        // Generous per-case limit: a hang shows up as silence, not as a slow case.
        match rx.recv_timeout(Duration::from_secs(30)) {
            Ok(Ok(_)) => {}
            Ok(Err(e)) => failures.push(e),
            Err(_) => panic!("a mutated program hung the parser (no answer in 30 s)"),
        }
    }
    assert!(failures.is_empty(), "{} of {total} mutants failed:\n{}", failures.len(), failures.join("\n\n"));
}
