//! Haas NGC variable numbers (Haas mill operator's manual, NGC, "Macros: system variables";
//! the table as reproduced at zappettiniconsulting.com/wiki/haas-system-variables, see
//! docs/semantics.md): the general-purpose variables are `#10000..#10999`; the ranges that
//! have a legacy number are the same variables as it (`#10100` is `#100`, `#10500` is `#500`,
//! `#10800` is `#800`); `#10000..#10099`, `#10200..#10499` and `#10700..#10799` exist on the
//! NGC only. On a FANUC these numbers are something else (tool offsets on a 0i), so all of
//! this applies under `[fanuc] series = "haas-ngc"` only.

/// The legacy number an NGC number is the same variable as (`#10100` → `#100`).
pub fn legacy(n: u32) -> Option<u32> {
    match n {
        10100..=10199 | 10500..=10699 | 10800..=10999 => Some(n - 10000),
        _ => None,
    }
}

/// An NGC general-purpose variable without a legacy number, kept on power off.
pub fn ngc_only(n: u32) -> bool {
    matches!(n, 10000..=10099 | 10200..=10499 | 10700..=10799)
}

/// A number the FANUC → Sinumerik translation treats as a common variable (one R
/// parameter, an is-set flag where its vacancy shows): `#100..#999`, and with `ngc` (the
/// `haas-ngc` profile) the NGC-only general-purpose numbers, which behave as `#500` does
/// (global, kept on power off, vacant until written).
pub fn common(n: u32, ngc: bool) -> bool {
    matches!(n, 100..=999) || (ngc && ngc_only(n))
}

/// [`common`] for the analyses that run without a profile (vacancy, the library scan): an
/// NGC-only number counts wherever it appears. On another control that number is a system
/// variable the translation refuses (NC365) before it is placed, so counting it there only
/// adds a variable no rule or place is ever used for; they sort after `#999`, so no other
/// variable's place moves.
pub fn maybe_common(n: u32) -> bool {
    common(n, true)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn legacy_ranges_fold_and_the_rest_is_ngc_only() {
        assert_eq!(legacy(10100), Some(100));
        assert_eq!(legacy(10599), Some(599));
        assert_eq!(legacy(10999), Some(999));
        assert_eq!(legacy(10000), None);
        assert_eq!(legacy(10700), None);
        assert!(ngc_only(10000) && ngc_only(10002) && ngc_only(10450) && ngc_only(10799));
        assert!(!ngc_only(10100) && !ngc_only(11000) && !ngc_only(9999));
        assert!(common(500, false) && common(10002, true) && !common(10002, false) && !common(10100, true));
    }
}
