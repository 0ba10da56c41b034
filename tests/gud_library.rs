//! Global user data (issue 21): `.DEF` definition files of a Siemens library are found
//! beside the programs (or listed in `[sinumerik] definitions`) and applied in `run`, in a
//! single-file translation and in a batch; a GUD variable goes to FANUC commons only where
//! a `--var-map` rule puts it (NC504 otherwise), and two different definitions of one name
//! are refused (NC503).

#[path = "support/cli_run.rs"]
mod cli_run;

use cli_run::{nctrans, workdir};
use std::path::Path;

const GUD: &str = "%_N_MGUD_DEF\n;$PATH=/_N_DEF_DIR\nDEF NCK REAL DEPTH[4]\nDef Nck Real FEEDR=250\nDEF CHAN INT PASSES\nDEF NCK STRING[20] SHAPE\nM30\n";

const SUB: &str = "PROC ROUGH\nDEPTH[2]=-5\nPASSES=PASSES+1\nG1 Z=DEPTH[2] F=FEEDR\nRET\n";

const MAIN: &str = "G0 X0 Y0 Z10\nDEPTH[1]=-2.5\nG1 Z=DEPTH[1] F=FEEDR\nROUGH\nG0 Z=10+PASSES\nM30\n";

/// A library: `DEF/MGUD.DEF`, `CMA/ROUGH.SPF`, `CMA/PART.MPF`.
fn library(name: &str) -> std::path::PathBuf {
    let d = workdir("gud", name);
    std::fs::create_dir_all(d.join("DEF")).unwrap();
    std::fs::create_dir_all(d.join("CMA")).unwrap();
    std::fs::write(d.join("DEF/MGUD.DEF"), GUD).unwrap();
    std::fs::write(d.join("CMA/ROUGH.SPF"), SUB).unwrap();
    std::fs::write(d.join("CMA/PART.MPF"), MAIN).unwrap();
    d
}

#[test]
fn run_declares_the_global_user_data_of_the_library() {
    let d = library("run");
    let (out, err, code) = nctrans(&d, &["run", "CMA/PART.MPF"]);
    assert_eq!(code, 0, "{err}");
    // DEPTH[1] from the program, FEEDR at its definition's start value, PASSES counted in the callee.
    assert!(out.contains("Z=-2.5 f=250"), "{out}");
    assert!(out.contains("Z=-5 f=250"), "{out}");
    assert!(out.contains("Z=11"), "{out}");
    // Without the definition file the name is unknown, as before.
    std::fs::remove_file(d.join("DEF/MGUD.DEF")).unwrap();
    let (_, err, code) = nctrans(&d, &["run", "CMA/PART.MPF"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC412"), "{err}");
}

#[test]
fn translation_needs_a_rule_for_global_user_data() {
    let d = library("translate");
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "CMA/PART.MPF", "-o", "part.nc"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC504") && err.contains("--var-map DEPTH=#n"), "{err}");
    let (_, err, code) = nctrans(
        &d,
        &["--to", "fanuc", "CMA/PART.MPF", "-o", "part.nc", "--var-map", "DEPTH=#500,FEEDR=#504,PASSES=#505"],
    );
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
    let out = std::fs::read_to_string(d.join("part.nc")).unwrap();
    assert!(out.contains("#501=-2.5") && out.contains("F#504") && out.contains("#505=#505+1."), "{out}");
    assert!(out.contains("DEPTH[…] [4 elements, global user data] = #500"), "{out}");
    // Commons that are not retained are refused for data that outlives the program.
    let (_, err, code) = nctrans(
        &d,
        &["--to", "fanuc", "CMA/PART.MPF", "-o", "p2.nc", "--var-map", "DEPTH=#100,FEEDR=#504,PASSES=#505"],
    );
    assert_ne!(code, 0);
    assert!(err.contains("NC504") && err.contains("not retained"), "{err}");
}

#[test]
fn definitions_listed_in_the_configuration_apply() {
    let d = workdir("gud", "config");
    std::fs::create_dir_all(d.join("defs")).unwrap();
    std::fs::write(d.join("defs/UGUD.DEF"), GUD).unwrap();
    std::fs::write(d.join("PART.MPF"), "G0 X0 Z10\nG1 Z=FEEDR/100 F100\nM30\n").unwrap();
    std::fs::write(
        d.join("nctrans.toml"),
        "[sinumerik]\ndefinitions = [\"defs/UGUD.DEF\"]\n[variables]\nto_fanuc = [\"FEEDR=#600\"]\n",
    )
    .unwrap();
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "PART.MPF", "-o", "part.nc"]);
    assert_eq!(code, 0, "{err}");
    let out = std::fs::read_to_string(d.join("part.nc")).unwrap();
    assert!(out.contains("Z[#600/100.]"), "{out}");
}

#[test]
fn a_batch_gives_every_program_the_same_homes() {
    let d = library("batch");
    std::fs::write(
        d.join("nctrans.toml"),
        "[variables]\nto_fanuc = [\"DEPTH=#500\", \"FEEDR=#504\", \"PASSES=#505\"]\n",
    )
    .unwrap();
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "-o", "out", "CMA", "--report", "r.json"]);
    assert_eq!(code, 0, "{err}");
    let report = std::fs::read_to_string(d.join("r.json")).unwrap();
    assert_eq!(report.matches("\"status\": \"verified\"").count(), 2, "{report}");
}

#[test]
fn string_data_and_two_definitions_are_refused_precisely() {
    let d = library("refused");
    std::fs::write(d.join("CMA/NAME.MPF"), "SHAPE=\"TRI\"\nM30\n").unwrap();
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "CMA/NAME.MPF", "-o", "n.nc"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC504") && err.contains("STRING[20] SHAPE"), "{err}");
    // A second file beside the first defines DEPTH otherwise: which one holds is unclear.
    std::fs::write(d.join("DEF/UGUD.DEF"), "DEF NCK REAL DEPTH[8]\nM30\n").unwrap();
    let (_, err, code) = nctrans(&d, &["run", "CMA/PART.MPF"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC503") && err.contains("DEPTH"), "{err}");
    assert!(Path::new(&d.join("DEF/UGUD.DEF")).exists());
}

const MACROS: &str =
    "; macro definitions\nDEFINE MAXSTAGE AS 3\nDEFINE LINE AS G1 G94 F300\nDEF NCK REAL STAGE_Z[MAXSTAGE]\nM30\n";

#[test]
fn define_macros_apply_to_programs_and_dimensions() {
    let d = workdir("gud", "macros");
    std::fs::write(d.join("UMAC.DEF"), MACROS).unwrap();
    std::fs::write(
        d.join("STAGES.MPF"),
        "DEF INT KS\nG0 X0 Z5\nFOR KS=0 TO MAXSTAGE-1\nSTAGE_Z[KS]=-KS-1\nLINE Z=STAGE_Z[KS]\nENDFOR\nM30\n",
    )
    .unwrap();
    let (out, err, code) = nctrans(&d, &["run", "STAGES.MPF"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("Z=-3 f=300"), "{out}");
    assert!(!out.contains("Z=-4"), "{out}");
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "STAGES.MPF", "-o", "s.nc", "--var-map", "STAGE_Z=#700"]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(d.join("s.nc")).unwrap();
    assert!(text.contains("WHILE [#100 LE 3.-1.] DO1") && text.contains("G01 G94 F300. Z#[#100+700.]"), "{text}");
    // An error inside a macro's text points at the macro's name in the program.
    std::fs::write(d.join("BAD.MPF"), "G0 X0\nLINE X=\nM30\n").unwrap();
    let (_, err, code) = nctrans(&d, &["parse", "BAD.MPF"]);
    assert_ne!(code, 0);
    assert!(err.contains("BAD.MPF:2:"), "{err}");
    // Macros do not nest.
    std::fs::write(d.join("UMAC.DEF"), "DEFINE A1 AS 2\nDEFINE B1 AS A1*2\nM30\n").unwrap();
    let (_, err, code) = nctrans(&d, &["run", "STAGES.MPF"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC503") && err.contains("do not nest"), "{err}");
}

#[test]
fn check_reads_both_sides_with_the_library_definitions() {
    let d = library("check");
    // The same job written with a plain DEF: equivalent to the GUD program.
    std::fs::write(d.join("CMA/PLAIN.MPF"), MAIN.replace("ROUGH\n", "G1 Z-5 F250\n").replace("10+PASSES", "11"))
        .unwrap();
    let (out, err, code) = nctrans(&d, &["check", "CMA/PART.MPF", "CMA/PLAIN.MPF"]);
    assert_eq!(code, 0, "{err}");
    assert!(format!("{out}{err}").contains("equivalent"), "{out}{err}");
}

/// A part that reads global user data with a `.DEF` start value (DEPTH) and without one (OFS).
const SEEDED_DEF: &str = "DEF NCK REAL DEPTH=5\nDEF NCK REAL OFS\nM30\n";
const SEEDED: &str = "G54 G90 G17\nG0 X0 Y0 Z50\nG1 Z=-DEPTH F100\nG1 X=OFS\nG0 Z50\nM30\n";

/// `nctrans check` of a Siemens program against its FANUC translation starts the commons
/// holding the global user data as the translation's proof does, and says so.
#[test]
fn check_seeds_the_fanuc_commons_of_global_user_data_as_the_proof_does() {
    let d = workdir("gud", "check_seeds");
    std::fs::write(d.join("MGUD.DEF"), SEEDED_DEF).unwrap();
    std::fs::write(d.join("PART.MPF"), SEEDED).unwrap();
    let (_, err, code) =
        nctrans(&d, &["--to", "fanuc", "PART.MPF", "-o", "part.nc", "--var-map", "DEPTH=#600,OFS=#601"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
    // The proof's verdict is check's: the homes come from the output's own header.
    let (out, err, code) = nctrans(&d, &["check", "PART.MPF", "part.nc"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.starts_with("equivalent ("), "{out}");
    assert!(out.contains("global user data started on FANUC") && out.contains("DEPTH #600=5, OFS #601=0"), "{out}");
    // Either order.
    let (out, _, code) = nctrans(&d, &["check", "part.nc", "PART.MPF"]);
    assert_eq!(code, 0, "{out}");
    // A planted wrong translation (DEPTH read where OFS lives) is still caught.
    let text = std::fs::read_to_string(d.join("part.nc")).unwrap();
    std::fs::write(d.join("wrong.nc"), text.replace("G01 X#601", "G01 X#600")).unwrap();
    let (out, _, code) = nctrans(&d, &["check", "PART.MPF", "wrong.nc"]);
    assert_eq!(code, 1, "{out}");
    assert!(out.starts_with("diverged at trace event 4") && out.contains("assumed: global user data"), "{out}");
}

/// The same two programs, differing only in whether the FANUC side's commons are seeded:
/// without any rule placing DEPTH the commons start vacant (divergent); with the project's
/// `[variables] to_fanuc` rule, or a `--map` file's, they start at the definition's value.
#[test]
fn check_seeds_only_where_a_rule_places_the_global_user_data() {
    let d = workdir("gud", "check_rules");
    std::fs::write(d.join("MGUD.DEF"), SEEDED_DEF).unwrap();
    std::fs::write(d.join("PART.MPF"), SEEDED).unwrap();
    let (_, err, code) =
        nctrans(&d, &["--to", "fanuc", "PART.MPF", "-o", "part.nc", "--var-map", "DEPTH=#600,OFS=#601"]);
    assert_eq!(code, 0, "{err}");
    // A hand-kept copy without the translation's header lines.
    let text = std::fs::read_to_string(d.join("part.nc")).unwrap();
    let bare: String = text.lines().filter(|l| !l.contains("global user data")).map(|l| format!("{l}\n")).collect();
    std::fs::write(d.join("bare.nc"), &bare).unwrap();
    let (out, _, code) = nctrans(&d, &["check", "PART.MPF", "bare.nc"]);
    assert_eq!(code, 1, "{out}");
    assert!(!out.contains("assumed"), "{out}");
    // The project's rule places them.
    std::fs::write(d.join("nctrans.toml"), "[variables]\nto_fanuc = [\"DEPTH=#600\", \"OFS=#601\"]\n").unwrap();
    let (out, err, code) = nctrans(&d, &["check", "PART.MPF", "bare.nc"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("DEPTH #600=5"), "{out}");
    // So do a map file's rules.
    std::fs::remove_file(d.join("nctrans.toml")).unwrap();
    std::fs::write(d.join("map.toml"), "[variables]\nrules = [\"DEPTH=#600\", \"OFS=#601\"]\n").unwrap();
    let (out, err, code) = nctrans(&d, &["check", "PART.MPF", "bare.nc", "--map", "map.toml"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("DEPTH #600=5"), "{out}");
}

/// A program's `nctrans: set` line for global user data reaches the FANUC side of the proof
/// (and the output's own header), so the proof does not call a right translation wrong.
#[test]
fn a_set_line_for_global_user_data_reaches_the_fanuc_side() {
    let d = workdir("gud", "set_line");
    std::fs::write(d.join("MGUD.DEF"), SEEDED_DEF).unwrap();
    std::fs::write(d.join("PART.MPF"), format!("; nctrans: set DEPTH=7\n{SEEDED}")).unwrap();
    let (_, err, code) =
        nctrans(&d, &["--to", "fanuc", "PART.MPF", "-o", "part.nc", "--var-map", "DEPTH=#600,OFS=#601"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
    let text = std::fs::read_to_string(d.join("part.nc")).unwrap();
    assert!(text.contains("(nctrans: set #600=7)"), "{text}");
    let (out, err, code) = nctrans(&d, &["check", "PART.MPF", "part.nc"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("DEPTH #600=5") && out.contains("own inputs set #600=7"), "{out}");
}

/// A divergence of a Siemens program reading global user data from its translation: the
/// diff's header and the labels name the two compared files, not the definition file
/// loaded between them (file 1 of the check was `MGUD.DEF`, and the `+++` line named it).
#[test]
fn a_divergence_names_the_two_compared_files_not_the_definitions() {
    let d = workdir("gud", "diff_names");
    std::fs::create_dir_all(d.join("DEF")).unwrap();
    std::fs::write(d.join("DEF/MGUD.DEF"), "DEF NCK REAL X_A\nM30\n").unwrap();
    std::fs::write(d.join("PART.MPF"), "G0 X0 Z10\nX_A=5\nG1 X=X_A F100\nM30\n").unwrap();
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "PART.MPF", "-o", "part.nc", "--var-map", "X_A=#500"]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(d.join("part.nc")).unwrap();
    assert!(text.contains("#500=5."), "{text}");
    std::fs::write(d.join("wrong.nc"), text.replace("#500=5.", "#500=6.")).unwrap();
    // The planted value is caught, with and without the rule that seeds the commons, and
    // with a tool map (the check that aligns both sides as a translation's proof does).
    for extra in [&[][..], &["--tool-map", "DRILL=1"][..]] {
        for toml in [None, Some("[variables]\nto_fanuc = [\"X_A=#500\"]\n")] {
            match toml {
                Some(t) => std::fs::write(d.join("nctrans.toml"), t).unwrap(),
                None => drop(std::fs::remove_file(d.join("nctrans.toml"))),
            }
            let args: Vec<&str> = ["check", "PART.MPF", "wrong.nc"].iter().chain(extra).copied().collect();
            let (out, err, code) = nctrans(&d, &args);
            assert_eq!(code, 1, "{args:?}\n{out}{err}");
            assert!(out.contains("\n--- PART.MPF\n+++ wrong.nc\n"), "{args:?}\n{out}");
            assert!(!out.contains("MGUD"), "{out}");
            assert!(err.contains("┌─ PART.MPF:3:1") && err.contains("┌─ wrong.nc:7:1"), "{err}");
            assert!(err.contains("X=5") && err.contains("X=6"), "{err}");
        }
    }
    // Either order.
    let (out, err, code) = nctrans(&d, &["check", "wrong.nc", "PART.MPF"]);
    assert_eq!(code, 1, "{out}{err}");
    assert!(out.contains("\n--- wrong.nc\n+++ PART.MPF\n"), "{out}");
    assert!(err.contains("┌─ wrong.nc:7:1") && err.contains("┌─ PART.MPF:3:1"), "{err}");
}
