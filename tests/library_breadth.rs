//! More forms of real Siemens libraries (issue 21): spindle-addressed M and S words of the
//! master spindle (`M1=3 S1=1000`) run and translate as `M3 S1000`, another spindle's are
//! refused (NC505); the string functions run (STRLEN, TOUPPER, INDEX, SUBSTR, NUMBER, …)
//! and are refused for FANUC (NC506); a computed `MSG` becomes a comment of its formula.

#[path = "support/cli_run.rs"]
mod cli_run;

use cli_run::{nctrans, workdir};

fn write(name: &str, file: &str, text: &str) -> std::path::PathBuf {
    let d = workdir("breadth", name);
    std::fs::write(d.join(file), text).unwrap();
    d
}

#[test]
fn master_spindle_words_are_the_plain_spindle_words() {
    let d = write("spindle", "WHEEL.MPF", "M1=3 S1=1500\nG1 X10 F200\nM1=5\nM30\n");
    let (out, err, code) = nctrans(&d, &["run", "WHEEL.MPF"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("spindle cw 1500") && out.contains("spindle stop"), "{out}");
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "WHEEL.MPF", "-o", "w.nc"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
    let out = std::fs::read_to_string(d.join("w.nc")).unwrap();
    assert!(out.contains("M03 S1500") && out.contains("M05"), "{out}");
    std::fs::write(d.join("DRESS.MPF"), "M2=3 S2=800\nM30\n").unwrap();
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "DRESS.MPF", "-o", "d.nc"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC505") && err.contains("spindle 2"), "{err}");
}

#[test]
fn string_functions_run_and_are_refused_for_fanuc() {
    let text = "DEF STRING[32] NAME_S\nDEF INT POS_U, LEN_U\nNAME_S=TOUPPER(\"shaft_a\")\nPOS_U=INDEX(NAME_S,\"_\")\n\
                LEN_U=STRLEN(SUBSTR(NAME_S,POS_U+1))\nR1=NUMBER(\"12.5\")+RINDEX(\"A_B_C\",\"_\")+ISNUMBER(\"X\")\n\
                G1 X=POS_U Y=LEN_U Z=R1 F100\nMSG(NAME_S)\nM30\n";
    let d = write("strings", "NAMES.MPF", text);
    let (out, err, code) = nctrans(&d, &["run", "NAMES.MPF"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("X=5 Y=1 Z=15.5"), "{out}");
    assert!(out.contains("message \"SHAFT_A\""), "{out}");
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "NAMES.MPF", "-o", "n.nc"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC506") && err.contains("NUMBER"), "{err}");
}

#[test]
fn a_computed_message_becomes_a_comment_of_its_formula() {
    let d = write("msg", "PASS.MPF", "R1=2\nMSG(\"pass \"<<R1<<\" of 4\")\nG1 X=R1 F100\nM30\n");
    let (out, err, code) = nctrans(&d, &["run", "PASS.MPF"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("message \"pass 2 of 4\""), "{out}");
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "PASS.MPF", "-o", "p.nc"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("NC320") && err.contains("1 message kept as a comment"), "{err}");
    let out = std::fs::read_to_string(d.join("p.nc")).unwrap();
    assert!(out.contains("(MSG: \"pass \"<<R1<<\" of 4\")"), "{out}");
}

#[test]
fn ret_with_a_target_reads_and_is_refused_by_name() {
    let d = write("ret", "MAIN.MPF", "BACK_SUB\nG1 X5 F100\nRESUME:\nG1 X9\nM30\n");
    std::fs::write(d.join("BACK_SUB.SPF"), "PROC BACK_SUB\nG1 X1 F100\nRET(\"RESUME\", 1)\n").unwrap();
    let (_, err, code) = nctrans(&d, &["parse", "--summary", "BACK_SUB.SPF"]);
    assert_eq!(code, 0, "{err}");
    let (_, err, code) = nctrans(&d, &["run", "MAIN.MPF"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC507") && err.contains("RET(\"RESUME\", 1)"), "{err}");
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "BACK_SUB.SPF", "-o", "b.nc"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC507"), "{err}");
}

#[test]
fn extcall_runs_the_named_program_and_gett_is_refused() {
    let d = write("extcall", "MAIN.MPF", "G0 X0\nEXTCALL \"ROUGH\"\nM30\n");
    std::fs::write(d.join("ROUGH.SPF"), "PROC ROUGH\nG1 X7 F100\nRET\n").unwrap();
    let (out, err, code) = nctrans(&d, &["run", "MAIN.MPF"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("X=7"), "{out}");
    std::fs::write(d.join("TOOL.MPF"), "DEF INT TNO\nTNO=GETT(\"DRILL_5\")\nT=TNO\nM6\nM30\n").unwrap();
    let (_, err, code) = nctrans(&d, &["run", "TOOL.MPF"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC508"), "{err}");
    // To FANUC the name needs the tool map's number (NC525 names the missing entry).
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "TOOL.MPF", "-o", "t.nc"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC525") && err.contains("DRILL_5"), "{err}");
}

#[test]
fn a_variable_may_have_the_name_of_a_string_function() {
    let d = write("names", "COUNT.MPF", "DEF INT COUNTER, NUMBER=7\nR1=NUMBER(\"2.5\")+NUMBER\nG1 X=R1 F100\nM30\n");
    let (out, err, code) = nctrans(&d, &["run", "COUNT.MPF"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("X=9.5"), "{out}");
}
