//! Haas-only G codes that neither `run` nor a translation carries (circular pocket milling,
//! engraving, bolt-hole patterns, …) are refused by their Haas name under a Haas profile, so
//! a user sees which cycle to rewrite; on a plain FANUC profile the same numbers keep the
//! generic refusal (they are not FANUC codes).

#[path = "support/cli_run.rs"]
mod cli_run;

use cli_run::{nctrans, workdir};

const POCKET: &str = "%
O1000 (COUNTERBORE)
G00 G17 G40 G49 G80 G90
G54 X50. Y30.
S2000 M03
G13 I8. K12. Q3. Z-4. F600. D01
G00 Z50.
M30
%
";

fn setup(name: &str, profile: &str) -> std::path::PathBuf {
    let d = workdir("haas-only", name);
    std::fs::write(d.join("nctrans.toml"), profile).unwrap();
    std::fs::write(d.join("O1000.nc"), POCKET).unwrap();
    d
}

#[test]
fn circular_pocket_is_refused_by_its_haas_name_in_run_and_translation() {
    let d = setup("named", "[fanuc]\nseries = \"haas-ngc\"\n");
    let (_, err, code) = nctrans(&d, &["run", "O1000.nc"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC403") && err.contains("G13 (Haas circular pocket milling, counterclockwise)"), "{err}");
    assert!(err.contains("O1000.nc:6:1"), "points at the block: {err}");
    let (_, err, code) = nctrans(&d, &["--to", "sinumerik", "O1000.nc", "-o", "o.mpf"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC363") && err.contains("G13 (Haas circular pocket milling, counterclockwise)"), "{err}");
    assert!(!d.join("o.mpf").exists(), "no partial output");
}

#[test]
fn the_same_number_on_plain_fanuc_keeps_the_generic_refusal() {
    let d = setup("plain", "");
    let (_, err, code) = nctrans(&d, &["run", "O1000.nc"]);
    assert_ne!(code, 0);
    assert!(err.contains("G13 is not modelled by the evaluator"), "{err}");
    assert!(!err.contains("Haas"), "{err}");
}
