//! Unit tests of the words pass (Sinumerik → FANUC words).

use super::super::build::*;
use super::*;

fn run_words(items: Vec<Item>, ctx: &mut Ctx) -> Vec<Stmt> {
    let mut prog = program(vec![block(items)]);
    run(ctx, &mut prog, &ProgInfo::default());
    prog.body
}

#[test]
fn letters_follow_spec_one_then_two() {
    let l = param_letters(3).unwrap_or_default();
    assert_eq!(l, vec![(b'A', 1), (b'B', 2), (b'C', 3)]);
    let l = param_letters(22).unwrap_or_default();
    assert_eq!(l[3], (b'I', 4));
    assert_eq!(l[21], (b'I', 22));
    assert!(param_letters(34).is_none());
}

#[test]
fn cr_becomes_r_and_g4_f_becomes_x() {
    let mut ctx = Ctx::new(0, UnsupportedPolicy::Error);
    let w = Word { addr: Addr::Name("CR".into()), value: WordValue::Expr(n(5.0)), span: sp() };
    let body = run_words(vec![item(ItemKind::Word(w), sp())], &mut ctx);
    assert_eq!(shape_words(&body[0]), "R");
    let body = run_words(vec![word_item(b'G', n(4.0)), word_item(b'F', n(2.0))], &mut ctx);
    assert_eq!(shape_words(&body[0]), "G X");
}

#[test]
fn unknown_tool_name_is_an_error_with_a_hint() {
    let mut ctx = Ctx::new(0, UnsupportedPolicy::Error);
    let t = Expr::new(ExprKind::Str("BALLNOSE_D8".into()), sp());
    run_words(vec![word_item(b'T', t)], &mut ctx);
    assert_eq!(ctx.diags[0].code, "NC301");
    assert!(ctx.diags[0].notes[0].contains("--tool-map BALLNOSE_D8="));
}

#[test]
fn ic_in_absolute_mode_switches_to_g91_and_back() {
    let mut ctx = Ctx::new(0, UnsupportedPolicy::Error);
    let w = Word { addr: Addr::Letter(b'X'), value: WordValue::Ic(n(5.0)), span: sp() };
    let body = run_words(vec![word_item(b'G', n(1.0)), item(ItemKind::Word(w), sp())], &mut ctx);
    assert_eq!(body.len(), 2);
    assert_eq!(shape_words(&body[0]), "G G X");
    assert_eq!(shape_words(&body[1]), "G");
}

/// A block's words as `G91 X2 F[500*25.4]` (constants, one binary operation, `#4003`).
fn words_text(s: &Stmt) -> String {
    fn e(x: &Expr) -> String {
        match &x.kind {
            ExprKind::Num(v) => format!("{}", v.value),
            ExprKind::Binary(op, a, b) => {
                let o = match op {
                    BinOp::Mul => "*",
                    BinOp::Div => "/",
                    _ => "?",
                };
                format!("[{}{o}{}]", e(a), e(b))
            }
            _ => "#".into(),
        }
    }
    let StmtKind::Block(b) = &s.kind else { return "structure".into() };
    let mut v: Vec<String> = b.meta.number.iter().map(|n| format!("N{}", n.value)).collect();
    for it in &b.items {
        match &it.kind {
            ItemKind::Word(Word { addr, value: WordValue::Expr(x), .. }) => {
                v.push(format!("{}{}", addr.as_str(), e(x)))
            }
            ItemKind::Assign { .. } => v.push("assign".into()),
            _ => v.push("other".into()),
        }
    }
    v.join(" ")
}

fn ic(letter: u8, v: f64) -> Item {
    item(ItemKind::Word(Word { addr: Addr::Letter(letter), value: WordValue::Ic(n(v)), span: sp() }), sp())
}

fn ac(letter: u8, v: f64) -> Item {
    item(ItemKind::Word(Word { addr: Addr::Letter(letter), value: WordValue::Ac(n(v)), span: sp() }), sp())
}

fn translate(body: Vec<Stmt>, is_sub: bool, ctx: &mut Ctx) -> Vec<String> {
    let mut prog = program(body);
    run(ctx, &mut prog, &ProgInfo { is_sub, ..ProgInfo::default() });
    prog.body.iter().map(words_text).collect()
}

#[test]
fn the_switch_replaces_the_blocks_own_g90_g91() {
    let mut ctx = Ctx::new(0, UnsupportedPolicy::Error);
    let g = |v: f64| word_item(b'G', n(v));
    // `N10 G90 X=IC(2) ; cmt`: only the switch, the N number and comment stay.
    let mut b10 = block(vec![g(90.0), ic(b'X', 2.0)]);
    if let StmtKind::Block(b) = &mut b10.kind {
        b.meta.number = Some(SeqNo { value: 10, span: sp() });
        b.meta.comments.push(Comment { text: "cmt".into(), span: sp() });
    }
    let out = translate(vec![b10], false, &mut ctx);
    assert_eq!(out, ["N10 G91 X2", "G90"]);
    let out = translate(vec![block(vec![g(91.0), ac(b'X', 5.0)])], false, &mut ctx);
    assert_eq!(out, ["G90 X5", "G91"]);
    let out = translate(vec![block(vec![g(90.0), g(1.0), ic(b'X', 2.0), ic(b'Y', 1.0)])], false, &mut ctx);
    assert_eq!(out, ["G91 G1 X2 Y1", "G90"]);
    // No switch: the block's own mode is the word's.
    let out = translate(vec![block(vec![g(91.0), ic(b'X', 2.0)])], false, &mut ctx);
    assert_eq!(out, ["G91 X2"]);
    // Unknown mode (a subprogram): the mode is read from #4003 before and set back after.
    let out = translate(vec![block(vec![ic(b'X', 2.0)])], true, &mut ctx);
    assert_eq!(out, ["assign", "G91 X2", "G#"]);
    // In a subprogram with its own G90 the mode is known.
    let out = translate(vec![block(vec![g(90.0), ic(b'X', 2.0)])], true, &mut ctx);
    assert_eq!(out, ["G91 X2", "G90"]);
    assert!(ctx.diags.is_empty());
}

#[test]
fn feeds_follow_their_own_unit() {
    let mut ctx = Ctx::new(0, UnsupportedPolicy::Error);
    let g = |v: f64| block(vec![word_item(b'G', n(v))]);
    let f = || block(vec![word_item(b'G', n(1.0)), word_item(b'F', n(500.0))]);
    // G700: lengths and feeds inch.
    let out = translate(vec![g(700.0), f()], false, &mut ctx);
    assert_eq!(out, ["G20", "G1 F500"]);
    // G700 then G71: F under G71 is in the basic system (metric), as lengths.
    let out = translate(vec![g(700.0), g(71.0), f()], false, &mut ctx);
    assert_eq!(out, ["G20", "G21", "G1 F500"]);
    // G70 from the start: lengths inch, feeds metric.
    let out = translate(vec![g(70.0), f()], false, &mut ctx);
    assert_eq!(out, ["G20", "G1 F[500/25.4]"]);
    // G700 then G70: F under G70 is mm/min again (828D FM G2, 7.3), not inch/min.
    let out = translate(vec![g(700.0), g(70.0), f()], false, &mut ctx);
    assert_eq!(out, ["G20", "G20", "G1 F[500/25.4]"]);
    // G710 sets both; G71 alone keeps the feeds metric.
    let out = translate(vec![g(70.0), g(710.0), f(), g(71.0), f()], false, &mut ctx);
    assert_eq!(out, ["G20", "G21", "G1 F500", "G21", "G1 F500"]);
    // A dwell's F is seconds.
    let dwell = block(vec![word_item(b'G', n(4.0)), word_item(b'F', n(2.0))]);
    let out = translate(vec![g(70.0), dwell], false, &mut ctx);
    assert_eq!(out[1], "G4 X2");
    assert!(ctx.diags.is_empty());
}

#[test]
fn a_subprogram_feed_after_g70_g71_is_in_the_basic_system() {
    let g = |v: f64| block(vec![word_item(b'G', n(v))]);
    let f = || block(vec![word_item(b'F', n(500.0))]);
    let mut ctx = Ctx::new(0, UnsupportedPolicy::Error);
    // Lengths and feeds in the caller's one unit: F as written.
    assert_eq!(translate(vec![f()], true, &mut ctx), ["F500"]);
    // After any unit word in the subprogram both are known: G70/G71 read F metric, whatever
    // the caller's G700/G710 (so no run-time factor from the caller's unit).
    assert_eq!(translate(vec![g(700.0), g(71.0), f()], true, &mut ctx), ["G20", "G21", "F500"]);
    let out = translate(vec![g(71.0), f(), g(70.0), f()], true, &mut ctx);
    assert_eq!(out, ["G21", "F500", "G20", "F[500/25.4]"]);
    assert!(ctx.diags.is_empty());
}

#[test]
fn a_call_is_declined_while_lengths_and_feeds_differ() {
    let callee = Callee { number: 9001, ..Callee::default() };
    let call = || {
        let c = Call { kind: CallKind::Named, target: CallTarget::Name("SUB".into()), args: vec![], repeat: None };
        block(vec![item(ItemKind::Call(Box::new(c)), sp())])
    };
    let g = |v: f64| block(vec![word_item(b'G', n(v))]);
    let mut ctx = Ctx::new(0, UnsupportedPolicy::Error);
    ctx.callees.insert("SUB".into(), callee);
    translate(vec![g(700.0), call(), g(710.0), call()], false, &mut ctx);
    assert!(ctx.diags.is_empty());
    translate(vec![g(70.0), call()], false, &mut ctx);
    assert_eq!(ctx.diags.len(), 1);
    assert_eq!(ctx.diags[0].code, "NC324");
}

#[test]
fn unknown_g_code_is_unsupported() {
    let mut ctx = Ctx::new(0, UnsupportedPolicy::Warn);
    let body = run_words(vec![word_item(b'G', n(500.0))], &mut ctx);
    assert_eq!(ctx.unsupported, 1);
    assert!(matches!(&body[0].kind, StmtKind::Block(b) if b.meta.comments[0].text.contains("G500")));
}
