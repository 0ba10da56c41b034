//! The repository's documentation stands alone (issue 16): the README, `docs/`, the sources'
//! comments, diagnostics and `--help` texts cite only files that are in the repository (or
//! public manuals), never the project's working material beside it (`../shared`: reference
//! notes, the trace spec, seed documents), and every `*.md` they name exists.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The README, the docs, and every source and grammar file.
fn texts() -> Vec<PathBuf> {
    let mut out = vec![root().join("README.md")];
    let mut stack = vec![root().join("docs"), root().join("src"), root().join("grammar")];
    while let Some(d) = stack.pop() {
        for p in std::fs::read_dir(&d).unwrap().flatten().map(|e| e.path()) {
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "md" || x == "rs" || x == "pest") {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}

/// The `*.md` names a text mentions: `docs/x.md`, `[..](x.md)`, a bare `x.md`.
fn md_names(text: &str) -> Vec<String> {
    let mut names = Vec::new();
    for (i, _) in text.match_indices(".md") {
        if text[i + 3..].starts_with(|c: char| c.is_alphanumeric()) {
            continue;
        }
        let start = text[..i].rfind(|c: char| !(c.is_alphanumeric() || "_-./".contains(c))).map_or(0, |s| s + 1);
        let name = &text[start..i + 3];
        if name.len() > 3 {
            names.push(name.to_string());
        }
    }
    names
}

/// Whether `name`, as cited from `from`, is a file of the repository.
fn exists(name: &str, from: &Path) -> bool {
    let name = name.trim_start_matches("./");
    [root().join(name), root().join("docs").join(name), from.parent().unwrap().join(name)].iter().any(|p| p.is_file())
}

#[test]
fn no_text_points_outside_the_repository() {
    let mut bad = Vec::new();
    for f in texts() {
        let text = std::fs::read_to_string(&f).unwrap();
        let rel = f.strip_prefix(root()).unwrap().display().to_string();
        for (n, line) in text.lines().enumerate() {
            // The README names the external test target's folder; nothing else may.
            let outside = ["dialects.md", "shared/spec", "shared/reference", "shared/design", "shared/seeds"]
                .iter()
                .any(|s| line.contains(s))
                || (line.contains("../shared") && rel != "README.md");
            if outside {
                bad.push(format!("{rel}:{}: {}", n + 1, line.trim()));
            }
            for name in md_names(line) {
                if !exists(&name, &f) {
                    bad.push(format!("{rel}:{}: {name} is not in the repository", n + 1));
                }
            }
        }
    }
    assert!(bad.is_empty(), "texts that point outside the repository:\n{}", bad.join("\n"));
}

#[test]
fn help_texts_cite_files_of_the_repository() {
    for args in [&["--help"][..], &["run", "--help"], &["check", "--help"], &["parse", "--help"]] {
        let o = Command::new(env!("CARGO_BIN_EXE_nctrans")).args(args).output().unwrap();
        let help = String::from_utf8_lossy(&o.stdout);
        for name in md_names(&help) {
            assert!(
                root().join(&name).is_file(),
                "`nctrans {}` cites {name}, which is not in the repository",
                args.join(" ")
            );
        }
    }
    let o = Command::new(env!("CARGO_BIN_EXE_nctrans")).args(["run", "--help"]).output().unwrap();
    assert!(String::from_utf8_lossy(&o.stdout).contains("docs/trace-format.md"));
}
