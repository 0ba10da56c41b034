//! Sinumerik → FANUC: a subprogram's modal call `MCALL NAME(args)` … `MCALL` is FANUC's
//! `G66 P… A…` … `G67` (both call the program after every later block that moves, with the
//! values the arguments had at the call), the mirror of FANUC → Sinumerik's G66. A program
//! whose later calls would change what the caller's following blocks see (modes, tool,
//! frames, R parameters), a second modal call over the first, a drilling cycle's MCALL under
//! it and an `MCALL` cancel away from its MCALL stay refused (NC318).

mod eval_support;

use eval_support::{nctrans, scratch_dir, write};

const MAIN: &str = "; SPOT FACE EACH HOLE WITH A MODAL SUBPROGRAM\nG17 G90 G54 G71\nT1 D1 M6\nS1500 M3 F100\n\
G0 X0 Y0 Z20\nMCALL SPOTF(2.5, 0.3)\nG0 X10 Y10\nG0 X30 Y10\nG0 X30 Y40\nMCALL\nG0 Z100 M5\nM30\n";
const SPOTF: &str = "PROC SPOTF(REAL DEPTH, REAL DWELL)\nG1 Z=-DEPTH F100\nG4 F=DWELL\nG0 Z2\nRET\n";

#[test]
fn a_modal_subprogram_call_is_g66_and_g67() {
    let d = scratch_dir("modal-call-to-fanuc", "plain");
    write(&d, "SPOTF.SPF", SPOTF);
    let src = write(&d, "MAINMC.MPF", MAIN);
    let (code, out, err) = nctrans(&["--to", "fanuc", &src]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent ("), "{err}");
    let lines: Vec<&str> = out.lines().collect();
    let on = lines.iter().position(|l| *l == "G66 P9000 A2.5 B0.3").expect("G66");
    let off = lines.iter().position(|l| *l == "G67").expect("G67");
    assert!(on < off && lines[on + 1..off].iter().all(|l| l.starts_with("G00 X")), "{out}");
    // Three holes, each spot-faced.
    let nc = write(&d, "main.nc", &out);
    let (code, trace, err) = nctrans(&["run", &nc]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(trace.matches("dwell 0.3").count(), 3, "{trace}");
    // A planted wrong depth is caught.
    let bad = write(&d, "bad.nc", &out.replacen("G66 P9000 A2.5", "G66 P9000 A3.5", 1));
    let (code, verdict, _) = nctrans(&["check", &src, &bad]);
    assert_ne!(code, 0, "{verdict}");
    assert!(verdict.contains("diverged"), "{verdict}");
}

#[test]
fn modal_calls_that_are_not_exact_are_refused() {
    let d = scratch_dir("modal-call-to-fanuc", "refused");
    write(&d, "SPOTF.SPF", SPOTF);
    write(&d, "INCR.SPF", "PROC INCR(REAL DEPTH)\nG91 G1 Z=-DEPTH F100\nG0 Z=DEPTH\nRET\n");
    write(&d, "SETR.SPF", "PROC SETR(REAL DEPTH)\nR5=DEPTH\nG1 Z=-DEPTH F100\nG0 Z2\nRET\n");
    let cases = [
        ("modes", MAIN.replace("SPOTF(2.5, 0.3)", "INCR(2)"), "modes (G90/G91"),
        ("rparams", MAIN.replace("SPOTF(2.5, 0.3)", "SETR(2)"), "R parameters"),
        ("nested", MAIN.replace("G0 X30 Y10\n", "MCALL SPOTF(1, 0.1)\nG0 X30 Y10\n"), "another modal call"),
        ("cycle", MAIN.replace("G0 X30 Y10\n", "MCALL CYCLE81(20,0,2,-5)\nG0 X30 Y10\n"), "a drilling cycle's MCALL"),
        ("elsewhere", MAIN.replace("MCALL\nG0 Z100", "IF R1==0\nMCALL\nENDIF\nG0 Z100"), "MCALL cancel"),
    ];
    for (name, text, what) in cases {
        let src = write(&d, &format!("{}.MPF", name.to_uppercase()), &text);
        let (code, _, err) = nctrans(&["--to", "fanuc", &src]);
        assert_ne!(code, 0, "{name}: {err}");
        assert!(err.contains("NC318") && err.contains(what), "{name}: {err}");
    }
}
