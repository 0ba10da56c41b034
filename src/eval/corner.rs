//! The geometry of a chamfer or a rounding inserted at the corner between two moves (FANUC
//! `,C`/`,R`, Siemens `CHR=`/`CHF=`/`RND=`/`RNDM=`), in the plane's (u, v) axes: the one
//! computation both dialects' runs and the translation use (docs/semantics.md, "Chamfers
//! and roundings").

/// A point in the working plane.
pub type Point = (f64, f64);

/// Diagnostic codes of corners (the range NC572–NC576).
pub const NOT_TRANSLATABLE: &str = "NC572";
/// The block after a corner is not the move in the plane the corner needs.
pub const NO_NEXT_MOVE: &str = "NC573";
/// The corner's geometry cannot be made (too long, no corner, out of the plane, a case not
/// modelled).
pub const BAD_CORNER: &str = "NC574";
/// The two moves' feeds differ, or a corner feed (FRC, FRCM) is programmed.
pub const CORNER_FEED: &str = "NC575";
/// Modal rounding (RNDM) that a translation cannot carry.
pub const MODAL_ROUND: &str = "NC576";

/// What the value of a corner word measures.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A chamfer given by its leg: the distance from the virtual corner to the chamfer's
    /// start and end on each move (FANUC `,C`, Siemens `CHR=`).
    Leg,
    /// A chamfer given by its own length (Siemens `CHF=`).
    Chord,
    /// A rounding of this radius (FANUC `,R`, Siemens `RND=`, `RNDM=`).
    Radius,
}

impl Kind {
    /// The IR (and Siemens) name of the word.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Leg => "CHR",
            Kind::Chord => "CHF",
            Kind::Radius => "RND",
        }
    }

    pub fn of_name(n: &str) -> Option<Kind> {
        match n {
            "CHR" => Some(Kind::Leg),
            "CHF" => Some(Kind::Chord),
            "RND" => Some(Kind::Radius),
            _ => None,
        }
    }
}

/// The corner between two lines: where the first move now ends, where the second now
/// starts, and for a rounding its centre and direction (`cw` seen from the plane's normal).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Corner {
    pub end1: Point,
    pub start2: Point,
    pub arc: Option<(Point, bool)>,
}

/// Why no corner can be made.
#[derive(Clone, Debug, PartialEq)]
pub enum Bad {
    /// The value is zero or negative.
    NotPositive,
    /// A move has no length, so it has no direction.
    Empty,
    /// The two moves are in line (no corner) or turn straight back.
    NoCorner,
    /// The chamfer or rounding needs more of a move than the move has.
    TooLong { trim: f64, first: f64, second: f64 },
}

impl Bad {
    pub fn text(&self) -> String {
        match self {
            Bad::NotPositive => "the chamfer or radius is not greater than 0".into(),
            Bad::Empty => "one of the two moves has no length in the plane".into(),
            Bad::NoCorner => "the two moves are in line or turn straight back: there is no corner to cut".into(),
            Bad::TooLong { trim, first, second } => format!(
                "the corner takes {} of each move, more than the first move's {} or the second's {}",
                crate::eval::value::fmt_num(round6(*trim)),
                crate::eval::value::fmt_num(round6(*first)),
                crate::eval::value::fmt_num(round6(*second))
            ),
        }
    }
}

fn round6(x: f64) -> f64 {
    (x * 1e6).round() / 1e6
}

fn unit(a: Point, b: Point) -> Option<(Point, f64)> {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let len = (dx * dx + dy * dy).sqrt();
    (len > 1e-9).then(|| ((dx / len, dy / len), len))
}

/// The angle between the two moves' directions `d1` and `d2`, 0 (in line) to π (reversal).
fn turn(d1: Point, d2: Point) -> f64 {
    let cross = d1.0 * d2.1 - d1.1 * d2.0;
    let dot = d1.0 * d2.0 + d1.1 * d2.1;
    cross.abs().atan2(dot)
}

/// The leg of a chamfer whose own length is `chord` between moves turning by `theta`: the
/// chamfer is the base of an isosceles triangle with the corner, so chord = 2·leg·cos(θ/2).
pub fn leg_of_chord(chord: f64, theta: f64) -> f64 {
    chord / (2.0 * (theta / 2.0).cos())
}

/// How far from the corner each move is cut for a corner of `kind` and `size` between
/// moves turning by `theta`.
pub fn trim(kind: Kind, size: f64, theta: f64) -> f64 {
    match kind {
        Kind::Leg => size,
        Kind::Chord => leg_of_chord(size, theta),
        Kind::Radius => size * (theta / 2.0).tan(),
    }
}

/// For a chamfer of own length `chord` at `corner` between the line from `start` and the line
/// to `end`: its leg (what each move is cut by) and the angle the path turns there, or why
/// [`line_line`] makes no such corner (the translation's leg is the run's, to the bit).
pub fn chord_leg(start: Point, corner: Point, end: Point, chord: f64) -> Result<(f64, f64), Bad> {
    line_line(start, corner, end, Kind::Chord, chord)?;
    let (d1, _) = unit(start, corner).ok_or(Bad::Empty)?;
    let (d2, _) = unit(corner, end).ok_or(Bad::Empty)?;
    let theta = turn(d1, d2);
    Ok((trim(Kind::Chord, chord, theta), theta))
}

/// The corner at `corner` between the line from `start` and the line to `end`. Either move
/// must keep some length (a trim equal to a move's whole length, within 1 µm, is allowed:
/// the move then vanishes, as a tangent rounding of a short leg does).
pub fn line_line(start: Point, corner: Point, end: Point, kind: Kind, size: f64) -> Result<Corner, Bad> {
    if size.is_nan() || size <= 0.0 {
        return Err(Bad::NotPositive);
    }
    let (d1, first) = unit(start, corner).ok_or(Bad::Empty)?;
    let (d2, second) = unit(corner, end).ok_or(Bad::Empty)?;
    let theta = turn(d1, d2);
    // Below 0.001° the corner is a straight line; near 180° the trim grows without bound.
    if theta < 1e-5 || std::f64::consts::PI - theta < 1e-5 {
        return Err(Bad::NoCorner);
    }
    let t = trim(kind, size, theta);
    if t > first + 1e-6 || t > second + 1e-6 {
        return Err(Bad::TooLong { trim: t, first, second });
    }
    let end1 = (corner.0 - t * d1.0, corner.1 - t * d1.1);
    let start2 = (corner.0 + t * d2.0, corner.1 + t * d2.1);
    let arc = (kind == Kind::Radius).then(|| {
        // Left turn: the centre lies left of the first move and the arc runs counter-clockwise.
        let left = d1.0 * d2.1 - d1.1 * d2.0 > 0.0;
        let n = if left { (-d1.1, d1.0) } else { (d1.1, -d1.0) };
        ((end1.0 + size * n.0, end1.1 + size * n.1), !left)
    });
    Ok(Corner { end1, start2, arc })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn near(a: Point, b: Point) -> bool {
        (a.0 - b.0).abs() < 1e-9 && (a.1 - b.1).abs() < 1e-9
    }

    #[test]
    fn leg_chamfer_cuts_both_moves_by_the_leg() {
        let c = line_line((0.0, 0.0), (60.0, 0.0), (60.0, 40.0), Kind::Leg, 5.0).unwrap();
        assert!(near(c.end1, (55.0, 0.0)) && near(c.start2, (60.0, 5.0)) && c.arc.is_none());
    }

    #[test]
    fn chord_chamfer_of_a_right_angle_is_leg_times_root_two() {
        let c = line_line((0.0, 0.0), (60.0, 0.0), (60.0, 40.0), Kind::Chord, 5.0 * 2f64.sqrt()).unwrap();
        assert!(near(c.end1, (55.0, 0.0)) && near(c.start2, (60.0, 5.0)));
    }

    #[test]
    fn chord_leg_is_the_trim_of_the_chord_corner() {
        let (leg, theta) = chord_leg((0.0, 0.0), (60.0, 0.0), (60.0, 40.0), 3.0).unwrap();
        assert!((theta - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        let c = line_line((0.0, 0.0), (60.0, 0.0), (60.0, 40.0), Kind::Chord, 3.0).unwrap();
        assert!(near(c.end1, (60.0 - leg, 0.0)) && (leg - 3.0 / 2f64.sqrt()).abs() < 1e-12);
        assert_eq!(chord_leg((0.0, 0.0), (4.0, 0.0), (8.0, 0.0), 1.0), Err(Bad::NoCorner));
    }

    #[test]
    fn rounding_is_tangent_with_its_centre_inside_the_turn() {
        // A left turn: counter-clockwise, centre to the left of the first move.
        let c = line_line((0.0, 0.0), (60.0, 0.0), (60.0, 40.0), Kind::Radius, 8.0).unwrap();
        assert!(near(c.end1, (52.0, 0.0)) && near(c.start2, (60.0, 8.0)));
        assert_eq!(c.arc, Some(((52.0, 8.0), false)));
        // A right turn: clockwise.
        let c = line_line((0.0, 0.0), (60.0, 0.0), (60.0, -40.0), Kind::Radius, 8.0).unwrap();
        let (centre, cw) = c.arc.unwrap();
        assert!(near(centre, (52.0, -8.0)) && cw);
        // 135° between the moves (a 45° turn): the tangent length is r·tan(22.5°).
        let c = line_line((0.0, 0.0), (10.0, 0.0), (20.0, 10.0), Kind::Radius, 2.0).unwrap();
        let t = 2.0 * (std::f64::consts::PI / 8.0).tan();
        assert!(near(c.end1, (10.0 - t, 0.0)));
    }

    #[test]
    fn impossible_corners_say_why() {
        let long = line_line((0.0, 0.0), (4.0, 0.0), (4.0, 40.0), Kind::Leg, 5.0);
        assert!(matches!(long, Err(Bad::TooLong { .. })));
        assert_eq!(line_line((0.0, 0.0), (4.0, 0.0), (8.0, 0.0), Kind::Radius, 1.0), Err(Bad::NoCorner));
        assert_eq!(line_line((0.0, 0.0), (4.0, 0.0), (0.0, 0.0), Kind::Radius, 1.0), Err(Bad::NoCorner));
        assert_eq!(line_line((0.0, 0.0), (0.0, 0.0), (4.0, 4.0), Kind::Leg, 1.0), Err(Bad::Empty));
        assert_eq!(line_line((0.0, 0.0), (4.0, 0.0), (4.0, 4.0), Kind::Leg, 0.0), Err(Bad::NotPositive));
    }
}
