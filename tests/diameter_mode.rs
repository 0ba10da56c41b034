//! Siemens instructions that change where the programmed values take the tool: diameter
//! programming (DIAMON, DIAM90: every X a diameter), kinematic transformations, tool- or
//! holder-aligned frames, approach paths under cutter compensation. The run refuses them
//! rather than show the programmed values as if they were not there; their off forms and
//! DIAMOF (radius, what the run models) run with a warning.

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

/// Kinematic transformations, frames aligned to the tool or holder, and the approach paths
/// of cutter compensation change where the tool goes: refused, not run "without effect".
#[test]
fn instructions_that_move_the_tool_otherwise_are_refused() {
    let d = scratch_dir("diameter-mode", "otherwise");
    for name in ["TRANSMIT", "TRACYL", "TOFRAME", "PAROT", "TOROT", "KONT", "KONTC", "KONTT"] {
        let src = write(&d, &format!("{name}.MPF"), &format!("G17 G90\n{name}\nG0 X50 Y2\nM30\n"));
        let (code, _, err) = nctrans(&["run", &src]);
        assert_ne!(code, 0, "{name}: {err}");
        assert!(err.contains("NC403"), "{name}: {err}");
    }
    // The off forms and the default approach change nothing the run does not model.
    for name in ["TRAFOOF", "PAROTOF", "TOROTOF", "NORM"] {
        let src = write(&d, &format!("{name}.MPF"), &format!("G17 G90\n{name}\nG0 X50 Y2\nM30\n"));
        let (code, _, err) = nctrans(&["run", &src]);
        assert_eq!(code, 0, "{name}: {err}");
    }
}
