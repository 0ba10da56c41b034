//! The exact moves `--expand-cycles` writes for G81, G83 (an infeed that does not divide
//! the depth), G73 and a Sinumerik CYCLE83, run from program text through the evaluator.

use super::Retracts;
use crate::dialect::{Dialect, ParseOptions};
use crate::eval::trace::text_line;
use crate::eval::{run, NoCallees, RunOptions, VecSink};
use crate::span::SourceDb;

const FANUC: Retracts = Retracts { chip_break: 0.6, peck_clearance: 0.25 };
const SIEMENS: Retracts = Retracts { chip_break: 1.0, peck_clearance: 0.6 };

fn trace(dialect: Dialect, text: &str, rt: Option<Retracts>) -> Vec<String> {
    let mut db = SourceDb::new();
    let name = if dialect == Dialect::Fanuc { "t.nc" } else { "t.mpf" };
    let loaded = crate::load(&mut db, name, text.as_bytes(), None);
    let parsed = crate::parse(&db, loaded.file, dialect, &ParseOptions::for_dialect(dialect));
    assert!(!crate::diag::has_errors(&parsed.diags), "{:?}", parsed.diags);
    let mut sink = VecSink::default();
    let opts = RunOptions { expand_cycles: rt, ..Default::default() };
    run(&mut db, &parsed.unit, &mut NoCallees, &opts, &mut sink);
    sink.events.iter().map(|(e, _)| text_line(e)).collect()
}

fn lines(v: &[&str]) -> Vec<String> {
    v.iter().map(|s| s.to_string()).collect()
}

#[test]
fn g81_rapids_to_r_feeds_to_the_bottom_and_rapids_to_the_initial_level() {
    let p = "O1\nG90 G0 X0 Y0 Z50.\nG98 G81 X10. Y10. Z-5. R2. F100.\nX20.\nG80\nM30\n";
    assert_eq!(
        trace(Dialect::Fanuc, p, Some(FANUC)),
        lines(&[
            "move rapid X=0 Y=0 Z=50 f=-",
            "move rapid X=10 Y=10 Z=50 f=-",
            "move rapid X=10 Y=10 Z=2 f=-",
            "move linear X=10 Y=10 Z=-5 f=100",
            "move rapid X=10 Y=10 Z=50 f=-",
            "move rapid X=20 Y=10 Z=50 f=-",
            "move rapid X=20 Y=10 Z=2 f=-",
            "move linear X=20 Y=10 Z=-5 f=100",
            "move rapid X=20 Y=10 Z=50 f=-",
            "end M30 steps=5",
        ])
    );
    // Without the option the holes stay `cycle` events.
    let plain = trace(Dialect::Fanuc, p, None);
    assert_eq!(plain.iter().filter(|l| l.starts_with("cycle drill")).count(), 2, "{plain:?}");
}

#[test]
fn g83_pecks_back_to_r_and_down_to_the_clearance_and_the_last_infeed_is_short() {
    // 12 mm from R to the bottom in 5 mm infeeds: 5, 5, 2.
    let p = "O1\nG90 G0 X0 Y0 Z50.\nG99 G83 X10. Y10. Z-10. R2. Q5. F80.\nG80\nM30\n";
    assert_eq!(
        trace(Dialect::Fanuc, p, Some(FANUC)),
        lines(&[
            "move rapid X=0 Y=0 Z=50 f=-",
            "move rapid X=10 Y=10 Z=50 f=-",
            "move rapid X=10 Y=10 Z=2 f=-",
            "move linear X=10 Y=10 Z=-3 f=80",
            "move rapid X=10 Y=10 Z=2 f=-",
            "move rapid X=10 Y=10 Z=-2.75 f=-",
            "move linear X=10 Y=10 Z=-8 f=80",
            "move rapid X=10 Y=10 Z=2 f=-",
            "move rapid X=10 Y=10 Z=-7.75 f=-",
            "move linear X=10 Y=10 Z=-10 f=80",
            "move rapid X=10 Y=10 Z=2 f=-",
            "end M30 steps=4",
        ])
    );
}

#[test]
fn g73_backs_off_by_the_return_amount_after_each_infeed() {
    let p = "O1\nG90 G0 X0 Y0 Z50.\nG98 G73 X10. Y10. Z-10. R2. Q5. F80.\nG80\nM30\n";
    assert_eq!(
        trace(Dialect::Fanuc, p, Some(Retracts { chip_break: 0.5, ..FANUC })),
        lines(&[
            "move rapid X=0 Y=0 Z=50 f=-",
            "move rapid X=10 Y=10 Z=50 f=-",
            "move rapid X=10 Y=10 Z=2 f=-",
            "move linear X=10 Y=10 Z=-3 f=80",
            "move rapid X=10 Y=10 Z=-2.5 f=-",
            "move linear X=10 Y=10 Z=-8 f=80",
            "move rapid X=10 Y=10 Z=-7.5 f=-",
            "move linear X=10 Y=10 Z=-10 f=80",
            "move rapid X=10 Y=10 Z=50 f=-",
            "end M30 steps=4",
        ])
    );
}

#[test]
fn sinumerik_cycle83_chip_removal_and_chip_breaking() {
    // RTP 50, RFP 2, SDIS 0, DP -10, FDPR 5, VARI 1 (chip removal), then VARI 0.
    let p = "G90 G0 X10 Y10 Z50 F80\nCYCLE83(50, 2, 0, -10, , , 5, , , , , 1)\n\
             CYCLE83(50, 2, 0, -10, , , 5, , , , , 0)\nM30\n";
    assert_eq!(
        trace(Dialect::Sinumerik, p, Some(SIEMENS)),
        lines(&[
            "move rapid X=10 Y=10 Z=50 f=-",
            "move rapid X=10 Y=10 Z=2 f=-",
            "move linear X=10 Y=10 Z=-3 f=80",
            "move rapid X=10 Y=10 Z=2 f=-",
            "move rapid X=10 Y=10 Z=-2.4 f=-",
            "move linear X=10 Y=10 Z=-8 f=80",
            "move rapid X=10 Y=10 Z=2 f=-",
            "move rapid X=10 Y=10 Z=-7.4 f=-",
            "move linear X=10 Y=10 Z=-10 f=80",
            "move rapid X=10 Y=10 Z=50 f=-",
            "move rapid X=10 Y=10 Z=2 f=-",
            "move linear X=10 Y=10 Z=-3 f=80",
            "move rapid X=10 Y=10 Z=-2 f=-",
            "move linear X=10 Y=10 Z=-8 f=80",
            "move rapid X=10 Y=10 Z=-7 f=-",
            "move linear X=10 Y=10 Z=-10 f=80",
            "move rapid X=10 Y=10 Z=50 f=-",
            "end M30 steps=4",
        ])
    );
}

#[test]
fn tapping_reverses_the_spindle_and_fine_boring_stays_a_cycle_event() {
    let p = "O1\nG90 G0 X0 Y0 Z20.\nS500 M3\nG98 G84 X5. Y5. Z-8. R3. F625.\nG80\n\
             G98 G76 X6. Y6. Z-8. R3. Q1. F50.\nG80\nM30\n";
    let t = trace(Dialect::Fanuc, p, Some(FANUC));
    assert_eq!(
        t[2..9].to_vec(),
        lines(&[
            "move rapid X=5 Y=5 Z=20 f=-",
            "move rapid X=5 Y=5 Z=3 f=-",
            "move linear X=5 Y=5 Z=-8 f=625",
            "spindle ccw 500",
            "move linear X=5 Y=5 Z=3 f=625",
            "spindle cw 500",
            "move rapid X=5 Y=5 Z=20 f=-",
        ]),
        "{t:?}"
    );
    assert!(t[10].starts_with("cycle fine_bore X=6 Y=6"), "{t:?}");
}

#[test]
fn a_hole_of_too_many_infeeds_is_refused_not_expanded_for_ever() {
    // 100 mm in 0.001 mm infeeds: 100 000 infeeds.
    let p = "O1\nG90 G0 X0 Y0 Z10.\nG99 G73 X1. Y1. Z-98. R2. Q0.001 F50.\nG80\nM30\n";
    let mut db = SourceDb::new();
    let loaded = crate::load(&mut db, "t.nc", p.as_bytes(), None);
    let parsed = crate::parse(&db, loaded.file, Dialect::Fanuc, &ParseOptions::for_dialect(Dialect::Fanuc));
    let mut sink = VecSink::default();
    let opts = RunOptions { expand_cycles: Some(FANUC), ..Default::default() };
    let out = run(&mut db, &parsed.unit, &mut NoCallees, &opts, &mut sink);
    assert!(out.diags.iter().any(|d| d.code == "NC453" && d.message.contains("100000 infeeds")), "{:?}", out.diags);
    // Without the option the hole is one event.
    let t = trace(Dialect::Fanuc, p, None);
    assert!(t.iter().any(|l| l.starts_with("cycle chip_break")), "{t:?}");
}
