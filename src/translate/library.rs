//! The library index: what every program of a set of files defines and calls (and with which
//! constant arguments), and which tool names it uses. A batch builds it over every file
//! before translation (reading the files: `batch::discover::scan`) and resolves calls
//! between files with it; the proof runs a called program with the argument vectors its
//! callers pass (`translate::called`), and a single file's translation builds one over the
//! file and its callees.

use crate::dialect::Dialect;
use crate::ir::*;
use std::collections::{BTreeMap, BTreeSet};
use std::fmt;

/// How programs are named across the library: a FANUC `O` number or a Siemens name.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum ProgKey {
    Number(u32),
    /// Upper case.
    Name(String),
}

impl fmt::Display for ProgKey {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ProgKey::Number(n) => write!(f, "O{n:04}"),
            ProgKey::Name(s) => f.write_str(s),
        }
    }
}

impl ProgKey {
    /// Reads `O9010`, `9010` (numbers) or a name.
    pub fn parse(s: &str) -> ProgKey {
        let t = s.trim();
        let digits = t.strip_prefix(['O', 'o']).unwrap_or(t);
        match digits.parse::<u32>() {
            Ok(n) if !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()) => ProgKey::Number(n),
            _ => ProgKey::Name(t.to_ascii_uppercase()),
        }
    }

    /// The k of a Siemens DIN subprogram name `L<k>` (what `--l-numbers` numbers it).
    pub fn l_number(&self) -> Option<u64> {
        match self {
            ProgKey::Name(n) => crate::translate::to_fanuc::numbers::l_number(n),
            ProgKey::Number(_) => None,
        }
    }
}

/// A constant argument of a call, as written: FANUC `A1.` (`#1`, point) or a Siemens
/// positional value resolved to the parameter name.
#[derive(Clone, Debug, PartialEq)]
pub struct ArgValue {
    /// `#1` … `#26` (FANUC) or the PROC parameter name (Siemens).
    pub var: String,
    pub value: f64,
    /// Written with a decimal point (FANUC's decimal-point rule applies to arguments).
    pub point: bool,
}

impl ArgValue {
    /// `#24=10.` / `LENGTH=5.5`, the `--set` spelling.
    pub fn to_set(&self) -> String {
        let mut v = format!("{}", self.value);
        if self.point && !v.contains('.') && !v.contains('e') {
            v.push('.');
        }
        format!("{}={v}", self.var)
    }
}

/// One call found in the library.
#[derive(Clone, Debug, PartialEq)]
pub struct CallSite {
    /// The calling file (index into the batch).
    pub file: usize,
    pub line: usize,
    pub target: ProgKey,
    pub kind: CallKind,
    /// The arguments when every one of them is a constant (else `None`).
    pub args: Option<Vec<ArgValue>>,
    /// The FANUC arguments given (not `#0`), in call order. Which arguments a macro receives,
    /// and which surely, decide its Siemens `PROC` parameters and is-set flags, whatever
    /// the values.
    pub given: Vec<Given>,
}

/// One FANUC argument of a call.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Given {
    pub letter: char,
    /// The local it fills (`#1`…`#33`, argument specification resolved).
    pub var: u8,
    /// The value can never be vacant (a constant, an expression), not `#5`.
    pub sure: bool,
}

/// One program defined in the library.
#[derive(Clone, Debug, PartialEq)]
pub struct ProgramInfo {
    pub key: ProgKey,
    /// The defining file (index into the batch) and the program's position in it.
    pub file: usize,
    pub position: usize,
    /// Siemens `PROC` parameter names, in order.
    pub params: Vec<String>,
}

/// What one file holds.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FileInfo {
    /// The dialect the file is read in (from its name, else from its content); `None` when
    /// the file could not be read.
    pub dialect: Option<Dialect>,
    /// Why the file could not be read.
    pub read_error: Option<String>,
    /// Parse errors found (the job reports them in full).
    pub parse_errors: usize,
    /// The programs, in file order (`None`: a program without name or number).
    pub programs: Vec<Option<ProgKey>>,
    /// A fingerprint of each program's text (blank lines and the spaces around lines left
    /// out), in the order of `programs`: copies of one program have the same.
    pub fingerprints: Vec<u64>,
    pub blocks: u64,
    /// Siemens tool names (`T="DRILL_5"`), as written.
    pub tools: BTreeSet<String>,
    /// FANUC common variables (`#100`..`#999`, the Haas NGC-only numbers) used by number.
    pub commons: BTreeSet<u32>,
    /// Read as a stream: a large program that calls nothing, or only by a constant name or
    /// number (FANUC: with subprograms after it; see `streamed::library_scan`),
    /// which its job then tries to translate as a stream too. Its `fingerprints` are not computed (0): a
    /// file whose program another file also defines is read whole instead.
    pub streamed: bool,
    /// A Siemens program of the file calls `"L"<<n` (a DIN subprogram named at run time).
    pub calls_built_l: bool,
}

/// The library: what every file defines and calls.
#[derive(Clone, Debug, Default)]
pub struct Library {
    pub files: Vec<FileInfo>,
    /// Every named program → where it is defined (the first file in batch order wins).
    pub programs: BTreeMap<ProgKey, ProgramInfo>,
    /// Programs defined more than once: key → the files after the first.
    pub duplicates: BTreeMap<ProgKey, Vec<usize>>,
    pub calls: Vec<CallSite>,
    /// Every FANUC common variable used anywhere, sorted.
    pub commons: BTreeSet<u32>,
    /// `--l-numbers` (`[programs] l_numbers`): a `CALL "L"<<n` may call every program `L<k>`
    /// of the library, so a file with one loads them all ([`Library::callee_files`]).
    pub l_numbers: bool,
}

/// The most argument vectors drawn from call sites for verifying one program alone.
pub const MAX_ARG_VECTORS: usize = 8;

impl Library {
    /// Builds the index from the scans of every file (in batch order).
    pub fn build(scans: Vec<Scan>) -> Library {
        let mut lib = Library::default();
        let mut raw_calls = Vec::new();
        for (i, scan) in scans.into_iter().enumerate() {
            for (pos, (key, params)) in scan.defined.into_iter().enumerate() {
                let Some(key) = key else { continue };
                if lib.programs.contains_key(&key) {
                    lib.duplicates.entry(key).or_default().push(i);
                } else {
                    lib.programs.insert(key.clone(), ProgramInfo { key, file: i, position: pos, params });
                }
            }
            raw_calls.extend(scan.calls.into_iter().map(|c| (i, c)));
            lib.commons.extend(scan.info.commons.iter().copied());
            lib.files.push(scan.info);
        }
        // Siemens positional arguments are named after the callee's parameters now that
        // every callee is known.
        for (file, c) in raw_calls {
            let args = c.args.map(|vals| {
                let params = lib.programs.get(&c.target).map(|p| p.params.clone()).unwrap_or_default();
                vals.into_iter()
                    .enumerate()
                    .filter_map(|(pos, a)| match a {
                        RawArg::Letter { var, value, point } => Some(ArgValue { var: format!("#{var}"), value, point }),
                        RawArg::Positional(Some((value, point))) => {
                            params.get(pos).map(|name| ArgValue { var: name.clone(), value, point })
                        }
                        RawArg::Positional(None) => None,
                    })
                    .collect()
            });
            lib.calls.push(CallSite { file, line: c.line, target: c.target, kind: c.kind, args, given: c.given });
        }
        lib
    }

    /// Whether the program `key` of `file` is the one calls in the library reach: the first
    /// definition, or a copy of it with the same text (as a Sinumerik → FANUC batch writes a
    /// subprogram into each caller's file).
    pub fn is_canonical(&self, key: &ProgKey, file: usize) -> bool {
        let Some(first) = self.programs.get(key) else { return false };
        if first.file == file {
            return true;
        }
        let print = |f: usize| {
            let info = self.files.get(f)?;
            let i = info.programs.iter().position(|p| p.as_ref() == Some(key))?;
            info.fingerprints.get(i).copied()
        };
        print(file).is_some() && print(file) == print(first.file)
    }

    /// Whether any file of the library calls the program.
    pub fn is_called(&self, key: &ProgKey) -> bool {
        self.calls.iter().any(|c| &c.target == key)
    }

    /// The files that hold the programs `file` calls, directly or through other programs
    /// (not `file` itself, nor for programs the calling file defines), in batch order. Calls to programs not in the library are left
    /// to the translator to report.
    pub fn callee_files(&self, file: usize) -> Vec<usize> {
        let mut seen = BTreeSet::new();
        let mut todo = vec![file];
        while let Some(f) = todo.pop() {
            if self.l_numbers && self.files.get(f).is_some_and(|i| i.calls_built_l) {
                for p in self.programs.values().filter(|p| p.key.l_number().is_some()) {
                    if p.file != file && seen.insert(p.file) {
                        todo.push(p.file);
                    }
                }
            }
            for c in self.calls.iter().filter(|c| c.file == f) {
                // A program of the calling file itself is found first (FANUC looks in the
                // file before the memory), even when the library holds another copy.
                if self.files.get(f).is_some_and(|i| i.programs.contains(&Some(c.target.clone()))) {
                    continue;
                }
                if let Some(p) = self.programs.get(&c.target) {
                    if p.file != file && seen.insert(p.file) {
                        todo.push(p.file);
                    }
                }
            }
        }
        seen.into_iter().collect()
    }

    /// The constant argument vectors the library calls `key` with (distinct, in batch
    /// order, at most [`MAX_ARG_VECTORS`]), for verifying the program alone.
    pub fn arg_vectors(&self, key: &ProgKey) -> Vec<Vec<ArgValue>> {
        let mut out: Vec<Vec<ArgValue>> = Vec::new();
        for c in self.calls.iter().filter(|c| &c.target == key) {
            if let Some(args) = &c.args {
                if !out.contains(args) {
                    out.push(args.clone());
                }
            }
            if out.len() == MAX_ARG_VECTORS {
                break;
            }
        }
        out
    }

    /// Every Siemens tool name used anywhere, sorted.
    pub fn tool_names(&self) -> BTreeSet<String> {
        self.files.iter().flat_map(|f| f.tools.iter().cloned()).collect()
    }
}

/// A call argument before the callee's parameter names are known.
#[derive(Clone, Debug, PartialEq)]
pub enum RawArg {
    Letter {
        var: u8,
        value: f64,
        point: bool,
    },
    /// `None`: omitted or not a constant.
    Positional(Option<(f64, bool)>),
}

#[derive(Clone, Debug, PartialEq)]
pub struct RawCall {
    pub line: usize,
    pub target: ProgKey,
    pub kind: CallKind,
    pub args: Option<Vec<RawArg>>,
    /// FANUC arguments given (see [`CallSite::given`]).
    pub given: Vec<Given>,
}

/// The result of reading one file for the index.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Scan {
    pub info: FileInfo,
    /// Per program in file order: its key and PROC parameter names.
    pub defined: Vec<(Option<ProgKey>, Vec<String>)>,
    pub calls: Vec<RawCall>,
}

/// What the index records of a parsed `unit` (its source `src`, a Siemens file's program
/// named by `stem` when it has one program without a name): also how a single file's
/// translation learns the calls among the programs it translates together
/// (`verify_called`). Parse errors are the caller's to count.
pub fn scan_unit(unit: &Unit, src: &crate::span::SourceFile, stem: &str) -> Scan {
    let dialect = unit.dialect;
    let stem = stem.to_string();
    let mut scan = Scan {
        info: FileInfo {
            dialect: Some(dialect),
            blocks: crate::ir::visit::count_blocks(unit) as u64,
            ..FileInfo::default()
        },
        ..Scan::default()
    };
    let single = unit.programs.len() == 1;
    scan.info.calls_built_l =
        dialect == Dialect::Sinumerik && crate::lower::to_fanuc::string_calls::calls_built_l(unit);
    for p in &unit.programs {
        let key = match (&p.name, dialect) {
            (Some(ProgName::Number(n)), _) => Some(ProgKey::Number(*n)),
            (Some(ProgName::Name(n)), _) => Some(ProgKey::Name(n.to_ascii_uppercase())),
            // Siemens finds a program by its file name.
            (None, Dialect::Sinumerik) if single && !stem.is_empty() => Some(ProgKey::Name(stem.clone())),
            (None, _) => None,
        };
        scan.info.programs.push(key.clone());
        scan.info.fingerprints.push(fingerprint(&program_text(&src.text, p)));
        if dialect == Dialect::Fanuc {
            scan.info.commons.extend(crate::translate::to_sinumerik::commons_of(p));
        }
        scan.defined.push((key, p.params.iter().map(|q| q.name.to_ascii_uppercase()).collect()));
        // A computed call whose target the translation knows (`#1=9004 … G65 P#1`, a STRING
        // holding one program name) calls that program: the library must load it.
        let resolved = match dialect {
            Dialect::Fanuc => crate::lower::to_sinumerik::indirect::resolve(p),
            Dialect::Sinumerik => crate::lower::to_fanuc::string_calls::resolve(p),
        };
        let p = resolved.as_ref().unwrap_or(p);
        walk_items(&p.body, &mut |item| match &item.kind {
            ItemKind::Call(c) => {
                let (line, _) = src.line_col(item.span.lo);
                scan.calls.extend(raw_call(c, line));
            }
            ItemKind::Word(w) if w.addr.is(b'T') => {
                if let WordValue::Expr(Expr { kind: ExprKind::Str(s), .. }) = &w.value {
                    scan.info.tools.insert(s.clone());
                }
            }
            _ => {}
        });
    }
    // A program name written into a STRING variable is a call target where the variable is
    // called through (`lower::to_fanuc::prog_vars`): its program belongs to the callees.
    if dialect == Dialect::Sinumerik {
        for name in crate::lower::to_fanuc::prog_vars::written_names(unit) {
            let c =
                Call { kind: crate::ir::CallKind::Named, target: CallTarget::Name(name), args: vec![], repeat: None };
            scan.calls.extend(raw_call(&c, 0));
        }
    }
    scan
}

/// What the index records of a call on `line` (1-based): `None` for a computed target.
pub fn raw_call(c: &Call, line: usize) -> Option<RawCall> {
    // Haas M97 runs a block of the same program: no program of the library is called.
    if c.kind == crate::ir::CallKind::M97 {
        return None;
    }
    let target = match &c.target {
        CallTarget::Number(n) => ProgKey::Number(*n),
        CallTarget::Name(s) => ProgKey::Name(s.to_ascii_uppercase()),
        CallTarget::Computed(_) => return None,
    };
    let args: Option<Vec<RawArg>> = c
        .args
        .iter()
        .map(|a| match a {
            Arg::Letter { var, value, .. } => {
                constant(value).map(|(value, point)| RawArg::Letter { var: *var, value, point })
            }
            Arg::Value(e) => constant(e).map(|v| RawArg::Positional(Some(v))),
            Arg::Omitted(_) => Some(RawArg::Positional(None)),
        })
        .collect();
    let given = c
        .args
        .iter()
        .filter_map(|a| match a {
            Arg::Letter { letter, var, value } if !matches!(value.kind, ExprKind::Vacant) => {
                Some(Given { letter: char::from(*letter).to_ascii_uppercase(), var: *var, sure: surely_set(value) })
            }
            _ => None,
        })
        .collect();
    Some(RawCall { line, target, kind: c.kind, args, given })
}

/// A program's text with blank lines, tape marks and the spaces around lines left out.
pub fn program_text(text: &str, p: &Program) -> String {
    let lo = (p.span.lo as usize).min(text.len());
    let hi = (p.span.hi as usize).clamp(lo, text.len());
    let slice = text.get(lo..hi).unwrap_or("");
    slice.lines().map(str::trim).filter(|l| !l.is_empty() && *l != "%").collect::<Vec<_>>().join("\n")
}

/// A fingerprint of a text, the same on every run of the same build.
fn fingerprint(text: &str) -> u64 {
    use std::hash::{Hash, Hasher};
    let mut h = std::collections::hash_map::DefaultHasher::new();
    text.hash(&mut h);
    h.finish()
}

/// Whether an argument value can never be vacant, judged from the call alone (the rule
/// the FANUC → Sinumerik vacancy analysis applies to macro arguments at entry).
fn surely_set(e: &Expr) -> bool {
    match &e.kind {
        ExprKind::Vacant => false,
        ExprKind::Unary(UnOp::Neg, a) => surely_set(a),
        ExprKind::Var(v) => match v.kind {
            VarKind::Hash(n) => !(n <= 33 || crate::dialect::fanuc::haas_vars::maybe_common(n)),
            VarKind::HashIndirect(_) => false,
            _ => true,
        },
        _ => true,
    }
}

/// A constant argument value and whether it had a decimal point.
fn constant(e: &Expr) -> Option<(f64, bool)> {
    match &e.kind {
        ExprKind::Num(n) => Some((n.value, n.point)),
        ExprKind::Unary(UnOp::Neg, inner) => constant(inner).map(|(v, p)| (-v, p)),
        _ => None,
    }
}

/// Calls `f` on every item of every block (and the statement of a FANUC `IF..THEN`).
pub fn walk_items(body: &[Stmt], f: &mut dyn FnMut(&Item)) {
    crate::ir::visit::walk_stmts(body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            for it in &b.items {
                f(it);
                if let ItemKind::IfThen { then, .. } = &it.kind {
                    f(then);
                }
                if let ItemKind::IfBlock { items, .. } = &it.kind {
                    items.iter().for_each(&mut *f);
                }
            }
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What `batch::discover::scan` gives for a file `name` holding `text`, without the file.
    fn scan_text(name: &str, text: &str) -> Scan {
        let mut db = crate::span::SourceDb::new();
        let loaded = crate::load(&mut db, name, text.as_bytes(), None);
        let dialect = crate::detect_dialect(name, text);
        let parsed = crate::parse(&db, loaded.file, dialect, &crate::dialect::ParseOptions::for_dialect(dialect));
        let stem = std::path::Path::new(name).file_stem().and_then(|s| s.to_str()).unwrap_or("").to_ascii_uppercase();
        scan_unit(&parsed.unit, db.get(loaded.file), &stem)
    }

    #[test]
    fn a_program_of_the_calling_file_is_found_before_a_copy_elsewhere() {
        let a = scan_text("a.nc", "%\nO1\nM98 P9000\nM30\nO9000\nG0 X1\nM99\n%\n");
        let b = scan_text("b.nc", "%\nO2\nM98 P9000\nM30\nO9000\nG0 X2\nM99\n%\n");
        let c = scan_text("c.nc", "%\nO3\nM98 P9000\nM30\n%\n");
        let d = scan_text("d.nc", "%\nO4\nM98 P9000\nM30\nO9000\n  G0 X1\n\nM99\n%\n");
        let lib = Library::build(vec![a, b, c, d]);
        let key = ProgKey::Number(9000);
        assert_eq!(lib.duplicates[&key], [1, 3]);
        assert!(lib.callee_files(1).is_empty(), "b.nc calls its own O9000");
        assert_eq!(lib.callee_files(2), [0], "c.nc reaches the first definition");
        assert!(lib.is_canonical(&key, 0));
        assert!(!lib.is_canonical(&key, 1), "another program of the same number");
        assert!(lib.is_canonical(&key, 3), "a copy (spacing aside) is the same program");
        assert!(!lib.is_canonical(&key, 2), "c.nc does not define it");
    }

    #[test]
    fn keys_parse_and_print() {
        assert_eq!(ProgKey::parse("O9010"), ProgKey::Number(9010));
        assert_eq!(ProgKey::parse("12"), ProgKey::Number(12));
        assert_eq!(ProgKey::parse("contour"), ProgKey::Name("CONTOUR".into()));
        assert_eq!(ProgKey::Number(12).to_string(), "O0012");
    }

    #[test]
    fn fanuc_calls_and_constant_arguments() {
        let s = scan_text("m.nc", "%\nO1000\nG65 P9010 A1. X-2 Y#1\nG65 P9010 A1. X-2\nM98 P9020\nM30\n%\n");
        assert_eq!(s.defined, [(Some(ProgKey::Number(1000)), vec![])]);
        assert_eq!(s.calls.len(), 3);
        assert_eq!(s.calls[0].args, None, "Y#1 is not a constant");
        assert_eq!(
            s.calls[1].args,
            Some(vec![
                RawArg::Letter { var: 1, value: 1.0, point: true },
                RawArg::Letter { var: 24, value: -2.0, point: false }
            ])
        );
        assert_eq!(s.calls[2].kind, CallKind::M98);
        assert_eq!(s.calls[1].line, 4);
    }

    #[test]
    fn siemens_names_params_tools_and_the_library() {
        let main = scan_text("part.mpf", "T=\"DRILL_5\" M6\nCONTOUR(5.5,,2)\nM30\n");
        let sub = scan_text("contour.spf", "PROC CONTOUR(REAL LEN, REAL WID, REAL DEP)\nG1 X=LEN\nM17\n");
        assert_eq!(main.defined[0].0, Some(ProgKey::Name("PART".into())));
        assert_eq!(main.info.tools.iter().collect::<Vec<_>>(), ["DRILL_5"]);
        let lib = Library::build(vec![sub, main]);
        let key = ProgKey::Name("CONTOUR".into());
        assert!(lib.is_called(&key));
        assert!(!lib.is_called(&ProgKey::Name("PART".into())));
        assert_eq!(lib.callee_files(1), [0]);
        let v = lib.arg_vectors(&key);
        assert_eq!(v.len(), 1);
        let sets: Vec<String> = v[0].iter().map(ArgValue::to_set).collect();
        assert_eq!(sets, ["LEN=5.5", "DEP=2"]);
    }
}
