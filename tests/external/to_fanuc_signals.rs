//! The horizon-juicer grinding library's PLC signal reads to FANUC: `F_GRINDWHEEL_RUN.SPF`
//! (`IF $A_DBB[12]==0`, the wheel not running) and `C_ROTATE_ANGLE.SPF` (`WHILE($A_DBB[14]==0)`,
//! wait for the unclamp) translate in a batch and are proven with the machine's wiring
//! (`[signals]`) and the signals' values as the proof's inputs (`[verify] set`); without the
//! wiring each read is refused naming the key to add (NC342).

use std::process::Command;

fn nctrans(dir: &std::path::Path, args: &[&str]) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_nctrans")).args(args).current_dir(dir).output().expect("run nctrans");
    let text = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    (out.status.code().unwrap_or(-1), text)
}

#[test]
fn the_wheel_and_unclamp_waits_translate_on_the_wiring() {
    let lib = crate::external("horizon-juicer-sinumerik/programs");
    let dir = std::env::temp_dir().join(format!("nctrans-external-signals-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("lib")).unwrap();
    for f in ["F_GRINDWHEEL_RUN.SPF", "C_ROTATE_ANGLE.SPF"] {
        std::fs::copy(lib.join("CMA").join(f), dir.join("lib").join(f)).unwrap();
    }
    let base = format!(
        "[sinumerik]\ndefinitions = [{:?}]\n[variables]\nto_fanuc = [\"INI=#500\"]\n",
        lib.join("DEF/MGUD.DEF").display().to_string()
    );
    let wiring = "[signals]\n\"$A_DBB[12]\" = \"#1012\"\n\"$A_DBB[14]\" = \"#1014\"\n\
                  [verify]\nset = [\"$A_DBB[12]=0\", \"$A_DBB[14]=1\"]\n";
    std::fs::write(dir.join("nctrans.toml"), format!("{base}{wiring}")).unwrap();
    let (code, out) = nctrans(&dir, &["--to", "fanuc", "-o", "out", "lib"]);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("every file verified"), "{out}");
    let wheel = std::fs::read_to_string(dir.join("out/F_GRINDWHEEL_RUN.NC")).unwrap();
    assert!(wheel.contains("IF [#1012 NE 0.] GOTO"), "{wheel}");
    let unclamp = std::fs::read_to_string(dir.join("out/C_ROTATE_ANGLE.NC")).unwrap();
    assert!(unclamp.contains("WHILE [#1014 EQ 0.] DO"), "{unclamp}");
    std::fs::write(dir.join("nctrans.toml"), base).unwrap();
    let (code, out) = nctrans(&dir, &["--to", "fanuc", "-o", "out2", "lib"]);
    assert_ne!(code, 0, "{out}");
    assert!(out.contains("NC342") && out.contains("$A_DBB[12] (PLC data byte 12)"), "{out}");
    // One file alone shows the hint naming the key.
    let (code, out) = nctrans(&dir, &["--to", "fanuc", "lib/F_GRINDWHEEL_RUN.SPF", "-o", "wheel.nc"]);
    assert_ne!(code, 0, "{out}");
    assert!(out.contains("[signals] \"$A_DBB[12]\" = \"#1000\""), "{out}");
}
