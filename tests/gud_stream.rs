//! Global user data on the streamed path (issues 18 and 21): `run --stream`, `check
//! --stream`, `--to fanuc --stream` and a batch's streamed members read a Siemens program
//! with its library's `.DEF` files exactly as the whole-file path does (the same definitions,
//! start values, `--set` inputs, `--var-map`/`[variables] to_fanuc` rules, and the FANUC
//! side's commons seeded from them): every output, trace and verdict is compared byte for
//! byte with the whole path's, and planted faults are caught both ways.

#[path = "support/cli_run.rs"]
mod cli_run;

use cli_run::{nctrans, workdir};
use std::path::{Path, PathBuf};

const GUD: &str =
    "%_N_MGUD_DEF\n;$PATH=/_N_DEF_DIR\nDEF NCK REAL DEPTH=5\nDEF NCK REAL OFS\nDEF CHAN INT PASSES\nM30\n";

const SUB: &str = "PROC ROUGH\nPASSES=PASSES+1\nG1 Z=-DEPTH-PASSES F100\nRET\n";

/// A part reading global user data (with and without a start value), in a callee too.
const MAIN: &str = "G54 G90 G17\nG0 X0 Y0 Z50\nG1 Z=-DEPTH F100\nG1 X=OFS\nROUGH\nG0 Z=10+PASSES\nM30\n";

/// Where the global user data goes on FANUC.
const RULES: &str = "DEPTH=#600,OFS=#601,PASSES=#602";

/// A library: `DEF/MGUD.DEF`, `CMA/ROUGH.SPF`, `CMA/PART.MPF` with `lines` straight blocks
/// after its start (so that it is as large as a test needs).
fn library(name: &str, lines: usize) -> PathBuf {
    let d = workdir("gudstream", name);
    std::fs::create_dir_all(d.join("DEF")).unwrap();
    std::fs::create_dir_all(d.join("CMA")).unwrap();
    std::fs::write(d.join("DEF/MGUD.DEF"), GUD).unwrap();
    std::fs::write(d.join("CMA/ROUGH.SPF"), SUB).unwrap();
    std::fs::write(d.join("CMA/PART.MPF"), with_lines(MAIN, lines)).unwrap();
    d
}

/// `main` with `lines` straight blocks after its third line.
fn with_lines(main: &str, lines: usize) -> String {
    let mut out = String::with_capacity(main.len() + lines * 20);
    for (k, l) in main.lines().enumerate() {
        out.push_str(l);
        out.push('\n');
        if k == 2 {
            for i in 0..lines {
                out.push_str(&format!("G1 X{}.{:03} Y{}.5\n", i % 97, i % 1000, i % 89));
            }
        }
    }
    out
}

/// Runs both ways; both results, which must be alike.
fn both(d: &Path, args: &[&str]) -> (String, String, i32) {
    let whole = nctrans(d, args);
    let mut streamed: Vec<&str> = args.to_vec();
    streamed.insert(1, "--stream");
    let s = nctrans(d, &streamed);
    assert_eq!(whole.2, s.2, "{args:?}: exit codes\nwhole: {}{}\nstreamed: {}{}", whole.0, whole.1, s.0, s.1);
    assert_eq!(whole.0, s.0, "{args:?}: standard output");
    assert_eq!(whole.1, s.1, "{args:?}: standard error");
    whole
}

#[test]
fn a_streamed_run_declares_the_global_user_data_as_a_whole_run() {
    let d = library("run", 50);
    for args in [
        &["run", "CMA/PART.MPF"][..],
        &["run", "CMA/PART.MPF", "--format", "jsonl"],
        &["run", "CMA/PART.MPF", "--set", "DEPTH=7", "--set", "OFS=2"],
    ] {
        let (out, err, code) = both(&d, args);
        assert_eq!(code, 0, "{args:?}: {err}");
        assert!(!out.is_empty() && !err.contains("NC412"), "{out}{err}");
    }
    let (out, _, _) = both(&d, &["run", "CMA/PART.MPF", "--set", "DEPTH=7"]);
    assert!(out.contains("Z=-7 f=100") && out.contains("Z=-8 f=100") && out.contains("Z=11"), "{out}");
    // Two definitions of one name: NC503 either way, the run refused.
    std::fs::write(d.join("DEF/UGUD.DEF"), "DEF NCK REAL DEPTH[8]\nM30\n").unwrap();
    let (_, err, code) = both(&d, &["run", "CMA/PART.MPF"]);
    assert_eq!(code, 1);
    assert!(err.contains("NC503") && err.contains("DEPTH"), "{err}");
    // Without any definition file the name is unknown both ways, as before.
    std::fs::remove_dir_all(d.join("DEF")).unwrap();
    let (_, err, code) = both(&d, &["run", "CMA/PART.MPF"]);
    assert_ne!(code, 0);
    assert!(err.contains("NC412"), "{err}");
}

/// A library macro that looks like a word of a plain line (`M9`) is expanded by the
/// stream's readers as by the whole-file reader (the quick raw readers stand down).
#[test]
fn library_macros_are_read_alike_in_a_stream() {
    let d = workdir("gudstream", "macros");
    std::fs::write(
        d.join("UMAC.DEF"),
        "DEFINE M9 AS G1 X5 F200\nDEFINE LINE AS G1 G94 F300\nDEF NCK REAL DEPTH=4\nM30\n",
    )
    .unwrap();
    let main = "G0 X0 Y0 Z5\nM9\nLINE Z=-DEPTH\nG1 X1 Y1\nM9\nM30\n";
    std::fs::write(d.join("P.MPF"), with_lines(main, 30)).unwrap();
    let (out, err, code) = both(&d, &["run", "P.MPF"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(out.matches(" f=200 ").count(), 2, "{out}");
    // A straight program: the straight stream expands it too.
    std::fs::write(d.join("S.MPF"), with_lines("G0 X0 Y0 Z5\nM9\nG1 X1 Y1\nM30\n", 30)).unwrap();
    let (out, err, code) = both(&d, &["run", "S.MPF"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("X=5 Y=0 Z=5 f=200"), "{out}");
    for (file, out) in [("P.MPF", "p.nc"), ("S.MPF", "s.nc")] {
        let whole = nctrans(&d, &["--to", "fanuc", file, "-o", out, "--var-map", "DEPTH=#500"]);
        let streamed =
            nctrans(&d, &["--to", "fanuc", "--stream", file, "-o", &format!("st-{out}"), "--var-map", "DEPTH=#500"]);
        assert_eq!((whole.2, &whole.1), (0, &streamed.1), "{file}: {}", streamed.1);
        let (w, s) = (read(&d.join(out)), read(&d.join(format!("st-{out}"))));
        assert_eq!(w, s, "{file}");
        assert!(w.contains("G01 X5. F200.") && !w.contains("M09"), "{w}");
    }
}

fn read(p: &Path) -> String {
    std::fs::read_to_string(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

/// The streamed translation to FANUC is the whole one, byte for byte, with the same proof:
/// the rules from `--var-map` or `[variables] to_fanuc`, a `nctrans: set` line for global
/// user data, and the refusal of data without a rule.
#[test]
fn a_streamed_translation_is_the_whole_one() {
    let d = library("translate", 200);
    let cases: [(&str, &[&str]); 3] =
        [("flags", &["--var-map", RULES]), ("config", &[]), ("set", &["--var-map", RULES])];
    for (name, extra) in cases {
        match name {
            "config" => std::fs::write(
                d.join("nctrans.toml"),
                "[variables]\nto_fanuc = [\"DEPTH=#600\", \"OFS=#601\", \"PASSES=#602\"]\n",
            )
            .unwrap(),
            _ => drop(std::fs::remove_file(d.join("nctrans.toml"))),
        }
        if name == "set" {
            std::fs::write(d.join("CMA/PART.MPF"), format!("; nctrans: set DEPTH=7\n{}", with_lines(MAIN, 200)))
                .unwrap();
        }
        let (w, s) = (format!("{name}-whole.nc"), format!("{name}-stream.nc"));
        let mut args = vec!["--to", "fanuc", "CMA/PART.MPF", "-o", &w];
        args.extend(extra);
        let whole = nctrans(&d, &args);
        args[4] = &s;
        args.insert(2, "--stream");
        let streamed = nctrans(&d, &args);
        assert_eq!(whole.2, 0, "{name}: {}", whole.1);
        assert_eq!((whole.2, &whole.1), (streamed.2, &streamed.1), "{name}");
        assert!(whole.1.contains("equivalent ("), "{}", whole.1);
        let text = read(&d.join(&w));
        assert_eq!(text, read(&d.join(&s)), "{name}");
        assert!(text.contains("DEPTH [global user data] = #600") && text.contains("Z-#600"), "{text}");
        if name == "set" {
            assert!(text.contains("(nctrans: set #600=7)"), "{text}");
        }
    }
    // No rule: refused alike (NC504), nothing written.
    let _ = std::fs::remove_file(d.join("nctrans.toml"));
    let whole = nctrans(&d, &["--to", "fanuc", "CMA/PART.MPF", "-o", "none.nc"]);
    let streamed = nctrans(&d, &["--to", "fanuc", "--stream", "CMA/PART.MPF", "-o", "none.nc"]);
    assert_eq!((whole.2, &whole.1), (streamed.2, &streamed.1));
    assert!(whole.2 != 0 && whole.1.contains("NC504"), "{}", whole.1);
    assert!(!d.join("none.nc").exists());
}

/// `check` of a Siemens program using global user data against its FANUC translation, each
/// side streamed or read whole: the FANUC commons are seeded alike, the verdict is the
/// same text, and a planted wrong start value (the FANUC program's own `nctrans: set` of a
/// GUD common) or a wrong assignment is caught both ways.
#[test]
fn a_streamed_check_seeds_the_fanuc_commons_as_a_whole_one() {
    let d = library("check", 200);
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "CMA/PART.MPF", "-o", "part.nc", "--var-map", RULES]);
    assert_eq!(code, 0, "{err}");
    let text = read(&d.join("part.nc"));
    for (a, b) in [("CMA/PART.MPF", "part.nc"), ("part.nc", "CMA/PART.MPF")] {
        let (out, err, code) = both(&d, &["check", a, b]);
        assert_eq!(code, 0, "{out}{err}");
        assert!(out.contains("global user data started on FANUC") && out.contains("DEPTH #600=5, OFS #601=0"), "{out}");
    }
    // The planted faults.
    let seeded = text.replace(
        "(NCTRANS: DEPTH [global user data] = #600)",
        "(NCTRANS: DEPTH [global user data] = #600)\n(nctrans: set #600=6)",
    );
    assert_ne!(seeded, text);
    std::fs::write(d.join("seed.nc"), seeded).unwrap();
    let (out, err, code) = both(&d, &["check", "CMA/PART.MPF", "seed.nc"]);
    assert_eq!(code, 1, "{out}{err}");
    assert!(out.starts_with("diverged at trace event 3") && out.contains("own inputs set #600=6"), "{out}");
    assert!(err.contains("Z=-5") && err.contains("Z=-6"), "{err}");
    let wrong = text.replace("G01 X#601", "G01 X#600");
    assert_ne!(wrong, text);
    std::fs::write(d.join("wrong.nc"), wrong).unwrap();
    let (out, _, code) = both(&d, &["check", "CMA/PART.MPF", "wrong.nc"]);
    assert_eq!(code, 1, "{out}");
    assert!(out.starts_with("diverged at trace event ") && out.contains("assumed: global user data"), "{out}");
    // A copy without the translation's header lines is seeded by the project's rules alike.
    let bare: String = text.lines().filter(|l| !l.contains("global user data")).map(|l| format!("{l}\n")).collect();
    std::fs::write(d.join("bare.nc"), bare).unwrap();
    let (out, _, code) = both(&d, &["check", "CMA/PART.MPF", "bare.nc"]);
    assert_eq!(code, 1, "{out}");
    assert!(!out.contains("assumed"), "{out}");
    std::fs::write(d.join("nctrans.toml"), "[variables]\nto_fanuc = [\"DEPTH=#600\", \"OFS=#601\", \"PASSES=#602\"]\n")
        .unwrap();
    let (out, err, code) = both(&d, &["check", "CMA/PART.MPF", "bare.nc"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("DEPTH #600=5"), "{out}");
}

/// A file large enough to stream by itself (8 MB) runs, translates and checks with its
/// global user data; the planted start value is caught.
#[test]
fn a_large_file_streams_with_its_global_user_data() {
    let d = library("large", 520_000);
    assert!(std::fs::metadata(d.join("CMA/PART.MPF")).unwrap().len() >= 8 * 1024 * 1024);
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "CMA/PART.MPF", "-o", "part.nc", "--var-map", RULES]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent (") && !err.contains("read whole"), "{err}");
    let (out, err, code) = nctrans(&d, &["check", "CMA/PART.MPF", "part.nc"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("DEPTH #600=5, OFS #601=0, PASSES #602=0"), "{out}");
    let text = read(&d.join("part.nc"));
    let seeded = text.replacen("(NCTRANS: DEPTH", "(nctrans: set #600=6)\n(NCTRANS: DEPTH", 1);
    std::fs::write(d.join("seed.nc"), seeded).unwrap();
    let (out, _, code) = nctrans(&d, &["check", "CMA/PART.MPF", "seed.nc"]);
    assert_eq!(code, 1, "{out}");
    assert!(out.starts_with("diverged at trace event 3"), "{out}");
    let (out, err, code) = nctrans(&d, &["run", "CMA/PART.MPF", "--set", "PASSES=4"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("Z=-10 f=100") && out.contains("Z=15"), "{}", &out[out.len().saturating_sub(300)..]);
}

/// A batch whose large members stream (`--stream`) translates and proves them with their
/// library's global user data as the whole-file jobs do: the same outputs and report.
#[test]
fn a_batch_streams_members_with_global_user_data_alike() {
    let d = library("batch", 300);
    std::fs::write(d.join("CMA/PLAIN.MPF"), with_lines("G0 X0 Y0 Z5\nG1 Z-1 F100\nM30\n", 300)).unwrap();
    std::fs::write(d.join("nctrans.toml"), "[variables]\nto_fanuc = [\"DEPTH=#600\", \"OFS=#601\", \"PASSES=#602\"]\n")
        .unwrap();
    let whole = nctrans(&d, &["--to", "fanuc", "-o", "o1", "CMA", "--report", "r1.json"]);
    let streamed = nctrans(&d, &["--to", "fanuc", "--stream", "-o", "o2", "CMA", "--report", "r2.json"]);
    assert_eq!(whole.2, 0, "{}", whole.1);
    assert_eq!(streamed.2, 0, "{}", streamed.1);
    for f in ["PART.NC", "PLAIN.NC", "ROUGH.NC"] {
        let (a, b) = (d.join("o1").join(f), d.join("o2").join(f));
        assert_eq!(a.exists(), b.exists(), "{f}");
        if a.exists() {
            assert_eq!(read(&a), read(&b), "{f}");
        }
    }
    let entries = |r: &str| -> Vec<String> {
        read(&d.join(r))
            .lines()
            .filter(|l| l.contains("\"path\""))
            .map(|l| l.split("\"time_ms\"").next().unwrap_or("").to_string())
            .collect()
    };
    assert_eq!(entries("r1.json"), entries("r2.json"));
    assert_eq!(read(&d.join("r2.json")).matches("\"status\": \"verified\"").count(), 3);
}

/// A jump to a numbered block of motion keeps it in what a streamed check reads for the
/// data the program uses (seeded alike); a program whose translation has other errors is
/// refused streamed (NC595), never checked with commons that might be seeded otherwise.
#[test]
fn a_streamed_check_keeps_jump_targets_and_refuses_what_it_cannot_settle() {
    let d = library("jumps", 0);
    let jumps =
        "G54 G90 G17\nG0 X0 Y0 Z50\nG1 Z=-DEPTH F100\nIF DEPTH>3 GOTOF N100\nG1 X5\nN100 G1 X=OFS\nG0 Z50\nM30\n";
    std::fs::write(d.join("CMA/JUMP.MPF"), with_lines(jumps, 40)).unwrap();
    let (_, err, code) = nctrans(&d, &["--to", "fanuc", "CMA/JUMP.MPF", "-o", "jump.nc", "--var-map", RULES]);
    assert_eq!(code, 0, "{err}");
    let (out, err, code) = both(&d, &["check", "CMA/JUMP.MPF", "jump.nc"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("DEPTH #600=5, OFS #601=0"), "{out}");
    // `$P_S[1]` does not translate (NC589): the whole check seeds from the marked translation,
    // the streamed one refuses.
    std::fs::write(d.join("CMA/REF.MPF"), with_lines(&jumps.replace("G0 Z50\n", "R10=$P_S[1]\nG0 Z50\n"), 40)).unwrap();
    let (out, _, _) = nctrans(&d, &["check", "CMA/REF.MPF", "jump.nc"]);
    assert!(out.contains("global user data started on FANUC"), "{out}");
    let (out, err, code) = nctrans(&d, &["check", "--stream", "CMA/REF.MPF", "jump.nc"]);
    assert_eq!(code, 1, "{out}{err}");
    assert!(out.is_empty() && err.contains("NC595") && err.contains("CMA/REF.MPF"), "{out}{err}");
}

/// On a Haas NGC the tables live in the NGC-only commons: the streamed translation is read
/// back and run with the NGC variables as the whole proof is (not as tool data), and a
/// streamed check seeds them alike.
#[test]
fn haas_ngc_tables_stream_alike() {
    let d = workdir("gudstream", "ngc");
    std::fs::create_dir_all(d.join("DEF")).unwrap();
    std::fs::write(
        d.join("DEF/MGUD.DEF"),
        "DEF NCK REAL DRESS_A[80]\nDEF NCK REAL DRESS_B[80]=SET(1.5,2.5)\nDEF NCK INT DRESSINGS=3\nM30\n",
    )
    .unwrap();
    let main = "DEF INT KS\nG0 X0 Y0 Z10\nFOR KS=0 TO 3\nDRESS_A[KS]=KS*0.25+DRESS_B[1]\nENDFOR\n\
G1 Z=-DRESS_A[2] F=100*DRESS_B[0]\nG0 X1 Y=DRESSINGS\nDRESSINGS=DRESSINGS+1\nM30\n";
    std::fs::write(d.join("DRESS.MPF"), with_lines(main, 30)).unwrap();
    std::fs::write(
        d.join("nctrans.toml"),
        "[fanuc]\nseries = \"haas-ngc\"\n[variables]\nto_fanuc = [\"DRESS_A=#10200\", \"DRESS_B=#10280\", \"DRESSINGS=#500\"]\n",
    )
    .unwrap();
    let whole = nctrans(&d, &["--to", "fanuc", "DRESS.MPF", "-o", "w.nc"]);
    let streamed = nctrans(&d, &["--to", "fanuc", "--stream", "DRESS.MPF", "-o", "s.nc"]);
    assert_eq!(whole.2, 0, "{}", whole.1);
    assert_eq!((whole.2, &whole.1), (streamed.2, &streamed.1));
    assert_eq!(read(&d.join("w.nc")), read(&d.join("s.nc")));
    let (out, err, code) = both(&d, &["check", "DRESS.MPF", "w.nc"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("DRESS_B #10280..#10359") && !err.contains("tool_data"), "{out}{err}");
}
