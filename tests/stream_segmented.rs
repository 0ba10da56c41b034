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
use nctrans::stream::segmented::fanuc as segmented;
use nctrans::stream::Fallback;
use nctrans::translate::{self, to_fanuc::TranslateOptions};
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
    compare_full(name, text, comments, false)
}

/// [`compare_with`]; `noted`: through `to_fanuc_with_notes` (its notes must be the whole
/// translation's diagnostics).
fn compare_full(name: &str, text: &str, comments: CommentMode, noted: bool) -> Outcome {
    compare_tools(name, text, comments, noted, &[])
}

/// [`compare_full`] with a tool map (`--tool-map NAME=n`).
fn compare_tools(name: &str, text: &str, comments: CommentMode, noted: bool, tools: &[(&str, u32)]) -> Outcome {
    let dir = scratch();
    let path = dir.join(name);
    std::fs::write(&path, text).expect("write");
    let mut db = SourceDb::new();
    let loaded = nctrans::load(&mut db, &path.display().to_string(), text.as_bytes(), None);
    let popts = ParseOptions::for_dialect(Dialect::Sinumerik);
    let parsed = nctrans::parse(&db, loaded.file, Dialect::Sinumerik, &popts);
    let mut o = TranslateOptions { comments, ..opts(&path, text) };
    o.tool_map.extend(tools.iter().map(|(k, v)| (k.to_string(), *v)));
    let t = translate::to_fanuc::to_fanuc(&parsed.unit, &[], &o);
    let mut out = Vec::new();
    let r = if noted {
        segmented::to_fanuc_with_notes(&path, &o, &mut out, None)
    } else {
        segmented::to_fanuc(&path, &o, &mut out, None).map(|s| (s, vec![]))
    };
    let (seg, notes) = match r {
        Ok(s) => s,
        Err(Fallback::NotStraight(why)) => return Outcome::Declined(why),
        Err(f) => return Outcome::Declined(format!("{f:?}")),
    };
    assert!(
        parsed.diags.is_empty() && t.diags == notes && t.unsupported == 0,
        "{name}: segmented took a program with diagnostics, or its notes differ"
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
    let v = nctrans::stream::verify::verify(seg.index, &out_path, MAX_STEPS, seg.inputs, None);
    let w = translate::to_fanuc::verify(&mut db, &parsed.unit, &[], &t.clone().into(), "out.nc", MAX_STEPS);
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
    let mut why = Vec::new();
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
        match compare_full(&format!("corpus-{name}"), &out, CommentMode::Keep, true) {
            Outcome::Same(_) => same += 1,
            Outcome::Declined(w) => {
                declined += 1;
                why.push(format!("{name}: {w}"));
            }
        }
    }
    println!("corpus: {same} segmented and identical, {declined} declined: {why:?}");
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

/// 120 programs from `generate` (seeded with `seed`; LF and CRLF, every comment mode),
/// each segmented and compared with the whole translation: how many came out the same,
/// how many of those verified equivalent, and why the others declined.
fn segment_generated(name: &str, seed: u64, generate: fn(&mut Rng, &str) -> String) -> (usize, usize, Vec<String>) {
    let mut r = Rng(seed);
    let (mut same, mut equivalent) = (0, 0);
    let mut why = Vec::new();
    for case in 0..120 {
        let eol = if case % 2 == 0 { "\n" } else { "\r\n" };
        let text = generate(&mut r, eol);
        let comments = [CommentMode::Keep, CommentMode::Drop, CommentMode::Ascii][case % 3];
        match compare_with(&format!("{name}{case}.mpf"), &text, comments) {
            Outcome::Same(eq) => {
                same += 1;
                equivalent += usize::from(eq);
            }
            Outcome::Declined(w) => why.push(w),
        }
    }
    println!(
        "{name}: {same} segmented and identical ({equivalent} verified equivalent), {} declined: {why:?}",
        why.len()
    );
    (same, equivalent, why)
}

#[test]
fn generated_macro_programs() {
    let (same, equivalent, why) = segment_generated("gen", 0xC0FF_EE07, generated);
    assert!(equivalent >= 90, "only {equivalent} verified equivalent");
    assert!(same >= 90, "only {same} of 120 generated programs were segmented: {why:?}");
}

/// A mode line for a CAM run: inch/metric switches (G70 reads F metric, after G700 too:
/// `F[f/25.4]`) and
/// G90/G91, alone or with a move.
fn mode_line(r: &mut Rng) -> String {
    let g = r.pick(&["G70", "G71", "G700", "G710", "G90", "G91", "G70 G91", "G71 G90", "G700 G71", "G710 G70"]);
    match r.below(3) {
        0 => g.to_string(),
        1 => format!("{g} G1 X{}.5 F{}", r.below(9), 100 + r.below(900)),
        _ => format!("{g} Y{}", r.below(9)),
    }
}

/// A generated program whose CAM runs switch G70/G71/G700/G710 and G90/G91, with a macro
/// part that reads those modes (F under G70, AC()/IC() words), MSG lines before a lone M0
/// (in the macro part or starting a run) and now and then a case that must decline (a MSG
/// not followed by M0, a MSG beside other items).
fn generated_modes(r: &mut Rng, eol: &str) -> String {
    let mut next = 0u32;
    let mut numbers = vec![];
    let mut s = format!("%_N_GENM_MPF{eol}R1={} R2=0{eol}", 1 + r.below(4));
    if r.chance(50) {
        s.push_str(&format!("MSG(\"SETUP {}\"){eol}M0{eol}", r.below(99)));
    }
    let g = r.pick(&["G70", "G71", "G700", "G710", "G90 G71", ""]);
    if !g.is_empty() {
        s.push_str(&format!("{g}{eol}"));
    }
    let n_runs = 2 + r.index(4);
    for k in 0..n_runs {
        let n = 1 + r.index(12);
        for _ in 0..n {
            if r.chance(25) {
                s.push_str(&mode_line(r));
                s.push_str(eol);
            }
            let m = 1 + r.index(3);
            s.push_str(&cam_run(r, m, &mut next, eol, &mut numbers));
        }
        match r.below(10) {
            0 => s.push_str(&format!("G1 X=AC(R1+{k}) F=R1*100{eol}")),
            1 => s.push_str(&format!("G1 Y=IC(R1) Z=IC(-1){eol}")),
            // Modes that differ by branch decline (the translator merges paths, a stream
            // follows the text): now and then only.
            2 if r.chance(20) => {
                s.push_str(&format!("IF R1>2{eol}G70 G1 X=R1 F200{eol}ELSE{eol}G91 X=AC(1){eol}ENDIF{eol}"))
            }
            2 => s.push_str(&format!("IF R1>2{eol}G1 X=R1 F200{eol}ELSE{eol}X=AC(1){eol}ENDIF{eol}")),
            3 => s.push_str(&format!("WHILE R2<2{eol}R2=R2+1{eol}G1 X=IC(R2) F=R2*50{eol}ENDWHILE{eol}R2=0{eol}")),
            // Paired with the M0 that starts the next run.
            4 => s.push_str(&format!("MSG(\"CHECK {k}\"){eol}M0{eol}")),
            5 => s.push_str(&format!("MSG(\"TURN {k}\"){eol}M0 ; turn over{eol}G1 F=R1*10 X=AC(3){eol}")),
            6 if r.chance(30) => s.push_str(&format!("MSG(\"INFO {k}\"){eol}")),
            7 if r.chance(30) => s.push_str(&format!("MSG(\"A\") R3=2{eol}M0{eol}")),
            _ => s.push_str(&format!("R{}=R1+{}.5 G1 F=R1*10 X=R1{eol}", 4 + k, k)),
        }
    }
    s.push_str(&format!("M30{eol}"));
    s
}

#[test]
fn generated_mode_switches_ac_ic_and_msg() {
    let (same, equivalent, why) = segment_generated("genm", 0x1DC7_0070, generated_modes);
    assert!(same >= 80, "only {same} of 120 programs with mode switches were segmented: {why:?}");
    assert!(equivalent >= 30, "only {equivalent} verified equivalent");
}

/// Each mode a CAM run changes reaches the skeleton after it, and each run starts in the
/// mode before it (small programs, each rule alone).
#[test]
fn modes_cross_run_boundaries() {
    for (name, text) in [
        // G70 in a run: F of the macro block after it is per inch.
        ("inch-run.mpf", "R1=1\nG1 X1 F100\nG70 X2\nR2=2\nG1 X=R1 F300\nM30\n"),
        // G70 in the macro part: the run after it divides F.
        ("inch-macro.mpf", "R1=1\nG70 G1 X=R1\nG1 X1 F100\nY2 F200\nR2=1\nG71 X=R2\nX3 F50\nM30\n"),
        ("inch-off.mpf", "R1=1\nG70\nG1 X1 F100\nG710 X2 F10\nR1=2\nG1 X=R1 F20\nM30\n"),
        // G91 in one branch: the AC() after it reads the mode at run time (#4003), in the
        // skeleton; the run between takes no mode from it.
        ("abs-if.mpf", "R1=1\nG1 X1 F100\nIF R1>5\nG91\nENDIF\nG1 X2\nX3\nR2=1\nX=AC(R2)\nM30\n"),
        // G91 in a run: the IC() word after it needs no switch; AC() does.
        ("abs-run.mpf", "R1=1\nG1 X1\nG91 X2\nR2=2\nG1 X=IC(R1)\nY=AC(R2)\nG90 X1\nR3=1\nG1 X=AC(R3)\nY=IC(1)\nM30\n"),
        // MSG in the macro part, M0 the next (straight) block: a stop with the message.
        ("msg-m0.mpf", "R1=1\nG1 X1\nMSG(\"LOOK\")\nM0\nG1 X2\nM30\n"),
        // CR line ends (the placeholder lines are found after a CR).
        ("cr.mpf", "R1=1\rG1 X1\rG70 Y1\rMSG(\"A\")\rM0\rG1 X=R1 F10\rM30\r"),
        ("msg-m0-crlf.mpf", "R1=1\r\nMSG(\"LOOK\")\r\nM0\r\nG1 X2\r\nMSG(\"B\")\r\nM0\r\nM30\r\n"),
    ] {
        match compare(name, text) {
            Outcome::Same(_) => {}
            Outcome::Declined(w) => panic!("{name} declined: {w}"),
        }
    }
    // G70 inside a structure: the units after it depend on the branch taken (the whole
    // translation refuses the F after it, NC324); the stream, which follows the text,
    // declines.
    match compare("inch-if.mpf", "R1=1\nIF R1>5\nG70 X=R1\nENDIF\nG1 X1 F100\nM30\n") {
        Outcome::Declined(w) => assert!(w.contains("path taken"), "{w}"),
        Outcome::Same(_) => panic!("inch-if.mpf segmented"),
    }
    // Lengths and feeds in different units each way, and AC()/IC() beside the block's own
    // G90/G91: identical and verified equivalent (each diverged before the words pass
    // followed the feed unit apart and dropped the block's own G90/G91 under a switch).
    for (name, text) in [
        // G71/G70 after G700 in a run: F after it is in mm/min (the basic system) again.
        ("feed-inch-run.mpf", "R1=1\nG700\nG1 X1 F10\nG71 X2\nR2=2\nG1 X=R1 F300\nM30\n"),
        // ... in the macro part: the run after it starts there.
        ("feed-inch-macro.mpf", "R1=1\nG700 G1 X=R1 F2\nG71 X=R1\nG1 X1 F100\nY2 F200\nR2=1\nG70 X=R2\nX3 F50\nM30\n"),
        ("feed-mm-run.mpf", "R1=1\nG700\nG1 X1 F10\nG710 G70 X2 F20\nR2=2\nG1 X=R1 F300\nG700 X2 F5\nM30\n"),
        (
            "ac-ic-own.mpf",
            "R1=1\nG1 X1 F100\nG90 X=IC(R1)\nG91 Y=AC(R1)\nN7 G90 G1 X=IC(2) Y=IC(R1) ; c\nG91 X=IC(1)\nG90 X2\nM30\n",
        ),
    ] {
        match compare(name, text) {
            Outcome::Same(true) => {}
            Outcome::Same(false) => panic!("{name}: not verified equivalent"),
            Outcome::Declined(w) => panic!("{name} declined: {w}"),
        }
    }
}

/// A generated program whose N numbers reach N99999 (the labels pass then numbers jump
/// targets from N1 up, skipping every N in use, the CAM runs' included): runs numbered from
/// a low pool (dense or sparse) and near N99999, structures and jumps to labels.
fn generated_high_numbers(r: &mut Rng, eol: &str) -> String {
    let pool = [20, 300, 2000][r.index(3)];
    let mut s = format!("%_N_GENH_MPF{eol}R1={} R2=0 R3=0{eol}", 1 + r.below(4));
    for k in 0..2 + r.index(4) {
        for _ in 0..1 + r.index(30) {
            let n = match r.below(3) {
                0 => Some(1 + r.below(pool) as u32),
                1 => Some(99_900 + r.below(100) as u32),
                _ => None,
            };
            s.push_str(&cam_block(r, n));
            s.push_str(eol);
        }
        match r.below(4) {
            0 => s.push_str(&format!("IF R1>2{eol}G1 X=R1{eol}ELSE{eol}G0 Z=R1{eol}ENDIF{eol}")),
            1 => s.push_str(&format!("WHILE R2<2{eol}R2=R2+1{eol}ENDWHILE{eol}R2=0{eol}")),
            2 => s.push_str(&format!("IF R1>1 GOTOF MK{k}{eol}G1 X9{eol}MK{k}: G0 Z{k}{eol}")),
            _ => s.push_str(&format!("N{} R3=R3+1{eol}", 1 + r.below(pool))),
        }
    }
    s.push_str(&format!("M30{eol}"));
    s
}

#[test]
fn generated_numbers_near_n99999() {
    let mut r = Rng(0x9_9999);
    let (mut same, mut declined) = (0, 0);
    let mut why = Vec::new();
    for case in 0..60 {
        let eol = if case % 2 == 0 { "\n" } else { "\r\n" };
        let text = generated_high_numbers(&mut r, eol);
        let comments = [CommentMode::Keep, CommentMode::Drop, CommentMode::Ascii][case % 3];
        match compare_with(&format!("genh{case}.mpf"), &text, comments) {
            Outcome::Same(_) => same += 1,
            Outcome::Declined(w) => {
                declined += 1;
                why.push(w);
            }
        }
    }
    println!("high numbers: {same} segmented and identical, {declined} declined: {why:?}");
    assert!(same >= 50, "only {same} of 60 programs with N numbers near N99999 were segmented: {why:?}");
}

/// A MSG the whole path leaves as a comment (with a note NC320): `to_fanuc_with_notes`
/// takes it, gives the note, and the streamed verifier leaves the MSG out of the source as
/// `align_source` does (without that the source's message would meet a move or merge into
/// an M1 stop, and the verdicts would differ).
#[test]
fn unpaired_msg_with_notes() {
    let mut checked = 0;
    for (name, text) in [
        ("um-run.mpf", "R1=1\nMSG(\"ROUGH\")\nG1 X1 F100\nG1 X2\nM0\nM30\n"),
        ("um-m1.mpf", "R1=1\nG1 X1\nMSG(\"ROUGH\")\nM1\nG1 X2\nM30\n"),
        ("um-numbered.mpf", "R1=1\nMSG(\"A\")\nN5 M0\nG1 X1\nM30\n"),
        ("um-if.mpf", "R1=1\nIF R1>0\nMSG(\"IN\")\nG1 X=R1\nENDIF\nG1 X2\nM0\nM30\n"),
        ("um-both.mpf", "R1=1\nMSG(\"A\")\nG1 X1\nMSG(\"B\")\nM0\nG1 X2\nMSG(\"C\")\nM30\n"),
        ("um-crlf.mpf", "R1=1\r\nMSG(\"ROUGH\")\r\nG70 G1 X1 F100\r\nM0\r\nM30\r\n"),
    ] {
        match compare_full(name, text, CommentMode::Keep, true) {
            Outcome::Same(eq) => {
                assert!(eq, "{name} not verified equivalent");
                checked += 1;
            }
            Outcome::Declined(w) => panic!("{name} declined: {w}"),
        }
        // Without notes allowed, declined.
        assert!(matches!(compare(name, text), Outcome::Declined(_)), "{name}");
    }
    // A MSG beside other items: the blocks pass splits it off, and as the last piece it
    // pairs with a lone M0 (where the whole path's aligned source drops it: both verdicts
    // say so alike), else it is a comment with a note.
    for (name, text) in [
        ("um-beside.mpf", "R1=1\nMSG(\"HI\") R2=1\nM0\nM30\n"),
        ("um-beside-last.mpf", "R1=1\nR2=1 MSG(\"HI\")\nM0\nG1 X1\nM30\n"),
        ("um-beside-m0.mpf", "R1=1\nMSG(\"HI\") M0\nG1 X1\nM30\n"),
        ("um-beside-move.mpf", "R1=1\nMSG(\"HI\") G1 X=R1\nG1 X2\nM0\nM30\n"),
    ] {
        match compare_full(name, text, CommentMode::Keep, true) {
            Outcome::Same(_) => checked += 1,
            Outcome::Declined(w) => panic!("{name} declined: {w}"),
        }
    }
    let mut r = Rng(0x03E5_5A9E);
    let (mut same, mut with_notes) = (0, 0);
    for case in 0..60 {
        let eol = if case % 2 == 0 { "\n" } else { "\r\n" };
        let text = generated_modes(&mut r, eol);
        if let Outcome::Same(_) = compare_full(&format!("umg{case}.mpf"), &text, CommentMode::Keep, true) {
            same += 1;
            with_notes += usize::from(matches!(compare(&format!("umh{case}.mpf"), &text), Outcome::Declined(_)));
        }
    }
    println!("unpaired MSG: {checked} small programs, {same} generated segmented ({with_notes} with notes)");
    assert!(same >= 45 && with_notes >= 5, "{same} segmented, {with_notes} with notes");
}

/// Tool names (`T="DRILL"`, with a tool map): the whole path numbers them in the output and
/// in the source it verifies against; the streamed source does the same. A tool change (M6)
/// makes the segmented path read the program whole (its cutting edge, `passes::comp_to_fanuc`),
/// so the selections here stand alone.
#[test]
fn tool_names_with_a_tool_map() {
    let tools = [("DRILL", 5), ("MILL_10", 12)];
    for (name, text) in [
        ("tool.mpf", "R1=1\nT=\"DRILL\"\nG1 X1 F100\nT=\"MILL_10\"\nG1 X2\nM30\n"),
        ("tool-if.mpf", "R1=1\r\nIF R1>0\r\nT=\"DRILL\"\r\nENDIF\r\nG1 X1 F100\r\nM30\r\n"),
    ] {
        match compare_tools(name, text, CommentMode::Keep, false, &tools) {
            Outcome::Same(eq) => assert!(eq, "{name} not verified equivalent"),
            Outcome::Declined(w) => panic!("{name} declined: {w}"),
        }
        // Without the map: an error, declined.
        assert!(matches!(compare(name, text), Outcome::Declined(_)), "{name}");
    }
}

/// Runs the command line with `--stream` on `text`: its output must be the whole
/// translation's (what the fallback writes when the segmented path declines).
fn cli_stream_matches_whole(name: &str, text: &str) {
    let path = scratch().join(name);
    std::fs::write(&path, text).expect("write");
    let out = scratch().join(format!("{name}.cli.nc"));
    // An earlier run's output: -o replaces an existing file only with --force.
    let _ = std::fs::remove_file(&out);
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_nctrans"))
        .args(["--stream", "--to", "fanuc"])
        .arg(&path)
        .arg("-o")
        .arg(&out)
        .output()
        .expect("run nctrans");
    let stderr = String::from_utf8_lossy(&run.stderr);
    let mut db = SourceDb::new();
    let loaded = nctrans::load(&mut db, &path.display().to_string(), text.as_bytes(), None);
    let parsed = nctrans::parse(&db, loaded.file, Dialect::Sinumerik, &ParseOptions::for_dialect(Dialect::Sinumerik));
    let whole = translate::to_fanuc::to_fanuc(&parsed.unit, &[], &opts(&path, text));
    if whole.unsupported == 0 {
        assert!(std::fs::read(&out).expect("output") == whole.text.as_bytes(), "{name}: {stderr}");
    }
}

#[test]
fn declines_what_it_does_not_handle() {
    for (name, text) in [
        // A MSG left as a comment: `to_fanuc` declines its note (the command line takes it
        // through `to_fanuc_with_notes`, `unpaired_msg_with_notes`).
        ("msg.mpf", "R1=1\nMSG(\"HI\")\nG1 X1\nM30\n"),
        ("msg-numbered-m0.mpf", "R1=1\nMSG(\"HI\")\nN5 M0\nM30\n"),
        ("call.mpf", "R1=1\nSUBPROG\nG1 X1\nM30\n"),
        // A tool name without a tool map (an error).
        ("string.mpf", "R1=1\nT=\"DRILL\"\nG1 X1\nM30\n"),
        // A computed jump target.
        ("goto-string.mpf", "DEF STRING[16] T1=\"FIN\"\nG1 X1\nGOTOF T1\nG0 X9\nFIN: M30\n"),
        // A PROC with parameters.
        ("proc.mpf", "PROC PMAIN(REAL P_A)\nR1=P_A\nG1 X1\nM30\n"),
        // A computed G word.
        ("g-computed.mpf", "R1=1\nG=R1 X1\nG1 X2\nM30\n"),
        // Run blocks the fast path declines, in metric and in inch: the one scan leaves the
        // runs to a writing scan, which translates them alone (they have diagnostics).
        ("alone.mpf", "R1=1\nG1 X1 F100\nG4 S2\nG70 X2\nG4 F3 S1\nR2=2\nG1 X=R1\nG4 S3\nM30\n"),
    ] {
        match compare(name, text) {
            Outcome::Declined(_) => {}
            Outcome::Same(_) => panic!("{name} was segmented"),
        }
        cli_stream_matches_whole(name, text);
    }
    // `--number-blocks` (every block numbered by its place in the whole program).
    let text = "R1=1\nG1 X1\nG1 X=R1\nM30\n";
    let path = scratch().join("numbered.mpf");
    std::fs::write(&path, text).expect("write");
    let o = TranslateOptions { number_blocks: Some(10), ..opts(&path, text) };
    assert!(segmented::to_fanuc_with_notes(&path, &o, &mut Vec::new(), None).is_err());
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
    // What Siemens post-processors put on top: a MSG (a comment with a note), G70 (inch),
    // then G71 again; AC()/IC() in the macro part.
    let mut text =
        String::from("%_N_BIGMACRO_MPF\nMSG(\"ROUGHING T1\")\nG70\nR1=5 R2=0\nN1 G90 G71\nIF R1>3 GOTOF N77777\n");
    let (mut numbers, mut middle) = (vec![], false);
    while text.len() < 8_500_000 {
        // Numbers repeat from run to run (the labels pass would wrap past N99999).
        let mut next = 100;
        text.push_str(&cam_run(&mut r, 1000, &mut next, "\n", &mut numbers));
        if text.len() > 4_000_000 && !middle {
            // N numbers of the runs end in 0: this one is unique.
            text.push_str("N77777 G0 Z10\nG1 X=IC(R1)\nR2=R2+1\nIF R2<2 GOTOB N1\n");
            middle = true;
        }
    }
    text.push_str("M30\n");
    std::fs::write(&path, &text).expect("write");
    let out = dir.join("bigmacro.nc");
    let _ = std::fs::remove_file(&out);
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
    segmented::to_fanuc_with_notes(&path, &opts(&path, &text), &mut lib, None)
        .map_err(|e| format!("{e:?}"))
        .expect("segmented");
    assert!(stderr.contains("NC320"), "{stderr}");
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
        let _ = std::fs::remove_file(&out);
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
        let whole = translate::to_fanuc::to_fanuc(&parsed.unit, &[], &opts(&path, &text));
        assert!(std::fs::read(&out).expect("output") == whole.text.as_bytes());
        // The library takes it segmented (so the command line did too, or it would have
        // said nothing different: the bytes are the same either way).
        assert!(matches!(compare(&format!("cli{k}b.mpf"), &text), Outcome::Same(true)));
    }
}

/// Runs whose translations pass the in-memory part of the spill (64 KiB) go through its
/// temporary file: the same bytes, with mode switches inside the runs and a macro part
/// reading them between.
#[test]
fn large_runs_through_the_spill_file() {
    let mut r = Rng(0x5B11_0001);
    for (k, eol) in ["\n", "\r\n"].into_iter().enumerate() {
        let (mut next, mut numbers) = (0u32, vec![]);
        let mut s = format!("%_N_BIGSPILL_MPF{eol}R1=2 R2=0{eol}");
        for j in 0..4 {
            for _ in 0..12 {
                s.push_str(&mode_line(&mut r));
                s.push_str(eol);
                s.push_str(&cam_run(&mut r, 150, &mut next, eol, &mut numbers));
            }
            s.push_str(&format!("G1 X=AC(R1+{j}) F=R1*100{eol}R2=R2+1{eol}"));
        }
        s.push_str(&format!("M30{eol}"));
        assert!(s.len() > 150_000, "{}", s.len());
        assert!(matches!(compare(&format!("bigspill{k}.mpf"), &s), Outcome::Same(_)), "bigspill{k} declined");
    }
}
