//! The differential test of the index-only first scan read straight from the buffer
//! (issue 7): `skeleton_bytes` of both dialects against the reader they stand for
//! (`Reader::scan_plain`'s `skeleton_raw`) on every corpus line and generated lines
//! (plain CAM lines and near misses: `N1.`, `X1=`, `GO1`, `1EX3`, 16 and more digits,
//! letters L/N/O/P, tabs, form feeds, comments, controls, non-ASCII, every line end), and
//! `stream::scan_index` against `stream::scan_index_general` (every line the general way)
//! on every corpus file and generated files (the external programs get both checks in the
//! `external` test target) (lines across buffer refills, CR LF cut by a
//! refill, macro parts among CAM lines, small and large chunks).
//!
//! `NCTRANS_SKELETON_LINES` sets how many lines are generated per dialect (default
//! 100,000); the ignored test runs a million per dialect
//! (`cargo test --release --test skeleton_diff -- --ignored`).

#[path = "support/rng.rs"]
mod rng;
#[path = "support/skeleton.rs"]
mod skeleton;

use nctrans::dialect::Dialect;
use rng::Rng;
use skeleton::{both_indexes, compare, dialect_of, AFTER};
use std::path::PathBuf;

/// A number as CAM output and hand-written code spell them, and near misses.
fn number(r: &mut Rng) -> String {
    fn digits(r: &mut Rng, lo: u64, spread: u64) -> String {
        let n = lo + r.below(spread);
        (0..n).map(|_| char::from(b'0' + r.below(10) as u8)).collect()
    }
    match r.below(12) {
        0 => digits(r, 1, 4),
        1 => format!("{}.", digits(r, 1, 4)),
        2 => {
            let a = digits(r, 1, 3);
            format!("{a}.{}", digits(r, 0, 5))
        }
        3 => format!(".{}", digits(r, 1, 4)),
        4 => digits(r, 13, 5),
        5 => {
            let a = digits(r, 1, 8);
            format!("{a}.{}", digits(r, 5, 10))
        }
        6 => r.pick(&["", ".", "..", "1..2", "1.2.3"]).to_string(),
        7 => {
            let a = digits(r, 1, 2);
            format!("{a}EX{}", r.pick(&["3", "-2", "", "X"]))
        }
        8 => {
            let a = digits(r, 1, 2);
            format!("{a}E{}", digits(r, 1, 1))
        }
        9 => r.pick(&["10", "65", "66", "67", "2", "30", "98", "99", "0065", "0000000000000065", "17"]).to_string(),
        _ => {
            let a = digits(r, 1, 1);
            format!("{a}.{}", digits(r, 4, 1))
        }
    }
}

const LETTERS: &[&str] = &[
    "G", "X", "Y", "Z", "F", "S", "T", "M", "I", "J", "K", "A", "B", "C", "E", "D", "H", "R", "U", "V", "W", "Q", "L",
    "N", "O", "P", "g", "x", "n", "e",
];

/// One generated line (without its line end); `siemens` picks the comment forms.
fn line(r: &mut Rng, siemens: bool) -> String {
    let mut s = String::new();
    if r.chance(10) {
        s.push_str(r.pick(&[" ", "\t", "  ", "\x0c", " \t"]));
    }
    if r.chance(5) {
        s.push_str(r.pick(&["/", "/2 ", "/ ", "%"]));
    }
    if r.chance(30) {
        let n = r.below(12) + u64::from(r.chance(20));
        let digits: String = (0..n).map(|_| char::from(b'0' + r.below(10) as u8)).collect();
        s.push_str(r.pick(&["N", "n", "N ", "N"]));
        s.push_str(&digits);
        s.push_str(r.pick(&[" ", " ", "", ".", "=1", "\t", ";x", "G1"]));
    }
    let words = r.below(7);
    for k in 0..words {
        s.push_str(r.pick(LETTERS));
        if !siemens && r.chance(5) {
            s.push(' ');
        }
        if r.chance(30) {
            s.push_str(r.pick(&["-", "+", "-", "- ", "--"]));
        }
        s.push_str(&number(r));
        if r.chance(3) {
            s.push_str(r.pick(&["=", "=2", "[1]", "(x)", " =3", " [", ":", "'", "\u{3000}", "\u{ff11}", "O", "#1"]));
        }
        if k + 1 < words || r.chance(10) {
            s.push_str(r.pick(&[" ", " ", " ", "", "\t", "  ", "\x0c", " \x1a"]));
        }
    }
    if r.chance(15) {
        let comment = r.pick(&["", "x", " tool 1", " é", " 注释", "\x01", "\x7f", "\t\x0c\x1a", "(;)", ";", " ; "]);
        if siemens || r.chance(50) {
            s.push(';');
            s.push_str(comment);
        } else {
            s.push_str(&format!("({comment})"));
        }
    }
    if r.chance(3) {
        // Blanks or `;` after the block (FANUC end-of-block marks).
        s.push_str(r.pick(&[" ", ";", " ;", ";;", "; ", "\t"]));
    }
    if r.chance(2) {
        s = r
            .pick(&[
                "",
                " ",
                "\t",
                "GOTOB LAB1",
                "LAB1:",
                "IF R1>2",
                "WHILE [#1 LT 3] DO1",
                "END1",
                "#1=#1+1",
                "M30",
                "M99",
                "M02",
                "G65 P9010",
                "O1000",
                "GO1 X1",
                "G1 XO.5",
                "X1.EX3",
                "R1=5",
            ])
            .to_string();
    }
    s
}

fn corpus_files() -> Vec<PathBuf> {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let mut dirs = vec![
        root.join("corpus/in/sinumerik"),
        root.join("corpus/in/fanuc"),
        root.join("corpus/err/sinumerik"),
        root.join("corpus/err/fanuc"),
    ];
    let mut files = Vec::new();
    while let Some(d) = dirs.pop() {
        let Ok(rd) = std::fs::read_dir(&d) else { continue };
        for p in rd.filter_map(|e| e.ok()).map(|e| e.path()) {
            if p.is_dir() {
                dirs.push(p);
            } else if dialect_of(&p).is_some() {
                files.push(p);
            }
        }
    }
    files.sort();
    files
}

#[test]
fn every_corpus_line_agrees() {
    let mut lines = 0;
    let mut taken = 0;
    for f in corpus_files() {
        let Ok(bytes) = std::fs::read(&f) else { continue };
        let text = String::from_utf8_lossy(&bytes);
        let siemens = dialect_of(&f) == Some(Dialect::Sinumerik);
        for l in text.split(['\n', '\r']) {
            compare(l, siemens, &mut taken);
            lines += 1;
        }
    }
    assert!(lines > 2000, "only {lines} corpus lines");
    println!("{lines} corpus lines, taken {taken} times");
    assert!(taken > 1000, "only {taken} corpus lines taken");
}

/// Where the automaton stops (a line end, a comment, a declined byte, an N, G or M word)
/// at every place in the eight bytes it steps at once without a test, and in the bytes
/// after the last eight: blanks of every count move it along.
#[test]
fn stops_at_every_place_in_eight_bytes_agree() {
    let mut taken = 0;
    for siemens in [true, false] {
        for pad in 0..20 {
            for word in ["X1", "X-1.5", "Y.25", "F800.", "Z12345678901234"] {
                for stop in ["", " ", ";C", " ; c", "#", "=", " G1", "G2", " m3", "N5", " X2", "  ", "\t", "X", "."] {
                    let text = format!("G1{}{word}{stop}", " ".repeat(pad));
                    compare(&text, siemens, &mut taken);
                }
            }
        }
    }
    assert!(taken > 2000, "only {taken} lines taken");
}

/// G and M words whose values are near those the fast reader declines (G10, G65-G67, M2,
/// M30, M98, M99), as the line's first word and after others, followed by every kind of
/// byte: FANUC's `skeleton_bytes` reads G and M words of one or two digits on the spot.
#[test]
fn g_and_m_values_near_the_limits_agree() {
    let values = [
        "0",
        "1",
        "2",
        "3",
        "9",
        "00",
        "01",
        "02",
        "03",
        "09",
        "10",
        "11",
        "29",
        "30",
        "31",
        "64",
        "65",
        "66",
        "67",
        "68",
        "97",
        "98",
        "99",
        "100",
        "010",
        "065",
        "002",
        "0030",
        "1.",
        "2.",
        "10.",
        ".5",
        "-2",
        "+10",
        "- 65",
        " 2",
        "0000000000000002",
        "000000000000002",
    ];
    let afters =
        ["", " ", "  ", "\t", "\x0c", ";", " ;", "X1", "x1", "G1", "M3", "O1", "=", ".", "..", "5", "(", "/", "#"];
    let befores = ["", " ", "N10 ", "G1 ", "X1 ", "X1", "G90 G1 ", "N1 M3 "];
    let mut taken = 0;
    for siemens in [false, true] {
        for letter in ["G", "M", "g", "m", "N"] {
            for v in values {
                for a in afters {
                    for b in befores {
                        compare(&format!("{b}{letter}{v}{a}"), siemens, &mut taken);
                        compare(&format!("{b}{letter}{v}{a} X2 Y3"), siemens, &mut taken);
                    }
                }
            }
        }
    }
    assert!(taken > 10_000, "only {taken} taken");
}

/// Digit runs of every length from 1 to 20 at every position modulo eight (the automaton
/// steps eight bytes at a time), before and after a point, in N, G, M and other words.
#[test]
fn digit_runs_at_every_alignment_agree() {
    let mut taken = 0;
    for siemens in [false, true] {
        for pad in 0..8 {
            for len in 1..=20 {
                let run: String = (0..len).map(|k| char::from(b'0' + ((k * 7 + len) % 10) as u8)).collect();
                for letter in ["X", "G", "M", "N", "F"] {
                    for shape in
                        [run.clone(), format!("{run}."), format!(".{run}"), format!("1.{run}"), format!("{run}.5")]
                    {
                        let blanks = " ".repeat(pad);
                        compare(&format!("{blanks}{letter}{shape}"), siemens, &mut taken);
                        compare(&format!("G1{blanks}{letter}{shape} Y-1"), siemens, &mut taken);
                        compare(&format!("N5 X1{blanks}{letter}-{shape}"), siemens, &mut taken);
                    }
                }
            }
        }
    }
    assert!(taken > 5_000, "only {taken} taken");
}

fn generated_lines(n: u64) {
    for siemens in [true, false] {
        let mut r = Rng(if siemens { 0x9E37_79B9_7F4A_7C15 } else { 0x2545_F491_4F6C_DD1D });
        let mut taken = 0;
        for _ in 0..n {
            compare(&line(&mut r, siemens), siemens, &mut taken);
        }
        // Both sides of the decision are exercised.
        let all = n * (AFTER.len() as u64 - 1);
        assert!(taken > all / 10 && taken < all * 9 / 10, "taken {taken} of {all} (siemens: {siemens})");
    }
}

#[test]
fn generated_lines_agree() {
    let n = std::env::var("NCTRANS_SKELETON_LINES").ok().and_then(|v| v.parse().ok()).unwrap_or(100_000);
    generated_lines(n);
}

#[test]
#[ignore]
fn a_million_generated_lines_agree() {
    generated_lines(1_000_000);
}

#[test]
fn every_corpus_file_has_the_same_index() {
    let mut compared = 0;
    for f in corpus_files() {
        let Ok(bytes) = std::fs::read(&f) else { continue };
        let Some(dialect) = dialect_of(&f) else { continue };
        for chunk in [1, 5, 2048] {
            let (fast, general) = both_indexes(&f, dialect, &bytes, chunk);
            assert_eq!(fast, general, "{} (chunks of {chunk})", f.display());
            compared += 1;
        }
    }
    assert!(compared > 300, "only {compared} scans compared");
}

/// A generated program of about `size` bytes: a header, CAM lines (some near misses) with
/// every line end, and now and then a macro part (labels, loops, jumps, variables).
fn program(r: &mut Rng, siemens: bool, size: usize) -> Vec<u8> {
    let mut text = String::from(if siemens { "; title\n; nctrans: set R1=2\n" } else { "%\nO1000 (TITLE)\n" });
    let macro_part = if siemens {
        ["LAB1:", "R1=R1+1", "IF R1<3 GOTOB LAB1", "WHILE R2<2", "R2=R2+1", "ENDWHILE", "N7 G1 X1 ; n", "DEF REAL QQ"]
    } else {
        ["#1=#1+1", "IF [#1 LT 3] GOTO 7", "WHILE [#2 LT 2] DO1", "#2=#2+1", "END1", "N7 G1 X1.", "(NOTE)", "G65 P9 A1"]
    };
    let mut n = 10;
    while text.len() < size {
        if r.chance(2) {
            let k = r.index(macro_part.len());
            text.push_str(macro_part[k]);
        } else if r.chance(90) {
            // A CAM line, numbered or not.
            if r.chance(50) {
                text.push_str(&format!("N{n} "));
                n += 10;
            }
            let cut = r.below(3) as usize;
            let words = ["G1", "X0.1394", "Y-0.4750", "Z-0.0225", "F800."];
            text.push_str(&words[cut..].join(" "));
            if r.chance(10) {
                text.push_str(if siemens { " ; cut" } else { " (cut)" });
            }
        } else {
            text.push_str(&line(r, siemens));
        }
        text.push_str(r.pick(&["\n", "\n", "\n", "\r\n", "\r"]));
    }
    text.push_str(if siemens { "M30\n" } else { "M30\n%\n" });
    text.into_bytes()
}

#[test]
fn generated_files_have_the_same_index() {
    let mut r = Rng(0xD1B5_4A32_D192_ED03);
    for siemens in [true, false] {
        let dialect = if siemens { Dialect::Sinumerik } else { Dialect::Fanuc };
        let path = PathBuf::from(if siemens { "gen.mpf" } else { "gen.nc" });
        for k in 0..6 {
            // Sizes across the 256 KiB refills (a CR LF cut by one now and then), a BOM.
            let mut bytes = program(&mut r, siemens, 4_000 + k * 150_000);
            if k == 2 {
                bytes.splice(0..0, *b"\xEF\xBB\xBF");
            }
            for chunk in [1, 64, 2048] {
                let (fast, general) = both_indexes(&path, dialect, &bytes, chunk);
                assert_eq!(fast, general, "{} of {} bytes (chunks of {chunk})", path.display(), bytes.len());
            }
        }
        // A CR as the last byte of the first buffer (256 KiB), then an LF or another line.
        const FIRST: usize = 256 * 1024;
        for end in ["\r\n", "\rG1 X2\n", "\r\r\n"] {
            let mut bytes = program(&mut r, siemens, FIRST - 100);
            let keep = bytes[..FIRST - 200].iter().rposition(|&c| c == b'\n').map_or(0, |i| i + 1);
            bytes.truncate(keep);
            bytes.extend_from_slice(b"G1 X1");
            bytes.resize(FIRST - 1, b' ');
            bytes.extend_from_slice(end.as_bytes());
            bytes.extend_from_slice(&program(&mut r, siemens, 2000));
            assert_eq!(bytes[FIRST - 1], b'\r');
            let (fast, general) = both_indexes(&path, dialect, &bytes, 2048);
            assert_eq!(fast, general, "a CR at the end of the first buffer, then {end:?}");
        }
    }
}
