//! Where a jump of a program may land: the blocks whose label or sequence number one of its
//! jumps names (`GOTOF`, `GOTOB`, `GOTO`, `GOTOC`, an `IF … GOTO…`, a `CASE` arm, a `REPEAT`
//! section's labels, `M99 Pn`), or every labelled or numbered block where a target is computed. The
//! passes that carry a state from block to block (frames, compensation, known values) treat
//! only those as places where another state may arrive: an `N70` that nothing jumps to is a
//! block number, not a join.

use crate::ir::*;
use std::collections::BTreeSet;

#[derive(Clone, Debug, Default)]
pub struct Landings {
    /// A computed target: any labelled or numbered block may be one.
    all: bool,
    labels: BTreeSet<String>,
    numbers: BTreeSet<u32>,
}

impl Landings {
    /// The landings of every jump in `body` (its structures' bodies included).
    pub fn of(body: &[Stmt]) -> Landings {
        let mut l = Landings::default();
        crate::ir::visit::walk_stmts(body, &mut |s| {
            if let StmtKind::Block(b) = &s.kind {
                for it in &b.items {
                    l.item(it);
                }
            }
        });
        l
    }

    fn item(&mut self, it: &Item) {
        match &it.kind {
            ItemKind::Goto(g) => self.goto(g),
            ItemKind::IfThen { then, .. } => self.item(then),
            ItemKind::IfBlock { items, .. } => items.iter().for_each(|i| self.item(i)),
            ItemKind::Case(c) => {
                c.arms.iter().for_each(|a| self.goto(&a.goto));
                if let Some(d) = &c.default {
                    self.goto(d);
                }
            }
            ItemKind::RepeatSection(r) => {
                self.labels.insert(r.start.name.clone());
                if let Some(e) = &r.end {
                    self.labels.insert(e.name.clone());
                }
            }
            // `M99 Pn` continues at Nn (of the caller, or of a main program itself).
            ItemKind::Return { to: Some(e) } => match crate::lower::literal(e) {
                Some(n) if n >= 0.0 && n.fract() == 0.0 && n <= f64::from(u32::MAX) => {
                    self.numbers.insert(n as u32);
                }
                _ => self.all = true,
            },
            _ => {}
        }
    }

    fn goto(&mut self, g: &Goto) {
        match &g.target {
            Target::Label(l) => {
                self.labels.insert(l.name.clone());
            }
            Target::Number(n) => {
                self.numbers.insert(n.value);
            }
            Target::Computed(_) => self.all = true,
        }
    }

    /// Whether the program jumps at all.
    pub fn any(&self) -> bool {
        self.all || !self.labels.is_empty() || !self.numbers.is_empty()
    }

    /// Whether a jump may land on the block with `meta`.
    pub fn at(&self, meta: &BlockMeta) -> bool {
        let label = meta.label.as_ref().is_some_and(|l| self.all || self.labels.contains(&l.name));
        let number = meta.number.as_ref().is_some_and(|n| self.all || self.numbers.contains(&n.value));
        label || number
    }
}
