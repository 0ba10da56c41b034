//! The differential test of the byte-level fast paths (issue 7): every corpus block and
//! generated plain motion blocks (random addresses, signs, decimals, exponents, spacing,
//! comments, block numbers and skips) go through both the fast path and the pest grammar;
//! wherever the fast path takes a block, the IR must be identical. Both dialects.
//!
//! Also: the index-only first scan (`stream::scan_index`, which skips building plain
//! blocks' items) against the full scan on every corpus file, mutated ones and generated
//! programs; the exact decimal reader the fast paths use (`read::decimal`) against `str::parse`
//! on generated literals, and the FANUC builder's direct route for plain word blocks
//! against its general route.
//!
//! `NCTRANS_FAST_BLOCKS` sets how many blocks are generated per dialect (default 20,000,
//! fast enough for `cargo test` in debug); the ignored test runs a million per dialect
//! (`cargo test --release --test fast_path_diff -- --ignored`, run by `bench/stream.sh`).

use nctrans::dialect::fanuc::{
    build_both_ways_for_test, parse_fast_for_test, parse_grammar_for_test, skeleton_both_ways_for_test,
};
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

/// A decimal literal as CAM output and people write it: 1 to 25 digits, leading zeros,
/// the point anywhere (or nowhere), long fractions.
fn literal(r: &mut Rng) -> String {
    let n = 1 + r.below(25) as usize;
    let mut digits: String = (0..n).map(|_| char::from(b'0' + r.below(10) as u8)).collect();
    if r.below(3) == 0 {
        // Runs of zeros: exact powers of ten, values just below or above them.
        let zeros = "0".repeat(r.below(20) as usize);
        digits = format!("{}{zeros}{}", r.below(10), r.below(1000));
    }
    match r.below(4) {
        0 => digits,
        _ => {
            let at = r.below(digits.len() as u64 + 1) as usize;
            format!("{}.{}", &digits[..at], &digits[at..])
        }
    }
}

fn decimals(n: u64) {
    let mut r = Rng(0xD1B5_4A32_D192_ED03);
    for _ in 0..n {
        let s = literal(&mut r);
        let want: f64 = s.parse().expect("a generated literal parses");
        let got = nctrans::read::decimal(&s);
        assert_eq!(got.map(f64::to_bits), Some(want.to_bits()), "literal {s:?}: {got:?} vs {want:?}");
    }
    for s in [
        "0",
        "0.",
        ".0",
        "9007199254740991",
        "9007199254740993",
        "900719925474099.3",
        "123456789012345",
        "1234567890123456",
        "0.1",
        "0.3",
        "2.675",
        "1e5",
        "",
        ".",
        "1.2.3",
        "-1",
        "+1",
        " 1",
        "1_0",
    ] {
        let want = s.parse::<f64>().ok().filter(|_| s.bytes().all(|c| c.is_ascii_digit() || c == b'.'));
        assert_eq!(nctrans::read::decimal(s).map(f64::to_bits), want.map(f64::to_bits), "literal {s:?}");
    }
}

#[test]
fn exact_decimals_agree_with_str_parse() {
    let n = std::env::var("NCTRANS_FAST_BLOCKS").ok().and_then(|v| v.parse().ok()).unwrap_or(20_000u64);
    decimals(n * 10);
}

/// A FANUC block of address words that may mean more than a word: program and sequence
/// numbers, calls, returns, ends, parameter-write mode and comments.
fn fanuc_word_block(r: &mut Rng) -> String {
    let mut s = String::new();
    if r.below(10) == 0 {
        s.push_str("/ ");
    }
    for k in 0..(1 + r.below(6)) {
        let letter = if k == 0 {
            r.pick(&["N", "N", "O", "G", "X", "M"])
        } else {
            r.pick(&["G", "G", "M", "M", "X", "Y", "P", "L", "N", "O", "R", "Q", "H", "F"])
        };
        s.push_str(letter);
        s.push_str(r.pick(&["", "", "", "", "-", "+"]));
        let value = match r.below(4) {
            0 => r.pick(&["10", "11", "50", "65", "66", "67", "2", "30", "98", "99", "0", "100000"]).to_string(),
            // More digits than a whole number is read exactly from (the value decides).
            1 if r.below(4) == 0 => {
                format!("{:016}", r.pick(&["1", "10", "30", "65", "99", "12345"]).parse::<u64>().unwrap_or(0))
            }
            1 => format!("{}.", r.below(100)),
            _ => format!("{}", r.below(100_000)),
        };
        s.push_str(&value);
        s.push_str(r.pick(&["", " "]));
        if r.below(25) == 0 {
            s.push_str("(NOTE)");
        }
    }
    s.trim().to_string()
}

#[test]
fn fanuc_plain_blocks_build_like_the_general_route() {
    let mut r = Rng(0x94D0_49BB_1331_11EB);
    let mut taken = 0;
    let mut skeletons = 0;
    let mut check = |b: &str, taken: &mut usize| {
        // The index-only reader: where it takes a block, the full route agrees.
        if let Some((skeleton, full)) = skeleton_both_ways_for_test(b) {
            assert_eq!(skeleton, full, "FANUC block {b:?} read for the index");
            skeletons += 1;
        }
        for param_mode in [false, true] {
            if let Some((plain, general)) = build_both_ways_for_test(b, param_mode) {
                assert_eq!(plain, general, "FANUC block {b:?} (parameter-write mode {param_mode})");
                *taken += 1;
            }
        }
    };
    for _ in 0..20_000 {
        check(&fanuc_word_block(&mut r), &mut taken);
        check(&block(&mut r, false), &mut taken);
    }
    assert!(taken > 10_000, "the direct route took only {taken} blocks");
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    for top in ["corpus/in/fanuc", "corpus/err/fanuc"] {
        let Ok(rd) = std::fs::read_dir(root.join(top)) else { continue };
        for f in rd.filter_map(|e| e.ok()).map(|e| e.path()) {
            let Ok(bytes) = std::fs::read(&f) else { continue };
            let text = nctrans::read::decode(&bytes, None).text;
            for raw in nctrans::read::blocks(&text) {
                for part in raw.text.split(';') {
                    check(part.trim(), &mut taken);
                }
            }
        }
    }
    assert!(skeletons > 10_000, "the index-only reader took only {skeletons} blocks");
}

/// A line with what a reader of plain lines taken as they are could get wrong: a letter O
/// where normalising reads a zero (`GO1`, `G0O`), full-width characters in code and in
/// comments, `;` ends of blocks (FANUC), vertical tabs and form feeds, `%`, program
/// numbers, a plain block spread over two blocks.
fn tricky_line(r: &mut Rng, siemens: bool) -> String {
    let pieces = [
        "GO1 X1",
        "G0O1 X2",
        "g0o Y3",
        "GO X1.5",
        "G1 O5",
        "N10 O1",
        "Ｇ１ Ｘ２",
        "G1 Ｘ2.5",
        "G1 X1 ;Ｘ注",
        "G1 X1 (Ｘ)",
        "G1 X1;",
        "G1 X1 ;  ",
        "G1 X1;;",
        "G1 X1; G2 Y1",
        "G1 X1;(C)",
        ";",
        "  ;",
        "\x0bG1 X1",
        "G1 X1\x0b",
        "\x0cG1 X1\x0c",
        "G1\tX1\t",
        "%",
        " %",
        "/1 G1 X1",
        "/ G1 X1;",
        "N5",
        "N5;",
        "N5 ;c",
        "X1 ;GO1",
        "G1 X1 (GO1)",
        "O2000",
        "G1 X1 ;",
        "N7 G1 X-.5;  ;",
        "G1 X1\u{3000}Y2",
        "GOTO1",
        "G1 X1.EX3",
        "G1 X1=2",
        "G1 X[1]",
    ];
    let mut s = String::from(r.pick(&pieces));
    if r.below(3) == 0 {
        s.push_str(r.pick(&[" ", "\t", " ;x", " (x)", "Y2", " Y-3.25", "\u{ff11}"]));
    }
    if !siemens && r.below(10) == 0 {
        s = s.replace(';', "(;)");
    }
    if !siemens && s.contains('%') {
        // A FANUC tape mark inside would end the program: everything after it is ignored.
        s = "G1 X9".to_string();
    }
    s
}

/// The index of `bytes` by the full first scan and by the index-only one, as debug text.
fn both_indexes(path: &std::path::Path, bytes: &[u8], chunk_ops: usize) -> (String, String) {
    use nctrans::dialect::{Dialect, ParseOptions};
    use nctrans::stream::{self, lines::Input};
    let dialect = match path.extension().and_then(|e| e.to_str()) {
        Some("mpf" | "spf") => Dialect::Sinumerik,
        _ => Dialect::Fanuc,
    };
    let opts = ParseOptions::for_dialect(dialect);
    let input = || Input::Mem(std::io::Cursor::new(bytes.to_vec()));
    let size = bytes.len() as u64;
    let full = stream::scan(input(), size, path, 0, dialect, &opts, chunk_ops, &mut |_, _| {}, None);
    let index = stream::scan_index(input(), size, path, 0, dialect, &opts, chunk_ops, None);
    (format!("{full:?}"), format!("{index:?}"))
}

#[test]
fn the_index_only_scan_gives_the_full_scans_index() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let mut files: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    for top in ["corpus/in", "corpus/err"] {
        for d in ["sinumerik", "fanuc"] {
            let Ok(rd) = std::fs::read_dir(root.join(top).join(d)) else { continue };
            for f in rd.filter_map(|e| e.ok()).map(|e| e.path()) {
                if let Ok(b) = std::fs::read(&f) {
                    files.push((f, b));
                }
            }
        }
    }
    files.sort();
    // Mutations: blocks cut, characters replaced, parts repeated (PROC after code, labels
    // and N numbers twice, structures left open, …).
    let nasty = b"()[]#=;:/%\r\n\t -+*.,0123456789ENOGXRIFDWHLPAB_";
    let mut r = Rng(0x2545_F491_4F6C_DD1D);
    let base = files.clone();
    for (f, b) in &base {
        for k in 0..4 {
            let mut m = b.clone();
            match k % 3 {
                0 => m.truncate(r.below(m.len() as u64 + 1) as usize),
                1 => {
                    for _ in 0..3 {
                        if !m.is_empty() {
                            let i = r.below(m.len() as u64) as usize;
                            m[i] = nasty[r.below(nasty.len() as u64) as usize];
                        }
                    }
                }
                _ => {
                    let i = r.below(m.len() as u64 + 1) as usize;
                    let piece: Vec<u8> = m[i..].iter().take(300).copied().collect();
                    m.splice(i..i, piece);
                }
            }
            files.push((f.clone(), m));
        }
    }
    // Generated programs of plain blocks with comments, numbers and a PROC or title, and
    // lines the index-only scan must not read as they are (it reads plain lines without
    // normalising them): letter O for zero, full-width characters, `;` block ends, odd
    // blanks, tape marks.
    for siemens in [true, false] {
        let mut text = String::from(if siemens { "; title\nPROC P1\n" } else { "%\n(TITLE)\nO1000\n" });
        for _ in 0..3000 {
            if r.below(4) == 0 {
                text.push_str(&tricky_line(&mut r, siemens));
            } else {
                text.push_str(&block(&mut r, siemens));
            }
            text.push('\n');
        }
        text.push_str(if siemens { "M30\nPROC Q\n" } else { "M30\n%\n" });
        files.push((PathBuf::from(if siemens { "gen.mpf" } else { "gen.nc" }), text.into_bytes()));
    }
    let mut compared = 0;
    for (f, b) in &files {
        for chunk in [1, 3, 4096] {
            let (full, index) = both_indexes(f, b, chunk);
            assert_eq!(full, index, "{} (chunks of {chunk})", f.display());
            compared += 1;
        }
    }
    assert!(compared > 1000, "only {compared} scans compared");
}
