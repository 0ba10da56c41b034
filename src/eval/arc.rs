//! Arc geometry: the centre of an arc from I/J/K, from a signed radius (FANUC `R`,
//! Siemens `CR=`), or from an opening angle (Siemens `AR=`), in the plane's (u, v) axes.

/// Centre of the arc from `s` to `e` with signed radius `r` (negative: more than 180°),
/// `cw` as seen from the positive normal axis. `None` when the chord is longer than the
/// diameter (beyond a small tolerance) or the chord is empty.
pub fn centre_from_radius(s: (f64, f64), e: (f64, f64), r: f64, cw: bool) -> Option<(f64, f64)> {
    let (dx, dy) = (e.0 - s.0, e.1 - s.1);
    let chord = (dx * dx + dy * dy).sqrt();
    if chord < 1e-9 || r == 0.0 {
        return None;
    }
    let half = chord / 2.0;
    let ra = r.abs();
    let h2 = ra * ra - half * half;
    let h = if h2 < 0.0 {
        // Within 2 µm of a half circle counts as one (values are rounded to 1 µm).
        if half - ra > 0.002 {
            return None;
        }
        0.0
    } else {
        h2.sqrt()
    };
    let (mx, my) = (s.0 + dx / 2.0, s.1 + dy / 2.0);
    // Unit vector to the left of the chord direction.
    let (lx, ly) = (-dy / chord, dx / chord);
    // A ccw arc of at most 180° has its centre on the left; cw on the right; a negative
    // radius (more than 180°) swaps the side.
    let left = cw != (r > 0.0);
    let sign = if left { 1.0 } else { -1.0 };
    Some((mx + sign * h * lx, my + sign * h * ly))
}

/// Radius of the arc from `s` to `e` with opening angle `ar` degrees (0 < ar < 360),
/// signed like `CR=` (negative above 180°).
pub fn radius_from_angle(s: (f64, f64), e: (f64, f64), ar: f64) -> Option<f64> {
    let (dx, dy) = (e.0 - s.0, e.1 - s.1);
    let chord = (dx * dx + dy * dy).sqrt();
    let sin_half = (ar.to_radians() / 2.0).sin();
    if chord < 1e-9 || sin_half.abs() < 1e-12 || ar <= 0.0 || ar >= 360.0 {
        return None;
    }
    let r = chord / 2.0 / sin_half;
    Some(if ar > 180.0 { -r.abs() } else { r.abs() })
}

/// End point of an arc that starts at `s`, turns around `c` by `ar` degrees.
pub fn end_from_angle(s: (f64, f64), c: (f64, f64), ar: f64, cw: bool) -> (f64, f64) {
    let a = if cw { -ar } else { ar }.to_radians();
    let (x, y) = (s.0 - c.0, s.1 - c.1);
    let (sn, cs) = a.sin_cos();
    (c.0 + x * cs - y * sn, c.1 + x * sn + y * cs)
}

/// A point in the plane of an arc.
pub type Point = (f64, f64);

/// How a block gives its arc: a radius, a centre (I/J/K already made coordinates), and a
/// Siemens opening angle (AR=), in that order of precedence.
pub struct Given {
    pub radius: Option<f64>,
    pub centre: Option<(f64, f64)>,
    pub angle: Option<f64>,
    /// The block names an axis of the plane: a centre with AR= then keeps its end point.
    pub end_named: bool,
}

/// The centre and the end point of an arc from `s` towards `e` as `g` gives it, checked to
/// lie on one circle (within 0.01, the controls' arc tolerance); `Err` is the alarm's text.
pub fn resolve(s: Point, mut e: Point, g: &Given, cw: bool) -> Result<(Point, Point), String> {
    let c = if let Some(rr) = g.radius {
        centre_from_radius(s, e, rr, cw).ok_or("arc radius too small for the end point, or no end point")?
    } else if let Some(c) = g.centre {
        if let Some(ang) = g.angle {
            if !g.end_named {
                e = end_from_angle(s, c, ang, cw);
            }
        }
        c
    } else if let Some(ang) = g.angle {
        let rr = radius_from_angle(s, e, ang).ok_or("AR= needs an end point different from the start")?;
        centre_from_radius(s, e, rr, cw).ok_or("no arc for AR=")?
    } else {
        return Err("arc without I/J/K, radius or opening angle".into());
    };
    let rs = ((s.0 - c.0).powi(2) + (s.1 - c.1).powi(2)).sqrt();
    let re = ((e.0 - c.0).powi(2) + (e.1 - c.1).powi(2)).sqrt();
    if (rs - re).abs() > 0.01 {
        return Err(format!("arc end point is not on the circle (start radius {rs:.4}, end radius {re:.4})"));
    }
    Ok((c, e))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: (f64, f64), b: (f64, f64)) -> bool {
        (a.0 - b.0).abs() < 1e-9 && (a.1 - b.1).abs() < 1e-9
    }

    #[test]
    fn radius_sign_rule() {
        // From (0,0) to (10,0): ccw R5 is a half circle centred at (5,0).
        assert!(close(centre_from_radius((0.0, 0.0), (10.0, 0.0), 5.0, false).unwrap(), (5.0, 0.0)));
        // cw, R=10, short arc: centre below the chord (right of travel to +X).
        let c = centre_from_radius((0.0, 0.0), (10.0, 0.0), 10.0, true).unwrap();
        assert!(c.1 < 0.0);
        // negative R: the long arc, centre above.
        let c = centre_from_radius((0.0, 0.0), (10.0, 0.0), -10.0, true).unwrap();
        assert!(c.1 > 0.0);
        // ccw R=10 short arc: centre above.
        let c = centre_from_radius((0.0, 0.0), (10.0, 0.0), 10.0, false).unwrap();
        assert!(c.1 > 0.0);
        assert!(centre_from_radius((0.0, 0.0), (10.0, 0.0), 4.0, false).is_none());
    }

    #[test]
    fn opening_angle() {
        let r = radius_from_angle((0.0, 0.0), (10.0, 0.0), 180.0).unwrap();
        assert!((r - 5.0).abs() < 1e-9);
        let e = end_from_angle((10.0, 0.0), (0.0, 0.0), 90.0, false);
        assert!(close(e, (0.0, 10.0)));
    }
}
