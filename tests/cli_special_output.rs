//! `-o` naming something that is not a regular file (a FIFO here; `/dev/null` alike): the
//! translation is written into it and the target stays what it was. Before, every route
//! renamed its finished temporary file over the target, which replaced `/dev/null` with a
//! regular file when run as root.

use std::os::unix::fs::{FileTypeExt, OpenOptionsExt};
use std::path::{Path, PathBuf};
use std::process::Command;

fn bin() -> &'static str {
    env!("CARGO_BIN_EXE_nctrans")
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("nctrans-special-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("scratch folder");
    d
}

/// A straight-line CAM program in `dialect` (streamed with `--stream`).
fn cam(dir: &Path, fanuc: bool) -> PathBuf {
    let mut text = String::from(if fanuc { "%\nO1000\nG21 G90 G94\n" } else { "G71 G90 G94\n" });
    for i in 0..500 {
        let x = i as f64 * 0.125;
        if fanuc {
            text.push_str(&format!("G1 X{x:.3} Y-{x:.3} F800.\n"));
        } else {
            text.push_str(&format!("G1 X{x:.3} Y-{x:.3} F800\n"));
        }
    }
    text.push_str(if fanuc { "M30\n%\n" } else { "M30\n" });
    let p = dir.join(if fanuc { "cam.nc" } else { "cam.mpf" });
    std::fs::write(&p, text).expect("program");
    p
}

/// Runs `nctrans ARGS -o FIFO` with a reader on the FIFO; gives what the reader got and the
/// exit status. The FIFO must still be a FIFO afterwards.
fn through_fifo(dir: &Path, args: &[&str]) -> (Vec<u8>, bool) {
    let fifo = dir.join("out.fifo");
    let _ = std::fs::remove_file(&fifo);
    let made = Command::new("mkfifo").arg(&fifo).status().expect("mkfifo runs");
    assert!(made.success(), "mkfifo");
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::read(&fifo).expect("read the FIFO"))
    };
    let st = Command::new(bin()).args(args).arg("-o").arg(&fifo).status().expect("nctrans runs");
    let ft = std::fs::symlink_metadata(&fifo).expect("target still there").file_type();
    // Checked before joining: a reader whose FIFO was replaced would wait forever.
    assert!(ft.is_fifo(), "{args:?}: -o replaced the FIFO with {ft:?}");
    // A writer opened and closed here ends the reader's wait even if nctrans never opened the
    // FIFO (O_NONBLOCK, Linux's 0o4000: fails at once when the reader has already gone).
    let _ = std::fs::OpenOptions::new().write(true).custom_flags(0o4000).open(&fifo);
    let got = reader.join().expect("reader");
    (got, st.success())
}

/// The output of the same command into a regular file.
fn into_file(dir: &Path, args: &[&str], name: &str) -> Vec<u8> {
    let out = dir.join(name);
    let st = Command::new(bin()).args(args).arg("-o").arg(&out).status().expect("nctrans runs");
    assert!(st.success(), "{args:?} into a file");
    std::fs::read(&out).expect("output")
}

#[test]
fn every_translation_route_writes_into_a_fifo_without_replacing_it() {
    let dir = scratch("routes");
    let mpf = cam(&dir, false);
    let nc = cam(&dir, true);
    let (mpf, nc) = (mpf.to_str().expect("utf-8 path"), nc.to_str().expect("utf-8 path"));
    let routes: [(&[&str], &str); 4] = [
        (&["--to", "fanuc", mpf], "whole.nc"),
        (&["--to", "fanuc", "--stream", mpf], "streamed.nc"),
        (&["--to", "sinumerik", nc], "whole.mpf"),
        (&["--to", "sinumerik", "--stream", nc], "streamed.mpf"),
    ];
    for (args, name) in routes {
        let want = into_file(&dir, args, name);
        let (got, ok) = through_fifo(&dir, args);
        assert!(ok, "{args:?} into a FIFO failed");
        assert_eq!(String::from_utf8_lossy(&got), String::from_utf8_lossy(&want), "{args:?}");
    }
    // No temporary file is left beside the target.
    let left: Vec<_> = std::fs::read_dir(&dir)
        .expect("list")
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains("nctrans-tmp"))
        .collect();
    assert!(left.is_empty(), "left behind: {left:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// `--stream -o DIR/` for a program the stream hands to the whole path, which then fails:
/// no output folder is left behind (the whole path alone creates none).
#[test]
fn a_failed_translation_leaves_no_output_folder() {
    let dir = scratch("no-folder");
    let src = dir.join("lost.nc");
    std::fs::write(&src, "%\nO1000\nG21 G0 X0\nM98 P1234\nM30\n%\n").expect("program");
    for (to, extra) in [("sinumerik", "out-s/"), ("fanuc", "out-f/")] {
        let input = if to == "fanuc" {
            let p = dir.join("lost.mpf");
            std::fs::write(&p, "G0 X0\nNOWHERE\nM30\n").expect("program");
            p
        } else {
            src.clone()
        };
        let out = dir.join(extra);
        let o = format!("{}/", out.display());
        let st = Command::new(bin()).args(["--to", to, "--stream"]).arg(&input).args(["-o", &o]).output().expect("run");
        assert!(!st.status.success(), "{to}: {}", String::from_utf8_lossy(&st.stderr));
        assert!(!out.exists(), "{to}: {} left behind", out.display());
    }
    let _ = std::fs::remove_dir_all(&dir);
}
