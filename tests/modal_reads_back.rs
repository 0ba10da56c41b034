//! Siemens `$P_F` and `$P_S` read back on FANUC (issue 20, "positions read back … both
//! ways"): `#4109` and `#4119`, the F and S of the preceding block, with `$P_F` scaled under
//! G70 (Siemens reads mm/min there, FANUC inch/min), proven by `check`; planted wrong reads
//! are caught, and the reads where the two controls may differ stay refused (NC588, NC589,
//! NC376).

mod eval_support;

use eval_support::{nctrans, scratch_dir, write};
use std::path::{Path, PathBuf};

fn scratch(name: &str) -> PathBuf {
    scratch_dir("modal-reads-back-tests", name)
}

/// The FANUC translation of `src` into `d/out/`, and its text.
fn translate(d: &Path, src: &str, file: &str) -> (String, String) {
    let out = d.join("out");
    let (code, _, err) = nctrans(&[src, "--to", "fanuc", "-o", &format!("{}/", out.display())]);
    assert_eq!(code, 0, "{err}");
    let nc = out.join(file);
    let text = std::fs::read_to_string(&nc).expect("translation written");
    (nc.to_string_lossy().into_owned(), text)
}

fn equivalent(src: &str, nc: &str) {
    let (code, out, err) = nctrans(&["check", src, nc]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.starts_with("equivalent"), "{out}");
}

fn diverges(d: &Path, src: &str, text: &str, from: &str, to: &str, what: &str) {
    assert!(text.contains(from), "`{from}` not in:\n{text}");
    let bad = write(d, "BAD.nc", &text.replacen(from, to, 1));
    let (code, out, _) = nctrans(&["check", src, &bad]);
    assert_eq!(code, 1, "{what}: a wrong translation passed: {out}");
    assert!(out.starts_with("diverged"), "{what}: {out}");
}

/// The corpus finishing program saves F and S, slows into the corners and restores both:
/// the reads become `#4109`/`#4119` and the translation is proven; `#4119` read for
/// `#4109` (and the other way round) is caught.
#[test]
fn the_feed_saving_corner_program_translates_and_is_proven() {
    let d = scratch("corner");
    let src = "corpus/in/sinumerik/corner-slowdown-feed-save.mpf";
    let (nc, text) = translate(&d, src, "corner-slowdown-feed-save.nc");
    for line in ["#510=#4109", "#511=#4119", "G01 X70. F[#510*0.5]", "S[#511*0.8]"] {
        assert!(text.contains(line), "`{line}` not in:\n{text}");
    }
    equivalent(src, &nc);
    diverges(&d, src, &text, "#510=#4109", "#510=#4119", "S read for F");
    diverges(&d, src, &text, "#511=#4119", "#511=#4109", "F read for S");
}

/// A corner macro called with the feed in force saves it, cuts slower and restores it.
#[test]
fn a_called_macro_saves_and_restores_the_feed() {
    let d = scratch("macro");
    let src = write(
        &d,
        "MAIN.MPF",
        "G17 G90 G54 G94 G71\nT3 D1 M6\nS2400 M3\nG0 X0 Y0 Z2\nG1 Z-3 F400\nG1 X30 F800\nCORNER_SLOW\nG1 Y20\nM30\n",
    );
    write(&d, "CORNER_SLOW.SPF", "PROC CORNER_SLOW\nR20=$P_F\nG1 X40 F=R20*0.4\nG1 Y10\nF=R20\nRET\n");
    let (nc, text) = translate(&d, &src, "MAIN.NC");
    assert!(text.contains("#520=#4109") && text.contains("F#520"), "{text}");
    equivalent(&src, &nc);
    diverges(&d, &src, &text, "#520=#4109", "#520=#4119", "S read for F in the macro");
}

/// Under G70 Siemens reads `$P_F` in mm/min and FANUC `#4109` in inch/min: the read is
/// scaled (`#4109*25.4`); under G700 both read inch/min. Without the factor it diverges.
#[test]
fn the_feed_read_is_scaled_under_g70_and_not_under_g700() {
    let d = scratch("g70");
    let src = write(
        &d,
        "UNITS.MPF",
        "G70 G90 G17 G94\nT1 M6 D1\nS2000 M3\nG0 X0 Y0 Z0.2\nG1 Z-0.1 F300\nR1=$P_F\nG1 X1 F=R1/2\n\
         IF $P_F<>R1/2 GOTOF BAD\nX2 F=R1\nG700\nR3=$P_F\nX3 F=R3*2\nM30\nBAD:\nM0\nM30\n",
    );
    let (nc, text) = translate(&d, &src, "UNITS.NC");
    for line in ["#501=#4109*25.4", "#1=#4109*25.4", "#503=#4109\n"] {
        assert!(text.contains(line), "`{line}` not in:\n{text}");
    }
    equivalent(&src, &nc);
    diverges(&d, &src, &text, "#501=#4109*25.4", "#501=#4109", "G70 unscaled");
    diverges(&d, &src, &text, "#503=#4109\n", "#503=#4109*25.4\n", "G700 scaled");
}

/// The reads whose value may differ between the controls are refused, each by name.
#[test]
fn reads_where_the_controls_may_differ_stay_refused() {
    let d = scratch("refused");
    write(&d, "SUBX.SPF", "PROC SUBX\nR1=$P_S\nR2=$P_F\nG1 X1 F=R2\nRET\n");
    write(&d, "SUBY.SPF", "PROC SUBY\nG1 X1\nRET\n");
    let tap = "G17 G90 G94\nT15 D1 M6\nG0 X0 Y0 Z30\nCYCLE84(30, 0, 5, -16, , 0, 5, 8, , 0, 400)\nR1=$P_S\nM30\n";
    for (name, text, code, what) in [
        ("A.MPF", "G71 G94\nF100\nR1=$P_F G1 X10 F200\nM30\n", "NC588", "$P_F read in a block that writes F itself"),
        ("B.MPF", "G94 S100 M3\nR1=$P_S S300\nM30\n", "NC589", "$P_S read in a block that writes S itself"),
        ("C.MPF", "G94 S100 M3\nR2=$P_S[1]\nM30\n", "NC589", "$P_S[…] with a spindle number"),
        ("D.MPF", tap, "NC589", "$P_S in a program with CYCLE84"),
        ("E.MPF", "G94 S100 M3\nSUBY\nR1=$P_S\nM30\n", "NC589", "$P_S in a program that calls another"),
        ("F.MPF", "G94 S100 M3 F100\nSUBX\nM30\n", "NC589", "$P_S in a called program"),
        (
            "G.MPF",
            "G94\nF100\nIF R9==1 GOTOF LA\nG70\nLA:\nR1=$P_F\nM30\n",
            "NC376",
            "$P_F where the units (G70/G71/G700/G710) depend on the path taken",
        ),
    ] {
        let f = write(&d, name, text);
        let (rc, _, err) =
            nctrans(&[&f, "--to", "fanuc", "-o", &format!("{}/", d.join(name).with_extension("out").display())]);
        assert_ne!(rc, 0, "{name} translated");
        assert!(err.contains(code) && err.contains(what), "{name}: {err}");
        // Refused once, by this rule (not again as an unknown system variable).
        assert!(!err.contains("NC342"), "{name}: {err}");
    }
    // The $P_F read of the called program itself is fine: only its $P_S is refused.
    let f = d.join("F.MPF").to_string_lossy().into_owned();
    let (_, _, err) = nctrans(&[&f, "--to", "fanuc", "-o", &format!("{}/", d.join("F2.out").display())]);
    assert_eq!(err.matches("error[NC").count(), 1, "{err}");
}

/// A cycle's `FFR=RFF=$P_F` is the feed in force, which the cycle's translation keeps as
/// FANUC's modal F: under G70 it takes no factor (it would no longer be `$P_F`, NC392).
#[test]
fn a_cycle_feed_of_p_f_under_g70_stays_the_feed_in_force() {
    let d = scratch("cycle85");
    let src = write(
        &d,
        "BORE.MPF",
        "G70 G90 G17 G94\nT1 M6 D1\nS800 M3\nG0 X0 Y0 Z1\nF20\nCYCLE85(1,0,0.1,-1,,0,$P_F,$P_F)\nG0 Z2\nM30\n",
    );
    let (nc, text) = translate(&d, &src, "BORE.NC");
    assert!(text.contains("G98 G85 Z-1. R0.1\n") && !text.contains("4109"), "{text}");
    equivalent(&src, &nc);
}
