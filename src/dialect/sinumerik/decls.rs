//! `EXTERN` declarations and the explicit call forms `CALL "NAME"`, `CALL PROG_VAR`,
//! `PCALL NAME(args)`: from the pest pairs to IR.

use super::parse::Lower;
use super::Rule;
use crate::ir::*;
use pest::iterators::{Pair, Pairs};

impl Lower<'_, '_> {
    /// `EXTERN NAME(REAL, VAR INT[3])`.
    pub(super) fn extern_decl(&mut self, inner: Pairs<'_, Rule>) -> Option<Item> {
        let pairs: Vec<Pair<'_, Rule>> = inner.collect();
        let span = self.span(pairs.first()?).to(self.span(pairs.last()?));
        let mut decl = ExternDecl { name: String::new(), params: Vec::new() };
        for p in pairs {
            match p.as_rule() {
                Rule::user_name => decl.name = p.as_str().to_ascii_uppercase(),
                Rule::ext_param => {
                    let (mut by_ref, mut ty, mut dims) = (false, DataType::Real, Vec::new());
                    for q in p.into_inner() {
                        match q.as_rule() {
                            Rule::kw_var => by_ref = true,
                            Rule::dims => dims = self.dims(q).unwrap_or_default(),
                            _ => ty = self.data_type(q).unwrap_or(ty),
                        }
                    }
                    decl.params.push((by_ref, ty, dims));
                }
                _ => {}
            }
        }
        Some(Item { kind: ItemKind::Extern(Box::new(decl)), span })
    }

    /// `CALL "NAME"` / `CALL VAR` / `PCALL NAME(args)`: a call by name, the name written as a
    /// string or held in a STRING variable (found when the call runs).
    pub(super) fn call_stmt(&mut self, p: Pair<'_, Rule>) -> Option<ItemKind> {
        let target = p.into_inner().nth(1)?;
        match target.as_rule() {
            Rule::call => self.item(target),
            Rule::string => {
                let name = target.into_inner().next().map(|t| t.as_str().trim().to_ascii_uppercase())?;
                Some(ItemKind::Call(Box::new(Call {
                    kind: CallKind::Named,
                    target: CallTarget::Name(name),
                    args: Vec::new(),
                    repeat: None,
                })))
            }
            _ => {
                let span = self.span(&target);
                let v = self.var(target);
                Some(ItemKind::Call(Box::new(Call {
                    kind: CallKind::Named,
                    target: CallTarget::Computed(Expr::new(ExprKind::Var(Box::new(v)), span)),
                    args: Vec::new(),
                    repeat: None,
                })))
            }
        }
    }
}
