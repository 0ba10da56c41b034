//! Current positions read under tool length compensation (issue 20, "Positions read back"):
//! FANUC `#5021+`/`#5041+` under G43/G44 hold the H register's length on Z (geometry plus
//! wear, + under G43, − under G44), Siemens `$AA_IM`/`$AA_MM` under an edge the edge's
//! `$TC_DP3+$TC_DP12`, where the run is given them; otherwise NC534 naming the inputs. The
//! translations write what both controls read alike and are proven; planted wrong ones are
//! caught; G41/G42 stays refused.

mod eval_support;

use eval_support::{nctrans, run_bare, scratch_dir, write};
use std::path::PathBuf;

fn scratch(name: &str) -> PathBuf {
    scratch_dir("position-reads-length-tests", name)
}

fn run(file: &str, extra: &[&str]) -> (String, String) {
    run_bare(file, extra)
}

/// `#1` Z in workpiece, `#2` Z in machine coordinates, `#3` X in workpiece coordinates, under
/// `g` H1, with G54 Z shifted by -20 so the two systems differ.
fn fanuc_reads(g: &str) -> String {
    format!(
        "G10 L2 P1 X0 Y0 Z-20.\nG54 G0 X3. Y4. Z50.\n{g} H1 Z10.\n#1=#5043\n#2=#5023\n#3=#5041\nG49\n\
         G0 X#1 Y#2 Z#3\nM30\n"
    )
}

#[test]
fn fanuc_current_positions_include_the_h_length_on_z() {
    let d = scratch("fanuc");
    let g43 = write(&d, "a.nc", &fanuc_reads("G43"));
    let g44 = write(&d, "b.nc", &fanuc_reads("G44"));
    // Positive length, negative wear: 99.5 on Z; X is not offset.
    let set = ["--set", "#11001=100.", "--set", "#10001=-0.5"];
    let (t, err) = run(&g43, &set);
    assert!(t.contains("move rapid X=109.5 Y=89.5 Z=-17 f=-"), "{t}{err}");
    let (t, err) = run(&g44, &set);
    assert!(t.contains("move rapid X=-89.5 Y=-109.5 Z=-17 f=-"), "{t}{err}");
    // A negative length (a gauge line below the spindle nose setting).
    let neg = ["--set", "#11001=-30.", "--set", "#10001=0"];
    assert!(run(&g43, &neg).0.contains("move rapid X=-20 Y=-40 Z=-17 f=-"), "{}", run(&g43, &neg).0);
    assert!(run(&g44, &neg).0.contains("move rapid X=40 Y=20 Z=-17 f=-"), "{}", run(&g44, &neg).0);
    // Under G49 (and H0) the reads hold no offset and need no input.
    let f = write(&d, "c.nc", "G0 X3. Y4. Z50.\nG43 H0 Z10.\n#1=#5043\nG49\n#2=#5023\nG0 X#1 Y#2\nM30\n");
    assert!(run(&f, &[]).0.contains("move rapid X=10 Y=10 Z=10 f=-"), "{}", run(&f, &[]).0);
}

#[test]
fn siemens_machine_positions_include_the_edge_length() {
    let d = scratch("siemens");
    let text = "G17 G90 G710\nT1 M6 D1\nG0 X3 Y4 Z10\nR1=$AA_IM[Z]\nR2=$AA_IM[X]\nR3=$AA_IW[Z]\n\
                MEAS=1 G1 Z0 F100\nSTOPRE\nR4=$AA_MM[Z]\nR5=$AA_MW[Z]\nD0\nG0 X=R1 Y=R2 Z=R3+R4+R5\nM30\n";
    let f = write(&d, "A.MPF", text);
    let set = ["--set", "$TC_DP3[1,1]=100", "--set", "$TC_DP12[1,1]=-0.5", "--probe", "Z=2"];
    let (t, err) = run(&f, &set);
    // $AA_IM[Z] 10 + 99.5; X not offset; $AA_IW the tip; $AA_MM 2 + 99.5, $AA_MW 2.
    assert!(t.contains("move rapid X=109.5 Y=3 Z=113.5 f=-"), "{t}{err}");
    let neg = ["--set", "$TC_DP3[1,1]=-30", "--set", "$TC_DP12[1,1]=0", "--probe", "Z=2"];
    assert!(run(&f, &neg).0.contains("move rapid X=-20 Y=3 Z=-16 f=-"), "{}", run(&f, &neg).0);
}

#[test]
fn a_length_the_run_is_not_given_is_refused_naming_the_inputs() {
    let d = scratch("refused");
    let f = write(&d, "a.nc", &fanuc_reads("G43"));
    let (_, err) = run(&f, &[]);
    assert!(err.contains("NC534") && err.contains("#5043 read under G43/G44"), "{err}");
    assert!(err.contains("--set '#11001=…' --set '#10001=…'"), "{err}");
    let (_, err) = run(&f, &["--set", "#11001=100."]);
    assert!(err.contains("NC534") && err.contains("(--set '#10001=…')"), "{err}");
    // X under G17 carries no length: read without the register.
    let x = write(&d, "x.nc", "G0 X3. Y4. Z50.\nG43 H1 Z10.\n#1=#5041\n#2=#5021\nG49\nG0 X[#1+#2]\nM30\n");
    assert!(run(&x, &[]).0.contains("move rapid X=6 Y=4 Z=10 f=-"), "{}", run(&x, &[]).1);
    let g18 = write(&d, "b.nc", "G18 G0 X0 Z50.\nG43 H1 Z10.\n#1=#5023\nM30\n");
    let (_, err) = run(&g18, &["--set", "#11001=100.", "--set", "#10001=0"]);
    assert!(err.contains("NC534") && err.contains("outside G17"), "{err}");
    let s = write(&d, "C.MPF", "G17 G710\nT1 M6 D1\nG0 X0 Y0 Z10\nR1=$AA_IM[Z]\nM30\n");
    let (_, err) = run(&s, &[]);
    assert!(err.contains("NC534") && err.contains("$AA_IM read under a cutting edge D active"), "{err}");
    assert!(err.contains("--set '$TC_DP3[1,1]=…' --set '$TC_DP12[1,1]=…'"), "{err}");
    let m = write(&d, "D.MPF", "G17 G710\nT1 M6 D1\nG0 X0 Y0 Z10\nMEAS=1 G1 Z0 F100\nR1=$AA_MM[Z]\nM30\n");
    let (_, err) = run(&m, &["--probe", "Z=2", "--set", "$TC_DP3[1,1]=100"]);
    assert!(err.contains("NC534") && err.contains("$AA_MM") && err.contains("$TC_DP12[1,1]"), "{err}");
}

#[test]
fn radius_compensation_keeps_its_refusal() {
    let d = scratch("radius");
    let set = ["--set", "#11001=100.", "--set", "#10001=0"];
    for (name, read) in [("a.nc", "#5041"), ("b.nc", "#5021"), ("c.nc", "#5043")] {
        let text = format!("G0 X0 Y0 Z50.\nG43 H1 Z10.\nG41 D1 G1 X10. F100.\n#1={read}\nG40 G1 X20.\nM30\n");
        let f = write(&d, name, &text);
        let (_, err) = run(&f, &set);
        assert!(err.contains("NC534") && err.contains("G41/G42"), "{name}: {err}");
    }
    let s = write(&d, "D.MPF", "G17 G710\nT1 M6 D1\nG0 X0 Y0 Z10\nG41 G1 X10 F100\nR1=$AA_IM[Z]\nM30\n");
    let (_, err) = run(&s, &["--set", "$TC_DP3[1,1]=100", "--set", "$TC_DP12[1,1]=0"]);
    assert!(err.contains("NC534") && err.contains("G41/G42"), "{err}");
}

const FANUC: &str = "(nctrans: set #11001=100.)\n(nctrans: set #10001=-0.5)\nO1\nT1 M6\nG0 G90 G54 X0 Y0\n\
                     G43 H1 Z50.\n#1=#5043\n#2=#5023\nG0 X#1 Y#2\nG49\nM30\n";

fn check(a: &str, b: &str) -> (i32, String) {
    let (code, out, err) = nctrans(&["check", a, b]);
    (code, format!("{out}{err}"))
}

#[test]
fn fanuc_to_sinumerik_adds_the_edge_length_where_g43_is_set_on_every_path() {
    let d = scratch("to-sinumerik");
    let f = write(&d, "c.nc", FANUC);
    let out = d.join("c");
    let (code, o, err) = nctrans(&[&f, "--to", "sinumerik", "-o", &format!("{}/", out.display())]);
    assert_eq!(code, 0, "{o}{err}");
    assert!(err.contains("equivalent") || o.contains("equivalent"), "{o}{err}");
    let mpf = out.join("P_C.MPF");
    let text = std::fs::read_to_string(&mpf).expect("written");
    let mpf = mpf.to_string_lossy().into_owned();
    let form = "LOC1=$AA_IW[Z]+($TC_DP3[1,1]+$TC_DP12[1,1])";
    assert!(text.contains(form) && text.contains("LOC2=$AA_IM[Z]"), "{text}");
    assert_eq!(check(&f, &mpf).0, 0, "{}", check(&f, &mpf).1);
    // Planted: the length subtracted, the length missing, the machine position less the length.
    for (name, bad) in [
        ("W1.MPF", text.replace("$AA_IW[Z]+(", "$AA_IW[Z]-(")),
        ("W2.MPF", text.replace(form, "LOC1=$AA_IW[Z]")),
        ("W3.MPF", text.replace("LOC2=$AA_IM[Z]", "LOC2=$AA_IM[Z]-$TC_DP3[1,1]")),
    ] {
        let w = write(&d, name, &bad);
        let (code, msg) = check(&f, &w);
        assert_eq!(code, 1, "{name}: {msg}");
        assert!(msg.contains("NC500"), "{name}: {msg}");
    }
    // Back to FANUC: the tip and H1's length, the same value as #5043 under G43 H1.
    let back = d.join("back.nc").to_string_lossy().into_owned();
    let (code, o, err) = nctrans(&[&mpf, "--to", "fanuc", "-o", &back]);
    assert_eq!(code, 0, "{o}{err}");
    let text = std::fs::read_to_string(&back).expect("written");
    assert!(text.contains("=#5003+[#11001+#10001]"), "{text}");
    // An H the flow does not know (the tool's variable): the active edge's length.
    let h = FANUC.replace("T1 M6", "#33=1\nT#33 M6").replace("H1", "H#33");
    let f = write(&d, "h.nc", &h);
    let out = d.join("h");
    let (code, o, err) = nctrans(&[&f, "--to", "sinumerik", "-o", &format!("{}/", out.display())]);
    assert_eq!(code, 0, "{o}{err}");
    let text = std::fs::read_to_string(out.join("P_H.MPF")).expect("written");
    let active = "$AA_IW[Z]+($TC_DP3[$P_TOOLNO,$P_TOOL]+$TC_DP12[$P_TOOLNO,$P_TOOL])";
    assert!(text.contains(active), "{text}");
    let w = write(&d, "W4.MPF", &text.replace(active, "$AA_IW[Z]+$TC_DP3[$P_TOOLNO,$P_TOOL]"));
    let (code, msg) = check(&f, &w);
    assert_eq!(code, 1, "{msg}");
    // G43 on one path only: refused by name.
    let one = "O1\nT1 M6\nG0 G90 G54 X0 Y0\nIF [#5 GT 0] GOTO 10\nG43 H1 Z50.\nN10 #1=#5043\nG0 X#1\nM30\n";
    let f = write(&d, "e.nc", one);
    let (code, _, err) = nctrans(&[&f, "--to", "sinumerik", "-o", &format!("{}/", d.join("e").display())]);
    assert_ne!(code, 0);
    assert!(err.contains("NC643") && err.contains("#5043"), "{err}");
    // Under G49 on every path (and before any G43) the plain tip.
    let plain = "O1\nT1 M6\nG0 G90 G54 X0 Y0 Z10.\n#1=#5043\nG43 H1 Z50.\nG49\nZ10.\n#2=#5043\nG0 X#1 Y#2\nM30\n";
    let f = write(&d, "g.nc", plain);
    let out = d.join("g");
    let (code, o, err) = nctrans(&[&f, "--to", "sinumerik", "-o", &format!("{}/", out.display())]);
    assert_eq!(code, 0, "{o}{err}");
    let text = std::fs::read_to_string(out.join("P_G.MPF")).expect("written");
    assert!(text.contains("LOC1=$AA_IW[Z]\n") && text.contains("LOC2=$AA_IW[Z]\n"), "{text}");
}

const SIEMENS: &str = "DEF REAL ZW, ZM\nG17 G90 G710 G54\nT1 M6 D1\nG0 X0 Y0 Z50\nZW=$AA_IW[Z]\nZM=$AA_IM[Z]\n\
                       G0 X=ZW Y=ZM\nM30\n";

#[test]
fn sinumerik_to_fanuc_reads_the_tip_as_the_block_end_position_under_an_edge() {
    let d = scratch("to-fanuc");
    let head = "; nctrans: set $TC_DP3[1,1]=100\n; nctrans: set $TC_DP12[1,1]=-0.5\n";
    let f = write(&d, "S1.MPF", &format!("{head}{SIEMENS}"));
    let nc = d.join("s1.nc").to_string_lossy().into_owned();
    let (code, o, err) = nctrans(&[&f, "--to", "fanuc", "-o", &nc]);
    assert_eq!(code, 0, "{o}{err}");
    assert!(err.contains("equivalent") || o.contains("equivalent"), "{o}{err}");
    let text = std::fs::read_to_string(&nc).expect("written");
    assert!(text.contains("#100=#5003\n#101=#5023\n"), "{text}");
    // The output with the inputs in FANUC's names, proven by check; planted wrong forms caught.
    let body: String = text.lines().filter(|l| !l.contains("nctrans: set")).map(|l| format!("{l}\n")).collect();
    let fanuc_head = "%\n(nctrans: set #11001=100)\n(nctrans: set #10001=-0.5)\n";
    let body = body.strip_prefix("%\n").unwrap_or(&body).to_string();
    let good = write(&d, "good.nc", &format!("{fanuc_head}{body}"));
    assert_eq!(check(&f, &good).0, 0, "{}", check(&f, &good).1);
    for (name, bad) in [
        ("w1.nc", body.replace("#100=#5003", "#100=#5043")),
        ("w2.nc", body.replace("#101=#5023", "#101=#5023-#11001")),
        ("w3.nc", body.replace("G43 H1", "G44 H1")),
    ] {
        let w = write(&d, name, &format!("{fanuc_head}{bad}"));
        let (code, msg) = check(&f, &w);
        assert_ne!(code, 0, "{name}: {msg}");
        assert!(msg.contains("NC500") || msg.contains("not equivalent"), "{name}: {msg}");
    }
    // Without an edge the tip stays #5043.
    let f = write(&d, "S2.MPF", &SIEMENS.replace("T1 M6 D1", "T1 M6 D0"));
    let (code, o, err) = nctrans(&[&f, "--to", "fanuc"]);
    assert_eq!(code, 0, "{o}{err}");
    assert!(o.contains("#100=#5043\n"), "{o}");
}

/// On a Haas profile the offset tables are not the tool data: `#5043` under G43 is refused
/// by name (NC644) instead of a translation the check could not prove.
#[test]
fn a_haas_current_z_under_g43_is_refused() {
    let d = scratch("haas");
    std::fs::write(d.join("nctrans.toml"), "[fanuc]\nseries = \"haas\"\n").expect("write");
    write(&d, "O1.nc", "O1\nT1 M6\nG0 G90 G54 X0 Y0\nG43 H1 Z50.\n#1=#5043\nG0 X#1\nG49\nM30\n");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_nctrans"))
        .current_dir(&d)
        .args(["O1.nc", "--to", "sinumerik", "-o", "out/"])
        .output()
        .expect("runs");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(err.contains("NC644") && err.contains("Haas"), "{err}");
}
