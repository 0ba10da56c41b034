//! Diagnostics: what every phase reports, and their rendering through codespan-reporting.
//!
//! Codes are stable and grouped by phase: NC1xx reading and parsing (NC100–NC119 shared
//! reading, NC120–NC159 Sinumerik, NC160–NC199 FANUC), NC2xx validation and structure
//! (NC200–NC229 Sinumerik, NC230–NC259 FANUC), NC3xx unsupported on a target, NC4xx
//! evaluation, NC5xx divergence, NC6xx files and batches. Each code is documented with the rule
//! that raises it: `docs/translation.md` and `docs/translation-fanuc-to-sinumerik.md`
//! (Diagnostics), `docs/semantics.md` (evaluation), the README (batches and files).

use crate::span::{FileId, SourceDb, Span};
use codespan_reporting::diagnostic as cs;
use codespan_reporting::term;

#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Severity {
    Note,
    Warning,
    Error,
}

/// A place in a file that a diagnostic points at.
#[derive(Clone, Debug, PartialEq)]
pub struct Label {
    pub file: FileId,
    pub span: Span,
    pub message: String,
    pub primary: bool,
}

/// One problem (or remark) found in a program.
#[derive(Clone, Debug, PartialEq)]
pub struct Diagnostic {
    pub severity: Severity,
    pub code: &'static str,
    pub message: String,
    pub labels: Vec<Label>,
    /// Hints and explanations, shown after the source excerpt.
    pub notes: Vec<String>,
}

/// Drops repeats of a diagnostic already in the list (same severity, code, message and
/// labels), keeping the first: a lowering that meets one refused construct once per use
/// (a modal cycle at each hole) reports it once.
pub fn dedup(diags: &mut Vec<Diagnostic>) {
    let mut seen = std::collections::HashSet::new();
    diags.retain(|d| {
        let labels: Vec<_> = d.labels.iter().map(|l| (l.file, l.span, l.message.clone(), l.primary)).collect();
        seen.insert((d.severity, d.code, d.message.clone(), labels))
    });
}

impl Diagnostic {
    pub fn new(severity: Severity, code: &'static str, message: impl Into<String>) -> Self {
        Diagnostic { severity, code, message: message.into(), labels: Vec::new(), notes: Vec::new() }
    }

    pub fn error(code: &'static str, message: impl Into<String>) -> Self {
        Self::new(Severity::Error, code, message)
    }

    pub fn warning(code: &'static str, message: impl Into<String>) -> Self {
        Self::new(Severity::Warning, code, message)
    }

    /// The main place: where the problem is.
    pub fn primary(mut self, file: FileId, span: Span, message: impl Into<String>) -> Self {
        self.labels.push(Label { file, span, message: message.into(), primary: true });
        self
    }

    /// A related place (the opening `WHILE` of an unmatched `ENDWHILE`, the other label…).
    pub fn secondary(mut self, file: FileId, span: Span, message: impl Into<String>) -> Self {
        self.labels.push(Label { file, span, message: message.into(), primary: false });
        self
    }

    pub fn note(mut self, note: impl Into<String>) -> Self {
        self.notes.push(note.into());
        self
    }

    /// `hint: …` note, the conventional suggestion of what to write instead.
    pub fn hint(mut self, hint: impl AsRef<str>) -> Self {
        self.notes.push(format!("hint: {}", hint.as_ref()));
        self
    }

    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }

    fn to_codespan(&self, db: &SourceDb) -> cs::Diagnostic<FileId> {
        self.to_codespan_with(&|l| shown_range(db, l))
    }

    /// The codespan form, with each label's byte range given by `range` (an excerpt of a
    /// file that is not in memory has its own offsets: see `crate::excerpt`).
    pub(crate) fn to_codespan_with(&self, range: &dyn Fn(&Label) -> std::ops::Range<usize>) -> cs::Diagnostic<FileId> {
        let sev = match self.severity {
            Severity::Error => cs::Severity::Error,
            Severity::Warning => cs::Severity::Warning,
            Severity::Note => cs::Severity::Note,
        };
        cs::Diagnostic::new(sev)
            .with_code(self.code)
            .with_message(self.message.clone())
            .with_labels(
                self.labels
                    .iter()
                    .map(|l| {
                        let style = if l.primary { cs::LabelStyle::Primary } else { cs::LabelStyle::Secondary };
                        cs::Label::new(style, l.file, range(l)).with_message(l.message.clone())
                    })
                    .collect(),
            )
            .with_notes(self.notes.clone())
    }
}

/// True when any diagnostic is an error.
pub fn has_errors(diags: &[Diagnostic]) -> bool {
    diags.iter().any(Diagnostic::is_error)
}

/// Renders diagnostics as codespan-reporting text (file, line, column, excerpt, notes).
pub fn render(db: &SourceDb, diags: &[Diagnostic]) -> String {
    let config = term::Config::default();
    let mut out = String::new();
    for d in diags {
        let mut one = String::new();
        // Rendering can only fail on a label outside its file; fall back to a plain line
        // rather than lose the diagnostic.
        if term::emit_to_string(&mut one, &config, db, &d.to_codespan(db)).is_ok() {
            out.push_str(&one);
        } else {
            out.push_str(&format!("{}[{}]: {}\n", sev_word(d.severity), d.code, d.message));
        }
    }
    out
}

/// Lines of a label that are shown at most; codespan prints every line of a label, and a
/// label over a whole large program would take minutes to render.
pub(crate) const MAX_LABEL_LINES: usize = 8;

/// The label's range, cut after its first line when it covers more than
/// [`MAX_LABEL_LINES`] lines.
pub(crate) fn shown_range(db: &SourceDb, l: &Label) -> std::ops::Range<usize> {
    let r = l.span.range();
    if l.file >= db.len() {
        return r;
    }
    let text = &db.get(l.file).text;
    let Some(slice) = text.get(r.clone()) else { return r };
    let mut lines = slice.match_indices(['\n', '\r']).take(MAX_LABEL_LINES + 1);
    match (lines.next(), lines.count() >= MAX_LABEL_LINES) {
        (Some((first_end, _)), true) => r.start..r.start + first_end,
        _ => r,
    }
}

pub(crate) fn sev_word(s: Severity) -> &'static str {
    match s {
        Severity::Error => "error",
        Severity::Warning => "warning",
        Severity::Note => "note",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_label_over_a_whole_program_shows_its_first_line_only() {
        let mut db = SourceDb::new();
        let text: String = (1..=5000).map(|i| format!("N{i} G1 X{i}\n")).collect();
        let f = db.add("big.mpf", text.clone());
        let d = Diagnostic::error("NC306", "too many").primary(f, Span::new(0, text.len() as u32), "here");
        let out = render(&db, &[d]);
        assert!(out.contains("N1 G1 X1"), "{out}");
        assert!(!out.contains("N2 G1 X2"), "{out}");
        // A short multi-line label is shown whole.
        let d = Diagnostic::error("NC200", "x").primary(f, Span::new(0, 20), "here");
        assert!(render(&db, &[d]).contains("N2 G1 X2"));
    }
}
