//! Segmented streaming translation, for every target: a program with a macro part is read
//! once into a skeleton (its top-level statements that are not straight blocks, as IR, with
//! each maximal run of straight blocks standing in it as ONE placeholder block), the
//! skeleton is translated whole by the target's whole-program translator, and its text is
//! written with each placeholder line replaced by its run, translated block by block by the
//! target's fast writer. Memory follows the macro part, not the motion part.
//!
//! Owns the one driver both targets run on (`driver`: the flow and the target's hooks,
//! `SegTarget`), written once with its three sinks (`sinks`): the skeleton scan, the one
//! scan that also spills the runs' translations and the writing scan;
//! what they share: the spill ([`spill`]), the output cursor that splices runs into the
//! skeleton's text ([`splice`]), the N-number sets of jump targets ([`nset`]), how callees
//! are given ([`LoadCallees`]) and what the verifier aligns in a streamed source
//! ([`SourceAlign`]). Each target's part is its hooks and public entry points: what a
//! skeleton keeps, which modes a run starts in, its fast writer of run blocks, how the
//! skeleton is translated and which diagnostics decline ([`fanuc`]: Sinumerik source;
//! [`sinumerik`]: FANUC source, with the straight stream's plan from
//! `stream::target::sinumerik`). May use what `stream` may use, and the straight stream's
//! targets (`stream::target`).

pub(crate) mod driver;
pub mod fanuc;
pub(crate) mod nset;
mod sinks;
pub mod sinumerik;
pub(crate) mod spill;
pub(crate) mod splice;

use crate::ir::{Expr, ExprKind, ItemKind, Number, Stmt, StmtKind, Unit, WordValue};
use crate::stream::Fallback;
use std::collections::BTreeMap;

/// The text of a placeholder comment, both targets (`k`: the run's index); no source
/// comment of the skeleton may hold it (checked on the translated skeleton).
pub(crate) const MARK: &str = "NCTRANS SEGMENT ";

/// The placeholder comment of run `k`.
pub(crate) fn mark(k: usize) -> String {
    format!("{MARK}{k}")
}

/// Gives the callee units of a skeleton (a unit holding the main program's macro part with
/// every call it has, as the whole program has them; for a FANUC source followed by the
/// other programs of the file, whole): the programs the whole path would load for the whole
/// file (file ids from 1 up, in its order), or `Err` to decline.
pub type LoadCallees<'a> = &'a mut dyn FnMut(&Unit) -> Result<Vec<Unit>, Fallback>;

/// `translate::to_fanuc::align_source` for a streamed source: what the whole path's verifier changes
/// in the source before running it, applied to each statement a run re-reads
/// (`stream::paged`). A string-valued word is in the macro part only (never in a plain line).
#[derive(Clone, Debug, Default)]
pub struct SourceAlign {
    /// Tool name → T number of the tools the translation maps (string-valued words).
    pub(crate) tools: BTreeMap<String, u32>,
}

impl SourceAlign {
    pub fn is_empty(&self) -> bool {
        self.tools.is_empty()
    }

    /// Aligns a re-read top-level statement.
    pub fn stmt(&self, s: &mut Stmt) {
        match &mut s.kind {
            StmtKind::Block(b) => {
                for it in &mut b.items {
                    if let ItemKind::Word(w) = &mut it.kind {
                        if let WordValue::Expr(Expr { kind: kind @ ExprKind::Str(_), .. }) = &mut w.value {
                            let n = match &*kind {
                                ExprKind::Str(name) => self.tools.get(name).copied(),
                                _ => None,
                            };
                            if let Some(n) = n {
                                *kind = ExprKind::Num(Number { value: f64::from(n), point: false });
                            }
                        }
                    }
                }
            }
            StmtKind::If(i) => {
                i.then_body.iter_mut().for_each(|s| self.stmt(s));
                if let Some(e) = &mut i.else_part {
                    e.body.iter_mut().for_each(|s| self.stmt(s));
                }
            }
            StmtKind::While(w) => w.body.iter_mut().for_each(|s| self.stmt(s)),
            StmtKind::Loop(l) => l.body.iter_mut().for_each(|s| self.stmt(s)),
            StmtKind::For(f) => f.body.iter_mut().for_each(|s| self.stmt(s)),
            StmtKind::Repeat(r) => r.body.iter_mut().for_each(|s| self.stmt(s)),
            StmtKind::Do(d) => d.body.iter_mut().for_each(|s| self.stmt(s)),
        }
    }
}
