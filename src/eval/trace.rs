//! The canonical trace (`docs/trace-format.md`): events, their origin, the sink they
//! stream into, and the text and jsonl writers.

use crate::span::{FileId, Span};
use std::io::{self, Write};

/// The axes a trace position may hold, in output order.
pub const AXES: [char; 9] = ['X', 'Y', 'Z', 'A', 'B', 'C', 'U', 'V', 'W'];

/// A position: `None` for an axis never positioned.
pub type Axes = [Option<f64>; 9];

/// Index of an axis letter in [`AXES`].
#[inline]
pub fn axis_index(c: u8) -> Option<usize> {
    // A match, not a search of `AXES`: asked for every word of every block.
    Some(match c {
        b'X' => 0,
        b'Y' => 1,
        b'Z' => 2,
        b'A' => 3,
        b'B' => 4,
        b'C' => 5,
        b'U' => 6,
        b'V' => 7,
        b'W' => 8,
        _ => return None,
    })
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Plane {
    XY,
    ZX,
    YZ,
}

impl Plane {
    pub fn name(self) -> &'static str {
        match self {
            Plane::XY => "XY",
            Plane::ZX => "ZX",
            Plane::YZ => "YZ",
        }
    }
    /// The two axes of the plane (first, second) and the axis normal to it, in the order
    /// that keeps the right-hand rule (G18 is Z then X).
    pub fn axes(self) -> (usize, usize, usize) {
        match self {
            Plane::XY => (0, 1, 2),
            Plane::ZX => (2, 0, 1),
            Plane::YZ => (1, 2, 0),
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub enum ToolId {
    Number(f64),
    Name(String),
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpindleDir {
    Cw,
    Ccw,
    Stop,
}

impl SpindleDir {
    pub fn name(self) -> &'static str {
        match self {
            SpindleDir::Cw => "cw",
            SpindleDir::Ccw => "ccw",
            SpindleDir::Stop => "stop",
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub enum Event {
    Move {
        rapid: bool,
        to: Axes,
        f: Option<f64>,
        /// A probing move (FANUC G31, Siemens MEAS=/MEAW=): `probe` in the text form,
        /// `"probe": true` in jsonl (trace format v2).
        probe: bool,
    },
    Arc {
        cw: bool,
        plane: Plane,
        to: Axes,
        /// The two plane axes' centre coordinates, in the plane's axis order.
        center: [(usize, f64); 2],
        f: Option<f64>,
    },
    Dwell {
        seconds: f64,
    },
    Tool {
        tool: ToolId,
    },
    Spindle {
        rpm: f64,
        dir: SpindleDir,
    },
    Coolant {
        on: bool,
    },
    Stop {
        optional: bool,
        message: Option<String>,
    },
    Message {
        text: String,
    },
    /// One line of text output (an nctrans extension of v2): FANUC `DPRNT[…]`, Siemens
    /// `WRITE(err, "file", text)`; `text` is the line as produced, without its line end.
    Print {
        text: String,
    },
    Alarm {
        number: i64,
        message: String,
    },
    End {
        code: &'static str,
        steps: u64,
    },
    Limit {
        steps: u64,
    },
    /// One hole of a drilling cycle (format v2; boxed: rare and large).
    Cycle(Box<crate::ir::cycle::Hole>),
    /// A work-offset selection (format v2): 0 none, 1..6 G54..G59 (Siemens G54..G57,
    /// G505, G506), 7.. FANUC G54.1 P1.. / Siemens G507...
    WorkOffset {
        n: u32,
    },
    /// A reference-point return (format v2; boxed: rare).
    Home(Box<HomeEv>),
    /// A change of tool length or cutter radius compensation (format v2; boxed: rare).
    Comp(Box<CompEv>),
    /// A program's write of tool offset data (Siemens `$TC_DP3/6/12/15[t,d]`, FANUC memory C
    /// `#10001+`..`#13001+`): the register, which value, the value as written. An extension
    /// of format v2 (docs/trace-format.md): the `comp` event names a register, so what a
    /// program writes into one must be in the trace for a translation to be proven.
    ToolData(Box<ToolDataEv>),
}

/// A compensation register as each control names it: FANUC the H or D number, Siemens
/// `"T.D"` (the tool as in `tool` events, then the cutting edge).
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum CompReg {
    Fanuc(i64),
    Edge(String),
}

/// The side of cutter radius compensation (G41 left, G42 right).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    Left,
    Right,
}

impl Side {
    pub fn name(self) -> &'static str {
        match self {
            Side::Left => "left",
            Side::Right => "right",
        }
    }
}

/// The fields of a `comp` event: the length register in force and the radius side and
/// register, `None` for off.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CompEv {
    pub length: Option<CompReg>,
    pub radius: Option<(Side, CompReg)>,
}

/// Which value of a compensation register a `tool_data` event writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ToolField {
    LengthGeometry,
    LengthWear,
    RadiusGeometry,
    RadiusWear,
}

impl ToolField {
    pub fn name(self) -> &'static str {
        match self {
            ToolField::LengthGeometry => "length",
            ToolField::LengthWear => "length_wear",
            ToolField::RadiusGeometry => "radius",
            ToolField::RadiusWear => "radius_wear",
        }
    }

    /// A length value (paired with `comp` length registers), else a radius one.
    pub fn is_length(self) -> bool {
        matches!(self, ToolField::LengthGeometry | ToolField::LengthWear)
    }
}

/// The fields of a `tool_data` event.
#[derive(Clone, Debug, PartialEq)]
pub struct ToolDataEv {
    pub register: CompReg,
    pub field: ToolField,
    pub value: f64,
}

/// The fields of a `home` event.
#[derive(Clone, Debug, PartialEq)]
pub struct HomeEv {
    /// The homed axes ([`AXES`] indices), in axis order.
    pub axes: Vec<u8>,
    /// Where the approach starts on each homed axis: the intermediate point (FANUC G28's
    /// axis words; the current position when the tool goes straight, as G74 does).
    pub via: Axes,
    /// 1: reference point; 2..4: second to fourth reference point (G30 Pn, G75 FP=n-1).
    pub point: u8,
    /// Where the tool stands after the return, as the next move's positions show it: not
    /// written or compared (the checker's `DeferLength` follows Z through it).
    pub at: Axes,
}

impl Event {
    /// The event's kind name as written in the trace (`"move"`, `"arc"`, …).
    pub fn kind(&self) -> &'static str {
        match self {
            Event::Move { .. } => "move",
            Event::Arc { .. } => "arc",
            Event::Dwell { .. } => "dwell",
            Event::Tool { .. } => "tool",
            Event::Spindle { .. } => "spindle",
            Event::Coolant { .. } => "coolant",
            Event::Stop { .. } => "stop",
            Event::Message { .. } => "message",
            Event::Print { .. } => "print",
            Event::Alarm { .. } => "alarm",
            Event::End { .. } => "end",
            Event::Limit { .. } => "limit",
            Event::Cycle(_) => "cycle",
            Event::WorkOffset { .. } => "work_offset",
            Event::Home(_) => "home",
            Event::Comp(_) => "comp",
            Event::ToolData(_) => "tool_data",
        }
    }
}

#[path = "trace_sink.rs"]
mod sink;
pub use sink::{GridMove, NullSink, Origin, TraceSink, VecSink};

#[path = "trace_json.rs"]
mod json;
pub use json::{json_line, write_json, write_json_bytes};

/// Appends a number in the trace's form (see [`super::numfmt`]) without allocating.
pub use super::numfmt::push_num;

/// What the writers append to: a byte buffer with the `String` methods they use, without
/// a `String`'s UTF-8 checks per number (everything written is UTF-8: ASCII and whole
/// `str`s).
struct TextBuf<'b>(&'b mut Vec<u8>);

impl TextBuf<'_> {
    fn push_str(&mut self, s: &str) {
        self.0.extend_from_slice(s.as_bytes());
    }

    fn push(&mut self, c: char) {
        if c.is_ascii() {
            self.0.push(c as u8);
        } else {
            self.push_str(c.encode_utf8(&mut [0; 4]));
        }
    }
}

fn push_num_b(out: &mut TextBuf, x: f64) {
    super::numfmt::put_num(out.0, x);
}

/// Appends the bytes written by `f` to `s` (always UTF-8, see [`TextBuf`]).
fn to_string_buf(s: &mut String, f: impl FnOnce(&mut TextBuf)) {
    let mut v = Vec::with_capacity(64);
    f(&mut TextBuf(&mut v));
    s.push_str(&String::from_utf8_lossy(&v));
}

fn axes_text(out: &mut TextBuf, to: &Axes) {
    for (i, v) in to.iter().enumerate() {
        if let Some(x) = v {
            out.0.extend_from_slice(&[b' ', AXES[i] as u8, b'=']);
            push_num_b(out, *x);
        }
    }
}

fn push_opt(out: &mut TextBuf, f: Option<f64>, none: &str) {
    match f {
        Some(x) => push_num_b(out, x),
        None => out.push_str(none),
    }
}

fn push_quoted(o: &mut TextBuf, s: &str) {
    o.push('"');
    for c in s.chars() {
        match c {
            '"' => o.push_str("\\\""),
            '\\' => o.push_str("\\\\"),
            '\n' => o.push_str("\\n"),
            '\r' => o.push_str("\\r"),
            '\t' => o.push_str("\\t"),
            c if (c as u32) < 0x20 => o.push_str(&format!("\\u{:04x}", c as u32)),
            c => o.push(c),
        }
    }
    o.push('"');
}

/// One event as a line of the text form (no newline). Stable: the corpus traces are
/// this form.
pub fn text_line(ev: &Event) -> String {
    let mut v = Vec::with_capacity(64);
    write_text_bytes(&mut v, ev);
    String::from_utf8(v).unwrap_or_else(|e| String::from_utf8_lossy(e.as_bytes()).into_owned())
}

/// Appends the text form of `ev` to `v` (UTF-8).
pub fn write_text_bytes(v: &mut Vec<u8>, ev: &Event) {
    text_form(&mut TextBuf(v), ev);
}

fn text_form(s: &mut TextBuf, ev: &Event) {
    match ev {
        Event::Move { rapid, to, f, probe } => {
            s.push_str(if *rapid { "move rapid" } else { "move linear" });
            axes_text(s, to);
            s.push_str(" f=");
            push_opt(s, *f, "-");
            if *probe {
                s.push_str(" probe");
            }
        }
        Event::Arc { cw, plane, to, center, f } => {
            s.push_str(if *cw { "arc cw " } else { "arc ccw " });
            s.push_str(plane.name());
            axes_text(s, to);
            s.push_str(" center");
            for (i, v) in center {
                s.push(' ');
                s.push(AXES[*i]);
                s.push('=');
                push_num_b(s, *v);
            }
            s.push_str(" f=");
            push_opt(s, *f, "-");
        }
        Event::Dwell { seconds } => {
            s.push_str("dwell ");
            push_num_b(s, *seconds);
        }
        Event::Tool { tool } => {
            s.push_str("tool ");
            match tool {
                ToolId::Number(n) => push_num_b(s, *n),
                ToolId::Name(n) => push_quoted(s, n),
            }
        }
        Event::Spindle { rpm, dir } => {
            s.push_str("spindle ");
            s.push_str(dir.name());
            s.push(' ');
            push_num_b(s, *rpm);
        }
        Event::Coolant { on } => s.push_str(if *on { "coolant on" } else { "coolant off" }),
        Event::Stop { optional, message } => {
            s.push_str(if *optional { "stop optional" } else { "stop" });
            if let Some(m) = message {
                s.push(' ');
                push_quoted(s, m);
            }
        }
        Event::Message { text } => {
            s.push_str("message ");
            push_quoted(s, text);
        }
        Event::Print { text } => {
            s.push_str("print ");
            push_quoted(s, text);
        }
        Event::Alarm { number, message } => {
            s.push_str(&format!("alarm {number} "));
            push_quoted(s, message);
        }
        Event::End { code, steps } => s.push_str(&format!("end {code} steps={steps}")),
        Event::Limit { steps } => s.push_str(&format!("limit steps={steps}")),
        Event::Cycle(h) => s.push_str(&super::cycles::text_form(h)),
        Event::WorkOffset { n } => s.push_str(&format!("work_offset {n}")),
        Event::Home(h) => {
            s.push_str(&format!("home point={} axes=", h.point));
            for &i in &h.axes {
                s.push(AXES[usize::from(i)]);
            }
            s.push_str(" via");
            axes_text(s, &h.via);
        }
        Event::Comp(c) => {
            s.push_str("comp length=");
            match &c.length {
                Some(r) => reg_text(s, r),
                None => s.push_str("off"),
            }
            s.push_str(" radius=");
            match &c.radius {
                Some((side, r)) => {
                    s.push_str(side.name());
                    s.push(':');
                    reg_text(s, r);
                }
                None => s.push_str("off"),
            }
        }
        Event::ToolData(t) => {
            s.push_str("tool_data register=");
            reg_text(s, &t.register);
            s.push_str(" field=");
            s.push_str(t.field.name());
            s.push_str(" value=");
            push_num_b(s, t.value);
        }
    }
}

/// A register in the text form (and in JSON): FANUC a number, Siemens a quoted string.
fn reg_text(s: &mut TextBuf, r: &CompReg) {
    match r {
        CompReg::Fanuc(n) => super::numfmt::put_int(s.0, *n),
        CompReg::Edge(e) => push_quoted(s, e),
    }
}

/// Output format of a streamed trace.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Text,
    Jsonl,
}

/// Bytes a [`WriterSink`] gathers before it hands them to its output in one write.
pub const WRITE_CHUNK: usize = 1 << 16;

/// Room for a grid move line (the longest is under 200 bytes); the chunk has twice this
/// after [`WRITE_CHUNK`], the window [`TraceSink::grid_move`] of [`WriterSink`] writes in.
const LINE_ROOM: usize = 256;

/// Writes each event as it arrives. `line_of` maps an origin to a 1-based line (jsonl
/// `line` field; text form appends `@line`). Write errors are kept and reported once.
///
/// The lines are gathered in a buffer of [`WRITE_CHUNK`] bytes and handed to `out` in
/// one `write_all` each time it fills (a call per line cost more than the line), and at
/// [`TraceSink::finish`], which a run calls at its end: `out` holds the whole trace only
/// after it (read `error` then).
pub struct WriterSink<'a, W: Write> {
    pub out: W,
    pub format: Format,
    pub line_of: Box<dyn Fn(Origin) -> Option<usize> + 'a>,
    pub error: Option<io::Error>,
    /// A file whose grid moves' own lines ([`GridMove::line`], when not 0) are the lines
    /// `line_of` gives for their origins: the writer takes them without asking it (a
    /// streamed run's re-read knows every block's line; the look-up costs a tenth of a
    /// `run`). `None` (the default): always `line_of`.
    pub block_lines: Option<crate::span::FileId>,
    /// Where [`TraceSink::event`] writes a line before it is gathered.
    buf: Vec<u8>,
    /// The gathered lines: `chunk[..used]` (`used <` [`WRITE_CHUNK`] between calls);
    /// 2 × [`LINE_ROOM`] bytes more, so that a grid move is written in place without a check
    /// per byte (kept: clearing it per line would cost more than writing the line).
    chunk: Box<[u8]>,
    used: usize,
    /// The `@line` number [`TraceSink::grid_move`] wrote last and its digits: the next
    /// line is nearly always this one plus one, counted up in the digits.
    last_line: (usize, [u8; 24], usize),
    /// Per axis (and the feed, last): the grid value [`TraceSink::grid_move`] wrote last
    /// and, once repeated, its bytes with their prefix (` X=12.5`, at most 14 of 16; see
    /// `put_cached`): CAM output repeats Z and F from line to line.
    last_text: [(i64, [u8; 16], usize); 10],
}

/// [`WriterSink`]'s `last_text` of nothing written yet (no grid value is `i64::MIN`).
const NO_TEXT: (i64, [u8; 16], usize) = (i64::MIN, [0; 16], 0);

/// Writes line number `l` at `b[i..]` (room for 24 bytes) as `put_int` does, from
/// `last` (the number written before and its digits) when `l` is that number or the next
/// one; `last` becomes `l`. Returns where the digits end.
#[inline(always)]
fn put_line(b: &mut [u8], i: usize, l: usize, last: &mut (usize, [u8; 24], usize)) -> usize {
    let (n, digits, len) = last;
    let counted = if l == *n {
        true
    } else if n.checked_add(1) == Some(l) && *len > 0 {
        // Add one from the last digit: nines become zeros; a number of nines only
        // (a new digit) is written afresh.
        let mut k = *len;
        while k > 0 && digits[k - 1] == b'9' {
            digits[k - 1] = b'0';
            k -= 1;
        }
        if k > 0 {
            digits[k - 1] += 1;
        }
        k > 0
    } else {
        false
    };
    if !counted {
        *len = super::numfmt::put_uint_at(digits, 0, l as u64);
    }
    *n = l;
    b[i..i + 24].copy_from_slice(digits);
    i + *len
}

impl<'a, W: Write> WriterSink<'a, W> {
    pub fn new(out: W, format: Format, line_of: Box<dyn Fn(Origin) -> Option<usize> + 'a>) -> Self {
        WriterSink {
            out,
            format,
            line_of,
            error: None,
            block_lines: None,
            buf: Vec::with_capacity(256),
            chunk: vec![0; WRITE_CHUNK + 2 * LINE_ROOM].into_boxed_slice(),
            used: 0,
            last_line: (0, *b"000000000000000000000000", 1),
            last_text: [NO_TEXT; 10],
        }
    }

    /// Hands the gathered lines to `out` (the first error is kept; nothing is written
    /// after it).
    fn drain(&mut self) {
        let used = std::mem::take(&mut self.used);
        if used == 0 || self.error.is_some() {
            return;
        }
        if let Err(e) = self.chunk.get(..used).map_or(Ok(()), |b| self.out.write_all(b)) {
            self.error = Some(e);
        }
    }

    /// Gathers `bytes` (a whole line) after the lines before it.
    fn gather(&mut self, bytes: &[u8]) {
        if self.used + bytes.len() > WRITE_CHUNK {
            self.drain();
        }
        match self.chunk.get_mut(self.used..self.used + bytes.len()) {
            Some(room) if self.used + bytes.len() <= WRITE_CHUNK => {
                room.copy_from_slice(bytes);
                self.used += bytes.len();
            }
            // A line longer than the chunk (a long message) goes out as it is.
            _ => {
                if self.error.is_none() {
                    if let Err(e) = self.out.write_all(bytes) {
                        self.error = Some(e);
                    }
                }
            }
        }
    }
}

/// Writes `text` (at most 16 bytes, the rest of the 16 written is not counted) at
/// `w[i..]`; returns where it ends. `i` is taken modulo 256 so that the compiler sees
/// every write inside the 512-byte window (a grid move line is under 200 bytes).
#[inline(always)]
fn put_at(w: &mut [u8; 2 * LINE_ROOM], i: usize, text: &[u8; 16], len: usize) -> usize {
    let i = i % LINE_ROOM;
    w[i..i + 16].copy_from_slice(text);
    i + len
}

/// Writes `prefix` (3 bytes) and the grid value `n` at `w[i..]` as [`put_at`] and
/// [`super::numfmt::put_grid`] do; returns where they end. `last`: the value written
/// before and, once it was written twice running, its bytes (length 0: not kept), from
/// which a repeated value is copied, not formatted again. A value that changes from line
/// to line (X and Y of CAM output) is only remembered, not kept: keeping bytes that are
/// not used again cost more than formatting.
#[inline(always)]
fn put_cached(
    w: &mut [u8; 2 * LINE_ROOM],
    i: usize,
    prefix: &[u8; 16],
    n: i64,
    last: &mut (i64, [u8; 16], usize),
) -> usize {
    if last.0 != n {
        last.0 = n;
        last.2 = 0;
        let end = put_at(w, i, prefix, 3);
        return super::numfmt::put_grid(w, end % LINE_ROOM, n);
    }
    if last.2 == 0 {
        // Repeated: formatted where it is kept (the prefix and at most 11 bytes fit in 16).
        last.1 = *prefix;
        last.2 = super::numfmt::put_grid(&mut last.1, 3, n);
    }
    put_at(w, i, &last.1, last.2 % 16)
}

/// `" X="` and the like for every axis, as 16 bytes for [`put_at`].
const AXIS_PREFIX: [[u8; 16]; 9] = {
    let mut t = [[0u8; 16]; 9];
    let mut a = 0;
    while a < 9 {
        t[a][0] = b' ';
        t[a][1] = AXES[a] as u8;
        t[a][2] = b'=';
        a += 1;
    }
    t
};

/// `s` (at most 16 bytes) as 16 bytes for [`put_at`].
const fn text16(s: &[u8]) -> [u8; 16] {
    let mut t = [0u8; 16];
    let mut k = 0;
    while k < s.len() {
        t[k] = s[k];
        k += 1;
    }
    t
}

impl<W: Write> TraceSink for WriterSink<'_, W> {
    fn event(&mut self, ev: &Event, origin: Origin) {
        if self.error.is_some() {
            return;
        }
        let line = (self.line_of)(origin);
        let mut buf = std::mem::take(&mut self.buf);
        buf.clear();
        match self.format {
            Format::Jsonl => write_json_bytes(&mut buf, ev, line),
            Format::Text => {
                write_text_bytes(&mut buf, ev);
                if let Some(l) = line {
                    buf.extend_from_slice(b"  @");
                    super::numfmt::put_int(&mut buf, l as i64);
                }
            }
        }
        buf.push(b'\n');
        self.gather(&buf);
        self.buf = buf;
    }

    fn grid_move(&mut self, m: &GridMove, origin: Origin) {
        if self.format != Format::Text {
            return self.event(&m.event(), origin);
        }
        if self.error.is_some() {
            return;
        }
        let line = match self.block_lines {
            Some(file) if file == origin.file && m.line != 0 => {
                debug_assert_eq!((self.line_of)(origin), Some(m.line as usize), "the line of {origin:?}");
                Some(m.line as usize)
            }
            _ => (self.line_of)(origin),
        };
        // The line `text_form` and `event` write, in one pass, in place after the lines
        // gathered so far: `used < WRITE_CHUNK`, so the window fits in the chunk.
        let used = self.used;
        let Some(Ok(w)) = self.chunk.get_mut(used..used + 2 * LINE_ROOM).map(<&mut [u8; 2 * LINE_ROOM]>::try_from)
        else {
            // Not reached (the chunk has the room); the general way, should it be.
            return self.event(&m.event(), origin);
        };
        const RAPID: [u8; 16] = text16(b"move rapid");
        const LINEAR: [u8; 16] = text16(b"move linear");
        const FEED: [u8; 16] = text16(b" f=");
        const NO_FEED: [u8; 16] = text16(b" f=-");
        const AT: [u8; 16] = text16(b"  @");
        const NL: [u8; 16] = text16(b"\n");
        let mut i = if m.rapid { put_at(w, 0, &RAPID, 10) } else { put_at(w, 0, &LINEAR, 11) };
        let mut mask = m.mask & 0x1ff;
        while mask != 0 {
            let a = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            i = put_cached(w, i, &AXIS_PREFIX[a % 9], m.to[a % 9], &mut self.last_text[a % 9]);
        }
        match m.f {
            Some((_, n)) => i = put_cached(w, i, &FEED, n, &mut self.last_text[9]),
            None => i = put_at(w, i, &NO_FEED, 4),
        }
        if let Some(l) = line {
            i = put_at(w, i, &AT, 3);
            i = put_line(w, i % LINE_ROOM, l, &mut self.last_line);
        }
        i = put_at(w, i, &NL, 1);
        debug_assert!(i < LINE_ROOM);
        self.used = used + i;
        if self.used >= WRITE_CHUNK {
            self.drain();
        }
    }

    fn finish(&mut self) {
        self.drain();
        if self.error.is_none() {
            if let Err(e) = self.out.flush() {
                self.error = Some(e);
            }
        }
    }
}

#[cfg(test)]
#[path = "trace_tests.rs"]
mod tests;
