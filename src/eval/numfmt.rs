//! The trace's number form (integers plain, else rounded to 6 decimals with trailing zeros
//! trimmed, `-0` as `0`), written without `core::fmt`: formatting every coordinate of a
//! long trace through `{:.6}` cost a fifth of a `run`. [`push_num_std`] is the definition;
//! [`push_num`] gives the same bytes, exactly, and falls back to it where it cannot.

/// Appends `x` in the trace's number form. Byte-identical to [`push_num_std`].
pub fn push_num(out: &mut String, x: f64) {
    let mut buf = [0u8; BUF];
    match fast(x, &mut buf) {
        Some(n) => out.push_str(std::str::from_utf8(&buf[..n]).unwrap_or("0")),
        None => push_num_std(out, x),
    }
}

/// [`push_num`] into a byte buffer (the trace writers' form).
#[inline]
pub fn put_num(out: &mut Vec<u8>, x: f64) {
    // The 0.001 grid below 10⁶ (nearly every coordinate and feed of a metric trace):
    // written as [`fast`] writes it ([`millis_digits`]), in one short buffer.
    if let Some(n) = millis(x) {
        if n.unsigned_abs() < 1_000_000_000 {
            put_small_millis(out, n);
            return;
        }
    }
    put_num_any(out, x);
}

/// [`millis_digits`] of `n` with `|n| < 10⁹` (at most a sign, 6 integer digits and
/// `.ddd`: 11 bytes), appended through a 16-byte buffer copied whole.
fn put_small_millis(out: &mut Vec<u8>, n: i64) {
    let mut buf = [0u8; 16];
    let len = small_millis(&mut buf, 0, n);
    let at = out.len();
    out.extend_from_slice(&buf);
    out.truncate(at + len);
}

/// Where [`put_num`] writes `x` from an integer: the `n` with `|n| < 10⁹` whose
/// [`put_grid`] writes what [`put_num`] writes for `x` (the 0.001 grid below 10⁶).
#[inline]
pub fn grid_of(x: f64) -> Option<i64> {
    millis(x).filter(|n| n.unsigned_abs() < GRID_LIMIT)
}

/// The bound of [`grid_of`]: `|n| < 10⁹` (values below 10⁶).
pub const GRID_LIMIT: u64 = 1_000_000_000;

/// Writes `n / 1000` (`|n| <` [`GRID_LIMIT`], as [`grid_of`] gives) at `out[at..]`, as
/// [`put_num`] writes the value, straight into `out` (a fixed-size window, so that the
/// compiler can see the writes inside it when `at` is bounded): bytes up to `at + 11`
/// are written (`out` must have room for them); returns where the number ends.
#[inline(always)]
pub fn put_grid<const N: usize>(out: &mut [u8; N], at: usize, n: i64) -> usize {
    small_millis(out, at, n)
}

/// Writes `n / 1000` (`|n| < 10⁹`) at `buf[at..]`, as [`millis_digits`] does; returns
/// where it ends. Every part is a 4-byte copy from a table ([`DIGITS3`], [`FRACTIONS`])
/// advanced by its length: no digit loop and few branches (this writes every coordinate
/// of a text trace).
#[inline(always)]
fn small_millis<const N: usize>(buf: &mut [u8; N], at: usize, n: i64) -> usize {
    debug_assert!(n.unsigned_abs() < GRID_LIMIT);
    buf[at] = b'-';
    let i = at + usize::from(n < 0);
    // Below 10⁹: 32-bit divisions.
    let a = n.unsigned_abs() as u32;
    let (int, frac) = (a / 1000, a % 1000);
    let i = if int >= 1000 {
        let i = put_upto3(buf, i, (int / 1000) % 1000);
        buf[i..i + 4].copy_from_slice(&PADDED3[(int % 1000) as usize].to_le_bytes());
        i + 3
    } else {
        put_upto3(buf, i, int)
    };
    // A zero fraction has length 0: its bytes are written but not counted.
    let (text, l) = FRACTIONS[frac as usize % 1000];
    buf[i..i + 4].copy_from_slice(&text);
    i + usize::from(l)
}

/// Writes the decimal digits of `n` at `out[at..]` (room for 20 bytes needed); returns
/// where they end (as [`put_int`] writes a non-negative number).
#[inline]
pub fn put_uint_at(out: &mut [u8], at: usize, n: u64) -> usize {
    let mut buf = [0u8; BUF];
    let len = put_digits(&mut buf, 0, n);
    out[at..at + 20].copy_from_slice(&buf[..20]);
    at + len
}

/// Writes `n < 1000` without leading zeros at `buf[at..]` (4 bytes written); returns
/// where it ends.
#[inline(always)]
fn put_upto3<const N: usize>(buf: &mut [u8; N], at: usize, n: u32) -> usize {
    let d = DIGITS3[n as usize % 1000];
    buf[at..at + 4].copy_from_slice(&d.to_le_bytes());
    at + (d >> 24) as usize
}

/// For every `n < 1000`: its digits without leading zeros in the low bytes (first digit
/// lowest, as they lie in memory little-endian) and in the top byte their count (`0` has
/// one digit). Written as 4 bytes, the top byte lies past the digits, where the next
/// part of the text goes.
static DIGITS3: [u32; 1000] = digits3(false);

/// [`DIGITS3`] with leading zeros: always three digits (`7` → `007`).
static PADDED3: [u32; 1000] = digits3(true);

const fn digits3(padded: bool) -> [u32; 1000] {
    let mut t = [0u32; 1000];
    let mut n = 0;
    while n < 1000 {
        let len = if padded || n >= 100 {
            3
        } else if n >= 10 {
            2
        } else {
            1
        };
        let mut v = 0u32;
        let mut k = 0;
        while k < len {
            // Digit k (from the first) of the `len` digits of `n`.
            let mut d = n as u32;
            let mut j = len - 1 - k;
            while j > 0 {
                d /= 10;
                j -= 1;
            }
            v |= (b'0' as u32 + d % 10) << (8 * k);
            k += 1;
        }
        t[n] = v | ((len as u32) << 24);
        n += 1;
    }
    t
}

/// [`put_num`] of any value.
fn put_num_any(out: &mut Vec<u8>, x: f64) {
    let mut buf = [0u8; BUF];
    match fast(x, &mut buf) {
        Some(n) => put_head(out, &buf, n),
        None => {
            let mut s = String::new();
            push_num_std(&mut s, x);
            out.extend_from_slice(s.as_bytes());
        }
    }
}

/// Appends an integer in decimal.
pub fn put_int(out: &mut Vec<u8>, n: i64) {
    let mut buf = [0u8; BUF];
    let len = int_digits(&mut buf, n);
    put_head(out, &buf, len);
}

/// Appends `buf[..n]`: the whole buffer is copied (a fixed size the compiler copies
/// inline, where a short copy of a varying length is a `memcpy` call) and the rest cut.
fn put_head(out: &mut Vec<u8>, buf: &[u8; BUF], n: usize) {
    let at = out.len();
    out.extend_from_slice(buf);
    out.truncate(at + n);
}

/// Room for a sign, 20 digits, a point and 6 decimals.
const BUF: usize = 32;

/// Writes the form of `x` at the start of `buf` (ASCII only) and returns its length;
/// `None` where the standard formatter must decide (an exact tie, `|x| ≥ 10¹²`).
fn fast(x: f64, buf: &mut [u8; BUF]) -> Option<usize> {
    // First the 0.001 grid (integers below 10⁹ included: they print the same either way).
    if let Some(n) = millis(x) {
        return Some(millis_digits(buf, n));
    }
    // An integer (what `x.fract() == 0.0` asks, without its `trunc` call): below 1e15
    // the cast truncates exactly.
    if x.abs() < 1e15 && (x as i64) as f64 == x {
        return Some(int_digits(buf, x as i64));
    }
    if !x.is_finite() {
        buf[0] = b'0';
        return Some(1);
    }
    let q = micros(x)?;
    Some(micros_digits(buf, x < 0.0, q))
}

/// The definition of the form through the standard formatter (the slow, general path).
pub fn push_num_std(out: &mut String, x: f64) {
    use std::fmt::Write;
    if x.is_finite() && x.fract() == 0.0 && x.abs() < 1e15 {
        let _ = write!(out, "{}", x as i64);
        return;
    }
    if !x.is_finite() {
        out.push('0');
        return;
    }
    let start = out.len();
    let _ = write!(out, "{x:.6}");
    while out.ends_with('0') {
        out.pop();
    }
    if out.ends_with('.') {
        out.pop();
    }
    if &out[start..] == "-0" {
        out.truncate(start);
        out.push('0');
    }
}

/// `|x| × 10⁶` rounded to the nearest integer, computed exactly from the binary value (the
/// standard formatter rounds the exact value too). `None` where this does not decide the
/// digits: an exact tie (the standard formatter's tie rule then applies), or `|x| ≥ 10¹²`.
fn micros(x: f64) -> Option<u64> {
    let a = x.abs();
    if a >= 1e12 {
        return None;
    }
    // Below 5e-7 every value rounds to 0 (and 5e-7 itself is not a binary fraction).
    if a < 1e-7 {
        return Some(0);
    }
    let bits = a.to_bits();
    let exp = ((bits >> 52) & 0x7ff) as i32;
    // a = m / 2^k exactly, with m < 2^53.
    let m = (bits & ((1u64 << 52) - 1)) | (1u64 << 52);
    let k = 1075 - exp;
    // k ≤ 0 would be an integer (handled by the caller); a ≥ 1e-7 keeps k ≤ 76.
    if !(1..=100).contains(&k) {
        return None;
    }
    // m × 10⁶ < 2^73: exact in u128; the quotient is below 10¹⁸ (a < 10¹²).
    let p = u128::from(m) * 1_000_000;
    let q = p >> k;
    let rem = p - (q << k);
    let half = 1u128 << (k - 1);
    let q = u64::try_from(q).ok()?;
    match rem.cmp(&half) {
        std::cmp::Ordering::Less => Some(q),
        std::cmp::Ordering::Greater => Some(q + 1),
        std::cmp::Ordering::Equal => None,
    }
}

/// `n` when `x` is the double nearest to the decimal `n / 1000` (a position on the
/// 0.001 mm grid, nearly every coordinate of a metric trace), `|x| < 10⁹`.
///
/// Then `x` prints as that decimal: `|x − n/1000|` is at most half an ulp of `x`, under
/// 2⁻²⁴ < 6·10⁻⁸ for `|x| < 2³⁰`, while `n/1000` is itself a multiple of 10⁻⁶ and every
/// other multiple is at least 10⁻⁶ − 6·10⁻⁸ from `x`: rounding the exact value of `x` to
/// six decimals (what the standard formatter does) gives `n/1000`, never a tie. The test
/// is `fl(n / 1000) == x` with an exact `n` (|n| < 10¹², the division correctly
/// rounded), so any candidate `n` that passes it is right. An integer `x` (|x| < 10⁹)
/// passes with `n = 1000x` and prints as the integer; `-0` passes with `n = 0`: `0`.
#[inline]
fn millis(x: f64) -> Option<i64> {
    let t = x * 1000.0;
    if t.abs() >= 1e12 || t.is_nan() {
        return None;
    }
    // On the grid `t` is within far less than 0.5 of `n`: half away from zero, truncated.
    let n = (t + 0.5f64.copysign(t)) as i64;
    (n as f64 / 1000.0 == x).then_some(n)
}

/// Writes `n / 1000` with the fraction's trailing zeros trimmed (`n` not a multiple of
/// 1000 gives a point, `0` no sign); returns the length.
fn millis_digits(buf: &mut [u8; BUF], n: i64) -> usize {
    let mut i = 0;
    if n < 0 {
        buf[0] = b'-';
        i = 1;
    }
    let a = n.unsigned_abs();
    let (int, frac) = (a / 1000, (a % 1000) as u32);
    i = put_digits(buf, i, int);
    if frac == 0 {
        return i;
    }
    // `.ddd` with its trailing zeros cut, from a table: one copy, no digit loop.
    let (text, len) = FRACTIONS[frac as usize % 1000];
    buf[i..i + 4].copy_from_slice(&text);
    i + usize::from(len)
}

/// For every fraction `0..1000` (thousandths): `.ddd` and its length once the trailing
/// zeros are cut (`5` → `.005`, 4; `500` → `.5`, 2; `0` → nothing, 0).
static FRACTIONS: [([u8; 4], u8); 1000] = fractions();

const fn fractions() -> [([u8; 4], u8); 1000] {
    let mut t = [([0u8; 4], 0u8); 1000];
    let mut f = 0;
    while f < 1000 {
        let d = [(f / 100) as u8, (f / 10 % 10) as u8, (f % 10) as u8];
        let mut len = 4;
        while len > 1 && d[len - 2] == 0 {
            len -= 1;
        }
        t[f] = ([b'.', b'0' + d[0], b'0' + d[1], b'0' + d[2]], len as u8);
        f += 1;
    }
    t[0].1 = 0;
    t
}

/// Writes `q / 10⁶` with the fraction's trailing zeros trimmed, `0` without a sign;
/// returns the length.
fn micros_digits(buf: &mut [u8; BUF], neg: bool, q: u64) -> usize {
    if q == 0 {
        buf[0] = b'0';
        return 1;
    }
    let mut i = 0;
    if neg {
        buf[0] = b'-';
        i = 1;
    }
    let (int, frac) = (q / 1_000_000, (q % 1_000_000) as u32);
    i = put_digits(buf, i, int);
    if frac == 0 {
        return i;
    }
    // The point and six digits, then the trailing zeros dropped (there is a non-zero one).
    buf[i] = b'.';
    let (hi, lo) = (frac / 10_000, frac % 10_000);
    buf[i + 1..i + 3].copy_from_slice(pair(hi));
    buf[i + 3..i + 5].copy_from_slice(pair(lo / 100));
    buf[i + 5..i + 7].copy_from_slice(pair(lo % 100));
    let mut end = i + 7;
    while buf[end - 1] == b'0' {
        end -= 1;
    }
    end
}

/// Writes `n` in decimal at the start of `buf`; returns the length.
fn int_digits(buf: &mut [u8; BUF], n: i64) -> usize {
    if n < 0 {
        buf[0] = b'-';
        put_digits(buf, 1, n.unsigned_abs())
    } else {
        put_digits(buf, 0, n.unsigned_abs())
    }
}

/// "00" to "99".
const PAIRS: &[u8; 200] = b"\
0001020304050607080910111213141516171819\
2021222324252627282930313233343536373839\
4041424344454647484950515253545556575859\
6061626364656667686970717273747576777879\
8081828384858687888990919293949596979899";

/// The two digits of `n` < 100.
#[inline(always)]
fn pair(n: u32) -> &'static [u8] {
    let i = (n as usize % 100) * 2;
    &PAIRS[i..i + 2]
}

/// Writes the digits of `n` from `buf[at]` on, two at a time from the last; returns
/// where they end. [`BUF`] leaves room for the 20 digits of any u64 after a sign.
fn put_digits(buf: &mut [u8; BUF], at: usize, mut n: u64) -> usize {
    // Most numbers of a trace are small: no digit count, no loop.
    if n < 10 {
        buf[at] = b'0' + n as u8;
        return at + 1;
    }
    if n < 100 {
        buf[at..at + 2].copy_from_slice(pair(n as u32));
        return at + 2;
    }
    if n < 1000 {
        buf[at] = b'0' + (n / 100) as u8;
        buf[at + 1..at + 3].copy_from_slice(pair((n % 100) as u32));
        return at + 3;
    }
    // The digit count from the bit length: `bits × log10(2)` (1233 / 4096) is the count
    // or one more than it, which one comparison settles.
    let bits = 64 - (n | 1).leading_zeros() as usize;
    let guess = (bits * 1233) >> 12;
    let digits = guess + 1 - usize::from(n < crate::dialect::numwrite::POW10[guess]);
    let end = at + digits;
    let mut i = end;
    while n >= 100 {
        i -= 2;
        buf[i..i + 2].copy_from_slice(pair((n % 100) as u32));
        n /= 100;
    }
    if n >= 10 {
        i -= 2;
        buf[i..i + 2].copy_from_slice(pair(n as u32));
    } else {
        i -= 1;
        buf[i] = b'0' + n as u8;
    }
    end
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// Asserts the fast and the standard path agree on `x`.
    pub fn same(x: f64, a: &mut String, b: &mut String) {
        a.clear();
        b.clear();
        push_num(a, x);
        push_num_std(b, x);
        assert_eq!(a, b, "x = {x:e} (bits {:#x})", x.to_bits());
        let mut v = Vec::new();
        put_num(&mut v, x);
        assert_eq!(v, b.as_bytes(), "x = {x:e} (bits {:#x})", x.to_bits());
    }

    /// A small deterministic generator (SplitMix64).
    pub struct Rng(pub u64);
    impl Rng {
        pub fn next(&mut self) -> u64 {
            self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
            let mut z = self.0;
            z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
            z ^ (z >> 31)
        }
        pub fn unit(&mut self) -> f64 {
            (self.next() >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// `n` values of each kind the evaluator produces, and the edges of the fast path.
    pub fn check_many(n: usize, seed: u64) {
        let (mut a, mut b) = (String::new(), String::new());
        let mut r = Rng(seed);
        for _ in 0..n {
            let u = r.unit();
            let sign = if r.next() & 1 == 0 { 1.0 } else { -1.0 };
            let mag = 10f64.powi((r.next() % 17) as i32 - 9);
            // Random magnitudes, 1e-9 .. 1e8.
            same(sign * u * mag, &mut a, &mut b);
            // Positions as the machine rounds them (0.001 mm, 0.0001 inch, then × 25.4).
            let mm = (sign * u * 2000.0 * 1000.0).round() / 1000.0;
            same(mm, &mut a, &mut b);
            let inch = (sign * u * 100.0 * 10000.0).round() / 10000.0;
            same(inch * 25.4, &mut a, &mut b);
            // The trace's `clean` (rounded to 1e-9), and sums as incremental moves make.
            same((sign * u * 5000.0 * 1e9).round() / 1e9, &mut a, &mut b);
            same(mm + inch * 0.1 + 0.1 + 0.2, &mut a, &mut b);
            // Near ties of the 6th decimal: k + 0.5 millionths, and the floats around it.
            let t = (sign * ((r.next() % 2_000_000_000) as f64 + 0.5)) / 1e6;
            same(t, &mut a, &mut b);
            same(f64::from_bits(t.to_bits() + 1), &mut a, &mut b);
            same(f64::from_bits(t.to_bits() - 1), &mut a, &mut b);
            // Any bit pattern at all (NaN, infinities, subnormals, huge).
            same(f64::from_bits(r.next()), &mut a, &mut b);
        }
    }

    #[test]
    fn edges() {
        let (mut a, mut b) = (String::new(), String::new());
        let xs = [
            0.0,
            -0.0,
            0.5,
            -0.5,
            1e-7,
            -1e-7,
            4.999999e-7,
            5e-7,
            -5e-7,
            5.000001e-7,
            0.0000015,
            0.0078125,
            -0.0078125,
            1.0000005,
            0.1 + 0.2,
            62.831853071,
            999_999.999_999_5,
            1e12 - 0.5,
            1e12 + 0.5,
            1e15 - 0.5,
            1e15,
            -1e15,
            1e300,
            f64::MIN_POSITIVE,
            5e-324,
            f64::MAX,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        for x in xs {
            same(x, &mut a, &mut b);
        }
        let mut ints = vec![0, 1, -1, 9, 10, 99, 100, -100, 12_345, i64::MAX, i64::MIN, i64::MIN + 1, 10i64.pow(18)];
        // Every power of ten and its neighbours (the digit count's edges).
        for k in 0..19 {
            let p = 10i64.pow(k);
            ints.extend([p - 1, p, p + 1, -p, 1 - p]);
        }
        for n in ints {
            let mut v = Vec::new();
            put_int(&mut v, n);
            assert_eq!(v, n.to_string().as_bytes());
        }
        // Every exact tie with few fraction bits (m / 2^k for small k).
        for k in 1..=30 {
            for m in 0..2000u64 {
                let x = m as f64 / (1u64 << k) as f64;
                same(x, &mut a, &mut b);
                same(-x, &mut a, &mut b);
                same(x + 123.0, &mut a, &mut b);
            }
        }
        // The 0.001 grid's edges: around 10⁹ (where it stops), and one ulp off the grid.
        for n in [999_999_999_999i64, 999_999_999_998, 1_000_000_000_000, 1_000_000_000_001, 123_456_789_012, 5, 1] {
            for x in [n as f64 / 1000.0, -(n as f64) / 1000.0] {
                same(x, &mut a, &mut b);
                same(f64::from_bits(x.to_bits() + 1), &mut a, &mut b);
                same(f64::from_bits(x.to_bits() - 1), &mut a, &mut b);
            }
        }
        // Large grid values: every integer-part length of the short grid writer and past it.
        for int in [999i64, 1000, 1001, 9999, 10_000, 99_999, 100_000, 123_456, 999_999, 1_000_000, 9_999_999] {
            for frac in [0i64, 1, 10, 100, 120, 500, 999] {
                let x = (int * 1000 + frac) as f64 / 1000.0;
                same(x, &mut a, &mut b);
                same(-x, &mut a, &mut b);
            }
        }
        // Every multiple of 0.001 in ±100 (all metric positions of a small part).
        for i in -100_000..=100_000 {
            same(i as f64 / 1000.0, &mut a, &mut b);
            same(i as f64 * 0.001, &mut a, &mut b);
        }
    }

    #[test]
    fn the_grid_writer_writes_what_the_standard_formatter_writes() {
        let check = |n: i64| {
            let mut b = [b'#'; 40];
            let end = put_grid(&mut b, 5, n);
            let mut want = String::new();
            push_num_std(&mut want, n as f64 / 1000.0);
            assert_eq!(&b[5..end], want.as_bytes(), "n = {n}");
        };
        for n in -300_000..=300_000 {
            check(n);
        }
        let mut r = Rng(5);
        for _ in 0..500_000 {
            let n = (r.next() % 1_999_999_999) as i64 - 999_999_999;
            check(n);
            check(n / 1000 * 1000);
        }
        for p in [1_000i64, 10_000, 100_000, 1_000_000, 10_000_000, 100_000_000, 1_000_000_000] {
            for n in [p - 1, p, p + 1, p - 1000, p + 1000] {
                if n.unsigned_abs() < GRID_LIMIT {
                    check(n);
                    check(-n);
                }
            }
        }
    }

    #[test]
    fn agrees_with_the_standard_formatter() {
        check_many(300_000, 7);
    }

    /// The long run: `cargo test --release numfmt -- --ignored` (about 100 M values).
    #[test]
    #[ignore]
    fn agrees_with_the_standard_formatter_long() {
        check_many(10_000_000, 11);
    }
}
