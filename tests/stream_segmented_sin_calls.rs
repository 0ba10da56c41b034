//! Segmented streaming (FANUC → Sinumerik) of main programs that call subprograms
//! (`segmented::to_sinumerik_with_subs`, and the command line's `--stream`): subprograms
//! after the main program's M30 in the same file and in files beside it (`O9030.nc`), called
//! by `M98 P` and `G65 P` with arguments and `G66 P`/`G67` around CAM runs, one calling
//! another, common variables shared. The
//! command line writes what the whole path writes in all three output modes (stdout with
//! separator lines, `-o FILE` with the subprograms beside it, `-o DIR/`), byte for byte,
//! with the same stderr and exit code; declined programs too. The streamed verification
//! fails when a subprogram of the output is broken.

#[path = "support/fanuc_runs.rs"]
mod fanuc_runs;
#[path = "support/rng.rs"]
mod rng;

use nctrans::check::Verdict;
use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::eval::{header_inputs, DirCallees, RunOptions};
use nctrans::ir::{CallTarget, ItemKind, ProgName, StmtKind, Unit};
use nctrans::read::LineEnding;
use nctrans::span::SourceDb;
use nctrans::stream::segmented::sinumerik as segmented;
use nctrans::stream::verify::{self as sv, StreamSide};
use nctrans::stream::Fallback;
use nctrans::translate::to_sinumerik::{Options, OutFile};
use rng::Rng;
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn scratch(name: &str) -> PathBuf {
    let d = root().join("target/stream-segmented-sin-calls").join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("dir");
    d
}

/// A run of `n` CAM blocks as bench/gen_cam.py writes them (linear moves, some feeds, some
/// numbered, now and then an arc by R).
fn cam(r: &mut Rng, n: usize) -> String {
    let mut s = String::new();
    let c = |r: &mut Rng| format!("{:.4}", r.below(200_000) as f64 / 1000.0 - 100.0);
    for k in 0..n {
        if r.chance(10) {
            s.push_str(&format!("N{} ", 5000 + r.below(4000)));
        }
        if r.chance(5) {
            s.push_str(&format!("G2 X{} Y{} R250.\n", c(r), c(r)));
            continue;
        }
        s.push_str(&format!("G1 X{} Y{} Z{}", c(r), c(r), c(r)));
        if k % 4 == 0 {
            s.push_str(&format!(" F{}.", 500 + r.below(900)));
        }
        s.push('\n');
    }
    s
}

/// The subprograms the generated programs call: number, text (without `%` lines).
const SUBS: [(u32, &str); 5] = [
    (9010, "O9010 (TOOL CHANGE)\n#102=#100+1\nG0 Z50.\nM98 P9030\nM99\n"),
    (9020, "O9020 (POCKET)\nG1 X#1 Y#2 F300.\n#100=#100+#1\nIF[#2GT5.]GOTO10\nG1 Z-#2\nN10 G0 Z5.\nM99\n"),
    (9030, "O9030\nG0 X#100 Y0.\nM99\n"),
    (9040, "O9040\n#1=0\nWHILE[#1LT3]DO1\nG1 X#1 Y#100\n#1=#1+1\nEND1\nM99\n"),
    (9050, "O9050 (DRILL AFTER EACH MOVE)\nG1 Z#26 F100.\nG0 Z#18\nM99\n"),
];

/// A generated main program: CAM runs around calls of 1-3 subprograms; the callees (and
/// what they call) after M30 in the same file or as `O<n>.nc` beside it.
fn generated(r: &mut Rng, dir: &Path, eol: &str) -> PathBuf {
    let calls =
        ["M98 P9010", "G65 P9020 A1.5 B#101", "M98 P9030 L2", "G65 P9040", "G65 P9020 A2. B7.", "G66 P9050 R2. Z-1."];
    let mut text = String::from("%\nO1000 (CAM)\n#100=5.\n#101=2.\nG21 G17 G90 G94\nG0 X0. Y0. Z5.\nG1 Z-1. F500.\n");
    let mut want = Vec::new();
    for _ in 0..1 + r.below(3) {
        let n = 20 + r.below(200) as usize;
        text.push_str(&cam(r, n));
        let c = calls[r.index(calls.len())];
        text.push_str(c);
        if c.starts_with("G66") {
            // A modal call over a CAM run: the macro runs after each of its moves.
            let n = 5 + r.below(30) as usize;
            text.push('\n');
            text.push_str(&cam(r, n));
            text.push_str("G67");
        }
        text.push_str(if r.chance(30) { "\n#101=#100*2\n" } else { "\n" });
        let n: u32 = c.split('P').nth(1).and_then(|p| p[..4].parse().ok()).expect("P");
        want.push(n);
        if n == 9010 {
            want.push(9030);
        }
    }
    text.push_str(&cam(r, 30));
    text.push_str("M30\n");
    want.sort_unstable();
    want.dedup();
    for n in want {
        let (_, sub) = SUBS.iter().find(|(k, _)| *k == n).expect("sub");
        if r.chance(50) {
            text.push_str(sub);
        } else {
            std::fs::write(dir.join(format!("O{n}.nc")), format!("%\n{sub}%\n").replace('\n', eol)).expect("write");
        }
    }
    text.push_str("%\n");
    let path = dir.join("main.nc");
    std::fs::write(&path, text.replace('\n', eol)).expect("write");
    path
}

struct Run {
    code: Option<i32>,
    stdout: Vec<u8>,
    stderr: String,
}

fn cli(dir: &Path, args: &[&str]) -> Run {
    let out = Command::new(env!("CARGO_BIN_EXE_nctrans")).current_dir(dir).args(args).output().expect("runs");
    Run { code: out.status.code(), stdout: out.stdout, stderr: String::from_utf8_lossy(&out.stderr).to_string() }
}

/// Every file under `d` (sorted) with its bytes.
fn tree(d: &Path) -> Vec<(String, Vec<u8>)> {
    let mut v: Vec<(String, Vec<u8>)> = std::fs::read_dir(d)
        .map(|rd| rd.filter_map(|e| e.ok()).map(|e| e.path()).collect::<Vec<_>>())
        .unwrap_or_default()
        .into_iter()
        .flat_map(|p| {
            if p.is_dir() {
                tree(&p)
            } else {
                let name = p.strip_prefix(d).map(|n| n.display().to_string()).unwrap_or_default();
                vec![(name, std::fs::read(&p).unwrap_or_default())]
            }
        })
        .collect();
    v.sort();
    v
}

/// `--to sinumerik` of `input` (a file name in `dir`) whole and `--stream`, to stdout, to
/// `-o FILE` and to `-o DIR/`: the same bytes, stderr (output folders named alike) and
/// exit codes. Returns the whole runs' last stderr lines.
fn same_three_ways(dir: &Path, input: &str) -> Vec<String> {
    let mut last = Vec::new();
    for mode in ["stdout", "file", "dir"] {
        let mut runs = Vec::new();
        for (tag, extra) in [("w", None), ("s", Some("--stream"))] {
            let out = format!("{tag}-{mode}");
            let _ = std::fs::remove_dir_all(dir.join(&out));
            std::fs::create_dir_all(dir.join(&out)).expect("dir");
            let target = match mode {
                "file" => Some(format!("{out}/x.mpf")),
                "dir" => Some(format!("{out}/d/")),
                _ => None,
            };
            let mut args = vec!["--to", "sinumerik", input];
            args.extend(extra);
            if let Some(t) = &target {
                args.extend(["-o", t.as_str()]);
            }
            let r = cli(dir, &args);
            runs.push((r, tree(&dir.join(&out))));
        }
        let [(w, wt), (s, st)] = <[_; 2]>::try_from(runs).ok().expect("two runs");
        let what = format!("{} {input} {mode}", dir.display());
        assert_eq!(s.code, w.code, "{what}: exit codes\n{}\n{}", w.stderr, s.stderr);
        assert!(s.stdout == w.stdout, "{what}: stdout differs");
        assert_eq!(s.stderr.replace("s-", "w-"), w.stderr, "{what}: stderr");
        assert!(st == wt, "{what}: written files differ");
        last.push(w.stderr.lines().last().unwrap_or("").to_string());
    }
    last
}

/// Program numbers called in a unit.
fn called(u: &Unit) -> Vec<u32> {
    let mut v = Vec::new();
    for p in &u.programs {
        nctrans::ir::visit::walk_stmts(&p.body, &mut |s| {
            if let StmtKind::Block(b) = &s.kind {
                for it in &b.items {
                    let then = match &it.kind {
                        ItemKind::IfThen { then, .. } => Some(&**then),
                        _ => None,
                    };
                    for it in std::iter::once(it).chain(then) {
                        if let ItemKind::Call(c) = &it.kind {
                            if let CallTarget::Number(n) = c.target {
                                v.push(n);
                            }
                        }
                    }
                }
            }
        });
    }
    v
}

/// The library's segmented translation with the callees `O<n>.nc` beside `main` (the
/// files these tests write); the main file's bytes and the other files.
fn library(main: &Path, o: &Options) -> Result<(Vec<u8>, Vec<OutFile>), Fallback> {
    let dir = main.parent().expect("dir").to_path_buf();
    let popts = ParseOptions { semantics: o.source.clone() };
    let mut load = |u: &Unit| {
        let mut db = SourceDb::new();
        db.add(main.display().to_string(), String::new());
        let mut units = vec![u.clone()];
        loop {
            let have: Vec<u32> = units
                .iter()
                .flat_map(|u| u.programs.iter())
                .filter_map(|p| match p.name {
                    Some(ProgName::Number(n)) => Some(n),
                    _ => None,
                })
                .collect();
            let mut want: Vec<u32> = units.iter().flat_map(called).filter(|n| !have.contains(n)).collect();
            want.sort_unstable();
            want.dedup();
            if want.is_empty() {
                break;
            }
            for n in want {
                let p = dir.join(format!("O{n}.nc"));
                let bytes = std::fs::read(&p).map_err(|_| Fallback::NotStraight("not found".into()))?;
                let l = nctrans::load(&mut db, &p.display().to_string(), &bytes, None);
                units.push(nctrans::parse(&db, l.file, Dialect::Fanuc, &popts).unit);
            }
        }
        units.remove(0);
        Ok(units)
    };
    let mut out = Vec::new();
    let eol = nctrans::read::detect_line_ending(&std::fs::read_to_string(main).expect("read"));
    let (_, subs) = segmented::to_sinumerik_with_subs(main, o, eol, &mut load, &mut out, None)?;
    Ok((out, subs))
}

#[test]
fn generated_main_programs_with_calls_stream_as_the_whole_translation() {
    let mut r = Rng(17);
    let mut streamed = 0;
    for k in 0..14 {
        let dir = scratch(&format!("gen{k}"));
        let eol = if k % 3 == 2 { "\r\n" } else { "\n" };
        let main = generated(&mut r, &dir, eol);
        let o = Options { main_name: "MAIN".into(), ..Options::default() };
        match library(&main, &o) {
            Ok(_) => streamed += 1,
            Err(e) => panic!("{}: declined: {e:?}", main.display()),
        }
        let last = same_three_ways(&dir, "main.nc");
        // Equivalent over the whole program (the generated moves are all reachable).
        let events = |l: &str| l.strip_prefix("equivalent (")?.split(' ').next()?.parse::<u64>().ok();
        assert!(last.iter().all(|l| events(l).is_some_and(|n| n > 50)), "{}: {last:?}", main.display());
    }
    assert_eq!(streamed, 14);
}

#[test]
fn declined_programs_give_the_whole_paths_output() {
    let mut r = Rng(5);
    let run = cam(&mut r, 40);
    let cases = [
        ("g66 computed", format!("O1\n#100=9030\n{run}G66 P#100\n{run}G67\nM30\nO9030\nG0 X1.\nM99\n"), false),
        ("g66 m98 both", format!("O1\n#100=1.\n{run}G66 P9030\n{run}G67\nM98 P9030\nM30\nO9030\nG0 X1.\nM99\n"), false),
        ("computed", format!("O1\n#100=9030\n{run}M98 P#100\n{run}M30\nO9030\nG0 X1.\nM99\n"), false),
        ("missing", format!("O1\n#100=1.\n{run}M98 P9031\n{run}M30\n"), false),
        (
            "m99 p in sub",
            format!("O1\n#100=1.\nM98 P9030\nN10 G0 X1.\n{run}N20 G0 X2.\n{run}M30\nO9030\nM99 P20\n"),
            false,
        ),
        ("m99 in main", format!("O1\n#100=1.\n{run}M98 P9030\n{run}M99\nO9030\nG0 X1.\nM99\n"), false),
        (
            "g66 in sub",
            format!(
                "O1\n#100=1.\n{run}M98 P9030\n{run}M30\nO9030\nG66 P9031 X1.\nG0 X1.\nG67\nM99\nO9031\nG0 Y#24\nM99\n"
            ),
            true,
        ),
        (
            "marker in sub",
            format!("O1\n#100=1.\n{run}M98 P9030\n{run}M30\nO9030\nG0 X1. (NCTRANS SEGMENT 0)\nM99\n"),
            false,
        ),
        ("uncalled sub", format!("O1\n#100=1.\n{run}#101=2.\n{run}M30\nO9030\nG0 X#100\nM99\n"), true),
        ("no m30", format!("O1\n#100=1.\n{run}M98 P9030\n{run}O9030\nG0 X#100\nM99\n"), true),
    ];
    for (what, text, streams) in cases {
        let dir = scratch(&format!("declined-{}", what.replace(' ', "-")));
        let main = dir.join("p.nc");
        std::fs::write(&main, &text).expect("write");
        let o = Options { main_name: "P".into(), ..Options::default() };
        assert_eq!(library(&main, &o).is_ok(), streams, "{what}");
        same_three_ways(&dir, "p.nc");
    }
    // A source with a byte-order mark or in a legacy encoding: the command line takes the
    // calls only from UTF-8 without a mark (its subprogram writer's case).
    for (what, bytes) in [
        (
            "bom",
            [
                b"\xEF\xBB\xBF".as_slice(),
                format!("O1\n#100=1.\n{run}M98 P9030\n{run}M30\nO9030\nG0 X1.\nM99\n").as_bytes(),
            ]
            .concat(),
        ),
        (
            "shift-jis",
            [
                b"O1 (\x89\xc1\x8d\x48)\n".as_slice(),
                format!("#100=1.\n{run}M98 P9030\n{run}M30\nO9030\nG0 X1.\nM99\n").as_bytes(),
            ]
            .concat(),
        ),
        (
            "latin1",
            [
                b"O1 (".as_slice(),
                b"\xB0C".as_slice(),
                format!(")\n#100=1.\n{run}M98 P9030\n{run}M30\nO9030\nG0 X1.\nM99\n").as_bytes(),
            ]
            .concat(),
        ),
    ] {
        let dir = scratch(&format!("declined-{what}"));
        std::fs::write(dir.join("p.nc"), bytes).expect("write");
        same_three_ways(&dir, "p.nc");
    }
    // `M99 P<n>` in a callee beside the file: its caller's return CASE lists every N of the
    // main program, run blocks' too.
    let dir = scratch("declined-m99p-beside");
    let p = dir.join("p.nc");
    std::fs::write(&p, format!("O1\n#100=1.\nG0 X0.\nM98 P9030\nN10 G0 X1.\n{run}N20 G0 X2.\n{run}M30\n"))
        .expect("write");
    std::fs::write(dir.join("O9030.nc"), "O9030\nG0 Y5.\nM99 P20\n").expect("write");
    assert!(library(&p, &Options::default()).is_err(), "M99 P beside");
    same_three_ways(&dir, "p.nc");
    // A callee beside the file with a reading diagnostic: declined by the command line's
    // loader (`callees_beside`), which the whole path shows.
    let dir = scratch("declined-callee-warning");
    std::fs::write(dir.join("p.nc"), format!("O1\n#100=1.\n{run}M98 P9030\n{run}M30\n")).expect("write");
    std::fs::write(dir.join("O9030.nc"), "O9030\nG0 X1．\nM99\n").expect("write");
    same_three_ways(&dir, "p.nc");
}

/// The streamed check of a segmented translation with the subprograms served from memory
/// (what the command line runs), the subprogram texts passed through `edit`.
fn streamed_verdict(main: &Path, o: &Options, edit: &dyn Fn(&str) -> String) -> Verdict {
    let (text, subs) = library(main, o).expect("streams");
    let out = main.with_extension("out.mpf");
    std::fs::write(&out, text).expect("write");
    let src = nctrans::stream::scan_path(
        main,
        0,
        Dialect::Fanuc,
        &ParseOptions { semantics: o.source.clone() },
        &mut |_, _| {},
        None,
    )
    .expect("scan");
    let back = sv::read_back(&out, 1, Dialect::Sinumerik, &ParseOptions { semantics: o.target.clone() }, None)
        .ok()
        .expect("back");
    let (in_a, in_b) = (header_inputs(&src.header).expect("a"), header_inputs(&back.header).expect("b"));
    let run = |inputs, sem: &nctrans::dialect::Semantics| RunOptions {
        inputs,
        max_steps: 1_000_000,
        semantics: Some(sem.clone()),
        probe_contact: None,
        probes: Vec::new(),
        interrupts: Vec::new(),
        expand_cycles: None,
    };
    let files = subs.iter().map(|f| (f.program.clone(), f.name.clone(), edit(&f.text))).collect();
    let emitted = nctrans::translate::to_sinumerik::verify::Emitted { files, semantics: o.target.clone() };
    let a = StreamSide {
        run: run(in_a, &o.source),
        index: src,
        name: main.display().to_string(),
        callees: Box::new(DirCallees { semantics: Some(o.source.clone()) }),
    };
    let b = StreamSide {
        run: run(in_b, &o.target),
        index: back,
        name: out.display().to_string(),
        callees: Box::new(emitted),
    };
    sv::compare(a, b).verdict
}

#[test]
fn a_broken_subprogram_in_the_output_fails_the_streamed_verification() {
    let dir = scratch("broken");
    let mut r = Rng(9);
    let run = cam(&mut r, 50);
    let text = format!("O1000\n#100=5.\n{run}M98 P9030\n{run}G65 P9020 A1.5 B2.\n{run}M30\n{}{}", SUBS[2].1, SUBS[1].1);
    let main = dir.join("m.nc");
    std::fs::write(&main, text).expect("write");
    let o = Options { main_name: "M".into(), ..Options::default() };
    let v = streamed_verdict(&main, &o, &|t| t.to_string());
    assert!(matches!(v, Verdict::Equivalent { events } if events > 150), "{v:?}");
    // The subprogram's move goes elsewhere: the runs diverge.
    let moved = streamed_verdict(&main, &o, &|t| t.replace("Y0", "Y1"));
    assert!(matches!(moved, Verdict::Diverged { .. }), "{moved:?}");
}

/// Every corpus FANUC program that calls other programs, as it is and with CAM runs put
/// between its first program's top-level statements: the command line's streamed output is
/// the whole path's (streamed or declined), in all three output modes.
#[test]
fn corpus_programs_with_calls_and_cam_runs_stream_as_the_whole_translation() {
    let Ok(rd) = std::fs::read_dir(root().join("corpus/in/fanuc")) else {
        println!("note: corpus/in/fanuc not found; skipped");
        return;
    };
    let mut files: Vec<PathBuf> = rd.filter_map(|e| e.ok()).map(|e| e.path()).collect();
    files.sort();
    let mut r = Rng(23);
    let (mut streamed, mut total) = (Vec::new(), 0);
    for f in files {
        let Ok(text) = std::fs::read_to_string(&f) else { continue };
        if !["M98", "G65", "G66", "m98", "g65"].iter().any(|c| text.contains(c)) {
            continue;
        }
        let name = f.file_name().map(|n| n.to_string_lossy().to_string()).unwrap_or_default();
        // (Not into CR-only files: `cam` writes LF lines.)
        let runs = fanuc_runs::with_runs(&text, &mut r, 50, |r, eol| {
            if eol == LineEnding::Cr {
                return None;
            }
            let n = 5 + r.below(30) as usize;
            Some(cam(r, n).replace('\n', eol.as_str()))
        });
        for (k, t) in [Some(text.clone()), runs].into_iter().flatten().enumerate() {
            let dir = scratch(&format!("corpus-{k}-{name}"));
            let main = dir.join(&name);
            std::fs::write(&main, t).expect("write");
            total += 1;
            let o = Options { main_name: nctrans_main_name(&name), ..Options::default() };
            if library(&main, &o).is_ok() {
                streamed.push(format!("{k}-{name}"));
            }
            same_three_ways(&dir, &name);
        }
    }
    assert!(total >= 20, "{total} corpus programs with calls");
    println!("streamed {} of {total}: {streamed:?}", streamed.len());
    assert!(streamed.len() >= 20, "streamed: {streamed:?}");
}

/// The main program name the command line gives a file stem (`cli::translate::job::main_name`).
fn nctrans_main_name(file: &str) -> String {
    let stem = file.rsplit_once('.').map_or(file, |(s, _)| s);
    let s: String =
        stem.chars().map(|c| if c.is_ascii_alphanumeric() { c.to_ascii_uppercase() } else { '_' }).collect();
    let ok = s.len() >= 2 && s.as_bytes()[..2].iter().all(|c| c.is_ascii_alphabetic() || *c == b'_');
    let mut s = if ok { s } else { format!("P_{s}") };
    s.truncate(31);
    s
}

/// The command line takes the segmented route for a large main program (over the 8 MB at
/// which it streams without `--stream`) calling a subprogram of the same file and one beside
/// it: no "read whole" note, and the files the library gives (seconds in a debug build).
#[test]
fn cli_streams_a_large_main_program_with_calls() {
    let dir = scratch("large");
    let mut r = Rng(31);
    let mut text = String::from("%\nO1000\n#100=5.\nG21 G90 G0 X0. Y0.\n");
    while text.len() < 4_300_000 {
        text.push_str(&cam(&mut r, 1000));
    }
    text.push_str("M98 P9010\n");
    while text.len() < 8_600_000 {
        text.push_str(&cam(&mut r, 1000));
    }
    text.push_str("G65 P9020 A1.5 B2.\nM30\n");
    text.push_str(SUBS[0].1);
    text.push_str(SUBS[1].1);
    text.push_str("%\n");
    std::fs::write(dir.join("O9030.nc"), format!("%\n{}%\n", SUBS[2].1)).expect("write");
    let main = dir.join("big.nc");
    std::fs::write(&main, &text).expect("write");
    let run = cli(&dir, &["--to", "sinumerik", "big.nc", "-o", "out/"]);
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    assert!(!run.stderr.contains("read whole") && run.stderr.contains("equivalent"), "{}", run.stderr);
    let o = Options { main_name: "BIG".into(), ..Options::default() };
    let (lib, subs) = library(&main, &o).unwrap_or_else(|e| panic!("declined: {e:?}"));
    assert!(std::fs::read(dir.join("out/BIG.MPF")).expect("main") == lib);
    assert_eq!(subs.len(), 3);
    for f in subs {
        assert_eq!(std::fs::read_to_string(dir.join("out").join(&f.name)).expect("sub"), f.text);
    }
}

/// A large main program in Shift_JIS (a comment in Japanese) calling subprograms: the
/// command line streams it from a decoded copy (no "read whole" note) and writes every file
/// as the whole translation encodes it, to a folder and to standard output (each file after
/// its separator line, encoded with it).
#[test]
fn cli_streams_a_large_legacy_encoded_main_program_with_calls() {
    let dir = scratch("large-sjis");
    let mut r = Rng(37);
    let mut text = b"%\nO1000 (\x89\xc1\x8d\x48)\n#100=5.\nG21 G90 G0 X0. Y0.\n".to_vec();
    while text.len() < 4_200_000 {
        text.extend_from_slice(cam(&mut r, 1000).as_bytes());
    }
    text.extend_from_slice(b"M98 P9010\n");
    while text.len() < 8_500_000 {
        text.extend_from_slice(cam(&mut r, 1000).as_bytes());
    }
    text.extend_from_slice(b"G65 P9020 A1.5 B2.\nM30\n");
    text.extend_from_slice(SUBS[0].1.as_bytes());
    text.extend_from_slice(b"O9020 (\x8c\x8a)\n");
    text.extend_from_slice(SUBS[1].1.split_once('\n').map_or("", |(_, rest)| rest).as_bytes());
    text.extend_from_slice(b"%\n");
    std::fs::write(dir.join("O9030.nc"), format!("%\n{}%\n", SUBS[2].1)).expect("write");
    let main = dir.join("big.nc");
    std::fs::write(&main, &text).expect("write");
    // The whole translation, encoded as the whole path encodes it.
    let mut db = SourceDb::new();
    let loaded = nctrans::load(&mut db, &main.display().to_string(), &text, None);
    assert_eq!(loaded.encoding, encoding_rs::SHIFT_JIS);
    let popts = ParseOptions::for_dialect(Dialect::Fanuc);
    let unit = nctrans::parse(&db, loaded.file, Dialect::Fanuc, &popts).unit;
    let callee = nctrans::load(&mut db, "O9030.nc", &std::fs::read(dir.join("O9030.nc")).expect("read"), None);
    let callee = nctrans::parse(&db, callee.file, Dialect::Fanuc, &popts).unit;
    let o = Options { main_name: "BIG".into(), ..Options::default() };
    let tr = nctrans::translate::to_sinumerik::translate(&[&unit, &callee], &o, loaded.line_ending);
    drop(unit);
    let enc = |t: &str| nctrans::read::encode(t, loaded.encoding, loaded.bom);
    let run = cli(&dir, &["--to", "sinumerik", "big.nc", "-o", "out/"]);
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    assert!(!run.stderr.contains("read whole") && run.stderr.contains("equivalent"), "{}", run.stderr);
    assert_eq!(tr.files.len(), 4);
    for f in &tr.files {
        assert!(std::fs::read(dir.join("out").join(&f.name)).expect("file") == enc(&f.text), "{}", f.name);
    }
    let run = cli(&dir, &["--to", "sinumerik", "big.nc"]);
    assert!(!run.stderr.contains("read whole") && run.stderr.contains("equivalent"), "{}", run.stderr);
    let want: Vec<u8> = tr.files.iter().flat_map(|f| enc(&format!("; ==== {} ====\n{}", f.name, f.text))).collect();
    assert!(run.stdout == want, "stdout differs");
}
