//! Atomic output: every file is written whole to a staging folder inside the output folder,
//! flushed to disk, then renamed into place, so a killed run never leaves a partial output
//! file. Existing outputs are kept unless `--force`; an input is never written, even with it.

use crate::same_file::FileKey;
use std::collections::HashSet;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// The staging folder, inside the output folder so the rename stays on one file system.
/// Hidden, so discovery never reads it; removed at the end of a run, and at the start of the
/// next one when a killed run left it behind.
pub const STAGING: &str = ".nctrans-tmp";

/// The staging folder of the output folder `root`.
pub fn staging_dir(root: &Path) -> PathBuf {
    root.join(STAGING)
}

/// Where a job writes a streamed output of input file `index` itself (see
/// `FileOutcome::staged`): in the staging folder, under a name [`Writer::stage`] never uses.
pub fn staged_path(root: &Path, index: usize) -> PathBuf {
    staging_dir(root).join(format!("stream-{index}.part"))
}

/// Why an output was not written.
#[derive(Clone, Debug, PartialEq)]
pub enum WriteError {
    /// The file exists and `--force` was not given.
    Exists(PathBuf),
    /// The path is one of the batch's inputs.
    IsInput(PathBuf),
    /// The path leaves the output folder (`..`, absolute) — a bug in the caller.
    Outside(PathBuf),
    Io(PathBuf, String),
}

impl WriteError {
    /// The diagnostic code in reports.
    pub fn code(&self) -> &'static str {
        match self {
            WriteError::Exists(_) => "NC601",
            WriteError::IsInput(_) | WriteError::Outside(_) => "NC602",
            WriteError::Io(..) => "NC603",
        }
    }

    pub fn message(&self) -> String {
        match self {
            WriteError::Exists(p) => {
                format!("{} exists already; not overwritten (give --force to replace it)", p.display())
            }
            WriteError::IsInput(p) => format!("{} is an input of this batch; inputs are never written", p.display()),
            WriteError::Outside(p) => format!("{} would be written outside the output folder", p.display()),
            WriteError::Io(p, e) => format!("cannot write {}: {e}", p.display()),
        }
    }
}

/// A complete file in the staging folder, waiting for [`Writer::commit`].
#[derive(Debug)]
pub struct Staged(PathBuf);

/// Writes the outputs of one batch.
pub struct Writer {
    root: PathBuf,
    staging: PathBuf,
    force: bool,
    inputs: HashSet<FileKey>,
    counter: AtomicU64,
}

impl Writer {
    /// Creates the output folder and the staging folder. `inputs` are the batch's input files
    /// (they are never overwritten). Returns the writer and whether a stale staging folder
    /// of a killed run was removed.
    pub fn new(root: &Path, force: bool, inputs: &[PathBuf]) -> std::io::Result<(Writer, bool)> {
        std::fs::create_dir_all(root)?;
        let staging = staging_dir(root);
        let stale = staging.exists();
        if stale {
            std::fs::remove_dir_all(&staging)?;
        }
        std::fs::create_dir_all(&staging)?;
        let inputs = inputs.iter().filter_map(|p| FileKey::of(p)).collect();
        Ok((Writer { root: root.to_path_buf(), staging, force, inputs, counter: AtomicU64::new(0) }, stale))
    }

    /// The output folder.
    pub fn root(&self) -> &Path {
        &self.root
    }

    /// The final path of `rel`, or why it may not be written.
    pub fn check(&self, rel: &Path) -> Result<PathBuf, WriteError> {
        if rel.is_absolute() || rel.components().any(|c| !matches!(c, std::path::Component::Normal(_))) {
            return Err(WriteError::Outside(rel.to_path_buf()));
        }
        let path = self.root.join(rel);
        // The same file by identity: another spelling, a symbolic or a hard link of an input.
        if FileKey::of(&path).is_some_and(|k| self.inputs.contains(&k)) {
            return Err(WriteError::IsInput(rel.to_path_buf()));
        }
        if !self.force && std::fs::symlink_metadata(&path).is_ok() {
            return Err(WriteError::Exists(rel.to_path_buf()));
        }
        Ok(path)
    }

    /// Writes `bytes` to a new file in the staging folder and flushes it to disk. Safe to
    /// call from several threads; the file is not visible in the output until [`commit`].
    ///
    /// [`commit`]: Writer::commit
    pub fn stage(&self, bytes: &[u8]) -> std::io::Result<Staged> {
        let n = self.counter.fetch_add(1, Ordering::Relaxed);
        let tmp = self.staging.join(format!("{n}.part"));
        let result = (|| {
            let mut f = std::fs::OpenOptions::new().write(true).create_new(true).open(&tmp)?;
            f.write_all(bytes)?;
            // On disk before the rename: after a power cut the file is the old one or the new
            // one, never a truncated one.
            f.sync_data()
        })();
        match result {
            Ok(()) => Ok(Staged(tmp)),
            Err(e) => {
                let _ = std::fs::remove_file(&tmp);
                Err(e)
            }
        }
    }

    /// Takes a file a job wrote (and flushed to disk) into the staging folder itself as a
    /// staged file; anything outside the staging folder is refused.
    pub fn adopt(&self, path: &Path) -> std::io::Result<Staged> {
        if path.parent() != Some(self.staging.as_path()) || !path.is_file() {
            return Err(std::io::Error::other(format!("{} is not a staged file", path.display())));
        }
        Ok(Staged(path.to_path_buf()))
    }

    /// Moves a staged file to `rel` (relative to the output folder): one rename, atomic.
    pub fn commit(&self, staged: Staged, rel: &Path) -> Result<(), WriteError> {
        let path = match self.check(rel) {
            Ok(p) => p,
            Err(e) => {
                self.discard(staged);
                return Err(e);
            }
        };
        let io = |e: std::io::Error| WriteError::Io(rel.to_path_buf(), e.to_string());
        let result =
            path.parent().map_or(Ok(()), std::fs::create_dir_all).and_then(|_| std::fs::rename(&staged.0, &path));
        if result.is_err() {
            self.discard(staged);
        }
        result.map_err(io)
    }

    /// Drops a staged file that will not be committed.
    pub fn discard(&self, staged: Staged) {
        let _ = std::fs::remove_file(&staged.0);
    }

    /// Writes `bytes` to `rel` atomically (stage, then commit).
    pub fn write(&self, rel: &Path, bytes: &[u8]) -> Result<(), WriteError> {
        self.check(rel)?;
        let staged = self.stage(bytes).map_err(|e| WriteError::Io(rel.to_path_buf(), e.to_string()))?;
        self.commit(staged, rel)
    }

    /// Removes the staging folder (empty unless a write failed half-way).
    pub fn finish(self) -> std::io::Result<()> {
        std::fs::remove_dir_all(&self.staging)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("nctrans-write-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        d
    }

    #[test]
    fn writes_refuses_existing_unless_forced_and_never_inputs() {
        let root = dir("a");
        let input = root.join("in.nc");
        std::fs::create_dir_all(&root).unwrap();
        std::fs::write(&input, "O1\n").unwrap();
        let (w, stale) = Writer::new(&root, false, std::slice::from_ref(&input)).unwrap();
        assert!(!stale);
        w.write(Path::new("sub/a.nc"), b"%\nO1\n%\n").unwrap();
        assert_eq!(std::fs::read(root.join("sub/a.nc")).unwrap(), b"%\nO1\n%\n");
        assert_eq!(w.write(Path::new("sub/a.nc"), b"x"), Err(WriteError::Exists("sub/a.nc".into())));
        assert!(matches!(w.write(Path::new("../x.nc"), b"x"), Err(WriteError::Outside(_))));
        w.finish().unwrap();
        let (w, _) = Writer::new(&root, true, std::slice::from_ref(&input)).unwrap();
        w.write(Path::new("sub/a.nc"), b"new").unwrap();
        assert_eq!(std::fs::read(root.join("sub/a.nc")).unwrap(), b"new");
        assert!(matches!(w.write(Path::new("in.nc"), b"x"), Err(WriteError::IsInput(_))));
        // A hard link of an input is the input, even with --force.
        #[cfg(unix)]
        {
            std::fs::hard_link(&input, root.join("link.nc")).unwrap();
            assert!(matches!(w.write(Path::new("link.nc"), b"x"), Err(WriteError::IsInput(_))));
        }
        assert_eq!(std::fs::read(&input).unwrap(), b"O1\n");
        w.finish().unwrap();
        assert!(!root.join(STAGING).exists());
        std::fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn a_stale_staging_folder_is_cleared() {
        let root = dir("b");
        std::fs::create_dir_all(root.join(STAGING)).unwrap();
        std::fs::write(root.join(STAGING).join("0.part"), "half").unwrap();
        let (w, stale) = Writer::new(&root, false, &[]).unwrap();
        assert!(stale);
        assert!(!root.join(STAGING).join("0.part").exists());
        w.finish().unwrap();
        std::fs::remove_dir_all(&root).unwrap();
    }
}
