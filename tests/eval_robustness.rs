//! Robustness of the evaluator: mutated copies of every corpus program (byte flips,
//! inserted digits and operators, duplicated lines) that still parse must run without a
//! panic and end within the step limit, and every evaluator diagnostic must render.
//! `NCTRANS_FUZZ_ROUNDS` raises the number of mutations per file.

mod eval_support;

use eval_support::root;
use nctrans::dialect::ParseOptions;
use nctrans::eval::{self, NoCallees, NullSink, RunOptions};
use nctrans::span::SourceDb;

#[path = "support/rng.rs"]
mod rng;
use rng::Rng;

const ALPHABET: &[u8] = b"0123456789.-+*/#[]()=XYZGMRIJKPLF \n";

fn mutate(rng: &mut Rng, text: &[u8]) -> Vec<u8> {
    let mut b = text.to_vec();
    for _ in 0..1 + rng.index(4) {
        if b.is_empty() {
            break;
        }
        let i = rng.index(b.len());
        match rng.index(4) {
            0 => {
                b.remove(i);
            }
            1 => b.insert(i, ALPHABET[rng.index(ALPHABET.len())]),
            2 => b[i] = ALPHABET[rng.index(ALPHABET.len())],
            _ => {
                let lines: Vec<&[u8]> = b.split(|c| *c == b'\n').collect();
                let j = rng.index(lines.len());
                let mut out: Vec<u8> = Vec::new();
                for (k, l) in lines.iter().enumerate() {
                    out.extend_from_slice(l);
                    out.push(b'\n');
                    if k == j {
                        out.extend_from_slice(l);
                        out.push(b'\n');
                    }
                }
                b = out;
            }
        }
    }
    b
}

#[test]
fn mutated_corpus_programs_run_without_panics() {
    let rounds: usize = std::env::var("NCTRANS_FUZZ_ROUNDS").ok().and_then(|s| s.parse().ok()).unwrap_or(8);
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let mut ran = 0;
    for d in ["fanuc", "sinumerik"] {
        let Ok(rd) = std::fs::read_dir(root().join("corpus/in").join(d)) else { continue };
        let mut files: Vec<_> = rd.filter_map(|e| e.ok()).map(|e| e.path()).collect();
        files.sort();
        for f in files {
            let text = std::fs::read(&f).expect("readable");
            for round in 0..rounds {
                let bytes = mutate(&mut rng, &text);
                let mut db = SourceDb::new();
                let name = format!("{}#{round}", f.display());
                let loaded = nctrans::load(&mut db, &name, &bytes, None);
                let dialect = nctrans::detect_dialect(&f.to_string_lossy(), &db.get(loaded.file).text);
                let parsed = nctrans::parse(&db, loaded.file, dialect, &ParseOptions::for_dialect(dialect));
                if nctrans::diag::has_errors(&parsed.diags) {
                    continue;
                }
                let opts = RunOptions { max_steps: 20_000, ..Default::default() };
                let out = eval::run(&mut db, &parsed.unit, &mut NoCallees, &opts, &mut NullSink);
                assert!(out.steps <= 20_000, "{name}: {} steps", out.steps);
                // Every diagnostic renders (its labels lie inside a known file).
                let rendered = nctrans::diag::render(&db, &out.diags);
                assert!(out.diags.is_empty() || !rendered.is_empty(), "{name}");
                for d in &out.diags {
                    for l in &d.labels {
                        assert!(l.file < db.len(), "{name}: label in unknown file: {}", d.message);
                        assert!(l.span.hi as usize <= db.get(l.file).text.len(), "{name}: span outside: {}", d.message);
                    }
                }
                ran += 1;
            }
        }
    }
    assert!(ran > 100, "only {ran} mutated programs parsed");
}
