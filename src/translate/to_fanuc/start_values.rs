//! Inputs of a proof that name a main-program DEF variable (`nctrans: set DEPTH=5`,
//! `--set DEPTH=5`). `run` gives such a DEF the input instead of its start value, but the
//! FANUC translation writes that start value as an assignment in the program body, which no
//! input of the FANUC side replaces: the two runs would start differently and the proof
//! would blame the translation. So the proof runs both with the start value, and says which
//! inputs it left out (warning NC661, and the verdict line through `check::Excluded`).

use super::SymbolMap;
use crate::diag::Diagnostic;
use crate::ir::{ItemKind, Program, Stmt, StmtKind};
use std::collections::BTreeSet;

/// The names (upper case) of the DEF variables of a main program (not global user data).
pub fn def_names(p: &Program) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    collect(&p.body, &mut out);
    out
}

fn collect(body: &[Stmt], out: &mut BTreeSet<String>) {
    for s in body {
        if let StmtKind::Block(b) = &s.kind {
            for it in &b.items {
                if let ItemKind::Def(d) = &it.kind {
                    if d.scope.is_none() {
                        out.extend(d.vars.iter().map(|v| v.name.clone()));
                    }
                }
            }
        }
    }
}

/// The words of a program's leading `nctrans: set` comment lines (as `map_set_lines` reads them).
pub(super) fn header_sets(body: &[Stmt]) -> Vec<String> {
    let mut out = Vec::new();
    for s in body {
        let StmtKind::Block(b) = &s.kind else { break };
        if !b.items.is_empty() || b.meta.number.is_some() || b.meta.label.is_some() {
            break;
        }
        for c in &b.meta.comments {
            if let Some(rest) = c.text.trim().strip_prefix("nctrans: set") {
                out.extend(rest.split_whitespace().map(str::to_string));
            }
        }
    }
    out
}

/// The variable an input `NAME=value` sets, upper case (`None` for `#n`, `$…` and bad ones).
fn input_name(set: &str) -> Option<String> {
    let lhs = set.split_once('=')?.0.trim();
    let plain = lhs.chars().next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_');
    plain.then(|| lhs.to_ascii_uppercase())
}

/// `sets` without those naming a main-program DEF variable of the translation, and those.
pub fn proof_sets(sets: &[String], map: &SymbolMap) -> (Vec<String>, Vec<String>) {
    sets.iter().cloned().partition(|s| input_name(s).is_none_or(|n| !map.def_inputs.contains(&n)))
}

/// The warning for the input `set` of the header line in `file`, pointing at the DEF.
pub fn warning(set: &str, p: &Program, file: crate::span::FileId) -> Option<Diagnostic> {
    let name = input_name(set)?;
    let span = def_span(&p.body, &name)?;
    Some(
        Diagnostic::warning(
            "NC661",
            format!(
                "the input {set} is not used by the proof: run gives the DEF {name} the input instead of its \
                 start value, but the FANUC program assigns the start value in its body, where no input replaces it"
            ),
        )
        .primary(file, span, "the start value both programs were run with")
        .hint("to prove that path, write the value as the DEF's start value, or make the variable an R parameter"),
    )
}

fn def_span(body: &[Stmt], name: &str) -> Option<crate::span::Span> {
    body.iter().find_map(|s| match &s.kind {
        StmtKind::Block(b) => b.items.iter().find_map(|it| match &it.kind {
            ItemKind::Def(d) if d.scope.is_none() => d.vars.iter().find(|v| v.name == name).map(|v| v.span),
            _ => None,
        }),
        _ => None,
    })
}
