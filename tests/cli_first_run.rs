//! What a new user meets first (issue 16, items 5–7): a program-less file is one diagnostic
//! in every command, a subprogram after the closing `%` is warned about and named as such,
//! and a file already in the target dialect is told so (never read as the other dialect).

#[path = "support/cli_run.rs"]
mod cli_run;

use cli_run::nctrans;
use std::path::PathBuf;

fn workdir(name: &str) -> PathBuf {
    cli_run::workdir("first-run", name)
}

const NC145: &str = "error[NC145]: the file holds no program: nothing to run, check or translate";

#[test]
fn a_program_less_file_is_nc145_in_every_command_and_both_dialects() {
    let dir = workdir("empty");
    let files: [(&str, &str); 10] = [
        ("empty.MPF", ""),
        ("blank.MPF", "\n\n  \n"),
        ("comment.MPF", "; only a comment\n"),
        ("header.MPF", "%_N_PART_MPF\n;$PATH=/_N_MPF_DIR\n"),
        ("percent.MPF", "%\n"),
        ("empty.nc", ""),
        ("blank.nc", "\r\n\r\n"),
        ("comment.nc", "(ONLY A COMMENT)\n"),
        ("percent.nc", "%\n%\n"),
        ("header.nc", "%\nO1000 (PART)\n%\n"),
    ];
    for (name, text) in files {
        std::fs::write(dir.join(name), text).expect("write");
        let commands: [Vec<&str>; 8] = [
            vec!["parse", name],
            vec!["parse", "--summary", name],
            vec!["run", name],
            vec!["run", "--stream", name],
            vec!["check", name, name],
            vec!["--to", "fanuc", name],
            vec!["--to", "sinumerik", name],
            vec!["--to", "fanuc", "--stream", name],
        ];
        for args in commands {
            let (out, err, code) = nctrans(&dir, &args);
            assert!(code != 0, "{args:?} succeeded:\n{out}\n{err}");
            assert!(err.contains(NC145), "{args:?}:\n{err}");
            assert!(!out.contains("equivalent") && !err.contains("equivalent"), "{args:?}:\n{out}{err}");
        }
    }
    // A batch reports each of them with the same code, in both directions.
    for (to, ext) in [("fanuc", "MPF"), ("sinumerik", "nc")] {
        let lib = dir.join(format!("lib-{to}"));
        std::fs::create_dir_all(&lib).expect("lib");
        std::fs::write(lib.join(format!("empty.{ext}")), "").expect("write");
        let report = dir.join(format!("report-{to}.json"));
        let (out, err, code) = nctrans(
            &dir,
            &["--to", to, "-o", &format!("out-{to}"), "--report", report.to_str().unwrap(), lib.to_str().unwrap()],
        );
        assert_eq!(code, 1, "{out}{err}");
        assert!(!out.contains("every file verified"), "{out}");
        let json = std::fs::read_to_string(&report).expect("report");
        assert!(json.contains("NC145"), "{json}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn an_empty_program_in_a_fanuc_file_is_refused_before_it_becomes_a_program_less_file() {
    // O1053 is empty, O10 is not: the file is not program-less, but O1053's Siemens file would
    // be (and every later command on it would stop at NC145).
    let dir = workdir("empty-program");
    std::fs::write(dir.join("two.nc"), "%\nO1053\n(EMPTY)\nO10\n#1=2\nM99\n%\n").expect("write");
    let (out, err, code) = nctrans(&dir, &["--to", "sinumerik", "two.nc"]);
    assert_eq!(code, 1, "{out}{err}");
    assert!(err.contains("error[NC146]: program O1053 holds no block to translate"), "{err}");
    assert!(out.is_empty(), "{out}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_file_with_only_a_comment_before_a_real_program_still_translates() {
    // The NC145 check looks at the whole file: comments in front of a program are fine.
    let dir = workdir("not-empty");
    std::fs::write(dir.join("part.MPF"), "; title\n\nG0 X1\nM30\n").expect("write");
    let (out, err, code) = nctrans(&dir, &["--to", "fanuc", "part.MPF"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("M30") && err.contains("equivalent"), "{out}{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

const AFTER_END: &str = "%\nO1000\nG65 P9100 A1.\nM30\n%\nO9100\n#100=#1\nM99\n%\n";

#[test]
fn a_subprogram_after_the_closing_percent_is_warned_about_and_named_in_every_command() {
    let dir = workdir("after-end");
    std::fs::write(dir.join("main.nc"), AFTER_END).expect("write");
    for args in [vec!["parse", "main.nc"], vec!["run", "main.nc"], vec!["--to", "sinumerik", "main.nc"]] {
        let (_, err, _) = nctrans(&dir, &args);
        assert!(err.contains("warning[NC237]: text after the closing `%` is not read"), "{args:?}:\n{err}");
    }
    let (_, err, code) = nctrans(&dir, &["--to", "sinumerik", "main.nc"]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("error[NC353]: the called program O9100 was not found"), "{err}");
    assert!(err.contains("O9100 is in the file, but after the closing `%`"), "{err}");
    // A program really missing keeps the hint to put it beside.
    std::fs::write(dir.join("missing.nc"), "%\nO1000\nG65 P9200 A1.\nM30\n%\n").expect("write");
    let (_, err, _) = nctrans(&dir, &["--to", "sinumerik", "missing.nc"]);
    assert!(err.contains("beside it as O9200.nc") && !err.contains("after the closing"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_file_in_the_target_dialect_is_told_so_with_how_that_was_decided() {
    let dir = workdir("direction");
    std::fs::write(dir.join("keep.MPF"), "G1 X10 F100\nM30\n").expect("write");
    std::fs::write(dir.join("keep"), "R1=10\nG1 X=R1 F100\nM30\n").expect("write");
    std::fs::write(dir.join("part.nc"), "O1000\n#1=10\nG1 X#1 F100\nM30\n").expect("write");
    // Before: read as FANUC and "translated" into `G1 X0.01`, called equivalent.
    let (out, err, code) = nctrans(&dir, &["--to", "sinumerik", "keep.MPF"]);
    assert_eq!(code, 2, "{out}{err}");
    assert!(out.is_empty() && !err.contains("equivalent"), "{out}{err}");
    assert!(
        err.contains("keep.MPF is a Sinumerik program (from its extension .MPF)")
            && err.contains("--to sinumerik translates FANUC → Sinumerik"),
        "{err}"
    );
    assert!(err.contains("nctrans --to fanuc keep.MPF") && err.contains("--from fanuc"), "{err}");
    let (_, err, code) = nctrans(&dir, &["--to", "sinumerik", "keep"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("keep is a Sinumerik program (judged from its content"), "{err}");
    let (_, err, code) = nctrans(&dir, &["--to", "fanuc", "part.nc"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("part.nc is a FANUC program (from its extension .nc)")
            && err.contains("--to fanuc translates Sinumerik → FANUC"),
        "{err}"
    );
    assert!(!err.contains("only Sinumerik"), "{err}");
    // An explicit --from reads it as said.
    let (out, err, code) = nctrans(&dir, &["--to", "sinumerik", "--from", "fanuc", "keep.MPF"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("G1 X0.01"), "{out}");
    let (_, err, code) = nctrans(&dir, &["--to", "fanuc", "--from", "fanuc", "part.nc"]);
    assert!(code == 2 && err.contains("(as given by --from)"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_batch_names_the_files_it_leaves_alone_and_how_their_dialect_was_decided() {
    let dir = workdir("batch-skip");
    let lib = dir.join("lib");
    std::fs::create_dir_all(&lib).expect("lib");
    std::fs::write(lib.join("part.MPF"), "R1=10\nG1 X=R1 F100\nM30\n").expect("write");
    std::fs::write(lib.join("done.nc"), "O1000\nG1 X10. F100.\nM30\n").expect("write");
    let (out, err, code) = nctrans(&dir, &["--to", "fanuc", "-o", "out", "lib"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(err.contains("note: left alone: done.nc (already fanuc, by its extension .nc)"), "{err}");
    assert!(!dir.join("out/done.nc").exists());
    let (_, err, _) = nctrans(&dir, &["--to", "fanuc", "--from", "sinumerik", "-o", "out2", "lib"]);
    assert!(err.contains("--from sinumerik applies to a single file"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// The README's first command, word for word as its set-up section gives it (after
/// `cargo run --release --`): it must keep translating and proving.
#[test]
fn the_readme_first_command_translates_and_proves() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(root.join("README.md")).expect("README.md");
    let line = readme.lines().find(|l| l.starts_with("cargo run --release -- ")).expect("the README's first command");
    let args: Vec<&str> = line.trim_start_matches("cargo run --release -- ").split_whitespace().collect();
    let (out, err, code) = nctrans(&root, &args);
    assert_eq!(code, 0, "{line}\n{err}");
    assert!(out.contains("WHILE") || out.contains("GOTO"), "{out}");
    let said = readme.lines().skip_while(|l| !l.starts_with("The first translates")).take(4).collect::<String>();
    let events = err.lines().find(|l| l.starts_with("equivalent")).unwrap_or_default().to_string();
    assert!(
        !events.is_empty() && said.contains(&format!("`{events}`")),
        "README says {said:?}, the run says {events:?}"
    );
}
