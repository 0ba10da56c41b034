//! `nctrans init [PATH]`: writes the commented project configuration (`nctrans.toml`) with
//! every key at its default.

use super::args::fail;
use nctrans::config;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// `nctrans init [PATH]`: writes the commented configuration; never overwrites one.
pub fn init(path: Option<&Path>) -> ExitCode {
    let path = path.map_or_else(|| PathBuf::from(config::FILE_NAME), Path::to_path_buf);
    let file = std::fs::OpenOptions::new().write(true).create_new(true).open(&path);
    match file.and_then(|mut f| f.write_all(config::TEMPLATE.as_bytes())) {
        Ok(()) => {
            eprintln!("wrote {}", path.display());
            ExitCode::SUCCESS
        }
        Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {
            fail(format!("{} exists already; not overwritten", path.display()))
        }
        Err(e) => fail(format!("cannot write {}: {e}", path.display())),
    }
}
