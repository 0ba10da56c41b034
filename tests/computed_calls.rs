//! Calls with a computed program number (issue 21): `M98 P#1` / `G65 P#1` whose number is one
//! value on every path translate to the call of the translated callee by name, verified;
//! a wrong callee is caught, and a number that may be any is refused (NC356).

#[path = "support/cli_run.rs"]
mod cli_run;

use cli_run::{nctrans, workdir};

const JOB: &str = "O0175\n#11=176\n#12=9075.\nG0 X0 Y0\nG65 P#12 A8.\nM98 P#11\nM30\n\
                   O0176\nG1 X20. F300.\nM99\nO9075\nG1 Y#1 F300.\nM99\n";

#[test]
fn a_known_computed_number_calls_the_translated_program() {
    let d = workdir("computed", "known");
    std::fs::write(d.join("O0175.nc"), JOB).unwrap();
    let (out, err, code) = nctrans(&d, &["--to", "sinumerik", "O0175.nc", "-o", "o.mpf"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(err.contains("equivalent"), "{err}");
    let main = std::fs::read_to_string(d.join("o.mpf")).unwrap();
    assert!(main.contains("O_9075(8") && main.contains("\nO_0176\n"), "{main}");
    assert!(d.join("O_0176.SPF").exists() && d.join("O_9075.SPF").exists());
    // A planted wrong callee (the subprogram called in place of the macro) is caught.
    let wrong = main.replace("\nO_0176\n", "\nO_9075(8,1)\n");
    assert_ne!(wrong, main);
    std::fs::write(d.join("WRONG.MPF"), wrong).unwrap();
    let (out, _, code) = nctrans(&d, &["check", "O0175.nc", "WRONG.MPF"]);
    assert_ne!(code, 0, "{out}");
}

#[test]
fn a_number_that_may_be_any_is_refused() {
    let d = workdir("computed", "path");
    let job = JOB.replace("#11=176\n", "#11=176\nIF [#5041 GT 0] THEN #11=#5042\n");
    std::fs::write(d.join("O0175.nc"), job).unwrap();
    let (_, err, code) = nctrans(&d, &["--to", "sinumerik", "O0175.nc", "-o", "o.mpf"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC356") && err.contains("not one number on every path"), "{err}");
}

/// A number of a few values dispatches over the programs they name (tests/calls_computed_numbers.rs);
/// here one of them is also called by G65: one Siemens PROC cannot be both (NC352).
#[test]
fn a_number_that_depends_on_the_path_calls_each_program_it_names() {
    let d = workdir("computed", "both");
    let job = JOB.replace("#11=176\n", "#11=176\nIF [#5041 GT 0] THEN #11=9075\n");
    std::fs::write(d.join("O0175.nc"), job).unwrap();
    let (_, err, code) = nctrans(&d, &["--to", "sinumerik", "O0175.nc", "-o", "o.mpf"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC352") && err.contains("O9075"), "{err}");
}

const SELECT: &str = "DEF STRING[24] OP=\"DEBUR\"\nG0 X0 Y0\nCALL OP\nM30\n";

/// Siemens `CALL PROG_VAR` whose STRING holds one program name is that call to FANUC.
#[test]
fn a_string_variable_naming_one_program_calls_it_on_fanuc() {
    let d = workdir("computed", "string");
    std::fs::write(d.join("MAIN.MPF"), SELECT).unwrap();
    std::fs::write(d.join("DEBUR.SPF"), "PROC DEBUR\nG1 X5 F300\nM17\n").unwrap();
    std::fs::write(d.join("CHAMFER.SPF"), "PROC CHAMFER\nG1 Y5 F300\nM17\n").unwrap();
    let (out, err, code) = nctrans(&d, &["--to", "fanuc", "MAIN.MPF", "-o", "main.nc"]);
    assert_eq!(code, 0, "{out}{err}");
    let text = std::fs::read_to_string(d.join("main.nc")).unwrap();
    assert!(text.contains("G65 P9000") && text.contains("O9000 (DEBUR)") && !text.contains("OP"), "{text}");
    // A planted wrong callee is caught.
    let wrong = text.replace("G01 X5.", "G01 Y5.");
    std::fs::write(d.join("wrong.nc"), wrong).unwrap();
    let (out, _, code) = nctrans(&d, &["check", "MAIN.MPF", "wrong.nc"]);
    assert_ne!(code, 0, "{out}");
    // Two names on the way: the variable holds the O number of each (tests/program_vars.rs).
    let two = SELECT.replace("M30\n", "OP=\"CHAMFER\"\nCALL OP\nM30\n");
    std::fs::write(d.join("TWO.MPF"), two).unwrap();
    let (out, err, code) = nctrans(&d, &["--to", "fanuc", "TWO.MPF", "-o", "two.nc"]);
    assert_eq!(code, 0, "{out}{err}");
    let text = std::fs::read_to_string(d.join("two.nc")).unwrap();
    assert!(err.contains("equivalent") && text.matches("G65 P#").count() == 2, "{text}");
    // A name no translated program has: refused, saying why.
    let lost = SELECT.replace("M30\n", "OP=\"LOST\"\nCALL OP\nM30\n");
    std::fs::write(d.join("LOST.MPF"), lost).unwrap();
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "LOST.MPF", "-o", "lost.nc"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC559") && err.contains("\"LOST\" names no program"), "{err}");
}
