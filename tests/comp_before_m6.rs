//! A Siemens cutting edge programmed between a tool's preselection and its M6 (`T1 D1` /
//! `M6`, the usual 840D order; issue 19): D selects an edge of the tool still in the
//! spindle, the M6 then selects the edge MD20270 chooses (840D sl W1 §2.1). The run holds
//! the old tool's length until something could show it and drops it at the M6; the
//! translation writes `T1` / `M06` / `G43 H1` where the profile states MD20270, proven, and
//! refuses what it cannot prove (NC470, NC567, NC568); planted wrong translations are
//! caught by the check.

#[path = "support/proven.rs"]
mod proven;
use nctrans::check::{self, Side, Verdict};
use nctrans::dialect::Dialect;
use nctrans::eval::{NoCallees, RunOptions, VecSink};
use nctrans::ir::Unit;
use nctrans::span::SourceDb;
use nctrans::translate::{self, to_fanuc::TranslateOptions};
use proven::{parse, proven_to_fanuc, STEPS};

/// The text trace of a Siemens program, places left out.
fn trace(text: &str) -> Vec<String> {
    let mut db = SourceDb::new();
    let u = parse(&mut db, "t.mpf", text, Dialect::Sinumerik);
    let mut sink = VecSink::default();
    let opts = RunOptions { max_steps: STEPS, ..RunOptions::default() };
    nctrans::eval::run(&mut db, &u, &mut NoCallees, &opts, &mut sink);
    sink.events.iter().map(|(e, _)| nctrans::eval::trace::text_line(e)).collect()
}

/// The profile's MD20270 stated as the factory setting (D1 after a tool change).
fn factory_d1() -> TranslateOptions {
    let mut o = TranslateOptions::default();
    o.source.cutting_edge_default = Some(1);
    o
}

fn codes(src: &str, opts: &TranslateOptions) -> Vec<&'static str> {
    let mut db = SourceDb::new();
    let u = parse(&mut db, "in.mpf", src, Dialect::Sinumerik);
    let t = translate::to_fanuc::to_fanuc(&u, &[], opts);
    assert!(!t.ok(), "translated:\n{}", t.text);
    t.diags.iter().filter(|d| d.is_error()).map(|d| d.code).collect()
}

fn check_pair(siemens: &str, fanuc: &str) -> Verdict {
    let mut db = SourceDb::new();
    let s = parse(&mut db, "a.mpf", siemens, Dialect::Sinumerik);
    let f = parse(&mut db, "b.nc", fanuc, Dialect::Fanuc);
    let side = |u: &Unit| Side {
        unit: u.clone(),
        callees: Box::new(NoCallees),
        run: RunOptions { max_steps: STEPS, ..RunOptions::default() },
    };
    check::check(&db, side(&s), side(&f)).verdict
}

/// Two tools, each preselected with its edge before the M6 at the safe level.
const TWO_TOOLS: &str = "G17 G90 G54 G71\nT1 D1\nM6\nS2000 M3 M8\nG0 X0 Y0\nZ5\nG1 Z-2 F300\nG0 Z50\n\
                         T2 D1\nM5 M9\nM6\nS1500 M3\nG0 X10 Y0\nZ5\nG1 Z-10 F150\nG0 Z50\nM5\nM30\n";

#[test]
fn an_edge_before_the_m6_acts_only_if_something_moves_before_it() {
    // Nothing moves between the D and the M6: the old tool's edge is never applied; the
    // trace shows the new tool's edge of MD20270 (factory setting 1) at the tool change.
    let t = trace("T1 D1\nM6\nS1000 M3\nG0 Z50\nM30\n");
    assert_eq!(t[..3], ["tool 1", "comp length=\"1.1\" radius=off", "spindle cw 1000"]);
    assert_eq!(t.iter().filter(|l| l.starts_with("comp")).count(), 1, "{t:?}");
    // Spindle and coolant in between do not show a length either.
    let t = trace("T1 M6 D1\nG0 Z50\nT2 D2\nM5\nM8\nM6\nG0 Z10\nM30\n");
    let comps: Vec<&String> = t.iter().filter(|l| l.starts_with("comp")).collect();
    assert_eq!(comps, ["comp length=\"1.1\" radius=off", "comp length=\"2.1\" radius=off"], "{t:?}");
    // A move before the M6 is made with the old tool's edge D2: its event comes before the
    // move, where the control applies the length.
    let t = trace("T1 M6 D1\nG0 Z50\nT2 D2\nG0 Z40\nM6\nG0 Z10\nM30\n");
    let at = t.iter().position(|l| l == "comp length=\"1.2\" radius=off").expect("the old tool's D2");
    assert!(t[at + 1].starts_with("move rapid Z=40"), "{t:?}");
    assert_eq!(t[at + 2], "tool 2");
    assert_eq!(t[at + 3], "comp length=\"2.1\" radius=off");
}

#[test]
fn the_tool_change_sequence_translates_to_g43_after_the_m6_and_verifies() {
    let out = proven_to_fanuc(TWO_TOOLS, &factory_d1());
    let at = |l: &str| out.iter().position(|x| x == l).unwrap_or_else(|| panic!("{l} not in {out:?}"));
    // The D before the M6 goes (it is the old tool's, never applied); the length of the
    // edge the tool change selects follows the M06 in a line of its own.
    assert_eq!(out[at("T1")..at("T1") + 3], ["T1", "M06", "G43 H1"]);
    assert_eq!(out[at("T2")..at("T2") + 4], ["T2", "M05 M09", "M06", "G43 H2"]);
    assert!(!out.iter().any(|l| l.contains('D')), "{out:?}");
}

#[test]
fn what_cannot_be_proven_is_refused_with_the_rule() {
    // The machine data not stated: the edge the M6 selects is not known, whatever the D
    // before it (the message says so).
    assert_eq!(codes("T1 D1\nM6\nG0 Z50\nM30\n", &TranslateOptions::default()), ["NC470"]);
    let mut db = SourceDb::new();
    let u = parse(&mut db, "in.mpf", "T1 D1\nM6\nG0 Z50\nM30\n", Dialect::Sinumerik);
    let t = translate::to_fanuc::to_fanuc(&u, &[], &TranslateOptions::default());
    assert!(t.diags.iter().any(|d| d.message.contains("D1 before it") && d.message.contains("MD20270")));
    // A move between the D and the M6 carries the old tool's edge (none in the spindle).
    assert_eq!(codes("T1 D1\nG0 Z50\nM6\nM30\n", &factory_d1()), ["NC567"]);
    // The edge before the M6 is not the one the tool change selects (MD20270 = 1).
    assert_eq!(codes("T1 D2\nM6\nG0 Z50\nM30\n", &factory_d1()), ["NC568"]);
    // In the M6 block, or after it, any edge translates.
    assert!(proven_to_fanuc("T1 M6 D1\nG0 Z50\nM30\n", &factory_d1()).contains(&"G43 H1".to_string()));
}

#[test]
fn planted_wrong_translations_of_the_tool_change_are_caught() {
    let right = proven_to_fanuc(TWO_TOOLS, &factory_d1());
    let fanuc = |lines: &[String]| format!("%\nO1\n{}\n%\n", lines.join("\n"));
    assert!(matches!(check_pair(TWO_TOOLS, &fanuc(&right)), Verdict::Equivalent { .. }));
    let edit = |f: &dyn Fn(&mut Vec<String>)| {
        let mut v = right.clone();
        f(&mut v);
        fanuc(&v)
    };
    let pos = |v: &Vec<String>, l: &str| v.iter().position(|x| x == l).expect("line");
    let wrong: [(&str, String); 4] = [
        // The length switched on before the tool change (the D's place).
        (
            "G43 before M06",
            edit(&|v| {
                let g = pos(v, "G43 H1");
                let l = v.remove(g);
                v.insert(pos(v, "T1") + 1, l);
            }),
        ),
        (
            "the first tool's H for the second",
            edit(&|v| {
                let g = pos(v, "G43 H2");
                v[g] = "G43 H1".into();
            }),
        ),
        ("no length after the second M06", edit(&|v| drop(v.remove(pos(v, "G43 H2"))))),
        // The D before the M6 taken as the new tool's, written at its place.
        (
            "the second length before its M06",
            edit(&|v| {
                let g = pos(v, "G43 H2");
                let l = v.remove(g);
                v.insert(pos(v, "T2") + 1, l);
            }),
        ),
    ];
    for (what, text) in wrong {
        assert!(matches!(check_pair(TWO_TOOLS, &text), Verdict::Diverged { .. }), "{what}:\n{text}");
    }
}
