//! Program ends in called programs, FANUC → Sinumerik: `M30` in a program called by `M98`
//! ends the whole FANUC run, while the same word in a Sinumerik subprogram returns to the
//! caller (as `M17`), so it is refused (NC592) instead of a translation that runs on.

use std::path::PathBuf;
use std::process::Command;

fn dir(name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/called-ends").join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("scratch dir");
    d
}

fn to_sinumerik(d: &PathBuf, main: &str) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_nctrans"))
        .args([main, "--to", "sinumerik", "-o", "out/"])
        .current_dir(d)
        .output()
        .expect("run nctrans");
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stderr).into_owned())
}

#[test]
fn m30_in_a_called_program_is_refused_and_m99_translates() {
    let d = dir("m30");
    std::fs::write(d.join("O1000.nc"), "%\nO1000\nG0 X1.\nM98 P2000\nG0 X5.\nM30\n%\n").unwrap();
    std::fs::write(d.join("O2000.nc"), "%\nO2000\nG0 X2.\nIF[#1 GT 0] M30\nM30\n%\n").unwrap();
    let (code, err) = to_sinumerik(&d, "O1000.nc");
    assert_ne!(code, 0, "{err}");
    assert_eq!(err.matches("error[NC592]").count(), 2, "{err}");
    // The same subprogram returning with M99 translates and verifies.
    std::fs::write(d.join("O2000.nc"), "%\nO2000\nG0 X2.\nM99\n%\n").unwrap();
    let (code, err) = to_sinumerik(&d, "O1000.nc");
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
}
