//! Siemens `CHF=` (a chamfer given by its own length) → FANUC `,C` (its leg from the virtual
//! corner) where the corner is known at translation: both moves G1 lines whose end points are
//! constants of one coordinate system (literal positions, increments from a known point, R
//! parameters and DEF variables of one value, `lower::known` through `cycles_known`), in a
//! known plane and unit, with no label, structure, call, frame, work offset or unit change
//! between the three points. The leg is `eval::corner`'s own computation of the run, so the
//! two cannot disagree; it is written only where it is a whole number of FANUC's input
//! increment (within half the trace tolerance), since FANUC rounds `,C` to the increment as
//! every length and any other value would make another chamfer than the Siemens one. Every
//! other CHF is refused (NC572) saying what is not known (docs/semantics.md, "Chamfers and
//! roundings").

use super::cycles_known::{self, Vals};
use super::{Ctx, ProgInfo};
use crate::dialect::semantics::input_increment;
use crate::eval::corner::{self, NOT_TRANSLATABLE};
use crate::eval::value::{fmt_num, round_to};
use crate::ir::*;
use crate::lower::g_codes;

const LETTERS: &[u8; 9] = b"XYZABCUVW";

/// How far (mm) the FANUC leg may lie from the run's: the chamfer's two points move by at
/// most this, half the trace tolerance (1e-6), so the proof passes with room to spare.
const SLACK_MM: f64 = 5e-7;

/// Why a streamed translation's stand-in for a stretch of plain blocks ends what is known.
const STREAMED: &str =
    "a streamed translation writes the blocks next to it one by one, without following positions: translate the file whole";

/// Name words that neither move an axis nor change what the positions mean.
const QUIET_NAMES: &[&str] = &["CHF", "CHR", "RND", "RNDM", "CR", "AR", "TURN"];

/// Letters that neither move a linear or rotary axis nor change a mode the corner needs.
const QUIET_LETTERS: &[u8] = b"FSTDMHIJKN";

/// What the walk knows before a block: each axis's programmed position (in the program's
/// unit, rounded as the run rounds the word) or why it is not known, and the modes.
#[derive(Clone, Debug)]
struct St {
    pos: [Result<f64, String>; 9],
    absolute: Option<bool>,
    /// The modal motion G code ×10 (0, 10, 20, 30).
    motion: Option<u32>,
    /// G17/G18/G19 ×10.
    plane: Option<u32>,
    inch: Option<bool>,
}

/// The modes that hold everywhere in the program (no word or call changes them): what a
/// body or a stretch after a label starts in.
#[derive(Clone, Copy, Debug, Default)]
struct Steady {
    absolute: Option<bool>,
    plane: Option<u32>,
    inch: Option<bool>,
}

impl St {
    fn forgotten(why: &str, steady: Steady) -> St {
        St {
            pos: std::array::from_fn(|_| Err(why.to_string())),
            absolute: steady.absolute,
            motion: None,
            plane: steady.plane,
            inch: steady.inch,
        }
    }

    fn forget_positions(&mut self, why: &str) {
        self.pos = std::array::from_fn(|_| Err(why.to_string()));
    }

    /// After `b` ran (its skip and label are the caller's).
    fn apply(&mut self, b: &Block, vals: &Vals, ctx: &Ctx) {
        for g in g_codes(&b.items) {
            match g {
                0 | 10 | 20 | 30 => self.motion = Some(g),
                900 => self.absolute = Some(true),
                910 => self.absolute = Some(false),
                170 | 180 | 190 => self.plane = Some(g),
                700 | 7000 | 710 | 7100 => {
                    self.inch = Some(g == 700 || g == 7000);
                    self.forget_positions("positions are not followed across a change of units (G70/G71/G700/G710)");
                }
                // Compensation, feed type, exact stop and continuous path, dwell: the programmed
                // positions keep their meaning.
                40 | 90 | 400 | 410 | 420 | 600 | 640 | 6410 | 6420 | 930 | 940 | 950 => {}
                _ => self
                    .forget_positions(&format!("positions are not followed across G{}", fmt_num(f64::from(g) / 10.0))),
            }
        }
        let inc = input_increment(ctx.source_increment_mm, self.inch == Some(true), false);
        for it in &b.items {
            match &it.kind {
                ItemKind::Word(w) => match &w.addr {
                    Addr::Letter(l) => {
                        if let Some(i) = LETTERS.iter().position(|c| c == l) {
                            self.pos[i] = self.axis(i, w, vals, inc);
                        } else if !QUIET_LETTERS.contains(l) && *l != b'G' {
                            self.forget_positions(&format!(
                                "positions are not followed across the word {}",
                                *l as char
                            ));
                        }
                    }
                    Addr::Name(n) if QUIET_NAMES.contains(&n.as_ref()) => {}
                    Addr::Name(n) => self.forget_positions(&format!("positions are not followed across {n}=")),
                    Addr::Axis(_) => {
                        self.forget_positions("positions are not followed across an axis chosen at run time (AX[…])")
                    }
                },
                ItemKind::Assign { target, .. } if !matches!(target.kind, VarKind::System { .. }) => {}
                ItemKind::Message { .. } | ItemKind::Def(_) | ItemKind::Stopre => {}
                ItemKind::Call(_) => {
                    self.forget_positions("positions are not followed across a call (it may move the axes)")
                }
                ItemKind::Frame { op, .. } => {
                    self.forget_positions(&format!("positions are not followed across {op} (it changes their frame)"))
                }
                _ => self.forget_positions(
                    "positions are not followed across a jump, a write of a system variable or an end",
                ),
            }
        }
    }

    /// Axis `i`'s programmed position after its word `w`.
    fn axis(&self, i: usize, w: &Word, vals: &Vals, inc: f64) -> Result<f64, String> {
        let l = LETTERS[i] as char;
        let (e, mode) = match &w.value {
            WordValue::Expr(e) => (e, self.absolute),
            WordValue::Ac(e) => (e, Some(true)),
            WordValue::Ic(e) => (e, Some(false)),
            WordValue::Rotary(..) => return Err(format!("{l} is a rotary positioning (ACP, DC, …)")),
        };
        let v = vals.value_at(w.span, e, "the block").map_err(|r| format!("{l} is a variable: {r}"))?;
        let v = round_to(v, inc);
        match mode {
            Some(true) => Ok(v),
            Some(false) => match &self.pos[i] {
                Ok(p) => Ok(p + v),
                Err(why) => Err(format!("{l} is an increment from a position not known: {why}")),
            },
            None => Err(format!("{l}: whether the position is absolute (G90) or incremental (G91) is not known there")),
        }
    }
}

/// The modes no word or call changes anywhere in `prog` (a main program starts in G17,
/// G90, metric: the power-on state of the trace convention).
fn steady(ctx: &Ctx, prog: &Program, is_sub: bool) -> Steady {
    if is_sub {
        return Steady::default();
    }
    let (mut planes, mut incremental, mut inch, mut calls) = (false, false, false, false);
    crate::ir::visit::walk_stmts(&prog.body, &mut |s| {
        let StmtKind::Block(b) = &s.kind else { return };
        for g in g_codes(&b.items) {
            planes |= g == 180 || g == 190;
            incremental |= g == 910;
            inch |= g == 700 || g == 7000;
        }
        for it in &b.items {
            if let ItemKind::Call(c) = &it.kind {
                calls |= match &c.target {
                    CallTarget::Name(n) => {
                        let n = n.to_ascii_uppercase();
                        crate::dialect::sinumerik::cycles::cycle_of(&n).is_none()
                            && ctx.callees.get(&n).is_none_or(|k| k.effect.leaves() != 0)
                    }
                    _ => true,
                };
            }
        }
    });
    if calls {
        return Steady::default();
    }
    Steady { absolute: (!incremental).then_some(true), plane: (!planes).then_some(170), inch: (!inch).then_some(false) }
}

fn has_chf(body: &[Stmt]) -> bool {
    let mut any = false;
    crate::ir::visit::walk_stmts(body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            any |= b.items.iter().any(|it| matches!(&it.kind, ItemKind::Word(w) if w.addr.as_str() == "CHF"));
        }
    });
    any
}

/// Makes each CHF of `prog` the CHR of its leg where the corner is known, refuses the rest;
/// runs before `corners`' own pass, which then treats the CHR as written.
pub fn run(ctx: &mut Ctx, prog: &mut Program, info: &ProgInfo) {
    if !has_chf(&prog.body) {
        return;
    }
    let want = |it: &Item| match &it.kind {
        ItemKind::Word(w) => {
            let axis = matches!(w.addr, Addr::Letter(l) if LETTERS.contains(&l));
            (axis || w.addr.as_str() == "CHF")
                && !matches!(&w.value, WordValue::Expr(e) if crate::lower::literal(e).is_some())
        }
        _ => false,
    };
    let vals = cycles_known::vals_where(ctx, prog, info, cycles_known::interrupt_and_sync(prog), &want);
    let steady = steady(ctx, prog, info.is_sub);
    let landings = crate::lower::landings::Landings::of(&prog.body);
    let start = if info.is_sub {
        St::forgotten("a subprogram starts where its caller left the axes", steady)
    } else {
        St { motion: Some(0), ..St::forgotten("where the axes stand when the program starts is not known", steady) }
    };
    let w = Walk { vals: &vals, steady, landings: &landings };
    w.body(ctx, &mut prog.body, start);
}

struct Walk<'a> {
    vals: &'a Vals,
    steady: Steady,
    landings: &'a crate::lower::landings::Landings,
}

impl Walk<'_> {
    fn body(&self, ctx: &mut Ctx, list: &mut [Stmt], mut st: St) {
        for j in 0..list.len() {
            if !matches!(list[j].kind, StmtKind::Block(_)) {
                self.nested(ctx, &mut list[j]);
                st = St::forgotten(
                    "positions are not followed across an IF, loop or CASE (they depend on the path)",
                    self.steady,
                );
                continue;
            }
            let StmtKind::Block(b) = &list[j].kind else { continue };
            if self.landings.at(&b.meta) {
                st = St::forgotten(
                    "positions are not followed across a jump target (a GOTO may come from elsewhere)",
                    self.steady,
                );
            }
            let before = st.clone();
            if super::stand_in(&b.meta).is_some() {
                st = St::forgotten(STREAMED, self.steady);
            } else if b.meta.skip.is_some() {
                // Whether it runs is the operator's switch: its positions and modes both.
                st = St::forgotten("positions are not followed across a block that may be skipped (/)", self.steady);
            } else {
                st.apply(b, self.vals, ctx);
            }
            let Some(k) =
                b.items.iter().position(|it| matches!(&it.kind, ItemKind::Word(w) if w.addr.as_str() == "CHF"))
            else {
                continue;
            };
            // A line with nothing but a comment or a number commands nothing (the run passes
            // over it); a streamed translation's stand-in has blocks behind it.
            let next = list[j + 1..].iter().find(
                |s| !matches!(&s.kind, StmtKind::Block(b) if b.items.is_empty() && super::stand_in(&b.meta).is_none()),
            );
            let outcome = self.corner(ctx, &before, &st, b, &b.items[k], next);
            let StmtKind::Block(b) = &mut list[j].kind else { continue };
            let ItemKind::Word(w) = &mut b.items[k].kind else { continue };
            match outcome {
                Ok(leg) => {
                    w.addr = Addr::Name("CHR".into());
                    w.value = WordValue::Expr(Expr::num(leg, true, w.span));
                }
                Err((why, hint)) => {
                    let _ =
                        ctx.unsupported(NOT_TRANSLATABLE, w.span, "CHF= (a chamfer given by its own length)", &hint);
                    if let Some(d) = ctx.diags.last_mut() {
                        *d = d.clone().note(why);
                    }
                }
            }
        }
    }

    /// The structure's own bodies, each from nothing known.
    fn nested(&self, ctx: &mut Ctx, s: &mut Stmt) {
        let fresh =
            || St::forgotten("the positions at the start of an IF, loop or CASE body depend on the path", self.steady);
        match &mut s.kind {
            StmtKind::Block(_) => {}
            StmtKind::If(i) => {
                self.body(ctx, &mut i.then_body, fresh());
                if let Some(e) = &mut i.else_part {
                    self.body(ctx, &mut e.body, fresh());
                }
            }
            StmtKind::While(w) => self.body(ctx, &mut w.body, fresh()),
            StmtKind::Loop(l) => self.body(ctx, &mut l.body, fresh()),
            StmtKind::For(x) => self.body(ctx, &mut x.body, fresh()),
            StmtKind::Repeat(r) => self.body(ctx, &mut r.body, fresh()),
            StmtKind::Do(d) => self.body(ctx, &mut d.body, fresh()),
        }
    }

    /// The leg to write for the CHF `item` of `b` (`before`/`after`: the walk around `b`,
    /// `next`: the statement after it), or why not and the hint.
    fn corner(
        &self,
        ctx: &Ctx,
        before: &St,
        after: &St,
        b: &Block,
        item: &Item,
        next: Option<&Stmt>,
    ) -> Result<f64, (String, String)> {
        let plain = |why: String| {
            (
                format!("the leg needs the corner's angle, but {why}"),
                "FANUC `,C` is the leg from the virtual corner, CHF / (2·cos(turn/2)); the translation works it out where \
                 both moves are G1 lines between end points known at translation (literal positions, or R parameters and \
                 DEF variables of one value; no label, structure, call, frame or unit change between): else write \
                 CHR=<leg>"
                    .to_string(),
            )
        };
        let ItemKind::Word(w) = &item.kind else { return Err(plain("the word is not a value".into())) };
        if b.meta.skip.is_some() {
            return Err(plain("the block may be skipped (/)".into()));
        }
        let plane = after.plane.ok_or_else(|| plain("the working plane (G17/G18/G19) is not known there".into()))?;
        let inch = after.inch.ok_or_else(|| plain("the units (G70/G71) are not known there".into()))?;
        let (u, v) = match plane {
            170 => (0, 1),
            180 => (2, 0),
            _ => (1, 2),
        };
        let point = |st: &St, what: &str| match (&st.pos[u], &st.pos[v]) {
            (Ok(a), Ok(b)) => Ok((*a, *b)),
            (Err(why), _) | (_, Err(why)) => Err(plain(format!("{what} is not known at translation: {why}"))),
        };
        let p0 = point(before, "where the move to the corner starts")?;
        let p1 = point(after, "the corner")?;
        motion(after.motion, "the move to the corner").map_err(plain)?;
        let nb = match next.map(|s| &s.kind) {
            Some(StmtKind::Block(nb)) if nb.meta.skip.is_none() => nb,
            Some(StmtKind::Block(_)) => return Err(plain("the block after it may be skipped (/)".into())),
            Some(_) => return Err(plain("the block after it begins an IF, loop or CASE, not a move".into())),
            None => return Err(plain("no block follows it in its body".into())),
        };
        if super::stand_in(&nb.meta).is_some() {
            return Err(plain(STREAMED.into()));
        }
        let mut st2 = after.clone();
        st2.apply(nb, self.vals, ctx);
        motion(st2.motion, "the move after the corner").map_err(plain)?;
        if st2.plane != after.plane || st2.inch != after.inch {
            return Err(plain("the block after it changes the plane or the units".into()));
        }
        let p2 = point(&st2, "the end point of the move after it")?;
        let WordValue::Expr(e) = &w.value else { return Err(plain("its value is not a length".into())) };
        let sie = input_increment(ctx.source_increment_mm, inch, false);
        let chf =
            self.vals.value_at(w.span, e, "the block").map_err(|r| plain(format!("its length is a variable: {r}")))?;
        let chf = round_to(chf, sie);
        let (leg, theta) = corner::chord_leg(p0, p1, p2, chf).map_err(|bad| {
            (
                format!("the corner cannot be made ({})", bad.text()),
                "the Siemens run refuses this corner too (FANUC alarms, Siemens reduces it by a rule not modelled): \
                 make the chamfer smaller or the corner a real one"
                    .to_string(),
            )
        })?;
        on_grid(ctx, chf, leg, theta, inch)
    }
}

/// Why the motion `m` is not the G1 line a known corner needs.
fn motion(m: Option<u32>, what: &str) -> Result<(), String> {
    match m {
        Some(10) => Ok(()),
        Some(20 | 30) => Err(format!(
            "{what} is an arc (G2/G3): chamfers next to arcs are not modelled (the run refuses them as well)"
        )),
        Some(_) => Err(format!("{what} is a rapid move (G0), which takes no chamfer")),
        None => Err(format!("the motion (G0–G3) of {what} is not known at translation")),
    }
}

/// The leg as FANUC takes it, where it is the run's leg: a whole number of the target's
/// input increment (FANUC rounds `,C` to it).
fn on_grid(ctx: &Ctx, chf: f64, leg: f64, theta: f64, inch: bool) -> Result<f64, (String, String)> {
    let inc = input_increment(ctx.target_increment_mm, inch, false);
    let scale = (1.0 / inc).round();
    let near = (leg * scale).round() / scale;
    let mm = if inch { 25.4 } else { 1.0 };
    if (near - leg).abs() * mm <= SLACK_MM {
        return Ok(near);
    }
    let unit = if inch { "in" } else { "mm" };
    let r7 = |x: f64| {
        let t = format!("{x:.7}");
        t.trim_end_matches('0').trim_end_matches('.').to_string()
    };
    let deg = theta.to_degrees();
    let why = format!(
        "the corner turns {}°, so the leg is {}/(2·cos {}°) = {}…, not a whole number of FANUC's input increment {} {unit}, \
         so `,C{}` would make a chamfer {} {unit} off the Siemens one",
        r7(deg),
        fmt_num(chf),
        r7(deg / 2.0),
        r7(leg),
        fmt_num(inc),
        fmt_num(near),
        r7((near - leg).abs()),
    );
    let hint = format!(
        "FANUC rounds `,C` to its increment like every length: write CHR={} if that chamfer is meant, or a CHF whose \
         leg lies on the grid",
        fmt_num(near)
    );
    Err((why, hint))
}
