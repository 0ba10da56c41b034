//! Single-file translation reads the project configuration `./nctrans.toml`, and flags given
//! on the command line win over it (issue 4: every mapping can be overridden by `--var-map`
//! and by the project config).

use std::path::PathBuf;
use std::process::Command;

fn workdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("nctrans-cli-config-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

fn translate(dir: &PathBuf, extra: &[&str]) -> (String, String, bool) {
    let out = Command::new(env!("CARGO_BIN_EXE_nctrans"))
        .current_dir(dir)
        .args(["--to", "fanuc"])
        .args(extra)
        .arg("part.mpf")
        .output()
        .expect("run nctrans");
    (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
        out.status.success(),
    )
}

const PART: &str = "; config test\nT=\"BALLNOSE_D8\"\nM6\nR1=30\nG0 X=R1\nM30\n";

#[test]
fn the_project_config_maps_variables_and_tools_and_flags_win() {
    let dir = workdir("maps");
    std::fs::write(dir.join("part.mpf"), PART).expect("write part");
    // Without a tool number the translation is refused, naming the flag.
    let (_, err, ok) = translate(&dir, &[]);
    assert!(!ok && err.contains("--tool-map BALLNOSE_D8="), "{err}");
    std::fs::write(dir.join("nctrans.toml"), "[variables]\nto_fanuc = [\"R0-R9=#600\"]\n\n[tools]\nBALLNOSE_D8 = 12\n")
        .expect("write config");
    let (out, err, ok) = translate(&dir, &[]);
    assert!(ok, "{err}");
    assert!(out.contains("T12") && out.contains("#601=30."), "{out}");
    assert!(err.contains("equivalent"), "{err}");
    let (out, err, ok) = translate(&dir, &["--var-map", "R0-R9=#700", "--tool-map", "BALLNOSE_D8=3"]);
    assert!(ok, "{err}");
    assert!(out.contains("T3") && out.contains("#701=30.") && !out.contains("#601"), "{out}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_wrong_config_key_is_a_clear_error() {
    let dir = workdir("bad");
    std::fs::write(dir.join("part.mpf"), PART).expect("write part");
    std::fs::write(dir.join("nctrans.toml"), "[translate]\nunsupported = \"maybe\"\n").expect("write config");
    let (_, err, ok) = translate(&dir, &[]);
    assert!(!ok);
    assert!(err.contains("translate.unsupported") && err.contains("\"error\""), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}
