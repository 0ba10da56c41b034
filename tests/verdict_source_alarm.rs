//! A divergence where the source program itself stops with an alarm (a drilling cycle with
//! no feed ever programmed: the control's 10860) is not called a bug in nctrans: the verdict
//! says the source is in error on that path, in the whole-file, streamed and batch paths;
//! a divergence on motion keeps the plain verdict.

#[path = "support/cli_run.rs"]
mod cli_run;

use std::path::{Path, PathBuf};

/// Spot-drilling four holes; no F word anywhere, so CYCLE81 alarms at its first hole.
const NO_FEED: &str = "\
; SPOT DRILL 4 HOLES
N10 G17 G90 G71 G54
N20 T1 D1 M6
N30 S2500 M3 M8
N40 G0 X0 Y0 Z50
N50 MCALL CYCLE81(10,0,2,-3)
N60 X20 Y20
N70 X-20 Y20
N80 MCALL
N90 G0 Z100 M9
N100 M30
";

fn dir(name: &str) -> PathBuf {
    cli_run::workdir("verdict-alarm", name)
}

fn nctrans(cwd: &Path, args: &[&str]) -> (i32, String, String) {
    let (out, err, code) = cli_run::nctrans(cwd, args);
    (code, out, err)
}

const SOURCE_ALARMS: &str = "the source stops with an alarm there";

#[test]
fn a_source_that_alarms_is_not_called_a_bug_in_nctrans() {
    let d = dir("single");
    std::fs::write(d.join("SPOT.MPF"), NO_FEED).unwrap();
    let (_, out, err) = nctrans(&d, &["run", "SPOT.MPF"]);
    assert!(out.contains("alarm 10860"), "{out}{err}");
    for extra in [None, Some("--stream")] {
        let mut args = vec!["--to", "fanuc", "SPOT.MPF"];
        args.extend(extra);
        let (code, out, err) = nctrans(&d, &args);
        assert_ne!(code, 0, "{extra:?}: {err}");
        let last = err.lines().last().unwrap_or_default();
        assert!(last.contains(SOURCE_ALARMS) && !last.contains("bug in nctrans"), "{extra:?}: {err}");
        std::fs::write(d.join("SPOT.nc"), out).unwrap();
    }
    // `check` of the two says the same of its first program.
    let (code, out, err) = nctrans(&d, &["check", "SPOT.MPF", "SPOT.nc"]);
    assert_ne!(code, 0, "{out}{err}");
    assert!(out.contains("the first program stops with an alarm there"), "{out}{err}");
}

#[test]
fn the_batch_report_says_the_source_alarms() {
    let d = dir("batch");
    std::fs::create_dir_all(d.join("in")).unwrap();
    std::fs::write(d.join("in/SPOT.MPF"), NO_FEED).unwrap();
    let (_, _, err) = nctrans(&d, &["--to", "fanuc", "-o", "out", "in", "--report", "r.json"]);
    let report = std::fs::read_to_string(d.join("r.json")).unwrap_or_else(|e| panic!("{e}: {err}"));
    assert!(report.contains(SOURCE_ALARMS) && !report.contains("bug in nctrans"), "{report}");
}

#[test]
fn a_divergence_on_motion_keeps_the_plain_verdict() {
    let d = dir("motion");
    let fed = NO_FEED.replace("N30 S2500 M3 M8", "N30 S2500 M3 M8 F120");
    std::fs::write(d.join("SPOT.MPF"), &fed).unwrap();
    let (code, fanuc, err) = nctrans(&d, &["--to", "fanuc", "SPOT.MPF"]);
    assert_eq!(code, 0, "{err}");
    // A planted wrong depth in the translation.
    assert!(fanuc.contains("Z-3."), "{fanuc}");
    std::fs::write(d.join("SPOT.nc"), fanuc.replace("Z-3.", "Z-4.")).unwrap();
    let (code, out, err) = nctrans(&d, &["check", "SPOT.MPF", "SPOT.nc"]);
    assert_ne!(code, 0, "{out}{err}");
    assert!(out.contains("diverged") && !out.contains(SOURCE_ALARMS), "{out}{err}");
}
