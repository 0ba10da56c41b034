//! Siemens `RET` with a jump target (issue 21): `RET("L")`, `RET(N100)`, `RET("L", n)`.
//! No stored Siemens manual page gives its parameters (which argument is the target, where the
//! control searches it in the caller, how many levels it returns), so the run stops at one it
//! reaches and the FANUC translation refuses any, both with NC507 saying why; a run that never
//! reaches it goes on as before. The corpus folder `corpus/in/sinumerik-calls/ret-to-label/`
//! holds a machinist's abort path; what the run shows of it is committed under
//! `corpus/out/diag/calls/ret-to-label/` (`NCTRANS_BLESS=1` rewrites it).

#[path = "support/cli_run.rs"]
mod cli_run;

use cli_run::{nctrans, workdir};
use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn corpus() -> PathBuf {
    root().join("corpus/in/sinumerik-calls/ret-to-label")
}

const REASON: &str = "no Siemens manual page at hand gives RET's parameters";

fn golden(name: &str, text: &str) {
    let path = root().join("corpus/out/diag/calls/ret-to-label").join(name);
    if std::env::var_os("NCTRANS_BLESS").is_some_and(|v| v != "0") {
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(&path, text).unwrap();
    } else {
        let want = std::fs::read_to_string(&path).unwrap_or_default();
        assert_eq!(text, want, "differs from {} (NCTRANS_BLESS=1 rewrites it)", path.display());
    }
}

#[test]
fn the_run_stops_at_the_abort_return_naming_the_block_and_the_reason() {
    let (out, err, code) = nctrans(&corpus(), &["run", "ABORT_PATH.MPF"]);
    assert_ne!(code, 0, "{out}");
    // The two good holes and the third (the one whose check breaks the tool) are drilled ...
    assert!(out.contains("move linear X=40 Y=0 Z=-8 f=120"), "{out}");
    // ... and nothing after the RET runs: neither the fourth hole nor either label's path.
    assert!(!out.contains("X=60") && !out.contains("Z=100") && !out.contains("Z=50"), "{out}");
    assert!(err.contains("error[NC507]") && err.contains("RET(\"BROKEN\")"), "{err}");
    assert!(err.contains("TOOL_CHECK.SPF:9:3") && err.contains(REASON), "{err}");
    golden("ABORT_PATH.MPF.run.txt", &format!("{out}--- stderr ---\n{err}"));
}

#[test]
fn the_translation_is_refused_whole_and_streamed() {
    let (out, err, code) = nctrans(&corpus(), &["--to", "fanuc", "ABORT_PATH.MPF"]);
    let (sout, serr, scode) = nctrans(&corpus(), &["--to", "fanuc", "--stream", "ABORT_PATH.MPF"]);
    assert_ne!(code, 0, "{out}");
    assert_eq!((scode, &sout), (code, &out), "{serr}");
    for e in [&err, &serr] {
        assert!(e.contains("error[NC507]") && e.contains("TOOL_CHECK.SPF:9:3") && e.contains(REASON), "{e}");
        // The only construct refused is the RET: the rest of the pair translates.
        assert!(e.contains("not translated (1 construct(s)"), "{e}");
    }
    golden("ABORT_PATH.MPF.to-fanuc.txt", &err);
}

#[test]
fn a_run_that_never_takes_the_abort_path_goes_on_but_the_translation_still_refuses() {
    let d = workdir("retlabel", "untaken");
    std::fs::write(d.join("MAIN.MPF"), "G0 X0 Y0 Z5\nCHECK\nG1 X5 F100\nM30\nGONE:\nG0 Z100\nM30\n").unwrap();
    std::fs::write(d.join("CHECK.SPF"), "PROC CHECK\nR10=0\nIF R10==1\n  RET(\"GONE\")\nENDIF\nRET\n").unwrap();
    let (out, err, code) = nctrans(&d, &["run", "MAIN.MPF"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("move linear X=5 Y=0 Z=5 f=100") && !out.contains("Z=100"), "{out}");
    // The translation cannot know the branch is never taken on the machine.
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "MAIN.MPF"]);
    assert_ne!(code, 0);
    assert!(err.contains("error[NC507]") && err.contains("CHECK.SPF:4:3"), "{err}");
}

#[test]
fn every_form_of_the_target_is_refused_in_the_run_and_the_translation() {
    for (i, ret) in
        ["RET(N100)", "RET(\"N100\")", "RET(\"GONE\", 2)", "RET(\"GONE\",,2)", "RET(, , 2)"].iter().enumerate()
    {
        let d = workdir("retlabel", &format!("form{i}"));
        std::fs::write(d.join("MAIN.MPF"), "G0 X0 Y0 Z5\nCHECK\nN100 G1 X5 F100\nGONE:\nM30\n").unwrap();
        std::fs::write(d.join("CHECK.SPF"), format!("PROC CHECK\nG1 X1 F100\n{ret}\n")).unwrap();
        let (out, err, code) = nctrans(&d, &["run", "MAIN.MPF"]);
        assert_ne!(code, 0, "{ret}: {out}");
        assert!(err.contains("error[NC507]") && err.contains(ret) && err.contains("CHECK.SPF:3:1"), "{ret}: {err}");
        assert!(out.contains("move linear X=1") && !out.contains("X=5"), "{ret}: {out}");
        for extra in [&[][..], &["--stream"][..]] {
            let mut args = vec!["--to", "fanuc"];
            args.extend_from_slice(extra);
            args.push("MAIN.MPF");
            let (_, err, code) = nctrans(&d, &args);
            assert_ne!(code, 0, "{ret} {extra:?}");
            assert!(err.contains("error[NC507]") && err.contains(REASON), "{ret} {extra:?}: {err}");
        }
    }
}

#[test]
fn a_plain_ret_in_the_same_subprogram_still_returns_after_the_call() {
    let d = workdir("retlabel", "plain");
    std::fs::write(d.join("MAIN.MPF"), "G0 X0 Y0 Z5\nCHECK\nG1 X5 F100\nM30\n").unwrap();
    std::fs::write(d.join("CHECK.SPF"), "PROC CHECK\nG1 X1 F100\nRET\n").unwrap();
    let (out, err, code) = nctrans(&d, &["--to", "fanuc", "MAIN.MPF"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent ("), "{err}");
    assert!(out.contains("M99"), "{out}");
}
