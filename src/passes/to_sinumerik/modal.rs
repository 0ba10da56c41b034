//! The modal G codes a FANUC → Sinumerik pass needs at a block: the active work offset
//! (G54..G59, re-selected after a `G10 L2` or `#5221+` write, since writing `$P_UIFR` does
//! not activate it) and G90/G91 (a `G10 L2` under G91 adds). Found by a forward dataflow
//! over the FANUC program's control-flow graph (`vacancy::flatten`: GOTO search order,
//! loops, every edge), so a value holds only where every path to the block agrees on it; a
//! block that may be skipped (`/`) passes both ways. Computed on the program as read, before
//! the passes restructure it, and looked up by block position.

use super::vacancy::{flatten, succs, Node};
use super::*;

/// The two modes at the exit of each block (text order), `None` where paths disagree.
#[derive(Default)]
pub struct ModalScan {
    /// (block span start, work offset G code ×10, incremental).
    blocks: Vec<(u32, Option<u32>, Option<bool>)>,
    /// The motion G code (×10: 0, 10, 20, 30) after each block, where every path agrees.
    motion: Vec<Option<u32>>,
    /// The axes (bit per `AXES` index) any `G52` of the program may leave shifted, and
    /// whether it is the main program (a called one starts with its caller's shift).
    pub g52: (u16, bool),
    /// Some block moves an axis where G91 may be in force (a Sinumerik incremental move
    /// after a frame change also travels the change, a FANUC one does not).
    pub incremental_motion: bool,
}

#[derive(Clone, Copy, PartialEq, Eq)]
struct State {
    offset: Option<u32>,
    incremental: Option<bool>,
    motion: Option<u32>,
}

impl State {
    fn merge(self, o: State) -> State {
        State {
            offset: if self.offset == o.offset { self.offset } else { None },
            incremental: if self.incremental == o.incremental { self.incremental } else { None },
            motion: if self.motion == o.motion { self.motion } else { None },
        }
    }

    fn apply(mut self, items: &[Item]) -> State {
        for g in g_codes(items) {
            match g {
                540 | 550 | 560 | 570 | 580 | 590 => self.offset = Some(g),
                // An extended offset (G54.1 Pn): a re-selection would need its P.
                541 => self.offset = None,
                900 => self.incremental = Some(false),
                910 => self.incremental = Some(true),
                0 | 10 | 20 | 30 => self.motion = Some(g),
                // Canned cycles and their cancel: the motion group is not followed here.
                730..=890 => self.motion = None,
                _ => {}
            }
        }
        self
    }
}

impl ModalScan {
    /// `main`: the program starts in G54 and G90 (power-on); a called program starts in its
    /// caller's modes, which are not known here.
    pub fn new(body: &[Stmt], main: bool) -> ModalScan {
        let flat = flatten(body);
        let len = flat.nodes.len();
        let start = if main {
            State { offset: Some(540), incremental: Some(false), motion: Some(0) }
        } else {
            State { offset: None, incremental: None, motion: None }
        };
        let out_of = |i: usize, s: State| match (&flat.nodes[i], flat.blocks[i]) {
            (Node::Items(items), Some((_, skip))) => {
                let after = s.apply(items);
                if skip {
                    after.merge(s)
                } else {
                    after
                }
            }
            _ => s,
        };
        let mut ins: Vec<Option<State>> = vec![None; len];
        if len > 0 {
            ins[0] = Some(start);
        }
        let edges: Vec<Vec<usize>> = (0..len).map(|i| succs(&flat, i)).collect();
        // Each value can only turn unknown (twice per node at most): this settles.
        let mut settled = false;
        for _ in 0..(2 * len + 2) {
            let mut changed = false;
            for i in 0..len {
                let Some(s) = ins[i] else { continue };
                let o = out_of(i, s);
                for &j in &edges[i] {
                    let new = ins[j].map_or(o, |old| old.merge(o));
                    if ins[j] != Some(new) {
                        ins[j] = Some(new);
                        changed = true;
                    }
                }
            }
            if !changed {
                settled = true;
                break;
            }
        }
        let mut motion = Vec::new();
        let mut incremental_motion = false;
        let blocks = (0..len)
            .filter_map(|i| {
                let (lo, _) = flat.blocks[i]?;
                let st = match (settled, ins[i]) {
                    (true, Some(s)) => out_of(i, s),
                    // Unreachable: nothing runs there, any value is as good; unsettled: none.
                    (true, None) => start,
                    (false, _) => State { offset: None, incremental: None, motion: None },
                };
                motion.push(st.motion);
                if let Node::Items(items) = &flat.nodes[i] {
                    let gs = g_codes(items);
                    let moves = items.iter().any(|it| {
                        matches!(&it.kind, ItemKind::Word(Word { addr: Addr::Letter(l), .. }) if b"XYZABCUVW".contains(l))
                    });
                    if moves && st.incremental != Some(false) && !gs.iter().any(|g| matches!(g, 100 | 280 | 300 | 520)) {
                        incremental_motion = true;
                    }
                }
                Some((lo, st.offset, st.incremental))
            })
            .collect();
        ModalScan { blocks, motion, g52: (super::frames::g52_axes(body), main), incremental_motion }
    }

    /// The block at or before `lo` in text order.
    fn at(&self, lo: u32) -> Option<&(u32, Option<u32>, Option<bool>)> {
        let i = self.blocks.partition_point(|b| b.0 <= lo);
        i.checked_sub(1).and_then(|i| self.blocks.get(i))
    }

    /// The work offset G code (×10) in force after the block at `lo`; `None` where the paths
    /// to it disagree (or a called program has not selected one itself).
    pub fn offset_at(&self, lo: u32) -> Option<u32> {
        self.at(lo).and_then(|b| b.1)
    }

    /// The motion G code (×10) in force after the block at `lo`; `None` where the paths
    /// disagree.
    pub fn motion_at(&self, lo: u32) -> Option<u32> {
        let i = self.blocks.partition_point(|b| b.0 <= lo);
        i.checked_sub(1).and_then(|i| self.motion.get(i).copied().flatten())
    }

    /// G91 in force after the block at `lo`; `None` where the paths disagree.
    pub fn incremental_at(&self, lo: u32) -> Option<bool> {
        self.at(lo).and_then(|b| b.2)
    }
}
