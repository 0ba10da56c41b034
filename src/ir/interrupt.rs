//! The interrupt instructions as the readers keep them (an `Instruction` with its text):
//! Siemens `SETINT(n) PRIO=p NAME [LIFTFAST] [BLSYNC]`, `ENABLE(n)`, `DISABLE(n)`,
//! `CLRINT(n)`, FANUC `M96 P…`, `M97`, read into what they do, once for the evaluator and
//! both translations.

use super::ProgName;

/// What an interrupt instruction does.
#[derive(Clone, Debug, PartialEq)]
pub enum IntOp {
    /// `SETINT(n) PRIO=p NAME` (assigned and enabled), FANUC `M96 Pp` (input 1, priority 1).
    /// `extra`: `LIFTFAST`, `BLSYNC` as written.
    Assign { input: u32, prio: u32, routine: ProgName, extra: Vec<String> },
    /// `ENABLE(n)`.
    Enable(u32),
    /// `DISABLE(n)`, FANUC `M97`: the assignment stays.
    Disable(u32),
    /// `CLRINT(n)`: the assignment is deleted.
    Clear(u32),
}

/// Reads an interrupt instruction as the readers keep it (`SETINT(3) PRIO=1 NAME`,
/// `ENABLE(3)`, `M96 P9000`, `M97`). `None`: not an interrupt; `Err`: one whose input,
/// priority or routine is not a constant the run can use.
pub fn op_of(name: &str) -> Option<Result<IntOp, String>> {
    if let Some(p) = name.strip_prefix("M96 P") {
        return Some(match p.trim().parse::<u32>() {
            Ok(n) => Ok(IntOp::Assign { input: 1, prio: 1, routine: ProgName::Number(n), extra: vec![] }),
            Err(_) => Err(format!("{name}: the interrupt program number must be a constant")),
        });
    }
    if name == "M97" {
        return Some(Ok(IntOp::Disable(1)));
    }
    // The readers keep the Siemens text as written (upper case): close the spaces around
    // `(`, `)` and `=` so that each part is one word.
    let mut t = name.to_string();
    for (a, b) in [(" (", "("), ("( ", "("), (" )", ")"), (" =", "="), ("= ", "=")] {
        while t.contains(a) {
            t = t.replace(a, b);
        }
    }
    let (head, rest) = t.split_once(')')?;
    let (kw, n) = head.split_once('(')?;
    if !matches!(kw, "SETINT" | "ENABLE" | "DISABLE" | "CLRINT") {
        return None;
    }
    let Ok(input) = n.trim().parse::<u32>() else {
        return Some(Err(format!("{name}: the input number must be a constant from 1 to 8")));
    };
    if !(1..=8).contains(&input) {
        return Some(Err(format!("{name}: the input number must be a constant from 1 to 8")));
    }
    Some(match kw {
        "ENABLE" => Ok(IntOp::Enable(input)),
        "DISABLE" => Ok(IntOp::Disable(input)),
        "CLRINT" => Ok(IntOp::Clear(input)),
        _ => {
            let (mut prio, mut routine, mut extra) = (None, None, Vec::new());
            for w in rest.split_whitespace() {
                if let Some(p) = w.strip_prefix("PRIO=") {
                    prio = p.parse::<u32>().ok().filter(|p| (1..=128).contains(p));
                    if prio.is_none() {
                        return Some(Err(format!("{name}: PRIO must be a constant from 1 to 128")));
                    }
                } else if w == "LIFTFAST" || w == "BLSYNC" {
                    extra.push(w.to_string());
                } else if routine.is_none() && w.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_') {
                    routine = Some(w.to_string());
                } else {
                    return Some(Err(format!(
                        "{name}: '{w}' is neither PRIO=, the routine's name, LIFTFAST nor BLSYNC"
                    )));
                }
            }
            match (prio, routine) {
                (Some(prio), Some(r)) => Ok(IntOp::Assign { input, prio, routine: ProgName::Name(r), extra }),
                (None, _) => Err(format!("{name}: SETINT needs PRIO=p")),
                (_, None) => Err(format!("{name}: SETINT needs the name of the routine")),
            }
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_both_spellings() {
        let a = op_of("SETINT(3) PRIO=2 ABHEB").unwrap().unwrap();
        assert_eq!(a, IntOp::Assign { input: 3, prio: 2, routine: ProgName::Name("ABHEB".into()), extra: vec![] });
        let a = op_of("SETINT (1) PRIO = 1 R LIFTFAST").unwrap().unwrap();
        assert!(matches!(a, IntOp::Assign { extra, .. } if extra == ["LIFTFAST"]));
        assert_eq!(op_of("DISABLE(2)").unwrap().unwrap(), IntOp::Disable(2));
        assert_eq!(op_of("CLRINT(2)").unwrap().unwrap(), IntOp::Clear(2));
        assert_eq!(op_of("ENABLE(2)").unwrap().unwrap(), IntOp::Enable(2));
        let m = op_of("M96 P9000").unwrap().unwrap();
        assert_eq!(m, IntOp::Assign { input: 1, prio: 1, routine: ProgName::Number(9000), extra: vec![] });
        assert_eq!(op_of("M97").unwrap().unwrap(), IntOp::Disable(1));
        assert!(op_of("FFWON").is_none());
        assert!(op_of("SETINT(R1) PRIO=1 A").unwrap().is_err());
        assert!(op_of("SETINT(9) PRIO=1 A").unwrap().is_err());
        assert!(op_of("SETINT(1) A").unwrap().is_err());
        assert!(op_of("SETINT(1) PRIO=1").unwrap().is_err());
        assert!(op_of("SETINT(1) PRIO=200 A").unwrap().is_err());
    }
}
