//! The library corpus (issue 21): two program libraries in the style shops keep them,
//! written for this project. `corpus/in/library-sinumerik/` is a machine builder's Siemens
//! library (global user data and macros in `DEF/`, subprograms called by name, CASE without
//! parentheses, spindle-addressed words, computed messages) with its `nctrans.toml` (tool
//! names, where the global data lives on FANUC); `corpus/in/library-fanuc/` is a Haas NGC
//! shop's templates (G65 macros with vacancy checks, M97/M98 subprograms, Haas IF forms,
//! NGC variables, the part counter). Every program parses and runs with the library's
//! profile; the whole folder is translated as a batch with verification, and what each file
//! became (verified, or refused with the codes that name why) is committed in
//! `corpus/out/library-<target>/status.txt` beside the outputs. `NCTRANS_BLESS=1` rewrites
//! them.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn bless() -> bool {
    std::env::var_os("NCTRANS_BLESS").is_some_and(|v| v != "0")
}

fn nctrans(dir: &Path, args: &[&str]) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_nctrans")).args(args).current_dir(dir).output().expect("run nctrans");
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stderr).into_owned())
}

/// The program files of a library folder (not its profile), relative, sorted.
fn programs(dir: &Path) -> Vec<String> {
    let mut v = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).expect("library folder").flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else if p
                .extension()
                .is_some_and(|x| ["mpf", "spf", "nc"].contains(&x.to_ascii_lowercase().to_str().unwrap_or("")))
            {
                v.push(p.strip_prefix(dir).unwrap_or(&p).to_string_lossy().replace('\\', "/"));
            }
        }
    }
    v.sort();
    v
}

/// `corpus/out/<out>/<rel>` compared with `actual` (or written when blessing).
fn golden(out: &str, rel: &str, actual: &str, failures: &mut Vec<String>) {
    let path = root().join("corpus/out").join(out).join(rel);
    if bless() {
        std::fs::create_dir_all(path.parent().unwrap_or(&root())).expect("output folder");
        std::fs::write(&path, actual).expect("write golden");
        return;
    }
    match std::fs::read_to_string(&path) {
        Ok(e) if e == actual => {}
        Ok(e) => {
            let diff =
                similar::TextDiff::from_lines(e.as_str(), actual).unified_diff().header("committed", "now").to_string();
            failures.push(format!("{}: differs\n{diff}", path.display()));
        }
        Err(_) => failures.push(format!("{}: missing (run with NCTRANS_BLESS=1 and review)", path.display())),
    }
}

fn library(name: &str, to: &str, out: &str) {
    let dir = root().join("corpus/in").join(name);
    let progs = programs(&dir);
    assert!(progs.len() >= 60, "{name} holds {} programs", progs.len());
    let mut failures = Vec::new();
    // Each program reads with the library's profile; a run either ends or stops with the
    // control's alarm (a macro run alone without its arguments alarms, as on the machine).
    let mut runs = std::collections::BTreeMap::new();
    for p in &progs {
        let (code, err) = nctrans(&dir, &["parse", "--summary", p]);
        if code != 0 {
            failures.push(format!("{p}: does not parse:\n{err}"));
        }
        let (code, err) = nctrans(&dir, &["run", "--quiet", p]);
        let how = match code {
            0 => "runs".to_string(),
            3 => "run ends in an alarm".to_string(),
            4 => "run stops at a limit".to_string(),
            _ => {
                let first = err.lines().find_map(|l| l.strip_prefix("error[")).and_then(|l| l.split(']').next());
                format!("run refused {}", first.unwrap_or("?"))
            }
        };
        runs.insert(p.clone(), how);
    }
    let tmp = std::env::temp_dir().join(format!("nctrans-library-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&tmp);
    let report = tmp.join("report.json");
    let (_, err) = nctrans(
        &dir,
        &["--to", to, "-o", &tmp.join("out").to_string_lossy(), ".", "--report", &report.to_string_lossy()],
    );
    let text = std::fs::read_to_string(&report).unwrap_or_else(|_| panic!("no report:\n{err}"));
    let mut status = String::new();
    let mut verified = 0;
    // The report writes one file per line: its path, status and diagnostics.
    let field = |line: &str, key: &str| -> String {
        let k = format!("\"{key}\": \"");
        line.find(&k).map_or(String::new(), |i| line[i + k.len()..].split('"').next().unwrap_or("").to_string())
    };
    for line in text.lines().filter(|l| l.trim_start().starts_with("{\"path\": ")) {
        let path = field(line, "path").replace("\\\\", "/");
        let st = field(line, "status");
        let mut codes: Vec<String> = line
            .split("{\"severity\": \"error\", \"code\": \"")
            .skip(1)
            .filter_map(|rest| rest.split('"').next().map(str::to_string))
            .collect();
        codes.sort();
        codes.dedup();
        if st == "verified" {
            verified += 1;
        } else if codes.is_empty() {
            failures.push(format!("{path}: {st} without a diagnostic naming why"));
        }
        let run = runs.get(&path).map_or("", String::as_str);
        status.push_str(&format!("{path}\t{st}\t{}\t{run}\n", codes.join(" ")));
    }
    status.push_str(&format!("# {verified} of {} verified\n", progs.len()));
    golden(out, "status.txt", &status, &mut failures);
    let mut outputs = Vec::new();
    let mut stack = vec![tmp.join("out")];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).into_iter().flatten().flatten() {
            if e.path().is_dir() {
                stack.push(e.path());
            } else {
                outputs.push(e.path());
            }
        }
    }
    outputs.sort();
    for o in outputs {
        let rel = o.strip_prefix(tmp.join("out")).unwrap_or(&o).to_string_lossy().replace('\\', "/");
        golden(out, &format!("files/{rel}"), &std::fs::read_to_string(&o).unwrap_or_default(), &mut failures);
    }
    let _ = std::fs::remove_dir_all(&tmp);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn the_siemens_library_reads_runs_and_translates_to_fanuc() {
    library("library-sinumerik", "fanuc", "library-fanuc-from-sinumerik");
}

#[test]
fn the_haas_library_reads_runs_and_translates_to_sinumerik() {
    library("library-fanuc", "sinumerik", "library-sinumerik-from-fanuc");
}
