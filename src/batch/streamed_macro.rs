//! Large programs with a macro part in a batch (`streamed.rs` does the rest): what the
//! library scan learns from a streamed file's statements, and the chain of streamed
//! translators a file goes through before it is left to the whole-file job — the
//! straight-line stream, then the segmented one (the macro part translated whole, its runs
//! of straight blocks streamed).

use crate::diag::Diagnostic;
use crate::dialect::Dialect;
use crate::ir::{CallKind, ItemKind, Program, Stmt, Unit, WordValue};
use crate::span::Span;
use crate::stream::segmented::LoadCallees;
use crate::stream::Fallback;
use crate::stream::{self, target::sinumerik as sts, Index};
use crate::translate::library;
use crate::translate::{to_fanuc::SymbolMap, to_fanuc::TranslateOptions};
use std::collections::BTreeSet;
use std::io::Write;
use std::path::Path;

/// What `library::scan` reports of a file's statements, gathered one top-level statement
/// at a time: its tools, its FANUC common variables, its Sinumerik calls by a constant name
/// (`segmented::calls_plain`: the only ones a streamed job can take), and whether it has a
/// call of another kind (such a file is read whole).
#[derive(Default)]
pub(super) struct LibItems {
    /// A call the streamed scan does not take: one not plain in Sinumerik, in FANUC one by a
    /// computed number or of a kind other than `M98`/`G65`/`G66`.
    pub other_calls: bool,
    /// The plain calls: the text offset of each (its line is found after the
    /// scan) and the call as `library::scan` records it (line 0 until then).
    pub calls: Vec<(u32, library::RawCall)>,
    pub tools: BTreeSet<String>,
    pub commons: BTreeSet<u32>,
}

impl LibItems {
    pub fn stmt(&mut self, dialect: Dialect, s: &Stmt) {
        let mut calls = Vec::new();
        library::walk_items(std::slice::from_ref(s), &mut |item| match &item.kind {
            ItemKind::Call(c) => calls.push((item.span.lo, library::raw_call(c, 0))),
            ItemKind::Word(w) if w.addr.is(b'T') => {
                if let WordValue::Expr(crate::ir::Expr { kind: crate::ir::ExprKind::Str(s), .. }) = &w.value {
                    self.tools.insert(s.clone());
                }
            }
            _ => {}
        });
        if !calls.is_empty() {
            let plain = match dialect {
                Dialect::Sinumerik => {
                    stream::segmented::fanuc::calls_plain(&Unit { dialect, file: 0, programs: vec![program_of(s)] })
                }
                // The calls the FANUC segmented stream keeps (`M98 P`, `G65 P`, `G66 P` by a
                // constant number); `raw_call` refuses a computed target below.
                Dialect::Fanuc => {
                    let mut kinds = true;
                    library::walk_items(std::slice::from_ref(s), &mut |item| {
                        if let ItemKind::Call(c) = &item.kind {
                            kinds &= matches!(c.kind, CallKind::M98 | CallKind::G65 | CallKind::G66);
                        }
                    });
                    kinds
                }
            };
            // A plain call has a constant target: `raw_call` gives it.
            match calls.into_iter().map(|(lo, c)| c.map(|c| (lo, c))).collect::<Option<Vec<_>>>() {
                Some(c) if plain => self.calls.extend(c),
                _ => self.other_calls = true,
            }
        }
        // A straight FANUC block has constant words only: no variable.
        if dialect == Dialect::Fanuc && sts::straight(s).is_err() {
            self.commons.extend(crate::translate::to_sinumerik::commons_of(&program_of(s)));
        }
    }
}

/// A nameless program holding the one statement `s` (what the whole-program helpers take).
fn program_of(s: &Stmt) -> Program {
    Program { name: None, head: None, params: vec![], save: false, body: vec![s.clone()], span: Span::default() }
}

/// One streamed translator into the staged output `part` (a fresh file): `Ok(None)` when
/// it declines because the program is not straight-line (the next translator may take it),
/// `Err(())` when it fails otherwise; nothing is left at `part` unless it is `Ok(Some)`.
pub(super) fn route<T>(
    part: &Path,
    bom: bool,
    translate: impl FnOnce(&mut dyn Write) -> Result<T, Fallback>,
) -> Result<Option<T>, ()> {
    match super::streamed::write_part(part, bom, translate) {
        Ok(t) => Ok(Some(t)),
        Err(Some(Fallback::NotStraight(_))) => Ok(None),
        Err(_) => Err(()),
    }
}

/// Sinumerik → FANUC into `part` as a straight-line stream, else segmented: the source's
/// index, the translation's symbol map (what the whole-file translation's would be) and its
/// notes (a MSG left as a comment: the whole-file job reports them too).
///
/// With `load` (a main that calls subprograms: it gives their units) only the segmented
/// stream with callees is tried (`segmented::to_fanuc_with_subs`).
pub(super) fn to_fanuc_part(
    path: &Path,
    opts: &TranslateOptions,
    part: &Path,
    bom: bool,
    load: Option<LoadCallees<'_>>,
) -> Option<(Index, SymbolMap, Vec<Diagnostic>)> {
    if let Some(load) = load {
        let with_subs = |w: &mut dyn Write| {
            let (done, notes) = stream::segmented::fanuc::to_fanuc_with_subs(path, opts, load, w, None)?;
            Ok((done.index, done.symbol_map, notes))
        };
        return route(part, bom, with_subs).ok()?;
    }
    let straight = |w: &mut dyn Write| {
        let done = stream::target::fanuc::to_fanuc(path, opts, w, None)?;
        // The names a straight-line program's translation uses depend on its name alone.
        let program = Program {
            name: done.index.programs.first().and_then(|p| p.program.name.clone()),
            head: None,
            params: vec![],
            save: false,
            body: vec![],
            span: Span::default(),
        };
        let unit = Unit { dialect: Dialect::Sinumerik, file: 0, programs: vec![program] };
        let map = crate::translate::to_fanuc::to_fanuc(&unit, &[], opts).symbol_map;
        Ok((done.index, map, Vec::new()))
    };
    if let Some(done) = route(part, bom, straight).ok()? {
        return Some(done);
    }
    let segmented = |w: &mut dyn Write| {
        let (done, notes) = stream::segmented::fanuc::to_fanuc_with_notes(path, opts, w, None)?;
        Ok((done.index, done.symbol_map, notes))
    };
    route(part, bom, segmented).ok()?
}
