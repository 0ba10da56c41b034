//! The streamed translators' first scan (`stream::scan_words`) against the whole-file reader
//! and the index-only scan: on every corpus file, the external programs and generated
//! programs (plain motion with numbers, comments, skips, program ends, blank and non-ASCII
//! lines, macro lines in between), it builds the same index and diagnostics as
//! `scan_index`, and what it hands out, plain lines as words and the rest as statements,
//! is line for line what `scan` (the whole-file reader) hands out.

#[path = "support/rng.rs"]
mod rng;

use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::ir::{Addr, BlockMeta, ExprKind, ItemKind, Stmt, StmtKind, WordValue};
use nctrans::stream::{self, Canon, PlainWord, WordsSink};
use rng::Rng;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// What a sink got, one entry per statement: a plain line as its meta and words, or a
/// statement's debug form.
#[derive(Debug, PartialEq)]
enum Got {
    Plain {
        prog: usize,
        number: Option<u32>,
        span: (u32, u32),
        comments: Vec<String>,
        words: Vec<(u8, u64, bool, (u32, u32))>,
    },
    Stmt(usize, String),
}

/// A plain block of a whole-file statement, as [`Got::Plain`]; else its debug form.
fn of_stmt(prog: usize, s: &Stmt, plain_ok: bool) -> Got {
    if plain_ok {
        if let StmtKind::Block(b) = &s.kind {
            let words: Option<Vec<_>> = b
                .items
                .iter()
                .map(|it| match &it.kind {
                    ItemKind::Word(w) => match (&w.addr, &w.value) {
                        (Addr::Letter(l), WordValue::Expr(e)) => match &e.kind {
                            ExprKind::Num(n) => Some((*l, n.value.to_bits(), n.point, (it.span.lo, it.span.hi))),
                            _ => None,
                        },
                        _ => None,
                    },
                    _ => None,
                })
                .collect();
            if let Some(words) = words.filter(|_| b.meta.label.is_none() && b.meta.skip.is_none()) {
                return plain(prog, &b.meta, words);
            }
        }
    }
    Got::Stmt(prog, format!("{s:?}"))
}

fn plain(prog: usize, meta: &BlockMeta, words: Vec<(u8, u64, bool, (u32, u32))>) -> Got {
    Got::Plain {
        prog,
        number: meta.number.as_ref().map(|n| n.value),
        span: (meta.span.lo, meta.span.hi),
        comments: meta.comments.iter().map(|c| c.text.clone()).collect(),
        words,
    }
}

struct Record {
    got: Vec<Got>,
    /// Whether plain lines are taken as words (else each is asked for as a statement).
    take: bool,
    /// Whether the scan may read plain lines with the quick readers (else all the general way).
    quick: bool,
}

impl WordsSink for Record {
    fn plain(&mut self, prog: usize, meta: &BlockMeta, words: &[PlainWord], _: &nctrans::read::RawBlock<'_>) -> bool {
        if self.take {
            let words = words.iter().map(|w| (w.letter, w.value.to_bits(), w.point, (w.span.lo, w.span.hi))).collect();
            self.got.push(plain(prog, meta, words));
        }
        self.take
    }

    fn stmt(&mut self, prog: usize, s: &Stmt) {
        self.got.push(Got::Stmt(prog, format!("{s:?}")));
    }

    fn active(&self) -> bool {
        true
    }

    fn quick(&self) -> bool {
        self.quick
    }
}

/// The plain lines a words scan should take, found as the words scan did before it read
/// a line once (`scan_plain_words`): a re-reading reader reads the line into its words
/// (`plain_words`; FANUC: no block skip) and the index-only reader takes it whole
/// (`scan_plain`); every other line goes through the index reader's `line`. `None` for a
/// file that is not UTF-8.
fn plain_lines_two_readers(path: &Path, dialect: Dialect) -> Option<Vec<Got>> {
    use nctrans::dialect::{fanuc, sinumerik};
    use nctrans::span::Span;
    let bytes = std::fs::read(path).ok()?;
    let text = std::str::from_utf8(bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(&bytes)).ok()?;
    let opts = ParseOptions::for_dialect(dialect);
    let mut out = Vec::new();
    let mut stmts = Vec::new();
    let mut words: Vec<PlainWord> = Vec::new();
    fn push(words: &mut Vec<PlainWord>) -> impl FnMut(u8, f64, bool, Span) -> bool + '_ {
        |letter, value, point, span| {
            words.push(PlainWord { letter, value, point, span, canon: Canon::NONE });
            true
        }
    }
    // What a sink gets for a plain line (the Sinumerik comment as the scan finds it).
    let got = |prog: usize, raw: &nctrans::read::RawBlock<'_>, span: Span, number, words: &[PlainWord]| {
        let from = words.last().map_or(0, |w| (w.span.hi - raw.start) as usize);
        let comment = match dialect {
            Dialect::Sinumerik => {
                raw.text.get(from..).and_then(|t| t.find(';')).map(|i| raw.text[from + i + 1..].to_string())
            }
            Dialect::Fanuc => None,
        };
        Got::Plain {
            prog,
            number,
            span: (span.lo, span.hi),
            comments: comment.into_iter().collect(),
            words: words.iter().map(|w| (w.letter, w.value.to_bits(), w.point, (w.span.lo, w.span.hi))).collect(),
        }
    };
    match dialect {
        Dialect::Sinumerik => {
            let mut r = sinumerik::Reader::new(0, &opts, text.len() as u32);
            r.compact_targets();
            r.index_only();
            let mut w = sinumerik::Reader::resume(0, &opts, &r.checkpoint());
            for raw in nctrans::read::blocks(text) {
                words.clear();
                if w.plain_words(&raw, false, push(&mut words)).is_some() {
                    if let Some((span, number)) = r.scan_plain(&raw, false) {
                        out.push(got(0, &raw, span, number.map(|n| n.value), &words));
                        continue;
                    }
                }
                r.line(&raw);
                r.drain_into(&mut stmts);
                stmts.clear();
            }
        }
        Dialect::Fanuc => {
            let mut r = fanuc::Reader::new(0, &opts);
            r.index_only();
            let mut w = fanuc::Reader::resume(0, &opts, r.checkpoint());
            for raw in nctrans::read::blocks(text) {
                words.clear();
                let skip = raw.text.trim_start_matches([' ', '\t', '\x0C']).starts_with('/');
                if !skip && w.plain_words(&raw, false, push(&mut words)).is_some() {
                    if let Some((span, number)) = r.scan_plain(&raw, false) {
                        out.push(got(r.current(), &raw, span, number.map(|n| n.value), &words));
                        continue;
                    }
                }
                r.line(&raw);
                r.drain_into(&mut stmts);
                stmts.clear();
            }
        }
    }
    Some(out)
}

/// Checks one file; returns how many lines went as words.
fn check(path: &Path, dialect: Dialect) -> usize {
    let opts = ParseOptions::for_dialect(dialect);
    let Ok(index) = stream::scan_index_path(path, 0, dialect, &opts, None) else { return 0 };
    let mut whole = Vec::new();
    let full = stream::scan_path(path, 0, dialect, &opts, &mut |p, s| whole.push((p, s.clone())), None).expect("scan");
    let mut words = 0;
    for (take, quick) in [(true, true), (false, true), (true, false), (false, false)] {
        let mut rec = Record { got: Vec::new(), take, quick };
        let ix = stream::scan_words_path(path, 0, dialect, &opts, &mut rec, None).expect("scan_words");
        assert_eq!(format!("{ix:?}"), format!("{index:?}"), "index of {}", path.display());
        // The whole-file scan's index is the same too (but for what index-only readers
        // leave out: compare what the runs need).
        assert_eq!(ix.blocks, full.blocks, "{}", path.display());
        assert_eq!(ix.diags.len(), full.diags.len(), "{}", path.display());
        let expected: Vec<Got> = if take {
            // Which whole-file statements are plain lines: those the words scan took.
            let mut exp = Vec::new();
            for (k, (p, s)) in whole.iter().enumerate() {
                let as_plain = matches!(rec.got.get(k), Some(Got::Plain { .. }));
                exp.push(of_stmt(*p, s, as_plain));
            }
            words = rec.got.iter().filter(|g| matches!(g, Got::Plain { .. })).count();
            exp
        } else {
            whole.iter().map(|(p, s)| Got::Stmt(*p, format!("{s:?}"))).collect()
        };
        if take {
            // Exactly the lines the two readers took as words, with the same words.
            if let Some(two) = plain_lines_two_readers(path, dialect) {
                let plain: Vec<&Got> = rec.got.iter().filter(|g| matches!(g, Got::Plain { .. })).collect();
                assert_eq!(plain.len(), two.len(), "plain lines of {}", path.display());
                for (a, b) in plain.iter().zip(&two) {
                    assert_eq!(*a, b, "{}", path.display());
                }
            }
        }
        assert_eq!(rec.got.len(), expected.len(), "{} (take {take}, quick {quick})", path.display());
        for (a, b) in rec.got.iter().zip(&expected) {
            assert_eq!(a, b, "{} (take {take}, quick {quick})", path.display());
        }
    }
    words
}

fn files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let Ok(rd) = std::fs::read_dir(dir) else { return out };
    for e in rd.filter_map(|e| e.ok()) {
        let p = e.path();
        if p.is_dir() {
            out.extend(files(&p));
        } else {
            out.push(p);
        }
    }
    out.sort();
    out
}

#[test]
fn corpus_and_external_programs_scan_the_same_with_words() {
    let mut words = 0;
    let mut n = 0;
    for (dir, d) in [("corpus/in/sinumerik", Dialect::Sinumerik), ("corpus/in/fanuc", Dialect::Fanuc)] {
        for f in files(&root().join(dir)) {
            words += check(&f, d);
            n += 1;
        }
    }
    let ext = root().join("../shared/external");
    if ext.is_dir() {
        for f in files(&ext) {
            let name = f.to_string_lossy().to_ascii_lowercase();
            let d = if name.contains("fanuc") { Dialect::Fanuc } else { Dialect::Sinumerik };
            if name.ends_with(".md") {
                continue;
            }
            words += check(&f, d);
            n += 1;
        }
    } else {
        eprintln!("note: {} not found; external programs skipped", ext.display());
    }
    assert!(n > 100 && words > 300, "{n} files, {words} lines as words");
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
