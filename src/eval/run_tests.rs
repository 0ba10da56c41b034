//! Runs hand-built IR programs through the whole evaluator: control flow, calls, the
//! machine model and limits, one test per rule of docs/semantics.md.

use super::test_ir::*;
use super::trace::text_line;
use super::{run, Ending, NoCallees, Outcome, RunOptions, VecSink};
use crate::dialect::{Dialect, Semantics};
use crate::ir::*;
use crate::span::SourceDb;

fn run_opts(u: &Unit, opts: &RunOptions) -> (Vec<String>, Outcome) {
    let mut db = SourceDb::new();
    db.add("t", "x".repeat(1000));
    let mut sink = VecSink::default();
    let out = run(&mut db, u, &mut NoCallees, opts, &mut sink);
    (sink.events.iter().map(|(e, _)| text_line(e)).collect(), out)
}
fn run_u(u: &Unit) -> (Vec<String>, Outcome) {
    run_opts(u, &RunOptions::default())
}
fn fanuc(body: Vec<Stmt>) -> Unit {
    unit(Dialect::Fanuc, vec![program(Some(ProgName::Number(1)), body)])
}
fn siemens(body: Vec<Stmt>) -> Unit {
    unit(Dialect::Sinumerik, vec![program(None, body)])
}
fn g(k: f64) -> Item {
    word("G", n(k))
}

#[test]
fn fanuc_decimal_point_rule() {
    let u = fanuc(vec![
        s(vec![g(1.0), word("X", n(10.0)), word("Y", p(10.0)), word("F", n(100.0))]),
        s(vec![assign(VarKind::Hash(1), n(123.0))]),
        s(vec![word("X", hash(1))]),
        s(vec![end()]),
    ]);
    let (t, _) = run_u(&u);
    assert_eq!(t[0], "move linear X=0.01 Y=10 f=100");
    assert_eq!(t[1], "move linear X=123 Y=10 f=100");
    let mut sem = Semantics::default_for(Dialect::Fanuc);
    sem.calculator_input = true;
    let (t, _) = run_opts(&u, &RunOptions { semantics: Some(sem), ..Default::default() });
    assert_eq!(t[0], "move linear X=10 Y=10 f=100");
}

#[test]
fn siemens_numbers_are_units() {
    let u = siemens(vec![s(vec![g(1.0), word("X", n(10.0)), word("F", n(100.0))]), s(vec![end()])]);
    assert_eq!(run_u(&u).0[0], "move linear X=10 f=100");
}

#[test]
fn values_round_to_the_increment_and_integer_addresses() {
    let u = fanuc(vec![
        s(vec![assign(VarKind::Hash(1), p(12.3456)), assign(VarKind::Hash(2), p(1000.5))]),
        s(vec![word("S", hash(2)), word("M", p(3.0))]),
        s(vec![g(0.0), word("X", hash(1))]),
        s(vec![end()]),
    ]);
    let (t, _) = run_u(&u);
    assert_eq!(t[0], "spindle cw 1001");
    assert_eq!(t[1], "move rapid X=12.346 f=-");
}

#[test]
fn vacant_variable_drops_the_word() {
    let u = fanuc(vec![
        s(vec![g(0.0), word("X", p(100.0)), word("Y", hash(1))]),
        s(vec![word("Y", hash(1))]),
        s(vec![word("Y", neg(hash(1)))]),
        s(vec![end()]),
    ]);
    let (t, out) = run_u(&u);
    assert_eq!(t, vec!["move rapid X=100 f=-", "end M30 steps=4"]);
    assert!(out.diags.iter().any(|d| d.code == "NC404" && d.message.contains("#1")));
}

#[test]
fn fanuc_goto_searches_forward_then_wraps() {
    // N1 X1 / GOTO 5 / N5 X2 / N5 X3 / M30 : the first N5 forward wins.
    let u = fanuc(vec![
        s(vec![assign(VarKind::Hash(100), p(0.0))]),
        blk(vec![assign(VarKind::Hash(100), bin(BinOp::Add, hash(100), p(1.0)))]).n(5).stmt(),
        s(vec![goto(
            Search::ForwardThenWrap,
            num_target(9),
            Some(cmp(CmpOp::Ge, Tolerance::Exact, hash(100), p(2.0))),
        )]),
        s(vec![goto(Search::ForwardThenWrap, num_target(5), None)]),
        blk(vec![g(0.0), word("X", p(2.0))]).n(5).stmt(),
        s(vec![goto(Search::ForwardThenWrap, num_target(6), None)]),
        blk(vec![word("X", p(3.0))]).n(6).stmt(),
        s(vec![goto(Search::ForwardThenWrap, num_target(5), None)]),
        blk(vec![end()]).n(9).stmt(),
    ]);
    let (t, _) = run_u(&u);
    // GOTO 5 from block 3 finds the N5 after it (X2); the GOTO 5 at the end wraps to the
    // top N5 (the counter reaches 2 and jumps to N9).
    assert_eq!(t, vec!["move rapid X=2 f=-", "move rapid X=3 f=-", "end M30 steps=11"]);
}

#[test]
fn computed_goto_rounds_and_missing_target_alarms() {
    let u = fanuc(vec![
        s(vec![assign(VarKind::Hash(1), p(4.5))]),
        s(vec![goto(Search::ForwardThenWrap, Target::Computed(hash(1)), None)]),
        blk(vec![g(0.0), word("X", p(4.0))]).n(4).stmt(),
        blk(vec![g(0.0), word("X", p(5.0))]).n(5).stmt(),
        s(vec![goto(Search::ForwardThenWrap, num_target(77), None)]),
    ]);
    let (t, out) = run_u(&u);
    assert_eq!(t[0], "move rapid X=5 f=-");
    assert!(t[1].starts_with("alarm 128 "), "{}", t[1]);
    assert!(matches!(out.ending, Ending::Alarm { number: 128, .. }));
}

#[test]
fn siemens_gotob_gotof_and_labels() {
    let u = siemens(vec![
        s(vec![assign(VarKind::R(1), p(0.0))]),
        blk(vec![assign(VarKind::R(1), bin(BinOp::Add, r(1), p(1.0)))]).label("TOP").stmt(),
        s(vec![goto(Search::Backward, label_target("TOP"), Some(cmp(CmpOp::Lt, Tolerance::Relative, r(1), p(3.0))))]),
        s(vec![goto(Search::Forward, label_target("FIN"), None)]),
        s(vec![g(0.0), word("X", p(99.0))]),
        blk(vec![g(0.0), word("X", r(1))]).label("FIN").stmt(),
        s(vec![end()]),
    ]);
    let (t, _) = run_u(&u);
    assert_eq!(t, vec!["move rapid X=3 f=-", "end M30 steps=10"]);
}

#[test]
fn while_do_loop_and_step_count() {
    let u = fanuc(vec![
        s(vec![assign(VarKind::Hash(1), p(0.0))]),
        do_(
            Some(cmp(CmpOp::Lt, Tolerance::Exact, hash(1), p(3.0))),
            vec![
                s(vec![assign(VarKind::Hash(1), bin(BinOp::Add, hash(1), p(1.0)))]),
                s(vec![g(1.0), word("X", hash(1)), word("F", p(100.0))]),
            ],
        ),
        s(vec![end()]),
    ]);
    let (t, out) = run_u(&u);
    assert_eq!(t.len(), 4);
    assert_eq!(t[2], "move linear X=3 f=100");
    // 1 + 3×(head + 2 + end) + final head + M30
    assert_eq!(out.steps, 1 + 3 * 4 + 1 + 1);
}

#[test]
fn endless_loop_hits_the_step_limit() {
    let u = fanuc(vec![do_(None, vec![s(vec![g(0.0), word("X", p(1.0))])])]);
    let (t, out) = run_opts(&u, &RunOptions { max_steps: 100, ..Default::default() });
    assert_eq!(t.last().map(String::as_str), Some("limit steps=100"));
    assert!(matches!(out.ending, Ending::Limit { .. }));
}

#[test]
fn g65_fresh_locals_args_and_m98_shares_locals() {
    let call = |kind, prog, args: Vec<Arg>, repeat: Option<Expr>| {
        item(ItemKind::Call(Box::new(Call { kind, target: CallTarget::Number(prog), args, repeat })))
    };
    let main = program(
        Some(ProgName::Number(1)),
        vec![
            s(vec![assign(VarKind::Hash(24), p(7.0))]),
            s(vec![call(
                CallKind::G65,
                9000,
                vec![Arg::Letter { letter: b'X', var: 24, value: n(10.0) }],
                Some(n(2.0)),
            )]),
            s(vec![g(0.0), word("Y", hash(24))]),
            s(vec![call(CallKind::M98, 9001, vec![], None)]),
            s(vec![g(0.0), word("Y", hash(24))]),
            s(vec![end()]),
        ],
    );
    // O9000: X#24 then #24=#24+1 (second repetition sees 0.011); M99.
    let m9000 = program(
        Some(ProgName::Number(9000)),
        vec![
            s(vec![g(0.0), word("X", hash(24))]),
            s(vec![assign(VarKind::Hash(24), bin(BinOp::Add, hash(24), p(0.001)))]),
            s(vec![item(ItemKind::Return { to: None })]),
        ],
    );
    // O9001 shares the caller's locals: #24 = 8.
    let m9001 = program(
        Some(ProgName::Number(9001)),
        vec![s(vec![assign(VarKind::Hash(24), p(8.0))]), s(vec![item(ItemKind::Return { to: None })])],
    );
    let u = unit(Dialect::Fanuc, vec![main, m9000, m9001]);
    let (t, _) = run_u(&u);
    assert_eq!(
        t,
        vec![
            "move rapid X=0.01 f=-",
            "move rapid X=0.011 f=-",
            "move rapid X=0.011 Y=7 f=-",
            "move rapid X=0.011 Y=8 f=-",
            "end M30 steps=14"
        ]
    );
}

#[test]
fn m99_in_main_ends_the_trace() {
    let u = fanuc(vec![s(vec![g(0.0), word("X", p(1.0))]), s(vec![item(ItemKind::Return { to: None })])]);
    let (t, _) = run_u(&u);
    assert_eq!(t.last().map(String::as_str), Some("end M99 steps=2"));
}

#[test]
fn macro_nesting_limit_is_inconclusive() {
    let call = item(ItemKind::Call(Box::new(Call {
        kind: CallKind::G65,
        target: CallTarget::Number(1),
        args: vec![],
        repeat: None,
    })));
    let u = fanuc(vec![s(vec![call])]);
    let (t, out) = run_u(&u);
    assert!(t[0].starts_with("limit"));
    assert!(matches!(&out.ending, Ending::Limit { reason } if reason.contains("4 levels")));
}

#[test]
fn missing_callee_is_an_error_naming_it() {
    let call = item(ItemKind::Call(Box::new(Call {
        kind: CallKind::Named,
        target: CallTarget::Name("CONTOUR".into()),
        args: vec![],
        repeat: None,
    })));
    let (_, out) = run_u(&siemens(vec![s(vec![call])]));
    assert_eq!(out.ending, Ending::Error);
    assert!(out.diags.iter().any(|d| d.code == "NC401" && d.message.contains("CONTOUR")));
}

#[test]
fn arcs_radius_sign_and_full_circle() {
    let u = fanuc(vec![
        s(vec![g(1.0), word("X", p(0.0)), word("Y", p(0.0)), word("F", p(100.0))]),
        s(vec![g(2.0), word("X", p(10.0)), word("R", p(-10.0))]),
        s(vec![g(3.0), word("I", p(-5.0))]),
        s(vec![end()]),
    ]);
    let (t, _) = run_u(&u);
    assert_eq!(t[1], "arc cw XY X=10 Y=0 center X=5 Y=8.660254 f=100");
    assert_eq!(t[2], "arc ccw XY X=10 Y=0 center X=5 Y=0 f=100");
}

#[test]
fn feed_motion_without_feed_alarms() {
    let (t, _) = run_u(&fanuc(vec![s(vec![g(1.0), word("X", p(1.0))])]));
    assert!(t[0].starts_with("alarm 11 "));
    let (t, _) = run_u(&siemens(vec![s(vec![g(1.0), word("X", p(1.0))])]));
    assert!(t[0].starts_with("alarm 10860 "));
}

#[test]
fn work_offsets_and_g53() {
    let u = fanuc(vec![
        s(vec![g(10.0), word("L", n(2.0)), word("P", n(1.0)), word("X", p(100.0))]),
        s(vec![g(54.0), g(0.0), word("X", p(5.0))]),
        s(vec![assign(VarKind::Hash(1), hash(5041))]),
        s(vec![g(53.0), word("X", p(0.0))]),
        s(vec![g(0.0), word("Y", hash(1))]),
        s(vec![end()]),
    ]);
    let (t, _) = run_u(&u);
    // The G10 write to the active G54 acts at once (a work_offset), then G54 selects it.
    assert_eq!(
        t,
        vec![
            "work_offset 1",
            "work_offset 1",
            "move rapid X=105 f=-",
            "move rapid X=0 f=-",
            "move rapid X=0 Y=5 f=-",
            "end M30 steps=6"
        ]
    );
}

#[test]
fn siemens_uifr_needs_reselection() {
    let uifr = VarKind::System {
        name: "P_UIFR".into(),
        indices: vec![
            n(1.0),
            Expr::new(ExprKind::Ident("X".into()), sp()),
            Expr::new(ExprKind::Ident("TR".into()), sp()),
        ],
    };
    let u = siemens(vec![
        s(vec![g(54.0)]),
        s(vec![assign(uifr, p(50.0))]),
        s(vec![g(0.0), word("X", p(1.0))]),
        s(vec![g(54.0), word("X", p(1.0))]),
        s(vec![end()]),
    ]);
    let (t, _) = run_u(&u);
    assert_eq!(
        t,
        vec!["work_offset 1", "move rapid X=1 f=-", "work_offset 1", "move rapid X=51 f=-", "end M30 steps=5"]
    );
}

#[test]
fn units_inch_feeds() {
    let u = fanuc(vec![s(vec![g(20.0), g(1.0), word("X", p(1.0)), word("F", p(10.0))]), s(vec![end()])]);
    assert_eq!(run_u(&u).0[0], "move linear X=25.4 f=254");
    let u = siemens(vec![s(vec![g(70.0), g(1.0), word("X", p(1.0)), word("F", p(10.0))]), s(vec![end()])]);
    assert_eq!(run_u(&u).0[0], "move linear X=25.4 f=10");
    let u = siemens(vec![s(vec![g(700.0), g(1.0), word("X", p(1.0)), word("F", p(10.0))]), s(vec![end()])]);
    assert_eq!(run_u(&u).0[0], "move linear X=25.4 f=254");
}

/// Siemens G70/G71 after G700/G710: F is read in the basic system (metric) again, and the
/// feed already in force keeps its physical value across every switch (828D FM G2, 7.3).
#[test]
fn siemens_g70_after_g700_reads_feeds_metric() {
    let u = siemens(vec![
        s(vec![g(700.0), g(1.0), word("X", p(1.0)), word("F", p(20.0))]),
        s(vec![g(70.0), word("Y", p(1.0))]),
        s(vec![word("Y", p(2.0)), word("F", p(300.0))]),
        s(vec![g(700.0), word("Y", p(3.0)), word("F", p(10.0))]),
        s(vec![g(71.0), word("Y", p(4.0))]),
        s(vec![word("Y", p(5.0)), word("F", p(300.0))]),
        s(vec![g(710.0), word("Y", p(6.0)), word("F", p(300.0))]),
        s(vec![end()]),
    ]);
    let t = run_u(&u).0;
    assert_eq!(t[0], "move linear X=25.4 f=508");
    assert_eq!(t[1], "move linear X=25.4 Y=25.4 f=508", "G70 keeps the feed in force");
    assert_eq!(t[2], "move linear X=25.4 Y=50.8 f=300", "F under G70 is mm/min");
    assert_eq!(t[3], "move linear X=25.4 Y=76.2 f=254");
    assert_eq!(t[4], "move linear X=25.4 Y=4 f=254", "G71 keeps the feed in force");
    assert_eq!(t[5], "move linear X=25.4 Y=5 f=300");
    assert_eq!(t[6], "move linear X=25.4 Y=6 f=300");
}

/// FANUC G04 X without a decimal point counts the increment system's dwell unit (IS-B
/// 0.001 s, IS-C 0.0001 s: S28), whatever G20/G21; G20 lengths count 0.0001 in (IS-B).
#[test]
fn fanuc_bare_dwell_and_inch_lengths_follow_the_increment_system() {
    let u = fanuc(vec![
        s(vec![g(4.0), word("X", n(1500.0))]),
        s(vec![g(20.0), g(0.0), word("Z", n(1000.0))]),
        s(vec![g(4.0), word("X", n(1500.0))]),
        s(vec![end()]),
    ]);
    let t = run_u(&u).0;
    assert_eq!(t[..3], ["dwell 1.5", "move rapid Z=2.54 f=-", "dwell 1.5"]);
    let mut sem = Semantics::default_for(Dialect::Fanuc);
    sem.least_increment_mm = 0.0001;
    let (t, _) = run_opts(&u, &RunOptions { semantics: Some(sem), ..Default::default() });
    assert_eq!(t[..3], ["dwell 0.15", "move rapid Z=0.254 f=-", "dwell 0.15"]);
}

#[test]
fn dwell_units_per_control() {
    let u = fanuc(vec![
        s(vec![g(4.0), word("P", n(500.0))]),
        s(vec![g(4.0), word("X", n(1500.0))]),
        s(vec![g(4.0), word("X", p(2.0))]),
        s(vec![end()]),
    ]);
    assert_eq!(run_u(&u).0[..3], ["dwell 0.5", "dwell 1.5", "dwell 2"]);
    let u = siemens(vec![
        s(vec![word("S", p(600.0)), word("M", n(3.0))]),
        s(vec![g(4.0), word("F", p(2.5))]),
        s(vec![g(4.0), word("S", p(30.0))]),
        s(vec![end()]),
    ]);
    assert_eq!(run_u(&u).0[1..3], ["dwell 2.5", "dwell 3"]);
}

#[test]
fn event_order_inside_a_block_and_msg_merge() {
    let u = siemens(vec![
        s(vec![word("T", Expr::new(ExprKind::Str("Ball".into()), sp()))]),
        s(vec![
            word("M", n(5.0)),
            word("M", n(9.0)),
            g(1.0),
            word("X", p(1.0)),
            word("F", p(1.0)),
            word("M", n(6.0)),
            word("S", p(100.0)),
            word("M", n(3.0)),
            word("M", n(8.0)),
        ]),
        s(vec![item(ItemKind::Message { text: Some(Expr::new(ExprKind::Str("check".into()), sp())) })]),
        s(vec![word("M", n(0.0))]),
        s(vec![item(ItemKind::Message { text: Some(Expr::new(ExprKind::Str("info".into()), sp())) })]),
        s(vec![end()]),
    ]);
    let (t, _) = run_u(&u);
    assert_eq!(
        t,
        vec![
            "tool \"Ball\"",
            // The tool change selects edge D1 (MD20270): in force before the block's motion.
            "comp length=\"Ball.1\" radius=off",
            "spindle cw 100",
            "coolant on",
            "move linear X=1 f=1",
            "spindle stop 100",
            "coolant off",
            "stop \"check\"",
            "message \"info\"",
            "end M30 steps=6"
        ]
    );
}

#[test]
fn siemens_int_variables_round_on_assignment() {
    let def = item(ItemKind::Def(Box::new(Def {
        scope: None,
        ty: DataType::Int,
        vars: vec![DefVar { name: "K".into(), dims: vec![], init: Some(Init::Value(p(2.5))), span: sp() }],
    })));
    let u = siemens(vec![
        s(vec![def]),
        s(vec![g(0.0), word("X", named("K"))]),
        s(vec![assign(VarKind::Named { name: "K".into(), indices: vec![] }, p(-1.5))]),
        s(vec![word("X", named("K"))]),
        s(vec![end()]),
    ]);
    let (t, _) = run_u(&u);
    assert_eq!(t[..2], ["move rapid X=3 f=-", "move rapid X=-2 f=-"]);
}

#[test]
fn unmodelled_system_variable_is_an_error() {
    let u = fanuc(vec![s(vec![assign(VarKind::Hash(1), hash(2001))]), s(vec![end()])]);
    let (_, out) = run_u(&u);
    assert_eq!(out.ending, Ending::Error);
    assert!(out.diags.iter().any(|d| d.code == "NC400" && d.message.contains("#2001")));
}

#[test]
fn fanuc_macro_alarm_and_stop_message() {
    let u = fanuc(vec![
        s(vec![item(ItemKind::StopMessage { text: Some("CHECK".into()) })]),
        s(vec![item(ItemKind::Alarm { style: AlarmStyle::FanucMacro, number: n(1.0), text: Some("NO PROBE".into()) })]),
        s(vec![end()]),
    ]);
    let (t, out) = run_u(&u);
    assert_eq!(t, vec!["stop \"CHECK\"", "alarm 3001 \"NO PROBE\""]);
    assert!(matches!(out.ending, Ending::Alarm { number: 3001, .. }));
}

#[test]
fn running_off_the_end_of_main_alarms() {
    let (t, _) = run_u(&siemens(vec![s(vec![g(0.0), word("X", p(1.0))])]));
    assert!(t[1].starts_with("alarm 0 "));
}

#[test]
fn inputs_set_variables() {
    let u = siemens(vec![s(vec![g(0.0), word("X", r(1))]), s(vec![end()])]);
    let opts = RunOptions { inputs: vec![super::parse_input("R1=5").unwrap()], ..Default::default() };
    assert_eq!(run_opts(&u, &opts).0[0], "move rapid X=5 f=-");
}

#[test]
fn siemens_ac_ic_per_word() {
    let u = siemens(vec![
        s(vec![g(90.0), g(0.0), word("X", p(1.0))]),
        s(vec![word_v("X", WordValue::Ic(p(2.0)))]),
        s(vec![g(91.0), word_v("X", WordValue::Ac(p(10.0))), word("Y", p(1.0))]),
        s(vec![word("Y", p(1.0))]),
        s(vec![end()]),
    ]);
    let (t, _) = run_u(&u);
    assert_eq!(
        t[..4],
        ["move rapid X=1 f=-", "move rapid X=3 f=-", "move rapid X=10 Y=1 f=-", "move rapid X=10 Y=2 f=-"]
    );
}

#[test]
fn goto_into_a_loop_body_runs_to_its_end_and_back_to_the_head() {
    // GOTO 7 jumps into the DO body; END1 goes back to the WHILE head, which tests #1.
    let u = fanuc(vec![
        s(vec![assign(VarKind::Hash(1), p(5.0))]),
        s(vec![goto(Search::ForwardThenWrap, num_target(7), None)]),
        do_(
            Some(cmp(CmpOp::Lt, Tolerance::Exact, hash(1), p(3.0))),
            vec![blk(vec![g(0.0), word("X", hash(1))]).n(7).stmt()],
        ),
        s(vec![end()]),
    ]);
    let (t, _) = run_u(&u);
    assert_eq!(t, vec!["move rapid X=5 f=-", "end M30 steps=6"]);
}

#[test]
fn siemens_for_end_value_is_evaluated_on_every_pass() {
    let var_i = VarKind::R(1);
    let for_ = Stmt {
        kind: StmtKind::For(Box::new(ForStmt {
            head: meta(),
            var: vref(var_i.clone()),
            from: p(1.0),
            to: r(2),
            body: vec![
                s(vec![g(0.0), word("X", r(1))]),
                // Lowering the end value inside the loop ends it early.
                s(vec![assign(VarKind::R(2), p(2.0))]),
            ],
            end: meta(),
        })),
        span: sp(),
    };
    let u = siemens(vec![s(vec![assign(VarKind::R(2), p(10.0))]), for_, s(vec![end()])]);
    let (t, _) = run_u(&u);
    assert_eq!(t, vec!["move rapid X=1 f=-", "move rapid X=2 f=-", "end M30 steps=9"]);
}

#[test]
fn g53_ignores_g91() {
    let u =
        fanuc(vec![s(vec![g(0.0), word("X", p(10.0))]), s(vec![g(91.0), g(53.0), word("X", p(-1.5))]), s(vec![end()])]);
    assert_eq!(run_u(&u).0[1], "move rapid X=-1.5 f=-");
}

#[test]
fn incremental_move_after_an_offset_change() {
    // FANUC: G91 after switching G54 → G55 moves by the increment only.
    let fan = fanuc(vec![
        s(vec![g(10.0), word("L", n(2.0)), word("P", n(2.0)), word("X", p(100.0))]),
        s(vec![g(54.0), g(0.0), word("X", p(1.0))]),
        s(vec![g(55.0), g(91.0), word("X", p(1.0))]),
        s(vec![end()]),
    ]);
    assert_eq!(run_u(&fan).0[3], "move rapid X=2 f=-");
    // Siemens (MD42440 = 1): the increment applies to the programmed position, so the
    // move also travels the new offset.
    let sie = siemens(vec![
        s(vec![g(0.0), word("X", p(1.0))]),
        s(vec![item(ItemKind::Frame {
            op: "TRANS".into(),
            words: vec![Word { addr: Addr::Letter(b'X'), value: WordValue::Expr(p(100.0)), span: sp() }],
        })]),
        s(vec![word_v("X", WordValue::Ic(p(1.0)))]),
        s(vec![end()]),
    ]);
    assert_eq!(run_u(&sie).0[1], "move rapid X=102 f=-");
}

#[test]
fn machine_specific_m_codes_emit_nothing_with_a_warning() {
    let u = fanuc(vec![s(vec![word("M", n(19.0))]), s(vec![end()])]);
    let (t, out) = run_u(&u);
    assert_eq!(t, vec!["end M30 steps=2"]);
    assert!(out.diags.iter().any(|d| d.code == "NC405" && d.message.contains("M19")));
}

#[test]
fn g66_is_modal_in_m98_subprograms_but_not_inside_its_macro() {
    let call = |kind, prog, args: Vec<Arg>| {
        item(ItemKind::Call(Box::new(Call { kind, target: CallTarget::Number(prog), args, repeat: None })))
    };
    let main = program(
        Some(ProgName::Number(1)),
        vec![
            s(vec![call(CallKind::G66, 9100, vec![Arg::Letter { letter: b'Z', var: 26, value: p(-1.0) }])]),
            s(vec![call(CallKind::M98, 2000, vec![])]),
            s(vec![item(ItemKind::ModalCallOff)]),
            s(vec![end()]),
        ],
    );
    let sub = program(
        Some(ProgName::Number(2000)),
        vec![s(vec![g(0.0), word("X", p(5.0))]), s(vec![item(ItemKind::Return { to: None })])],
    );
    // The modal macro moves too: that move must not call it again.
    let mac = program(
        Some(ProgName::Number(9100)),
        vec![s(vec![g(0.0), word("Z", hash(26))]), s(vec![item(ItemKind::Return { to: None })])],
    );
    let (t, _) = run_u(&unit(Dialect::Fanuc, vec![main, sub, mac]));
    assert_eq!(t, vec!["move rapid X=5 f=-", "move rapid X=5 Z=-1 f=-", "end M30 steps=8"]);
}

#[test]
fn fanuc_3003_3004_are_stored_without_effect() {
    let u = fanuc(vec![
        s(vec![assign(VarKind::Hash(3004), p(3.0))]),
        s(vec![assign(VarKind::Hash(1), hash(3004))]),
        s(vec![g(0.0), word("X", hash(1))]),
        s(vec![end()]),
    ]);
    let (t, out) = run_u(&u);
    assert_eq!(t[0], "move rapid X=3 f=-");
    assert!(out.diags.iter().any(|d| d.code == "NC405" && d.message.contains("#3004")));
}

#[test]
fn fanuc_modal_group_variables() {
    let u = fanuc(vec![
        s(vec![g(91.0), g(18.0), g(41.0), g(43.0), word("H", n(1.0))]),
        s(vec![assign(VarKind::Hash(1), hash(4003))]),
        s(vec![assign(VarKind::Hash(2), hash(4002))]),
        s(vec![assign(VarKind::Hash(3), hash(4007))]),
        s(vec![assign(VarKind::Hash(4), hash(4008))]),
        s(vec![assign(VarKind::Hash(5), hash(4012))]),
        s(vec![
            g(90.0),
            g(0.0),
            word("X", hash(1)),
            word("Y", hash(2)),
            word("Z", hash(3)),
            word("A", hash(4)),
            word("B", hash(5)),
        ]),
        s(vec![end()]),
    ]);
    // G41 without D and G43 with H1: length on, radius off (D0).
    assert_eq!(run_u(&u).0[0], "comp length=1 radius=off");
    assert_eq!(run_u(&u).0[1], "move rapid X=91 Y=18 Z=41 A=43 B=67 f=-");
}

#[test]
fn probe_moves_reach_the_end_point_unless_a_contact_is_given() {
    // FANUC G31: the skip position #5061 is where the move stopped.
    let f = fanuc(vec![
        s(vec![g(31.0), word("X", p(10.0)), word("F", p(100.0))]),
        s(vec![assign(VarKind::Hash(1), hash(5061))]),
        s(vec![g(1.0), word("Y", hash(1))]),
        s(vec![end()]),
    ]);
    let (t, _) = run_u(&f);
    assert_eq!(t[0], "move linear X=10 f=100 probe");
    assert_eq!(t[1], "move linear X=10 Y=10 f=100");
    let (t, _) = run_opts(&f, &RunOptions { probe_contact: Some(0.25), ..Default::default() });
    assert_eq!(t[0], "move linear X=2.5 f=100 probe");
    assert_eq!(t[1], "move linear X=2.5 Y=2.5 f=100");
    // Siemens MEAS=1: $AA_MW is written only when the probe switches (0 before).
    let aa_mw =
        var(VarKind::System { name: "AA_MW".into(), indices: vec![Expr::new(ExprKind::Ident("X".into()), sp())] });
    let u = siemens(vec![
        s(vec![word("MEAS", n(1.0)), g(1.0), word("X", n(10.0)), word("F", n(100.0))]),
        s(vec![word("Y", aa_mw)]),
        s(vec![end()]),
    ]);
    let (t, _) = run_u(&u);
    assert_eq!(t[0], "move linear X=10 f=100 probe");
    assert_eq!(t[1], "move linear X=10 Y=0 f=100");
    let (t, _) = run_opts(&u, &RunOptions { probe_contact: Some(0.5), ..Default::default() });
    assert_eq!(t[0], "move linear X=5 f=100 probe");
    assert_eq!(t[1], "move linear X=5 Y=5 f=100");
}
