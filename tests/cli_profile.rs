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

#[test]
fn haas_ngc_variables_alias_their_legacy_numbers() {
    let d = workdir("profile", "ngc");
    std::fs::write(d.join("nctrans.toml"), "[fanuc]\nseries = \"haas-ngc\"\n").unwrap();
    // #10100 is #100; #10002 is a variable of its own; G103 limits look-ahead only.
    std::fs::write(
        d.join("O2000.nc"),
        "O2000\nG103 P1\n#10100=5.\n#10002=2.\n#1=#100+#10002\nG1 X#1 F100.\nG103 P0\nM30\n",
    )
    .unwrap();
    let (out, err, code) = nctrans(&d, &["run", "O2000.nc"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("move linear X=7"), "{out}");
    assert!(err.contains("G103 P1 (Haas look-ahead limit of 1 block)") && err.contains("NC560"), "{err}");
    let (_, err, code) = nctrans(&d, &["--to", "sinumerik", "O2000.nc", "-o", "o.mpf"]);
    assert_ne!(code, 0);
    // #10002 has an R parameter now (tests/haas_vars.rs); G103 P1 is what stops this one.
    assert!(!err.contains("NC509") && err.contains("NC562"), "{err}");
    assert!(err.contains("#10002 has no default R parameter"), "{err}");
    std::fs::write(d.join("O2001.nc"), "O2001\n#10500=4.\nG1 X#500 F100.\nM30\n").unwrap();
    let (_, err, code) = nctrans(&d, &["--to", "sinumerik", "O2001.nc", "-o", "p.mpf"]);
    assert_eq!(code, 0, "{err}");
    let out = std::fs::read_to_string(d.join("p.mpf")).unwrap();
    assert!(out.contains("R0=4") && out.contains("X=R0"), "{out}");
    // Without the NGC profile #10500 is not a common variable: on a FANUC it is the length
    // wear of offset 500 (tool compensation memory C), and #500 stays vacant.
    std::fs::remove_file(d.join("nctrans.toml")).unwrap();
    let (out, err, code) = nctrans(&d, &["run", "O2001.nc"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("tool_data register=500 field=length_wear value=4") && !out.contains("X=4"), "{out}");
    assert!(err.contains("#500 is read but was never set"), "{err}");
}

#[test]
fn a_dprnt_number_field_is_read_not_compared_and_refused_for_sinumerik() {
    let d = workdir("profile", "dprnt");
    std::fs::write(
        d.join("O3000.nc"),
        "O3000\nG0 X10. Y0\nPOPEN\nDPRNT[X*#5041[43]**PART*#3901[30]]\nPCLOS\nG1 X20. F100.\nM30\n",
    )
    .unwrap();
    let (_, err, code) = nctrans(&d, &["parse", "--summary", "O3000.nc"]);
    assert_eq!(code, 0, "{err}");
    let (out, err, code) = nctrans(&d, &["run", "O3000.nc"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("X=20") && !out.contains("print"), "{out}");
    assert!(err.contains("NC554") && err.contains("`#5041[43]`"), "{err}");
    let (_, err, code) = nctrans(&d, &["--to", "sinumerik", "O3000.nc", "-o", "o.mpf"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC556") && err.contains("#5041[43]"), "{err}");
}

#[test]
fn a_parameter_bit_read_is_named_when_it_is_refused() {
    let d = workdir("profile", "bits");
    std::fs::write(d.join("O3001.nc"), "O3001\n#1=#30057.21\nM30\n").unwrap();
    let (_, err, code) = nctrans(&d, &["parse", "O3001.nc"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC511") && err.contains("`#30057.21`"), "{err}");
}
