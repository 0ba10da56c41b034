//! `nctrans parse FILE`: the IR as a stable text dump, or with `--summary` one line
//! (programs, blocks, diagnostics); a large file's summary is read as a stream.

use super::args::{read_file, InputOpts};
use super::stream::{self, Source};
use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::span::SourceDb;
use nctrans::{diag, ir};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Runs `nctrans parse`.
pub fn parse(path: &PathBuf, from: Option<Dialect>, summary: bool, input: &InputOpts) -> ExitCode {
    if summary && stream::wanted(path, input) {
        if let Some(code) = parse_summary(path, from, input.encoding) {
            return code;
        }
    }
    let bytes = match read_file(path) {
        Ok(b) => b,
        Err(code) => return code,
    };
    let mut db = SourceDb::new();
    let name = path.display().to_string();
    let loaded = nctrans::load(&mut db, &name, &bytes, input.encoding);
    let dialect = from.unwrap_or_else(|| nctrans::detect_dialect(&name, &db.get(loaded.file).text));
    let sem = match super::profile::semantics(&mut db, path, dialect) {
        Ok(s) => s,
        Err(code) => return code,
    };
    let parsed = nctrans::parse(&db, loaded.file, dialect, &ParseOptions { semantics: sem });
    eprint!("{}", diag::render(&db, &parsed.diags));
    if diag::has_errors(&parsed.diags) {
        return ExitCode::from(1);
    }
    let text = if summary {
        format!(
            "{}: {} program(s), {} blocks, {} warning(s)\n",
            name,
            parsed.unit.programs.len(),
            ir::visit::count_blocks(&parsed.unit),
            parsed.diags.len()
        )
    } else {
        ir::dump::dump(&parsed.unit)
    };
    let mut out = std::io::stdout().lock();
    if out.write_all(text.as_bytes()).is_err() {
        return ExitCode::from(2);
    }
    ExitCode::SUCCESS
}

/// `nctrans parse --summary` streamed.
fn parse_summary(
    path: &Path,
    from: Option<Dialect>,
    forced: Option<&'static encoding_rs::Encoding>,
) -> Option<ExitCode> {
    let mut src = Source::new(path, forced)?;
    let ix = match stream::scan(&mut src, from, 0)? {
        Ok(ix) => ix,
        Err(code) => return Some(code),
    };
    let text = format!(
        "{}: {} program(s), {} blocks, {} warning(s)\n",
        path.display(),
        ix.programs.len(),
        ix.blocks,
        ix.diags.len()
    );
    Some(if std::io::stdout().lock().write_all(text.as_bytes()).is_err() {
        ExitCode::from(2)
    } else {
        ExitCode::SUCCESS
    })
}
