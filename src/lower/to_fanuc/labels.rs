//! Labels and N numbers → FANUC N numbers.
//!
//! Each jump is resolved the way the Siemens control searches (GOTOF forward, GOTOB backward
//! from the jump's own block, GOTO/GOTOC forward then backward), so duplicate labels or
//! N numbers keep their meaning; the block found gets an N number no other block in the
//! program has: its own when that is unique and in 1..99999, else a fresh one from the next
//! thousand above the highest N in the program (deterministic). Other blocks keep their N.
//! A GOTOC whose target is missing is dropped (it continues with the next block). With
//! `--number-blocks k` every block is numbered k, 2k, … and jumps use those numbers.

use super::*;
use crate::span::Span;
use std::collections::{BTreeMap, BTreeSet, HashMap};

const MAX_N: u32 = 99999;

struct Pos {
    label: Option<String>,
    number: Option<u32>,
    /// The block, for diagnostics.
    span: Span,
}

struct Jump {
    target: Option<usize>,
}

/// Resolves every jump of `prog` to a unique N number. Returns the label → N map of the
/// labels that were jump targets (`"MARKE1"`, `"N10"`).
pub fn run(ctx: &mut Ctx, prog: &mut Program, number_blocks: Option<u32>) -> BTreeMap<String, u32> {
    let mut pos: Vec<Pos> = Vec::new();
    let mut gotos: Vec<(usize, Goto)> = Vec::new();
    collect(&prog.body, &mut pos, &mut gotos);
    let mut jumps = Vec::with_capacity(gotos.len());
    for (at, g) in &gotos {
        let found = |p: &Pos| match &g.target {
            Target::Label(l) => p.label.as_deref() == Some(l.name.as_str()),
            Target::Number(n) => p.number == Some(n.value),
            Target::Computed(_) => false,
        };
        let fwd = || (*at + 1..pos.len()).find(|&k| found(&pos[k]));
        let bwd = || (0..=*at).rev().find(|&k| found(&pos[k]));
        let target = match g.search {
            Search::Forward => fwd(),
            Search::Backward => bwd(),
            Search::ForwardThenBackward => fwd().or_else(bwd),
            Search::ForwardThenWrap => fwd().or_else(|| (0..=*at).find(|&k| found(&pos[k]))),
        };
        let (span, name) = match &g.target {
            Target::Label(l) => (l.span, l.name.clone()),
            Target::Number(n) => (n.span, format!("N{}", n.value)),
            Target::Computed(e) => (e.span, String::new()),
        };
        if let Target::Computed(_) = g.target {
            ctx.unsupported("NC305", span, "a jump to a computed label", "jump to a fixed label");
        } else if target.is_none() && !g.missing_continues {
            ctx.error("NC305", span, &format!("jump target {name} not found"), "add the label, or use GOTOC");
        }
        jumps.push(Jump { target });
    }
    let targets: BTreeSet<usize> = jumps.iter().filter_map(|j| j.target).collect();
    let mut numbers: Vec<Option<u32>> = vec![None; pos.len()];
    let mut numbered = false;
    if let Some(step) = number_blocks.filter(|s| *s > 0) {
        if (pos.len() as u64) * step as u64 <= MAX_N as u64 {
            for (k, n) in numbers.iter_mut().enumerate() {
                *n = Some((k as u32 + 1) * step);
            }
            numbered = true;
        } else {
            // Point at the first block whose number would not fit, not at the whole program.
            let first_over = (MAX_N / step) as usize;
            let span = pos.get(first_over).map_or(prog.span, |p| p.span);
            let msg = format!("{} blocks numbered by {step} pass N{MAX_N}", pos.len());
            ctx.error("NC306", span, &msg, "use a smaller --number-blocks step");
        }
    }
    if !numbered {
        let mut count: HashMap<u32, usize> = HashMap::new();
        for p in &pos {
            if let Some(n) = p.number {
                *count.entry(n).or_default() += 1;
            }
        }
        let max_used = count.keys().copied().filter(|n| *n <= MAX_N).max().unwrap_or(0);
        let mut next = (max_used / 1000 + 1) * 1000;
        if next as usize + targets.len() > MAX_N as usize {
            next = 1;
        }
        let mut out_of_numbers = false;
        for (k, p) in pos.iter().enumerate() {
            let valid = p.number.filter(|n| (1..=MAX_N).contains(n));
            if targets.contains(&k) {
                numbers[k] = match valid {
                    Some(n) if count.get(&n) == Some(&1) => Some(n),
                    _ => {
                        while count.contains_key(&next) {
                            next += 1;
                        }
                        if next > MAX_N {
                            // Once, at the first jump target that gets no number.
                            if !out_of_numbers {
                                let msg = format!("no free N numbers left: {} jump targets", targets.len());
                                ctx.error("NC306", p.span, &msg, "split the program into subprograms");
                                out_of_numbers = true;
                            }
                            None
                        } else {
                            next += 1;
                            Some(next - 1)
                        }
                    }
                };
            } else {
                numbers[k] = valid;
            }
        }
    }
    let mut names = BTreeMap::new();
    for j in &jumps {
        if let (Some(t), Some(n)) = (j.target, j.target.and_then(|t| numbers[t])) {
            match (&pos[t].label, pos[t].number) {
                (Some(l), _) if !l.starts_with(LABEL_PREFIX) => {
                    names.insert(l.clone(), n);
                }
                (_, Some(src)) => {
                    names.insert(format!("N{src}"), n);
                }
                _ => {}
            }
        }
    }
    let mut k = 0usize;
    let mut gi = 0usize;
    apply(&mut prog.body, &numbers, &jumps, &mut k, &mut gi);
    names
}

fn collect(body: &[Stmt], pos: &mut Vec<Pos>, gotos: &mut Vec<(usize, Goto)>) {
    let add = |m: &BlockMeta, pos: &mut Vec<Pos>| {
        pos.push(Pos {
            label: m.label.as_ref().map(|l| l.name.clone()),
            number: m.number.as_ref().map(|n| n.value),
            span: m.span,
        });
        pos.len() - 1
    };
    for s in body {
        match &s.kind {
            StmtKind::Block(b) => {
                let at = add(&b.meta, pos);
                for it in &b.items {
                    if let ItemKind::Goto(g) = &it.kind {
                        gotos.push((at, (**g).clone()));
                    }
                }
            }
            StmtKind::Do(d) => {
                add(&d.head, pos);
                collect(&d.body, pos, gotos);
                add(&d.end, pos);
            }
            // The structure pass leaves only blocks and DO loops.
            _ => {
                for m in crate::ir::visit::metas(&s.kind) {
                    add(m, pos);
                }
            }
        }
    }
}

/// A label the FANUC → Sinumerik translation made from an N number (`LBL_11`, `LBL_11_2`).
fn is_fanuc_label(name: &str) -> bool {
    name.strip_prefix("LBL_")
        .is_some_and(|r| !r.is_empty() && r.split('_').all(|p| !p.is_empty() && p.bytes().all(|c| c.is_ascii_digit())))
}

fn set_meta(m: &mut BlockMeta, n: Option<u32>) {
    if let Some(l) = m.label.take() {
        // `LBL_11` on N11 is what the FANUC → Sinumerik translation names N11: the N
        // number says it already (a round trip would add it again each time).
        if !l.name.starts_with(LABEL_PREFIX) && !is_fanuc_label(&l.name) {
            m.comments.insert(0, Comment { text: format!("{}:", l.name), span: l.span });
        }
    }
    let span = m.number.as_ref().map_or(m.span, |s| s.span);
    m.number = n.map(|value| SeqNo { value, span });
}

fn apply(body: &mut [Stmt], numbers: &[Option<u32>], jumps: &[Jump], k: &mut usize, gi: &mut usize) {
    for s in body.iter_mut() {
        match &mut s.kind {
            StmtKind::Block(b) => {
                set_meta(&mut b.meta, numbers.get(*k).copied().flatten());
                *k += 1;
                // In place: rebuilding the vector grew every block's items once more
                // (a large share of a long program's memory in the whole-file path).
                b.items.retain_mut(|it| {
                    let ItemKind::Goto(g) = &mut it.kind else { return true };
                    let j = jumps.get(*gi);
                    *gi += 1;
                    let n = j.and_then(|j| j.target).and_then(|t| numbers.get(t).copied().flatten());
                    match n {
                        Some(n) => {
                            let span = match &g.target {
                                Target::Label(l) => l.span,
                                Target::Number(s) => s.span,
                                Target::Computed(e) => e.span,
                            };
                            g.target = Target::Number(SeqNo { value: n, span });
                            g.search = Search::ForwardThenWrap;
                            g.missing_continues = false;
                            true
                        }
                        // GOTOC to a missing label: continue with the next block.
                        None => false,
                    }
                });
            }
            StmtKind::Do(d) => {
                set_meta(&mut d.head, numbers.get(*k).copied().flatten());
                *k += 1;
                apply(&mut d.body, numbers, jumps, k, gi);
                set_meta(&mut d.end, numbers.get(*k).copied().flatten());
                *k += 1;
            }
            other => {
                // Not produced by the structure pass; count its metas to stay aligned.
                *k += crate::ir::visit::metas(other).len();
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::build::*;
    use super::*;

    fn labelled(name: &str, items: Vec<Item>) -> Stmt {
        let meta = BlockMeta { label: Some(Label { name: name.into(), span: sp() }), ..BlockMeta::default() };
        meta_stmt(meta, items)
    }

    fn numbered(n: u32, items: Vec<Item>) -> Stmt {
        let meta = BlockMeta { number: Some(SeqNo { value: n, span: sp() }), ..BlockMeta::default() };
        meta_stmt(meta, items)
    }

    fn goto(search: Search, name: &str) -> Item {
        item(
            ItemKind::Goto(Box::new(Goto {
                search,
                target: Target::Label(Label { name: name.into(), span: sp() }),
                cond: None,
                missing_continues: false,
            })),
            sp(),
        )
    }

    fn numbers_of(body: &[Stmt]) -> Vec<Option<u32>> {
        body.iter()
            .map(|s| match &s.kind {
                StmtKind::Block(b) => b.meta.number.as_ref().map(|n| n.value),
                _ => None,
            })
            .collect()
    }

    fn target_of(s: &Stmt) -> u32 {
        match &s.kind {
            StmtKind::Block(b) => match &b.items[0].kind {
                ItemKind::Goto(g) => match &g.target {
                    Target::Number(n) => n.value,
                    _ => 0,
                },
                _ => 0,
            },
            _ => 0,
        }
    }

    #[test]
    fn duplicate_labels_follow_the_search_direction() {
        let body = vec![
            labelled("A", vec![]),
            block(vec![goto(Search::Backward, "A")]),
            block(vec![goto(Search::Forward, "A")]),
            labelled("A", vec![]),
        ];
        let mut prog = program(body);
        let mut ctx = Ctx::new(0, UnsupportedPolicy::Error);
        run(&mut ctx, &mut prog, None);
        assert_eq!(numbers_of(&prog.body), [Some(1000), None, None, Some(1001)]);
        assert_eq!(target_of(&prog.body[1]), 1000);
        assert_eq!(target_of(&prog.body[2]), 1001);
    }

    #[test]
    fn unique_n_numbers_are_kept_and_gotoc_to_nothing_continues() {
        let mut g = goto(Search::ForwardThenBackward, "NOWHERE");
        if let ItemKind::Goto(x) = &mut g.kind {
            x.missing_continues = true;
        }
        let body = vec![
            numbered(10, vec![]),
            block(vec![item(
                ItemKind::Goto(Box::new(Goto {
                    search: Search::Backward,
                    target: Target::Number(SeqNo { value: 10, span: sp() }),
                    cond: None,
                    missing_continues: false,
                })),
                sp(),
            )]),
            block(vec![g]),
        ];
        let mut prog = program(body);
        let mut ctx = Ctx::new(0, UnsupportedPolicy::Error);
        run(&mut ctx, &mut prog, None);
        assert!(ctx.diags.is_empty());
        assert_eq!(target_of(&prog.body[1]), 10);
        assert!(matches!(&prog.body[2].kind, StmtKind::Block(b) if b.items.is_empty()));
    }

    #[test]
    fn number_blocks_numbers_everything() {
        let body = vec![block(vec![]), labelled("A", vec![]), block(vec![goto(Search::Backward, "A")])];
        let mut prog = program(body);
        let mut ctx = Ctx::new(0, UnsupportedPolicy::Error);
        run(&mut ctx, &mut prog, Some(10));
        assert_eq!(numbers_of(&prog.body), [Some(10), Some(20), Some(30)]);
        assert_eq!(target_of(&prog.body[2]), 20);
    }
}
