//! The streaming readers and the straight-line stream translator on the external programs:
//! the words scan agrees with the index-only and whole-file scans, the fast line skeleton
//! and first scan with the general ones, and a Sinumerik program that streams gives exactly its whole
//! translation.

use crate::fast_same::{opts, same};
use crate::skeleton::{both_indexes, compare, dialect_of};
use crate::words_scan::{check, files, same_as_whole_parse};
use nctrans::dialect::fanuc::emit::CommentMode;
use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::span::SourceDb;
use nctrans::stream::target::fanuc as st;
use nctrans::translate;

#[test]
fn external_programs_scan_the_same_with_words() {
    let (mut words, mut n, mut whole) = (0, 0, 0);
    for f in files(&crate::external("")) {
        // Program files by their extension (the GUD `.DEF` file too); not the notes, licences and CSVs.
        let Some(d) = dialect_of(&f)
            .or_else(|| f.extension().is_some_and(|x| x.eq_ignore_ascii_case("def")).then_some(Dialect::Sinumerik))
        else {
            continue;
        };
        words += check(&f, d);
        whole += usize::from(same_as_whole_parse(&f, d));
        n += 1;
    }
    assert!(n > 50 && words > 0 && whole > 500, "{n} files, {words} lines as words, {whole} compared whole");
}

#[test]
fn external_siemens_programs_stream_only_to_their_whole_translation() {
    let files: Vec<_> = files(&crate::external("cead-sinumerik"))
        .into_iter()
        .filter(|p| p.extension().and_then(|x| x.to_str()).is_some_and(|x| x.eq_ignore_ascii_case("mpf")))
        .collect();
    assert!(files.len() >= 30, "expected the CEAD examples, found {}", files.len());
    let mut streamed = 0;
    for f in &files {
        let o = {
            let text = String::from_utf8_lossy(&std::fs::read(f).expect("read")).to_string();
            opts(f, &text, CommentMode::Keep)
        };
        let mut out = Vec::new();
        if st::to_fanuc(f, &o, &mut out, None).is_err() {
            continue;
        }
        let bytes = std::fs::read(f).expect("read");
        let mut db = SourceDb::new();
        let loaded = nctrans::load(&mut db, &f.display().to_string(), &bytes, None);
        let parsed =
            nctrans::parse(&db, loaded.file, Dialect::Sinumerik, &ParseOptions::for_dialect(Dialect::Sinumerik));
        let whole = translate::to_fanuc::to_fanuc(&parsed.unit, &[], &o);
        same(&f.display().to_string(), &out, &whole.text, &db.get(loaded.file).text);
        streamed += 1;
    }
    eprintln!("{streamed} of {} external programs streamed", files.len());
}

#[test]
fn external_lines_and_indexes_agree_with_the_general_readers() {
    let (mut lines, mut taken, mut compared) = (0, 0, 0);
    for f in files(&crate::external("")) {
        let Some(dialect) = dialect_of(&f) else { continue };
        let bytes = std::fs::read(&f).expect("read");
        for l in String::from_utf8_lossy(&bytes).split(['\n', '\r']) {
            compare(l, dialect == Dialect::Sinumerik, &mut taken);
            lines += 1;
        }
        for chunk in [1, 5, 2048] {
            let (fast, general) = both_indexes(&f, dialect, &bytes, chunk);
            assert_eq!(fast, general, "{} (chunks of {chunk})", f.display());
            compared += 1;
        }
    }
    assert!(lines > 1000 && taken > 100 && compared > 100, "{lines} lines, {taken} taken, {compared} scans");
}
