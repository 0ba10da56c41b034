//! Streaming files in legacy encodings: `stream::transcode` decides exactly what
//! `read::decode` decides (for every chunk size, so multi-byte characters straddle chunk
//! boundaries), the decoded copy is the decoded text, and the command line gives the same
//! traces, summaries, translations, diagnostics and exit codes with `--stream` as whole.

use encoding_rs::Encoding;
use nctrans::read;
use nctrans::stream::transcode;
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("nctrans-test-enc-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Legacy encodings with a comment each can hold.
fn legacy() -> Vec<(&'static Encoding, &'static str)> {
    vec![
        (encoding_rs::WINDOWS_1252, "Fräser Ø10 Spindel grüßt"),
        (encoding_rs::GBK, "粗加工 刀具 铣刀 直径十毫米 精加工"),
        (encoding_rs::SHIFT_JIS, "荒加工 工具 エンドミル 仕上げ"),
        (encoding_rs::WINDOWS_1250, "Fréza průměr žluťoučký kůň"),
    ]
}

fn sinumerik_text(comment: &str, eol: &str, blocks: usize) -> String {
    let mut s = format!("; {comment}{eol}G90 G17 G71{eol}R1=2.5{eol}MSG(\"{comment}\"){eol}");
    for i in 0..blocks {
        s.push_str(&format!("N{} G1 X{}.{} Y-{} F1200 ; {comment}{eol}", 10 * (i + 1), i, i % 10, i % 7));
    }
    s.push_str(&format!("M30{eol}"));
    s
}

fn fanuc_text(comment: &str, eol: &str, blocks: usize) -> String {
    let mut s = format!("O1000 ({comment}){eol}G90 G17 G21{eol}#100=2.5{eol}");
    for i in 0..blocks {
        s.push_str(&format!("N{} G01 X{}.{} Y-{} F1200. ({comment}){eol}", 10 * (i + 1), i, i % 10, i % 7));
    }
    s.push_str(&format!("M30{eol}"));
    s
}

fn encoded(text: &str, enc: &'static Encoding, bom: bool) -> Vec<u8> {
    let (b, _, unmappable) = enc.encode(text);
    assert!(!unmappable, "{} cannot hold the test text", enc.name());
    let mut v = if bom { b"\xEF\xBB\xBF".to_vec() } else { Vec::new() };
    v.extend_from_slice(&b);
    v
}

fn check_detection(path: &Path, forced: Option<&'static Encoding>, chunk_sizes: &[usize]) {
    let bytes = std::fs::read(path).unwrap();
    let whole = read::decode(&bytes, forced);
    for &c in chunk_sizes {
        let d = transcode::detect_chunked(path, forced, c).unwrap();
        assert_eq!(
            (d.encoding.name(), d.bom, d.line_ending),
            (whole.encoding.name(), whole.bom, whole.line_ending),
            "{} forced {:?} chunk {c}",
            path.display(),
            forced.map(|e| e.name())
        );
    }
    let d = transcode::detect(path, forced).unwrap();
    let mut copy = Vec::new();
    transcode::decode_to(path, &d, &mut copy).unwrap();
    assert_eq!(String::from_utf8(copy).unwrap(), whole.text, "{}", path.display());
}

#[test]
fn detection_matches_the_whole_path_for_every_chunk_size() {
    let dir = scratch("detect");
    let mut n = 0;
    for (enc, comment) in legacy() {
        for eol in ["\n", "\r\n", "\r"] {
            for bom in [false, true] {
                for (ext, text) in [("mpf", sinumerik_text(comment, eol, 12)), ("nc", fanuc_text(comment, eol, 12))] {
                    let p = dir.join(format!("f{n}.{ext}"));
                    n += 1;
                    std::fs::write(&p, encoded(&text, enc, bom)).unwrap();
                    check_detection(&p, None, &[1, 2, 3, 5, 7, 64, 65536]);
                    check_detection(&p, Some(enc), &[1, 3, 64]);
                    // Forced wrong: the whole path's windows-1252 fallback (or a lucky decode).
                    check_detection(&p, Some(encoding_rs::UTF_8), &[1, 4]);
                    check_detection(&p, Some(encoding_rs::SHIFT_JIS), &[1, 4]);
                    check_detection(&p, Some(encoding_rs::UTF_16LE), &[2]);
                }
            }
        }
    }
    // Edge cases: empty, BOM only, a lone CR at the end, bytes no guess decodes exactly.
    for (i, bytes) in [
        b"".to_vec(),
        b"\xEF\xBB\xBF".to_vec(),
        b"\xEF\xBB".to_vec(),
        b"G1 X1\r".to_vec(),
        b"(\x81\x8d\x8f\x90\x9d)\nM30\n".to_vec(),
        b"(\xff\xfe\xfd)\r\nM30".to_vec(),
        b"(\xe4\xb8)\n".to_vec(),
    ]
    .into_iter()
    .enumerate()
    {
        let p = dir.join(format!("edge{i}.nc"));
        std::fs::write(&p, &bytes).unwrap();
        check_detection(&p, None, &[1, 2, 3, 4, 1024]);
        check_detection(&p, Some(encoding_rs::GBK), &[1, 2, 5]);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn detection_matches_the_whole_path_on_the_corpus() {
    let mut seen = 0;
    for d in ["corpus/in/fanuc", "corpus/in/sinumerik"] {
        let Ok(rd) = std::fs::read_dir(root().join(d)) else {
            println!("note: {d} not found; skipped");
            continue;
        };
        for e in rd.flatten() {
            check_detection(&e.path(), None, &[1, 7, 4096]);
            seen += 1;
        }
    }
    println!("{seen} corpus files");
}

#[test]
fn encode_to_matches_read_encode() {
    let dir = scratch("encode");
    for (enc, comment) in legacy() {
        for bom in [false, true] {
            // "€" and "ℵ" are not in every encoding: numeric references, as read::encode writes.
            let text = format!("(A {comment} € ℵ)\r\nG1 X1\r\n");
            let p = dir.join("u.nc");
            std::fs::write(&p, &text).unwrap();
            let mut out = Vec::new();
            transcode::encode_to(&p, enc, bom, &mut out).unwrap();
            assert_eq!(out, read::encode(&text, enc, bom), "{}", enc.name());
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn copy_is_removed_on_drop() {
    let dir = scratch("copy");
    let p = dir.join("x.mpf");
    std::fs::write(&p, encoded(&sinumerik_text("Fräser", "\n", 3), encoding_rs::WINDOWS_1252, false)).unwrap();
    let c = transcode::copy(&p, None).unwrap().expect("a legacy file gets a copy");
    let cp = c.path().to_path_buf();
    assert_eq!(cp.file_name(), p.file_name());
    assert!(std::fs::read_to_string(&cp).unwrap().contains("Fräser"));
    drop(c);
    assert!(!cp.exists() && !cp.parent().unwrap().exists());
    std::fs::write(&p, "G1 X1\n").unwrap();
    assert!(transcode::copy(&p, None).unwrap().is_none());
    let _ = std::fs::remove_dir_all(&dir);
}

fn nctrans(args: &[&str], cwd: &Path, tmp: &Path) -> (i32, Vec<u8>, String) {
    let o =
        Command::new(env!("CARGO_BIN_EXE_nctrans")).args(args).current_dir(cwd).env("TMPDIR", tmp).output().unwrap();
    (o.status.code().unwrap_or(-1), o.stdout, String::from_utf8_lossy(&o.stderr).into_owned())
}
