//! Constructs the evaluator reads but cannot run exactly, each with the error that names it
//! and says why the trace cannot carry it (a run that guessed would make "equivalent" a lie).

use super::fault::Fault;
use crate::diag::Diagnostic;
use crate::ir::{RotaryMode, SyncAction, Word};
use crate::span::{FileId, Span};

/// Why a rotary positioning word has no exact counterpart: shared with the translator.
pub const ROTARY_WHY: &str = "the direction (ACP/ACN/DC) or coded position (CAC…) of a rotary-axis move is \
     machine data and interpolation, not a programmed end point; the trace records end points only and \
     FANUC has no word that chooses the direction";

/// `C=ACP(…)` and its kin.
pub fn rotary(file: FileId, w: &Word, m: RotaryMode) -> Fault {
    Fault::error(
        Diagnostic::error("NC430", format!("{}={}(…) is not modelled by the evaluator", w.addr.as_str(), m.name()))
            .primary(file, w.span, "rotary-axis positioning")
            .note(ROTARY_WHY)
            .hint(format!(
                "write the end position as a plain value (`{}=…`) if the direction does not matter",
                w.addr.as_str()
            )),
    )
}

/// A short description of a synchronized action, for messages: `ID=1 WHEN … DO DELDTG`.
pub fn sync_name(a: &SyncAction) -> String {
    let mut s = String::from("synchronized action");
    if let Some((scope, _)) = &a.id {
        s.push_str(if *scope == crate::ir::SyncScope::Static { " IDS=…" } else { " ID=…" });
    }
    if let Some((t, _)) = &a.trigger {
        s.push(' ');
        s.push_str(t.name());
        s.push_str(" …");
    }
    s.push_str(" DO …");
    s
}

/// Why a synchronized action cannot be carried: shared with the translator.
pub const SYNC_WHY: &str = "a synchronized action is checked in every interpolation cycle beside the \
     program (inputs, measured positions, distance to go); the trace has no interpolation cycle and FANUC \
     Macro B has no counterpart";

pub fn sync_action(file: FileId, span: Span, a: &SyncAction) -> Fault {
    Fault::error(
        Diagnostic::error("NC431", format!("{} is not modelled by the evaluator", sync_name(a)))
            .primary(file, span, "runs beside the program in the interpolation cycle")
            .note(SYNC_WHY)
            .hint("the program cannot be run or proven with it; remove or rewrite the action by hand"),
    )
}
