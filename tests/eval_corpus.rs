//! Every `corpus/in/<dialect>/*` program runs in the evaluator and its text trace matches
//! `corpus/out/trace/<dialect>/<name>.trace` (`NCTRANS_BLESS=1` rewrites; review the diff).
//! Runs stop at 100 000 blocks so that a program that loops forever (the seed O9051
//! waits for #3 to change) ends quickly with a `limit` event. Each drilling-cycle program
//! (one whose trace has a `cycle` event) also has its `nctrans run --expand-cycles` trace,
//! `<name>.expanded.trace`, with the default profile's retract amounts.

mod eval_support;

use eval_support::*;
use std::fs;

#[test]
fn corpus_traces_match() {
    let mut failures = Vec::new();
    let mut count = 0;
    for (_, d) in dialect_dirs() {
        let dir = root().join("corpus/in").join(d);
        let Ok(rd) = fs::read_dir(&dir) else { continue };
        let mut files: Vec<_> = rd.filter_map(|e| e.ok()).map(|e| e.path()).filter(|p| p.is_file()).collect();
        files.sort();
        for f in files {
            let rel = f.strip_prefix(root()).unwrap_or(&f).to_path_buf();
            let name = f.file_name().unwrap_or_default().to_string_lossy().to_string();
            let mut drills = false;
            for expand in [false, true] {
                if expand && !drills {
                    break;
                }
                // Tests run with the package root as the working directory, so `rel` opens.
                let ran = run_file_expanding(&rel, &[], 100_000, expand);
                if ran.parse_errors.is_some() {
                    // The parser harness reports it; nothing to run.
                    continue;
                }
                count += 1;
                let suffix = if expand { "expanded.trace" } else { "trace" };
                let out = root().join("corpus/out/trace").join(d).join(format!("{name}.{suffix}"));
                drills = ran.sink.events.iter().any(|e| matches!(e, nctrans::eval::Event::Cycle(_)));
                let actual = ran.text();
                if bless() {
                    fs::create_dir_all(out.parent().expect("parent")).expect("mkdir");
                    fs::write(&out, &actual).expect("write trace");
                    continue;
                }
                match fs::read_to_string(&out) {
                    Ok(expected) if expected == actual => {}
                    Ok(expected) => failures.push(format!(
                        "{}: trace differs\n{}",
                        rel.display(),
                        similar::TextDiff::from_lines(&expected, &actual).unified_diff().header("committed", "actual")
                    )),
                    Err(_) => failures.push(format!("{}: no committed trace {}", rel.display(), out.display())),
                }
            }
        }
    }
    assert!(count > 0 || !root().join("corpus/in").exists(), "no corpus program ran");
    assert!(
        failures.is_empty(),
        "{} corpus trace(s) differ (NCTRANS_BLESS=1 to rewrite):\n{}",
        failures.len(),
        failures.join("\n")
    );
}
