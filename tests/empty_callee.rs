//! A call of a program whose file holds no program (issue 21, NC593): the empty file keeps
//! its own NC145, and the caller is told at its call site (file, line, column) that the called
//! program's file is empty: in a single-file translation, in a batch (the caller's status is
//! `error` naming that reason, not a parse error) and in a run, which stops when the call
//! executes, not before. Both directions alike.

#[path = "support/cli_run.rs"]
mod cli_run;

use cli_run::{nctrans, workdir};
use std::path::Path;

const FANUC_MAIN: &str = "%\nO0001 (MAIN)\nG0 X0. Y0. Z10.\nG1 X5. F100.\nM98 P60\nG0 X7.\nM30\n%\n";
/// A program header and nothing else, as in the real library's `1 VERH/O00060.nc`.
const FANUC_EMPTY: &str = "%\nO0060 (xxxxx)\n\n\n%";

const SIEMENS_MAIN: &str = "G0 X0 Y0 Z10\nG1 X5 F100\nPOCKET_A\nG0 X7\nCALL \"POCKET_B\"\nM30\n";

fn fanuc(name: &str) -> std::path::PathBuf {
    let d = workdir("empty-callee", name);
    std::fs::write(d.join("O0001.nc"), FANUC_MAIN).unwrap();
    std::fs::write(d.join("O0060.nc"), FANUC_EMPTY).unwrap();
    d
}

fn siemens(name: &str) -> std::path::PathBuf {
    let d = workdir("empty-callee", name);
    std::fs::write(d.join("MAIN.MPF"), SIEMENS_MAIN).unwrap();
    std::fs::write(d.join("POCKET_A.SPF"), "").unwrap();
    std::fs::write(d.join("POCKET_B.SPF"), "; nothing here yet\n").unwrap();
    d
}

/// One file's entry of the batch report (one line each), with its diagnostics as
/// (code, message, file, line, column).
struct Entry {
    text: String,
    diags: Vec<(String, String, String, u64, u64)>,
}

impl Entry {
    fn field(&self, key: &str) -> String {
        field(&self.text, key)
    }
}

/// A string or number field's value, the first after `key` in `s`.
fn field(s: &str, key: &str) -> String {
    let at = s.find(&format!("\"{key}\": ")).unwrap_or_else(|| panic!("{key} in {s}")) + key.len() + 4;
    let rest = &s[at..];
    match rest.strip_prefix('"') {
        Some(r) => r[..r.find('"').unwrap()].to_string(),
        None => rest[..rest.find([',', '}']).unwrap()].to_string(),
    }
}

fn entry(d: &Path, path: &str) -> Entry {
    let report = std::fs::read_to_string(d.join("r.json")).unwrap();
    let line = report
        .lines()
        .find(|l| l.contains(&format!("{{\"path\": \"{path}\"")))
        .unwrap_or_else(|| panic!("{path} in {report}"));
    let diags = line
        .split("{\"severity\": ")
        .skip(1)
        .map(|d| {
            let n = |k: &str| field(d, k).parse().unwrap_or(0);
            (field(d, "code"), field(d, "message"), field(d, "file"), n("line"), n("column"))
        })
        .collect();
    Entry { text: line.to_string(), diags }
}

#[test]
fn fanuc_translation_names_the_empty_callee_at_the_call() {
    let d = fanuc("fanuc_single");
    for extra in [&[][..], &["--stream"][..]] {
        let args: Vec<&str> = ["--to", "sinumerik", "O0001.nc", "-o", "out/"].iter().chain(extra).copied().collect();
        let (_, err, code) = nctrans(&d, &args);
        assert_ne!(code, 0, "{args:?}");
        assert!(
            err.contains("error[NC593]: the called program O0060 is in ./O0060.nc, but that file holds no program"),
            "{args:?}\n{err}"
        );
        assert!(err.contains("┌─ O0001.nc:5:1") && err.contains("calls O0060"), "{err}");
        assert!(err.contains("┌─ ./O0060.nc:1:1") && err.contains("alarm on the control"), "{err}");
        assert!(!err.contains("error[NC145]"), "{err}");
        assert!(!d.join("out").exists());
    }
    // The empty file itself is still NC145.
    let (_, err, code) = nctrans(&d, &["--to", "sinumerik", "O0060.nc", "-o", "o60/"]);
    assert_ne!(code, 0);
    assert!(err.contains("error[NC145]") && !err.contains("NC593"), "{err}");
}

#[test]
fn fanuc_run_stops_at_the_call_not_before() {
    let d = fanuc("fanuc_run");
    let (out, err, code) = nctrans(&d, &["run", "O0001.nc"]);
    assert_ne!(code, 0);
    // The blocks before the call ran.
    assert!(out.contains("move linear X=5"), "{out}");
    assert!(!out.contains("X=7"), "{out}");
    assert!(err.contains("error[NC593]") && err.contains("┌─ O0001.nc:5:1"), "{err}");
    // A call in a branch not taken does not stop the run.
    std::fs::write(
        d.join("O0002.nc"),
        FANUC_MAIN.replace("M98 P60", "IF [#1 EQ 1] GOTO 10\nGOTO 20\nN10 M98 P60\nN20"),
    )
    .unwrap();
    let (out, err, code) = nctrans(&d, &["run", "O0002.nc"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("X=7"), "{out}");
    let (_, err, code) = nctrans(&d, &["run", "O0002.nc", "--set", "#1=1"]);
    assert_ne!(code, 0);
    assert!(err.contains("error[NC593]") && err.contains("┌─ O0002.nc:7:5"), "{err}");
}

#[test]
fn fanuc_batch_gives_the_caller_the_reason() {
    let d = fanuc("fanuc_batch");
    std::fs::create_dir_all(d.join("lib")).unwrap();
    for f in ["O0001.nc", "O0060.nc"] {
        std::fs::rename(d.join(f), d.join("lib").join(f)).unwrap();
    }
    // An empty file without even a header: known by its name only.
    std::fs::write(d.join("lib/O0001.nc"), FANUC_MAIN.replace("G0 X7.", "G65 P61 A1.\nG0 X7.")).unwrap();
    std::fs::write(d.join("lib/O0061.nc"), "").unwrap();
    let (out, err, code) = nctrans(&d, &["--to", "sinumerik", "-o", "out/", "lib", "--report", "r.json"]);
    assert_ne!(code, 0);
    let main = entry(&d, "O0001.nc");
    let t = &main.text;
    assert_eq!(main.field("status"), "error", "{t}");
    assert!(
        main.field("summary").starts_with("the called program O0060 is in O0060.nc, but that file holds no program"),
        "{t}"
    );
    assert_eq!(main.diags.len(), 2, "{t}");
    assert!(main.diags.iter().all(|x| x.0 == "NC593" && x.2 == "O0001.nc"), "{t}");
    assert_eq!((main.diags[0].3, main.diags[0].4), (5, 1), "{t}");
    assert!(main.diags[1].1.contains("O0061 is in O0061.nc") && main.diags[1].3 == 6, "{t}");
    for empty in ["O0060.nc", "O0061.nc"] {
        let e = entry(&d, empty);
        assert_eq!(e.field("status"), "parse-error", "{}", e.text);
        assert_eq!(e.diags[0].0, "NC145", "{}", e.text);
    }
    // The worst files name it too.
    assert!(format!("{out}{err}").contains("O0001.nc  NC593 line 5"), "{out}{err}");
}

#[test]
fn siemens_translation_names_the_empty_callee_at_the_call() {
    let d = siemens("siemens_single");
    for extra in [&[][..], &["--stream"][..]] {
        let args: Vec<&str> = ["--to", "fanuc", "MAIN.MPF", "-o", "main.nc"].iter().chain(extra).copied().collect();
        let (_, err, code) = nctrans(&d, &args);
        assert_ne!(code, 0, "{args:?}");
        let a = err.find("the called program POCKET_A is in ./POCKET_A.SPF, but that file holds no program");
        let b = err.find("the called program POCKET_B is in ./POCKET_B.SPF, but that file holds no program");
        // In source order.
        assert!(a.is_some() && b.is_some() && a < b, "{args:?}\n{err}");
        assert!(err.contains("┌─ MAIN.MPF:3:1") && err.contains("┌─ MAIN.MPF:5:1"), "{err}");
        assert!(!err.contains("error[NC145]"), "{err}");
        assert!(!d.join("main.nc").exists());
    }
}

#[test]
fn siemens_run_stops_at_the_call_not_before() {
    let d = siemens("siemens_run");
    let (out, err, code) = nctrans(&d, &["run", "MAIN.MPF"]);
    assert_ne!(code, 0);
    assert!(out.contains("move linear X=5"), "{out}");
    assert!(!out.contains("X=7"), "{out}");
    assert!(err.contains("error[NC593]: the called program POCKET_A"), "{err}");
    assert!(err.contains("┌─ MAIN.MPF:3:1"), "{err}");
}

#[test]
fn siemens_batch_gives_the_caller_the_reason() {
    let d = siemens("siemens_batch");
    std::fs::create_dir_all(d.join("lib")).unwrap();
    for f in ["MAIN.MPF", "POCKET_A.SPF", "POCKET_B.SPF"] {
        std::fs::rename(d.join(f), d.join("lib").join(f)).unwrap();
    }
    let (_, _, code) = nctrans(&d, &["--to", "fanuc", "-o", "out/", "lib", "--report", "r.json"]);
    assert_ne!(code, 0);
    let main = entry(&d, "MAIN.MPF");
    let t = &main.text;
    assert_eq!(main.field("status"), "error", "{t}");
    assert!(main.field("summary").contains("POCKET_A is in POCKET_A.SPF"), "{t}");
    let lines: Vec<_> = main.diags.iter().map(|x| (x.0.as_str(), x.3)).collect();
    assert_eq!(lines, [("NC593", 3), ("NC593", 5)], "{t}");
    assert_eq!(entry(&d, "POCKET_A.SPF").diags[0].0, "NC145");
    // A real parse error in the caller stays a parse error, with the call named too.
    std::fs::write(d.join("lib/MAIN.MPF"), SIEMENS_MAIN.replace("G0 X7", "G0 X=")).unwrap();
    let (_, _, _) = nctrans(&d, &["--to", "fanuc", "-o", "out2/", "lib", "--report", "r.json"]);
    let main = entry(&d, "MAIN.MPF");
    assert_eq!(main.field("status"), "parse-error", "{}", main.text);
    assert!(main.diags.iter().any(|x| x.0 == "NC593"), "{}", main.text);
}

/// The real library: `(SHABLON 2)/(SHABLON 2)/O00998.nc` calls O0060 (`M98 P [ 60 ]`, line
/// 20), whose file `1 VERH/O00060.nc` is a header alone, and O0080 (`3 FASKA/O00080.nc`).
#[test]
fn the_real_library_names_the_empty_callees_of_its_main_program() {
    let lib =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/external/rcod2-haas/programs/(SHABLON 2)/(SHABLON 2)");
    if !lib.join("O00998.nc").exists() {
        eprintln!("skipped: {} is not here", lib.display());
        return;
    }
    let d = workdir("empty-callee", "real");
    std::fs::write(d.join("nctrans.toml"), "[fanuc]\nseries = \"haas-ngc\"\n").unwrap();
    let (_, _, _) = nctrans(&d, &["--to", "sinumerik", "-o", "out/", lib.to_str().unwrap(), "--report", "r.json"]);
    let main = entry(&d, "O00998.nc");
    let t = &main.text;
    assert_eq!(main.field("status"), "error", "{t}");
    let first = &main.diags[0];
    assert!(first.0 == "NC593" && first.1.contains("O0060 is in 1 VERH/O00060.nc"), "{t}");
    assert_eq!((first.2.as_str(), first.3, first.4), ("O00998.nc", 20, 1), "{t}");
    assert!(main.diags.iter().any(|x| x.1.contains("O0080 is in 3 FASKA/O00080.nc")), "{t}");
    assert_eq!(entry(&d, "1 VERH/O00060.nc").diags[0].0, "NC145");
}
