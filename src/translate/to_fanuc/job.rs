//! What a batch job to FANUC does as its own (`batch::jobs::Target`): the options from the
//! batch's maps, one output file named after the input, the names used, and the proof with
//! the argument vectors the library's callers pass.

use crate::batch::jobs::{combine, Input, Job, JobSettings, MemCallees, Prepared, Target, Verified};
use crate::batch::library::{ArgValue, ProgKey};
use crate::batch::{discover, maps, BatchContext, DiagRecord, FileOutcome, InputFile, Status};
use crate::check::{self, Side};
use crate::config::{Comments, Unsupported};
use crate::diag::{self, Diagnostic};
use crate::dialect::fanuc::emit::CommentMode;
use crate::dialect::{Dialect, Semantics};
use crate::eval::{self, NoCallees, RunOptions};
use crate::ir::{ProgName, Unit};
use crate::lower::to_fanuc::{varmap, UnsupportedPolicy};
use crate::read::LineEnding;
use crate::span::{FileId, SourceDb};
use crate::translate::{self, OutFile, TranslateOptions, Translation};
use std::path::{Path, PathBuf};

/// The FANUC target of a batch.
pub struct Fanuc;

impl Job<Fanuc> {
    /// The translation's options for `file`, whose line ending is `eol`, from the batch.
    pub(crate) fn options(
        &self,
        ctx: &BatchContext,
        file: &InputFile,
        eol: LineEnding,
    ) -> Result<TranslateOptions, String> {
        let mut var_rules = Vec::new();
        for r in &ctx.maps.var_rules {
            var_rules.extend(varmap::parse_rules(r).map_err(|e| format!("variables.to_fanuc: {e}"))?);
        }
        let s = &self.settings;
        Ok(TranslateOptions {
            unsupported: match s.unsupported {
                Unsupported::Error => UnsupportedPolicy::Error,
                Unsupported::Warn => UnsupportedPolicy::Warn,
            },
            var_rules,
            tool_map: ctx.maps.tools.clone(),
            program_map: ctx.maps.fanuc_numbers(),
            program_number: None,
            comments: match s.comments {
                Comments::Keep => CommentMode::Keep,
                Comments::Ascii => CommentMode::Ascii,
                Comments::Drop => CommentMode::Drop,
            },
            number_blocks: s.number_blocks,
            line_ending: s.line_ending(eol),
            compound_conditions: s.compound_conditions,
            target: s.fanuc.clone(),
            source: s.sinumerik.clone(),
            main_name: file.rel.file_stem().and_then(|x| x.to_str()).unwrap_or("MAIN").to_ascii_uppercase(),
            source_name: file.rel.file_name().and_then(|x| x.to_str()).unwrap_or("").to_string(),
            main_is_sub: file.rel.extension().is_some_and(|e| e.eq_ignore_ascii_case("spf")),
        })
    }
}

impl Target for Fanuc {
    const DIALECT: Dialect = Dialect::Fanuc;
    const NAME: &'static str = "FANUC";

    fn streamed(job: &Job<Fanuc>, file: &InputFile, ctx: &BatchContext) -> Option<FileOutcome> {
        crate::batch::streamed::to_fanuc(job, file, ctx)
    }

    fn prepare(job: &Job<Fanuc>, input: &mut Input, source: Semantics) -> Result<Prepared, String> {
        let mut opts = job.options(input.ctx, input.file, input.main.loaded.line_ending)?;
        opts.source = source;
        Ok(Prepared::new(translate::Options::to_fanuc(opts)))
    }

    fn used(t: &Translation, _own: FileId) -> maps::Used {
        used_names(t.symbols.fanuc())
    }

    fn refused(t: &Translation, _own_diags: &[Diagnostic], _own: FileId) -> Option<usize> {
        // The FANUC target counts the constructs refused under the error policy too.
        (!t.ok())
            .then(|| t.diags.iter().filter(|d| d.is_error() || d.code.starts_with("NC3")).count().max(t.unsupported))
    }

    fn output(rel: &Path, _f: &OutFile) -> PathBuf {
        discover::fanuc_output(rel)
    }

    fn verify(job: &Job<Fanuc>, input: &mut Input, t: &Translation, p: &Prepared) -> Verified {
        let main = &input.main.unit;
        let key = main.programs.first().map(|p0| match &p0.name {
            Some(ProgName::Name(n)) => ProgKey::Name(n.to_ascii_uppercase()),
            _ => ProgKey::Name(p.opts.fanuc.main_name.clone()),
        });
        let vectors = key.map(|k| input.ctx.library.arg_vectors(&k)).unwrap_or_default();
        let out_name = crate::batch::rel_string(&discover::fanuc_output(&input.file.rel));
        let subs: Vec<&Unit> = input.subs.iter().map(|l| &l.unit).collect();
        verify(&job.settings, &mut input.db, main, &subs, t, &out_name, &vectors)
    }
}

/// The names a translation to FANUC used: programs, tools, variables.
pub fn used_names(map: &translate::SymbolMap) -> maps::Used {
    let mut used = maps::Used::default();
    for (name, n) in &map.programs {
        used.programs.insert(ProgKey::Name(name.clone()), ProgKey::Number(*n));
    }
    used.tools = map.tools.clone();
    for m in &map.vars {
        let key = match &m.program {
            Some(p) => format!("{p}.{}", m.source),
            None => m.source.clone(),
        };
        used.variables.insert(key, format!("#{}", m.number));
    }
    used
}

/// Parses the output back as FANUC (it must be valid FANUC), then runs both programs:
/// once with the program's own inputs, and once per argument vector its callers use.
fn verify(
    s: &JobSettings,
    db: &mut SourceDb,
    main: &Unit,
    subs: &[&Unit],
    t: &Translation,
    out_name: &str,
    vectors: &[Vec<ArgValue>],
) -> Verified {
    let parsed = translate::reparse(db, t, out_name);
    if diag::has_errors(&parsed.diags) {
        return Verified {
            status: Status::Diverged,
            summary: "the output does not parse as FANUC (a bug in nctrans)".into(),
            events: None,
            excluded: Default::default(),
            diagnostics: DiagRecord::from_diags(db, &parsed.diags),
        };
    }
    // The Siemens side starts with R parameters 0; their FANUC homes are set to 0 too
    // (FANUC commons may be vacant), like `nctrans --to fanuc` does.
    let map = t.symbols.fanuc();
    let mut fanuc_inputs: Vec<String> = translate::to_fanuc::r_param_homes(map);
    fanuc_inputs.extend(map.gud_seeds.iter().map(|(n, v)| format!("#{n}={v}")));
    let sinumerik = translate::to_fanuc::source_semantics(t, Some(&s.sinumerik)).unwrap_or_else(|| s.sinumerik.clone());
    let params = main.programs.first().map(|p| p.params.clone()).unwrap_or_default();
    let letters = crate::lower::to_fanuc::words::param_letters(params.len()).unwrap_or_default();
    let mut runs = Vec::new();
    let mut cases: Vec<(String, Vec<(usize, String)>)> = vec![(String::new(), vec![])];
    for (k, v) in vectors.iter().enumerate() {
        let vals = v
            .iter()
            .filter_map(|a| params.iter().position(|p| p.name.eq_ignore_ascii_case(&a.var)).map(|i| (i, a.to_set())))
            .collect();
        cases.push((format!(" (with the arguments of call site {})", k + 1), vals));
    }
    for (label, vals) in cases {
        let mut a_in = Vec::new();
        let mut b_in = std::mem::take(&mut fanuc_inputs);
        fanuc_inputs = b_in.clone();
        // Parameters not passed are 0 on Siemens; the argument locals get the same value.
        for (i, (_, var)) in letters.iter().enumerate() {
            if params.get(i).is_some_and(|p| p.by_ref) {
                continue;
            }
            let given = vals.iter().find(|(j, _)| *j == i);
            let value = given.map_or("0".to_string(), |(_, s)| s.split_once('=').map_or("0", |x| x.1).to_string());
            b_in.push(format!("#{var}={value}"));
            if let Some((_, s)) = given {
                a_in.push(s.clone());
            }
        }
        b_in.extend(translate::var_param_inputs(&params, map));
        a_in.extend(s.set.iter().cloned());
        b_in.extend(s.set.iter().filter(|s| s.trim_start().starts_with('#')).cloned());
        let parse_all = |v: &[String]| v.iter().filter_map(|s| eval::parse_input(s).ok()).collect::<Vec<_>>();
        let run = |inputs, sem: &Semantics| RunOptions {
            max_steps: s.max_steps,
            inputs,
            semantics: Some(sem.clone()),
            probe_contact: None,
            expand_cycles: None,
        };
        let source = translate::align_source(main, map);
        let callees = MemCallees(subs.iter().map(|u| translate::align_source(u, map)).collect());
        let a = Side { unit: source, callees: Box::new(callees), run: run(parse_all(&a_in), &sinumerik) };
        let b = Side { unit: parsed.unit.clone(), callees: Box::new(NoCallees), run: run(parse_all(&b_in), &s.fanuc) };
        runs.push((label, check::check_excluding(db, a, b, translate::EXCLUDE)));
    }
    combine(runs)
}
