//! FANUC → Sinumerik batches stream a large main program that calls subprograms: its own
//! after M30 and programs of other batch files (`M98 P`, `G65 P` with arguments, `G66 P` …
//! `G67`). The streamed batch writes the same files (`.mpf`, `.spf`, the map file), the same
//! report and exit code as with streaming off; the main streams (with the whole job's
//! stand-in caller when other files call its callees too: many CAM mains calling the
//! macros of one library file), its callee files go whole, and so do mains whose job the
//! streamed one is not (a subprogram its own file does not call). The library scan of such a file streams and
//! reports what the whole scan reports.

#[path = "support/batch_out.rs"]
mod batch_out;
#[path = "support/rng.rs"]
mod rng;

use batch_out::{snapshot, untimed};
use nctrans::batch::jobs::{Job, JobSettings};
use nctrans::batch::target::sinumerik::Sinumerik;
use nctrans::batch::{self, BatchContext, BatchOptions, FileJob, FileOutcome, InputFile};
use nctrans::dialect::Dialect;
use rng::Rng;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::AtomicBool;
use std::sync::{Arc, Mutex};

fn scratch(name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/batch-stream-calls").join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("dir");
    d
}

/// A FANUC CAM block.
fn cam(r: &mut Rng) -> String {
    let mut s = String::from(r.pick(&["G01 ", "G00 ", "", ""]));
    for a in ["X", "Y", "Z"] {
        if r.chance(70) {
            let neg = if r.chance(30) { "-" } else { "" };
            s.push_str(&format!("{a}{neg}{}.{:03}", r.below(300), r.below(1000)));
        }
    }
    if s.trim().is_empty() {
        s.push_str("Y2.");
    }
    s.trim_end().to_string()
}

/// A FANUC main program `O<number>` with a macro part around runs of CAM blocks; the k-th
/// entry of `calls` is put after the k-th run; `tail` follows its `M30` (subprograms).
fn main_program(seed: u64, number: u32, calls: &[&str], tail: &str) -> String {
    let mut r = Rng(seed);
    let mut s = format!("%\nO{number}\n#1=2.\n#2=0\nG21 G17 G90 F400.\n");
    for (k, call) in calls.iter().enumerate() {
        for _ in 0..120 + r.index(150) {
            s.push_str(&cam(&mut r));
            s.push('\n');
        }
        match k % 3 {
            0 => s.push_str("WHILE [#2 LT 2] DO1\n#2=#2+1\nG01 Y#2 F200.\nEND1\n#2=0\n"),
            1 => s.push_str(&format!("N{} #3=#3+1\nIF [#3 LT 2] GOTO{}\n", 700 + k, 700 + k)),
            _ => s.push_str("G00 Z[#1*3]\n"),
        }
        s.push_str(call);
        s.push('\n');
    }
    s.push_str("G00 Z50.\nM30\n");
    s.push_str(tail);
    s.push_str("%\n");
    s
}

/// The batch: mains that stream with their callees, and files that go whole.
fn library(input: &Path) {
    let fan = input.join("fan");
    std::fs::create_dir_all(&fan).expect("dir");
    let w = |name: &str, t: String| std::fs::write(fan.join(name), t).expect("write");
    // Own subprograms after M30 and programs of two other files (one calling the other).
    let own = "O2001\nG01 X#1 F120.\nM99\nO2002\n#10=#1+#2\nG01 Z-#10 F90.\nM99\n";
    w(
        "main1.nc",
        main_program(
            1,
            1000,
            &["M98 P2001", "G65 P2002 A1. B2.", "M98 P8001", "G65 P8002 X3. Y#1", "G65 P2002 A#1 B0.5"],
            own,
        ),
    );
    w("lib1.nc", "%\nO8001\nG00 X10. Y10.\nG01 Z-1. F100.\nM99\n%\n".into());
    w("lib2.nc", "%\nO8002\nG01 X#24 F150.\nIF [#25 GT 1.] THEN #26=#25*2\nM98 P8001\nM99\n%\n".into());
    // Own subprograms only, a modal call among them (CRLF line ends).
    let modal = "O2101\nG01 Z-#26 F80.\nG00 Z1.\nM99\nO2102\nG00 X0 Y0\nM99\n";
    let text = main_program(2, 1100, &["G66 P2101 Z2.", "G01 X5. F300.\nG67", "M98 P2102"], modal);
    w("main2.nc", text.replace('\n', "\r\n"));
    // A legacy encoding (the comment's byte is not UTF-8), and a byte-order mark: the
    // outputs keep both, the subprograms' too.
    let latin = main_program(
        5,
        1500,
        &["(KOPF \u{c4}NDERN)", "M98 P2501", "G65 P8501 R4."],
        "O2501\n(\u{d6}L)\nG00 X9.\nM99\n",
    );
    let bytes: Vec<u8> = latin.chars().map(|c| u8::try_from(u32::from(c)).expect("latin-1")).collect();
    std::fs::write(fan.join("main5.nc"), bytes).expect("write");
    w("lib5.nc", "%\nO8501\n(\u{dc}BER)\nG01 Z-#18 F60.\nM99\n%\n".into());
    w("main6.nc", format!("\u{feff}{}", main_program(6, 1600, &["M98 P2601", "G00 Y1."], "O2601\nG00 X8.\nM99\n")));
    // A callee another file calls too: the whole job adds a stand-in caller; so does the
    // streamed one.
    w("main3.nc", main_program(3, 1200, &["M98 P8004", "G00 X1."], ""));
    w("shared.nc", "%\nO8004\nG01 X7. F100.\nM99\n%\n".into());
    w("other.nc", "%\nO1300\nM98 P8004\nM30\n%\n".into());
    // A subprogram its own file does not call: verified as a main of its own; goes whole.
    w("main4.nc", main_program(4, 1400, &["M98 P2401", "G00 X2."], "O2401\nG00 Y3.\nM99\nO2402\nG00 Y4.\nM99\n"));
}

/// A job that notes which files its streamed path translated.
struct Watched {
    job: Job<Sinumerik>,
    streamed: Mutex<Vec<String>>,
}

impl FileJob for Watched {
    fn run(&self, f: &InputFile, ctx: &BatchContext) -> FileOutcome {
        match batch::streamed::run(&self.job, f, ctx) {
            Some(o) => {
                self.streamed.lock().expect("lock").push(batch::rel_string(&f.rel));
                o
            }
            None => self.job.run(f, ctx),
        }
    }
}

fn settings(max_steps: u64) -> JobSettings {
    let mut s = JobSettings::from_config(&nctrans::config::Config::default()).expect("settings");
    s.max_steps = max_steps;
    s
}

/// Runs the batch with streaming off and on (every file): the same records, the same files
/// written (the map file too), no staging folder left. Returns the files the streamed run
/// streamed, and its result.
fn both_ways(input: &Path, dir: &Path, max_steps: u64) -> (Vec<String>, batch::BatchResult) {
    let mut results = Vec::new();
    let mut streamed = Vec::new();
    for (k, bytes) in [u64::MAX, 0].into_iter().enumerate() {
        let out = dir.join(format!("out{k}"));
        let mut opts = BatchOptions::new(input, &out, Dialect::Sinumerik);
        opts.stream_bytes = bytes;
        opts.jobs = 2;
        let job = Watched { job: Job::<Sinumerik>::new(settings(max_steps)), streamed: Mutex::new(vec![]) };
        let r = batch::run_batch(opts, &job, Arc::new(AtomicBool::new(false)), &mut |_| {}).expect("batch");
        streamed = job.streamed.into_inner().expect("lock");
        assert!(!out.join(batch::write::STAGING).exists(), "the staging folder is gone");
        results.push((r, snapshot(&out)));
    }
    let (b, a) = (results.pop().expect("streamed"), results.pop().expect("whole"));
    batch_out::assert_same(&a, &b);
    (streamed, b.0)
}

#[test]
fn a_main_with_calls_streams_with_the_same_outputs_map_and_report() {
    let dir = scratch("api");
    let input = dir.join("in");
    library(&input);
    let (streamed, r) = both_ways(&input, &dir, 2_000_000);
    for must in ["fan/main1.nc", "fan/main2.nc", "fan/main5.nc", "fan/main6.nc"] {
        assert!(streamed.iter().any(|s| s == must), "{must} not streamed: {streamed:?}");
        let f = r.files.iter().find(|f| f.path == must).expect("record");
        assert_eq!(f.status, batch::Status::Verified, "{must}: {}", f.summary);
        assert!(f.outputs.len() >= 2, "{must}: the main and its subprograms: {:?}", f.outputs);
    }
    // Its callee is called from other.nc too: with the stand-in.
    assert!(streamed.iter().any(|s| s == "fan/main3.nc"), "main3 not streamed: {streamed:?}");
    for never in ["fan/lib1.nc", "fan/lib2.nc", "fan/lib5.nc", "fan/shared.nc", "fan/main4.nc"] {
        assert!(!streamed.iter().any(|s| s == never), "{never} streamed");
    }
    // The callee files' programs are written by their own jobs, once.
    let main1 = r.files.iter().find(|f| f.path == "fan/main1.nc").expect("main1");
    assert!(main1.outputs.iter().all(|o| !o.contains("8001") && !o.contains("8002")), "{:?}", main1.outputs);
}

/// A main whose check does not prove equivalence (the step limit) is left to the whole job,
/// which gives its verdict: the same records and files as with streaming off.
#[test]
fn a_main_with_calls_that_does_not_verify_gives_the_whole_jobs_verdict() {
    let dir = scratch("steps");
    let input = dir.join("in");
    library(&input);
    let (streamed, r) = both_ways(&input, &dir, 300);
    for f in ["fan/main1.nc", "fan/main2.nc"] {
        assert!(!streamed.iter().any(|s| s == f), "{f} streamed");
        let rec = r.files.iter().find(|x| x.path == f).expect("record");
        assert_ne!(rec.status, batch::Status::Verified, "{f}: {}", rec.summary);
    }
}

/// What `library_scan` reports of a streamed FANUC file with calls and subprograms is what
/// the whole scan reports.
#[test]
fn streamed_scans_of_mains_with_calls_report_what_whole_scans_do() {
    let dir = scratch("scan");
    let input = dir.join("in");
    library(&input);
    let mut names: Vec<_> = std::fs::read_dir(input.join("fan")).expect("dir").filter_map(|e| e.ok()).collect();
    names.sort_by_key(|e| e.file_name());
    let mut with_subs = 0;
    for (index, e) in names.into_iter().enumerate() {
        let f = InputFile { index, rel: Path::new("fan").join(e.file_name()), abs: e.path() };
        let whole = batch::discover::scan(&f, None);
        let mut s =
            batch::streamed::library_scan(&f, None, 0).unwrap_or_else(|| panic!("{} not streamed", f.rel.display()));
        assert!(s.info.streamed);
        s.info.streamed = false;
        s.info.fingerprints = whole.info.fingerprints.clone();
        assert_eq!(s, whole, "{}", f.rel.display());
        if whole.defined.len() > 1 && !whole.calls.is_empty() {
            with_subs += 1;
        }
    }
    assert!(with_subs >= 3, "{with_subs}");
}

#[test]
fn cli_batch_of_mains_with_calls_gives_the_same_files_report_and_exit_code() {
    let dir = scratch("cli");
    let input = dir.join("in");
    library(&input);
    shared_macros(&input);
    let i = input.to_string_lossy().to_string();
    // Verified, and (the subprograms staged without a check) with --no-verify.
    for verify in [true, false] {
        let mut runs = Vec::new();
        for stream in [false, true] {
            let out = dir.join(format!("out-{verify}-{stream}"));
            let report = dir.join(format!("report-{verify}-{stream}.json"));
            let (o, r) = (out.to_string_lossy().to_string(), report.to_string_lossy().to_string());
            let mut args = vec!["--to", "sinumerik", &i, "-o", &o, "--report", &r, "-j", "2"];
            if stream {
                args.push("--stream");
            }
            if !verify {
                args.push("--no-verify");
            }
            let code = Command::new(env!("CARGO_BIN_EXE_nctrans")).args(&args).output().expect("runs").status.code();
            let report = untimed(&std::fs::read_to_string(&report).expect("report")).replace(&o, "OUT");
            runs.push((code, report, snapshot(&out)));
        }
        let (b, a) = (runs.pop().expect("streamed"), runs.pop().expect("whole"));
        assert_eq!((a.0, &a.1), (b.0, &b.1), "verify {verify}");
        assert_eq!(a.2, b.2, "verify {verify}");
        assert!(b.2.contains_key("fan/O_2001.spf") && b.2.contains_key("fan/O_2501.spf"), "{:?}", b.2.keys());
        assert!(b.2.contains_key("fan/MAINC.mpf") && b.2.contains_key("fan/O_9010.spf"), "{:?}", b.2.keys());
    }
}

/// The shop's common case: large CAM mains all calling the macros and subprograms of one
/// library file (G65 with different argument letters, M98, G66), a small file calling them
/// too. Every job translates with a stand-in for the calls the other files make, so the
/// macro's `PROC` line is the same in every job.
fn shared_macros(input: &Path) -> Vec<(&'static str, String)> {
    let fan = input.join("fan");
    std::fs::create_dir_all(&fan).expect("dir");
    let macros = "%\nO9010\nIF [#2 EQ #0] THEN #2=1.\nIF [#24 NE #0] GOTO5\n#24=#1*2\nN5 G01 X#24 Y#2 F200.\n\
                  IF [#26 NE #0] THEN #3=#26\nM99\nO9020\nG00 X#1 Y5.\nM99\nO9030\nG01 Z-#26 F#9\nG00 Z2.\nM99\n%\n";
    let mains = vec![
        ("mainA.nc", main_program(11, 4000, &["G65 P9010 A1. B2.", "M98 P9020", "G65 P9030 Z2. F100."], "")),
        ("mainB.nc", main_program(12, 4100, &["G65 P9010 X3. Z#1", "G65 P9030 Z1. F50.", "G00 X1."], "")),
        (
            "mainC.nc",
            main_program(
                13,
                4200,
                &["G65 P9010 A#1", "M98 P9020", "G66 P9030 Z1. F60.", "G01 X5. F300.\nG67", "M98 P2301"],
                "O2301\nG65 P9010 B4.\nM99\n",
            ),
        ),
    ];
    for (name, text) in &mains {
        std::fs::write(fan.join(name), text).expect("write");
    }
    std::fs::write(fan.join("macros.nc"), macros).expect("write");
    std::fs::write(fan.join("small.nc"), "%\nO4300\nG65 P9010 C5. A1.\nG65 P9030 Z3. F20.\nM30\n%\n").expect("write");
    let mut all: Vec<(&'static str, String)> = mains;
    all.push(("macros.nc", macros.to_string()));
    all
}

/// The trace events of `nctrans run FILE` (the end line left out: step counts differ).
fn events(file: &Path) -> Vec<String> {
    let out = Command::new(env!("CARGO_BIN_EXE_nctrans")).arg("run").arg(file).output().expect("run");
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    text.lines().map(|l| l.split("  @").next().unwrap_or(l).to_string()).filter(|l| !l.starts_with("end ")).collect()
}

#[test]
fn mains_calling_one_shared_macro_file_stream_with_the_whole_jobs_stand_in() {
    let dir = scratch("shared");
    let input = dir.join("in");
    let texts = shared_macros(&input);
    let (streamed, r) = both_ways(&input, &dir, 2_000_000);
    for must in ["fan/mainA.nc", "fan/mainB.nc", "fan/mainC.nc"] {
        assert!(streamed.iter().any(|s| s == must), "{must} not streamed: {streamed:?}");
        let f = r.files.iter().find(|f| f.path == must).expect("record");
        assert_eq!(f.status, batch::Status::Verified, "{must}: {}", f.summary);
    }
    assert!(!streamed.iter().any(|s| s == "fan/macros.nc"), "the macro file streamed");
    // The streamed output folder runs as the library does: each main's calls fit the
    // PROC lines the macro file's own job wrote.
    let macros = &texts.iter().find(|(n, _)| *n == "macros.nc").expect("macros").1;
    let out = dir.join("out1/fan");
    for (name, text) in texts.iter().filter(|(n, _)| n.starts_with("main")) {
        let all = format!("{}{}", text.trim_end_matches("%\n"), macros.trim_start_matches("%\n"));
        let whole = dir.join("all.nc");
        std::fs::write(&whole, all).expect("all");
        let want = events(&whole);
        let mpf = out.join(format!("{}.mpf", name.trim_end_matches(".nc").to_ascii_uppercase()));
        assert!(want.len() > 100, "{name}: {}", want.len());
        assert_eq!(events(&mpf), want, "{name}: the output folder does not run as the library does");
    }
}
