//! No command writes over a program it reads (issue 16): `-o` naming the input, by any
//! spelling, symbolic link or hard link, in both directions, whole and streamed, and the
//! subprogram files read beside it or written beside the output; `-o` onto an existing
//! file needs `--force`; a batch refuses overlapping folders and folders without programs,
//! and its report never lands on a program.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("nctrans-safety-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn nctrans(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_nctrans")).args(args).current_dir(dir).output().unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).to_string()
}

/// Asserts a refusal: exit 2, the code on stderr, and every file of `kept` as it was.
fn refused(o: &Output, code: &str, kept: &[(&Path, &[u8])]) {
    assert_eq!(o.status.code(), Some(2), "{}", stderr(o));
    assert!(stderr(o).contains(&format!("error[{code}]")), "{}", stderr(o));
    for (p, bytes) in kept {
        assert_eq!(std::fs::read(p).unwrap(), *bytes, "{} was changed", p.display());
    }
}

const SIEMENS: &[u8] = b"; same\nR1=2\nG1 X=R1 F100\nM30\n";
const FANUC_MAIN: &[u8] = b"%\nO1000\nG65 P9100 A1.\nM30\n%\n";
const FANUC_SUB: &[u8] = b"%\nO9100\nG01 X#1 F100.\nM99\n%\n";

#[test]
fn output_naming_the_siemens_input_is_refused_in_every_spelling() {
    let d = scratch("s2f");
    std::fs::create_dir_all(d.join("dir")).unwrap();
    let src = d.join("dir/same.MPF");
    std::fs::write(&src, SIEMENS).unwrap();
    let kept: &[(&Path, &[u8])] = &[(&src, SIEMENS)];
    for stream in [false, true] {
        let mut runs = vec![
            (d.clone(), vec!["--to", "fanuc", "dir/same.MPF", "-o", "dir/same.MPF"]),
            (d.join("dir"), vec!["--to", "fanuc", "same.MPF", "-o", "../dir/same.MPF"]),
            (d.clone(), vec!["--to", "fanuc", "dir/same.MPF", "-o", "dir/./same.MPF", "--force"]),
        ];
        if stream {
            runs.iter_mut().for_each(|(_, a)| a.push("--stream"));
        }
        for (at, args) in runs {
            refused(&nctrans(&at, &args), "NC602", kept);
        }
    }
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink("same.MPF", d.join("dir/sym.nc")).unwrap();
        std::fs::hard_link(&src, d.join("dir/hard.nc")).unwrap();
        for link in ["dir/sym.nc", "dir/hard.nc"] {
            for extra in [&[][..], &["--stream"][..]] {
                let mut args = vec!["--to", "fanuc", "dir/same.MPF", "-o", link, "--force"];
                args.extend(extra);
                refused(&nctrans(&d, &args), "NC602", kept);
            }
        }
    }
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn output_naming_the_fanuc_input_or_a_callee_is_refused() {
    let d = scratch("f2s");
    std::fs::write(d.join("main.nc"), FANUC_MAIN).unwrap();
    std::fs::write(d.join("O9100.nc"), FANUC_SUB).unwrap();
    let kept: &[(&Path, &[u8])] = &[(&d.join("main.nc"), FANUC_MAIN), (&d.join("O9100.nc"), FANUC_SUB)];
    for extra in [&[][..], &["--stream"][..]] {
        for out in ["main.nc", "./main.nc", "O9100.nc"] {
            let mut args = vec!["--to", "sinumerik", "main.nc", "-o", out, "--force"];
            args.extend(extra);
            refused(&nctrans(&d, &args), "NC602", kept);
        }
    }
    // The subprogram file written beside the output is a link to the callee read beside
    // the input: written through, it would replace the FANUC program.
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink("O9100.nc", d.join("O_9100.SPF")).unwrap();
        for extra in [&[][..], &["--stream"][..]] {
            let mut args = vec!["--to", "sinumerik", "main.nc", "-o", "./", "--force"];
            args.extend(extra);
            let o = nctrans(&d, &args);
            refused(&o, "NC602", kept);
            assert!(stderr(&o).contains("O_9100.SPF"), "{}", stderr(&o));
            assert!(!d.join("MAIN.MPF").exists(), "nothing is written when one file is refused");
        }
    }
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn a_subprogram_read_beside_a_siemens_main_is_an_input() {
    let d = scratch("s2f-sub");
    let sub: &[u8] = b"PROC SUBA\nG1 X2\nM17\n";
    std::fs::write(d.join("main.mpf"), b"G1 X1 F100\nSUBA\nG1 X3\nM30\n").unwrap();
    std::fs::write(d.join("SUBA.SPF"), sub).unwrap();
    for extra in [&[][..], &["--stream"][..]] {
        let mut args = vec!["--to", "fanuc", "main.mpf", "-o", "SUBA.SPF", "--force"];
        args.extend(extra);
        refused(&nctrans(&d, &args), "NC602", &[(&d.join("SUBA.SPF"), sub)]);
    }
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn an_existing_output_is_replaced_only_with_force() {
    let d = scratch("force");
    std::fs::write(d.join("a.mpf"), SIEMENS).unwrap();
    std::fs::write(d.join("main.nc"), FANUC_MAIN).unwrap();
    std::fs::write(d.join("O9100.nc"), FANUC_SUB).unwrap();
    for (args, out) in [
        (vec!["--to", "fanuc", "a.mpf", "-o", "old.nc"], "old.nc"),
        (vec!["--to", "fanuc", "a.mpf", "-o", "old.nc", "--stream"], "old.nc"),
        (vec!["--to", "sinumerik", "main.nc", "-o", "OLD.MPF"], "OLD.MPF"),
        (vec!["--to", "sinumerik", "main.nc", "-o", "OLD.MPF", "--stream"], "OLD.MPF"),
    ] {
        std::fs::write(d.join(out), b"keep me").unwrap();
        refused(&nctrans(&d, &args), "NC601", &[(&d.join(out), b"keep me")]);
        let mut forced = args.clone();
        forced.push("--force");
        let o = nctrans(&d, &forced);
        assert_eq!(o.status.code(), Some(0), "{args:?}: {}", stderr(&o));
        assert_ne!(std::fs::read(d.join(out)).unwrap(), b"keep me");
    }
    // A subprogram file beside the output counts too; a device is written into as before.
    std::fs::write(d.join("O_9100.SPF"), b"keep me").unwrap();
    refused(&nctrans(&d, &["--to", "sinumerik", "main.nc", "-o", "NEW.MPF"]), "NC601", &[]);
    assert!(!d.join("NEW.MPF").exists(), "nothing is written when one file is refused");
    assert_eq!(nctrans(&d, &["--to", "fanuc", "a.mpf", "-o", "/dev/null"]).status.code(), Some(0));
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn batch_folders_that_overlap_are_refused_and_nothing_is_written() {
    let d = scratch("overlap");
    std::fs::create_dir_all(d.join("lib/sub")).unwrap();
    std::fs::write(d.join("lib/a.mpf"), SIEMENS).unwrap();
    for (at, out, input) in [
        (d.clone(), "lib", "lib"),
        (d.clone(), "lib/", "./lib"),
        (d.clone(), "lib/out", "lib"),
        (d.clone(), "lib/sub/new/out", "lib"),
        (d.clone(), ".", "lib"),
        (d.join("lib"), ".", "."),
        (d.join("lib/sub"), "../..", ".."),
    ] {
        let o = nctrans(&at, &["--to", "fanuc", "-o", out, input]);
        refused(&o, "NC610", &[(&d.join("lib/a.mpf"), SIEMENS)]);
        assert!(stderr(&o).contains("hint: give an output folder"), "{}", stderr(&o));
        assert!(
            !d.join("lib/nctrans-map.toml").exists()
                && !d.join("lib/out").exists()
                && !d.join("nctrans-map.toml").exists()
        );
        assert!(String::from_utf8_lossy(&o.stdout).is_empty(), "no summary for a refused batch");
    }
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink("lib", d.join("link")).unwrap();
        refused(&nctrans(&d, &["--to", "fanuc", "-o", "link/out", "lib"]), "NC610", &[]);
    }
    // Beside it is fine.
    let o = nctrans(&d, &["--to", "fanuc", "-o", "lib-fanuc", "lib"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn a_batch_without_programs_to_translate_is_not_a_success() {
    let d = scratch("empty");
    std::fs::create_dir_all(d.join("empty")).unwrap();
    std::fs::write(d.join("empty/notes.txt"), "no programs").unwrap();
    let o = nctrans(&d, &["--to", "fanuc", "-o", "out", "empty"]);
    refused(&o, "NC611", &[]);
    assert!(!String::from_utf8_lossy(&o.stdout).contains("every file verified"));
    assert!(!d.join("out").exists());
    std::fs::create_dir_all(d.join("fanuc")).unwrap();
    std::fs::write(d.join("fanuc/O1000.nc"), FANUC_MAIN).unwrap();
    let o = nctrans(&d, &["--to", "fanuc", "-o", "out", "fanuc"]);
    refused(&o, "NC612", &[]);
    assert!(stderr(&o).contains("--to sinumerik"), "{}", stderr(&o));
    assert!(!d.join("out").exists());
    std::fs::remove_dir_all(&d).unwrap();
}

#[cfg(unix)]
#[test]
fn a_batch_report_never_lands_on_a_program() {
    let d = scratch("report");
    std::fs::create_dir_all(d.join("lib")).unwrap();
    std::fs::write(d.join("lib/a.mpf"), SIEMENS).unwrap();
    std::os::unix::fs::symlink("lib/a.mpf", d.join("r.json")).unwrap();
    let o = nctrans(&d, &["--to", "fanuc", "-o", "out", "lib", "--report", "r.json"]);
    refused(&o, "NC602", &[(&d.join("lib/a.mpf"), SIEMENS)]);
    assert!(stderr(&o).contains("give --report another file"), "{}", stderr(&o));
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn a_streamed_output_that_cannot_be_put_in_place_leaves_no_temporary_file() {
    // `-o` naming a folder, to FANUC (one output file): the stream writes its temporary
    // file beside it and cannot rename it onto the folder; the temporary file goes too.
    let d = scratch("rename");
    let src = d.join("same.MPF");
    std::fs::write(&src, SIEMENS).unwrap();
    std::fs::create_dir_all(d.join("taken.nc")).unwrap();
    let o = nctrans(&d, &["--to", "fanuc", "same.MPF", "-o", "taken.nc", "--force", "--stream"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).starts_with("error: cannot write taken.nc: "), "{}", stderr(&o));
    let mut left: Vec<String> =
        std::fs::read_dir(&d).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    left.sort();
    assert_eq!(left, ["same.MPF", "taken.nc"]);
    assert_eq!(std::fs::read(&src).unwrap(), SIEMENS);
    assert_eq!(std::fs::read_dir(d.join("taken.nc")).unwrap().count(), 0);
}

#[test]
fn output_into_a_folder_to_fanuc_names_the_file_and_leaves_nothing_behind() {
    let d = scratch("to-dir");
    std::fs::write(d.join("PART.MPF"), SIEMENS).unwrap();
    // `-o out/` (a folder not there yet) takes the input's name.
    let o = nctrans(&d, &["--to", "fanuc", "PART.MPF", "-o", "out/"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let written = std::fs::read(d.join("out/PART.NC")).expect("out/PART.NC written");
    // Again: the named file exists, so it is refused without --force and kept.
    let o = nctrans(&d, &["--to", "fanuc", "PART.MPF", "-o", "out"]);
    refused(&o, "NC601", &[(&d.join("out/PART.NC"), &written)]);
    assert!(stderr(&o).contains("PART.NC"), "{}", stderr(&o));
    let left: Vec<_> = std::fs::read_dir(&d).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(left.len(), 2, "no temporary file is left beside them: {left:?}");
}
