//! Synchronized actions (`ID=1 WHEN cond DO actions`, `WHENEVER`, `EVERY`, `FROM`, `IDS=`):
//! from the pest pairs to [`SyncAction`], so the rest of a file that uses them can be read.

use super::parse::Lower;
use super::Rule;
use crate::ir::*;
use pest::iterators::{Pair, Pairs};

impl Lower<'_, '_> {
    /// The `sync_line` children → one item holding the action.
    pub(super) fn sync_line(&mut self, inner: Pairs<'_, Rule>) -> Option<Item> {
        let pairs: Vec<Pair<'_, Rule>> = inner.collect();
        let span = self.span(pairs.first()?).to(self.span(pairs.last()?));
        let mut action = SyncAction { id: None, trigger: None, actions: Vec::new() };
        for p in pairs {
            match p.as_rule() {
                Rule::sync_head => {
                    let mut it = p.into_inner();
                    while let Some(q) = it.next() {
                        match q.as_rule() {
                            Rule::sync_id_eq => {
                                let mut idp = q.into_inner();
                                let kw = idp.next()?;
                                let scope = if kw.as_str().eq_ignore_ascii_case("IDS") {
                                    SyncScope::Static
                                } else {
                                    SyncScope::Modal
                                };
                                let e = idp.find(|x| x.as_rule() == Rule::expr)?;
                                action.id = Some((scope, self.expr(e)));
                            }
                            Rule::sync_kw => {
                                let trigger = match q.as_str().to_ascii_uppercase().as_str() {
                                    "WHENEVER" => SyncTrigger::Whenever,
                                    "EVERY" => SyncTrigger::Every,
                                    "FROM" => SyncTrigger::From,
                                    _ => SyncTrigger::When,
                                };
                                let cond = it.next().map(|e| self.expr(e))?;
                                action.trigger = Some((trigger, cond));
                            }
                            _ => {}
                        }
                    }
                }
                Rule::sync_actions => action.actions = self.items(p.into_inner()),
                _ => {}
            }
        }
        Some(Item { kind: ItemKind::SyncAction(Box::new(action)), span })
    }
}
