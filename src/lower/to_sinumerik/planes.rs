//! The plane (G17/G18/G19) in force at each block of a FANUC program, where every path to
//! the block agrees on it: what a `G68 R a` without a centre needs (`rotation.rs`), whose
//! centre is the tool position in the two axes of that plane. A forward must-analysis over
//! the program's control-flow graph (`vacancy::flatten`: FANUC jump order, loops, the Haas
//! `M97` sections followed as jumps), starting in G17 in a main program (the power-on plane
//! the FANUC run takes) and, in a called program, in the plane every call of it in the job is
//! made in ([`start_planes`], a fixed point over the call graph). A call of a program that may
//! select a plane (itself or through its calls, [`setters`]), a computed call or G code, or a
//! modal G66 macro that may, makes the plane unknown from there on. Beside the plane the
//! flow follows whether the tool stands on the grid of the input increment ([`At::grid`]).

use super::vacancy::{flatten, succs, Node};
use super::*;

/// What a block starts in, each part where every path to it agrees.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct At {
    /// The plane G code (×10: 170, 180, 190), `None` where not known.
    pub plane: Option<u32>,
    /// The axes X, Y, Z (bits 0..2) whose workpiece position is surely on the grid of the
    /// input increment (0.001 mm): each was last positioned by an absolute word (or an
    /// increment from such a position) with no frame mode in force. A rotated, scaled or
    /// polar move, a reference return, G53, a probe move, an offset write, a unit change
    /// ([`At::inch`]) or a call that may do any of these leaves it off: the Sinumerik frame
    /// value the tool position becomes (`ATRANS X=..`) is rounded to the increment as a
    /// word, FANUC's centre is not.
    pub grid: u8,
    /// The frame modes (bits: G68, G51, G51.1, G16) that may be in force.
    pub modes: u8,
    /// G91 (`Some(true)`), G90, or not known.
    pub incremental: Option<bool>,
    /// G20 (`Some(true)`), G21, or not known: a position on one unit's grid is not on the
    /// other's, so a unit change leaves every axis off the grid.
    pub inch: Option<bool>,
}

impl At {
    pub const UNKNOWN: At = At { plane: None, grid: 0, modes: 0xf, incremental: None, inch: None };

    fn meet(self, o: At) -> At {
        At {
            plane: if self.plane == o.plane { self.plane } else { None },
            grid: self.grid & o.grid,
            modes: self.modes | o.modes,
            incremental: if self.incremental == o.incremental { self.incremental } else { None },
            inch: if self.inch == o.inch { self.inch } else { None },
        }
    }
}

/// The per-block states of one program ([`At`] at the start of each block).
#[derive(Default)]
pub struct Planes {
    at: Vec<(u32, At)>,
}

/// What a block's own words do to the plane: `Some(Some(p))` select `p`, `Some(None)` may
/// select any (a computed G code), `None` leave it.
fn own_plane(items: &[Item]) -> Option<Option<u32>> {
    let mut out = None;
    for it in items {
        if let ItemKind::Word(w) = &it.kind {
            if w.addr.is(b'G') {
                match &w.value {
                    WordValue::Expr(e) => match literal(e).map(|v| (v * 10.0).round() as u32) {
                        Some(g @ (170 | 180 | 190)) => out = Some(Some(g)),
                        Some(_) => {}
                        None => out = Some(None),
                    },
                    _ => out = Some(None),
                }
            }
        }
    }
    out
}

/// G codes (×10) after which the workpiece position may leave the grid: the frame and polar
/// modes' moves, reference returns, G53, the probe move.
const OFF_GRID_G: [u32; 9] = [680, 510, 511, 160, 280, 290, 300, 530, 310];

/// Whether a block may select a plane, or move the tool off the grid by itself (`grid`).
fn marks(items: &[Item], grid: bool) -> bool {
    let gs = g_codes(items);
    let computed = items.iter().any(|it| {
        matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'G') && !matches!(&w.value, WordValue::Expr(e) if literal(e).is_some()))
    });
    let plane = own_plane(items).is_some()
        || items.iter().any(|it| match &it.kind {
            ItemKind::IfBlock { .. } => true,
            ItemKind::IfThen { then, .. } => own_plane(std::slice::from_ref(then)).is_some(),
            _ => false,
        });
    if !grid {
        return plane;
    }
    computed || gs.iter().any(|g| OFF_GRID_G.contains(g)) || items.iter().any(offset_write) || plane
}

/// An assignment that may change a work offset (or any variable by number).
fn offset_write(it: &Item) -> bool {
    match &it.kind {
        ItemKind::Assign { target, .. } => matches!(target.kind, VarKind::Hash(5201..=5340) | VarKind::HashIndirect(_)),
        // A Haas `IF [c] #5221=..` writes it or not.
        ItemKind::IfThen { then, .. } => offset_write(then),
        _ => false,
    }
}

/// Whether `body` has a block that [`marks`].
fn selects(body: &[Stmt], grid: bool) -> bool {
    let mut any = false;
    crate::ir::visit::walk_stmts(body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            any |= marks(&b.items, grid);
        }
    });
    any
}

/// The numbers of the programs of the job that may select a plane (`grid`: or move the tool
/// off the grid), by their own blocks or through a call (of one of them, of a computed
/// target, or of a number not in the job).
pub fn setters(progs: &[ProgPlan], bodies: &[&[Stmt]], grid: bool) -> Vec<u32> {
    // A SAVE subprogram gives its caller the plane back (its moves may still leave the grid).
    let mut set: Vec<bool> = bodies.iter().zip(progs).map(|(b, p)| selects(b, grid) && (grid || !p.save)).collect();
    let known: Vec<u32> = progs.iter().filter_map(|p| p.number).collect();
    for _ in 0..=progs.len() {
        let list: Vec<u32> = progs.iter().zip(&set).filter(|(_, s)| **s).filter_map(|(p, _)| p.number).collect();
        let mut changed = false;
        for (i, body) in bodies.iter().enumerate() {
            if !set[i] && (grid || !progs[i].save) && calls_setter(body, &list, &known) {
                set[i] = true;
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    progs.iter().zip(&set).filter(|(_, s)| **s).filter_map(|(p, _)| p.number).collect()
}

/// Whether `c` may do what the programs `setters` may: a call of one, of a number not in
/// the job, or a computed one (`known`: the numbers of the job).
fn call_sets(c: &Call, setters: &[u32], known: &[u32]) -> bool {
    match (&c.kind, &c.target) {
        // A local section: its blocks are this program's, which the flow follows.
        (CallKind::M97, _) => false,
        _ if super::dispatch::stops(c) => false,
        (_, CallTarget::Number(n)) => setters.contains(n) || !known.contains(n),
        _ => true,
    }
}

fn calls_setter(body: &[Stmt], setters: &[u32], known: &[u32]) -> bool {
    let mut any = false;
    crate::ir::visit::walk_stmts(body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            any |= b.items.iter().any(|it| matches!(&it.kind, ItemKind::Call(c) if call_sets(c, setters, known)));
        }
    });
    any
}

/// The job's callers' view of calls: the programs that may select a plane, those that may
/// move the tool off the grid, and the numbers of the job.
#[derive(Clone, Copy)]
pub struct Calls<'a> {
    pub planes: &'a [u32],
    pub grid: &'a [u32],
    /// The programs whose call may leave a frame mode or G16 in force (`modal::frame_calls`).
    pub framers: &'a [u32],
    /// The programs that may select G90 or G91 (`ProgPlan::sets_distance`, `sets_g90`).
    pub distance: &'a [u32],
    /// The programs that may select G20 or G21 (`ProgPlan::sets_units`).
    pub units: &'a [u32],
    pub known: &'a [u32],
}

/// The lists a [`Calls`] borrows, from the job's plans.
pub struct Lists {
    planes: Vec<u32>,
    grid: Vec<u32>,
    framers: Vec<u32>,
    distance: Vec<u32>,
    units: Vec<u32>,
    known: Vec<u32>,
}

impl Lists {
    pub fn of(progs: &[ProgPlan]) -> Lists {
        let numbers = |f: &dyn Fn(&ProgPlan) -> bool| progs.iter().filter(|p| f(p)).filter_map(|p| p.number).collect();
        Lists {
            planes: numbers(&|p| p.sets_plane.0),
            grid: numbers(&|p| p.sets_plane.1),
            framers: numbers(&|p| p.leaves_frames || p.leaves_polar),
            distance: numbers(&|p| p.sets_distance || p.sets_g90),
            units: numbers(&|p| p.sets_units),
            known: numbers(&|_| true),
        }
    }

    pub fn calls(&self) -> Calls<'_> {
        Calls {
            planes: &self.planes,
            grid: &self.grid,
            framers: &self.framers,
            distance: &self.distance,
            units: &self.units,
            known: &self.known,
        }
    }
}

fn axis_bit(l: u8) -> u8 {
    match l {
        b'X' => 1,
        b'Y' => 2,
        b'Z' => 4,
        _ => 0,
    }
}

/// The state after a block entered in `s`.
fn apply(items: &[Item], mut s: At, calls: Calls) -> At {
    if let Some(p) = own_plane(items) {
        s.plane = p;
    }
    let gs = g_codes(items);
    let computed = items.iter().any(|it| {
        matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'G') && !matches!(&w.value, WordValue::Expr(e) if literal(e).is_some()))
    });
    if computed || items.iter().any(offset_write) {
        // A computed G code or an offset write: anything may have happened.
        return At { plane: if computed { None } else { s.plane }, ..At::UNKNOWN };
    }
    let mut has_call = false;
    for it in items {
        match &it.kind {
            ItemKind::Call(c) => {
                has_call = true;
                if call_sets(c, calls.planes, calls.known) {
                    s.plane = None;
                }
                if call_sets(c, calls.grid, calls.known) {
                    s.grid = 0;
                }
                if call_sets(c, calls.framers, calls.known) {
                    s.modes = 0xf;
                }
                if call_sets(c, calls.distance, calls.known) {
                    s.incremental = None;
                }
                if call_sets(c, calls.units, calls.known) {
                    s.inch = None;
                    s.grid = 0;
                }
            }
            ItemKind::IfThen { then, .. } if own_plane(std::slice::from_ref(then)).is_some() => s.plane = None,
            ItemKind::IfBlock { .. } => return At::UNKNOWN,
            _ => {}
        }
    }
    for g in &gs {
        match g {
            200 | 210 => {
                let inch = Some(*g == 200);
                if s.inch != inch {
                    s.grid = 0;
                }
                s.inch = inch;
            }
            900 => s.incremental = Some(false),
            910 => s.incremental = Some(true),
            680 => s.modes |= 1,
            690 => s.modes &= !1,
            510 => s.modes |= 2,
            500 => s.modes &= !2,
            511 => s.modes |= 4,
            // G50.1 may leave an axis mirrored (the axes it names): mirrored moves stay on
            // the grid (about a word's value) only where the mode is gone, so keep the bit.
            160 => s.modes |= 8,
            150 => s.modes &= !8,
            _ => {}
        }
    }
    let named: u8 = items
        .iter()
        .filter_map(|it| match &it.kind {
            ItemKind::Word(w) => match w.addr {
                Addr::Letter(l) => Some(axis_bit(l)),
                _ => None,
            },
            _ => None,
        })
        .fold(0, |a, b| a | b);
    if named == 0 || has_call {
        return s;
    }
    if gs.iter().any(|g| matches!(g, 280 | 290 | 300 | 530 | 310)) {
        s.grid &= !named;
        if gs.contains(&310) {
            s.grid = 0;
        }
    } else if gs.iter().any(|g| matches!(g, 100 | 520 | 680 | 690 | 510 | 500 | 511 | 501 | 650 | 660)) {
        // Data, not a move (G10, G52 by a word on the grid, the frame codes' centres).
    } else if gs.contains(&920) {
        // G92 gives the named axes the word's value.
        s.grid |= named;
    } else if s.modes != 0 {
        // A frame mode mixes the axes (a rotation) or scales them.
        s.grid = 0;
    } else if s.incremental == Some(false) {
        s.grid |= named;
    }
    // Under G91 (or not known) an increment keeps an axis on the grid if it was on it.
    s
}

impl Planes {
    /// The flow over `body` from `start`.
    pub fn new(body: &[Stmt], start: At, calls: Calls) -> Planes {
        let flat = flatten(body);
        let len = flat.nodes.len();
        // Under a G66 macro that may select a plane or leave the grid, it may do so after
        // every later move.
        let mut modal = false;
        crate::ir::visit::walk_stmts(body, &mut |s| {
            if let StmtKind::Block(b) = &s.kind {
                modal |= b.items.iter().any(|it| {
                    matches!(&it.kind, ItemKind::Call(c) if c.kind == CallKind::G66
                        && (call_sets(c, calls.planes, calls.known) || call_sets(c, calls.grid, calls.known)))
                });
            }
        });
        let start = if modal { At::UNKNOWN } else { start };
        let mut ins: Vec<Option<At>> = vec![None; len];
        if len > 0 {
            ins[0] = Some(start);
        }
        let mut work = vec![0usize];
        // Each entry only goes down (plane to unknown, grid bits off, mode bits on): it settles.
        while let Some(i) = work.pop() {
            let Some(s) = ins.get(i).copied().flatten() else { continue };
            let out = match &flat.nodes[i] {
                Node::Items(items) => {
                    let after = apply(items, s, calls);
                    // A block that may be skipped (`/`) passes its entry on as well.
                    if flat.blocks[i].is_some_and(|b| b.1) {
                        after.meet(s)
                    } else {
                        after
                    }
                }
                _ => s,
            };
            for j in succs(&flat, i) {
                if j >= len {
                    continue;
                }
                let m = ins[j].map_or(out, |old| old.meet(out));
                if ins[j] != Some(m) {
                    ins[j] = Some(m);
                    work.push(j);
                }
            }
        }
        let mut at: Vec<(u32, At)> = flat
            .blocks
            .iter()
            .zip(&ins)
            // Unreachable blocks: nothing known (none of them runs).
            .filter_map(|(b, s)| b.map(|(lo, _)| (lo, s.unwrap_or(At::UNKNOWN))))
            .collect();
        at.sort_by_key(|a| a.0);
        Planes { at }
    }

    /// The state at the start of the block that starts at `lo`.
    pub fn before(&self, lo: u32) -> At {
        let i = self.at.partition_point(|a| a.0 < lo);
        self.at.get(i).filter(|a| a.0 == lo).map_or(At::UNKNOWN, |a| a.1)
    }

    /// The plane a block's own modal words leave in force for what it does (a G68 in it
    /// rotates in it): its last plane word, else the plane before it.
    pub fn of_block(&self, lo: u32, items: &[Item]) -> Option<u32> {
        match own_plane(items) {
            Some(p) => p,
            None => self.before(lo).plane,
        }
    }
}

/// What each program of the job starts in: the main program in G17 and G90 with the tool on
/// the grid and no mode in force (power-on); a called one in the plane and with the axes on
/// the grid that every call of it (`M98`/`G65` blocks without a plane word of their own)
/// agrees on, no mode, G90/G91 not known; nothing known where a call is modal (G66) or
/// computed, or where no call reaches it. Fixed point over the call graph: a callee's start
/// only goes down from unseen.
pub fn start_planes(progs: &[ProgPlan], bodies: &[&[Stmt]], calls: Calls) -> Vec<At> {
    let n = progs.len();
    let main = |i: usize| progs[i].role == Role::Main;
    let power_on = At { plane: Some(170), grid: 7, modes: 0, incremental: Some(false), inch: Some(false) };
    let start = |seen: &[Option<At>], i: usize| {
        if main(i) {
            power_on
        } else {
            seen[i].map_or(At::UNKNOWN, |s| At { modes: 0, incremental: None, inch: None, ..s })
        }
    };
    let unknown = || (0..n).map(|i| if main(i) { power_on } else { At::UNKNOWN }).collect();
    let mut seen: Vec<Option<At>> = vec![None; n];
    for _ in 0..(2 * n + 2) {
        let mut next: Vec<Option<At>> = vec![None; n];
        let mut computed = false;
        for (i, body) in bodies.iter().enumerate() {
            let planes = Planes::new(body, start(&seen, i), calls);
            crate::ir::visit::walk_stmts(body, &mut |s| {
                let StmtKind::Block(b) = &s.kind else { return };
                for it in &b.items {
                    let ItemKind::Call(c) = &it.kind else { continue };
                    let j = match (&c.kind, &c.target) {
                        (CallKind::M97, _) => continue,
                        _ if super::dispatch::stops(c) => continue,
                        (_, CallTarget::Number(k)) => progs.iter().position(|p| p.number == Some(*k)),
                        _ => {
                            computed = true;
                            None
                        }
                    };
                    let Some(j) = j else { continue };
                    let here = if c.kind == CallKind::G66 || own_plane(&b.items).is_some() {
                        At::UNKNOWN
                    } else {
                        // The block's own words act before the call.
                        apply(
                            &b.items
                                .iter()
                                .filter(|it| !matches!(it.kind, ItemKind::Call(_)))
                                .cloned()
                                .collect::<Vec<_>>(),
                            planes.before(b.meta.span.lo),
                            calls,
                        )
                    };
                    next[j] = Some(next[j].map_or(here, |o| o.meet(here)));
                }
            });
        }
        if computed {
            return unknown();
        }
        if next == seen {
            return (0..n).map(|i| start(&seen, i)).collect();
        }
        seen = next;
    }
    unknown()
}

/// Whether `body` has a G68 that names fewer than two centre axes by constants: its
/// translation needs the plane at the block, so every plane word of the program (the
/// segmented stream reads such a program whole: its runs may hold them).
pub fn needs_plane(body: &[Stmt]) -> bool {
    let mut any = false;
    crate::ir::visit::walk_stmts(body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            if g_codes(&b.items).contains(&680) {
                // A word of a variable may be vacant (then left out: the tool position).
                let axes = b
                    .items
                    .iter()
                    .filter(|it| {
                        matches!(&it.kind, ItemKind::Word(w) if matches!(w.addr, Addr::Letter(b'X' | b'Y' | b'Z'))
                            && matches!(&w.value, WordValue::Expr(e) if literal(e).is_some()))
                    })
                    .count();
                any |= axes < 2;
            }
        }
    });
    any
}
