//! Comparing what two batch runs left behind (shared by the batch streaming tests): the
//! output folder's files, the report without its timings, and the records and maps.

#![allow(dead_code)]

use std::collections::BTreeMap;
use std::path::Path;

/// Every file under `root` by its path relative to it (`/` separators), with its bytes.
pub fn snapshot(root: &Path) -> BTreeMap<String, Vec<u8>> {
    let mut out = BTreeMap::new();
    let mut stack = vec![root.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).expect("dir").filter_map(|e| e.ok()) {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else {
                let rel = p.strip_prefix(root).expect("below").to_string_lossy().replace('\\', "/");
                out.insert(rel, std::fs::read(&p).expect("read"));
            }
        }
    }
    out
}

/// A report line with its timings (`time_ms`, `elapsed_s`) written `_`.
pub fn untimed_line(l: &str) -> String {
    let mut l = l.to_string();
    for key in ["\"time_ms\": ", "\"elapsed_s\": "] {
        if let Some(i) = l.find(key) {
            let rest = &l[i + key.len()..];
            let end = rest.find([',', '}']).unwrap_or(rest.len());
            l = format!("{}_{}", &l[..i + key.len()], &rest[end..]);
        }
    }
    l
}

/// The report without its timings.
pub fn untimed(report: &str) -> String {
    report.lines().map(untimed_line).collect::<Vec<_>>().join("\n")
}

/// Two batch runs (result and output folder) with the same records, maps and files.
pub fn assert_same(
    a: &(nctrans::batch::BatchResult, BTreeMap<String, Vec<u8>>),
    b: &(nctrans::batch::BatchResult, BTreeMap<String, Vec<u8>>),
) {
    assert_eq!(a.0.files.len(), b.0.files.len());
    for (x, y) in a.0.files.iter().zip(&b.0.files) {
        let key = |f: &nctrans::batch::FileRecord| {
            (f.path.clone(), f.outputs.clone(), f.status, f.summary.clone(), f.events, f.blocks, f.diagnostics.clone())
        };
        assert_eq!(key(x), key(y), "{}", x.path);
    }
    assert_eq!(a.0.maps, b.0.maps, "the batch's maps");
    assert_eq!(a.1.keys().collect::<Vec<_>>(), b.1.keys().collect::<Vec<_>>());
    for (k, v) in &a.1 {
        assert!(
            b.1[k] == *v,
            "{k} differs:\n{}\n---\n{}",
            String::from_utf8_lossy(v),
            String::from_utf8_lossy(&b.1[k])
        );
    }
}
