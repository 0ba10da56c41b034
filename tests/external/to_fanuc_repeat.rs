//! The horizon-juicer grinding library's program-section repetition to FANUC: its dressing
//! subprograms compute a flank's points in a section `BEGIN: … END:` and run it again with
//! `REPEAT BEGIN END` for the other flank's roller radius. With the machine's set-up (the
//! Haas NGC profile, its global user data in retained commons, the axis letters fixed) the
//! REPEAT no longer stops them: `D_TaiDaoLiang.SPF` translates and is proven once its
//! triangle data `TRI` has a home, and so do both `D_TRIANGLE.SPF` (their TRANS under the caller's
//! G90/G91 written `G90 G52 …`, the incremental moves after absolute ones in the frame).

use std::process::Command;

fn nctrans(dir: &std::path::Path, args: &[&str]) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_nctrans")).args(args).current_dir(dir).output().expect("run nctrans");
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stderr).into_owned())
}

/// The set-up of the issue: the globals' homes, `extra` added to them.
fn config(def: &std::path::Path, extra: &str) -> String {
    format!(
        "[fanuc]\nseries = \"haas-ngc\"\n[sinumerik]\ndefinitions = [{:?}]\n[variables]\n\
         to_fanuc = [\"INI=#500\",\"DRESSER=#660\",\"PROCESS=#800\",\"GRIND=#930\",\"WHEEL=#940\",\"WORK=#970\",\
         \"DIY=#980\",\"TECH_TIME=#990\",\"TECH_DRESS_DEEP=#10000\",\"COMMON_RND=#10080\",\"SHAPE_MODEL=#10200\",\
         \"TECH_DRESS_FEED=#10320\",{extra}\"COMMON_ANG=#10480\",\"TECH_DRESS_TIME=#10700\",\"COMMON_LENGTH=#10780\"]\n\
         fixed = {{ AXIS_HORI=\"Z\", AXIS_VER=\"X\", AXIS_EW=\"A\", G_0=\"X\", G_1=\"Z\", G_2=\"C\", D_0=\"X\", D_1=\"Z\" }}\n",
        def.display().to_string()
    )
}

#[test]
fn the_dressing_sections_repeated_with_repeat_translate() {
    let lib = crate::external("horizon-juicer-sinumerik/programs");
    let dir = std::env::temp_dir().join(format!("nctrans-external-repeat-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let def = lib.join("DEF/MGUD.DEF");
    let part = lib.join("CMA/DRESS_PART");
    let run = |file: &str, out: &str| {
        let p = part.join(file).display().to_string();
        nctrans(&dir, &["--to", "fanuc", &p, "-o", out, "--force"])
    };
    // The map, as given: every program stops only where TRI has no home.
    std::fs::write(dir.join("nctrans.toml"), config(&def, "\"WHEEL_LINESPEED_DRESS=#10400\",")).unwrap();
    for file in ["D_TaiDaoLiang.SPF", "shape/SN/D_TRIANGLE.SPF", "shape/SW/D_TRIANGLE.SPF"] {
        let (code, err) = run(file, "o.nc");
        assert_ne!(code, 0, "{file}: {err}");
        assert!(!err.contains("NC317"), "{file}: REPEAT is translated now: {err}");
        assert!(err.contains("error[NC504]: global user data TRI"), "{file}: {err}");
    }
    // TRI in the commons these programs leave free (they do not use WHEEL_LINESPEED_DRESS).
    std::fs::write(dir.join("nctrans.toml"), config(&def, "\"TRI=#10400\",")).unwrap();
    let (code, err) = run("D_TaiDaoLiang.SPF", "taidao.nc");
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent ("), "{err}");
    let text = std::fs::read_to_string(dir.join("taidao.nc")).unwrap();
    assert!(text.contains("(REPEAT SECTION BEGIN TO END, ONCE)"), "{text}");
    assert_eq!(text.matches("(BEGIN:)").count(), 1, "the labels stay on the original section:\n{text}");
    for file in ["shape/SN/D_TRIANGLE.SPF", "shape/SW/D_TRIANGLE.SPF"] {
        // Its TRANS (in the caller's G90/G91) is written `G90 G52 …` and the mode selected
        // again; its G91 moves follow absolute ones in the frame (frames_incr).
        let (code, err) = run(file, "tri.nc");
        assert_eq!(code, 0, "{file}: {err}");
        assert!(err.contains("equivalent ("), "{file}: {err}");
    }
}
