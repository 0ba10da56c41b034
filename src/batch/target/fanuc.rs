//! What a batch job to FANUC does as its own (`jobs::Target`): the options from the
//! batch's maps, one output file named after the input, the names used, and the proof with
//! the argument vectors the library's callers pass.

use crate::batch::jobs::{self, Input, Job, JobSettings, Prepared, Target, Verified};
use crate::batch::streamed::{self, Here, Side, Streams, Translated};
use crate::batch::{discover, maps, streamed_macro, BatchContext, InputFile, Status};
use crate::check::CheckReport;
use crate::config::{Comments, Unsupported};
use crate::diag::Diagnostic;
use crate::dialect::fanuc::emit::CommentMode;
use crate::dialect::{Dialect, ParseOptions, Semantics};
use crate::eval::{CalleeSource, NoCallees};
use crate::ir::Unit;
use crate::lower::to_fanuc::{varmap, UnsupportedPolicy};
use crate::read::LineEnding;
use crate::span::{FileId, SourceDb};
use crate::stream::{segmented::LoadCallees, verify::ReadBack, Fallback};
use crate::translate::called::{parse_all, MemCallees};
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
            l_numbers: ctx.library.l_numbers,
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

impl Streams for Fanuc {
    const SCRATCH: &'static str = "batch.utf8.nc";
    const EXCLUDE: crate::check::Exclude = translate::to_fanuc::EXCLUDE;
    /// The callee files of a Sinumerik main (none: it calls nothing).
    type With = Vec<usize>;
    /// The translation's symbol map and the callees' units (for the source side's runs).
    type Kept = (translate::to_fanuc::SymbolMap, Vec<Unit>);

    const SCRATCH_DECODED: bool = false;

    fn with(h: Here<'_, Fanuc>) -> Option<Vec<usize>> {
        // The stream reads the Siemens file with the default profile.
        if h.0.settings.sinumerik != Semantics::default_for(Dialect::Sinumerik) {
            return None;
        }
        streamed::streamable_with_callees(h.2, h.1)
    }

    fn translate(
        h: Here<'_, Fanuc>,
        callees: &Vec<usize>,
        path: &Path,
        eol: LineEnding,
        into: &Path,
        bom: bool,
    ) -> Option<Translated<Self::Kept>> {
        let (job, ctx, file) = h;
        let mut opts = job.options(ctx, file, eol).ok()?;
        // Read with the profile the whole job reads the file with: its library's global
        // user data and macros (definition files that do not read are the whole job's to say).
        opts.source = jobs::source_profile(&job.settings, &mut SourceDb::new(), file, Dialect::Sinumerik).ok()?;
        // The callees' units, kept for the verifier's source side.
        let mut subs: Vec<Unit> = Vec::new();
        let mut load = |_: &Unit| {
            subs = load_callees(ctx, callees, &opts.source)?;
            Ok(subs.clone())
        };
        let load: Option<LoadCallees<'_>> = if callees.is_empty() { None } else { Some(&mut load) };
        let (index, map, notes) = streamed_macro::to_fanuc_part(path, &opts, into, bom, load)?;
        let rel_out = discover::fanuc_output(&file.rel);
        Some(Translated {
            index,
            diags: notes,
            used: used_names(&map),
            shown: crate::batch::rel_string(&rel_out),
            rel_out,
            with_calls: !subs.is_empty(),
            kept: (map, subs),
        })
    }

    fn read_back(_: &Job<Fanuc>) -> ParseOptions {
        ParseOptions::for_dialect(Dialect::Fanuc)
    }

    fn unreadable(e: ReadBack, files: &[(FileId, &str, &Path)]) -> Verified {
        let diagnostics = match e {
            ReadBack::Diags(d) => streamed::records(&d, files),
            ReadBack::Unreadable(m) => {
                let out = files.get(1).map_or("", |f| f.1);
                vec![crate::batch::DiagRecord::error("NC603", format!("cannot read {out}: {m}"))]
            }
        };
        let summary = "the output does not parse as FANUC (a bug in nctrans)".to_string();
        Verified { status: Status::Diverged, summary, events: None, excluded: Default::default(), diagnostics }
    }

    /// As `Job<Fanuc>::verify` runs a program no file calls: `--set` on both sides, the
    /// mapped R parameters 0 on FANUC and the commons of global user data at their start
    /// values, the Siemens side with that data (`translate::to_fanuc::with_globals`,
    /// `proof_source`); the callees as the whole job's verifier serves them
    /// (aligned as it aligns them). The FANUC side finds the output's own O programs in the
    /// read-back index, as the whole job's finds them in the parsed output.
    fn sides(
        job: &Job<Fanuc>,
        (map, subs): &Self::Kept,
        _: (&str, &str),
        _: &str,
    ) -> Result<[Side; 2], Box<CheckReport>> {
        let s = &job.settings;
        let set = translate::to_fanuc::proof_sets(&s.set, map).0;
        let mut b_in = translate::to_fanuc::proof_homes(map);
        b_in.extend(translate::to_fanuc::fanuc_set_inputs(&set, map));
        let source_callees: Box<dyn CalleeSource + Send> = if subs.is_empty() {
            Box::new(NoCallees)
        } else {
            Box::new(MemCallees(subs.iter().map(|u| translate::to_fanuc::align_source(u, map)).collect()))
        };
        let source = translate::to_fanuc::with_globals(Some(&s.sinumerik), map);
        let source = translate::to_fanuc::proof_source(source, map).unwrap_or_else(|| s.sinumerik.clone());
        Ok([
            (streamed::run_options(parse_all(&set), s.max_steps, &source), source_callees),
            (streamed::run_options(parse_all(&b_in), s.max_steps, &s.fanuc), Box::new(NoCallees)),
        ])
    }
}

/// The units of the `callees` files, loaded as `jobs::load_with_callees` loads them for the
/// whole job (file ids from 1 up after the main's 0, the job's encoding and the main's
/// profile);
/// declines one with any diagnostic or a call `segmented::to_fanuc_with_subs` cannot take.
fn load_callees(ctx: &BatchContext, callees: &[usize], profile: &Semantics) -> Result<Vec<Unit>, Fallback> {
    let no = |why: &str| Fallback::NotStraight(why.into());
    let mut db = SourceDb::new();
    db.add("", String::new());
    let mut units = Vec::new();
    for &i in callees {
        let f = ctx.files.get(i).ok_or_else(|| no("a callee not in the batch"))?;
        let l = jobs::load(&mut db, f, Dialect::Sinumerik, ctx.options.encoding, profile).map_err(|e| no(&e))?;
        if !l.diags.is_empty() || !crate::stream::segmented::fanuc::calls_plain(&l.unit) {
            return Err(no("a callee with diagnostics or a call of another kind"));
        }
        units.push(l.unit);
    }
    Ok(units)
}
