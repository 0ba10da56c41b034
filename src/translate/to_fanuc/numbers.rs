//! The O number of every program of a Sinumerik → FANUC translation: the main program's
//! (`--program-number`, a map entry, else O0001), the mapped ones, and, with `--l-numbers`,
//! a program named `L<k>` (the DIN subprogram name, no leading zero) as `O<k>`, so that
//! `CALL "L"<<R1` has the exact counterpart `G65 P#n`; every other subprogram from O9000 up
//! in name order, past the numbers already taken.

use super::{TranslateOptions, DEFAULT_MAIN_NUMBER, FIRST_SUB_NUMBER};
use crate::lower::to_fanuc::LFault;
use std::collections::BTreeMap;

/// The numbers, and with `--l-numbers` every `L<k>` program with its `O<k>` or why it has
/// none (it is then numbered as any other subprogram, and a built call of it is refused).
pub struct Numbers {
    pub numbers: BTreeMap<String, u32>,
    pub l_programs: Option<BTreeMap<String, Result<u32, LFault>>>,
}

/// `k` of a DIN subprogram name `L<k>`: `L` and digits, the first not `0` (`L010` is another
/// program than `L10`, and `"L"<<10` builds `L10`). `L0` gives 0, which is no O number.
pub fn l_number(name: &str) -> Option<u64> {
    let digits = name.strip_prefix(['L', 'l'])?;
    let ok = !digits.is_empty()
        && digits.bytes().all(|b| b.is_ascii_digit())
        && (digits == "0" || !digits.starts_with('0'))
        && digits.len() <= 8;
    ok.then(|| digits.parse().ok()).flatten()
}

/// Numbers `main_name` and `subs` (upper case, in name order) under `opts`.
pub fn assign(main_name: &str, subs: &[String], opts: &TranslateOptions) -> Numbers {
    let mut numbers: BTreeMap<String, u32> = BTreeMap::new();
    let mut taken: Vec<u32> = opts.program_map.values().copied().collect();
    let main_no =
        opts.program_number.or_else(|| opts.program_map.get(main_name).copied()).unwrap_or(DEFAULT_MAIN_NUMBER);
    taken.push(main_no);
    numbers.insert(main_name.to_string(), main_no);
    // Who holds each number taken so far, for the message of a clash.
    let owner = |n: u32, numbers: &BTreeMap<String, u32>| {
        numbers
            .iter()
            .find(|(_, &m)| m == n)
            .map(|(s, _)| s.clone())
            .or_else(|| opts.program_map.iter().find(|(_, &m)| m == n).map(|(s, _)| s.clone()))
    };
    let mut l_programs = opts.l_numbers.then(BTreeMap::new);
    if let Some(l) = &mut l_programs {
        for name in subs {
            let Some(k) = l_number(name) else { continue };
            let mapped = opts.program_map.get(name).copied();
            let fault = if let Some(n) = mapped.filter(|&n| u64::from(n) != k) {
                Some(LFault::Mapped { to: n })
            } else if mapped.is_some() {
                None
            } else if k == 0 || k > u64::from(opts.max_program_number) {
                Some(LFault::Beyond { max: opts.max_program_number })
            } else {
                owner(k as u32, &numbers).map(|other| LFault::Clash { other })
            };
            match fault {
                Some(f) => {
                    l.insert(name.clone(), Err(f));
                }
                None if mapped.is_some() => {
                    l.insert(name.clone(), Ok(k as u32));
                }
                None => {
                    let k = k as u32;
                    taken.push(k);
                    numbers.insert(name.clone(), k);
                    l.insert(name.clone(), Ok(k));
                }
            }
        }
    }
    let mut next = FIRST_SUB_NUMBER;
    for name in subs {
        if numbers.contains_key(name) {
            continue;
        }
        let n = match opts.program_map.get(name) {
            Some(&n) => n,
            None => {
                while taken.contains(&next) {
                    next += 1;
                }
                taken.push(next);
                next
            }
        };
        numbers.insert(name.clone(), n);
    }
    Numbers { numbers, l_programs }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn din_names_only() {
        assert_eq!(l_number("L10"), Some(10));
        assert_eq!(l_number("L0"), Some(0));
        assert_eq!(l_number("L010"), None);
        assert_eq!(l_number("LX10"), None);
        assert_eq!(l_number("L"), None);
    }

    #[test]
    fn l_programs_keep_their_number_and_clashes_are_named() {
        let opts = TranslateOptions { l_numbers: true, ..TranslateOptions::default() };
        let subs: Vec<String> = ["A_SUB", "L1", "L20", "L12345"].iter().map(|s| s.to_string()).collect();
        let n = assign("MAIN", &subs, &opts);
        assert_eq!(n.numbers["L20"], 20);
        assert_eq!(n.numbers["A_SUB"], 9000);
        let l = n.l_programs.unwrap();
        assert_eq!(l["L1"], Err(LFault::Clash { other: "MAIN".into() }));
        assert_eq!(l["L12345"], Err(LFault::Beyond { max: 9999 }));
        // A map entry wins; one that is not O<k> is no L number.
        let mut opts = opts;
        opts.program_map.insert("L20".into(), 9100);
        opts.program_map.insert("L1".into(), 1);
        opts.program_number = Some(5);
        let l = assign("MAIN", &subs, &opts).l_programs.unwrap();
        assert_eq!((&l["L20"], &l["L1"]), (&Err(LFault::Mapped { to: 9100 }), &Ok(1)));
        // Off: numbered by name as before.
        let n = assign("MAIN", &subs, &TranslateOptions::default());
        assert_eq!((n.numbers["A_SUB"], n.numbers["L1"], n.numbers["L20"]), (9000, 9001, 9002));
        assert!(n.l_programs.is_none());
    }
}
