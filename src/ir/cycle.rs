//! Drilling cycles as meaning, shared by both dialects: what kind of hole, where the tool
//! returns, and one drilled hole as the trace's `cycle` event reports it
//! (docs/trace-format.md, format v2). FANUC G73–G89 and Siemens CYCLE81–CYCLE89 are
//! spellings of these; the dialects map their codes onto [`CycleKind`].

/// What a drilling cycle does in the hole (the trace's `kind`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CycleKind {
    /// Feed to the bottom, rapid out (FANUC G81, Siemens CYCLE81).
    Drill,
    /// Feed to the bottom, dwell, rapid out (G82, CYCLE82).
    DwellDrill,
    /// Peck with a full retract to the R plane after every infeed (G83, CYCLE83 chip removal).
    Peck,
    /// Peck with a short retract to break the chip (G73, CYCLE83 chip breaking).
    ChipBreak,
    /// Tapping with the spindle turning clockwise in (G84, CYCLE84/CYCLE840).
    Tap,
    /// Left-hand tapping, spindle counter-clockwise in (G74).
    TapLeft,
    /// Feed in, feed out (G85, CYCLE85).
    Bore,
    /// Feed in, spindle stop at the bottom, rapid out (G86).
    BoreStop,
    /// Feed in, dwell, feed out (G89, CYCLE89).
    BoreDwell,
    /// Back boring from below: positioned under the part, feeds upward (G87).
    BackBore,
    /// Fine boring: oriented spindle stop and shift at the bottom, rapid out (G76).
    FineBore,
}

impl CycleKind {
    /// The name the trace writes.
    pub fn name(self) -> &'static str {
        match self {
            CycleKind::Drill => "drill",
            CycleKind::DwellDrill => "dwell_drill",
            CycleKind::Peck => "peck",
            CycleKind::ChipBreak => "chip_break",
            CycleKind::Tap => "tap",
            CycleKind::TapLeft => "tap_left",
            CycleKind::Bore => "bore",
            CycleKind::BoreStop => "bore_stop",
            CycleKind::BoreDwell => "bore_dwell",
            CycleKind::BackBore => "back_bore",
            CycleKind::FineBore => "fine_bore",
        }
    }

    /// The kinds that infeed in steps (a peck depth is required).
    pub fn pecks(self) -> bool {
        matches!(self, CycleKind::Peck | CycleKind::ChipBreak)
    }
}

/// Where the tool goes after the hole (the trace's `retract`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Retract {
    /// The level the tool stood at when the cycle mode began (FANUC G98; Siemens RTP).
    Initial,
    /// The R (reference) plane (FANUC G99; Siemens RFP + SDIS).
    R,
}

impl Retract {
    pub fn name(self) -> &'static str {
        match self {
            Retract::Initial => "initial",
            Retract::R => "r",
        }
    }
}

/// How a tapping cycle holds the tap (the trace's `tapping`, written for `tap` and
/// `tap_left` only): the feed is the same, the machine is not (a rigid holder in a
/// floating cycle, or the reverse, breaks the tap), so two traces must agree on it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Tapping {
    /// Spindle and feed axis interpolated (FANUC `M29 S` + G84/G74, Siemens CYCLE84).
    Rigid,
    /// A compensating (floating) holder, the spindle reversed at the bottom (FANUC G84/G74
    /// without M29, Siemens CYCLE840).
    Floating,
}

impl Tapping {
    pub fn name(self) -> &'static str {
        match self {
            Tapping::Rigid => "rigid",
            Tapping::Floating => "floating",
        }
    }
}

/// One hole as the trace reports it. Positions are in the trace's frame (workpiece
/// position plus the active work offset, like every `to`).
#[derive(Clone, Debug, PartialEq)]
pub struct Hole {
    pub kind: CycleKind,
    /// The two axes of the working plane (their indices in the trace's axis list) and the
    /// hole's position on each.
    pub at: [(usize, f64); 2],
    /// The R plane on the drilling axis.
    pub r: f64,
    /// The final depth on the drilling axis.
    pub bottom: f64,
    /// The depth of each infeed, for the pecking kinds.
    pub peck: Option<f64>,
    /// Seconds at the bottom.
    pub dwell: Option<f64>,
    pub retract: Retract,
    /// Feed in mm/min (mm/rev under G95).
    pub f: f64,
    /// Rigid or floating, for the tapping kinds (`None` for the others).
    pub tapping: Option<Tapping>,
}

impl Hole {
    /// The hole as both evaluators report it: a dwell of 0 is no dwell, and a dwelling
    /// kind without a dwell is the same motion as its kind without one (G82 P0 = G81,
    /// G89 P0 = G85, CYCLE82 with DTB 0 = CYCLE81), so they compare equal.
    pub fn normalised(mut self) -> Hole {
        if self.dwell.is_some_and(|d| d == 0.0) {
            self.dwell = None;
        }
        if self.dwell.is_none() {
            self.kind = match self.kind {
                CycleKind::DwellDrill => CycleKind::Drill,
                CycleKind::BoreDwell => CycleKind::Bore,
                k => k,
            };
        }
        self
    }
}
