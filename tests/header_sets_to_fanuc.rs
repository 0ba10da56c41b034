//! A Siemens program's `nctrans: set` header lines in a translation to FANUC: the proof runs
//! the source with them (as `run` does), and the output carries them in its own variable
//! names, so `run` and `check` of the written file start from the same inputs.

mod eval_support;

use eval_support::{nctrans, scratch_dir, write};

const SRC: &str = "; nctrans: set R1=5 R2=2 R77=1\nIF R1==0 GOTOF SKIP\nG0 X=R1 Z=-R2\nSKIP:\nM30\n";

#[test]
fn the_proof_takes_the_header_and_the_output_carries_it_in_fanuc_names() {
    let d = scratch_dir("header-sets-tests", "mapped");
    let src = write(&d, "HDR.MPF", SRC);
    let out = d.join("hdr.nc").to_string_lossy().into_owned();
    let (code, _, err) = nctrans(&["--to", "fanuc", &src, "-o", &out]);
    assert_eq!(code, 0, "{err}");
    // The path the header selects (R1=5) is the one proven: the move is compared.
    assert!(err.contains("equivalent (2 events)"), "{err}");
    assert!(!err.contains("NC404"), "the header's R1 is set in the proof: {err}");
    let text = std::fs::read_to_string(&out).unwrap();
    let line = text.lines().find(|l| l.contains("nctrans: set")).expect("header line kept");
    // R77, which the program never uses, has no FANUC home and is left out.
    assert!(line.contains("#501=5") && line.contains("=2") && !line.contains('R'), "{line}");
    let (code, trace, err) = nctrans(&["run", &out]);
    assert_eq!(code, 0, "{err}");
    assert!(trace.contains("move rapid X=5 Z=-2"), "{trace}");
    let (code, verdict, err) = nctrans(&["check", &src, &out]);
    assert_eq!(code, 0, "{verdict}{err}");
    assert!(format!("{verdict}{err}").contains("equivalent"), "{verdict}{err}");
}
