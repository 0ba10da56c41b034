//! Calls of what the Siemens control itself provides: a cycle of its package other than the
//! drilling cycles (`POCKET3`, `CYCLE61`, `SLOT1` …) and a predefined procedure nctrans does
//! not model (`FGROUP`, `DRFOF` …) are named as such, in `run` and in translation, with what
//! to do, instead of being looked for as subprograms; a cycle's name given as a program
//! beside the main program is read and translated as that subprogram.

#[path = "support/cli_run.rs"]
mod cli_run;

use std::path::{Path, PathBuf};

const MAIN: &str = "\
; POCKET AND FACE
N10 G17 G90 G71 G54
N20 T1 D1 M6
N30 S3000 M3 F300
N40 G0 X0 Y0 Z10
N50 POCKET3(10,0,1,-5,40,30,5,50,25,0,2,0.1,0.1,300,150,0,11,8)
N60 G0 Z100
N70 M30
";

fn dir(name: &str) -> PathBuf {
    cli_run::workdir("control-calls", name)
}

fn nctrans(cwd: &Path, args: &[&str]) -> (i32, String, String) {
    let (out, err, code) = cli_run::nctrans(cwd, args);
    (code, out, err)
}

#[test]
fn a_package_cycle_is_named_as_one() {
    let d = dir("named");
    std::fs::write(d.join("PART.MPF"), MAIN).unwrap();
    let (code, out, err) = nctrans(&d, &["run", "PART.MPF"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC402") && err.contains("unknown cycle POCKET3"), "{out}{err}");
    let (code, _, err) = nctrans(&d, &["--to", "fanuc", "PART.MPF"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC303") && err.contains("cycle POCKET3 (of the control's cycle package"), "{err}");
    assert!(err.contains("replace POCKET3 by explicit moves") && !err.contains("translate POCKET3 too"), "{err}");
    // An ordinary subprogram name keeps its own hint.
    std::fs::write(d.join("OTHER.MPF"), MAIN.replace("POCKET3(", "ROUGH_A(")).unwrap();
    let (_, _, err) = nctrans(&d, &["--to", "fanuc", "OTHER.MPF"]);
    assert!(err.contains("translate ROUGH_A too"), "{err}");
}

#[test]
fn its_program_beside_the_main_is_a_subprogram() {
    let d = dir("beside");
    std::fs::write(d.join("PART.MPF"), MAIN).unwrap();
    // A shop's own stand-in with the cycle's name (as a cycles folder copied beside would be).
    let sub = "PROC POCKET3(REAL RTP,REAL RFP,REAL SDIS,REAL DP,REAL LENG,REAL WID,REAL CRAD,REAL PA,REAL PO,REAL STA,REAL MID,REAL FAL,REAL FALD,REAL FFP1,REAL FFD,INT CDIR,INT VARI,REAL MIDA)\n\
G0 X=PA Y=PO\nG0 Z=RFP+SDIS\nG1 Z=DP F=FFD\nG1 X=PA+LENG/2 F=FFP1\nG0 Z=RTP\nM17\n";
    std::fs::write(d.join("POCKET3.SPF"), sub).unwrap();
    let (code, out, err) = nctrans(&d, &["run", "PART.MPF"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("X=70 Y=25"), "{out}");
    let (code, out, err) = nctrans(&d, &["--to", "fanuc", "PART.MPF"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("G65 P") && err.lines().last().unwrap_or_default().starts_with("equivalent"), "{out}{err}");
}

#[test]
fn a_predefined_procedure_is_named_as_one() {
    let d = dir("procedure");
    let main = "; THREAD GRIND\nN10 G18 G90 G0 X10 Z10\nN20 FGROUP(Z)\nN30 G1 Z30 F100\nN40 DRFOF\nN50 M30\n";
    std::fs::write(d.join("GRIND.MPF"), main).unwrap();
    let (code, out, err) = nctrans(&d, &["run", "GRIND.MPF"]);
    assert_ne!(code, 0);
    // FGROUP is modelled (tests/rotary_feed.rs): the run stops at DRFOF, after the move.
    assert!(err.contains("NC651") && err.contains("DRFOF is a predefined procedure"), "{out}{err}");
    assert!(out.contains("Z=30 f=100"), "{out}{err}");
    assert!(!err.contains("FGROUP.SPF") && !err.contains("DRFOF.SPF"), "{err}");
    let (code, _, err) = nctrans(&d, &["--to", "fanuc", "GRIND.MPF"]);
    assert_ne!(code, 0);
    assert!(err.contains("DRFOF (a predefined procedure of the control, not modelled)"), "{err}");
    assert!(!err.contains("FGROUP"), "{err}");
}
