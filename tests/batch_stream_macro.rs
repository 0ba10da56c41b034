//! Batches stream programs with a macro part: a Sinumerik program whose macro part the
//! segmented stream takes is translated and verified as a stream, and the batch writes the
//! same files (outputs and the map file: names used, R parameter homes) and the same report
//! as with streaming off; a Sinumerik main calling subprogram files streams to FANUC with
//! them (the callees go whole), a FANUC main calling another file's program to Sinumerik
//! (more in `batch_stream_calls.rs`); files that must not stream (other calls, a callee,
//! duplicates, diagnostics, names the library collects: tools, FANUC commons) go whole, and
//! the library the batch builds from streamed scans is the one whole scans give. Both
//! directions, through the library API and through the command line (exit code, report).

#[path = "support/batch_out.rs"]
mod batch_out;
#[path = "support/rng.rs"]
mod rng;

use batch_out::{snapshot, untimed};
use nctrans::batch::jobs::{Job, JobSettings};
use nctrans::batch::target::{fanuc::Fanuc, sinumerik::Sinumerik};
use nctrans::batch::{self, BatchContext, BatchOptions, FileJob, FileOutcome, InputFile};
use nctrans::dialect::Dialect;
use rng::Rng;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::AtomicBool;
use std::sync::{Arc, Mutex};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn scratch(name: &str) -> PathBuf {
    let d = root().join("target/batch-stream-macro").join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("dir");
    d
}

/// A Sinumerik CAM block.
fn cam_sinumerik(r: &mut Rng, n: Option<u32>) -> String {
    let mut s = n.map(|n| format!("N{n} ")).unwrap_or_default();
    s.push_str(r.pick(&["G1 ", "G0 ", "", ""]));
    for a in ["X", "Y", "Z"] {
        if r.chance(70) {
            let neg = if r.chance(30) { "-" } else { "" };
            s.push_str(&format!("{a}{neg}{}.{:03} ", r.below(300), r.below(1000)));
        }
    }
    if r.chance(15) {
        s.push_str(&format!("F{} ", 100 + r.below(2000)));
    }
    let t = s.trim_end();
    if t.is_empty() || n.is_some_and(|_| !t.contains(' ')) {
        format!("{t} G1 X1").trim_start().to_string()
    } else {
        t.to_string()
    }
}

/// A Sinumerik program with a macro part (R parameters, structures, labels, jumps to
/// labels and to an N number of a CAM run) around runs of CAM blocks.
fn sinumerik_macro(seed: u64, runs: usize, eol: &str, extra: &str) -> String {
    let mut r = Rng(seed);
    let mut s =
        format!("; generated with a macro part{eol}R1={} R2=0 R9=0{eol}G71 G17 G90 G94 F500{eol}", 2 + r.below(4));
    s.push_str(extra);
    let mut next = 100u32;
    for k in 0..runs {
        let n = 200 + r.index(300);
        let mut numbered = Vec::new();
        for _ in 0..n {
            let num = r.chance(20).then(|| {
                next += 10;
                next
            });
            numbered.extend(num);
            s.push_str(&cam_sinumerik(&mut r, num));
            s.push_str(eol);
        }
        match k % 5 {
            0 => s.push_str(&format!("IF R1>2{eol}G1 X=R1*2 F200{eol}ELSE{eol}G0 Z=R1{eol}ENDIF{eol}")),
            1 => s.push_str(&format!("WHILE R2<3{eol}R2=R2+1{eol}G1 Y=R2{eol}ENDWHILE{eol}R2=0{eol}")),
            2 => s.push_str(&format!(
                "LOOP{eol}R2=R2+1{eol}IF R2>2 GOTOF OUT{k}{eol}ENDLOOP{eol}OUT{k}: G0 Z5{eol}R2=0{eol}"
            )),
            3 if !numbered.is_empty() => {
                let n = numbered[r.index(numbered.len())];
                s.push_str(&format!("R9=R9+1{eol}IF R9<2 GOTOB N{n}{eol}"));
            }
            _ => s.push_str(&format!("R{}=R1+{}.5{eol}G1 X=R{} F300{eol}", 4 + k, k, 4 + k)),
        }
    }
    s.push_str(&format!("G0 Z=R1+10{eol}M30{eol}"));
    s
}

/// A FANUC CAM block.
fn cam_fanuc(r: &mut Rng) -> String {
    let mut s = String::from(r.pick(&["G01 ", "G00 ", "", ""]));
    for a in ["X", "Y", "Z"] {
        if r.chance(70) {
            let neg = if r.chance(30) { "-" } else { "" };
            s.push_str(&format!("{a}{neg}{}.{:03}", r.below(300), r.below(1000)));
        }
    }
    if s.trim().is_empty() {
        s.push_str("X1.");
    }
    s.trim_end().to_string()
}

/// A FANUC program `O<number>` with a macro part (locals, common variables `commons`, a
/// WHILE loop, a backward GOTO) around runs of CAM blocks.
fn fanuc_macro(seed: u64, number: u32, runs: usize, commons: &[u32], extra: &str) -> String {
    let mut r = Rng(seed);
    let mut s = format!("%\nO{number}\n#1=2.\n#2=0\n");
    for c in commons {
        s.push_str(&format!("#{c}=#1+{c}.\n"));
    }
    s.push_str("G21 G17 G90 F500.\n");
    s.push_str(extra);
    for k in 0..runs {
        for _ in 0..150 + r.index(200) {
            s.push_str(&cam_fanuc(&mut r));
            s.push('\n');
        }
        match k % 3 {
            0 => s.push_str("WHILE [#2 LT 3] DO1\n#2=#2+1\nG01 Y#2 F200.\nEND1\n#2=0\n"),
            1 => s.push_str(&format!("N{} #3=#3+1\nIF [#3 LT 2] GOTO{}\n", 900 + k, 900 + k)),
            _ => s.push_str("G00 Z[#1*2]\n"),
        }
    }
    for c in commons {
        s.push_str(&format!("G01 X#{c} F100.\n"));
    }
    s.push_str("M30\n%\n");
    s
}

/// The batch folder: macro programs of both dialects that stream (Sinumerik), that the
/// library scan streams but whose job goes whole, and that must be read whole.
fn library(input: &Path) {
    let sin = input.join("sin");
    let fan = input.join("fan");
    std::fs::create_dir_all(&sin).expect("dir");
    std::fs::create_dir_all(&fan).expect("dir");
    let w = |p: PathBuf, t: String| std::fs::write(p, t).expect("write");
    // Stream (segmented).
    // R8 is read before any write: 0 on Siemens, its FANUC home must be set to 0 too.
    w(sin.join("seg1.mpf"), sinumerik_macro(1, 5, "\n", "G0 X=R8 Y1\nIF R8==0\nG0 Z7\nENDIF\n"));
    w(sin.join("seg2.mpf"), sinumerik_macro(2, 4, "\r\n", ""));
    w(sin.join("seg3.mpf"), format!("%_N_SEGNAMED_MPF\n{}", sinumerik_macro(3, 3, "\n", "")));
    // A byte-order mark (kept in the output).
    w(sin.join("seg4.mpf"), format!("\u{feff}{}", sinumerik_macro(8, 3, "\n", "")));
    // A subprogram no file calls (translated as a subprogram: segmented declines).
    w(sin.join("lone.spf"), sinumerik_macro(9, 2, "\n", "").replace("M30", "M17"));
    // A tool name (the library's tool table numbers it, the segmented stream too). A tool
    // selection alone: a tool change (M6) makes the stream read the program whole (its
    // cutting edge, `passes::comp_to_fanuc`).
    w(sin.join("tools.mpf"), sinumerik_macro(4, 3, "\n", "T=\"MILL_A\"\n"));
    w(sin.join("drill.mpf"), "R1=1\nT=\"ZED_1\"\nG1 X=R1 F100\nM30\n".into());
    // A MSG left as a comment (a note in the report), and one paired with the M0 after it.
    w(sin.join("msg.mpf"), sinumerik_macro(20, 3, "\n", "MSG(\"ROUGHING\")\nG1 X=R2 F100\n"));
    w(sin.join("msgstop.mpf"), sinumerik_macro(21, 3, "\r\n", "MSG(\"CHECK PART\")\r\nM0\r\n"));
    // Calls between files: a main calling subprograms by name streams (to FANUC), with
    // its callees (read whole); a callee goes whole. SUBX sets G71 alone: its F words are
    // in its caller's feed unit, read at run time.
    w(sin.join("caller.mpf"), sinumerik_macro(5, 2, "\n", "SUBX\n"));
    w(sin.join("subx.spf"), format!("PROC SUBX\n{}", sinumerik_macro(6, 2, "\n", "").replace("M30", "M17")));
    w(sin.join("caller3.mpf"), sinumerik_macro(24, 3, "\r\n", "SUBW\r\n"));
    let subw = sinumerik_macro(25, 2, "\n", "").replace("M30", "M17").replace("G71 G17", "G710 G17");
    w(sin.join("subw.spf"), format!("PROC SUBW\n{subw}"));
    // Two callees, one with a parameter, called inside the macro part and between runs.
    let calls2 = sinumerik_macro(22, 4, "\n", "SUBY\nIF R1>1\nSUBZ(2.5)\nENDIF\n").replace("M30", "SUBZ(R1)\nM30");
    w(sin.join("caller2.mpf"), calls2);
    w(sin.join("suby.spf"), "PROC SUBY\nR20=R1+1\nG1 X=R20 F150\nM17\n".into());
    w(sin.join("subz.spf"), "PROC SUBZ(REAL DEP)\nG1 Z=-DEP F80\nIF DEP>2\nSUBY\nENDIF\nM17\n".into());
    // A call of a program no file defines: goes whole.
    w(sin.join("lost.mpf"), sinumerik_macro(23, 2, "\n", "NOWHERE\n"));
    // A warning (a full-width letter).
    w(sin.join("warn.mpf"), sinumerik_macro(7, 2, "\n", "G1 Ｘ5 F100\n"));

    w(fan.join("mac1.nc"), fanuc_macro(11, 7201, 4, &[100, 250], ""));
    w(fan.join("mac2.nc"), fanuc_macro(12, 7202, 3, &[], ""));
    w(fan.join("small.nc"), "%\nO7203\n#120=1.\n#260=2.\nG01 X#120 Y#260 F100.\nM30\n%\n".into());
    w(fan.join("caller.nc"), fanuc_macro(13, 7204, 2, &[], "M98 P7300\n"));
    w(fan.join("callee.nc"), fanuc_macro(14, 7300, 2, &[], "").replace("M30", "M99"));
    w(fan.join("dup1.nc"), fanuc_macro(15, 7400, 2, &[], ""));
    w(fan.join("dup2.nc"), fanuc_macro(16, 7400, 2, &[], ""));
    w(fan.join("warn.nc"), fanuc_macro(17, 7205, 2, &[], "G01 Ｘ5. F100.\n"));
    // Header inputs (both sides read them), CRLF line ends.
    let hdr = fanuc_macro(18, 7206, 3, &[], "G01 X#5 F100.\n").replace("O7206\n", "O7206\n(nctrans: set #5=3.)\n");
    w(fan.join("hdr.nc"), hdr.replace('\n', "\r\n"));
    // A subprogram no file calls.
    w(fan.join("sub.nc"), fanuc_macro(19, 7207, 2, &[], "").replace("M30", "M99"));
    w(sin.join("hdr.mpf"), format!("; nctrans: set R7=2\n{}", sinumerik_macro(10, 2, "\n", "G1 X=R7 F100\n")));
}

/// A job that notes which files its streamed path translated.
struct Watched<J> {
    job: J,
    streamed: Mutex<Vec<String>>,
}

impl<J> Watched<J> {
    fn note(&self, f: &InputFile, o: Option<FileOutcome>) -> Option<FileOutcome> {
        if o.is_some() {
            self.streamed.lock().expect("lock").push(batch::rel_string(&f.rel));
        }
        o
    }
}

impl FileJob for Watched<Job<Sinumerik>> {
    fn run(&self, f: &InputFile, ctx: &BatchContext) -> FileOutcome {
        self.note(f, batch::streamed::run(&self.job, f, ctx)).unwrap_or_else(|| self.job.run(f, ctx))
    }
}

impl FileJob for Watched<Job<Fanuc>> {
    fn run(&self, f: &InputFile, ctx: &BatchContext) -> FileOutcome {
        self.note(f, batch::streamed::run(&self.job, f, ctx)).unwrap_or_else(|| self.job.run(f, ctx))
    }
}

fn settings() -> JobSettings {
    let mut s = JobSettings::from_config(&nctrans::config::Config::default()).expect("settings");
    s.max_steps = 2_000_000;
    s
}

/// Runs the batch with streaming off and on (every file): the same records, the same files
/// written (the map file too). Returns the files the streamed run streamed, and its result.
fn both_ways(input: &Path, dir: &Path, target: Dialect) -> (Vec<String>, batch::BatchResult) {
    let mut results = Vec::new();
    let mut streamed = Vec::new();
    for (k, bytes) in [u64::MAX, 0].into_iter().enumerate() {
        let out = dir.join(format!("out{k}"));
        let mut opts = BatchOptions::new(input, &out, target);
        opts.stream_bytes = bytes;
        opts.jobs = 2;
        // The tool table of tools.mpf and drill.mpf (nctrans never numbers tools itself).
        opts.pinned.tools = [("MILL_A".to_string(), 4), ("ZED_1".to_string(), 7)].into_iter().collect();
        let cancel = Arc::new(AtomicBool::new(false));
        let (r, s) = match target {
            Dialect::Sinumerik => {
                let job = Watched { job: Job::<Sinumerik>::new(settings()), streamed: Mutex::new(vec![]) };
                let r = batch::run_batch(opts, &job, cancel, &mut |_| {}).expect("batch");
                (r, job.streamed.into_inner().expect("lock"))
            }
            Dialect::Fanuc => {
                let job = Watched { job: Job::<Fanuc>::new(settings()), streamed: Mutex::new(vec![]) };
                let r = batch::run_batch(opts, &job, cancel, &mut |_| {}).expect("batch");
                (r, job.streamed.into_inner().expect("lock"))
            }
        };
        results.push((r, snapshot(&out)));
        streamed = s;
    }
    let (b, a) = (results.pop().expect("streamed"), results.pop().expect("whole"));
    batch_out::assert_same(&a, &b);
    (streamed, b.0)
}

#[test]
fn batches_stream_macro_programs_with_the_same_outputs_map_and_report() {
    let dir = scratch("api");
    let input = dir.join("in");
    library(&input);

    let (streamed, r) = both_ways(&input, &dir.join("to-fanuc"), Dialect::Fanuc);
    // tools.mpf, drill.mpf: tool names the batch's tool table numbers (the segmented
    // stream aligns the source it verifies against as the whole path does).
    let must = [
        "sin/seg1.mpf",
        "sin/seg2.mpf",
        "sin/seg3.mpf",
        "sin/seg4.mpf",
        "sin/hdr.mpf",
        "sin/tools.mpf",
        "sin/drill.mpf",
        "sin/msg.mpf",
        "sin/msgstop.mpf",
        "sin/caller3.mpf",
        "sin/caller2.mpf",
        "sin/caller.mpf",
    ];
    for must in must {
        assert!(streamed.iter().any(|s| s == must), "{must} not streamed: {streamed:?}");
        let f = r.files.iter().find(|f| f.path == must).expect("record");
        assert_eq!(f.status, batch::Status::Verified, "{must}: {}", f.summary);
    }
    for never in
        ["sin/subx.spf", "sin/subw.spf", "sin/suby.spf", "sin/subz.spf", "sin/lost.mpf", "sin/warn.mpf", "sin/lone.spf"]
    {
        assert!(!streamed.iter().any(|s| s == never), "{never} streamed");
    }
    assert!(r.maps.tools.contains_key("MILL_A"), "{:?}", r.maps.tools);
    let warn = r.files.iter().find(|f| f.path == "sin/warn.mpf").expect("warn");
    assert!(warn.diagnostics.iter().any(|d| d.code == "NC110"), "{:?}", warn.diagnostics);

    // FANUC → Sinumerik: the library scan streams the macro programs (their commons count
    // for every file's variable places), and the segmented FANUC stream translates them.
    let (streamed, r) = both_ways(&input, &dir.join("to-sinumerik"), Dialect::Sinumerik);
    // caller.nc streams with its callee file (`streamed_calls`); the callee goes whole.
    for must in ["fan/mac1.nc", "fan/mac2.nc", "fan/small.nc", "fan/hdr.nc", "fan/caller.nc"] {
        assert!(streamed.iter().any(|s| s == must), "{must} not streamed: {streamed:?}");
    }
    for never in ["fan/callee.nc", "fan/dup1.nc", "fan/dup2.nc", "fan/warn.nc"] {
        assert!(!streamed.iter().any(|s| s == never), "{never} streamed");
    }
    for f in ["fan/mac1.nc", "fan/mac2.nc", "fan/small.nc", "fan/hdr.nc", "fan/sub.nc"] {
        let f = r.files.iter().find(|x| x.path == f).expect("record");
        assert_eq!(f.status, batch::Status::Verified, "{}: {}", f.path, f.summary);
    }
}

/// What `library_scan` reports of a streamed file is what the whole scan reports.
#[test]
fn streamed_library_scans_report_what_whole_scans_do() {
    let dir = scratch("scan");
    let input = dir.join("in");
    library(&input);
    let mut checked = 0;
    let mut with_calls = 0;
    for sub in ["sin", "fan"] {
        let mut names: Vec<_> = std::fs::read_dir(input.join(sub)).expect("dir").filter_map(|e| e.ok()).collect();
        names.sort_by_key(|e| e.file_name());
        for (index, e) in names.into_iter().enumerate() {
            let f = InputFile { index, rel: Path::new(sub).join(e.file_name()), abs: e.path() };
            let whole = batch::discover::scan(&f, None);
            let Some(mut s) = batch::streamed::library_scan(&f, None, 0) else {
                let rel = batch::rel_string(&f.rel);
                assert!(
                    !whole.calls.is_empty() || whole.info.parse_errors > 0 || rel.contains("warn"),
                    "{rel} not streamed"
                );
                continue;
            };
            // Calls by a constant name (Sinumerik) or number (FANUC) are streamed.
            if !whole.calls.is_empty() {
                with_calls += 1;
            }
            assert!(s.info.streamed);
            s.info.streamed = false;
            s.info.fingerprints = whole.info.fingerprints.clone();
            assert_eq!(s, whole, "{}", f.rel.display());
            checked += 1;
        }
    }
    assert!(checked >= 17, "{checked}");
    assert!(with_calls >= 4, "{with_calls}");
}

fn cli(args: &[&str]) -> Option<i32> {
    Command::new(env!("CARGO_BIN_EXE_nctrans")).args(args).output().expect("runs").status.code()
}

#[test]
fn cli_batch_with_stream_gives_the_same_files_report_and_exit_code() {
    let dir = scratch("cli");
    let input = dir.join("in");
    library(&input);
    let i = input.to_string_lossy().to_string();
    for to in ["fanuc", "sinumerik"] {
        let mut runs = Vec::new();
        for stream in [false, true] {
            let out = dir.join(format!("out-{to}-{stream}"));
            let report = dir.join(format!("report-{to}-{stream}.json"));
            let (o, r) = (out.to_string_lossy().to_string(), report.to_string_lossy().to_string());
            let mut args = vec!["--to", to, &i, "-o", &o, "--report", &r, "-j", "2"];
            if stream {
                args.push("--stream");
            }
            let code = cli(&args);
            let report = untimed(&std::fs::read_to_string(&report).expect("report")).replace(&o, "OUT");
            runs.push((code, report, snapshot(&out)));
        }
        let (b, a) = (runs.pop().expect("streamed"), runs.pop().expect("whole"));
        assert_eq!((a.0, &a.1), (b.0, &b.1), "--to {to}");
        assert_eq!(a.2, b.2, "--to {to}");
    }
}
