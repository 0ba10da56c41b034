//! Drilling cycles in the evaluator: the modal cycle state both dialects' readers fill
//! (`fanuc`: G73–G89 with G98/G99, G80, K/L repeats; `siemens`: CYCLE81–CYCLE89, CYCLE840,
//! MCALL), the hole they drill (one `cycle`
//! event each, `ir::cycle::Hole`) and the event's text and JSON forms.

pub mod expand;
pub mod fanuc;
pub mod siemens;

use crate::diag::Diagnostic;
use crate::eval::fault::Fault;
use crate::eval::numfmt::push_num;
use crate::eval::trace::{Event, AXES};
use crate::ir::cycle::{CycleKind, Hole, Retract};
use crate::span::Span;

/// A length of a cycle as programmed: absolute (the work offset still to add) or
/// incremental (from the level the control measures it from).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Level {
    pub mm: f64,
    pub incremental: bool,
}

/// The modal cycle data (FANUC group 09 and the values it keeps between holes).
#[derive(Clone, Debug, PartialEq)]
pub struct State {
    /// The active cycle: its kind and the G code (×10) that selected it.
    pub active: Option<(CycleKind, i64)>,
    /// G98 (initial level, the power-on state) or G99 (R plane).
    pub retract: Retract,
    /// Machine position of the drilling axis when the cycle mode began.
    pub initial: f64,
    pub r: Option<Level>,
    pub z: Option<Level>,
    /// Q in mm: the infeed of G73/G83, the shift of G76/G87.
    pub q: Option<f64>,
    /// P in seconds.
    pub p: Option<f64>,
    /// `M29 S`: the next tapping cycles are rigid (the event's `tapping`).
    pub rigid: bool,
    /// Rigid tapping from a turning spindle was warned about in this cycle (NC592).
    pub rigid_noted: bool,
    /// Sinumerik: the cycle `MCALL` made modal.
    pub mcall: Option<siemens::McallCycle>,
}

impl Default for State {
    fn default() -> State {
        State {
            active: None,
            retract: Retract::Initial,
            initial: 0.0,
            r: None,
            z: None,
            q: None,
            p: None,
            rigid: false,
            rigid_noted: false,
            mcall: None,
        }
    }
}

impl State {
    /// G80 or a group-01 code: the cycle and the data it kept are cleared (the return
    /// level G98/G99 is its own modal group and stays).
    pub fn cancel(&mut self) {
        *self = State { retract: self.retract, ..State::default() };
    }
}

/// Writes one hole: its `cycle` event, or under `--expand-cycles` (`retracts` given) the
/// moves the control makes for it. A halting hole (G88, CYCLE87/88) is followed by its
/// `stop` (the expansion puts the stop at the bottom, where the control halts).
pub fn push_hole(
    retracts: Option<&expand::Retracts>,
    hole: Hole,
    cx: &expand::Context,
    span: Span,
    out: &mut dyn FnMut(Event),
) -> Result<(), Fault> {
    if let Some(rt) = retracts {
        match expand::expand(&hole, cx, rt) {
            Ok(Some(evs)) => {
                evs.into_iter().for_each(&mut *out);
                return Ok(());
            }
            Ok(None) => {}
            Err(expand::TooManyInfeeds(n)) => {
                return Err(Fault::error(
                    Diagnostic::error(
                        "NC453",
                        format!(
                            "--expand-cycles: this hole takes {} infeeds, more than the {} a hole is expanded into",
                            crate::eval::value::fmt_num(n),
                            expand::MAX_INFEEDS
                        ),
                    )
                    .primary(usize::MAX, span, "here")
                    .hint("run without --expand-cycles to see the hole as its cycle event, or check the peck depth"),
                ))
            }
        }
    }
    out(Event::Cycle(Box::new(hole)));
    if cx.halt {
        out(Event::Stop { optional: false, message: None });
    }
    Ok(())
}

/// The text form of a hole (`cycle drill X=10 Y=10 r=2 bottom=-5 peck=- dwell=-
/// retract=initial f=100`).
pub fn text_form(h: &Hole) -> String {
    let mut s = String::with_capacity(96);
    s.push_str("cycle ");
    s.push_str(h.kind.name());
    for (i, v) in h.at {
        s.push(' ');
        s.push(AXES[i]);
        s.push('=');
        push_num(&mut s, v);
    }
    s.push_str(" r=");
    push_num(&mut s, h.r);
    s.push_str(" bottom=");
    push_num(&mut s, h.bottom);
    for (name, v) in [(" peck=", h.peck), (" dwell=", h.dwell)] {
        s.push_str(name);
        match v {
            Some(x) => push_num(&mut s, x),
            None => s.push('-'),
        }
    }
    s.push_str(" retract=");
    s.push_str(h.retract.name());
    s.push_str(" f=");
    push_num(&mut s, h.f);
    if let Some(t) = h.tapping {
        s.push_str(" tapping=");
        s.push_str(t.name());
    }
    s
}

/// The JSON fields of a hole after `"ev":"cycle"`, each with its leading comma.
pub fn json_fields(h: &Hole) -> String {
    let mut s = String::with_capacity(128);
    s.push_str(",\"kind\":\"");
    s.push_str(h.kind.name());
    s.push_str("\",\"at\":{");
    for (k, (i, v)) in h.at.iter().enumerate() {
        if k > 0 {
            s.push(',');
        }
        s.push('"');
        s.push(AXES[*i]);
        s.push_str("\":");
        push_num(&mut s, *v);
    }
    s.push_str("},\"r\":");
    push_num(&mut s, h.r);
    s.push_str(",\"bottom\":");
    push_num(&mut s, h.bottom);
    for (name, v) in [(",\"peck\":", h.peck), (",\"dwell\":", h.dwell)] {
        s.push_str(name);
        match v {
            Some(x) => push_num(&mut s, x),
            None => s.push_str("null"),
        }
    }
    s.push_str(",\"retract\":\"");
    s.push_str(h.retract.name());
    s.push_str("\",\"f\":");
    push_num(&mut s, h.f);
    if let Some(t) = h.tapping {
        s.push_str(",\"tapping\":\"");
        s.push_str(t.name());
        s.push('"');
    }
    s
}
