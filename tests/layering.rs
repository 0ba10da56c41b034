//! The layering of the top-level modules (docs/architecture.md, "Lowering and module
//! dependencies"): every `crate::<other>` a module's code names (`nctrans::<other>` in the
//! command line) must be in the module's row of [`ALLOWED`], and the table itself must have
//! no cycle, so no import cycle between top-level modules can come in unnoticed. Unit-test
//! modules (`#[cfg(test)] mod …`) are not counted: a test may build its input with any
//! lower layer's helpers.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// What each top-level module may use. Keep in step with the table in docs/architecture.md
/// and the "May use" line at the top of each folder's `mod.rs`.
const ALLOWED: &[(&str, &[&str])] = &[
    ("span", &[]),
    ("diag", &["span"]),
    ("read", &["diag", "span"]),
    ("excerpt", &["diag", "span", "stream"]),
    ("ir", &["span"]),
    ("dialect", &["ir", "read", "diag", "span"]),
    ("eval", &["dialect", "ir", "read", "diag", "span"]),
    ("gud", &["dialect", "ir", "diag", "span"]),
    ("lower", &["eval", "dialect", "ir", "read", "diag", "span"]),
    ("check", &["eval", "dialect", "ir", "diag", "span"]),
    ("unfinished", &["ir", "diag", "span"]),
    ("translate", &["check", "unfinished", "lower", "eval", "dialect", "ir", "read", "diag", "span"]),
    ("stream", &["translate", "check", "lower", "eval", "dialect", "ir", "read", "diag", "span"]),
    ("config", &["translate", "lower", "eval", "dialect", "ir", "read", "diag", "span"]),
    ("same_file", &[]),
    (
        "batch",
        &[
            "config",
            "stream",
            "translate",
            "check",
            "gud",
            "same_file",
            "lower",
            "eval",
            "dialect",
            "ir",
            "read",
            "diag",
            "span",
        ],
    ),
    (
        "cli",
        &[
            "batch",
            "config",
            "stream",
            "translate",
            "check",
            "gud",
            "unfinished",
            "excerpt",
            "same_file",
            "lower",
            "eval",
            "dialect",
            "ir",
            "read",
            "diag",
            "span",
        ],
    ),
];

/// Names at the crate root that are not modules (functions and types of `lib.rs`).
const ROOT_ITEMS: &[&str] = &["load", "parse", "detect_dialect", "Loaded", "test_rng"];

fn rs_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<_> = std::fs::read_dir(dir).expect("src folder").map(|e| e.unwrap().path()).collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            rs_files(&p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push(p);
        }
    }
}

/// The top-level module a file of `src/` belongs to (`None`: the crate root).
fn module_of(rel: &Path) -> Option<String> {
    let first = rel.components().next()?.as_os_str().to_str()?.to_string();
    let name = first.strip_suffix(".rs").unwrap_or(&first).to_string();
    match name.as_str() {
        "lib" => None,
        "main" => Some("cli".into()),
        // `read_tests.rs` is `read`'s unit tests.
        n => Some(n.strip_suffix("_tests").unwrap_or(n).to_string()),
    }
}

/// The code of a file without comments and without its unit-test modules.
fn code_lines(text: &str) -> Vec<&str> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < lines.len() {
        let t = lines[i].trim_start();
        if t.starts_with("#[cfg(test)]") {
            let next = lines.get(i + 1).map_or("", |l| l.trim_start());
            if next.starts_with("mod ") || next.starts_with("pub(crate) mod ") || next.starts_with("pub mod ") {
                if next.trim_end().ends_with(';') {
                    // A test module in its own file: that file is skipped (`test_files`).
                    i += 2;
                    continue;
                }
                // A test module in line: skip to its closing brace.
                let mut depth = 0i64;
                let mut j = i + 1;
                while j < lines.len() {
                    depth += lines[j].matches('{').count() as i64 - lines[j].matches('}').count() as i64;
                    j += 1;
                    if depth <= 0 && lines[j - 1].contains('}') {
                        break;
                    }
                }
                i = j;
                continue;
            }
        }
        if !t.starts_with("//") {
            out.push(lines[i].split(" // ").next().unwrap_or(""));
        }
        i += 1;
    }
    out
}

/// The files that `#[cfg(test)] mod name;` declares, by path relative to `src/`.
fn test_files(src: &Path, files: &[PathBuf]) -> BTreeSet<PathBuf> {
    let mut out = BTreeSet::new();
    for f in files {
        let text = std::fs::read_to_string(f).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        for w in lines.windows(2) {
            if !w[0].trim_start().starts_with("#[cfg(test)]") {
                continue;
            }
            let decl = w[1].trim();
            let Some(name) = decl.strip_suffix(';').and_then(|d| d.split_whitespace().last()) else { continue };
            if !decl.contains("mod ") {
                continue;
            }
            let dir = if f.file_name().is_some_and(|n| n == "mod.rs" || n == "lib.rs") {
                f.parent().unwrap().to_path_buf()
            } else {
                f.with_extension("")
            };
            let path_attr = lines
                .iter()
                .position(|l| std::ptr::eq(*l, w[1]))
                .and_then(|k| k.checked_sub(2).map(|k| lines[k].trim()))
                .and_then(|l| l.strip_prefix("#[path = \"").and_then(|l| l.strip_suffix("\"]")));
            let file = match path_attr {
                Some(p) => f.parent().unwrap().join(p),
                None if dir.join(format!("{name}.rs")).exists() => dir.join(format!("{name}.rs")),
                None => dir.join(name).join("mod.rs"),
            };
            if let Ok(rel) = file.strip_prefix(src) {
                out.insert(rel.to_path_buf());
            }
        }
    }
    out
}

/// The top-level modules named after `prefix` (`crate::`) on `line`, including the names in
/// a `crate::{a, b::c}` group.
fn named_after(line: &str, prefix: &str, out: &mut BTreeSet<String>) {
    let mut rest = line;
    while let Some(k) = rest.find(prefix) {
        let before = rest[..k].chars().last();
        rest = &rest[k + prefix.len()..];
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
            continue;
        }
        if let Some(group) = rest.strip_prefix('{') {
            let mut depth = 0;
            let mut item = String::new();
            let mut first = true;
            for c in group.chars() {
                match c {
                    '{' => depth += 1,
                    '}' if depth == 0 => break,
                    '}' => depth -= 1,
                    ',' if depth == 0 => {
                        first = true;
                        item.clear();
                        continue;
                    }
                    _ => {}
                }
                if depth == 0 && first {
                    if c.is_alphanumeric() || c == '_' {
                        item.push(c);
                        continue;
                    }
                    if !item.is_empty() {
                        out.insert(item.clone());
                        first = false;
                    }
                }
            }
            if first && !item.is_empty() {
                out.insert(item);
            }
            continue;
        }
        let name: String = rest.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
        if !name.is_empty() {
            out.insert(name);
        }
    }
}

/// Every top-level module's uses of the others: module → (used module → first file and line).
fn actual_uses() -> BTreeMap<String, BTreeMap<String, String>> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rs_files(&src, &mut files);
    let tests = test_files(&src, &files);
    let mut uses: BTreeMap<String, BTreeMap<String, String>> = BTreeMap::new();
    for f in &files {
        let rel = f.strip_prefix(&src).unwrap();
        if tests.contains(rel) {
            continue;
        }
        let Some(module) = module_of(rel) else { continue };
        let prefix = if module == "cli" { "nctrans::" } else { "crate::" };
        let text = std::fs::read_to_string(f).unwrap();
        for (n, line) in code_lines(&text).iter().enumerate() {
            let mut names = BTreeSet::new();
            named_after(line, prefix, &mut names);
            for used in names {
                if used == module || ROOT_ITEMS.contains(&used.as_str()) || (module == "cli" && used == "cli") {
                    continue;
                }
                uses.entry(module.clone())
                    .or_default()
                    .entry(used)
                    .or_insert_with(|| format!("src/{}:{}: {}", rel.display(), n + 1, line.trim()));
            }
        }
    }
    uses
}

fn allowed() -> BTreeMap<&'static str, BTreeSet<&'static str>> {
    ALLOWED.iter().map(|(m, deps)| (*m, deps.iter().copied().collect())).collect()
}

/// A cycle of `graph`, if it has one (depth-first, in name order).
fn find_cycle(graph: &BTreeMap<&str, BTreeSet<&str>>) -> Option<Vec<String>> {
    fn visit<'a>(
        n: &'a str,
        graph: &BTreeMap<&'a str, BTreeSet<&'a str>>,
        state: &mut BTreeMap<&'a str, u8>,
        path: &mut Vec<&'a str>,
    ) -> Option<Vec<String>> {
        match state.get(n) {
            Some(2) => return None,
            Some(1) => {
                let at = path.iter().position(|p| *p == n).unwrap();
                let mut c: Vec<String> = path[at..].iter().map(|s| s.to_string()).collect();
                c.push(n.to_string());
                return Some(c);
            }
            _ => {}
        }
        state.insert(n, 1);
        path.push(n);
        for m in graph.get(n).into_iter().flatten() {
            if let Some(c) = visit(m, graph, state, path) {
                return Some(c);
            }
        }
        path.pop();
        state.insert(n, 2);
        None
    }
    let mut state = BTreeMap::new();
    for n in graph.keys() {
        if let Some(c) = visit(n, graph, &mut state, &mut Vec::new()) {
            return Some(c);
        }
    }
    None
}

#[test]
fn every_module_uses_only_what_its_row_allows() {
    let allowed = allowed();
    let mut bad = Vec::new();
    for (module, used) in actual_uses() {
        let Some(row) = allowed.get(module.as_str()) else {
            bad.push(format!("{module}: a top-level module without a row in ALLOWED"));
            continue;
        };
        for (other, at) in used {
            if !row.contains(other.as_str()) {
                bad.push(format!("{module} may not use {other}: {at}"));
            }
        }
    }
    assert!(bad.is_empty(), "layering broken:\n{}", bad.join("\n"));
}

#[test]
fn the_table_has_no_cycle() {
    assert_eq!(find_cycle(&allowed()), None, "the allowed dependencies form a cycle");
}

#[test]
fn the_check_sees_a_use_of_a_higher_layer() {
    // The scanner itself: a `use crate::batch` in `translate` is a use of `batch`, in a group
    // too, and a comment or a unit-test module is not.
    let mut names = BTreeSet::new();
    named_after("use crate::batch::jobs::Target;", "crate::", &mut names);
    named_after("use crate::{stream::Out, cli};", "crate::", &mut names);
    named_after("let x = not_crate::config::X;", "crate::", &mut names);
    assert_eq!(names, ["batch", "cli", "stream"].into_iter().map(String::from).collect());
    let text =
        "use crate::ir::Unit;\n// crate::batch\n#[cfg(test)]\nmod tests {\n    use crate::batch;\n}\nfn f() {}\n";
    assert_eq!(code_lines(text), ["use crate::ir::Unit;", "fn f() {}"]);
    let row = allowed();
    assert!(!row["translate"].contains("batch") && !row["translate"].contains("stream"));
    let mut cyclic = row.clone();
    cyclic.get_mut("translate").unwrap().insert("batch");
    assert!(find_cycle(&cyclic).is_some(), "translate -> batch -> translate is a cycle");
}
