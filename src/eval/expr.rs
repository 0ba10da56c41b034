//! Operators and functions per control, and the expression walker.
//!
//! The IR already says which control's operation a node is (FANUC `FUP` vs Siemens
//! `ROUNDUP`, bitwise FANUC `AND` vs logical `AND`, exact vs relative comparison); this
//! file gives each its exact arithmetic. Variables are read through [`Env`] so that the
//! rules can be tested without a machine.

use super::fault::{AlarmNumbers, Fault};
use super::value::{fmt_num, round_half_away, round_to, Value};
use crate::diag::Diagnostic;
use crate::ir::{BinOp, CmpOp, Expr, ExprKind, Func, Tolerance, UnOp, VarRef};
use crate::span::{FileId, Span};

/// Deepest expression nesting evaluated: a recursion guard. The readers build no tree deeper
/// than [`limits::MAX_EXPR_DEPTH`](crate::dialect::limits::MAX_EXPR_DEPTH); the margin is for
/// the few levels flattening may wrap around one (loop conditions, FOR steps), so NC411 is
/// only ever an IR built by other code.
pub const MAX_EXPR_DEPTH: u32 = 2 * crate::dialect::limits::MAX_EXPR_DEPTH;

/// What an expression needs from its surroundings.
#[derive(Clone, Copy, Debug)]
pub struct Cx {
    pub file: FileId,
    /// FANUC rules (vacant values, overflow at 1e47).
    pub fanuc: bool,
    /// FANUC NAT (6004#0): false gives ATAN 0..360 and ASIN 270..90.
    pub nat: bool,
    /// Relative tolerance of `Tolerance::Relative` comparisons (Siemens 1e-12).
    pub rel_tol: f64,
    pub alarms: &'static AlarmNumbers,
    /// Inside an NC address: FANUC `ROUND` rounds to the address increment there.
    pub in_address: bool,
    /// The address increment in the programmed unit (0.001 mm / 0.0001 inch).
    pub increment: f64,
}

/// Variable access for expressions.
pub trait Env {
    fn read(&mut self, var: &VarRef, cx: &Cx) -> Result<Value, Fault>;
    /// A bare identifier used as a value (a Siemens axis name or label held in a
    /// variable); the default is an error naming it.
    fn ident(&mut self, name: &str, span: Span, cx: &Cx) -> Result<Value, Fault> {
        Err(Fault::error(
            Diagnostic::error("NC412", format!("'{name}' is not a value"))
                .primary(cx.file, span, "used as a number here")
                .hint("declare it with DEF or use an R parameter"),
        ))
    }
    /// The T number tool management gives the tool `name` (`GETT`): the set-up's tool map;
    /// `None` when the run knows no tool map.
    fn tool_number(&self, _name: &str) -> Option<Option<u32>> {
        None
    }
}

/// Evaluates `e`.
pub fn eval<E: Env + ?Sized>(env: &mut E, e: &Expr, cx: &Cx) -> Result<Value, Fault> {
    eval_depth(env, e, cx, 0)
}

/// Evaluates `e` to a number (vacant reads as 0).
pub fn eval_num<E: Env + ?Sized>(env: &mut E, e: &Expr, cx: &Cx) -> Result<f64, Fault> {
    let v = eval(env, e, cx)?;
    num_of(&v, e.span, cx)
}

fn num_of(v: &Value, span: Span, cx: &Cx) -> Result<f64, Fault> {
    v.num().ok_or_else(|| {
        Fault::error(
            Diagnostic::error("NC412", "a string is used where a number is needed")
                .primary(cx.file, span, "this is a string")
                .hint("convert it with NUMBER(...) or use a numeric variable"),
        )
    })
}

fn eval_depth<E: Env + ?Sized>(env: &mut E, e: &Expr, cx: &Cx, depth: u32) -> Result<Value, Fault> {
    if depth > MAX_EXPR_DEPTH {
        return Err(Fault::error(
            Diagnostic::error("NC411", "expression nested too deeply to evaluate")
                .primary(cx.file, e.span, "this expression")
                .hint("split it into several assignments"),
        ));
    }
    let d = depth + 1;
    match &e.kind {
        ExprKind::Num(n) => Ok(Value::Num(n.value)),
        ExprKind::Vacant => Ok(if cx.fanuc { Value::Vacant } else { Value::Num(0.0) }),
        ExprKind::Str(s) => Ok(Value::Str(s.clone())),
        ExprKind::Ident(name) => env.ident(name, e.span, cx),
        ExprKind::Var(v) => env.read(v, cx),
        ExprKind::Unary(op, a) => {
            let va = eval_depth(env, a, cx, d)?;
            // `-#1` with #1 vacant stays vacant, so `X-#1` drops the word like `X#1`.
            if va.is_vacant() && *op == UnOp::Neg {
                return Ok(Value::Vacant);
            }
            let x = num_of(&va, a.span, cx)?;
            Ok(Value::Num(match op {
                UnOp::Neg => -x,
                UnOp::Not => b(x == 0.0),
                UnOp::BitNot => !(to_int(x)) as f64,
            }))
        }
        ExprKind::Binary(op, a, bx) => {
            let va = eval_depth(env, a, cx, d)?;
            // Logical operators do not need the right side when the left decides, but
            // both controls evaluate both; keep it simple and evaluate both.
            let vb = eval_depth(env, bx, cx, d)?;
            if *op == BinOp::Concat {
                return Ok(Value::Str(format!("{}{}", as_text(&va), as_text(&vb))));
            }
            let x = num_of(&va, a.span, cx)?;
            let y = num_of(&vb, bx.span, cx)?;
            binary(*op, x, y, e.span, cx).map(Value::Num)
        }
        ExprKind::Cmp(op, tol, a, bx) => {
            let va = eval_depth(env, a, cx, d)?;
            let vb = eval_depth(env, bx, cx, d)?;
            Ok(Value::Num(b(compare(*op, *tol, &va, &vb, cx))))
        }
        // AXNAME("X"): the axis of that name, held as its upper-case name (like `Ident`).
        ExprKind::Func(Func::AxName, args) if args.len() == 1 => match eval_depth(env, &args[0], cx, d)? {
            Value::Str(s) => Ok(Value::Str(s.trim().to_ascii_uppercase())),
            _ => Err(Fault::error(
                Diagnostic::error("NC432", "AXNAME needs the axis name as a string")
                    .primary(cx.file, args[0].span, "not a string")
                    .hint("write `AXNAME(\"X\")` or pass a STRING variable"),
            )),
        },
        ExprKind::Func(Func::GetT, args) => {
            let name = match args.first().map(|a| eval_depth(env, a, cx, d)).transpose()? {
                Some(Value::Str(s)) => s,
                _ => return super::strings::call(Func::GetT, &[], e.span, cx),
            };
            super::strings::gett(env.tool_number(&name), &name, args.len() > 1, e.span, cx)
        }
        // Refused before their arguments run (GETSELT's first is a whole array).
        ExprKind::Func(f @ (Func::Sprint | Func::IsVar | Func::IsFile | Func::GetSelT), _) => {
            Err(super::strings::refused(*f, e.span, cx))
        }
        ExprKind::Func(f, args) if f.is_string() => {
            let mut vs = Vec::with_capacity(args.len());
            for a in args {
                vs.push(eval_depth(env, a, cx, d)?);
            }
            super::strings::call(*f, &vs, e.span, cx)
        }
        ExprKind::Func(f, args) => {
            let mut xs = [0.0f64; 3];
            if args.len() > 3 {
                return Err(Fault::error(
                    Diagnostic::error("NC412", "too many arguments for a function").primary(cx.file, e.span, "here"),
                ));
            }
            for (i, a) in args.iter().enumerate() {
                let v = eval_depth(env, a, cx, d)?;
                xs[i] = num_of(&v, a.span, cx)?;
            }
            func(*f, &xs[..args.len()], e.span, cx).map(Value::Num)
        }
    }
}

pub(super) fn as_text(v: &Value) -> String {
    match v {
        Value::Str(s) => s.clone(),
        Value::Num(x) => fmt_num(*x),
        Value::Vacant => String::new(),
    }
}

fn b(t: bool) -> f64 {
    if t {
        1.0
    } else {
        0.0
    }
}

/// The integer part used by bit operations (FANUC: "only the integer portion is used").
fn to_int(x: f64) -> i64 {
    x.trunc() as i64
}

/// Checks a result against the control's value range.
pub fn checked(x: f64, span: Span, cx: &Cx) -> Result<f64, Fault> {
    // FANUC 16i-class range is ±1e47 (alarm 111); Siemens REAL is IEEE double.
    let limit = if cx.fanuc { 1e47 } else { f64::MAX };
    if !x.is_finite() || x.abs() > limit {
        return Err(Fault::alarm(cx.alarms.overflow, "calculated data overflow", span));
    }
    Ok(x)
}

/// A binary arithmetic or logical operator.
pub fn binary(op: BinOp, x: f64, y: f64, span: Span, cx: &Cx) -> Result<f64, Fault> {
    let div0 = || Fault::alarm(cx.alarms.div_zero, "division by zero", span);
    let r = match op {
        BinOp::Add => x + y,
        BinOp::Sub => x - y,
        BinOp::Mul => x * y,
        BinOp::Div => {
            if y == 0.0 {
                return Err(div0());
            }
            x / y
        }
        // Truncated: the sign follows the dividend (C fmod); DIV truncates toward zero.
        BinOp::IntDiv => {
            if y == 0.0 {
                return Err(div0());
            }
            (x / y).trunc()
        }
        BinOp::Mod => {
            if y == 0.0 {
                return Err(div0());
            }
            x % y
        }
        BinOp::FanucBitAnd | BinOp::BitAnd => (to_int(x) & to_int(y)) as f64,
        BinOp::FanucBitOr | BinOp::BitOr => (to_int(x) | to_int(y)) as f64,
        BinOp::FanucBitXor | BinOp::BitXor => (to_int(x) ^ to_int(y)) as f64,
        BinOp::And => b(x != 0.0 && y != 0.0),
        BinOp::Or => b(x != 0.0 || y != 0.0),
        BinOp::Xor => b((x != 0.0) != (y != 0.0)),
        BinOp::Concat => 0.0,
    };
    checked(r, span, cx)
}

/// Relative equality (Siemens, MD10280 bit0 = 0): |a−b| ≤ tol·max(|a|,|b|).
pub fn rel_eq(a: f64, b: f64, tol: f64) -> bool {
    a == b || (a - b).abs() <= tol * a.abs().max(b.abs())
}

/// A comparison. FANUC: vacant differs from 0 only in EQ/NE; GE/LE read it as 0 (the
/// Mitsubishi table; the choice docs/semantics.md documents). Strings compare
/// exactly.
pub fn compare(op: CmpOp, tol: Tolerance, a: &Value, bv: &Value, cx: &Cx) -> bool {
    if let (Value::Str(x), Value::Str(y)) = (a, bv) {
        return match op {
            CmpOp::Eq => x == y,
            CmpOp::Ne => x != y,
            CmpOp::Gt => x > y,
            CmpOp::Ge => x >= y,
            CmpOp::Lt => x < y,
            CmpOp::Le => x <= y,
        };
    }
    if matches!(op, CmpOp::Eq | CmpOp::Ne) && (a.is_vacant() || bv.is_vacant()) {
        let same = a.is_vacant() == bv.is_vacant();
        return if op == CmpOp::Eq { same } else { !same };
    }
    let x = a.num().unwrap_or(0.0);
    let y = bv.num().unwrap_or(0.0);
    let eq = match tol {
        Tolerance::Exact => x == y,
        Tolerance::Relative => rel_eq(x, y, cx.rel_tol),
    };
    match op {
        CmpOp::Eq => eq,
        CmpOp::Ne => !eq,
        CmpOp::Gt => x > y && !eq,
        CmpOp::Ge => x > y || eq,
        CmpOp::Lt => x < y && !eq,
        CmpOp::Le => x < y || eq,
    }
}

/// Sine and cosine of an angle in degrees, exact at multiples of 90° so that full
/// circles and `COS[90]` give exact zeros.
pub fn sin_deg(a: f64) -> f64 {
    let r = a.rem_euclid(360.0);
    match r {
        x if x == 0.0 || x == 180.0 => 0.0,
        90.0 => 1.0,
        270.0 => -1.0,
        _ => r.to_radians().sin(),
    }
}

pub fn cos_deg(a: f64) -> f64 {
    sin_deg(a + 90.0)
}

/// A built-in function.
pub fn func(f: Func, xs: &[f64], span: Span, cx: &Cx) -> Result<f64, Fault> {
    let arg = |i: usize| xs.get(i).copied().unwrap_or(0.0);
    let x = arg(0);
    let domain = |what: &str| Fault::alarm(cx.alarms.domain, what.to_string(), span);
    let nat_wrap = |deg: f64| if !cx.nat && deg < 0.0 { deg + 360.0 } else { deg };
    let r = match f {
        // Strings only; reached with a number when the argument count is wrong.
        Func::AxName => return Err(domain("AXNAME needs one string argument")),
        // Evaluated on values (`eval::strings`) before the numbers are taken.
        Func::StrLen
        | Func::ToUpper
        | Func::ToLower
        | Func::Index
        | Func::RIndex
        | Func::Substr
        | Func::Number
        | Func::IsNumber
        | Func::GetT
        | Func::Sprint
        | Func::IsVar
        | Func::IsFile
        | Func::GetSelT => return Err(domain("a string function needs its string arguments")),
        Func::Sin => sin_deg(x),
        Func::Cos => cos_deg(x),
        Func::Tan => {
            // FANUC computes TAN as SIN/COS (source F2 of docs/semantics.md); at 90° that divides by 0.
            let c = cos_deg(x);
            if c == 0.0 {
                return Err(Fault::alarm(cx.alarms.div_zero, "TAN of an odd multiple of 90 degrees", span));
            }
            sin_deg(x) / c
        }
        Func::FanucAsin | Func::Asin => {
            if !(-1.0..=1.0).contains(&x) {
                return Err(domain("ASIN argument outside -1..1"));
            }
            let d = x.asin().to_degrees();
            if f == Func::FanucAsin {
                nat_wrap(d)
            } else {
                d
            }
        }
        Func::FanucAcos | Func::Acos => {
            if !(-1.0..=1.0).contains(&x) {
                return Err(domain("ACOS argument outside -1..1"));
            }
            x.acos().to_degrees()
        }
        Func::FanucAtan2 | Func::Atan2 => {
            let (y, xx) = (arg(0), arg(1));
            if y == 0.0 && xx == 0.0 {
                return Err(domain("ATAN of 0/0"));
            }
            let d = y.atan2(xx).to_degrees();
            if f == Func::FanucAtan2 {
                nat_wrap(d)
            } else {
                d
            }
        }
        Func::FanucAtan => nat_wrap(x.atan().to_degrees()),
        Func::Sqrt => {
            if x < 0.0 {
                return Err(domain("SQRT of a negative number"));
            }
            x.sqrt()
        }
        Func::Abs => x.abs(),
        Func::FanucRound => {
            if cx.in_address {
                round_to(x, cx.increment)
            } else {
                round_half_away(x)
            }
        }
        Func::Round => round_half_away(x),
        Func::Trunc => x.trunc(),
        Func::FanucFup => {
            let t = x.trunc();
            if t == x {
                t
            } else {
                t + x.signum()
            }
        }
        Func::RoundUp => x.ceil(),
        Func::Ln => {
            if x <= 0.0 {
                return Err(domain("LN of a number that is not positive"));
            }
            x.ln()
        }
        Func::Exp => x.exp(),
        Func::Pot => x * x,
        Func::Pow => {
            let r = x.powf(arg(1));
            if r.is_nan() {
                return Err(domain("POW of a negative base with a fractional exponent"));
            }
            r
        }
        Func::MinVal => x.min(arg(1)),
        Func::MaxVal => x.max(arg(1)),
        Func::Bound => {
            let (lo, hi, v) = (arg(0), arg(1), arg(2));
            v.max(lo).min(hi)
        }
        Func::Bin => {
            // BCD → binary: each nibble is a decimal digit.
            let mut n = to_int(x).unsigned_abs();
            let (mut r, mut m) = (0u64, 1u64);
            while n > 0 {
                let digit = n & 0xF;
                if digit > 9 {
                    return Err(domain("BIN of a value that is not BCD"));
                }
                r += digit * m;
                m *= 10;
                n >>= 4;
            }
            r as f64
        }
        Func::Bcd => {
            let mut n = to_int(x).unsigned_abs();
            let (mut r, mut shift) = (0u64, 0u32);
            while n > 0 && shift < 64 {
                r |= (n % 10) << shift;
                n /= 10;
                shift += 4;
            }
            r as f64
        }
        // ADP needs to know whether the argument was written with a decimal point, which
        // the value no longer says.
        Func::Adp => {
            return Err(Fault::error(
                Diagnostic::error("NC403", "ADP[...] is not modelled by the evaluator")
                    .primary(cx.file, span, "ADP here")
                    .hint("pass the argument with a decimal point instead"),
            ))
        }
    };
    checked(r, span, cx)
}
