//! `nctrans run` and `nctrans parse` read the current folder's `nctrans.toml` (issue 21): a
//! Haas profile runs `M97 Pn` as the local subprogram call it is there, as the translation
//! already did; without the file M97 stays a machine builder's M code.

#[path = "support/cli_run.rs"]
mod cli_run;

use cli_run::{nctrans, workdir};

const HAAS: &str = "O1000\nG0 X0 Y0\nM97 P100\nG0 X5.\nM30\nN100 G1 X2. F100.\nM99\n";

#[test]
fn run_and_parse_take_the_haas_profile_from_the_project_file() {
    let d = workdir("profile", "haas");
    std::fs::write(d.join("O1000.nc"), HAAS).unwrap();
    let (out, err, code) = nctrans(&d, &["run", "O1000.nc"]);
    assert_eq!(code, 0, "{err}");
    assert!(!out.contains("X=2 "), "{out}");
    assert!(err.contains("NC253"), "{err}");
    std::fs::write(d.join("nctrans.toml"), "[fanuc]\nseries = \"haas\"\n").unwrap();
    let (out, err, code) = nctrans(&d, &["run", "O1000.nc"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("move linear X=2 Y=0 f=100"), "{out}");
    assert!(!err.contains("NC253"), "{err}");
    let (_, err, code) = nctrans(&d, &["parse", "--summary", "O1000.nc"]);
    assert_eq!(code, 0, "{err}");
    assert!(!err.contains("NC253"), "{err}");
    // A wrong key is an error naming it, as in translation.
    std::fs::write(d.join("nctrans.toml"), "[fanuc]\nseries = \"haas-x\"\n").unwrap();
    let (_, err, code) = nctrans(&d, &["run", "O1000.nc"]);
    assert_eq!(code, 2);
    assert!(err.contains("fanuc.series"), "{err}");
}
