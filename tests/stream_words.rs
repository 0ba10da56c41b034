//! The streamed translators' first scan (`stream::scan_words`) against the whole-file reader
//! and the index-only scan: on every corpus file and generated
//! programs (plain motion with numbers, comments, skips, program ends, blank and non-ASCII
//! lines, macro lines in between), it builds the same index and diagnostics as
//! `scan_index`, and what it hands out, plain lines as words and the rest as statements,
//! is line for line what `scan` (the whole-file reader) hands out. The external programs
//! get the same check in the `external` test target.

#[path = "support/rng.rs"]
mod rng;
#[path = "support/words_scan.rs"]
mod words_scan;

use nctrans::dialect::Dialect;
use rng::Rng;
use std::path::PathBuf;
use words_scan::{check, files, same_as_whole_parse};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn corpus_programs_scan_the_same_with_words() {
    let (mut words, mut n, mut whole) = (0, 0, 0);
    for (dir, d) in [("corpus/in/sinumerik", Dialect::Sinumerik), ("corpus/in/fanuc", Dialect::Fanuc)] {
        for f in files(&root().join(dir)) {
            words += check(&f, d);
            whole += usize::from(same_as_whole_parse(&f, d));
            n += 1;
        }
    }
    assert!(n > 150 && words > 200 && whole > 100, "{n} files, {words} lines as words, {whole} compared whole");
}

/// A program of mostly plain lines with everything around them that a reader may treat
/// differently.
fn generated(d: Dialect, seed: u64, lines: usize) -> String {
    let mut r = Rng(seed);
    let mut out = String::new();
    match d {
        Dialect::Sinumerik => out.push_str("%_N_GEN_MPF\n; head\n"),
        Dialect::Fanuc => out.push_str("%\nO1234 (GEN)\n"),
    }
    let letters = b"XYZFSGMABCIJKRDTHUVW";
    for i in 0..lines {
        let mut l = String::new();
        if r.chance(20) {
            l.push_str(&format!("N{} ", 1 + r.below(200) * 10));
        }
        if d == Dialect::Fanuc && r.chance(5) {
            l.insert_str(0, if r.chance(50) { "/" } else { "/2 " });
        }
        for _ in 0..r.below(6) {
            let c = letters[r.index(letters.len())] as char;
            let sign = if r.chance(30) { "-" } else { "" };
            let v = match r.below(4) {
                0 => format!("{}", r.below(100)),
                1 => format!("{}.{}", r.below(1000), r.below(10_000)),
                2 => format!("{}.", r.below(1000)),
                _ => format!(".{}", r.below(100)),
            };
            let sep = if r.chance(20) { "" } else { " " };
            l.push_str(&format!("{c}{sign}{v}{sep}"));
        }
        match r.below(40) {
            0 if d == Dialect::Sinumerik => l.push_str("; a comment ; two"),
            1 if d == Dialect::Sinumerik => l.push_str(";Ümlaut"),
            2 => l.push_str("M30"),
            3 => l.clear(),
            4 => l = if d == Dialect::Sinumerik { "R1=R1+1".into() } else { "#1=#1+1".into() },
            5 if d == Dialect::Fanuc => l.push_str("(COMMENT)"),
            6 if d == Dialect::Fanuc => l.push(';'),
            7 => l = "   ".into(),
            8 => l.push_str("GO1"),
            _ => {}
        }
        if i % 97 == 0 {
            l.push('\r');
        }
        out.push_str(&l);
        out.push('\n');
    }
    if d == Dialect::Fanuc {
        out.push_str("M30\n%\n");
    }
    out
}

#[test]
fn generated_programs_scan_the_same_with_words() {
    let dir = root().join("target/stream-words-tests");
    std::fs::create_dir_all(&dir).expect("dir");
    let mut words = 0;
    for seed in 1..=12u64 {
        for d in [Dialect::Sinumerik, Dialect::Fanuc] {
            let path = dir.join(format!("gen{seed}.{}", if d == Dialect::Fanuc { "nc" } else { "mpf" }));
            std::fs::write(&path, generated(d, seed, 3000)).expect("write");
            words += check(&path, d);
        }
    }
    assert!(words > 20_000, "{words} lines as words");
}

/// A CAM line of the shape the quick readers take (`N10 G1 X1.5 Y-2. F800`), now and then
/// just off it (a letter a dialect judges, two blanks, a trailing blank, a comment, a long
/// number, lower case).
fn cam_line(d: Dialect, r: &mut Rng) -> String {
    let mut l = String::new();
    if r.chance(4) {
        l.push_str(&format!("N{} ", r.below(100_001)));
    }
    let letters: &[u8] = if r.chance(30) { b"XYZFGMNOLPEx" } else { b"XYZFGIJKAB" };
    for k in 0..1 + r.below(6) {
        if k > 0 {
            l.push_str(if r.chance(60) { "  " } else { " " });
        }
        let c = letters[r.index(letters.len())] as char;
        let sign = ["", "", "", "-", "+"][r.index(5)];
        let v = match r.below(6) {
            0 => format!("{}", r.below(100)),
            1 => format!("{}.{}", r.below(1000), r.below(10_000)),
            2 => format!("{}.", r.below(100_000)),
            3 => format!(".{:03}", r.below(1000)),
            4 => format!("{}.{:07}", r.below(10_000_000), r.below(10_000_000)),
            _ => ["10", "65", "0", "00", "1", "3", "66.", "99999999", "0.0", "12345678.1"][r.index(10)].to_string(),
        };
        l.push_str(&format!("{c}{sign}{v}"));
    }
    match r.below(60) {
        0 => l.push(' '),
        1 if d == Dialect::Sinumerik => l.push_str(" ; cut"),
        2 if d == Dialect::Fanuc => l.push_str(" (CUT)"),
        3 => l.insert(0, ' '),
        4 => l.push_str("M30"),
        _ => {}
    }
    l
}

/// A CAM program of about `bytes` bytes with mixed line ends; `tail` goes at text offset
/// `at` (the first refill of the 256 KiB read buffer is there: a line across it, a CR LF
/// split by it, a lone CR just before it) and the file ends with or without a line end.
fn cam_program(d: Dialect, seed: u64, at: usize, tail: &str, end: &str) -> String {
    let mut r = Rng(seed);
    let mut out = String::from(if d == Dialect::Sinumerik { "%_N_CAM_MPF\n; head\n" } else { "%\nO1234 (CAM)\n" });
    let eol = |r: &mut Rng| ["\n", "\n", "\n", "\r\n", "\r"][r.index(5)];
    while out.len() < at {
        let l = cam_line(d, &mut r);
        out.push_str(&l);
        out.push_str(eol(&mut r));
    }
    // Back to a line start before `at`, then a filler line so that `tail` starts at `at`.
    while out.len() > at - 60 {
        let cut = out[..out.len() - 1].rfind(['\n', '\r']).map_or(0, |i| i + 1);
        out.truncate(cut);
    }
    let n = at - out.len() - 1;
    let mut fill = String::new();
    while n - fill.len() > 9 {
        fill.push_str("Y12345 ");
    }
    let rest = n - fill.len();
    fill.push_str(&"X1.234567"[..rest]);
    if rest < 9 {
        fill.replace_range(fill.len() - rest.., &format!("X{}", "1".repeat(rest - 1)));
    }
    out.push_str(&fill);
    out.push('\n');
    out.push_str(tail);
    for _ in 0..r.below(2000) + 2000 {
        let l = cam_line(d, &mut r);
        out.push_str(&l);
        out.push_str(eol(&mut r));
    }
    out.push_str(&cam_line(d, &mut r));
    if d == Dialect::Fanuc {
        out.push_str("\nM30\n%");
    }
    out.push_str(end);
    out
}

#[test]
fn cam_programs_scan_the_same_with_words_across_buffer_ends() {
    const CHUNK: usize = 256 * 1024;
    let dir = root().join("target/stream-words-tests");
    std::fs::create_dir_all(&dir).expect("dir");
    // Lines around the first buffer end: across it in a word, at a point, a CR LF split by
    // it, a CR before it, a line end just after it.
    let tails: [(usize, &str); 7] = [
        (CHUNK - 5, "G1 X12.3456 Y-7.5\n"),
        (CHUNK - 8, "X1.5 Y2\r\nY3\n"),
        (CHUNK - 14, "N20 G1 X-12.5\r\nY3\r\n"),
        (CHUNK - 7, "N20 X1\rY2\n"),
        (CHUNK - 9, "X-12.5 Y2\r\nY3\n"),
        (CHUNK - 1, "X\n"),
        (CHUNK - 2, "X1\n"),
    ];
    let mut words = 0;
    for (k, (at, tail)) in tails.iter().enumerate() {
        for d in [Dialect::Sinumerik, Dialect::Fanuc] {
            let end = ["", "\n", "\r", "\r\n"][k % 4];
            let text = cam_program(d, 100 + k as u64, *at, tail, end);
            assert!(text[*at..].starts_with(tail), "{k}");
            let path = dir.join(format!("cam{k}.{}", if d == Dialect::Fanuc { "nc" } else { "mpf" }));
            std::fs::write(&path, &text).expect("write");
            words += check(&path, d);
        }
    }
    assert!(words > 60_000, "{words} lines as words");
}

/// A structure still open at the end of the file (an error file) is handed out with the
/// words of its blocks, as the whole-file reader has them (the index reader keeps none).
#[test]
fn an_unclosed_structure_at_the_end_keeps_its_words() {
    let dir = std::env::temp_dir().join(format!("nctrans-words-unclosed-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let cases = [
        ("u.mpf", "IF R1<R2\nG00 Z200.\n", Dialect::Sinumerik),
        ("u.nc", "O1\nWHILE[#1 LT 2]DO1\nG00 Z200.\n", Dialect::Fanuc),
    ];
    for (name, text, d) in cases {
        let p = dir.join(name);
        std::fs::write(&p, text).expect("write");
        check(&p, d);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The construct of a real Haas template program (rcod2-haas `O00010.nc`): a one-line
/// `IF [..] THEN #i=…` in a `WHILE [..] DO1` loop, with blanks around the brackets and before
/// the line ends, plain motion around it. As FANUC the streamed readers close the loop at
/// END1 and hand out what the whole-file reader reads. Read as Sinumerik (as the words test
/// once picked a dialect by the folder's name) the same text leaves an IF and a WHILE open at
/// the end of the file: the words scan then handed out the index reader's blocks with no
/// words (fixed with `an_unclosed_structure_at_the_end_keeps_its_words`).
#[test]
fn a_one_line_if_then_in_a_loop_streams_as_the_whole_file_reads_it() {
    let dir = std::env::temp_dir().join(format!("nctrans-words-if-then-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let text = "%\nO0010 (LOOP)\nG00 G17 G90 \n#1= 2. (START)\n#2= 0.\n\nWHILE [ #1 GT #2 ] DO1 \n\
                #1= #1 - 0.5 \nIF [ #1 LT #2 ] THEN #1= #2 \n \nG00 X [ #1 ] Y0. \nG01 X10. \n\nEND1 \n\
                G00 Z200. M09 \nG53 Y0 \nM30 \n\n%";
    for (name, text, d) in [
        ("loop.nc", text.to_string(), Dialect::Fanuc),
        ("loop-crlf.nc", text.replace('\n', "\r\n"), Dialect::Fanuc),
        ("loop.mpf", text.to_string(), Dialect::Sinumerik),
    ] {
        let p = dir.join(name);
        std::fs::write(&p, text).expect("write");
        assert!(check(&p, d) > 0, "{name}: no line taken as words");
        if d == Dialect::Fanuc {
            assert!(same_as_whole_parse(&p, d), "{name}: the whole-file reader refused it");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
