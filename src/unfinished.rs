//! `--unsupported warn`, both directions: a source block with a construct the target cannot
//! express becomes one marked comment as a whole (none of its words survive as motion: a
//! cycle's `X10. Y10. Z-2.` would otherwise run as a rapid plunge), and the written program
//! raises an alarm on its first line, so it cannot be run as if it were finished.
//!
//! The translation is first made with the error policy; every block an error points at is
//! replaced in a copy of the source by a comment-only block (its N number and label kept, so
//! jumps still find it), and the copy is translated again, until nothing is refused (at most
//! [`ROUNDS`] times: a dropped DEF can make its uses unknown). A span inside a structure's
//! head replaces the whole structure. An error that points at no statement (a PROC line)
//! stays an error. The marked blocks' diagnostics are reported as warnings.

use crate::diag::{Diagnostic, Severity};
use crate::ir::*;
use crate::span::{FileId, Span};

/// Most translate-and-mark rounds.
pub const ROUNDS: usize = 8;

/// FANUC alarm number (3000 + n) and Siemens SETAL number of the first line.
pub const ALARM: u32 = 999;
/// The alarm's text (26 characters fit every FANUC alarm line).
pub const ALARM_TEXT: &str = "UNFINISHED TRANSLATION";

/// What [`mark`] did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Marked {
    /// The statement is now a marked comment block.
    New,
    /// It already was (another construct of the same block).
    Already,
    /// No statement of the file holds the span.
    Nowhere,
}

/// Replaces the statement `span` lies in with a marked comment block.
pub fn mark(units: &mut [Unit], file: FileId, span: Span, text: &str) -> Marked {
    for u in units.iter_mut().filter(|u| u.file == file) {
        for p in &mut u.programs {
            match mark_in(&mut p.body, span, text) {
                Marked::Nowhere => {}
                m => return m,
            }
        }
    }
    Marked::Nowhere
}

fn contains(outer: Span, inner: Span) -> bool {
    outer.lo <= inner.lo && inner.hi <= outer.hi && outer.hi > outer.lo
}

fn mark_in(body: &mut [Stmt], span: Span, text: &str) -> Marked {
    for s in body.iter_mut() {
        if !contains(s.span, span) {
            continue;
        }
        if is_marker(s) {
            return Marked::Already;
        }
        for child in crate::ir::visit::child_bodies_mut(&mut s.kind) {
            match mark_in(child, span, text) {
                Marked::Nowhere => {}
                m => return m,
            }
        }
        let first = crate::ir::visit::metas(&s.kind).first().map(|m| (*m).clone()).unwrap_or_default();
        let meta = BlockMeta {
            span: first.span,
            number: first.number,
            label: first.label,
            comments: vec![Comment { text: text.to_string(), span: first.span }],
            ..BlockMeta::default()
        };
        s.kind = StmtKind::Block(Block { meta, items: vec![] });
        return Marked::New;
    }
    Marked::Nowhere
}

fn is_marker(s: &Stmt) -> bool {
    matches!(&s.kind, StmtKind::Block(b) if b.items.is_empty() && b.meta.comments.iter().any(|c| c.text.contains("NCTRANS UNSUPPORTED")))
}

/// The primary place of a diagnostic.
pub fn place(d: &Diagnostic) -> Option<(FileId, Span)> {
    d.labels.iter().find(|l| l.primary).map(|l| (l.file, l.span))
}

/// The note [`as_warning`] adds.
const MARKED_NOTE: &str =
    "--unsupported warn: the whole block is a marked comment, the program alarms on its first line, and the run fails";

/// The error as the warning the warn policy reports.
pub fn as_warning(d: &Diagnostic) -> Diagnostic {
    let mut w = d.clone();
    w.severity = Severity::Warning;
    w.notes.push(MARKED_NOTE.into());
    w
}

/// Whether `d` is the warning of a block written as a marked comment ([`as_warning`]),
/// whatever its code: the output it belongs to is unfinished.
pub fn is_marked(d: &Diagnostic) -> bool {
    d.notes.iter().any(|n| n == MARKED_NOTE)
}

/// Runs `translate` on copies of `units`, marking refused blocks until it succeeds. Returns
/// the last result, the warnings of the marked blocks, how many blocks were marked, and
/// the marked copies.
pub fn translate_marking<T>(
    units: &[&Unit],
    style: impl Fn(&str) -> String,
    mut translate: impl FnMut(&[&Unit]) -> (T, Vec<Diagnostic>),
) -> (T, Vec<Diagnostic>, usize, Vec<Unit>) {
    let mut owned: Vec<Unit> = units.iter().map(|u| (*u).clone()).collect();
    let mut warnings = Vec::new();
    let mut marked = 0;
    let mut round = 0;
    loop {
        let refs: Vec<&Unit> = owned.iter().collect();
        let (t, diags) = translate(&refs);
        let errors: Vec<&Diagnostic> = diags.iter().filter(|d| d.is_error()).collect();
        if errors.is_empty() || round == ROUNDS {
            return (t, warnings, marked, owned);
        }
        round += 1;
        let mut progress = false;
        for d in errors {
            let Some((file, span)) = place(d) else { continue };
            match mark(&mut owned, file, span, &style(&d.message)) {
                Marked::New => {
                    marked += 1;
                    progress = true;
                    warnings.push(as_warning(d));
                }
                Marked::Already => warnings.push(as_warning(d)),
                Marked::Nowhere => {}
            }
        }
        if !progress {
            return (t, warnings, marked, owned);
        }
    }
}

/// The block that opens an unfinished program: FANUC `#3000=999(UNFINISHED TRANSLATION)`
/// (Siemens `SETAL(65999)` with the text as its comment, as `#3000` translates).
pub fn alarm_block(span: Span) -> Stmt {
    let number = Expr::num(f64::from(ALARM), false, span);
    let item = Item {
        kind: ItemKind::Alarm { style: AlarmStyle::FanucMacro, number, text: Some(ALARM_TEXT.to_string()) },
        span,
    };
    Stmt { kind: StmtKind::Block(Block { meta: BlockMeta { span, ..BlockMeta::default() }, items: vec![item] }), span }
}

/// The comment line after the alarm: how many blocks are marked (`prefix` is the
/// direction's marker opening, so comment filters keep it).
pub fn summary_block(span: Span, prefix: &str, marked: usize) -> Stmt {
    let text = format!("{prefix} UNFINISHED, BLOCKS NOT TRANSLATED: {marked}, EACH MARKED WHERE IT STOOD");
    let meta = BlockMeta { span, comments: vec![Comment { text, span }], ..BlockMeta::default() };
    Stmt { kind: StmtKind::Block(Block { meta, items: vec![] }), span }
}
