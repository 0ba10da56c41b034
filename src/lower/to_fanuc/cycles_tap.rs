//! Sinumerik tapping → FANUC, for `cycles::plan`: CYCLE84 (rigid) becomes `M29 S<SST>` and
//! G84/G74 (the pitch's sign is the hand) with F = pitch × SST (G94) or the pitch (G95);
//! CYCLE840 without an encoder (ENC 1, SDR the reverse of SDAC) becomes floating G84 (SDAC
//! 3) or G74 (SDAC 4) at the programmed feed. What the control does that FANUC's cycle
//! cannot say is refused: tapping with an encoder (CYCLE840 ENC 0 couples the feed to the
//! spindle, G33), a pitch under ENC 1, a retract speed SST1, an oriented start POSS, rigid
//! tapping with the spindle turning. Sources: docs/semantics.md ("Tapping").

use super::cycles::{arg, constant};
use super::*;
use crate::dialect::sinumerik::cycles::{metric_coarse_pitch, SieCycle};
use crate::lower::literal;

/// What the block list before the call says about the spindle and the feed.
#[derive(Clone, Copy, Debug, Default)]
pub struct SieState {
    /// M3, M4, M5 last programmed; `None`: not known.
    pub spindle: Option<u8>,
    /// G95 in force; `None`: not known.
    pub per_rev: Option<bool>,
    /// The modal F: `Some(None)` none programmed yet, `Some(Some(f))` a number, `None` not
    /// known.
    pub feed: Option<Option<f64>>,
}

impl SieState {
    pub fn start(top: bool) -> SieState {
        if top {
            SieState { spindle: Some(5), per_rev: Some(false), feed: Some(None) }
        } else {
            SieState::default()
        }
    }

    /// The words of a plain block, in the order the control takes them.
    pub fn observe(&mut self, letter: &str, value: Option<f64>) {
        match (letter, value) {
            ("M", Some(v)) if v == 3.0 || v == 4.0 || v == 5.0 => self.spindle = Some(v as u8),
            ("G", Some(94.0)) => self.per_rev = Some(false),
            ("G", Some(95.0)) => self.per_rev = Some(true),
            ("F", v) => self.feed = v.map(Some),
            _ => {}
        }
    }
}

/// The FANUC side of a tapping call.
pub struct TapPlan {
    /// 84 or 74.
    pub g: f64,
    /// The F word of the cycle block (rigid tapping).
    pub f: Option<Expr>,
    /// `M29 S<this>` before the cycle block.
    pub m29: Option<Expr>,
    /// The F to write again after G80 (the feed before the cycle).
    pub restore: Option<f64>,
}

pub type Why = (&'static str, String, &'static str);

/// The pitch (signed: negative is left hand) from MPIT or PIT, as a number.
fn pitch(c: &Call, k: SieCycle) -> Result<Option<f64>, Why> {
    let (Some(mpit), Some(pit)) = (constant(c, k, "MPIT"), constant(c, k, "PIT")) else {
        return Err((
            "NC486",
            format!("{} with a pitch known only at run time", k.name()),
            "write MPIT or PIT as a number",
        ));
    };
    if pit != 0.0 {
        return Ok(Some(pit));
    }
    if mpit != 0.0 {
        return match metric_coarse_pitch(mpit.abs()) {
            Some(p) => Ok(Some(p.copysign(mpit))),
            None => {
                Err(("NC486", format!("MPIT={mpit}: not a metric coarse thread M3 to M48"), "give the pitch as PIT"))
            }
        };
    }
    Ok(None)
}

pub fn plan(c: &Call, k: SieCycle, st: &SieState) -> Result<TapPlan, Why> {
    let span = c.args.first().map_or(Span::default(), |a| match a {
        Arg::Value(e) => e.span,
        Arg::Omitted(s) => *s,
        _ => Span::default(),
    });
    let sdac = constant(c, k, "SDAC");
    if k == SieCycle::C84 {
        let Some(p) = pitch(c, k)? else {
            return Err(("NC486", "CYCLE84 without a pitch (MPIT or PIT)".into(), "give the thread pitch"));
        };
        let Some(sst) = arg(c, k, "SST").filter(|e| literal(e) != Some(0.0)).cloned() else {
            return Err(("NC486", "CYCLE84 without a tapping speed SST".into(), "give SST: it becomes M29 S…"));
        };
        spindle_settled(st.spindle, sdac)?;
        let Some(per_rev) = st.per_rev else {
            return Err(("NC487", "CYCLE84 where G94/G95 is not known".into(), "program G94 or G95 before the cycle"));
        };
        let Some(feed) = st.feed else {
            return Err((
                "NC487",
                "CYCLE84 where the feed before it is not known".into(),
                "FANUC's G84 F changes the modal feed, which is written back after G80: program F as a number before the cycle",
            ));
        };
        let lead = p.abs();
        let f = if per_rev {
            Expr::num(lead, true, span)
        } else {
            match literal(&sst) {
                Some(s) => Expr::num(((lead * s) * 1e6).round() / 1e6, true, span),
                None => bin(BinOp::Mul, Expr::num(lead, true, span), sst.clone()),
            }
        };
        let g = if p < 0.0 { 74.0 } else { 84.0 };
        // FANUC's modal F already is the tapping feed: no F word, nothing to give back.
        if feed.is_some() && feed == literal(&f) {
            return Ok(TapPlan { g, f: None, m29: Some(sst), restore: None });
        }
        return Ok(TapPlan { g, f: Some(f), m29: Some(sst), restore: feed });
    }
    // CYCLE840.
    if constant(c, k, "ENC") != Some(1.0) {
        return Err((
            "NC488",
            "CYCLE840 with an encoder (ENC 0): its feed follows the spindle (G33)".into(),
            "FANUC's G84 without M29 feeds at F without that coupling, with M29 it is rigid tapping (CYCLE84): give ENC 1 or use CYCLE84",
        ));
    }
    if pitch(c, k)?.is_some() {
        return Err((
            "NC488",
            "CYCLE840 without an encoder but with a pitch (the feed is pitch × S)".into(),
            "FANUC's G84 feeds at the modal F: leave MPIT and PIT empty and program F",
        ));
    }
    let (Some(sdr), Some(sdac)) = (constant(c, k, "SDR"), sdac) else {
        return Err(("NC488", "CYCLE840 with SDR or SDAC known only at run time".into(), "write them as 3 or 4"));
    };
    let g = match (sdac, sdr) {
        (s, r) if s == 3.0 && r == 4.0 => 84.0,
        (s, r) if s == 4.0 && r == 3.0 => 74.0,
        _ => {
            return Err((
                "NC488",
                format!("CYCLE840 with SDAC {sdac} and SDR {sdr}"),
                "FANUC's G84 taps M3 in and M4 out (SDAC 3, SDR 4), G74 the reverse (SDAC 4, SDR 3)",
            ))
        }
    };
    Ok(TapPlan { g, f: None, m29: None, restore: None })
}

/// Rigid tapping is settled on FANUC only from a stopped spindle that stays stopped (M5
/// before, SDAC 5 or empty after): what M29 does with a turning spindle and the state FANUC
/// leaves after the cycle are settled by no source at hand (docs/semantics.md, "Drilling
/// cycles", rigid tapping). The refusal names which side differs.
fn spindle_settled(spindle: Option<u8>, sdac: Option<f64>) -> Result<(), Why> {
    const HINT: &str = "stop the spindle (M5) before the cycle and give SDAC 5 (or leave it empty); start it \
                        again after the cycle if it is needed";
    match spindle {
        Some(5) => {}
        Some(c) => {
            return Err((
                "NC487",
                format!(
                    "CYCLE84 with the spindle turning M{c} before it (FANUC's rigid tapping starts at M29, and \
                     what M29 does with a turning spindle, stop it or alarm, and the state it leaves after the \
                     cycle are not settled by a source)"
                ),
                HINT,
            ))
        }
        None => {
            return Err((
                "NC487",
                "CYCLE84 where the spindle's state before the cycle is not known here (a called program, a \
                 jump target or a call above it; FANUC's rigid tapping is settled only from a stopped spindle)"
                    .into(),
                HINT,
            ))
        }
    }
    match sdac {
        Some(x) if x == 0.0 || x == 5.0 => Ok(()),
        Some(x) => Err((
            "NC487",
            format!(
                "CYCLE84 with SDAC {x} (the spindle's state after each hole; FANUC's spindle after rigid \
                 tapping is settled only for one that stays stopped, SDAC 5)"
            ),
            HINT,
        )),
        None => {
            Err(("NC487", "CYCLE84 with SDAC known only at run time".into(), "write SDAC as 5 (or leave it empty)"))
        }
    }
}

/// The FANUC side of a Sinumerik boring call (CYCLE85, CYCLE87, CYCLE88): the G code, the
/// F word (CYCLE85 carries its feed, FANUC's G85/G89 take the modal F) and the F to write
/// back after G80.
pub fn plan_boring(c: &Call, k: SieCycle, st: &SieState) -> Result<TapPlan, Why> {
    let span = Span::default();
    match k {
        SieCycle::C85 => {
            let g = if constant(c, k, "DTB").is_some_and(|d| d != 0.0) { 89.0 } else { 85.0 };
            // FFR = RFF = `$P_F` (the feed in force, as the FANUC → Sinumerik translation
            // writes G85): FANUC's modal F already is that feed.
            if arg(c, k, "FFR").is_some_and(is_feed) && arg(c, k, "RFF").is_some_and(is_feed) {
                return Ok(TapPlan { g, f: None, m29: None, restore: None });
            }
            let (Some(ffr), Some(rff)) = (constant(c, k, "FFR"), constant(c, k, "RFF")) else {
                return Err((
                    "NC392",
                    "CYCLE85 with FFR or RFF known only at run time".into(),
                    "write them as numbers",
                ));
            };
            if ffr <= 0.0 || ffr != rff {
                return Err((
                    "NC391",
                    "CYCLE85 with a retract feed RFF other than its infeed FFR".into(),
                    "FANUC's G85 and G89 feed out at the feed they fed in at",
                ));
            }
            let Some(feed) = st.feed else {
                return Err((
                    "NC392",
                    "CYCLE85 where the feed before it is not known".into(),
                    "FANUC's G85 F changes the modal feed, which is written back after G80: program F as a number before the cycle",
                ));
            };
            // With a dwell at the bottom the motion is G89's.
            Ok(TapPlan { g, f: Some(Expr::num(ffr, true, span)), m29: None, restore: feed.filter(|p| *p != ffr) })
        }
        _ => {
            // CYCLE87/CYCLE88: spindle stop and program stop at the bottom (CYCLE88 after its
            // dwell), as FANUC's G88. SDIR is the direction the spindle turns in.
            let Some(sdir) = constant(c, k, "SDIR") else {
                return Err((
                    "NC392",
                    format!("{} with SDIR known only at run time", k.name()),
                    "write SDIR as 3 or 4",
                ));
            };
            match st.spindle {
                Some(s) if (s == 3 || s == 4) && (sdir == 0.0 || sdir == f64::from(s)) => {}
                _ => {
                    return Err((
                        "NC391",
                        format!("{} where the spindle is not known to turn in its direction SDIR", k.name()),
                        "FANUC's G88 bores with the spindle as it turns: program M3 or M4 (the same as SDIR) before the cycle",
                    ))
                }
            }
            Ok(TapPlan { g: 88.0, f: None, m29: None, restore: None })
        }
    }
}

/// Whether `e` is `$P_F`, the programmed feed.
fn is_feed(e: &Expr) -> bool {
    matches!(&e.kind, ExprKind::Var(v) if matches!(&v.kind, VarKind::System { name, indices } if name.eq_ignore_ascii_case("P_F") && indices.is_empty()))
}
