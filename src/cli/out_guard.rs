//! The output rules of the single-file translations (both directions, whole or streamed),
//! the same as a batch's writer: an output is never one of the inputs (the program, or a
//! subprogram read beside it), whatever path leads to it (another spelling, a symbolic or a
//! hard link), even with `--force`; and an existing file is replaced only with `--force`.
//! A device or FIFO (`-o /dev/null`) is written into, so it is never "existing".

use nctrans::batch::write::WriteError;
use nctrans::same_file;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Whether `out` may be written: `Err` (after printing why) when it is one of `inputs`, or
/// an existing file and not `force`. `flag` names the option that gave it (`-o`, `--report`).
pub fn check(out: &Path, inputs: &[PathBuf], force: bool, flag: &str) -> Result<(), ExitCode> {
    let refused = if let Some(input) = same_file::input_at(out, inputs) {
        let e = WriteError::IsInput(out.to_path_buf());
        let shown = if input == out { String::new() } else { format!(" (it is {})", input.display()) };
        Some((
            e.code(),
            format!(
                "{} is an input of this translation{shown}; inputs are never written, even with --force",
                out.display()
            ),
            format!("give {flag} another file"),
        ))
    } else if !force && std::fs::symlink_metadata(out).is_ok() && !super::stream::is_special(out) {
        let e = WriteError::Exists(out.to_path_buf());
        Some((e.code(), e.message(), format!("or give {flag} another file to keep it")))
    } else {
        None
    };
    match refused {
        Some((code, message, hint)) => {
            eprintln!("error[{code}]: {message}\n  = hint: {hint}");
            Err(ExitCode::from(2))
        }
        None => Ok(()),
    }
}

/// [`check`] on every file a translation's `-o` writes, before any is written.
pub fn check_all<'a>(
    outs: impl IntoIterator<Item = &'a Path>,
    inputs: &[PathBuf],
    force: bool,
) -> Result<(), ExitCode> {
    outs.into_iter().try_for_each(|o| check(o, inputs, force, "-o"))
}
