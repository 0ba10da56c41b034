//! Segmented streaming translation (Sinumerik → FANUC with a macro part): where it does not
//! decline, its output is byte-identical to the whole-file translation and its streamed
//! verification gives the same verdict as `translate::verify`. Inputs: every corpus
//! Sinumerik program with runs of generated CAM blocks put between its top-level
//! statements, and generated programs (macro prologue/epilogue, structures, jumps to labels
//! and to N numbers inside CAM runs, duplicate N numbers, LF and CRLF).

#[path = "support/rng.rs"]
mod rng;

use nctrans::dialect::fanuc::emit::CommentMode;
use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::span::SourceDb;
use nctrans::stream::segmented;
use nctrans::stream::translate::Fallback;
use nctrans::translate::{self, TranslateOptions};
use rng::Rng;
use std::path::{Path, PathBuf};

const MAX_STEPS: u64 = 200_000;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn scratch() -> PathBuf {
    let d = root().join("target/stream-segmented-tests");
    std::fs::create_dir_all(&d).expect("dir");
    d
}

fn opts(path: &Path, text: &str) -> TranslateOptions {
    TranslateOptions {
        main_name: path.file_stem().and_then(|s| s.to_str()).unwrap_or("MAIN").to_ascii_uppercase(),
        source_name: path.file_name().and_then(|s| s.to_str()).unwrap_or("").to_string(),
        line_ending: nctrans::read::detect_line_ending(text),
        ..TranslateOptions::default()
    }
}

/// What happened to one program.
enum Outcome {
    Declined(String),
    /// Identical; whether verification found them equivalent.
    Same(bool),
}

/// Translates `text` (written to `name`) whole and segmented; when segmented does not
/// decline, asserts the same bytes and the same verification verdict.
fn compare(name: &str, text: &str) -> Outcome {
    compare_with(name, text, CommentMode::Keep)
}

/// [`compare`] with a comment mode.
fn compare_with(name: &str, text: &str, comments: CommentMode) -> Outcome {
    let dir = scratch();
    let path = dir.join(name);
    std::fs::write(&path, text).expect("write");
    let mut db = SourceDb::new();
    let loaded = nctrans::load(&mut db, &path.display().to_string(), text.as_bytes(), None);
    let popts = ParseOptions::for_dialect(Dialect::Sinumerik);
    let parsed = nctrans::parse(&db, loaded.file, Dialect::Sinumerik, &popts);
    let o = TranslateOptions { comments, ..opts(&path, text) };
    let t = translate::to_fanuc(&parsed.unit, &[], &o);
    let mut out = Vec::new();
    let seg = match segmented::to_fanuc(&path, &o, &mut out, None) {
        Ok(s) => s,
        Err(Fallback::NotStraight(why)) => return Outcome::Declined(why),
        Err(f) => return Outcome::Declined(format!("{f:?}")),
    };
    assert!(
        parsed.diags.is_empty() && t.diags.is_empty() && t.unsupported == 0,
        "{name}: segmented took a program with diagnostics"
    );
    let got = String::from_utf8_lossy(&out);
    if got != t.text {
        let at = got.bytes().zip(t.text.bytes()).take_while(|(a, b)| a == b).count();
        panic!(
            "{name}: segmented output differs at byte {at}:\n--- whole ---\n{}\n--- segmented ---\n{}",
            &t.text[at.saturating_sub(200).min(t.text.len())..(at + 200).min(t.text.len())],
            &got[at.saturating_sub(200).min(got.len())..(at + 200).min(got.len())]
        );
    }
    let out_path = dir.join(format!("{name}.nc"));
    std::fs::write(&out_path, &out).expect("write");
    let v = nctrans::stream::translate::verify(seg.index, &out_path, MAX_STEPS, seg.inputs, None);
    let w = translate::verify(&mut db, &parsed.unit, &[], &t, "out.nc", MAX_STEPS);
    assert_eq!(v.equivalent, w.equivalent, "{name}: verdicts {} / {}", v.summary, w.summary);
    assert_eq!(v.summary, w.summary, "{name}");
    Outcome::Same(v.equivalent)
}

/// A generated CAM block (no N number unless `n`).
fn cam_block(r: &mut Rng, n: Option<u32>) -> String {
    let mut s = String::new();
    if r.chance(5) {
        s.push('/');
    }
    if let Some(n) = n {
        s.push_str(&format!("N{n} "));
    }
    match r.below(6) {
        0 => s.push_str("G0 "),
        1 => s.push_str("G1 "),
        2 => s.push_str("g01 "),
        _ => {}
    }
    for a in ["X", "Y", "Z"] {
        if r.chance(70) {
            let neg = if r.chance(30) { "-" } else { "" };
            match r.below(3) {
                0 => s.push_str(&format!("{a}{neg}{}.{:03} ", r.below(500), r.below(1000))),
                1 => s.push_str(&format!("{a}{neg}{} ", r.below(500))),
                _ => s.push_str(&format!("{a}={neg}{}.{} ", r.below(50), r.below(10))),
            }
        }
    }
    if r.chance(20) {
        s.push_str(&format!("F{} ", 100 + r.below(2000)));
    }
    if r.chance(10) {
        s.push_str("; cam (pass)");
    }
    let t = s.trim_end().to_string();
    if t.is_empty() || t == "/" {
        "G1 X1".into()
    } else {
        t
    }
}

/// `n` CAM blocks, numbered from `next` now and then.
fn cam_run(r: &mut Rng, n: usize, next: &mut u32, eol: &str, numbers: &mut Vec<u32>) -> String {
    let mut s = String::new();
    for _ in 0..n {
        let num = if r.chance(40) {
            *next += 10;
            // Now and then a number used before (duplicate N numbers).
            let v = if r.chance(10) && !numbers.is_empty() { numbers[r.index(numbers.len())] } else { *next };
            numbers.push(v);
            Some(v)
        } else {
            None
        };
        s.push_str(&cam_block(r, num));
        s.push_str(eol);
    }
    s
}

#[test]
fn corpus_programs_with_cam_runs_inserted() {
    let Ok(rd) = std::fs::read_dir(root().join("corpus/in/sinumerik")) else {
        println!("note: corpus/in/sinumerik not found; skipped");
        return;
    };
    let mut files: Vec<PathBuf> = rd.filter_map(|e| e.ok()).map(|e| e.path()).collect();
    files.sort();
    let (mut same, mut declined) = (0, 0);
    let mut r = Rng(0x5E6_0007);
    for f in &files {
        let Ok(text) = String::from_utf8(std::fs::read(f).expect("read")) else { continue };
        let text = text.trim_start_matches('\u{feff}').to_string();
        let eol = nctrans::read::detect_line_ending(&text).as_str();
        let mut db = SourceDb::new();
        let l = nctrans::load(&mut db, "x.mpf", text.as_bytes(), None);
        let parsed = nctrans::parse(&db, l.file, Dialect::Sinumerik, &ParseOptions::for_dialect(Dialect::Sinumerik));
        // Insert after the line each top-level statement ends on.
        let mut cuts: Vec<usize> = parsed
            .unit
            .programs
            .first()
            .map(|p| {
                p.body
                    .iter()
                    .filter_map(|s| {
                        let hi = s.span.hi as usize;
                        let rest = text.get(hi..)?;
                        let k = rest.find(eol)?;
                        Some(hi + k + eol.len())
                    })
                    .collect()
            })
            .unwrap_or_default();
        cuts.sort();
        cuts.dedup();
        let mut out = String::new();
        let mut at = 0;
        let mut next = 50_000;
        let mut numbers = vec![];
        for c in cuts {
            out.push_str(&text[at..c]);
            let n = r.index(12);
            out.push_str(&cam_run(&mut r, n, &mut next, eol, &mut numbers));
            at = c;
        }
        out.push_str(&text[at..]);
        let name = f.file_name().and_then(|s| s.to_str()).unwrap_or("x.mpf").to_string();
        match compare(&format!("corpus-{name}"), &out) {
            Outcome::Same(_) => same += 1,
            Outcome::Declined(_) => declined += 1,
        }
    }
    println!("corpus: {same} segmented and identical, {declined} declined");
    assert!(same >= 10, "only {same} corpus programs were segmented ({declined} declined)");
}

/// A generated program with a macro part around CAM runs.
fn generated(r: &mut Rng, eol: &str) -> String {
    let mut numbers: Vec<u32> = vec![];
    let mut next = 0u32;
    let mut runs: Vec<String> = Vec::new();
    // The numbers of the runs up to and after each one (forward and backward jump targets).
    let mut upto: Vec<Vec<u32>> = Vec::new();
    let n_runs = 2 + r.index(4);
    for _ in 0..n_runs {
        let n = 1 + r.index(40);
        runs.push(cam_run(r, n, &mut next, eol, &mut numbers));
        upto.push(numbers.clone());
    }
    let mut s = format!("%_N_GEN_MPF{eol}; generated{eol}R1={} R2=0 R9=0{eol}", r.below(6));
    if r.chance(50) {
        s.push_str(&format!("N5 G90 G17 G71{eol}"));
    }
    for (k, run) in runs.iter().enumerate() {
        s.push_str(run);
        match r.below(7) {
            0 => s.push_str(&format!("IF R1>2{eol}G1 X=R1*2 F200{eol}ELSE{eol}G0 Z=R1{eol}ENDIF{eol}")),
            1 => s.push_str(&format!("WHILE R2<3{eol}R2=R2+1{eol}G1 Y=R2{eol}ENDWHILE{eol}R2=0{eol}")),
            2 => s.push_str(&format!(
                "LOOP{eol}R2=R2+1{eol}IF R2>2 GOTOF OUT{k}{eol}ENDLOOP{eol}OUT{k}: G0 Z5{eol}R2=0{eol}"
            )),
            3 if numbers.len() > upto[k].len() => {
                // A jump forward into a later CAM run (maybe to a duplicate number).
                let later = &numbers[upto[k].len()..];
                let n = later[r.index(later.len())];
                let how = r.pick(&["GOTOF", "GOTO", "GOTOC"]);
                s.push_str(&format!("IF R1>1 {how} N{n}{eol}"));
            }
            4 if !upto[k].is_empty() => {
                // Back into an earlier CAM run, once.
                let n = upto[k][r.index(upto[k].len())];
                let how = r.pick(&["GOTOB", "GOTO"]);
                s.push_str(&format!("R9=R9+1{eol}IF R9<2 {how} N{n}{eol}"));
            }
            5 => s.push_str(&format!("LBL{k}: G1 X{k}{eol}R3=R3+{k}{eol}")),
            _ => s.push_str(&format!("R{}=R1+{}.5{eol}", 4 + k, k)),
        }
    }
    if r.chance(50) {
        s.push_str(&format!("GOTOF FIN{eol}G1 X999{eol}FIN:{eol}"));
    }
    s.push_str(&format!("M30{eol}"));
    s
}

#[test]
fn generated_macro_programs() {
    let mut r = Rng(0xC0FF_EE07);
    let (mut same, mut declined, mut equivalent) = (0, 0, 0);
    let mut why = Vec::new();
    for case in 0..120 {
        let eol = if case % 2 == 0 { "\n" } else { "\r\n" };
        let text = generated(&mut r, eol);
        let comments = [CommentMode::Keep, CommentMode::Drop, CommentMode::Ascii][case % 3];
        match compare_with(&format!("gen{case}.mpf"), &text, comments) {
            Outcome::Same(eq) => {
                same += 1;
                equivalent += usize::from(eq);
            }
            Outcome::Declined(w) => {
                declined += 1;
                why.push(w);
            }
        }
    }
    println!(
        "generated: {same} segmented and identical ({equivalent} verified equivalent), {declined} declined: {why:?}"
    );
    assert!(equivalent >= 90, "only {equivalent} verified equivalent");
    assert!(same >= 90, "only {same} of 120 generated programs were segmented: {why:?}");
}

#[test]
fn declines_what_it_does_not_handle() {
    for (name, text) in [
        ("inch.mpf", "R1=1\nG70 G1 X1\nX2\nM30\n"),
        ("msg.mpf", "MSG(\"HI\")\nG1 X1\nM30\n"),
        ("call.mpf", "R1=1\nSUBPROG\nG1 X1\nM30\n"),
        ("acic.mpf", "R1=1\nG1 X=AC(R1)\nM30\n"),
    ] {
        match compare(name, text) {
            Outcome::Declined(_) => {}
            Outcome::Same(_) => panic!("{name} was segmented"),
        }
    }
}

/// The command line takes the segmented route for a large program with a macro part (no
/// "read whole" note), writes what the library writes, and verifies it. Minutes in a debug
/// build: `cargo test --release --test stream_segmented -- --ignored`.
#[test]
#[ignore]
fn cli_streams_a_large_macro_program() {
    let dir = scratch();
    let path = dir.join("bigmacro.mpf");
    let mut r = Rng(0xB16);
    let mut text = String::from("%_N_BIGMACRO_MPF\nR1=5 R2=0\nN1 G90 G71\nIF R1>3 GOTOF N77777\n");
    let (mut numbers, mut middle) = (vec![], false);
    while text.len() < 8_500_000 {
        // Numbers repeat from run to run (the labels pass would wrap past N99999).
        let mut next = 100;
        text.push_str(&cam_run(&mut r, 1000, &mut next, "\n", &mut numbers));
        if text.len() > 4_000_000 && !middle {
            // N numbers of the runs end in 0: this one is unique.
            text.push_str("N77777 G0 Z10\nR2=R2+1\nIF R2<2 GOTOB N1\n");
            middle = true;
        }
    }
    text.push_str("M30\n");
    std::fs::write(&path, &text).expect("write");
    let out = dir.join("bigmacro.nc");
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_nctrans"))
        .args(["--to", "fanuc"])
        .arg(&path)
        .arg("-o")
        .arg(&out)
        .output()
        .expect("run nctrans");
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{stderr}");
    assert!(!stderr.contains("read whole") && stderr.contains("equivalent"), "{stderr}");
    // What the library writes (identical to the whole translation: the tests above; the
    // whole-file path would need gigabytes here).
    let mut lib = Vec::new();
    segmented::to_fanuc(&path, &opts(&path, &text), &mut lib, None).map_err(|e| format!("{e:?}")).expect("segmented");
    assert!(std::fs::read(&out).expect("output") == lib);
}

/// `--stream` on a small program with a macro part: the whole translation's bytes, verified.
#[test]
fn cli_stream_writes_the_whole_translation() {
    let mut r = Rng(0x5EC7);
    for (k, eol) in ["\n", "\r\n"].into_iter().enumerate() {
        let text = generated(&mut r, eol);
        let path = scratch().join(format!("cli{k}.mpf"));
        std::fs::write(&path, &text).expect("write");
        let out = scratch().join(format!("cli{k}.nc"));
        let run = std::process::Command::new(env!("CARGO_BIN_EXE_nctrans"))
            .args(["--stream", "--to", "fanuc"])
            .arg(&path)
            .arg("-o")
            .arg(&out)
            .output()
            .expect("run nctrans");
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert!(run.status.success() && stderr.contains("equivalent"), "{stderr}");
        let mut db = SourceDb::new();
        let loaded = nctrans::load(&mut db, &path.display().to_string(), text.as_bytes(), None);
        let popts = ParseOptions::for_dialect(Dialect::Sinumerik);
        let parsed = nctrans::parse(&db, loaded.file, Dialect::Sinumerik, &popts);
        let whole = translate::to_fanuc(&parsed.unit, &[], &opts(&path, &text));
        assert!(std::fs::read(&out).expect("output") == whole.text.as_bytes());
        // The library takes it segmented (so the command line did too, or it would have
        // said nothing different: the bytes are the same either way).
        assert!(matches!(compare(&format!("cli{k}b.mpf"), &text), Outcome::Same(true)));
    }
}
