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

const PART: &str = "; config test\nT=\"BALLNOSE_D8\"\nM6 D1\nR1=30\nG0 X=R1\nM30\n";

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

/// `run --expand-cycles` takes the pecking retracts from the profile (parameter 5115 as
/// `fanuc.g83_clearance`); without the flag the hole stays one `cycle` event.
#[test]
fn run_expand_cycles_takes_the_retracts_from_the_profile() {
    let dir = workdir("expand");
    let part = "O1\nG90 G0 X0 Y0 Z20.\nG99 G83 X5. Y5. Z-6. R2. Q5. F100.\nG80\nM30\n";
    std::fs::write(dir.join("deep.nc"), part).expect("write part");
    let run = |extra: &[&str]| {
        let out = Command::new(env!("CARGO_BIN_EXE_nctrans"))
            .current_dir(&dir)
            .arg("run")
            .args(extra)
            .arg("deep.nc")
            .output()
            .expect("run nctrans");
        (String::from_utf8_lossy(&out.stdout).into_owned(), String::from_utf8_lossy(&out.stderr).into_owned())
    };
    let (out, err) = run(&[]);
    assert!(out.contains("cycle peck X=5 Y=5 r=2 bottom=-6 peck=5"), "{out}{err}");
    // The default clearance (0.25 mm) above the first depth, -3.
    let (out, err) = run(&["--expand-cycles"]);
    assert!(!out.contains("cycle ") && out.contains("move rapid X=5 Y=5 Z=-2.75 f=-"), "{out}{err}");
    std::fs::write(dir.join("nctrans.toml"), "[fanuc]\ng83_clearance = 1\n").expect("write config");
    let (out, err) = run(&["--expand-cycles"]);
    assert!(out.contains("move rapid X=5 Y=5 Z=-2 f=-") && !out.contains("Z=-2.75"), "{out}{err}");
    std::fs::write(dir.join("nctrans.toml"), "[fanuc]\ng83_clearance = -1\n").expect("write config");
    let (_, err) = run(&["--expand-cycles"]);
    assert!(err.contains("fanuc.g83_clearance"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}
