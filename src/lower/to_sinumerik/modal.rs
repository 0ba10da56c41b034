//! The modal G codes a FANUC → Sinumerik pass needs at a block: the active work offset
//! (G54..G59, re-selected after a `G10 L2` or `#5221+` write, since writing `$P_UIFR` does
//! not activate it), G90/G91 (a `G10 L2` under G91 adds) and G20/G21 (the unit a value
//! written without a decimal point is counted in). Found by a forward dataflow
//! over the FANUC program's control-flow graph (`vacancy::flatten`: GOTO search order,
//! loops, every edge), so a value holds only where every path to the block agrees on it; a
//! block that may be skipped (`/`) passes both ways. Computed on the program as read, before
//! the passes restructure it, and looked up by block position.

use super::modal_flow::{out_of, Local};
use super::vacancy::{flatten, Node};
use super::*;

/// The two modes at the exit of each block (text order), `None` where paths disagree.
#[derive(Default)]
pub struct ModalScan {
    /// (block span start, the modes after it).
    blocks: Vec<(u32, State)>,
    /// The axes (bit per `AXES` index) any `G52` of the program may leave shifted, and
    /// whether it is the main program (a called one starts with its caller's shift).
    pub g52: (u16, bool),
    /// Some block moves an axis where G91 may be in force (a Sinumerik incremental move
    /// after a frame change also travels the change, a FANUC one does not).
    pub incremental_motion: bool,
    /// The G68, G51 or G51.1 in force at the start of each block (text order; `rotation.rs`).
    rot_in: Vec<(u32, Option<u32>)>,
    /// [`State::g52`] before each block (block start, text order).
    shift_in: Vec<(u32, u16)>,
    /// Each G68, G51 and G51.1 block: its [`State::rot`] key, the block's start and its items.
    g68s: Vec<(u32, u32, Vec<Item>)>,
    /// Some block selects G18/G19.
    other_plane: bool,
    /// Some block has G52, G68, G51, G51.1 or G16 (a Sinumerik frame of their own).
    frames: bool,
    /// Each G28/G30 block: the start of its first item ([`State::inter`]) and its items.
    homes: Vec<(u32, Vec<Item>)>,
    /// The modal information values (`#4001`.., D, H, T) the program itself has set at
    /// each block, for the reads that become constants (`modal_reads`; set beside `new`).
    pub reads: super::modal_reads::Reads,
    /// Where G43/G44 may be in force, for the `#5043` reads (`position_length`).
    pub lengths: super::position_length::Lengths,
    /// The plane in force at each block (`planes`; set beside `new`).
    pub planes: super::planes::Planes,
    /// What the paths to the program's ends (M99, M30, M2, the last block) agree on;
    /// `None` where no end is reached (or the scan did not settle: [`State::UNKNOWN`]).
    exit: Option<State>,
}

/// What a call does to the modes [`State::apply`] follows beyond the unit.
#[derive(Clone, Copy)]
pub struct CallModes<'a> {
    /// The programs of the job that may select G20/G21.
    pub setters: &'a [u32],
    /// The programs of the job that may select G91 (it outlives the return), and those
    /// that may select G90 (after their call G90 is known only where it was before).
    pub distance_setters: &'a [u32],
    pub g90_setters: &'a [u32],
    /// The programs of the job whose call may leave a G68, G51 or G51.1 in force
    /// (or one not known; [`frame_calls`]).
    pub framers: &'a [u32],
    /// Those whose call may leave G16 in force.
    pub polar_framers: &'a [u32],
}

/// The modes after a block, each `None` where the paths to it disagree.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct State {
    /// The work offset G code ×10.
    pub offset: Option<u32>,
    pub incremental: Option<bool>,
    /// G20 (`true`) or G21.
    pub inch: Option<bool>,
    /// The motion G code ×10 (0, 10, 20, 30); `None` while a drilling cycle is in force.
    pub motion: Option<u32>,
    /// A drilling cycle in force: `Some(m)` with the group 01 code `m` it leaves in force
    /// when G80 cancels it (FANUC's cycles are group 09; the translation writes that code
    /// again after `MCALL`, `cycles.rs`); `None` when no cycle is in force.
    pub cycle: Option<Option<u32>>,
    /// The G68 rotation, G51 scaling or G51.1 mirror image in force (one at a time):
    /// `Some(0)` none, `Some(k)` the mode of [`frame_key`] `k` (`rotation.rs`),
    /// `Some(`[`ROT_ANY`]`)` none or one of this program's G68s (paths or calls of a
    /// section that disagree only on which rotation).
    pub rot: Option<u32>,
    /// G16 polar coordinates in force (a called program starts without: a call in G16
    /// mode is refused, `polar.rs`).
    pub polar: Option<bool>,
    /// Per axis X Y Z A B C: the G28/G30 block (the start of its first item) whose
    /// intermediate point, an absolute constant, is the one a G29 goes through; `None`
    /// where not known so (or a work offset, G52, G92, unit or call came since).
    pub inter: [Option<u32>; 6],
    /// The axes (bit per `frames` axis letter, X Y Z A B C U V W) whose G52 shift may not
    /// be 0: a G52 word sets or clears its axis, a call of another program may set any;
    /// paths join by union.
    pub g52: u16,
}

impl State {
    pub(super) const UNKNOWN: State = State {
        offset: None,
        incremental: None,
        inch: None,
        motion: None,
        cycle: Some(None),
        rot: None,
        polar: None,
        inter: [None; 6],
        g52: ALL_AXES,
    };

    pub(super) fn merge(self, o: State) -> State {
        State {
            offset: if self.offset == o.offset { self.offset } else { None },
            incremental: if self.incremental == o.incremental { self.incremental } else { None },
            inch: if self.inch == o.inch { self.inch } else { None },
            motion: if self.motion == o.motion { self.motion } else { None },
            cycle: if self.cycle == o.cycle { self.cycle } else { Some(None) },
            rot: merge_rot(self.rot, o.rot),
            polar: if self.polar == o.polar { self.polar } else { None },
            inter: std::array::from_fn(|i| if self.inter[i] == o.inter[i] { self.inter[i] } else { None }),
            g52: self.g52 | o.g52,
        }
    }

    /// After a call of a program of `calls.setters` (or of a computed target) the unit is
    /// not known, after one of `calls.framers` the frame modes. An `M97` runs blocks of this
    /// program, which the flow follows (`modal_flow`): the call itself changes none of them.
    pub(super) fn apply(mut self, items: &[Item], calls: CallModes) -> State {
        for it in items {
            if let ItemKind::Call(c) = &it.kind {
                // The not-found call of a dispatch stops the run: nothing follows it.
                if super::dispatch::stops(c) {
                    continue;
                }
                let sets = match (&c.kind, &c.target) {
                    (CallKind::M97, _) => false,
                    (_, CallTarget::Number(n)) => calls.setters.contains(n),
                    _ => true,
                };
                if sets {
                    self.inch = None;
                }
                let distance = match (&c.kind, &c.target) {
                    (CallKind::M97, _) => false,
                    (_, CallTarget::Number(n)) => calls.distance_setters.contains(n),
                    _ => true,
                };
                let g90 = matches!((&c.kind, &c.target), (CallKind::M98 | CallKind::G65 | CallKind::G66, CallTarget::Number(n))
                    if calls.g90_setters.contains(n));
                if distance || (g90 && self.incremental != Some(false)) {
                    self.incremental = None;
                }
                let leaves = |list: &[u32]| match (&c.kind, &c.target) {
                    (CallKind::M97, _) => false,
                    (_, CallTarget::Number(n)) => list.contains(n),
                    _ => true,
                };
                if leaves(calls.framers) {
                    self.rot = None;
                }
                if leaves(calls.polar_framers) {
                    self.polar = None;
                }
                if c.kind != CallKind::M97 {
                    self.g52 = ALL_AXES;
                }
                self.inter = [None; 6];
            }
            if let ItemKind::Assign { target, .. } = &it.kind {
                if matches!(target.kind, VarKind::Hash(5201..=5340) | VarKind::HashIndirect(_)) {
                    self.inter = [None; 6];
                }
            }
        }
        for g in g_codes(items) {
            match g {
                540 | 550 | 560 | 570 | 580 | 590 => self.offset = Some(g),
                // An extended offset (G54.1 Pn): a re-selection would need its P.
                541 => self.offset = None,
                900 => self.incremental = Some(false),
                910 => self.incremental = Some(true),
                200 => self.inch = Some(true),
                210 => self.inch = Some(false),
                0 | 10 | 20 | 30 => {
                    self.motion = Some(g);
                    self.cycle = None;
                }
                680 | 510 | 511 => self.rot = items.first().map(|it| frame_key(it.span.lo, g)),
                // A cancel of another mode than the one in force changes nothing.
                690 | 500 | 501 if self.rot.is_some_and(|k| k == 0 || k & 3 == frame_kind(mode_of_cancel(g))) => {
                    self.rot = Some(0)
                }
                160 => self.polar = Some(true),
                150 => self.polar = Some(false),
                // G80 gives back the group 01 code the cycle held (unknown where paths disagree).
                800 => {
                    if let Some(held) = self.cycle.take() {
                        self.motion = held;
                    }
                }
                730..=890 => {
                    if self.cycle.is_none() {
                        self.cycle = Some(self.motion);
                    }
                    self.motion = None;
                }
                _ => {}
            }
        }
        let gs = g_codes(items);
        // G52 becomes TRANS, which deletes any rotation of the programmable frame; on FANUC
        // G52 under G68, G51 or G51.1 is refused by the evaluator, so in every run that
        // proves a translation none is in force after it either (docs/semantics.md).
        if gs.contains(&520) && !gs.iter().any(|g| FRAME_CODES[..6].contains(g)) {
            self.rot = Some(0);
        }
        if gs.contains(&520) {
            for it in items {
                if let ItemKind::Word(Word { addr: Addr::Letter(l), value: WordValue::Expr(e), .. }) = &it.kind {
                    if let Some(i) = b"XYZABCUVW".iter().position(|c| c == l) {
                        if literal(e) == Some(0.0) {
                            self.g52 &= !(1 << i);
                        } else {
                            self.g52 |= 1 << i;
                        }
                    }
                }
            }
        }
        if gs.iter().any(|g| matches!(g, 540..=590 | 520 | 920 | 100 | 200 | 210)) {
            self.inter = [None; 6];
        }
        if gs.iter().any(|g| matches!(g, 280 | 300)) {
            for it in items {
                if let ItemKind::Word(Word { addr: Addr::Letter(l), value: WordValue::Expr(e), .. }) = &it.kind {
                    if let Some(i) = b"XYZABC".iter().position(|c| c == l) {
                        let known = self.incremental == Some(false) && literal(e).is_some();
                        self.inter[i] = known.then(|| items.first().map_or(0, |f| f.span.lo));
                    }
                }
            }
        }
        self
    }
}

/// [`State::rot`] where paths agree only that no G51 or G51.1 is in force: a G68 of the
/// program (which one not known) or none. A key of the rotation kind that no block has
/// ([`frame_key`] starts at 4).
pub const ROT_ANY: u32 = 1;

/// Paths joined: the same mode, or a rotation of either or none ([`ROT_ANY`]), else not known.
fn merge_rot(a: Option<u32>, b: Option<u32>) -> Option<u32> {
    let rotation_or_none = |k: Option<u32>| k.is_some_and(|k| k == 0 || k & 3 == 1);
    if a == b {
        a
    } else if rotation_or_none(a) && rotation_or_none(b) {
        Some(ROT_ANY)
    } else {
        None
    }
}

/// Every axis bit of [`State::g52`].
const ALL_AXES: u16 = 0x1ff;

/// The mode G code a cancel (G69, G50, G50.1 ×10) ends.
fn mode_of_cancel(g: u32) -> u32 {
    match g {
        690 => 680,
        500 => 510,
        _ => 511,
    }
}

/// The kind of a frame mode G code (G68, G51, G51.1 ×10): 1, 2, 3.
fn frame_kind(g: u32) -> u32 {
    match g {
        680 => 1,
        510 => 2,
        _ => 3,
    }
}

/// The [`State::rot`] key of the mode G code `g` in the block whose first word starts at
/// `lo`: the start and the kind, never 0.
fn frame_key(lo: u32, g: u32) -> u32 {
    ((lo + 1) << 2) | frame_kind(g)
}

impl ModalScan {
    /// `main`: the program starts in G54 and G90 (power-on) and in the unit `inch` (G21 for
    /// a main program, [`call_units`]; a streamed chunk's may differ); a called
    /// program starts in its caller's modes, which are not known here, except the unit,
    /// G90/G91 and the motion mode when every call in the job is made in the same one
    /// (`inch`, `incremental`, `motion`, [`call_units`]).
    /// `clear`: no G68, G51, G51.1 is in force at any call of it ([`frame_calls`]).
    /// `locals`: the `M97` calls translated as section repetitions, followed as calls
    /// (`modal_flow`).
    pub fn new(
        body: &[Stmt],
        main: bool,
        (inch, incremental, motion): (Option<bool>, Option<bool>, Option<u32>),
        clear: bool,
        calls: CallModes,
        locals: &[Local],
    ) -> ModalScan {
        let flat = flatten(body);
        let len = flat.nodes.len();
        let start = if main {
            State {
                offset: Some(540),
                incremental: Some(false),
                inch,
                motion: Some(0),
                cycle: None,
                rot: Some(0),
                polar: Some(false),
                inter: [None; 6],
                g52: 0,
            }
        } else {
            // A motion mode known at every call: no drilling cycle is in force there.
            let cycle = if motion.is_some() { None } else { State::UNKNOWN.cycle };
            State { inch, incremental, motion, cycle, polar: Some(false), rot: clear.then_some(0), ..State::UNKNOWN }
        };
        let out_of = |i: usize, s: State| out_of(&flat, i, s, calls);
        let flow = super::modal_flow::run(&flat, start, calls, locals);
        let settled = flow.settled;
        let ins = flow.ins;
        let mut blocks = Vec::new();
        let mut rot_in = Vec::new();
        let mut shift_in = Vec::new();
        let mut modal_call = false;
        crate::ir::visit::walk_stmts(body, &mut |s| {
            if let StmtKind::Block(b) = &s.kind {
                modal_call |= b.items.iter().any(|it| matches!(&it.kind, ItemKind::Call(c) if c.kind == CallKind::G66));
            }
        });
        let mut g68s = Vec::new();
        let mut other_plane = false;
        let mut frames = false;
        let mut homes = Vec::new();
        let mut incremental_motion = false;
        let mut exit: Option<State> = None;
        let mut prev = start;
        for (i, at) in ins.iter().enumerate() {
            // The program's ends on its own paths (a section's are its calls').
            if let (true, Some(s)) = (settled, flow.top[i]) {
                let ends = match &flat.nodes[i] {
                    Node::Items(items) => i + 1 == len || flow.end[i] || items.iter().any(ends_program),
                    Node::Head { exit, .. } => i + 1 == len || *exit >= len,
                    Node::End { .. } => i + 1 == len,
                };
                if ends {
                    let o = out_of(i, s);
                    exit = Some(exit.map_or(o, |e| e.merge(o)));
                }
            }
            let Some((lo, _)) = flat.blocks[i] else { continue };
            let first = match &flat.nodes[i] {
                Node::Items(items) => items.first().map_or(lo, |it| it.span.lo),
                _ => lo,
            };
            rot_in.push((first, if settled { at.map_or(Some(0), |s| s.rot) } else { None }));
            // A G66 macro runs after each later move, where it may shift any axis.
            let known = settled && !modal_call;
            shift_in.push((lo, if known { at.map_or(ALL_AXES, |s| s.g52) } else { ALL_AXES }));
            if let Node::Items(items) = &flat.nodes[i] {
                other_plane |= g_codes(items).iter().any(|g| matches!(g, 180 | 190));
                frames |= g_codes(items).iter().any(|g| matches!(g, 520 | 680 | 510 | 511 | 160));
                if g_codes(items).iter().any(|g| matches!(g, 280 | 300)) {
                    homes.push((first, items.to_vec()));
                }
                if let Some(&g) = g_codes(items).iter().find(|g| matches!(g, 680 | 510 | 511)) {
                    g68s.push((frame_key(first, g), lo, items.to_vec()));
                }
            }
            let st = match (settled, *at) {
                (true, Some(s)) => out_of(i, s),
                // Unreachable (after M30, say): nothing runs there, any value is as good;
                // the text before it, as the streamed translator follows it.
                (true, None) => out_of(i, prev),
                (false, _) => State::UNKNOWN,
            };
            prev = st;
            if let Node::Items(items) = &flat.nodes[i] {
                let gs = g_codes(items);
                let moves = items.iter().any(|it| {
                    matches!(&it.kind, ItemKind::Word(Word { addr: Addr::Letter(l), .. }) if b"XYZABCUVW".contains(l))
                });
                if moves && st.incremental != Some(false) && !gs.iter().any(|g| matches!(g, 100 | 280 | 300 | 520)) {
                    incremental_motion = true;
                }
            }
            blocks.push((lo, st));
        }
        ModalScan {
            blocks,
            g52: (super::frames::g52_axes(body), main),
            incremental_motion,
            rot_in,
            shift_in,
            g68s,
            other_plane,
            frames,
            homes,
            reads: Default::default(),
            lengths: Default::default(),
            planes: Default::default(),
            exit: if settled { exit } else { Some(State::UNKNOWN) },
        }
    }

    /// Whether every path to the program's ends leaves no G68, G51, G51.1 in force, and
    /// whether no G16.
    pub fn ends_clear(&self) -> (bool, bool) {
        (self.exit.is_none_or(|e| e.rot == Some(0)), self.exit.is_none_or(|e| e.polar == Some(false)))
    }

    /// G16 in force after the block at `lo`; `None` where the paths disagree.
    pub fn polar_at(&self, lo: u32) -> Option<bool> {
        self.at(lo).and_then(|b| b.1.polar)
    }

    /// Whether some block of the program selects G18 or G19 (a G16 plane not known here).
    pub fn other_plane(&self) -> bool {
        self.other_plane
    }

    /// The intermediate point of axis `i` (X Y Z A B C) a G29 at `lo` goes through: the
    /// word of the G28/G30 that set it ([`State::inter`]), with that block's start.
    pub fn intermediate_at(&self, lo: u32, i: usize) -> Option<(u32, &Expr)> {
        let key = self.at(lo).and_then(|b| b.1.inter[i])?;
        let (_, items) = self.homes.iter().find(|h| h.0 == key)?;
        items.iter().rev().find_map(|it| match &it.kind {
            ItemKind::Word(Word { addr: Addr::Letter(l), value: WordValue::Expr(e), .. }) if *l == b"XYZABC"[i] => {
                Some((key, e))
            }
            _ => None,
        })
    }

    /// Whether some block of the program has G52, G68, G51, G51.1 or G16.
    pub fn frames(&self) -> bool {
        self.frames
    }

    /// The G68, G51 or G51.1 in force before the block whose first word starts at `lo`
    /// ([`State::rot`]; `None` where the paths disagree or the caller's is in force).
    pub fn rot_before(&self, lo: u32) -> Option<u32> {
        self.rot_in.iter().find(|b| b.0 == lo).and_then(|b| b.1)
    }

    /// Whether the Sinumerik programmable frame under the G68, G51 or G51.1 in force before
    /// the block at `lo` is empty: a main program (its frame starts empty) whose G52 shift is
    /// 0 on every axis on every path (every G52 became a bare `TRANS`, or there was none).
    pub fn frame_base_empty(&self, lo: u32) -> bool {
        self.g52.1 && self.g52_before(lo) == 0
    }

    /// The axes whose G52 shift may not be 0 before the block at `lo` ([`State::g52`]; all
    /// where not known).
    pub fn g52_before(&self, lo: u32) -> u16 {
        let i = self.shift_in.partition_point(|b| b.0 <= lo);
        i.checked_sub(1).and_then(|i| self.shift_in.get(i)).map_or(ALL_AXES, |b| b.1)
    }

    /// The G68, G51 or G51.1 block of [`State::rot`] key `k`: its start and items.
    pub fn g68_block(&self, k: u32) -> Option<(u32, &[Item])> {
        self.g68s.iter().find(|g| g.0 == k).map(|g| (g.1, g.2.as_slice()))
    }

    /// The block at or before `lo` in text order.
    fn at(&self, lo: u32) -> Option<&(u32, State)> {
        let i = self.blocks.partition_point(|b| b.0 <= lo);
        i.checked_sub(1).and_then(|i| self.blocks.get(i))
    }

    /// The work offset G code (×10) in force after the block at `lo`; `None` where the paths
    /// to it disagree (or a called program has not selected one itself).
    pub fn offset_at(&self, lo: u32) -> Option<u32> {
        self.at(lo).and_then(|b| b.1.offset)
    }

    /// G91 in force after the block at `lo`; `None` where the paths disagree.
    pub fn incremental_at(&self, lo: u32) -> Option<bool> {
        self.at(lo).and_then(|b| b.1.incremental)
    }

    /// The motion G code (×10) in force after the block at `lo`; `None` where the paths
    /// disagree.
    pub fn motion_at(&self, lo: u32) -> Option<u32> {
        self.at(lo).and_then(|b| b.1.motion)
    }

    /// The motion G code (×10) a drilling cycle in force after the block at `lo` holds (G80
    /// gives it back); `None` where no cycle is in force or the paths disagree.
    pub fn held_at(&self, lo: u32) -> Option<u32> {
        self.at(lo).and_then(|b| b.1.cycle.flatten())
    }

    /// G20 in force after the block at `lo` (a value of the block is read in it); `None`
    /// where the paths disagree or a called program runs in its caller's unveiled unit.
    pub fn inch_at(&self, lo: u32) -> Option<bool> {
        self.at(lo).and_then(|b| b.1.inch)
    }
}

/// The unit (G20/G21) each program of a job starts in, where every call of it in the job is
/// made in the same one: the main program (index 0 when `main0`) starts metric; a called
/// program in the unit at its call sites (`M98`/`G65` blocks; for `G66`, every block of the
/// caller, since the macro runs after each move); `None` where they differ, where no call
/// of it is in the job, or where a call is computed (`P#1`). Fixed point over the call
/// graph: a callee's start can only go from unseen to a unit to unknown.
/// What a program starts in: the unit (G20 `true`), G91 (`true`) and the motion mode (G code
/// ×10), each `None` where not known.
pub type Starts = (Option<bool>, Option<bool>, Option<u32>);

pub fn call_units(progs: &[ProgPlan], bodies: &[&[Stmt]]) -> Vec<Starts> {
    #[derive(Clone, Copy, PartialEq)]
    enum Seen<T> {
        None,
        Unit(T),
        Mixed,
    }
    fn see<T: PartialEq + Copy>(slot: &mut Seen<T>, u: Option<T>) {
        *slot = match (*slot, u) {
            (Seen::None, Some(u)) => Seen::Unit(u),
            (Seen::Unit(a), Some(b)) if a == b => Seen::Unit(a),
            _ => Seen::Mixed,
        };
    }
    let n = progs.len();
    let setters: Vec<u32> = progs.iter().filter(|p| p.sets_units).filter_map(|p| p.number).collect();
    let distance: Vec<u32> = progs.iter().filter(|p| p.sets_distance).filter_map(|p| p.number).collect();
    let g90: Vec<u32> = progs.iter().filter(|p| p.sets_g90).filter_map(|p| p.number).collect();
    let by_number = |num: u32| progs.iter().position(|p| p.number == Some(num));
    // Per program: the unit and G90/G91 at its calls.
    let mut seen = vec![(Seen::None, Seen::None, Seen::None); n];
    let locals: Vec<Vec<Local>> = bodies.iter().map(|b| super::m97::locals(b)).collect();
    fn get<T>(s: Seen<T>) -> Option<T> {
        match s {
            Seen::Unit(u) => Some(u),
            _ => None,
        }
    }
    let start = |seen: &[(Seen<bool>, Seen<bool>, Seen<u32>)], i: usize| -> Starts {
        if progs[i].role == Role::Main {
            return (Some(false), Some(false), Some(0));
        }
        (get(seen[i].0), get(seen[i].1), get(seen[i].2))
    };
    let mut computed = false;
    let mut settled = false;
    for _ in 0..(2 * n + 2) {
        let mut next = vec![(Seen::None, Seen::None, Seen::None); n];
        for i in 0..n {
            let main = progs[i].role == Role::Main;
            let calls = CallModes {
                setters: &setters,
                distance_setters: &distance,
                g90_setters: &g90,
                framers: &[],
                polar_framers: &[],
            };
            let scan = ModalScan::new(bodies[i], main, start(&seen, i), false, calls, &locals[i]);
            let all: Vec<Starts> = scan.blocks.iter().map(|b| (b.1.inch, b.1.incremental, b.1.motion)).collect();
            crate::ir::visit::walk_stmts(bodies[i], &mut |s| {
                let StmtKind::Block(b) = &s.kind else { return };
                for it in &b.items {
                    let ItemKind::Call(c) = &it.kind else { continue };
                    let j = match (&c.kind, &c.target) {
                        // A local subprogram (its blocks are this program's).
                        (CallKind::M97, _) => continue,
                        (_, CallTarget::Number(num)) => by_number(*num),
                        _ => {
                            computed = true;
                            None
                        }
                    };
                    let Some(j) = j else { continue };
                    if c.kind == CallKind::G66 {
                        for &(u, d, m) in &all {
                            see(&mut next[j].0, u);
                            see(&mut next[j].1, d);
                            see(&mut next[j].2, m);
                        }
                    } else {
                        let lo = b.meta.span.lo;
                        see(&mut next[j].0, scan.inch_at(lo));
                        see(&mut next[j].1, scan.incremental_at(lo));
                        see(&mut next[j].2, scan.motion_at(lo));
                    }
                }
            });
        }
        if next == seen {
            settled = true;
            break;
        }
        seen = next;
    }
    let known = settled && !computed;
    (0..n).map(|i| if known || progs[i].role == Role::Main { start(&seen, i) } else { (None, None, None) }).collect()
}

/// The frame mode G codes (×10): G68/G69, G51/G50, G51.1/G50.1, G16/G15.
pub const FRAME_CODES: [u32; 8] = [680, 690, 510, 500, 511, 501, 160, 150];

/// Whether an item ends the program (M99, M30, M2), also as an `IF` block's action.
fn ends_program(it: &Item) -> bool {
    match &it.kind {
        ItemKind::Return { .. } | ItemKind::End { .. } => true,
        ItemKind::IfThen { then, .. } => ends_program(then),
        _ => false,
    }
}

/// For each program of a job: whether no G68, G51 or G51.1 is in force at any call of it
/// (its frame codes then know the mode in force: none at the start), and whether a call
/// of it may leave one (or G16) in force or not known ("framers": after their call the
/// caller's modes are not known). A program without frame G codes, in it or in what it
/// calls (`comp_flow::touch_effects`, the summary the tools use), leaves the caller's
/// modes as they were; one with them leaves none only where it starts clear and every
/// path to its ends cancels what it set. Calls of a G66 modal macro, computed calls and a
/// program no call in the job reaches count as not clear. Fixed point over the call graph
/// from the optimistic start (all clear, no framers): each pass can only turn programs
/// unclear or into framers, so it settles within a pass per program; where it does not,
/// nothing is clear.
pub fn frame_calls(progs: &[ProgPlan], programs: &[(FileId, &Program)]) -> Vec<(bool, bool, bool)> {
    use crate::lower::comp_flow::{touch_effects, CallRuns};
    let n = progs.len();
    let numbered: Vec<(u32, &Program)> =
        progs.iter().zip(programs).filter_map(|(pl, (_, p))| pl.number.map(|k| (k, *p))).collect();
    let runs = |c: &Call| match (&c.kind, &c.target) {
        (CallKind::M97, _) => CallRuns::Harmless,
        _ if super::dispatch::stops(c) => CallRuns::Harmless,
        (_, CallTarget::Number(k)) => CallRuns::Program(*k),
        _ => CallRuns::Unknown,
    };
    let touching = touch_effects(&numbered, &|items| g_codes(items).iter().any(|g| FRAME_CODES.contains(g)), &runs);
    let touches = |i: usize| progs[i].number.is_none_or(|k| touching.get(&k) != Some(&false));
    let main = |i: usize| progs[i].role == Role::Main;
    if !(0..n).any(touches) {
        return (0..n).map(|i| (main(i), false, false)).collect();
    }
    let setters: Vec<u32> = progs.iter().filter(|p| p.sets_units).filter_map(|p| p.number).collect();
    let distance: Vec<u32> = progs.iter().filter(|p| p.sets_distance).filter_map(|p| p.number).collect();
    let g90: Vec<u32> = progs.iter().filter(|p| p.sets_g90).filter_map(|p| p.number).collect();
    let by_number = |k: u32| progs.iter().position(|p| p.number == Some(k));
    let locals: Vec<Vec<Local>> = programs.iter().map(|(_, p)| super::m97::locals(&p.body)).collect();
    let mut clear: Vec<bool> = vec![true; n];
    let mut framers: (Vec<u32>, Vec<u32>) = (Vec::new(), Vec::new());
    for _ in 0..(2 * n + 2) {
        let mut called = vec![false; n];
        let mut next_clear = vec![true; n];
        let mut next_framers = (Vec::new(), Vec::new());
        for i in 0..n {
            let calls = CallModes {
                setters: &setters,
                distance_setters: &distance,
                g90_setters: &g90,
                framers: &framers.0,
                polar_framers: &framers.1,
            };
            let body = &programs[i].1.body;
            let start = (progs[i].start_inch, progs[i].start_incremental, progs[i].start_motion);
            let scan = ModalScan::new(body, main(i), start, clear[i] || main(i), calls, &locals[i]);
            crate::ir::visit::walk_stmts(&programs[i].1.body, &mut |s| {
                let StmtKind::Block(b) = &s.kind else { return };
                for it in &b.items {
                    let ItemKind::Call(c) = &it.kind else { continue };
                    let j = match (&c.kind, &c.target) {
                        (CallKind::M97, _) => continue,
                        (_, CallTarget::Number(k)) => by_number(*k),
                        // A computed call may run any program of the job.
                        _ => {
                            next_clear = vec![false; n];
                            None
                        }
                    };
                    let Some(j) = j else { continue };
                    called[j] = true;
                    let first = b.items.first().map_or(b.meta.span.lo, |f| f.span.lo);
                    let in_block = g_codes(&b.items).iter().any(|g| FRAME_CODES.contains(g));
                    if c.kind == CallKind::G66 || in_block || scan.rot_before(first) != Some(0) {
                        next_clear[j] = false;
                    }
                }
            });
            let (rot, polar) = scan.ends_clear();
            if touches(i) && !main(i) && !(clear[i] && rot) {
                next_framers.0.extend(progs[i].number);
            }
            // A called program starts without G16 (a call in G16 mode is refused).
            if touches(i) && !main(i) && !polar {
                next_framers.1.extend(progs[i].number);
            }
        }
        for (c, k) in next_clear.iter_mut().zip(&called) {
            *c &= *k;
        }
        next_framers.0.sort_unstable();
        next_framers.1.sort_unstable();
        if next_clear == clear && next_framers == framers {
            let has = |list: &[u32], i: usize| list.iter().any(|&k| Some(k) == progs[i].number);
            return (0..n).map(|i| (main(i) || clear[i], has(&framers.0, i), has(&framers.1, i))).collect();
        }
        clear = next_clear;
        framers = next_framers;
    }
    (0..n).map(|i| (main(i), touches(i) && !main(i), touches(i) && !main(i))).collect()
}

/// Whether `body` has a G20 or G21 word (a constant one; a computed G code is refused).
pub fn sets_units(body: &[Stmt]) -> bool {
    has_g(body, &[200, 210])
}

/// Whether `body` has a G91 word.
pub fn sets_distance(body: &[Stmt]) -> bool {
    has_g(body, &[910])
}

/// Whether `body` has one of the G codes `codes` (×10).
pub fn has_g(body: &[Stmt], codes: &[u32]) -> bool {
    let mut any = false;
    crate::ir::visit::walk_stmts(body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            any |= g_codes(&b.items).iter().any(|g| codes.contains(g));
        }
    });
    any
}

/// Marks the programs that call (directly or through others) a program that may select
/// G20/G21 (G90/G91): after their call, too, the caller's unit (distance mode) is not known.
pub fn close_setters(progs: &mut [ProgPlan], bodies: &[&[Stmt]]) {
    close(progs, bodies, |p| &mut p.sets_units);
    close(progs, bodies, |p| &mut p.sets_distance);
    close(progs, bodies, |p| &mut p.sets_g90);
}

fn close(progs: &mut [ProgPlan], bodies: &[&[Stmt]], flag: fn(&mut ProgPlan) -> &mut bool) {
    for _ in 0..progs.len() {
        let setters: Vec<u32> = progs.iter_mut().filter_map(|p| if *flag(p) { p.number } else { None }).collect();
        let mut changed = false;
        for (p, body) in progs.iter_mut().zip(bodies) {
            // A SAVE subprogram's return restores the modes whatever it calls.
            if *flag(p) || p.save {
                continue;
            }
            let mut calls = false;
            crate::ir::visit::walk_stmts(body, &mut |s| {
                if let StmtKind::Block(b) = &s.kind {
                    calls |= b.items.iter().any(|it| match &it.kind {
                        ItemKind::Call(c) => match (&c.kind, &c.target) {
                            (CallKind::M97, _) => false,
                            (_, CallTarget::Number(n)) => setters.contains(n),
                            _ => !setters.is_empty(),
                        },
                        _ => false,
                    });
                }
            });
            if calls {
                *flag(p) = true;
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
}
