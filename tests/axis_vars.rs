//! Siemens axes named by a value (`DEF AXIS`, `AX[…]`, `AXNAME(…)`) to FANUC where the
//! machine's set-up fixes the axis letters (`[variables] fixed`): a dressing subprogram as a
//! grinding library writes it translates to plain axis words and is proven; a FANUC program
//! with the wrong letter is caught by `check`; what is not one known axis is refused saying
//! why (NC542–NC544), and `run` starts the fixed values and refuses a write to them.

#[path = "support/cli_run.rs"]
mod cli_run;

use cli_run::{nctrans, workdir};

const GUD: &str = "DEF NCK STRING[1] AXIS_HORI ;horizontal axis\nDEF NCK STRING[1] AXIS_VER ;vertical axis\nDEF NCK STRING[1] AXIS_EW\nM30\n";

const CONFIG: &str = "[variables]\nfixed = { AXIS_HORI = \"Z\", AXIS_VER = \"X\" }\n";

/// A dressing pass as the library writes it: the axes from the set-up's letters, the
/// roller moved through them, a second assignment of the same axis inside a loop.
const DRESS: &str = "PROC D_DRESS
DEF REAL DEPTH,PASS
DEF AXIS AX_H,AX_V ;horizontal and vertical axis
DEPTH=0.02
AX_H=AXNAME(AXIS_HORI) ;horizontal
AX_V=AXNAME(AXIS_VER)
G90 G0 AX[AX_V]=5 AX[AX_H]=-2
PASS=0
WHILE PASS<3
  AX_H=AXNAME(AXIS_HORI)
  G1 AX[AX_V]=-PASS*DEPTH F200
  G1 AX[AX_H]=40 F800
  G0 AX[AX_V]=5
  G0 AX[AXNAME(AXIS_HORI)]=-2
  PASS=PASS+1
ENDWHILE
M17
";

fn library(name: &str, programs: &[(&str, &str)]) -> std::path::PathBuf {
    let d = workdir("axis_vars", name);
    std::fs::create_dir_all(d.join("DEF")).unwrap();
    std::fs::write(d.join("DEF/MGUD.DEF"), GUD).unwrap();
    std::fs::write(d.join("nctrans.toml"), CONFIG).unwrap();
    for (file, text) in programs {
        std::fs::write(d.join(file), text).unwrap();
    }
    d
}

#[test]
fn a_dressing_subprogram_translates_to_the_set_up_letters_and_is_proven() {
    let d = library("dress", &[("D_DRESS.SPF", DRESS)]);
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "D_DRESS.SPF", "-o", "dress.nc"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent ("), "{err}");
    assert!(err.contains("assumed from the set-up (variables.fixed): AXIS_HORI = \"Z\", AXIS_VER = \"X\""), "{err}");
    let out = std::fs::read_to_string(d.join("dress.nc")).unwrap();
    assert!(out.contains("G90 G00 X5. Z-2."), "{out}");
    assert!(out.contains("G01 Z40. F800."), "{out}");
    assert!(!out.contains("AX") && !out.contains("AXNAME"), "{out}");
    // The run of the source rests on the same values: the roller moves on Z and X.
    let (trace, err, code) = nctrans(&d, &["run", "D_DRESS.SPF"]);
    assert_eq!(code, 0, "{err}");
    assert!(trace.contains("move linear X=-0.04 Z=-2 f=200"), "{trace}");
    // The flag gives the same value as the file; another letter is another translation.
    let (_, err, code) =
        nctrans(&d, &["--to", "fanuc", "D_DRESS.SPF", "-o", "dress_y.nc", "--fixed", "AXIS_HORI=Y", "--force"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("AXIS_HORI = \"Y\""), "{err}");
    let out = std::fs::read_to_string(d.join("dress_y.nc")).unwrap();
    assert!(out.contains("G01 Y40. F800."), "{out}");
}

#[test]
fn a_wrong_letter_in_the_fanuc_program_is_caught_by_check() {
    let d = library("planted", &[("D_DRESS.SPF", DRESS)]);
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "D_DRESS.SPF", "-o", "dress.nc"]);
    assert_eq!(code, 0, "{err}");
    let good = std::fs::read_to_string(d.join("dress.nc")).unwrap();
    let (out, err, code) = nctrans(&d, &["check", "D_DRESS.SPF", "dress.nc"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("assumed from the set-up (variables.fixed): AXIS_HORI = \"Z\", AXIS_VER = \"X\""), "{out}");
    // The roller's horizontal stroke written on X: the letter the set-up does not give.
    let wrong = good.replacen("G01 Z40. F800.", "G01 X40. F800.", 1);
    assert_ne!(wrong, good);
    std::fs::write(d.join("wrong.nc"), wrong).unwrap();
    let (out, _, code) = nctrans(&d, &["check", "D_DRESS.SPF", "wrong.nc"]);
    assert_eq!(code, 1, "{out}");
    assert!(out.contains("diverged at trace event"), "{out}");
}

/// The codes of the errors `err` reports, in order.
fn error_codes(err: &str) -> Vec<&str> {
    err.lines().filter_map(|l| l.strip_prefix("error[")?.split(']').next()).collect()
}

/// Translates `program` and expects it refused with exactly the errors `codes` (one per
/// construct, in order: no general refusal beside the specific one), one saying `words`.
fn refused(name: &str, program: &str, codes: &[&str], words: &str) -> std::path::PathBuf {
    let file = format!("{name}.SPF");
    let d = library(name, &[(&file, program)]);
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", &file, "-o", "out.nc"]);
    assert_ne!(code, 0, "{err}");
    assert_eq!(error_codes(&err), codes, "{err}");
    assert!(err.contains(words), "{words}: {err}");
    assert!(!d.join("out.nc").exists());
    d
}

#[test]
fn an_axis_variable_with_two_axes_is_refused() {
    let p = "PROC TWO\nDEF AXIS AX_H\nAX_H=AXNAME(AXIS_HORI)\nG1 AX[AX_H]=10 F100\nAX_H=AXNAME(AXIS_VER)\nG1 AX[AX_H]=5\nM17\n";
    let _ = refused("TWO", p, &["NC542"; 3], "AX_H holds two different axes (Z and X)");
}

#[test]
fn an_axis_from_a_parameter_is_refused() {
    let p = "PROC PAR(STRING[1] WHICH)\nDEF AXIS AX_H\nAX_H=AXNAME(WHICH)\nG1 AX[AX_H]=10 F100\nM17\n";
    let _ = refused("PAR", p, &["NC542"; 2], "WHICH is a parameter: each caller chooses the axis");
}

#[test]
fn an_axis_read_before_any_assignment_on_a_path_is_refused() {
    let p = "PROC UNSET\nDEF AXIS AX_H\nIF $AA_IW[X]>0\n  AX_H=AXNAME(AXIS_HORI)\nENDIF\nG1 AX[AX_H]=10 F100\nM17\n";
    let _ = refused("UNSET", p, &["NC542"; 2], "AX_H may be read unset");
    let p = "PROC JUMP\nDEF AXIS AX_H\nGOTOF SKIP\nAX_H=AXNAME(AXIS_HORI)\nSKIP:\nG1 AX[AX_H]=10 F100\nM17\n";
    let _ = refused("JUMP", p, &["NC542"; 2], "a jump before its first assignment can pass it");
}

#[test]
fn a_global_string_the_set_up_does_not_give_is_refused() {
    let p = "PROC EW\nG1 AX[AXNAME(AXIS_EW)]=10 F100\nM17\n";
    let _ = refused("EW", p, &["NC543"], "AXIS_EW is global user data that no [variables] fixed entry gives");
}

#[test]
fn an_axis_the_fanuc_profile_lacks_is_refused() {
    let p = "PROC SPND\nDEF AXIS AX_S\nAX_S=AXNAME(\"SP1\")\nG1 AX[AX_S]=10 F100\nM17\n";
    let _ = refused("SPND", p, &["NC543"; 2], "axis \"SP1\" is not an axis of the FANUC profile");
}

#[test]
fn a_program_writing_a_fixed_value_is_refused_in_translation_and_run() {
    let p = "PROC SETS\nAXIS_HORI=\"X\"\nG1 AX[AXNAME(AXIS_HORI)]=10 F100\nM17\n";
    let d = refused("SETS", p, &["NC544"], "a write to AXIS_HORI (a value [variables] fixed says the set-up fixes)");
    let (_, err, code) = nctrans(&d, &["run", "SETS.SPF"]);
    assert_ne!(code, 0);
    assert!(err.contains("error[NC544]") && err.contains("the program writes AXIS_HORI"), "{err}");
    assert_eq!(error_codes(&err), ["NC544"], "{err}");
}

#[test]
fn each_refused_write_is_said_once_with_its_reason() {
    // Each write of a fixed value is NC544 alone: not also a string value (NC314), a
    // concatenation (NC314) or a STRING GUD without a FANUC variable (NC504).
    let p =
        "PROC SETS2\nDEF REAL RR\nAXIS_HORI=AXIS_VER\nIF RR>0\n  AXIS_VER=\"Y\"<<\"Z\" RR=2\nENDIF\nG1 X10 F100\nM17\n";
    let _ = refused("SETS2", p, &["NC544"; 2], "a write to AXIS_VER");
    // The assignments of a refused AXIS variable are not AXNAME refusals (NC632) or string
    // values (NC314) besides: the DEF and each AX[…] say why.
    let p = "PROC LOOPS\nDEF AXIS AX_H\nDEF REAL RR\nRR=1\nWHILE RR<3\n  AX_H=AXNAME(AXIS_HORI)\n  AX_H=AXNAME(\"X\")\n  RR=RR+1\nENDWHILE\nG1 AX[AX_H]=4 F10\nM17\n";
    let _ = refused("LOOPS", p, &["NC542"; 2], "AX_H holds two different axes (Z and X)");
    let p = "PROC EWV\nDEF AXIS AX_E\nAX_E=AXNAME(AXIS_EW)\nG1 AX[AX_E]=4 F10\nM17\n";
    let _ = refused("EWV", p, &["NC543"; 2], "AXIS_EW is global user data that no [variables] fixed entry gives");
    // Where the variable is refused without a reason of its own, the general refusals
    // stay: they are the only explanation (NC310 for the DEF, NC632 for AXNAME).
    let p = "PROC FORS\nDEF AXIS AX_H\nDEF INT II\nAX_H=AXNAME(AXIS_HORI)\nFOR II=1 TO 2\n  G1 AX[AX_H]=II F10\nENDFOR\nR1=AX_H\nM17\n";
    let _ = refused("FORS", p, &["NC310", "NC635", "NC632"], "DEF AXIS AX_H");
}

#[test]
fn without_the_table_the_general_refusals_stay() {
    let d = library("plain", &[("D_DRESS.SPF", DRESS)]);
    std::fs::remove_file(d.join("nctrans.toml")).unwrap();
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "D_DRESS.SPF", "-o", "out.nc"]);
    assert_ne!(code, 0);
    assert!(err.contains("error[NC543]") && err.contains("AXIS_HORI is global user data"), "{err}");
    // A bad table entry names the key.
    std::fs::write(d.join("nctrans.toml"), "[variables]\nfixed = { AXIS_HORI = 3 }\n").unwrap();
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "D_DRESS.SPF", "-o", "out.nc"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("variables.fixed.AXIS_HORI"), "{err}");
}

#[test]
fn a_batch_names_the_set_up_values_in_each_verdict() {
    let main = "G90 G0 X50 Z10\nD_DRESS\nG1 AX[AXNAME(AXIS_VER)]=20 F500\nM30\n";
    let d = library("batch", &[]);
    let lib = d.join("lib");
    std::fs::create_dir_all(lib.join("DEF")).unwrap();
    std::fs::rename(d.join("DEF/MGUD.DEF"), lib.join("DEF/MGUD.DEF")).unwrap();
    std::fs::write(lib.join("D_DRESS.SPF"), DRESS).unwrap();
    std::fs::write(lib.join("GRIND.MPF"), main).unwrap();
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "-o", "out", "lib", "--report", "r.json"]);
    assert_eq!(code, 0, "{err}");
    let report = std::fs::read_to_string(d.join("r.json")).unwrap();
    assert_eq!(report.matches("assumed from the set-up (variables.fixed): AXIS_HORI").count(), 2, "{report}");
}

#[test]
fn an_unread_copy_of_a_set_up_letter_goes_and_a_read_one_stays_refused() {
    let copy = "PROC COPY\nDEF STRING[1] HOR_NAME\nDEF AXIS AX_H\nHOR_NAME=AXIS_HORI ;name of the horizontal axis\nAX_H=AXNAME(AXIS_HORI)\nG1 AX[AX_H]=10 F100\nM17\n";
    let d = library("copy", &[("COPY.SPF", copy)]);
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "COPY.SPF", "-o", "copy.nc"]);
    assert_eq!(code, 0, "{err}");
    let out = std::fs::read_to_string(d.join("copy.nc")).unwrap();
    assert!(out.contains("G01 Z10. F100.") && out.contains("(name of the horizontal axis)"), "{out}");
    let read = copy.replace("G1 AX[AX_H]=10 F100", "G1 AX[AXNAME(HOR_NAME)]=10 F100");
    let _ = refused("READ", &read, &["NC310", "NC635", "NC504"], "DEF STRING[1] HOR_NAME");
}
