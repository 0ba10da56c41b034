//! FANUC drilling cycles with incremental data (G91) → Sinumerik: R counts from the initial
//! level and Z from the R plane (FANUC), the Sinumerik cycle takes them absolute, so RFP and
//! DP become expressions of the level the tool stands at the MCALL (`$P_EP[Z]`); the hole
//! positions stay incremental moves. Where the tool no longer stands at the initial level (a
//! G98 hole or new G91 R after a G99 hole), the level is kept in `NCTRANS_CYC_Z` where the
//! cycle began. Every translation is verified and a planted wrong depth, R plane or return
//! level is caught.

mod eval_support;

use eval_support::{nctrans, scratch_file};

fn scratch(ext: &str, text: &str) -> String {
    scratch_file("tinc", ext, text)
}

fn fanuc(body: &str) -> String {
    format!("%\nO1\nG21 G17 G90 G94\nG54 G0 X0 Y0\nT1 M6\nS1000 M3\nG0 Z50.\n{body}M30\n%\n")
}

/// The verified translation: (source path, output path, output text).
fn translate(body: &str) -> (String, String, String) {
    let src = scratch("nc", &fanuc(body));
    let out = scratch("mpf", "");
    let (code, _, err) = nctrans(&[&src, "--to", "sinumerik", "-o", &out, "--force"]);
    assert_eq!(code, 0, "{body}\n{err}");
    assert!(err.contains("equivalent"), "{err}");
    let text = std::fs::read_to_string(&out).expect("translation");
    (src, out, text)
}

#[test]
fn g91_r_and_z_become_absolute_parameters_from_the_initial_level() {
    let (src, _, t) = translate("G91 G98 G81 X10. Y10. Z-7. R-48. F100.\nX15. K3\nG90 G80\n");
    assert!(t.contains("MCALL CYCLE81($P_EP[Z],$P_EP[Z]-48,0,$P_EP[Z]-48-7)\n"), "{t}");
    // The holes stay incremental moves, a repeat moves again.
    assert!(t.contains("G0 G91 X10 Y10\nG0 X15\nG0 X15\nG0 X15\nMCALL\nG90\n"), "{t}");
    for (what, from, to) in [("depth", "-48-7)", "-48-8)"), ("R plane", "$P_EP[Z]-48,0", "$P_EP[Z]-47,0")] {
        let bad = scratch("mpf", &t.replacen(from, to, 1));
        assert_ne!(nctrans(&["check", &src, &bad]).0, 0, "a wrong {what} was not caught");
    }
    // G99: the retraction plane is the R plane.
    let (_, _, t) = translate("G91 G99 G83 X10. Y10. Z-20. R-49. Q4. F100.\nX10.\nG90 G80\n");
    assert!(t.contains("MCALL CYCLE83($P_EP[Z]-49,$P_EP[Z]-49,0,$P_EP[Z]-49-20,,,4,0,0,0,1,1)\n"), "{t}");
}

#[test]
fn an_incremental_depth_after_an_absolute_r_counts_from_r() {
    let (_, _, t) = translate("G99 G81 X10. Y10. Z-5. R2. F100.\nG91 X10. Z-3.\nG90 G80\n");
    assert!(t.contains("MCALL CYCLE81(2,2,0,2-3)\n"), "{t}");
}

#[test]
fn new_incremental_r_after_a_g99_hole_counts_from_the_kept_initial_level() {
    let (src, _, t) = translate("G91 G99 G81 X10. Y10. Z-7. R-48. F100.\nX10. R-45.\nG90 G80\n");
    assert!(t.contains("NCTRANS_CYC_Z=$P_EP[Z]\nF100\nMCALL CYCLE81($P_EP[Z]-48,"), "{t}");
    assert!(t.contains("MCALL CYCLE81(NCTRANS_CYC_Z-45,NCTRANS_CYC_Z-45,0,NCTRANS_CYC_Z-45-7)\n"), "{t}");
    let bad = scratch("mpf", &t.replacen("NCTRANS_CYC_Z-45,NCTRANS_CYC_Z-45", "NCTRANS_CYC_Z-44,NCTRANS_CYC_Z-44", 1));
    assert_ne!(nctrans(&["check", &src, &bad]).0, 0, "a wrong R plane was not caught");
}

#[test]
fn a_g98_hole_after_g99_holes_returns_to_the_initial_level_where_the_cycle_began() {
    // The usual clamp-clearing pattern: G99 between holes, G98 on the last one.
    let body = "G99 G81 X10. Y10. Z-12. R2. F120.\nX30.\nG98 X50.\nG99 Y30.\nG80\n";
    let (src, _, t) = translate(body);
    assert!(t.contains("NCTRANS_CYC_Z=$P_EP[Z]\nF120\nMCALL CYCLE81(2,2,0,-12)\n"), "{t}");
    assert!(
        t.contains("G0 X30\nMCALL CYCLE81(NCTRANS_CYC_Z,2,0,-12)\nG0 X50\nMCALL CYCLE81(2,2,0,-12)\nG0 Y30\n"),
        "{t}"
    );
    assert!(t.contains("DEF REAL NCTRANS_CYC_Z\n"), "{t}");
    // Returning to R instead, or saving the level after the first hole, is caught.
    for (what, from, to) in [
        ("return level", "MCALL CYCLE81(NCTRANS_CYC_Z,", "MCALL CYCLE81(2,"),
        (
            "saved level",
            "NCTRANS_CYC_Z=$P_EP[Z]\nF120\nMCALL CYCLE81(2,2,0,-12)\nG0 X10 Y10\n",
            "F120\nMCALL CYCLE81(2,2,0,-12)\nG0 X10 Y10\nNCTRANS_CYC_Z=$P_EP[Z]\n",
        ),
    ] {
        let planted = t.replacen(from, to, 1);
        assert_ne!(planted, t, "{what}");
        let bad = scratch("mpf", &planted);
        assert_ne!(nctrans(&["check", &src, &bad]).0, 0, "a wrong {what} was not caught");
    }
}
