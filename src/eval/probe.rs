//! Probe test inputs (`--probe`, header lines `nctrans: probe`): for each probing move in
//! the order the run reaches them (FANUC `G31`, Siemens `MEAS=`/`MEAW=`), where the probe
//! triggers, or that it does not. The same list is given to both programs of a check, so a
//! probing macro is proven on the path where the probe touches and on the one where it
//! misses. Probing moves beyond the list do not trigger (trace format v2).

/// What happens on one probing move.
#[derive(Clone, Debug, PartialEq)]
pub enum ProbeInput {
    /// The probe does not switch: the move reaches its end point.
    Miss,
    /// The probe switches where these axes (index into `trace::AXES`) reach these
    /// positions, in the trace's coordinates (the `to` of the move event). Axes not named
    /// are found on the programmed line; the point must lie on the move.
    At(Vec<(usize, f64)>),
}

/// Parses `miss` or `X=12.5,Y=-3` (commas or `;` between axes; `X12.5` also accepted).
pub fn parse_probe(s: &str) -> Result<ProbeInput, String> {
    let t = s.trim();
    if t.eq_ignore_ascii_case("miss") {
        return Ok(ProbeInput::Miss);
    }
    let mut axes = Vec::new();
    for part in t.split([',', ';']).map(str::trim).filter(|p| !p.is_empty()) {
        let mut chars = part.chars();
        let letter = chars.next().map(|c| c.to_ascii_uppercase()).unwrap_or(' ');
        let Some(i) = super::trace::AXES.iter().position(|&a| a == letter) else {
            return Err(format!("'{part}': expected an axis X Y Z A B C U V W, e.g. X=12.5"));
        };
        let rest = chars.as_str().trim_start();
        let rest = rest.strip_prefix('=').unwrap_or(rest).trim();
        let v: f64 = rest.parse().map_err(|_| format!("'{part}': expected a position, e.g. X=12.5"))?;
        if axes.iter().any(|(a, _)| *a == i) {
            return Err(format!("'{s}': axis {letter} named twice"));
        }
        axes.push((i, v));
    }
    if axes.is_empty() {
        return Err(format!("'{s}': expected `miss` or where the probe triggers, e.g. X=12.5 or X=3,Y=4"));
    }
    Ok(ProbeInput::At(axes))
}

/// Probe inputs written in a file's header comments, before its first block:
/// `; nctrans: probe X=12.5 miss` (Siemens) or `(nctrans: probe X=12.5 miss)` (FANUC), one
/// input per probing move, separated by spaces, in order.
pub fn header_probes(text: &str) -> Result<Vec<ProbeInput>, String> {
    super::input::header_words(text, "nctrans: probe", true).map(parse_probe).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_points_and_misses() {
        assert_eq!(parse_probe("miss").unwrap(), ProbeInput::Miss);
        assert_eq!(parse_probe("X=12.5").unwrap(), ProbeInput::At(vec![(0, 12.5)]));
        assert_eq!(parse_probe("x3,Y=-4").unwrap(), ProbeInput::At(vec![(0, 3.0), (1, -4.0)]));
        assert!(parse_probe("Q=1").is_err());
        assert!(parse_probe("X=a").is_err());
        assert!(parse_probe("X=1,X=2").is_err());
        assert!(parse_probe("").is_err());
    }

    #[test]
    fn header_lines() {
        let t = "O9810\n(nctrans: probe X=20. miss)\n(nctrans: set #1=2.)\nG0 X0\n(nctrans: probe X=1)\n";
        assert_eq!(header_probes(t).unwrap(), vec![ProbeInput::At(vec![(0, 20.0)]), ProbeInput::Miss]);
        assert_eq!(header_probes("; nctrans: probe Y=-3\nG0 X0\n").unwrap().len(), 1);
        assert_eq!(header_probes("DEF REAL A\n; nctrans: probe Y=-3\nG0 X0\n").unwrap().len(), 1);
        assert!(header_probes("; nctrans: probe Y\n").is_err());
    }
}
