//! Streaming files in legacy encodings: `stream::transcode` decides exactly what
//! `read::decode` decides (for every chunk size, so multi-byte characters straddle chunk
//! boundaries), the decoded copy is the decoded text, and the command line gives the same
//! traces, summaries, translations, diagnostics and exit codes with `--stream` as whole.

#[path = "support/batch_out.rs"]
mod batch_out;

use batch_out::{snapshot, untimed_line};
use encoding_rs::Encoding;
use nctrans::read;
use nctrans::stream::transcode;
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("nctrans-test-enc-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Legacy encodings with a comment each can hold.
fn legacy() -> Vec<(&'static Encoding, &'static str)> {
    vec![
        (encoding_rs::WINDOWS_1252, "Fräser Ø10 Spindel grüßt"),
        (encoding_rs::GBK, "粗加工 刀具 铣刀 直径十毫米 精加工"),
        (encoding_rs::SHIFT_JIS, "荒加工 工具 エンドミル 仕上げ"),
        (encoding_rs::WINDOWS_1250, "Fréza průměr žluťoučký kůň"),
    ]
}

/// A Sinumerik CAM program; with `msg`, an R parameter and a message too (not a
/// straight-line program then).
fn sinumerik_text(comment: &str, eol: &str, blocks: usize, msg: bool) -> String {
    let mut s = format!("; {comment}{eol}G90 G17 G71{eol}");
    if msg {
        s.push_str(&format!("R1=2.5{eol}MSG(\"{comment}\"){eol}"));
    }
    for i in 0..blocks {
        s.push_str(&format!("N{} G1 X{}.{} Y-{} F1200 ; {comment}{eol}", 10 * (i + 1), i, i % 10, i % 7));
    }
    s.push_str(&format!("M30{eol}"));
    s
}

fn fanuc_text(comment: &str, eol: &str, blocks: usize) -> String {
    let mut s = format!("O1000 ({comment}){eol}G90 G17 G21{eol}#100=2.5{eol}");
    for i in 0..blocks {
        s.push_str(&format!("N{} G01 X{}.{} Y-{} F1200. ({comment}){eol}", 10 * (i + 1), i, i % 10, i % 7));
    }
    s.push_str(&format!("M30{eol}"));
    s
}

fn encoded(text: &str, enc: &'static Encoding, bom: bool) -> Vec<u8> {
    let (b, _, unmappable) = enc.encode(text);
    assert!(!unmappable, "{} cannot hold the test text", enc.name());
    let mut v = if bom { b"\xEF\xBB\xBF".to_vec() } else { Vec::new() };
    v.extend_from_slice(&b);
    v
}

fn check_detection(path: &Path, forced: Option<&'static Encoding>, chunk_sizes: &[usize]) {
    let bytes = std::fs::read(path).unwrap();
    let whole = read::decode(&bytes, forced);
    for &c in chunk_sizes {
        let d = transcode::detect_chunked(path, forced, c).unwrap();
        assert_eq!(
            (d.encoding.name(), d.bom, d.line_ending),
            (whole.encoding.name(), whole.bom, whole.line_ending),
            "{} forced {:?} chunk {c}",
            path.display(),
            forced.map(|e| e.name())
        );
    }
    let d = transcode::detect(path, forced).unwrap();
    let mut copy = Vec::new();
    transcode::decode_to(path, &d, &mut copy).unwrap();
    assert_eq!(String::from_utf8(copy).unwrap(), whole.text, "{}", path.display());
}

#[test]
fn detection_matches_the_whole_path_for_every_chunk_size() {
    let dir = scratch("detect");
    let mut n = 0;
    for (enc, comment) in legacy() {
        for eol in ["\n", "\r\n", "\r"] {
            for bom in [false, true] {
                for (ext, text) in
                    [("mpf", sinumerik_text(comment, eol, 12, true)), ("nc", fanuc_text(comment, eol, 12))]
                {
                    let p = dir.join(format!("f{n}.{ext}"));
                    n += 1;
                    std::fs::write(&p, encoded(&text, enc, bom)).unwrap();
                    check_detection(&p, None, &[1, 2, 3, 5, 7, 64, 65536]);
                    check_detection(&p, Some(enc), &[1, 3, 64]);
                    // Forced wrong: the whole path's windows-1252 fallback (or a lucky decode).
                    check_detection(&p, Some(encoding_rs::UTF_8), &[1, 4]);
                    check_detection(&p, Some(encoding_rs::SHIFT_JIS), &[1, 4]);
                    check_detection(&p, Some(encoding_rs::UTF_16LE), &[2]);
                }
            }
        }
    }
    // Edge cases: empty, BOM only, a lone CR at the end, bytes no guess decodes exactly.
    for (i, bytes) in [
        b"".to_vec(),
        b"\xEF\xBB\xBF".to_vec(),
        b"\xEF\xBB".to_vec(),
        b"G1 X1\r".to_vec(),
        b"(\x81\x8d\x8f\x90\x9d)\nM30\n".to_vec(),
        b"(\xff\xfe\xfd)\r\nM30".to_vec(),
        b"(\xe4\xb8)\n".to_vec(),
    ]
    .into_iter()
    .enumerate()
    {
        let p = dir.join(format!("edge{i}.nc"));
        std::fs::write(&p, &bytes).unwrap();
        check_detection(&p, None, &[1, 2, 3, 4, 1024]);
        check_detection(&p, Some(encoding_rs::GBK), &[1, 2, 5]);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn detection_matches_the_whole_path_on_the_corpus() {
    let mut seen = 0;
    for d in ["corpus/in/fanuc", "corpus/in/sinumerik"] {
        let Ok(rd) = std::fs::read_dir(root().join(d)) else {
            println!("note: {d} not found; skipped");
            continue;
        };
        for e in rd.flatten() {
            check_detection(&e.path(), None, &[1, 7, 4096]);
            seen += 1;
        }
    }
    println!("{seen} corpus files");
}

#[test]
fn encode_to_matches_read_encode() {
    let dir = scratch("encode");
    for (enc, comment) in legacy() {
        for bom in [false, true] {
            // "€" and "ℵ" are not in every encoding: numeric references, as read::encode writes.
            let text = format!("(A {comment} € ℵ)\r\nG1 X1\r\n");
            let p = dir.join("u.nc");
            std::fs::write(&p, &text).unwrap();
            let mut out = Vec::new();
            transcode::encode_to(&p, enc, bom, &mut out).unwrap();
            assert_eq!(out, read::encode(&text, enc, bom), "{}", enc.name());
            // A mark at the start of the UTF-8 text (a stream keeping its source's) is not text.
            std::fs::write(&p, format!("\u{feff}{text}")).unwrap();
            let mut out = Vec::new();
            transcode::encode_to(&p, enc, bom, &mut out).unwrap();
            assert_eq!(out, read::encode(&text, enc, bom), "{} after a mark", enc.name());
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn copy_is_removed_on_drop() {
    let _lock = TEMP.lock().unwrap_or_else(|e| e.into_inner());
    let dir = scratch("copy");
    let p = dir.join("x.mpf");
    std::fs::write(&p, encoded(&sinumerik_text("Fräser", "\n", 3, true), encoding_rs::WINDOWS_1252, false)).unwrap();
    let c = transcode::copy(&p, None).unwrap().expect("a legacy file gets a copy");
    let cp = c.path().to_path_buf();
    assert_eq!(cp.file_name(), p.file_name());
    assert!(std::fs::read_to_string(&cp).unwrap().contains("Fräser"));
    drop(c);
    assert!(!cp.exists() && !cp.parent().unwrap().exists());
    std::fs::write(&p, "G1 X1\n").unwrap();
    assert!(transcode::copy(&p, None).unwrap().is_none());
    let _ = std::fs::remove_dir_all(&dir);
}

/// What a command gives: exit code, stdout, stderr and the files it wrote.
#[derive(Debug, PartialEq)]
struct Ran {
    code: i32,
    stdout: Vec<u8>,
    stderr: String,
    files: Vec<(String, Vec<u8>)>,
}

/// Runs nctrans in a fresh folder holding `input` (as `name`) and `nctrans.toml` (when
/// given), with TMPDIR a fresh empty folder: whole, then with `--stream`. Checks the
/// streamed run went through a temporary file (the temp folder changed, when `copied`) and
/// left nothing behind. (That the translations stream is shown at the library level:
/// [`translations_stream_from_the_copy`].)
fn both(case: &str, name: &str, input: &[u8], toml: Option<&str>, args: &[&str], copied: bool) -> (Ran, Ran) {
    let mut out = Vec::new();
    for stream in [false, true] {
        let dir = scratch(&format!("{case}-{stream}"));
        let work = dir.join("w");
        let tmp = dir.join("tmp");
        std::fs::create_dir_all(&work).unwrap();
        std::fs::create_dir_all(&tmp).unwrap();
        std::fs::write(work.join(name), input).unwrap();
        if let Some(t) = toml {
            std::fs::write(work.join("nctrans.toml"), t).unwrap();
        }
        let mut a: Vec<&str> = args.to_vec();
        if stream {
            a.push("--stream");
        }
        let (o, touched) = watched(&work, &tmp, &a, case);
        if stream && copied {
            assert!(touched, "{case}: the streamed run made no decoded copy (read whole?)");
        }
        let mut files: Vec<(String, Vec<u8>)> = std::fs::read_dir(&work)
            .unwrap()
            .flatten()
            .map(|e| (e.file_name().to_string_lossy().into_owned(), std::fs::read(e.path()).unwrap()))
            .collect();
        files.sort();
        out.push(Ran {
            code: o.status.code().unwrap_or(-1),
            stdout: o.stdout,
            stderr: String::from_utf8_lossy(&o.stderr).into_owned(),
            files,
        });
        let _ = std::fs::remove_dir_all(&dir);
    }
    let s = out.pop().unwrap();
    let w = out.pop().unwrap();
    (w, s)
}

fn same(case: &str, name: &str, input: &[u8], toml: Option<&str>, args: &[&str], copied: bool) -> Ran {
    let (w, s) = both(case, name, input, toml, args, copied);
    assert_eq!(w.code, s.code, "{case}: exit codes\nwhole: {}\nstream: {}", w.stderr, s.stderr);
    assert_eq!(w.stderr, s.stderr, "{case}: stderr");
    assert!(w.stdout == s.stdout, "{case}: stdout differs");
    assert!(w.files == s.files, "{case}: written files differ");
    s
}

/// A Sinumerik program with a macro part (a loop back over CAM runs) and legacy comments.
fn sinumerik_macro(comment: &str, eol: &str) -> String {
    let mut s = format!("; {comment}{eol}R1=5 R2=0{eol}N1 G90 G71 F1000{eol}IF R1>3 GOTOF N777{eol}");
    for i in 0..30 {
        s.push_str(&format!("N{} G1 X{}.25 Y{} ; {comment}{eol}", 100 + 10 * i, i, i % 5));
    }
    s.push_str(&format!("N777 G0 Z10{eol}R2=R2+1{eol}IF R2<2 GOTOB N1{eol}M30{eol}"));
    s
}

fn fanuc_macro(comment: &str, eol: &str) -> String {
    let mut s = format!("O2000 ({comment}){eol}#1=0{eol}N1 G90 G21 F1000.{eol}");
    for i in 0..30 {
        s.push_str(&format!("G01 X{}.25 Y{} ({comment}){eol}", i, i % 5));
    }
    s.push_str(&format!("#1=#1+1{eol}IF[#1LT2]GOTO1{eol}M30{eol}"));
    s
}

#[test]
fn cli_streams_legacy_files_as_the_whole_path_reads_them() {
    for (k, (enc, comment)) in legacy().into_iter().enumerate() {
        for (e, eol) in ["\n", "\r\n"].into_iter().enumerate() {
            let bom = e == 1 && k % 2 == 0;
            let forced = enc.name().to_ascii_lowercase();
            let case = format!("{}-{e}", enc.name());
            let sin = encoded(&sinumerik_text(comment, eol, 40, true), enc, bom);
            let sin_t = encoded(&sinumerik_text(comment, eol, 40, false), enc, bom);
            let fan = encoded(&fanuc_text(comment, eol, 40), enc, bom);
            let sin_m = encoded(&sinumerik_macro(comment, eol), enc, bom);
            let fan_m = encoded(&fanuc_macro(comment, eol), enc, bom);
            for (forced_args, tr_args) in
                [(vec![], vec![]), (vec!["--encoding", forced.as_str()], vec!["--input-encoding", forced.as_str()])]
            {
                let f = if forced_args.is_empty() { "detected" } else { "forced" };
                for (n, name, bytes) in [
                    (0, "p.mpf", &sin),
                    (1, "q.nc", &fan),
                    (2, "m.mpf", &sin_m),
                    (3, "n.nc", &fan_m),
                    (4, "t.mpf", &sin_t),
                ] {
                    let mut a = vec!["run", name];
                    a.extend(&forced_args);
                    let r = same(&format!("{case}-{f}-run{n}"), name, bytes, None, &a, true);
                    assert!(!r.stdout.is_empty());
                    let mut a = vec!["parse", "--summary", name];
                    a.extend(&forced_args);
                    same(&format!("{case}-{f}-sum{n}"), name, bytes, None, &a, true);
                    let to = if name.ends_with(".mpf") { "fanuc" } else { "sinumerik" };
                    let out = if to == "fanuc" { "out.nc" } else { "out.mpf" };
                    let mut a = vec!["--to", to, name, "-o", out];
                    a.extend(&tr_args);
                    let r = same(&format!("{case}-{f}-to-{to}{n}"), name, bytes, None, &a, true);
                    assert_eq!(r.code, 0, "{}", r.stderr);
                    // The translation is in the source's encoding and keeps its comment.
                    let written = &r.files.iter().find(|x| x.0 == out).expect("output").1;
                    let back = read::decode(written, Some(enc));
                    assert!(back.text.contains(comment.split(' ').next().unwrap()), "{case}: {}", back.text);
                    let mut a = vec!["--to", to, name];
                    a.extend(&tr_args);
                    same(&format!("{case}-{f}-stdout-{to}{n}"), name, bytes, None, &a, true);
                }
            }
        }
    }
}

#[test]
fn cli_output_encoding_and_bom() {
    let (enc, comment) = legacy()[1];
    let gbk = encoded(&sinumerik_text(comment, "\r\n", 20, false), enc, true);
    // A legacy source with a BOM written as UTF-8: the BOM comes back.
    let r = same(
        "out-utf8",
        "p.mpf",
        &gbk,
        Some("[output]\nencoding = \"utf-8\"\n"),
        &["--to", "fanuc", "p.mpf", "-o", "o.nc"],
        true,
    );
    let o = &r.files.iter().find(|x| x.0 == "o.nc").unwrap().1;
    assert!(o.starts_with(b"\xEF\xBB\xBF") && std::str::from_utf8(o).is_ok());
    // A UTF-8 source written in GBK (no copy of the source; the output is encoded).
    let utf = sinumerik_text(comment, "\n", 20, false);
    let r = same(
        "out-gbk",
        "p.mpf",
        utf.as_bytes(),
        Some("[output]\nencoding = \"gbk\"\n"),
        &["--to", "fanuc", "p.mpf", "-o", "o.nc"],
        true,
    );
    let o = &r.files.iter().find(|x| x.0 == "o.nc").unwrap().1;
    assert!(std::str::from_utf8(o).is_err() && read::decode(o, Some(enc)).text.contains("粗加工"));
    // windows-1252 source, output in Shift-JIS: "ä" has no Shift-JIS code, a reference.
    let latin = encoded(&sinumerik_text("Fräser", "\n", 10, false), encoding_rs::WINDOWS_1252, false);
    let r = same(
        "out-sjis",
        "p.mpf",
        &latin,
        Some("[output]\nencoding = \"shift_jis\"\n"),
        &["--to", "fanuc", "p.mpf", "-o", "o.nc"],
        true,
    );
    assert!(String::from_utf8_lossy(&r.files.iter().find(|x| x.0 == "o.nc").unwrap().1).contains("&#228;"));
}

#[test]
fn cli_diagnostics_point_into_the_decoded_text() {
    let cases: Vec<(&str, Vec<u8>, Vec<&str>)> = vec![
        // A parse error after lines with two-byte characters: line and column from the copy.
        (
            "parse-gbk",
            encoded(
                "; 粗加工 刀具\nG90 G71 F100\nN10 G1 X1 ; 粗加工\nN20 G1 X=(1+ ; 刀具\nM30\n",
                encoding_rs::GBK,
                false,
            ),
            vec!["run", "p.mpf"],
        ),
        (
            "parse-sum",
            encoded("; 粗加工 刀具\r\nN20 G1 X=(1+ ; 刀具\r\nM30\r\n", encoding_rs::GBK, false),
            vec!["parse", "--summary", "p.mpf"],
        ),
        // An alarm while running (in the trace), an evaluation error.
        (
            "alarm-1252",
            encoded("; Fräser Ø10\nG90 G71\nN10 G1 X1 ; Fräser\nM30\n", encoding_rs::WINDOWS_1252, false),
            vec!["run", "p.mpf"],
        ),
        (
            "eval-sjis",
            encoded(
                "; 荒加工 工具\nG90 G71 F100\nN10 G1 X1 ; 荒加工\nR3=UNDEF_VAR+1 ; 工具\nM30\n",
                encoding_rs::SHIFT_JIS,
                false,
            ),
            vec!["run", "p.mpf"],
        ),
        (
            "tr-error",
            encoded("; Fréza žluťoučký\nG90 G71 F100\nN10 G1 X=(1+ ; kůň\nM30\n", encoding_rs::WINDOWS_1250, false),
            vec!["--to", "fanuc", "p.mpf", "-o", "o.nc"],
        ),
    ];
    for (case, bytes, args) in cases {
        let r = same(case, "p.mpf", &bytes, None, &args, true);
        assert_ne!(r.code, 0, "{case}: {}", r.stderr);
        // The alarm is in the trace; the others are rendered with their line.
        assert!(r.stderr.contains("p.mpf:") || case.starts_with("alarm"), "{case}: {}", r.stderr);
        if case == "eval-sjis" {
            assert!(r.stderr.contains("p.mpf:4:4") && r.stderr.contains("R3=UNDEF_VAR+1 ; 工具"), "{}", r.stderr);
        }
    }
}

/// The translations the command-line tests compare do stream (from the decoded copy): the
/// straight or segmented translators accept them (the command line cannot be asked).
#[test]
fn translations_stream_from_the_copy() {
    use nctrans::stream::target::sinumerik as sts;
    use nctrans::stream::{segmented::fanuc as segmented, target::fanuc as st};
    let _lock = TEMP.lock().unwrap_or_else(|e| e.into_inner());
    let dir = scratch("lib");
    for (enc, comment) in legacy() {
        for eol in ["\n", "\r\n"] {
            for (name, text) in [
                ("t.mpf", sinumerik_text(comment, eol, 40, false)),
                ("m.mpf", sinumerik_macro(comment, eol)),
                ("q.nc", fanuc_text(comment, eol, 40)),
                ("n.nc", fanuc_macro(comment, eol)),
            ] {
                let p = dir.join(name);
                std::fs::write(&p, encoded(&text, enc, false)).unwrap();
                let copy = transcode::copy(&p, None).unwrap().expect("a copy");
                let c = copy.path();
                let mut out = Vec::new();
                let case = format!("{} {name} {eol:?}", enc.name());
                if name.ends_with(".mpf") {
                    let o = nctrans::translate::to_fanuc::TranslateOptions {
                        main_name: "T".into(),
                        source_name: name.into(),
                        line_ending: copy.detected.line_ending,
                        ..Default::default()
                    };
                    let straight = st::to_fanuc(c, &o, &mut out, None).is_ok();
                    if !straight {
                        out.clear();
                        assert!(segmented::to_fanuc(c, &o, &mut out, None).is_ok(), "{case}");
                    }
                    assert_eq!(straight, name == "t.mpf", "{case}");
                } else {
                    let o = nctrans::translate::to_sinumerik::Options { main_name: "T".into(), ..Default::default() };
                    let le = copy.detected.line_ending;
                    let straight = sts::to_sinumerik(c, &o, le, &mut out, None).is_ok();
                    if !straight {
                        out.clear();
                        assert!(
                            nctrans::stream::segmented::sinumerik::to_sinumerik(c, &o, le, &mut out, None).is_ok(),
                            "{case}"
                        );
                    }
                }
                let text = String::from_utf8(out).unwrap();
                assert!(text.contains(comment.split(' ').next().unwrap()), "{case}: {text}");
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `check` reads a side that is not UTF-8 whole (its diagnostics are rendered from the
/// file itself): the same verdict with `--stream`, detected or forced, and no copy.
#[test]
fn cli_check_reads_legacy_sides_whole() {
    for (enc, comment) in legacy() {
        let bytes = encoded(&sinumerik_text(comment, "\r\n", 10, true), enc, false);
        let name = enc.name().to_ascii_lowercase();
        let r = same(&format!("check-{name}"), "p.mpf", &bytes, None, &["check", "p.mpf", "p.mpf"], false);
        assert_eq!(r.code, 0, "{}", r.stderr);
        same(
            &format!("checkf-{name}"),
            "p.mpf",
            &bytes,
            None,
            &["check", "p.mpf", "p.mpf", "--encoding", &name],
            false,
        );
    }
}

/// In-process tests that make temporary copies run one at a time, so one can check that
/// none is left in the temp folder.
static TEMP: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// The temp folder's entries this process made (`nctrans-<pid>-…`).
fn my_temp_files() -> Vec<PathBuf> {
    let prefix = format!("nctrans-{}-", std::process::id());
    std::fs::read_dir(std::env::temp_dir())
        .unwrap()
        .flatten()
        .filter(|e| e.file_name().to_string_lossy().starts_with(&prefix))
        .map(|e| e.path())
        .collect()
}

mod batch_jobs {
    use nctrans::batch::jobs::{Job, JobSettings};
    use nctrans::batch::target::{fanuc::Fanuc, sinumerik::Sinumerik};
    use nctrans::batch::{self, BatchContext, FileJob, FileOutcome, InputFile};
    use std::sync::Mutex;

    /// A job that notes which files its streamed path translated.
    pub struct Watched<J> {
        pub job: J,
        pub streamed: Mutex<Vec<String>>,
    }

    impl<J> Watched<J> {
        fn note(&self, f: &InputFile, o: Option<FileOutcome>) -> Option<FileOutcome> {
            if o.is_some() {
                self.streamed.lock().unwrap().push(batch::rel_string(&f.rel));
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

    pub fn settings(out: Option<&'static encoding_rs::Encoding>) -> JobSettings {
        let mut s = JobSettings::from_config(&nctrans::config::Config::default()).unwrap();
        s.max_steps = 2_000_000;
        s.output_encoding = out;
        s
    }
}

/// A batch with streaming off and on: the same records and files. Returns what streamed.
fn batch_both_ways(
    input: &Path,
    dir: &Path,
    target: nctrans::dialect::Dialect,
    forced: Option<&'static Encoding>,
    out_enc: Option<&'static Encoding>,
) -> Vec<String> {
    use batch_jobs::{settings, Watched};
    use nctrans::batch::jobs::Job;
    use nctrans::batch::target::{fanuc::Fanuc, sinumerik::Sinumerik};
    use nctrans::batch::{self, BatchOptions};
    use nctrans::dialect::Dialect;
    use std::sync::atomic::AtomicBool;
    use std::sync::{Arc, Mutex};
    let mut runs = Vec::new();
    let mut streamed = Vec::new();
    for (k, bytes) in [u64::MAX, 0].into_iter().enumerate() {
        let out = dir.join(format!("out{k}"));
        let _ = std::fs::remove_dir_all(&out);
        let mut opts = BatchOptions::new(input, &out, target);
        opts.stream_bytes = bytes;
        opts.jobs = 2;
        opts.encoding = forced;
        let cancel = Arc::new(AtomicBool::new(false));
        let (r, s) = match target {
            Dialect::Sinumerik => {
                let job = Watched { job: Job::<Sinumerik>::new(settings(out_enc)), streamed: Mutex::new(vec![]) };
                (batch::run_batch(opts, &job, cancel, &mut |_| {}).unwrap(), job.streamed.into_inner().unwrap())
            }
            Dialect::Fanuc => {
                let job = Watched { job: Job::<Fanuc>::new(settings(out_enc)), streamed: Mutex::new(vec![]) };
                (batch::run_batch(opts, &job, cancel, &mut |_| {}).unwrap(), job.streamed.into_inner().unwrap())
            }
        };
        runs.push((r, snapshot(&out)));
        streamed = s;
    }
    let (b, a) = (runs.pop().unwrap(), runs.pop().unwrap());
    assert_eq!(a.0.files.len(), b.0.files.len());
    for (x, y) in a.0.files.iter().zip(&b.0.files) {
        let key = |f: &batch::FileRecord| {
            (f.path.clone(), f.outputs.clone(), f.status, f.summary.clone(), f.events, f.blocks, f.diagnostics.clone())
        };
        assert_eq!(key(x), key(y), "{}", x.path);
        // Files already in the target dialect are left alone.
        assert!(matches!(x.status, batch::Status::Verified | batch::Status::Skipped), "{}: {}", x.path, x.summary);
    }
    assert_eq!(a.0.maps, b.0.maps);
    assert_eq!(a.1.keys().collect::<Vec<_>>(), b.1.keys().collect::<Vec<_>>());
    for (k, v) in &a.1 {
        assert!(b.1[k] == *v, "{k} differs");
    }
    streamed.sort();
    streamed
}

#[test]
fn batches_stream_legacy_files_with_the_same_outputs_and_report() {
    use nctrans::dialect::Dialect;
    let _lock = TEMP.lock().unwrap_or_else(|e| e.into_inner());
    let dir = scratch("batch");
    let input = dir.join("in");
    std::fs::create_dir_all(&input).unwrap();
    let mut names = Vec::new();
    for (k, (enc, comment)) in legacy().into_iter().enumerate() {
        let eol = if k % 2 == 0 { "\r\n" } else { "\n" };
        let n = enc.name().to_ascii_lowercase().replace(['-', '_'], "");
        std::fs::write(input.join(format!("s{n}.mpf")), encoded(&sinumerik_text(comment, eol, 30, false), enc, false))
            .unwrap();
        std::fs::write(input.join(format!("m{n}.mpf")), encoded(&sinumerik_macro(comment, eol), enc, false)).unwrap();
        std::fs::write(
            input.join(format!("f{n}.nc")),
            encoded(&fanuc_text(comment, eol, 30).replace("O1000", &format!("O{}", 1100 + k)), enc, false),
        )
        .unwrap();
        std::fs::write(
            input.join(format!("g{n}.nc")),
            encoded(&fanuc_macro(comment, eol).replace("O2000", &format!("O{}", 2100 + k)), enc, false),
        )
        .unwrap();
        names.push(n);
    }
    // A UTF-8 file with a mark beside them.
    std::fs::write(input.join("utf.mpf"), format!("\u{feff}{}", sinumerik_text("Fräser", "\n", 10, false))).unwrap();
    std::fs::write(
        input.join("utf.nc"),
        format!("\u{feff}{}", fanuc_text("Fräser", "\n", 10).replace("O1000", "O1200")),
    )
    .unwrap();
    let to_f = batch_both_ways(&input, &dir.join("f"), Dialect::Fanuc, None, None);
    let to_s = batch_both_ways(&input, &dir.join("s"), Dialect::Sinumerik, None, None);
    for n in &names {
        for f in [format!("s{n}.mpf"), format!("m{n}.mpf")] {
            assert!(to_f.contains(&f), "{f} not streamed: {to_f:?}");
        }
        for f in [format!("f{n}.nc"), format!("g{n}.nc")] {
            assert!(to_s.contains(&f), "{f} not streamed: {to_s:?}");
        }
    }
    // Outputs in another encoding than the sources'.
    for out in [encoding_rs::UTF_8, encoding_rs::GBK] {
        let s = batch_both_ways(&input, &dir.join("fo"), Dialect::Fanuc, None, Some(out));
        assert!(s.len() >= 9, "{s:?}");
        let s = batch_both_ways(&input, &dir.join("so"), Dialect::Sinumerik, None, Some(out));
        assert!(s.len() >= 9, "{s:?}");
    }
    // A forced encoding over files in it.
    let gbk = dir.join("gbk");
    std::fs::create_dir_all(&gbk).unwrap();
    for f in ["sgbk.mpf", "mgbk.mpf", "fgbk.nc", "ggbk.nc"] {
        std::fs::copy(input.join(f), gbk.join(f)).unwrap();
    }
    let s = batch_both_ways(&gbk, &dir.join("gf"), Dialect::Fanuc, Some(encoding_rs::GBK), None);
    assert_eq!(s, ["mgbk.mpf", "sgbk.mpf"]);
    let s = batch_both_ways(&gbk, &dir.join("gs"), Dialect::Sinumerik, Some(encoding_rs::GBK), None);
    assert_eq!(s, ["fgbk.nc", "ggbk.nc"]);
    assert!(my_temp_files().is_empty(), "left behind: {:?}", my_temp_files());
    // The command line: the same report, files and exit code with --stream, nothing left in
    // the temp folder.
    let tmp = dir.join("tmp");
    std::fs::create_dir_all(&tmp).unwrap();
    for to in ["fanuc", "sinumerik"] {
        let mut runs = Vec::new();
        for stream in [false, true] {
            let out = dir.join(format!("cli-{to}-{stream}"));
            let report = dir.join(format!("report-{to}-{stream}.json"));
            let mut args = vec![
                "--to".to_string(),
                to.into(),
                input.display().to_string(),
                "-o".into(),
                out.display().to_string(),
            ];
            args.extend(["--report".to_string(), report.display().to_string()]);
            if stream {
                args.push("--stream".into());
            }
            let o = Command::new(env!("CARGO_BIN_EXE_nctrans")).args(&args).env("TMPDIR", &tmp).output().unwrap();
            let report = std::fs::read_to_string(&report).unwrap().replace(&out.display().to_string(), "OUT");
            let report: Vec<String> = report.lines().map(untimed_line).collect();
            runs.push((o.status.code(), report, snapshot(&out)));
        }
        assert!(runs[0] == runs[1], "--to {to}: {:?}\n{:?}", runs[0].1, runs[1].1);
        assert!(runs[0].1.iter().filter(|l| l.contains("\"status\": \"verified\"")).count() >= 9, "{:?}", runs[0].1);
        assert_eq!(std::fs::read_dir(&tmp).unwrap().count(), 0, "left in the temp folder");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `check` of two legacy-encoded programs (one per dialect): streamed sides read decoded
/// copies and render the divergence from them, exactly as the whole path renders it.
#[test]
fn cli_check_streams_legacy_sides() {
    let a = encoded(
        "; Fräser Ø10\nR1=5\nG0 X=R1 Y0\nG1 X10 F100 ; Schlichten ä\nX12 ; Ø\nM30\n",
        encoding_rs::WINDOWS_1252,
        false,
    );
    for (case, last) in [("equal", "X12."), ("diverged", "X13.")] {
        let b = encoded(
            &format!(
                "%\r\nO1 (粗加工 刀具)\r\n#100=5\r\nG0 X#100 Y0\r\nG1 X10. F100.\r\n{last} (刀具)\r\nM30\r\n%\r\n"
            ),
            encoding_rs::GBK,
            false,
        );
        let mut ran = Vec::new();
        for stream in [false, true] {
            let dir = scratch(&format!("check-{case}-{stream}"));
            let tmp = dir.join("tmp");
            std::fs::create_dir_all(&tmp).unwrap();
            std::fs::write(dir.join("a.mpf"), &a).unwrap();
            std::fs::write(dir.join("b.nc"), &b).unwrap();
            let mut args = vec!["check", "a.mpf", "b.nc"];
            if stream {
                args.push("--stream");
            }
            let (o, touched) = watched(&dir, &tmp, &args, case);
            assert_eq!(touched, stream, "{case}: a decoded copy is made exactly when streaming");
            ran.push((o.status.code(), o.stdout, String::from_utf8_lossy(&o.stderr).into_owned()));
            let _ = std::fs::remove_dir_all(&dir);
        }
        assert_eq!(ran[0], ran[1], "{case}: whole vs streamed");
        if case == "diverged" {
            assert_eq!(ran[1].0, Some(1));
            // (Detection of so short a GBK text guesses another CJK encoding: both paths alike.)
            assert!(ran[1].2.contains("b.nc:6:1") && ran[1].2.contains("a.mpf:5:1") && ran[1].2.contains("X12 ; Ø"));
        } else {
            assert_eq!(ran[1].0, Some(0), "{}", ran[1].2);
        }
    }
}

/// Runs `nctrans ARGS` in `dir` with `tmp` as its temp folder: nothing may be left there;
/// also says whether the run wrote into it (a decoded copy), read off the folder's time.
fn watched(dir: &Path, tmp: &Path, args: &[&str], case: &str) -> (std::process::Output, bool) {
    let old = std::time::SystemTime::UNIX_EPOCH + std::time::Duration::from_secs(1_000_000_000);
    std::fs::File::open(tmp).unwrap().set_modified(old).unwrap();
    let o =
        Command::new(env!("CARGO_BIN_EXE_nctrans")).args(args).current_dir(dir).env("TMPDIR", tmp).output().unwrap();
    let left: Vec<_> = std::fs::read_dir(tmp).unwrap().flatten().map(|e| e.path()).collect();
    assert!(left.is_empty(), "{case}: left behind {left:?}");
    let touched = std::fs::metadata(tmp).unwrap().modified().unwrap() != old;
    (o, touched)
}
