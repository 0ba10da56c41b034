//! A Siemens program's `nctrans: set` header lines in a translation to FANUC: the proof runs
//! the source with them (as `run` does), so the path they select is the one proven.

mod eval_support;

use eval_support::{nctrans, scratch_dir, write};

const SRC: &str = "; nctrans: set R1=5 R2=2 R77=1\nIF R1==0 GOTOF SKIP\nG0 X=R1 Z=-R2\nSKIP:\nM30\n";

#[test]
fn the_proof_takes_the_source_header() {
    let d = scratch_dir("header-sets-tests", "mapped");
    let src = write(&d, "HDR.MPF", SRC);
    let out = d.join("hdr.nc").to_string_lossy().into_owned();
    let (code, _, err) = nctrans(&["--to", "fanuc", &src, "-o", &out]);
    assert_eq!(code, 0, "{err}");
    // The path the header selects (R1=5) is the one proven: the move is compared.
    assert!(err.contains("equivalent (2 events)"), "{err}");
    assert!(!err.contains("NC404"), "the header's R1 is set in the proof: {err}");
}
