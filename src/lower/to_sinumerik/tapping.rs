//! FANUC tapping G84/G74 → Sinumerik, for `cycles::lower`: rigid tapping (`M29 S` before
//! the cycle) becomes CYCLE84 with the pitch and the tapping speed, floating tapping (no
//! M29) CYCLE840 without an encoder (ENC 1) at the programmed feed, with the retract
//! direction SDR and the direction SDAC the next threads start in. What the block list
//! does to the spindle and the feed mode before the cycle is followed here in text order;
//! where it is not known the cycle is refused. Sources and choices: docs/semantics.md
//! ("Tapping") and docs/translation-fanuc-to-sinumerik.md.

use super::*;

/// The spindle and feed state a tapping cycle needs, followed through one block list.
#[derive(Clone, Debug, Default)]
pub struct TapState {
    /// M3, M4 or M5 last programmed (`None`: not known here).
    pub spindle: Option<u8>,
    /// G95 (feed per revolution) in force; `None`: not known here.
    pub per_rev: Option<bool>,
    /// `M29 S…` seen: the S word's value (`None` inside: M29 without S) and where.
    pub rigid: Option<(Option<Expr>, Span)>,
    /// The last F programmed, where it is a number (the lead of a rigid cycle without its
    /// own F is F/S of it).
    pub feed: Option<f64>,
}

impl TapState {
    /// The state at the start of a block list: a main program's top starts with the spindle
    /// stopped and in G94 (power-on); elsewhere nothing is known.
    pub fn start(top: bool) -> TapState {
        if top {
            TapState { spindle: Some(5), per_rev: Some(false), rigid: None, feed: None }
        } else {
            TapState::default()
        }
    }

    /// A statement that is not a block (a structure, a call): nothing is known after it.
    pub fn forget(&mut self) {
        *self = TapState::default();
    }

    /// M3/M4/M5 and G94/G95 of a block inside a cycle (M29 there is refused by the caller).
    pub fn observe_modes(&mut self, items: &[Item]) {
        for it in items {
            if let ItemKind::Word(w) = &it.kind {
                match (w.addr.as_str(), word_literal(w)) {
                    ("M", Some(3.0)) => self.spindle = Some(3),
                    ("M", Some(4.0)) => self.spindle = Some(4),
                    ("M", Some(5.0)) => self.spindle = Some(5),
                    ("G", Some(94.0)) => self.per_rev = Some(false),
                    ("G", Some(95.0)) => self.per_rev = Some(true),
                    _ => {}
                }
            }
        }
    }

    /// Reads a block outside a cycle: M3/M4/M5, G94/G95 and `M29` (taken out of the block:
    /// the Sinumerik tapping cycle is chosen by it, it has no M29). A call makes the spindle
    /// unknown.
    pub fn observe(&mut self, b: &mut Block) {
        let mut m29 = None;
        for it in &b.items {
            match &it.kind {
                ItemKind::Word(w) => match (w.addr.as_str(), word_literal(w)) {
                    ("M", Some(3.0)) => self.spindle = Some(3),
                    ("M", Some(4.0)) => self.spindle = Some(4),
                    ("M", Some(5.0)) => self.spindle = Some(5),
                    ("M", Some(29.0)) => m29 = Some(it.span),
                    ("G", Some(94.0)) => self.per_rev = Some(false),
                    ("G", Some(95.0)) => self.per_rev = Some(true),
                    ("F", f) => self.feed = f,
                    _ => {}
                },
                ItemKind::Call(_) => self.forget(),
                _ => {}
            }
        }
        if let Some(at) = m29 {
            let s = b.items.iter().find_map(|it| match &it.kind {
                ItemKind::Word(w) if w.addr.is(b'S') => match &w.value {
                    WordValue::Expr(e) => Some(e.clone()),
                    _ => None,
                },
                _ => None,
            });
            b.items.retain(
                |it| !matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'M') && word_literal(w) == Some(29.0)),
            );
            self.rigid = Some((s, at));
        }
    }
}

fn word_literal(w: &Word) -> Option<f64> {
    match &w.value {
        WordValue::Expr(e) => literal(e),
        _ => None,
    }
}

/// What a tapping cycle call needs from the FANUC side.
pub struct Tap<'a> {
    /// 840 (G84) or 740 (G74).
    pub g: u32,
    /// The F word of the cycle sequence, if one was given there.
    pub f: Option<&'a Expr>,
    pub state: &'a TapState,
}

/// A refusal: what differs, and a hint.
pub type Why = (&'static str, String, &'static str);

/// The cycle name and the arguments after RTP, RFP, SDIS, DP, DPR, DTB.
pub fn call_args(t: &Tap, span: Span) -> Result<(&'static str, Vec<Arg>), Why> {
    let left = t.g == 740;
    let (code, name) = if left { (4u8, "G74") } else { (3u8, "G84") };
    let v = |e: Expr| Arg::Value(e);
    let none = || Arg::Omitted(span);
    match &t.state.rigid {
        Some((s, _)) => {
            let Some(s) = s.clone() else {
                return Err((
                    "NC483",
                    "M29 without a spindle speed S".into(),
                    "write the tapping speed in the M29 block: M29 S…",
                ));
            };
            // What FANUC does with a spindle that turns at M29 (stops it, alarms) and in
            // which state it leaves it after the rigid cycle and G80 is settled by no source
            // at hand (docs/semantics.md, "Drilling cycles", rigid tapping), so no SDAC of
            // CYCLE84 can be shown to match; from a stopped spindle both controls tap at the
            // M29 speed and leave it stopped (SDAC 5).
            if let Some(why) = not_stopped(t.state.spindle, name) {
                return Err(why);
            }
            let Some(per_rev) = t.state.per_rev else {
                return Err((
                    "NC485",
                    format!("rigid tapping {name} where G94/G95 is not known"),
                    "program G94 or G95 before the cycle",
                ));
            };
            let f = t.f.cloned().unwrap_or_else(|| match t.state.feed {
                Some(x) => num(x, span),
                None => var_expr(VarKind::Hash(4109), span),
            });
            // The thread lead: F itself per revolution, F/S per minute (FANUC 0i connection
            // manual, rigid tapping); its sign is the hand.
            let mut pit = if per_rev { f.clone() } else { ratio(&f, &s, span) };
            if left {
                pit = match literal(&pit) {
                    Some(x) => num(-x, span),
                    None => Expr::new(ExprKind::Unary(UnOp::Neg, Box::new(pit)), span),
                };
            }
            // SDAC 5: the spindle stays stopped; MPIT and POSS empty.
            Ok(("CYCLE84", vec![v(int(5, span)), none(), v(pit), none(), v(s)]))
        }
        None => {
            match t.state.spindle {
                Some(c) if c == code => {}
                Some(c) => {
                    return Err((
                        "NC484",
                        format!(
                            "floating tapping {name} with the spindle {}",
                            if c == 5 {
                                "stopped"
                            } else if c == 3 {
                                "turning M3"
                            } else {
                                "turning M4"
                            }
                        ),
                        if left {
                            "G74 taps with the spindle turning M4: program M4 before the cycle"
                        } else {
                            "G84 taps with the spindle turning M3: program M3 before the cycle"
                        },
                    ))
                }
                None => {
                    return Err((
                        "NC484",
                        format!("floating tapping {name} where the spindle direction is not known"),
                        "program M3 (G84) or M4 (G74) in this block list before the cycle",
                    ))
                }
            }
            let sdr = if left { 3 } else { 4 };
            // SDR: the retract direction, SDAC: the direction the next threads start in,
            // ENC 1: no encoder, the programmed feed (FANUC's F).
            Ok(("CYCLE840", vec![v(int(sdr, span)), v(int(code as i64, span)), v(int(1, span))]))
        }
    }
}

/// The refusal of rigid tapping from a spindle not known to be stopped: what differs is
/// named for a spindle turning M3/M4 and for one not known here.
fn not_stopped(spindle: Option<u8>, name: &str) -> Option<Why> {
    const HINT: &str = "program M5 before M29 S…: from a stopped spindle both controls tap at the M29 speed and \
                        leave it stopped (CYCLE84 SDAC 5); start it again after G80 if it is needed";
    match spindle {
        Some(5) => None,
        Some(c) => Some((
            "NC484",
            format!(
                "rigid tapping {name} with the spindle turning M{c} before M29: what FANUC does with a turning \
                 spindle at M29 (stop it or alarm) and the state it leaves after the cycle and G80 are not \
                 settled by a source, so no CYCLE84 SDAC (3, 4, 5) can be shown to match"
            ),
            HINT,
        )),
        None => Some((
            "NC484",
            format!(
                "rigid tapping {name} where the spindle's state before M29 is not known here (a called \
                 program, a jump target or a call above it): FANUC's rigid tapping is settled only from a \
                 stopped spindle (M5)"
            ),
            HINT,
        )),
    }
}

/// `f / s`, as a number where the quotient is exact to the output's precision.
fn ratio(f: &Expr, s: &Expr, span: Span) -> Expr {
    if let (Some(a), Some(b)) = (literal(f), literal(s)) {
        if b != 0.0 {
            let q = ((a / b) * 1e6).round() / 1e6;
            if (q * b - a).abs() < 1e-9 {
                return num(q, span);
            }
        }
    }
    bin(BinOp::Div, f.clone(), s.clone())
}
