//! Siemens diameter programming (DIAMON, DIAM90) changes what every X value means: the
//! run refuses it rather than show the programmed values as if they were radii; DIAMOF
//! (radius, what the run models) runs with a warning.

mod eval_support;

use eval_support::{nctrans, scratch_dir, write};

#[test]
fn diameter_programming_is_refused_and_radius_runs() {
    let d = scratch_dir("diameter-mode", "run");
    for on in ["DIAMON", "DIAM90"] {
        let src = write(&d, &format!("{on}.MPF"), &format!("G18 G90\n{on}\nG0 X50 Z2\nG1 X40 Z-10 F0.2\nM30\n"));
        let (code, _, err) = nctrans(&["run", &src]);
        assert_ne!(code, 0, "{on}: {err}");
        assert!(err.contains("NC403") && err.contains("diameter"), "{on}: {err}");
    }
    let src = write(&d, "RADIUS.MPF", "G18 G90\nDIAMOF\nG0 X50 Z2\nM30\n");
    let (code, trace, err) = nctrans(&["run", &src]);
    assert_eq!(code, 0, "{err}");
    assert!(trace.contains("X=50"), "{trace}");
}
