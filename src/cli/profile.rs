//! The control profile `run` and `parse` read a program with: the current folder's
//! `nctrans.toml` (its `[fanuc]` series, such as the Haas profile, and `[sinumerik]` machine
//! data), and for Siemens programs the library's definition files (global user data and
//! `DEFINE` macros, `nctrans::gud`), found as the translation finds them.

use nctrans::config::Config;
use nctrans::diag;
use nctrans::dialect::{Dialect, Semantics};
use nctrans::span::SourceDb;
use std::path::Path;
use std::process::ExitCode;

/// The project configuration: `nctrans.toml` of the current folder, else the defaults.
pub fn project() -> Result<Config, ExitCode> {
    let project = Path::new(nctrans::config::FILE_NAME);
    if !project.is_file() {
        return Ok(Config::default());
    }
    Config::load(project).map_err(|e| {
        eprintln!("error: {e}");
        ExitCode::from(2)
    })
}

/// The profile for reading and running `path` as `dialect`; the definition files' errors
/// are printed and stop the command.
pub fn semantics(db: &mut SourceDb, path: &Path, dialect: Dialect) -> Result<Semantics, ExitCode> {
    let config = project()?;
    match dialect {
        Dialect::Fanuc => Ok(config.fanuc_semantics()),
        Dialect::Sinumerik => sinumerik(&config, db, path),
    }
}

/// The Siemens profile of `config` for the program `path`, with the global user data and
/// `DEFINE` macros of its library's definition files (read into `db`): the one way every
/// command, whole or streamed, finds and loads them. Their errors are printed and stop the
/// command.
pub fn sinumerik(config: &Config, db: &mut SourceDb, path: &Path) -> Result<Semantics, ExitCode> {
    let mut sem = config.sinumerik_semantics();
    let gud = nctrans::gud::apply(&mut sem, db, path, None, &config.definitions);
    eprint!("{}", diag::render(db, &gud));
    if diag::has_errors(&gud) {
        return Err(ExitCode::from(1));
    }
    Ok(sem)
}

/// [`semantics`] for a streamed command: the definition files are read into a database of
/// their own (a streamed file's ids are its index's), so only the profile comes back.
pub fn streamed(path: &Path, dialect: Dialect) -> Result<Semantics, ExitCode> {
    semantics(&mut SourceDb::new(), path, dialect)
}
