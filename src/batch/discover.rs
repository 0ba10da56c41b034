//! Finding the programs of a library (recursively, in a stable order) and naming their
//! outputs: `.mpf/.spf` → `.nc`; `.nc/.tap` → `.mpf`, or `.spf` for called programs.

use crate::dialect::{Dialect, ParseOptions};
use crate::span::SourceDb;
use crate::translate::library::{scan_unit, FileInfo, Scan};
use std::path::{Path, PathBuf};

/// One input program file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct InputFile {
    /// Position in the batch (files are sorted by `rel`).
    pub index: usize,
    /// Path relative to the input folder.
    pub rel: PathBuf,
    /// The path to read.
    pub abs: PathBuf,
}

/// What discovery found.
#[derive(Clone, Debug, Default)]
pub struct Found {
    pub files: Vec<InputFile>,
    /// Files that are not NC programs by their name (`.txt`, `.csv`, …), relative paths.
    pub ignored: Vec<PathBuf>,
}

/// Whether a file name is an NC program by its name: an NC extension (`.mpf .spf .nc .tap
/// .fnc .cnc`, any case), or no extension and a FANUC-style name `O1234`.
pub fn is_program_name(name: &str) -> bool {
    match Path::new(name).extension().and_then(|e| e.to_str()) {
        Some(ext) => Dialect::from_extension(ext).is_some(),
        None => {
            let upper = name.to_ascii_uppercase();
            upper
                .strip_prefix('O')
                .is_some_and(|d| !d.is_empty() && d.len() <= 5 && d.bytes().all(|b| b.is_ascii_digit()))
        }
    }
}

/// Lists the program files below `root`, sorted by relative path (byte order of the
/// `/`-joined path, so the order is the same on every platform). Hidden entries (`.git`,
/// `.nctrans-tmp`) and `exclude` (the output folder when it lies inside the input) are not
/// entered; symbolic links to folders are not followed (no cycles).
pub fn discover(root: &Path, exclude: Option<&Path>) -> std::io::Result<Found> {
    let mut files = Vec::new();
    let mut ignored = Vec::new();
    let exclude = exclude.and_then(|e| e.canonicalize().ok());
    let mut stack = vec![PathBuf::new()];
    while let Some(rel_dir) = stack.pop() {
        let dir = root.join(&rel_dir);
        if let (Some(ex), Ok(canon)) = (&exclude, dir.canonicalize()) {
            if *ex == canon {
                continue;
            }
        }
        let entries = std::fs::read_dir(&dir)?;
        for entry in entries {
            let entry = entry?;
            let name = entry.file_name();
            let Some(name_str) = name.to_str() else {
                // A name that is not Unicode cannot be mapped to an output name reliably.
                ignored.push(rel_dir.join(&name));
                continue;
            };
            if name_str.starts_with('.') {
                continue;
            }
            let rel = rel_dir.join(&name);
            let ft = entry.file_type()?;
            if ft.is_dir() {
                stack.push(rel);
            } else if ft.is_file() || (ft.is_symlink() && entry.path().is_file()) {
                if is_program_name(name_str) {
                    files.push(rel);
                } else {
                    ignored.push(rel);
                }
            }
        }
    }
    files.sort_by_key(|p| super::rel_string(p));
    ignored.sort_by_key(|p| super::rel_string(p));
    let files =
        files.into_iter().enumerate().map(|(index, rel)| InputFile { index, abs: root.join(&rel), rel }).collect();
    Ok(Found { files, ignored })
}

/// The dialect a file's name implies, if any.
pub fn dialect_of_name(path: &Path) -> Option<Dialect> {
    match path.extension().and_then(|e| e.to_str()) {
        Some(ext) => Dialect::from_extension(ext),
        None => path.file_name().and_then(|n| n.to_str()).filter(|n| is_program_name(n)).map(|_| Dialect::Fanuc),
    }
}

/// Writes `ext` in the case of `like`: `NC` for `MPF`, `nc` for `mpf` (mixed case: lower).
fn ext_like(ext: &str, like: Option<&str>) -> String {
    match like {
        Some(l) if !l.is_empty() && l.chars().all(|c| !c.is_ascii_lowercase()) => ext.to_ascii_uppercase(),
        _ => ext.to_ascii_lowercase(),
    }
}

/// The output path of a Siemens file translated to FANUC: the same folder and stem, `.nc`.
/// All programs of the file (and the subprograms the translator inlines) go into one file:
/// FANUC keeps several `O` programs in one file.
pub fn fanuc_output(rel: &Path) -> PathBuf {
    let like = rel.extension().and_then(|e| e.to_str());
    rel.with_extension(ext_like("nc", like))
}

/// The output path of one program of a FANUC file translated to Sinumerik: the same
/// folder, the Siemens program name (the name is how Siemens finds a program), `.spf` for
/// a program that is called, `.mpf` for a main program. Several programs of one file
/// become several files.
pub fn sinumerik_output(rel: &Path, name: &str, called: bool) -> PathBuf {
    let like = rel.extension().and_then(|e| e.to_str());
    let ext = ext_like(if called { "spf" } else { "mpf" }, like);
    let dir = rel.parent().unwrap_or(Path::new(""));
    dir.join(format!("{name}.{ext}"))
}

/// The dialect of a file: its name, else its content.
pub fn dialect_of(rel: &Path, text: &str) -> Dialect {
    dialect_of_name(rel).unwrap_or_else(|| Dialect::sniff(text))
}

/// Reads and parses one file for the index.
pub fn scan(file: &InputFile, encoding: Option<&'static encoding_rs::Encoding>) -> Scan {
    let bytes = match std::fs::read(&file.abs) {
        Ok(b) => b,
        Err(e) => {
            return Scan {
                info: FileInfo { read_error: Some(format!("cannot read: {e}")), ..FileInfo::default() },
                ..Scan::default()
            }
        }
    };
    let mut db = SourceDb::new();
    let name = super::rel_string(&file.rel);
    let loaded = crate::load(&mut db, &name, &bytes, encoding);
    let dialect = dialect_of(&file.rel, &db.get(loaded.file).text);
    let parsed = crate::parse(&db, loaded.file, dialect, &ParseOptions::for_dialect(dialect));
    let stem = file.rel.file_stem().and_then(|s| s.to_str()).unwrap_or("").to_ascii_uppercase();
    let mut scan = scan_unit(&parsed.unit, db.get(loaded.file), &stem);
    scan.info.parse_errors = parsed.diags.iter().filter(|d| d.is_error()).count();
    scan
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn program_names() {
        for n in ["a.mpf", "B.SPF", "x.nc", "y.TAP", "O1234", "o12"] {
            assert!(is_program_name(n), "{n}");
        }
        for n in ["readme.txt", "O12A", "O", "notes", "O123456"] {
            assert!(!is_program_name(n), "{n}");
        }
    }

    #[test]
    fn extension_mapping_keeps_case_and_folder() {
        assert_eq!(fanuc_output(Path::new("a/b/PART.MPF")), Path::new("a/b/PART.NC"));
        assert_eq!(fanuc_output(Path::new("a/sub.spf")), Path::new("a/sub.nc"));
        assert_eq!(sinumerik_output(Path::new("m/o9010.nc"), "PROBE_X", true), Path::new("m/PROBE_X.spf"));
        assert_eq!(sinumerik_output(Path::new("m/O1.TAP"), "MAIN1", false), Path::new("m/MAIN1.MPF"));
        assert_eq!(sinumerik_output(Path::new("O1"), "O0001", false), Path::new("O0001.mpf"));
    }

    #[test]
    fn discovery_is_sorted_recursive_and_skips_hidden_and_output() {
        let dir = std::env::temp_dir().join(format!("nctrans-discover-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        for p in ["b/z.mpf", "b/a.nc", "a.spf", "notes.txt", ".git/x.nc", "out/o.nc", "O100"] {
            let f = dir.join(p);
            std::fs::create_dir_all(f.parent().unwrap()).unwrap();
            std::fs::write(&f, "M30\n").unwrap();
        }
        let found = discover(&dir, Some(&dir.join("out"))).unwrap();
        let rels: Vec<String> = found.files.iter().map(|f| super::super::rel_string(&f.rel)).collect();
        assert_eq!(rels, ["O100", "a.spf", "b/a.nc", "b/z.mpf"]);
        assert_eq!(found.ignored, [PathBuf::from("notes.txt")]);
        assert!(found.files.iter().enumerate().all(|(i, f)| f.index == i));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
