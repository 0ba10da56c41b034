//! The number writers of the streamed translators: a value as the FANUC emitter writes it
//! (`emit::fmt_num`) and as the shortest decimal that reads back to it, without `format!`
//! (shared by both directions' fast paths; split from `fast.rs` for size).

use crate::dialect::fanuc::emit;

/// 10⁰ to 10¹⁹ (these writers' and the evaluator's number formatter's, `eval::numfmt`).
pub(crate) const POW10: [u64; 20] = {
    let mut t = [1u64; 20];
    let mut i = 1;
    while i < 20 {
        t[i] = t[i - 1] * 10;
        i += 1;
    }
    t
};

/// Digits FANUC accepts in a number (`emit::fmt_num`).
const MAX_DIGITS: usize = 8;

/// Appends `emit::fmt_num(v, point).0` and returns its `.1` (false: more than 8 digits).
pub fn push_num(out: &mut Vec<u8>, v: f64, point: bool) -> bool {
    let v = if v == 0.0 { 0.0 } else { v };
    if push_short(out, v, point, true) {
        return true;
    }
    // More than 8 digits (`m >= 10^8` with a fraction) are rounded by `fmt_num`.
    if let Some((m, d)) = shortest(v.abs()).filter(|&(m, d)| d == 0 || m < POW10[MAX_DIGITS]) {
        push_decimal(out, m, d, v < 0.0, point);
        return true;
    }
    let (s, exact) = emit::fmt_num(v, point);
    out.extend_from_slice(s.as_bytes());
    exact
}

/// Appends what `shortest` and `push_decimal` write for `|v| < 10^7` (the usual CAM
/// coordinate) and returns true; returns false, writing nothing, for the rest, and with
/// `max8` also for more than 8 significant digits with a fraction (`push_num`'s limit).
///
/// The same digits as `shortest` without its searches: `m` is `|v|` at 8 places, and
/// `m / 10^8 == |v|` is the same test as `shortest`'s `m' / 10^d == |v|` after taking off
/// the trailing zeros (the same rational number, both divisions correctly rounded). The
/// 8 fraction digits are made at once in the bytes of one `u64` (first digit in the low
/// byte), so the trailing zeros are its high zero bytes.
#[inline]
pub fn push_short(out: &mut Vec<u8>, v: f64, point: bool, max8: bool) -> bool {
    let a = v.abs();
    if a.is_nan() || a >= 1e7 {
        return false;
    }
    let m = (a * 1e8 + 0.5) as u64;
    if m as f64 / 1e8 != a {
        return false;
    }
    let (int, frac) = (m / 100_000_000, m % 100_000_000);
    // Two 4-digit lanes of 32 bits, then 2-digit lanes of 16, then digits in bytes; each
    // multiply-shift is an exact division for its range (x < 10^4 by 100, x < 100 by 10).
    let x = (frac / 10_000) | ((frac % 10_000) << 32);
    let q = ((x * 5243) >> 19) & 0x0000_007f_0000_007f;
    let y = q | ((x - q * 100) << 16);
    let q = ((y * 103) >> 10) & 0x000f_000f_000f_000f;
    let digits = q | ((y - q * 10) << 8);
    let places = 8 - digits.leading_zeros() as usize / 8;
    // The digits without trailing zeros are `m / 10^(8 - places)`: at least 10^8 of them
    // is more than 8 digits.
    if max8 && places > 0 && m >= POW10[16 - places] {
        return false;
    }
    // Sign, up to 7 integer digits, point, 8 fraction digits.
    let mut buf = [0u8; 24];
    buf[8] = b'.';
    buf[9..17].copy_from_slice(&(digits | 0x3030_3030_3030_3030).to_le_bytes());
    let mut k = 8;
    let mut n = int as usize;
    while n >= 100 {
        let r = (n % 100) * 2;
        n /= 100;
        k -= 2;
        buf[k..k + 2].copy_from_slice(&PAIRS[r..r + 2]);
    }
    if n >= 10 {
        k -= 2;
        buf[k..k + 2].copy_from_slice(&PAIRS[n * 2..n * 2 + 2]);
    } else {
        k -= 1;
        buf[k] = b'0' + n as u8;
    }
    if v < 0.0 {
        k -= 1;
        buf[k] = b'-';
    }
    let end = if places > 0 { 9 + places } else { 8 + usize::from(point) };
    out.extend_from_slice(&buf[k..end]);
    true
}

/// Two-digit groups `00`..`99`: a number is written two digits per division.
const PAIRS: [u8; 200] = {
    let mut t = [0u8; 200];
    let mut i = 0;
    while i < 100 {
        t[2 * i] = b'0' + (i / 10) as u8;
        t[2 * i + 1] = b'0' + (i % 10) as u8;
        i += 1;
    }
    t
};

/// Appends `m / 10^d` in decimal: `-` when `neg`, the integer part, then the point and
/// the `d` fraction digits (the point also without them when `point`). `m < 10^20`.
pub fn push_decimal(out: &mut Vec<u8>, mut m: u64, d: usize, neg: bool, point: bool) {
    // Written backwards: the fraction's digits, the point, the integer part.
    let mut buf = [0u8; 48];
    let mut k = buf.len();
    let mut left = d;
    if left % 2 == 1 {
        k -= 1;
        buf[k] = b'0' + (m % 10) as u8;
        m /= 10;
        left -= 1;
    }
    while left > 0 {
        let r = (m % 100) as usize * 2;
        m /= 100;
        k -= 2;
        buf[k..k + 2].copy_from_slice(&PAIRS[r..r + 2]);
        left -= 2;
    }
    if d > 0 || point {
        k -= 1;
        buf[k] = b'.';
    }
    while m >= 100 {
        let r = (m % 100) as usize * 2;
        m /= 100;
        k -= 2;
        buf[k..k + 2].copy_from_slice(&PAIRS[r..r + 2]);
    }
    if m >= 10 {
        let r = m as usize * 2;
        k -= 2;
        buf[k..k + 2].copy_from_slice(&PAIRS[r..r + 2]);
    } else {
        k -= 1;
        buf[k] = b'0' + m as u8;
    }
    if neg {
        k -= 1;
        buf[k] = b'-';
    }
    out.extend_from_slice(&buf[k..]);
}

/// The shortest decimal of `a >= 0` as `fmt_num` gets it from Rust's `{}` (the shortest
/// digits that parse back to `a`): `a = m / 10^d` with `d <= 8` decimal places; `None`
/// leaves it to `fmt_num`.
///
/// A candidate `(m, d)` is checked by `m / 10^d == a`: both are exact doubles (`m < 10^15`)
/// and the division is correctly rounded, as parsing the decimal is, so this is exactly the
/// round-trip test. Two different decimals of at most 15 significant digits never round to
/// the same double, so when `m` does not end in 0 no decimal with fewer places round-trips
/// (it would give a second one with `d` places), and `{}` writes exactly these digits.
pub fn shortest(a: f64) -> Option<(u64, usize)> {
    if a < 1e7 {
        // The usual case, one try: the digits at 8 places without their trailing zeros.
        let (mut m, mut d) = ((a * 1e8 + 0.5) as u64, MAX_DIGITS);
        // The trailing zeros (at most 8) taken off by halves: 8, else 4, 2, 1.
        if m.is_multiple_of(100_000_000) {
            m /= 100_000_000;
            d = 0;
        } else {
            for (k, p) in [(4, 10_000), (2, 100), (1, 10)] {
                if m.is_multiple_of(p) {
                    m /= p;
                    d -= k;
                }
            }
        }
        return (m as f64 / POW10[d] as f64 == a).then_some((m, d));
    }
    for (d, &pow) in POW10.iter().enumerate().take(MAX_DIGITS + 1) {
        let x = a * pow as f64;
        if x.is_nan() || x >= 1e15 {
            break;
        }
        let m = (x + 0.5) as u64;
        if m as f64 / pow as f64 == a {
            return (d == 0 || !m.is_multiple_of(10)).then_some((m, d));
        }
    }
    None
}

/// Appends a block skip as both dialects write it: `/`, or `/k` for skip level k.
pub fn push_skip(out: &mut Vec<u8>, skip: Option<u8>) {
    match skip {
        Some(0) => out.push(b'/'),
        Some(k) => {
            out.push(b'/');
            push_u64(out, u64::from(k));
        }
        None => {}
    }
}

/// Appends `n` in decimal (block numbers, integer parts).
pub fn push_u64(out: &mut Vec<u8>, mut n: u64) {
    let mut buf = [0u8; 20];
    let mut k = buf.len();
    loop {
        k -= 1;
        buf[k] = b'0' + (n % 10) as u8;
        n /= 10;
        if n == 0 {
            break;
        }
    }
    out.extend_from_slice(&buf[k..]);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fast(v: f64, point: bool) -> (String, bool) {
        let mut out = Vec::new();
        let exact = push_num(&mut out, v, point);
        (String::from_utf8(out).unwrap_or_default(), exact)
    }

    use crate::test_rng::Rng;

    #[test]
    fn numbers_are_written_as_fmt_num_writes_them() {
        let mut values: Vec<f64> = vec![
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.5,
            10.0,
            0.1,
            0.2,
            0.3,
            1e-7,
            1e-8,
            1e-9,
            0.000001,
            0.00000001,
            12345678.0,
            1234567.8,
            123456789.0,
            12345678.9,
            99999999.0,
            99999999.5,
            0.99999999,
            0.999999999,
            57.295779513,
            1e14,
            1e15,
            1e16,
            1e20,
            2f64.powi(53),
            1.0 / 3.0,
            2.0 / 3.0,
            25.4,
            800.0 / 25.4,
            1e-300,
            5e-324,
            f64::MAX,
            0.1 + 0.2,
            1.005,
            2.675,
            9.995,
            0.045,
            1234.5678,
            -1234.5678,
        ];
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        for _ in 0..200_000 {
            // Decimals as CAM programs write them: up to 8 integer and 8 fraction digits.
            let int = rng.next() % POW10[(rng.next() % 9) as usize];
            let dec = (rng.next() % 9) as i32;
            let frac = rng.next() % POW10[dec as usize];
            let text = format!("{int}.{frac:0w$}", w = dec as usize);
            let v: f64 = text.parse().unwrap_or(0.0);
            values.push(if rng.next().is_multiple_of(2) { v } else { -v });
            // Any double: computed values, huge and tiny ones.
            values.push(f64::from_bits(rng.next()));
            values.push((rng.next() % 1_000_000) as f64 / 7.0);
        }
        for v in values {
            for point in [true, false] {
                assert_eq!(fast(v, point), emit::fmt_num(v, point), "{v:e} point {point}");
            }
        }
    }

    /// `push_short` against the definition it replaces: `shortest` then `push_decimal`,
    /// with and without `push_num`'s 8-digit limit, where it writes anything.
    #[test]
    fn push_short_writes_what_shortest_and_push_decimal_write() {
        let mut values: Vec<f64> = vec![
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.5,
            9_999_999.0,
            9_999_999.5,
            9_999_999.999_999_99,
            10_000_000.0,
            1e7 - 1e-9,
            12_345_678.0,
            1_234_567.8,
            1_234_567.812_345_67,
            0.123_456_789,
            0.999_999_99,
            0.999_999_999,
            0.000_000_01,
            0.000_000_005,
            1e-9,
            5e-324,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            0.1 + 0.2,
            2.675,
            1.0 / 3.0,
        ];
        let mut rng = Rng(0x2545_f491_4f6c_dd1d);
        for _ in 0..100_000 {
            let int = rng.next() % POW10[(rng.next() % 9) as usize];
            let dec = (rng.next() % 10) as usize;
            let frac = rng.next() % POW10[dec];
            let v: f64 = format!("{int}.{frac:0dec$}").parse().unwrap_or(0.0);
            values.push(if rng.next().is_multiple_of(2) { v } else { -v });
            values.push(int as f64);
            values.push(f64::from_bits(rng.next()));
            values.push((rng.next() % 10_000_000_000) as f64 / 7.0);
            values.push((rng.next() % 1_000_000_000_000_000) as f64 * 1e-8);
        }
        let mut written = 0;
        for v in values {
            for (point, max8) in [(false, false), (false, true), (true, false), (true, true)] {
                let old = shortest(v.abs()).filter(|&(m, d)| !max8 || d == 0 || m < POW10[MAX_DIGITS]).map(|(m, d)| {
                    let mut out = Vec::new();
                    push_decimal(&mut out, m, d, v < 0.0, point);
                    out
                });
                let mut new = Vec::new();
                if push_short(&mut new, v, point, max8) {
                    written += 1;
                    assert_eq!(Some(new), old, "{v:e} point {point} max8 {max8}");
                } else {
                    assert!(new.is_empty(), "{v:e}");
                    // Declined only where the old definition declines too or `|v| >= 10^7`.
                    assert!(old.is_none() || v.abs() >= 1e7, "{v:e} point {point} max8 {max8}");
                }
            }
        }
        assert!(written > 500_000, "{written}");
    }
}
