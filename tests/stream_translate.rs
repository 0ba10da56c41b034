//! Streamed translation (Sinumerik → FANUC, straight-line programs) writes exactly what the
//! whole-program translator writes, over several chunks; programs that need whole-program
//! passes are refused (and translated whole by the CLI); a streamed verification agrees.

use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::span::SourceDb;
use nctrans::stream::translate::{self as st, Fallback};
use nctrans::translate::{self, TranslateOptions};
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
    let whole = translate::to_fanuc(&parsed.unit, &[], &o).text;
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
            2 => text.push_str(&format!("G1 Z-{}.5 A{}\n", i % 3, i % 360)),
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
    let v = st::verify(ix, &out, 1_000_000, None);
    assert!(v.equivalent && v.summary.contains("(10"), "{}", v.summary);

    // A broken translation is caught by the streamed verification.
    let bad = String::from_utf8_lossy(&streamed).replacen("X1.25", "X1.26", 1);
    assert_ne!(bad.as_bytes(), &streamed[..]);
    std::fs::write(&out, bad).expect("write");
    let ix = nctrans::stream::scan_path(&path, 0, Dialect::Sinumerik, &popts, &mut |_, _| {}, None).expect("scan");
    let v = st::verify(ix, &out, 1_000_000, None);
    assert!(!v.equivalent && v.summary.contains("diverged"), "{}", v.summary);
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
