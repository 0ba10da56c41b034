//! The two built-in dialects as descriptions ([`Spec`]), delegating to their readers and
//! writers: what a pair with a described dialect on one side reads and writes through. A
//! pair of the two built-ins never comes here (the generic entry takes their own
//! translation and proof).

use crate::diag::Diagnostic;
use crate::dialect::fanuc::emit::{CommentMode, EmitOptions};
use crate::dialect::sinumerik::emit::{emit_program, Frame};
use crate::dialect::{Dialect, ParseOptions, Parsed, Semantics, Spec, Written};
use crate::ir::{ProgName, Unit};
use crate::read::LineEnding;
use crate::span::{FileId, SourceFile, Span};
use crate::translate::{to_fanuc::DEFAULT_MAIN_NUMBER, to_fanuc::FIRST_SUB_NUMBER};

/// FANUC Custom Macro B (and Haas) as a description.
pub struct Fanuc;
/// Siemens Sinumerik as a description.
pub struct Sinumerik;

/// The built-in description of `d`.
pub fn builtin(d: Dialect) -> &'static dyn Spec {
    match d {
        Dialect::Fanuc => &Fanuc,
        Dialect::Sinumerik => &Sinumerik,
    }
}

/// The IR handed to a built-in's lowering runs under the other model: the generic entry
/// bridges first, so this is a gap in it.
fn wrong_model(unit: &Unit, to: Dialect) -> Vec<Diagnostic> {
    let span = unit.programs.first().map_or(Span::default(), |p| p.span);
    vec![Diagnostic::error(
        "NC516",
        format!("IR that runs as {} handed to the {} writer", unit.dialect.name(), to.name()),
    )
    .primary(unit.file, span, "this program")
    .note("the generic entry translates between the two execution models before it lowers")
    .hint("report it with the dialect description")]
}

fn with_ending(text: String, line_ending: LineEnding) -> String {
    match line_ending {
        LineEnding::Lf => text,
        other => text.replace('\n', other.as_str()),
    }
}

impl Spec for Fanuc {
    fn name(&self) -> &str {
        Dialect::Fanuc.name()
    }

    fn extensions(&self) -> &[&str] {
        &["nc", "tap", "fnc", "cnc"]
    }

    fn sniff(&self, text: &str) -> u32 {
        Dialect::sniff_scores(text).0.max(0) as u32
    }

    fn runs_as(&self) -> Dialect {
        Dialect::Fanuc
    }

    fn semantics(&self) -> Semantics {
        Semantics::default_for(Dialect::Fanuc)
    }

    fn parse(&self, src: &SourceFile, file: FileId, opts: &ParseOptions) -> Parsed {
        crate::dialect::parse(src, file, Dialect::Fanuc, opts)
    }

    /// FANUC IR read with a profile: bare lengths restated in units
    /// ([`crate::lower::restate`]), as the writer gives them a decimal point; every program gets the O number FANUC writes (the
    /// first the main program's, the others from the subprogram range).
    fn lower(&self, unit: &Unit, source: &Semantics) -> Result<Unit, Vec<Diagnostic>> {
        if unit.dialect != Dialect::Fanuc {
            return Err(wrong_model(unit, Dialect::Fanuc));
        }
        let mut u = unit.clone();
        // The FANUC writer gives every length a decimal point: the literals must be in units.
        let units = Semantics { calculator_input: true, ..self.semantics() };
        let diags = crate::lower::restate::restate(&mut u, source, &units);
        if crate::diag::has_errors(&diags) {
            return Err(diags);
        }
        let mut next = FIRST_SUB_NUMBER;
        for (i, p) in u.programs.iter_mut().enumerate() {
            if p.name.is_none() {
                let n = if i == 0 {
                    DEFAULT_MAIN_NUMBER
                } else {
                    next += 1;
                    next - 1
                };
                p.name = Some(ProgName::Number(n));
            }
        }
        Ok(u)
    }

    fn emit(&self, unit: &Unit, line_ending: LineEnding) -> Written {
        let e = crate::dialect::fanuc::emit::emit(
            unit,
            &EmitOptions { comments: CommentMode::Keep, line_ending, file: unit.file },
        );
        Written { text: e.text, diags: e.diags }
    }

    fn builtin(&self) -> Option<Dialect> {
        Some(Dialect::Fanuc)
    }
}

impl Spec for Sinumerik {
    fn name(&self) -> &str {
        Dialect::Sinumerik.name()
    }

    fn extensions(&self) -> &[&str] {
        &["mpf", "spf"]
    }

    fn sniff(&self, text: &str) -> u32 {
        Dialect::sniff_scores(text).1.max(0) as u32
    }

    fn runs_as(&self) -> Dialect {
        Dialect::Sinumerik
    }

    fn semantics(&self) -> Semantics {
        Semantics::default_for(Dialect::Sinumerik)
    }

    fn parse(&self, src: &SourceFile, file: FileId, opts: &ParseOptions) -> Parsed {
        crate::dialect::parse(src, file, Dialect::Sinumerik, opts)
    }

    /// Siemens IR is expressible as it is: no profile reads a literal differently.
    fn lower(&self, unit: &Unit, _source: &Semantics) -> Result<Unit, Vec<Diagnostic>> {
        if unit.dialect != Dialect::Sinumerik {
            return Err(wrong_model(unit, Dialect::Sinumerik));
        }
        Ok(unit.clone())
    }

    /// One program per file (a Siemens file holds one).
    fn emit(&self, unit: &Unit, line_ending: LineEnding) -> Written {
        let mut diags = Vec::new();
        for p in unit.programs.iter().skip(1) {
            diags.push(
                Diagnostic::error("NC518", "a second program in one Sinumerik file")
                    .primary(unit.file, p.span, "this program")
                    .note("a Sinumerik file holds one program")
                    .hint("give each program its own unit"),
            );
        }
        let Some(p) = unit.programs.first() else { return Written { text: String::new(), diags } };
        let e = emit_program(p, &Frame { header: &[], defs: &[], proc_line: false });
        for (span, what) in &e.problems {
            diags.push(
                Diagnostic::error("NC518", format!("cannot write {what} in Sinumerik syntax"))
                    .primary(unit.file, *span, "from here")
                    .note("the dialect's lowering left a construct the Sinumerik writer has no spelling for")
                    .hint("refuse it in the lowering of the dialect description"),
            );
        }
        Written { text: with_ending(e.text, line_ending), diags }
    }

    fn builtin(&self) -> Option<Dialect> {
        Some(Dialect::Sinumerik)
    }
}
