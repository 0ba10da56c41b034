//! Differential execution: runs two programs (either dialect) side by side and compares
//! their traces event by event with the tolerances of the trace spec. The second program
//! runs on its own thread and streams its events through a bounded channel in batches of
//! [`BATCH`] (one event at a time made the two threads hand over the core at every event),
//! so memory does not grow with the trace length. The first divergence becomes one
//! diagnostic (NC500) with a label in each file, plus the two traces around it as a unified
//! diff; the events kept for that context are written as text only when it is needed.

use crate::diag::Diagnostic;
use crate::eval::trace::{text_line, GridMove};
use crate::eval::{self, CalleeSource, Ending, Event, Origin, Outcome, RunOptions, TraceSink};
use crate::ir::Unit;
use crate::span::{FileId, SourceDb};
use std::borrow::Cow;
use std::cell::Cell;
use std::sync::mpsc::{channel, sync_channel, Receiver, Sender, SyncSender};

mod defer;
mod exclude;
mod regs;
pub use defer::DeferLength;
pub use exclude::{Exclude, Excluded};

/// Absolute tolerance for numbers (trace spec).
pub const TOLERANCE: f64 = 1e-6;
/// Events of context shown on each side of a divergence.
pub const CONTEXT: usize = 3;
/// Events the second run sends at a time.
pub const BATCH: usize = 1024;
/// Batches on their way (the second run waits when the first falls this far behind).
const IN_FLIGHT: usize = 4;

/// One program to run.
pub struct Side {
    pub unit: Unit,
    pub callees: Box<dyn CalleeSource + Send>,
    pub run: RunOptions,
}

#[derive(Clone, Debug, PartialEq)]
pub enum Verdict {
    /// Same events within tolerance, both ended the same way.
    Equivalent { events: u64 },
    /// Event number `index` (0-based) differs.
    Diverged { index: u64 },
    /// A run hit a limit: nothing is proven.
    Inconclusive { reason: String },
    /// A run could not be evaluated (see the diagnostics).
    Failed,
}

pub struct CheckReport {
    pub verdict: Verdict,
    /// The events left out of the comparison (by the check's [`Exclude`]).
    pub excluded: Excluded,
    /// All files of both runs (callees included), for rendering `diags`.
    pub db: SourceDb,
    pub diags: Vec<Diagnostic>,
    /// The traces around the divergence as a unified diff (empty otherwise).
    pub diff: String,
    pub outcome_a: Outcome,
    pub outcome_b: Outcome,
    /// The programs the first run found outside its own file (`O9100`, `DRILL`), when the
    /// proof recorded them (`translate::called::Reached`): what a caller's proof ran of the
    /// library.
    pub called: Vec<String>,
    /// The first program's event where the traces part is its alarm: the source stops with
    /// an error on this path, which its translation does not reproduce ([`diverged_summary`]).
    pub diverged_on_alarm: bool,
}

impl CheckReport {
    /// A check that could not run (an output that does not read back, a bad header line, a
    /// checker that stopped): `Failed`, with why in `diags`.
    pub fn failed(db: SourceDb, diags: Vec<Diagnostic>) -> CheckReport {
        let none = || Outcome { ending: Ending::Error, steps: 0, diags: vec![] };
        CheckReport {
            verdict: Verdict::Failed,
            excluded: Default::default(),
            db,
            diags,
            diff: String::new(),
            outcome_a: none(),
            outcome_b: none(),
            called: vec![],
            diverged_on_alarm: false,
        }
    }

    /// Whether the check proved equivalence, and its verdict line as a translation reports
    /// it (whole file and stream alike; the batch adds its run labels).
    pub fn verdict_line(&self) -> (bool, String) {
        match &self.verdict {
            Verdict::Equivalent { events } => (true, self.excluded.equivalent(&format!("{events} events"))),
            Verdict::Diverged { index } => (false, diverged_summary(*index, "", self.diverged_on_alarm)),
            Verdict::Inconclusive { reason } => (false, format!("inconclusive: {reason}")),
            Verdict::Failed => (false, "not verified: a run could not be evaluated (see above)".into()),
        }
    }
}

/// The verdict line of a divergence at trace event `index` (0-based) of the run `label`
/// (empty for the plain run); `on_alarm` as [`CheckReport::diverged_on_alarm`]. One wording
/// for every path that translates (whole file, stream, batch).
pub fn diverged_summary(index: u64, label: &str, on_alarm: bool) -> String {
    if on_alarm {
        format!(
            "diverged at trace event {}{label}: the source stops with an alarm there and the translation \
             does not stop the same way (the source is in error on this path; correct it, or give inputs \
             that avoid it)",
            index + 1
        )
    } else {
        format!("diverged at trace event {}{label}: the translation is wrong (a bug in nctrans)", index + 1)
    }
}

/// One event as a check carries it: a move on the grid as its integers (copied without
/// a clone's dispatch, compared as integers: two grid values within the tolerance are
/// the same value), any other event boxed (rare in the motion that makes up long
/// traces; the box keeps every item as small as a grid move, so that it is moved in a
/// few registers, not by `memcpy`).
#[derive(Clone, Debug)]
enum Item {
    Grid(GridMove),
    Ev(Box<Event>),
}

impl Item {
    fn event(&self) -> Cow<'_, Event> {
        match self {
            Item::Grid(g) => Cow::Owned(g.event()),
            Item::Ev(e) => Cow::Borrowed(e),
        }
    }

    fn into_event(self) -> Event {
        match self {
            Item::Grid(g) => g.event(),
            Item::Ev(e) => *e,
        }
    }

    fn text(&self) -> String {
        text_line(&self.event())
    }

    fn is_limit(&self) -> bool {
        matches!(self, Item::Ev(e) if matches!(**e, Event::Limit { .. }))
    }
}

/// [`same_event`] of two items. Two grid moves agree exactly when their integers do:
/// grid values `n / 1000` that differ differ by 0.001, far beyond [`TOLERANCE`].
fn same_item(a: &Item, b: &Item) -> bool {
    match (a, b) {
        (Item::Grid(x), Item::Grid(y)) => same_grid(x, y),
        _ => same_event(&a.event(), &b.event()),
    }
}

/// [`same_item`] of two grid moves: a few integer compares.
#[inline]
fn same_grid(x: &GridMove, y: &GridMove) -> bool {
    // The positions of axes not in the mask are 0 ([`GridMove::to`]): the arrays compare
    // whole.
    debug_assert!((0..9).all(|i| (x.mask | y.mask) & (1 << i) != 0 || x.to[i] == 0 && y.to[i] == 0));
    // The positions as one fold of differences: `x.to == y.to` called `memcmp`.
    let to_differ = x.to.iter().zip(&y.to).fold(0, |d, (a, b)| d | (a ^ b));
    x.rapid == y.rapid && (x.mask ^ y.mask) & 0x1ff == 0 && to_differ == 0 && x.f.map(|f| f.1) == y.f.map(|f| f.1)
}

/// Events of the second run, in order.
type Msg = Vec<(Item, Origin)>;

/// Where the second run's events go: a bounded channel to the comparing thread, or (one
/// thread) an unbounded buffer read after the run.
enum Tx {
    Bounded(SyncSender<Msg>),
    Buffered(Sender<Msg>),
}

struct ChannelSink {
    tx: Tx,
    batch: Msg,
    dead: bool,
}

impl ChannelSink {
    fn new(tx: Tx) -> ChannelSink {
        ChannelSink { tx, batch: Vec::with_capacity(BATCH), dead: false }
    }

    /// Sends the events gathered so far (at a batch's end and after the run).
    fn send(&mut self) {
        if self.batch.is_empty() || self.dead {
            return;
        }
        let msg = std::mem::replace(&mut self.batch, Vec::with_capacity(BATCH));
        let sent = match &self.tx {
            Tx::Bounded(t) => t.send(msg).is_ok(),
            Tx::Buffered(t) => t.send(msg).is_ok(),
        };
        self.dead |= !sent;
    }
}

impl ChannelSink {
    fn push(&mut self, item: Item, origin: Origin) {
        self.batch.push((item, origin));
        if self.batch.len() >= BATCH {
            self.send();
        }
    }
}

impl TraceSink for ChannelSink {
    fn event(&mut self, ev: &Event, origin: Origin) {
        self.push(Item::Ev(Box::new(ev.clone())), origin);
    }
    fn grid_move(&mut self, m: &GridMove, origin: Origin) {
        self.push(Item::Grid(*m), origin);
    }
    fn wants_stop(&self) -> bool {
        self.dead
    }
}

struct Divergence {
    index: u64,
    a: Option<(Event, Origin)>,
    b: Option<(Event, Origin)>,
}

/// An agreeing event of the first run, kept for a divergence's context.
enum Agreed {
    Own(Item),
    /// A grid move equal to the second run's grid move of the same index ([`same_grid`]):
    /// its text is that one's (equal integers, and a feed on the grid is the one double
    /// `n / 1000`), so nothing is copied (this is every move of a long agreeing trace).
    AsB,
}

struct CompareSink {
    rx: Receiver<Msg>,
    /// The batch being compared and the index of its next event; the batch before it
    /// (the events before a divergence may be there).
    batch: Msg,
    at: usize,
    prev: Msg,
    index: u64,
    /// The last agreeing events of the first run, by `index % CONTEXT` (the second run's
    /// are still in its batches): written as text for a divergence's diff.
    before_a: [Option<Agreed>; CONTEXT],
    before_b: Vec<String>,
    after_a: Vec<String>,
    after_b: Vec<String>,
    div: Option<Divergence>,
    limit_seen: bool,
    exclude: Exclude,
    excluded: Excluded,
    /// The compensation registers paired so far.
    regs: regs::Registers,
}

fn num_eq(a: f64, b: f64) -> bool {
    (a - b).abs() <= TOLERANCE
}

fn axes_eq(a: &eval::trace::Axes, b: &eval::trace::Axes) -> bool {
    a.iter().zip(b).all(|(x, y)| match (x, y) {
        (Some(x), Some(y)) => num_eq(*x, *y),
        (None, None) => true,
        _ => false,
    })
}

fn opt_eq(a: Option<f64>, b: Option<f64>) -> bool {
    match (a, b) {
        (Some(x), Some(y)) => num_eq(x, y),
        (None, None) => true,
        _ => false,
    }
}

/// The FANUC alarm a Siemens `SETAL(64000+n)` stands for: the FANUC → Sinumerik
/// translation raises FANUC run-time alarm n itself where Siemens has no alarm of its own
/// for the case (`SETAL(64115)` guards an indirect variable out of range, FANUC 115).
fn fanuc_alarm_of(n: i64) -> Option<i64> {
    (64_000..=64_999).contains(&n).then_some(n - 64_000)
}

/// The class of a run-time alarm, so that FANUC 112 and Siemens 14051 (both a division
/// by zero) compare equal; user alarms compare FANUC `#3000=n` (3000+n) with Siemens
/// `SETAL(65000+n)`; `SETAL(64000+n)` has the class of FANUC alarm n.
fn alarm_class(n: i64) -> Option<String> {
    if let Some(f) = fanuc_alarm_of(n) {
        return alarm_class(f);
    }
    Some(match n {
        111 | 112 | 14051 => "arithmetic".into(),
        128 | 14080 => "jump target".into(),
        11 | 10860 => "no feed".into(),
        20 | 14040 => "arc".into(),
        115 | 17020 => "index".into(),
        116 | 14130 => "read-only".into(),
        0 => "program end".into(),
        3000..=3999 => format!("user {}", n - 3000),
        65000..=65999 => format!("user {}", n - 65000),
        _ => return None,
    })
}

/// True when two events agree within the trace spec's tolerance. `steps` of `end` and
/// alarm texts are not compared (block counts and alarm texts differ between dialects);
/// `M99`, `RET` and `M17` ends are the same return.
pub fn same_event(a: &Event, b: &Event) -> bool {
    use Event::*;
    match (a, b) {
        (Move { rapid: r1, to: t1, f: f1, probe: p1 }, Move { rapid: r2, to: t2, f: f2, probe: p2 }) => {
            r1 == r2 && axes_eq(t1, t2) && opt_eq(*f1, *f2) && p1 == p2
        }
        (
            Arc { cw: c1, plane: p1, to: t1, center: k1, f: f1 },
            Arc { cw: c2, plane: p2, to: t2, center: k2, f: f2 },
        ) => {
            c1 == c2
                && p1 == p2
                && axes_eq(t1, t2)
                && k1.iter().zip(k2).all(|(x, y)| x.0 == y.0 && num_eq(x.1, y.1))
                && opt_eq(*f1, *f2)
        }
        (Dwell { seconds: s1 }, Dwell { seconds: s2 }) => num_eq(*s1, *s2),
        (Tool { tool: t1 }, Tool { tool: t2 }) => match (t1, t2) {
            (eval::trace::ToolId::Number(x), eval::trace::ToolId::Number(y)) => num_eq(*x, *y),
            (eval::trace::ToolId::Name(x), eval::trace::ToolId::Name(y)) => x == y,
            _ => false,
        },
        (Spindle { rpm: r1, dir: d1 }, Spindle { rpm: r2, dir: d2 }) => num_eq(*r1, *r2) && d1 == d2,
        (Coolant { on: o1 }, Coolant { on: o2 }) => o1 == o2,
        (Stop { optional: o1, message: m1 }, Stop { optional: o2, message: m2 }) => o1 == o2 && m1 == m2,
        (Message { text: t1 }, Message { text: t2 }) => t1 == t2,
        (Print { text: t1 }, Print { text: t2 }) => t1 == t2,
        (Alarm { number: n1, .. }, Alarm { number: n2, .. }) => {
            n1 == n2
                || fanuc_alarm_of(*n1) == Some(*n2)
                || fanuc_alarm_of(*n2) == Some(*n1)
                || (alarm_class(*n1).is_some() && alarm_class(*n1) == alarm_class(*n2))
        }
        (End { code: c1, .. }, End { code: c2, .. }) => {
            let ret = |c: &str| matches!(c, "M99" | "RET" | "M17");
            c1 == c2 || (ret(c1) && ret(c2))
        }
        (Limit { .. }, Limit { .. }) => true,
        (Cycle(h1), Cycle(h2)) => {
            h1.kind == h2.kind
                && h1.retract == h2.retract
                && h1.at.iter().zip(&h2.at).all(|(x, y)| x.0 == y.0 && num_eq(x.1, y.1))
                && num_eq(h1.r, h2.r)
                && num_eq(h1.bottom, h2.bottom)
                && opt_eq(h1.peck, h2.peck)
                && opt_eq(h1.dwell, h2.dwell)
                && num_eq(h1.f, h2.f)
                && h1.tapping == h2.tapping
        }
        (WorkOffset { n: n1 }, WorkOffset { n: n2 }) => n1 == n2,
        (Home(h1), Home(h2)) => h1.point == h2.point && h1.axes == h2.axes && axes_eq(&h1.via, &h2.via),
        // The registers' names are paired by `regs::Registers` as the check goes.
        (Comp(c1), Comp(c2)) => regs::same_shape(c1, c2),
        (ToolData(t1), ToolData(t2)) => t1.field == t2.field && num_eq(t1.value, t2.value),
        _ => false,
    }
}

impl CompareSink {
    fn new(rx: Receiver<Msg>, exclude: Exclude) -> CompareSink {
        CompareSink {
            exclude,
            excluded: Excluded::default(),
            rx,
            batch: Vec::new(),
            at: 0,
            prev: Vec::new(),
            index: 0,
            before_a: [const { None }; CONTEXT],
            before_b: Vec::new(),
            after_a: Vec::new(),
            after_b: Vec::new(),
            div: None,
            limit_seen: false,
            regs: regs::Registers::default(),
        }
    }

    /// Moves on to the second run's next event (at `batch[at - 1]`); `false` at its end.
    fn advance_b(&mut self) -> bool {
        while self.at >= self.batch.len() {
            let Ok(next) = self.rx.recv() else { return false };
            self.prev = std::mem::replace(&mut self.batch, next);
            self.at = 0;
        }
        self.at += 1;
        true
    }

    /// The second run's next event, moved out (after a divergence only).
    fn next_b(&mut self) -> Option<(Item, Origin)> {
        if !self.advance_b() {
            return None;
        }
        let slot = self.batch.get_mut(self.at - 1)?;
        Some((std::mem::replace(&mut slot.0, Item::Ev(Box::new(Event::Limit { steps: 0 }))), slot.1))
    }

    fn fill_after_b(&mut self) {
        while self.after_b.len() < CONTEXT {
            match self.next_b() {
                Some((e, _)) => self.after_b.push(e.text()),
                None => break,
            }
        }
    }

    /// Records the divergence at event `index`: `a` against the second run's event at
    /// `batch[b_at]` (`None`: its trace ended), with the agreeing events before each.
    fn diverge(&mut self, a: Option<(Event, Origin)>, b_at: Option<usize>) {
        // The second run's agreeing events end just before its divergent one (or at the
        // end of its batches), in this batch and the one before.
        let end = b_at.unwrap_or(self.batch.len());
        let n = (self.index as usize).min(CONTEXT);
        let from_prev = n.saturating_sub(end);
        let prev = &self.prev[self.prev.len().saturating_sub(from_prev)..];
        self.before_b = prev.iter().chain(&self.batch[end - (n - from_prev)..end]).map(|x| x.0.text()).collect();
        let b = b_at.and_then(|i| self.batch.get(i)).map(|(item, o)| (item.clone().into_event(), *o));
        self.div = Some(Divergence { index: self.index, a, b });
        self.fill_after_b();
    }

    /// The first run's agreeing events before the divergence, oldest first, as text
    /// (after [`CompareSink::diverge`]: the second run's events of the same indexes are
    /// `before_b`).
    fn before_a_text(&self) -> Vec<String> {
        let n = (self.index as usize).min(CONTEXT);
        let from = self.index as usize - n;
        (from..self.index as usize)
            .filter_map(|k| match self.before_a[k % CONTEXT].as_ref()? {
                Agreed::Own(item) => Some(item.text()),
                Agreed::AsB => self.before_b.get(k - from).cloned(),
            })
            .collect()
    }

    /// After A ended: B must have ended too.
    fn finish(&mut self) {
        if self.div.is_some() {
            return;
        }
        if self.advance_b() {
            if self.batch[self.at - 1].0.is_limit() {
                self.limit_seen = true;
                return;
            }
            self.diverge(None, Some(self.at - 1));
        }
    }

    /// One event of the first run (`ev`: its event, for a divergence).
    fn compare(&mut self, a: Item, origin: Origin) {
        if self.div.is_some() {
            if self.after_a.len() < CONTEXT {
                self.after_a.push(a.text());
            }
            return;
        }
        if a.is_limit() {
            self.limit_seen = true;
        }
        if self.exclude.messages && matches!(&a, Item::Ev(e) if matches!(**e, Event::Message { .. })) {
            self.excluded.messages += 1;
            return;
        }
        let b_at = self.advance_b().then(|| self.at - 1);
        let b = b_at.and_then(|i| self.batch.get(i));
        if b.is_some_and(|b| b.0.is_limit()) {
            self.limit_seen = true;
        }
        let message_left_out = self.exclude.messages && b.is_some_and(|b| stop_without_message(&a, &b.0));
        if message_left_out {
            self.excluded.messages += 1;
        }
        let agrees = |regs: &mut regs::Registers, b: &Item| {
            same_item(&a, b) && (matches!(a, Item::Grid(_)) || regs.agree(&a.event(), &b.event()))
        };
        if message_left_out || b.is_some_and(|b| agrees(&mut self.regs, &b.0)) {
            self.before_a[self.index as usize % CONTEXT] = Some(Agreed::Own(a));
            self.index += 1;
            return;
        }
        if self.limit_seen {
            return;
        }
        self.diverge(Some((a.into_event(), origin)), b_at);
    }
}

/// `a` is a stop with a message and `b` the same stop without one.
fn stop_without_message(a: &Item, b: &Item) -> bool {
    match (a, b) {
        (Item::Ev(a), Item::Ev(b)) => matches!(
            (&**a, &**b),
            (Event::Stop { optional: o1, message: Some(_) }, Event::Stop { optional: o2, message: None }) if o1 == o2
        ),
        _ => false,
    }
}

impl TraceSink for CompareSink {
    fn event(&mut self, ev: &Event, origin: Origin) {
        self.compare(Item::Ev(Box::new(ev.clone())), origin);
    }

    fn grid_move(&mut self, m: &GridMove, origin: Origin) {
        // What `compare` does when the second run's next event is at hand and agrees
        // (nearly every move of a long trace), without building an item to compare.
        if self.div.is_none() {
            if let Some((Item::Grid(y), _)) = self.batch.get(self.at) {
                if same_grid(m, y) {
                    self.at += 1;
                    self.before_a[self.index as usize % CONTEXT] = Some(Agreed::AsB);
                    self.index += 1;
                    return;
                }
            }
        }
        self.compare(Item::Grid(*m), origin);
    }

    fn wants_stop(&self) -> bool {
        self.limit_seen || (self.div.is_some() && self.after_a.len() >= CONTEXT)
    }
}

/// One side of a check as a run: given its copy of the file database and the sink, it runs
/// its program (a unit in memory, or a streamed file: `crate::stream::runner`).
pub struct Runner {
    /// The side's own file, which the diff's header names. Not always file 1 for the second
    /// side: a Siemens first side's definition files (`MGUD.DEF`) are loaded before it.
    pub file: FileId,
    run: Run,
}

type Run = Box<dyn FnOnce(&mut SourceDb, &mut dyn TraceSink) -> Outcome + Send>;

impl Runner {
    pub fn new(file: FileId, run: impl FnOnce(&mut SourceDb, &mut dyn TraceSink) -> Outcome + Send + 'static) -> Self {
        Runner { file, run: Box::new(run) }
    }

    /// Runs the side alone, its trace into `sink`.
    pub fn run(self, db: &mut SourceDb, sink: &mut dyn TraceSink) -> Outcome {
        (self.run)(db, sink)
    }
}

impl Side {
    pub fn runner(self) -> Runner {
        Runner::new(self.unit.file, move |db, sink| {
            let mut callees = self.callees;
            eval::run(db, &self.unit, callees.as_mut(), &self.run, sink)
        })
    }
}

/// Runs both programs and compares their traces. `db` holds both main files (and is
/// cloned for each run); the report's `db` also holds every callee either run loaded.
pub fn check(db: &SourceDb, a: Side, b: Side) -> CheckReport {
    check_runners(db, a.runner(), b.runner())
}

/// [`check`] leaving out (and counting) what `exclude` names.
pub fn check_excluding(db: &SourceDb, a: Side, b: Side, exclude: Exclude) -> CheckReport {
    check_runners_excluding(db, a.runner(), b.runner(), exclude)
}

thread_local! {
    static ONE_THREAD: Cell<bool> = const { Cell::new(false) };
}

/// Runs `f` with every check on this thread done in this thread alone: the second program
/// runs first with its trace buffered, then the first runs against it. Batch workers use it
/// so that `-j N` means N busy cores; memory then grows with the second trace, which suits
/// the batch's program-sized files (large files stream, see `crate::stream`).
pub fn in_one_thread<T>(f: impl FnOnce() -> T) -> T {
    let before = ONE_THREAD.with(|c| c.replace(true));
    let out = f();
    ONE_THREAD.with(|c| c.set(before));
    out
}

/// [`check`] for any two runs.
pub fn check_runners(db: &SourceDb, a: Runner, b: Runner) -> CheckReport {
    check_runners_excluding(db, a, b, Exclude::default())
}

/// [`check_runners`] leaving out (and counting) what `exclude` names.
pub fn check_runners_excluding(db: &SourceDb, a: Runner, b: Runner, exclude: Exclude) -> CheckReport {
    let n0 = db.len();
    let (file_a, file_b) = (a.file, b.file);
    let (a, b) = (a.run, b.run);
    let db_b = db.clone();
    let (rx, handle) = if ONE_THREAD.with(Cell::get) {
        let (tx, rx) = channel::<Msg>();
        let mut db_b = db_b;
        let mut sink = ChannelSink::new(Tx::Buffered(tx));
        let out = b(&mut db_b, &mut eval::collapse::CollapseWorkOffsets::new(&mut DeferLength::new(&mut sink)));
        sink.send();
        drop(sink);
        (rx, Err((out, db_b)))
    } else {
        let (tx, rx) = sync_channel::<Msg>(IN_FLIGHT);
        let run = move || {
            let mut db_b = db_b;
            let mut sink = ChannelSink::new(Tx::Bounded(tx));
            let out = b(&mut db_b, &mut eval::collapse::CollapseWorkOffsets::new(&mut DeferLength::new(&mut sink)));
            sink.send();
            (out, db_b)
        };
        let stack = crate::dialect::limits::THREAD_STACK;
        let handle = std::thread::Builder::new().stack_size(stack).spawn(run).expect("start the checker's thread");
        (rx, Ok(handle))
    };
    let mut db_a = db.clone();
    let mut sink = CompareSink::new(rx, exclude);
    let outcome_a = a(&mut db_a, &mut eval::collapse::CollapseWorkOffsets::new(&mut DeferLength::new(&mut sink)));
    if !matches!(outcome_a.ending, Ending::Stopped) {
        sink.finish();
    }
    let before_a = sink.before_a_text();
    let CompareSink { rx, index, before_b, after_a, after_b, div, limit_seen, mut excluded, .. } = sink;
    // Look-ahead settings have no event: the first run's are counted as not compared.
    let lookahead = eval::machine::lookahead::NOT_COMPARED;
    excluded.modes = outcome_a.diags.iter().filter(|d| d.code == lookahead).count() as u64;
    // Interrupt routines that did not run (no switch given for them) were not compared either.
    excluded.interrupts = outcome_a.diags.iter().filter(|d| d.code == "NC566").count() as u64;
    // Signal writes have no event either (`eval::signals`).
    let write = eval::signals::WRITE;
    excluded.signals =
        outcome_a.diags.iter().filter(|d| d.code == write && d.severity == crate::diag::Severity::Warning).count()
            as u64;
    drop(rx);
    let joined = match handle {
        Ok(h) => h.join().map_err(|_| ()),
        Err(done) => Ok(done),
    };
    let (outcome_b, db_b) = match joined {
        Ok(r) => r,
        Err(()) => (
            Outcome {
                ending: Ending::Error,
                steps: 0,
                diags: vec![Diagnostic::error("NC502", "the second run failed unexpectedly")],
            },
            db.clone(),
        ),
    };
    // Merge the files the B run loaded after the shared ones.
    let mut merged = db_a;
    let offset = merged.len();
    for id in n0..db_b.len() {
        let f = db_b.get(id);
        merged.add(f.name.clone(), f.text.clone());
    }
    let map_b = |id: FileId| if id >= n0 { id - n0 + offset } else { id };
    let mut diags = Vec::new();
    for d in &outcome_a.diags {
        diags.push(d.clone());
    }
    for d in &outcome_b.diags {
        let mut d = d.clone();
        for l in &mut d.labels {
            l.file = map_b(l.file);
        }
        diags.push(d);
    }
    let failed = matches!(outcome_a.ending, Ending::Error) || matches!(outcome_b.ending, Ending::Error);
    let limited = limit_seen
        || matches!(outcome_a.ending, Ending::Limit { .. })
        || matches!(outcome_b.ending, Ending::Limit { .. });
    let mut diff = String::new();
    let diverged_on_alarm = matches!(&div, Some(dv) if matches!(&dv.a, Some((Event::Alarm { .. }, _))));
    let verdict = if failed {
        Verdict::Failed
    } else if let (Some(dv), false) = (&div, limited) {
        let shown = |e: &Option<(Event, Origin)>| e.as_ref().map_or("<end of trace>".to_string(), |x| text_line(&x.0));
        let (ta, tb) = (shown(&dv.a), shown(&dv.b));
        let mut d = Diagnostic::error(
            "NC500",
            format!("the programs diverge at trace event {}: `{ta}` vs `{tb}`", dv.index + 1),
        );
        if let Some((_, o)) = &dv.a {
            d = d.primary(o.file, o.span, format!("first program: {ta}"));
        }
        if let Some((_, o)) = &dv.b {
            let label = format!("second program: {tb}");
            d = if dv.a.is_some() {
                d.secondary(map_b(o.file), o.span, label)
            } else {
                d.primary(map_b(o.file), o.span, label)
            };
        }
        d = d.note(format!("{} events agreed before this one", dv.index));
        // A tool name against a number: the two are a program and its translation, compared
        // without the tool map the translation used.
        let tool = |e: &Option<(Event, Origin)>, named: bool| matches!(e, Some((Event::Tool { tool }, _)) if matches!(tool, eval::trace::ToolId::Name(_)) == named);
        if (tool(&dv.a, true) && tool(&dv.b, false)) || (tool(&dv.a, false) && tool(&dv.b, true)) {
            d = d.hint(
                "a tool name against a T number: give the tool map the translation used \
                 (nctrans check A B --tool-map NAME=n, or --map nctrans-map.toml)",
            );
        } else {
            d = d.hint("compare the two blocks labelled above; the diff below shows the traces around the divergence");
        }
        diags.push(d);
        let mut old = before_a;
        old.push(ta);
        old.extend(after_a);
        let mut new = before_b;
        new.push(tb);
        new.extend(after_b);
        let old = old.join("\n") + "\n";
        let new = new.join("\n") + "\n";
        // Each side's own file: with definition files loaded, file 1 is not the second side.
        let name = |id: FileId, or: &str| if id < merged.len() { merged.get(id).name.clone() } else { or.into() };
        let (name_a, name_b) = (name(file_a, "a"), name(map_b(file_b), "b"));
        diff = similar::TextDiff::from_lines(&old, &new)
            .unified_diff()
            .context_radius(CONTEXT)
            .header(&name_a, &name_b)
            .to_string();
        Verdict::Diverged { index: dv.index }
    } else if limited {
        let reason = match (&outcome_a.ending, &outcome_b.ending) {
            (Ending::Limit { reason }, _) | (_, Ending::Limit { reason }) => reason.clone(),
            _ => "a run stopped at its limit".into(),
        };
        diags.push(
            Diagnostic::warning("NC501", format!("inconclusive: {reason}"))
                .note("a run that stops at a limit proves nothing; the programs are not reported equal")
                .hint("raise --max-steps, or give inputs that make the loops finish"),
        );
        Verdict::Inconclusive { reason }
    } else {
        Verdict::Equivalent { events: index }
    };
    // The set-up values either run read (`[variables] fixed`): the verdict names them.
    excluded.assumed = crate::dialect::fixed::assumed_in(outcome_a.diags.iter().chain(&outcome_b.diags));
    CheckReport { verdict, excluded, db: merged, diags, diff, outcome_a, outcome_b, called: vec![], diverged_on_alarm }
}

#[cfg(test)]
mod tests;
