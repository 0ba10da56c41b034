//! The maps of a whole batch: one program map (Siemens names ↔ FANUC `O` numbers), one
//! tool map (Siemens tool names → T numbers) and one variable map, fixed before any file is
//! translated so that every call in every output points at the right program. They are
//! written to `OUT/nctrans-map.toml` and read back (`--map`) so a rerun is byte-identical.

use crate::config::{program_table, string_list, tool_table, Config};
use crate::dialect::Dialect;
use crate::translate::library::{Library, ProgKey};
use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;

/// First `O` number given to a called program (FANUC's macro range).
pub const FIRST_SUB_NUMBER: u32 = 9000;
/// First `O` number given to a main program.
pub const FIRST_MAIN_NUMBER: u32 = 1;
/// Largest four-digit `O` number.
pub const MAX_O_NUMBER: u32 = 9999;

/// The maps of a batch. Keys and values are spelled as the user writes them: programs
/// `"CONTOUR" = "O9000"` (to FANUC) or `"O9010" = "PROBE_X"` (to Sinumerik).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BatchMaps {
    /// Source program → target program.
    pub programs: BTreeMap<ProgKey, ProgKey>,
    /// Siemens tool name (as written) → T number.
    pub tools: BTreeMap<String, u32>,
    /// `--var-map` rules in force, in order (`R0-R99=#100`, `#500-#599=R100`).
    pub var_rules: Vec<String>,
    /// The variables the translations used (`R1` → `#501`, `PART.CNT` → `#100`); written for
    /// people, and read back only to be written again.
    pub variables: BTreeMap<String, String>,
    /// The H ↔ T/D offset map the translations used (`[offsets]` of nctrans.toml or
    /// `--offset-map`), so a rerun with the map translates compensation alike.
    pub offsets: crate::dialect::offsets::OffsetMap,
    /// The machine's signal wiring the translations used (`[signals]` of nctrans.toml),
    /// so a rerun with the map reads the same signals; written only when there is one.
    pub signals: crate::dialect::signals::SignalMap,
}

/// What one file's translation used; merged into the written map.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Used {
    pub programs: BTreeMap<ProgKey, ProgKey>,
    pub tools: BTreeMap<String, u32>,
    pub variables: BTreeMap<String, String>,
}

impl BatchMaps {
    /// `Siemens name → O number`, the program map of the Sinumerik → FANUC translator.
    pub fn fanuc_numbers(&self) -> BTreeMap<String, u32> {
        self.programs
            .iter()
            .filter_map(|(k, v)| match (k, v) {
                (ProgKey::Name(s), ProgKey::Number(n)) => Some((s.clone(), *n)),
                _ => None,
            })
            .collect()
    }

    /// `O number → Siemens name`, the program map of the FANUC → Sinumerik translator.
    pub fn siemens_names(&self) -> BTreeMap<u32, String> {
        self.programs
            .iter()
            .filter_map(|(k, v)| match (k, v) {
                (ProgKey::Number(n), ProgKey::Name(s)) => Some((*n, s.clone())),
                _ => None,
            })
            .collect()
    }

    /// Adds what a file used; an entry already present is kept (the batch pins programs and
    /// tools before translating, so they agree). Returns one message per variable that this
    /// file placed differently from an earlier file (the FANUC → Sinumerik translation
    /// places common variables without a default R parameter, and the is-set flags, per
    /// file), or per target two files gave to different variables: such files do not
    /// share the variable on the control.
    pub fn merge_used(&mut self, used: &Used) -> Vec<String> {
        for (k, v) in &used.programs {
            self.programs.entry(k.clone()).or_insert_with(|| v.clone());
        }
        for (k, v) in &used.tools {
            self.tools.entry(k.clone()).or_insert(*v);
        }
        let mut conflicts = Vec::new();
        for (k, v) in &used.variables {
            match self.variables.get(k) {
                Some(old) if old != v => conflicts.push(format!("{k} is {old} in one file and {v} in another")),
                Some(_) => {}
                None => {
                    // Plain global variables only: locals live in their program, and an
                    // array entry (`R[i]`) overlaps its elements on purpose.
                    let plain = |k: &str| k.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'#' || b == b'_');
                    let taken =
                        plain(k).then(|| self.variables.iter().find(|(k2, v2)| *v2 == v && plain(k2))).flatten();
                    if let Some((other, _)) = taken {
                        conflicts.push(format!("{v} stands for {other} in one file and for {k} in another"));
                    }
                    self.variables.insert(k.clone(), v.clone());
                }
            }
        }
        conflicts
    }
}

/// A valid Siemens program name from a file stem: letters, digits and `_`, the first two
/// characters letters or `_` (the control's rule), upper case (`10-bracket` →
/// `P_10_BRACKET`, `o9010` → `P_O9010`).
pub fn siemens_name(stem: &str) -> String {
    let mut s: String =
        stem.chars().map(|c| if c.is_ascii_alphanumeric() { c.to_ascii_uppercase() } else { '_' }).collect();
    if s.len() < 2 || !s.bytes().take(2).all(|b| b.is_ascii_alphabetic() || b == b'_') {
        s.insert_str(0, "P_");
    }
    s.truncate(24);
    s
}

/// The Siemens name of FANUC program `n` when nothing else names it: `O_9010`, as the
/// single-file translation writes it.
pub fn numbered_name(n: u32) -> String {
    format!("O_{n:04}")
}

/// Fixes the program and tool maps for a batch: pinned entries first, then deterministic
/// defaults for everything else in the library. Returns the maps and one message per program
/// that got no number (four-digit `O` numbers exhausted).
pub fn allocate(lib: &Library, pinned: &BatchMaps, target: Dialect, stems: &[String]) -> (BatchMaps, Vec<String>) {
    let mut maps = BatchMaps {
        programs: BTreeMap::new(),
        tools: pinned.tools.clone(),
        var_rules: pinned.var_rules.clone(),
        variables: BTreeMap::new(),
        offsets: pinned.offsets.clone(),
        signals: pinned.signals.clone(),
    };
    let mut problems = Vec::new();
    match target {
        Dialect::Fanuc => {
            let mut taken: BTreeSet<u32> = pinned.fanuc_numbers().values().copied().collect();
            // Under --l-numbers a program L<k> is O<k> (a `CALL "L"<<n` is `G65 P<n>`), so
            // those numbers go first; one already pinned elsewhere stays a clash its
            // callers' translation names (NC648).
            if lib.l_numbers {
                for (key, info) in &lib.programs {
                    let Some(k) = key.l_number().and_then(|k| u32::try_from(k).ok()) else { continue };
                    let sinumerik = lib.files[info.file].dialect == Some(Dialect::Sinumerik);
                    if sinumerik
                        && !pinned.programs.contains_key(key)
                        && (1..=MAX_O_NUMBER).contains(&k)
                        && taken.insert(k)
                    {
                        maps.programs.insert(key.clone(), ProgKey::Number(k));
                    }
                }
            }
            // Mains from 1 up, called programs (and PROCs) from 9000 up, in name order.
            for (key, info) in &lib.programs {
                if maps.programs.contains_key(key) {
                    continue;
                }
                let ProgKey::Name(name) = key else { continue };
                if lib.files[info.file].dialect != Some(Dialect::Sinumerik) {
                    continue;
                }
                let n = match pinned.programs.get(key) {
                    Some(ProgKey::Number(n)) => Some(*n),
                    _ => {
                        let sub = lib.is_called(key) || !info.params.is_empty();
                        let first = if sub { FIRST_SUB_NUMBER } else { FIRST_MAIN_NUMBER };
                        let n = (first..=MAX_O_NUMBER).find(|n| !taken.contains(n));
                        if let Some(n) = n {
                            taken.insert(n);
                        }
                        n
                    }
                };
                match n {
                    Some(n) => {
                        maps.programs.insert(key.clone(), ProgKey::Number(n));
                    }
                    None => problems.push(format!("no free O number left for {name}")),
                }
            }
            // Tools: only the numbers given (--tool-map, [tools], an earlier map). A T number
            // names a pocket and its offsets on the machine, which nctrans cannot know, and the
            // trace would call a chosen one equivalent: a name without a number is refused in
            // its files (NC301), as in a single-file translation, and listed here once.
            let missing: Vec<String> = lib.tool_names().into_iter().filter(|n| !maps.tools.contains_key(n)).collect();
            if !missing.is_empty() {
                let table: Vec<String> = missing.iter().map(|n| format!("{} = <T number>", quote(n))).collect();
                problems.push(format!(
                    "{} tool name(s) have no FANUC T number, so the files using them are not translated (NC301); \
                     give them under [tools] in nctrans.toml: {}",
                    missing.len(),
                    table.join(", ")
                ));
            }
        }
        Dialect::Sinumerik => {
            let mut taken: BTreeSet<String> = pinned.siemens_names().into_values().collect();
            for (key, info) in &lib.programs {
                let ProgKey::Number(n) = key else { continue };
                if lib.files[info.file].dialect != Some(Dialect::Fanuc) {
                    continue;
                }
                let name = match pinned.programs.get(key) {
                    Some(ProgKey::Name(s)) => s.clone(),
                    _ => {
                        // The first program of a file, when nothing calls it, keeps the file's
                        // name (that is how the operator knows it); the others are named after
                        // their number.
                        let base = match stems.get(info.file) {
                            Some(stem) if info.position == 0 && !lib.is_called(key) => siemens_name(stem),
                            _ => numbered_name(*n),
                        };
                        let mut name = base.clone();
                        let mut k = 2;
                        while taken.contains(&name) {
                            name = format!("{base}_{k}");
                            k += 1;
                        }
                        taken.insert(name.clone());
                        name
                    }
                };
                maps.programs.insert(key.clone(), ProgKey::Name(name));
            }
        }
    }
    // Pinned entries for programs that are not in this library are kept: the map file
    // stays the same across reruns on part of a library.
    for (k, v) in &pinned.programs {
        maps.programs.entry(k.clone()).or_insert_with(|| v.clone());
    }
    (maps, problems)
}

/// Quotes a TOML key or string (basic string with escapes); also a valid JSON string.
pub fn quote(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            c if c.is_control() => {
                let _ = write!(out, "\\u{:04X}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// The map file's text. Stable: sorted keys, no timestamps.
pub fn to_toml(maps: &BatchMaps, target: Dialect) -> String {
    let mut s = String::new();
    s.push_str("# nctrans-map.toml: the names this batch used, written by nctrans.\n");
    s.push_str("# Give it back (nctrans --map nctrans-map.toml, or leave it in the output folder) and a\n");
    s.push_str("# rerun names every program, tool and variable the same way: byte-identical output.\n");
    s.push_str("# Edit a value to rename; the next run checks and uses it.\n\n");
    let _ = writeln!(s, "target = {}\n", quote(target.name()));
    match target {
        Dialect::Fanuc => s.push_str("# Siemens program name = FANUC O number\n"),
        Dialect::Sinumerik => s.push_str("# FANUC O number = Siemens program name\n"),
    }
    s.push_str("[programs]\n");
    for (k, v) in &maps.programs {
        let _ = writeln!(s, "{} = {}", quote(&k.to_string()), quote(&v.to_string()));
    }
    s.push_str("\n# Siemens tool name = FANUC T number\n[tools]\n");
    for (k, v) in &maps.tools {
        let _ = writeln!(s, "{} = {v}", quote(k));
    }
    s.push_str(
        "\n# Siemens cutting edge \"T.D\" = FANUC registers (the others: edge D1 of tool n is Hn, Dn)\n[offsets]\n",
    );
    for ((t, e), (h, d)) in &maps.offsets.edges {
        let _ = writeln!(s, "\"{t}.{e}\" = \"H{h},D{d}\"");
    }
    if !maps.signals.is_empty() {
        s.push_str("\n# The machine's signal wiring: Siemens signal = FANUC interface signal\n[signals]\n");
        for (k, v) in &maps.signals.pairs {
            let _ = writeln!(s, "{} = {}", quote(&k.key()), quote(&v.key()));
        }
    }
    s.push_str("\n[variables]\n# --var-map rules in force, in order\nrules = [");
    let rules: Vec<String> = maps.var_rules.iter().map(|r| quote(r)).collect();
    s.push_str(&rules.join(", "));
    s.push_str("]\n\n# The variables the translations used (for reading; the rules above decide)\n[variables.used]\n");
    for (k, v) in &maps.variables {
        let _ = writeln!(s, "{} = {}", quote(k), quote(v));
    }
    s
}

/// Reads a map file. Errors name the key and what is allowed.
pub fn from_toml(text: &str) -> Result<(BatchMaps, Option<Dialect>), String> {
    let table: toml::Table = text.parse().map_err(|e: toml::de::Error| e.to_string().trim_end().to_string())?;
    let mut maps = BatchMaps::default();
    let mut target = None;
    // The target decides how program keys read (a Siemens program may be called `O100`).
    if let Some(value) = table.get("target") {
        let s = value.as_str().ok_or("target: expected a string, \"fanuc\" or \"sinumerik\"")?;
        target = Some(
            Dialect::from_name(s)
                .ok_or_else(|| format!("target: unknown dialect '{s}' (allowed: fanuc, sinumerik)"))?,
        );
    }
    for (key, value) in &table {
        match key.as_str() {
            "target" => {}
            "programs" => maps.programs = program_table(value, "programs", target)?,
            "tools" => maps.tools = tool_table(value, "tools")?,
            "offsets" => {
                let t = value.as_table().ok_or("offsets: expected a table of \"T.D\" = \"Hh,Dd\"")?;
                for (k, v) in t {
                    let text = v.as_str().ok_or_else(|| format!("offsets.{k}: expected a string like \"H26,D46\""))?;
                    let (edge, regs) = crate::dialect::offsets::OffsetMap::parse_entry(k, text)
                        .map_err(|e| format!("offsets.{k}: {e}"))?;
                    maps.offsets.edges.insert(edge, regs);
                }
            }
            "signals" => maps.signals = crate::dialect::signals::SignalMap::table("signals", value)?,
            "variables" => {
                let t = value.as_table().ok_or("variables: expected a table with 'rules' and 'used'")?;
                for (k, v) in t {
                    match k.as_str() {
                        "rules" => maps.var_rules = string_list(v, "variables.rules")?,
                        "used" => {
                            let used =
                                v.as_table().ok_or("variables.used: expected a table of \"SOURCE\" = \"TARGET\"")?;
                            for (src, tgt) in used {
                                let t = tgt
                                    .as_str()
                                    .ok_or_else(|| format!("variables.used.{src}: expected a string like \"#501\""))?;
                                maps.variables.insert(src.clone(), t.to_string());
                            }
                        }
                        other => return Err(format!("variables.{other}: unknown key (allowed: rules, used)")),
                    }
                }
            }
            other => {
                return Err(format!(
                    "{other}: unknown key (allowed: target, programs, tools, offsets, signals, variables)"
                ))
            }
        }
    }
    Ok((maps, target))
}

impl BatchMaps {
    /// The pinned maps of `nctrans.toml` and the flags (`c`) for a direction: programs,
    /// tools, variable rules and offsets.
    pub fn from_config(c: &Config, target: Dialect) -> BatchMaps {
        let (programs, rules) = match target {
            Dialect::Fanuc => (&c.programs_to_fanuc, &c.var_map_to_fanuc),
            Dialect::Sinumerik => (&c.programs_to_sinumerik, &c.var_map_to_sinumerik),
        };
        BatchMaps {
            programs: programs.clone(),
            tools: c.tools.clone(),
            var_rules: rules.clone(),
            variables: BTreeMap::new(),
            offsets: c.offsets.clone(),
            signals: c.signals.clone(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::translate::library::{FileInfo, ProgramInfo};

    fn lib_with(progs: &[(ProgKey, usize, Dialect)], called: &[ProgKey], files: usize) -> Library {
        let mut lib = Library::default();
        for i in 0..files {
            let programs = progs.iter().filter(|p| p.1 == i).map(|p| Some(p.0.clone())).collect();
            let dialect = progs.iter().find(|p| p.1 == i).map(|p| p.2);
            lib.files.push(FileInfo { dialect, programs, ..FileInfo::default() });
        }
        for (k, f, _) in progs {
            lib.programs.insert(k.clone(), ProgramInfo { key: k.clone(), file: *f, position: 0, params: vec![] });
        }
        for c in called {
            lib.calls.push(crate::translate::library::CallSite {
                file: 0,
                line: 1,
                target: c.clone(),
                kind: crate::ir::CallKind::Named,
                args: None,
                given: vec![],
            });
        }
        lib
    }

    #[test]
    fn fanuc_numbers_mains_low_subs_high_pins_respected() {
        let name = |s: &str| ProgKey::Name(s.into());
        let lib = lib_with(
            &[
                (name("PART"), 0, Dialect::Sinumerik),
                (name("A_SUB"), 1, Dialect::Sinumerik),
                (name("B_SUB"), 2, Dialect::Sinumerik),
            ],
            &[name("A_SUB"), name("B_SUB")],
            3,
        );
        let mut pinned = BatchMaps::default();
        pinned.programs.insert(name("B_SUB"), ProgKey::Number(9000));
        let (maps, problems) = allocate(&lib, &pinned, Dialect::Fanuc, &[]);
        assert!(problems.is_empty());
        assert_eq!(maps.programs[&name("PART")], ProgKey::Number(1));
        assert_eq!(maps.programs[&name("B_SUB")], ProgKey::Number(9000));
        assert_eq!(maps.programs[&name("A_SUB")], ProgKey::Number(9001));
    }

    #[test]
    fn siemens_names_from_stems_and_numbers() {
        let lib = lib_with(
            &[(ProgKey::Number(100), 0, Dialect::Fanuc), (ProgKey::Number(9010), 1, Dialect::Fanuc)],
            &[ProgKey::Number(9010)],
            2,
        );
        let (maps, _) =
            allocate(&lib, &BatchMaps::default(), Dialect::Sinumerik, &["10-bracket".into(), "o9010".into()]);
        assert_eq!(maps.programs[&ProgKey::Number(100)], ProgKey::Name("P_10_BRACKET".into()));
        assert_eq!(maps.programs[&ProgKey::Number(9010)], ProgKey::Name("O_9010".into()));
        assert_eq!(siemens_name("part1"), "PART1");
        assert_eq!(siemens_name("o9010"), "P_O9010");
    }

    #[test]
    fn map_file_round_trips_byte_identical() {
        let mut m = BatchMaps::default();
        m.programs.insert(ProgKey::Name("CONTOUR".into()), ProgKey::Number(9000));
        m.programs.insert(ProgKey::Name("PART \"1\"".into()), ProgKey::Number(1));
        m.tools.insert("BallNose_D8".into(), 3);
        m.var_rules = vec!["R0-R99=#100".into()];
        m.variables.insert("R1".into(), "#101".into());
        m.offsets.edges.insert((6, 2), (26, 46));
        m.signals.add("$A_DBB[17]", "#1001").unwrap();
        let text = to_toml(&m, Dialect::Fanuc);
        let (back, target) = from_toml(&text).unwrap();
        assert_eq!(target, Some(Dialect::Fanuc));
        assert_eq!(back, m);
        assert_eq!(to_toml(&back, Dialect::Fanuc), text);
    }

    #[test]
    fn variables_placed_differently_by_two_files_are_reported() {
        let mut m = BatchMaps::default();
        let used = |pairs: &[(&str, &str)]| Used {
            variables: pairs.iter().map(|(k, v)| (k.to_string(), v.to_string())).collect(),
            ..Used::default()
        };
        assert!(m.merge_used(&used(&[("#801", "R5"), ("O_9010.#24", "ARG_X")])).is_empty());
        assert!(m.merge_used(&used(&[("#801", "R5"), ("O_9011.#24", "ARG_X")])).is_empty());
        let c = m.merge_used(&used(&[("#801", "R6"), ("#802", "R5")]));
        assert_eq!(
            c,
            ["#801 is R5 in one file and R6 in another", "R5 stands for #801 in one file and for #802 in another"]
        );
    }

    #[test]
    fn map_file_errors_name_the_key() {
        let e = from_toml("[tools]\nDRILL = \"x\"\n").unwrap_err();
        assert!(e.contains("tools.DRILL"), "{e}");
        let e = from_toml("colour = 1\n").unwrap_err();
        assert!(e.contains("colour: unknown key") && e.contains("programs"), "{e}");
        let e = from_toml("[programs]\n\"O9010\" = \"9 BAD\"\n").unwrap_err();
        assert!(e.contains("programs.O9010"), "{e}");
    }

    #[test]
    fn the_pinned_maps_of_the_configuration_are_per_direction() {
        let mut c = Config::default();
        c.set_flag("programs.to_fanuc", "CONTOUR=9001").unwrap();
        c.set_flag("programs.to_sinumerik", "9010=PROBE_X").unwrap();
        c.set_flag("tools", "MILL=7").unwrap();
        let m = BatchMaps::from_config(&c, Dialect::Fanuc);
        assert_eq!(m.fanuc_numbers().get("CONTOUR"), Some(&9001));
        assert!(m.siemens_names().is_empty());
        assert_eq!(m.tools.get("MILL"), Some(&7));
        let m = BatchMaps::from_config(&c, Dialect::Sinumerik);
        assert_eq!(m.siemens_names().get(&9010).map(String::as_str), Some("PROBE_X"));
        assert!(m.fanuc_numbers().is_empty());
    }
}
