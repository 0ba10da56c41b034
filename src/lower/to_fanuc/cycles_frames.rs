//! Sinumerik → FANUC drilling cycles beside the frame blocks the words pass wrote for
//! TRANS/ROT/AROT (`G69`, `G52 X0 Y0 Z0`, `G68 X0 Y0 R..`; `G51`, `G51.1` and their
//! cancels): whether such a block leaves the tool's level on the drilling axis where it was
//! (`cycles.rs` compares a cycle's RTP with it), and so whether an `MCALL` may stay open
//! across it (FANUC's cycle is closed with G80 before the frame block and opened again at
//! the next hole: docs/translation.md, "Drilling cycles under a rotation").

use super::*;

/// Whether the Z shift of G52 is known to be 0 (a main program starts without one), and
/// whether a G68/G69 came since the last block that named X and Y (`turned`).
pub(super) struct Shift(bool, bool);

/// The G codes (×10) of frame blocks, whose X Y Z are no positions.
const FRAME_G: [i64; 9] = [680, 690, 520, 500, 510, 501, 511, 920, 100];

impl Shift {
    pub(super) fn start(top: bool) -> Shift {
        Shift(top, false)
    }

    /// A structure may hold a G52 of its own: the shift after it is not known here.
    pub(super) fn pass(&mut self, s: &Stmt) {
        if !matches!(s.kind, StmtKind::Block(_)) {
            self.0 = false;
        }
    }

    /// Whether a rotation changed (G68/G69) since the last block naming both X and Y: FANUC
    /// keeps the programmed value of a plane axis left out, which the new rotation turns;
    /// Sinumerik drills where the tool stands (the FANUC run refuses that hole, NC496).
    pub(super) fn turned(&self) -> bool {
        self.1
    }

    /// Notes the block's positioning: `false` when the frame turned since the last X Y and
    /// this block names only one of them.
    pub(super) fn positioned(&mut self, items: &[Item]) -> bool {
        let g = |it: &Item| match &it.kind {
            ItemKind::Word(w) if w.addr.is(b'G') => match &w.value {
                WordValue::Expr(e) => crate::lower::literal(e).map(|v| (v * 10.0).round() as i64),
                _ => None,
            },
            _ => None,
        };
        if items.iter().filter_map(g).any(|v| FRAME_G.contains(&v)) {
            return true;
        }
        let has = |l: u8| items.iter().any(|it| matches!(&it.kind, ItemKind::Word(w) if w.addr.is(l)));
        match (has(b'X'), has(b'Y')) {
            (true, true) => {
                self.1 = false;
                true
            }
            (false, false) => true,
            _ => !self.1,
        }
    }

    /// For a block of frame codes only (G68/G69, G52, G51/G50, G51.1/G50.1, no motion):
    /// `Some(true)` when the programmed level of Z is the same after it (a rotation in the
    /// XY plane, a G52 whose Z shift stays 0), `Some(false)` when it may change (a Z shift,
    /// a scale or mirror, which may take Z, a rotation naming a Z centre); `None` for any
    /// other block.
    pub(super) fn frame_block(&mut self, b: &Block) -> Option<bool> {
        let mut frame = false;
        let mut keeps = true;
        let mut z = None;
        for it in &b.items {
            let ItemKind::Word(w) = &it.kind else { return None };
            let v = match &w.value {
                WordValue::Expr(e) => crate::lower::literal(e),
                _ => None,
            };
            match (w.addr.as_str(), v) {
                ("G", Some(g)) if [68.0, 69.0, 52.0].contains(&g) => frame = true,
                ("G", Some(g)) if [50.0, 51.0, 50.1, 51.1].contains(&g) => (frame, keeps) = (true, false),
                ("G", _) => return None,
                ("Z", v) => z = Some(v),
                _ => {}
            }
        }
        if !frame {
            return None;
        }
        self.1 |= b.items.iter().any(|it| {
            matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'G') && matches!(&w.value, WordValue::Expr(e) if matches!(crate::lower::literal(e), Some(g) if g == 68.0 || g == 69.0)))
        });
        let g52 = b.items.iter().any(|it| {
            matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'G') && matches!(&w.value, WordValue::Expr(e) if crate::lower::literal(e) == Some(52.0)))
        });
        match (g52, z) {
            (true, Some(v)) => {
                keeps &= self.0 && v == Some(0.0);
                self.0 = v == Some(0.0);
            }
            (false, Some(_)) => keeps = false,
            _ => {}
        }
        Some(keeps)
    }
}

/// A frame block while an `MCALL` of `f` is open: FANUC's cycle is cancelled before it
/// (G80) when a hole was drilled, and the next hole block opens it again (the tool stands
/// at RTP then, FANUC's initial level: no approach). A block that may move the levels of Z
/// is refused: Sinumerik reads RTP, RFP and DP in the new frame, FANUC's G98 returns to
/// where the tool stood.
pub(super) fn across(ctx: &mut Ctx, keeps: bool, first: &mut bool, cancel: Vec<Item>, span: Span, out: &mut Vec<Stmt>) {
    if !keeps {
        out.extend(ctx.unsupported(
            "NC652",
            span,
            "a frame change that may move the drilling axis (a Z shift, scale or mirror) while MCALL of a drilling cycle is open",
            "end the cycle with MCALL before the frame change and call it again after it",
        ));
        return;
    }
    if std::mem::take(first) {
        out.push(block_stmt(cancel, span));
    }
}

/// The refusal of a hole that would be FANUC's first move after a G68/G69 with a plane
/// axis left out.
pub(super) fn first_hole(ctx: &mut Ctx, span: Span, out: &mut Vec<Stmt>) {
    out.extend(ctx.unsupported(
        "NC653",
        span,
        "a drilling cycle as the first move after a rotation changed, without both X and Y",
        "position the hole with G0 X.. Y.. (both axes) after ROT/AROT, before the cycle",
    ));
}
