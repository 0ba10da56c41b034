//! Unit tests of `check` (trace comparison, verdicts, exclusions).

use super::*;
use crate::dialect::Dialect;
use crate::eval::test_ir::*;
use crate::eval::NoCallees;
use crate::ir::{BinOp, CmpOp, ProgName, Tolerance, VarKind};

fn side(unit: Unit) -> Side {
    Side { unit, callees: Box::new(NoCallees), run: RunOptions::default() }
}
fn db2() -> SourceDb {
    let mut db = SourceDb::new();
    db.add("a.nc", "x\n".repeat(50));
    db.add("b.mpf", "y\n".repeat(50));
    db
}
/// FANUC: #1 = 0; WHILE [#1 LT 5] DO1; #1 = #1 + 1; G1 X#1 F100.; END1; M30
fn fanuc_loop(step: f64) -> Unit {
    fanuc_loop_to(step, 5.0)
}
fn fanuc_loop_to(step: f64, to: f64) -> Unit {
    let mut u = unit(
        Dialect::Fanuc,
        vec![program(
            Some(ProgName::Number(1)),
            vec![
                s(vec![assign(VarKind::Hash(1), p(0.0))]),
                do_(
                    Some(cmp(CmpOp::Lt, Tolerance::Exact, hash(1), p(to))),
                    vec![
                        s(vec![assign(VarKind::Hash(1), bin(BinOp::Add, hash(1), p(step)))]),
                        s(vec![word("G", n(1.0)), word("X", hash(1)), word("F", p(100.0))]),
                    ],
                ),
                s(vec![end()]),
            ],
        )],
    );
    u.file = 0;
    u
}
/// Siemens: R1=0; WHILE R1<5; R1=R1+1; G1 X=R1 F100; ENDWHILE; M30
fn siemens_loop() -> Unit {
    siemens_loop_to(5.0)
}
fn siemens_loop_to(to: f64) -> Unit {
    let mut u = unit(
        Dialect::Sinumerik,
        vec![program(
            None,
            vec![
                s(vec![assign(VarKind::R(1), p(0.0))]),
                while_(
                    cmp(CmpOp::Lt, Tolerance::Relative, r(1), p(to)),
                    vec![
                        s(vec![assign(VarKind::R(1), bin(BinOp::Add, r(1), p(1.0)))]),
                        s(vec![word("G", n(1.0)), word("X", r(1)), word("F", p(100.0))]),
                    ],
                ),
                s(vec![end()]),
            ],
        )],
    );
    u.file = 1;
    u
}

#[test]
fn equal_programs_in_two_dialects_are_equivalent() {
    let r = check(&db2(), side(fanuc_loop(1.0)), side(siemens_loop()));
    assert_eq!(r.verdict, Verdict::Equivalent { events: 6 });
    assert!(r.diff.is_empty());
}

#[test]
fn an_altered_program_diverges_at_the_right_event() {
    let r = check(&db2(), side(fanuc_loop(2.0)), side(siemens_loop()));
    // Steps of 2 move to X=2 first where the Siemens loop moves to X=1.
    assert_eq!(r.verdict, Verdict::Diverged { index: 0 });
    let d = r.diags.iter().find(|d| d.code == "NC500").expect("divergence diagnostic");
    assert!(d.message.contains("`move linear X=2 f=100` vs `move linear X=1 f=100`"), "{}", d.message);
    assert_eq!(d.labels.len(), 2);
    assert_eq!((d.labels[0].file, d.labels[1].file), (0, 1));
    assert!(r.diff.contains("-move linear X=6 f=100"), "{}", r.diff);
    assert!(r.diff.contains("+move linear X=1 f=100"), "{}", r.diff);
}

#[test]
fn divergences_after_many_batches_show_the_events_around_them() {
    // 2500 moves agree, then one program ends where the other moves on (and the other
    // way round): the divergence, its context and its diff are found across batches,
    // in two threads and in one.
    for (fa, sb) in [(2500.0, 3000.0), (3000.0, 2500.0)] {
        let run = || check(&db2(), side(fanuc_loop_to(1.0, fa)), side(siemens_loop_to(sb)));
        let r = run();
        assert_eq!(r.verdict, Verdict::Diverged { index: 2500 });
        let (ended, moved) = if fa < sb { ("-", "+") } else { ("+", "-") };
        assert!(r.diff.contains(&format!("{ended}end M30")), "{}", r.diff);
        assert!(r.diff.contains(&format!("{moved}move linear X=2501 f=100")), "{}", r.diff);
        assert!(r.diff.contains(" move linear X=2498 f=100\n move linear X=2499 f=100\n move linear X=2500 f=100\n"));
        let one = in_one_thread(run);
        assert_eq!((one.verdict, one.diff, one.diags), (r.verdict, r.diff, r.diags));
    }
    let r = check(&db2(), side(fanuc_loop_to(1.0, 5000.0)), side(siemens_loop_to(5000.0)));
    assert_eq!(r.verdict, Verdict::Equivalent { events: 5001 });
}

#[test]
fn a_limit_is_inconclusive_never_equal() {
    let mut a = side(fanuc_loop(1.0));
    a.run.max_steps = 5;
    let mut b = side(siemens_loop());
    b.run.max_steps = 5;
    let r = check(&db2(), a, b);
    assert!(matches!(r.verdict, Verdict::Inconclusive { .. }), "{:?}", r.verdict);
}

#[test]
fn runtime_alarms_compare_by_class() {
    assert!(same_event(
        &Event::Alarm { number: 112, message: "x".into() },
        &Event::Alarm { number: 14051, message: "y".into() }
    ));
    assert!(!same_event(
        &Event::Alarm { number: 112, message: "x".into() },
        &Event::Alarm { number: 14080, message: "x".into() }
    ));
    assert!(same_event(&Event::End { code: "M99", steps: 3 }, &Event::End { code: "RET", steps: 9 }));
}

#[test]
fn setal_64000_plus_n_is_fanuc_alarm_n() {
    let alarm = |number| Event::Alarm { number, message: String::new() };
    assert!(same_event(&alarm(115), &alarm(64115)));
    assert!(same_event(&alarm(64115), &alarm(115)));
    assert!(same_event(&alarm(64115), &alarm(17020)), "the same class as Siemens' own index alarm");
    assert!(same_event(&alarm(500), &alarm(64500)), "a FANUC alarm without a class pairs by number");
    assert!(!same_event(&alarm(112), &alarm(64115)));
    assert!(!same_event(&alarm(3115), &alarm(64115)), "user alarms are 65000+n");
}

#[test]
fn one_thread_checks_give_the_same_verdicts() {
    let both = |f: f64| {
        let two = check(&db2(), side(fanuc_loop(f)), side(siemens_loop()));
        let one = in_one_thread(|| check(&db2(), side(fanuc_loop(f)), side(siemens_loop())));
        assert_eq!(one.verdict, two.verdict);
        assert_eq!(one.diff, two.diff);
        assert_eq!(one.diags, two.diags);
    };
    both(1.0);
    both(2.0);
    let mut a = side(fanuc_loop(1.0));
    a.run.max_steps = 5;
    let r = in_one_thread(|| check(&db2(), a, side(siemens_loop())));
    assert!(matches!(r.verdict, Verdict::Inconclusive { .. }), "{:?}", r.verdict);
    assert!(!ONE_THREAD.with(Cell::get), "the mode ends with the closure");
}
