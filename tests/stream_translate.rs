//! Streamed translation (Sinumerik → FANUC, straight-line programs) writes exactly what the
//! whole-program translator writes, over several chunks; programs that need whole-program
//! passes are refused (and translated whole by the CLI); a streamed verification agrees.

use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::span::SourceDb;
use nctrans::stream::{target::fanuc as st, Fallback};
use nctrans::translate::{self, to_fanuc::TranslateOptions};
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn opts(path: &Path, text: &str) -> TranslateOptions {
    TranslateOptions {
        main_name: path.file_stem().and_then(|s| s.to_str()).unwrap_or("MAIN").to_ascii_uppercase(),
        source_name: path.file_name().and_then(|s| s.to_str()).unwrap_or("").to_string(),
        line_ending: nctrans::read::detect_line_ending(text),
        ..TranslateOptions::default()
    }
}

/// (whole translation text, streamed result).
fn both(path: &Path) -> (String, Result<Vec<u8>, Fallback>) {
    let bytes = std::fs::read(path).expect("read");
    let mut db = SourceDb::new();
    let loaded = nctrans::load(&mut db, &path.display().to_string(), &bytes, None);
    let text = db.get(loaded.file).text.clone();
    let parsed = nctrans::parse(&db, loaded.file, Dialect::Sinumerik, &ParseOptions::for_dialect(Dialect::Sinumerik));
    let o = opts(path, &text);
    let whole = translate::to_fanuc::to_fanuc(&parsed.unit, &[], &o).text;
    let mut out = Vec::new();
    let r = st::to_fanuc(path, &o, &mut out, None).map(|_| out);
    (whole, r)
}

#[test]
fn streamed_translation_is_the_whole_translation() {
    let dir = root().join("target/stream-tests");
    std::fs::create_dir_all(&dir).expect("dir");
    let mut text = String::from("%_N_CAMPART_MPF\n; generated\nN1 G90 G71 G17\nG0 X0 Y0 Z5\n");
    for i in 0..10_000 {
        match i % 5 {
            0 => text.push_str(&format!("N{} G1 X{}.5 Y-{} F{}\n", 10 + i, i % 97, i % 13, 500 + i % 7)),
            1 => text.push_str(&format!("X{}.25 ; step {i}\n", i % 50)),
            // A turns alone: Z with it would be dragged along on Siemens (docs/semantics.md,
            // "Feed of moves with rotary axes and FGROUP"), and FGROUP does not stream.
            2 => text.push_str(&format!("G1 Z-{}.5\nA{}\n", i % 3, i % 360)),
            3 => text.push_str("/G1 Z-0.5\n"),
            _ => text.push_str(&format!("G0 Z{}.\n", i % 4)),
        }
    }
    text.push_str("M30\n");
    let path = dir.join("campart.mpf");
    std::fs::write(&path, &text).expect("write");
    let (whole, streamed) = both(&path);
    let streamed = streamed.map_err(|e| format!("{e:?}")).expect("streams");
    assert_eq!(String::from_utf8_lossy(&streamed), whole);

    // Verified streamed: both programs run streamed, traces compared as they come.
    let out = dir.join("campart.nc");
    std::fs::write(&out, &streamed).expect("write");
    let popts = ParseOptions::for_dialect(Dialect::Sinumerik);
    let ix = nctrans::stream::scan_path(&path, 0, Dialect::Sinumerik, &popts, &mut |_, _| {}, None).expect("scan");
    let v = nctrans::stream::verify::verify(ix, &out, 1_000_000, Vec::new(), None);
    assert!(v.equivalent && v.summary.contains("(12002 events"), "{}", v.summary);

    // A broken translation is caught by the streamed verification.
    let bad = String::from_utf8_lossy(&streamed).replacen("X1.25", "X1.26", 1);
    assert_ne!(bad.as_bytes(), &streamed[..]);
    std::fs::write(&out, bad).expect("write");
    let ix = nctrans::stream::scan_path(&path, 0, Dialect::Sinumerik, &popts, &mut |_, _| {}, None).expect("scan");
    let v = nctrans::stream::verify::verify(ix, &out, 1_000_000, Vec::new(), None);
    assert!(!v.equivalent && v.summary.contains("diverged"), "{}", v.summary);
}

/// Generated programs switching G70/G71/G700/G710 (alone and beside moves) with F words and
/// dwells: the stream writes the whole translation, both unit cases occur (F as written,
/// `F[f/25.4]` under G70; never `F[f*25.4]`: G71 reads F in mm/min like G710), and the
/// streamed verification finds it equivalent.
#[test]
fn feed_units_stream_identically_and_verify_equivalent() {
    let dir = root().join("target/stream-tests");
    std::fs::create_dir_all(&dir).expect("dir");
    let mut seed = 0x0f33_d700_0071_u64;
    let mut next = |n: u64| {
        seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (seed >> 33) % n
    };
    let units = ["G70", "G71", "G700", "G710"];
    for case in 0..6 {
        let mut text = format!("%_N_FEED{case}_MPF\nG90 G17 G94\n");
        for i in 0..3000 {
            if next(7) == 0 {
                let g = units[next(4) as usize];
                match next(3) {
                    0 => text.push_str(&format!("{g}\n")),
                    1 => text.push_str(&format!("{g} G1 X{}.5 F{}\n", i % 9, 1 + next(900))),
                    _ => text.push_str(&format!("{} {g} Y{}\n", units[next(4) as usize], i % 7)),
                }
            }
            match next(5) {
                0 => text.push_str(&format!("G4 F{}.5\n", next(3))),
                1 | 2 => text.push_str(&format!("G1 X{}.25 Y{} F{}\n", i % 31, i % 11, 1 + next(2000))),
                _ => text.push_str(&format!("N{} Z-{}.5 F{}.5\n", 10 + i, i % 3, next(50))),
            }
        }
        text.push_str("M30\n");
        let path = dir.join(format!("feed{case}.mpf"));
        std::fs::write(&path, &text).expect("write");
        let (whole, streamed) = both(&path);
        let streamed = streamed.map_err(|e| format!("case {case}: {e:?}")).expect("streams");
        assert_eq!(String::from_utf8_lossy(&streamed), whole, "case {case}");
        assert!(whole.contains("/25.4]") && !whole.contains("*25.4]"), "case {case}: F conversions");
        let out = dir.join(format!("feed{case}.nc"));
        std::fs::write(&out, &streamed).expect("write");
        let popts = ParseOptions::for_dialect(Dialect::Sinumerik);
        let ix = nctrans::stream::scan_path(&path, 0, Dialect::Sinumerik, &popts, &mut |_, _| {}, None).expect("scan");
        let v = nctrans::stream::verify::verify(ix, &out, 1_000_000, Vec::new(), None);
        assert!(v.equivalent, "case {case}: {}", v.summary);
    }
}

#[test]
fn corpus_programs_stream_only_when_straight_and_then_identically() {
    let Ok(rd) = std::fs::read_dir(root().join("corpus/in/sinumerik")) else { return };
    let mut files: Vec<PathBuf> = rd.filter_map(|e| e.ok()).map(|e| e.path()).collect();
    files.sort();
    let (mut streamed, mut refused) = (0, 0);
    for f in files {
        match both(&f) {
            (whole, Ok(out)) => {
                assert_eq!(String::from_utf8_lossy(&out), whole, "{}", f.display());
                streamed += 1;
            }
            (_, Err(_)) => refused += 1,
        }
    }
    assert!(streamed > 0 && refused > 10, "{streamed} streamed, {refused} refused");
}

/// A line of the translation that no longer parses when the run re-reads it (the file
/// changed after it was read back and indexed) fails the check with the reader's own
/// diagnostic, in both directions; untouched, the same check is equivalent.
#[test]
fn an_output_line_broken_after_its_index_fails_the_check_with_its_diagnostic() {
    use nctrans::eval::{DirCallees, NoCallees, RunOptions};
    use nctrans::stream::target::sinumerik as sts;
    use nctrans::stream::verify::{self as sv, StreamSide};
    let dir = root().join("target/stream-tests");
    std::fs::create_dir_all(&dir).expect("dir");
    let mut sin = String::from("%_N_BROKEN_MPF\nG90 G71 G17\n");
    let mut fan = String::from("%\nO1000 (BROKEN)\nG90 G21 G17\n");
    for i in 0..20_000 {
        sin.push_str(&format!("G1 X{}.25 Y{}.5 F{}\n", i % 97, i % 13, 500 + i % 7));
        fan.push_str(&format!("G1 X{}.25 Y{}.5 F{}.\n", i % 97, i % 13, 500 + i % 7));
    }
    sin.push_str("M30\n");
    fan.push_str("M30\n%\n");
    for (dialect, text, ext) in [(Dialect::Sinumerik, &sin, "mpf"), (Dialect::Fanuc, &fan, "nc")] {
        let path = dir.join(format!("broken.{ext}"));
        std::fs::write(&path, text).expect("write");
        let out = dir.join(format!("broken-out.{ext}"));
        let (source, target) = match dialect {
            Dialect::Sinumerik => {
                let mut w = Vec::new();
                let s = st::to_fanuc(&path, &opts(&path, text), &mut w, None)
                    .map_err(|e| format!("{e:?}"))
                    .expect("streams");
                std::fs::write(&out, &w).expect("write");
                (s.index, Dialect::Fanuc)
            }
            Dialect::Fanuc => {
                let o = nctrans::translate::to_sinumerik::Options::default();
                let mut w = Vec::new();
                let s = sts::to_sinumerik(&path, &o, nctrans::read::LineEnding::Lf, &mut w, None)
                    .map_err(|e| format!("{e:?}"))
                    .expect("streams");
                std::fs::write(&out, &w).expect("write");
                (s.index, Dialect::Sinumerik)
            }
        };
        let popts = ParseOptions::for_dialect(target);
        let check = |source: nctrans::stream::Index| {
            let read = sv::read_back(&out, 1, target, &popts, None).ok().expect("reads back");
            (source, read)
        };
        let run = || RunOptions { max_steps: 1_000_000, ..RunOptions::default() };
        let side = |index, name: &str, dir: bool| StreamSide {
            index,
            name: name.to_string(),
            callees: if dir { Box::new(DirCallees { semantics: None }) } else { Box::new(NoCallees) },
            run: run(),
        };
        let (a, b) = check(source.clone());
        let r = sv::compare(side(a, "source", true), side(b, "output", false));
        assert!(matches!(r.verdict, nctrans::check::Verdict::Equivalent { .. }), "{ext}: {:?}", r.verdict);

        // Broken after reading back: a block in the middle gets a character no reader takes
        // (same size, so only re-reading the line can tell).
        let (a, b) = check(source);
        let written = std::fs::read(&out).expect("read");
        let at = written.len() / 2;
        let at = at + written[at..].iter().position(|&c| c == b'X').expect("an X word");
        let mut broken = written.clone();
        broken[at + 1] = b'$';
        std::fs::write(&out, &broken).expect("write");
        let r = sv::compare(side(a, "source", true), side(b, "output", false));
        assert!(!matches!(r.verdict, nctrans::check::Verdict::Equivalent { .. }), "{ext}: {:?}", r.verdict);
        let line = 1 + written[..at].iter().filter(|&&c| c == b'\n').count();
        let codes: Vec<String> = r.diags.iter().map(|d| format!("{} {}", d.code, d.message)).collect();
        let parse = r
            .diags
            .iter()
            .find(|d| d.code.starts_with("NC1"))
            .unwrap_or_else(|| panic!("{ext} line {line}: {codes:?}"));
        let span = parse.labels.iter().find(|l| l.primary).map(|l| l.span).expect("span");
        // On the broken line.
        let lo = written[..at].iter().rposition(|&c| c == b'\n').map_or(0, |i| i + 1);
        let hi = at + written[at..].iter().position(|&c| c == b'\n').unwrap_or(written.len() - at);
        assert!(
            lo <= span.lo as usize && span.hi as usize <= hi,
            "{ext}: {codes:?} at {span:?}, line {line} {lo}..{hi}"
        );
    }
}
