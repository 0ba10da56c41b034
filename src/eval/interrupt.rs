//! Interrupt routines and the test inputs that switch them (`--interrupt N@K`, header lines
//! `nctrans: interrupt`): Siemens `SETINT(n) PRIO=p NAME`, `ENABLE(n)`, `DISABLE(n)`,
//! `CLRINT(n)` and FANUC `M96 P…` / `M97` (read as interrupts only where the profile says the
//! machine has the custom macro interrupt). An input switches only where the test inputs say;
//! the routine then runs as a subprogram call at the end of the block whose motion event was
//! the K-th of the run, and the program goes on with the next block (docs/semantics.md,
//! "Interrupts").

use super::calls::CalleeName;
use super::exec::{Flow, FrameKind, Interp};
use super::fault::Fault;
use crate::diag::Diagnostic;
use crate::ir::ProgName;
use crate::span::{FileId, Span};

/// One switch of an interrupt input: input `input` switches on right after the `after`-th
/// motion event (`move`, `arc`, `cycle`, `home`) of the run. FANUC's one interrupt signal
/// (UINT) is input 1.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct InterruptInput {
    pub input: u32,
    pub after: u64,
}

/// Parses `N@K` (`1@3`: input 1 switches after the third motion event).
pub fn parse_interrupt(s: &str) -> Result<InterruptInput, String> {
    let t = s.trim();
    let Some((n, k)) = t.split_once('@') else {
        return Err(format!("'{t}': expected INPUT@MOTION, e.g. 1@3 (input 1 switches after the 3rd motion event)"));
    };
    let input: u32 = n
        .trim()
        .parse()
        .ok()
        .filter(|n| (1..=8).contains(n))
        .ok_or_else(|| format!("'{t}': the input is a number from 1 to 8 (FANUC's UINT signal is input 1)"))?;
    let after: u64 = k
        .trim()
        .parse()
        .ok()
        .filter(|k| *k >= 1)
        .ok_or_else(|| format!("'{t}': after '@' comes the motion event it follows, a whole number from 1"))?;
    Ok(InterruptInput { input, after })
}

/// Interrupt inputs written in a file's header comments, before its first block:
/// `; nctrans: interrupt 1@3` (Siemens) or `(nctrans: interrupt 1@3)` (FANUC).
pub fn header_interrupts(text: &str) -> Result<Vec<InterruptInput>, String> {
    super::input::header_words(text, "nctrans: interrupt", true).map(parse_interrupt).collect()
}

pub use crate::ir::interrupt::{op_of, IntOp};

/// One input's assignment.
#[derive(Clone, Debug)]
struct Slot {
    routine: CalleeName,
    enabled: bool,
    /// The index of the instruction that assigned it (in `State::places`).
    place: usize,
}

/// The run's interrupt state.
#[derive(Debug, Default)]
pub struct State {
    /// The switches still to come, by motion event.
    pending: Vec<InterruptInput>,
    /// Motion events so far.
    pub motions: u64,
    slots: std::collections::BTreeMap<u32, Slot>,
    /// Every assigning instruction met: its text, place and whether its routine ran.
    places: Vec<(String, FileId, Span, bool)>,
    /// The routine each of `places` assigns.
    place_routines: Vec<CalleeName>,
    /// The routines that ran (from any of their assignments).
    ran: Vec<CalleeName>,
    /// The frame depth of a routine running (its frame and those it calls).
    running: Option<usize>,
}

impl State {
    pub fn new(mut inputs: Vec<InterruptInput>) -> State {
        inputs.sort_by_key(|i| i.after);
        State { pending: inputs, ..State::default() }
    }

    /// A switch is due: the motion events reached its K.
    pub fn due(&self) -> bool {
        self.pending.first().is_some_and(|p| p.after <= self.motions)
    }

    /// Switches are still to come (the literal fast path must stop at block ends).
    pub fn active(&self) -> bool {
        !self.pending.is_empty()
    }
}

/// The event kinds that count as motion for `N@K`.
pub fn is_motion(ev: &super::trace::Event) -> bool {
    use super::trace::Event;
    matches!(ev, Event::Move { .. } | Event::Arc { .. } | Event::Cycle(_) | Event::Home(_))
}

impl Interp<'_> {
    /// Runs one interrupt instruction (assign, enable, disable, clear).
    pub(super) fn interrupt_op(&mut self, name: &str, span: Span) -> Result<(), Fault> {
        let op = match op_of(name) {
            Some(Ok(op)) => op,
            Some(Err(msg)) => {
                let d = Diagnostic::error("NC638", msg)
                    .primary(self.file(), span, "here")
                    .hint("write the input, PRIO and the routine's name as constants: SETINT(1) PRIO=1 RETRACT");
                return Err(Fault::error(d));
            }
            None => return Ok(()),
        };
        match op {
            IntOp::Assign { input, routine, extra, .. } => {
                let routine = match routine {
                    ProgName::Number(n) => CalleeName::Number(n),
                    ProgName::Name(s) => CalleeName::Name(s.to_ascii_uppercase()),
                };
                if let Some(w) = extra.first() {
                    let d = Diagnostic::error("NC639", format!("{name}: {w} is not modelled"))
                        .primary(self.file(), span, "here")
                        .note(if w == "LIFTFAST" {
                            "LIFTFAST lifts the tool fast before the routine runs, by a direction and distance set \
                             by LFTXT/LFWP/ALF and machine data the trace does not see"
                        } else {
                            "BLSYNC lets the interrupted block finish before the routine runs"
                        })
                        .hint("without it the routine runs at the end of the block the input switches in");
                    return Err(Fault::error(d));
                }
                let file = self.file();
                let place = match self.ints.places.iter().position(|p| p.1 == file && p.2 == span) {
                    Some(i) => i,
                    None => {
                        self.ints.places.push((name.to_string(), file, span, false));
                        self.ints.place_routines.push(routine.clone());
                        self.ints.places.len() - 1
                    }
                };
                self.ints.slots.insert(input, Slot { routine, enabled: true, place });
            }
            IntOp::Enable(n) | IntOp::Disable(n) => {
                let on = matches!(op, IntOp::Enable(_));
                match self.ints.slots.get_mut(&n) {
                    Some(s) => s.enabled = on,
                    // FANUC M97 without an M96 is harmless; ENABLE of an input nothing is
                    // assigned to is an alarm on the control (unsourced: refused).
                    None if !on => {}
                    None => {
                        let d = Diagnostic::error("NC640", format!("{name}: no routine is assigned to input {n}"))
                            .primary(self.file(), span, "here")
                            .hint(format!("assign one first: SETINT({n}) PRIO=1 NAME"));
                        return Err(Fault::error(d));
                    }
                }
            }
            IntOp::Clear(n) => {
                self.ints.slots.remove(&n);
            }
        }
        Ok(())
    }

    /// Refuses a switch due on a block that also ends, returns, jumps or calls: whether
    /// the routine runs before or after that is not in the sources.
    pub(super) fn interrupt_clash(&mut self, what: &str, span: Span) -> Result<(), Fault> {
        if !self.ints.due() {
            return Ok(());
        }
        let p = self.ints.pending[0];
        let d = Diagnostic::error(
            "NC641",
            format!("interrupt input {} switches after motion {} in a block that also {what}", p.input, p.after),
        )
        .primary(self.file(), span, "this block")
        .note("whether the routine runs before or after that is not modelled")
        .hint("give the switch at another motion event (--interrupt N@K)");
        Err(Fault::error(d))
    }

    /// At the end of a block: runs the routine of a switch that is due. `pc` is the block
    /// just done; the program goes on after it when the routine returns.
    pub(super) fn interrupt_fire(&mut self, pc: usize, span: Span) -> Result<Flow, Fault> {
        let p = self.ints.pending.remove(0);
        if self.ints.running.is_some_and(|d| self.frames.len() >= d) {
            let d = Diagnostic::error(
                "NC641",
                format!(
                    "interrupt input {} switches after motion {} while an interrupt routine runs",
                    p.input, p.after
                ),
            )
            .primary(self.file(), span, "inside the routine")
            .note("priorities and nested interrupts are not modelled")
            .hint("give the switch outside the routine's moves");
            return Err(Fault::error(d));
        }
        let Some(slot) = self.ints.slots.get(&p.input).cloned() else {
            let msg = format!(
                "interrupt input {} switches after motion {}, but no routine is assigned to it: nothing runs",
                p.input, p.after
            );
            self.warn("NC642", msg, span);
            return Ok(Flow::Next);
        };
        if !slot.enabled {
            let msg = format!(
                "interrupt input {} switches after motion {} while its routine is disabled: it does not run \
                 (whether the control keeps the switch for a later ENABLE is not modelled)",
                p.input, p.after
            );
            self.warn("NC642", msg, span);
            return Ok(Flow::Next);
        }
        let Some(code) = self.find_code(&slot.routine, span)? else {
            return Err(self.missing_callee(&slot.routine, span));
        };
        if let Some(pl) = self.ints.places.get_mut(slot.place) {
            pl.3 = true;
        }
        self.ints.ran.push(slot.routine.clone());
        self.frames.last_mut().ok_or_else(super::exec::internal)?.pc = pc + 1;
        // FANUC: the interrupt program has its own local variables, like a G65 macro.
        let kind = if self.fanuc { FrameKind::Macro } else { FrameKind::Proc };
        self.push_call_frame(code, kind, span)?;
        if !self.fanuc {
            self.bind_no_args(code, span)?;
        }
        self.ints.running = Some(self.frames.len());
        Ok(Flow::Switched)
    }

    /// The end of the run: every assignment whose routine never ran (from it or another
    /// assignment of the same routine) is a warning (NC566), which a check counts as not
    /// compared.
    pub(super) fn interrupt_finish(&mut self) {
        let routines = std::mem::take(&mut self.ints.place_routines);
        for (i, (name, file, span, ran)) in std::mem::take(&mut self.ints.places).into_iter().enumerate() {
            if !ran && !routines.get(i).is_some_and(|r| self.ints.ran.contains(r)) {
                let msg = format!(
                    "{name}: the run assumes the interrupt input never switches while the routine is enabled, so \
                     its routine does not run (give --interrupt N@K to run it)"
                );
                self.diags.push(Diagnostic::warning("NC566", msg).primary(file, span, "here"));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_switches_and_headers() {
        assert_eq!(parse_interrupt("1@3").unwrap(), InterruptInput { input: 1, after: 3 });
        assert_eq!(parse_interrupt(" 8 @ 12 ").unwrap(), InterruptInput { input: 8, after: 12 });
        for bad in ["1", "0@1", "9@1", "1@0", "1@-2", "a@1", "1@x"] {
            assert!(parse_interrupt(bad).is_err(), "{bad}");
        }
        let t = "O1\n(nctrans: interrupt 1@2 1@5)\nG0 X0\n(nctrans: interrupt 1@9)\n";
        assert_eq!(header_interrupts(t).unwrap().len(), 2);
        assert!(header_interrupts("; nctrans: interrupt 1\nG0 X0\n").is_err());
        let s = State::new(vec![InterruptInput { input: 1, after: 5 }, InterruptInput { input: 2, after: 2 }]);
        assert_eq!(s.pending[0].after, 2);
        assert!(!s.due() && s.active());
    }
}
