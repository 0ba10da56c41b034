//! Text output (issue 21): FANUC `DPRNT[…]` and Siemens `WRITE(err, "file", text)` are the
//! trace's `print` events, translated both ways where the text is carried exactly, and a
//! translation that prints another text is caught.

#[path = "support/cli_run.rs"]
mod cli_run;

use cli_run::{nctrans, workdir};

const FANUC: &str = "O0161\nG0 X0 Y0\nPOPEN\nDPRNT[PART*7731*OK]\nPCLOS\nG1 X5. F100.\nM30\n";
const SIEMENS: &str = "DEF INT WERR\nG0 X0 Y0\nWRITE(WERR,\"LOG\",\"PART 7731 OK\")\nG1 X5 F100\nM30\n";

#[test]
fn dprnt_and_write_print_the_same_line_and_translate_both_ways() {
    let d = workdir("print", "both");
    std::fs::write(d.join("O0161.nc"), FANUC).unwrap();
    std::fs::write(d.join("LOG_PART.MPF"), SIEMENS).unwrap();
    let (out, err, code) = nctrans(&d, &["run", "O0161.nc"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("print \"PART 7731 OK\""), "{out}");
    let (out, err, code) = nctrans(&d, &["run", "--format", "jsonl", "LOG_PART.MPF"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("{\"ev\":\"print\",\"text\":\"PART 7731 OK\""), "{out}");
    let (out, err, code) = nctrans(&d, &["check", "O0161.nc", "LOG_PART.MPF"]);
    assert_eq!(code, 0, "{out}{err}");
    // FANUC -> Siemens: WRITE to the profile's file, said in a comment.
    std::fs::write(d.join("nctrans.toml"), "[sinumerik]\nwrite_file = \"PROBE_LOG\"\n").unwrap();
    let (_, err, code) = nctrans(&d, &["--to", "sinumerik", "O0161.nc", "-o", "o.mpf"]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(d.join("o.mpf")).unwrap();
    assert!(text.contains("DEF INT NCTRANS_WERR"), "{text}");
    assert!(text.contains("WRITE(NCTRANS_WERR,\"PROBE_LOG\",\"PART 7731 OK\")"), "{text}");
    assert!(text.contains("; DPRNT lines are written to file PROBE_LOG"), "{text}");
    // Siemens -> FANUC: POPEN, DPRNT with * for each space, PCLOS.
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "LOG_PART.MPF", "-o", "log.nc"]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(d.join("log.nc")).unwrap();
    assert!(text.contains("POPEN") && text.contains("DPRNT[PART*7731*OK]\n") && text.contains("PCLOS"), "{text}");
}

#[test]
fn a_planted_wrong_text_is_caught() {
    let d = workdir("print", "planted");
    std::fs::write(d.join("O0161.nc"), FANUC).unwrap();
    std::fs::write(d.join("WRONG.MPF"), SIEMENS.replace("7731", "7713")).unwrap();
    let (out, _, code) = nctrans(&d, &["check", "O0161.nc", "WRONG.MPF"]);
    assert_ne!(code, 0, "{out}");
    assert!(out.contains("PART 7713 OK") && out.contains("PART 7731 OK"), "{out}");
    // A translation that lost the line is caught as well.
    std::fs::write(d.join("LOST.nc"), FANUC.replace("DPRNT[PART*7731*OK]\n", "")).unwrap();
    let (out, _, code) = nctrans(&d, &["check", "O0161.nc", "LOST.nc"]);
    assert_ne!(code, 0, "{out}");
}

#[test]
fn text_that_cannot_be_carried_is_refused_by_name() {
    let d = workdir("print", "refused");
    let built = "DEF INT WERR\nDEF STRING[20] TXT\nR1=2\nTXT=\"D\"<<R1\nWRITE(WERR,\"LOG\",TXT)\nM30\n";
    std::fs::write(d.join("BUILT.MPF"), built).unwrap();
    let (out, err, code) = nctrans(&d, &["run", "BUILT.MPF"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("print \"D2\""), "{out}");
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "BUILT.MPF", "-o", "b.nc"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC557") && err.contains("computed text"), "{err}");
    std::fs::write(d.join("DOT.MPF"), "DEF INT WERR\nWRITE(WERR,\"LOG\",\"DIA 20.5\")\nM30\n").unwrap();
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "DOT.MPF", "-o", "d.nc"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC557") && err.contains("`.`"), "{err}");
    std::fs::write(d.join("BAD.MPF"), "WRITE(\"LOG\",\"X\")\nM30\n").unwrap();
    let (_, err, code) = nctrans(&d, &["parse", "BAD.MPF"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC555"), "{err}");
    // A DPRNT with a literal space is kept as written and not compared.
    std::fs::write(d.join("O0162.nc"), "O0162\nDPRNT[A B]\nM30\n").unwrap();
    let (_, err, code) = nctrans(&d, &["run", "O0162.nc"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("NC554"), "{err}");
    let (_, err, code) = nctrans(&d, &["--to", "sinumerik", "O0162.nc", "-o", "o.mpf"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC510"), "{err}");
}

#[test]
fn the_write_file_must_be_a_program_memory_name() {
    let d = workdir("print", "file");
    std::fs::write(d.join("O0161.nc"), FANUC).unwrap();
    std::fs::write(d.join("nctrans.toml"), "[sinumerik]\nwrite_file = \"LOG FILE\"\n").unwrap();
    let (_, err, code) = nctrans(&d, &["--to", "sinumerik", "O0161.nc", "-o", "o.mpf"]);
    assert_ne!(code, 0);
    assert!(err.contains("sinumerik.write_file"), "{err}");
}
