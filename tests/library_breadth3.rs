//! Forms of real libraries, third part (issue 21): look-ahead and high-speed modes (FANUC
//! `G05.1 Q1/Q0`, `G05 P10000/P0`, `G08 P1/P0`, Haas `G187`, `G103`; Siemens `FFWON`/`FFWOF`,
//! `CYCLE832`) run without an event, translate both ways, and every verdict says how many
//! were not compared; values the controls do not document are refused (NC561–NC563).

#[path = "support/cli_run.rs"]
mod cli_run;

use cli_run::{nctrans, workdir};
use std::path::PathBuf;

fn write(name: &str, files: &[(&str, &str)]) -> PathBuf {
    let d = workdir("breadth3", name);
    for (f, t) in files {
        std::fs::write(d.join(f), t).unwrap();
    }
    d
}

const HAAS: &str = "[fanuc]\nseries = \"haas\"\n";

#[test]
fn fanuc_look_ahead_modes_become_feed_forward_and_are_not_compared() {
    let prog = "O1000\nG05.1 Q1\nG08 P1\nG05 P10000\nG01 X10. F100.\nN20 G05.1 Q0\nG08 P0\nG05 P0\nM30\n";
    let d = write("fanuc-modes", &[("a.nc", prog)]);
    let (out, err, code) = nctrans(&d, &["run", "a.nc"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("X=10"), "{out}");
    assert_eq!(err.matches("warning[NC560]").count(), 6, "{err}");
    assert!(
        err.contains("G05.1 Q1 (AI contour control on)") && err.contains("G08 P0 (advanced preview control off)"),
        "{err}"
    );
    let (_, err, code) = nctrans(&d, &["--to", "sinumerik", "a.nc", "-o", "out/"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("; 6 look-ahead settings not compared)"), "{err}");
    let mpf = std::fs::read_to_string(d.join("out/P_A.MPF")).unwrap();
    assert_eq!(mpf.matches("FFWON").count(), 3, "{mpf}");
    assert!(mpf.contains("N20 FFWOF") && mpf.matches("FFWOF").count() == 3, "{mpf}");
}

#[test]
fn undocumented_values_and_mixed_blocks_are_refused() {
    let d = write("fanuc-bad", &[("q2.nc", "O1\nG05.1 Q2\nM30\n"), ("mix.nc", "O2\nG05.1 Q1 G01 X5. F100.\nM30\n")]);
    let (_, err, code) = nctrans(&d, &["run", "q2.nc"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC561") && err.contains("G05.1 Q2 is not modelled"), "{err}");
    let (_, err, code) = nctrans(&d, &["--to", "sinumerik", "mix.nc", "-o", "out/"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC562") && err.contains("with other words in its block"), "{err}");
    let d = write("sie-bad", &[("A.MPF", "CYCLE832(0.1,9)\nM30\n"), ("B.MPF", "R1=1\nCYCLE832(0.1,R1)\nM30\n")]);
    let (_, err, code) = nctrans(&d, &["run", "A.MPF"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC561") && err.contains("machining type 9"), "{err}");
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "B.MPF", "-o", "b.nc"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC563") && err.contains("computed tolerance or machining type"), "{err}");
}

#[test]
fn haas_smoothness_becomes_cycle832_and_back() {
    let prog = "O1000\nG187 P1 E0.05\nG103 P0\nG01 X10. F100.\nG187 P3 E0.01\nG187\nM30\n";
    let d = write("haas", &[("h.nc", prog), ("nctrans.toml", HAAS)]);
    let (_, err, code) = nctrans(&d, &["--to", "sinumerik", "h.nc", "-o", "out/"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("NC562") && err.contains("G103 P0 (Haas look-ahead limit off) dropped"), "{err}");
    assert!(err.contains("; 4 look-ahead settings not compared)"), "{err}");
    let mpf = std::fs::read_to_string(d.join("out/P_H.MPF")).unwrap();
    assert!(mpf.contains("CYCLE832(0.05,3,1)") && mpf.contains("CYCLE832(0.01,1,1)"), "{mpf}");
    assert!(mpf.contains("CYCLE832(0,0,1)") && !mpf.contains("G103"), "{mpf}");
    // Back to Haas: roughing is P1, finishing P3, deselection a bare G187.
    std::fs::copy(d.join("out/P_H.MPF"), d.join("BACK.MPF")).unwrap();
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "BACK.MPF", "-o", "back.nc"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("; 3 look-ahead settings not compared)"), "{err}");
    let nc = std::fs::read_to_string(d.join("back.nc")).unwrap();
    assert!(nc.contains("G187 P1 E0.05") && nc.contains("G187 P3 E0.01") && nc.contains("\nG187\n"), "{nc}");
    // A look-ahead limit of n blocks has no Sinumerik counterpart.
    std::fs::write(d.join("l.nc"), "O1001\nG103 P5\nG01 X1. F100.\nM30\n").unwrap();
    let (_, err, code) = nctrans(&d, &["--to", "sinumerik", "l.nc", "-o", "out2/"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC562") && err.contains("G103 P5 (Haas look-ahead limit of 5 blocks)"), "{err}");
    // E without P: the smoothness is Setting 191, not in the program.
    std::fs::write(d.join("e.nc"), "O1002\nG187 E0.01\nM30\n").unwrap();
    let (_, err, code) = nctrans(&d, &["--to", "sinumerik", "e.nc", "-o", "out3/"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC562") && err.contains("Setting 191"), "{err}");
    // CYCLE832 keeps the tool and its edge: a tool change and G43 after a G187 translate.
    let prog = "O1003\nT1 M6\nG43 H1 Z50.\nG187 P3 E0.01\nG01 X10. F100.\nG187\nG53 G0 Z0.\nT2 M6\nG0 X5. Y5.\nG43 Z20. H2\nM30\n";
    std::fs::write(d.join("t.nc"), prog).unwrap();
    let (_, err, code) = nctrans(&d, &["--to", "sinumerik", "t.nc", "-o", "out4/"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
}

#[test]
fn siemens_high_speed_settings_become_aicc_for_fanuc() {
    let prog = "FFWON\nCYCLE832(0.01,_FINISH,1)\nG1 X10 F100\nCYCLE832(0,_OFF,1)\nFFWOF\nM30\n";
    let d = write("sie", &[("HSC.MPF", prog)]);
    let (_, err, code) = nctrans(&d, &["run", "HSC.MPF"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("CYCLE832(0.01, 1) (high-speed settings: finishing)"), "{err}");
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "HSC.MPF", "-o", "h.nc"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("; 4 look-ahead settings not compared)"), "{err}");
    assert!(err.contains("NC563") && err.contains("CYCLE832 becomes G05.1 Q1"), "{err}");
    let nc = std::fs::read_to_string(d.join("h.nc")).unwrap();
    // Q is a mode number: no decimal point.
    assert_eq!(nc.matches("G05.1 Q1\n").count(), 2, "{nc}");
    assert_eq!(nc.matches("G05.1 Q0\n").count(), 2, "{nc}");
    // Haas has no feed-forward switch: FFWON is dropped with a note there.
    std::fs::write(d.join("nctrans.toml"), HAAS).unwrap();
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "HSC.MPF", "-o", "hh.nc"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("NC323") && err.contains("FFWON dropped"), "{err}");
    let nc = std::fs::read_to_string(d.join("hh.nc")).unwrap();
    assert!(nc.contains("G187 P3 E0.01") && !nc.contains("G05.1"), "{nc}");
}

#[test]
fn siemens_smoothing_is_not_compared_and_g642_becomes_g64() {
    // G641/G642 round the corners the trace records as programmed: the run says they are not
    // compared (they were "no effect on the trace"); G642 (within the machine's tolerances) is
    // FANUC's cutting mode G64 with a note, G641 (a programmed distance ADIS) has no FANUC form.
    let prog = "G90 G1 X0 Y0 F100\nG642\nG1 X10\nY10\nG60\nM30\n";
    let d = write("sie-smooth", &[("S.MPF", prog), ("A.MPF", &prog.replace("G642", "G641 ADIS=0.5"))]);
    let (_, err, code) = nctrans(&d, &["run", "S.MPF"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("warning[NC560]: G642 (smoothing"), "{err}");
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "S.MPF", "-o", "s.nc"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("NC620") && err.contains("(4 events; 1 look-ahead setting not compared)"), "{err}");
    let nc = std::fs::read_to_string(d.join("s.nc")).unwrap();
    assert!(nc.lines().any(|l| l == "G64") && !nc.contains("G642"), "{nc}");
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "A.MPF", "-o", "a.nc"]);
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("NC311") && err.contains("G641"), "{err}");
}

#[test]
fn a_numbered_high_speed_block_keeps_its_number_on_its_fanuc_words() {
    // `N60 CYCLE832(…)` is `N60 G05.1 Q1`, not an empty `N60` above or below a `G05.1 Q1`
    // block (a jump to N80 landed below FFWON's); a skipped block's words are skipped with it.
    let prog = "N50 G1 X0 F100\nN60 CYCLE832(0.01,_FINISH,1)\nN70 G1 X10\nN80 FFWON\n/N90 CYCLE832(0,_OFF,1)\nM30\n";
    let d = write("sie-numbered", &[("HSN.MPF", prog)]);
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "HSN.MPF", "-o", "h.nc"]);
    assert_eq!(code, 0, "{err}");
    let nc = std::fs::read_to_string(d.join("h.nc")).unwrap();
    let lines: Vec<&str> = nc.lines().collect();
    assert!(lines.contains(&"N60 G05.1 Q1") && lines.contains(&"N80 G05.1 Q1"), "{nc}");
    assert!(!lines.contains(&"N60") && !lines.contains(&"N80"), "{nc}");
    assert!(lines.contains(&"/ N90 G05.1 Q0"), "{nc}");
}

#[test]
fn a_bracketed_program_number_is_that_program() {
    let prog = "O1000\nM98 P [ 10 ]\nG65 P[20] A1.\nM30\nO10\nG01 X1. F100.\nM99\nO20\nG01 X#1\nM99\n";
    let d = write(
        "pconst",
        &[("c.nc", prog), ("d.nc", "O1000\n#1=10\nIF[#5041 GT 0]THEN #1=20\nM98 P#1\nM30\nO10\nG01 X1. F100.\nM99\n")],
    );
    let (out, err, code) = nctrans(&d, &["parse", "c.nc"]);
    assert_eq!(code, 0, "{err}");
    assert!(!out.contains("Computed"), "{out}");
    let (_, err, code) = nctrans(&d, &["--to", "sinumerik", "c.nc", "-o", "out/"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
    let mpf = std::fs::read_to_string(d.join("out/P_C.MPF")).unwrap();
    assert!(mpf.contains("O_0010\n") && mpf.contains("O_0020(1"), "{mpf}");
    // A number that depends on the path is a dispatch over the programs its values name
    // (O10 here; 20 names none: Siemens' own "program not found"), tests/calls_computed_numbers.rs.
    let (_, err, code) = nctrans(&d, &["--to", "sinumerik", "d.nc", "-o", "out2/"]);
    assert_eq!(code, 0, "{err}");
    let mpf = std::fs::read_to_string(d.join("out2/P_D.MPF")).unwrap();
    assert!(mpf.contains("ROUND(LOC1)-10<>0") && mpf.contains("NCTRANS_NO_PROG"), "{mpf}");
    // One that may be any value stays refused, naming why.
    std::fs::write(d.join("e.nc"), "O1000\n#1=#5041\nM98 P#1\nM30\nO10\nG01 X1. F100.\nM99\n").unwrap();
    let (_, err, code) = nctrans(&d, &["--to", "sinumerik", "e.nc", "-o", "out3/"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC356") && err.contains("computed program number"), "{err}");
}

#[test]
fn haas_settings_and_parameters_are_the_machine_inputs() {
    let prog = "O1000\n#1=#20009\n#2=#30057\nG01 X#1 Y#2 F100.\nM30\n";
    let d = write("haasdata", &[("s.nc", prog), ("w.nc", "O1001\n#20009=1.\nM30\n"), ("nctrans.toml", HAAS)]);
    let (_, err, code) = nctrans(&d, &["run", "s.nc"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC564") && err.contains("#20009 is Haas Setting 9"), "{err}");
    let (out, err, code) = nctrans(&d, &["run", "s.nc", "--set", "#20009=1", "--set", "#30057=4"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("X=1 Y=4"), "{out}");
    let (_, err, code) = nctrans(&d, &["run", "w.nc"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC564") && err.contains("read-only"), "{err}");
    // Header inputs give the run its values; the translation is refused naming the setting.
    std::fs::write(d.join("h.nc"), format!("%\n(nctrans: set #20009=1. #30057=4.)\n{prog}%\n")).unwrap();
    let (_, err, code) = nctrans(&d, &["--to", "sinumerik", "h.nc", "-o", "out/"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC564") && err.contains("Haas parameter 57, the machine's own data"), "{err}");
    // Without the Haas profile they are plain unmodelled system variables.
    std::fs::remove_file(d.join("nctrans.toml")).unwrap();
    let (_, err, code) = nctrans(&d, &["run", "s.nc"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC400"), "{err}");
}

#[test]
fn siemens_queries_are_read_and_refused_naming_why() {
    let cases = [
        ("SP.MPF", "DEF STRING[40] TXT\nTXT=SPRINT(\"X=%F\",R1)\nM30\n", "NC565", "SPRINT", "NC506"),
        ("IV.MPF", "IF ISVAR(\"R1\")\nG1 X1 F10\nENDIF\nM30\n", "NC565", "ISVAR", "NC506"),
        ("IF.MPF", "IF ISFILE(\"/_N_WKS_DIR/A_MPF\")\nM0\nENDIF\nM30\n", "NC565", "file system", "NC506"),
        ("GS.MPF", "DEF INT _LIST[5]\nR1=GETSELT(_LIST,1)\nM30\n", "NC508", "GETSELT", "NC508"),
    ];
    for (file, text, run_code, what, fanuc_code) in cases {
        let d = write(&format!("query-{file}"), &[(file, text)]);
        let (out, err, code) = nctrans(&d, &["parse", file]);
        assert_eq!(code, 0, "{file}: {err}");
        assert!(out.contains(&what.to_ascii_lowercase()) || out.contains("getselt") || out.contains("isfile"), "{out}");
        let (_, err, code) = nctrans(&d, &["run", file]);
        assert_ne!(code, 0);
        assert!(err.contains(run_code) && err.contains(what), "{file}: {err}");
        let (_, err, code) = nctrans(&d, &["--to", "fanuc", file, "-o", "o.nc"]);
        assert_ne!(code, 0);
        assert!(err.contains(fanuc_code), "{file}: {err}");
    }
    // The documented STRING limit is 200 characters.
    let d = write("string255", &[("S.MPF", "DEF STRING[255] TXT\nM30\n")]);
    let (_, err, code) = nctrans(&d, &["parse", "S.MPF"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC134") && err.contains("at most 200 characters"), "{err}");
}

#[test]
fn interrupt_instructions_are_read_whole_and_refused_for_fanuc() {
    let prog = "SETINT(3) PRIO=1 ABHEB LIFTFAST\nG1 X10 F100\nDISABLE(3)\nENABLE(3)\nCLRINT(3)\nM30\n";
    let d = write("interrupts", &[("I.MPF", prog)]);
    let (out, err, code) = nctrans(&d, &["parse", "I.MPF"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("instruction SETINT(3) PRIO=1 ABHEB LIFTFAST") && !out.contains("assign PRIO"), "{out}");
    // LIFTFAST's lift is not modelled: the run refuses it (tests/interrupts.rs runs the rest).
    let (_, err, code) = nctrans(&d, &["run", "I.MPF"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC639") && err.contains("LIFTFAST"), "{err}");
    let plain = prog.replace(" LIFTFAST", "");
    let d = write("interrupts-plain", &[("I.MPF", &plain)]);
    let (out, err, code) = nctrans(&d, &["run", "I.MPF"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("X=10"), "{out}");
    assert_eq!(err.matches("warning[NC566]").count(), 1, "{err}");
    assert!(err.contains("the run assumes the interrupt input never switches"), "{err}");
    // Without `[fanuc] macro_interrupt` every interrupt instruction is refused for FANUC.
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "I.MPF", "-o", "i.nc"]);
    assert_ne!(code, 0);
    assert_eq!(err.matches("error[NC566]").count(), 4, "{err}");
    assert!(err.contains("M96"), "{err}");
}

#[test]
fn a_batch_reports_the_look_ahead_settings_it_did_not_compare() {
    let d = write("batch", &[("HSC.MPF", "FFWON\nG1 X10 F100\nFFWOF\nM30\n")]);
    std::fs::create_dir_all(d.join("in")).unwrap();
    std::fs::rename(d.join("HSC.MPF"), d.join("in/HSC.MPF")).unwrap();
    let (out, err, code) = nctrans(&d, &["--to", "fanuc", "-o", "out/", "in/", "--report", "r.json"]);
    assert_eq!(code, 0, "{out}{err}");
    let json = std::fs::read_to_string(d.join("r.json")).unwrap();
    assert!(json.contains("\"not_compared\": {\"messages\": 0, \"look_ahead\": 2, \"interrupts\": 0}"), "{json}");
    assert!(format!("{out}{err}").contains("2 look-ahead settings not compared"), "{out}{err}");
}

#[test]
fn a_computed_spindle_speed_is_rounded_as_fanuc_rounds_it() {
    // From a tapping template: S from the cutting speed, 10 m/min on a 16 mm tap.
    let prog = "O1000\n#2=10.\n#5=16.\n#10=[[#2*1000.]/3.14159]/#5\nS#10 M03\nG01 X1. F100.\nS1000.6\nM05\nM30\n";
    let d = write("speed", &[("s.nc", prog)]);
    let (out, err, code) = nctrans(&d, &["run", "s.nc"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("spindle cw 199") && out.contains("spindle cw 1001"), "{out}");
    let (_, err, code) = nctrans(&d, &["--to", "sinumerik", "s.nc", "-o", "out/"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
    let mpf = std::fs::read_to_string(d.join("out/P_S.MPF")).unwrap();
    assert!(mpf.contains("S=ROUND(LOC10) M3") && mpf.contains("S1001"), "{mpf}");
    // And back: FANUC's own rounding is the ROUND.
    std::fs::copy(d.join("out/P_S.MPF"), d.join("BACK.MPF")).unwrap();
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "BACK.MPF", "-o", "back.nc"]);
    assert_eq!(code, 0, "{err}");
    let nc = std::fs::read_to_string(d.join("back.nc")).unwrap();
    assert!(!nc.contains("ROUND"), "{nc}");
}
