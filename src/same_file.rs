//! Whether two paths name one file, and whether one folder lies within another: what keeps
//! every command (a batch's writer, the single-file translations) from writing over an
//! input, whatever spelling, symbolic link or hard link leads to it.

use std::path::{Component, Path, PathBuf};

/// What makes a file itself: device and inode on Unix, so hard links are one file; the
/// canonical path elsewhere. Symbolic links are followed.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct FileKey(Key);

#[cfg(unix)]
type Key = (u64, u64);
#[cfg(not(unix))]
type Key = PathBuf;

impl FileKey {
    /// The key of the file `p` names; `None` when nothing is there.
    pub fn of(p: &Path) -> Option<FileKey> {
        #[cfg(unix)]
        {
            use std::os::unix::fs::MetadataExt;
            let m = std::fs::metadata(p).ok()?;
            Some(FileKey((m.dev(), m.ino())))
        }
        #[cfg(not(unix))]
        {
            p.canonicalize().ok().map(FileKey)
        }
    }
}

/// The first of `inputs` that is the same file as `out`, if any (none when `out` does not
/// exist: a new file is no input).
pub fn input_at<'a>(out: &Path, inputs: &'a [PathBuf]) -> Option<&'a Path> {
    let key = FileKey::of(out)?;
    inputs.iter().find(|i| FileKey::of(i).as_ref() == Some(&key)).map(PathBuf::as_path)
}

/// `p` as an absolute path with its symbolic links resolved, also when its last parts do
/// not exist yet (a folder a batch is about to create): the longest existing ancestor is
/// resolved and the rest appended.
pub fn resolved(p: &Path) -> Option<PathBuf> {
    let abs = if p.is_absolute() { p.to_path_buf() } else { std::env::current_dir().ok()?.join(p) };
    let mut rest = Vec::new();
    let mut base = abs.as_path();
    loop {
        if let Ok(c) = base.canonicalize() {
            let mut out = c;
            for part in rest.iter().rev() {
                match part {
                    // A missing folder is no link: `..` after it goes back lexically.
                    Component::ParentDir => {
                        out.pop();
                    }
                    Component::Normal(n) => out.push(n),
                    _ => {}
                }
            }
            return Some(out);
        }
        rest.push(base.components().next_back()?);
        base = base.parent()?;
    }
}

/// Whether folder `inner` is folder `outer` or lies inside it, once both are resolved.
pub fn within(inner: &Path, outer: &Path) -> bool {
    match (resolved(inner), resolved(outer)) {
        (Some(i), Some(o)) => i.starts_with(&o),
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("nctrans-same-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn spellings_and_links_of_an_input_are_the_input() {
        let d = dir("links");
        let input = d.join("same.MPF");
        std::fs::write(&input, "G1 X1\n").unwrap();
        std::fs::create_dir_all(d.join("sub")).unwrap();
        let inputs = vec![input.clone()];
        assert_eq!(input_at(&input, &inputs), Some(input.as_path()));
        assert!(input_at(&d.join("sub/../same.MPF"), &inputs).is_some());
        assert!(input_at(&d.join("new.nc"), &inputs).is_none());
        std::fs::write(d.join("other.nc"), "x").unwrap();
        assert!(input_at(&d.join("other.nc"), &inputs).is_none());
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink(&input, d.join("sym.MPF")).unwrap();
            std::fs::hard_link(&input, d.join("hard.MPF")).unwrap();
            assert!(input_at(&d.join("sym.MPF"), &inputs).is_some());
            assert!(input_at(&d.join("hard.MPF"), &inputs).is_some());
        }
        std::fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn folders_within_folders() {
        let d = dir("within");
        std::fs::create_dir_all(d.join("lib/a")).unwrap();
        assert!(within(&d.join("lib"), &d.join("lib")));
        assert!(within(&d.join("lib/a"), &d.join("lib")));
        assert!(within(&d.join("lib/new/out"), &d.join("lib")));
        assert!(within(&d.join("lib/a/../b"), &d.join("lib")));
        assert!(!within(&d.join("lib"), &d.join("lib/a")));
        assert!(!within(&d.join("libout"), &d.join("lib")));
        assert!(!within(&d.join("lib/../out"), &d.join("lib")));
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink(d.join("lib"), d.join("link")).unwrap();
            assert!(within(&d.join("link/x"), &d.join("lib")));
        }
        std::fs::remove_dir_all(&d).unwrap();
    }
}
