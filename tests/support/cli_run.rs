//! Running the nctrans binary from CLI tests: a fresh scratch folder, and one run's output.

use std::path::{Path, PathBuf};
use std::process::Command;

/// A new, empty folder in the temp folder for one test (`prefix` names the test file).
pub fn workdir(prefix: &str, name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("nctrans-{prefix}-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

/// Runs nctrans in `dir`: (stdout, stderr, exit code).
pub fn nctrans(dir: &Path, args: &[&str]) -> (String, String, i32) {
    let out = Command::new(env!("CARGO_BIN_EXE_nctrans")).current_dir(dir).args(args).output().expect("run nctrans");
    (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
        out.status.code().unwrap_or(-1),
    )
}
