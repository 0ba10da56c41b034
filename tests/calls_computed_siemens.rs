//! Siemens call forms of issue 21: `CALL "L"<<R1` (the program name built by a STRING
//! expression) runs the program of that name and is refused to FANUC (NC585, no `M98 P#n`
//! is the same call); `PCALL NAME` of an undeclared name calls that program.

#[path = "support/cli_run.rs"]
mod cli_run;

use cli_run::{nctrans, workdir};

#[test]
fn a_name_built_with_concat_runs_that_program() {
    let d = workdir("calls21", "built");
    std::fs::write(d.join("MAIN.MPF"), "R1=100\nCALL \"L\"<<R1\nDEF STRING[8] NM=\"SUB\"\nCALL NM<<\"_A\"\nM30\n")
        .unwrap();
    std::fs::write(d.join("L100.SPF"), "G0 X10\nM17\n").unwrap();
    std::fs::write(d.join("SUB_A.SPF"), "PROC SUB_A\nG0 Y7\nM17\n").unwrap();
    let (out, err, code) = nctrans(&d, &["run", "MAIN.MPF"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("X=10") && out.contains("Y=7"), "{out}");
}

#[test]
fn a_name_built_at_run_time_that_names_no_program_is_the_controls_alarm() {
    let d = workdir("calls21", "unknown");
    std::fs::write(d.join("MAIN.MPF"), "R1=101\nCALL \"L\"<<R1\nM30\n").unwrap();
    std::fs::write(d.join("L100.SPF"), "G0 X10\nM17\n").unwrap();
    let (out, err, code) = nctrans(&d, &["run", "MAIN.MPF"]);
    assert_ne!(code, 0, "{out}");
    assert!(err.contains("L101") && !err.contains("panicked"), "{err}");
}

#[test]
fn a_built_name_is_refused_to_fanuc_with_the_reason() {
    let d = workdir("calls21", "fanuc");
    std::fs::write(d.join("MAIN.MPF"), "R1=100\nCALL \"L\"<<R1\nM30\n").unwrap();
    std::fs::write(d.join("L100.SPF"), "G0 X10\nM17\n").unwrap();
    let (out, err, code) = nctrans(&d, &["--to", "fanuc", "MAIN.MPF"]);
    assert_ne!(code, 0, "{out}");
    assert!(err.contains("NC585") && err.contains("O9000"), "{err}");
}

#[test]
fn pcall_of_a_program_name_calls_it_and_translates() {
    let d = workdir("calls21", "pcall");
    std::fs::write(d.join("MAIN.MPF"), "PCALL SUB1\nM30\n").unwrap();
    std::fs::write(d.join("SUB1.SPF"), "PROC SUB1\nG0 X5\nM17\n").unwrap();
    let (out, err, code) = nctrans(&d, &["run", "MAIN.MPF"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("X=5"), "{out}");
    let (out, err, code) = nctrans(&d, &["--to", "fanuc", "MAIN.MPF"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("O9000 (SUB1)") && err.contains("equivalent"), "{out}{err}");
}

#[test]
fn pcall_of_a_declared_string_variable_stays_computed() {
    let d = workdir("calls21", "pcallvar");
    std::fs::write(d.join("MAIN.MPF"), "DEF STRING[8] SUB1=\"OTHER\"\nPCALL SUB1\nM30\n").unwrap();
    std::fs::write(d.join("OTHER.SPF"), "PROC OTHER\nG0 Y3\nM17\n").unwrap();
    std::fs::write(d.join("SUB1.SPF"), "PROC SUB1\nG0 X5\nM17\n").unwrap();
    let (out, err, code) = nctrans(&d, &["run", "MAIN.MPF"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("Y=3") && !out.contains("X=5"), "{out}");
}

#[test]
fn an_l_program_without_a_proc_line_is_found() {
    let d = workdir("calls21", "lnum");
    std::fs::write(d.join("MAIN.MPF"), "L100\nM30\n").unwrap();
    std::fs::write(d.join("L100.SPF"), "G0 X10\nM17\n").unwrap();
    let (out, err, code) = nctrans(&d, &["run", "MAIN.MPF"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("X=10"), "{out}");
    let (out, err, code) = nctrans(&d, &["--to", "fanuc", "MAIN.MPF"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("O9000 (L100)") && err.contains("equivalent"), "{out}{err}");
}
