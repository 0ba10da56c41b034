//! What a batch job to FANUC does as its own (`jobs::Target`): the options from the
//! batch's maps, one output file named after the input, the names used, and the proof with
//! the argument vectors the library's callers pass.

use crate::batch::jobs::{Input, Job, JobSettings, Prepared, Target};
use crate::batch::{discover, maps, BatchContext, FileOutcome, InputFile};
use crate::config::{Comments, Unsupported};
use crate::diag::Diagnostic;
use crate::dialect::fanuc::emit::CommentMode;
use crate::dialect::{Dialect, Semantics};
use crate::lower::to_fanuc::{varmap, UnsupportedPolicy};
use crate::read::LineEnding;
use crate::span::FileId;
use crate::translate::library::ProgKey;
use crate::translate::{self, to_fanuc::TranslateOptions, OutFile, Translation};
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
        Ok(TranslateOptions {
            var_rules,
            tool_map: ctx.maps.tools.clone(),
            program_map: ctx.maps.fanuc_numbers(),
            ..file_options(&self.settings, &file.rel, eol)
        })
    }
}

/// The options of a translation of the file `name`, written with line ending `eol`, under
/// the settings `s`, without maps (the batch's or the command line's).
pub fn file_options(s: &JobSettings, name: &Path, eol: LineEnding) -> TranslateOptions {
    TranslateOptions {
        unsupported: match s.unsupported {
            Unsupported::Error => UnsupportedPolicy::Error,
            Unsupported::Warn => UnsupportedPolicy::Warn,
        },
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
        main_name: name.file_stem().and_then(|x| x.to_str()).unwrap_or("MAIN").to_ascii_uppercase(),
        source_name: name.file_name().and_then(|x| x.to_str()).unwrap_or("").to_string(),
        main_is_sub: name.extension().is_some_and(|e| e.eq_ignore_ascii_case("spf")),
        ..TranslateOptions::default()
    }
}

impl Target for Fanuc {
    const DIALECT: Dialect = Dialect::Fanuc;
    const NAME: &'static str = "FANUC";
    const ONE_FILE: bool = true;

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
}

/// The names a translation to FANUC used: programs, tools, variables.
pub fn used_names(map: &translate::to_fanuc::SymbolMap) -> maps::Used {
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
