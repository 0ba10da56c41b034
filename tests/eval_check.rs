//! `nctrans check A B` end to end: a FANUC program and its Siemens equivalent agree; a
//! deliberately altered copy diverges at the right event with a label in each file and a
//! diff; a step limit is inconclusive; `nctrans run` writes the spec's jsonl.

mod eval_support;

use eval_support::{nctrans, root};

const FANUC: &str = "%\nO100\n#1=0\nG90 G0 X0 Y0\nWHILE[#1 LT 5]DO1\n#1=#1+1\nG1 X[#1*2.] F200.\nEND1\nM30\n%\n";
const SIEMENS: &str = "R1=0\nG90 G0 X0 Y0\nWHILE R1<5\nR1=R1+1\nG1 X=R1*2 F200\nENDWHILE\nM30\n";
/// The same program with the fourth iteration moving 0.5 mm too far.
const ALTERED: &str =
    "R1=0\nG90 G0 X0 Y0\nWHILE R1<5\nR1=R1+1\nIF R1==4\nG1 X=R1*2+0.5 F200\nELSE\nG1 X=R1*2 F200\nENDIF\nENDWHILE\nM30\n";

fn write(name: &str, text: &str) -> String {
    let dir = root().join("target/eval-tests");
    std::fs::create_dir_all(&dir).expect("scratch dir");
    let p = dir.join(name);
    std::fs::write(&p, text).expect("write");
    p.to_string_lossy().to_string()
}

#[test]
fn equal_programs_are_equivalent() {
    let a = write("check-a.nc", FANUC);
    let b = write("check-b.mpf", SIEMENS);
    let (code, out, err) = nctrans(&["check", &a, &b]);
    assert_eq!(code, 0, "{out}\n{err}");
    assert_eq!(out, "equivalent (7 trace events agree)\n");
}

#[test]
fn altered_program_diverges_at_the_fourth_move() {
    let a = write("check-a2.nc", FANUC);
    let b = write("check-altered.mpf", ALTERED);
    let (code, out, err) = nctrans(&["check", &a, &b]);
    assert_eq!(code, 1, "{out}\n{err}");
    // Events: rapid, then moves X2 X4 X6 X8: the fifth event differs.
    assert!(out.starts_with("diverged at trace event 5\n"), "{out}");
    assert!(out.contains("-move linear X=8 Y=0 f=200\n+move linear X=8.5 Y=0 f=200\n"), "{out}");
    assert!(err.contains("error[NC500]"), "{err}");
    // A label in each file: the FANUC G1 block (line 7) and the altered Siemens block (line 6).
    assert!(err.contains("check-a2.nc:7:1"), "{err}");
    assert!(err.contains("check-altered.mpf:6:1"), "{err}");
}

#[test]
fn a_step_limit_is_inconclusive() {
    let a = write("check-a3.nc", FANUC);
    let b = write("check-b3.mpf", SIEMENS);
    let (code, out, _) = nctrans(&["check", &a, &b, "--max-steps", "6"]);
    assert_eq!(code, 4);
    assert!(out.starts_with("inconclusive"), "{out}");
}

#[test]
fn run_writes_jsonl_and_takes_inputs() {
    // The header comment line is a block too: 3 steps.
    let b = write("run-set.mpf", "; nctrans: set R1=2\nG0 X=R1 Y=R2\nM30\n");
    let (code, out, _) = nctrans(&["run", &b, "--format", "jsonl", "--set", "R2=-1.5"]);
    assert_eq!(code, 0);
    assert_eq!(
        out,
        "{\"ev\":\"move\",\"mode\":\"rapid\",\"to\":{\"X\":2,\"Y\":-1.5},\"f\":null,\"line\":2}\n\
         {\"ev\":\"end\",\"code\":\"M30\",\"steps\":3,\"line\":3}\n"
    );
}

/// Issue 17 item 6 / issue 19: the trace compares compensation (`comp` events), so Siemens
/// `T6 D1` (cutting edge 1 of tool 6) against FANUC `T6 D1` without `G43 H6` diverges, as
/// does G41 against G42; G44, whose direction the event does not hold, is never called
/// equivalent: `check` says compensation was not compared, exit 4.
#[test]
fn compensation_is_compared_and_g44_is_inconclusive() {
    let a = write("comp-a.mpf", "T6 M6 D1\nG0 X0 Y0 Z50\nG1 Z-2 F200\nM30\n");
    let b = write("comp-b.nc", "%\nO1\nT6 D1 M06\nG00 X0 Y0 Z50.\nG01 Z-2. F200.\nM30\n%\n");
    let (code, out, _) = nctrans(&["check", &a, &b]);
    assert_eq!(code, 1, "{out}");
    assert!(out.contains("comp length=\"6.1\""), "{out}");
    let right = write("comp-b2.nc", "%\nO1\nT6 M06\nG43 H6\nG00 X0 Y0 Z50.\nG01 Z-2. F200.\nM30\n%\n");
    let (code, out, _) = nctrans(&["check", &a, &right]);
    assert_eq!(code, 0, "{out}");
    let c = write("comp-c.nc", "%\nO1\nG00 X0 Y0\nG41 D04 X10. Y5.\nG01 X20. F100.\nG40 X0 Y0\nM30\n%\n");
    let d = write("comp-d.nc", "%\nO1\nG00 X0 Y0\nG42 D04 X10. Y5.\nG01 X20. F100.\nG40 X0 Y0\nM30\n%\n");
    let (code, out, _) = nctrans(&["check", &c, &d]);
    assert_eq!(code, 1, "{out}");
    let e = write("comp-e.nc", "%\nO1\nT1 M06\nG44 H1 Z50.\nM30\n%\n");
    let (code, out, err) = nctrans(&["check", &e, &e]);
    assert_eq!(code, 4, "{out}\n{err}");
    assert!(out.starts_with("inconclusive:") && out.contains("tool compensation"), "{out}");
    assert!(err.contains("warning[NC387]"), "{err}");
}

/// Issue 17 item 6 on the streamed paths: past the first chunks the straight-line
/// translators write blocks without the passes; a program with compensation far down a CAM
/// program is translated whole, so it is translated as without --stream (the same bytes),
/// and a register that cannot be proven is refused, both ways.
#[test]
fn compensation_far_down_a_streamed_program_is_translated_whole() {
    let mut fanuc = String::from("%\nO1\nG00 X0 Y0\nG01 F100.\n");
    let mut siemens = String::from("G0 X0 Y0\nG1 F100\n");
    for i in 0..6000 {
        fanuc.push_str(&format!("X{}.{}\n", i % 50, i % 7));
        siemens.push_str(&format!("X{}.{}\n", i % 50, i % 7));
    }
    let (bad_f, bad_s) = (
        format!("{fanuc}G41 D04 X10. Y5.\nX20.\nG40 X0 Y0\nM30\n%\n"),
        format!("{siemens}G41 D4 X10 Y5\nX20\nG40 X0 Y0\nM30\n"),
    );
    let f = write("comp-stream.nc", &bad_f);
    let s = write("comp-stream.mpf", &bad_s);
    for (input, to, code) in [(&f, "sinumerik", "NC472"), (&s, "fanuc", "NC470")] {
        let (exit, out, err) = nctrans(&["--to", to, "--stream", "--no-verify", input]);
        assert_eq!(exit, 1, "{input}: {out}\n{err}");
        assert!(err.contains(&format!("error[{code}]")), "{input}: {err}");
        assert!(!out.contains("G41"), "{input}: {out}");
    }
    let good_f = format!("{fanuc}T4 M06\nG43 H4 Z5.\nG41 D04 X10. Y5.\nX20.\nG40 X0 Y0\nG49\nM30\n%\n");
    let good_s = format!("{siemens}T4 M6 D1\nZ5\nG41 X10 Y5\nX20\nG40 X0 Y0\nD0\nM30\n");
    for (name, text, to) in [("comp-ok.nc", &good_f, "sinumerik"), ("comp-ok.mpf", &good_s, "fanuc")] {
        let input = write(name, text);
        let (exit, streamed, err) = nctrans(&["--to", to, "--stream", &input]);
        assert_eq!(exit, 0, "{input}: {err}");
        let (exit, whole, err) = nctrans(&["--to", to, &input]);
        assert_eq!(exit, 0, "{input}: {err}");
        assert_eq!(streamed, whole, "{input}");
        assert!(whole.contains("G41"), "{whole}");
    }
}

/// Issue 17 item 7 on the streamed paths: under `--unsupported warn` a multi-step skip move
/// (G31 P, no Sinumerik form) far down a streamed CAM program becomes one marked comment as a
/// whole, and the file alarms first.
#[test]
fn warn_far_down_a_streamed_program_marks_the_whole_block() {
    let mut fanuc = String::from("%\nO1\nG00 X0 Y0 Z5.\nG01 F100.\n");
    let mut siemens = String::from("G0 X0 Y0 Z5\nG1 F100\n");
    for i in 0..6000 {
        fanuc.push_str(&format!("X{}.{}\n", i % 50, i % 7));
        siemens.push_str(&format!("X{}.{}\n", i % 50, i % 7));
    }
    fanuc.push_str("G31 P2 X77. Y77. F150.\nG00 Z50.\nM30\n%\n");
    siemens.push_str("ROT Z=45 X77\nG0 Z50\nM30\n");
    let f = write("warn-stream.nc", &fanuc);
    let s = write("warn-stream.mpf", &siemens);
    for (input, to, alarm) in [(&f, "sinumerik", "SETAL(65999)"), (&s, "fanuc", "#3000=999")] {
        let (code, out, err) = nctrans(&["--to", to, "--stream", "--unsupported", "warn", input]);
        assert_eq!(code, 1, "{input}: {err}");
        assert!(!out.contains("X77"), "{input}: the marked block's words survived");
        assert!(out.lines().take(4).any(|l| l.starts_with(alarm)), "{input}: {}", &out[..200.min(out.len())]);
        assert!(out.contains("NCTRANS UNSUPPORTED"), "{input}");
        assert!(err.contains("not verified"), "{input}: {err}");
    }
}

#[test]
fn corner_rounding_and_chamfers_run_and_contour_words_are_refused_not_ignored() {
    // A rounded corner is not the sharp one: the two programs differ at the corner.
    let round = "G17 G90 G0 X0 Y0\nG1 X100 RND=5 F300\nY80\nM30\n";
    let sharp = "G17 G90 G0 X0 Y0\nG1 X100 F300\nY80\nM30\n";
    let (a, b) = (write("rnd-a.mpf", round), write("rnd-b.mpf", sharp));
    let (code, out, err) = nctrans(&["check", &a, &b]);
    assert_ne!(code, 0, "{out}\n{err}");
    assert!(!out.contains("equivalent") && err.contains("NC500"), "{out}\n{err}");
    for word in ["CHF=2", "CHR=2", "RNDM=3"] {
        let p = write("rnd-c.mpf", &format!("G17 G90 G0 X0 Y0\nG1 X100 {word} F300\nY80 RNDM=0\nM30\n"));
        let (code, _, err) = nctrans(&["run", &p]);
        assert_eq!(code, 0, "{word}: {err}");
    }
    for word in ["ANG=30", "OFFN=0.5"] {
        let p = write("rnd-c.mpf", &format!("G17 G90 G0 X0 Y0\nG1 X100 {word} F300\nY80\nM30\n"));
        let (code, _, err) = nctrans(&["run", &p]);
        assert_ne!(code, 0, "{word}: {err}");
        assert!(err.contains("NC403"), "{word}: {err}");
    }
    // Off is off: RNDM=0 and OFFN=0 change nothing.
    let p = write("rnd-d.mpf", "G17 G90 G0 X0 Y0\nRNDM=0 OFFN=0\nG1 X100 F300\nM30\n");
    let (code, _, err) = nctrans(&["run", &p]);
    assert_eq!(code, 0, "{err}");
}
