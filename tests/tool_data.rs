//! Tool management and tool offset data (issue 21): `GETT("NAME")` from the tool map, and
//! Siemens cutting edge data `$TC_DP3/6/12/15[t,d]` ↔ FANUC memory C `#11001+`/`#10001+`/
//! `#13001+`/`#12001+` through the offset map, proven by verify; planted wrong translations
//! (another register, geometry for wear) caught by the check; every refusal names its code.

use std::path::{Path, PathBuf};
use std::process::Command;

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("nctrans-tool-data-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn nctrans(cwd: &Path, args: &[&str]) -> (bool, String) {
    let o = Command::new(env!("CARGO_BIN_EXE_nctrans")).current_dir(cwd).args(args).output().unwrap();
    (o.status.success(), format!("{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr)))
}

/// A tool-setting routine a setter would write: the measured length goes into the edge,
/// the wear is cleared, the radius of the cutter sets the stepover, and the probe's T
/// number comes from tool management.
const SETTER: &str = "\
; set T12 after measuring it on the presetter, then face with 60 % stepover
DEF REAL MEASURED, STEPOVER
R30=6
MEASURED=142.118
$TC_DP3[12,1]=MEASURED
$TC_DP12[12,1]=0
$TC_DP6[12,1]=R30
STEPOVER=$TC_DP6[12,1]*2*0.6
T12 D1 M6
S2400 M3
G0 X-10 Y0 Z5
G1 Z=-0.5-$TC_DP12[12,1] F250
G1 X80
G1 Y=STEPOVER
G1 X-10
R40=GETT(\"PROBE_3D\")
G0 Z50 M5
G0 X=R40
M30
";

#[test]
fn the_setter_translates_to_memory_c_and_verifies() {
    let d = dir("setter");
    std::fs::write(d.join("setter.mpf"), SETTER).unwrap();
    let (ok, out) = nctrans(&d, &["--to", "fanuc", "setter.mpf", "--tool-map", "PROBE_3D=31", "-o", "setter.nc"]);
    assert!(ok, "{out}");
    assert!(out.contains("equivalent"), "{out}");
    let nc = std::fs::read_to_string(d.join("setter.nc")).unwrap();
    for want in ["#11012=#100", "#10012=0.", "#13012=#530", "#101=#13012*2.*0.6", "Z[-0.5-#10012]", "#540=31."] {
        assert!(nc.contains(want), "missing {want}:\n{nc}");
    }
    // Planted: the length into another register, or into the wear instead of the geometry.
    for (from, to) in [("#11012=", "#11013="), ("#11012=", "#10012="), ("#13012=#530", "#12012=#530")] {
        std::fs::write(d.join("bad.nc"), nc.replacen(from, to, 1)).unwrap();
        let (ok, out) = nctrans(&d, &["check", "setter.mpf", "bad.nc", "--tool-map", "PROBE_3D=31"]);
        // Caught as a divergence, or as the read of a register the bad program never wrote.
        assert!(!ok && (out.contains("diverge") || out.contains("NC571")), "{from} -> {to} not caught:\n{out}");
    }
}

#[test]
fn an_edge_of_the_offset_map_uses_its_own_registers() {
    let d = dir("map");
    std::fs::write(d.join("nctrans.toml"), "[offsets]\n\"6.2\" = \"H26,D46\"\n").unwrap();
    let src = "T6 M6 D2\n$TC_DP15[6,2]=-0.02\n$TC_DP12[6,2]=0.015\nG0 X0 Y0 Z10\nM30\n";
    std::fs::write(d.join("edge.mpf"), src).unwrap();
    let (ok, out) = nctrans(&d, &["--to", "fanuc", "edge.mpf", "-o", "edge.nc"]);
    assert!(ok, "{out}");
    let nc = std::fs::read_to_string(d.join("edge.nc")).unwrap();
    assert!(nc.contains("#12046=-0.02") && nc.contains("#10026=0.015"), "{nc}");
}

#[test]
fn what_has_no_counterpart_is_refused_by_name() {
    let d = dir("refuse");
    let cases: &[(&str, &str, &str)] = &[
        ("R1=GETT(\"NOT_THERE\")\nG0 X=R1\nM30\n", "NC525", "NOT_THERE"),
        ("R1=GETT(\"PROBE_3D\", 2)\nG0 X=R1\nM30\n", "NC526", "duplo"),
        ("R1=$TC_DP1[3,1]\nG0 X=R1\nM30\n", "NC526", "tool type"),
        ("$TC_DP3[3,2]=100\nM30\n", "NC527", "3.2"),
    ];
    for (i, (src, code, word)) in cases.iter().enumerate() {
        let f = format!("c{i}.mpf");
        std::fs::write(d.join(&f), src).unwrap();
        let (ok, out) = nctrans(&d, &["--to", "fanuc", &f, "--tool-map", "PROBE_3D=31"]);
        assert!(!ok && out.contains(code) && out.contains(word), "{src}: {out}");
    }
}

#[test]
fn a_read_of_data_the_run_was_not_given_is_an_error_and_an_input_gives_it() {
    let d = dir("input");
    std::fs::write(d.join("r.mpf"), "R1=$TC_DP6[4,1]*2\nG0 X=R1\nM30\n").unwrap();
    let (ok, out) = nctrans(&d, &["run", "r.mpf"]);
    assert!(!ok && out.contains("NC571"), "{out}");
    let (ok, out) = nctrans(&d, &["run", "r.mpf", "--set", "$TC_DP6[4,1]=5"]);
    assert!(ok && out.contains("X=10"), "{out}");
    std::fs::write(d.join("r.nc"), "#1=#13004*2\nG0 X#1\nM30\n").unwrap();
    let (ok, out) = nctrans(&d, &["run", "r.nc", "--set", "#13004=5."]);
    assert!(ok && out.contains("X=10"), "{out}");
}

/// A wear update after probing, as a FANUC macro writes it: memory C registers become the
/// cutting edge data of edge 1 of the tool, and a planted wrong edge is caught.
const WEAR: &str = "\
%
O1200 (WEAR UPDATE AFTER PROBING)
(nctrans: set #10012=0.01 #13012=4.)
#1=142.118
#11012=#1
#10012=#10012-0.012
#2=#13012*2*0.6
T12 M06
G43 H12
G00 X0 Y0 Z50.
G01 Z[-1-#10012] F300.
G01 X#2
#3=#[11000+12]
G01 Y#3
M30
%
";

#[test]
fn memory_c_translates_to_cutting_edge_data_and_verifies() {
    let d = dir("wear");
    std::fs::write(d.join("wear.nc"), WEAR).unwrap();
    let (ok, out) = nctrans(&d, &["--to", "sinumerik", "wear.nc", "-o", "WEAR.MPF"]);
    assert!(ok && out.contains("equivalent"), "{out}");
    let s = std::fs::read_to_string(d.join("WEAR.MPF")).unwrap();
    for want in [
        "nctrans: set $TC_DP12[12,1]=0.01 $TC_DP6[12,1]=4.",
        "$TC_DP3[12,1]=LOC1",
        "$TC_DP12[12,1]=$TC_DP12[12,1]-0.012",
        "LOC3=$TC_DP3[12,1]",
    ] {
        assert!(s.contains(want), "missing {want}:\n{s}");
    }
    std::fs::write(d.join("BAD.MPF"), s.replacen("$TC_DP3[12,1]=LOC1", "$TC_DP3[12,2]=LOC1", 1)).unwrap();
    let (ok, out) = nctrans(&d, &["check", "wear.nc", "BAD.MPF"]);
    assert!(!ok && (out.contains("diverge") || out.contains("NC571")), "{out}");
}

#[test]
fn tool_management_data_and_a_haas_target_are_refused() {
    let d = dir("tp");
    std::fs::write(d.join("tp.mpf"), "R1=$TC_TP8[3]\nG0 X=R1\nM30\n").unwrap();
    let (ok, out) = nctrans(&d, &["--to", "fanuc", "tp.mpf"]);
    assert!(!ok && out.contains("NC526") && out.contains("$TC_TP8"), "{out}");
    std::fs::write(d.join("nctrans.toml"), "[fanuc]\nseries = \"haas-ngc\"\n").unwrap();
    std::fs::write(d.join("h.mpf"), "$TC_DP3[3,1]=100\nM30\n").unwrap();
    let (ok, out) = nctrans(&d, &["--to", "fanuc", "h.mpf"]);
    assert!(!ok && out.contains("NC528"), "{out}");
}

#[test]
fn g10_l10_to_l13_write_the_edge_data_and_g91_adds() {
    let d = dir("g10");
    let src = "%\nO1300 (SET T7)\n(nctrans: set #10007=0.02)\nG90 G10 L10 P7 R98.765\nG91 G10 L11 P7 R-0.005\nG90\n\
               G10 L12 P7 R5.\n#1=#10007\nG0 X#1 Y#11007 Z#13007\nM30\n%\n";
    std::fs::write(d.join("g10.nc"), src).unwrap();
    let (ok, out) = nctrans(&d, &["run", "g10.nc"]);
    assert!(ok && out.contains("tool_data register=7 field=length_wear value=0.015"), "{out}");
    let (ok, out) = nctrans(&d, &["--to", "sinumerik", "g10.nc", "-o", "G10.MPF"]);
    assert!(ok && out.contains("equivalent"), "{out}");
    let s = std::fs::read_to_string(d.join("G10.MPF")).unwrap();
    for want in ["$TC_DP3[7,1]=98.765", "G91\n$TC_DP12[7,1]=$TC_DP12[7,1]+(-0.005)", "$TC_DP6[7,1]=5"] {
        assert!(s.contains(want), "missing {want}:\n{s}");
    }
    // Planted: the radius into the wear.
    std::fs::write(d.join("BAD.MPF"), s.replacen("$TC_DP6[7,1]=5", "$TC_DP15[7,1]=5", 1)).unwrap();
    let (ok, out) = nctrans(&d, &["check", "g10.nc", "BAD.MPF"]);
    assert!(!ok && (out.contains("diverge") || out.contains("NC571")), "{out}");
    // Without a decimal point R depends on the increment system: refused.
    std::fs::write(d.join("bare.nc"), "G90 G10 L10 P7 R98765\nM30\n").unwrap();
    let (ok, out) = nctrans(&d, &["--to", "sinumerik", "bare.nc"]);
    assert!(!ok && out.contains("NC529"), "{out}");
    // A fractional L is not translated as the L below it (the run rounds every G10 L).
    std::fs::write(d.join("frac.nc"), "G90 G10 L10.5 P7 R98.765\nM30\n").unwrap();
    let (ok, out) = nctrans(&d, &["--to", "sinumerik", "frac.nc"]);
    assert!(!ok && !out.contains("$TC_DP3"), "{out}");
}
