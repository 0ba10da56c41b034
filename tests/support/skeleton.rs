//! The two comparisons of `tests/skeleton_diff.rs` on one line or file (shared with the
//! external programs' test): the fast line skeleton against the reader it stands for, and
//! the fast first scan's index against the general one's.

use nctrans::dialect::{fanuc, sinumerik, Dialect, ParseOptions};
use nctrans::stream::{self, lines::Input};
use std::path::Path;

/// The line ends `skeleton_bytes` sees after a line (the first starts none: it must decline).
pub const AFTER: &[&str] = &["", "\n", "\r\n", "\r", "\rG1 X2", "\nN5 G1", "\n\n"];

/// Whether `skeleton_bytes` may decline a line the old reader takes: not plain bytes (it
/// reads only those), and for FANUC a block skip or an N, G or M word of 16 or more digits.
fn may_decline(text: &str, siemens: bool) -> bool {
    let plain = text.bytes().all(|c| matches!(c, b'\t' | 0x0c | 0x1a | 0x20..=0x7e));
    if !plain {
        return true;
    }
    if siemens {
        return false;
    }
    let b = text.as_bytes();
    let mut run = 0;
    let long = b.iter().any(|c| {
        run = if c.is_ascii_digit() { run + 1 } else { 0 };
        run >= 16
    });
    text.contains('/') || long
}

/// Compares both readers on `text` with every line end after it; counts the lines both take.
pub fn compare(text: &str, siemens: bool, taken: &mut u64) {
    for after in AFTER {
        let (old, new) = if siemens {
            sinumerik::skeleton_both_for_test(text, after)
        } else {
            fanuc::skeleton_both_for_test(text, after)
        };
        if after.is_empty() {
            assert_eq!(new, None, "a line without its end: {text:?}");
            continue;
        }
        match (&old, &new) {
            (_, Some(_)) => assert_eq!(old, new, "{text:?} then {after:?}"),
            (Some(_), None) => assert!(may_decline(text, siemens), "declined {text:?} then {after:?}: {old:?}"),
            (None, None) => {}
        }
        *taken += u64::from(new.is_some());
    }
}

/// The dialect of a program file by its extension.
pub fn dialect_of(p: &Path) -> Option<Dialect> {
    match p.extension()?.to_str()?.to_ascii_lowercase().as_str() {
        "mpf" | "spf" => Some(Dialect::Sinumerik),
        "nc" => Some(Dialect::Fanuc),
        _ => None,
    }
}

/// The index of `bytes` by the fast first scan and by the general one, as debug text.
pub fn both_indexes(path: &Path, dialect: Dialect, bytes: &[u8], chunk_ops: usize) -> (String, String) {
    let opts = ParseOptions::for_dialect(dialect);
    let input = || Input::Mem(std::io::Cursor::new(bytes.to_vec()));
    let size = bytes.len() as u64;
    let fast = stream::scan_index(input(), size, path, 0, dialect, &opts, chunk_ops, None);
    let general = stream::scan_index_general(input(), size, path, 0, dialect, &opts, chunk_ops);
    (format!("{fast:?}"), format!("{general:?}"))
}
