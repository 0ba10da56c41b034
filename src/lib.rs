//! nctrans: translate CNC macro programs between Siemens Sinumerik and FANUC Macro B, and
//! prove each translation by running both in a bundled evaluator.
//!
//! The pipeline (see `docs/architecture.md`): `read` → `dialect::*::parse` (one block at a
//! time, then a structurer) → [`ir`] → passes → emit, behind the one entry
//! [`translate::translate`] → the proof ([`check`]). The library never prints; the command
//! line (`src/cli/`, in the binary) renders.

pub mod batch;
pub mod check;
pub mod config;
pub mod diag;
pub mod dialect;
pub mod eval;
pub mod excerpt;
pub mod gud;
pub mod ir;
pub mod lower;
pub mod read;
pub mod same_file;
pub mod span;
pub mod stream;
/// The deterministic generator the randomised tests share (unit and integration tests).
#[cfg(test)]
#[path = "../tests/support/rng.rs"]
mod test_rng;
pub mod translate;
pub mod unfinished;

use dialect::{Dialect, ParseOptions, Parsed};
use span::{FileId, SourceDb};

/// A file loaded into a [`SourceDb`], with what is needed to write output like it.
#[derive(Clone, Debug)]
pub struct Loaded {
    pub file: FileId,
    pub encoding: &'static encoding_rs::Encoding,
    pub bom: bool,
    pub line_ending: read::LineEnding,
}

/// Decodes `bytes` (see [`read::decode`]) and adds the text to `db` under `name`.
pub fn load(db: &mut SourceDb, name: &str, bytes: &[u8], encoding: Option<&'static encoding_rs::Encoding>) -> Loaded {
    let d = read::decode(bytes, encoding);
    let file = db.add(name, d.text);
    Loaded { file, encoding: d.encoding, bom: d.bom, line_ending: d.line_ending }
}

/// The dialect of a file: from its extension, else from its content.
pub fn detect_dialect(name: &str, text: &str) -> Dialect {
    std::path::Path::new(name)
        .extension()
        .and_then(|e| e.to_str())
        .and_then(Dialect::from_extension)
        .unwrap_or_else(|| Dialect::sniff(text))
}

/// Parses a loaded file.
pub fn parse(db: &SourceDb, file: FileId, dialect: Dialect, opts: &ParseOptions) -> Parsed {
    dialect::parse(db.get(file), file, dialect, opts)
}
