//! Sinumerik → FANUC translation of main programs with the subprograms they call, found
//! beside them: every folder of `corpus/in/sinumerik-calls/` holds main programs (`.MPF`)
//! and their subprograms (`.SPF`). Each main is translated by the command line as a user
//! runs it, whole and `--stream`, and verified; outputs are committed under
//! `corpus/out/fanuc-calls/<folder>/` (`NCTRANS_BLESS=1` rewrites them). Mains listed in
//! [`REFUSED`] must be refused with their code. The modes a subprogram changes or restores
//! (SAVE) are what these programs exercise.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Mains that cannot be translated, with the diagnostic that says why.
const REFUSED: &[(&str, &str)] = &[
    ("units-after-call/UNKNOWN.MPF", "NC324"),
    // A subprogram's own DEF variable passed by reference: FANUC locals are per call level.
    ("var-parameters/LOCAL_COUNTER.MPF", "NC381"),
    // RET with a jump target: its parameters are in no stored manual (tests/ret_to_label.rs).
    ("ret-to-label/ABORT_PATH.MPF", "NC507"),
];

fn nctrans(dir: &Path, args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_nctrans")).args(args).current_dir(dir).output().expect("run nctrans");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn mains() -> Vec<(PathBuf, String)> {
    let mut v = Vec::new();
    let Ok(rd) = std::fs::read_dir(root().join("corpus/in/sinumerik-calls")) else { return v };
    let mut dirs: Vec<PathBuf> = rd.filter_map(|e| e.ok().map(|e| e.path())).filter(|p| p.is_dir()).collect();
    dirs.sort();
    for d in dirs {
        let mut files: Vec<String> = std::fs::read_dir(&d)
            .map(|r| r.filter_map(|e| e.ok()?.file_name().into_string().ok()).collect())
            .unwrap_or_default();
        files.sort();
        v.extend(files.into_iter().filter(|f| f.ends_with(".MPF")).map(|f| (d.clone(), f)));
    }
    v
}

#[test]
fn mains_with_subprograms_translate_and_verify() {
    let bless = std::env::var_os("NCTRANS_BLESS").is_some_and(|v| v != "0");
    let mut failures = Vec::new();
    let all = mains();
    assert!(all.len() >= 6, "corpus/in/sinumerik-calls holds {} mains", all.len());
    for (dir, main) in all {
        let case = dir.file_name().and_then(|s| s.to_str()).unwrap_or("").to_string();
        let key = format!("{case}/{main}");
        let (code, out, err) = nctrans(&dir, &["--to", "fanuc", &main]);
        // Streamed or not, the user gets the same program and the same verdict.
        let (scode, sout, serr) = nctrans(&dir, &["--to", "fanuc", "--stream", &main]);
        if (scode, &sout) != (code, &out) || serr.lines().last() != err.lines().last() {
            failures.push(format!("{key}: --stream differs:\n{sout}\n{serr}\nvs\n{out}\n{err}"));
        }
        if let Some((_, want)) = REFUSED.iter().find(|(k, _)| *k == key) {
            if code == 0 || !err.contains(&format!("error[{want}]")) {
                failures.push(format!("{key}: should be refused with {want}:\n{err}"));
            }
            continue;
        }
        if code != 0 || !err.contains("equivalent (") {
            failures.push(format!("{key}: not translated and verified:\n{err}"));
            continue;
        }
        let golden = root().join("corpus/out/fanuc-calls").join(&case).join(format!("{main}.nc"));
        if bless {
            let _ = std::fs::create_dir_all(golden.parent().unwrap_or(&root()));
            let _ = std::fs::write(&golden, &out);
        } else if std::fs::read_to_string(&golden).ok().as_deref() != Some(out.as_str()) {
            failures.push(format!("{key}: differs from {} (NCTRANS_BLESS=1 rewrites it)", golden.display()));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The restore of a SAVE subprogram's modes is what makes its caller right: without it,
/// `nctrans check` finds the divergence (the checker runs the Siemens SAVE semantics).
#[test]
fn a_save_subprogram_without_its_restore_diverges() {
    let dir = root().join("corpus/in/sinumerik-calls/save-restores-modes");
    let (code, out, err) = nctrans(&dir, &["--to", "fanuc", "MAIN.MPF"]);
    assert_eq!(code, 0, "{err}");
    let tmp = std::env::temp_dir().join(format!("nctrans-save-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).expect("temp dir");
    for f in ["MAIN.MPF", "POCKET_SAVE.SPF"] {
        std::fs::copy(dir.join(f), tmp.join(f)).expect("copy");
    }
    let check = |text: &str| {
        std::fs::write(tmp.join("OUT.nc"), text).expect("write");
        nctrans(&tmp, &["check", "MAIN.MPF", "OUT.nc"])
    };
    let (ok, _, ok_err) = check(&out);
    assert_eq!(ok, 0, "the translation itself checks equivalent: {ok_err}");
    let broken: String = out.lines().filter(|l| !l.starts_with("G#")).map(|l| format!("{l}\n")).collect();
    assert_ne!(broken, out, "the translation restores with G#t words");
    let (bad, _, bad_err) = check(&broken);
    assert_ne!(bad, 0, "without the restore the check must fail: {bad_err}");
    let _ = std::fs::remove_dir_all(&tmp);
}

/// A VAR parameter is carried as the number of the caller's variable, written through
/// `#[#n]`: `nctrans check` (Siemens by-reference semantics against FANUC's) proves it, and
/// finds the divergence when the caller passes the value instead of the number.
#[test]
fn var_parameters_passed_by_value_diverge() {
    let dir = root().join("corpus/in/sinumerik-calls/var-parameters");
    let (code, out, err) = nctrans(&dir, &["--to", "fanuc", "MAIN.MPF"]);
    assert_eq!(code, 0, "{err}");
    let tmp = std::env::temp_dir().join(format!("nctrans-var-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).expect("temp dir");
    for f in ["MAIN.MPF", "ADD_PASS.SPF", "TWO_PASSES.SPF", "SUM3.SPF", "ALIASED.SPF"] {
        std::fs::copy(dir.join(f), tmp.join(f)).expect("copy");
    }
    let check = |text: &str| {
        std::fs::write(tmp.join("OUT.nc"), text).expect("write");
        nctrans(&tmp, &["check", "MAIN.MPF", "OUT.nc"])
    };
    let (ok, _, ok_err) = check(&out);
    assert_eq!(ok, 0, "the translation itself checks equivalent: {ok_err}");
    assert!(out.contains("G65 P9000 A104. B2.5 C105.") && out.contains("#[#1]=#[#1]+#2"), "{out}");
    let by_value = out.replace("G65 P9000 A104. B2.5 C105.", "G65 P9000 A#104 B2.5 C#105");
    let (bad, _, bad_err) = check(&by_value);
    assert_ne!(bad, 0, "passing the values must fail the check: {bad_err}");
    let _ = std::fs::remove_dir_all(&tmp);
}

/// What a VAR parameter cannot be given is refused where it is passed: a value that is not
/// a variable (NC380), a variable of another type or shape (NC382).
#[test]
fn var_parameters_refuse_values_and_other_types() {
    let tmp = std::env::temp_dir().join(format!("nctrans-var-refused-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).expect("temp dir");
    let sub = "PROC ADD_ONE(VAR REAL SUM)\nSUM=SUM+1\nRET\n";
    std::fs::write(tmp.join("ADD_ONE.SPF"), sub).expect("write");
    let cases = [
        (
            "CONST.MPF",
            "ADD_ONE(5)\nM30\n",
            "NC380",
            "argument 1 of ADD_ONE for VAR parameter SUM that is not a variable",
        ),
        ("OMITTED.MPF", "ADD_ONE()\nM30\n", "NC380", "not a variable"),
        (
            "INT.MPF",
            "DEF INT NUM\nADD_ONE(NUM)\nG1 X=NUM F100\nM30\n",
            "NC382",
            "INT passed for VAR parameter SUM REAL",
        ),
        ("ARRAY.MPF", "DEF REAL VALS[2]\nADD_ONE(VALS)\nM30\n", "NC382", "REAL[2] passed for VAR parameter SUM REAL"),
    ];
    for (name, text, code, what) in cases {
        std::fs::write(tmp.join(name), text).expect("write");
        let (rc, _, err) = nctrans(&tmp, &["--to", "fanuc", name]);
        assert!(rc != 0 && err.contains(&format!("error[{code}]")) && err.contains(what), "{name}: {err}");
    }
    let _ = std::fs::remove_dir_all(&tmp);
}

/// NC381's way out: the subprogram's local mapped to a common variable has a number its
/// callee can reach, and the call translates and verifies.
#[test]
fn a_local_mapped_to_a_common_variable_can_be_passed_by_reference() {
    let dir = root().join("corpus/in/sinumerik-calls/var-parameters");
    let (code, out, err) = nctrans(&dir, &["--to", "fanuc", "--var-map", "KOUNT=#150", "LOCAL_COUNTER.MPF"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("G65 P9000 A#1 B1. C150.") && err.contains("equivalent ("), "{out}\n{err}");
}
