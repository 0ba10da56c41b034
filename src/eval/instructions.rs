//! Siemens value-less instructions that run without a trace event, each with the warning
//! that says why: interrupts (`SETINT(n) PRIO=p NAME`, `ENABLE(n)`, `DISABLE(n)`,
//! `CLRINT(n)`, FANUC `M96 P…`/`M97`: run by `interrupt.rs`, the routine only where a test
//! input switches), feed-forward control (`FFWON`/`FFWOF`: a look-ahead setting, not compared), and the
//! rest (`SOFT`, `CFC`, …: no effect on the trace). FANUC output the reader keeps as written
//! (`BPRNT`, a DPRNT it does not read) warns NC554: its text is not compared.

use super::exec::Interp;
use crate::span::Span;

/// An interrupt instruction as the readers keep it (`SETINT(3) PRIO=1 NAME`, `ENABLE(3)`,
/// `DISABLE(3)`, `CLRINT(3)`; FANUC `M96 P9000`, `M97` where the profile has the custom
/// macro interrupt).
pub fn is_interrupt(name: &str) -> bool {
    ["SETINT(", "ENABLE(", "DISABLE(", "CLRINT(", "M96 P"].iter().any(|p| name.starts_with(p)) || name == "M97"
}

/// Instructions that switch the facing axis to diameter values (Siemens DIAMON, DIAM90,
/// and their axis-wise forms).
const DIAMETER_ON: [&str; 4] = ["DIAMON", "DIAM90", "DIAMONA", "DIAM90A"];

/// Instructions that change where the programmed positions take the tool (a kinematic
/// transformation, a frame aligned to the tool or the holder, the approach path under
/// cutter compensation), with what they do. Their off forms (TRAFOOF, PAROTOF, TOROTOF) and
/// the default NORM change nothing the run does not model.
const MOVES_OTHERWISE: [(&str, &str); 8] = [
    ("TRANSMIT", "the face-end transformation: X, Y become polar motion of X and the C axis"),
    ("TRACYL", "the peripheral-surface transformation: Y becomes a rotation of the cylinder"),
    ("TOFRAME", "a frame aligned to the tool's orientation"),
    ("PAROT", "a frame rotated to the workpiece holder"),
    ("TOROT", "a frame rotated to the tool's orientation"),
    ("KONT", "approach and retract around the contour's end point under G41/G42"),
    ("KONTC", "approach and retract on a curvature-continuous path under G41/G42"),
    ("KONTT", "approach and retract on a tangent-continuous path under G41/G42"),
];

impl Interp<'_> {
    pub(super) fn warn_instruction(&mut self, name: &str, span: Span) -> Result<(), super::fault::Fault> {
        if is_interrupt(name) {
            // Run by `interrupt.rs`; a routine that never runs is warned of at the run's end.
            return self.interrupt_op(name, span);
        } else if super::print::is_external_device(name) {
            return Err(super::print::external_device(name, span, self.file()));
        } else if name.starts_with("DPRNT[") || name.starts_with("BPRNT[") {
            let why = if name.starts_with("BPRNT[") {
                "binary output is not text"
            } else {
                "it holds a character the sources do not list for DPRNT (letters, digits, + - /, * for a space)"
            };
            let msg = format!("{name}: the output is not modelled ({why}), so it is not compared");
            self.warn(super::print::PRINT_NOT_MODELLED, msg, span);
        } else if DIAMETER_ON.contains(&name) {
            // X in diameter: the machine goes to half of every X the trace would show.
            return Err(super::fault::Fault::error(
                crate::diag::Diagnostic::error(
                    "NC403",
                    format!("{name} (diameter programming of the facing axis) is not modelled by the evaluator"),
                )
                .primary(self.file(), span, "here")
                .note("under it every X value is a diameter, so the tool goes to half of it; the trace would show the programmed value and call a radius program equivalent")
                .hint("program the facing axis in radius (DIAMOF) for a proof"),
            ));
        } else if let Some(why) = MOVES_OTHERWISE.iter().find(|(n, _)| *n == name).map(|(_, w)| w) {
            return Err(super::fault::Fault::error(
                crate::diag::Diagnostic::error("NC403", format!("{name} ({why}) is not modelled by the evaluator"))
                    .primary(self.file(), span, "here")
                    .note("the trace would show the programmed values as if it were not there, and call a program without it equivalent")
                    .hint("prove the program without it; its motion has no counterpart the run models"),
            ));
        } else if name == "FGROUP" {
            // `FGROUP()` is the default group; no source says the bare word is the same.
            return Err(super::fault::Fault::error(
                crate::diag::Diagnostic::error(
                    super::machine::path_feed::FGROUP_AXIS,
                    "FGROUP without parentheses: whether it selects the default feed group as FGROUP() does is not stated",
                )
                .primary(self.file(), span, "here")
                .hint("write FGROUP() for the default group (X, Y, Z), or FGROUP(X,Y,Z,A) naming the axes"),
            ));
        } else if name == "FFWON" || name == "FFWOF" {
            let what = if name == "FFWON" { "on" } else { "off" };
            let msg = format!(
                "{name} (feed-forward control {what}) changes how the control plans feed and corners, \
                 not the programmed positions: not compared"
            );
            self.warn(super::machine::lookahead::NOT_COMPARED, msg, span);
        } else {
            self.warn("NC405", format!("{name} has no effect on the trace"), span);
        }
        Ok(())
    }
}
