//! Siemens G74/G75 with other words in the block (`G74 Z1=0 M5`; issue 19, item 3): the
//! approach stands alone ("G75 requires a separate block", Siemens 802D programming
//! manual §10.3.6; no source lets G74 share its block), so the run refuses it (NC569) and
//! the translation's refusal (NC445) cites the rule; written alone with the M5 after it,
//! the same part runs, translates to `G91 G28 Z0` / `M05` and verifies, and planted wrong
//! translations of it are caught.

use nctrans::check::Verdict;
use nctrans::dialect::Dialect;
use nctrans::span::SourceDb;

#[path = "support/frame_check.rs"]
mod frame_check;
use frame_check::*;

/// The diagnostics of a translation to FANUC that is refused: (code, message).
fn refusal(siemens: &str) -> Vec<(String, String)> {
    let mut db = SourceDb::new();
    let s = load(&mut db, siemens, Dialect::Sinumerik);
    let t = nctrans::translate::to_fanuc::to_fanuc(&s, &[], &Default::default());
    assert!(!t.ok(), "translated:\n{}", t.text);
    t.diags.iter().filter(|d| d.is_error()).map(|d| (d.code.to_string(), d.message.clone())).collect()
}

const ALONE: &str = "G17 G90 G54 G71\nT1 M6 D1\nS1000 M3\nG0 X0 Y0 Z50\nG1 Z-2 F200\nG74 Z1=0\nM5\nM30\n";

#[test]
fn a_reference_approach_with_other_words_is_refused_citing_the_rule() {
    for (src, word) in
        [("G74 Z1=0 M5\nM30\n", "M5"), ("G75 FP=1 X1=0 Y1=0 S200\nM30\n", "S200"), ("G0 G74 Z1=0\nM30\n", "G0")]
    {
        let t = trace(src, Dialect::Sinumerik);
        assert!(t.ends_with("error NC569"), "{src}: {t}");
        let mut db = SourceDb::new();
        let u = load(&mut db, src, Dialect::Sinumerik);
        let mut sink = nctrans::eval::VecSink::default();
        let out = nctrans::eval::run(&mut db, &u, &mut nctrans::eval::NoCallees, &Default::default(), &mut sink);
        let d = out.diags.iter().find(|d| d.code == "NC569").expect("NC569");
        assert!(d.message.contains(&format!("`{word}`")) && d.message.contains("§10.3.6"), "{}", d.message);
    }
    // The translation names the rule too.
    let r = refusal("G74 Z1=0 M5\nM30\n");
    assert_eq!(r.len(), 1, "{r:?}");
    assert_eq!(r[0].0, "NC445");
    assert!(r[0].1.contains("separate block") && r[0].1.contains("§10.3.6"), "{}", r[0].1);
    // Alone, the approach and the axes it names still run (NC441 for a geometry axis).
    assert!(trace("G74 Z1=0\nG75 FP=2 X1=0 Y1=0\nM30\n", Dialect::Sinumerik).starts_with("home point=1 axes=Z"));
    assert!(trace("G74 Z=0\nM30\n", Dialect::Sinumerik).ends_with("error NC441"));
}

#[test]
fn the_approach_alone_translates_and_verifies() {
    let out = s_to_f(ALONE).expect("translated");
    assert!(out.contains("G91 G28 Z0.\nG90\nM05\n"), "{out}");
    // The FANUC form of the same part with the M05 in the G28 block (it acts after the
    // return) is the same machine.
    let one_block = out.replace("G91 G28 Z0.\nG90\nM05\n", "G91 G28 Z0. M05\nG90\n");
    assert!(matches!(verdict(&one_block, ALONE), Verdict::Equivalent { .. }), "{one_block}");
}

#[test]
fn planted_wrong_translations_of_the_approach_are_caught() {
    let out = s_to_f(ALONE).expect("translated");
    for (what, from, to) in [
        ("the second reference point", "G91 G28 Z0.", "G91 G30 P2 Z0."),
        ("the spindle stopped before the return", "G91 G28 Z0.\nG90\nM05\n", "M05\nG91 G28 Z0.\nG90\n"),
        ("another axis homed", "G91 G28 Z0.", "G91 G28 X0."),
        ("an intermediate point", "G91 G28 Z0.", "G91 G28 Z10."),
    ] {
        assert!(out.contains(from), "{from:?} not in\n{out}");
        let bad = out.replacen(from, to, 1);
        assert!(matches!(verdict(&bad, ALONE), Verdict::Diverged { .. }), "{what}:\n{bad}");
    }
}
