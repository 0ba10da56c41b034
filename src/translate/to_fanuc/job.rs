//! What a batch job to FANUC does as its own (`batch::jobs::Target`): the options from the
//! batch's maps, one output file named after the input, the names used, and the proof with
//! the argument vectors the library's callers pass.

use crate::batch::jobs::{combine, Input, Job, Prepared, Target, Verified};
use crate::batch::library::ProgKey;
use crate::batch::{discover, maps, BatchContext, DiagRecord, FileOutcome, InputFile, Status};
use crate::config::{Comments, Unsupported};
use crate::diag::Diagnostic;
use crate::dialect::fanuc::emit::CommentMode;
use crate::dialect::{Dialect, Semantics};
use crate::ir::Unit;
use crate::lower::to_fanuc::{varmap, UnsupportedPolicy};
use crate::read::LineEnding;
use crate::span::FileId;
use crate::translate::to_sinumerik::verify::Profiles;
use crate::translate::{self, InLibrary, OutFile, TranslateOptions, Translation};
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
        let (file, ctx, s) = (input.file, input.ctx, &job.settings);
        let out_name = crate::batch::rel_string(&discover::fanuc_output(&file.rel));
        let units: Vec<&Unit> = std::iter::once(&input.main).chain(&input.subs).map(|l| &l.unit).collect();
        let opts = translate::VerifyOptions {
            max_steps: s.max_steps,
            profiles: Some(Profiles { fanuc: s.fanuc.clone(), sinumerik: s.sinumerik.clone() }),
            set: &s.set,
            library: Some(InLibrary { library: &ctx.library, file: file.index, main_name: &p.opts.fanuc.main_name }),
            each_vacant: !ctx.options.specialise_callers,
        };
        let v = translate::verify(&mut input.db, &units, t, &out_name, opts);
        if !v.unreadable.is_empty() {
            return Verified {
                status: Status::Diverged,
                summary: "the output does not parse as FANUC (a bug in nctrans)".into(),
                events: None,
                excluded: Default::default(),
                diagnostics: DiagRecord::from_diags(&input.db, &v.unreadable),
            };
        }
        combine(v.runs)
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
