//! Helpers of the straight-line stream translator's tests (`tests/stream_translate_fast.rs`
//! and the external programs' test): the options a file is translated with, and a
//! comparison of the streamed bytes with the whole translation that names the first line
//! that differs.

use nctrans::dialect::fanuc::emit::CommentMode;
use nctrans::translate::to_fanuc::TranslateOptions;
use std::path::Path;

/// The options `nctrans --to fanuc` translates `path` (decoded to `text`) with.
pub fn opts(path: &Path, text: &str, comments: CommentMode) -> TranslateOptions {
    TranslateOptions {
        main_name: path.file_stem().and_then(|s| s.to_str()).unwrap_or("MAIN").to_ascii_uppercase(),
        source_name: path.file_name().and_then(|s| s.to_str()).unwrap_or("").to_string(),
        line_ending: nctrans::read::detect_line_ending(text),
        comments,
        ..TranslateOptions::default()
    }
}

/// Asserts `out == whole`, naming the first line that differs and its source lines.
pub fn same(what: &str, out: &[u8], whole: &str, source: &str) {
    let out = String::from_utf8_lossy(out);
    if out == whole {
        return;
    }
    let (a, b): (Vec<&str>, Vec<&str>) = (out.lines().collect(), whole.lines().collect());
    let k = a.iter().zip(&b).position(|(x, y)| x != y).unwrap_or(a.len().min(b.len()));
    let near: Vec<&str> = source.lines().skip(k.saturating_sub(4)).take(6).collect();
    panic!(
        "{what}: line {}: streamed {:?}, whole {:?}\nsource near it:\n{}",
        k + 1,
        a.get(k),
        b.get(k),
        near.join("\n")
    );
}
