//! The trace writer (`WriterSink`: lines gathered in a 64 KiB chunk, grid moves formatted
//! from their integers in place) against a reference writer: one `write_all` per line,
//! moves written here with `push_num_std` (the number form's definition through
//! `core::fmt`, sharing no table with the writer), other events by `text_line` /
//! `json_line`. Every corpus program and generated
//! CAM programs (both dialects, in memory and streamed, traces far longer than a chunk)
//! must give the same bytes; a failing output must still be reported.

use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::eval::numfmt::push_num_std;
use nctrans::eval::trace::{json_line, text_line, Format, GridMove, Origin, WriterSink, AXES, WRITE_CHUNK};
use nctrans::eval::{self, Event, RunOptions, TraceSink};
use nctrans::span::SourceDb;
use std::fmt::Write as _;
use std::io::{self, Write};
use std::path::{Path, PathBuf};
#[path = "support/rng.rs"]
mod rng;
use rng::Rng;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

type LineOf = Box<dyn Fn(Origin) -> Option<usize>>;

/// The writer before the chunk: each event's line written by itself.
struct Reference {
    out: Vec<u8>,
    format: Format,
    line_of: LineOf,
}

/// A move as the trace spec writes it, numbers by `push_num_std`.
fn move_line(ev: &Event, json: bool, line: Option<usize>) -> Option<String> {
    let Event::Move { rapid, to, f, probe } = ev else { return None };
    let mode = if *rapid { "rapid" } else { "linear" };
    let axes = to.iter().enumerate().filter_map(|(i, x)| x.map(|x| (AXES[i], x)));
    let mut s = String::new();
    if json {
        let _ = write!(s, "{{\"ev\":\"move\",\"mode\":\"{mode}\",\"to\":{{");
        for (k, (a, x)) in axes.enumerate() {
            let _ = write!(s, "{}\"{a}\":", if k > 0 { "," } else { "" });
            push_num_std(&mut s, x);
        }
        s.push_str("},\"f\":");
        match f {
            Some(f) => push_num_std(&mut s, *f),
            None => s.push_str("null"),
        }
        if *probe {
            s.push_str(",\"probe\":true");
        }
        if let Some(l) = line {
            let _ = write!(s, ",\"line\":{l}");
        }
        s.push('}');
    } else {
        let _ = write!(s, "move {mode}");
        for (a, x) in axes {
            let _ = write!(s, " {a}=");
            push_num_std(&mut s, x);
        }
        s.push_str(" f=");
        match f {
            Some(f) => push_num_std(&mut s, *f),
            None => s.push('-'),
        }
        if *probe {
            s.push_str(" probe");
        }
    }
    Some(s)
}

impl Reference {
    fn line(&mut self, ev: &Event, origin: Origin) {
        let line = (self.line_of)(origin);
        let mut s = match self.format {
            Format::Jsonl => move_line(ev, true, line).unwrap_or_else(|| json_line(ev, line)),
            Format::Text => {
                let mut s = move_line(ev, false, None).unwrap_or_else(|| text_line(ev));
                if let Some(l) = line {
                    let _ = write!(s, "  @{l}");
                }
                s
            }
        };
        s.push('\n');
        self.out.write_all(s.as_bytes()).expect("a Vec takes every write");
    }
}

/// An output that counts its writes (the chunk must reach it in few of them).
#[derive(Default)]
struct Counted {
    bytes: Vec<u8>,
    writes: usize,
}

impl Write for Counted {
    fn write(&mut self, b: &[u8]) -> io::Result<usize> {
        self.writes += 1;
        self.bytes.extend_from_slice(b);
        Ok(b.len())
    }
    fn flush(&mut self) -> io::Result<()> {
        Ok(())
    }
}

/// Both writers, fed the same events: the new one gets grid moves as such (the fast
/// path's way), the reference their events.
struct Tee {
    new: WriterSink<'static, Counted>,
    old: Reference,
    grid_moves: usize,
}

impl TraceSink for Tee {
    fn event(&mut self, ev: &Event, origin: Origin) {
        self.new.event(ev, origin);
        self.old.line(ev, origin);
    }
    fn grid_move(&mut self, m: &GridMove, origin: Origin) {
        self.grid_moves += 1;
        self.new.grid_move(m, origin);
        self.old.line(&m.event(), origin);
    }
    fn finish(&mut self) {
        self.new.finish();
    }
}

/// Line numbers for a trace: the real ones of the text (`text`), or made up from the
/// span so that they jump about, grow long and go missing (as callee lines do).
fn line_of(text: Option<String>, file: usize) -> LineOf {
    match text {
        Some(t) => {
            let starts: Vec<usize> = t.bytes().enumerate().filter(|&(_, c)| c == b'\n').map(|(i, _)| i).collect();
            Box::new(move |o: Origin| (o.file == file).then(|| starts.partition_point(|&i| i < o.span.lo as usize) + 1))
        }
        None => Box::new(|o: Origin| {
            let lo = o.span.lo as usize;
            (lo % 11 != 3).then_some(if lo.is_multiple_of(5) { lo * 1_000_003 + 999 } else { lo / 9 })
        }),
    }
}

fn tee(format: Format, text: Option<&str>, file: usize) -> Tee {
    let own = |t: Option<&str>| t.map(str::to_string);
    Tee {
        new: WriterSink::new(Counted::default(), format, line_of(own(text), file)),
        old: Reference { out: Vec::new(), format, line_of: line_of(own(text), file) },
        grid_moves: 0,
    }
}

/// Asserts the two traces are the same bytes and came in few writes; returns the number
/// of grid moves and the trace's length.
fn compare(what: &str, t: &Tee) -> (usize, usize) {
    assert!(t.new.error.is_none(), "{what}: {:?}", t.new.error);
    let (new, old) = (&t.new.out.bytes, &t.old.out);
    if new != old {
        let at = new.iter().zip(old).position(|(a, b)| a != b).unwrap_or(new.len().min(old.len()));
        let from = old[..at].iter().rposition(|&c| c == b'\n').map_or(0, |i| i + 1);
        let show = |b: &[u8]| String::from_utf8_lossy(&b[from.min(b.len())..(from + 160).min(b.len())]).into_owned();
        panic!("{what}: the writers differ at byte {at}\n  new: {}\n  old: {}", show(new), show(old));
    }
    let chunks = new.len() / WRITE_CHUNK + 1;
    assert!(t.new.out.writes <= 2 * chunks + 1, "{what}: {} writes for {} bytes", t.new.out.writes, new.len());
    (t.grid_moves, new.len())
}

/// Runs the file in memory with both writers, in each format and line numbering.
fn run_mem(path: &Path) -> (usize, usize) {
    let Ok(bytes) = std::fs::read(path) else { return (0, 0) };
    let mut total = (0, 0);
    for (format, real_lines) in [(Format::Text, true), (Format::Text, false), (Format::Jsonl, true)] {
        let mut db = SourceDb::new();
        let name = path.to_string_lossy().replace('\\', "/");
        let loaded = nctrans::load(&mut db, &name, &bytes, None);
        let text = db.get(loaded.file).text.clone();
        let dialect = nctrans::detect_dialect(&name, &text);
        let parsed = nctrans::parse(&db, loaded.file, dialect, &ParseOptions::for_dialect(dialect));
        if nctrans::diag::has_errors(&parsed.diags) {
            return total;
        }
        let inputs = eval::header_inputs(&text).unwrap_or_default();
        let opts = RunOptions { max_steps: 200_000, inputs, ..Default::default() };
        let mut sink = tee(format, real_lines.then_some(text.as_str()), loaded.file);
        eval::run(&mut db, &parsed.unit, &mut eval::DirCallees { semantics: None }, &opts, &mut sink);
        let (g, n) = compare(&format!("{} ({format:?}, real lines {real_lines})", path.display()), &sink);
        total = (total.0 + g, total.1 + n);
    }
    total
}

/// Runs the file streamed, the writer taking the lines the re-read gives its blocks.
fn run_streamed(path: &Path, dialect: Dialect) -> Option<(usize, usize)> {
    let text = std::fs::read_to_string(path).ok()?;
    let opts = ParseOptions::for_dialect(dialect);
    let ix = nctrans::stream::scan_index_path(path, 0, dialect, &opts, None).ok()?;
    let mut db = SourceDb::new();
    let file = db.add(path.display().to_string(), String::new());
    let run = RunOptions { max_steps: 1_000_000, ..Default::default() };
    let runner = nctrans::stream::runner(std::sync::Arc::new(ix), Box::new(eval::DirCallees { semantics: None }), run);
    let mut sink = tee(Format::Text, Some(&text), file);
    sink.new.block_lines = Some(file);
    runner.run(&mut db, &mut sink);
    Some(compare(&format!("{} streamed", path.display()), &sink))
}

#[test]
fn corpus_traces_are_written_as_the_reference_writes_them() {
    let (mut count, mut moves) = (0, 0);
    for top in ["corpus/in", "corpus/err"] {
        for d in ["fanuc", "sinumerik"] {
            let Ok(rd) = std::fs::read_dir(root().join(top).join(d)) else { continue };
            let mut files: Vec<_> = rd.filter_map(|e| e.ok()).map(|e| e.path()).filter(|p| p.is_file()).collect();
            files.sort();
            for f in files {
                moves += run_mem(&f).0;
                count += 1;
            }
        }
    }
    if root().join("corpus/in").exists() {
        assert!(count > 50, "only {count} corpus programs ran");
        assert!(moves > 200, "only {moves} grid moves");
    }
}

/// A coordinate as CAM output has it: mostly on the 0.001 grid, of every integer length
/// the writer has a way for (up to 999999.999), sometimes off it (the general way).
fn coord(r: &mut Rng) -> String {
    let sign = if r.chance(40) { "-" } else { "" };
    let int = r.next() % [1, 10, 100, 1000, 10_000, 100_000, 1_000_000][r.index(7)];
    match r.below(10) {
        0 => format!("{sign}{int}"),
        1 => format!("{sign}{int}.{:05}", r.below(100_000)),
        2 => format!("{sign}{int}.{}", r.below(10)),
        3 => format!("{sign}{int}.{:02}", r.below(100)),
        _ => format!("{sign}{int}.{:03}", r.below(1000)),
    }
}

/// A CAM program of `blocks` straight moves (any axes, rapids, feeds changing or not,
/// N numbers, now and then a block the fast path leaves to the general one).
fn cam(r: &mut Rng, fanuc: bool, blocks: usize) -> String {
    cam_with(r, fanuc, blocks, false)
}

/// [`cam`]; `held`: as 2D passes are, X and Y nearly every block and Z and F seldom
/// (the writer copies a value repeated from the line before instead of formatting it).
fn cam_with(r: &mut Rng, fanuc: bool, blocks: usize, held: bool) -> String {
    // Siemens: every axis in the feed group, so that a block moving U, V or W alone has a
    // feed (under the default group it is NC662), as FANUC's F runs along every axis.
    let mut t = String::from(if fanuc {
        "%\nO1000\nG21 G17 G90 G94 F500.\n"
    } else {
        "G71 G17 G90 G94 F500\nFGROUP(X,Y,Z,A,B,C,U,V,W)\n"
    });
    let mut n = 0;
    for _ in 0..blocks {
        if r.chance(20) {
            n += 10;
            let _ = write!(t, "N{n} ");
        }
        t.push_str(if r.chance(10) { "G0 " } else { "G1 " });
        for a in ["X", "Y", "Z", "A", "B", "C", "U", "V", "W"] {
            let chance = match (held, a) {
                (true, "X" | "Y") => 90,
                (true, "Z") => 3,
                (true, _) => 1,
                (false, "X" | "Y" | "Z") => 80,
                (false, _) => 5,
            };
            if r.chance(chance) {
                let c = coord(r);
                let c = if fanuc && !c.contains('.') { format!("{c}.") } else { c };
                let _ = write!(t, "{a}{c} ");
            }
        }
        if r.chance(if held { 4 } else { 30 }) {
            let f = r.below(20_000);
            let _ = if r.chance(80) { write!(t, "F{f}.") } else { write!(t, "F{f}.{}", r.below(1000)) };
        }
        if r.chance(2) {
            t.push_str(if fanuc { "\nM8" } else { "\nMSG(\"a \\\"note\\\"\")" });
        }
        t.push('\n');
    }
    t.push_str(if fanuc { "M30\n%\n" } else { "M30\n" });
    t
}

#[test]
fn cam_traces_across_many_chunks_are_written_as_the_reference_writes_them() {
    let dir = root().join("target/trace-writer-tests");
    std::fs::create_dir_all(&dir).expect("scratch dir");
    let mut r = Rng(4242);
    let (mut moves, mut bytes, mut streamed) = (0, 0, 0);
    for i in 0..12 {
        let fanuc = i % 2 == 0;
        let text = cam_with(&mut r, fanuc, 2000 + 1000 * (i % 8), i >= 8);
        let path = dir.join(if fanuc { "cam.nc" } else { "cam.mpf" });
        std::fs::write(&path, &text).expect("scratch file");
        let (g, n) = run_mem(&path);
        moves += g;
        bytes += n;
        let dialect = if fanuc { Dialect::Fanuc } else { Dialect::Sinumerik };
        if let Some((g, _)) = run_streamed(&path, dialect) {
            streamed += 1;
            moves += g;
        }
    }
    assert!(moves > 60_000, "only {moves} grid moves");
    assert!(bytes > 20 * WRITE_CHUNK, "only {bytes} bytes: the chunk must fill many times");
    assert!(streamed >= 6, "only {streamed} programs streamed");
}

/// Takes `room` bytes, then fails as a full disk does.
struct Full {
    bytes: Vec<u8>,
    room: usize,
}

impl Write for Full {
    fn write(&mut self, b: &[u8]) -> io::Result<usize> {
        if self.bytes.len() + b.len() > self.room {
            return Err(io::Error::other("no space left"));
        }
        self.bytes.extend_from_slice(b);
        Ok(b.len())
    }
    fn flush(&mut self) -> io::Result<()> {
        Ok(())
    }
}

#[test]
fn a_failing_output_is_reported_and_nothing_is_written_after_it() {
    let mut r = Rng(7);
    let text = cam(&mut r, false, 6000);
    let dir = root().join("target/trace-writer-tests");
    std::fs::create_dir_all(&dir).expect("scratch dir");
    let path = dir.join("full.mpf");
    std::fs::write(&path, &text).expect("scratch file");
    let mut whole = None;
    for room in [usize::MAX, 0, 100, WRITE_CHUNK - 1, WRITE_CHUNK, 3 * WRITE_CHUNK + 5] {
        let mut db = SourceDb::new();
        let file = db.add("full.mpf", text.clone());
        let parsed = nctrans::parse(&db, file, Dialect::Sinumerik, &ParseOptions::for_dialect(Dialect::Sinumerik));
        let mut sink = WriterSink::new(Full { bytes: Vec::new(), room }, Format::Text, line_of(None, file));
        let opts = RunOptions::default();
        eval::run(&mut db, &parsed.unit, &mut eval::NoCallees, &opts, &mut sink);
        let Some(all) = &whole else {
            assert!(sink.error.is_none());
            assert!(sink.out.bytes.len() > 4 * WRITE_CHUNK);
            whole = Some(sink.out.bytes);
            continue;
        };
        let err = sink.error.as_ref().map(|e| e.to_string());
        assert_eq!(err.as_deref(), Some("no space left"), "room {room}");
        assert!(all.starts_with(&sink.out.bytes), "room {room}: what was written is the trace's start");
        assert!(sink.out.bytes.len() <= room);
    }
}
