//! The streaming path against the whole-file path: on every corpus program (and generated
//! ones with loops and jumps across many chunks) the streamed statements make the same IR,
//! the same diagnostics codes, and a streamed run gives the same trace, line numbers included.

mod eval_support;

use eval_support::*;
use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::eval::{self, trace, Origin, RunOptions, TraceSink};
use nctrans::ir::{Program, Stmt, Unit};
use nctrans::span::SourceDb;
use nctrans::stream::{self, lines::Input, paged::Pager};
use std::path::Path;
use std::rc::Rc;
use std::sync::Arc;

struct Streamed {
    index: stream::Index,
    unit: Unit,
}

/// Scans `bytes` with chunks of `chunk_ops` ops and assembles the statements into a unit.
fn stream_unit(path: &Path, bytes: &[u8], dialect: Dialect, chunk_ops: usize) -> Option<Streamed> {
    let mut by_prog: Vec<Vec<Stmt>> = Vec::new();
    let input = Input::Mem(std::io::Cursor::new(bytes.to_vec()));
    let opts = ParseOptions::for_dialect(dialect);
    let index = stream::scan(
        input,
        bytes.len() as u64,
        path,
        0,
        dialect,
        &opts,
        chunk_ops,
        &mut |p, s| {
            while by_prog.len() <= p {
                by_prog.push(Vec::new());
            }
            by_prog[p].push(s.clone());
        },
        None,
    )
    .ok()?;
    let programs = index
        .programs
        .iter()
        .map(|pi| Program { body: by_prog.get(pi.raw).cloned().unwrap_or_default(), ..pi.program.clone() })
        .collect();
    Some(Streamed { unit: Unit { dialect, file: 0, programs }, index })
}

fn whole(path: &Path, bytes: &[u8]) -> (SourceDb, nctrans::dialect::Parsed, Dialect) {
    let mut db = SourceDb::new();
    let name = path.to_string_lossy().to_string();
    let loaded = nctrans::load(&mut db, &name, bytes, None);
    let dialect = nctrans::detect_dialect(&name, &db.get(loaded.file).text);
    let parsed = nctrans::parse(&db, loaded.file, dialect, &ParseOptions::for_dialect(dialect));
    (db, parsed, dialect)
}

fn codes(d: &[nctrans::diag::Diagnostic]) -> Vec<&'static str> {
    let mut v: Vec<_> = d.iter().map(|d| d.code).collect();
    v.sort();
    v
}

#[test]
fn streamed_ir_is_the_whole_file_ir_on_every_corpus_program() {
    let mut compared = 0;
    for f in corpus_files() {
        let bytes = std::fs::read(&f).expect("read");
        let (_, parsed, dialect) = whole(&f, &bytes);
        let utf8 = std::str::from_utf8(&bytes).is_ok() && !bytes.contains(&0);
        for chunk in [1, 2, 5, 4096] {
            let Some(s) = stream_unit(&f, &bytes, dialect, chunk) else {
                assert!(
                    !utf8 || nctrans::read::binary_garbage(&String::from_utf8_lossy(&bytes)).is_some(),
                    "{}: UTF-8 but not streamable",
                    f.display()
                );
                continue;
            };
            let errors = nctrans::diag::has_errors(&parsed.diags);
            assert_eq!(nctrans::diag::has_errors(&s.index.diags), errors, "{}: errors differ", f.display());
            if errors {
                continue;
            }
            assert_eq!(codes(&s.index.diags), codes(&parsed.diags), "{}", f.display());
            assert_eq!(
                nctrans::ir::dump::dump(&s.unit),
                nctrans::ir::dump::dump(&parsed.unit),
                "{} (chunks of {chunk})",
                f.display()
            );
            assert_eq!(s.index.blocks as usize, nctrans::ir::visit::count_blocks(&parsed.unit), "{}", f.display());
            compared += 1;
        }
    }
    assert!(compared > 100, "only {compared} comparisons");
}

/// Events as text with `@line`; lines from `line_of`.
struct Lines<'a> {
    out: Vec<String>,
    line_of: Box<dyn Fn(Origin) -> Option<usize> + 'a>,
}

impl TraceSink for Lines<'_> {
    fn event(&mut self, ev: &eval::Event, origin: Origin) {
        let mut l = trace::text_line(ev);
        if let Some(n) = (self.line_of)(origin) {
            l.push_str(&format!("  @{n}"));
        }
        self.out.push(l);
    }
}

/// Runs a file in memory and streamed (chunks of `chunk_ops`); returns both traces.
fn both_runs(path: &Path, chunk_ops: usize, max_steps: u64) -> Option<(Vec<String>, Vec<String>, u64)> {
    let bytes = std::fs::read(path).ok()?;
    let (mut db, parsed, dialect) = whole(path, &bytes);
    if !parsed.diags.is_empty() {
        return None;
    }
    let text = db.get(0).text.clone();
    let inputs = eval::header_inputs(&text).ok()?;
    let opts = RunOptions { max_steps, inputs, ..Default::default() };
    let src = db.get(0).clone();
    let mut mem = Lines { out: vec![], line_of: Box::new(move |o| (o.file == 0).then(|| src.line_col(o.span.lo).0)) };
    let o1 = eval::run(&mut db, &parsed.unit, &mut eval::DirCallees { semantics: None }, &opts, &mut mem);

    let mut db2 = SourceDb::new();
    let file = db2.add(path.to_string_lossy().to_string(), String::new());
    let (input, size) = stream::open(path).ok()?;
    let popts = ParseOptions::for_dialect(dialect);
    let index = stream::scan(input, size, path, file, dialect, &popts, chunk_ops, &mut |_, _| {}, None).ok()?;
    let from_header = eval::header_inputs(&index.header).ok()?;
    assert_eq!(format!("{from_header:?}"), format!("{:?}", opts.inputs), "{}", path.display());
    let pager = Rc::new(Pager::new(Arc::new(index)));
    let p2 = Rc::clone(&pager);
    let mut st =
        Lines { out: vec![], line_of: Box::new(move |o| (o.file == 0).then(|| p2.line_of(o.span.lo)).flatten()) };
    let o2 = eval::run_stream(&mut db2, pager.clone(), &mut eval::DirCallees { semantics: None }, &opts, &mut st);
    assert_eq!(o1.ending, o2.ending, "{}", path.display());
    assert_eq!(o1.steps, o2.steps, "{}", path.display());
    assert_eq!(codes(&o1.diags), codes(&o2.diags), "{}", path.display());
    // Pages read beyond one read per chunk: re-reading for jumps and loops.
    let chunks: usize = pager.index().programs.iter().map(|p| p.chunks.len()).sum();
    let reads = (*pager.reads.borrow()).saturating_sub(chunks as u64);
    Some((mem.out, st.out, reads))
}

#[test]
fn streamed_runs_give_the_in_memory_trace_on_every_corpus_program() {
    let mut ran = 0;
    for f in corpus_files().into_iter().filter(|f| f.starts_with(root().join("corpus/in"))) {
        let rel = f.strip_prefix(root()).unwrap_or(&f).to_path_buf();
        for chunk in [1, 3, 4096] {
            let Some((a, b, _)) = both_runs(&rel, chunk, 20_000) else { continue };
            assert_eq!(a, b, "{} (chunks of {chunk})", rel.display());
            ran += 1;
        }
    }
    assert!(ran > 100, "only {ran} runs compared");
}

#[test]
fn loops_and_backward_jumps_across_many_chunks() {
    let dir = root().join("target/stream-tests");
    std::fs::create_dir_all(&dir).expect("dir");
    // FANUC: a WHILE loop whose body spans chunks, GOTO back over thousands of blocks,
    // N numbers on every block (one run), a subprogram in the same file.
    let mut f = String::from("%\nO1000 (STREAM)\n#1=0\nN1 G0 X0 Y0\n");
    f.push_str("F500.\nWHILE[#1 LT 3]DO1\n");
    for i in 0..300 {
        f.push_str(&format!("N{} G1 X{}. Y[#1*{}]\n", 10 + i * 10, i, i % 7));
    }
    f.push_str("#1=#1+1\nEND1\n");
    for i in 0..40 {
        f.push_str(&format!("G1 Z-{i}.\n"));
    }
    f.push_str("#2=#2+1\nIF[#2 LT 2]GOTO1\nM98 P2000\nM30\nO2000\nG1 Z-1.\nM99\n%\n");
    let fanuc = dir.join("loops.nc");
    std::fs::write(&fanuc, &f).expect("write");
    // Siemens: GOTOB to a label far above, FOR and REPEAT across chunks.
    let mut s = String::from("DEF INT KCNT\nR1=0\nF500\nTOP:\nFOR KCNT=1 TO 2\n");
    for i in 0..200 {
        s.push_str(&format!("N{} G1 X{} Y=R1+KCNT\n", i + 1, i));
    }
    s.push_str("ENDFOR\n");
    for i in 0..40 {
        s.push_str(&format!("G1 Z-{i}\n"));
    }
    s.push_str("R1=R1+1\nIF R1<3 GOTOB TOP\nSTART:\nG0 Z5\nREPEAT START P=2\nM30\n");
    let sie = dir.join("loops.mpf");
    std::fs::write(&sie, &s).expect("write");
    for path in [fanuc, sie] {
        for chunk in [1, 7, 64, 4096] {
            let (a, b, reads) = both_runs(&path, chunk, 1_000_000).expect("runs");
            assert!(a.len() > 800, "{} events", a.len());
            assert_eq!(a, b, "{} chunks of {chunk}", path.display());
            if chunk == 7 {
                assert!(reads > 3, "{} re-read {reads} pages", path.display());
            }
        }
    }
}

/// Mutated corpus files through the streaming path (scan, then a streamed run at small
/// chunks): no panic, and a file has errors in the stream exactly when it has them whole.
#[test]
fn mutated_programs_stream_without_panics() {
    let dir = root().join("target/stream-tests/mutated");
    std::fs::create_dir_all(&dir).expect("dir");
    let nasty = b"()[]#=;:/%\r\n\t -+*.,0123456789ENOGXRIFDWHLPAB_\xEF\xBC\x00";
    let mut seed = 0x2545_F491_4F6C_DD1Du64;
    let mut next = move |n: usize| {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed % n.max(1) as u64) as usize
    };
    let mut count = 0;
    for f in corpus_files() {
        let Ok(base) = std::fs::read(&f) else { continue };
        for k in 0..6 {
            let mut b = base.clone();
            match k % 3 {
                0 => b.truncate(next(b.len() + 1)),
                1 => {
                    for _ in 0..3 {
                        if !b.is_empty() {
                            let i = next(b.len());
                            b[i] = nasty[next(nasty.len())];
                        }
                    }
                }
                _ => {
                    let i = next(b.len() + 1);
                    let piece: Vec<u8> = b[i..].iter().take(200).copied().collect();
                    b.splice(i..i, piece);
                }
            }
            let ext = f.extension().and_then(|e| e.to_str()).unwrap_or("nc");
            let path = dir.join(format!("m{count}.{ext}"));
            std::fs::write(&path, &b).expect("write");
            count += 1;
            let (_, parsed, dialect) = whole(&path, &b);
            let Some(s) = stream_unit(&path, &b, dialect, 2) else { continue };
            assert_eq!(
                nctrans::diag::has_errors(&s.index.diags),
                nctrans::diag::has_errors(&parsed.diags),
                "{} ({})",
                path.display(),
                f.display()
            );
            if parsed.diags.is_empty() {
                if let Some((a, b, _)) = both_runs(&path, 2, 5_000) {
                    assert_eq!(a, b, "{} ({})", path.display(), f.display());
                }
            }
        }
    }
    assert!(count > 500, "{count} mutations");
}

/// A file whose only lines after the header are separators (comments, NC250) holds no
/// program: the stream reports NC145 as the whole-file parse does.
#[test]
fn a_file_of_only_separator_lines_is_program_less_when_streamed_too() {
    let dir = root().join("target/stream-tests");
    std::fs::create_dir_all(&dir).expect("dir");
    let path = dir.join("separators-only.nc");
    let b = b"%\nO1203 (TEMPLATE)\n* * * * * * * \n=====\n%\n";
    std::fs::write(&path, b).expect("write");
    let (_, parsed, dialect) = whole(&path, b);
    assert!(codes(&parsed.diags).contains(&"NC145"), "{:?}", codes(&parsed.diags));
    let s = stream_unit(&path, b, dialect, 2).expect("streams");
    assert_eq!(codes(&s.index.diags), codes(&parsed.diags));
}

/// The command line: `--stream` gives the same output as reading whole (summary, traces
/// in both formats, check verdicts), and a run-time warning of a streamed file is rendered
/// with its line read from the file.
#[test]
fn cli_streams_with_the_same_output() {
    let bin = env!("CARGO_BIN_EXE_nctrans");
    let run = |args: &[&str]| {
        let o = std::process::Command::new(bin).args(args).output().expect("runs");
        (
            o.status.code(),
            String::from_utf8_lossy(&o.stdout).to_string(),
            String::from_utf8_lossy(&o.stderr).to_string(),
        )
    };
    let files =
        ["corpus/in/fanuc/bare-do-loop.nc", "corpus/in/sinumerik/while-endwhile.mpf", "corpus/in/fanuc/block-skip.nc"];
    let mut compared = 0;
    for f in files {
        let p = root().join(f);
        if !p.exists() {
            continue;
        }
        let p = p.to_string_lossy().to_string();
        for args in [vec!["parse", "--summary"], vec!["run", "--format", "jsonl"], vec!["run"]] {
            let mut a = args.clone();
            a.push(&p);
            let whole = run(&a);
            a.push("--stream");
            assert_eq!(run(&a), whole, "{args:?} {f}");
            compared += 1;
        }
        let whole = run(&["check", &p, &p]);
        assert_eq!(run(&["check", "--stream", &p, &p]), whole, "check {f}");
    }
    assert!(compared >= 3, "no corpus file found");
    let dir = root().join("target/stream-tests");
    std::fs::create_dir_all(&dir).expect("dir");
    let long = dir.join("long.mpf");
    let mut text = String::from("G0 X0 F100\n");
    for i in 0..300 {
        text.push_str(&format!("G1 X{i}\n"));
    }
    std::fs::write(&long, text).expect("write");
    let long_s = long.to_string_lossy().to_string();
    let whole = run(&["--to", "fanuc", &long_s]);
    assert_eq!(whole.0, Some(0), "{}", whole.2);
    assert_eq!(run(&["--to", "fanuc", "--stream", &long_s]), whole, "streamed translation to stdout");
    let (code, _, err) = run(&["run", "--stream", "--quiet", "--max-steps", "200", &long.to_string_lossy()]);
    assert_eq!(code, Some(4));
    assert!(err.contains("NC408") && err.contains("long.mpf:201:1") && err.contains("G1 X199"), "{err}");
}
