//! Haas programs to Sinumerik (issue 21, real Haas libraries): the NGC-only general-purpose
//! variables (`#10000+` without a legacy number) live on R parameters like other commons,
//! `G04 P` dwells what the Haas control dwells (a decimal point means seconds); each
//! translation is proven by its own verification and by `nctrans check`, planted wrong
//! translations are caught, and the Haas system variables without a counterpart (clocks,
//! the tool in the spindle, offset tables) are refused saying what they are.

#[path = "support/cli_run.rs"]
mod cli_run;

use cli_run::{nctrans, workdir};
use std::path::{Path, PathBuf};

const NGC: &str = "[fanuc]\nseries = \"haas-ngc\"\n";

/// A fixture plate: the pitch kept in an NGC variable with a default when the setter left
/// it vacant, three hole positions stored by a computed index into #10200.., a counter in
/// #10010 that survives the run, the tool number logged, and a half-second dwell.
const PLATE: &str = "%
O2100 (FIXTURE PLATE - NGC VARIABLES)
G00 G17 G40 G49 G80 G90
T4 M06
S2500 M03
#10012=4. (TOOL NUMBER LOGGED)
IF [#10020 EQ #0] THEN #10020=12.5 (PITCH DEFAULT)
#1=0
WHILE [#1 LT 3] DO1
#[10200+#1]=#1*#10020+5.
#1=#1+1
END1
G00 G54 X#10200 Y0.
G01 Z-2. F150.
G04 P0.5
G00 Z5.
X#10201
G01 Z-2.
G04 P250
G00 Z5.
X#10202 Y#10012
IF [#10010 EQ #0] THEN #10010=0
#10010=#10010+1.
M05
M30
%
";

fn setup(name: &str, profile: Option<&str>, file: &str, text: &str) -> PathBuf {
    let d = workdir("haas-vars", name);
    if let Some(p) = profile {
        std::fs::write(d.join("nctrans.toml"), p).unwrap();
    }
    std::fs::write(d.join(file), text).unwrap();
    d
}

fn translate(d: &Path, file: &str, extra: &[&str]) -> (String, String, i32) {
    let mut args = vec!["--to", "sinumerik", file, "-o", "o.mpf", "--force"];
    args.extend_from_slice(extra);
    let (_, err, code) = nctrans(d, &args);
    (std::fs::read_to_string(d.join("o.mpf")).unwrap_or_default(), err, code)
}

fn check(d: &Path, file: &str, text: &str) -> (String, i32) {
    std::fs::write(d.join("planted.mpf"), text).unwrap();
    let (out, err, code) = nctrans(d, &["check", file, "planted.mpf"]);
    (format!("{out}{err}"), code)
}

fn run(d: &Path, file: &str) -> (String, String, i32) {
    nctrans(d, &["run", file])
}

#[test]
fn ngc_variables_get_r_parameters_and_the_translation_is_proven() {
    let d = setup("plate", Some(NGC), "O2100.nc", PLATE);
    let (text, err, code) = translate(&d, "O2100.nc", &[]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
    // Placed as #200..#499 are: the lowest free R with NC360, flags from the top.
    assert!(err.contains("#10020 has no default R parameter"), "{err}");
    for line in [";   #10020 = R2 (is-set flag R298)", ";   #10200 = R3", "R1=4", "G4 F0.5", "G4 F0.25"] {
        assert!(text.contains(line), "missing `{line}` in\n{text}");
    }
    assert!(!err.contains("NC509") && !err.contains("NC365"), "{err}");
    // The computed index reaches #10200.. through the dispatch, one range for the three.
    assert!(text.contains("NCTRANS_IX1=ROUND(10200+LOC1)"), "{text}");
    assert!(text.contains("(NCTRANS_IX1>=10200) AND (NCTRANS_IX1<=10202)"), "{text}");
    let (out, code) = check(&d, "O2100.nc", &text);
    assert_eq!(code, 0, "{out}");
}

#[test]
fn planted_wrong_translations_of_the_plate_are_caught() {
    let d = setup("plate-planted", Some(NGC), "O2100.nc", PLATE);
    let (text, err, code) = translate(&d, "O2100.nc", &[]);
    assert_eq!(code, 0, "{err}");
    let plants = [
        // The dwell Haas reads as milliseconds although P0.5 has a point.
        ("G4 F0.5", "G4 F0.0005"),
        // The computed index lands one variable off.
        ("NCTRANS_IX1-10197", "NCTRANS_IX1-10196"),
        // Another default pitch.
        ("R2=12.5", "R2=12"),
        // Another logged tool number (it is a Y position below).
        ("R1=4", "R1=3"),
    ];
    for (from, to) in plants {
        assert!(text.contains(from), "`{from}` not in\n{text}");
        let wrong = text.replacen(from, to, 1);
        let (out, code) = check(&d, "O2100.nc", &wrong);
        assert_ne!(code, 0, "planting `{to}` for `{from}` must diverge: {out}");
    }
}

#[test]
fn a_var_map_rule_places_an_ngc_range_and_the_dispatch_follows_it() {
    let d = setup("rule", Some(NGC), "O2100.nc", PLATE);
    let (text, err, code) = translate(&d, "O2100.nc", &["--var-map", "#10200-#10299=R150"]);
    assert_eq!(code, 0, "{err}");
    assert!(text.contains(";   #10200 = R150") && text.contains(";   #10202 = R152"), "{text}");
    assert!(text.contains("NCTRANS_IX1=NCTRANS_IX1-10050"), "{text}");
    assert!(!err.contains("#10200 has no default R parameter"), "{err}");
    // A rule running from an NGC range into the legacy-aliased numbers is refused.
    let (_, err, code) = translate(&d, "O2100.nc", &["--var-map", "#10050-#10150=R150"]);
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("#10150 is a system variable"), "{err}");
}

#[test]
fn without_the_ngc_profile_the_numbers_stay_system_variables() {
    // On a FANUC (memory C) #10002 is the length wear of offset 2, tool data, not a common
    // variable: no R parameter; the run refuses reading it before it is given.
    let text = "O2200\n#1=#10002\nG00 X#1\nM30\n";
    let d = setup("fanuc", None, "O2200.nc", text);
    let (_, err, code) = translate(&d, "O2200.nc", &[]);
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("NC571") && err.contains("#10002") && err.contains("length_wear"), "{err}");
    assert!(!err.contains("NC360"), "{err}");
}

#[test]
fn haas_dwell_p_with_a_point_is_seconds_and_without_milliseconds() {
    let text = "O2300\nG04 P0.5\nG04 P250\nG04 P2.\nM30\n";
    let d = setup("dwell", Some(NGC), "O2300.nc", text);
    let (out, err, code) = run(&d, "O2300.nc");
    assert_eq!(code, 0, "{err}");
    let dwells: Vec<&str> = out.lines().filter(|l| l.starts_with("dwell")).collect();
    assert_eq!(dwells.len(), 3, "{out}");
    assert!(dwells[0].starts_with("dwell 0.5 ") || dwells[0] == "dwell 0.5", "{out}");
    assert!(dwells[1].starts_with("dwell 0.25"), "{out}");
    assert!(dwells[2].starts_with("dwell 2"), "{out}");
    let (mpf, err, code) = translate(&d, "O2300.nc", &[]);
    assert_eq!(code, 0, "{err}");
    assert!(mpf.contains("G4 F0.5") && mpf.contains("G4 F0.25") && mpf.contains("G4 F2"), "{mpf}");
    let (out, code) = check(&d, "O2300.nc", &mpf.replace("G4 F2", "G4 F0.002"));
    assert_ne!(code, 0, "P2. read as milliseconds must diverge: {out}");
}

#[test]
fn dwell_forms_the_sources_do_not_settle_are_refused() {
    // A FANUC P with a written point.
    let d = setup("fanuc-point", None, "O2400.nc", "O2400\nG04 P0.5\nM30\n");
    let (_, err, code) = run(&d, "O2400.nc");
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("NC513"), "{err}");
    let (_, err, code) = translate(&d, "O2400.nc", &[]);
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("NC513") && !err.contains("NC363"), "{err}");
    // A Haas P from a variable: which unit a computed value takes is not settled.
    let d = setup("haas-computed", Some(NGC), "O2500.nc", "O2500\n#1=0.5\nG04 P#1\nM30\n");
    let (_, err, code) = run(&d, "O2500.nc");
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("NC512"), "{err}");
    let (_, err, code) = translate(&d, "O2500.nc", &[]);
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("NC512"), "{err}");
}

#[test]
fn a_computed_fanuc_dwell_is_rounded_to_whole_milliseconds_in_both() {
    let d = setup("fanuc-computed", None, "O2600.nc", "O2600\n#1=250.4\nG04 P#1\nM30\n");
    let (out, err, code) = run(&d, "O2600.nc");
    assert_eq!(code, 0, "{err}");
    assert!(out.lines().any(|l| l.starts_with("dwell 0.25")), "{out}");
    let (mpf, err, code) = translate(&d, "O2600.nc", &[]);
    assert_eq!(code, 0, "{err}");
    assert!(mpf.contains("G4 F=ROUND(LOC1)/1000"), "{mpf}");
    let (out, code) = check(&d, "O2600.nc", &mpf.replace("ROUND(LOC1)/1000", "LOC1/1000"));
    assert_ne!(code, 0, "the unrounded value must diverge: {out}");
}

#[test]
fn haas_clock_and_offset_variables_are_refused_saying_what_they_are() {
    let cases = [
        ("O2700\n#10000=#3020\nM30\n", "NC365", "power-on timer"),
        ("O2700\n#10001=#3012\nM30\n", "NC365", "time of day"),
        ("O2700\nT2 M06\n#1=#3026\nG00 X#1\nM30\n", "NC365", "the tool in the spindle"),
        ("O2700\n#3026=5.\nM30\n", "NC365", "writing #3026"),
        ("O2700\nT2 M06\n#4=#[2400+#3026]\nM30\n", "NC514", "tool diameter/radius geometry offsets"),
        ("O2700\n#4=#2405\nM30\n", "NC365", "diameter/radius geometry offset of tool 5"),
    ];
    for (i, (text, code, what)) in cases.into_iter().enumerate() {
        let d = setup(&format!("refused{i}"), Some(NGC), "O2700.nc", text);
        let (_, err, rc) = translate(&d, "O2700.nc", &[]);
        assert_ne!(rc, 0, "{text}: {err}");
        assert!(err.contains(code) && err.contains(what), "{text}: expected {code} naming `{what}` in {err}");
    }
}
