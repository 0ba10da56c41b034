//! A batch's outputs work together: a program translated in one file's job calls a
//! program written by another file's job, so every call must fit the `PROC` line the
//! callee's own job writes. Each job verifies against its own translation of the callees,
//! so this test runs the Siemens output folder as a whole (the main finds its `.spf`
//! files beside it) against the FANUC library run as one program set.

use std::path::{Path, PathBuf};
use std::process::Command;

fn bin() -> &'static str {
    env!("CARGO_BIN_EXE_nctrans")
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("nctrans-cross-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(d.join("in")).expect("scratch");
    d
}

/// The trace events of `nctrans run FILE` (the end line left out: step counts differ).
fn events(file: &Path) -> Vec<String> {
    let out = Command::new(bin()).arg("run").arg(file).output().expect("run");
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    text.lines().map(|l| l.split("  @").next().unwrap_or(l).to_string()).filter(|l| !l.starts_with("end ")).collect()
}

#[test]
fn calls_between_files_fit_the_callees_proc_lines() {
    // main: its own M98 subprogram reads #1 (so #1 has an is-set flag there); lib's
    // subprograms share #1 or not at all. Before, the main's job gave the other file's
    // subprogram the caller's flag (`O_8001(LOC1,LOC1_SET)`) while lib's own job wrote
    // `PROC O_8001` without it: an alarm on the machine, "every file verified" in the report.
    let cases: [(&str, &str, &str); 2] = [
        (
            "untouched",
            "%\nO1000\n#1=2.\nM98 P2001\nM98 P8001\nM30\nO2001\nG1 X#1 F100.\nM99\n%\n",
            "%\nO8001\nG0 X1.\nM99\n%\n",
        ),
        (
            "arithmetic",
            "%\nO1000\n#1=2.\nM98 P2001\nM98 P8001\nG0 X#1\nM30\nO2001\nG1 X#1 F100.\nM99\n%\n",
            "%\nO8001\n#1=#1+1.\nG0 Y#1\nM99\n%\n",
        ),
    ];
    for (name, main, lib) in cases {
        let d = scratch(name);
        std::fs::write(d.join("in/main.nc"), main).expect("main");
        std::fs::write(d.join("in/lib.nc"), lib).expect("lib");
        let st = Command::new(bin())
            .args(["--to", "sinumerik"])
            .arg(d.join("in"))
            .arg("-o")
            .arg(d.join("out"))
            .output()
            .expect("batch");
        assert!(st.status.success(), "{name}: {}", String::from_utf8_lossy(&st.stderr));
        // The FANUC library as one file: the main program first, then every other program.
        let all = format!("{}{}", main.trim_end_matches("%\n"), lib.trim_start_matches("%\n"));
        std::fs::write(d.join("all.nc"), all).expect("all");
        let want = events(&d.join("all.nc"));
        let got = events(&d.join("out/MAIN.mpf"));
        assert!(want.len() >= 2, "{name}: {want:?}");
        assert_eq!(got, want, "{name}: the output folder does not run as the library does");
        let _ = std::fs::remove_dir_all(&d);
    }
}

/// G65 arguments from callers in two files: the macro's `PROC` line takes every letter
/// any caller gives (its own job learns them from a stand-in caller), and each call puts
/// its values in those positions.
#[test]
fn macro_calls_from_two_files_fill_the_same_parameters() {
    let d = scratch("g65");
    let main = "%\nO1000\n#1=2.\nG65 P8002 X3. Y#1\nM30\n%\n";
    let lib = "%\nO8002\nG01 X#24 F150.\nIF [#25 GT 1.] THEN #26=#25*2\nG0 Z#26\nM99\n%\n";
    let other = "%\nO3000\nG65 P8002 A1. Z2.\nM30\n%\n";
    for (f, t) in [("main.nc", main), ("lib.nc", lib), ("other.nc", other)] {
        std::fs::write(d.join("in").join(f), t).expect("file");
    }
    let st = Command::new(bin()).args(["--to", "sinumerik"]).arg(d.join("in")).arg("-o").arg(d.join("out")).output();
    let st = st.expect("batch");
    assert!(st.status.success(), "{}", String::from_utf8_lossy(&st.stderr));
    for (caller, out) in [(main, "MAIN.mpf"), (other, "OTHER.mpf")] {
        let all = format!("{}{}", caller.trim_end_matches("%\n"), lib.trim_start_matches("%\n"));
        std::fs::write(d.join("all.nc"), all).expect("all");
        let want = events(&d.join("all.nc"));
        assert!(!want.is_empty(), "{out}");
        assert_eq!(events(&d.join("out").join(out)), want, "{out}");
    }
    let _ = std::fs::remove_dir_all(&d);
}
