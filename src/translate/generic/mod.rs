//! The generic entry: a translation and its proof between any two dialect descriptions
//! ([`Spec`], `src/dialect/spec.rs`), for a dialect added outside the two built-ins
//! (`docs/adding-a-dialect.md`). A pair of the two built-ins takes their own tuned paths
//! ([`super::translate`], [`super::verify`]); everything else goes through the
//! descriptions: the source's units are bridged to the target's execution model when the
//! two differ (by the built-in translation between the models), lowered by the target
//! ([`Spec::lower`]) and written by it ([`Spec::emit`]). The proof reads the output back
//! with the target, runs both sides in the evaluator with each description's profile and
//! compares the traces (`check`).
//!
//! Refusals are errors (the generic path has no warn policy: a described dialect's lowering
//! refuses whole). May use what `translate` uses.

pub mod builtin;

pub use builtin::builtin;

use super::{to_fanuc, translate, verify, Options, OutFile, Symbols, Translation, Verification};
use crate::check::{self, Exclude, Side};
use crate::diag::{self, Diagnostic};
use crate::dialect::{Dialect, ParseOptions, Semantics, Spec};
use crate::eval::{input, CalleeName, CalleeSource, Input, RunOptions};
use crate::ir::{ProgName, Unit};
use crate::span::{FileId, SourceDb, Span};

/// Translates `inputs` (read by `from`: the main file's unit first, then the files its
/// callees were found in) to `to`. The two built-ins between each other: exactly
/// [`translate`]. Otherwise each unit becomes one written file, the main program's first.
pub fn translate_between(inputs: &[&Unit], from: &dyn Spec, to: &dyn Spec, opts: &Options) -> Translation {
    if let (Some(a), Some(b)) = (from.builtin(), to.builtin()) {
        if a != b {
            return translate(inputs, b, opts);
        }
    }
    let model = to.runs_as();
    let empty = |diags| Translation { files: vec![], symbols: no_symbols(model), diags, unsupported: 0 };
    if inputs.iter().any(|u| u.dialect != from.runs_as()) {
        return empty(vec![Diagnostic::error("NC516", format!("a unit not read as {}", from.name()))
            .note(format!("{} reads units that run as {}", from.name(), from.runs_as().name()))
            .hint("read every input with the source dialect's description")]);
    }
    // The units in the target's model, the profile they were read with, their symbol map.
    let (units, source, symbols, mut diags): (Vec<Unit>, Semantics, Symbols, Vec<Diagnostic>) =
        if from.runs_as() == model {
            (inputs.iter().map(|u| (*u).clone()).collect(), from.semantics(), no_symbols(model), vec![])
        } else if to.builtin() == Some(model) {
            // A built-in target's own translation writes the files; it reads the source
            // with the source's profile.
            let mut o = opts.clone();
            match model {
                Dialect::Sinumerik => o.sinumerik.source = from.semantics(),
                Dialect::Fanuc => o.fanuc.source = from.semantics(),
            }
            return translate(inputs, model, &o);
        } else {
            match model {
                Dialect::Fanuc => {
                    let Some((main, subs)) = inputs.split_first() else { return empty(vec![]) };
                    let fanuc = to_fanuc::TranslateOptions {
                        line_ending: opts.line_ending,
                        unsupported: crate::lower::to_fanuc::UnsupportedPolicy::Error,
                        source: from.semantics(),
                        ..opts.fanuc.clone()
                    };
                    let mut out = to_fanuc::to_fanuc(main, subs, &fanuc);
                    // Its header names FANUC as the target; the target writes its own.
                    out.unit.programs.iter_mut().for_each(crate::lower::own_header::drop_own_header);
                    if diag::has_errors(&out.diags) {
                        return Translation {
                            files: vec![],
                            symbols: Symbols::Fanuc(Box::new(out.symbol_map)),
                            ..empty(out.diags)
                        };
                    }
                    // The written IR's lengths are in units whatever their `point` (the
                    // FANUC writer gives each one a decimal point): read as calculator input.
                    let written = Semantics { calculator_input: true, ..fanuc.target };
                    (vec![out.unit], written, Symbols::Fanuc(Box::new(out.symbol_map)), out.diags)
                }
                Dialect::Sinumerik => {
                    let span = inputs.first().and_then(|u| u.programs.first()).map_or(Span::default(), |p| p.span);
                    let file = inputs.first().map_or(0, |u| u.file);
                    return empty(vec![Diagnostic::error(
                        "NC516",
                        format!("no translation from {} to {}, which runs as Sinumerik", from.name(), to.name()),
                    )
                    .primary(file, span, "this program")
                    .note("the FANUC → Sinumerik translation writes Sinumerik text, not IR a description can lower")
                    .hint("translate to sinumerik itself, or describe the target as running as FANUC")]);
                }
            }
        };
    let mut files = Vec::new();
    for (i, unit) in units.iter().enumerate() {
        let lowered = match to.lower(unit, &source) {
            Ok(u) => u,
            Err(mut d) => {
                diags.append(&mut d);
                continue;
            }
        };
        let mut w = to.emit(&lowered, opts.line_ending);
        diags.append(&mut w.diags);
        let program = match lowered.programs.first().and_then(|p| p.name.as_ref()) {
            Some(ProgName::Number(n)) => format!("O{n:04}"),
            Some(ProgName::Name(n)) => n.clone(),
            None => "MAIN".to_string(),
        };
        let ext = to.extensions().first().copied().unwrap_or("txt");
        files.push(OutFile {
            name: format!("{program}.{ext}"),
            program,
            fanuc_number: None,
            main: i == 0,
            text: w.text,
            source: unit.file,
            lines: vec![],
        });
    }
    if diag::has_errors(&diags) {
        files.clear();
    }
    Translation { files, symbols, diags, unsupported: 0 }
}

fn no_symbols(model: Dialect) -> Symbols {
    match model {
        Dialect::Fanuc => Symbols::Fanuc(Default::default()),
        Dialect::Sinumerik => Symbols::Sinumerik(Default::default()),
    }
}

/// Proves a translation made by [`translate_between`]: every written file is read back with
/// `to` (so it is valid text of the target), the first program of `inputs[0]` runs with
/// `from`'s profile (its callees from the other inputs) and the main written program with
/// `to`'s (its callees from the other written files), at most `max_steps` blocks each, and
/// the traces are compared. The two built-ins between each other: exactly [`verify`].
/// `out` is the folder the written files are shown in.
pub fn verify_between(
    db: &mut SourceDb,
    inputs: &[&Unit],
    from: &dyn Spec,
    to: &dyn Spec,
    t: &Translation,
    out: &str,
    max_steps: u64,
) -> Verification {
    if let (Some(a), Some(b)) = (from.builtin(), to.builtin()) {
        if a != b {
            return verify(db, inputs, t, out, max_steps);
        }
    }
    let not = |summary: String, rendered: String| Verification { summary, rendered, ..Verification::default() };
    let Some((main, subs)) = inputs.split_first() else {
        return not("not verified: no program to run".into(), String::new());
    };
    if t.has_errors() || t.files.is_empty() {
        return not("not verified: the translation was refused (see its diagnostics)".into(), String::new());
    }
    let path = |name: &str| if out.is_empty() { name.to_string() } else { format!("{out}/{name}") };
    let popts = ParseOptions { semantics: to.semantics() };
    let mut main_b = None;
    let mut others = Vec::new();
    for f in &t.files {
        let id = db.add(path(&f.name), f.text.clone());
        let parsed = to.parse(db.get(id), id, &popts);
        if diag::has_errors(&parsed.diags) {
            let mut diags = parsed.diags;
            diags.push(
                Diagnostic::error("NC518", format!("the translation does not read back as {}", to.name()))
                    .note("a gap in the target's writer or reader, not in the program")
                    .hint("report it with the program and the dialect description"),
            );
            let summary = format!("not verified: the output does not read back as {}", to.name());
            return not(summary, diag::render(db, &diags));
        }
        if f.main && main_b.is_none() {
            main_b = Some(parsed.unit);
        } else {
            others.push(parsed.unit);
        }
    }
    let Some(main_b) = main_b else { return not("not verified: no main program written".into(), String::new()) };
    let mut sem_a = from.semantics();
    let mut source: Unit = (*main).clone();
    let mut callees_a: Vec<Unit> = subs.iter().map(|u| (*u).clone()).collect();
    let (mut in_a, mut in_b): (Vec<Input>, Vec<Input>) = (vec![], vec![]);
    let mut exclude = Exclude::default();
    match (main.dialect, main_b.dialect) {
        // Bridged by the Sinumerik → FANUC translation: its proof's alignment and inputs.
        (Dialect::Sinumerik, Dialect::Fanuc) => {
            let map = t.symbols.fanuc();
            source = to_fanuc::align_source(main, map);
            callees_a = subs.iter().map(|u| to_fanuc::align_source(u, map)).collect();
            sem_a = to_fanuc::source_semantics(t, Some(&sem_a)).unwrap_or(sem_a);
            in_b = to_fanuc::r_param_inputs(map);
            in_b.extend(to_fanuc::standalone_args(main, map));
            in_b.extend(to_fanuc::gud_inputs(t));
            exclude = to_fanuc::EXCLUDE;
        }
        // Bridged by the FANUC → Sinumerik translation: both sides' `nctrans: set` lines.
        (Dialect::Fanuc, Dialect::Sinumerik) => {
            let text_b = t.main().map_or("", |f| f.text.as_str());
            match (input::header_inputs(&db.get(main.file).text), input::header_inputs(text_b)) {
                (Ok(a), Ok(b)) => (in_a, in_b) = (a, b),
                (Err(e), _) | (_, Err(e)) => {
                    return not(format!("not verified: bad `nctrans: set` header line: {e}"), String::new())
                }
            }
        }
        _ => {}
    }
    let a = Side {
        unit: source,
        callees: Box::new(Units(callees_a)),
        run: RunOptions { max_steps, inputs: in_a, semantics: Some(sem_a), ..RunOptions::default() },
    };
    let b = Side {
        unit: main_b.clone(),
        callees: Box::new(Units(others)),
        run: RunOptions { max_steps, inputs: in_b, semantics: Some(to.semantics()), ..RunOptions::default() },
    };
    let report = check::check_excluding(db, a, b, exclude);
    let mut v = Verification::of(&report);
    v.reparsed = Some(main_b);
    v
}

/// Serves called programs from units already read, by `O` number or name.
struct Units(Vec<Unit>);

impl CalleeSource for Units {
    fn find(
        &mut self,
        _db: &mut SourceDb,
        _caller: FileId,
        _dialect: Dialect,
        name: &CalleeName,
    ) -> Result<Option<Unit>, Diagnostic> {
        let hit = |p: &crate::ir::Program| match (name, &p.name) {
            (CalleeName::Number(n), Some(ProgName::Number(m))) => n == m,
            (CalleeName::Name(n), Some(ProgName::Name(m))) => n.eq_ignore_ascii_case(m),
            _ => false,
        };
        Ok(self.0.iter().find(|u| u.programs.first().is_some_and(hit)).cloned())
    }
}
