//! Look-ahead and high-speed modes (FANUC `G05.1 Q1/Q0`, `G05 P10000/P0`, `G08 P1/P0`, Haas
//! `G187 P E`, `G103 P`; Siemens `FFWON`/`FFWOF`, `CYCLE832`): they change how the control
//! plans feed and acceleration, never the programmed path, so they have no trace event. Each
//! one run is warning [`NOT_COMPARED`], which a check counts (`check::Excluded::modes`) so
//! that its verdict says these settings were not compared; a value the controls do not
//! document is refused (NC561).

use super::{Fault, Machine, Span, Warn};

/// The warning of a look-ahead setting: counted by the check as "not compared".
pub const NOT_COMPARED: &str = "NC560";
/// A look-ahead setting whose value has no documented meaning (or no counterpart).
pub const BAD_VALUE: &str = "NC561";

/// The FANUC G codes (`g_index`) of look-ahead modes: G05, G05.1, G08, and on Haas G103,
/// G187.
pub fn is_mode_g(gi: i64, haas: bool) -> bool {
    matches!(gi, 50 | 51 | 80) || (haas && matches!(gi, 1030 | 1870))
}

/// What a FANUC look-ahead G code with its P, Q and E values sets, for messages:
/// `G05.1 Q1 (AI contour control on)`; `Err` text for a value it does not take.
pub fn fanuc_mode(gi: i64, p: Option<f64>, q: Option<f64>, e: Option<f64>) -> Result<String, String> {
    let int = |v: Option<f64>| v.filter(|x| x.fract() == 0.0).map(|x| x as i64);
    match gi {
        51 => match int(q) {
            Some(1) => Ok("G05.1 Q1 (AI contour control on)".into()),
            Some(0) => Ok("G05.1 Q0 (AI contour control off)".into()),
            _ => Err(format!(
                "G05.1 {} is not modelled: only Q1 and Q0 (AI contour control on and off) are",
                q.map_or("without Q".into(), |q| format!("Q{q}"))
            )),
        },
        50 => match int(p) {
            Some(10000) => Ok("G05 P10000 (high-precision contour control on)".into()),
            Some(0) => Ok("G05 P0 (high-precision contour control off)".into()),
            _ => Err(format!(
                "G05 {} is not modelled: only P10000 and P0 (high-precision contour control on and off) are; \
                 other G05 forms are high-speed cycle machining",
                p.map_or("without P".into(), |p| format!("P{p}"))
            )),
        },
        80 => match int(p) {
            Some(1) => Ok("G08 P1 (advanced preview control on)".into()),
            Some(0) => Ok("G08 P0 (advanced preview control off)".into()),
            _ => Err(format!(
                "G08 {} is not modelled: only P1 and P0 (advanced preview control on and off) exist",
                p.map_or("without P".into(), |p| format!("P{p}"))
            )),
        },
        1030 => match int(p) {
            None if p.is_none() => Ok("G103 (Haas look-ahead limit off)".into()),
            Some(0) => Ok("G103 P0 (Haas look-ahead limit off)".into()),
            Some(1) => Ok("G103 P1 (Haas look-ahead limit of 1 block)".into()),
            Some(n @ 2..=15) => Ok(format!("G103 P{n} (Haas look-ahead limit of {n} blocks)")),
            _ => Err(format!("G103 P{} is not modelled: Haas takes P0 to P15", p.unwrap_or_default())),
        },
        1870 => {
            let level = match int(p) {
                None if p.is_none() => None,
                Some(n @ 1..=3) => Some(n),
                _ => return Err(format!("G187 P{} is not modelled: Haas takes P1, P2 or P3", p.unwrap_or_default())),
            };
            match (level, e) {
                (_, Some(e)) if e < 0.0 => {
                    Err(format!("G187 E{e} is not modelled: a corner tolerance is not negative"))
                }
                (None, None) => Ok("G187 (Haas smoothness back to Setting 191)".into()),
                (Some(n), None) => Ok(format!("G187 P{n} (Haas smoothness {})", haas_level(n))),
                (None, Some(e)) => Ok(format!("G187 E{e} (Haas corner tolerance)")),
                (Some(n), Some(e)) => {
                    Ok(format!("G187 P{n} E{e} (Haas smoothness {}, corner tolerance)", haas_level(n)))
                }
            }
        }
        _ => Err(format!("G{gi} is not a look-ahead mode")),
    }
}

/// Haas G187 P1–P3: rough, medium, finish (Haas mill operator's manual, G187).
pub fn haas_level(n: i64) -> &'static str {
    match n {
        1 => "rough",
        2 => "medium",
        _ => "finish",
    }
}

/// Siemens CYCLE832 machining type (`_TOLM` units digit): 0 deselection, 1 finishing,
/// 2 semi-finishing, 3 roughing, 4 smooth finishing (Sinumerik programming manual,
/// CYCLE832 parameters).
pub fn cycle832_type(m: i64) -> Option<&'static str> {
    Some(match m {
        0 => "deselection",
        1 => "finishing",
        2 => "semi-finishing",
        3 => "roughing",
        4 => "smooth finishing",
        _ => return None,
    })
}

/// Siemens G641 (smoothing by the distance `ADIS`) and G642 (by the axis tolerances of the
/// machine data): the control inserts transitions at the corners, so the path near them is
/// the control's, not the programmed corner the trace records; a check counts it as not
/// compared. `None` for another G code (`gi` ×10) or on FANUC.
pub fn smoothing(gi: i64, fanuc: bool) -> Option<String> {
    let what = match gi {
        6410 if !fanuc => "G641 (smoothing by the distance ADIS)",
        6420 if !fanuc => "G642 (smoothing within the axis tolerances of the machine data)",
        _ => return None,
    };
    Some(format!("{what} rounds the corners the trace records as programmed: not compared"))
}

/// What a `CYCLE832(tol, tolm, …)` with these values sets, for messages; `Err` for a type
/// it does not take. Only the units digit of `_TOLM` selects the type (the higher digits
/// choose orientation tolerance and surface functions, none of which moves the path).
pub fn cycle832_mode(tol: Option<f64>, tolm: Option<f64>) -> Result<String, String> {
    let m = tolm.unwrap_or(0.0);
    if m.fract() != 0.0 || m < 0.0 {
        return Err(format!("CYCLE832 with machining type {m} is not modelled: the units digit is 0 to 4"));
    }
    let units = (m as i64) % 10;
    let Some(name) = cycle832_type(units) else {
        return Err(format!("CYCLE832 with machining type {m} is not modelled: the units digit is 0 to 4"));
    };
    match tol {
        Some(t) if units != 0 => Ok(format!("CYCLE832({t}, {}) (high-speed settings: {name})", m as i64)),
        _ => Ok(format!("CYCLE832 (high-speed settings: {name})")),
    }
}

impl Machine {
    /// A FANUC look-ahead G code of this block: a warning that it is not compared, or the
    /// refusal of a value it does not take.
    pub(super) fn lookahead_g(
        &self,
        gi: i64,
        p: Option<f64>,
        q: Option<f64>,
        e: Option<f64>,
        span: Span,
        warns: &mut Vec<Warn>,
    ) -> Result<(), Fault> {
        match fanuc_mode(gi, p, q, e) {
            Ok(what) => {
                warns.push((
                    NOT_COMPARED,
                    format!("{what} changes how the control plans feed and corners, not the programmed positions: not compared"),
                    span,
                ));
                Ok(())
            }
            // `usize::MAX`: the file is filled in by the interpreter (`fix_file`).
            Err(what) => Err(Fault::error(
                crate::diag::Diagnostic::error(BAD_VALUE, what)
                    .primary(usize::MAX, span, "here")
                    .hint("write the look-ahead mode with one of the values listed, or remove it"),
            )),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_the_controls_document_are_read_and_others_refused() {
        assert!(fanuc_mode(51, None, Some(1.0), None).unwrap().contains("AI contour control on"));
        assert!(fanuc_mode(51, None, Some(2.0), None).is_err());
        assert!(fanuc_mode(50, Some(10000.0), None, None).is_ok());
        assert!(fanuc_mode(50, Some(1.0), None, None).is_err());
        assert!(fanuc_mode(80, Some(0.0), None, None).unwrap().contains("off"));
        assert!(fanuc_mode(1030, Some(16.0), None, None).is_err());
        assert!(fanuc_mode(1870, Some(3.0), None, Some(0.01)).unwrap().contains("finish"));
        assert!(fanuc_mode(1870, Some(4.0), None, None).is_err());
        assert!(cycle832_mode(Some(0.01), Some(1.0)).unwrap().contains("finishing"));
        assert!(cycle832_mode(Some(0.01), Some(100003.0)).unwrap().contains("roughing"));
        assert!(cycle832_mode(None, Some(7.0)).is_err());
    }
}
