//! A macro written for every possible caller is proven so on every path (issue 17 item 9):
//! `nctrans --to sinumerik`, whole or streamed, runs each macro called by G65/G66 alone with
//! its callers' arguments and again with each of them vacant (`verify_called`, the rule the
//! batch uses), so a wrong default or a missing alarm for a vacant argument is caught even
//! when every call seen gives every argument. A batch does it for a macro in its caller's
//! file too, whole and streamed, with one verdict.

use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::ir::Unit;
use nctrans::read::LineEnding;
use nctrans::span::SourceDb;
use nctrans::translate::called::{called_runs, combine, Combined, RunSettings};
use nctrans::translate::to_sinumerik::{Options, OutFile, Translation};
use std::path::PathBuf;
use std::process::Command;

fn corpus_file() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("corpus/in/fanuc/macro-defaults-all-given.nc")
}

/// The macro's default for H, planted wrong: only a run with H vacant sees it.
fn tamper(files: &mut [OutFile]) {
    let f = files.iter_mut().find(|f| f.name == "O_9100.SPF").expect("the macro's file");
    assert!(f.text.contains("ARG_H=1 ARG_H_SET=1"), "{}", f.text);
    f.text = f.text.replace("ARG_H=1 ARG_H_SET=1", "ARG_H=2 ARG_H_SET=1");
}

fn verdict(db: &SourceDb, units: &[&Unit], tr: &Translation) -> Combined {
    let profiles = nctrans::translate::to_sinumerik::verify::Profiles::default();
    let settings = RunSettings { out_dir: "", max_steps: 100_000, profiles: &profiles, set: &[] };
    combine(called_runs(db, units, tr, &settings, true))
}

#[test]
fn a_wrong_default_is_caught_in_the_whole_translation() {
    let bytes = std::fs::read(corpus_file()).expect("corpus file");
    let mut db = SourceDb::new();
    let loaded = nctrans::load(&mut db, "m.nc", &bytes, None);
    let parsed = nctrans::parse(&db, loaded.file, Dialect::Fanuc, &ParseOptions::for_dialect(Dialect::Fanuc));
    let tr = nctrans::translate::to_sinumerik::translate(&[&parsed.unit], &Options::default(), LineEnding::Lf);
    assert!(!tr.has_errors());
    match verdict(&db, &[&parsed.unit], &tr) {
        // Two call sites, then H, D, K vacant in turn for each.
        Combined::Equivalent { runs, .. } => assert_eq!(runs, 8),
        Combined::Not(label, r) => panic!("{label}: {:?}\n{}", r.verdict, r.diff),
    }
    let mut bad = tr.clone();
    tamper(&mut bad.files);
    // The main program's run alone does not see it: every call gives H.
    let main = nctrans::translate::to_sinumerik::verify::verify(&db, loaded.file, &parsed.unit, &bad, "");
    assert!(matches!(main.verdict, nctrans::check::Verdict::Equivalent { .. }), "{:?}", main.verdict);
    match verdict(&db, &[&parsed.unit], &bad) {
        Combined::Not(label, r) => {
            assert!(matches!(r.verdict, nctrans::check::Verdict::Diverged { .. }), "{:?}", r.verdict);
            assert!(label.contains("O_9100 alone") && label.contains("#11 vacant"), "{label}");
        }
        Combined::Equivalent { .. } => panic!("the wrong default was not caught"),
    }
}

#[test]
fn a_wrong_default_is_caught_in_the_streamed_translation() {
    use nctrans::stream::segmented::sinumerik::to_sinumerik_with_subs;
    let path = corpus_file();
    let mut skeleton: Vec<Unit> = Vec::new();
    let mut load = |u: &Unit| {
        skeleton.push(u.clone());
        Ok(Vec::new())
    };
    let mut out: Vec<u8> = Vec::new();
    let (done, mut subs) =
        match to_sinumerik_with_subs(&path, &Options::default(), LineEnding::Lf, &mut load, &mut out, None) {
            Ok(r) => r,
            Err(_) => panic!("the file streams"),
        };
    let mut db = SourceDb::new();
    db.add(path.display().to_string(), String::new());
    let units: Vec<&Unit> = skeleton.iter().collect();
    let tr = |files: &[OutFile]| Translation {
        files: files.to_vec(),
        symbols: nctrans::translate::Symbols::Sinumerik(done.symbols.clone()),
        diags: Vec::new(),
        unsupported: 0,
    };
    assert!(matches!(verdict(&db, &units, &tr(&subs)), Combined::Equivalent { runs: 8, .. }));
    tamper(&mut subs);
    assert!(matches!(verdict(&db, &units, &tr(&subs)), Combined::Not(..)), "the wrong default was not caught");
}

fn nctrans(args: &[&str], dir: &std::path::Path) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_nctrans")).args(args).current_dir(dir).output().expect("run");
    (out.status.success(), String::from_utf8_lossy(&out.stdout).into(), String::from_utf8_lossy(&out.stderr).into())
}

#[test]
fn the_verdict_counts_the_runs_whole_and_streamed() {
    let dir = std::env::temp_dir().join(format!("nctrans-verify-called-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("dir");
    std::fs::copy(corpus_file(), dir.join("pocket.nc")).expect("copy");
    for stream in [false, true] {
        let mut args = vec!["--to", "sinumerik", "pocket.nc", "-o", "out/"];
        if stream {
            args.push("--stream");
        }
        let (ok, _, err) = nctrans(&args, &dir);
        assert!(ok, "{err}");
        // The main program, then the macro alone: two call sites, each with H, D, K vacant.
        assert!(err.contains("equivalent (34 events in 9 runs)"), "stream {stream}: {err}");
        let spf = std::fs::read_to_string(dir.join("out/O_9100.SPF")).expect("macro written");
        assert!(spf.contains("IF NOT ARG_H_SET\n  ARG_H=1 ARG_H_SET=1\nENDIF\n"), "{spf}");
        assert!(!spf.contains("IF 0"), "{spf}");
        let _ = std::fs::remove_dir_all(dir.join("out"));
    }
    // Specialised: the defaults are decided for the calls seen, and no vacant run is made.
    let (ok, out, err) = nctrans(&["--to", "sinumerik", "--specialise-callers", "pocket.nc"], &dir);
    assert!(ok, "{err}");
    // The decided default is folded away, not written as `IF 0`.
    assert!(out.contains("PROC O_9100") && !out.contains("ARG_H=1") && !out.contains("IF 0"), "{out}");
    assert!(err.contains("equivalent (16 events in 3 runs)"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A batch whose one file holds the main program and its macro (`pocket.nc`), with
/// streaming at `stream_bytes` (0: every file the streamed job takes, `u64::MAX`: none) and
/// the job's `fault` applied to every output: the file's record, and whether the streamed
/// job took the file.
fn batch_record(
    name: &str,
    stream_bytes: u64,
    specialise: bool,
    fault: Option<Box<nctrans::batch::jobs::Fault>>,
) -> (nctrans::batch::FileRecord, bool) {
    use nctrans::batch::jobs::Job;
    use nctrans::batch::target::sinumerik::Sinumerik;
    use nctrans::batch::{self, BatchOptions, FileJob};
    struct Watched(Job<Sinumerik>, std::sync::atomic::AtomicBool);
    impl FileJob for Watched {
        fn run(&self, f: &batch::InputFile, ctx: &batch::BatchContext) -> batch::FileOutcome {
            match batch::streamed::run(&self.0, f, ctx) {
                Some(o) => {
                    self.1.store(true, std::sync::atomic::Ordering::SeqCst);
                    o
                }
                None => self.0.run(f, ctx),
            }
        }
    }
    let dir = std::env::temp_dir().join(format!("nctrans-verify-called-batch-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("in")).expect("dir");
    std::fs::copy(corpus_file(), dir.join("in/pocket.nc")).expect("copy");
    let settings =
        nctrans::batch::jobs::JobSettings::from_config(&nctrans::config::Config::default()).expect("settings");
    let mut job = Job::<Sinumerik>::new(settings);
    job.fault = fault;
    let job = Watched(job, Default::default());
    let mut opts = BatchOptions::new(dir.join("in"), dir.join("out"), Dialect::Sinumerik);
    opts.stream_bytes = stream_bytes;
    opts.specialise_callers = specialise;
    let stop = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    let r = batch::run_batch(opts, &job, stop, &mut |_| {}).expect("batch");
    let _ = std::fs::remove_dir_all(&dir);
    let rec = r.files.into_iter().find(|f| f.path == "pocket.nc").expect("the file's record");
    (rec, job.1.load(std::sync::atomic::Ordering::SeqCst))
}

#[test]
fn a_batch_runs_a_macro_of_its_callers_file_alone_with_each_argument_vacant() {
    use nctrans::batch::Status;
    let (rec, _) = batch_record("whole", u64::MAX, false, None);
    assert_eq!(rec.status, Status::Verified, "{}", rec.summary);
    // The main program, then the macro alone: two call sites, each with H, D, K vacant.
    assert_eq!(rec.summary, "equivalent (34 events in 9 runs)");
    let (rec, _) = batch_record("specialised", u64::MAX, true, None);
    assert_eq!(rec.summary, "equivalent (16 events in 3 runs)");
    // The macro's default for H planted wrong: only a run with H vacant sees it.
    let fault: Box<nctrans::batch::jobs::Fault> = Box::new(|_: &nctrans::batch::InputFile, text: &mut String| {
        *text = text.replace("ARG_H=1 ARG_H_SET=1", "ARG_H=2 ARG_H_SET=1");
    });
    let (rec, _) = batch_record("tampered", u64::MAX, false, Some(fault));
    assert_eq!(rec.status, Status::Diverged, "{}", rec.summary);
    assert!(rec.summary.contains("O_9100 alone") && rec.summary.contains("#11 vacant"), "{}", rec.summary);
}

#[test]
fn the_streamed_batch_gives_the_whole_batchs_verdict_for_a_macro_of_its_callers_file() {
    for specialise in [false, true] {
        let (whole, streamed_whole) = batch_record("w", u64::MAX, specialise, None);
        let (streamed, took) = batch_record("s", 0, specialise, None);
        assert!(!streamed_whole && took, "the streamed job takes the file only when streaming");
        // The main program and the macro alone (each argument vacant unless specialised).
        let runs = if specialise { "in 3 runs)" } else { "in 9 runs)" };
        assert!(streamed.summary.ends_with(runs), "{}", streamed.summary);
        assert_eq!(streamed.status, whole.status);
        assert_eq!(streamed.summary, whole.summary);
        assert_eq!(streamed.events, whole.events);
        assert_eq!(streamed.outputs, whole.outputs);
    }
}
