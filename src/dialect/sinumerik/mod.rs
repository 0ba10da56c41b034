//! The sinumerik dialect: parsing (grammar/sinumerik.pest) into the IR.

pub mod emit;

use crate::diag::Diagnostic;
use crate::dialect::{Dialect, ParseOptions, Parsed};
use crate::ir::Unit;
use crate::span::{FileId, SourceFile, Span};

/// Parses one sinumerik file.
pub fn parse(src: &SourceFile, file: FileId, _opts: &ParseOptions) -> Parsed {
    let diags = vec![Diagnostic::error("NC100", "the sinumerik reader is being written").primary(
        file,
        Span::new(0, src.text.len().min(1) as u32),
        "not read",
    )];
    Parsed { unit: Unit { dialect: Dialect::Sinumerik, file, programs: vec![] }, diags }
}
