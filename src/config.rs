//! The project configuration `nctrans.toml`: the target control profiles, the variable,
//! tool and program maps, the unsupported policy, comment and output handling, and the batch
//! settings. Every command-line flag has a key here and goes through the same checks
//! ([`Config::set`]), so flags win and a wrong value reads the same from either place: the
//! error names the key and the allowed values. `nctrans init` writes [`TEMPLATE`].

use crate::dialect::{Dialect, Semantics};
use crate::translate::library::ProgKey;
use std::collections::BTreeMap;
use std::path::PathBuf;

mod tables;
pub use tables::{program_table, string_list, tool_table};

/// The configuration file name looked for in the current folder.
pub const FILE_NAME: &str = "nctrans.toml";

/// FANUC series accepted by `fanuc.series`; the 30i class takes 8-digit program numbers.
/// `haas` and `haas-ngc` are Haas controls read as FANUC with their own forms (M97).
pub const SERIES: [&str; 12] =
    ["0i", "0i-F", "15i", "16i", "18i", "21i", "30i", "31i", "32i", "0i-F Plus", "haas", "haas-ngc"];

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Unsupported {
    Error,
    Warn,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Comments {
    Keep,
    Ascii,
    Drop,
}

/// How output line ends are chosen.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LineEnds {
    /// Like the input file.
    Keep,
    Lf,
    CrLf,
    Cr,
}

/// The FANUC control profile.
#[derive(Clone, Debug, PartialEq)]
pub struct FanucProfile {
    pub series: String,
    /// Least input increment in mm: IS-A 0.01, IS-B 0.001, IS-C 0.0001.
    pub increment: &'static str,
    /// Parameter 3401#0 DPI: calculator-type input (`X10` = 10 mm).
    pub calculator_input: bool,
    /// Parameter 6004#0 NAT.
    pub nat: bool,
    /// The control accepts `[[a] AND [b]]` in IF and WHILE.
    pub compound_conditions: bool,
    /// Parameter 5114: the return amount d of G73 (mm), for `run --expand-cycles`.
    pub g73_return: f64,
    /// Parameter 5115: the clearance d of G83 (mm), for `run --expand-cycles`.
    pub g83_clearance: f64,
    /// The machine has the custom macro interrupt (M96/M97, `Semantics::macro_interrupt`).
    pub macro_interrupt: bool,
}

impl FanucProfile {
    /// Largest program number the series accepts (4 digits; 8 on the 30i class).
    pub fn max_program_number(&self) -> u32 {
        if ["30i", "31i", "32i"].contains(&self.series.as_str()) {
            99_999_999
        } else {
            9999
        }
    }
}

/// The whole configuration. `Default` is what `nctrans init` writes.
#[derive(Clone, Debug, PartialEq)]
pub struct Config {
    /// The dialect written (`--to`).
    pub to: Option<Dialect>,
    pub fanuc: FanucProfile,
    /// Siemens MD28050: number of R parameters.
    pub r_parameters: u32,
    /// Siemens MD20270: the edge a tool change without D selects (`None`: not stated).
    pub cutting_edge_default: Option<u32>,
    /// `[offsets]`: the FANUC H and D registers of Siemens cutting edges.
    pub offsets: crate::dialect::offsets::OffsetMap,
    /// `[signals]`: the FANUC interface signal of each Siemens PLC datum or NCK input/output.
    pub signals: crate::dialect::signals::SignalMap,
    /// CYCLE83 chip breaking (VARI 0): the retract after each infeed (`_VRT`'s default), mm.
    pub cycle83_retract: f64,
    /// CYCLE83 chip removal (VARI 1): the anticipation distance above the last depth, mm.
    pub cycle83_clearance: f64,
    /// The file FANUC DPRNT lines go to as Siemens `WRITE` (`[sinumerik] write_file`).
    pub write_file: String,
    /// Siemens definition files (`.DEF`, global user data) for every program; empty: the
    /// `.DEF` files nearest each program (`crate::gud::discover`).
    pub definitions: Vec<PathBuf>,
    /// `--var-map` rules for Sinumerik → FANUC (`R0-R99=#100`).
    pub var_map_to_fanuc: Vec<String>,
    /// `--var-map` rules for FANUC → Sinumerik (`#500-#599=R100`).
    pub var_map_to_sinumerik: Vec<String>,
    /// `[variables] fixed`, `--fixed NAME=VALUE`: Siemens STRING global user data the
    /// machine's set-up fixes (`AXIS_HORI = "Z"`), upper-case names (`Semantics::fixed`).
    pub fixed: BTreeMap<String, String>,
    /// `--tool-map NAME=n`.
    pub tools: BTreeMap<String, u32>,
    /// `--program-map NAME=9001` (Sinumerik → FANUC).
    pub programs_to_fanuc: BTreeMap<ProgKey, ProgKey>,
    /// `--program-map 9010=PROBE_X` (FANUC → Sinumerik).
    pub programs_to_sinumerik: BTreeMap<ProgKey, ProgKey>,
    /// `--l-numbers` (Sinumerik → FANUC): a program named `L<k>` is FANUC `O<k>`, so a call
    /// of a name built at run time (`CALL "L"<<R1`) is `G65 P#n`.
    pub l_numbers: bool,
    pub unsupported: Unsupported,
    pub comments: Comments,
    /// `--number-blocks k` (0: off).
    pub number_blocks: u32,
    /// `--specialise-callers` (FANUC → Sinumerik): write each macro for the calls seen only.
    pub specialise_callers: bool,
    /// `--program-number n` (single-file translation to FANUC).
    pub program_number: Option<u32>,
    /// `--encoding`: input encoding (`None`: detect).
    pub input_encoding: Option<&'static encoding_rs::Encoding>,
    /// Output encoding (`None`: like the input).
    pub output_encoding: Option<&'static encoding_rs::Encoding>,
    pub line_ends: LineEnds,
    /// `-o`.
    pub output: Option<PathBuf>,
    /// `-j` (0: the number of cores).
    pub jobs: usize,
    pub force: bool,
    /// `--no-verify` sets false.
    pub verify: bool,
    pub report: Option<PathBuf>,
    /// `--map`.
    pub map: Option<PathBuf>,
    pub max_steps: u64,
    /// `--set VAR=VALUE`.
    pub set: Vec<String>,
}

impl Default for Config {
    fn default() -> Self {
        Config {
            to: None,
            fanuc: FanucProfile {
                series: "0i-F".into(),
                increment: "IS-B",
                calculator_input: false,
                nat: false,
                compound_conditions: false,
                g73_return: 0.6,
                g83_clearance: 0.25,
                macro_interrupt: false,
            },
            r_parameters: 300,
            cutting_edge_default: None,
            offsets: Default::default(),
            signals: Default::default(),
            cycle83_retract: 1.0,
            cycle83_clearance: 0.6,
            write_file: crate::dialect::semantics::DEFAULT_WRITE_FILE.into(),
            definitions: vec![],
            var_map_to_fanuc: vec![],
            var_map_to_sinumerik: vec![],
            fixed: BTreeMap::new(),
            tools: BTreeMap::new(),
            programs_to_fanuc: BTreeMap::new(),
            programs_to_sinumerik: BTreeMap::new(),
            l_numbers: false,
            unsupported: Unsupported::Error,
            comments: Comments::Keep,
            number_blocks: 0,
            specialise_callers: false,
            program_number: None,
            input_encoding: None,
            output_encoding: None,
            line_ends: LineEnds::Keep,
            output: None,
            jobs: 0,
            force: false,
            verify: true,
            report: None,
            map: None,
            max_steps: 10_000_000,
            set: vec![],
        }
    }
}

/// The keys, the flag each one stands for (`-` where the key has no flag yet: profile keys,
/// output encoding and line ends, `verify.set` outside `run`/`check`), and what it takes.
pub const KEYS: [(&str, &str, &str); 40] = [
    ("to", "--to", "\"fanuc\" or \"sinumerik\" (alias \"siemens\")"),
    ("fanuc.series", "-", "one of 0i, 0i-F, 0i-F Plus, 15i, 16i, 18i, 21i, 30i, 31i, 32i, haas, haas-ngc"),
    ("fanuc.increment", "-", "\"IS-A\", \"IS-B\" or \"IS-C\""),
    ("fanuc.decimal_point", "-", "\"increment\" (X10 = 10 increments) or \"calculator\" (X10 = 10 mm)"),
    ("fanuc.nat", "-", "true or false"),
    ("fanuc.compound_conditions", "--compound-conditions", "true or false"),
    ("fanuc.g73_return", "-", "a length in mm from 0 to 100 (parameter 5114)"),
    ("fanuc.g83_clearance", "-", "a length in mm from 0 to 100 (parameter 5115)"),
    ("fanuc.macro_interrupt", "-", "true or false (the custom macro interrupt M96/M97 is set up)"),
    ("sinumerik.r_parameters", "-", "a number from 1 to 32535"),
    ("sinumerik.cycle83_retract", "-", "a length in mm from 0 to 100"),
    ("sinumerik.cycle83_clearance", "-", "a length in mm from 0 to 100"),
    (
        "sinumerik.write_file",
        "-",
        "the file name FANUC DPRNT lines are written to by Siemens WRITE (letters, digits, _)",
    ),
    ("sinumerik.cutting_edge_default", "-", "the edge a tool change without D selects, 0 to 9 (MD20270)"),
    ("offsets", "-", "a table of \"T.D\" = \"Hh,Dd\" (FANUC registers of a Siemens cutting edge)"),
    (
        "signals",
        "-",
        "a table of \"$A_DBB[2]\" = \"#1002\" (the FANUC interface signal of a Siemens PLC datum or NCK input/output)",
    ),
    ("sinumerik.definitions", "-", "a list of definition file paths like [\"DEF/MGUD.DEF\"]"),
    ("variables.to_fanuc", "--var-map", "a list of rules like [\"R0-R99=#100\", \"COUNT=#150\"]"),
    ("variables.to_sinumerik", "--var-map", "a list of rules like [\"#500-#599=R100\"]"),
    (
        "variables.fixed",
        "--fixed",
        "a table of NAME = \"text\" (STRING global user data the set-up fixes, like AXIS_HORI = \"Z\")",
    ),
    ("tools", "--tool-map", "a table of \"TOOL NAME\" = T number"),
    ("programs.l_numbers", "--l-numbers", "true or false"),
    ("programs.to_fanuc", "--program-map", "a table of \"SIEMENS_NAME\" = O number"),
    ("programs.to_sinumerik", "--program-map", "a table of \"O9010\" = \"SIEMENS_NAME\""),
    ("translate.unsupported", "--unsupported", "\"error\" or \"warn\""),
    ("translate.comments", "--comments", "\"keep\", \"ascii\" or \"drop\""),
    ("translate.number_blocks", "--number-blocks", "a step from 0 (off) to 1000"),
    ("translate.specialise_callers", "--specialise-callers", "true or false"),
    ("translate.program_number", "--program-number", "an O number from 1 to 99999999"),
    ("input.encoding", "--encoding", "\"auto\" or an encoding label (utf-8, gbk, shift_jis, windows-1250, …)"),
    ("output.encoding", "-", "\"keep\" or an encoding label (utf-8, gbk, …)"),
    ("output.line_ending", "-", "\"keep\", \"lf\", \"crlf\" or \"cr\""),
    ("batch.output", "-o", "a folder path"),
    ("batch.jobs", "-j", "a number of threads, 0 for the number of cores"),
    ("batch.force", "--force", "true or false"),
    ("batch.verify", "--no-verify", "true or false"),
    ("batch.report", "--report", "a file path ending in .json or .csv"),
    ("batch.map", "--map", "a map file path (nctrans-map.toml)"),
    ("verify.max_steps", "--max-steps", "a number of blocks from 1 up"),
    ("verify.set", "-", "a list like [\"R1=5\", \"#24=10.\"]"),
];

fn allowed(key: &str) -> &'static str {
    KEYS.iter().find(|k| k.0 == key).map_or("", |k| k.2)
}

fn bad(key: &str, got: &toml::Value) -> String {
    format!("{key}: {got} is not allowed (allowed: {})", allowed(key))
}

fn as_str<'a>(key: &str, v: &'a toml::Value) -> Result<&'a str, String> {
    v.as_str().ok_or_else(|| bad(key, v))
}

fn as_bool(key: &str, v: &toml::Value) -> Result<bool, String> {
    v.as_bool().ok_or_else(|| bad(key, v))
}

fn as_int(key: &str, v: &toml::Value, lo: i64, hi: i64) -> Result<i64, String> {
    v.as_integer().filter(|n| (lo..=hi).contains(n)).ok_or_else(|| bad(key, v))
}

/// A retract amount: 0 to 100 mm, written as a float or an integer.
fn as_mm(key: &str, v: &toml::Value) -> Result<f64, String> {
    let x = v.as_float().or_else(|| v.as_integer().map(|n| n as f64));
    x.filter(|x| (0.0..=100.0).contains(x)).ok_or_else(|| bad(key, v))
}

fn one_of<T: Copy>(key: &str, v: &toml::Value, options: &[(&str, T)]) -> Result<T, String> {
    let s = as_str(key, v)?;
    options.iter().find(|(n, _)| n.eq_ignore_ascii_case(s)).map(|(_, t)| *t).ok_or_else(|| bad(key, v))
}

fn encoding(key: &str, v: &toml::Value, auto: &str) -> Result<Option<&'static encoding_rs::Encoding>, String> {
    let s = as_str(key, v)?;
    if s.eq_ignore_ascii_case(auto) {
        return Ok(None);
    }
    encoding_rs::Encoding::for_label(s.as_bytes()).map(Some).ok_or_else(|| bad(key, v))
}

fn list(key: &str, v: &toml::Value) -> Result<Vec<String>, String> {
    string_list(v, key).map_err(|_| bad(key, v))
}

impl Config {
    /// Reads `nctrans.toml` text over the defaults.
    pub fn from_toml(text: &str) -> Result<Config, String> {
        let table: toml::Table = text.parse().map_err(|e: toml::de::Error| e.to_string().trim_end().to_string())?;
        let mut c = Config::default();
        for (k, v) in &table {
            match (k.as_str(), v) {
                ("to" | "tools" | "offsets" | "signals", _) => c.set(k, v)?,
                (section, toml::Value::Table(t))
                    if KEYS.iter().any(|key| key.0.split_once('.').is_some_and(|(s, _)| s == section)) =>
                {
                    for (sub, val) in t {
                        let full = format!("{section}.{sub}");
                        if !KEYS.iter().any(|key| key.0 == full) {
                            let names: Vec<&str> =
                                KEYS.iter().filter_map(|key| key.0.strip_prefix(&format!("{section}."))).collect();
                            return Err(format!("{full}: unknown key (allowed in [{section}]: {})", names.join(", ")));
                        }
                        c.set(&full, val)?;
                    }
                }
                _ if KEYS.iter().any(|key| key.0.starts_with(&format!("{k}."))) => {
                    return Err(format!("{k}: expected a [{k}] table"));
                }
                _ => {
                    let sections: Vec<&str> = {
                        let mut s: Vec<&str> =
                            KEYS.iter().map(|key| key.0.split('.').next().unwrap_or(key.0)).collect();
                        s.dedup();
                        s
                    };
                    return Err(format!("{k}: unknown key (allowed: {})", sections.join(", ")));
                }
            }
        }
        c.check_program_number()?;
        Ok(c)
    }

    /// Reads a configuration file.
    pub fn load(path: &std::path::Path) -> Result<Config, String> {
        let text = std::fs::read_to_string(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
        Config::from_toml(&text).map_err(|e| format!("{}: {e}", path.display()))
    }

    /// Sets one key, with the checks of the file. Table keys (`tools`, `programs.*`) and
    /// lists add to what is there, so repeated flags accumulate.
    pub fn set(&mut self, key: &str, v: &toml::Value) -> Result<(), String> {
        match key {
            "to" => {
                self.to = Some(Dialect::from_name(as_str(key, v)?).ok_or_else(|| bad(key, v))?);
            }
            "fanuc.series" => {
                let s = as_str(key, v)?;
                let found = SERIES.iter().find(|n| n.eq_ignore_ascii_case(s)).ok_or_else(|| bad(key, v))?;
                self.fanuc.series = (*found).to_string();
            }
            "fanuc.increment" => {
                self.fanuc.increment = one_of(key, v, &[("IS-A", "IS-A"), ("IS-B", "IS-B"), ("IS-C", "IS-C")])?;
            }
            "fanuc.decimal_point" => {
                self.fanuc.calculator_input = one_of(key, v, &[("increment", false), ("calculator", true)])?;
            }
            "fanuc.nat" => self.fanuc.nat = as_bool(key, v)?,
            "fanuc.compound_conditions" => self.fanuc.compound_conditions = as_bool(key, v)?,
            "sinumerik.r_parameters" => self.r_parameters = as_int(key, v, 1, 32535)? as u32,
            "sinumerik.cutting_edge_default" => self.cutting_edge_default = Some(as_int(key, v, 0, 9)? as u32),
            "offsets" => {
                let t = v.as_table().ok_or_else(|| bad(key, v))?;
                for (k, val) in t {
                    let text = as_str(&format!("offsets.{k}"), val)?;
                    let (edge, regs) = crate::dialect::offsets::OffsetMap::parse_entry(k, text)
                        .map_err(|e| format!("offsets.{k}: {e}"))?;
                    self.offsets.edges.insert(edge, regs);
                }
            }
            "signals" => {
                let m = crate::dialect::signals::SignalMap::table(key, v)?;
                for (k, f) in m.pairs {
                    self.signals.add(&k.key(), &f.key()).map_err(|e| format!("{key}: {e}"))?;
                }
            }
            "fanuc.g73_return" => self.fanuc.g73_return = as_mm(key, v)?,
            "fanuc.g83_clearance" => self.fanuc.g83_clearance = as_mm(key, v)?,
            "fanuc.macro_interrupt" => self.fanuc.macro_interrupt = as_bool(key, v)?,
            "sinumerik.cycle83_retract" => self.cycle83_retract = as_mm(key, v)?,
            "sinumerik.cycle83_clearance" => self.cycle83_clearance = as_mm(key, v)?,
            "sinumerik.write_file" => {
                let name = as_str(key, v)?;
                let ok = !name.is_empty()
                    && name.len() <= 24
                    && name.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_' || b == b'.');
                if !ok {
                    return Err(bad(key, v));
                }
                self.write_file = name.to_string();
            }
            "sinumerik.definitions" => self.definitions.extend(list(key, v)?.into_iter().map(PathBuf::from)),
            "variables.to_fanuc" => self.var_map_to_fanuc.extend(list(key, v)?),
            "variables.to_sinumerik" => self.var_map_to_sinumerik.extend(list(key, v)?),
            "variables.fixed" => self.fixed.extend(crate::dialect::fixed::table(key, v)?),
            "tools" => {
                let t = tool_table(v, key).map_err(|e| format!("{e} (allowed: {})", allowed(key)))?;
                self.tools.extend(t);
            }
            "programs.to_fanuc" | "programs.to_sinumerik" => {
                let d = if key == "programs.to_fanuc" { Dialect::Fanuc } else { Dialect::Sinumerik };
                let t = program_table(v, key, Some(d))?;
                for (k, target) in &t {
                    match (d, target) {
                        (Dialect::Fanuc, ProgKey::Number(n)) if *n <= self.fanuc.max_program_number() => {}
                        (Dialect::Fanuc, _) => {
                            return Err(format!(
                                "{key}.{k}: {target} is not a program number of a FANUC {} (1 to {})",
                                self.fanuc.series,
                                self.fanuc.max_program_number()
                            ))
                        }
                        (Dialect::Sinumerik, ProgKey::Name(_)) => {}
                        (Dialect::Sinumerik, _) => {
                            return Err(format!("{key}.{k}: expected a Siemens program name like \"PROBE_X\""))
                        }
                    }
                }
                let map =
                    if d == Dialect::Fanuc { &mut self.programs_to_fanuc } else { &mut self.programs_to_sinumerik };
                map.extend(t);
            }
            "programs.l_numbers" => self.l_numbers = as_bool(key, v)?,
            "translate.unsupported" => {
                self.unsupported = one_of(key, v, &[("error", Unsupported::Error), ("warn", Unsupported::Warn)])?;
            }
            "translate.comments" => {
                self.comments =
                    one_of(key, v, &[("keep", Comments::Keep), ("ascii", Comments::Ascii), ("drop", Comments::Drop)])?;
            }
            "translate.number_blocks" => self.number_blocks = as_int(key, v, 0, 1000)? as u32,
            "translate.specialise_callers" => self.specialise_callers = as_bool(key, v)?,
            "translate.program_number" => {
                // Checked against the series once the whole file is read (`check_program_number`).
                self.program_number = Some(as_int(key, v, 1, 99_999_999)? as u32);
            }
            "input.encoding" => self.input_encoding = encoding(key, v, "auto")?,
            "output.encoding" => self.output_encoding = encoding(key, v, "keep")?,
            "output.line_ending" => {
                self.line_ends = one_of(
                    key,
                    v,
                    &[("keep", LineEnds::Keep), ("lf", LineEnds::Lf), ("crlf", LineEnds::CrLf), ("cr", LineEnds::Cr)],
                )?;
            }
            "batch.output" => self.output = Some(PathBuf::from(as_str(key, v)?)),
            "batch.jobs" => self.jobs = as_int(key, v, 0, 1024)? as usize,
            "batch.force" => self.force = as_bool(key, v)?,
            "batch.verify" => self.verify = as_bool(key, v)?,
            "batch.report" => {
                let s = as_str(key, v)?;
                if !(s.ends_with(".json") || s.ends_with(".csv")) {
                    return Err(bad(key, v));
                }
                self.report = Some(PathBuf::from(s));
            }
            "batch.map" => self.map = Some(PathBuf::from(as_str(key, v)?)),
            "verify.max_steps" => self.max_steps = as_int(key, v, 1, i64::MAX)? as u64,
            "verify.set" => self.set.extend(list(key, v)?),
            _ => {
                let names: Vec<&str> = KEYS.iter().map(|k| k.0).collect();
                return Err(format!("{key}: unknown key (allowed: {})", names.join(", ")));
            }
        }
        Ok(())
    }

    /// The series decides how many digits an O number may have: a main program number
    /// beyond it is refused, naming the series. Checked after the whole file is read (the
    /// series may come after the number) and after the flags.
    pub fn check_program_number(&self) -> Result<(), String> {
        match self.program_number {
            Some(n) if n > self.fanuc.max_program_number() => Err(format!(
                "translate.program_number: O{n} has more digits than a FANUC {} program number takes \
                 (O1 to O{}); choose a smaller number, or set fanuc.series to the control's series",
                self.fanuc.series,
                self.fanuc.max_program_number()
            )),
            _ => Ok(()),
        }
    }

    /// Sets a key from a command-line flag's text: numbers and booleans are read as such,
    /// `NAME=VALUE` pairs fill tables, everything else is a string.
    pub fn set_flag(&mut self, key: &str, text: &str) -> Result<(), String> {
        let v = match key {
            "tools" | "programs.to_fanuc" | "programs.to_sinumerik" | "variables.fixed" => {
                let (k, val) = text
                    .split_once('=')
                    .ok_or_else(|| format!("{key}: '{text}': expected NAME=VALUE ({})", allowed(key)))?;
                let val = val.trim();
                let val = match val.parse::<i64>() {
                    Ok(n) if !matches!(key, "programs.to_sinumerik" | "variables.fixed") => toml::Value::Integer(n),
                    _ => toml::Value::String(val.to_string()),
                };
                let mut t = toml::Table::new();
                t.insert(k.trim().to_string(), val);
                toml::Value::Table(t)
            }
            "variables.to_fanuc" | "variables.to_sinumerik" | "verify.set" => toml::Value::Array(
                text.split(',')
                    .map(str::trim)
                    .filter(|s| !s.is_empty())
                    .map(|s| toml::Value::String(s.into()))
                    .collect(),
            ),
            _ => {
                if let Ok(n) = text.parse::<i64>() {
                    toml::Value::Integer(n)
                } else if let Ok(b) = text.parse::<bool>() {
                    toml::Value::Boolean(b)
                } else {
                    toml::Value::String(text.to_string())
                }
            }
        };
        self.set(key, &v)
    }

    /// The FANUC profile as evaluator semantics.
    pub fn fanuc_semantics(&self) -> Semantics {
        let mut s = Semantics::default_for(Dialect::Fanuc);
        s.least_increment_mm = match self.fanuc.increment {
            "IS-A" => 0.01,
            "IS-C" => 0.0001,
            _ => 0.001,
        };
        s.calculator_input = self.fanuc.calculator_input;
        s.nat = self.fanuc.nat;
        s.haas = self.fanuc.series.starts_with("haas");
        s.offsets = self.offsets.clone();
        s.haas_ngc = self.fanuc.series == "haas-ngc";
        s.macro_interrupt = self.fanuc.macro_interrupt && !s.haas;
        s.signals = std::sync::Arc::new(self.signals.clone());
        s
    }

    /// The Siemens profile as evaluator semantics.
    pub fn sinumerik_semantics(&self) -> Semantics {
        let mut s = Semantics::default_for(Dialect::Sinumerik);
        s.r_param_count = self.r_parameters;
        s.offsets = self.offsets.clone();
        s.cutting_edge_default = self.cutting_edge_default;
        s.write_file = self.write_file.clone();
        s.fixed = std::sync::Arc::new(self.fixed.clone());
        s.signals = std::sync::Arc::new(self.signals.clone());
        s
    }

    /// The retract amounts of the pecking cycles on a control of `dialect`, for
    /// `run --expand-cycles`.
    pub fn cycle_retracts(&self, dialect: Dialect) -> crate::eval::cycles::expand::Retracts {
        use crate::eval::cycles::expand::Retracts;
        match dialect {
            Dialect::Fanuc => Retracts { chip_break: self.fanuc.g73_return, peck_clearance: self.fanuc.g83_clearance },
            Dialect::Sinumerik => Retracts { chip_break: self.cycle83_retract, peck_clearance: self.cycle83_clearance },
        }
    }
}

/// Reads an offset map file (`--offset-map`): a TOML file whose only table is `[offsets]`,
/// read as the `[offsets]` of nctrans.toml.
pub fn load_offset_map(path: &std::path::Path) -> Result<crate::dialect::offsets::OffsetMap, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let at = |e: String| format!("{}: {e}", path.display());
    let table: toml::Table = text.parse().map_err(|e: toml::de::Error| at(e.to_string().trim_end().to_string()))?;
    if let Some(k) = table.keys().find(|k| *k != "offsets") {
        return Err(at(format!("{k}: unknown key (an offset map holds only an [offsets] table)")));
    }
    let v = table
        .get("offsets")
        .ok_or_else(|| at("no [offsets] table (expected like [offsets] \"6.2\" = \"H26,D46\")".into()))?;
    let mut c = Config::default();
    c.set("offsets", v).map_err(at)?;
    Ok(c.offsets)
}

/// What `nctrans init` writes: every key, commented, at its default.
pub const TEMPLATE: &str = r##"# nctrans.toml: the project configuration of nctrans (written by `nctrans init`).
# Every key has a command-line flag (named after it); a flag given on the command line wins.
# Values shown are the defaults. A wrong key or value is an error naming the key.

# The dialect written: "fanuc" or "sinumerik". (--to)
# to = "fanuc"

[fanuc]
# The FANUC control: 0i, 0i-F, 0i-F Plus, 15i, 16i, 18i, 21i, 30i, 31i, 32i.
# The 30i class takes 8-digit program numbers, the others 4.
series = "0i-F"
# Increment system: "IS-A" (0.01 mm), "IS-B" (0.001 mm), "IS-C" (0.0001 mm).
increment = "IS-B"
# Parameter 3401#0 DPI: "increment" (X10 means 10 increments) or "calculator" (X10 means 10 mm).
decimal_point = "increment"
# Parameter 6004#0 NAT: false gives ATAN 0..360 and ASIN 270..90.
nat = false
# The control accepts [[a] AND [b]] in IF and WHILE (newer controls; check the manual).
compound_conditions = false
# Drilling cycles, used by `nctrans run --expand-cycles` (machine data, not in the program):
# parameter 5114, the return amount d of G73 (high-speed peck) in mm;
g73_return = 0.6
# parameter 5115, the clearance d of G83 (peck) in mm: where the rapid back into the hole stops.
g83_clearance = 0.25
# The custom macro interrupt (M96 P… enables the interrupt program for the UINT signal,
# M97 disables it): true only where parameter 6003 and the wiring set it up on this machine.
macro_interrupt = false

[sinumerik]
# MD28050: the number of R parameters (828D: 300).
r_parameters = 300
# CYCLE83, used by `nctrans run --expand-cycles`: the chip-breaking retract (VARI 0) in mm,
cycle83_retract = 1.0
# and the anticipation distance above the last depth for chip removal (VARI 1) in mm.
cycle83_clearance = 0.6
# The file a FANUC DPRNT line goes to when translated to WRITE (FANUC prints to the I/O
# channel; WRITE appends the line to a file in the program's directory).
write_file = "NCTRANS_PRINT"
# MD20270: the cutting edge a tool change (M6) without D selects; `run` takes the factory 1
# (D1). Not stated, the Sinumerik -> FANUC translation refuses such a tool change (NC470).
# cutting_edge_default = 1
# Definition files with global user data (DEF NCK/CHAN ...), for every program. Empty: the
# .DEF files nearest each program (its folder or a DEF folder there, then the folder above).
definitions = []

[variables]
# Where variables go, as --var-map rules. Sinumerik -> FANUC defaults: R n -> #(500+n), DEF
# variables of main programs -> free commons from #100. FANUC -> Sinumerik: #100.. and #500..
# -> R parameters. Every rule is checked for collisions and range.
to_fanuc = []        # e.g. ["R0-R99=#100", "COUNT=#150"]
to_sinumerik = []    # e.g. ["#500-#599=R100"]
# STRING global user data the set-up fixes and no program writes (the axis letters of a .DEF
# file): runs start with them, a write is refused (NC544), to FANUC AXNAME(AXIS_HORI) is that
# letter, and every verdict names the values it assumed. (--fixed NAME=VALUE)
fixed = {}           # e.g. { AXIS_HORI = "Z", AXIS_VER = "X" }

[tools]
# Siemens tool names -> FANUC T numbers (--tool-map NAME=n). A name not listed is refused
# (NC301): nctrans never chooses a T number. The numbers used are written to nctrans-map.toml.
# "DRILL_5" = 12

[offsets]
# The FANUC registers of Siemens cutting edges, "T.D" = "Hh,Dd": edge D of tool T is length
# register H h and radius register D d. Unlisted: edge D1 of tool n is H n and D n (a tool
# listed here has only the edges given); any other register is refused (NC472).
# "6.2" = "H26,D46"

[signals]
# The machine's signal wiring: the FANUC custom macro interface signal the PMC connects to
# each Siemens PLC datum or NCK input/output the programs read. Inputs #1000..#1015 (one bit,
# read-only) and #1032 (all 16), outputs #1100..#1115 and #1132. A byte mapped to a bit is
# translated only where the program compares it with 0 or 1 (NC597). Unlisted: refused.
# "$A_DBB[2]" = "#1002"
# "$A_IN[1]" = "#1000"

[programs]
# Sinumerik -> FANUC: a program named L<k> (the DIN name: L and digits, no leading zero) is
# O<k>, so a call of a name built at run time, CALL "L"<<R1, is G65 P#n (--l-numbers).
# Off: such a call is refused (NC585).
l_numbers = false

[programs.to_fanuc]
# Siemens program names -> FANUC O numbers (--program-map NAME=9001). Unlisted: main
# programs from O0001 up, called programs from O9000 up, in name order.
# "CONTOUR" = 9001

[programs.to_sinumerik]
# FANUC O numbers -> Siemens program names (--program-map 9010=PROBE_X). Unlisted: a main
# program alone in its file keeps the file name, others are named O_9010 (Siemens names start with two letters or _).
# "O9010" = "PROBE_X"

[translate]
# A construct the target cannot express: "error" (no output), or "warn" (a visibly marked
# comment line stands in its place, and the file still fails). (--unsupported)
unsupported = "error"
# Comment text: "keep", "ascii" (transliterate), or "drop". (--comments)
comments = "keep"
# Number the output blocks N10, N20, ... with this step; 0 is off. (--number-blocks)
number_blocks = 0
# FANUC -> Sinumerik: write each macro only for the calls this run sees (an argument they all
# give is taken as set, and the macro's default for it is dropped). Off: every macro keeps
# its vacancy logic, right for any caller. (--specialise-callers)
specialise_callers = false
# O number of the main program of a single-file translation. (--program-number)
# program_number = 1

[input]
# "auto" detects each file's encoding (UTF-8, GBK, Shift-JIS, cp1250, ...). (--encoding)
encoding = "auto"

[output]
# "keep" writes each file in its input's encoding, or give a label like "utf-8".
encoding = "keep"
# "keep" (like each input), "lf", "crlf" or "cr".
line_ending = "keep"

[batch]
# Output folder of a batch (-o).
# output = "out"
# Worker threads; 0 is the number of cores. (-j)
jobs = 0
# Replace existing output files. (--force)
force = false
# Verify every translation by running both programs. (--no-verify sets false)
verify = true
# Write a per-file report, .json or .csv. (--report)
# report = "report.json"
# Read program, tool and variable names from an earlier run's map. (--map)
# map = "out/nctrans-map.toml"

[verify]
# Stop a run after this many blocks; the check is then inconclusive. (--max-steps)
max_steps = 10000000
# Variables set before each run, like --set. Called programs are also run with the
# arguments their callers pass.
set = []
"##;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_template_reads_back_as_the_defaults_and_names_every_key() {
        assert_eq!(Config::from_toml(TEMPLATE).unwrap(), Config::default());
        for (key, _, _) in KEYS {
            let last = key.rsplit('.').next().unwrap_or(key);
            assert!(TEMPLATE.contains(last), "template lacks {key}");
        }
    }

    #[test]
    fn values_are_read_and_flags_win() {
        let mut c = Config::from_toml(
            "to = \"siemens\"\n[fanuc]\nincrement = \"IS-C\"\nnat = true\n[tools]\nDRILL = 4\n[batch]\njobs = 3\n",
        )
        .unwrap();
        assert_eq!(c.to, Some(Dialect::Sinumerik));
        assert_eq!(c.fanuc_semantics().least_increment_mm, 0.0001);
        assert!(c.fanuc_semantics().nat);
        c.set_flag("batch.jobs", "1").unwrap();
        c.set_flag("tools", "MILL=7").unwrap();
        c.set_flag("programs.to_fanuc", "CONTOUR=9001").unwrap();
        c.set_flag("programs.to_sinumerik", "9010=PROBE_X").unwrap();
        assert_eq!(c.jobs, 1);
        assert_eq!(c.tools.get("MILL"), Some(&7));
        assert_eq!(c.tools.get("DRILL"), Some(&4));
        assert_eq!(c.programs_to_fanuc.get(&ProgKey::Name("CONTOUR".into())), Some(&ProgKey::Number(9001)));
        assert_eq!(c.programs_to_sinumerik.get(&ProgKey::Number(9010)), Some(&ProgKey::Name("PROBE_X".into())));
    }

    #[test]
    fn errors_name_the_key_and_the_allowed_values() {
        let e = Config::from_toml("[fanuc]\nincrement = \"IS-D\"\n").unwrap_err();
        assert_eq!(e, "fanuc.increment: \"IS-D\" is not allowed (allowed: \"IS-A\", \"IS-B\" or \"IS-C\")");
        let e = Config::from_toml("[fanuc]\nnatt = true\n").unwrap_err();
        assert!(e.starts_with("fanuc.natt: unknown key (allowed in [fanuc]: series, increment"), "{e}");
        let e = Config::from_toml("colour = 1\n").unwrap_err();
        assert!(e.starts_with("colour: unknown key (allowed: to, fanuc, sinumerik"), "{e}");
        let e = Config::from_toml("[translate]\nunsupported = \"ignore\"\n").unwrap_err();
        assert!(e.contains("translate.unsupported") && e.contains("\"error\" or \"warn\""), "{e}");
        let e = Config::from_toml("[programs.to_fanuc]\nCONTOUR = 123456\n").unwrap_err();
        assert!(e.contains("programs.to_fanuc.CONTOUR") && e.contains("1 to 9999"), "{e}");
        let mut c = Config::default();
        let e = c.set_flag("batch.jobs", "many").unwrap_err();
        assert!(e.starts_with("batch.jobs: \"many\" is not allowed"), "{e}");
        let e = Config::from_toml("fanuc = 3\n").unwrap_err();
        assert_eq!(e, "fanuc: expected a [fanuc] table");
        assert!(Config::from_toml("[batch]\nreport = \"r.txt\"\n").is_err());
    }
}
