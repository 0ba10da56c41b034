//! Machine signals a program reads and writes: Siemens PLC data `$A_DBB/$A_DBW/$A_DBD/$A_DBR[n]`
//! and NCK digital inputs/outputs `$A_IN[n]`/`$A_OUT[n]`; FANUC custom macro interface
//! signals, inputs `#1000..#1015` (one bit each) and `#1032` (all 16 at once), outputs
//! `#1100..#1115` and `#1132` (docs/semantics.md, Machine signals). Which Siemens signal is
//! which FANUC variable is the machine integrator's wiring, so the set-up says it
//! (`[signals]` in nctrans.toml, [`SignalMap`]); nothing here guesses it.

use std::collections::BTreeMap;

/// The kind of a signal variable.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Kind {
    /// `$A_DBB[n]`: PLC data byte at byte offset n, 0..255 (S-DBB).
    Dbb,
    /// `$A_DBW[n]`: PLC data word, -32768..32767.
    Dbw,
    /// `$A_DBD[n]`: PLC data double word, 32-bit signed.
    Dbd,
    /// `$A_DBR[n]`: PLC real (32 bits).
    Dbr,
    /// `$A_IN[n]`: NCK digital input (S-AIN).
    In,
    /// `$A_OUT[n]`: NCK digital output.
    Out,
    /// FANUC `#1000..#1015`: interface input signal UI0..UI15 (F-UIO), read-only.
    UiBit,
    /// FANUC `#1032`: UI0..UI15 read at once.
    UiWord,
    /// FANUC `#1100..#1115`: interface output signal UO0..UO15, read and written.
    UoBit,
    /// FANUC `#1132`: UO0..UO15 written at once.
    UoWord,
}

/// The values a signal holds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Range {
    /// 0 or 1.
    Bit,
    /// Whole numbers from..to.
    Int(i64, i64),
    /// A 32-bit real.
    Real,
}

impl Range {
    /// Every value of `self` is one of `other`.
    pub fn within(self, other: Range) -> bool {
        match (self, other) {
            (_, Range::Real) => true,
            (Range::Real, _) => false,
            (Range::Bit, Range::Bit) => true,
            (Range::Bit, Range::Int(lo, hi)) => lo <= 0 && hi >= 1,
            (Range::Int(lo, hi), Range::Bit) => lo >= 0 && hi <= 1,
            (Range::Int(a, b), Range::Int(lo, hi)) => a >= lo && b <= hi,
        }
    }

    /// Whether `x` is a value of the range.
    pub fn holds(self, x: f64) -> bool {
        match self {
            Range::Real => x.is_finite(),
            Range::Bit => x == 0.0 || x == 1.0,
            Range::Int(lo, hi) => x.fract() == 0.0 && x >= lo as f64 && x <= hi as f64,
        }
    }

    pub fn describe(self) -> String {
        match self {
            Range::Bit => "0 or 1".into(),
            Range::Int(lo, hi) => format!("a whole number {lo}..{hi}"),
            Range::Real => "a 32-bit real".into(),
        }
    }
}

/// One signal variable: its kind and its index (the byte offset or input number for
/// Siemens, the variable number for FANUC).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Signal {
    pub kind: Kind,
    pub index: u32,
}

impl Signal {
    /// A Siemens system variable `$name[index]` (name upper case, without `$`) that is a signal.
    pub fn siemens(name: &str, index: u32) -> Option<Signal> {
        Some(Signal { kind: siemens_kind(name)?, index })
    }

    /// FANUC `#n` when it is an interface signal.
    pub fn fanuc(n: u32) -> Option<Signal> {
        let kind = match n {
            1000..=1015 => Kind::UiBit,
            1032 => Kind::UiWord,
            1100..=1115 => Kind::UoBit,
            1132 => Kind::UoWord,
            _ => return None,
        };
        Some(Signal { kind, index: n })
    }

    /// `$A_DBB[2]` or `#1002` (spaces allowed, any case).
    pub fn parse(text: &str) -> Result<Signal, String> {
        let t: String = text.chars().filter(|c| !c.is_whitespace()).collect::<String>().to_ascii_uppercase();
        if let Some(n) = t.strip_prefix('#') {
            let n: u32 = n.parse().map_err(|_| format!("'{text}': not a FANUC variable number"))?;
            return Signal::fanuc(n).ok_or_else(|| {
                format!("'{text}': not a FANUC interface signal (#1000..#1015, #1032, #1100..#1115, #1132)")
            });
        }
        let bad = || format!("'{text}': expected $A_DBB[n], $A_DBW[n], $A_DBD[n], $A_DBR[n], $A_IN[n] or $A_OUT[n]");
        let rest = t.strip_prefix('$').ok_or_else(bad)?;
        let (name, idx) = rest.split_once('[').ok_or_else(bad)?;
        let idx: u32 = idx.strip_suffix(']').and_then(|i| i.parse().ok()).ok_or_else(bad)?;
        Signal::siemens(name, idx).ok_or_else(bad)
    }

    pub fn is_fanuc(self) -> bool {
        matches!(self.kind, Kind::UiBit | Kind::UiWord | Kind::UoBit | Kind::UoWord)
    }

    /// As a program writes it: `$A_DBB[2]`, `#1002`.
    pub fn key(self) -> String {
        match self.kind {
            Kind::Dbb => format!("$A_DBB[{}]", self.index),
            Kind::Dbw => format!("$A_DBW[{}]", self.index),
            Kind::Dbd => format!("$A_DBD[{}]", self.index),
            Kind::Dbr => format!("$A_DBR[{}]", self.index),
            Kind::In => format!("$A_IN[{}]", self.index),
            Kind::Out => format!("$A_OUT[{}]", self.index),
            _ => format!("#{}", self.index),
        }
    }

    /// What it is, for messages: `PLC data byte 2`, `interface input signal UI2`.
    pub fn what(self) -> String {
        let i = self.index;
        match self.kind {
            Kind::Dbb => format!("PLC data byte {i}"),
            Kind::Dbw => format!("PLC data word at byte {i}"),
            Kind::Dbd => format!("PLC data double word at byte {i}"),
            Kind::Dbr => format!("PLC real at byte {i}"),
            Kind::In => format!("NCK digital input {i}"),
            Kind::Out => format!("NCK digital output {i}"),
            Kind::UiBit => format!("interface input signal UI{}", i - 1000),
            Kind::UiWord => "interface input signals UI0..UI15 at once".into(),
            Kind::UoBit => format!("interface output signal UO{}", i - 1100),
            Kind::UoWord => "interface output signals UO0..UO15 at once".into(),
        }
    }

    /// `$A_DBB[2] (PLC data byte 2)`.
    pub fn named(self) -> String {
        format!("{} ({})", self.key(), self.what())
    }

    pub fn range(self) -> Range {
        match self.kind {
            Kind::Dbb => Range::Int(0, 255),
            Kind::Dbw => Range::Int(-32768, 32767),
            Kind::Dbd => Range::Int(-2_147_483_648, 2_147_483_647),
            Kind::Dbr => Range::Real,
            Kind::In | Kind::Out | Kind::UiBit | Kind::UoBit => Range::Bit,
            Kind::UiWord | Kind::UoWord => Range::Int(0, 65535),
        }
    }

    /// The bytes `[first, last]` a PLC datum covers (`None` for the other signals), so a run
    /// refuses reading one datum through another's width (their byte order is machine data).
    pub fn plc_bytes(self) -> Option<(u32, u32)> {
        let width = match self.kind {
            Kind::Dbb => 1,
            Kind::Dbw => 2,
            Kind::Dbd | Kind::Dbr => 4,
            _ => return None,
        };
        Some((self.index, self.index + width - 1))
    }

    /// FANUC `#1000..#1015` and `#1032`: read-only (F-UIO).
    pub fn read_only(self) -> bool {
        matches!(self.kind, Kind::UiBit | Kind::UiWord)
    }
}

fn siemens_kind(name: &str) -> Option<Kind> {
    Some(match name {
        "A_DBB" => Kind::Dbb,
        "A_DBW" => Kind::Dbw,
        "A_DBD" => Kind::Dbd,
        "A_DBR" => Kind::Dbr,
        "A_IN" => Kind::In,
        "A_OUT" => Kind::Out,
        _ => return None,
    })
}

/// Whether a Siemens system variable name (upper case, without `$`) is a signal.
pub fn is_siemens_signal(name: &str) -> bool {
    siemens_kind(name).is_some()
}

/// The set-up's wiring (`[signals]`): each Siemens signal with the FANUC variable the
/// machine's PMC connects to the same thing. One FANUC variable per Siemens signal and back.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SignalMap {
    pub pairs: BTreeMap<Signal, Signal>,
}

/// The nctrans.toml key of the map, for hints.
pub const KEY: &str = "[signals]";

impl SignalMap {
    pub fn is_empty(&self) -> bool {
        self.pairs.is_empty()
    }

    /// The FANUC variable of a Siemens signal.
    pub fn fanuc_of(&self, s: Signal) -> Option<Signal> {
        self.pairs.get(&s).copied()
    }

    /// The Siemens signal of a FANUC variable.
    pub fn siemens_of(&self, f: Signal) -> Option<Signal> {
        self.pairs.iter().find(|(_, v)| **v == f).map(|(k, _)| *k)
    }

    /// Adds one entry `"$A_DBB[2]" = "#1002"`, with the checks of the file.
    pub fn add(&mut self, key: &str, value: &str) -> Result<(), String> {
        let s = Signal::parse(key)?;
        let f = Signal::parse(value)?;
        if s.is_fanuc() || !f.is_fanuc() {
            return Err(format!(
                "'{key}' = '{value}': expected a Siemens signal = a FANUC variable, like \"$A_DBB[2]\" = \"#1002\""
            ));
        }
        pairing(s, f).map_err(|why| format!("{} = {}: {why}", s.key(), f.key()))?;
        if let Some(other) = self.siemens_of(f).filter(|o| *o != s) {
            return Err(format!(
                "{} is mapped twice ({} and {}): one FANUC variable per signal",
                f.key(),
                other.key(),
                s.key()
            ));
        }
        // Two entries over the same bits or bytes would let one run's inputs disagree with
        // the other's (the word and its bits are one store on FANUC; how PLC bytes make a
        // word is machine data on Siemens).
        for (k, v) in self.pairs.iter().filter(|(k, _)| **k != s) {
            if let Some(why) = overlap(*v, f).or_else(|| overlap(*k, s)) {
                return Err(format!("{} = {} and {} = {}: {why}", s.key(), f.key(), k.key(), v.key()));
            }
        }
        self.pairs.insert(s, f);
        Ok(())
    }

    /// `[signals]` of nctrans.toml: a table of `"$A_DBB[2]" = "#1002"`.
    pub fn table(key: &str, v: &toml::Value) -> Result<SignalMap, String> {
        let t = v.as_table().ok_or_else(|| format!("{key}: expected a table of \"$A_DBB[2]\" = \"#1002\""))?;
        let mut m = SignalMap::default();
        for (k, val) in t {
            let text = val.as_str().ok_or_else(|| format!("{key}.{k}: expected a FANUC variable like \"#1002\""))?;
            m.add(k, text).map_err(|e| format!("{key}: {e}"))?;
        }
        Ok(m)
    }
}

/// Why two signals of one control share bits (`None` when they do not).
fn overlap(a: Signal, b: Signal) -> Option<String> {
    let word_of = |x: Signal| match x.kind {
        Kind::UiBit | Kind::UiWord => Some(1000),
        Kind::UoBit | Kind::UoWord => Some(1100),
        _ => None,
    };
    let is_word = |x: Signal| matches!(x.kind, Kind::UiWord | Kind::UoWord);
    if a != b && word_of(a).is_some() && word_of(a) == word_of(b) && (is_word(a) || is_word(b)) {
        return Some(format!(
            "#{} holds the 16 bits of #{}..#{} (one wiring each)",
            word_of(a)? + 32,
            word_of(a)?,
            word_of(a)? + 15
        ));
    }
    match (a.plc_bytes(), b.plc_bytes()) {
        (Some((x, y)), Some((u, w))) if a != b && x <= w && u <= y => {
            Some("the two PLC data cover the same bytes, whose order is machine data (MD10399)".into())
        }
        _ => None,
    }
}

/// Whether Siemens signal `s` may be wired to FANUC variable `f`: an input to an input, an
/// output to an output (a PLC datum to either); `$A_DBR` to none (the interface signals
/// hold whole numbers).
fn pairing(s: Signal, f: Signal) -> Result<(), String> {
    let input = matches!(f.kind, Kind::UiBit | Kind::UiWord);
    match s.kind {
        Kind::Dbr => Err("a PLC real has no FANUC counterpart (the interface signals hold whole numbers)".into()),
        Kind::In if !input => Err("an NCK input goes to an interface input (#1000..#1015, #1032)".into()),
        Kind::Out if input => Err("an NCK output goes to an interface output (#1100..#1115, #1132)".into()),
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_and_pairs() {
        assert_eq!(Signal::parse("$a_dbb[ 2 ]").unwrap(), Signal { kind: Kind::Dbb, index: 2 });
        assert_eq!(Signal::parse("#1032").unwrap().kind, Kind::UiWord);
        assert!(Signal::parse("#1016").is_err());
        let mut m = SignalMap::default();
        m.add("$A_DBB[2]", "#1002").unwrap();
        assert!(m.add("$A_IN[1]", "#1002").unwrap_err().contains("mapped twice"));
        assert!(m.add("$A_IN[1]", "#1101").is_err());
        assert!(m.add("$A_DBR[4]", "#1003").is_err());
        assert!(m.add("$A_DBW[4]", "#1032").unwrap_err().contains("16 bits"));
        assert!(m.add("$A_DBW[2]", "#1004").unwrap_err().contains("same bytes"));
        assert_eq!(m.siemens_of(Signal::parse("#1002").unwrap()), Signal::parse("$A_DBB[2]").ok());
        assert!(Range::Bit.within(Signal::parse("$A_DBB[0]").unwrap().range()));
        assert!(!Signal::parse("$A_DBB[0]").unwrap().range().within(Range::Bit));
    }
}
