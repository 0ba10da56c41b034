//! Diagnostics of streamed files: a file read as a stream (`--stream`) reports its warnings
//! and errors exactly as the same file read whole, rendered from excerpts of the file, and
//! a warning no longer makes a large file fall back to being read whole.

use std::path::{Path, PathBuf};
use std::process::Command;

fn bin() -> &'static str {
    env!("CARGO_BIN_EXE_nctrans")
}

fn dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("nctrans-stream-diag-{}-{tag}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// (exit code, stdout, stderr) of `nctrans ARGS`.
fn run(args: &[&str]) -> (i32, String, String) {
    let o = Command::new(bin()).args(args).output().unwrap();
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stdout).into(),
        String::from_utf8_lossy(&o.stderr).into(),
    )
}

fn program(lines: usize, edits: &[(usize, &str)]) -> String {
    let mut v: Vec<String> = vec!["; streamed".into(), "G71 G90 G94".into()];
    v.extend((0..lines).map(|i| format!("N{} G1 X{}.5 Y-{} F{}", 10 * (i + 1), i % 97, i % 13, 500 + i % 5)));
    v.push("M30".into());
    for (at, text) in edits {
        v[*at] = text.to_string();
    }
    v.join("\n") + "\n"
}

fn same_both_ways(path: &Path, cmd: &str) -> (i32, String, String) {
    let p = path.to_str().unwrap();
    let streamed = run(&[cmd, "--stream", p]);
    let whole = run(&[cmd, p]);
    assert_eq!(streamed, whole, "{cmd} {p}: streamed and whole differ");
    streamed
}

#[test]
fn warnings_render_with_their_line_and_the_program_still_runs() {
    let d = dir("warn");
    let f = d.join("warn.mpf");
    std::fs::write(&f, program(3000, &[(2500, "N9999 G1 Ｘ10 Y2")])).unwrap();
    let (code, out, err) = same_both_ways(&f, "run");
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("warning[NC110]") && err.contains(":2501:"), "{err}");
    assert!(err.contains("2501 │ N9999 G1 Ｘ10 Y2"), "{err}");
    assert!(out.lines().count() > 3000, "the run went on");
    let (code, out, _) = same_both_ways(&f, "parse");
    assert_eq!(code, 0);
    assert!(!out.is_empty());
    let summary = run(&["parse", "--summary", "--stream", f.to_str().unwrap()]);
    assert!(summary.1.ends_with("3003 blocks, 1 warning(s)\n"), "{}", summary.1);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn errors_render_with_their_line_and_nothing_runs() {
    let d = dir("err");
    let f = d.join("err.mpf");
    std::fs::write(&f, program(3000, &[(40, "G1 X=(1+ Y2"), (2900, "ENDIF")])).unwrap();
    let (code, out, err) = same_both_ways(&f, "run");
    assert_eq!(code, 1, "{err}");
    assert!(out.is_empty(), "no trace for a program with errors: {out}");
    assert!(err.contains("error[NC121]") && err.contains(":41:"), "{err}");
    assert!(err.contains(":2901:"), "{err}");
    let (code, _, _) = same_both_ways(&f, "parse");
    assert_eq!(code, 1);
    let _ = std::fs::remove_dir_all(&d);
}

/// `--to fanuc` of a file with a byte-order mark: the streamed output keeps the mark, as the
/// whole-file output does, byte for byte.
#[test]
fn a_byte_order_mark_is_kept_by_the_streamed_translation() {
    let d = dir("bom");
    let f = d.join("bom.mpf");
    let mut bytes = b"\xEF\xBB\xBF".to_vec();
    bytes.extend_from_slice(program(500, &[]).as_bytes());
    std::fs::write(&f, &bytes).unwrap();
    let (s, w) = (d.join("s.nc"), d.join("w.nc"));
    let p = f.to_str().unwrap();
    let a = run(&["--to", "fanuc", "--stream", p, "-o", s.to_str().unwrap()]);
    let b = run(&["--to", "fanuc", p, "-o", w.to_str().unwrap()]);
    assert_eq!((a.0, b.0), (0, 0), "{}\n{}", a.2, b.2);
    let (s, w) = (std::fs::read(&s).unwrap(), std::fs::read(&w).unwrap());
    assert!(w.starts_with(b"\xEF\xBB\xBF%"));
    assert_eq!(s, w);
    let _ = std::fs::remove_dir_all(&d);
}

/// `--to fanuc --stream IN -o IN`: the input is never written (issue 16: it used to be
/// replaced by its translation), streamed or not.
#[test]
fn writing_over_the_input_is_refused() {
    let d = dir("over");
    let f = d.join("over.mpf");
    let text = program(300, &[]);
    std::fs::write(&f, &text).unwrap();
    let p = f.to_str().unwrap();
    for args in [&["--to", "fanuc", "--stream", p, "-o", p][..], &["--to", "fanuc", p, "-o", p, "--force"][..]] {
        let a = run(args);
        assert_eq!(a.0, 2, "{}", a.2);
        assert!(a.2.contains("error[NC602]"), "{}", a.2);
        assert_eq!(std::fs::read_to_string(&f).unwrap(), text);
    }
    let _ = std::fs::remove_dir_all(&d);
}
