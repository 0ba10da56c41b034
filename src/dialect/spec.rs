//! The description of a dialect as one value: what a library user implements to add a dialect
//! (`docs/adding-a-dialect.md`), and what the generic entry
//! (`translate::generic::translate_between`, `verify_between`) reads and writes through.
//!
//! A description names the dialect, recognises its files, reads its text into the IR, says
//! what the IR must become to be expressible in it (its lowering) and writes the IR back. Its
//! programs run in the bundled evaluator, which knows two execution models (FANUC's and
//! Siemens'): a dialect says which one its IR runs under ([`Spec::runs_as`], also the tag of
//! the units it reads) and gives its own control profile ([`Spec::semantics`]). The two
//! built-in descriptions (`translate::generic::builtin`) delegate to the existing readers,
//! writers and translations; the enum [`Dialect`] stays their registry.

use super::{Dialect, ParseOptions, Parsed, Semantics};
use crate::diag::Diagnostic;
use crate::ir::Unit;
use crate::read::LineEnding;
use crate::span::{FileId, SourceFile};

/// The text a description writes for one unit, and what it could not write.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Written {
    pub text: String,
    /// Errors mean the text is not a translation (a construct without a spelling).
    pub diags: Vec<Diagnostic>,
}

/// One dialect, described. Every method is pure: no printing, no file access.
pub trait Spec: Send + Sync {
    /// Lower case, as the command line and messages name it (`fanuc`, `iso`).
    fn name(&self) -> &str;

    /// File extensions that imply the dialect, lower case, without the dot; the first one
    /// names the files a translation to it writes.
    fn extensions(&self) -> &[&str];

    /// How much `text` looks like this dialect (0: not at all). [`detect`] takes the
    /// description with the highest score.
    fn sniff(&self, text: &str) -> u32;

    /// The evaluator's execution model its IR runs under, and the [`Unit::dialect`] of the
    /// units [`Spec::parse`] returns. A dialect that runs like one of the built-ins says
    /// which, and differs from it in [`Spec::semantics`] and in what it can express.
    fn runs_as(&self) -> Dialect;

    /// The control profile its programs are read and run with (the evaluator's flags).
    fn semantics(&self) -> Semantics;

    /// Reads one file: the unit (as much as could be read, every node with its span into
    /// `src`) and every diagnostic. A bad block gives a diagnostic, never a panic.
    fn parse(&self, src: &SourceFile, file: FileId, opts: &ParseOptions) -> Parsed;

    /// What the IR must become to be expressible here. `unit` runs under
    /// [`Spec::runs_as`] (the generic entry bridges between the two models before) and was
    /// read with the profile `source`; the result must mean the same under
    /// [`Spec::semantics`]. A construct the dialect cannot express is an error diagnostic
    /// at its span (the whole translation is then refused).
    fn lower(&self, unit: &Unit, source: &Semantics) -> Result<Unit, Vec<Diagnostic>>;

    /// Writes a lowered unit as the text of one file.
    fn emit(&self, unit: &Unit, line_ending: LineEnding) -> Written;

    /// The built-in dialect this description is, if it is one: the generic entry then takes
    /// that pair's own tuned translation and proof.
    fn builtin(&self) -> Option<Dialect> {
        None
    }
}

/// The description among `specs` that `name` and `text` point to: the file extension
/// first, else the highest [`Spec::sniff`] score (the first of equals); `None` when `specs`
/// is empty.
pub fn detect<'a>(specs: &[&'a dyn Spec], name: &str, text: &str) -> Option<&'a dyn Spec> {
    let ext = std::path::Path::new(name).extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    if let Some(ext) = ext {
        if let Some(s) = specs.iter().find(|s| s.extensions().iter().any(|e| e.eq_ignore_ascii_case(&ext))) {
            return Some(*s);
        }
    }
    let mut best: Option<(&'a dyn Spec, u32)> = None;
    for s in specs {
        let score = s.sniff(text);
        if best.is_none_or(|(_, b)| score > b) {
            best = Some((*s, score));
        }
    }
    best.map(|(s, _)| s)
}
