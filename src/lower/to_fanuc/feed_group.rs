//! A Siemens feed move known at translation time to move an axis outside the feed group
//! (`FGROUP`, the geometry axes X, Y, Z by default) together with an axis inside it: the
//! control runs F along the group's axes only and drags the other along, FANUC runs F along
//! every axis, so the same F is another speed (docs/semantics.md, "Feed of moves with rotary
//! axes and FGROUP"). Such a move is refused here, naming it and the group, rather than left
//! to the proof's divergence; FANUC has no word for the Siemens feed, and a recomputed F
//! would be a near value. Where the move is not known (a value from a variable, a position
//! a jump or call may have changed) the proof compares each move's feed.
//!
//! Known means: top-level blocks in order from the program's start (a main program starts
//! in G0 G90 with the default group), every axis word a literal, the positions before the
//! block written by literal words since the last label, structure, call or frame change.
//! Runs after `axis_vars`, so an axis an AXIS variable holds is already its letter.

use super::Ctx;
use crate::ir::*;
use crate::lower::{g_codes, literal};
use crate::span::Span;

/// A Siemens move whose feed differs on FANUC (the run's own refusal is NC662).
pub const MOVE_FEED_DIFFERS: &str = "NC664";
/// `FGREF[A]=r`: FANUC has no reference radius (its F counts a degree as a millimetre).
pub const REFERENCE_RADIUS: &str = "NC619";

/// Whether `b` assigns the reference radius of a rotary axis (`FGREF[A]=r`).
fn is_fgref(b: &Block) -> bool {
    b.items.iter().any(|it| {
        matches!(&it.kind, ItemKind::Assign { target, .. }
            if matches!(&target.kind, VarKind::Named { name, indices } if name == "FGREF" && indices.len() == 1))
    })
}

/// Refuses every `FGREF[…]=…` of `body` in its place: FANUC's feed along a rotary axis
/// counts each degree as a millimetre whatever the radius, so a program that sets one
/// moves its rotary axes at other speeds there (the run models it, `eval::fgroup`).
fn refuse_fgref(ctx: &mut Ctx, body: &mut Vec<Stmt>, declared: bool) {
    let mut i = 0;
    while i < body.len() {
        match &mut body[i].kind {
            StmtKind::Block(b) if !declared && is_fgref(b) => {
                let span = b.meta.span;
                let what = "FGREF (the reference radius of a rotary axis in the feed group)";
                let hint = "FANUC runs F along every axis with a degree counted as a millimetre, whatever the radius: \
                            program the rotary moves' F as FANUC reads it, without FGREF";
                match ctx.unsupported(REFERENCE_RADIUS, span, what, hint) {
                    Some(mark) => {
                        body[i] = mark;
                        i += 1;
                    }
                    None => {
                        body.remove(i);
                    }
                }
                continue;
            }
            k => crate::ir::visit::child_bodies_mut(k).into_iter().for_each(|c| refuse_fgref(ctx, c, declared)),
        }
        i += 1;
    }
}

const LETTERS: &[u8; 9] = b"XYZABCUVW";
/// The Siemens default feed group: the geometry axes X, Y, Z.
const GEOMETRY: u16 = 0b111;

/// The axis letters of a bit set, comma separated (`X, A`).
fn names(bits: u16) -> String {
    let v: Vec<String> = (0..9).filter(|i| bits & (1 << i) != 0).map(|i| (LETTERS[i] as char).to_string()).collect();
    v.join(", ")
}

#[derive(Clone, Copy)]
struct State {
    /// The feed group and where it was set (`None` at the default group).
    group: Option<(u16, Option<Span>)>,
    absolute: Option<bool>,
    /// The modal motion G code ×10 (0, 10, 20, 30).
    motion: Option<u32>,
    pos: [Option<f64>; 9],
    /// A frame was programmed: a programmed axis may move other machine axes.
    framed: bool,
}

impl State {
    /// After a label, a structure or a call: neither positions nor modes are known.
    fn forget_positions(&mut self) {
        self.pos = [None; 9];
        self.absolute = None;
        self.motion = None;
    }
}

fn is_fgroup(c: &Call) -> bool {
    matches!(&c.target, CallTarget::Name(n) if n.eq_ignore_ascii_case("FGROUP"))
}

/// The axes `FGROUP(…)` names, where each is a letter.
fn fgroup_axes(c: &Call) -> Option<u16> {
    let mut bits = 0;
    for a in &c.args {
        let Arg::Value(e) = a else { return None };
        let name = match &e.kind {
            ExprKind::Ident(n) => n.as_str(),
            ExprKind::Var(v) => match &v.kind {
                VarKind::Named { name, indices } if indices.is_empty() => name.as_str(),
                _ => return None,
            },
            _ => return None,
        };
        let [l] = name.as_bytes() else { return None };
        bits |= 1 << LETTERS.iter().position(|c| c.eq_ignore_ascii_case(l))?;
    }
    Some(if bits == 0 { GEOMETRY } else { bits })
}

/// Whether `stmts` hold an FGROUP or a call anywhere (a group a jump or return may bring).
fn may_set_group(stmts: &[Stmt]) -> bool {
    let mut found = false;
    crate::ir::visit::walk_stmts(stmts, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            found |= b.items.iter().any(|it| matches!(it.kind, ItemKind::Call(_)));
        }
    });
    found
}

pub fn run(ctx: &mut Ctx, prog: &mut Program, is_sub: bool) {
    // A program's own variable named FGREF is that variable.
    let mut declared = false;
    crate::ir::visit::walk_stmts(&prog.body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            declared |= b
                .items
                .iter()
                .any(|it| matches!(&it.kind, ItemKind::Def(d) if d.vars.iter().any(|v| v.name == "FGREF")));
        }
    });
    refuse_fgref(ctx, &mut prog.body, declared);
    let any_group = may_set_group(&prog.body);
    let mut st = State {
        group: (!is_sub).then_some((GEOMETRY, None)),
        absolute: (!is_sub).then_some(true),
        motion: (!is_sub).then_some(0),
        pos: [None; 9],
        framed: false,
    };
    for s in prog.body.iter_mut() {
        let StmtKind::Block(b) = &s.kind else {
            if may_set_group(std::slice::from_ref(s)) {
                st.group = None;
            }
            st.forget_positions();
            continue;
        };
        if b.meta.label.is_some() {
            st.forget_positions();
            if any_group {
                st.group = None;
            }
        }
        if let Some(refusal) = block(ctx, &mut st, b) {
            *s = refusal;
        }
    }
}

/// Follows one block; a refusal to stand in its place (`--unsupported warn`), if any.
fn block(ctx: &mut Ctx, st: &mut State, b: &Block) -> Option<Stmt> {
    if b.meta.skip.is_some() {
        // Block skip: the operator's switch decides whether it runs.
        if b.items.iter().any(|it| matches!(it.kind, ItemKind::Call(_))) {
            st.group = None;
        }
        // G codes the block would not change anything with (`/G1 Z-0.5` in G1).
        let same = |g: &u32| match g {
            0 | 10 | 20 | 30 => st.motion == Some(*g),
            900 => st.absolute == Some(true),
            910 => st.absolute == Some(false),
            _ => false,
        };
        let plain = g_codes(&b.items).iter().all(same)
            && b.items
                .iter()
                .all(|it| matches!(&it.kind, ItemKind::Word(w) if matches!(w.addr, Addr::Letter(l) if l != b'F')));
        if !plain {
            st.forget_positions();
            return None;
        }
        for it in &b.items {
            if let ItemKind::Word(Word { addr: Addr::Letter(l), .. }) = &it.kind {
                if let Some(i) = LETTERS.iter().position(|c| c == l) {
                    st.pos[i] = None;
                }
            }
        }
        return None;
    }
    let mut words: Vec<(usize, Option<f64>, Option<bool>)> = Vec::new();
    for it in &b.items {
        match &it.kind {
            ItemKind::Call(c) if is_fgroup(c) => {
                st.group = fgroup_axes(c).map(|g| (g, (g != GEOMETRY || !c.args.is_empty()).then_some(it.span)));
            }
            ItemKind::Word(w) => match &w.addr {
                Addr::Letter(l) => {
                    if let Some(i) = LETTERS.iter().position(|c| c == l) {
                        let (v, mode) = match &w.value {
                            WordValue::Expr(e) => (literal(e), None),
                            WordValue::Ac(e) => (literal(e), Some(true)),
                            WordValue::Ic(e) => (literal(e), Some(false)),
                            _ => (None, None),
                        };
                        words.push((i, v, mode));
                    }
                }
                _ => {
                    // An axis chosen at run time: any axis may move.
                    st.forget_positions();
                    return None;
                }
            },
            ItemKind::Assign { .. }
            | ItemKind::Message { .. }
            | ItemKind::Def(_)
            | ItemKind::Stopre
            | ItemKind::End { .. } => {}
            _ => {
                match it.kind {
                    ItemKind::Call(_) => st.group = None,
                    ItemKind::Frame { .. } => st.framed = true,
                    _ => {}
                }
                st.forget_positions();
                return None;
            }
        }
    }
    let gs = g_codes(&b.items);
    for g in &gs {
        match g {
            0 | 10 | 20 | 30 => st.motion = Some(*g),
            900 => st.absolute = Some(true),
            910 => st.absolute = Some(false),
            170 | 180 | 190 | 940 | 640 | 600 | 90 => {}
            // Units, frames, machine coordinates, reference returns …: positions start over.
            _ => {
                st.pos = [None; 9];
                return None;
            }
        }
    }
    if words.is_empty() {
        return None;
    }

    let mut moved = 0u16;
    let mut known = true;
    for &(i, v, mode) in &words {
        let abs = mode.or(st.absolute);
        let new = match (v, abs) {
            (Some(v), Some(true)) => Some(v),
            (Some(v), Some(false)) => st.pos[i].map(|p| p + v),
            _ => None,
        };
        let did_move = match (v, abs, st.pos[i]) {
            (Some(v), Some(true), Some(old)) => Some((v - old).abs() > 1e-9),
            (Some(v), Some(false), _) => Some(v.abs() > 1e-9),
            _ => None,
        };
        match did_move {
            Some(true) => moved |= 1 << i,
            Some(false) => {}
            None => known = false,
        }
        st.pos[i] = new;
    }
    let (Some(10), Some((group, set_at)), true, false) = (st.motion, st.group, known, st.framed) else { return None };
    let outside = moved & !group;
    if outside == 0 || moved & group == 0 {
        return None;
    }
    let which = match set_at {
        Some(_) => format!("FGROUP({})", names(group).replace(' ', "")),
        None => "the default feed group (X, Y, Z)".to_string(),
    };
    let what = format!("the feed of this move of {}", names(moved));
    let why = format!(
        "under {which} Sinumerik runs F along {} only and drags {} along; FANUC runs F along every axis that moves (degrees counted as mm), so the same F is another speed",
        names(moved & group),
        names(outside)
    );
    let hint = format!(
        "write FGROUP({}) before the move, so that F runs along every axis that moves as on FANUC, or move {} in a block of its own",
        names(group | outside).replace(' ', ""),
        names(outside)
    );
    let refusal = ctx.unsupported(MOVE_FEED_DIFFERS, b.meta.span, &what, &hint);
    if let Some(d) = ctx.diags.last_mut() {
        let mut n = d.clone().note(why);
        if let Some(at) = set_at {
            n = n.secondary(ctx.file, at, "the feed group set here");
        }
        *d = n;
    }
    refusal
}
