//! Unit tests of operators and functions, one per rule of docs/semantics.md.

use super::expr::{eval, Cx, Env};
use super::fault::{AlarmNumbers, Fault};
use super::test_ir::*;
use super::value::Value;
use crate::ir::{BinOp, CmpOp, Func, Tolerance, VarKind, VarRef};
use std::collections::HashMap;

#[derive(Default)]
struct Vars(HashMap<u32, Value>);

impl Env for Vars {
    fn read(&mut self, v: &VarRef, _cx: &Cx) -> Result<Value, Fault> {
        match &v.kind {
            VarKind::Hash(k) | VarKind::R(k) => Ok(self.0.get(k).cloned().unwrap_or(Value::Vacant)),
            _ => Ok(Value::Vacant),
        }
    }
}

fn fanuc() -> Cx {
    Cx {
        file: 0,
        fanuc: true,
        nat: false,
        rel_tol: 0.0,
        alarms: &AlarmNumbers::FANUC,
        in_address: false,
        increment: 0.001,
    }
}
fn siemens() -> Cx {
    Cx { fanuc: false, rel_tol: 1e-12, alarms: &AlarmNumbers::SINUMERIK, ..fanuc() }
}

fn ev(cx: &Cx, e: crate::ir::Expr) -> Result<Value, Fault> {
    let mut v = Vars::default();
    v.0.insert(2, Value::Num(0.0));
    eval(&mut v, &e, cx)
}
fn num(cx: &Cx, e: crate::ir::Expr) -> f64 {
    match ev(cx, e) {
        Ok(Value::Num(x)) => x,
        other => panic!("expected a number, got {other:?}"),
    }
}
fn alarm(cx: &Cx, e: crate::ir::Expr) -> i64 {
    match ev(cx, e) {
        Err(Fault::Alarm { number, .. }) => number,
        other => panic!("expected an alarm, got {other:?}"),
    }
}
fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-9
}

#[test]
fn fanuc_fix_fup_and_siemens_trunc_roundup() {
    let f = fanuc();
    assert_eq!(num(&f, func(Func::FanucFup, vec![p(-1.2)])), -2.0);
    assert_eq!(num(&f, func(Func::FanucFup, vec![p(1.2)])), 2.0);
    assert_eq!(num(&f, func(Func::Trunc, vec![p(-1.2)])), -1.0);
    assert_eq!(num(&f, func(Func::Trunc, vec![p(1.2)])), 1.0);
    let s = siemens();
    assert_eq!(num(&s, func(Func::RoundUp, vec![p(-3.1)])), -3.0);
    assert_eq!(num(&s, func(Func::RoundUp, vec![p(-3.6)])), -3.0);
    assert_eq!(num(&s, func(Func::RoundUp, vec![p(3.1)])), 4.0);
    assert_eq!(num(&s, func(Func::Trunc, vec![p(-3.7)])), -3.0);
}

#[test]
fn round_ties_half_away_from_zero() {
    let s = siemens();
    assert_eq!(num(&s, func(Func::Round, vec![p(2.5)])), 3.0);
    assert_eq!(num(&s, func(Func::Round, vec![p(-2.5)])), -3.0);
    let f = fanuc();
    assert_eq!(num(&f, func(Func::FanucRound, vec![p(-0.5)])), -1.0);
    // In an address, FANUC ROUND rounds to the increment (Haas example).
    let fa = Cx { in_address: true, ..fanuc() };
    let e = bin(BinOp::Add, func(Func::FanucRound, vec![p(1.00333)]), func(Func::FanucRound, vec![p(1.00333)]));
    assert!(close(num(&fa, e), 2.006));
}

#[test]
fn fanuc_nat0_angle_ranges() {
    let f = fanuc();
    assert!(close(num(&f, func(Func::FanucAtan2, vec![p(-1.0), p(-1.0)])), 225.0));
    assert!(close(num(&f, func(Func::FanucAsin, vec![p(-0.5)])), 330.0));
    assert!(close(num(&f, func(Func::FanucAcos, vec![p(-1.0)])), 180.0));
    let f1 = Cx { nat: true, ..fanuc() };
    assert!(close(num(&f1, func(Func::FanucAtan2, vec![p(-1.0), p(-1.0)])), -135.0));
    assert!(close(num(&f1, func(Func::FanucAsin, vec![p(-0.5)])), -30.0));
}

#[test]
fn siemens_angle_ranges() {
    let s = siemens();
    assert!(close(num(&s, func(Func::Atan2, vec![p(-1.0), p(-1.0)])), -135.0));
    assert!(close(num(&s, func(Func::Asin, vec![p(-0.5)])), -30.0));
    assert!(close(num(&s, func(Func::Acos, vec![p(-1.0)])), 180.0));
}

#[test]
fn trig_is_exact_at_quadrants() {
    let s = siemens();
    assert_eq!(num(&s, func(Func::Cos, vec![p(90.0)])), 0.0);
    assert_eq!(num(&s, func(Func::Sin, vec![p(180.0)])), 0.0);
    assert_eq!(num(&s, func(Func::Sin, vec![p(-90.0)])), -1.0);
    assert_eq!(alarm(&fanuc(), func(Func::Tan, vec![p(90.0)])), 112);
}

#[test]
fn mod_and_div_signs() {
    let s = siemens();
    assert!(close(num(&s, bin(BinOp::Mod, p(7.0), p(4.1))), 2.9));
    assert_eq!(num(&s, bin(BinOp::Mod, p(-7.0), p(3.0))), -1.0);
    assert_eq!(num(&s, bin(BinOp::Mod, p(7.0), p(-3.0))), 1.0);
    assert_eq!(num(&s, bin(BinOp::IntDiv, p(7.0), p(0.4))), 17.0);
    assert_eq!(num(&s, bin(BinOp::IntDiv, p(-7.0), p(2.0))), -3.0);
    assert_eq!(num(&fanuc(), bin(BinOp::Mod, p(27.0), p(20.0))), 7.0);
}

#[test]
fn fanuc_bitwise_vs_siemens_logical() {
    let f = fanuc();
    assert_eq!(num(&f, bin(BinOp::FanucBitAnd, p(13.7), p(8.0))), 8.0);
    assert_eq!(num(&f, bin(BinOp::FanucBitOr, p(5.0), p(2.0))), 7.0);
    assert_eq!(num(&f, bin(BinOp::FanucBitXor, p(6.0), p(3.0))), 5.0);
    let s = siemens();
    assert_eq!(num(&s, bin(BinOp::And, p(13.0), p(8.0))), 1.0);
    assert_eq!(num(&s, bin(BinOp::Or, p(0.0), p(0.0))), 0.0);
    assert_eq!(num(&s, bin(BinOp::Xor, p(2.0), p(3.0))), 0.0);
    assert_eq!(num(&s, bin(BinOp::BitAnd, p(12.0), p(10.0))), 8.0);
    assert_eq!(num(&s, bin(BinOp::BitXor, p(12.0), p(10.0))), 6.0);
}

#[test]
fn siemens_relative_equality() {
    let s = siemens();
    let a = bin(BinOp::Add, p(0.1), p(0.2));
    assert_eq!(num(&s, cmp(CmpOp::Eq, Tolerance::Relative, a.clone(), p(0.3))), 1.0);
    // FANUC compares raw values.
    assert_eq!(num(&fanuc(), cmp(CmpOp::Eq, Tolerance::Exact, a, p(0.3))), 0.0);
    assert_eq!(num(&s, cmp(CmpOp::Gt, Tolerance::Relative, p(1.0 + 1e-14), p(1.0))), 0.0);
    assert_eq!(num(&s, cmp(CmpOp::Ge, Tolerance::Relative, p(1.0 - 1e-14), p(1.0))), 1.0);
    assert_eq!(num(&s, cmp(CmpOp::Eq, Tolerance::Relative, p(1.0), p(1.0 + 1e-9))), 0.0);
}

#[test]
fn fanuc_vacant_table() {
    let f = fanuc();
    // #1 is vacant, #2 is 0 (see `ev`).
    let t = |op, a, b| num(&f, cmp(op, Tolerance::Exact, a, b));
    assert_eq!(t(CmpOp::Eq, hash(1), vacant()), 1.0);
    assert_eq!(t(CmpOp::Eq, hash(2), vacant()), 0.0);
    assert_eq!(t(CmpOp::Ne, hash(1), n(0.0)), 1.0);
    assert_eq!(t(CmpOp::Ne, hash(2), n(0.0)), 0.0);
    assert_eq!(t(CmpOp::Ge, hash(1), vacant()), 1.0);
    assert_eq!(t(CmpOp::Ge, hash(2), vacant()), 1.0);
    assert_eq!(t(CmpOp::Gt, hash(1), n(0.0)), 0.0);
    assert_eq!(t(CmpOp::Le, hash(1), vacant()), 1.0);
    assert_eq!(t(CmpOp::Lt, hash(1), n(0.0)), 0.0);
    // Arithmetic reads vacant as 0; copying keeps vacancy.
    assert_eq!(num(&f, bin(BinOp::Mul, hash(1), p(5.0))), 0.0);
    assert_eq!(num(&f, bin(BinOp::Add, hash(1), hash(1))), 0.0);
    assert_eq!(num(&f, bin(BinOp::Add, vacant(), p(1.0))), 1.0);
    assert_eq!(ev(&f, hash(1)), Ok(Value::Vacant));
    assert_eq!(ev(&f, neg(hash(1))), Ok(Value::Vacant));
    assert!(close(num(&f, bin(BinOp::Add, hash(1), p(10.0))), 10.0));
}

#[test]
fn arithmetic_faults_raise_the_controls_alarms() {
    let (f, s) = (fanuc(), siemens());
    assert_eq!(alarm(&f, bin(BinOp::Div, p(1.0), p(0.0))), 112);
    assert_eq!(alarm(&s, bin(BinOp::Div, p(1.0), p(0.0))), 14051);
    assert_eq!(alarm(&f, func(Func::Sqrt, vec![p(-1.0)])), 111);
    assert_eq!(alarm(&f, func(Func::Ln, vec![p(0.0)])), 111);
    assert_eq!(alarm(&f, func(Func::FanucAsin, vec![p(1.5)])), 111);
    assert_eq!(alarm(&s, func(Func::Asin, vec![p(1.5)])), 14051);
    assert_eq!(alarm(&f, bin(BinOp::Mul, p(1e30), p(1e30))), 111);
    assert_eq!(alarm(&s, bin(BinOp::Mul, p(1e300), p(1e300))), 14051);
    assert_eq!(alarm(&s, bin(BinOp::Mod, p(1.0), p(0.0))), 14051);
}

#[test]
fn bcd_conversions_and_siemens_min_max() {
    let f = fanuc();
    assert_eq!(num(&f, func(Func::Bcd, vec![p(1234.0)])), 4660.0);
    assert_eq!(num(&f, func(Func::Bin, vec![p(4660.0)])), 1234.0);
    let s = siemens();
    assert_eq!(num(&s, func(Func::Bound, vec![p(0.0), p(10.0), p(12.0)])), 10.0);
    assert_eq!(num(&s, func(Func::MinVal, vec![p(3.0), p(-1.0)])), -1.0);
    assert_eq!(num(&s, func(Func::Pot, vec![p(-3.0)])), 9.0);
}

#[test]
fn fanuc_one_argument_atan_wraps_with_nat0() {
    assert!(close(num(&fanuc(), func(Func::FanucAtan, vec![p(-1.0)])), 315.0));
    let f1 = Cx { nat: true, ..fanuc() };
    assert!(close(num(&f1, func(Func::FanucAtan, vec![p(-1.0)])), -45.0));
}
