//! What a Siemens subprogram changes of the modes its caller runs in, for the words pass
//! of the caller (which follows G90/G91 and the units in textual order, and so must know
//! what they are after a call) and of the subprogram itself (a `PROC … SAVE` subprogram
//! restores its caller's modal G functions on return; its FANUC translation saves and
//! restores the groups it sets, read from the `#4001..` modal variables).

use super::units::Units;
use crate::ir::{Call, CallTarget, ItemKind, Program, Stmt, StmtKind};
use crate::lower::comp_flow::{self, CallRuns};
use std::collections::BTreeMap;

/// The FANUC modal groups a subprogram can set that its translation restores (SAVE), as
/// bits, with the system variable that reads each and the Siemens G codes that set it.
pub const GROUPS: &[(u16, u32, &[u32])] = &[
    (1 << 0, 4001, &[0, 1, 2, 3]),
    (1 << 1, 4002, &[17, 18, 19]),
    (1 << 2, 4003, &[90, 91]),
    (1 << 3, 4005, &[94, 95]),
    (1 << 4, 4006, &[70, 71, 700, 710]),
    (1 << 5, 4007, &[40, 41, 42]),
    (1 << 6, 4014, &[54, 55, 56, 57]),
    (1 << 7, 4015, &[64]),
];
/// The bit of G90/G91.
pub const ABS: u16 = 1 << 2;
/// The axes X Y Z A B C U V W, as the bits of `Effect::incr_first` and `stale_exit`.
const ALL_AXES: u16 = (1 << 9) - 1;

/// What the units are after a call, given the caller's (one unit: calls are declined
/// where lengths and feeds differ).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum UnitEffect {
    /// Unchanged: no unit word runs (or SAVE restores them).
    #[default]
    None,
    /// Both set (by the last unit word: each of G70, G71, G700, G710 sets both).
    Both(Units),
    /// Depends on the path taken (unit words under a condition, jumps, early returns).
    Unknown,
}

/// A subprogram's effects, its callees' included.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Effect {
    /// The groups it (or a subprogram it calls) sets, SAVE or not.
    pub sets: u16,
    /// The units its caller continues in.
    pub units: UnitEffect,
    /// `PROC … SAVE`: the caller continues in the modes it called in.
    pub save: bool,
    /// It (or a subprogram it calls, or a call it makes of a program not among those
    /// translated) may change the tool or the compensation: a T, D, M6 or G40–G42 word
    /// (`comp_flow::program_tools`, the summary FANUC → Sinumerik reads too). A call of one
    /// leaves the caller's tool and edge unknown.
    pub tools: bool,
    /// It (or a subprogram it calls, or a call it makes of a program not among those
    /// translated) has a frame instruction (TRANS, ROT, …): the caller's programmable frame
    /// may differ after the call (`frame_chain`, which follows the frame in variables).
    pub frames: bool,
    /// It (or a subprogram it calls, or a call it makes of a program not among those
    /// translated) may write an R parameter (they are global): an assignment, an
    /// interrupt routine it sets up, EXECSTRING (`lower::known`, the values the drilling
    /// cycles need at translation).
    pub r_params: bool,
    /// It (or a subprogram it calls) sets up an interrupt routine, which stays armed after
    /// the return and may write R parameters at any later block of the caller.
    pub interrupts: bool,
    /// The axes it (or a program it calls) may move incrementally before programming them
    /// absolutely, called in G90 and in G91: where the caller's frame changed and they are
    /// not programmed again, the Siemens move travels the change (`frames_incr`).
    pub incr_first: [u16; 2],
    /// The axes its own frame instructions (or those of a program it calls) may leave with
    /// a changed shift, not programmed again, at its end (`frames_incr`).
    pub stale_exit: u16,
    /// G90 (`Some(true)`) or G91 in force at its end, called in G90 and in G91; `None`:
    /// not known (`frames_incr`, which follows the mode through its flow and calls).
    pub abs_exit: [Option<bool>; 2],
}

impl Effect {
    /// G90/G91 after the call made in G90 (`k` 0) or G91 (1).
    pub fn abs_after_call(&self, k: usize) -> Option<bool> {
        self.abs_after(Some(k == 0))
    }

    /// G90/G91 after the call, given the caller's.
    pub fn abs_after(&self, abs: Option<bool>) -> Option<bool> {
        if self.leaves() & ABS == 0 {
            return abs;
        }
        match abs {
            Some(true) => self.abs_exit[0],
            Some(false) => self.abs_exit[1],
            None => self.abs_exit[0].filter(|a| self.abs_exit[1] == Some(*a)),
        }
    }
}

impl Effect {
    /// The groups the caller finds changed after the call.
    pub fn leaves(&self) -> u16 {
        if self.save {
            0
        } else {
            self.sets
        }
    }
}

/// The effects of `progs` (by upper-case name), followed through calls among them to a
/// fixed point (each pass can only add groups or move a unit effect towards `Unknown`).
pub fn effects(progs: &[(String, &Program)]) -> BTreeMap<String, Effect> {
    let mut map: BTreeMap<String, Effect> = progs.iter().map(|(n, _)| (n.clone(), Effect::default())).collect();
    for _ in 0..=progs.len() {
        let mut changed = false;
        for (name, p) in progs {
            let any = crate::lower::to_fanuc::frames_incr::any_callee(map.values());
            let e = effect_of(p, &|n| {
                if n == crate::lower::to_fanuc::frames_incr::ANY_CALLEE {
                    any
                } else {
                    map.get(n).copied()
                }
            });
            if map.get(name) != Some(&e) {
                map.insert(name.clone(), e);
                changed = true;
            }
        }
        if !changed {
            return map;
        }
    }
    // Not settled (calls among many programs): every program may move any axis first and
    // leave any stale, which refuses rather than misses a frame change.
    for e in map.values_mut() {
        e.incr_first = [ALL_AXES; 2];
        e.stale_exit = ALL_AXES;
        e.abs_exit = [None; 2];
    }
    map
}

/// A constant, whole G code of an item (G codes are at most G1000 here).
fn g_code(it: &crate::ir::Item) -> Option<u32> {
    super::const_g(it).filter(|v| v.fract() == 0.0 && (0.0..=1000.0).contains(v)).map(|v| v as u32)
}

fn group_of(g: u32) -> u16 {
    GROUPS.iter().find(|(_, _, gs)| gs.contains(&g)).map_or(0, |(bit, _, _)| *bit)
}

/// `p`'s effect, with its callees' from `known` (by upper-case name).
pub fn effect_of(p: &Program, known: &dyn Fn(&str) -> Option<Effect>) -> Effect {
    let mut sets = 0u16;
    // Unit words and callees that change units; where they are; jumps and early returns.
    let mut unit_words = 0usize;
    let mut callee_units = false;
    let mut jumps = false;
    let mut returns = 0usize;
    let mut frames = false;
    let mut r_params = false;
    let mut interrupts = false;
    crate::ir::visit::walk_stmts(&p.body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            for it in &b.items {
                r_params |= writes_r(it);
                interrupts |= matches!(&it.kind, ItemKind::Instruction { name }
                    if crate::ir::interrupt::op_of(&name.to_ascii_uppercase()).is_some());
                if let Some(g) = g_code(it) {
                    sets |= group_of(g);
                    unit_words += usize::from(Units::default().g(f64::from(g)));
                }
                match &it.kind {
                    ItemKind::Frame { .. } => frames = true,
                    ItemKind::Call(c) => {
                        if let CallTarget::Name(n) = &c.target {
                            let name = n.to_ascii_uppercase();
                            if let Some(e) = known(&name) {
                                sets |= e.leaves();
                                callee_units |= !e.save && e.units != UnitEffect::None;
                                frames |= e.frames;
                                r_params |= e.r_params;
                                interrupts |= e.interrupts;
                            } else if crate::dialect::sinumerik::cycles::cycle_of(&name).is_none() {
                                frames = true;
                                r_params = true;
                            }
                        } else {
                            frames = true;
                            r_params = true;
                        }
                    }
                    ItemKind::Goto(_) | ItemKind::Case(_) | ItemKind::RepeatSection(_) => jumps = true,
                    ItemKind::Return { .. } | ItemKind::End { .. } => returns += 1,
                    _ => {}
                }
            }
        }
    });
    let units = if unit_words == 0 && !callee_units {
        UnitEffect::None
    } else if callee_units || jumps || !linear(&p.body, returns, unit_words) {
        UnitEffect::Unknown
    } else {
        fold_units(&p.body)
    };
    let tools = comp_flow::program_tools(p, false, &runs, &|n: &String| known(n).map(|e| e.tools));
    let s = crate::lower::to_fanuc::frames_incr::summary(&p.body, p.save, known);
    Effect {
        sets,
        units,
        save: p.save,
        tools,
        frames,
        r_params,
        interrupts,
        incr_first: s.incr_first,
        stale_exit: s.stale_exit,
        abs_exit: s.abs_exit,
    }
}

/// Whether an item may write an R parameter itself (its calls are the caller's to look up).
fn writes_r(it: &crate::ir::Item) -> bool {
    use crate::ir::VarKind;
    match &it.kind {
        ItemKind::Assign { target, .. } => {
            matches!(target.kind, VarKind::R(_) | VarKind::RIndirect(_) | VarKind::HashIndirect(_))
        }
        ItemKind::Print(p) => {
            p.status.as_deref().is_some_and(|v| matches!(v.kind, VarKind::R(_) | VarKind::RIndirect(_)))
        }
        ItemKind::Instruction { name } => {
            let up = name.to_ascii_uppercase();
            up.starts_with("EXEC") || crate::ir::interrupt::op_of(&up).is_some()
        }
        ItemKind::SyncAction(_) => true,
        ItemKind::IfThen { then, .. } => writes_r(then),
        ItemKind::IfBlock { items, .. } => items.iter().any(writes_r),
        _ => false,
    }
}

/// What a Siemens call runs: a drilling cycle touches neither tool nor compensation; any
/// other name is looked up among the programs translated.
fn runs(c: &Call) -> CallRuns<String> {
    match &c.target {
        CallTarget::Name(n) if crate::dialect::sinumerik::cycles::cycle_of(&n.to_ascii_uppercase()).is_some() => {
            CallRuns::Harmless
        }
        CallTarget::Name(n) => CallRuns::Program(n.to_ascii_uppercase()),
        _ => CallRuns::Unknown,
    }
}

/// Every unit word in a top-level block that cannot be skipped, and the one return (if any)
/// in the last statement: then every run of the subprogram passes every unit word in
/// textual order.
fn linear(body: &[Stmt], returns: usize, unit_words: usize) -> bool {
    let mut top_words = 0usize;
    for s in body {
        if let StmtKind::Block(b) = &s.kind {
            if b.meta.skip.is_some() {
                continue;
            }
            for g in b.items.iter().filter_map(g_code) {
                top_words += usize::from(Units::default().g(f64::from(g)));
            }
        }
    }
    let last_returns = body.last().is_some_and(|s| match &s.kind {
        StmtKind::Block(b) => {
            b.items.iter().any(|it| matches!(it.kind, ItemKind::Return { .. } | ItemKind::End { .. }))
        }
        _ => false,
    });
    top_words == unit_words && (returns == 0 || (returns == 1 && last_returns))
}

/// The units after the top-level blocks, from the caller's one unit.
fn fold_units(body: &[Stmt]) -> UnitEffect {
    let mut e = UnitEffect::None;
    for s in body {
        if let StmtKind::Block(b) = &s.kind {
            for g in b.items.iter().filter_map(g_code) {
                let mut u = Units::default();
                if u.g(f64::from(g)) {
                    e = UnitEffect::Both(u);
                }
            }
        }
    }
    e
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dialect::{Dialect, ParseOptions};

    fn effects_of(files: &[(&str, &str)]) -> BTreeMap<String, Effect> {
        let mut db = crate::span::SourceDb::new();
        let units: Vec<(String, crate::ir::Unit)> = files
            .iter()
            .map(|(name, text)| {
                let f = db.add(*name, *text);
                let parsed = crate::parse(&db, f, Dialect::Sinumerik, &ParseOptions::for_dialect(Dialect::Sinumerik));
                assert!(!crate::diag::has_errors(&parsed.diags), "{name}");
                (name.to_string(), parsed.unit)
            })
            .collect();
        let progs: Vec<(String, &Program)> = units.iter().map(|(n, u)| (n.clone(), &u.programs[0])).collect();
        effects(&progs)
    }

    #[test]
    fn what_a_subprogram_leaves_its_caller() {
        let e = effects_of(&[
            ("PLAIN", "PROC PLAIN\nG1 X1 F100\nM17\n"),
            ("LEN", "PROC LEN\nG70 X1\nG0 Y1\nM17\n"),
            ("BOTH", "PROC BOTH\nG70\nG700 X1\nG71\nM17\n"),
            ("COND", "PROC COND\nIF R1>1\nG70\nENDIF\nM17\n"),
            ("EARLY", "PROC EARLY\nIF R1>1 GOTOF DONE\nG70\nDONE: M17\n"),
            ("SKIP", "PROC SKIP\n/G70\nM17\n"),
            ("OUTER", "PROC OUTER\nLEN\nM17\n"),
            ("SAVED", "PROC SAVED SAVE\nG91 G70 G18\nLEN\nM17\n"),
            ("SHIFT", "PROC SHIFT\nG90\nTRANS X5\nG0 Y1\nM17\n"),
        ]);
        // Called in G91 its X word is an incremental move of an axis it has not programmed.
        let plain = Effect { sets: 1, incr_first: [0, 1], abs_exit: [Some(true), Some(false)], ..Effect::default() };
        assert_eq!(e["PLAIN"], plain);
        // Its TRANS changes every shift (the caller's are not known); Y is programmed again.
        assert_eq!(e["SHIFT"].incr_first, [0, 0]);
        assert_eq!(e["SHIFT"].stale_exit, ALL_AXES & !(1 << 1));
        assert_eq!(e["LEN"].units, UnitEffect::Both(Units { inch: true, inch_feed: false }));
        // G71 after G700 reads F metric again.
        assert_eq!(e["BOTH"].units, UnitEffect::Both(Units::default()));
        for unknown in ["COND", "EARLY", "SKIP", "OUTER"] {
            assert_eq!(e[unknown].units, UnitEffect::Unknown, "{unknown}");
        }
        // A SAVE subprogram sets G90/G91, units, plane, motion (its callee's too) and leaves none.
        let saved = e["SAVED"];
        assert!(saved.save && saved.leaves() == 0);
        assert_eq!(saved.sets & (ABS | 1 << 4 | 1 << 1 | 1), ABS | 1 << 4 | 1 << 1 | 1);
        assert_eq!(e["OUTER"].leaves() & 1, 1, "the callee's G0 reaches OUTER's caller");
    }
}
