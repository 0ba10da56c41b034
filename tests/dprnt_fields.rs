//! DPRNT number fields and external output (issue 21): no stored source settles the text a
//! field `#v[ab]` prints (docs/semantics.md, "External output"), so a run warns NC554 and prints
//! nothing for that line, a check with one is never "equivalent" (a different field format is
//! inconclusive, a Siemens WRITE of any digits diverges), the translation to Sinumerik refuses it
//! (NC556), BPRNT stays NC554 / NC510, a format the Haas manual calls illegal is an error on the
//! Haas profile (NC587), and Siemens EXTOPEN / EXTCLOSE are refused by name (NC586) instead of
//! being looked up as programs.

#[path = "support/cli_run.rs"]
mod cli_run;

use cli_run::{nctrans, workdir};

/// A probe-style report line: text, then X with four integer and three fraction places.
fn report(format: &str) -> String {
    format!(
        "O0170\n#1=12.3456\n#2=-0.5\nG0 X0 Y0\nPOPEN\nDPRNT[BORE*1]\nDPRNT[X#1[{format}]*Y#2[{format}]]\nPCLOS\nM30\n"
    )
}

#[test]
fn a_number_field_warns_nc554_naming_what_is_unsettled_and_prints_nothing() {
    let d = workdir("dprnt-fields", "run");
    std::fs::write(d.join("O0170.nc"), report("43")).unwrap();
    let (out, err, code) = nctrans(&d, &["run", "O0170.nc"]);
    assert_eq!(code, 0, "{err}");
    // The text line prints; the line with fields does not (its text is not modelled).
    assert!(out.contains("print \"BORE 1\""), "{out}");
    assert_eq!(out.matches("print ").count(), 1, "{out}");
    assert!(err.contains("NC554") && err.contains("`#1[43]`"), "{err}");
    for what in ["leading spaces or zeros", "the sign's place", "the rounding", "a vacant variable"] {
        assert!(err.contains(what), "{what}: {err}");
    }
    // A vacant variable in a field is the same: warned, not printed.
    std::fs::write(d.join("O0171.nc"), "O0171\nDPRNT[X#1[43]]\nM30\n").unwrap();
    let (out, err, code) = nctrans(&d, &["run", "O0171.nc"]);
    assert_eq!(code, 0, "{err}");
    assert!(!out.contains("print"), "{out}");
    assert!(err.contains("NC554") && err.contains("`#1[43]`"), "{err}");
}

#[test]
fn programs_that_print_other_digits_are_never_called_equivalent() {
    let d = workdir("dprnt-fields", "check");
    std::fs::write(d.join("A.nc"), report("43")).unwrap();
    // A planted change of the places: the motion agrees, the output is not compared.
    std::fs::write(d.join("B.nc"), report("53")).unwrap();
    let (out, err, code) = nctrans(&d, &["check", "A.nc", "B.nc"]);
    assert_eq!(code, 4, "{out}{err}");
    assert!(out.contains("inconclusive") && out.contains("NC554"), "{out}");
    // A hand translation that writes the digits (right or wrong) is not taken on trust.
    for digits in ["X 12.346 Y -0.500", "X 12.345 Y -0.500"] {
        let siemens =
            format!("DEF INT WERR\nG0 X0 Y0\nWRITE(WERR,\"LOG\",\"BORE 1\")\nWRITE(WERR,\"LOG\",\"{digits}\")\nM30\n");
        std::fs::write(d.join("HAND.MPF"), siemens).unwrap();
        let (out, err, code) = nctrans(&d, &["check", "A.nc", "HAND.MPF"]);
        assert_eq!(code, 1, "{digits}: {out}{err}");
        assert!(out.contains("diverged"), "{out}");
    }
}

#[test]
fn the_translation_to_sinumerik_refuses_a_field_with_nc556() {
    let d = workdir("dprnt-fields", "to-sinumerik");
    std::fs::write(d.join("O0170.nc"), report("43")).unwrap();
    let (_, err, code) = nctrans(&d, &["--to", "sinumerik", "O0170.nc", "-o", "o.mpf"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC556") && err.contains("#1[43]") && err.contains("SPRINT"), "{err}");
    assert!(!d.join("o.mpf").exists());
    // Under the warn policy the rest translates and the field line is marked, not guessed.
    let (_, err, code) = nctrans(&d, &["--to", "sinumerik", "--unsupported", "warn", "O0170.nc", "-o", "w.mpf"]);
    assert_ne!(code, 0, "{err}");
    let text = std::fs::read_to_string(d.join("w.mpf")).unwrap();
    assert!(text.contains("WRITE(NCTRANS_WERR,\"NCTRANS_PRINT\",\"BORE 1\")"), "{text}");
    assert!(text.contains("; NCTRANS UNSUPPORTED: the DPRNT number field `#1[43]`"), "{text}");
    assert_eq!(text.matches("WRITE(").count(), 1, "{text}");
}

#[test]
fn bprnt_and_a_dprnt_not_read_stay_refused() {
    let d = workdir("dprnt-fields", "bprnt");
    std::fs::write(d.join("O0172.nc"), "O0172\nPOPEN\nBPRNT[X#1[3]]\nPCLOS\nM30\n").unwrap();
    let (out, err, code) = nctrans(&d, &["run", "O0172.nc"]);
    assert_eq!(code, 0, "{err}");
    assert!(!out.contains("print"), "{out}");
    assert!(err.contains("NC554") && err.contains("binary output"), "{err}");
    let (_, err, code) = nctrans(&d, &["--to", "sinumerik", "O0172.nc", "-o", "o.mpf"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC510"), "{err}");
}

#[test]
fn extopen_and_extclose_are_refused_by_name_not_looked_up_as_programs() {
    let d = workdir("dprnt-fields", "extopen");
    let text = "DEF INT ERR\nEXTOPEN(ERR,\"/dev/ext/1\",\"SYN\",\"EXCL\")\nWRITE(ERR,\"/dev/ext/1\",\"BORE OK\")\n\
                extclose(ERR,\"/dev/ext/1\")\nM30\n";
    std::fs::write(d.join("LOG.MPF"), text).unwrap();
    let (out, err, code) = nctrans(&d, &["parse", "LOG.MPF"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("instruction EXTOPEN(ERR,\"/dev/ext/1\",\"SYN\",\"EXCL\")"), "{out}");
    assert!(out.contains("instruction EXTCLOSE(ERR,\"/dev/ext/1\")"), "{out}");
    let (_, err, code) = nctrans(&d, &["run", "LOG.MPF"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC586") && err.contains("external device") && err.contains("extdev.ini"), "{err}");
    assert!(!err.contains("NC401"), "{err}");
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "LOG.MPF", "-o", "log.nc"]);
    assert_ne!(code, 0);
    assert!(err.contains("EXTOPEN(") && err.contains("EXTCLOSE("), "{err}");
    assert!(err.contains("NC586") && err.contains("POPEN"), "refused naming the device and FANUC's POPEN: {err}");
    assert!(!err.contains("NC303"), "{err}");
    // Streamed, the same refusal.
    let (_, err, code) = nctrans(&d, &["run", "--stream", "LOG.MPF"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC586"), "{err}");
}

#[test]
fn a_field_haas_calls_illegal_is_an_error_on_the_haas_profile_only() {
    let d = workdir("dprnt-fields", "haas");
    std::fs::write(d.join("O0173.nc"), "O0173\n#1=1.5\nDPRNT[X#1[54]]\nM30\n").unwrap();
    // FANUC: the sources give no limit; the field warns as any other.
    let (_, err, code) = nctrans(&d, &["run", "O0173.nc"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("NC554") && !err.contains("NC587"), "{err}");
    std::fs::write(d.join("nctrans.toml"), "[fanuc]\nseries = \"haas\"\n").unwrap();
    let (_, err, code) = nctrans(&d, &["run", "O0173.nc"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC587") && err.contains("`#1[54]`") && err.contains("1..8"), "{err}");
    for ok in ["44", "80", "08"] {
        std::fs::write(d.join("O0174.nc"), format!("O0174\n#1=1.5\nDPRNT[X#1[{ok}]]\nM30\n")).unwrap();
        let (_, err, code) = nctrans(&d, &["run", "O0174.nc"]);
        assert_eq!(code, 0, "[{ok}] {err}");
        assert!(err.contains("NC554") && !err.contains("NC587"), "{err}");
    }
    std::fs::write(d.join("O0175.nc"), "O0175\nDPRNT[X#1[00]]\nM30\n").unwrap();
    let (_, err, code) = nctrans(&d, &["run", "O0175.nc"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC587") && err.contains("`#1[00]`"), "{err}");
}
