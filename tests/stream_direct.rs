//! The direct route of a streamed re-read (plain lines straight into compact ops, see
//! `stream::reread`) against the general one (reader → IR → flatten), for both dialects:
//! on every corpus program and on generated ones, every page has the same ops, and a run
//! the same trace.

mod eval_support;
#[path = "support/rng.rs"]
mod rng;

use eval_support::*;
use nctrans::dialect::lit::NO_MILLI;
use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::eval::paged::PagedSource;
use nctrans::eval::{self, trace, Origin, RunOptions, TraceSink};
use nctrans::span::SourceDb;
use nctrans::stream::{self, lines::Input, paged::Pager};
use rng::Rng;
use std::path::Path;
use std::rc::Rc;
use std::sync::Arc;

/// Every page of every program of `path` (scanned with chunks of `chunk_ops`), as text,
/// read with the direct route on or off; and how many lines took the direct route.
fn pages(path: &Path, dialect: Dialect, chunk_ops: usize, direct: bool) -> Option<(Vec<String>, u64)> {
    let bytes = std::fs::read(path).ok()?;
    let input = Input::Mem(std::io::Cursor::new(bytes.clone()));
    let opts = ParseOptions::for_dialect(dialect);
    let ix = stream::scan_index(input, bytes.len() as u64, path, 0, dialect, &opts, chunk_ops, None).ok()?;
    let pager = Pager::new(Arc::new(ix.clone()));
    pager.set_direct(direct);
    let mut out = Vec::new();
    for (prog, p) in ix.programs.iter().enumerate() {
        for c in &p.chunks {
            match pager.page(prog, c.op_base) {
                Ok(Some(page)) => {
                    known_millis_are_right(page.ops());
                    out.push(without_lines(&format!("{prog} {} {:?}", c.op_base, page.ops())))
                }
                Ok(None) => out.push(format!("{prog} {} none", c.op_base)),
                Err(d) => out.push(format!("{prog} {} error {}", c.op_base, d.code)),
            }
        }
    }
    let n = *pager.direct_lines.borrow();
    Some((out, n))
}

fn dialect_of(path: &Path) -> Dialect {
    let text = String::from_utf8_lossy(&std::fs::read(path).unwrap_or_default()).to_string();
    nctrans::detect_dialect(&path.to_string_lossy(), &text)
}

/// Every count of thousandths a compact word carries (`LitWord::milli`, which only the
/// direct route works out, from the digits) is the one the machine would round its
/// value to.
fn known_millis_are_right(ops: &[nctrans::eval::flow::Op]) {
    for op in ops {
        let nctrans::eval::flow::Op::Lit(b) = op else { continue };
        for w in b.words() {
            if w.milli != NO_MILLI {
                let want = nctrans::eval::value::decimal_count(w.value, 1000.0);
                assert_eq!(Some(i64::from(w.milli)), want, "{w:?}");
            }
        }
    }
}

/// `text` with the line numbers of compact blocks (`line: N`) and the counts of
/// thousandths of their words (`milli: N`, checked by [`known_millis_are_right`]) blanked:
/// only the direct route knows them (the general one builds blocks from IR, which has
/// spans and values only); tests/eval_fast.rs checks that the carried line is the line of
/// the block's span.
fn without_lines(text: &str) -> String {
    let mut text = text.to_string();
    for key in ["line: ", "milli: "] {
        let mut out = String::with_capacity(text.len());
        let mut rest = text.as_str();
        while let Some(i) = rest.find(key) {
            out.push_str(&rest[..i + key.len()]);
            rest = rest[i + key.len()..].trim_start_matches(|c: char| c == '-' || c.is_ascii_digit());
            out.push('_');
        }
        out.push_str(rest);
        text = out;
    }
    text
}

/// Same pages both ways; returns how many lines took the direct route.
fn same_pages(path: &Path, chunk_ops: usize) -> u64 {
    let dialect = dialect_of(path);
    let on = pages(path, dialect, chunk_ops, true);
    let off = pages(path, dialect, chunk_ops, false);
    match (on, off) {
        (Some((a, n)), Some((b, m))) => {
            assert_eq!(m, 0, "{}: direct route taken while off", path.display());
            assert_eq!(a.len(), b.len(), "{} at chunks of {chunk_ops}", path.display());
            for (x, y) in a.iter().zip(&b) {
                assert_eq!(x, y, "{} at chunks of {chunk_ops}", path.display());
            }
            n
        }
        (None, None) => 0,
        (a, b) => panic!("{}: scanned {} / {}", path.display(), a.is_some(), b.is_some()),
    }
}

#[test]
fn direct_route_gives_the_same_ops_on_every_corpus_program() {
    let (mut direct, mut fanuc) = (0, 0);
    let files = corpus_files();
    assert!(files.len() > 20, "{} corpus files", files.len());
    for path in &files {
        for chunk in [1, 3, 2048] {
            let n = same_pages(path, chunk);
            direct += n;
            if dialect_of(path) == Dialect::Fanuc {
                fanuc += n;
            }
        }
    }
    // The route is really taken (both corpora have plain motion blocks).
    assert!(direct > 100, "{direct} direct lines");
    assert!(fanuc > 100, "{fanuc} direct FANUC lines");
}

/// A Sinumerik line: mostly plain motion blocks in their many spellings, some that must
/// not take the direct route (normalised, M30/M17, too many words, structures, labels…).
fn line(r: &mut Rng) -> String {
    let num = |r: &mut Rng| -> String {
        let sign = r.pick(&["", "", "-", "+"]);
        match r.below(7) {
            0 => format!("{sign}{}", r.below(1000)),
            1 => format!("{sign}{}.", r.below(100)),
            2 => format!("{sign}.{}", r.below(1000)),
            3 => format!("{sign}0.0"),
            4 => format!("{sign}{}.{:03}", r.below(10_000), r.below(1000)),
            // Whole numbers of up to 19 digits: up to 15 are read exactly, longer ones
            // are left to the grammar.
            5 => format!("{sign}{}", r.below(1 << 60) >> r.below(60)),
            _ => format!("{sign}{}.{}", r.below(100), r.below(100_000_000)),
        }
    };
    match r.below(40) {
        0 => "IF R1>0".into(),
        1 => "ENDIF".into(),
        2 => "WHILE R2<0".into(),
        3 => "ENDWHILE".into(),
        4 => "LAB1: G1 X1".into(),
        5 => "M30".into(),
        6 => format!("N{} M17", r.below(100)),
        7 => "M2 X1".into(),
        8 => "GO X1 Y2".into(),
        9 => "G1 X\u{FF11}0 Y2".into(),
        10 => "G1 X1 Y2 Z3 A4 B5 C6 F7 S8".into(),
        11 => "".into(),
        12 => "   ; comment only".into(),
        13 => "R1=R1+1".into(),
        14 => "G1 X=AC(5) Y2".into(),
        15 => "/G1 X1".into(),
        16 => "%_N_X_MPF".into(),
        17 => "L10".into(),
        18 => "G0O X1".into(),
        19 => "M3.5 S1000".into(),
        // A letter O for a zero that, read without normalising, would be an O word; a
        // letter O in a comment (normalising leaves it); full-width text in a comment.
        20 => r.pick(&["G0O1 X2", "g0o1 Y3", "N10 O5", "G1 X1 ;GO1", "G1 X1 ;\u{FF38}2"]).into(),
        // CAM output as it nearly always is (the quick reader's shape, `dialect::quick`).
        21..=26 => {
            let mut words = vec![r.pick(&["G1", "G0", "G1", "G01"]).to_string()];
            for axis in ["X", "Y", "Z", "F"] {
                if r.chance(70) {
                    let v = num(r);
                    words.push(format!("{axis}{}", if axis == "F" { v.trim_start_matches(['-', '+']) } else { &v }));
                }
            }
            words.join(" ")
        }
        _ => {
            let mut s = String::new();
            if r.chance(40) {
                s.push_str(&format!("{} ", r.pick(&["N", "n"])));
                s.pop();
                s.push_str(&format!("{} ", r.below(100_000)));
            }
            for _ in 0..r.below(9) {
                let letter = r.pick(&["G", "X", "Y", "Z", "A", "F", "S", "M", "x", "g", "T", "D", "E", "H"]);
                let v = if letter == "G" || letter == "M" { r.below(100).to_string() } else { num(r) };
                s.push_str(letter);
                s.push_str(&v);
                s.push_str(r.pick(&[" ", " ", "", "\t", "  "]));
            }
            if r.chance(15) {
                s.push_str("; note X1");
            }
            s
        }
    }
}

#[test]
fn direct_route_gives_the_same_ops_and_trace_on_generated_programs() {
    let dir = root().join("target/stream-direct-tests");
    std::fs::create_dir_all(&dir).expect("dir");
    let mut direct = 0;
    for seed in 1..=12u64 {
        let mut r = Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15));
        let mut text = String::from("%_N_GEN_MPF\nDEF REAL QQ\n");
        for _ in 0..600 {
            text.push_str(&line(&mut r));
            text.push_str(r.pick(&["\n", "\n", "\r\n"]));
        }
        // Close whatever the random structures left open, so the file is streamable.
        text.push_str("ENDIF\nENDWHILE\nENDIF\nENDWHILE\nM30\n");
        let path = dir.join(format!("gen{seed}.mpf"));
        std::fs::write(&path, &text).expect("write");
        for chunk in [1, 3, 64, 2048] {
            direct += same_pages(&path, chunk);
        }
    }
    assert!(direct > 1000, "{direct} direct lines");
}

/// A FANUC line: mostly plain motion blocks in their many spellings, and lines that must
/// not take the direct route: several blocks, comments, normalised text, program numbers,
/// calls and ends (G65/M98/M99/M30), loops (words go into the open loop), parameter
/// writes (`G10 L50` … `G11`), too many words, variables, GOTOs, a lone skip…; with
/// `runnable`, only lines that leave a program runnable (no errors).
fn fanuc_line(r: &mut Rng, runnable: bool) -> String {
    let num = |r: &mut Rng| -> String {
        let sign = r.pick(&["", "", "-", "+"]);
        match r.below(6) {
            0 => format!("{sign}{}", r.below(1000)),
            1 => format!("{sign}{}.", r.below(100)),
            2 => format!("{sign}.{}", r.below(1000)),
            3 => format!("{sign}0.0"),
            4 => format!("{sign}{}.{:04}", r.below(10_000), r.below(10_000)),
            _ => format!("{sign}{}.{}", r.below(100), r.below(10_000_000_000_000_000)),
        }
    };
    let pick = match r.below(60) {
        k if runnable && !matches!(k, 4..=10 | 17 | 18 | 21 | 22 | 32 | 33 | 34..) => 40,
        k => k,
    };
    match pick {
        0 => "WHILE[#1 LT 3]DO1".into(),
        1 => "END1".into(),
        2 => "DO2".into(),
        3 => "END2".into(),
        4 => "#1=#1+1".into(),
        5 => "G1 X1; G1 Y2".into(),
        6 => "G1 X1 ;Y2;".into(),
        7 => "G1 X1 (cut) Y2".into(),
        8 => "(comment only)".into(),
        9 => "G1 X\u{FF11}0 Y2".into(),
        10 => "G0O X1".into(),
        11 => "G10 L50".into(),
        12 => "N1 R1 P2".into(),
        13 => "G11".into(),
        14 => "G65 P9010 A1.".into(),
        15 => "M98 P9020".into(),
        16 => format!("O{}", 2000 + r.below(50)),
        17 => "G1 X1 Y2 Z3 A4 B5 C6 F7 S8".into(),
        18 => "G1 X#1 Y2".into(),
        19 => "GOTO 20".into(),
        20 => "IF[#1 GT 2]GOTO 30".into(),
        21 => "/".into(),
        22 => "".into(),
        23 => "N0 G1 X1".into(),
        24 => "N100000 G1 X1".into(),
        25 => "G1 N10 X1".into(),
        26 => "M30".into(),
        27 => "M99".into(),
        28 => "G66 P9030".into(),
        29 => "G67".into(),
        30 => ":3000".into(),
        31 => "X1.2.3".into(),
        32 => format!("N{} ;", r.below(9000) + 1),
        33 => "   ;".into(),
        // Read without normalising, these must still be cut and read as `line` would.
        34 => r.pick(&["G0O1 X2", "G1 X1;  ;", "G1 X1;;", "G1 X1; (C)", "\x0bG1 X1", "N5;", "G1 X1 \x0c;"]).into(),
        _ => {
            let mut s = String::new();
            if r.chance(10) {
                s.push_str(r.pick(&["/", "/2 ", "/ "]));
            }
            if r.chance(40) {
                s.push_str(&format!("{}{} ", r.pick(&["N", "n"]), r.below(99_999) + 1));
            }
            for _ in 0..r.below(9) {
                let letter = r.pick(&["G", "X", "Y", "Z", "A", "F", "S", "M", "x", "g", "T", "D", "H", "I", "J", "R"]);
                let v = if runnable && (letter == "G" || letter == "g") {
                    r.pick(&["0", "1", "01", "17", "90", "91", "94"]).to_string()
                } else if runnable && letter == "M" {
                    r.pick(&["3", "5", "8", "09"]).to_string()
                } else if letter == "G" || letter == "M" || letter == "g" {
                    // Sometimes with more digits than an exact whole number read holds
                    // (`G0000000000000065` is G65: not plain).
                    let width = if r.chance(10) { 16 } else { 1 };
                    format!("{:0width$}", r.below(100))
                } else {
                    num(r)
                };
                s.push_str(letter);
                s.push_str(r.pick(&["", "", " "]));
                s.push_str(&v);
                s.push_str(r.pick(&[" ", " ", "", "\t", "  "]));
            }
            if r.chance(10) {
                s.push(';');
            }
            s
        }
    }
}

/// A generated FANUC file of 600 lines (its `%` marks: `tape`; only runnable lines:
/// `runnable`).
fn fanuc_program(seed: u64, tape: bool, runnable: bool) -> String {
    let mut r = Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15));
    let mut text = String::from(if tape { "%\nO1000 (GEN)\n" } else { "O1000 (GEN)\n" });
    for i in 0..600 {
        // A `%` late in some files ends the tape (with or without an opening `%`):
        // what follows is not read (both ways).
        if i == 550 && seed.is_multiple_of(3) && !runnable {
            text.push_str("%\n");
        }
        text.push_str(&fanuc_line(&mut r, runnable));
        text.push_str(r.pick(&["\n", "\n", "\r\n"]));
    }
    if !runnable {
        text.push_str("G11\nEND2\nEND1\nEND2\nEND1\n");
    }
    text.push_str("M30\n");
    if tape {
        text.push_str("%\n");
    }
    text
}

#[test]
fn direct_route_gives_the_same_ops_on_generated_fanuc_programs() {
    let dir = root().join("target/stream-direct-tests");
    std::fs::create_dir_all(&dir).expect("dir");
    let mut direct = 0;
    for seed in 1..=12u64 {
        let path = dir.join(format!("gen{seed}.nc"));
        std::fs::write(&path, fanuc_program(seed, seed.is_multiple_of(2), seed % 4 == 1)).expect("write");
        for chunk in [1, 3, 64, 2048] {
            direct += same_pages(&path, chunk);
        }
    }
    assert!(direct > 1000, "{direct} direct lines");
}

#[test]
fn direct_route_leaves_the_fanuc_reader_as_the_general_route_does() {
    // A `%` after content ends the tape; after nothing but a program number it opens it.
    // Whether the plain line before it counts as content is reader state the direct route
    // must keep too.
    let dir = root().join("target/stream-direct-tests");
    std::fs::create_dir_all(&dir).expect("dir");
    let cases = [
        "O1000\nG1 X1\n%\nG1 X2\nG1 X3\nM30\n",
        "O1000\nN10 G1 X1\n%\nN20 G1 X2\nM30\n",
        "G1 X1\n%\nG1 X2\nM30\n",
        "%\nO1000\nG1 X1\n%\nG1 X2\nM30\n%\n",
        "O1000\nG1 X1;\n%\nG1 X2;\nM30;\n",
    ];
    let mut direct = 0;
    for (k, text) in cases.iter().enumerate() {
        let path = dir.join(format!("reader{k}.nc"));
        std::fs::write(&path, text).expect("write");
        for chunk in [1, 2, 3, 2048] {
            direct += same_pages(&path, chunk);
        }
    }
    assert!(direct > 5, "{direct} direct lines");
}

/// Straight FANUC CAM code with a loop back over many chunks.
fn fanuc_cam(r: &mut Rng) -> String {
    let mut text = String::from("%\nO1000 (CAM)\nG21 G17 G90 F1000.\n#1=0\nN5 G0 X0. Y0.\n");
    for i in 0..3000 {
        let n = if i % 4 == 0 { format!("N{} ", i * 2 + 10) } else { String::new() };
        text.push_str(&format!(
            "{n}G1 X{}.{:03} Y-{}.{:02} Z{}{}\n",
            r.below(500),
            r.below(1000),
            r.below(300),
            r.below(100),
            r.below(20),
            if i % 5 == 0 { ";" } else { "" }
        ));
    }
    text.push_str("#1=#1+1\nIF[#1LT2]GOTO5\nM30\n%\n");
    text
}

/// Events as text with `@line`.
struct Trace {
    out: Vec<String>,
    pager: Rc<Pager>,
}

impl TraceSink for Trace {
    fn event(&mut self, ev: &eval::Event, origin: Origin) {
        let mut l = trace::text_line(ev);
        if let Some(n) = (origin.file == 0).then(|| self.pager.line_of(origin.span.lo)).flatten() {
            l.push_str(&format!("  @{n}"));
        }
        self.out.push(l);
    }
}

/// The trace of a streamed run of `path` with the direct route on or off.
fn streamed_trace(path: &Path, chunk_ops: usize, direct: bool) -> Vec<String> {
    let dialect = dialect_of(path);
    let mut db = SourceDb::new();
    let file = db.add(path.to_string_lossy().to_string(), String::new());
    let (input, size) = stream::open(path).expect("open");
    let popts = ParseOptions::for_dialect(dialect);
    let index = stream::scan_index(input, size, path, file, dialect, &popts, chunk_ops, None).expect("scan");
    let inputs = eval::header_inputs(&index.header).expect("header");
    let opts = RunOptions { max_steps: 1_000_000, inputs, ..Default::default() };
    let pager = Rc::new(Pager::new(Arc::new(index)));
    pager.set_direct(direct);
    let mut t = Trace { out: vec![], pager: Rc::clone(&pager) };
    let o = eval::run_stream(&mut db, pager.clone(), &mut eval::DirCallees { semantics: None }, &opts, &mut t);
    t.out.push(format!("{:?} {} {:?}", o.ending, o.steps, o.diags.iter().map(|d| d.code).collect::<Vec<_>>()));
    t.out
}

#[test]
fn direct_route_runs_like_the_general_route() {
    // Straight CAM code with a loop back over many chunks in both dialects, generated
    // FANUC programs and the corpus.
    let dir = root().join("target/stream-direct-tests");
    std::fs::create_dir_all(&dir).expect("dir");
    let mut r = Rng(7);
    let mut text = String::from("%_N_CAM_MPF\nG90 G17 F1000\nR1=0\nTOP:\n");
    for i in 0..3000 {
        text.push_str(&format!(
            "N{} G1 X{}.{:03} Y-{}.{:02} Z{} ; cut\n",
            i * 2 + 10,
            r.below(500),
            r.below(1000),
            r.below(300),
            r.below(100),
            r.below(20)
        ));
    }
    text.push_str("R1=R1+1\nIF R1<2 GOTOB TOP\nM30\n");
    let path = dir.join("cam.mpf");
    std::fs::write(&path, &text).expect("write");
    assert!(same_pages(&path, 64) >= 3000);
    let fpath = dir.join("cam.nc");
    std::fs::write(&fpath, fanuc_cam(&mut r)).expect("write");
    assert!(same_pages(&fpath, 64) >= 3000);
    let mut files = vec![path, fpath];
    for seed in [1, 2, 3] {
        let p = dir.join(format!("run{seed}.nc"));
        std::fs::write(&p, fanuc_program(seed + 100, seed != 3, true)).expect("write");
        files.push(p);
    }
    let generated = files.len();
    files.extend(corpus_files());
    let mut compared = 0;
    for path in &files {
        // Files with errors do not run streamed (the CLI reads them whole).
        let Some(ix) = scan(path) else { continue };
        if ix.diags.iter().any(|d| d.severity == nctrans::diag::Severity::Error) {
            assert!(!files[..generated].contains(path), "{}: {:?}", path.display(), ix.diags);
            continue;
        }
        for chunk in [3, 64] {
            let a = streamed_trace(path, chunk, true);
            let b = streamed_trace(path, chunk, false);
            assert_eq!(a, b, "{} at chunks of {chunk}", path.display());
            compared += 1;
        }
    }
    assert!(compared > 10, "{compared} compared");
}

fn scan(path: &Path) -> Option<stream::Index> {
    let dialect = dialect_of(path);
    let (input, size) = stream::open(path).ok()?;
    stream::scan_index(input, size, path, 0, dialect, &ParseOptions::for_dialect(dialect), 64, None).ok()
}

/// Files longer than the 256 KiB read buffer, so that re-read lines cross its end: lines
/// in the quick reader's shape (and others), with LF, CR LF and lone CR line ends, a CR LF
/// split across the first buffer's end (its CR the buffer's last byte), a line across it,
/// with and without a line end after the last line. Same pages and runs both ways.
#[test]
fn direct_route_reads_across_the_read_buffer_end() {
    const BUF: usize = 256 * 1024;
    let dir = root().join("target/stream-direct-tests");
    std::fs::create_dir_all(&dir).expect("dir");
    let mut direct = 0;
    for (k, (fanuc, split, last_end)) in
        [(false, true, true), (false, false, false), (true, true, false), (true, false, true)].into_iter().enumerate()
    {
        let mut r = Rng(k as u64 * 77 + 5);
        let mut text = String::from(if fanuc { "O1000 (BIG)\n" } else { "%_N_BIG_MPF\n" });
        let quick = |r: &mut Rng| {
            format!(
                "G1 X{}.{:04} Y-{}.{} Z{} F{}",
                r.below(500),
                r.below(10_000),
                r.below(90),
                r.below(99),
                r.below(9),
                r.below(900)
            )
        };
        while text.len() < BUF * 5 / 2 {
            // Near the first buffer's end: a quick line whose CR LF straddles it, or a
            // line across it.
            if text.len() > BUF - 200 && text.len() < BUF {
                let l = quick(&mut r);
                let want = BUF - 1 - text.len();
                if split && want > 12 {
                    let mut l = l;
                    while l.len() < want {
                        l.push('0');
                    }
                    l.truncate(want);
                    // Ends in a digit (not a point or sign): still the quick shape.
                    while !l.ends_with(|c: char| c.is_ascii_digit()) {
                        l.pop();
                        l.push('1');
                    }
                    text.push_str(&l);
                    text.push_str("\r\n");
                    assert!(!split || text.len() == BUF + 1, "{}", text.len());
                    continue;
                }
            }
            let l = match r.below(10) {
                0 if fanuc => fanuc_line(&mut r, true),
                0 => line(&mut r),
                _ => quick(&mut r),
            };
            // No structures (a random `IF` might not close) and no program ends.
            if l.contains("IF") || l.contains("WHILE") || l.contains("M30") || l.contains("M17") || l.contains('%') {
                continue;
            }
            text.push_str(&l);
            text.push_str(r.pick(&["\n", "\r\n", "\r", "\n"]));
        }
        text.push_str("M30");
        if last_end {
            text.push('\n');
        }
        let path = dir.join(format!("big{k}.{}", if fanuc { "nc" } else { "mpf" }));
        std::fs::write(&path, &text).expect("write");
        for chunk in [1, 64, 2048] {
            direct += same_pages(&path, chunk);
        }
        assert_eq!(streamed_trace(&path, 64, true), streamed_trace(&path, 64, false), "{}", path.display());
    }
    assert!(direct > 50_000, "{direct} direct lines");
}
