//! Siemens STRING variables that hold program names (issue 21), as a grinding library writes
//! them: an init program picks the shape program in IF branches (`SHAPE="D_TRIANGLE"`), a
//! dressing program runs it (`EXECSTRING(SHAPE)`). To FANUC the variable is the O number of
//! the program it names and the call `G65 P#n`, proven equivalent in a single-file and a batch
//! translation; a wrong O number is caught by `check`; other uses are refused with why.

#[path = "support/cli_run.rs"]
mod cli_run;

use cli_run::{nctrans, workdir};
use std::path::Path;

const MAIN: &str = "; grinding: choose the shape, then dress\nR1=2\nPAR_INI\nDRESS\nM30\n";
const PAR_INI: &str = "PROC PAR_INI\nIF R1==1\n  SHAPE=\"D_TRIANGLE\"\nELSE\n  IF R1==2\n    SHAPE=\"D_TRAPEZ\"\n  \
                       ELSE\n    SHAPE=\"\"\n  ENDIF\nENDIF\nRET\n";
const DRESS: &str =
    "PROC DRESS\nIF SHAPE<>\"\"\n  EXECSTRING(SHAPE)\nENDIF\nIF SHAPE==\"D_TRAPEZ\"\n  G1 Z-1 F50\nENDIF\nRET\n";

fn library(d: &Path, main: &str, par_ini: &str, dress: &str) {
    std::fs::write(d.join("MGUD.DEF"), "DEF NCK STRING[20] SHAPE\nM17\n").unwrap();
    std::fs::write(d.join("GRIND.MPF"), main).unwrap();
    std::fs::write(d.join("PAR_INI.SPF"), par_ini).unwrap();
    std::fs::write(d.join("DRESS.SPF"), dress).unwrap();
    std::fs::write(d.join("D_TRIANGLE.SPF"), "PROC D_TRIANGLE\nG1 X10 Y5 F200\nRET\n").unwrap();
    std::fs::write(d.join("D_TRAPEZ.SPF"), "PROC D_TRAPEZ\nG1 X20 Y8 F200\nRET\n").unwrap();
    std::fs::write(d.join("nctrans.toml"), "[variables]\nto_fanuc = [\"SHAPE=#600\"]\n").unwrap();
}

#[test]
fn a_gud_shape_name_is_the_o_number_of_the_shape_program() {
    for r1 in ["1", "2", "3"] {
        let d = workdir("progvars", &format!("gud{r1}"));
        library(&d, &MAIN.replace("R1=2", &format!("R1={r1}")), PAR_INI, DRESS);
        let (out, err, code) = nctrans(&d, &["--to", "fanuc", "GRIND.MPF", "-o", "o.nc"]);
        assert_eq!(code, 0, "{out}{err}");
        assert!(err.contains("equivalent"), "{err}");
        let nc = std::fs::read_to_string(d.join("o.nc")).unwrap();
        assert!(nc.contains("G65 P#600\n") && nc.contains("#600=9001.") && nc.contains("#600=0."), "{nc}");
        assert!(nc.contains("O9001 (D_TRAPEZ)") && nc.contains("O9002 (D_TRIANGLE)"), "{nc}");
        // A planted wrong O number in the assignment calls the other shape: caught.
        let wrong = nc.replace("#600=9001.", "#600=9002.");
        assert_ne!(wrong, nc);
        std::fs::write(d.join("wrong.nc"), wrong).unwrap();
        if r1 == "2" {
            let (out, err, code) = nctrans(&d, &["check", "GRIND.MPF", "wrong.nc"]);
            assert_ne!(code, 0, "{out}{err}");
        }
    }
}

#[test]
fn a_local_string_chosen_in_branches_is_called_through_its_number() {
    let d = workdir("progvars", "local");
    let main = "DEF STRING[20] SH\nR1=1\nIF R1==1\nSH=\"D_TRIANGLE\"\nELSE\nSH=\"D_TRAPEZ\"\nENDIF\nCALL SH\nM30\n";
    library(&d, main, PAR_INI, DRESS);
    let (out, err, code) = nctrans(&d, &["--to", "fanuc", "GRIND.MPF"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(err.contains("equivalent") && out.contains("G65 P#"), "{out}{err}");
}

/// `SHAPE=WORM_SHAPE`: a copy of another program-name variable holds the names it holds.
#[test]
fn a_copy_of_another_program_name_variable_is_a_copy_of_its_number() {
    let d = workdir("progvars", "copy");
    let par = "PROC PAR_INI\nWORM=\"D_TRIANGLE\"\nIF R1==2\n  SHAPE=WORM\nELSE\n  SHAPE=\"D_TRAPEZ\"\nENDIF\nRET\n";
    library(&d, MAIN, par, DRESS);
    std::fs::write(d.join("MGUD.DEF"), "DEF NCK STRING[20] SHAPE, WORM\nM17\n").unwrap();
    std::fs::write(d.join("nctrans.toml"), "[variables]\nto_fanuc = [\"SHAPE=#600\", \"WORM=#601\"]\n").unwrap();
    let (out, err, code) = nctrans(&d, &["--to", "fanuc", "GRIND.MPF", "-o", "o.nc"]);
    assert_eq!(code, 0, "{out}{err}");
    let nc = std::fs::read_to_string(d.join("o.nc")).unwrap();
    assert!(err.contains("equivalent") && nc.contains("#600=#601") && nc.contains("#601=9002."), "{nc}");
}

#[test]
fn the_batch_translates_the_library_and_refuses_the_dressing_program_alone_with_why() {
    let d = workdir("progvars", "batch");
    let lib = d.join("lib");
    std::fs::create_dir_all(&lib).unwrap();
    library(&lib, MAIN, PAR_INI, DRESS);
    let (out, err, _) = nctrans(&lib, &["--to", "fanuc", "-o", "../out/", "."]);
    let all = format!("{out}{err}");
    assert!(all.contains("verified               GRIND.MPF"), "{all}");
    let nc = std::fs::read_to_string(d.join("out/GRIND.NC")).unwrap();
    assert!(nc.contains("G65 P#600"), "{nc}");
    // DRESS.SPF alone does not include the programs SHAPE names: refused, saying so.
    assert!(all.contains("NC559") && all.contains("SHAPE"), "{all}");
}

#[test]
fn other_uses_of_a_program_name_variable_are_refused_with_why() {
    let cases = [
        ("SHAPE=\"D_\"<<\"TRAPEZ\"", "concatenation"),
        ("SHAPE=\"NOT_THERE\"", "names no program"),
        ("MSG(SHAPE)", "read as text"),
    ];
    for (i, (line, why)) in cases.iter().enumerate() {
        let d = workdir("progvars", &format!("refuse{i}"));
        let par = PAR_INI.replace("RET\n", &format!("{line}\nRET\n"));
        library(&d, MAIN, &par, DRESS);
        let (out, err, code) = nctrans(&d, &["--to", "fanuc", "GRIND.MPF"]);
        assert_ne!(code, 0, "{line}: {out}{err}");
        assert!(err.contains("NC559") && err.contains(why), "{line}: {err}");
    }
}

#[test]
fn the_evaluator_runs_execstring_of_a_name_and_refuses_other_lines() {
    let d = workdir("progvars", "eval");
    library(&d, MAIN, PAR_INI, DRESS);
    let (out, err, code) = nctrans(&d, &["run", "GRIND.MPF"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("X=20 Y=8") && out.contains("Z=-1"), "{out}");
    for (text, why) in [("G1 X5", "the line \"G1 X5\""), ("", "an empty line")] {
        let main = format!("DEF STRING[20] LINE_TXT=\"{text}\"\nEXECSTRING(LINE_TXT)\nM30\n");
        std::fs::write(d.join("E.MPF"), main).unwrap();
        let (out, err, code) = nctrans(&d, &["run", "E.MPF"]);
        assert_ne!(code, 0, "{out}");
        assert!(err.contains("NC553") && err.contains(why), "{err}");
    }
}

/// A PROC parameter named as the GUD is the caller's value, not the GUD: its call stays refused.
#[test]
fn a_parameter_named_as_the_gud_is_not_the_gud() {
    let d = workdir("progvars", "param");
    let dress = "PROC DRESS(STRING[20] SHAPE)\nEXECSTRING(SHAPE)\nRET\n";
    library(&d, &MAIN.replace("DRESS\n", "DRESS(\"D_TRAPEZ\")\n"), PAR_INI, dress);
    let (out, err, code) = nctrans(&d, &["--to", "fanuc", "GRIND.MPF"]);
    assert_ne!(code, 0, "{out}{err}");
    assert!(err.contains("NC303") && !err.contains("G65 P#600"), "{err}");
}

/// A shape program that leaves G91 in force: after the call G90/G91 depends on the name, as
/// where paths meet; the caller's next moves are translated with it and proven for each name.
/// One that changes the units stays refused (NC558).
#[test]
fn a_callee_that_leaves_g91_is_merged_one_that_changes_units_is_refused() {
    let main = "DEF STRING[20] SH\nR1=1\nG90 G0 X0 Y0\nIF R1==1\nSH=\"D_TRIANGLE\"\nELSE\nSH=\"D_TRAPEZ\"\nENDIF\n\
CALL SH\nG1 X5 F100\nG1 X=IC(2) Y=AC(1)\nG90 G1 X0\nM30\n";
    for r1 in ["1", "2"] {
        let d = workdir("progvars", &format!("g91-{r1}"));
        library(&d, &main.replace("R1=1", &format!("R1={r1}")), PAR_INI, DRESS);
        std::fs::write(d.join("D_TRAPEZ.SPF"), "PROC D_TRAPEZ\nG91 G1 X20 Y8 F200\nRET\n").unwrap();
        let (out, err, code) = nctrans(&d, &["--to", "fanuc", "GRIND.MPF"]);
        assert_eq!(code, 0, "{r1}: {out}{err}");
        assert!(err.lines().last().unwrap_or_default().starts_with("equivalent"), "{r1}: {err}");
    }
    let d = workdir("progvars", "g70");
    library(&d, main, PAR_INI, DRESS);
    std::fs::write(d.join("D_TRAPEZ.SPF"), "PROC D_TRAPEZ\nG70\nG1 X2 Y1 F20\nRET\n").unwrap();
    let (out, err, code) = nctrans(&d, &["--to", "fanuc", "GRIND.MPF"]);
    assert_ne!(code, 0, "{out}{err}");
    assert!(err.contains("NC558") && err.contains("leaves the units"), "{err}");
}
