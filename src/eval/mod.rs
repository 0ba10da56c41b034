//! The bundled evaluator: runs a FANUC or Siemens program with each control's exact
//! semantics and streams the canonical trace (`docs/trace-format.md`) into a
//! [`TraceSink`]. The library never prints; it returns an [`Outcome`].
//!
//! Owns: running a program (interpreter, machine state, the trace) and the interface it reads
//! streamed programs through (`paged::PagedSource`). May use: `ir`, `dialect` (spellings,
//! `Semantics`, the compact blocks of `dialect::lit`), `read`, `diag`, `span` (`tests/layering.rs`). Never `stream`, `lower`, `check` or the translators,
//! which all use it.
//!
//! Layout: `value` (values and typed conversion), `expr` (operators and functions per
//! control), `flow` (flattening to linear code with jump tables; `lit`: blocks of
//! constant words in compact form), `exec` (the interpreter loop), `access` + `vars`
//! (variables), `calls` (calls, returns, callee lookup), `machine` + `arc` (modal state
//! and motion; `cycles`: drilling cycles; `corner`: the geometry of chamfers and roundings,
//! which `machine::corners` inserts and the FANUC translation shares), `sysvars`, `trace` (events and writers; `numfmt`: the trace's number
//! form), `input` (`--set` and header inputs), `fault` (alarms, errors, limits).
//! Choices are in docs/semantics.md.

pub mod access;
pub mod arc;
pub mod axes;
pub mod callee_files;
pub mod calls;
pub mod collapse;
pub mod corner;
pub mod cycle832;
pub mod cycles;
pub mod exec;
pub mod expr;
pub mod fault;
mod fgroup;
pub mod flow;
pub mod haas_data;
pub mod input;
pub mod instructions;
pub mod interrupt;

pub mod machine;
pub mod numfmt;
pub mod paged;
pub mod print;
pub mod probe;
pub mod refuse;
pub mod signals;
mod strings;
pub mod sysvars;
pub mod tool_data;
pub mod trace;
pub mod value;
pub mod vars;

#[cfg(test)]
mod expr_tests;
#[cfg(test)]
mod lit_tests;
#[cfg(test)]
mod run_tests;
#[cfg(test)]
pub(crate) mod test_ir;

pub use calls::{CalleeName, CalleeSource, DirCallees, NoCallees};
pub use input::{header_inputs, parse_input, Input, InputTarget};
pub use interrupt::{header_interrupts, parse_interrupt, InterruptInput};
pub use probe::{header_probes, parse_probe, ProbeInput};
pub use trace::{Event, Format, NullSink, Origin, TraceSink, VecSink, WriterSink};

use crate::diag::Diagnostic;
use crate::dialect::{Dialect, Semantics};
use crate::ir::Unit;
use crate::span::SourceDb;
use exec::{Frame, FrameKind, Interp};
use fault::Fault;

/// Default step limit (blocks executed).
pub const DEFAULT_MAX_STEPS: u64 = 10_000_000;

#[derive(Clone, Debug)]
pub struct RunOptions {
    pub max_steps: u64,
    /// Variable values set before the run (`--set`, header lines).
    pub inputs: Vec<Input>,
    /// The control profile; `None`: the dialect's default.
    pub semantics: Option<Semantics>,
    /// Where along every probe move (FANUC `G31`, Siemens `MEAS=`/`MEAW=`) the probe
    /// touches, as a fraction of the move in (0, 1]; `None`: no contact, the move reaches
    /// its end point (FANUC then reports the end point in `#5061+`).
    pub probe_contact: Option<f64>,
    /// `--probe`: for each probing move in run order, where the probe triggers or that it
    /// misses (`probe`); moves beyond the list do not trigger. Given, it replaces
    /// `probe_contact`.
    pub probes: Vec<ProbeInput>,
    /// `--interrupt N@K`: interrupt input N switches on right after the K-th motion event
    /// of the run (`interrupt::InterruptInput`); without any, no input ever switches.
    pub interrupts: Vec<InterruptInput>,
    /// `--expand-cycles`: every drilling hole is written as the moves, dwells and spindle
    /// events the control makes (`cycles::expand`), with these retract amounts, instead of
    /// its `cycle` event. For viewing: `check` never sets it.
    pub expand_cycles: Option<cycles::expand::Retracts>,
}

impl Default for RunOptions {
    fn default() -> Self {
        RunOptions {
            max_steps: DEFAULT_MAX_STEPS,
            inputs: Vec::new(),
            semantics: None,
            probe_contact: None,
            probes: Vec::new(),
            interrupts: Vec::new(),
            expand_cycles: None,
        }
    }
}

/// How a run ended.
#[derive(Clone, Debug, PartialEq)]
pub enum Ending {
    /// `end` event with this code.
    End(&'static str),
    /// `alarm` event.
    Alarm { number: i64, message: String },
    /// `limit` event: inconclusive.
    Limit { reason: String },
    /// The sink asked to stop early (the checker had seen the divergence).
    Stopped,
    /// The evaluator could not run the program (the diagnostic is in `diags`); the trace
    /// stops without a final event.
    Error,
}

#[derive(Clone, Debug)]
pub struct Outcome {
    pub ending: Ending,
    pub steps: u64,
    /// Warnings (once per place) and, for [`Ending::Error`], the error.
    pub diags: Vec<Diagnostic>,
}

/// Runs the first program of `unit` (other programs of the unit are callable by number or
/// name). Callees outside the unit come from `callees`.
pub fn run(
    db: &mut SourceDb,
    unit: &Unit,
    callees: &mut dyn CalleeSource,
    opts: &RunOptions,
    sink: &mut dyn TraceSink,
) -> Outcome {
    let dialect = unit.dialect;
    let mut it = Interp::new(dialect, opts, db, callees, sink);
    let ids = match it.register_unit(unit, None) {
        Ok(ids) => ids,
        Err(d) => return Outcome { ending: Ending::Error, steps: 0, diags: vec![d] },
    };
    run_registered(it, dialect, &ids)
}

/// Runs the first program of a streamed file (see `crate::stream`): its ops are read
/// page by page through `pager`, so memory does not grow with the file's length. The
/// file must be in `db` under `pager.file()` (its text may be empty).
pub fn run_stream(
    db: &mut SourceDb,
    pager: std::rc::Rc<dyn paged::PagedSource>,
    callees: &mut dyn CalleeSource,
    opts: &RunOptions,
    sink: &mut dyn TraceSink,
) -> Outcome {
    let dialect = pager.dialect();
    let mut it = Interp::new(dialect, opts, db, callees, sink);
    let ids = it.register_stream(&pager);
    run_registered(it, dialect, &ids)
}

fn run_registered(mut it: Interp<'_>, dialect: Dialect, ids: &[usize]) -> Outcome {
    let Some(&main) = ids.first() else {
        let d = Diagnostic::error("NC401", "the file holds no program to run");
        return Outcome { ending: Ending::Error, steps: 0, diags: vec![d] };
    };
    it.frames.push(Frame {
        code: main,
        pc: 0,
        level: 0,
        sframe: 0,
        kind: FrameKind::Main,
        repeats_left: 0,
        call_span: Default::default(),
        reps: Vec::new(),
        modal: false,
        saved: None,
        start: 0,
    });
    let result = declare_globals(&mut it, dialect)
        .and_then(|_| apply_inputs(&mut it, dialect, main))
        .and_then(|_| it.run_loop());
    let ending = match result {
        Ok(e) => e,
        Err(Fault::Alarm { number, message, span }) => {
            it.emit(Event::Alarm { number, message: message.clone() }, span);
            Ending::Alarm { number, message }
        }
        Err(Fault::Limit { reason, span }) => {
            let steps = it.steps.min(it.max_steps);
            it.emit(Event::Limit { steps }, span);
            let file = it.file();
            it.diags.push(
                Diagnostic::warning("NC408", format!("run stopped: {reason}"))
                    .primary(file, span, "stopped here")
                    .note("a run that hits a limit proves nothing")
                    .hint("raise --max-steps, or check the program for an endless loop"),
            );
            Ending::Limit { reason }
        }
        Err(Fault::Error(d)) => {
            it.diags.push(*d);
            Ending::Error
        }
    };
    it.interrupt_finish();
    it.flush();
    // The trace is complete: a writer hands over the lines it still holds.
    it.sink.finish();
    Outcome { ending, steps: it.steps.min(it.max_steps), diags: std::mem::take(&mut it.diags) }
}

/// Siemens global user data (`Semantics::globals`, from the library's `.DEF` files) exists
/// before the program starts, at its definition's start value (or an input's), in the main
/// program's frame, so every subprogram sees it.
fn declare_globals(it: &mut Interp, dialect: Dialect) -> Result<(), Fault> {
    if dialect != Dialect::Sinumerik {
        return Ok(());
    }
    let globals = it.sem.globals.clone();
    for def in globals.iter() {
        it.define(def)?;
    }
    Ok(())
}

fn apply_inputs(it: &mut Interp, dialect: Dialect, main: usize) -> Result<(), Fault> {
    let inputs = it.inputs.clone();
    // A PROC run as the main program: its parameters are inputs (0 when not given).
    let params = it.params.get(main).cloned().unwrap_or_default();
    for p in &params {
        let v = inputs
            .iter()
            .find(|i| matches!(&i.target, InputTarget::Name(n) if *n == p.name))
            .map(|i| i.value.clone())
            .unwrap_or_else(|| vars::zero_of(p.ty));
        let len = vars::array_len(&p.dims).ok_or_else(|| {
            Fault::alarm(it.alarms.bad_index, format!("array parameter {} too large", p.name), Default::default())
        })?;
        let mut data = vec![vars::zero_of(p.ty); len];
        data[0] = value::convert_for(p.ty, v).unwrap_or_else(|_| vars::zero_of(p.ty));
        it.vars.frames[0].insert(p.name.clone(), vars::Slot::Own { ty: p.ty, dims: p.dims.clone(), data });
    }
    let span = Default::default();
    for i in &inputs {
        match (&i.target, dialect) {
            (InputTarget::Hash(n), Dialect::Fanuc) if it.is_haas_data(i64::from(*n)) => {
                it.set_haas_data(i64::from(*n), &i.value)?
            }
            (InputTarget::Hash(n), Dialect::Fanuc) if it.is_tool_data(i64::from(*n)) => {
                it.set_tool_data(format!("#{n}"), &i.value)?
            }
            (InputTarget::ToolData(key), Dialect::Sinumerik) => it.set_tool_data(key.clone(), &i.value)?,
            (InputTarget::Hash(n), Dialect::Fanuc) if let Some(s) = it.signal_at(i64::from(*n)) => {
                it.set_signal(s, &i.value)?
            }
            (InputTarget::Signal(s), Dialect::Sinumerik) => it.set_signal(*s, &i.value)?,
            (InputTarget::Hash(n), Dialect::Fanuc) => it.write_fanuc(i64::from(*n), i.value.clone(), span)?,
            (InputTarget::R(n), Dialect::Sinumerik) => {
                let r = crate::ir::VarRef { kind: crate::ir::VarKind::R(*n), span };
                it.write_var(&r, i.value.clone())?
            }
            // Names are applied when the DEF (or PROC parameter) creates them.
            (InputTarget::Name(_), Dialect::Sinumerik) => {}
            _ => {
                return Err(Fault::error(Diagnostic::error(
                    "NC407",
                    format!("input {} does not fit a {} program", i.text, dialect.name()),
                )))
            }
        }
    }
    Ok(())
}
