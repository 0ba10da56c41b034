//! Proof of a FANUC → Sinumerik translation: the Siemens main program is parsed back from the
//! emitted text (so the output is shown to be valid Sinumerik), the subprograms are served
//! from the emitted texts too, both programs run in the evaluator, and the checker compares
//! the traces. Inputs come from each program's `nctrans: set` header lines (the translation
//! writes the FANUC ones in Siemens names), so both runs start from the same state.

use crate::check::{self, CheckReport, Side};
use crate::diag::Diagnostic;
use crate::dialect::{Dialect, ParseOptions, Semantics};
use crate::eval::calls::{CalleeName, CalleeSource, DirCallees};
use crate::eval::{input, Input, RunOptions};
use crate::ir::Unit;
use crate::span::{FileId, SourceDb};
use crate::translate::called::{self, RunSettings};
use crate::translate::{OutFile, Translation, VerifyOptions};

/// Serves the translation's `.SPF` files to the Siemens run, from memory (also the streamed
/// verification's, `cli::translate`).
pub struct Emitted {
    /// Siemens program name, the path shown, the text.
    pub files: Vec<(String, String, String)>,
    pub semantics: Semantics,
}

impl CalleeSource for Emitted {
    fn find(
        &mut self,
        db: &mut SourceDb,
        _caller: FileId,
        dialect: Dialect,
        name: &CalleeName,
    ) -> Result<Option<Unit>, Diagnostic> {
        let CalleeName::Name(n) = name else { return Ok(None) };
        let Some((_, path, text)) = self.files.iter().find(|(p, _, _)| p.eq_ignore_ascii_case(n)) else {
            return Ok(None);
        };
        let id = db.add(path.clone(), text.clone());
        let parsed = crate::parse(db, id, dialect, &ParseOptions { semantics: self.semantics.clone() });
        if let Some(first) = parsed.diags.iter().find(|d| d.is_error()) {
            let mut d = first.clone();
            d.notes.push(format!("the translation {path} does not read back as Sinumerik"));
            return Err(d);
        }
        Ok(Some(parsed.unit))
    }
}

/// The runs of the proof of a FANUC → Sinumerik translation (`translate::verify`): in a
/// library, each program of the file that runs as a main and the macros it calls
/// (`called::library_runs`); else the first program (its FANUC callees found beside it on
/// disk), then each macro the programs call by G65/G66 alone (`called::called_runs`).
pub fn runs(
    db: &SourceDb,
    inputs: &[&Unit],
    tr: &Translation,
    out: &str,
    opts: &VerifyOptions,
) -> Vec<(String, CheckReport)> {
    let profiles = opts.profiles.clone().unwrap_or_default();
    let settings = RunSettings { out_dir: out, max_steps: opts.max_steps, profiles: &profiles, set: opts.set };
    if let Some(lib) = &opts.library {
        return crate::translate::called::library_runs(db, inputs, tr, &settings, (lib, opts.each_vacant));
    }
    let main = inputs[0];
    let mut runs = vec![(String::new(), verify_profiled(db, main.file, main, tr, out, opts.max_steps, &profiles))];
    runs.extend(called::called_runs(db, inputs, tr, &settings, opts.each_vacant));
    runs
}

fn failed(db: SourceDb, diags: Vec<Diagnostic>) -> CheckReport {
    CheckReport::failed(db, diags)
}

/// Runs the FANUC program (`fanuc`, file `fanuc_file` in `db`; its callees are found beside
/// it on disk) and the translation, and compares the traces. `out_dir` names the folder the
/// Siemens files are shown in (diagnostics point at `out_dir/NAME.MPF`).
pub fn verify(db: &SourceDb, fanuc_file: FileId, fanuc: &Unit, tr: &Translation, out_dir: &str) -> CheckReport {
    verify_with(db, fanuc_file, fanuc, tr, out_dir, crate::eval::DEFAULT_MAX_STEPS)
}

/// The control profiles of the two runs.
#[derive(Clone, Debug)]
pub struct Profiles {
    pub fanuc: Semantics,
    pub sinumerik: Semantics,
}

impl Default for Profiles {
    fn default() -> Self {
        Profiles {
            fanuc: Semantics::default_for(Dialect::Fanuc),
            sinumerik: Semantics::default_for(Dialect::Sinumerik),
        }
    }
}

/// [`verify`] with a step limit for each run.
pub fn verify_with(
    db: &SourceDb,
    fanuc_file: FileId,
    fanuc: &Unit,
    tr: &Translation,
    out_dir: &str,
    max_steps: u64,
) -> CheckReport {
    verify_profiled(db, fanuc_file, fanuc, tr, out_dir, max_steps, &Profiles::default())
}

/// [`verify_with`] for the given control profiles (the project's FANUC increment, DPI and
/// NAT, the Siemens R parameter count).
pub fn verify_profiled(
    db: &SourceDb,
    fanuc_file: FileId,
    fanuc: &Unit,
    tr: &Translation,
    out_dir: &str,
    max_steps: u64,
    profiles: &Profiles,
) -> CheckReport {
    let Some(main) = tr.main() else {
        return failed(db.clone(), vec![Diagnostic::error("NC372", "the translation has no main program to run")]);
    };
    let spec = RunSpec {
        main,
        out_dir,
        max_steps,
        profiles,
        fanuc_callees: Box::new(DirCallees { semantics: Some(profiles.fanuc.clone()) }),
        extra_fanuc: vec![],
        extra_siemens: vec![],
    };
    verify_run(db, fanuc_file, fanuc, tr, spec)
}

/// One run of a proof: which translated program runs, where the FANUC side finds its
/// callees, and inputs beyond the header lines (a batch's argument vectors and `--set`).
pub struct RunSpec<'a> {
    /// The Siemens program run against the first program of the FANUC unit.
    pub main: &'a OutFile,
    /// The folder the Siemens files are shown in (diagnostics point at `out_dir/NAME.MPF`).
    pub out_dir: &'a str,
    /// The step limit of each run.
    pub max_steps: u64,
    pub profiles: &'a Profiles,
    pub fanuc_callees: Box<dyn CalleeSource + Send>,
    /// Given after the header inputs of each side, so they win.
    pub extra_fanuc: Vec<Input>,
    pub extra_siemens: Vec<Input>,
}

/// Runs the first program of `fanuc` and `spec.main` (the other programs of the translation
/// served from memory) and compares the traces.
pub fn verify_run(db: &SourceDb, fanuc_file: FileId, fanuc: &Unit, tr: &Translation, spec: RunSpec) -> CheckReport {
    let mut db = db.clone();
    let RunSpec { main, out_dir, max_steps, profiles, .. } = spec;
    let path = |name: &str| if out_dir.is_empty() { name.to_string() } else { format!("{out_dir}/{name}") };
    let main_id = db.add(path(&main.name), main.text.clone());
    let parsed =
        crate::parse(&db, main_id, Dialect::Sinumerik, &ParseOptions { semantics: profiles.sinumerik.clone() });
    if crate::diag::has_errors(&parsed.diags) {
        let mut diags = parsed.diags;
        diags.push(
            Diagnostic::error("NC372", "the translation does not read back as Sinumerik")
                .note("this is a gap in nctrans's writer, not in the program")
                .hint("report it with the program"),
        );
        return failed(db, diags);
    }
    let inputs = |text: &str| input::header_inputs(text);
    let (mut in_a, mut in_b) = match (inputs(&db.get(fanuc_file).text), inputs(&main.text)) {
        (Ok(a), Ok(b)) => (a, b),
        (Err(e), _) | (_, Err(e)) => {
            return failed(db, vec![Diagnostic::error("NC407", format!("bad `nctrans: set` header line: {e}"))])
        }
    };
    // Both programs meet the same probe inputs: the source's (`nctrans: probe`).
    let probes = match crate::eval::header_probes(&db.get(fanuc_file).text) {
        Ok(p) => p,
        Err(e) => {
            return failed(db, vec![Diagnostic::error("NC539", format!("bad `nctrans: probe` header line: {e}"))])
        }
    };
    // And the same interrupt inputs (`nctrans: interrupt`).
    let interrupts = match crate::eval::header_interrupts(&db.get(fanuc_file).text) {
        Ok(p) => p,
        Err(e) => {
            return failed(db, vec![Diagnostic::error("NC638", format!("bad `nctrans: interrupt` header line: {e}"))])
        }
    };
    in_a.extend(spec.extra_fanuc);
    in_b.extend(spec.extra_siemens);
    let files = tr
        .files
        .iter()
        .filter(|f| f.name != main.name)
        .map(|f| (f.program.clone(), path(&f.name), f.text.clone()))
        .collect();
    let emitted = Emitted { files, semantics: profiles.sinumerik.clone() };
    let reached = called::Reached::default();
    let a = Side {
        unit: fanuc.clone(),
        callees: reached.wrap(spec.fanuc_callees),
        run: RunOptions {
            inputs: in_a,
            max_steps,
            semantics: Some(profiles.fanuc.clone()),
            probes: probes.clone(),
            interrupts: interrupts.clone(),
            ..RunOptions::default()
        },
    };
    let b = Side {
        unit: parsed.unit,
        callees: Box::new(emitted),
        run: RunOptions {
            inputs: in_b,
            max_steps,
            semantics: Some(profiles.sinumerik.clone()),
            probes,
            interrupts,
            ..RunOptions::default()
        },
    };
    let mut report = check::check(&db, a, b);
    report.called = reached.names();
    report
}
