//! The segmented stream (Sinumerik → FANUC) on programs with `DEF AXIS` variables and
//! program-section repetitions (`REPEAT`, `REPEATB`, `ENDLABEL`): where it does not decline,
//! its output and notes are the whole-file translation's byte for byte and its streamed
//! verification gives the whole path's verdict; where it declines, it says why, and the
//! command line then writes the whole translation. Inputs: the corpus programs with these
//! constructs, with runs of generated CAM blocks put between their top-level statements
//! (LF and CRLF), and planted cases for what made the two paths differ: a DEF's start value
//! that a later assignment replaces, with a run between (`lower::to_fanuc::blocks`, the dead
//! start value's search through the run's blocks), and units a repeated section changes.
//! (These constructs are Siemens ones: the FANUC → Sinumerik stream has no such source.)

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
    let d = root().join("target/stream-segmented-axis-tests");
    std::fs::create_dir_all(&d).expect("dir");
    d
}

fn opts(path: &Path, text: &str) -> TranslateOptions {
    TranslateOptions {
        main_name: path.file_stem().and_then(|s| s.to_str()).unwrap_or("MAIN").to_ascii_uppercase(),
        source_name: path.file_name().and_then(|s| s.to_str()).unwrap_or("").to_string(),
        line_ending: nctrans::read::detect_line_ending(text),
        comments: CommentMode::Keep,
        ..TranslateOptions::default()
    }
}

#[derive(Debug)]
enum Outcome {
    Declined(String),
    /// Identical; whether verification found them equivalent.
    Same(bool),
}

/// Translates `text` (written to `name`) whole and segmented (with notes); when segmented
/// does not decline, asserts the same bytes, notes and verdict.
fn compare(name: &str, text: &str) -> Outcome {
    let path = scratch().join(name);
    std::fs::write(&path, text).expect("write");
    let mut db = SourceDb::new();
    let loaded = nctrans::load(&mut db, &path.display().to_string(), text.as_bytes(), None);
    let parsed = nctrans::parse(&db, loaded.file, Dialect::Sinumerik, &ParseOptions::for_dialect(Dialect::Sinumerik));
    let o = opts(&path, text);
    let t = translate::to_fanuc::to_fanuc(&parsed.unit, &[], &o);
    let mut out = Vec::new();
    let (seg, notes) = match segmented::to_fanuc_with_notes(&path, &o, &mut out, None) {
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
    let out_path = scratch().join(format!("{name}.nc"));
    std::fs::write(&out_path, &out).expect("write");
    let v = nctrans::stream::verify::verify(seg.index, &out_path, MAX_STEPS, seg.inputs, None);
    let w = translate::to_fanuc::verify(&mut db, &parsed.unit, &[], &t.clone().into(), "out.nc", MAX_STEPS);
    assert_eq!(v.summary, w.summary, "{name}: verdicts");
    assert_eq!(v.equivalent, w.equivalent, "{name}");
    Outcome::Same(v.equivalent)
}

/// `--stream --to fanuc` on the command line writes the whole translation's bytes (taken
/// segmented or, where that declines, whole).
fn cli_matches_whole(name: &str, text: &str) {
    let path = scratch().join(name);
    std::fs::write(&path, text).expect("write");
    let out = scratch().join(format!("{name}.cli.nc"));
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
    assert!(whole.ok(), "{name}: {:?}", whole.diags);
    assert!(run.status.success() && stderr.contains("equivalent"), "{name}: {stderr}");
    assert!(std::fs::read(&out).expect("output") == whole.text.as_bytes(), "{name}: {stderr}");
}

/// A generated CAM block: now and then skipped (`/`) or numbered.
fn cam_block(r: &mut Rng, next: &mut u32) -> String {
    let mut s = String::new();
    if r.chance(8) {
        s.push('/');
    }
    if r.chance(30) {
        *next += 10;
        s.push_str(&format!("N{next} "));
    }
    s.push_str(r.pick(&["G0 ", "G1 ", "", ""]));
    for a in ["X", "Y", "Z"] {
        if r.chance(70) {
            s.push_str(&format!("{a}{}.{:03} ", r.below(400), r.below(1000)));
        }
    }
    if r.chance(20) {
        s.push_str(&format!("F{} ", 100 + r.below(2000)));
    }
    let t = s.trim_end().to_string();
    if t.is_empty() || t == "/" {
        "G1 X1".into()
    } else {
        t
    }
}

fn cam_run(r: &mut Rng, n: usize, next: &mut u32, eol: &str) -> String {
    (0..n).map(|_| cam_block(r, next) + eol).collect()
}

/// `text` with a run of 0..`max` CAM blocks put after the line of each top-level statement
/// (with `outside`, only before the first label and after the last REPEAT: outside every
/// repeated section).
fn with_runs(text: &str, r: &mut Rng, max: usize, outside: bool) -> String {
    let eol = nctrans::read::detect_line_ending(text).as_str();
    let mut db = SourceDb::new();
    let l = nctrans::load(&mut db, "x.mpf", text.as_bytes(), None);
    let parsed = nctrans::parse(&db, l.file, Dialect::Sinumerik, &ParseOptions::for_dialect(Dialect::Sinumerik));
    let body = parsed.unit.programs.first().map_or(&[][..], |p| &p.body[..]);
    let labelled =
        |s: &nctrans::ir::Stmt| nctrans::ir::visit::metas(&s.kind).first().is_some_and(|m| m.label.is_some());
    let repeats = |s: &nctrans::ir::Stmt| {
        matches!(&s.kind, nctrans::ir::StmtKind::Block(b)
            if b.items.iter().any(|it| matches!(it.kind, nctrans::ir::ItemKind::RepeatSection(_))))
    };
    let first_label = body.iter().position(labelled).unwrap_or(body.len());
    let last_repeat = body.iter().rposition(repeats);
    let mut cuts: Vec<usize> = {
        body.iter()
            .enumerate()
            .filter(|(k, _)| !outside || *k + 1 < first_label || last_repeat.is_some_and(|l| *k >= l))
            .map(|(_, s)| s)
            .filter_map(|s| {
                let hi = s.span.hi as usize;
                Some(hi + text.get(hi..)?.find(eol)? + eol.len())
            })
            .collect()
    };
    cuts.sort();
    cuts.dedup();
    let (mut out, mut at, mut next) = (String::new(), 0, 50_000);
    for c in cuts {
        out.push_str(&text[at..c]);
        let n = r.index(max + 1);
        out.push_str(&cam_run(r, n, &mut next, eol));
        at = c;
    }
    out.push_str(&text[at..]);
    out
}

/// A corpus program with its tool changes taken out (`T… M6`, `D1`: a tool change sends the
/// segmented stream whole), in line ends `eol`.
fn corpus(name: &str, eol: &str) -> String {
    let text = std::fs::read_to_string(root().join("corpus/in/sinumerik").join(name)).expect("corpus program");
    let lines: Vec<&str> = text
        .lines()
        .filter(|l| {
            let t = l.trim();
            !(t.starts_with('T') && t.contains("M6") || t == "D1")
        })
        .collect();
    lines.join(eol) + eol
}

/// Whether a decline is one these programs may meet, said as the stream says it.
fn allowed(why: &str) -> bool {
    why == "units that differ from the text's at a run"
        // A run right after a TRANS, before the axes it shifts are programmed absolutely
        // again (`lower::to_fanuc::frames_incr`): read whole.
        || why == "a run where a frame change leaves an axis to be programmed again"
}

#[test]
fn corpus_axis_and_repeat_programs_with_runs_give_the_whole_bytes() {
    let files = [
        "axis-vars-dressing-trans.spf",
        "repeat-section.mpf",
        "repeat-section-endlabel.mpf",
        "repeat-section-repeatb.mpf",
        "repeat-section-two-labels.mpf",
        "repeat-section-groove-p3.mpf",
    ];
    let mut r = Rng(0xA815_0001);
    let mut summary = Vec::new();
    for file in files {
        let (mut same, mut declined) = (0, Vec::new());
        for (k, eol) in ["\n", "\r\n"].into_iter().enumerate() {
            let base = corpus(file, eol);
            // Without runs (the straight stream stops at the first macro line), then with.
            let o = compare(&format!("{k}-plain-{file}"), &base);
            assert!(
                matches!(o, Outcome::Same(true)) || matches!(&o, Outcome::Declined(w) if allowed(w)),
                "{file}: {o:?}"
            );
            // Every other variant with runs only outside the repeated sections.
            for v in 0..12 {
                let text = with_runs(&base, &mut r, 12, v % 2 == 1);
                match compare(&format!("{k}-{v}-{file}"), &text) {
                    Outcome::Same(eq) => {
                        assert!(eq, "{file} variant {v}: not equivalent");
                        same += 1;
                    }
                    Outcome::Declined(why) => {
                        assert!(allowed(&why), "{file} variant {v} declined: {why}");
                        declined.push(why);
                    }
                }
            }
        }
        // The dressing shape shifts Z and X with TRANS right after its start and again at its
        // end: a run there comes before those axes are programmed absolutely again, and the
        // stream reads such a program whole (`frames_incr`, a placeholder's blocks are not
        // looked into); the repeated sections stream.
        let needed = if file == "axis-vars-dressing-trans.spf" { 0 } else { 12 };
        assert!(same >= needed, "{file}: only {same} of 24 variants segmented ({declined:?})");
        summary.push(format!("{file}: {same} segmented, {} declined", declined.len()));
    }
    println!("{summary:?}");
}

/// The case that made the two paths differ: `DEF REAL WB,VB` ahead of a run with a skipped
/// block, the two set after it (the whole translation keeps `#100=0.`: its search for the
/// store that replaces it stops at the `/` block).
#[test]
fn axis_dressing_with_a_skipped_block_in_the_run() {
    let text = corpus("axis-vars-dressing-trans.spf", "\n")
        .replace("DEF REAL WB,VB\n", "DEF REAL WB,VB\nG0 X1\n/N7 G1 X2\nG1 X3\n");
    assert!(matches!(compare("dress-skip.spf", &text), Outcome::Same(true)));
    let path = scratch().join("dress-skip-cli.mpf");
    let mut db = SourceDb::new();
    let loaded = nctrans::load(&mut db, "x.mpf", text.as_bytes(), None);
    let parsed = nctrans::parse(&db, loaded.file, Dialect::Sinumerik, &ParseOptions::for_dialect(Dialect::Sinumerik));
    let whole = translate::to_fanuc::to_fanuc(&parsed.unit, &[], &opts(&path, &text));
    assert!(whole.text.contains("#100=0.\n#101=0.\n"), "{}", whole.text);
    cli_matches_whole("dress-skip-cli.mpf", &text);
}

/// A DEF's start value and the assignment that replaces it around runs of every kind: a
/// skipped block in the run, a program end in it, a run longer than the search's window, a
/// run that just fits it, and short plain runs (the store goes in both), once and twice.
#[test]
fn a_start_value_replaced_after_a_run() {
    let plain = |n: usize| (0..n).map(|k| format!("G1 X{k}\n")).collect::<String>();
    let cases = [
        ("skip", "G0 X1\n/G1 X2\nG1 X3\n".to_string()),
        ("skip-first", "/G1 X2\nG1 X3\n".to_string()),
        ("end", "G1 X1\nG0 X2 M30\n".to_string()),
        ("long", plain(70)),
        ("window-62", plain(62)),
        ("window-63", plain(63)),
        ("window-64", plain(64)),
        ("short", plain(3)),
        ("two-runs", format!("{}R9=1\n{}", plain(20), plain(20))),
        ("two-runs-long", format!("{}R9=1\n{}", plain(40), plain(40))),
    ];
    let mut kept = 0;
    for (name, run) in cases {
        for eol in ["\n", "\r\n"] {
            let text = format!("DEF REAL WB, VB\n{run}WB=4.5\nG1 X=WB\nVB=WB*2\nG1 Y=VB\nM30\n").replace('\n', eol);
            let file = format!("dead-{name}-{}.mpf", eol.len());
            match compare(&file, &text) {
                Outcome::Same(true) => {}
                o => panic!("{file}: {o:?}"),
            }
            let mut db = SourceDb::new();
            let loaded = nctrans::load(&mut db, "x.mpf", text.as_bytes(), None);
            let popts = ParseOptions::for_dialect(Dialect::Sinumerik);
            let parsed = nctrans::parse(&db, loaded.file, Dialect::Sinumerik, &popts);
            let whole = translate::to_fanuc::to_fanuc(&parsed.unit, &[], &opts(Path::new(&file), &text));
            kept += usize::from(whole.text.contains(&format!("#100=0.{eol}")));
        }
        cli_matches_whole(&format!("dead-{name}-cli.mpf"), &format!("DEF REAL WB\n{run}WB=4.5\nG1 X=WB\nM30\n"));
    }
    // Both ways occur: kept (skip, end, long, window-64, two-runs-long), dropped (the others).
    assert!(kept > 0 && kept < 20, "{kept}");
}

/// A repeated section that changes the units: the runs after its REPEAT are translated in
/// the units it leaves, not those of the text before the REPEAT: declined, read whole.
#[test]
fn a_repeated_section_that_changes_the_units_declines() {
    let text = "R1=0\nG71 G1 X0 F100\nSEC: G70 R1=R1+1\nG71 R2=1\nG1 X2 F100\nREPEATB SEC\nG1 X1 F200\nG1 X3\nM30\n";
    match compare("repeat-units.mpf", text) {
        Outcome::Declined(why) => assert_eq!(why, "units that differ from the text's at a run"),
        o => panic!("{o:?}"),
    }
    cli_matches_whole("repeat-units-cli.mpf", text);
    // The same without the unit word in the section: segmented.
    let same = text.replace("SEC: G70 R1=R1+1", "SEC: R1=R1+1");
    assert!(matches!(compare("repeat-units-same.mpf", &same), Outcome::Same(true)));
}

/// Straight blocks inside a repeated section (their copies are written where the REPEAT
/// stands, without N numbers and in the modes there): the skeleton keeps them (a second
/// scan), so the copies are the whole translation's; runs outside every section stream.
#[test]
fn runs_in_repeated_sections_stay_in_the_skeleton() {
    for (name, text) in [
        ("in-two-labels.mpf", "R1=0\nLA: R1=R1+1\nN10 G1 X1\nG1 X2\nLB: R2=R1\nREPEAT LA LB P=2\nG1 X9\nM30\n"),
        ("in-endlabel.mpf", "R1=0\nLA: R1=R1+1\nG1 X1\nENDLABEL: R2=1\nG1 X7\nREPEAT LA P=1\nM30\n"),
        ("in-to-repeat.mpf", "R1=0\nLA: R1=R1+1\nG1 X1\nREPEAT LA P=3\nG1 X8\nM30\n"),
        (
            "in-nested.mpf",
            "R1=0\nLA: R1=R1+1\nG1 X1 F100\nLB: G1 X2\nREPEAT LB P=2\nG1 X3\nREPEAT LA P=1\nG1 X8\nM30\n",
        ),
        ("in-if.mpf", "R1=0\nLA: R1=R1+1\nG1 X1\nIF R1<3\nG1 X2\nENDIF\nG1 X3\nREPEAT LA P=2\nG1 X8\nM30\n"),
        ("out-two-labels.mpf", "G1 X0\nR1=0\nLA: R1=R1+1\nLB: R2=R1\nG1 X1\nG1 X2\nREPEAT LA LB P=2\nG1 X9\nM30\n"),
        ("out-endlabel.mpf", "G1 X0\nR1=0\nLA: R1=R1+1\nENDLABEL: R2=1\nG1 X7\nREPEAT LA P=2\nG1 X6\nM30\n"),
        ("out-repeatb.mpf", "G1 X0\nLA: R1=R1+1\nG1 X1\nG1 X2\nREPEATB LA P=2\nG1 X8\nM30\n"),
    ] {
        for eol in ["\n", "\r\n"] {
            let text = text.replace('\n', eol);
            let file = format!("{}-{name}", eol.len());
            let o = compare(&file, &text);
            assert!(matches!(o, Outcome::Same(true)), "{file}: {o:?}");
        }
        cli_matches_whole(name, text);
    }
}

/// The corpus job whose subprogram names its axes (`DEF AXIS`) and whose main program moves
/// an axis the set-up fixes (`AX[AXNAME(AXIS_VER)]`, `[variables] fixed` in nctrans.toml),
/// with runs put into the main program: `--stream` writes the whole job's bytes, with the
/// same verdict line, as the whole translation on the command line.
#[test]
fn cli_job_with_axis_variables_in_a_subprogram() {
    let src = root().join("corpus/in/sinumerik-calls/axis-vars");
    let mut r = Rng(0xA815_0002);
    for (k, eol) in ["\n", "\r\n"].into_iter().enumerate() {
        let dir = scratch().join(format!("job{k}"));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("dir");
        std::fs::create_dir_all(dir.join("DEF")).expect("dir");
        for f in ["D_DRESS.SPF", "nctrans.toml", "DEF/MGUD.DEF"] {
            std::fs::copy(src.join(f), dir.join(f)).expect("copy");
        }
        let main = std::fs::read_to_string(src.join("MAIN.MPF")).expect("main");
        let main: String = main.lines().map(|l| format!("{l}{eol}")).collect();
        std::fs::write(dir.join("MAIN.MPF"), with_runs(&main, &mut r, 8, false)).expect("write");
        let run = |args: &[&str], out: &str| {
            let _ = std::fs::remove_file(dir.join(out));
            let o = std::process::Command::new(env!("CARGO_BIN_EXE_nctrans"))
                .current_dir(&dir)
                .args(args)
                .args(["--to", "fanuc", "MAIN.MPF", "-o", out])
                .output()
                .expect("run nctrans");
            let stderr = String::from_utf8_lossy(&o.stderr).to_string();
            assert!(o.status.success(), "{stderr}");
            (std::fs::read(dir.join(out)).expect("output"), stderr)
        };
        let (whole, w_err) = run(&[], "whole.nc");
        let (streamed, s_err) = run(&["--stream"], "streamed.nc");
        assert!(whole == streamed, "job{k}: the outputs differ");
        let verdict = |e: &str| e.lines().filter(|l| l.contains("equivalent")).map(str::to_string).collect::<Vec<_>>();
        assert!(!verdict(&w_err).is_empty() && verdict(&w_err) == verdict(&s_err), "{w_err}\n---\n{s_err}");
    }
}

/// Modal rounding (RNDM) over a run whose placeholder carries the G91 the run leaves: the
/// placeholder is a stand-in all the same (the corners pass refuses the stretch there), so
/// the segmented stream declines and the command line writes the whole translation (it
/// wrote the run without its `,R` words before).
#[test]
fn modal_rounding_over_a_run_that_changes_g90_g91_declines() {
    let text = "R1=1\nRNDM=1\nG1 X1 Y0 F100\nG91 G1 X2 Y2\nG1 X3 Y0\nRNDM=0\nR2=2\nM30\n";
    assert!(matches!(compare("rndm-g91.mpf", text), Outcome::Declined(_)));
    let path = scratch().join("rndm-g91-cli.mpf");
    std::fs::write(&path, text).expect("write");
    let out = scratch().join("rndm-g91-cli.nc");
    let _ = std::fs::remove_file(&out);
    std::process::Command::new(env!("CARGO_BIN_EXE_nctrans"))
        .args(["--stream", "--to", "fanuc"])
        .arg(&path)
        .arg("-o")
        .arg(&out)
        .output()
        .expect("run nctrans");
    let written = std::fs::read_to_string(&out).expect("output");
    assert!(written.contains("G91 G01 X2. Y2. ,R1."), "{written}");
}
