//! Issue 21, the small ones: `nctrans check --tool-map` gives `GETT` the map as the
//! translation's verification does.

#[path = "support/cli_run.rs"]
mod cli_run;

use cli_run::{nctrans, workdir};

#[test]
fn check_with_a_tool_map_gives_gett_the_mapped_number() {
    let d = workdir("check_inputs", "gett");
    std::fs::write(d.join("G.MPF"), "R1=GETT(\"DRILL_8\")\nT=R1\nM6\nG0 X10\nM30\n").unwrap();
    std::fs::write(d.join("G.nc"), "O0001\nT8 M6\nG43 H8\nG0 X10.\nM30\n").unwrap();
    let (out, err, code) = nctrans(&d, &["check", "G.MPF", "G.nc", "--tool-map", "DRILL_8=8"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("equivalent"), "{out}");
    // Another number in the map is another tool: caught.
    let (out, _, code) = nctrans(&d, &["check", "G.MPF", "G.nc", "--tool-map", "DRILL_8=9"]);
    assert_ne!(code, 0, "{out}");
    assert!(out.contains("tool 9") && out.contains("tool 8"), "{out}");
}
