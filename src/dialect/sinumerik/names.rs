//! Sinumerik names: built-in functions with their arity, the multi-letter addresses and the
//! named NC instructions the reader knows, and the rule that tells an address word
//! (`ELX=3`) from an assignment to a user variable (`E_MULTIPLIER=1`).

use crate::ir::Func;

/// A built-in function: its IR operation and how many arguments it takes.
pub struct Builtin {
    pub func: Func,
    pub arity: usize,
}

/// The Siemens arithmetic functions (`docs/semantics.md`, Operators and functions), by
/// upper-case name.
pub fn builtin(name: &str) -> Option<Builtin> {
    let (func, arity) = match name {
        "SIN" => (Func::Sin, 1),
        "COS" => (Func::Cos, 1),
        "TAN" => (Func::Tan, 1),
        "ASIN" => (Func::Asin, 1),
        "ACOS" => (Func::Acos, 1),
        "ATAN2" => (Func::Atan2, 2),
        "SQRT" => (Func::Sqrt, 1),
        "ABS" => (Func::Abs, 1),
        "TRUNC" => (Func::Trunc, 1),
        "ROUND" => (Func::Round, 1),
        "ROUNDUP" => (Func::RoundUp, 1),
        "LN" => (Func::Ln, 1),
        "EXP" => (Func::Exp, 1),
        "POT" => (Func::Pot, 1),
        "MINVAL" => (Func::MinVal, 2),
        "MAXVAL" => (Func::MaxVal, 2),
        "BOUND" => (Func::Bound, 3),
        "AXNAME" => (Func::AxName, 1),
        "STRLEN" => (Func::StrLen, 1),
        "TOUPPER" => (Func::ToUpper, 1),
        "TOLOWER" => (Func::ToLower, 1),
        "INDEX" => (Func::Index, 2),
        "RINDEX" => (Func::RIndex, 2),
        // Also with two arguments (to the end of the string).
        "SUBSTR" => (Func::Substr, 3),
        "NUMBER" => (Func::Number, 1),
        "ISNUMBER" => (Func::IsNumber, 1),
        // Also with one argument (duplo number 1).
        "GETT" => (Func::GetT, 2),
        // A format and its values (any number of them).
        "SPRINT" => (Func::Sprint, 1),
        "ISVAR" => (Func::IsVar, 1),
        "ISFILE" => (Func::IsFile, 1),
        "GETSELT" => (Func::GetSelT, 2),
        _ => return None,
    };
    Some(Builtin { func, arity })
}

/// Multi-letter NC addresses that take a value with `=` (source S26 of `docs/semantics.md`): arc radius
/// and angle, polar coordinates, extra turns, spindle positioning, spline parameters, and
/// other per-block addresses. Anything not listed is decided by [`is_address_name`].
const ADDRESSES: &[&str] = &[
    "CR", "AR", "AP", "RP", "TURN", "SPOS", "SPOSA", "PW", "SD", "PL", "OFFN", "ACC", "FA", "FL", "OVR", "OVRA", "SF",
    "DC", "ACN", "ACP", "CAC", "CIC", "CDC", "CACP", "CACN", "MEAS", "MEAW", "ANG", "CHR", "CHF", "RND", "RNDM", "FRC",
    "FRCM", "FAD", "ADIS", "ADISPOS", "STOPFIFO",
];

/// Whether `NAME=value` (no subscripts) writes an NC address rather than a variable.
/// Siemens decides by its configuration (declared variables, machine axis names); the
/// reader decides without it, in this order: a declared name is a variable; a letter
/// followed by digits (`X1`, `I1`) is a numbered address; a known address is an address; a
/// name with `_` is a variable (the manual's advice for user names); a short name of up to
/// three letters (`ELX`) is a machine axis; anything longer is a variable.
pub fn is_address_name(upper: &str, declared: bool) -> bool {
    if declared {
        return false;
    }
    let b = upper.as_bytes();
    let letters = b.iter().take_while(|c| c.is_ascii_alphabetic()).count();
    let numbered = letters >= 1 && letters < b.len() && b[letters..].iter().all(u8::is_ascii_digit);
    if numbered && letters <= 3 {
        return true;
    }
    if ADDRESSES.contains(&upper) {
        return true;
    }
    if upper.contains('_') {
        return false;
    }
    b.len() <= 3 && letters == b.len()
}

/// Named NC instructions written without a value: motion and interpolation modes, spline
/// conditions, path modes, frame suppression, single-block control. A bare name that is not
/// listed is a subprogram call.
const INSTRUCTIONS: &[&str] = &[
    "CIP",
    "CT",
    "ASPLINE",
    "BSPLINE",
    "CSPLINE",
    "POLY",
    "BAUTO",
    "BNAT",
    "BTAN",
    "EAUTO",
    "ENAT",
    "ETAN",
    "SOFT",
    "BRISK",
    "DRIVE",
    "CFC",
    "CFTCP",
    "CFIN",
    "SUPA",
    "DIAMON",
    "DIAMOF",
    "DIAM90",
    "SBLOF",
    "SBLON",
    "FFWON",
    "FFWOF",
    "WALIMON",
    "WALIMOF",
    "CUT2D",
    "CUT2DF",
    "CUT3DC",
    "TRAFOOF",
    "TRANSMIT",
    "TRACYL",
    "SPLINEPATH",
    "UPATH",
    "SPATH",
    "CPRECON",
    "CPRECOF",
    "ORIWKS",
    "ORIMKS",
    "TOFRAME",
    "TCARR",
    "PAROT",
    "PAROTOF",
    "TOROT",
    "TOROTOF",
    "G_GROUP",
    "RTLION",
    "RTLIOF",
    "COMPON",
    "COMPOF",
    "COMPCURV",
    "COMPCAD",
    "BRISKA",
    "SOFTA",
    "DRIVEA",
    "OFFN",
    "NORM",
    "KONT",
    "KONTC",
    "KONTT",
    "DISC",
    "SPIF1",
    "SPIF2",
    "ACTBLOCNO",
    "DISPLOF",
    "DISPLON",
    "PREVENT",
    "SAVE",
    "TOFFON",
    "TOFFOF",
    "FGROUP",
];

/// Predefined procedures of the control (called as `NAME(…)` or bare) that no program of a
/// library provides and nctrans does not model: handwheel and preset
/// offsets, axis and channel coordination, waiting, transformations, couplings. A call of
/// one is named as such rather than looked for as a subprogram.
const PREDEFINED_PROCEDURES: &[&str] = &[
    "DRFOF",
    "PRESETON",
    "SETPIECE",
    "DELDTG",
    "WAITP",
    "WAITM",
    "WAITMC",
    "WAITE",
    "SETM",
    "CLEARM",
    "TRAORI",
    "TRAFOOF",
    "TRANSMIT",
    "TRACYL",
    "TRAANG",
    "COUPON",
    "COUPOF",
    "LEADON",
    "LEADOF",
    "EGON",
    "EGOF",
    "GEOAX",
    "RELEASE",
    "GET",
    "GETD",
    "AXTOCHAN",
    "STARTFIFO",
    "STOPFIFO",
    "DZERO",
];

/// Whether `upper` is one of the control's predefined procedures nctrans does not model.
pub fn is_predefined_procedure(upper: &str) -> bool {
    PREDEFINED_PROCEDURES.contains(&upper)
}

/// Whether a bare name is a named NC instruction rather than a subprogram call.
pub fn is_instruction(upper: &str) -> bool {
    INSTRUCTIONS.contains(&upper)
}

/// Built-ins whose subscript is an axis (`ACC[E]`, `FA[Y]`, `AX[X1]`): a bare name inside
/// their brackets is an axis identifier, not a variable.
pub fn axis_indexed(upper: &str) -> bool {
    matches!(
        upper,
        "ACC" | "AX" | "FA" | "FL" | "OVRA" | "POS" | "POSA" | "SPOS" | "SPOSA" | "FGREF" | "JERKA" | "VELOLIMA"
    )
}

/// Whether a name has the shape of an R parameter (`R12`): never a user name.
pub fn r_number(upper: &str) -> Option<&str> {
    let digits = upper.strip_prefix('R')?;
    (!digits.is_empty() && digits.bytes().all(|c| c.is_ascii_digit())).then_some(digits)
}

/// Words the control reserves beyond the grammar's keywords (which the reader already
/// refuses as names, NC136): per-word value forms, call forms and the identifier `RL`
/// (reserved for conventional turning machines, S9).
const RESERVED: &[&str] = &["AC", "IC", "SET", "REP", "CALL", "PCALL", "EXTCALL", "RL", "GOTOS"];

/// Why `upper` cannot name a user variable (DEF) or a PROC parameter, if it cannot.
///
/// S9: identifiers begin with two letters or underscores, and reserved words must not be
/// used as identifiers. A single letter is an address (`I=0` is the arc centre, whatever
/// was declared), and so are the built-in functions, the multi-letter addresses and the
/// named instructions this reader knows. Letters followed by digits (`L1`, `X1`) break the
/// two-letter rule too, but the reader keeps them apart from addresses once declared and
/// real programs use them, so they stay accepted (R numbers get warning NC133).
pub fn reserved_name(upper: &str) -> Option<String> {
    let b = upper.as_bytes();
    if b.len() == 1 {
        return Some(match b[0] {
            b'_' => "`_` alone is not an identifier".to_string(),
            _ => format!("{upper} is an address letter"),
        });
    }
    // The string functions (and GETT) are known by their call form `NAME(`; programs declare
    // variables of those names (`DEF INT NUMBER`), which the reader keeps apart.
    if builtin(upper).is_some_and(|b| !b.func.is_string()) || axis_indexed(upper) {
        return Some(format!("{upper} is a built-in function"));
    }
    if ADDRESSES.contains(&upper) {
        return Some(format!("{upper} is an NC address"));
    }
    if is_instruction(upper) {
        return Some(format!("{upper} is an NC instruction"));
    }
    if RESERVED.contains(&upper) {
        return Some(format!("{upper} is a reserved word"));
    }
    None
}

#[cfg(test)]
mod tests {
    use super::reserved_name;

    #[test]
    fn address_letters_and_reserved_words_are_not_names() {
        for bad in ["I", "X", "R", "N", "SIN", "CR", "SPOS", "CIP", "AC", "SET", "SAVE"] {
            assert!(reserved_name(bad).is_some(), "{bad} accepted");
        }
        for good in ["I_COUNT", "COUNT", "II", "L1", "R0", "_RPM", "AM", "OFFSET"] {
            assert_eq!(reserved_name(good), None, "{good} refused");
        }
    }
}
