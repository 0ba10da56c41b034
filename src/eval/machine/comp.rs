//! Tool length and cutter radius compensation: the modal state of both controls and the
//! `comp` event (trace format v2) emitted at every change of it.
//!
//! FANUC: group 08 (G43 / G44 / G49) with the modal H number, group 07 (G40 / G41 / G42)
//! with the modal D number; H0 and D0 are offset 0, so no compensation (0i-MB B-63844EN
//! 14.1; 15i-MA: "0 has been commanded as the offset number" cancels cutter compensation).
//! Siemens: the active cutting edge D of the tool in the spindle carries length and radius;
//! D0 deselects it; a tool change (M6) selects the edge of MD20270 (factory setting 1,
//! D1) unless the M6 block programs a D (840D sl function manual W1 §2.1). G41/G42/G40 set
//! the side; the radius applies while an edge is active. Positions stay the programmed
//! contour: the trace holds which register is in force, not the offset path.
//!
//! A D programmed while a tool is preselected (T before its M6, MD22550 = 1) selects an
//! edge of the tool still in the spindle (W1 §2.1: "on the active tool"), whose length acts
//! at the first traversing motion; its `comp` event is held until an event that could
//! show it (a move, a cycle, …) and dropped when the M6 changes the tool first: a length
//! the control never applies is not in the trace (docs/semantics.md, "Edge before M6").

use crate::eval::trace::{CompEv, CompReg, Side, ToolId};
use crate::span::Span;

/// MD20270 `$MC_CUTTING_EDGE_DEFAULT`'s factory setting: the edge a tool change selects when
/// its block programs none (the profile may state another, `Semantics::cutting_edge_default`).
pub const CUTTING_EDGE_DEFAULT: u32 = 1;

/// The compensation words of one block, gathered by `Machine::apply_words`.
#[derive(Clone, Debug, Default)]
pub struct BlockComp {
    /// The last group 08 code of the block (430, 440, 490), FANUC only.
    pub length_g: Option<(i64, Span)>,
    /// The last group 07 code of the block (400, 410, 420).
    pub radius_g: Option<(i64, Span)>,
    pub d: Option<(f64, Span)>,
    pub h: Option<(f64, Span)>,
}

impl BlockComp {
    pub fn is_empty(&self) -> bool {
        self.length_g.is_none() && self.radius_g.is_none() && self.d.is_none() && self.h.is_none()
    }
}

/// The compensation state of a machine.
#[derive(Clone, Debug, PartialEq)]
pub struct Comp {
    /// FANUC group 08: 430 (G43), 440 (G44) or 490 (G49, power-on).
    pub length_g: i64,
    /// Group 07 (both controls): `None` for G40 (power-on), else the side.
    pub side: Option<Side>,
    /// Siemens: the active edge number (0: D0, power-on: no tool, no edge).
    pub edge: u32,
    /// What the last `comp` event said (power-on: everything off).
    pub last: CompEv,
    /// The edge a tool change without D selects (MD20270, [`CUTTING_EDGE_DEFAULT`]).
    pub edge_default: u32,
    /// Siemens: the event of an edge selected before the M6 of a preselected tool, not yet
    /// applied by any motion (see the module comment); `last` is still the one before it.
    pub held: Option<(CompEv, Span)>,
}

impl Default for Comp {
    fn default() -> Self {
        Comp {
            length_g: 490,
            side: None,
            edge: 0,
            last: CompEv::default(),
            edge_default: CUTTING_EDGE_DEFAULT,
            held: None,
        }
    }
}

impl Comp {
    /// The state as the trace writes it. `tool`: the tool in the spindle (Siemens);
    /// `h`, `d`: the modal H and D numbers (FANUC).
    pub fn event(&self, fanuc: bool, tool: Option<&ToolId>, h: f64, d: f64) -> CompEv {
        if fanuc {
            let length = (self.length_g != 490 && h != 0.0).then_some(CompReg::Fanuc(h as i64));
            let radius = self.side.filter(|_| d != 0.0).map(|s| (s, CompReg::Fanuc(d as i64)));
            CompEv { length, radius }
        } else {
            let reg = (self.edge != 0).then(|| CompReg::Edge(edge_name(tool, self.edge)));
            CompEv { length: reg.clone(), radius: self.side.zip(reg) }
        }
    }
}

/// A Siemens register as the trace names it: `"T.D"`, the tool as in `tool` events
/// (`"5.1"`, `"DRILL_D10.1"`); `"0.D"` for an edge selected with no tool in the spindle.
pub fn edge_name(tool: Option<&ToolId>, edge: u32) -> String {
    match tool {
        Some(ToolId::Number(n)) => format!("{}.{edge}", crate::eval::value::fmt_num(*n)),
        Some(ToolId::Name(s)) => format!("{s}.{edge}"),
        None => format!("0.{edge}"),
    }
}

impl super::Machine {
    /// Applies a block's compensation words after its tool change (`changed`: the block
    /// changed the tool with M6); pushes a `comp` event when the state the trace sees
    /// changed. Runs for every block (a tool change alone changes a Siemens edge).
    pub(crate) fn apply_comp(
        &mut self,
        b: &BlockComp,
        changed: bool,
        out: &mut Vec<(crate::eval::trace::Event, Span)>,
        warns: &mut Vec<super::Warn>,
        block_span: Span,
    ) {
        if b.is_empty() && !changed {
            return;
        }
        if let Some((h, _)) = b.h {
            self.h = crate::eval::value::round_half_away(h);
        }
        if let Some((d, _)) = b.d {
            self.d = crate::eval::value::round_half_away(d);
        }
        if let Some((g, span)) = b.length_g {
            if self.fanuc {
                self.comp.length_g = g;
                self.set_group_g(8, g);
                if g == 440 {
                    // The trace names the register, not its sign: G43 and G44 with one H
                    // would trace alike, so `check` does not call such programs equivalent.
                    warns.push((
                        super::COMPENSATION_NOTE,
                        "G44 (negative tool length offset) is run as a length register; the trace does not \
                         hold its direction"
                            .into(),
                        span,
                    ));
                }
            }
        }
        if let Some((g, _)) = b.radius_g {
            self.comp.side = match g {
                410 => Some(Side::Left),
                420 => Some(Side::Right),
                _ => None,
            };
            self.set_group_g(7, g);
        }
        if !self.fanuc {
            if let Some((d, _)) = b.d {
                self.comp.edge = d.max(0.0) as u32;
            } else if changed {
                self.comp.edge = self.comp.edge_default;
            }
            // `$P_TOOL` reads the active edge.
            self.d = f64::from(self.comp.edge);
        }
        let now = self.comp.event(self.fanuc, self.tool.as_ref(), self.h, self.d);
        let span = [b.length_g.map(|x| x.1), b.radius_g.map(|x| x.1), b.d.map(|x| x.1), b.h.map(|x| x.1)]
            .into_iter()
            .flatten()
            .reduce(|a, s| a.to(s))
            .unwrap_or(block_span);
        // An edge of the tool still in the spindle, selected while another is preselected:
        // held (its length acts at the first traverse, the M6 may replace it first).
        let preselected = self.tool_sel.is_some() && self.tool_sel != self.tool;
        if !self.fanuc && !changed && b.d.is_some() && b.radius_g.is_none() && preselected {
            self.comp.held = (now != self.comp.last).then_some((now, span));
            return;
        }
        match self.comp.held.take() {
            // The tool change comes before any motion: the held edge never acted.
            Some(_) if changed => {}
            Some((h, hs)) => {
                self.comp.last = h.clone();
                out.push((crate::eval::trace::Event::Comp(Box::new(h)), hs));
            }
            None => {}
        }
        if now != self.comp.last {
            self.comp.last = now.clone();
            out.push((crate::eval::trace::Event::Comp(Box::new(now)), span));
        }
    }

    /// The held `comp` event (see [`Comp::held`]) if `ev` is one it must come before: any
    /// event but those that cannot show a tool length (spindle, coolant, a dwell, a work
    /// offset selection) or that come with the tool change replacing it.
    pub(crate) fn release_held(&mut self, ev: &crate::eval::trace::Event) -> Option<(CompEv, Span)> {
        use crate::eval::trace::Event as E;
        if matches!(ev, E::Spindle { .. } | E::Coolant { .. } | E::Dwell { .. } | E::WorkOffset { .. } | E::Tool { .. })
        {
            return None;
        }
        let (h, s) = self.comp.held.take()?;
        self.comp.last = h.clone();
        Some((h, s))
    }

    /// After a Siemens SAVE subprogram restored group 07: the `comp` event of the change.
    pub(crate) fn comp_restored(&mut self) -> Option<crate::eval::trace::Event> {
        // A held edge is in force when the return restores the side: the event says it.
        self.comp.held = None;
        let now = self.comp.event(self.fanuc, self.tool.as_ref(), self.h, self.d);
        (now != self.comp.last).then(|| {
            self.comp.last = now.clone();
            crate::eval::trace::Event::Comp(Box::new(now))
        })
    }
}
