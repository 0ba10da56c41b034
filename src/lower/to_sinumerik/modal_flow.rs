//! The dataflow under the modal scan (`modal.rs`): the modes in force at each node of one
//! program's control-flow graph, following each Haas `M97` local subprogram (`m97.rs`) as a
//! call rather than as jumps. The modes at the call enter the section, the modes at its M99
//! come back to that call only, once per pass of its count `L`. Each (section, entry modes)
//! is walked once and remembered; a section's blocks get what every one of its entries
//! agrees on (they are translated once, so a mode a block reads must be the same at every
//! call), while the modes after each call stay those of its own entry. Nesting is bounded
//! ([`DEPTH`], [`WALKS`]); a section reached again while it runs (recursion), a walk past
//! the bounds or one that does not settle makes the whole scan unknown ([`Flow::settled`]).

use super::modal::{CallModes, State};
use super::vacancy::{succs, Flat, Node};
use crate::ir::{CallKind, ItemKind};
use std::collections::{BTreeSet, HashMap};

/// One `M97` the translation makes a section repetition of (`m97::Plan`), by span starts.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Local {
    /// The M97 item.
    pub call: u32,
    /// The section's first block and its M99 block (block span starts).
    pub start: u32,
    pub end: u32,
    /// The count `L`: `Some(m)` passes, `None` computed (rounded; no pass below one).
    pub count: Option<u64>,
}

/// Sections running inside each other at most (Haas nests subprograms a few levels).
const DEPTH: usize = 16;
/// Walks of sections per program at most.
const WALKS: usize = 1024;
/// Passes of a fixed count followed one by one; past them the passes are merged.
const PASSES: u64 = 8;

/// What [`run`] found.
pub(super) struct Flow {
    /// The modes before each node, merged over every walk that reaches it.
    pub ins: Vec<Option<State>>,
    /// Those of the program's own walk (its ends are the program's).
    pub top: Vec<Option<State>>,
    /// Section end nodes (the M99 block, whose M99 the translation drops): they end a walk.
    pub end: Vec<bool>,
    /// Every walk settled within the bounds; otherwise nothing above is meaningful.
    pub settled: bool,
}

/// The modes after node `i` entered with `s` (a skippable block both ways).
pub(super) fn out_of(flat: &Flat, i: usize, s: State, calls: CallModes) -> State {
    match (&flat.nodes[i], flat.blocks[i]) {
        (Node::Items(items), Some((_, skip))) => {
            let after = s.apply(items, calls);
            if skip {
                after.merge(s)
            } else {
                after
            }
        }
        _ => s,
    }
}

/// One walk: the reached nodes with their modes, what reaches its ends, the walks it used.
#[derive(Default)]
struct Walk {
    ins: Vec<(usize, State)>,
    exit: Option<State>,
    uses: Vec<usize>,
}

/// How an `M97` node runs: the planned section (start node, count), or not planned.
#[derive(Clone, Copy)]
enum Call {
    Section(usize, Option<u64>),
    Unplanned,
}

struct Engine<'f, 'a, 'c> {
    flat: &'f Flat<'a>,
    calls: CallModes<'c>,
    edges: Vec<Vec<usize>>,
    call: Vec<Option<Call>>,
    end: Vec<bool>,
    memo: HashMap<(usize, State), usize>,
    walks: Vec<Walk>,
    stack: Vec<usize>,
    failed: bool,
}

/// The modes at each node of `flat` for a program starting in `start`.
pub(super) fn run(flat: &Flat, start: State, calls: CallModes, locals: &[Local]) -> Flow {
    let len = flat.nodes.len();
    let node_of = |lo: u32| (0..len).find(|&i| flat.blocks[i].is_some_and(|b| b.0 == lo));
    let mut call = vec![None; len];
    let mut end = vec![false; len];
    let mut edges: Vec<Vec<usize>> = (0..len).map(|i| succs(flat, i)).collect();
    for &(i, _) in &flat.m97 {
        call[i] = Some(Call::Unplanned);
    }
    for l in locals {
        let at = (0..len).find(|&i| match &flat.nodes[i] {
            Node::Items(items) => items
                .iter()
                .any(|it| it.span.lo == l.call && matches!(&it.kind, ItemKind::Call(c) if c.kind == CallKind::M97)),
            _ => false,
        });
        let (Some(at), Some(st), Some(en)) = (at, node_of(l.start), node_of(l.end)) else { continue };
        call[at] = Some(Call::Section(st, l.count));
        end[en] = true;
        // The call goes on below once the section is back (the plan keeps M97 alone).
        edges[at] = (at + 1 < len).then_some(at + 1).into_iter().collect();
    }
    let mut e = Engine {
        flat,
        calls,
        edges,
        call,
        end,
        memo: HashMap::new(),
        walks: Vec::new(),
        stack: Vec::new(),
        failed: false,
    };
    let (top, settled) = if len == 0 { (Vec::new(), true) } else { e.walk(0, start) };
    let mut ins = top.clone();
    let first: Vec<usize> = e.top_uses(&top);
    let mut seen = BTreeSet::new();
    let mut todo = first;
    while let Some(k) = todo.pop() {
        if !seen.insert(k) {
            continue;
        }
        for &(i, s) in &e.walks[k].ins {
            ins[i] = Some(ins[i].map_or(s, |o| o.merge(s)));
        }
        todo.extend(e.walks[k].uses.iter().copied());
    }
    Flow { ins, top, end: e.end, settled: settled && !e.failed }
}

impl Engine<'_, '_, '_> {
    /// The walks the settled modes `ins` use at their calls.
    fn top_uses(&mut self, ins: &[Option<State>]) -> Vec<usize> {
        let mut uses = Vec::new();
        for (i, s) in ins.iter().enumerate() {
            if let (Some(c), Some(s)) = (self.call[i], *s) {
                self.after_call(i, c, s, &mut uses);
            }
        }
        uses
    }

    /// The fixed point from node `from` entered with `entry`: the modes before each node
    /// and whether it settled. Section end nodes end the walk.
    fn walk(&mut self, from: usize, entry: State) -> (Vec<Option<State>>, bool) {
        let len = self.flat.nodes.len();
        let mut ins: Vec<Option<State>> = vec![None; len];
        ins[from] = Some(entry);
        // Each value can only turn unknown: this settles well within the bound.
        for _ in 0..(2 * len + 16) {
            let mut changed = false;
            for i in 0..len {
                let Some(s) = ins[i] else { continue };
                // A section's end (possibly its start too) goes nowhere in the walk.
                if self.end[i] || self.failed {
                    continue;
                }
                let o = match self.call[i] {
                    Some(c) => self.after_call(i, c, s, &mut Vec::new()),
                    None => Some(out_of(self.flat, i, s, self.calls)),
                };
                let Some(o) = o else { continue };
                for k in 0..self.edges[i].len() {
                    let j = self.edges[i][k];
                    let new = ins[j].map_or(o, |old| old.merge(o));
                    if ins[j] != Some(new) {
                        ins[j] = Some(new);
                        changed = true;
                    }
                }
            }
            if !changed {
                return (ins, !self.failed);
            }
        }
        (ins, false)
    }

    /// The modes after the `M97` node `i` entered with `s`; `None` where the section never
    /// comes back. `uses` gets the walks it takes.
    fn after_call(&mut self, i: usize, c: Call, s: State, uses: &mut Vec<usize>) -> Option<State> {
        let Node::Items(items) = &self.flat.nodes[i] else { return Some(s) };
        let skip = self.flat.blocks[i].is_some_and(|b| b.1);
        let a = s.apply(items, self.calls);
        let after = match c {
            // Not translated (refused): its modes after are not known.
            Call::Unplanned => Some(State::UNKNOWN),
            Call::Section(st, Some(m)) => {
                let mut cur = Some(a);
                let mut done = 0;
                while done < m.min(PASSES) {
                    let Some(x) = cur else { break };
                    let next = self.pass(st, x, uses);
                    done += 1;
                    if next == Some(x) {
                        // The same modes every further pass.
                        done = m;
                    }
                    cur = next;
                }
                if done < m {
                    cur = cur.and_then(|x| self.widen(st, x, uses));
                }
                cur
            }
            // A computed count: any number of passes, none included.
            Call::Section(st, None) => self.widen(st, a, uses),
        };
        if skip {
            Some(after.map_or(s, |x| x.merge(s)))
        } else {
            after
        }
    }

    /// What every number of further passes from `w` agree on (monotone: it settles within a
    /// pass per field).
    fn widen(&mut self, st: usize, mut w: State, uses: &mut Vec<usize>) -> Option<State> {
        for _ in 0..32 {
            let n = match self.pass(st, w, uses) {
                Some(x) => w.merge(x),
                None => w,
            };
            if n == w {
                return Some(w);
            }
            w = n;
        }
        self.failed = true;
        None
    }

    /// One pass of the section from node `st` entered with `entry`: the modes at its end.
    fn pass(&mut self, st: usize, entry: State, uses: &mut Vec<usize>) -> Option<State> {
        if let Some(&k) = self.memo.get(&(st, entry)) {
            uses.push(k);
            return self.walks[k].exit;
        }
        if self.stack.contains(&st) || self.stack.len() >= DEPTH || self.walks.len() >= WALKS || self.failed {
            self.failed = true;
            return None;
        }
        self.stack.push(st);
        let (ins, settled) = self.walk(st, entry);
        let mut inner = Vec::new();
        if settled {
            inner = self.top_uses(&ins);
        }
        self.stack.pop();
        if !settled {
            self.failed = true;
        }
        let exit = (0..ins.len())
            .filter(|&i| self.end[i])
            .filter_map(|i| ins[i].map(|s| out_of(self.flat, i, s, self.calls)))
            .reduce(State::merge);
        let reached = ins.iter().enumerate().filter_map(|(i, s)| s.map(|s| (i, s))).collect();
        let k = self.walks.len();
        self.walks.push(Walk { ins: reached, exit, uses: inner });
        self.memo.insert((st, entry), k);
        uses.push(k);
        exit
    }
}

#[cfg(test)]
mod tests {
    use super::super::vacancy::flatten;
    use super::*;
    use crate::dialect::{Dialect, ParseOptions};
    use crate::ir::{Program, Stmt, StmtKind};
    use crate::span::SourceDb;

    fn program(text: &str) -> Program {
        let mut db = SourceDb::new();
        let id = db.add("t.nc", text);
        let mut opts = ParseOptions::for_dialect(Dialect::Fanuc);
        opts.semantics.haas = true;
        let p = crate::parse(&db, id, Dialect::Fanuc, &opts);
        assert!(!crate::diag::has_errors(&p.diags));
        p.unit.programs.into_iter().next().expect("a program")
    }

    fn block_lo(body: &[Stmt], n: u32) -> u32 {
        body.iter()
            .find_map(|s| match &s.kind {
                StmtKind::Block(b) if b.meta.number.as_ref().is_some_and(|m| m.value == n) => Some(b.meta.span.lo),
                _ => None,
            })
            .expect("the block")
    }

    fn call_lo(body: &[Stmt], n: u32) -> u32 {
        body.iter()
            .find_map(|s| match &s.kind {
                StmtKind::Block(b) if b.meta.number.as_ref().is_some_and(|m| m.value == n) => {
                    b.items.iter().find(|it| matches!(it.kind, ItemKind::Call(_))).map(|it| it.span.lo)
                }
                _ => None,
            })
            .expect("the call")
    }

    const START: State = State {
        offset: Some(540),
        incremental: Some(false),
        inch: Some(false),
        motion: Some(0),
        cycle: None,
        rot: Some(0),
        polar: Some(false),
        inter: [None; 6],
        g52: 0,
    };

    /// The G90/G91 mode before block `at` after the section N100 (ending at N199) is
    /// called from N1 with the count `count`.
    fn incremental_after(count: Option<u64>, text: &str) -> (Option<bool>, bool) {
        let p = program(text);
        let flat = flatten(&p.body);
        let locals =
            [Local { call: call_lo(&p.body, 1), start: block_lo(&p.body, 100), end: block_lo(&p.body, 199), count }];
        let calls =
            CallModes { setters: &[], distance_setters: &[], g90_setters: &[], framers: &[], polar_framers: &[] };
        let flow = run(&flat, START, calls, &locals);
        let at = (0..flat.nodes.len()).find(|&i| flat.numbers[i] == Some(2)).expect("N2");
        (flow.ins[at].and_then(|s| s.incremental), flow.settled)
    }

    const G91_SECTION: &str = "O1\nG90\nN1 M97 P100\nN2 G00 X0\nM30\nN100 G91 G00 X1.\nN199 M99\n";

    #[test]
    fn the_modes_of_the_section_come_back_to_its_call() {
        assert_eq!(incremental_after(Some(1), G91_SECTION), (Some(true), true));
        assert_eq!(incremental_after(Some(9999), G91_SECTION), (Some(true), true));
        // A computed count may run no pass: G90 or G91.
        assert_eq!(incremental_after(None, G91_SECTION), (None, true));
    }

    #[test]
    fn a_section_that_runs_itself_again_is_not_followed() {
        // The inner M97 (N150) named as a call of its own section: recursion, not settled.
        let text = "O1\nG90\nN1 M97 P100\nN2 G00 X0\nM30\nN100 G91 G00 X1.\nN150 M97 P100\nN199 M99\n";
        let p = program(text);
        let flat = flatten(&p.body);
        let (start, end) = (block_lo(&p.body, 100), block_lo(&p.body, 199));
        let locals = [
            Local { call: call_lo(&p.body, 1), start, end, count: Some(1) },
            Local { call: call_lo(&p.body, 150), start, end, count: Some(1) },
        ];
        let calls =
            CallModes { setters: &[], distance_setters: &[], g90_setters: &[], framers: &[], polar_framers: &[] };
        assert!(!run(&flat, START, calls, &locals).settled);
        // Without the inner call followed (refused by m97.rs), it settles.
        assert!(run(&flat, START, calls, &locals[..1]).settled);
    }
}
