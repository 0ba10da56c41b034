//! Frames that turn, scale or mirror the coordinates (trace v2): FANUC G68/G69 and Siemens
//! ROT/AROT, SCALE/ASCALE, MIRROR/AMIRROR, kept as one affine map from programmed to
//! workpiece coordinates over X, Y, Z, and the moves and arcs made through it
//! (docs/semantics.md, "Rotation, scaling and mirroring").

use super::{arc, clean, AbsInc, Event, Fault, Machine, Motion, Plane, Span, WordVal, WV};

/// Programmed → workpiece coordinates over X, Y, Z: `w = a·p + b` (the workpiece position
/// before the work offset, G52 and Siemens TRANS are added).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Xform {
    pub a: [[f64; 3]; 3],
    pub b: [f64; 3],
}

impl Xform {
    pub const ID: Xform = Xform { a: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], b: [0.0; 3] };

    /// A rotation by `deg` in `plane`, counter-clockwise seen from the positive normal
    /// (G17: X towards Y, G18: Z towards X, G19: Y towards Z), about `centre` (the plane's
    /// two coordinates).
    pub fn rotation(plane: Plane, deg: f64, centre: (f64, f64)) -> Xform {
        let (u, v, _) = plane.axes();
        let (s, c) = deg.to_radians().sin_cos();
        // Exact at the quarter turns, so that 90° moves land on the grid.
        let snap = |x: f64| if x.abs() < 1e-15 { 0.0 } else { x };
        let (s, c) = (snap(s), snap(c));
        let mut x = Xform::ID;
        x.a[u][u] = c;
        x.a[u][v] = -s;
        x.a[v][u] = s;
        x.a[v][v] = c;
        // Rotation about the centre: w = R(p − c) + c.
        x.b[u] = centre.0 - (c * centre.0 - s * centre.1);
        x.b[v] = centre.1 - (s * centre.0 + c * centre.1);
        x
    }

    /// `self` after `inner`: the map `p ↦ self(inner(p))`.
    pub fn after(&self, inner: &Xform) -> Xform {
        let mut r = Xform { a: [[0.0; 3]; 3], b: self.b };
        for i in 0..3 {
            for j in 0..3 {
                r.a[i][j] = (0..3).map(|k| self.a[i][k] * inner.a[k][j]).sum();
            }
            r.b[i] += (0..3).map(|k| self.a[i][k] * inner.b[k]).sum::<f64>();
        }
        r
    }

    /// A diagonal map (scale factors, -1 for a mirrored axis).
    pub fn diagonal(d: [f64; 3]) -> Xform {
        let mut x = Xform::ID;
        for (i, f) in d.into_iter().enumerate() {
            x.a[i][i] = f;
        }
        x
    }

    pub fn apply(&self, p: [f64; 3]) -> [f64; 3] {
        let mut w = self.b;
        for (i, wi) in w.iter_mut().enumerate() {
            *wi += (0..3).map(|k| self.a[i][k] * p[k]).sum::<f64>();
        }
        w
    }

    /// The linear part applied to a vector (an increment).
    pub fn vector(&self, d: [f64; 3]) -> [f64; 3] {
        let mut w = [0.0; 3];
        for (i, wi) in w.iter_mut().enumerate() {
            *wi = (0..3).map(|k| self.a[i][k] * d[k]).sum::<f64>();
        }
        w
    }

    /// The programmed point of workpiece point `w` (`None`: a factor 0 was refused, so never).
    pub fn invert(&self, w: [f64; 3]) -> Option<[f64; 3]> {
        let a = &self.a;
        let det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
            + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
        if det.abs() < 1e-12 {
            return None;
        }
        let r = [w[0] - self.b[0], w[1] - self.b[1], w[2] - self.b[2]];
        let col = |m: [[f64; 3]; 3], j: usize| {
            let mut m = m;
            for i in 0..3 {
                m[i][j] = r[i];
            }
            m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
        };
        Some([col(*a, 0) / det, col(*a, 1) / det, col(*a, 2) / det])
    }

    /// The axes (bits 0..2) whose row mixes in another axis: what a rotation turns.
    pub fn turned(&self) -> u8 {
        let mut bits = 0;
        for i in 0..3 {
            if (0..3).any(|j| j != i && self.a[i][j] != 0.0) {
                bits |= 1 << i;
            }
        }
        bits
    }

    /// The axes (bits 0..2) whose row differs in `other`: what a change of frame moves.
    pub fn changed(&self, other: &Xform) -> u8 {
        let mut bits = 0;
        for i in 0..3 {
            if self.a[i] != other.a[i] || self.b[i] != other.b[i] {
                bits |= 1 << i;
            }
        }
        bits
    }
}

/// A FANUC `G68` rotation in force: its plane, centre (local coordinates) and angle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FanucRot {
    pub plane: Plane,
    pub centre: (f64, f64),
    pub deg: f64,
}

pub(super) fn error(code: &'static str, msg: String, span: Span, hint: &str) -> Fault {
    Fault::Error(Box::new(crate::diag::Diagnostic::error(code, msg).primary(usize::MAX, span, "here").hint(hint)))
}

const GEO: &[u8; 3] = b"XYZ";

/// The error for a drilling cycle under a frame the model does not take it through: `why`
/// names what the frame does (it scales, mirrors, tilts the drilling axis) or which position
/// the controls would read differently right after the frame changed.
pub fn framed_cycle(span: Span, why: &str) -> Fault {
    error(
        "NC496",
        format!("a drilling cycle {why} is not modelled (only a rotation in the plane of the cycle, about its drilling axis)"),
        span,
        "drill under a rotation in the cycle's plane (G17: G68 / ROT RPL=), or with the frame cancelled (G69, G50, G50.1; Siemens TRANS), after a positioning move naming both plane axes absolute",
    )
}

impl Machine {
    /// Whether the frame in force takes a drilling cycle in `plane` through as a move: it
    /// turns only within the plane (a rotation about the drilling axis, which keeps that
    /// axis and its levels), so the hole is the plane position through the frame and R,
    /// bottom and initial level stay where the drilling axis is. `Err`: what it does besides.
    pub(crate) fn cycle_frame(&self, span: Span) -> Result<(), Fault> {
        let (u, v, n) = self.modal.plane.axes();
        let a = &self.xf.a;
        let tiny = |x: f64| x.abs() < 1e-12;
        let why = if !(tiny(a[n][u]) && tiny(a[n][v]) && tiny(a[u][n]) && tiny(a[v][n]) && tiny(self.xf.b[n])) {
            Some("under a frame that turns the drilling axis out of its direction or moves its levels")
        } else if (a[n][n] - 1.0).abs() > 1e-12 {
            Some("under a frame that scales or mirrors the drilling axis")
        } else {
            let (m00, m01, m10, m11) = (a[u][u], a[u][v], a[v][u], a[v][v]);
            let det = m00 * m11 - m01 * m10;
            let orthonormal = (m00 * m00 + m10 * m10 - 1.0).abs() < 1e-9
                && (m01 * m01 + m11 * m11 - 1.0).abs() < 1e-9
                && (m00 * m01 + m10 * m11).abs() < 1e-9;
            if det < 0.0 {
                Some("under a mirrored frame")
            } else if !orthonormal {
                Some("under a scaled frame")
            } else {
                None
            }
        };
        match why {
            None => Ok(()),
            Some(why) => Err(framed_cycle(span, why)),
        }
    }

    /// A FANUC hole's plane position under a frame that rotates in the cycle's plane (or
    /// right after one changed): the block's plane words are programmed coordinates mapped
    /// through the frame as a move's end point is, by the same rules (an increment along
    /// the turned axes once they were positioned absolute; right after the frame changed
    /// an incremental position, or a plane axis left out, is refused: FANUC keeps or turns
    /// the programmed value there, the controls differ).
    pub(crate) fn framed_hole(&mut self, plane: [Option<(&WordVal, f64)>; 2], span: Span) -> Result<(), Fault> {
        self.cycle_frame(span)?;
        let (u, v, _) = self.modal.plane.axes();
        let off = [self.active_offset(0), self.active_offset(1), self.active_offset(2)];
        let wnow = [self.pos[0] - off[0], self.pos[1] - off[1], self.pos[2] - off[2]];
        let p0 = self.xf.invert(wnow).unwrap_or(wnow);
        let mut p1 = p0;
        let mut absolute = 0u8;
        for (k, axis) in [u, v].into_iter().enumerate() {
            let Some((w, x)) = plane[k] else { continue };
            let val = self.length(w, x, false);
            if w.mode == AbsInc::Ic || (w.mode == AbsInc::Plain && !self.modal.absolute) {
                if self.fresh & (1 << axis) != 0 {
                    let why = format!("with an incremental {} right after the frame changed", GEO[axis] as char);
                    return Err(framed_cycle(w.span, &why));
                }
                p1[axis] = p0[axis] + val;
            } else {
                p1[axis] = val;
                absolute |= 1 << axis;
            }
        }
        let left_out = (self.fresh >> 4) & !absolute & ((1 << u) | (1 << v));
        let same = self.kept_bits(left_out, p0, off);
        let left_out = left_out & !same;
        if left_out != 0 {
            let missing: String = (0..3).filter(|i| left_out & (1 << i) != 0).map(|i| GEO[i] as char).collect();
            let why = format!("as the first move after the frame changed, leaving {missing} out");
            return Err(framed_cycle(span, &why));
        }
        let w1 = self.xf.apply(p1);
        for axis in [u, v] {
            self.pos[axis] = w1[axis] + off[axis];
            self.applied[axis] = off[axis];
        }
        self.fresh &= !(absolute | ((absolute | same) << 4));
        self.refresh_framed();
        Ok(())
    }

    /// After a hole the drilling axis stands at an absolute level of the frame in force.
    pub(crate) fn cycle_positioned(&mut self) {
        let n = self.modal.plane.axes().2;
        self.fresh &= !((1 << n) | (1 << (n + 4)));
        self.refresh_framed();
    }

    /// Installs `x` as the frame's map; the axes it (or the one before) turns, scales or
    /// mirrors must be positioned absolute before an incremental move or a move that
    /// leaves one of them out (`fresh`).
    pub(crate) fn set_xform(&mut self, x: Xform) {
        // A rotation and its inverse (a G69 written as the undoing AROT) leave float noise:
        // snapped, so that the frame is the identity again.
        let mut x = x;
        for v in x.a.iter_mut().flatten().chain(x.b.iter_mut()) {
            for k in [-1.0, 0.0, 1.0] {
                if (*v - k).abs() < 1e-12 {
                    *v = k;
                }
            }
        }
        if x != self.xf {
            let changed = self.xf.changed(&x);
            let turned = changed & (self.xf.turned() | x.turned());
            // The value a FANUC move leaving the axis out would keep: its programmed value in
            // the frame it was last positioned in (an axis already waiting keeps the older one).
            let newly = turned & !(self.fresh >> 4);
            let off = [self.active_offset(0), self.active_offset(1), self.active_offset(2)];
            let wnow = [self.pos[0] - off[0], self.pos[1] - off[1], self.pos[2] - off[2]];
            let p = self.xf.invert(wnow).unwrap_or(wnow);
            for i in (0..3).filter(|i| newly & (1 << i) != 0) {
                self.kept[i] = (p[i], off[i]);
            }
            self.fresh |= changed | (turned << 4);
            self.xf = x;
        }
        self.refresh_framed();
    }

    /// The axes of `left_out` where the two readings of a move leaving them out right after
    /// the frame turned agree: the programmed value kept (FANUC's, as far as read) is the
    /// position worked out again through the new frame (`p0`, Siemens') under the same offset,
    /// as at the centre of a rotation. Where they agree the target is known whichever the
    /// control does, so the move is not refused.
    pub(super) fn kept_bits(&self, left_out: u8, p0: [f64; 3], off: [f64; 3]) -> u8 {
        (0..3)
            .filter(|&i| left_out & (1 << i) != 0)
            .filter(|&i| (self.kept[i].0 - p0[i]).abs() < 1e-9 && self.kept[i].1 == off[i])
            .fold(0, |bits, i| bits | (1 << i))
    }

    pub(super) fn refresh_framed(&mut self) {
        self.framed = self.fresh != 0 || self.xf != Xform::ID;
    }

    /// Whether the frame turns, scales or mirrors (position read-backs are refused then).
    pub fn transforms(&self) -> bool {
        self.xf.a != Xform::ID.a
    }

    /// Whether the frame moves axis `axis` with the others (a rotation about another axis
    /// than it, a scale or mirror of it): a programmed position of an axis it leaves alone
    /// (Z under a rotation in the XY plane) is its workpiece position.
    pub fn turns_axis(&self, axis: usize) -> bool {
        axis < 3
            && ((0..3).any(|k| {
                self.xf.a[axis][k] != f64::from(u8::from(k == axis))
                    || self.xf.a[k][axis] != f64::from(u8::from(k == axis))
            }) || self.xf.b[axis] != 0.0)
    }

    /// FANUC `G68 X.. Y.. R..` (the centre in the plane's two axes, absolute; none: where
    /// the tool stands) and the angle R (absolute, or added to the angle in force under
    /// G91 with parameter 5400#0 RIN = 1). No motion.
    pub(super) fn g68(
        &mut self,
        axes: &[Option<(&WordVal, f64)>; 9],
        ijk: bool,
        r: Option<(&WordVal, f64)>,
        span: Span,
    ) -> Result<(), Fault> {
        if ijk {
            return Err(error(
                "NC490",
                "G68 with I, J, K (three-dimensional coordinate conversion) is not modelled".into(),
                span,
                "rotate in the plane: `G68 X.. Y.. R..`",
            ));
        }
        let plane = self.modal.plane;
        let (u, v, _) = plane.axes();
        if let Some((w, _)) =
            axes.iter().enumerate().find(|(i, a)| a.is_some() && *i != u && *i != v).and_then(|x| *x.1)
        {
            return Err(error(
                "NC490",
                format!("G68 names {}, which is not an axis of the plane", w.addr),
                w.span,
                "name the centre in the two axes of the selected plane (G17: X Y, G18: Z X, G19: Y Z)",
            ));
        }
        let incremental = !self.modal.absolute || axes.iter().flatten().any(|(w, _)| w.mode == AbsInc::Ic);
        let given = axes[u].is_some() || axes[v].is_some();
        if incremental && given {
            return Err(error(
                "NC490",
                "G68 with its centre under G91 is not modelled (the controls read it as absolute or refuse it)".into(),
                span,
                "give the centre of rotation under G90: `G90 G68 X.. Y.. R..`",
            ));
        }
        let Some((rw, rx)) = r else {
            return Err(error(
                "NC490",
                "G68 without R (the angle is then machine parameter 5410)".into(),
                span,
                "write the angle: `G68 X.. Y.. R30.`",
            ));
        };
        // The tool position when G68 is commanded, in local coordinates (unrotated; in G68
        // mode too: a new G68 replaces the rotation, about its own centre); under G51 the
        // programmed point that scales to it.
        let here = self.unscaled_position();
        let coord = |i: usize| axes[i].map_or(here[i], |(w, x)| self.length(w, x, false));
        let centre = (coord(u), coord(v));
        let mut deg = self.length(rw, rx, true);
        if self.rotation_angle_incremental && !self.modal.absolute {
            deg += self.rot.map_or(0.0, |r| r.deg);
        }
        self.rot = Some(FanucRot { plane, centre, deg });
        self.fanuc_compose();
        Ok(())
    }

    /// FANUC `G69`: the rotation ends; the next move names the plane axes absolute.
    pub(super) fn g69(&mut self) {
        self.rot = None;
        self.fanuc_compose();
    }

    /// Siemens `ROT`/`AROT`, `SCALE`/`ASCALE`, `MIRROR`/`AMIRROR` with values, and the
    /// translations under a frame that turns (`ATRANS` in the turned system).
    pub(super) fn siemens_frame(&mut self, op: &str, words: &[WordVal], span: Span) -> Result<(), Fault> {
        let additive = op.starts_with('A');
        let base = if additive { self.xf } else { Xform::ID };
        let mut geo_words = Vec::new();
        let mut rpl = None;
        for w in words {
            let WV::Num(x) = w.val else {
                return Err(error("NC492", format!("{op} with a string value"), w.span, "write a number"));
            };
            match (w.addr.as_ref(), GEO.iter().position(|&c| w.addr.as_bytes() == [c])) {
                ("RPL", _) if matches!(op, "ROT" | "AROT") => rpl = Some((x, w.span)),
                (_, Some(i)) => geo_words.push((i, w, x)),
                _ => {
                    return Err(error(
                        "NC492",
                        format!("{op} with {} is not modelled", w.addr),
                        w.span,
                        "frames here turn, scale and mirror the geometry axes X, Y, Z",
                    ))
                }
            }
        }
        let step = match op {
            "ROT" | "AROT" => {
                let (plane, deg) = match (rpl, geo_words.as_slice()) {
                    (Some((deg, _)), []) => (self.modal.plane, deg),
                    // A rotation about one geometry axis is one in the plane normal to it.
                    (None, [(i, _, deg)]) => ([Plane::YZ, Plane::ZX, Plane::XY][*i], *deg),
                    _ => {
                        return Err(error(
                            "NC492",
                            format!("{op} about more than one axis (a rotation in space) is not modelled"),
                            span,
                            "rotate in the plane: `ROT RPL=30`, or about one axis: `ROT Z30`",
                        ))
                    }
                };
                Xform::rotation(plane, deg, (0.0, 0.0))
            }
            "SCALE" | "ASCALE" => {
                let mut d = [1.0; 3];
                for (i, w, x) in &geo_words {
                    if *x == 0.0 {
                        return Err(error(
                            "NC492",
                            format!("{op} with the factor 0"),
                            w.span,
                            "a scale factor is not 0",
                        ));
                    }
                    d[*i] = *x;
                }
                Xform::diagonal(d)
            }
            _ => {
                let mut d = [1.0; 3];
                for (i, _, _) in &geo_words {
                    d[*i] = -1.0;
                }
                Xform::diagonal(d)
            }
        };
        if !additive {
            // An absolute frame instruction replaces the whole programmable frame.
            self.set_trans([0.0; 9]);
        }
        self.set_xform(base.after(&step));
        Ok(())
    }

    /// Sets the Siemens programmable translation; under a frame that turns, the axes whose
    /// shift changes must be positioned absolute again (`fresh`).
    pub(crate) fn set_trans(&mut self, t: [f64; 9]) {
        if self.transforms() {
            for (i, (new, old)) in t.iter().zip(self.trans).enumerate().take(3) {
                if *new != old {
                    self.fresh |= 1 << i;
                }
            }
        }
        self.trans = t.map(clean);
        self.refresh_framed();
    }

    /// A move or arc through a frame that turns, scales or mirrors (or the first one after
    /// such a frame changed): the block's X Y Z words are programmed coordinates, mapped
    /// by [`Xform`] to the workpiece position.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn framed_motion(
        &mut self,
        axes: &[Option<(&WordVal, f64)>; 9],
        ijk: &[Option<(&WordVal, f64)>; 3],
        r: Option<(&WordVal, f64)>,
        ar: Option<f64>,
        probe: bool,
        out: &mut Vec<(Event, Span)>,
        span: Span,
    ) -> Result<bool, Fault> {
        let arc_mode = matches!(self.modal.motion, Motion::Cw | Motion::Ccw);
        let any_axis = axes.iter().any(Option::is_some);
        let any_ijk = ijk.iter().any(Option::is_some);
        if !any_axis && !(arc_mode && (any_ijk || ar.is_some())) {
            return Ok(false);
        }
        if probe {
            return Err(error(
                "NC493",
                "a probing move under a rotated, scaled or mirrored frame is not modelled".into(),
                span,
                "probe with the frame cancelled",
            ));
        }
        let rapid = self.modal.motion == Motion::Rapid;
        if !rapid && self.feed.is_none() {
            return Err(Fault::alarm(self.alarms.no_feed, "feed motion without any feed programmed", span));
        }
        let off = [self.active_offset(0), self.active_offset(1), self.active_offset(2)];
        let wnow = [self.pos[0] - off[0], self.pos[1] - off[1], self.pos[2] - off[2]];
        let p0 = self.xf.invert(wnow).unwrap_or(wnow);
        let mut p1 = p0;
        let mut absolute = 0u8;
        let mut target = self.pos;
        for (i, a) in axes.iter().enumerate() {
            let Some((w, x)) = a else { continue };
            let val = self.length(w, *x, (3..6).contains(&i));
            let inc = w.mode == AbsInc::Ic || (w.mode == AbsInc::Plain && !self.modal.absolute);
            if i >= 3 {
                target[i] = self.axis_target(i, val, w.mode, false);
                continue;
            }
            if inc {
                // Both controls move an increment along the turned axes once the position
                // is known in them; right after a frame change they differ (FANUC: the
                // centre of rotation; Siemens MD42440: the frame change is travelled too).
                let changed = self.incr_travels_offset && self.applied[i] != off[i];
                if self.fresh & (1 << i) != 0 || changed {
                    return Err(error(
                        "NC494",
                        format!(
                            "an incremental {} right after the frame changed (the controls differ there)",
                            GEO[i] as char
                        ),
                        w.span,
                        "position the axes of the plane absolute (G90) first after G68/G69, ROT, SCALE, MIRROR or TRANS",
                    ));
                }
                p1[i] = p0[i] + val;
            } else {
                p1[i] = val;
                absolute |= 1 << i;
            }
        }
        // FANUC keeps the programmed value of an axis left out, which a new rotation then
        // turns ("the first move command after G69 must be specified as an absolute
        // command"); Siemens works the workpiece position out again through the new frame.
        let left_out = (self.fresh >> 4) & !absolute & 0b111;
        let same = self.kept_bits(left_out, p0, off);
        let left_out = left_out & !same;
        if self.fanuc && left_out != 0 {
            let missing: String = (0..3).filter(|i| left_out & (1 << i) != 0).map(|i| GEO[i] as char).collect();
            return Err(error(
                "NC494",
                format!("the first move after the frame changed leaves {missing} out (the controls differ there)"),
                span,
                "name both axes of the plane absolute in the first move after G68 and G69",
            ));
        }
        let mut cw = self.modal.motion == Motion::Cw;
        let mut centre = None;
        if arc_mode {
            let (u, v, n) = self.modal.plane.axes();
            let a = &self.xf.a;
            let tol = 1e-12;
            let closed = a[n][u].abs() < tol && a[n][v].abs() < tol && a[u][n].abs() < tol && a[v][n].abs() < tol;
            // The plane's 2×2 part: a similarity (rotation, one factor, mirror) keeps arcs arcs.
            let (m00, m01, m10, m11) = (a[u][u], a[u][v], a[v][u], a[v][v]);
            let similar =
                (m00 * m00 + m10 * m10 - (m01 * m01 + m11 * m11)).abs() < 1e-9 && (m00 * m01 + m10 * m11).abs() < 1e-9;
            if !closed || !similar {
                return Err(error(
                    "NC495",
                    "an arc in a plane the frame turns out of, or scales by unequal factors, is not modelled".into(),
                    span,
                    "program the arc in the plane of the rotation, with equal scale factors in it",
                ));
            }
            let s = (p0[u], p0[v]);
            let e = (p1[u], p1[v]);
            let ijk_len = |axis: usize| -> Option<(f64, bool)> {
                ijk.get(axis).copied().flatten().map(|(w, x)| (self.length(w, x, false), w.mode == AbsInc::Ac))
            };
            let cc = |axis: usize, start: f64| ijk_len(axis).map(|(v, ac)| if ac { v } else { start + v });
            let given = arc::Given {
                radius: r.map(|(w, rv)| self.length(w, rv, false)),
                centre: any_ijk.then(|| (cc(u, s.0).unwrap_or(s.0), cc(v, s.1).unwrap_or(s.1))),
                angle: ar,
                end_named: axes[u].is_some() || axes[v].is_some(),
            };
            let (c, e) = arc::resolve(s, e, &given, cw).map_err(|why| Fault::alarm(self.alarms.arc, why, span))?;
            p1[u] = e.0;
            p1[v] = e.1;
            let mut pc = p1;
            pc[u] = c.0;
            pc[v] = c.1;
            let wc = self.xf.apply(pc);
            // A mirrored plane runs the arc the other way round.
            if m00 * m11 - m01 * m10 < 0.0 {
                cw = !cw;
            }
            centre = Some([(u, clean(wc[u] + off[u])), (v, clean(wc[v] + off[v]))]);
        }
        let w1 = self.xf.apply(p1);
        for i in 0..3 {
            let t = w1[i] + off[i];
            if axes[i].is_some() || (t - self.pos[i]).abs() > 1e-9 || centre.is_some_and(|c| c.iter().any(|x| x.0 == i))
            {
                self.seen[i] = true;
                self.applied[i] = off[i];
            }
            target[i] = t;
        }
        for (i, a) in axes.iter().enumerate().skip(3) {
            if a.is_some() {
                self.seen[i] = true;
                self.applied[i] = self.active_offset(i);
            }
        }
        let f = if rapid { None } else { self.path_feed(&self.pos, &target, centre.is_some(), span)? };
        self.pos = target;
        self.fresh &= !(absolute | ((absolute | same) << 4));
        self.refresh_framed();
        match centre {
            Some(center) => {
                out.push((Event::Arc { cw, plane: self.modal.plane, to: self.trace_pos(), center, f }, span))
            }
            None => out.push((Event::Move { rapid, to: self.trace_pos(), f, probe: false }, span)),
        }
        Ok(true)
    }
}
