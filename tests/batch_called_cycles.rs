//! A subprogram holding a drilling cycle that reads its arguments (FANUC `G65 P9100 R2.
//! Z-5.` into `G98 G81 … R#18 Z#26`, Siemens `DRILL(-8)` into `CYCLE81(…, DEPTH)`) cannot
//! run alone from the power-on state (Z=0 is below its R plane, NC425), though every call of
//! it is proven. In a batch it is written and reported as proven in its callers' runs, both
//! directions alike; one that no proven caller runs stays inconclusive and unwritten.

use nctrans::batch::jobs::{Job, JobSettings};
use nctrans::batch::target::{fanuc::Fanuc, sinumerik::Sinumerik};
use nctrans::batch::{self, BatchOptions, FileJob, InputFile, Status};
use nctrans::config::Config;
use nctrans::dialect::Dialect;
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::sync::Arc;

/// The main program as a machinist writes it; `call` is the line that calls the macro.
fn fanuc_main(call: &str) -> String {
    format!(
        "%\nO0001 (MAIN)\nG54 G90 G17\nT1 M6\nG43 H1 Z50.\nS1200 M3\nG00 X10. Y10.\n{call}\nG80\nG28 G91 Z0\nM30\n%\n"
    )
}

const MACRO: &str = "%\nO9100 (DRILL)\nG98 G81 X0 Y0 R#18 Z#26 F100.\nG80\nM99\n%\n";

const SIEMENS_MAIN: &str = "G54 G90 G17\nT1 M6\nD1\nS1200 M3\nG0 X10 Y10 Z50\nDRILL(-8)\nG0 Z100\nM30\n";
const SIEMENS_SUB: &str = "PROC DRILL(REAL DEPTH)\nG90 F100\nCYCLE81(-1, -2, 1, DEPTH)\nRET\n";

fn library(name: &str, files: &[(&str, &str)]) -> PathBuf {
    let d = std::env::temp_dir().join(format!("nctrans-called-cycles-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(d.join("lib")).unwrap();
    for (f, text) in files {
        std::fs::write(d.join("lib").join(f), text).unwrap();
    }
    d
}

fn run(d: &Path, target: Dialect, job: &dyn FileJob) -> batch::BatchResult {
    let mut opts = BatchOptions::new(d.join("lib"), d.join("out"), target);
    opts.specialise_callers = true;
    opts.jobs = 1;
    batch::run_batch(opts, job, Arc::new(AtomicBool::new(false)), &mut |_| {}).unwrap()
}

fn record<'a>(r: &'a batch::BatchResult, path: &str) -> &'a batch::FileRecord {
    r.files.iter().find(|f| f.path == path).unwrap_or_else(|| panic!("no record for {path}"))
}

fn settings() -> JobSettings {
    JobSettings::from_config(&Config::default()).unwrap()
}

/// A job whose translation of `file` gets one extra move: verification must catch it.
fn faulty<T: nctrans::batch::jobs::Target>(file: &'static str, end: &'static str, extra: &'static str) -> Job<T> {
    let mut job = Job::<T>::new(settings());
    job.fault = Some(Box::new(move |f: &InputFile, text: &mut String| {
        if batch::rel_string(&f.rel) == file {
            *text = text.replacen(end, &format!("{extra}{end}"), 1);
        }
    }));
    job
}

#[test]
fn a_fanuc_macro_that_cannot_run_alone_is_proven_in_its_callers_runs() {
    let d = library("to-sinumerik", &[("O0001.nc", &fanuc_main("G65 P9100 R2. Z-5.")), ("O9100.nc", MACRO)]);
    let r = run(&d, Dialect::Sinumerik, &Job::<Sinumerik>::new(settings()));
    assert!(r.all_verified(), "{:?}", r.files);
    let m = record(&r, "O9100.nc");
    assert_eq!(m.status, Status::Verified);
    assert!(m.summary.starts_with("proven in the runs of its callers: O0001.nc (alone: "), "{}", m.summary);
    assert_eq!(m.outputs, ["O_9100.spf"]);
    assert!(d.join("out/O_9100.spf").is_file());
    // Why its run alone is not its proof stays, as a note.
    let d425 = m.diagnostics.iter().find(|x| x.code == "NC425").expect("the run alone's NC425");
    assert_eq!(d425.severity, "note");
}

#[test]
fn a_siemens_subprogram_that_cannot_run_alone_is_proven_in_its_callers_runs() {
    let d = library("to-fanuc", &[("PART.MPF", SIEMENS_MAIN), ("DRILL.SPF", SIEMENS_SUB)]);
    let r = run(&d, Dialect::Fanuc, &Job::<Fanuc>::new(settings()));
    assert!(r.all_verified(), "{:?}", r.files);
    let s = record(&r, "DRILL.SPF");
    assert!(s.summary.starts_with("proven in the runs of its callers: PART.MPF (alone: "), "{}", s.summary);
    assert_eq!(s.outputs, ["DRILL.NC"]);
}

#[test]
fn a_caller_that_diverges_proves_nothing() {
    let d = library("caller-wrong", &[("O0001.nc", &fanuc_main("G65 P9100 R2. Z-5.")), ("O9100.nc", MACRO)]);
    let r = run(&d, Dialect::Sinumerik, &faulty::<Sinumerik>("O0001.nc", "\nM30", "\nG1 X1 Y1"));
    assert_eq!(record(&r, "O0001.nc").status, Status::Diverged);
    let m = record(&r, "O9100.nc");
    assert_eq!(m.status, Status::Inconclusive, "{}", m.summary);
    assert!(m.outputs.is_empty() && !d.join("out/O_9100.spf").exists());
    // The same to FANUC.
    let d = library("caller-wrong-fanuc", &[("PART.MPF", SIEMENS_MAIN), ("DRILL.SPF", SIEMENS_SUB)]);
    let r = run(&d, Dialect::Fanuc, &faulty::<Fanuc>("PART.MPF", "\nM30", "\nG01 X1. Y1."));
    assert_eq!(record(&r, "PART.MPF").status, Status::Diverged);
    assert_eq!(record(&r, "DRILL.SPF").status, Status::Inconclusive);
}

#[test]
fn a_file_that_writes_another_program_than_its_callers_ran_is_not_proven_by_them() {
    // The macro's own output gets a planted extra move its callers' runs never ran.
    let d = library("own-wrong", &[("O0001.nc", &fanuc_main("G65 P9100 R2. Z-5.")), ("O9100.nc", MACRO)]);
    let r = run(&d, Dialect::Sinumerik, &faulty::<Sinumerik>("O9100.nc", "\nRET", "\nG1 X1 Y1"));
    assert_eq!(record(&r, "O0001.nc").status, Status::Verified);
    let m = record(&r, "O9100.nc");
    assert_ne!(m.status, Status::Verified, "{}", m.summary);
    assert!(m.outputs.is_empty());
    let d = library("own-wrong-fanuc", &[("PART.MPF", SIEMENS_MAIN), ("DRILL.SPF", SIEMENS_SUB)]);
    let r = run(&d, Dialect::Fanuc, &faulty::<Fanuc>("DRILL.SPF", "\nM99", "\nG01 X1. Y1."));
    assert_eq!(record(&r, "PART.MPF").status, Status::Verified);
    assert_ne!(record(&r, "DRILL.SPF").status, Status::Verified);
}

#[test]
fn a_call_the_callers_runs_never_reach_proves_nothing() {
    let skipped = "GOTO 10\nG65 P9100 R2. Z-5.\nN10 G00 Z50.";
    let d = library("unreached", &[("O0001.nc", &fanuc_main(skipped)), ("O9100.nc", MACRO)]);
    let r = run(&d, Dialect::Sinumerik, &Job::<Sinumerik>::new(settings()));
    assert_eq!(record(&r, "O0001.nc").status, Status::Verified, "{}", record(&r, "O0001.nc").summary);
    let m = record(&r, "O9100.nc");
    assert_eq!(m.status, Status::Inconclusive, "{}", m.summary);
    assert!(m.outputs.is_empty());
}

#[test]
fn a_macro_no_file_calls_stays_as_it_was() {
    let d = library("uncalled", &[("O0001.nc", &fanuc_main("G00 Z50.")), ("O9100.nc", MACRO)]);
    let r = run(&d, Dialect::Sinumerik, &Job::<Sinumerik>::new(settings()));
    let m = record(&r, "O9100.nc");
    assert_ne!(m.status, Status::Verified, "{}", m.summary);
    assert!(!m.summary.contains("callers"), "{}", m.summary);
    assert!(m.outputs.is_empty());
}
