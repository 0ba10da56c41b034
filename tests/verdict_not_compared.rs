//! A verdict says what verification knowingly did not compare: a Siemens `MSG` shown without
//! a stop has no FANUC counterpart and is kept as a comment, so the check leaves its message
//! events out and counts them as the run makes them (a `MSG` in a loop counts each time).
//! Whole, streamed and batch paths give the same count; the batch report carries it.

use nctrans::check::{self, Exclude, Side, Verdict};
use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::eval::{NoCallees, RunOptions};
use nctrans::span::SourceDb;
use nctrans::translate::{self, to_fanuc::TranslateOptions};
use std::path::PathBuf;
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

const PROGRAM: &str = "corpus/in/sinumerik/msg-progress-messages.mpf";
/// ROUGHING, ROUGHING PASS three times, FINISHING; the MSG before M0 becomes `#3006=1(…)`.
const VERDICT: &str = "equivalent (18 events; 5 messages kept as comments)";

fn nctrans(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_nctrans")).args(args).current_dir(root()).output().expect("run");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn the_verdict_counts_the_messages_kept_as_comments() {
    for extra in [None, Some("--stream")] {
        let mut args = vec!["--to", "fanuc", PROGRAM];
        args.extend(extra);
        let (code, out, err) = nctrans(&args);
        assert_eq!(code, 0, "{extra:?}: {err}");
        assert!(out.contains("(MSG: ROUGHING PASS)") && out.contains("#3006=1(CHECK THE PART)"), "{out}");
        assert_eq!(err.lines().last(), Some(VERDICT), "{extra:?}: {err}");
    }
}

/// The count is what the check excluded: without the exclusion the same two programs differ
/// at the first message; with it they agree and the report counts five.
#[test]
fn the_count_comes_from_the_check() {
    let mut db = SourceDb::new();
    let text = std::fs::read_to_string(root().join(PROGRAM)).expect("read");
    let file = db.add(PROGRAM, text);
    let src = nctrans::parse(&db, file, Dialect::Sinumerik, &ParseOptions::for_dialect(Dialect::Sinumerik)).unit;
    let t = translate::to_fanuc::to_fanuc(&src, &[], &TranslateOptions::default());
    assert!(t.ok(), "{:?}", t.diags);
    let out = translate::to_fanuc::reparse(&mut db, &t.clone().into(), "out.nc").unit;
    let sides = || {
        let a = Side { unit: src.clone(), callees: Box::new(NoCallees), run: RunOptions::default() };
        let b = Side { unit: out.clone(), callees: Box::new(NoCallees), run: RunOptions::default() };
        (a, b)
    };
    let (a, b) = sides();
    let plain = check::check(&db, a, b);
    assert_eq!(plain.verdict, Verdict::Diverged { index: 1 }, "{}", plain.diff);
    assert!(plain.excluded.is_empty());
    let (a, b) = sides();
    let r = check::check_excluding(&db, a, b, Exclude { messages: true });
    assert_eq!(r.verdict, Verdict::Equivalent { events: 18 });
    assert_eq!(r.excluded.messages, 5);
    assert_eq!(r.excluded.equivalent("18 events"), VERDICT);
}

/// A stop whose message the translation could not carry (the MSG is not alone in its block
/// before M0) is a stop on both sides; its message counts as not compared.
#[test]
fn a_stop_message_left_out_is_counted() {
    let dir = std::env::temp_dir().join(format!("nctrans-msg-stop-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    let p = dir.join("STOP.MPF");
    std::fs::write(&p, "R1=2\nMSG(\"TURN THE PART\") R1=R1+1\nM0\nG0 X=R1\nM30\n").expect("write");
    let (code, out, err) = nctrans(&["--to", "fanuc", &p.to_string_lossy()]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("(MSG: TURN THE PART)\n#501=#501+1.\nM00\n"), "{out}");
    assert_eq!(err.lines().last(), Some("equivalent (3 events; 1 message kept as a comment)"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_batch_summary_and_report_carry_the_count() {
    let base = std::env::temp_dir().join(format!("nctrans-msg-batch-{}", std::process::id()));
    let (input, output) = (base.join("in"), base.join("out"));
    std::fs::create_dir_all(&input).expect("dir");
    std::fs::copy(root().join(PROGRAM), input.join("MSGS.MPF")).expect("copy");
    for report in ["r.json", "r.csv"] {
        let rep = base.join(report);
        let (i, o, r) = (input.to_string_lossy(), output.to_string_lossy(), rep.to_string_lossy());
        let (code, out, err) = nctrans(&["--to", "fanuc", &i, "-o", &o, "--force", "--report", &r]);
        assert_eq!(code, 0, "{out}{err}");
        let all = format!("{out}{err}");
        assert!(all.contains("not compared: 5 messages kept as comments (in 1 verified file(s))"), "{all}");
        let text = std::fs::read_to_string(&rep).expect("report");
        if report.ends_with("json") {
            assert!(
                text.contains("\"not_compared\": {\"messages\": 5, \"look_ahead\": 0, \"interrupts\": 0}"),
                "{text}"
            );
            assert!(text.contains(VERDICT), "{text}");
        } else {
            assert!(text.contains(",5 messages kept as comments,"), "{text}");
        }
    }
    let _ = std::fs::remove_dir_all(&base);
}
