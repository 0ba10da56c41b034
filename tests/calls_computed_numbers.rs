//! Calls of a program chosen at run time (issue 21), both ways. Siemens → FANUC: with
//! `--l-numbers` (`[programs] l_numbers = true`) a program named `L<k>` is `O<k>`, so
//! `CALL "L"<<R1` is `G65 P#<R1>`, proven on each path the inputs take; the refusals where it
//! would not be the same program (option off, another prefix, a number not provably an
//! integer, a clash, a number beyond the series, parameters). FANUC → Sinumerik: `M98 P#1`
//! whose number is one of a few known values is a dispatch over the programs they name, each
//! path proven, a wrong branch caught; a number that may be any stays NC356.

#[path = "support/cli_run.rs"]
mod cli_run;

use cli_run::{nctrans, workdir};
use std::path::Path;

/// R2 picks L10 or L20; the programs are found beside the main program (any case).
const MAIN: &str = "R1=10\nIF R2>0\nR1=20\nENDIF\nG0 X0 Y0\nCALL \"L\"<<R1\nG1 X5 F300\nM30\n";

fn folder(name: &str, main: &str) -> std::path::PathBuf {
    let d = workdir("lnum", name);
    std::fs::write(d.join("MAIN.MPF"), main).unwrap();
    std::fs::write(d.join("l10.spf"), "G1 X10 F300\nM17\n").unwrap();
    std::fs::write(d.join("L20.SPF"), "G1 Y20 F300\nM17\n").unwrap();
    d
}

fn to_fanuc(d: &Path, extra: &[&str]) -> (String, String, i32) {
    let mut args = vec!["--to", "fanuc"];
    args.extend_from_slice(extra);
    args.push("MAIN.MPF");
    nctrans(d, &args)
}

#[test]
fn a_built_l_name_is_the_call_of_that_number_on_each_path() {
    for (set, callee) in [("", "X=10"), ("; nctrans: set R2=1\n", "Y=20")] {
        let d = folder(if set.is_empty() { "path10" } else { "path20" }, &format!("{set}{MAIN}"));
        let (out, err, code) = to_fanuc(&d, &["--l-numbers"]);
        assert_eq!(code, 0, "{out}{err}");
        assert!(err.contains("equivalent"), "{err}");
        assert!(
            out.contains("\nG65 P#501\n") && out.contains("\nO0010 (L10)\n") && out.contains("\nO0020 (L20)\n"),
            "{out}"
        );
        // The path the input takes runs the program it names.
        let (run, _, _) = nctrans(&d, &["run", "MAIN.MPF"]);
        assert!(run.contains(callee), "{run}");
        // Streamed: the same program.
        let (sout, serr, scode) = to_fanuc(&d, &["--l-numbers", "--stream"]);
        assert_eq!((scode, &sout), (0, &out), "{serr}");
    }
}

#[test]
fn a_planted_call_of_another_program_is_caught() {
    let d = folder("planted", MAIN);
    let (out, err, code) = to_fanuc(&d, &["--l-numbers", "-o", "main.nc"]);
    assert_eq!(code, 0, "{out}{err}");
    let text = std::fs::read_to_string(d.join("main.nc")).unwrap();
    let wrong = text.replace("G65 P#501\n", "G65 P[#501+10.]\n");
    assert_ne!(wrong, text);
    std::fs::write(d.join("wrong.nc"), wrong).unwrap();
    let (out, err, code) = nctrans(&d, &["check", "MAIN.MPF", "wrong.nc"]);
    assert_ne!(code, 0, "{out}{err}");
    let (_, _, code) = nctrans(&d, &["check", "MAIN.MPF", "main.nc"]);
    assert_eq!(code, 0);
}

#[test]
fn the_option_comes_from_nctrans_toml_too() {
    let d = folder("toml", MAIN);
    std::fs::write(d.join("nctrans.toml"), "[programs]\nl_numbers = true\n").unwrap();
    let (out, err, code) = to_fanuc(&d, &[]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("G65 P#501"), "{out}");
    std::fs::write(d.join("nctrans.toml"), "[programs]\nl_numbers = 1\n").unwrap();
    let (_, err, code) = to_fanuc(&d, &[]);
    assert_ne!(code, 0);
    assert!(err.contains("programs.l_numbers"), "{err}");
}

#[test]
fn without_the_option_the_call_is_refused_with_a_hint_naming_it() {
    let d = folder("off", MAIN);
    let (out, err, code) = to_fanuc(&d, &[]);
    assert_ne!(code, 0, "{out}");
    assert!(err.contains("NC585") && err.contains("--l-numbers") && err.contains("l_numbers = true"), "{err}");
}

#[test]
fn another_prefix_or_a_name_built_otherwise_stays_refused() {
    let d = folder("prefix", &MAIN.replace("\"L\"<<R1", "\"P\"<<R1"));
    std::fs::write(d.join("P10.SPF"), "G1 X10 F300\nM17\n").unwrap();
    let (_, err, code) = to_fanuc(&d, &["--l-numbers"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC585") && err.contains("only `\"L\"<<n`"), "{err}");
    let d = folder("twice", &MAIN.replace("\"L\"<<R1", "\"L\"<<R1<<\"\""));
    let (_, err, code) = to_fanuc(&d, &["--l-numbers"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC585"), "{err}");
    // The name kept in a STRING variable: FANUC has no strings to keep it in.
    let main =
        format!("DEF STRING[8] PRG_NAME\n{}", MAIN.replace("CALL \"L\"<<R1", "PRG_NAME=\"L\"<<R1\nCALL PRG_NAME"));
    let d = folder("string", &main);
    let (run, _, _) = nctrans(&d, &["run", "MAIN.MPF"]);
    assert!(run.contains("X=10"), "{run}");
    let (_, err, code) = to_fanuc(&d, &["--l-numbers"]);
    assert_ne!(code, 0);
    // The call through it names the reason (NC559: written from a concatenation).
    assert!(err.contains("NC559") && err.contains("concatenation"), "{err}");
}

#[test]
fn a_number_not_provably_an_integer_is_refused() {
    for (name, main) in [
        ("half", MAIN.replace("R1=20\n", "R1=20.5\n")),
        ("input", MAIN.replace("R1=20\n", "R1=R3\n")),
        ("product", MAIN.replace("R1=20\n", "R1=R1*2\n")),
    ] {
        let d = folder(name, &main);
        let (out, err, code) = to_fanuc(&d, &["--l-numbers"]);
        assert_ne!(code, 0, "{name}: {out}");
        assert!(err.contains("NC647") && err.contains("MAIN.MPF:6:"), "{name}: {err}");
    }
}

/// The folder's programs copied into `lib/`, the folder a batch reads.
fn library(d: &Path) {
    let lib = d.join("lib");
    std::fs::create_dir_all(&lib).unwrap();
    for f in ["MAIN.MPF", "l10.spf", "L20.SPF"] {
        std::fs::copy(d.join(f), lib.join(f)).unwrap();
    }
}

/// A batch under `--l-numbers` numbers each `L<k>` of the library `O<k>` in its map before
/// the mains (which take the next free numbers), loads every `L` program for a file with a
/// built call, and proves it on the path its inputs take; a rerun with the map written
/// gives the same output.
#[test]
fn a_batch_numbers_l_programs_by_their_number_and_proves_the_built_call() {
    let d = folder("batch", MAIN);
    library(&d);
    let (out, err, code) = nctrans(&d, &["--to", "fanuc", "--l-numbers", "-o", "out", "lib"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(format!("{out}{err}").contains("every file verified"), "{out}{err}");
    let main = std::fs::read_to_string(d.join("out/MAIN.NC")).unwrap();
    assert!(main.contains("\nG65 P#501\n") && main.contains("\nO0010 (L10)\n"), "{main}");
    assert!(main.starts_with("%\nO0001 (MAIN)"), "the main takes the first free number: {main}");
    let map = std::fs::read_to_string(d.join("out/nctrans-map.toml")).unwrap();
    assert!(map.contains("\"L10\" = \"O0010\"") && map.contains("\"L20\" = \"O0020\""), "{map}");
    // Without the option the same batch refuses the call, naming the option.
    let (out, err, code) = nctrans(&d, &["--to", "fanuc", "-o", "out2", "lib"]);
    assert_ne!(code, 0, "{out}{err}");
    assert!(format!("{out}{err}").contains("NC585"), "{out}{err}");
}

/// The batch's proof runs the path the source's inputs choose: R2=1 calls L20 there.
#[test]
fn a_batch_proves_the_other_path_and_catches_a_planted_wrong_number() {
    let d = folder("batch-path", &format!("; nctrans: set R2=1\n{MAIN}"));
    library(&d);
    let (out, err, code) = nctrans(&d, &["--to", "fanuc", "--l-numbers", "-o", "out", "lib"]);
    assert_eq!(code, 0, "{out}{err}");
    let main = std::fs::read_to_string(d.join("out/MAIN.NC")).unwrap();
    // Plant the wrong program: the check of the source against it diverges.
    std::fs::write(d.join("bad.nc"), main.replace("G65 P#501", "G65 P10")).unwrap();
    let (out, err, code) = nctrans(&d, &["check", "lib/MAIN.MPF", "bad.nc"]);
    assert_ne!(code, 0, "{out}{err}");
    assert!(format!("{out}{err}").contains("diverge"), "{out}{err}");
}

/// A DIN subprogram file without a PROC line is called by its file name in a batch as in a
/// single-file translation (`L20` on a line of its own).
#[test]
fn a_batch_finds_a_din_subprogram_by_its_file_name() {
    let d = workdir("lnum", "batch-din");
    let lib = d.join("lib");
    std::fs::create_dir_all(&lib).unwrap();
    std::fs::write(lib.join("MAIN.MPF"), "G0 X0 Y0\nL20\nM30\n").unwrap();
    std::fs::write(lib.join("L20.SPF"), "G1 Y20 F300\nM17\n").unwrap();
    let (out, err, code) = nctrans(&d, &["--to", "fanuc", "-o", "out", "lib"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(format!("{out}{err}").contains("every file verified"), "{out}{err}");
    let main = std::fs::read_to_string(d.join("out/MAIN.NC")).unwrap();
    assert!(main.contains("\nM98 P9000\n") || main.contains("\nG65 P9000\n"), "{main}");
}

/// An INT variable is an integer wherever it is read (Siemens rounds on assignment), so an
/// input may choose the program.
#[test]
fn an_int_variable_set_from_an_input_chooses_the_program() {
    let main = "; nctrans: set R2=19.6\nDEF INT NUM_K\nNUM_K=R2\nCALL \"L\"<<NUM_K\nM30\n";
    let d = folder("int", main);
    let (out, err, code) = to_fanuc(&d, &["--l-numbers"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(err.contains("equivalent") && out.contains("G65 P#"), "{out}{err}");
    let (run, _, _) = nctrans(&d, &["run", "MAIN.MPF"]);
    assert!(run.contains("Y=20"), "{run}");
}

#[test]
fn an_l_program_whose_number_is_taken_is_refused() {
    // O0001 is the main program's.
    let d = folder("clash-main", MAIN);
    std::fs::write(d.join("L1.SPF"), "G1 Z1 F300\nM17\n").unwrap();
    let (_, err, code) = to_fanuc(&d, &["--l-numbers"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC648") && err.contains("L1") && err.contains("MAIN"), "{err}");
    // A mapped program holds O0020.
    let d = folder("clash-map", &MAIN.replace("M30\n", "CONTOUR\nM30\n"));
    std::fs::write(d.join("CONTOUR.SPF"), "PROC CONTOUR\nG1 Z2 F300\nM17\n").unwrap();
    let (_, err, code) = to_fanuc(&d, &["--l-numbers", "--program-map", "CONTOUR=20"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC648") && err.contains("L20") && err.contains("CONTOUR"), "{err}");
    // A map entry that numbers L20 otherwise: the built call would miss it.
    let d = folder("mapped", MAIN);
    let (_, err, code) = to_fanuc(&d, &["--l-numbers", "--program-map", "L20=9100"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC648") && err.contains("O9100"), "{err}");
    // Without the built call, the programs translate: L1 is numbered from O9000 up.
    let d = folder("clash-named", "L1\nM30\n");
    std::fs::write(d.join("L1.SPF"), "G1 Z1 F300\nM17\n").unwrap();
    let (out, err, code) = to_fanuc(&d, &["--l-numbers"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("O9000 (L1)"), "{out}");
}

#[test]
fn an_l_number_beyond_the_series_is_refused() {
    let d = folder("digits", MAIN);
    std::fs::write(d.join("L12345.SPF"), "G1 Z1 F300\nM17\n").unwrap();
    let (_, err, code) = to_fanuc(&d, &["--l-numbers"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC649") && err.contains("L12345") && err.contains("9999"), "{err}");
    // Eight digits on the 30i class.
    std::fs::write(d.join("nctrans.toml"), "[fanuc]\nseries = \"30i\"\n").unwrap();
    let (out, err, code) = to_fanuc(&d, &["--l-numbers"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("O12345 (L12345)"), "{out}");
}

#[test]
fn a_reachable_program_with_parameters_is_refused() {
    let d = folder("params", MAIN);
    std::fs::write(d.join("L20.SPF"), "PROC L20(REAL U_A)\nG1 Y=U_A F300\nM17\n").unwrap();
    let (_, err, code) = to_fanuc(&d, &["--l-numbers"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC650") && err.contains("L20") && err.contains("parameters"), "{err}");
}

/// A name of `L` with a leading zero is another program: `"L"<<10` never names `L010`.
#[test]
fn a_leading_zero_name_is_not_reached() {
    let d = folder("zero", MAIN);
    std::fs::write(d.join("L010.SPF"), "G1 Z9 F300\nM17\n").unwrap();
    let (out, err, code) = to_fanuc(&d, &["--l-numbers"]);
    assert_eq!(code, 0, "{err}");
    assert!(!out.contains("L010") && !out.contains("Z9"), "{out}");
}

// ---- FANUC → Sinumerik ----

/// #2 picks O0176 or, by default, O0177; #3 a packed count (`P20176`: O0176 twice).
const JOB: &str = "O0100\n#1=177\nIF [#2 GT 0] THEN #1=176\nIF [#3 GT 0] THEN #1=20176\nIF [#4 GT 0] THEN #1=175.6\n\
                   G0 X0 Y0\nM98 P#1\nG0 X0 Y0\nM30\nO0176\nG91 G1 X20. F300.\nG90\nM99\nO0177\nG1 Y20. F300.\nM99\n";

fn fanuc_job(name: &str, set: &str) -> std::path::PathBuf {
    let d = workdir("dispatch", name);
    std::fs::write(d.join("O0100.nc"), format!("{set}{JOB}")).unwrap();
    d
}

#[test]
fn a_number_of_a_few_values_calls_each_program_it_names_on_each_path() {
    for (name, set, events) in [
        ("default", "", "Y=20"),
        ("o176", "(nctrans: set #2=1.)\n", "X=20"),
        ("packed", "(nctrans: set #3=1.)\n", "X=40"),
        ("rounded", "(nctrans: set #4=1.)\n", "X=20"),
    ] {
        let d = fanuc_job(name, set);
        let (out, err, code) = nctrans(&d, &["--to", "sinumerik", "O0100.nc", "-o", "m.mpf"]);
        assert_eq!(code, 0, "{name}: {out}{err}");
        assert!(err.contains("equivalent"), "{name}: {err}");
        let main = std::fs::read_to_string(d.join("m.mpf")).unwrap();
        assert!(main.contains("IF ROUND(LOC1)-176<>0 GOTOF") && main.contains("\nO_0176\n"), "{main}");
        assert!(main.contains("O_0176 P=TRUNC(ROUND(LOC1)/10000)"), "{main}");
        assert!(!main.contains("NCTRANS_NO_PROG"), "every value names a program: {main}");
        let (run, _, _) = nctrans(&d, &["run", "O0100.nc"]);
        assert!(run.contains(events), "{name}: {run}");
    }
}

#[test]
fn a_planted_wrong_branch_is_caught() {
    let d = fanuc_job("planted", "");
    let (out, err, code) = nctrans(&d, &["--to", "sinumerik", "O0100.nc", "-o", "m.mpf"]);
    assert_eq!(code, 0, "{out}{err}");
    let main = std::fs::read_to_string(d.join("m.mpf")).unwrap();
    // The default path (#1=177) calls O_0176 in place of O_0177.
    let wrong = main.replace("O_0177\n", "O_0176\n");
    assert_ne!(wrong, main);
    std::fs::write(d.join("WRONG.MPF"), wrong).unwrap();
    let (out, err, code) = nctrans(&d, &["check", "O0100.nc", "WRONG.MPF"]);
    assert_ne!(code, 0, "{out}{err}");
    let (_, err, code) = nctrans(&d, &["check", "O0100.nc", "m.mpf"]);
    assert_eq!(code, 0, "{err}");
}

/// A value that names no program of the file: Siemens' own "program not found", as FANUC
/// stops there.
#[test]
fn a_value_naming_no_program_is_the_not_found_call() {
    let d = workdir("dispatch", "missing");
    let job = JOB.replace("IF [#3 GT 0] THEN #1=20176\n", "IF [#3 GT 0] THEN #1=500\n");
    std::fs::write(d.join("O0100.nc"), format!("(nctrans: set #2=1.)\n{job}")).unwrap();
    let (out, err, code) = nctrans(&d, &["--to", "sinumerik", "O0100.nc", "-o", "m.mpf"]);
    assert_eq!(code, 0, "{out}{err}");
    let main = std::fs::read_to_string(d.join("m.mpf")).unwrap();
    assert!(main.contains("NCTRANS_NO_PROG"), "{main}");
    // That path fails on both controls.
    std::fs::write(d.join("O0101.nc"), job.replace("O0100", "O0101").replace("#1=177\n", "#1=177\n#3=1.\n")).unwrap();
    let (_, err, code) = nctrans(&d, &["run", "O0101.nc"]);
    assert_ne!(code, 0);
    assert!(err.contains("O500"), "{err}");
}

#[test]
fn a_number_that_may_be_any_or_a_call_with_words_stays_refused() {
    for (name, job) in [
        ("input", JOB.replace("#1=177\n", "#1=#5041\n")),
        ("words", JOB.replace("G0 X0 Y0\nM98 P#1", "G0 X0 Y0 M98 P#1")),
        ("main", JOB.replace("#1=20176", "#1=100")),
    ] {
        let d = fanuc_job(name, "");
        std::fs::write(d.join("O0100.nc"), job).unwrap();
        let (_, err, code) = nctrans(&d, &["--to", "sinumerik", "O0100.nc", "-o", "m.mpf"]);
        assert_ne!(code, 0, "{name}");
        assert!(err.contains("NC356"), "{name}: {err}");
    }
}
