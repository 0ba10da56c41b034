//! The skip position of Z under tool length compensation, both ways (issue 20, probing):
//! FANUC `#5063` under G43 H holds the trigger point with the H register's length in force at
//! the G31, the Siemens kept `$AA_MW[Z]` the tip. FANUC → Sinumerik adds the length of the
//! edge the G43 H became where G43 is set on every path to the G31 (NC550 elsewhere, G44
//! NC474, Haas NC654); Sinumerik → FANUC takes the H register's length off the kept `#5063`
//! where the H at the measuring block is known (NC551 elsewhere, Haas NC655). Both proven
//! with the lengths given in the programs; planted wrong translations are caught.

mod eval_support;

use eval_support::{nctrans, scratch_dir, write};
use std::path::PathBuf;

fn scratch(name: &str) -> PathBuf {
    scratch_dir("probe-skip-length-tests", name)
}

fn check(a: &str, b: &str) -> (i32, String) {
    let (code, out, err) = nctrans(&["check", a, b]);
    (code, format!("{out}{err}"))
}

fn to_sinumerik(d: &std::path::Path, name: &str, text: &str) -> (i32, String, String, String) {
    let f = write(d, &format!("{name}.nc"), text);
    let out = d.join(name);
    let (code, o, err) = nctrans(&[&f, "--to", "sinumerik", "-o", &format!("{}/", out.display())]);
    let mpf = std::fs::read_dir(&out)
        .ok()
        .and_then(|mut r| r.next())
        .and_then(|e| e.ok())
        .map(|e| e.path().to_string_lossy().into_owned())
        .unwrap_or_default();
    (code, format!("{o}{err}"), f, mpf)
}

/// A Z touch under G43 H20 (150 less 0.2 wear), with the hit `probe`; H21 another tool.
fn fanuc(g43: &str, probe: &str) -> String {
    format!(
        "(nctrans: probe {probe})\nO1\nG10 L10 P20 R150.\nG10 L11 P20 R-0.2\nG10 L10 P21 R90.\nG10 L11 P21 R0.\n\
         T20 M6\nG0 G90 G54 X0 Y0\n{g43} Z50.\nG31 Z-20. F200.\n#1=#5063\n#2=#5061\nG0 X#1 Y#2\nG49\nM30\n"
    )
}

#[test]
fn fanuc_to_sinumerik_adds_the_edge_length_at_the_g31() {
    let d = scratch("to-sinumerik");
    for probe in ["Z=2.5", "miss"] {
        let (code, msg, f, mpf) = to_sinumerik(&d, &format!("a{}", probe.len()), &fanuc("G43 H20", probe));
        assert_eq!(code, 0, "{msg}");
        assert!(msg.contains("equivalent"), "{msg}");
        let text = std::fs::read_to_string(&mpf).expect("written");
        let hit = "NCTRANS_SKIP_Z=$AA_MW[Z]+($TC_DP3[20,1]+$TC_DP12[20,1])";
        let miss = "NCTRANS_SKIP_Z=$AA_IW[Z]+($TC_DP3[20,1]+$TC_DP12[20,1])";
        assert!(text.contains(hit) && text.contains(miss), "{text}");
        // X carries no length.
        assert!(text.contains("NCTRANS_SKIP_X=$AA_IW[X]\n"), "{text}");
        assert_eq!(check(&f, &mpf).0, 0, "{}", check(&f, &mpf).1);
        // Back to FANUC: the keep with H20's length under G43 H20 is #5063 itself.
        let back = d.join(format!("back{}.nc", probe.len())).to_string_lossy().into_owned();
        let (code, o, err) = nctrans(&[&mpf, "--to", "fanuc", "-o", &back]);
        assert_eq!(code, 0, "{o}{err}");
        let again = std::fs::read_to_string(&back).expect("written");
        assert!(again.contains("G31 Z-20. F200.\nG00\n#1=#5063\n"), "{again}");
        // Planted: the sign, the length missing, the wear missing, another tool's length.
        for (name, bad) in [
            ("W1.MPF", text.replace("[Z]+(", "[Z]-(")),
            ("W2.MPF", text.replace("+($TC_DP3[20,1]+$TC_DP12[20,1])", "")),
            ("W3.MPF", text.replace("+$TC_DP12[20,1]", "")),
            ("W4.MPF", text.replace("[20,1]+$TC_DP12[20,1]", "[21,1]+$TC_DP12[21,1]")),
        ] {
            assert_ne!(bad, text, "{name}");
            let w = write(&d, name, &bad);
            let (code, msg) = check(&f, &w);
            assert_eq!(code, 1, "{name} {probe}: {msg}");
            assert!(msg.contains("NC500"), "{name}: {msg}");
        }
        // Another edge's length in the translation's own variable under H20: refused by name.
        let other = text.replace("[Z]+($TC_DP3[20,1]+$TC_DP12[20,1])", "[Z]+($TC_DP3[21,1]+$TC_DP12[21,1])");
        let o_mpf = write(&d, &format!("OTHER{}.MPF", probe.len()), &other);
        let (code, _, err) = nctrans(&[&o_mpf, "--to", "fanuc"]);
        assert_ne!(code, 0);
        assert!(err.contains("NC551") && err.contains("NCTRANS_SKIP_Z"), "{err}");
    }
}

#[test]
fn the_length_is_the_one_in_force_at_the_g31_not_at_the_read() {
    let d = scratch("at-g31");
    // H20 rewritten after the G31, before the read: #5063 keeps the length at the G31, as the
    // Siemens keep right after the measuring block does.
    let text = fanuc("G43 H20", "Z=2.5").replace("#1=#5063\n", "G10 L10 P20 R50.\n#1=#5063\n");
    let (code, msg, f, mpf) = to_sinumerik(&d, "b", &text);
    assert_eq!(code, 0, "{msg}");
    let out = std::fs::read_to_string(&mpf).expect("written");
    let keep = out.find("$AA_MW[Z]+($TC_DP3[20,1]+$TC_DP12[20,1])").expect("kept with the length");
    let write_at = out.find("$TC_DP3[20,1]=50").expect("the register write");
    assert!(keep < write_at, "{out}");
    assert_eq!(check(&f, &mpf).0, 0, "{}", check(&f, &mpf).1);
    // Planted: the length taken at the read (after the write).
    let moved = out
        .replace("+($TC_DP3[20,1]+$TC_DP12[20,1])", "")
        .replace("LOC1=NCTRANS_SKIP_Z", "LOC1=NCTRANS_SKIP_Z+($TC_DP3[20,1]+$TC_DP12[20,1])");
    assert_ne!(moved, out);
    let w = write(&d, "W6.MPF", &moved);
    assert_eq!(check(&f, &w).0, 1, "{}", check(&f, &w).1);
}

#[test]
fn an_h_the_flow_does_not_know_takes_the_active_edge() {
    let d = scratch("active");
    let text = fanuc("G43 H#33", "Z=2.5").replace("T20 M6", "#33=20\nT#33 M6");
    let (code, msg, f, mpf) = to_sinumerik(&d, "c", &text);
    assert_eq!(code, 0, "{msg}");
    let out = std::fs::read_to_string(&mpf).expect("written");
    let active = "$AA_MW[Z]+($TC_DP3[$P_TOOLNO,$P_TOOL]+$TC_DP12[$P_TOOLNO,$P_TOOL])";
    assert!(out.contains(active), "{out}");
    assert_eq!(check(&f, &mpf).0, 0, "{}", check(&f, &mpf).1);
    let w = write(&d, "W5.MPF", &out.replace(active, "$AA_MW[Z]+$TC_DP3[$P_TOOLNO,$P_TOOL]"));
    assert_eq!(check(&f, &w).0, 1, "{}", check(&f, &w).1);
}

#[test]
fn fanuc_refusals_name_what_is_not_settled() {
    let d = scratch("refused");
    // G43 on one path only.
    let one = fanuc("G43 H20", "Z=2.5")
        .replace("T20 M6\n", "T20 M6\nIF [#5 GT 0] GOTO 10\n")
        .replace("G43 H20 Z50.\n", "G43 H20 Z50.\nN10 G0 Z50.\n");
    let (code, msg, _, _) = to_sinumerik(&d, "e", &one);
    assert_ne!(code, 0);
    assert!(msg.contains("NC550") && msg.contains("not set on every path"), "{msg}");
    // G44 keeps the compensation translation's refusal; the evaluator subtracts its length.
    let (code, msg, _, _) = to_sinumerik(&d, "g", &fanuc("G44 H20", "Z=2.5"));
    assert_ne!(code, 0);
    assert!(msg.contains("NC474"), "{msg}");
    // A Haas profile: its offset tables are not the tool data.
    let h = d.join("haas");
    std::fs::create_dir_all(&h).expect("dir");
    std::fs::write(h.join("nctrans.toml"), "[fanuc]\nseries = \"haas\"\n").expect("write");
    write(&h, "O1.nc", "O1\nT1 M6\nG0 G90 G54 X0 Y0\nG43 H1 Z50.\nG31 Z0 F100.\n#1=#5063\nG0 X#1\nG49\nM30\n");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_nctrans"))
        .current_dir(&h)
        .args(["O1.nc", "--to", "sinumerik", "-o", "out/"])
        .output()
        .expect("runs");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(err.contains("NC654") && err.contains("Haas"), "{err}");
}

/// A Z touch under T20 D1 (150 less 0.2 wear), the lengths written by the program.
const SIEMENS: &str = "DEF REAL ZS\nG90 G17 G710\n$TC_DP3[20,1]=150\n$TC_DP12[20,1]=-0.2\n$TC_DP3[21,1]=90\n\
                       $TC_DP12[21,1]=0\nG54\nT20 M6 D1\nG0 X0 Y0 Z50\nMEAS=1 G1 Z-20 F200\nSTOPRE\n\
                       IF $AC_MEA[1]==1\n  ZS=$AA_MW[Z]\nELSE\n  ZS=$AA_IW[Z]\nENDIF\nG0 X=ZS\nD0\nM30\n";

#[test]
fn sinumerik_to_fanuc_takes_the_h_length_off_the_skip_position() {
    let d = scratch("to-fanuc");
    for probe in ["Z=2.5", "miss"] {
        let f = write(&d, &format!("S{}.MPF", probe.len()), &format!("; nctrans: probe {probe}\n{SIEMENS}"));
        let nc = d.join(format!("s{}.nc", probe.len())).to_string_lossy().into_owned();
        let (code, o, err) = nctrans(&[&f, "--to", "fanuc", "-o", &nc]);
        assert_eq!(code, 0, "{o}{err}");
        assert!(err.contains("equivalent") || o.contains("equivalent"), "{o}{err}");
        let text = std::fs::read_to_string(&nc).expect("written");
        assert!(text.contains("G43 H20\n") && text.contains("#100=#5063-[#11020+#10020]\n"), "{text}");
        assert_eq!(check(&f, &nc).0, 0, "{}", check(&f, &nc).1);
        for (name, bad) in [
            ("w1.nc", text.replace("#5063-[", "#5063+[")),
            ("w2.nc", text.replace("#5063-[#11020+#10020]", "#5063")),
            ("w3.nc", text.replace("#5063-[#11020+#10020]", "#5063-#11020")),
            ("w4.nc", text.replace("[#11020+#10020]", "[#11021+#10021]")),
        ] {
            assert_ne!(bad, text, "{name}");
            let w = write(&d, name, &bad);
            let (code, msg) = check(&f, &w);
            assert_ne!(code, 0, "{name} {probe}: {msg}");
            assert!(msg.contains("NC500") || msg.contains("not equivalent"), "{name}: {msg}");
        }
    }
    // A keep that adds another edge's length: H20's taken off, that one added, proven.
    let other = SIEMENS
        .replace("ZS=$AA_MW[Z]", "ZS=$AA_MW[Z]+($TC_DP3[21,1]+$TC_DP12[21,1])")
        .replace("ZS=$AA_IW[Z]", "ZS=$AA_IW[Z]+($TC_DP3[21,1]+$TC_DP12[21,1])");
    let f = write(&d, "SO.MPF", &format!("; nctrans: probe Z=2.5\n{other}"));
    let nc = d.join("so.nc").to_string_lossy().into_owned();
    let (code, o, err) = nctrans(&[&f, "--to", "fanuc", "-o", &nc]);
    assert_eq!(code, 0, "{o}{err}");
    assert!(err.contains("equivalent") || o.contains("equivalent"), "{o}{err}");
    let text = std::fs::read_to_string(&nc).expect("written");
    assert!(text.contains("#100=#5063-[#11020+#10020]+[#11021+#10021]\n"), "{text}");
    let w = write(&d, "w5.nc", &text.replace("-[#11020+#10020]+[#11021+#10021]", "+[#11021+#10021]"));
    assert_ne!(check(&f, &w).0, 0, "{}", check(&f, &w).1);
    // D0 at the measuring block: #5063 as it is.
    let f = write(&d, "S0.MPF", &SIEMENS.replace("T20 M6 D1", "T20 M6 D0"));
    let (code, o, err) = nctrans(&[&f, "--to", "fanuc"]);
    assert_eq!(code, 0, "{o}{err}");
    assert!(o.contains("#100=#5063\n"), "{o}");
}

#[test]
fn sinumerik_refusals_name_the_unknown_edge() {
    let d = scratch("to-fanuc-refused");
    // The edge decided on a path.
    let text = SIEMENS.replace("G0 X0 Y0 Z50\n", "G0 X0 Y0 Z50\nIF R1>0 GOTOF NOD\nD0\nNOD:\n");
    let f = write(&d, "P.MPF", &text);
    let (code, o, err) = nctrans(&[&f, "--to", "fanuc"]);
    assert_ne!(code, 0, "{o}");
    assert!(err.contains("NC551") && err.contains("not known on every path"), "{err}");
    // A PROC runs under its caller's edge.
    let proc_text = "PROC TOUCH\nDEF REAL ZS\nMEAS=1 G1 Z-20 F200\nSTOPRE\nIF $AC_MEA[1]==1\n  ZS=$AA_MW[Z]\nELSE\n  \
                     ZS=$AA_IW[Z]\nENDIF\nG0 X=ZS\nRET\n";
    let f = write(&d, "TOUCH.SPF", proc_text);
    let (code, _, err) = nctrans(&[&f, "--to", "fanuc"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC551"), "{err}");
    // A Haas target.
    let h = d.join("haas");
    std::fs::create_dir_all(&h).expect("dir");
    std::fs::write(h.join("nctrans.toml"), "[fanuc]\nseries = \"haas\"\n").expect("write");
    write(&h, "S.MPF", SIEMENS);
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_nctrans"))
        .current_dir(&h)
        .args(["S.MPF", "--to", "fanuc", "-o", "s.nc"])
        .output()
        .expect("runs");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(err.contains("NC655") && err.contains("Haas"), "{err}");
}
