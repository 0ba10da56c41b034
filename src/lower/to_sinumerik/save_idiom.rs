//! The save/restore idiom of FANUC macros: `#3=#4003` … `G#3 M99` (the caller's modes read
//! at the start, selected again before each return) becomes a Siemens `PROC … SAVE`, whose
//! return gives the caller its modal G functions back (docs/semantics.md, `PROC … SAVE`),
//! with the reads and the restoring words dropped. Only where it is exact: SAVE restores
//! every modal group the evaluator models (motion, plane, G90/G91, G94/G95, units), the
//! cutter radius side, the settable frame and the programmable frame, so each of those the
//! macro (or a program it calls) may change must be one it restores before every M99, and
//! the restore must be the last thing before each M99 on every path. Everything else keeps
//! the refusals of the passes (NC549, NC363), with a note saying why the idiom was not taken
//! (NC617: a mode SAVE would restore and the macro does not; NC618: the shape).

use super::*;
use crate::diag::Severity;
use crate::lower::comp_flow::{touch_effects, CallRuns};
use crate::lower::landings::Landings;

/// The modal information reads the idiom restores with `G#k`, with the FANUC G codes (×10)
/// of their group and the group's name.
const GROUPS: [(u32, &[u32], &str); 5] = [
    (4001, &[0, 10, 20, 30], "G00..G03 (group 01)"),
    (4002, &[170, 180, 190], "G17..G19 (group 02)"),
    (4003, &[900, 910], "G90/G91 (group 03)"),
    (4005, &[930, 940, 950], "G93..G95 (group 05)"),
    (4006, &[200, 210], "G20/G21 (group 06)"),
];

/// G codes (×10) whose effect a Siemens SAVE would undo at the return where FANUC keeps it
/// (or that the idiom cannot restore): cutter radius side, work offsets, the frame modes,
/// offset writes, drilling cycles (group 09), polar coordinates, the Haas mirror, and the
/// modes the trace does not see but whose Siemens forms are G functions SAVE would restore
/// (exact stop G61..G64 → G60/G64, look-ahead G05/G05.1/G08 and Haas G187 → FFWON and
/// CYCLE832, constant surface speed G96/G97): a difference there would not be caught.
fn unrestorable(g: u32) -> bool {
    matches!(g, 400 | 410 | 420 | 520 | 540..=591 | 680 | 690 | 510 | 500 | 511 | 501 | 920 | 160 | 150 | 100)
        || matches!(g, 730..=890 | 1000 | 1010 | 610 | 620 | 630 | 640 | 50 | 51 | 80 | 1870 | 960 | 970)
}

/// What [`recognise`] found for a job.
pub struct Found {
    /// Per program: the body without the idiom's reads and restoring words, where taken.
    pub programs: Vec<Option<Program>>,
    /// Notes on macros that were almost the idiom (NC617, NC618).
    pub diags: Vec<Diagnostic>,
}

/// A saved local: its number and the modal information variable read into it.
struct Saved {
    local: u32,
    var: u32,
}

/// Finds the idiom in every G65/G66 macro of the job (`programs`: the main file's programs
/// first, as `lower` gets them).
pub fn recognise(programs: &[(FileId, &Program)]) -> Found {
    let numbered: Vec<(u32, &Program)> = programs
        .iter()
        .filter_map(|(_, p)| match p.name {
            Some(ProgName::Number(n)) => Some((n, *p)),
            _ => None,
        })
        .collect();
    let runs = |c: &Call| match (&c.kind, &c.target) {
        (CallKind::M97, _) => CallRuns::Harmless,
        _ if super::dispatch::stops(c) => CallRuns::Harmless,
        (_, CallTarget::Number(k)) => CallRuns::Program(*k),
        _ => CallRuns::Unknown,
    };
    // What each program (with what it calls) may change, per group, and beyond them.
    let per_group: Vec<BTreeMap<u32, bool>> = GROUPS
        .iter()
        .map(|(_, codes, _)| touch_effects(&numbered, &|items| g_codes(items).iter().any(|g| codes.contains(g)), &runs))
        .collect();
    let offset_write = |items: &[Item]| {
        items.iter().any(|it| matches!(&it.kind, ItemKind::Assign { target, .. } if matches!(target.kind, VarKind::Hash(5201..=5340))))
    };
    let beyond =
        touch_effects(&numbered, &|items| g_codes(items).into_iter().any(unrestorable) || offset_write(items), &runs);
    let mut macro_called = BTreeSet::new();
    let mut m98_called = BTreeSet::new();
    for (_, p) in programs {
        crate::ir::visit::walk_stmts(&p.body, &mut |s| {
            if let StmtKind::Block(b) = &s.kind {
                each_item(&b.items, &mut |it| {
                    if let ItemKind::Call(c) = &it.kind {
                        if let CallTarget::Number(n) = c.target {
                            match c.kind {
                                CallKind::G65 | CallKind::G66 => {
                                    macro_called.insert(n);
                                }
                                CallKind::M98 => {
                                    m98_called.insert(n);
                                }
                                _ => {}
                            }
                        }
                    }
                });
            }
        });
    }
    let mut found = Found { programs: Vec::new(), diags: Vec::new() };
    for (i, (file, p)) in programs.iter().enumerate() {
        let number = match p.name {
            Some(ProgName::Number(n)) => Some(n),
            _ => None,
        };
        let called = number.is_some_and(|n| macro_called.contains(&n) || m98_called.contains(&n));
        let by_m98 = number.is_some_and(|n| m98_called.contains(&n));
        let by_macro = number.is_some_and(|n| macro_called.contains(&n));
        let standalone = i == 0 && !called && has(&p.body, &|k| matches!(k, ItemKind::Return { .. }));
        let effects = |k: &BTreeMap<u32, bool>| number.is_none_or(|n| k.get(&n) != Some(&false));
        let changes: Vec<bool> = per_group.iter().map(effects).collect();
        let view = Macro { body: &p.body, changes: &changes, beyond: effects(&beyond) };
        let out = match view.check(by_m98 && !by_macro, !(by_macro || standalone)) {
            Ok(saved) => Some(strip(p, &saved)),
            Err(Some((code, span, why))) => {
                found.diags.push(
                    Diagnostic::new(Severity::Note, code, format!("save/restore idiom not exact: {why}"))
                        .primary(*file, span, "here")
                        .note(
                            "a macro that reads the caller's modes (#4001..#4006) at its start and selects them \
                             again (G#k) before each M99 translates as PROC … SAVE where the Siemens return \
                             restores exactly what the macro restores",
                        )
                        .hint(
                            "restore every mode the macro changes right before each M99, or leave the modes the \
                             caller had to the caller",
                        ),
                );
                None
            }
            Err(None) => None,
        };
        found.programs.push(out);
    }
    found
}

/// The macro body with what the program (and its calls) may change: per [`GROUPS`] entry,
/// and beyond them (`unrestorable` codes, or a call that may do anything).
struct Macro<'a> {
    body: &'a [Stmt],
    changes: &'a [bool],
    beyond: bool,
}

type Miss = Option<(&'static str, Span, String)>;

impl Macro<'_> {
    /// The saved locals where the body is the idiom exactly; `Err(None)` where it is not the
    /// idiom at all, `Err(Some(..))` where it almost is (the note to give).
    fn check(&self, sub: bool, not_macro: bool) -> Result<Vec<Saved>, Miss> {
        let body = self.body;
        // Every read of the modal information into a local, and the restoring words G#k.
        let mut reads: Vec<(u32, u32, Span)> = Vec::new();
        let mut restores: Vec<(u32, Span)> = Vec::new();
        walk_items(body, &mut |it| match &it.kind {
            ItemKind::Assign { target, value } => {
                if let (VarKind::Hash(k @ 1..=33), Some(v)) = (&target.kind, bare_hash(value)) {
                    if GROUPS.iter().any(|g| g.0 == v) {
                        reads.push((*k, v, it.span));
                    }
                }
            }
            ItemKind::Word(w) if w.addr.is(b'G') => {
                if let WordValue::Expr(e) = &w.value {
                    if let Some(k @ 1..=33) = bare_hash(e) {
                        restores.push((k, it.span));
                    }
                }
            }
            _ => {}
        });
        let Some(&(_, _, first)) = reads.first() else { return Err(None) };
        if !restores.iter().any(|(k, _)| reads.iter().any(|r| r.0 == *k)) {
            return Err(None);
        }
        let miss = |code: &'static str, span: Span, why: String| Err(Some((code, span, why)));
        if sub {
            return miss("NC618", first, "the program is called by M98 and shares its caller's locals".into());
        }
        if not_macro {
            return Err(None);
        }
        // The reads stand in the leading blocks of assignments, before anything runs.
        let landings = Landings::of(body);
        let mut prologue: BTreeSet<(u32, u32)> = BTreeSet::new();
        for s in body {
            let StmtKind::Block(b) = &s.kind else { break };
            if b.meta.skip.is_some()
                || landings.at(&b.meta)
                || !b.items.iter().all(|it| matches!(it.kind, ItemKind::Assign { .. }))
            {
                break;
            }
            prologue.extend(b.items.iter().map(|it| (it.span.lo, it.span.hi)));
        }
        let mut saved: Vec<Saved> = Vec::new();
        for &(k, var, span) in &reads {
            if !prologue.contains(&(span.lo, span.hi)) {
                return miss(
                    "NC618",
                    span,
                    format!("#{k}=#{var} is not read in the leading blocks, before the macro changes anything"),
                );
            }
            if saved.iter().any(|s| s.local == k) {
                return miss("NC618", span, format!("#{k} is read twice"));
            }
            saved.push(Saved { local: k, var });
        }
        // The saved locals are used for nothing but the restore.
        let mut other: Option<(u32, Span)> = None;
        walk_items(body, &mut |it| {
            let restore_word = matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'G')
                && matches!(&w.value, WordValue::Expr(e) if bare_hash(e).is_some()));
            let read = matches!(&it.kind, ItemKind::Assign { target, value }
                if matches!(target.kind, VarKind::Hash(_)) && bare_hash(value).is_some_and(|v| (4001..=4006).contains(&v)));
            if let ItemKind::Assign { target, .. } = &it.kind {
                match target.kind {
                    VarKind::Hash(k) if !read && saved.iter().any(|s| s.local == k) => {
                        other = other.or(Some((k, it.span)))
                    }
                    VarKind::HashIndirect(_) => other = other.or(Some((0, it.span))),
                    _ => {}
                }
            }
            if restore_word || read {
                return;
            }
            for e in crate::ir::visit::item_exprs(it) {
                if let Some(k) = uses(e, &|k| saved.iter().any(|s| s.local == k)) {
                    other = other.or(Some((k, it.span)));
                }
            }
        });
        if let Some((k, span)) = other {
            let why = if k == 0 {
                "a computed #[…] write may change the saved locals".to_string()
            } else {
                format!("#{k} is used for more than the restore")
            };
            return miss("NC618", span, why);
        }
        // A restoring word of a local that holds no mode: not the idiom's.
        if let Some((k, span)) = restores.iter().find(|(k, _)| !saved.iter().any(|s| s.local == *k)) {
            return miss("NC618", *span, format!("G#{k} selects a G code the macro did not read from the caller"));
        }
        // Every end is an M99 whose blocks before it restore, with no way around them.
        let mut bad: Miss = None;
        let mut returns = Vec::new();
        let mut placed = BTreeSet::new();
        self.ends(body, &landings, &saved, &mut returns, &mut placed, &mut bad);
        if let Some(b) = bad {
            return Err(Some(b));
        }
        // A G#k elsewhere selects the caller's mode in the middle: dropping it would change that.
        if let Some((k, span)) = restores.iter().find(|(_, sp)| !placed.contains(&(sp.lo, sp.hi))) {
            return miss(
                "NC618",
                *span,
                format!("G#{k} selects the caller's mode before the blocks that end the macro"),
            );
        }
        match body.last().map(|s| &s.kind) {
            // An alarm stops the run: nothing after it needs the caller's modes.
            Some(StmtKind::Block(b))
                if b.items
                    .iter()
                    .any(|it| matches!(it.kind, ItemKind::Return { to: None } | ItemKind::Alarm { .. })) => {}
            _ => {
                let span = body.last().map_or(first, |s| s.span);
                return miss("NC618", span, "the macro does not end with M99".into());
            }
        }
        if self.beyond {
            return miss(
                "NC617",
                first,
                "the macro (or a program it calls) also changes the cutter radius side, a work offset, a frame \
                 mode, a drilling cycle, polar coordinates, the exact-stop or look-ahead mode or G96/G97, which \
                 PROC … SAVE would restore at its return"
                    .into(),
            );
        }
        for (gi, (var, _, name)) in GROUPS.iter().enumerate() {
            if !self.changes[gi] {
                continue;
            }
            let restored = |set: &BTreeSet<u32>| saved.iter().any(|s| s.var == *var && set.contains(&s.local));
            if let Some((span, _)) = returns.iter().find(|(_, set)| !restored(set)) {
                return miss(
                    "NC617",
                    *span,
                    format!("the macro also changes {name} and does not select the caller's again before this M99"),
                );
            }
        }
        Ok(saved)
    }

    /// Checks every return in `list` (and nested lists): an `M99` as a block's own item whose
    /// block and the blocks right before it hold only restoring words, none of them after
    /// the first a jump target; the set restored before each one in `returns`, the restoring
    /// words of those blocks in `placed`.
    fn ends(
        &self,
        list: &[Stmt],
        landings: &Landings,
        saved: &[Saved],
        returns: &mut Vec<(Span, BTreeSet<u32>)>,
        placed: &mut BTreeSet<(u32, u32)>,
        bad: &mut Miss,
    ) {
        let restore_local = |it: &Item| match &it.kind {
            ItemKind::Word(w) if w.addr.is(b'G') => match &w.value {
                WordValue::Expr(e) => bare_hash(e).filter(|k| saved.iter().any(|s| s.local == *k)),
                _ => None,
            },
            _ => None,
        };
        for (j, s) in list.iter().enumerate() {
            for child in crate::ir::visit::child_bodies(&s.kind) {
                self.ends(child, landings, saved, returns, placed, bad);
            }
            let StmtKind::Block(b) = &s.kind else { continue };
            let mut nested = false;
            each_item(&b.items, &mut |it| match &it.kind {
                ItemKind::Return { .. } | ItemKind::End { .. } => nested = true,
                _ => {}
            });
            let direct = b.items.iter().any(|it| matches!(it.kind, ItemKind::Return { .. } | ItemKind::End { .. }));
            if !nested {
                continue;
            }
            let why = |why: &str| Some(("NC618", s.span, why.to_string()));
            if bad.is_some() {
                return;
            }
            if !direct {
                *bad = why("a return inside an IF");
                return;
            }
            if b.items.iter().any(|it| matches!(it.kind, ItemKind::End { .. })) {
                *bad = why("the macro ends the program (M30/M02)");
                return;
            }
            if b.items.iter().any(|it| matches!(it.kind, ItemKind::Return { to: Some(_) })) {
                *bad = why("M99 P returns to another block of the caller");
                return;
            }
            if b.meta.skip.is_some()
                || !b.items.iter().all(|it| matches!(it.kind, ItemKind::Return { .. }) || restore_local(it).is_some())
            {
                *bad = why("the M99 block does more than restore the modes");
                return;
            }
            let mut set: BTreeSet<u32> = b.items.iter().filter_map(restore_local).collect();
            let mut start = j;
            while start > 0 {
                let StmtKind::Block(p) = &list[start - 1].kind else { break };
                if p.meta.skip.is_some() || !p.items.iter().all(|it| restore_local(it).is_some()) {
                    break;
                }
                start -= 1;
                set.extend(p.items.iter().filter_map(restore_local));
            }
            // A jump into the run of restoring blocks (after its first) would skip a restore.
            let skipped = list[start + 1..=j].iter().any(|s| match &s.kind {
                StmtKind::Block(b) => landings.at(&b.meta),
                _ => true,
            });
            if skipped {
                *bad = why("a jump reaches the M99 past the blocks that restore the modes");
                return;
            }
            for r in &list[start..=j] {
                if let StmtKind::Block(b) = &r.kind {
                    placed.extend(
                        b.items.iter().filter(|it| restore_local(it).is_some()).map(|it| (it.span.lo, it.span.hi)),
                    );
                }
            }
            returns.push((s.span, set));
        }
    }
}

/// The program with the reads of the saved locals and the restoring words dropped (their
/// blocks stay, with their numbers and comments).
fn strip(p: &Program, saved: &[Saved]) -> Program {
    fn drop_in(list: &mut [Stmt], saved: &[Saved]) {
        let is_saved = |k: u32| saved.iter().any(|s| s.local == k);
        for s in list {
            for child in crate::ir::visit::child_bodies_mut(&mut s.kind) {
                drop_in(child, saved);
            }
            if let StmtKind::Block(b) = &mut s.kind {
                b.items.retain(|it| match &it.kind {
                    ItemKind::Assign { target, value } => {
                        !(matches!(target.kind, VarKind::Hash(k) if is_saved(k))
                            && bare_hash(value).is_some_and(|v| GROUPS.iter().any(|g| g.0 == v)))
                    }
                    ItemKind::Word(w) if w.addr.is(b'G') => {
                        !matches!(&w.value, WordValue::Expr(e) if bare_hash(e).is_some_and(is_saved))
                    }
                    _ => true,
                });
            }
        }
    }
    let mut out = p.clone();
    drop_in(&mut out.body, saved);
    out
}

/// Whether `e` reads a local `pick` accepts (its number).
fn uses(e: &Expr, pick: &dyn Fn(u32) -> bool) -> Option<u32> {
    if let Some(k) = bare_hash(e).filter(|k| pick(*k)) {
        return Some(k);
    }
    if let ExprKind::Var(v) = &e.kind {
        if matches!(v.kind, VarKind::HashIndirect(_)) {
            // A computed read may reach a saved local.
            if let Some(k) = (1..=33).find(|k| pick(*k)) {
                return Some(k);
            }
        }
    }
    e.children().into_iter().find_map(|c| uses(c, pick))
}

/// Calls `f` on every item of `items`, the actions of IF blocks included.
fn each_item<'a>(items: &'a [Item], f: &mut dyn FnMut(&'a Item)) {
    for it in items {
        f(it);
        match &it.kind {
            ItemKind::IfThen { then, .. } => each_item(std::slice::from_ref(then), f),
            ItemKind::IfBlock { items, .. } => each_item(items, f),
            _ => {}
        }
    }
}

/// [`each_item`] over every block of `body`.
fn walk_items<'a>(body: &'a [Stmt], f: &mut dyn FnMut(&'a Item)) {
    crate::ir::visit::walk_stmts(body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            each_item(&b.items, f);
        }
    });
}

fn has(body: &[Stmt], pick: &dyn Fn(&ItemKind) -> bool) -> bool {
    let mut any = false;
    walk_items(body, &mut |it| any |= pick(&it.kind));
    any
}
