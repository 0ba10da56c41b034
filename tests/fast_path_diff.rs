//! The differential test of the byte-level fast paths (issue 7): every corpus block and
//! generated plain motion blocks (random addresses, signs, decimals, exponents, spacing,
//! comments, block numbers and skips) go through both the fast path and the pest grammar;
//! wherever the fast path takes a block, the IR must be identical. Both dialects.
//!
//! `NCTRANS_FAST_BLOCKS` sets how many blocks are generated per dialect (default 20,000,
//! fast enough for `cargo test` in debug); the ignored test runs a million per dialect
//! (`cargo test --release --test fast_path_diff -- --ignored`, run by `bench/stream.sh`).

use nctrans::dialect::fanuc::{parse_fast_for_test, parse_grammar_for_test};
use nctrans::dialect::sinumerik::{block_via_fast_path, block_via_grammar};
use std::path::PathBuf;

struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
    fn pick<'a>(&mut self, v: &[&'a str]) -> &'a str {
        v[self.below(v.len() as u64) as usize]
    }
}

fn number(r: &mut Rng, siemens: bool) -> String {
    let int = r.below(100_000);
    let mut s = match r.below(8) {
        0 => format!("{int}"),
        1 => format!("{int}."),
        2 => format!("{int}.{}", r.below(1000)),
        3 => format!(".{}", r.below(1000) + 1),
        4 => format!("{:05}", r.below(100)),
        5 => format!("{}.{:04}", r.below(10), r.below(10000)),
        6 => format!("{}.{:015}", r.below(10), r.below(1 << 40)),
        _ => format!("{int}.{:03}", r.below(1000)),
    };
    // Siemens writes exponents as `EX` (the fast path declines them; the grammar reads them).
    if siemens && r.below(40) == 0 {
        s.push_str(&format!("EX{}{}", r.pick(&["", "-", "+"]), r.below(12)));
    }
    s
}

/// One generated block; `siemens` picks the comment form.
fn block(r: &mut Rng, siemens: bool) -> String {
    let mut s = String::new();
    let sep = |r: &mut Rng| r.pick(&["", " ", " ", "\t", "  ", " \t"]);
    s.push_str(r.pick(&["", "", "", " ", "\t"]));
    if r.below(12) == 0 {
        s.push('/');
        if r.below(2) == 0 {
            s.push_str(&r.below(10).to_string());
        }
        s.push(' ');
    }
    if r.below(2) == 0 {
        s.push_str(&format!("{}{}", r.pick(&["N", "N", "n"]), r.below(99_999) + 1));
        s.push_str(sep(r));
    }
    let letters: &[&str] = if siemens {
        &["G", "X", "Y", "Z", "F", "S", "M", "T", "D", "I", "J", "K", "A", "B", "C", "E", "H", "U", "V", "W"]
    } else {
        &["G", "X", "Y", "Z", "F", "S", "M", "T", "D", "I", "J", "K", "R", "A", "B", "C", "E", "H", "P", "Q"]
    };
    for _ in 0..(1 + r.below(7)) {
        let l = r.pick(letters);
        s.push_str(&if r.below(8) == 0 { l.to_ascii_lowercase() } else { l.to_string() });
        if !siemens && r.below(10) == 0 {
            s.push(' ');
        }
        s.push_str(r.pick(&["", "", "", "-", "-", "+"]));
        s.push_str(&number(r, siemens));
        s.push_str(sep(r));
    }
    if r.below(5) == 0 {
        if siemens {
            s.push_str(r.pick(&[";", "; finish pass", " ;注释 X1", ";(G1)"]));
        } else {
            s.push_str(r.pick(&["(FINISH)", " (注释 X1)", "()"]));
        }
    }
    s
}

fn sinumerik_same(b: &str) -> bool {
    match block_via_fast_path(b) {
        Some(fast) => {
            assert_eq!(Some(&fast), block_via_grammar(b).as_ref(), "Sinumerik block {b:?}");
            true
        }
        None => false,
    }
}

fn fanuc_same(b: &str) -> bool {
    match parse_fast_for_test(b) {
        Some(fast) => {
            assert_eq!(Ok(&fast), parse_grammar_for_test(b).as_ref(), "FANUC block {b:?}");
            true
        }
        None => false,
    }
}

fn generated(n: u64) {
    for (siemens, seed) in [(true, 0x2545_F491_4F6C_DD1D), (false, 0x9E37_79B9_7F4A_7C15)] {
        let mut r = Rng(seed);
        let mut taken = 0u64;
        for _ in 0..n {
            let b = block(&mut r, siemens);
            taken += u64::from(if siemens { sinumerik_same(&b) } else { fanuc_same(&b) });
        }
        // Most generated blocks are plain motion: the fast path must take them.
        assert!(taken * 2 > n, "{} fast path took only {taken} of {n}", if siemens { "Sinumerik" } else { "FANUC" });
    }
}

#[test]
fn generated_blocks_agree() {
    let n = std::env::var("NCTRANS_FAST_BLOCKS").ok().and_then(|v| v.parse().ok()).unwrap_or(20_000);
    generated(n);
}

#[test]
#[ignore = "a million blocks per dialect: run in release (bench/stream.sh)"]
fn a_million_generated_blocks_agree() {
    generated(1_000_000);
}

#[test]
fn every_corpus_block_agrees() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let mut taken = 0;
    for top in ["corpus/in", "corpus/err"] {
        for d in ["sinumerik", "fanuc"] {
            let Ok(rd) = std::fs::read_dir(root.join(top).join(d)) else { continue };
            for f in rd.filter_map(|e| e.ok()).map(|e| e.path()) {
                let Ok(bytes) = std::fs::read(&f) else { continue };
                let text = nctrans::read::decode(&bytes, None).text;
                for raw in nctrans::read::blocks(&text) {
                    if d == "sinumerik" {
                        taken += usize::from(sinumerik_same(raw.text));
                    } else {
                        // FANUC blocks end at `;` too.
                        for part in raw.text.split(';') {
                            taken += usize::from(fanuc_same(part.trim()));
                        }
                    }
                }
            }
        }
    }
    assert!(taken > 500, "the fast path took only {taken} corpus blocks");
}
