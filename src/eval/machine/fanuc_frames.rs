//! FANUC scaling (G51/G50) and programmable mirror image (G51.1/G50.1), composed with the
//! G68 rotation in the order the controls apply them: mirror, then scaling, then rotation
//! (docs/semantics.md, "Rotation, scaling and mirroring").

use super::frames::{error, Xform};
use super::{AbsInc, Fault, Machine, Span, WordVal};

/// A FANUC `G51` scaling in force: the centre and the factor of each scaled axis (1 for
/// the others).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FanucScale {
    pub centre: [f64; 3],
    pub factor: [f64; 3],
}

impl FanucScale {
    fn xform(&self) -> Xform {
        let mut x = Xform::ID;
        for i in 0..3 {
            x.a[i][i] = self.factor[i];
            x.b[i] = self.centre[i] - self.factor[i] * self.centre[i];
        }
        x
    }
}

impl Machine {
    /// The frame of the FANUC modes in force: rotation ∘ scaling ∘ mirror; the centre of
    /// a rotation commanded in G51 mode is scaled too (30i user's manual B-63944EN-2,
    /// "Scaling and coordinate system rotation").
    pub(super) fn fanuc_compose(&mut self) {
        let mut m = Xform::ID;
        for (i, a) in self.mirror.iter().enumerate() {
            if let Some(a) = a {
                m.a[i][i] = -1.0;
                m.b[i] = 2.0 * a;
            }
        }
        let s = self.scale.map_or(Xform::ID, |s| s.xform());
        let mut x = s.after(&m);
        if let Some(r) = self.rot {
            let (u, v, _) = r.plane.axes();
            let mut c = [0.0; 3];
            c[u] = r.centre.0;
            c[v] = r.centre.1;
            let c = s.apply(c);
            x = Xform::rotation(r.plane, r.deg, (c[u], c[v])).after(&x);
        }
        self.set_xform(x);
    }

    /// The workpiece position of X, Y, Z (local coordinates) taken back through the
    /// scaling in force: the centre of a G68 or G51 written without one.
    pub(super) fn unscaled_position(&self) -> [f64; 3] {
        let w = [0, 1, 2].map(|i| self.pos[i] - self.active_offset(i));
        self.scale.map_or(w, |s| s.xform().invert(w).unwrap_or(w))
    }

    /// FANUC `G51 X.. Y.. Z.. P..` (or `I.. J.. K..`, a factor per axis): the axes whose
    /// centre the block names are scaled about it by the factor (P or their own of I J K;
    /// written without a decimal point in 0.001, parameter 5400#7 SCR = 0). No motion.
    pub(super) fn g51(
        &mut self,
        axes: &[Option<(&WordVal, f64)>; 9],
        ijk: &[Option<(&WordVal, f64)>; 3],
        p: Option<(&WordVal, f64)>,
        span: Span,
    ) -> Result<(), Fault> {
        let factor_of = |w: &WordVal, x: f64| if w.bare { x * 0.001 } else { x };
        let mut centre = [0.0; 3];
        let mut factor = [1.0; 3];
        let mut named = false;
        for i in 0..3 {
            let Some((w, x)) = axes[i] else { continue };
            if w.mode == AbsInc::Ic || (w.mode == AbsInc::Plain && !self.modal.absolute) {
                return Err(error(
                    "NC490",
                    "G51 with its centre under G91 is not modelled".into(),
                    w.span,
                    "give the centre of scaling under G90: `G90 G51 X.. Y.. P..`",
                ));
            }
            named = true;
            centre[i] = self.length(w, x, false);
            factor[i] = match (p, ijk[i]) {
                (_, Some((w, x))) => factor_of(w, x),
                (Some((w, x)), None) => factor_of(w, x),
                (None, None) => {
                    return Err(error(
                        "NC490",
                        "G51 without P or I J K (the factor is then a machine parameter)".into(),
                        span,
                        "write the factor: `G51 X0 Y0 P2000` (2×) or `P2.`",
                    ))
                }
            };
            if factor[i] == 0.0 {
                return Err(error("NC490", "G51 with the factor 0".into(), span, "a scale factor is not 0"));
            }
        }
        if !named || axes.iter().skip(3).any(Option::is_some) {
            return Err(error(
                "NC490",
                "G51 without the centre of the axes it scales (which axes scale is then machine parameter 5401)".into(),
                span,
                "name the centre in each axis to scale: `G51 X0 Y0 Z0 P..`",
            ));
        }
        self.scale = Some(FanucScale { centre, factor });
        self.fanuc_compose();
        Ok(())
    }

    /// FANUC `G51.1 X.. Y..`: each named axis is mirrored about that position (absolute);
    /// `G50.1 X0 ..`: the named axes are mirrored no more. No motion.
    pub(super) fn g51_1(&mut self, on: bool, axes: &[Option<(&WordVal, f64)>; 9], span: Span) -> Result<(), Fault> {
        if axes.iter().skip(3).any(Option::is_some) || axes.iter().all(Option::is_none) {
            return Err(error(
                "NC490",
                format!("G5{}.1 names no geometry axis X, Y, Z", if on { 1 } else { 0 }),
                span,
                "name the axes to mirror: `G51.1 X50.`; cancel with `G50.1 X0`",
            ));
        }
        for (i, a) in axes.iter().enumerate().take(3) {
            let Some((w, x)) = *a else { continue };
            if on && (w.mode == AbsInc::Ic || (w.mode == AbsInc::Plain && !self.modal.absolute)) {
                return Err(error(
                    "NC490",
                    "G51.1 with its axis of symmetry under G91 is not modelled".into(),
                    w.span,
                    "give the axis of symmetry under G90: `G90 G51.1 X..`",
                ));
            }
            self.mirror[i] = on.then(|| self.length(w, x, false));
        }
        self.fanuc_compose();
        Ok(())
    }

    /// FANUC `G92 X.. Y..`: the named axes' current position gets the given coordinates;
    /// every work offset moves by the same amount (Mitsubishi M700V, FANUC-compatible: "the
    /// other workpiece coordinate systems 2 through 6 (G55 to G59) will move in parallel").
    /// No motion. Under G91, with a G52 shift, or in the frame and polar modes: NC491.
    pub(super) fn g92_shift(&mut self, axes: &[Option<(&WordVal, f64)>; 9], span: Span) -> Result<(), Fault> {
        let incremental = !self.modal.absolute || axes.iter().flatten().any(|(w, _)| w.mode != AbsInc::Plain);
        let shifted = self.local.iter().any(|v| *v != 0.0);
        let framed = self.rot.is_some() || self.scale.is_some() || self.mirror.iter().any(Option::is_some);
        if incremental || shifted || self.framed || self.polar {
            // Under a frame mode: which coordinates G92 gives the tool (the programmed,
            // rotated ones or the unrotated local ones) and whether the rotation centre moves
            // with the new system is in no FANUC manual read (docs/semantics.md, "Rotation").
            let msg = if framed {
                "G92 under G68, G51 or G51.1 is not modelled: no FANUC source read says whether the coordinates it sets are the rotated (scaled, mirrored) programmed ones or the local ones, nor whether the centre of the mode moves with the new system"
            } else if shifted {
                "G92 with a G52 shift is not modelled: no FANUC source read says whether G92 keeps or clears the local shift"
            } else {
                "G92 under G91 or G16 is not modelled"
            };
            return Err(error(
                "NC491",
                msg.into(),
                span,
                "set the coordinate system under G90 with the other modes cancelled (G52 X0 Y0 Z0, G69, G50, G50.1, G15)",
            ));
        }
        for (i, a) in axes.iter().enumerate() {
            if let Some((w, x)) = a {
                let v = self.length(w, *x, (3..6).contains(&i));
                let rest = self.active_offset(i) - self.g92[i];
                self.g92[i] = self.pos[i] - rest - v;
                // The tool does not move: the increment after it travels only its own.
                self.applied[i] = self.active_offset(i);
            }
        }
        Ok(())
    }

    /// What the FANUC frame modes do not allow: a plane change in G68 mode ("G17, G18 or
    /// G19 must not be designated in the mode of coordinate system rotation"), modes out
    /// of the order mirror, scaling, rotation (and cancelled the other way round: "Do not
    /// specify G50.1 or G51.1 during scaling or coordinate rotation mode"), and the
    /// coordinate system codes in these modes, whose interaction is not modelled.
    pub(super) fn check_fanuc_frames(&self, gi: i64, span: Span) -> Result<(), Fault> {
        let rot = self.rot.is_some();
        let any = rot || self.scale.is_some() || self.mirror.iter().any(Option::is_some);
        if !self.fanuc || !any {
            return Ok(());
        }
        let what = match gi {
            170 | 180 | 190 if rot => "a plane selection (G17/G18/G19) in G68 mode",
            511 | 501 if rot || self.scale.is_some() => "G51.1/G50.1 in G51 or G68 mode",
            510 | 500 if rot => "G51/G50 in G68 mode",
            520 if rot => {
                return Err(error(
                    "NC491",
                    "G52 under G68 is not modelled: no FANUC source read says whether the new local origin is measured along the rotated or the unrotated axes, nor whether the rotation's centre moves with the local system".into(),
                    span,
                    "cancel the rotation first and give it again after the shift: `G69` / `G52 X.. Y..` / `G68 X.. Y.. R..`",
                ))
            }
            520 => "G52 under G51 or G51.1 (whether the new origin is scaled or mirrored is in no FANUC source read)",
            280 | 290 | 300 => "a reference return (G28/G29/G30) under G68, G51 or G51.1",
            540..=599 => "a work offset selection under G68, G51 or G51.1",
            100 => "G10 under G68, G51 or G51.1",
            _ => return Ok(()),
        };
        Err(error(
            "NC491",
            format!("{what} is not modelled"),
            span,
            "program mirror, scaling, rotation in this order and cancel them the other way round (G69, G50, G50.1); select offsets and planes outside them",
        ))
    }
}
