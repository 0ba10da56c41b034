//! A call of a program whose file holds no program (NC593): the empty file keeps its own
//! NC145, and every caller is told at its call site what is wrong there (the called program's
//! file is empty), in a run when the call executes and in a translation before anything is
//! written, both dialects alike. Without it a caller's error was the callee's NC145, which
//! reads as if the caller itself did not parse.

use crate::diag::Diagnostic;
use crate::ir::{CallKind, CallTarget, Item, ItemKind, ProgName, StmtKind, Unit};
use crate::span::{FileId, SourceDb, Span};

pub const CODE: &str = "NC593";

/// How messages name a called program: `O0060` (FANUC, as the control lists it) or the name.
pub fn shown(key: &ProgName) -> String {
    match key {
        ProgName::Number(n) => format!("O{n:04}"),
        ProgName::Name(s) => s.clone(),
    }
}

/// The program-less file's NC145 among `diags`, if any: what a loaded callee file says when
/// it holds no program.
pub fn is_program_less(diags: &[Diagnostic]) -> bool {
    diags.iter().any(|d| d.code == "NC145")
}

/// The NC593 error at the call site `(file, span)` of `key`, which the program-less file
/// `callee` (in `db`) was to hold.
pub fn diagnostic(db: &SourceDb, (file, span): (FileId, Span), key: &ProgName, callee: FileId) -> Diagnostic {
    let name = shown(key);
    let path = db.get(callee).name.clone();
    let text = &db.get(callee).text;
    let first = text.find(['\n', '\r']).unwrap_or(text.len()) as u32;
    Diagnostic::error(CODE, format!("the called program {name} is in {path}, but that file holds no program"))
        .primary(file, span, format!("calls {name}"))
        .secondary(callee, Span::new(0, first), "no block with a word or statement in this file (NC145)")
        .note("the file is empty, or holds only blank lines, comments, `%` marks and a program header")
        .note(format!(
            "the call would alarm on the control: {name} is missing there, or has nothing to run and no return"
        ))
        .hint(format!(
            "check that the transfer of {path} finished (an empty file is often a failed copy), or put {name} in it"
        ))
}

/// The call sites in `unit` of `key` by a constant number or name (`M98 P60`, `G65 P60`,
/// `CALL "SUB"`, `SUB`), in source order. Haas `M97` names a block, not a program.
pub fn sites(unit: &Unit, key: &ProgName) -> Vec<Span> {
    let mut out = Vec::new();
    for p in &unit.programs {
        crate::ir::visit::walk_stmts(&p.body, &mut |s| {
            if let StmtKind::Block(b) = &s.kind {
                for it in &b.items {
                    item_sites(it, key, &mut out);
                }
            }
        });
    }
    out
}

/// The program numbers `unit` calls by a constant (not the ones it defines itself): where a
/// batch looks for an empty file named by the number.
pub fn numbers_called(unit: &Unit) -> std::collections::BTreeSet<u32> {
    let mut out = std::collections::BTreeSet::new();
    for p in &unit.programs {
        crate::ir::visit::walk_stmts(&p.body, &mut |s| {
            if let StmtKind::Block(b) = &s.kind {
                for it in &b.items {
                    item_numbers(it, &mut out);
                }
            }
        });
    }
    for p in &unit.programs {
        if let Some(ProgName::Number(n)) = &p.name {
            out.remove(n);
        }
    }
    out
}

fn item_numbers(it: &Item, out: &mut std::collections::BTreeSet<u32>) {
    match &it.kind {
        ItemKind::Call(c) if c.kind != CallKind::M97 => {
            if let CallTarget::Number(n) = &c.target {
                out.insert(*n);
            }
        }
        ItemKind::IfThen { then, .. } => item_numbers(then, out),
        ItemKind::IfBlock { items, .. } => items.iter().for_each(|i| item_numbers(i, out)),
        _ => {}
    }
}

fn item_sites(it: &Item, key: &ProgName, out: &mut Vec<Span>) {
    match &it.kind {
        ItemKind::Call(c) if c.kind != CallKind::M97 => {
            let hit = match (&c.target, key) {
                (CallTarget::Number(n), ProgName::Number(k)) => n == k,
                (CallTarget::Name(n), ProgName::Name(k)) => n.eq_ignore_ascii_case(k),
                _ => false,
            };
            if hit {
                out.push(it.span);
            }
        }
        ItemKind::IfThen { then, .. } => item_sites(then, key, out),
        ItemKind::IfBlock { items, .. } => items.iter().for_each(|i| item_sites(i, key, out)),
        _ => {}
    }
}

/// The NC593 errors for the program-less callee files `empties` (each with the program it
/// was loaded for), at every call site in `callers`; `diags` loses those files' NC145 where a
/// call site says it instead (a file no caller names keeps its NC145).
pub fn at_call_sites(db: &SourceDb, callers: &[&Unit], empties: &[(FileId, ProgName)], diags: &mut Vec<Diagnostic>) {
    let mut found = Vec::new();
    for (callee, key) in empties {
        let mut any = false;
        for u in callers.iter().filter(|u| u.file != *callee) {
            for span in sites(u, key) {
                found.push(diagnostic(db, (u.file, span), key, *callee));
                any = true;
            }
        }
        if any {
            diags.retain(|d| !(d.code == "NC145" && d.labels.first().is_some_and(|l| l.file == *callee)));
        }
    }
    // In source order, before the rest: the caller's first error is why it cannot be
    // translated.
    found.sort_by_key(|d| d.labels.first().map(|l| (l.file, l.span.lo)));
    found.append(diags);
    *diags = found;
}
