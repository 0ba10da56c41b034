//! The horizon-juicer grinding library's axis variables to FANUC: its roller-dressing
//! subprogram `D_ROLLING.SPF` (`DEF AXIS AXIVER`, `AXIVER=AXNAME(AXIS_VER)`, `G91 G1
//! AX[AXIVER]=0.1`) translates and is proven with the machine's axis letter stated in
//! `[variables] fixed` and its global user data placed by `--var-map` rules; without the
//! letter the axis is refused naming the global (NC543).

use std::process::Command;

fn nctrans(dir: &std::path::Path, args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_nctrans")).args(args).current_dir(dir).output().expect("run nctrans");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn the_rolling_dresser_translates_on_the_set_up_letter() {
    let lib = crate::external("horizon-juicer-sinumerik/programs");
    let dir = std::env::temp_dir().join(format!("nctrans-external-axes-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let def = lib.join("DEF/MGUD.DEF");
    let program = lib.join("CMA/DRESS_PART/D_ROLLING.SPF");
    let config = |fixed: &str| {
        format!(
            "[fanuc]\nseries = \"haas-ngc\"\n[sinumerik]\ndefinitions = [{:?}]\n[variables]\n{fixed}\
             to_fanuc = [\"DRESSER=#500\", \"WHEEL=#660\", \"GRIND=#750\"]\n",
            def.display().to_string()
        )
    };
    std::fs::write(dir.join("nctrans.toml"), config("fixed = { AXIS_VER = \"X\" }\n")).unwrap();
    let p = program.display().to_string();
    let (code, out, err) = nctrans(&dir, &["--to", "fanuc", &p]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent (") && err.contains("AXIS_VER = \"X\""), "{err}");
    assert!(out.contains("G91 G01 X0.1 F#510") && !out.contains("AX"), "{out}");
    std::fs::write(dir.join("nctrans.toml"), config("")).unwrap();
    let (code, _, err) = nctrans(&dir, &["--to", "fanuc", &p]);
    assert_ne!(code, 0);
    assert!(err.contains("error[NC543]") && err.contains("AXIS_VER is global user data"), "{err}");
}
