//! Chamfers and roundings under a frame that mirrors or scales (issue 20). A mirror (FANUC
//! G51.1, G51 with factors ±1; Siemens MIRROR/AMIRROR) keeps lengths and angles: the corner
//! is the mirror image of the programmed one, its rounding turning the other way, and both
//! runs make it, so translations prove equivalent and wrong ones are caught. Under scaling no
//! source read says whether the corner's size is scaled with the contour: the corner stays
//! refused (NC574) with a message that says so.

mod eval_support;

use eval_support::{nctrans, scratch_dir, write};

/// The programmed contour: from X0 Y0 to X15 Y5, down to a chamfer of 1.5 at X15 Y-5, along
/// to X-15, up to a rounding of radius 2 at X-15 Y5, and back to X15. `{ON}`/`{OFF}` are the
/// frame's blocks.
const FAN: &str = "%\nO1000\nG17 G90 G54 G21\nT4 M06\nG43 H4 Z50.\nS3000 M03\n{ON}\nG00 X0. Y0. Z5.\n\
G01 Z-2. F150.\nG01 X15. Y5. F600.\nG01 Y-5. ,C1.5\nG01 X-15.\nG01 Y5. ,R2.\nG01 X15.\nG00 Z50.\n{OFF}\nM30\n%\n";

const SIE: &str = "G17 G90 G54 G71\nT4 M6\nD1\nS3000 M3\n{ON}\nG0 X0 Y0 Z5\nG1 Z-2 F150\nG1 X15 Y5 F600\n\
G1 Y-5 CHR=1.5\nG1 X-15\nG1 Y5 RND=2\nG1 X15\nG0 Z50\n{OFF}\nM30\n";

fn fanuc(on: &str, off: &str) -> String {
    FAN.replace("{ON}", on).replace("{OFF}", off)
}

fn siemens(on: &str, off: &str) -> String {
    SIE.replace("{ON}", on).replace("{OFF}", off)
}

/// A mirror, its FANUC and Siemens spellings, and what the run must show: the chamfer's two
/// ends and the rounding arc (its direction, end and centre).
struct Mirror {
    name: &'static str,
    fanuc: (&'static str, &'static str),
    siemens: (&'static str, &'static str),
    chamfer: [&'static str; 2],
    arc: &'static str,
}

const MIRRORS: &[Mirror] = &[
    // Unmirrored the chamfer runs X15 Y-3.5 → X13.5 Y-5 and the rounding is `arc cw` to
    // X-13 Y5 about X-13 Y3.
    Mirror {
        name: "x",
        fanuc: ("G51.1 X0.", "G50.1 X0."),
        siemens: ("MIRROR X0", "MIRROR"),
        chamfer: ["X=-15 Y=-3.5", "X=-13.5 Y=-5"],
        arc: "arc ccw XY X=13 Y=5 Z=-2 center X=13 Y=3 f=600",
    },
    Mirror {
        name: "y",
        fanuc: ("G51.1 Y0.", "G50.1 Y0."),
        siemens: ("AMIRROR Y0", "MIRROR"),
        chamfer: ["X=15 Y=3.5", "X=13.5 Y=5"],
        arc: "arc ccw XY X=-13 Y=-5 Z=-2 center X=-13 Y=-3 f=600",
    },
    // Both axes: a half turn, which keeps the turning sense.
    Mirror {
        name: "xy",
        fanuc: ("G51.1 X0. Y0.", "G50.1 X0. Y0."),
        siemens: ("MIRROR X0 Y0", "MIRROR"),
        chamfer: ["X=-15 Y=3.5", "X=-13.5 Y=5"],
        arc: "arc cw XY X=13 Y=-5 Z=-2 center X=13 Y=-3 f=600",
    },
    // FANUC scaling of each axis with -1 is a mirror image too.
    Mirror {
        name: "g51-negative",
        fanuc: ("G51 X0. Y0. I-1000 J1000", "G50"),
        siemens: ("AMIRROR X0", "MIRROR"),
        chamfer: ["X=-15 Y=-3.5", "X=-13.5 Y=-5"],
        arc: "arc ccw XY X=13 Y=5 Z=-2 center X=13 Y=3 f=600",
    },
];

#[test]
fn mirrored_corners_run_as_the_mirror_image_of_the_programmed_ones() {
    let d = scratch_dir("corners-scaled", "run");
    for m in MIRRORS {
        let fan = write(&d, &format!("O_{}.nc", m.name), &fanuc(m.fanuc.0, m.fanuc.1));
        let sie = write(&d, &format!("M_{}.MPF", m.name), &siemens(m.siemens.0, m.siemens.1));
        for src in [&fan, &sie] {
            let (code, trace, err) = nctrans(&["run", src]);
            assert_eq!(code, 0, "{src}: {err}");
            for p in m.chamfer {
                assert!(trace.contains(&format!("move linear {p} Z=-2 f=600")), "{src}: chamfer end {p}:\n{trace}");
            }
            assert!(trace.contains(m.arc), "{src}: {}:\n{trace}", m.arc);
        }
    }
}

#[test]
fn mirrored_corners_translate_both_ways_and_prove_equivalent() {
    let d = scratch_dir("corners-scaled", "pairs");
    for m in MIRRORS {
        let fan = write(&d, &format!("O_{}.nc", m.name), &fanuc(m.fanuc.0, m.fanuc.1));
        let sie = write(&d, &format!("M_{}.MPF", m.name), &siemens(m.siemens.0, m.siemens.1));
        let (code, out, err) = nctrans(&["--to", "fanuc", &sie]);
        assert_eq!(code, 0, "{sie}: {err}");
        assert!(err.contains("equivalent"), "{sie}: {err}");
        assert!(out.contains("G51.1") && out.contains(",C1.5") && out.contains(",R2."), "{sie}:\n{out}");
        let (code, out, err) = nctrans(&["--to", "sinumerik", &fan]);
        assert_eq!(code, 0, "{fan}: {err}");
        assert!(err.contains("equivalent"), "{fan}: {err}");
        assert!(out.contains("CHR=1.5") && out.contains("RND=2"), "{fan}:\n{out}");
    }
}

/// The mirrored rounding is the arc a programmer would write for the mirrored part: the same
/// radius, turning the other way. Written with the unmirrored direction (its centre on the
/// other side of the chord, the corner on the wrong side), it is caught.
#[test]
fn the_mirrored_rounding_is_the_explicit_arc_turned_the_other_way() {
    let d = scratch_dir("corners-scaled", "explicit");
    let body = "G00 X0. Y0. Z5.\nG01 Z-2. F150.\nG01 X-15. Y5. F600.\nG01 Y-3.5\nG01 X-13.5 Y-5.\nG01 X15.\nG01 Y3.\n\
G03 X13. Y5. R2.\nG01 X-15.\nG00 Z50.\n";
    let explicit = format!("%\nO1000\nG17 G90 G54 G21\nT4 M06\nG43 H4 Z50.\nS3000 M03\n{body}M30\n%\n");
    let sie_body = "G0 X0 Y0 Z5\nG1 Z-2 F150\nG1 X-15 Y5 F600\nG1 Y-3.5\nG1 X-13.5 Y-5\nG1 X15\nG1 Y3\n\
G3 X13 Y5 CR=2\nG1 X-15\nG0 Z50\n";
    let sie_explicit = format!("G17 G90 G54 G71\nT4 M6\nD1\nS3000 M3\n{sie_body}M30\n");
    let pairs = [
        (
            fanuc("G51.1 X0.", "G50.1 X0."),
            "MIRRORED.nc",
            explicit.clone(),
            explicit.replace("G03 X13.", "G02 X13."),
            "nc",
        ),
        (
            siemens("MIRROR X0", "MIRROR"),
            "MIRRORED.MPF",
            sie_explicit.clone(),
            sie_explicit.replace("G3 X13", "G2 X13"),
            "MPF",
        ),
    ];
    for (mirrored, name, good, wrong, ext) in pairs {
        assert_ne!(good, wrong);
        let src = write(&d, name, &mirrored);
        let good = write(&d, &format!("EXPLICIT.{ext}"), &good);
        let wrong = write(&d, &format!("WRONG_SIDE.{ext}"), &wrong);
        let (code, verdict, err) = nctrans(&["check", &src, &good]);
        assert_eq!(code, 0, "{src}: {verdict}{err}");
        let (code, verdict, err) = nctrans(&["check", &src, &wrong]);
        assert_ne!(code, 0, "{src}: {verdict}{err}");
        assert!(format!("{verdict}{err}").contains("diverge"), "{verdict}{err}");
    }
}

fn assert_caught(d: &std::path::Path, src: &str, planted: &str, name: &str) {
    let bad = write(d, name, planted);
    let (code, verdict, err) = nctrans(&["check", src, &bad]);
    assert_ne!(code, 0, "planted {name} passed:\n{planted}\n{verdict}{err}");
    assert!(format!("{verdict}{err}").contains("diverge"), "{verdict}{err}");
}

#[test]
fn planted_wrong_translations_under_a_mirror_are_caught() {
    let d = scratch_dir("corners-scaled", "planted");
    // Siemens → FANUC.
    let sie = write(&d, "MIRRORED.MPF", &siemens("MIRROR X0", "MIRROR"));
    let (code, out, err) = nctrans(&["--to", "fanuc", &sie]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("G51.1 X0.") && out.contains("G01 Y-5. ,C1.5") && out.contains(",R2."), "{out}");
    let planted = [
        // The size a scaled frame would give (factor 2), or the corner left out.
        out.replace(",R2.", ",R4."),
        out.replace(",C1.5", ",C3."),
        out.replace(",R2.", ""),
        // The chamfer at the next corner of the contour.
        out.replace("G01 Y-5. ,C1.5", "G01 Y-5.").replace("G01 X-15.", "G01 X-15. ,C1.5"),
        // The corners on the wrong side: mirrored in Y, or not mirrored at all.
        out.replace("G51.1 X0.", "G51.1 Y0."),
        out.replace("G51.1 X0.", ""),
    ];
    for (i, p) in planted.iter().enumerate() {
        assert_ne!(p, &out, "planting {i} changed nothing");
        assert_caught(&d, &sie, p, &format!("BAD{i}.nc"));
    }
    // FANUC → Siemens.
    let fan = write(&d, "MIRRORED.nc", &fanuc("G51.1 Y0.", "G50.1 Y0."));
    let (code, out, err) = nctrans(&["--to", "sinumerik", &fan]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("MIRROR Y0") && out.contains("RND=2") && out.contains("CHR=1.5"), "{out}");
    let planted = [
        out.replace("RND=2", "RND=1"),
        out.replace("CHR=1.5", "CHR=0.75"),
        out.replace("MIRROR Y0", "MIRROR X0"),
        out.replace("RND=2", "CHR=2"),
    ];
    for (i, p) in planted.iter().enumerate() {
        assert_ne!(p, &out, "planting {i} changed nothing");
        assert_caught(&d, &fan, p, &format!("BAD{i}.MPF"));
    }
}

/// A scale of the third axis alone leaves the plane of the corner as it is: whether the
/// corner's size scales with the plane or not, it is the same corner, made at the scaled depth.
#[test]
fn a_scale_of_the_depth_alone_leaves_the_corner_as_it_is() {
    let d = scratch_dir("corners-scaled", "depth");
    let fan = write(&d, "DEPTH.nc", &fanuc("G51 X0. Y0. Z0. I1000 J1000 K2000", "G50"));
    let sie = write(&d, "DEPTH.MPF", &siemens("SCALE Z2", "SCALE"));
    for (src, to) in [(&fan, "sinumerik"), (&sie, "fanuc")] {
        let (code, trace, err) = nctrans(&["run", src]);
        assert_eq!(code, 0, "{src}: {err}");
        assert!(trace.contains("arc cw XY X=-13 Y=5 Z=-4 center X=-13 Y=3 f=600"), "{src}:\n{trace}");
        let (code, _, err) = nctrans(&["--to", to, src]);
        assert_eq!(code, 0, "{src}: {err}");
        assert!(err.contains("equivalent"), "{src}: {err}");
    }
}

/// Scaling: uniform, unequal in the plane, and a mirror with a factor. Each run and each
/// translation stops at the corner with NC574, the message saying what is not known (a
/// mirror combined with a scale stops the translation earlier, at the frame: NC498, NC497).
#[test]
fn corners_under_scaling_stay_refused_and_say_what_is_unknown() {
    let d = scratch_dir("corners-scaled", "refused");
    let uniform = "whether the control scales its size with the contour or keeps it in workpiece units is not stated";
    let unequal = "the factors differ in the plane";
    let cases = [
        ("S_SCALE.MPF", siemens("SCALE X2 Y2", "SCALE"), uniform),
        ("S_ASCALE.MPF", siemens("TRANS X10\nASCALE X0.5 Y0.5", "TRANS"), uniform),
        ("S_UNEQUAL.MPF", siemens("SCALE X2 Y1", "SCALE"), unequal),
        ("S_MIRROR_SCALE.MPF", siemens("MIRROR X0\nASCALE X2 Y2", "MIRROR"), uniform),
        ("F_P.nc", fanuc("G51 X0. Y0. P2000", "G50"), uniform),
        ("F_IJ_EQUAL.nc", fanuc("G51 X0. Y0. I1500 J1500", "G50"), uniform),
        ("F_IJ.nc", fanuc("G51 X0. Y0. I2000 J1000", "G50"), unequal),
        ("F_MIRROR_SCALE.nc", fanuc("G51 X0. Y0. I-2000 J2000", "G50"), uniform),
        ("F_G511_AND_SCALE.nc", fanuc("G51.1 X0.\nG51 X0. Y0. P500", "G50\nG50.1 X0."), uniform),
    ];
    for (name, text, why) in &cases {
        let src = write(&d, name, text);
        let (code, _, err) = nctrans(&["run", &src]);
        assert_ne!(code, 0, "{name}: {err}");
        assert!(err.contains("error[NC574]") && err.contains("under a frame that scales"), "{name}: {err}");
        assert!(err.contains(why), "{name}: {err}");
        let to = if name.ends_with(".nc") { "sinumerik" } else { "fanuc" };
        let (code, _, err) = nctrans(&["--to", to, &src]);
        assert_ne!(code, 0, "{name}: {err}");
        let want = match *name {
            "S_MIRROR_SCALE.MPF" => "error[NC498]",
            "F_G511_AND_SCALE.nc" => "error[NC497]",
            _ => "error[NC574]",
        };
        assert!(err.contains(want), "{name}: {err}");
    }
}

/// The corpus pair of pockets, the left one mirrored, in each dialect: the committed
/// translations verify against their sources, and planted faults in them are caught (a
/// rounding of another size, the mirror dropped or about the other axis).
#[test]
fn the_mirrored_pocket_pair_of_the_corpus_and_its_planted_faults() {
    let root = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let read = |rel: &str| std::fs::read_to_string(root.join(rel)).expect(rel);
    // FANUC → Sinumerik: the main and its subprogram side by side.
    let d = scratch_dir("corners-scaled", "corpus-fanuc");
    let src = write(&d, "PAIR.nc", &read("corpus/in/fanuc/corner-mirrored-chamfer-pockets.nc"));
    let main = read("corpus/out/sinumerik/corner-mirrored-chamfer-pockets/O_2130.MPF");
    let sub = read("corpus/out/sinumerik/corner-mirrored-chamfer-pockets/O_2131.SPF");
    assert!(main.contains("AMIRROR X0") && sub.contains("RND=3") && sub.contains("CHR=2"), "{main}{sub}");
    let faults = [
        (main.clone(), sub.clone(), true),
        (main.clone(), sub.replace("RND=3", "RND=1.5"), false),
        (main.clone(), sub.replace("CHR=2", "CHR=4"), false),
        (main.replacen("AMIRROR X0", "AMIRROR Y0", 1).replacen("AMIRROR X0", "AMIRROR Y0", 1), sub.clone(), false),
        (main.replace("AMIRROR X0\n", ""), sub.clone(), false),
    ];
    for (i, (m, s, good)) in faults.iter().enumerate() {
        write(&d, "O_2130.MPF", m);
        write(&d, "O_2131.SPF", s);
        let (code, verdict, err) = eval_support::nctrans_in(&d, &["check", &src, "O_2130.MPF"]);
        assert_eq!(code == 0 && verdict.contains("equivalent"), *good, "case {i}:\n{m}{s}\n{verdict}{err}");
    }
    // Sinumerik → FANUC: one file with the subprogram as O9000.
    let d = scratch_dir("corners-scaled", "corpus-siemens");
    let dir = root.join("corpus/in/sinumerik-calls/mirrored-chamfer-pockets");
    for f in ["MAIN.MPF", "POCKET.SPF"] {
        write(&d, f, &std::fs::read_to_string(dir.join(f)).expect(f));
    }
    let out = read("corpus/out/fanuc-calls/mirrored-chamfer-pockets/MAIN.MPF.nc");
    assert!(out.contains("G51.1 X0.") && out.contains(",R3.") && out.contains(",C2."), "{out}");
    let faults = [
        (out.clone(), true),
        (out.replace(",R3.", ",R6."), false),
        (out.replace("G51.1 X0.", "G51.1 Y0."), false),
        (out.replace("G51.1 X0.\n", ""), false),
    ];
    for (i, (p, good)) in faults.iter().enumerate() {
        write(&d, "OUT.nc", p);
        let (code, verdict, err) = eval_support::nctrans_in(&d, &["check", "MAIN.MPF", "OUT.nc"]);
        assert_eq!(code == 0 && verdict.contains("equivalent"), *good, "case {i}:\n{p}\n{verdict}{err}");
    }
}
