//! `--offset-map FILE` (issue 19): the H ↔ T/D offset map from a file of its own, for a
//! single-file translation both ways and for a batch, winning over `[offsets]` of
//! nctrans.toml with a note; the batch writes the map it used into nctrans-map.toml, and a
//! rerun without the flag reads it from there.

use std::path::{Path, PathBuf};
use std::process::Command;

fn workdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("nctrans-cli-offsets-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

/// Runs nctrans in `dir`: (stdout, stderr, success).
fn nctrans(dir: &Path, args: &[&str]) -> (String, String, bool) {
    let out = Command::new(env!("CARGO_BIN_EXE_nctrans")).current_dir(dir).args(args).output().expect("run nctrans");
    (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
        out.status.success(),
    )
}

/// Edge D2 of tool 6: no registers under the default map (edge D1 of tool n is H n, D n).
const PART: &str = "T6 M6 D2\nG41 G1 X1 Y0 F100\nG40 X2\nM30\n";
const OFFSETS: &str = "[offsets]\n\"6.2\" = \"H26,D46\"\n";

#[test]
fn the_flag_gives_the_registers_both_ways_and_wins_over_nctrans_toml() {
    let dir = workdir("single");
    std::fs::write(dir.join("part.mpf"), PART).expect("write");
    std::fs::write(dir.join("offsets.toml"), OFFSETS).expect("write");
    // Without a map the edge has no registers.
    let (_, err, ok) = nctrans(&dir, &["--to", "fanuc", "part.mpf"]);
    assert!(!ok && err.contains("NC472"), "{err}");
    let (out, err, ok) = nctrans(&dir, &["--to", "fanuc", "--offset-map", "offsets.toml", "part.mpf"]);
    assert!(ok, "{err}");
    assert!(out.contains("G43 H26") && out.contains("D46"), "{out}");
    assert!(err.contains("equivalent") && !err.contains("note:"), "{err}");
    // nctrans.toml names other registers: the flag wins, with a note.
    std::fs::write(dir.join("nctrans.toml"), "[offsets]\n\"6.2\" = \"H16,D36\"\n").expect("write");
    let (out, _, ok) = nctrans(&dir, &["--to", "fanuc", "part.mpf"]);
    assert!(ok && out.contains("G43 H16"), "{out}");
    let (out, err, ok) = nctrans(&dir, &["--to", "fanuc", "--offset-map", "offsets.toml", "part.mpf"]);
    assert!(ok && out.contains("G43 H26") && !out.contains("H16"), "{out}");
    assert!(err.contains("note: --offset-map offsets.toml replaces the [offsets]"), "{err}");
    std::fs::remove_file(dir.join("nctrans.toml")).expect("remove");
    // FANUC → Sinumerik: H26 is edge D2 of tool 6 only under the map.
    let fanuc = "%\nO1\nT6 M06\nG43 H26 Z50.\nG49\nM30\n%\n";
    std::fs::write(dir.join("part.nc"), fanuc).expect("write");
    let (_, err, ok) = nctrans(&dir, &["--to", "sinumerik", "-o", "a.mpf", "part.nc"]);
    assert!(!ok && err.contains("NC472"), "{err}");
    let (_, err, ok) = nctrans(&dir, &["--to", "sinumerik", "--offset-map", "offsets.toml", "-o", "b.mpf", "part.nc"]);
    assert!(ok && err.contains("equivalent"), "{err}");
    let text = std::fs::read_to_string(dir.join("b.mpf")).expect("output");
    assert!(text.contains("D2 Z50"), "{text}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_bad_offset_map_file_is_a_clear_error() {
    let dir = workdir("bad");
    std::fs::write(dir.join("part.mpf"), PART).expect("write");
    for (text, expect) in [
        ("[tools]\nDRILL = 3\n", "tools: unknown key (an offset map holds only an [offsets] table)"),
        ("", "no [offsets] table"),
        ("[offsets]\n\"6\" = \"H1,D1\"\n", "offsets.6"),
        ("[offsets\n", "offsets.toml"),
    ] {
        std::fs::write(dir.join("offsets.toml"), text).expect("write");
        let (_, err, ok) = nctrans(&dir, &["--to", "fanuc", "--offset-map", "offsets.toml", "part.mpf"]);
        assert!(!ok && err.contains("--offset-map") && err.contains(expect), "{text:?}: {err}");
    }
    let (_, err, ok) = nctrans(&dir, &["--to", "fanuc", "--offset-map", "missing.toml", "part.mpf"]);
    assert!(!ok && err.contains("cannot read missing.toml"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_batch_keeps_the_offset_map_it_used_for_the_rerun() {
    let dir = workdir("batch");
    std::fs::create_dir_all(dir.join("lib")).expect("lib");
    std::fs::write(dir.join("lib/part.mpf"), PART).expect("write");
    std::fs::write(dir.join("offsets.toml"), OFFSETS).expect("write");
    let (out, err, ok) = nctrans(&dir, &["--to", "fanuc", "--offset-map", "offsets.toml", "-o", "out", "lib"]);
    assert!(ok, "{out}\n{err}");
    let map = std::fs::read_to_string(dir.join("out/nctrans-map.toml")).expect("map");
    assert!(map.contains("[offsets]\n\"6.2\" = \"H26,D46\"\n"), "{map}");
    let first = std::fs::read(dir.join("out/part.nc")).expect("output");
    assert!(String::from_utf8_lossy(&first).contains("G43 H26"));
    // The rerun without the flag reads the map in the output folder: the same output.
    let (out, err, ok) = nctrans(&dir, &["--to", "fanuc", "--force", "-o", "out", "lib"]);
    assert!(ok, "{out}\n{err}");
    assert_eq!(std::fs::read(dir.join("out/part.nc")).expect("output"), first);
    assert_eq!(std::fs::read_to_string(dir.join("out/nctrans-map.toml")).expect("map"), map);
    // A configuration with other registers replaces the map's, with a note.
    std::fs::write(dir.join("nctrans.toml"), "[offsets]\n\"6.2\" = \"H16,D36\"\n").expect("write");
    let (out, err, ok) = nctrans(&dir, &["--to", "fanuc", "--force", "-o", "out", "lib"]);
    assert!(ok, "{out}\n{err}");
    assert!(err.contains("note: the offset map of the configuration replaces the [offsets] of"), "{err}");
    let text = std::fs::read_to_string(dir.join("out/part.nc")).expect("output");
    assert!(text.contains("G43 H16"), "{text}");
    let _ = std::fs::remove_dir_all(&dir);
}
