//! Which file beside a FANUC program holds the program a call names (`M98 P9724`): by file
//! name first (`O9724.nc`, `O09724.nc`, `9724.nc`), then a name that starts with it
//! (`O09724_PROBE_X.nc`), then any FANUC file of the folder whose text has the program
//! number line `O9724` / `:9724` (`PROBE.NC` holding O9724): libraries are named by people.

use std::path::{Path, PathBuf};

/// Larger files are not scanned for a program number (CAM output, not macro libraries).
const SCAN_LIMIT: u64 = 4 << 20;

/// The file names a program number goes by, most exact first.
fn stems(n: u32) -> [String; 4] {
    [format!("O{n}"), format!("O{n:04}"), format!("{n}"), format!("{n:04}")]
}

/// Whether a file named `stem` goes by program number `n` (`O0060`, `O60`, `60`, `0060`): how
/// a file that holds no program is still known as the one a call meant.
pub fn names_number(stem: &str, n: u32) -> bool {
    stems(n).iter().any(|s| s.eq_ignore_ascii_case(stem))
}

/// Whether a file extension is one a FANUC program is kept in.
pub fn fanuc_ext(p: &Path) -> bool {
    let ext = p.extension().and_then(|s| s.to_str()).unwrap_or("").to_ascii_lowercase();
    matches!(ext.as_str(), "nc" | "tap" | "txt" | "")
}

/// The file in `dir` (other than `caller`) that holds program `n`; `exts` filters the
/// candidates by path (the callers' own extension rules).
pub fn find(dir: &Path, caller: Option<&Path>, n: u32, exts: &dyn Fn(&Path) -> bool) -> Option<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .ok()?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.is_file() && Some(p.as_path()) != caller && exts(p))
        .collect();
    files.sort();
    let stem = |p: &PathBuf| p.file_stem().and_then(|s| s.to_str()).unwrap_or("").to_ascii_uppercase();
    let names = stems(n);
    if let Some(f) = names.iter().find_map(|s| files.iter().find(|f| stem(f).eq_ignore_ascii_case(s))) {
        return Some(f.clone());
    }
    // `O09724_PROBE_X`: the number, then something that is not a digit.
    let prefixed = |f: &&PathBuf| {
        let st = stem(f);
        names.iter().any(|s| {
            st.len() > s.len()
                && st.starts_with(&s.to_ascii_uppercase())
                && !st.as_bytes()[s.len()].is_ascii_alphanumeric()
        })
    };
    if let Some(f) = files.iter().find(prefixed) {
        return Some(f.clone());
    }
    files.into_iter().filter(|f| fanuc_ext(f)).find(|f| holds_program(f, n))
}

/// Whether the file has a block that is the program number `O<n>` or `:<n>` (leading zeros,
/// a comment after it allowed).
fn holds_program(path: &Path, n: u32) -> bool {
    if std::fs::metadata(path).map_or(true, |m| m.len() > SCAN_LIMIT) {
        return false;
    }
    let Ok(bytes) = std::fs::read(path) else { return false };
    let text = String::from_utf8_lossy(&bytes);
    text.lines().any(|line| {
        let l = line.trim_start();
        let Some(rest) = l.strip_prefix(['O', 'o', ':']) else { return false };
        let digits: String = rest.chars().take_while(char::is_ascii_digit).collect();
        let after = rest[digits.len()..].trim_start();
        !digits.is_empty()
            && digits.parse::<u32>().ok() == Some(n)
            && (after.is_empty() || after.starts_with(['(', ';']))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn folder(files: &[(&str, &str)]) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("nctrans-callee-{}-{}", std::process::id(), files[0].0));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("temp dir");
        for (name, text) in files {
            std::fs::write(dir.join(name), text).expect("write");
        }
        dir
    }

    #[test]
    fn a_program_is_found_by_name_then_by_name_prefix_then_by_its_number_line() {
        let d = folder(&[("MAIN.nc", "O1\nM98 P9724\nM30\n"), ("O09724_PROBE_X.nc", "O9724\nM99\n")]);
        let found = find(&d, Some(&d.join("MAIN.nc")), 9724, &fanuc_ext);
        assert_eq!(found.as_deref(), Some(d.join("O09724_PROBE_X.nc").as_path()));
        let d =
            folder(&[("MAIN2.nc", "O1\nM98 P9725\nM30\n"), ("PROBE.NC", "%\nO9001\nM99\nO09725 (PROBE Y)\nM99\n%\n")]);
        let found = find(&d, Some(&d.join("MAIN2.nc")), 9725, &fanuc_ext);
        assert_eq!(found.as_deref(), Some(d.join("PROBE.NC").as_path()));
        // O97250 is another program; the caller itself is never its own callee file.
        assert_eq!(find(&d, Some(&d.join("MAIN2.nc")), 9726, &fanuc_ext), None);
        let d = folder(&[("O9727.nc", "O9727\nM99\n"), ("O97270.nc", "O97270\nM99\n")]);
        assert_eq!(find(&d, None, 9727, &fanuc_ext).as_deref(), Some(d.join("O9727.nc").as_path()));
    }
}
