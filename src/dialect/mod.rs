//! The dialects: what is spelled differently lives here, one module per control with the
//! same small surface (`parse`, later `emit`), and the [`Semantics`] flags they share.
//!
//! Owns: reading (`<name>/parse`, the fast readers) and writing (`<name>/emit`) each dialect,
//! the [`Semantics`] flags, the description a dialect implements ([`spec::Spec`]; the
//! built-ins' are `translate::generic::builtin`), the block-number runs of an index
//! ([`runs`]), the program-less file check ([`empty`]), what the streamed fast writers read
//! of a plain word ([`plain`]) and the numbers they write from its digits (`digits`,
//! `numwrite`), the compact op of a constant-word block the fast readers write and the
//! evaluator runs (`lit`), and the tool offset map of a set-up (`offsets`). May use: `ir`,
//! `read`, `diag`, `span`; never `eval`, `lower`, `stream`, `check` (but the unit tests
//! build IR with `lower::build` and compare with `eval::value`; `tests/layering.rs`).

pub(crate) mod digits;
pub mod empty;
pub mod empty_call;
pub mod fanuc;
pub mod fixed;
pub mod limits;
pub mod lit;
pub(crate) mod numwrite;
pub mod offsets;
pub mod plain;
pub mod quick;
pub mod runs;
pub mod semantics;
pub mod signals;
pub mod sinumerik;
pub mod spec;

pub use crate::ir::Dialect;
pub use semantics::Semantics;
pub use spec::{Spec, Written};

use crate::diag::Diagnostic;
use crate::ir::Unit;
use crate::span::{FileId, SourceFile};

/// The dialect's names, its file extensions and the sniffing of a text are spelling, so they
/// are here; the type is the IR's (a unit records the dialect it was read from).
impl Dialect {
    pub fn name(self) -> &'static str {
        match self {
            Dialect::Sinumerik => "sinumerik",
            Dialect::Fanuc => "fanuc",
        }
    }

    /// Parses a dialect name as the CLI accepts it (`siemens` is an alias).
    pub fn from_name(s: &str) -> Option<Dialect> {
        match s.to_ascii_lowercase().as_str() {
            "sinumerik" | "siemens" => Some(Dialect::Sinumerik),
            "fanuc" => Some(Dialect::Fanuc),
            _ => None,
        }
    }

    /// The dialect a file extension implies: `.mpf/.spf` Siemens, `.nc/.tap` FANUC.
    pub fn from_extension(ext: &str) -> Option<Dialect> {
        match ext.to_ascii_lowercase().as_str() {
            "mpf" | "spf" => Some(Dialect::Sinumerik),
            "nc" | "tap" | "fnc" | "cnc" => Some(Dialect::Fanuc),
            _ => None,
        }
    }

    /// Guesses the dialect from the text when the extension does not tell: `#` variables,
    /// `O` numbers and `[ ]` expressions are FANUC; `R` parameters with `=`, `DEF`, `GOTOF`,
    /// `;` comments are Siemens.
    pub fn sniff(text: &str) -> Dialect {
        let (fanuc, siemens) = Dialect::sniff_scores(text);
        if fanuc > siemens {
            Dialect::Fanuc
        } else {
            Dialect::Sinumerik
        }
    }

    /// The scores [`Dialect::sniff`] compares: how FANUC and how Siemens `text` looks.
    pub fn sniff_scores(text: &str) -> (i32, i32) {
        let mut fanuc = 0i32;
        let mut siemens = 0i32;
        for line in text.lines().take(400) {
            let t = line.trim_start().to_ascii_uppercase();
            if t.starts_with('%') && t.contains("_N_") {
                siemens += 5;
            }
            if t.starts_with('O') && t[1..].chars().next().is_some_and(|c| c.is_ascii_digit()) {
                fanuc += 3;
            }
            fanuc += t.matches('#').count() as i32
                + t.matches("GOTO").filter(|_| !t.contains("GOTOF") && !t.contains("GOTOB")).count() as i32;
            siemens += ["DEF ", "GOTOF", "GOTOB", "ENDIF", "ENDWHILE", "PROC ", "MSG(", "==", "<>", "ENDFOR", "ENDLOOP"]
                .iter()
                .filter(|k| t.contains(*k))
                .count() as i32
                * 2;
            if t.contains(';') && !t.trim_end().ends_with(';') {
                siemens += 1;
            }
            if t.contains('R') && t.contains('=') && !t.contains('#') {
                siemens += 1;
            }
        }
        (fanuc, siemens)
    }
}

/// Options that change how programs are read.
#[derive(Clone, Debug)]
pub struct ParseOptions {
    pub semantics: Semantics,
}

impl ParseOptions {
    pub fn for_dialect(d: Dialect) -> Self {
        ParseOptions { semantics: Semantics::default_for(d) }
    }
}

/// The result of parsing one file: the unit (as much as could be read) and every
/// diagnostic. The unit is only meaningful for later phases when there is no error.
#[derive(Clone, Debug)]
pub struct Parsed {
    pub unit: Unit,
    pub diags: Vec<Diagnostic>,
    /// FANUC: the `O` numbers in the text after the closing `%` (not read, NC237), so a
    /// call of one can be told it is there but after the `%`.
    pub after_end_programs: Vec<u32>,
}

/// Parses one file in the given dialect.
/// A file that is binary data is rejected as a whole (NC101) before any grammar sees it.
pub fn parse(src: &SourceFile, file: FileId, dialect: Dialect, opts: &ParseOptions) -> Parsed {
    if let Some(at) = crate::read::binary_garbage(&src.text) {
        let end = src.text[at as usize..].chars().next().map_or(at, |c| at + c.len_utf8() as u32);
        let d = Diagnostic::error("NC101", "this file is binary data, not an NC program")
            .primary(file, crate::span::Span::new(at, end), "control character in program text")
            .note("NC programs are text; NUL bytes and control characters are not allowed")
            .hint("check that the right file was given, and that it was transferred in text mode");
        return Parsed { unit: Unit { dialect, file, programs: vec![] }, diags: vec![d], after_end_programs: vec![] };
    }
    let mut parsed = match dialect {
        Dialect::Sinumerik => sinumerik::parse(src, file, opts),
        Dialect::Fanuc => fanuc::parse(src, file, opts),
    };
    // A file that read without error but holds nothing to execute (NC145): said here, so
    // every command that reads a program says it the same way.
    if !crate::diag::has_errors(&parsed.diags) && crate::dialect::empty::program_less(&parsed.unit) {
        parsed.diags.push(crate::dialect::empty::diagnostic(file, &src.text));
    }
    parsed
}
