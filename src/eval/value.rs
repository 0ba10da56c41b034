//! Run-time values: FANUC `Vacant | Num`, Siemens typed values (numbers, strings), and the
//! conversions the two controls apply on assignment.

use crate::ir::DataType;

/// A value during evaluation. FANUC values are `Vacant` or `Num`; Siemens values are `Num`
/// (INT, REAL, BOOL, CHAR all held as f64 after conversion) or `Str`.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    Vacant,
    Num(f64),
    Str(String),
}

impl Value {
    /// The numeric reading: vacant reads as 0 everywhere except EQ/NE and copying
    /// (`docs/semantics.md`, Vacant values).
    pub fn num(&self) -> Option<f64> {
        match self {
            Value::Vacant => Some(0.0),
            Value::Num(x) => Some(*x),
            Value::Str(_) => None,
        }
    }

    pub fn is_vacant(&self) -> bool {
        matches!(self, Value::Vacant)
    }

    /// Truth of a condition value: non-zero is true (Siemens: `IF R11`).
    pub fn truthy(&self) -> bool {
        match self {
            Value::Vacant => false,
            Value::Num(x) => *x != 0.0,
            Value::Str(s) => !s.is_empty(),
        }
    }
}

/// Half away from zero: the rounding both controls document for ROUND and for integer
/// addresses (`M#1` with 3.5 → M4, source A1 of `docs/semantics.md`). Ties choice in docs/semantics.md.
pub fn round_half_away(x: f64) -> f64 {
    round(x)
}

/// `f64::round` (half away from zero), exactly, without the software `round` call the
/// baseline x86-64 target makes (several per motion block). Below 2^52 the cast truncates
/// exactly and `x - t` is the exact fraction; at or above, `x` is already an integer (or
/// not finite). `copysign` keeps `round`'s sign of zero (`-0.3` → `-0`).
#[inline]
pub fn round(x: f64) -> f64 {
    if x.abs() < 4_503_599_627_370_496.0 {
        let t = (x as i64) as f64;
        let d = x - t;
        let r = if d >= 0.5 {
            t + 1.0
        } else if d <= -0.5 {
            t - 1.0
        } else {
            t
        };
        r.copysign(x)
    } else {
        x
    }
}

/// Rounds `x` to a multiple of `inc` (an address's least increment), ties away from zero.
pub fn round_to(x: f64, inc: f64) -> f64 {
    if inc <= 0.0 {
        return x;
    }
    round_to_scaled(x, inc, 1.0 / inc)
}

/// [`round_to`] with `scale` = `1.0 / inc` (`inc > 0`) worked out by the caller: the same
/// result, one division less for a caller that rounds many values to one increment.
pub fn round_to_scaled(x: f64, inc: f64, scale: f64) -> f64 {
    if is_decimal_scale(scale) {
        return round_to_decimal(x, scale);
    }
    // Pre-round the quotient so that 0.0005/0.001 = 0.49999.. still counts as a tie.
    let q = round((x / inc) * 1e6) / 1e6;
    let r = round(q) * inc;
    // Clean the binary representation (0.1+0.2 style noise) so that printed values and
    // comparisons stay stable.
    let digits = (-inc.log10()).ceil().max(0.0) as i32 + 1;
    let p = 10f64.powi(digits);
    let cleaned = round(r * p) / p;
    if cleaned == 0.0 {
        0.0
    } else {
        cleaned
    }
}

/// Whether [`round_to_scaled`] takes [`round_to_decimal`] for `scale`: an integer up to
/// 10⁹ (`scale.fract() == 0.0` without its `trunc` call: the cast is exact up to 1e9).
#[inline]
pub fn is_decimal_scale(scale: f64) -> bool {
    scale <= 1e9 && (scale as i64) as f64 == scale
}

/// [`round_to_scaled`] for a `scale` of [`is_decimal_scale`] (a decimal increment), which
/// a caller rounding many values to one increment checks once.
#[inline]
pub fn round_to_decimal(x: f64, scale: f64) -> f64 {
    let n = match decimal_count(x, scale) {
        Some(n) => n as f64,
        None => round(round((x * scale) * 1e6) / 1e6),
    };
    // Dividing the integer count by a power of ten gives the double nearest to the
    // decimal value, with no noise to clean.
    let r = n / scale;
    if r == 0.0 {
        0.0
    } else {
        r
    }
}

/// The count of increments [`round_to_decimal`] rounds `x` to (it returns the count
/// divided by `scale`): `None` when it is not worked out in integers (`|x × scale|` of
/// 10⁹ and more), where [`round_to_decimal`] takes floating point.
#[inline]
pub fn decimal_count(x: f64, scale: f64) -> Option<i64> {
    // Pre-round the quotient so that 0.0005/0.001 = 0.49999.. still counts as a tie.
    let raw = (x * scale) * 1e6;
    // (NaN too takes the definition.)
    if raw.abs() >= 2e15 || raw.is_nan() {
        return decimal_count_of(round(raw));
    }
    // `round(raw)` in integers (below 2⁵² the cast truncates exactly, and the
    // difference is exact): the same ties away from zero, without its float round trip.
    let t = raw as i64;
    let d = raw - t as f64;
    let k = t + i64::from(d >= 0.5) - i64::from(d <= -0.5);
    if k.unsigned_abs() < 1_000_000_000_000_000 {
        // `round(k / 1e6)` in integers: below 1e15 the quotient is a tie exactly when
        // k is, and otherwise at least 1e-6 from one, farther than its rounding error
        // (under 1.2e-7), so the division rounds the same way. Saves a division.
        let q = (k.abs() + 500_000) / 1_000_000;
        Some(if k < 0 { -q } else { q })
    } else {
        None
    }
}

/// [`decimal_count`] from `k`, the pre-rounded count of millionths of an increment (the
/// definition, which [`decimal_count`] works out in integers).
fn decimal_count_of(k: f64) -> Option<i64> {
    if k.abs() < 1e15 {
        let ki = k as i64;
        let q = (ki.abs() + 500_000) / 1_000_000;
        Some(if ki < 0 { -q } else { q })
    } else {
        None
    }
}

/// Why a Siemens typed assignment failed.
#[derive(Clone, Debug, PartialEq)]
pub enum ConvError {
    /// A number outside the type's range (INT beyond 32 bits, CHAR beyond 0..255).
    Range(f64),
    /// A string into a number or the reverse.
    Type,
}

/// Converts a value for storage in a Siemens variable of type `ty`.
/// REAL→INT rounds half away from zero (the documented choice, docs/semantics.md);
/// any number → BOOL is "non-zero is TRUE".
pub fn convert_for(ty: DataType, v: Value) -> Result<Value, ConvError> {
    match ty {
        // An axis name (`AXNAME("X")`, `"X"`) is kept as its upper-case name.
        DataType::Axis if matches!(v, Value::Str(_)) => match v {
            Value::Str(s) => Ok(Value::Str(s.trim().to_ascii_uppercase())),
            other => Ok(other),
        },
        DataType::Real | DataType::Axis | DataType::Frame => match v {
            Value::Str(_) => Err(ConvError::Type),
            other => Ok(Value::Num(other.num().unwrap_or(0.0))),
        },
        DataType::Int => {
            let x = v.num().ok_or(ConvError::Type)?;
            let r = round_half_away(x);
            if !(-2147483648.0..=2147483647.0).contains(&r) {
                return Err(ConvError::Range(x));
            }
            Ok(Value::Num(r))
        }
        DataType::Bool => {
            let x = v.num().ok_or(ConvError::Type)?;
            Ok(Value::Num(if x != 0.0 { 1.0 } else { 0.0 }))
        }
        DataType::Char => match v {
            Value::Str(s) => Ok(Value::Num(s.bytes().next().map_or(0.0, f64::from))),
            other => {
                let r = round_half_away(other.num().unwrap_or(0.0));
                if !(0.0..=255.0).contains(&r) {
                    return Err(ConvError::Range(r));
                }
                Ok(Value::Num(r))
            }
        },
        DataType::String(n) => {
            let s = match v {
                Value::Str(s) => s,
                Value::Vacant => String::new(),
                Value::Num(x) => fmt_num(x),
            };
            let max = if n == 0 { 200 } else { n as usize };
            Ok(Value::Str(s.chars().take(max).collect()))
        }
    }
}

/// Formats a number the way the trace does: up to 6 decimals, trailing zeros removed,
/// never `-0`.
pub fn fmt_num(x: f64) -> String {
    if !x.is_finite() {
        return "0".to_string();
    }
    if x.fract() == 0.0 && x.abs() < 1e15 {
        return (x as i64).to_string();
    }
    let mut s = format!("{:.6}", x);
    if s.contains('.') {
        while s.ends_with('0') {
            s.pop();
        }
        if s.ends_with('.') {
            s.pop();
        }
    }
    if s == "-0" {
        s = "0".to_string();
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decimal_count_in_integers_is_its_definition() {
        let mut seed = 0x1234_5678_9abc_def0u64;
        let mut next = move || {
            seed = seed.wrapping_add(0x9e37_79b9_7f4a_7c15);
            let mut z = seed;
            z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
            z ^ (z >> 31)
        };
        let mut xs = vec![0.0, -0.0, 0.0005, -0.0005, 0.0015, 1e6, 999_999.999_5, 1e300, f64::NAN, f64::INFINITY];
        for _ in 0..200_000 {
            let r = next();
            let mag = 10f64.powi((r % 14) as i32 - 6);
            let x = (next() >> 11) as f64 / (1u64 << 53) as f64 * mag;
            // Ties of the thousandth and their neighbours, and any bit pattern.
            let tie = ((next() % 2_000_000) as f64 + 0.5) / 1000.0;
            xs.extend([x, -x, tie, -tie, f64::from_bits(tie.to_bits() + 1), f64::from_bits(tie.to_bits() - 1)]);
            xs.push(f64::from_bits(next()));
            // Exact halves of the pre-rounded count (`raw` = k + 0.5) for each scale.
            let half = (next() % 1_000_000_000_000) as f64 + 0.5;
            for scale in [1e9, 1e10, 1e6] {
                let x = half / scale;
                xs.extend([x, -x, f64::from_bits(x.to_bits() + 1), f64::from_bits(x.to_bits() - 1)]);
            }
        }
        for x in xs {
            for scale in [1000.0, 10_000.0, 1.0] {
                let want = decimal_count_of(round((x * scale) * 1e6));
                assert_eq!(decimal_count(x, scale), want, "x = {x:e}, scale {scale}");
            }
        }
    }

    /// `thousandths` is `decimal_count` of the parsed literal, wherever it answers: every
    /// digit count and place of the point, ties of the thousandth and their neighbours,
    /// and the largest digit strings it takes and the smallest it declines.
    #[test]
    fn thousandths_of_the_digits_are_the_rounded_literal() {
        use crate::dialect::lit::thousandths;
        let mut seed = 0x0bad_cafe_1234_5678u64;
        let mut next = move || {
            seed = seed.wrapping_add(0x9e37_79b9_7f4a_7c15);
            let mut z = seed;
            z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
            z ^ (z >> 31)
        };
        let mut cases: Vec<(u64, usize)> = vec![(0, 0), (5, 4), (49_999, 8), (12_345, 4), (15, 4), (25, 4)];
        for frac in 0..=15usize {
            let top = 10u64.pow((6 + frac).min(15) as u32);
            cases.extend([(top - 1, frac), (top, frac), (top / 2, frac), (top / 2 - 1, frac), (top / 2 + 1, frac)]);
        }
        let mut answered = 0;
        for _ in 0..400_000 {
            let digits = (next() % 16) as u32;
            let frac = (next() % u64::from(digits.min(10) + 1)) as usize;
            let mut mant = next() % 10u64.pow(digits);
            // Often a tie (`..5`) or next to one at the thousandth.
            if frac > 3 && next() % 2 == 0 {
                let unit = 10u64.pow(frac as u32 - 3);
                mant = mant / unit * unit + unit / 2 - 1 + next() % 3;
            }
            cases.push((mant, frac));
        }
        for (mant, frac) in cases {
            let Some(x) = crate::read::exact(mant, frac) else { continue };
            let want = decimal_count(x, 1000.0);
            match thousandths(mant, frac) {
                Some(q) => {
                    answered += 1;
                    assert_eq!(Some(q), want, "mant {mant} frac {frac}");
                    assert_eq!(Some(-q), decimal_count(-x, 1000.0), "mant -{mant} frac {frac}");
                    assert!(q <= 1_000_000_000);
                }
                None => assert!(frac > 9 || mant >= 10u64.pow(6 + frac as u32)),
            }
        }
        assert!(answered > 200_000, "{answered}");
    }

    #[test]
    fn int_conversion_rounds_half_away() {
        assert_eq!(convert_for(DataType::Int, Value::Num(2.5)), Ok(Value::Num(3.0)));
        assert_eq!(convert_for(DataType::Int, Value::Num(-2.5)), Ok(Value::Num(-3.0)));
        assert_eq!(convert_for(DataType::Int, Value::Num(2.4)), Ok(Value::Num(2.0)));
        assert!(convert_for(DataType::Int, Value::Num(3e9)).is_err());
    }

    #[test]
    fn bool_and_char_conversion() {
        assert_eq!(convert_for(DataType::Bool, Value::Num(0.2)), Ok(Value::Num(1.0)));
        assert_eq!(convert_for(DataType::Bool, Value::Num(0.0)), Ok(Value::Num(0.0)));
        assert_eq!(convert_for(DataType::Char, Value::Str("A".into())), Ok(Value::Num(65.0)));
        assert!(convert_for(DataType::Char, Value::Num(300.0)).is_err());
        assert_eq!(convert_for(DataType::String(3), Value::Str("ABCDE".into())), Ok(Value::Str("ABC".into())));
    }

    #[test]
    fn number_format_is_stable() {
        assert_eq!(fmt_num(10.0), "10");
        assert_eq!(fmt_num(-0.0000001), "0");
        assert_eq!(fmt_num(0.1 + 0.2), "0.3");
        assert_eq!(fmt_num(62.831853071), "62.831853");
    }

    #[test]
    fn round_is_f64_round_bit_for_bit() {
        let same = |x: f64| assert_eq!(round(x).to_bits(), x.round().to_bits(), "x = {x:e}");
        for x in [0.0, -0.0, 0.5, -0.5, 1.5, -2.5, 0.49999999999999994, -0.49999999999999994, 4503599627370495.5] {
            same(x);
        }
        for x in [4503599627370496.0, 9e15, 1e300, f64::MAX, f64::MIN_POSITIVE, 5e-324, f64::INFINITY] {
            same(x);
            same(-x);
        }
        assert!(round(f64::NAN).is_nan());
        for i in -100_000..=100_000 {
            // Every half and its neighbours.
            let x = f64::from(i) + 0.5;
            same(x);
            same(f64::from_bits(x.to_bits() + 1));
            same(f64::from_bits(x.to_bits() - 1));
            same(f64::from(i) / 1000.0);
        }
        let mut r = crate::eval::numfmt::tests::Rng(3);
        for _ in 0..2_000_000 {
            let u = r.unit() * 10f64.powi((r.next() % 40) as i32 - 20);
            same(u);
            same(-u);
            let b = f64::from_bits(r.next());
            if !b.is_nan() {
                same(b);
            }
        }
    }

    /// `round_to` as it was written before the integer second stage.
    fn round_to_ref(x: f64, inc: f64) -> f64 {
        let scale = 1.0 / inc;
        if scale.fract() == 0.0 && scale <= 1e9 {
            let q = ((x * scale) * 1e6).round() / 1e6;
            let r = q.round() / scale;
            return if r == 0.0 { 0.0 } else { r };
        }
        round_to(x, inc)
    }

    #[test]
    fn round_to_matches_the_division_form() {
        let same = |x: f64, inc: f64| {
            assert_eq!(round_to(x, inc).to_bits(), round_to_ref(x, inc).to_bits(), "x = {x:e}, inc = {inc}")
        };
        let incs = [0.001, 0.0001, 1.0, 0.01, 0.1, 1e-9];
        for inc in incs {
            for i in -200_000..=200_000 {
                let x = f64::from(i) * inc * 0.5;
                same(x, inc);
                same(f64::from_bits(x.to_bits() + 1), inc);
                same(x * 25.4, inc);
            }
        }
        let mut r = crate::eval::numfmt::tests::Rng(5);
        for _ in 0..1_000_000 {
            let x = (r.unit() - 0.5) * 10f64.powi((r.next() % 30) as i32 - 10);
            for inc in incs {
                same(x, inc);
            }
            let b = f64::from_bits(r.next());
            if !b.is_nan() {
                same(b, 0.001);
            }
        }
    }

    #[test]
    fn rounding_to_increment() {
        assert_eq!(round_to(12.3456, 0.001), 12.346);
        assert_eq!(round_to(-0.0004, 0.001), 0.0);
        assert_eq!(round_to(0.0005, 0.001), 0.001);
    }
}
