//! Chamfers and roundings in the run: the move of a block with a corner word is held until
//! the next block's move is known, then written shortened, followed by the chamfer line or
//! the rounding arc and the next move (geometry: `eval::corner`). Anything the controls'
//! manuals do not settle is refused with a diagnostic, never run as a sharp corner.

use super::{clean, Event, Fault, Machine, Span, WordVal};
use crate::eval::corner::{self, Kind, BAD_CORNER, CORNER_FEED, NO_NEXT_MOVE};
use crate::eval::trace::{Axes, Plane};

/// How the frame `x` maps the corner's plane (axes `u`, `v`): `None` where it keeps lengths
/// and angles there (turns, shifts and mirrors, in either orientation; a scale of the third
/// axis alone leaves the plane as it is), else `Some(uniform)`, whether it scales the plane
/// by one factor. Where it keeps them, chamfers and roundings are the same figures in the
/// workpiece coordinates the run keeps as in the programmed ones, whose contour the frame
/// carries, so the corner is made there: its legs and radius are lengths the map keeps, and
/// a mirror turns the rounding arc the other way by itself, as the controls swap G02/G03.
/// Whether the corner's size scales with a scaled plane is not settled ([`scaled`]).
fn plane_scaling(x: &super::Xform, u: usize, v: usize) -> Option<bool> {
    let a = &x.a;
    let dot = |i: usize, j: usize| (0..3).map(|k| a[k][i] * a[k][j]).sum::<f64>();
    let orthogonal = dot(u, v).abs() < 1e-12;
    if orthogonal && (dot(u, u) - 1.0).abs() < 1e-12 && (dot(v, v) - 1.0).abs() < 1e-12 {
        return None;
    }
    // Equal lengths at a right angle: a similarity (a uniform factor), else the plane is distorted.
    Some(orthogonal && (dot(u, u) - dot(v, v)).abs() < 1e-12)
}

/// The refusal of a corner under a frame that scales (SCALE/ASCALE, G51 with a factor other
/// than ±1): whether the chamfer's leg or the radius is scaled with the contour or kept in
/// workpiece units is not stated by any source read (docs/semantics.md, "Chamfers and
/// roundings"), and under unequal factors a scaled rounding would not be a circle at all.
fn scaled(kind: Kind, uniform: bool, span: Span) -> Fault {
    let what = if uniform {
        "whether the control scales its size with the contour or keeps it in workpiece units is not stated in the sources read"
    } else {
        "the factors differ in the plane, where a scaled rounding is no circle, and what the control makes (an alarm, or the size in workpiece units) is not stated in the sources read"
    };
    refuse(
        BAD_CORNER,
        format!("a corner ({}) under a frame that scales is not modelled: {what}", kind.name()),
        span,
        "write the corner as its own G1 or G2/G3 move, or cancel the scaling (G50, SCALE) around the contour",
    )
}

/// A corner word of the block being run (or the modal rounding in force).
#[derive(Clone, Copy, Debug)]
pub struct CornerWord {
    pub kind: Kind,
    /// In mm, after units and the FANUC decimal-point rule.
    pub size: f64,
    pub span: Span,
    /// From `RNDM=` (a block without a move then simply has no corner).
    pub modal: bool,
    /// The block's motion is a plain G0–G3 move (no cycle, dwell, reference return, G53,
    /// probe or polar coordinates; the frame is judged where the corner is made).
    pub plain: bool,
}

/// A move held back until the next block's move is known.
#[derive(Clone, Debug)]
pub struct Held {
    word: CornerWord,
    /// Where the held move starts (after a corner before it) and its corner, in the plane.
    start: (f64, f64),
    corner: (f64, f64),
    /// The machine position at the corner (every axis).
    at: [f64; 9],
    to: Axes,
    plane: Plane,
    f: Option<f64>,
    span: Span,
}

/// The corner state of a run.
#[derive(Clone, Debug, Default)]
pub struct Corners {
    pub held: Option<Held>,
    /// Siemens `RNDM=r`: every following corner is rounded with r (in mm) until `RNDM=0`.
    pub modal: Option<(f64, Span)>,
    /// The corner word of the block being run, set by the word loop.
    pub word: Option<CornerWord>,
}

impl Corners {
    /// A corner is held or may be made by the next block: the literal fast path stays off.
    pub fn active(&self) -> bool {
        self.held.is_some() || self.modal.is_some()
    }

    /// The span of the held corner's word, if one is held.
    pub fn held_span(&self) -> Option<Span> {
        self.held.as_ref().map(|h| h.word.span)
    }
}

fn refuse(code: &'static str, msg: String, span: Span, hint: &str) -> Fault {
    Fault::error(crate::diag::Diagnostic::error(code, msg).primary(usize::MAX, span, "corner").hint(hint))
}

/// `,C` and `,R` (or two of CHR, CHF, RND) in one block: an error on FANUC-compatible
/// controls (docs/semantics.md, F-CR1), which one a Siemens makes is not stated.
pub(super) fn two_in_one_block(span: Span) -> Fault {
    refuse(
        BAD_CORNER,
        "two corner words in one block: a block ends in one corner".into(),
        span,
        "keep either the chamfer or the rounding",
    )
}

/// FRC/FRCM: a corner feed of its own, which the trace's moves do not carry.
pub(super) fn own_feed(word: &str, span: Span) -> Fault {
    Fault::error(
        crate::diag::Diagnostic::error(
            crate::eval::corner::CORNER_FEED,
            format!("{word} (a feed of its own for chamfers and roundings) is not modelled"),
        )
        .primary(usize::MAX, span, "here")
        .hint("leave the corner at the path feed F"),
    )
}

fn describe(ev: &Event) -> &'static str {
    match ev {
        Event::Move { rapid: true, .. } => "a rapid move (G0)",
        Event::Move { probe: true, .. } => "a probing move",
        Event::Move { .. } => "a move",
        Event::Arc { .. } => "an arc (G2/G3): corners next to arcs are not modelled yet",
        Event::Dwell { .. } => "a dwell",
        Event::Tool { .. } => "a tool change",
        Event::Spindle { .. } => "a spindle command",
        Event::Coolant { .. } => "a coolant command",
        Event::Comp(_) => "a change of tool compensation",
        Event::Stop { .. } | Event::Message { .. } => "a stop or a message",
        _ => "another machine function",
    }
}

impl Machine {
    /// The block's corner words (`CHR`/`CHF`/`RND`, Siemens `RNDM`): the corner this block's
    /// move ends in, if any. `plain`: see [`CornerWord::plain`].
    pub(super) fn corner_words(
        &mut self,
        corner: Option<(&WordVal, f64)>,
        rndm: Option<(&WordVal, f64)>,
        plain: bool,
    ) -> Result<(), Fault> {
        if let Some((w, x)) = rndm {
            self.corners.modal = (x != 0.0).then(|| (self.length(w, x, false), w.span));
        }
        let explicit = match corner {
            Some((w, x)) => {
                let Some(kind) = Kind::of_name(&w.addr) else { return Err(crate::eval::exec::internal()) };
                Some(CornerWord { kind, size: self.length(w, x, false), span: w.span, modal: false, plain })
            }
            None => None,
        };
        if let (Some(w), Some(_)) = (explicit, self.corners.modal) {
            return Err(refuse(
                BAD_CORNER,
                format!(
                    "{} while modal rounding (RNDM) is in force: which one the control makes is not settled",
                    w.kind.name()
                ),
                w.span,
                "switch modal rounding off (RNDM=0) before a block with its own corner",
            ));
        }
        let modal =
            self.corners.modal.map(|(size, span)| CornerWord { kind: Kind::Radius, size, span, modal: true, plain });
        self.corners.word = explicit.or(modal);
        Ok(())
    }

    /// After the block's words ran (`before`: the machine position when it began, `start`:
    /// where its events begin in `out`): joins a held corner with this block's move and holds
    /// this block's move if it has a corner of its own.
    pub(super) fn corner_after_block(
        &mut self,
        before: [f64; 9],
        out: &mut Vec<(Event, Span)>,
        start: usize,
        ends: bool,
        block_span: Span,
    ) -> Result<(), Fault> {
        let word = self.corners.word.take();
        let mut from = None;
        if let Some(h) = self.corners.held.take() {
            from = Some(self.join(h, out, start, block_span)?);
        }
        let Some(w) = word else { return Ok(()) };
        let is_move = |e: &Event| matches!(e, Event::Move { .. } | Event::Arc { .. });
        let last_move = out.len() > start && out.last().is_some_and(|(e, _)| is_move(e));
        if !last_move {
            let moved = out[start..].iter().any(|(e, _)| is_move(e));
            if moved {
                return Err(refuse(
                    BAD_CORNER,
                    format!(
                        "{} in a block with functions after its move (M5, M9, M0, M1): not modelled",
                        w.kind.name()
                    ),
                    w.span,
                    "put those functions in a block of their own after the contour",
                ));
            }
            if w.modal {
                return Ok(());
            }
            return Err(refuse(
                BAD_CORNER,
                format!("{} in a block without a move: the corner ends a move", w.kind.name()),
                w.span,
                "write the corner word in the block of the move that leads to the corner",
            ));
        }
        if out[start..].iter().any(|(e, _)| matches!(e, Event::WorkOffset { .. } | Event::Home(_))) {
            return Err(refuse(
                BAD_CORNER,
                "a corner in a block that changes the work offset: the move before it is not one line".into(),
                w.span,
                "select the work offset in a block before the contour",
            ));
        }
        let (u, v, _) = self.modal.plane.axes();
        let (ev, span) = out.pop().unwrap_or((Event::Dwell { seconds: 0.0 }, block_span));
        if let Some(uniform) = plane_scaling(&self.xf, u, v) {
            return Err(scaled(w.kind, uniform, w.span));
        }
        let why = match &ev {
            _ if !w.plain => {
                Some("a move of a cycle, a reference return, G53, a probe or polar coordinates".to_string())
            }
            Event::Move { rapid: false, probe: false, .. } => None,
            other => Some(describe(other).to_string()),
        };
        if let Some(why) = why {
            return Err(refuse(
                BAD_CORNER,
                format!("a corner ({}) after {why} is not modelled: only a G1 line to a G1 line is", w.kind.name()),
                w.span,
                "write the corner as its own G1 or G2/G3 move",
            ));
        }
        if ends {
            return Err(refuse(
                NO_NEXT_MOVE,
                "the block with the corner ends the program or returns: there is no next move".into(),
                w.span,
                "program the move after the corner before the end",
            ));
        }
        if (0..9).any(|i| i != u && i != v && (before[i] - self.pos[i]).abs() > 1e-9) {
            return Err(refuse(
                BAD_CORNER,
                "the move before the corner leaves the working plane: corners are made in the plane".into(),
                w.span,
                "move the other axes in a block of their own",
            ));
        }
        let Event::Move { to, f, .. } = ev else { return Ok(()) };
        self.corners.held = Some(Held {
            word: w,
            start: from.unwrap_or((before[u], before[v])),
            corner: (self.pos[u], self.pos[v]),
            at: self.pos,
            to,
            plane: self.modal.plane,
            f,
            span,
        });
        Ok(())
    }

    /// Writes the held move shortened and its corner before this block's move (the events
    /// from `start`); returns where this block's move now starts in the plane.
    fn join(&mut self, h: Held, out: &mut Vec<(Event, Span)>, start: usize, span: Span) -> Result<(f64, f64), Fault> {
        let w = h.word;
        let next = &out[start..];
        let why = match next {
            [(Event::Move { rapid: false, probe: false, .. }, _)] => None,
            [] => Some("a block without a move".to_string()),
            [(ev, _)] => Some(describe(ev).to_string()),
            [(ev, _), ..] => Some(format!("{} and more in the same block", describe(ev))),
        };
        if let Some(why) = why {
            return Err(Fault::error(
                crate::diag::Diagnostic::error(
                    NO_NEXT_MOVE,
                    format!("the corner ({}) needs the next block to be a G1 move in the plane; it is {why}", w.kind.name()),
                )
                .primary(usize::MAX, w.span, "corner")
                .secondary(usize::MAX, span, "next block")
                .note("FANUC: the block after chamfering or corner R must be a move; Siemens: the corner is made with the next move in the plane, the blocks between and what they take is machine data")
                .hint("put the next move of the contour right after the block with the corner"),
            ));
        }
        let (u, v, _) = h.plane.axes();
        if self.modal.plane != h.plane || (0..9).any(|i| i != u && i != v && (h.at[i] - self.pos[i]).abs() > 1e-9) {
            return Err(refuse(
                BAD_CORNER,
                "the move after the corner leaves the working plane (or the plane changed)".into(),
                w.span,
                "corners are made between two moves in the selected plane",
            ));
        }
        let Some((Event::Move { f, .. }, _)) = out.get(start) else { return Err(crate::eval::exec::internal()) };
        if *f != h.f {
            return Err(refuse(
                CORNER_FEED,
                "the moves before and after the corner have different feeds: which one the corner takes is not settled"
                    .into(),
                w.span,
                "program the same F for both moves (FANUC does not document it; Siemens takes it from MD20201)",
            ));
        }
        let end = (self.pos[u], self.pos[v]);
        let c = corner::line_line(h.start, h.corner, end, w.kind, w.size).map_err(|b| {
            refuse(
                BAD_CORNER,
                format!("the corner ({}) cannot be made: {}", w.kind.name(), b.text()),
                w.span,
                "FANUC stops with an alarm; Siemens reduces the corner by a rule not modelled: make the corner smaller",
            )
        })?;
        let at = |p: (f64, f64)| {
            let mut to = h.to;
            to[u] = Some(clean(p.0));
            to[v] = Some(clean(p.1));
            to
        };
        let first = (Event::Move { rapid: false, to: at(c.end1), f: h.f, probe: false }, h.span);
        let cut = match c.arc {
            None => Event::Move { rapid: false, to: at(c.start2), f: h.f, probe: false },
            Some((centre, cw)) => Event::Arc {
                cw,
                plane: h.plane,
                to: at(c.start2),
                center: [(u, clean(centre.0)), (v, clean(centre.1))],
                f: h.f,
            },
        };
        out.splice(start..start, [first, (cut, h.span)]);
        Ok(c.start2)
    }
}
