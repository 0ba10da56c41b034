//! Global user data on a Haas NGC (issue 21): under `[fanuc] series = "haas-ngc"` a GUD
//! table may live in the NGC-only general-purpose variables (`#10000..#10099`,
//! `#10200..#10499`, `#10700..#10799`, kept on power off as `#500..#999` are), wholly inside
//! one range; the translation is proven with the NGC variables read back and the tables
//! starting at their definitions' start values. A table across two ranges, one touching
//! the NGC spellings of `#100`/`#500`/`#800`, and the same mapping for a plain FANUC are
//! refused (NC504); a planted wrong number is caught by the verification.

#[path = "support/cli_run.rs"]
mod cli_run;

use cli_run::{nctrans, workdir};
use nctrans::dialect::{Dialect, ParseOptions, Semantics};
use nctrans::span::SourceDb;
use nctrans::translate::{self, to_fanuc::TranslateOptions};
use std::path::{Path, PathBuf};

/// A grinding library's tables: two dressing tables of 80 (one with start values), the
/// tool set of 70 and a counter.
const GUD: &str = "%_N_MGUD_DEF\n;$PATH=/_N_DEF_DIR\nDEF NCK REAL DRESS_A[80]\nDEF NCK REAL DRESS_B[80]=SET(1.5,2.5)\n\
DEF NCK REAL TOOL_SET[70]\nDEF NCK INT DRESSINGS=3\nM30\n";

/// Writes a computed row of DRESS_A from a start value of DRESS_B, keeps one in the tool
/// set's last element, moves by them, and counts the dressing.
const MAIN: &str = "DEF INT KS\nG0 X0 Y0 Z10\nFOR KS=0 TO 3\nDRESS_A[KS]=KS*0.25+DRESS_B[1]\nENDFOR\n\
TOOL_SET[69]=DRESS_A[3]\nG1 Z=-DRESS_A[2] F=100*DRESS_B[0]\nG0 X=TOOL_SET[69] Y=DRESSINGS\nDRESSINGS=DRESSINGS+1\nM30\n";

const RULES: &str = "\"DRESS_A=#10200\", \"DRESS_B=#10280\", \"TOOL_SET=#10700\", \"DRESSINGS=#500\"";

fn library(name: &str, series: Option<&str>, rules: &str) -> PathBuf {
    let d = workdir("gud-ngc", name);
    std::fs::create_dir_all(d.join("DEF")).unwrap();
    std::fs::write(d.join("DEF/MGUD.DEF"), GUD).unwrap();
    std::fs::write(d.join("DRESS.MPF"), MAIN).unwrap();
    let fanuc = series.map(|s| format!("[fanuc]\nseries = \"{s}\"\n")).unwrap_or_default();
    std::fs::write(d.join("nctrans.toml"), format!("{fanuc}[variables]\nto_fanuc = [{rules}]\n")).unwrap();
    d
}

fn translate_in(d: &Path) -> (String, String, i32) {
    let (_, err, code) = nctrans(d, &["--to", "fanuc", "DRESS.MPF", "-o", "dress.nc"]);
    (std::fs::read_to_string(d.join("dress.nc")).unwrap_or_default(), err, code)
}

#[test]
fn tables_in_the_ngc_ranges_translate_and_are_proven() {
    let d = library("proven", Some("haas-ngc"), RULES);
    let (text, err, code) = translate_in(&d);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
    for line in [
        "(NCTRANS: DRESS_A[…] [80 elements, global user data] = #10200)",
        "(NCTRANS: TOOL_SET[…] [70 elements, global user data] = #10700)",
        "#[#100+10200.]=#100*0.25+#10281",
        "#10769=#10203",
        "G01 Z-#10202 F[100.*#10280]",
        "G00 X#10769 Y#500",
    ] {
        assert!(text.contains(line), "missing `{line}` in\n{text}");
    }
}

#[test]
fn a_batch_of_the_library_is_verified() {
    let d = library("batch", Some("haas-ngc"), RULES);
    std::fs::create_dir_all(d.join("CMA")).unwrap();
    std::fs::rename(d.join("DRESS.MPF"), d.join("CMA/DRESS.MPF")).unwrap();
    std::fs::write(d.join("CMA/SETUP.MPF"), "TOOL_SET[0]=12.5\nDRESS_A[79]=TOOL_SET[0]/2\nG0 X=DRESS_A[79]\nM30\n")
        .unwrap();
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "-o", "out", "CMA", "--report", "r.json"]);
    assert_eq!(code, 0, "{err}");
    let report = std::fs::read_to_string(d.join("r.json")).unwrap();
    assert_eq!(report.matches("\"status\": \"verified\"").count(), 2, "{report}");
}

#[test]
fn tables_across_ranges_or_on_aliases_are_refused() {
    let cases = [
        // #10450..#10529: across #10499/#10500, and #10500 is the NGC spelling of #500.
        ("DRESS_A=#10450", "#10450..#10529, but #10500 on a Haas NGC is the same variable as #500"),
        // Inside #10500..#10699 altogether: the legacy #520..#599.
        ("DRESS_A=#10520", "#10520..#10599, but #10520 on a Haas NGC is the same variable as #520"),
        // #10050..#10129 runs into the NGC spelling of #100.
        ("DRESS_A=#10050", "but #10100 on a Haas NGC is the same variable as #100"),
        // #10760..#10839: past #10799 into the spelling of #800.
        ("DRESS_A=#10760", "but #10800 on a Haas NGC is the same variable as #800"),
        // #940..#1019: out of #500..#999.
        ("DRESS_A=#940", "#940..#1019, which does not lie wholly inside #500..#999"),
        // Past the general-purpose variables.
        ("DRESS_A=#11000", "#11000..#11079, not retained common variables"),
    ];
    for (rule, want) in cases {
        let rules = RULES.replace("DRESS_A=#10200", rule);
        let d = library("refused", Some("haas-ngc"), &rules);
        let (_, err, code) = translate_in(&d);
        assert_ne!(code, 0, "{rule}: {err}");
        assert!(err.contains("NC504") && err.contains(want), "{rule}: {err}");
        assert!(err.contains("#500..#999, #10000..#10099, #10200..#10499 or #10700..#10799"), "{rule}: {err}");
    }
}

#[test]
fn the_same_mapping_for_a_plain_fanuc_is_refused_as_before() {
    for series in [None, Some("0i-F"), Some("haas")] {
        let d = library("plain", series, RULES);
        let (_, err, code) = translate_in(&d);
        assert_ne!(code, 0, "{series:?}: {err}");
        assert!(err.contains("NC504") && err.contains("#10200..#10279, not retained common variables"), "{err}");
        assert!(err.contains("map it into #500..#999") && !err.contains("#10700..#10799"), "{err}");
    }
}

#[test]
fn names_and_r_parameters_may_live_in_the_ngc_ranges() {
    let d = workdir("gud-ngc", "names");
    std::fs::write(d.join("nctrans.toml"), "[fanuc]\nseries = \"haas-ngc\"\n").unwrap();
    std::fs::write(d.join("P.MPF"), "DEF REAL ROW[5]\nROW[4]=R2+1\nR3=ROW[4]*2\nG0 X=R3 Y=ROW[4]\nM30\n").unwrap();
    let args = ["--to", "fanuc", "P.MPF", "-o", "p.nc", "--force", "--var-map"];
    let (_, err, code) = nctrans(&d, &[&args[..], &["ROW=#10000,R0-R9=#10490"]].concat());
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
    let text = std::fs::read_to_string(d.join("p.nc")).unwrap();
    assert!(text.contains("#10004=#10492+1.") && text.contains("#10493=#10004*2."), "{text}");
    // A table running into the NGC spelling of #100, an R parameter on that of #500.
    let (_, err, code) = nctrans(&d, &[&args[..], &["ROW=#10096"]].concat());
    assert_ne!(code, 0);
    assert!(err.contains("NC302") && err.contains("ROW would be #10096..#10100, but #10100 on a Haas NGC"), "{err}");
    let (_, err, code) = nctrans(&d, &[&args[..], &["R0-R9=#10498"]].concat());
    assert_ne!(code, 0);
    assert!(
        err.contains("NC302") && err.contains("R2 would be #10500, on a Haas NGC the same variable as #500"),
        "{err}"
    );
}

/// The translation of MAIN in-process, with the library's definitions and rules.
fn in_process(ngc: bool) -> (SourceDb, nctrans::ir::Unit, translate::Translation) {
    let d = library(if ngc { "api" } else { "api-plain" }, Some("haas-ngc"), RULES);
    let mut db = SourceDb::new();
    let defs = nctrans::gud::load(&mut db, &[d.join("DEF/MGUD.DEF")], None);
    assert!(defs.diags.is_empty());
    let mut source = Semantics::default_for(Dialect::Sinumerik);
    source.globals = std::sync::Arc::new(defs.defs);
    let mut popts = ParseOptions::for_dialect(Dialect::Sinumerik);
    popts.semantics = source.clone();
    let id = db.add("DRESS.MPF", MAIN);
    let parsed = nctrans::parse(&db, id, Dialect::Sinumerik, &popts);
    assert!(!nctrans::diag::has_errors(&parsed.diags));
    let mut target = Semantics::default_for(Dialect::Fanuc);
    target.haas = true;
    target.haas_ngc = ngc;
    let rules = RULES.replace('"', "").replace(", ", ",");
    let opts = TranslateOptions {
        source,
        target,
        var_rules: nctrans::lower::to_fanuc::varmap::parse_rules(&rules).unwrap(),
        ..TranslateOptions::default()
    };
    let t = translate::to_fanuc::to_fanuc(&parsed.unit, &[], &opts);
    (db, parsed.unit, t.into())
}

#[test]
fn the_verification_reads_the_ngc_variables_and_catches_a_planted_number() {
    let (mut db, u, t) = in_process(true);
    assert!(t.ok(), "{}", nctrans::diag::render(&db, &t.diags));
    let v = translate::to_fanuc::verify(&mut db, &u, &[], &t, "out.nc", 100_000);
    assert!(v.equivalent, "{}\n{}", v.summary, v.rendered);
    // The GUD start values are where the FANUC side starts: #10280, #10281 and #500.
    let seeds = &t.symbols.fanuc().gud_seeds;
    for (n, x) in [(10280, 1.5), (10281, 2.5), (10282, 0.0), (500, 3.0), (10769, 0.0)] {
        assert!(seeds.contains(&(n, x)), "#{n}={x} not in {seeds:?}");
    }
    // One variable off: a read of the row, a write of the tool set, a start value.
    for (from, to) in [("#10769=#10203", "#10769=#10204"), ("#10769=#10203", "#10768=#10203"), ("+#10281", "+#10282")] {
        let mut bad = t.clone();
        assert!(bad.files[0].text.contains(from), "{from}");
        bad.files[0].text = bad.files[0].text.replacen(from, to, 1);
        let v = translate::to_fanuc::verify(&mut db, &u, &[], &bad, "bad.nc", 100_000);
        assert!(!v.equivalent, "{from} -> {to}: {}", v.summary);
    }
    // Read back as a plain FANUC, #10200 would be something else: the map says NGC.
    let mut plain = t.clone();
    if let translate::Symbols::Fanuc(m) = &mut plain.symbols {
        m.haas_ngc = false;
    }
    let v = translate::to_fanuc::verify(&mut db, &u, &[], &plain, "plain.nc", 100_000);
    assert!(!v.equivalent, "{}", v.summary);
}

#[test]
fn off_the_ngc_profile_the_library_api_refuses_as_before() {
    let (db, _, t) = in_process(false);
    assert!(!t.ok());
    let text = nctrans::diag::render(&db, &t.diags);
    assert!(text.contains("NC504") && text.contains("not retained common variables"), "{text}");
}

#[test]
fn global_user_data_passed_for_a_var_parameter_passes_its_number() {
    // On a plain FANUC at #500.., on a Haas NGC at #10200..: the callee writes through it.
    for (series, rule, arg) in [(None, "DRESS_A=#600", "B602."), (Some("haas-ngc"), "DRESS_A=#10200", "B10202.")] {
        let d = library("byref", series, &format!("\"{rule}\""));
        std::fs::write(d.join("BUMP.SPF"), "PROC BUMP(REAL STEP, VAR REAL VAL)\nVAL=VAL+STEP\nRET\n").unwrap();
        std::fs::write(d.join("P.MPF"), "DRESS_A[2]=1\nBUMP(0.5, DRESS_A[2])\nG0 X=DRESS_A[2]\nM30\n").unwrap();
        let (_, err, code) = nctrans(&d, &["--to", "fanuc", "P.MPF", "-o", "p.nc"]);
        assert_eq!(code, 0, "{series:?}: {err}");
        assert!(err.contains("equivalent"), "{err}");
        let text = std::fs::read_to_string(d.join("p.nc")).unwrap();
        assert!(text.contains(&format!("A0.5 {arg}")), "{series:?}: `{arg}` not in\n{text}");
    }
}
