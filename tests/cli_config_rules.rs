//! Configuration that does what it says (issue 16, item 8): `to` in nctrans.toml, one
//! `--encoding` flag everywhere, one tool-number rule for single files and batches, var-map
//! rules refused in the wrong direction, O numbers checked against the series, and `check`
//! taking a translation's maps.

#[path = "support/cli_run.rs"]
mod cli_run;

use cli_run::nctrans;
use std::path::PathBuf;

fn workdir(name: &str) -> PathBuf {
    cli_run::workdir("config-rules", name)
}

const SIEMENS: &str = "R1=10\nG1 X=R1 F100\nM30\n";
const FANUC: &str = "O1000\n#1=10\nG1 X#1 F100\nM30\n";

#[test]
fn to_in_the_project_config_stands_for_the_flag() {
    let dir = workdir("to");
    std::fs::write(dir.join("part.mpf"), SIEMENS).expect("write");
    std::fs::write(dir.join("part.nc"), FANUC).expect("write");
    let (_, err, code) = nctrans(&dir, &["part.mpf"]);
    assert_eq!(code, 2);
    assert!(err.contains("a translation needs a target") && err.contains("`to` in nctrans.toml"), "{err}");
    std::fs::write(dir.join("nctrans.toml"), "to = \"fanuc\"\n").expect("config");
    let (out, err, code) = nctrans(&dir, &["part.mpf"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("O0001 (PART)") && err.contains("equivalent"), "{out}{err}");
    std::fs::write(dir.join("nctrans.toml"), "to = \"sinumerik\"\n[verify]\nmax_steps = 2\n").expect("config");
    // The configuration's other keys apply to --to sinumerik too (here: a step limit).
    let (out, err, code) = nctrans(&dir, &["part.nc"]);
    assert_eq!(code, 1, "{out}{err}");
    assert!(out.contains("LOC1=10") && err.contains("inconclusive"), "{out}{err}");
    // The flag wins over the file.
    std::fs::write(dir.join("nctrans.toml"), "to = \"sinumerik\"\n").expect("config");
    let (out, err, code) = nctrans(&dir, &["--to", "fanuc", "part.mpf"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("O0001"), "{out}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn encoding_is_one_flag_in_every_command_with_the_old_name_as_alias() {
    let dir = workdir("encoding");
    // `Ø` in windows-1252: one byte, not UTF-8.
    std::fs::write(dir.join("p.mpf"), b"; \xd8 10\nR1=10\nG1 X=R1 F100\nM30\n").expect("write");
    std::fs::write(dir.join("q.nc"), b"O1000\n(\xd8 10)\n#1=10\nG1 X#1 F100\nM30\n").expect("write");
    for flag in ["--encoding", "--input-encoding"] {
        for args in [
            vec!["parse", flag, "windows-1252", "p.mpf"],
            vec!["run", flag, "windows-1252", "p.mpf"],
            vec!["check", flag, "windows-1252", "p.mpf", "p.mpf"],
            vec!["--to", "fanuc", flag, "windows-1252", "p.mpf"],
            vec!["--to", "sinumerik", flag, "windows-1252", "q.nc"],
        ] {
            let (out, err, code) = nctrans(&dir, &args);
            assert_eq!(code, 0, "{args:?}: {err}");
            assert!(!out.is_empty(), "{args:?}");
        }
    }
    // The configuration documents the primary name.
    let (_, err, code) = nctrans(&dir, &["init"]);
    assert_eq!(code, 0, "{err}");
    let template = std::fs::read_to_string(dir.join("nctrans.toml")).expect("template");
    assert!(template.contains("(--encoding)"), "{template}");
    // `--to sinumerik` takes input.encoding from the configuration as `--to fanuc` does.
    std::fs::write(dir.join("nctrans.toml"), "[input]\nencoding = \"shift_jis\"\n").expect("config");
    let (out, _, _) = nctrans(&dir, &["--to", "sinumerik", "q.nc"]);
    assert!(out.contains("LOC1=10") && !out.contains('Ø'), "read as Shift-JIS, not windows-1252: {out}");
    let _ = std::fs::remove_dir_all(&dir);
}

const TOOLS: &str = "; tools\nT=\"ENDMILL_D6\"\nM6 D1\nR1=30\nMSG(\"ROUGHING\")\nG0 X=R1\nM30\n";

#[test]
fn a_tool_name_without_a_number_is_refused_in_a_single_file_and_in_a_batch() {
    let dir = workdir("tools");
    let lib = dir.join("lib");
    std::fs::create_dir_all(&lib).expect("lib");
    std::fs::write(lib.join("t.mpf"), TOOLS).expect("write");
    std::fs::write(lib.join("r.mpf"), SIEMENS).expect("write");
    let (out, err, code) = nctrans(&dir, &["--to", "fanuc", "lib/t.mpf"]);
    assert_eq!(code, 1, "{out}{err}");
    assert!(err.contains("error[NC301]: tool \"ENDMILL_D6\" has no FANUC tool number"), "{err}");
    assert!(err.contains("--tool-map ENDMILL_D6=<number>") && err.contains("[tools]"), "{err}");
    // Before, a batch numbered it T1 silently and called the file verified.
    let (out, err, code) = nctrans(&dir, &["--to", "fanuc", "-o", "out", "lib"]);
    assert_eq!(code, 1, "{out}{err}");
    assert!(out.contains("t.mpf  NC301"), "{out}");
    assert!(err.contains("\"ENDMILL_D6\" = <T number>"), "{err}");
    assert!(!dir.join("out/t.nc").exists());
    assert!(dir.join("out/r.nc").exists());
    let map = std::fs::read_to_string(dir.join("out/nctrans-map.toml")).expect("map");
    assert!(!map.contains("ENDMILL_D6"), "{map}");
    // Given a number, both translate with it, and the batch writes it to the map.
    let (out, err, code) = nctrans(&dir, &["--to", "fanuc", "--tool-map", "ENDMILL_D6=12", "lib/t.mpf"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("T12"), "{out}");
    std::fs::write(dir.join("nctrans.toml"), "[tools]\nENDMILL_D6 = 7\n").expect("config");
    let (out, err, code) = nctrans(&dir, &["--to", "fanuc", "-o", "out2", "lib"]);
    assert_eq!(code, 0, "{out}{err}");
    let map = std::fs::read_to_string(dir.join("out2/nctrans-map.toml")).expect("map");
    assert!(map.contains("\"ENDMILL_D6\" = 7"), "{map}");
    assert!(std::fs::read_to_string(dir.join("out2/t.nc")).expect("out").contains("T7"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn check_compares_a_program_with_its_translation_through_the_translations_maps() {
    let dir = workdir("check-maps");
    let lib = dir.join("lib");
    std::fs::create_dir_all(&lib).expect("lib");
    std::fs::write(lib.join("t.mpf"), TOOLS).expect("write");
    let (_, err, code) = nctrans(&dir, &["--to", "fanuc", "--tool-map", "ENDMILL_D6=12", "lib/t.mpf", "-o", "t.nc"]);
    assert_eq!(code, 0, "{err}");
    // Without the map: a name against a number, and the hint says what to give.
    let (out, err, code) = nctrans(&dir, &["check", "lib/t.mpf", "t.nc"]);
    assert_eq!(code, 1, "{out}{err}");
    assert!(err.contains("`tool \"ENDMILL_D6\"` vs `tool 12`") && err.contains("--tool-map NAME=n"), "{err}");
    let (out, err, code) = nctrans(&dir, &["check", "lib/t.mpf", "t.nc", "--tool-map", "ENDMILL_D6=12"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("equivalent"), "{out}");
    // The message the translation keeps as a comment is left out, and the verdict says so.
    assert!(out.contains("1 message kept as a comment"), "{out}");
    // A wrong number is a divergence, not an equivalence.
    let (out, _, code) = nctrans(&dir, &["check", "lib/t.mpf", "t.nc", "--tool-map", "ENDMILL_D6=13"]);
    assert!(code == 1 && out.contains("diverged"), "{out}");
    // A batch's map file.
    std::fs::write(dir.join("nctrans.toml"), "[tools]\nENDMILL_D6 = 7\n").expect("config");
    let (out, err, code) = nctrans(&dir, &["--to", "fanuc", "-o", "out", "lib"]);
    assert_eq!(code, 0, "{out}{err}");
    std::fs::remove_file(dir.join("nctrans.toml")).expect("rm");
    let (out, err, code) = nctrans(&dir, &["check", "lib/t.mpf", "out/t.nc", "--map", "out/nctrans-map.toml"]);
    assert_eq!(code, 0, "{out}{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_var_map_rule_is_applied_in_its_direction_and_refused_in_the_other() {
    let dir = workdir("var-map");
    std::fs::write(dir.join("v.nc"), "O1000\n#30=5\n#31=#30+1\n#500=#31\nG1 X#500 F100\nM30\n").expect("write");
    std::fs::write(dir.join("v.mpf"), "R50=5\nR51=R50+1\nG1 X=R51 F100\nM30\n").expect("write");
    // Before: ignored silently (#30-#33 are locals, which a rule never placed).
    let (out, err, code) = nctrans(&dir, &["--to", "sinumerik", "--var-map", "#30-#33=R50", "v.nc"]);
    assert_eq!(code, 2, "{out}{err}");
    assert!(err.contains("#30 is a local variable") && err.contains("common variables #100–#999"), "{err}");
    let (_, err, code) = nctrans(&dir, &["--to", "sinumerik", "--var-map", "R50-R53=#30", "v.nc"]);
    assert_eq!(code, 2);
    assert!(err.contains("a Sinumerik → FANUC rule (--to fanuc)"), "{err}");
    let (_, err, code) = nctrans(&dir, &["--to", "fanuc", "--var-map", "#30-#33=R50", "v.mpf"]);
    assert_eq!(code, 2);
    assert!(err.contains("a FANUC → Sinumerik rule (--to sinumerik)"), "{err}");
    // Each form works in its own direction.
    let (out, err, code) = nctrans(&dir, &["--to", "sinumerik", "--var-map", "#500-#599=R150", "v.nc"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("R150="), "{out}");
    let (out, err, code) = nctrans(&dir, &["--to", "fanuc", "--var-map", "R50-R53=#150", "v.mpf"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("#150=5"), "{out}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_program_number_the_series_cannot_hold_is_refused_naming_the_series() {
    let dir = workdir("o-number");
    std::fs::write(dir.join("p.mpf"), SIEMENS).expect("write");
    let (out, err, code) = nctrans(&dir, &["--to", "fanuc", "--program-number", "12345", "p.mpf"]);
    assert_eq!(code, 2, "{out}{err}");
    assert!(err.contains("O12345") && err.contains("FANUC 0i-F") && err.contains("O1 to O9999"), "{err}");
    std::fs::write(dir.join("nctrans.toml"), "[translate]\nprogram_number = 12345\n").expect("config");
    let (_, err, code) = nctrans(&dir, &["--to", "fanuc", "p.mpf"]);
    assert!(code == 2 && err.contains("translate.program_number") && err.contains("0i-F"), "{err}");
    // A series with longer program numbers takes it (written before or after the number).
    std::fs::write(dir.join("nctrans.toml"), "[translate]\nprogram_number = 12345\n[fanuc]\nseries = \"30i\"\n")
        .expect("config");
    let (out, err, code) = nctrans(&dir, &["--to", "fanuc", "p.mpf"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("O12345"), "{out}");
    let (_, err, code) = nctrans(&dir, &["--to", "fanuc", "--program-number", "9999", "p.mpf"]);
    assert_eq!(code, 0, "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}
