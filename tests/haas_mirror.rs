//! Haas mirror image `G101`/`G100` (about the work zero, Haas VF manual p. 201): it runs as
//! FANUC's `G51.1`/`G50.1` about 0 under a Haas profile, translates to Sinumerik `AMIRROR`
//! and back (a Sinumerik `MIRROR X0` on a Haas target is `G101 X0.`, not G51.1), each proven;
//! an axis value other than 0 and a G52 shift, which the page does not settle, are refused.

#[path = "support/cli_run.rs"]
mod cli_run;

use cli_run::{nctrans, workdir};
use std::path::{Path, PathBuf};

const PROFILE: &str = "[fanuc]\nseries = \"haas-ngc\"\n";

/// A slot cut by a local subprogram, then again mirrored in Y (the library's form).
const SHOP: &str = "%
O1000 (MIRRORED SLOT)
G00 G17 G40 G80 G90
G54 X0. Y0.
G52 X0. Y0. Z0.
M97 P100
G101 Y0.
M97 P100
G100 Y0.
G00 Z50.
M30
N100 G00 X10. Y10. Z2.
G01 Z-1. F200.
G03 X20. Y20. R10.
G00 Z2.
M99
%
";

fn setup(name: &str, file: &str, text: &str) -> PathBuf {
    let d = workdir("haas-mirror", name);
    std::fs::write(d.join("nctrans.toml"), PROFILE).unwrap();
    std::fs::write(d.join(file), text).unwrap();
    d
}

fn read(d: &Path, f: &str) -> String {
    std::fs::read_to_string(d.join(f)).unwrap_or_default()
}

#[test]
fn g101_mirrors_about_the_work_zero_and_reverses_the_arc() {
    let d = setup("run", "O1000.nc", SHOP);
    let (out, err, code) = nctrans(&d, &["run", "O1000.nc"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("arc ccw XY X=20 Y=20 Z=-1 center X=10 Y=20"), "{out}");
    assert!(out.contains("arc cw XY X=20 Y=-20 Z=-1 center X=10 Y=-20"), "mirrored in Y, turned: {out}");
    // Without the Haas profile G101 is no code.
    std::fs::remove_file(d.join("nctrans.toml")).unwrap();
    let (_, err, code) = nctrans(&d, &["run", "O1000.nc"]);
    assert_ne!(code, 0);
    assert!(err.contains("G101 is not modelled"), "{err}");
}

#[test]
fn g101_translates_to_amirror_and_is_proven_and_a_dropped_mirror_is_caught() {
    let d = setup("to-sin", "O1000.nc", SHOP);
    let (_, err, code) = nctrans(&d, &["--to", "sinumerik", "O1000.nc", "-o", "o.mpf"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
    let text = read(&d, "o.mpf");
    assert_eq!(text.matches("\nAMIRROR Y0\n").count(), 2, "{text}");
    // Streamed: the same text.
    let (_, err, code) = nctrans(&d, &["--to", "sinumerik", "--stream", "O1000.nc", "-o", "s.mpf"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(read(&d, "s.mpf"), text);
    // Planted: the mirror left out, or on the other axis.
    for (name, bad) in [
        ("none.mpf", text.replacen("AMIRROR Y0\n", "", 1)),
        ("x.mpf", text.replacen("AMIRROR Y0\n", "AMIRROR X0\n", 1)),
    ] {
        std::fs::write(d.join(name), bad).unwrap();
        let (out, err, code) = nctrans(&d, &["check", "O1000.nc", name]);
        assert_ne!(code, 0, "{name}: {out}{err}");
        assert!(format!("{out}{err}").contains("diverge"), "{name}: {out}{err}");
    }
}

#[test]
fn a_value_other_than_zero_or_a_g52_shift_is_refused_both_in_run_and_translation() {
    for (name, from, to, run_code) in
        [("value", "G101 Y0.", "G101 Y5.", "NC490"), ("shift", "G52 X0. Y0. Z0.", "G52 X10. Y0. Z0.", "NC491")]
    {
        let d = setup(name, "O1000.nc", &SHOP.replacen(from, to, 1));
        let (_, err, code) = nctrans(&d, &["run", "O1000.nc"]);
        assert_ne!(code, 0, "{name}");
        assert!(err.contains(run_code) && err.contains("G101"), "{name}: {err}");
        let (_, err, code) = nctrans(&d, &["--to", "sinumerik", "O1000.nc", "-o", "o.mpf"]);
        assert_ne!(code, 0, "{name}");
        assert!(
            err.contains("NC363") && err.contains("Haas mirror image on") && err.contains("work zero"),
            "{name}: {err}"
        );
        assert!(!d.join("o.mpf").exists(), "{name}: nothing written");
    }
}

const SIEMENS: &str = "G0 G17 G90 G54\nSLOT\nMIRROR X0\nSLOT\nMIRROR\nG0 Z50\nM30\n";
const SLOT: &str = "G0 X10 Y10 Z2\nG1 Z-1 F200\nG2 X20 Y20 CR=10\nG0 Z2\nM17\n";

#[test]
fn a_siemens_mirror_on_a_haas_target_is_g101_and_proven() {
    let d = setup("to-haas", "MAIN.MPF", SIEMENS);
    std::fs::write(d.join("SLOT.SPF"), SLOT).unwrap();
    let (out, err, code) = nctrans(&d, &["--to", "fanuc", "MAIN.MPF"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
    assert!(out.contains("\nG101 X0.\n") && out.contains("\nG100 X0. Y0. Z0.\n"), "{out}");
    assert!(!out.contains("G51.1") && !out.contains("G50.1"), "{out}");
    // On a plain FANUC the same mirror stays G51.1.
    std::fs::remove_file(d.join("nctrans.toml")).unwrap();
    let (out, err, code) = nctrans(&d, &["--to", "fanuc", "MAIN.MPF"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("\nG51.1 X0.\n") && !out.contains("G101"), "{out}");
}

#[test]
fn a_siemens_mirror_over_a_shift_has_no_haas_form() {
    let d = setup("to-haas-shift", "MAIN.MPF", "G0 G17 G90 G54\nTRANS X10\nMIRROR X0\nSLOT\nMIRROR\nTRANS\nM30\n");
    std::fs::write(d.join("SLOT.SPF"), SLOT).unwrap();
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "MAIN.MPF", "-o", "o.nc"]);
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("NC552") && err.contains("MAIN.MPF:3:1"), "{err}");
    assert!(!d.join("o.nc").exists());
}

/// A `G52 X0. Y0. Z0.` while mirrored, with no shift in force, changes nothing: it runs, and
/// the translation writes no bare TRANS (which would delete the mirror on Sinumerik). A G52
/// that shifts stays refused there (NC491).
#[test]
fn a_g52_of_zeros_while_mirrored_changes_nothing_and_a_shift_stays_refused() {
    let text = "%\nO1002\nG00 G17 G40 G80 G90\nG54 X0. Y0.\nG52 X0. Y0. Z0.\nG101 Y0.\nG00 X10. Y10.\n\
                G52 X0. Y0. Z0.\nG00 X20. Y20.\nG01 X30. F100.\nG02 X40. Y10. R10.\nG100 Y0.\nM30\n%\n";
    let d = setup("g52-zero", "O1002.nc", text);
    let (out, err, code) = nctrans(&d, &["run", "O1002.nc"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("move rapid X=20 Y=-20"), "still mirrored after the G52: {out}");
    let (_, err, code) = nctrans(&d, &["--to", "sinumerik", "O1002.nc", "-o", "o.mpf"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
    let out = read(&d, "o.mpf");
    assert_eq!(out.matches("\nTRANS\n").count(), 1, "only the G52 before the mirror: {out}");
    // The same on a plain FANUC with G51.1.
    let plain = text.replace("G101 Y0.", "G51.1 Y0.").replace("G100 Y0.", "G50.1 Y0.");
    let d = workdir("haas-mirror", "g52-zero-plain");
    std::fs::write(d.join("O1002.nc"), &plain).unwrap();
    let (_, err, code) = nctrans(&d, &["--to", "sinumerik", "O1002.nc", "-o", "o.mpf"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
    // A G52 that shifts under the mirror is not settled.
    std::fs::write(d.join("O1003.nc"), plain.replacen("G52 X0. Y0. Z0.\nG00 X20.", "G52 X5. Y0. Z0.\nG00 X20.", 1))
        .unwrap();
    let (_, err, code) = nctrans(&d, &["run", "O1003.nc"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC491"), "{err}");
}
