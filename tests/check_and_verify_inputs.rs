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

/// A batch's `--set` inputs (`[verify] set`) of the Siemens side reach the FANUC side
/// translated: `$TC_DP3[5,1]` as the `#11005` the translation reads, `R1` as its `#501`.
#[test]
fn siemens_set_inputs_reach_the_fanuc_side_of_the_verification() {
    let d = workdir("check_inputs", "tcdp");
    std::fs::create_dir_all(d.join("in")).unwrap();
    std::fs::write(d.join("in/t.mpf"), "T5 M6 D1\nG0 X=R1\nG0 Y=$TC_DP3[5,1]\nM30\n").unwrap();
    std::fs::write(d.join("nctrans.toml"), "[verify]\nset = [\"R1=5\", \"$TC_DP3[5,1]=120.5\"]\n").unwrap();
    let (out, err, code) = nctrans(&d, &["--to", "fanuc", "-o", "out", "in"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("every file verified") || err.contains("every file verified"), "{out}{err}");
    let text = std::fs::read_to_string(d.join("out/t.nc")).unwrap();
    assert!(text.contains("Y#11005") && text.contains("X#501"), "{text}");
    // With another edge value on one side only the runs differ: the FANUC side reads what
    // the Siemens one was given, so a value given as FANUC #11005 that disagrees is caught.
    std::fs::write(d.join("nctrans.toml"), "[verify]\nset = [\"R1=5\", \"$TC_DP3[5,1]=120.5\", \"#11005=99\"]\n")
        .unwrap();
    let (out, err, code) = nctrans(&d, &["--to", "fanuc", "-o", "out2", "in"]);
    assert_ne!(code, 0, "{out}{err}");
}
