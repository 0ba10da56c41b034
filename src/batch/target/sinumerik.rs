//! What a batch job to Sinumerik does as its own (`jobs::Target`): one FANUC file
//! in, one Siemens file per program out (`NAME.MPF` for main programs, `NAME.SPF` for
//! called ones), named by the batch's program map, each proved by running it against its
//! FANUC source.
//!
//! A FANUC macro's Siemens form (its `PROC` parameters and is-set flags, `VAR` parameters for
//! M98 subprograms) depends on how the program is called. The translator learns that from
//! the calls among the programs it is given, so every job also gives it the calls the rest
//! of the library makes to its programs (as a stand-in caller program whose output is
//! dropped): the macro's own job and every caller's job then see the same calls and write
//! the same `PROC` line, so each call in one output file fits the program in another.

use crate::batch::jobs::{Input, Job, LoadedFile, Prepared, Target, Verified};
use crate::batch::streamed::{self, Here, Side, Staged, Streams, Translated};
use crate::batch::{discover, maps, BatchContext, DiagRecord, InputFile};
use crate::batch::{streamed_calls, streamed_macro::route};
use crate::check::CheckReport;
use crate::config::Unsupported;
use crate::diag::Diagnostic;
use crate::dialect::{Dialect, ParseOptions, Semantics};
use crate::eval::calls::CalleeSource;
use crate::eval::{header_inputs, NoCallees};
use crate::ir::{CallKind, Unit};
use crate::read::LineEnding;
use crate::span::{FileId, SourceDb};
use crate::stream::verify::ReadBack;
use crate::translate::called::{self as verify_called, number_of, RunSettings};
use crate::translate::called::{parse_all, siemens_inputs, MemCallees};
use crate::translate::library::ProgKey;
use crate::translate::to_sinumerik::{self as ts, Options, OutFile, Translation, UnsupportedPolicy, VarMapRule};
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The name the stand-in caller program is shown under in diagnostics.
const CALLERS_FILE: &str = "(calls from other files of the library)";

/// The Sinumerik target of a batch.
pub struct Sinumerik;

impl Job<Sinumerik> {
    /// The translation's options for `file`, from the batch (its maps and the library's
    /// common variables).
    pub(crate) fn options(&self, ctx: &BatchContext, file: &InputFile) -> Result<Options, String> {
        let mut var_map = Vec::new();
        for r in &ctx.maps.var_rules {
            var_map.push(VarMapRule::parse(r).map_err(|e| format!("variables.to_sinumerik: {e}"))?);
        }
        let s = &self.settings;
        var_map.extend(library_places(&ctx.library.commons, &var_map, s.sinumerik.r_param_count));
        let flag_places = library_flag_places(&ctx.library.commons, &var_map, s.sinumerik.r_param_count);
        Ok(Options {
            source: s.fanuc.clone(),
            target: s.sinumerik.clone(),
            var_map,
            program_map: ctx.maps.siemens_names(),
            unsupported: match s.unsupported {
                Unsupported::Error => UnsupportedPolicy::Error,
                Unsupported::Warn => UnsupportedPolicy::Warn,
            },
            main_name: maps::siemens_name(&stem(file)),
            flag_places,
            after_end: BTreeSet::new(),
            specialise_callers: ctx.options.specialise_callers,
        })
    }
}

/// Places for the is-set flags of the library's common variables, fixed over the whole
/// library so a program that leaves `#500` vacant and another that tests it use the same
/// flag: from the highest R parameter down, past every R a rule or a default place of any
/// common variable of the library takes. Commons left without a place (no R free) are placed
/// per file by the translator, as in single-file translation.
fn library_flag_places(commons: &BTreeSet<u32>, rules: &[VarMapRule], count: u32) -> BTreeMap<u32, u32> {
    let mut taken = rule_places(rules, count);
    for &n in commons.iter().filter(|&&n| !covered(rules, n)) {
        taken.extend(default_r(n));
    }
    let mut free = (0..count).rev().filter(|r| !taken.contains(r));
    commons.iter().map_while(|&n| free.next().map(|r| (n, r))).collect()
}

/// Places for the common variables that have no default R parameter (#200..#499,
/// #800..#999, or a default outside the R range or under a rule), fixed over the whole
/// library: the translator would otherwise place them per file, and two files would not
/// share them. Each gets the lowest R parameter no rule and no default place of any common
/// variable of the library uses.
fn library_places(commons: &BTreeSet<u32>, rules: &[VarMapRule], count: u32) -> Vec<VarMapRule> {
    let mut taken = rule_places(rules, count);
    let mut leftovers = Vec::new();
    for &n in commons.iter().filter(|&&n| !covered(rules, n)) {
        match default_r(n) {
            Some(r) if r < count && !taken.contains(&r) => {
                taken.insert(r);
            }
            _ => leftovers.push(n),
        }
    }
    let mut out = Vec::new();
    for n in leftovers {
        // None left: the translator reports it (NC350) in the files that use it.
        let Some(r) = (0..count).find(|r| !taken.contains(r)) else { break };
        taken.insert(r);
        out.push(VarMapRule { from: n, to: n, r_start: r });
    }
    out
}

/// Whether a rule places common variable `n`.
fn covered(rules: &[VarMapRule], n: u32) -> bool {
    rules.iter().any(|r| r.from <= n && n <= r.to)
}

/// The R parameters the rules place variables in (up to `count`).
fn rule_places(rules: &[VarMapRule], count: u32) -> BTreeSet<u32> {
    rules.iter().flat_map(|r| r.r_start..=r.r_start.saturating_add(r.to - r.from).min(count)).collect()
}

/// The default R parameter of common variable `n` (`#500` → R0, `#100` → R100).
fn default_r(n: u32) -> Option<u32> {
    match n {
        500..=799 => Some(n - 500),
        100..=199 => Some(n),
        _ => None,
    }
}

fn stem(file: &InputFile) -> String {
    file.rel.file_stem().and_then(|x| x.to_str()).unwrap_or("MAIN").to_string()
}

/// The programs of this file whose number the library gives to an earlier file. A copy of
/// that program (the same text, as a Sinumerik → FANUC batch writes a subprogram into every
/// caller's file) is the same program: it keeps the map's name and only the earlier file
/// writes it. A different program of the same number is named after this file (`STEM`, or
/// `STEM_O2001` after the first program) and a warning says so: calls elsewhere in the
/// library reach the earlier one. Returns the numbers not to write, and the notes.
fn duplicates(
    ctx: &BatchContext,
    file: &InputFile,
    main: &LoadedFile,
    opts: &mut Options,
) -> (BTreeSet<u32>, Vec<DiagRecord>) {
    let mut notes = Vec::new();
    let mut copies = BTreeSet::new();
    let base = maps::siemens_name(&stem(file));
    for (i, p) in main.unit.programs.iter().enumerate() {
        let Some(n) = number_of(p) else { continue };
        let Some(first) = ctx.library.programs.get(&ProgKey::Number(n)) else { continue };
        if first.file == file.index {
            continue;
        }
        let Some(other) = ctx.files.get(first.file) else { continue };
        let other_name = crate::batch::rel_string(&other.rel);
        if i > 0 && ctx.library.is_canonical(&ProgKey::Number(n), file.index) {
            let mut d = DiagRecord::error(
                "NC607",
                format!("O{n:04} is the same program as in {other_name}; it is written from there"),
            );
            d.severity = "note";
            notes.push(d);
            copies.insert(n);
            continue;
        }
        let name = if i == 0 { base.clone() } else { format!("{base}_O{n:04}") };
        let mut d = DiagRecord::error(
            "NC607",
            format!("O{n:04} is also defined in {other_name}, which calls in the library reach; this one is written as {name}"),
        );
        d.severity = "warning";
        notes.push(d);
        opts.program_map.insert(n, name);
    }
    (copies, notes)
}

/// The stand-in caller: every call the files outside this job make to the job's programs,
/// one block each, with constant arguments for the surely-set letters and a local (maybe
/// vacant) for the others. `None` when there is no such call.
fn callers_text(ctx: &BatchContext, job: &[(usize, &Unit)]) -> Option<String> {
    // The job's programs that calls elsewhere reach: the first definition or a copy of it
    // (each number counts once, from the first job file that defines it).
    let mut defined: BTreeSet<u32> = BTreeSet::new();
    let mut canonical: BTreeSet<u32> = BTreeSet::new();
    for (f, unit) in job {
        for n in unit.programs.iter().filter_map(number_of) {
            if defined.insert(n) && ctx.library.is_canonical(&ProgKey::Number(n), *f) {
                canonical.insert(n);
            }
        }
    }
    let job_files: BTreeSet<usize> = job.iter().map(|(f, _)| *f).collect();
    let mut blocks: BTreeSet<String> = BTreeSet::new();
    for c in &ctx.library.calls {
        let ProgKey::Number(n) = c.target else { continue };
        if job_files.contains(&c.file) || !canonical.contains(&n) {
            continue;
        }
        // A caller with a different program of that number of its own calls that one.
        let own_copy = ctx.library.files.get(c.file).is_some_and(|f| f.programs.contains(&Some(c.target.clone())));
        if own_copy && !ctx.library.is_canonical(&c.target, c.file) {
            continue;
        }
        let args: String = c
            .given
            .iter()
            .map(|g| if g.sure { format!(" {}0.", g.letter) } else { format!(" {}#1", g.letter) })
            .collect();
        match c.kind {
            CallKind::G65 => blocks.insert(format!("G65 P{n}{args}")),
            CallKind::G66 => blocks.insert(format!("G66 P{n}{args}\nG67")),
            CallKind::M98 => blocks.insert(format!("M98 P{n}")),
            _ => false,
        };
    }
    if blocks.is_empty() {
        return None;
    }
    // A number no program of the library has: the stand-in is never called, and no name of
    // the map is given to it.
    let number =
        (1..=99_999).find(|k| !defined.contains(k) && !ctx.library.programs.contains_key(&ProgKey::Number(*k)))?;
    let mut text = format!("O{number}\n");
    for b in blocks {
        text.push_str(&b);
        text.push('\n');
    }
    text.push_str("M30\n");
    Some(text)
}

/// The stand-in caller of a job (`callers_text`) added to `db` and parsed with the job's
/// FANUC profile: its file and unit; `None` when there is no call to stand in for or it does
/// not parse (the job goes without it). Shared by the whole job and the streamed one
/// (`streamed_calls`), which must translate with the same stand-in.
pub(crate) fn stand_in(
    db: &mut SourceDb,
    ctx: &BatchContext,
    job: &[(usize, &Unit)],
    fanuc: &crate::dialect::Semantics,
) -> Option<(FileId, Unit)> {
    let text = callers_text(ctx, job)?;
    let id = db.add(CALLERS_FILE, text);
    let parsed = crate::parse(db, id, Dialect::Fanuc, &ParseOptions { semantics: fanuc.clone() });
    (!crate::diag::has_errors(&parsed.diags)).then_some((id, parsed.unit))
}

/// The names a file's translation used: its programs (`O` number → Siemens name, for the
/// numbered ones) and the variables of those programs and the common ones.
pub(crate) fn used_names(programs: &[(Option<u32>, &str)], symbols: &ts::SymbolMap) -> maps::Used {
    let mut used = maps::Used::default();
    for (number, name) in programs {
        if let Some(n) = number {
            used.programs.insert(ProgKey::Number(*n), ProgKey::Name(name.to_string()));
        }
    }
    let own_names: BTreeSet<&str> = programs.iter().map(|(_, name)| *name).collect();
    for v in &symbols.vars {
        let key = match &v.program {
            Some(p) if own_names.contains(p.as_str()) => format!("{p}.{}", v.fanuc),
            Some(_) => continue,
            None => v.fanuc.clone(),
        };
        used.variables.insert(key.clone(), v.siemens.clone());
        if let Some(flag) = &v.flag {
            used.variables.insert(format!("{key} is set"), flag.clone());
        }
    }
    used
}

impl Target for Sinumerik {
    const DIALECT: Dialect = Dialect::Sinumerik;
    const NAME: &'static str = "Sinumerik";
    const ONE_FILE: bool = false;

    fn prepare(job: &Job<Sinumerik>, input: &mut Input, _source: Semantics) -> Result<Prepared, String> {
        let (ctx, file, main, subs) = (input.ctx, input.file, &input.main, &input.subs);
        let mut opts = job.options(ctx, file)?;
        opts.after_end = std::iter::once(main).chain(subs.iter()).flat_map(|l| l.after_end.iter().copied()).collect();
        let (copies, notes) = duplicates(ctx, file, main, &mut opts);
        // The programs of the job and the calls the rest of the library makes to them.
        let mut job_files: Vec<usize> = vec![file.index];
        job_files.extend(ctx.library.callee_files(file.index));
        let all = std::iter::once(main).chain(subs.iter()).map(|l| &l.unit);
        let units: Vec<(usize, &Unit)> = job_files.iter().copied().zip(all).collect();
        let stand_in = stand_in(&mut input.db, ctx, &units, &job.settings.fanuc);
        let eol = job.settings.line_ending(main.loaded.line_ending);
        let opts = crate::translate::Options::to_sinumerik(opts, eol);
        Ok(Prepared { opts, notes, copies, stand_in })
    }

    fn used(t: &Translation, own: FileId) -> maps::Used {
        let own_programs: Vec<(Option<u32>, &str)> =
            t.files.iter().filter(|f| f.source == own).map(|f| (f.fanuc_number, f.program.as_str())).collect();
        used_names(&own_programs, t.symbols.sinumerik())
    }

    fn refused(t: &Translation, own_diags: &[Diagnostic], own: FileId) -> Option<usize> {
        let marked: usize =
            t.files.iter().filter(|f| f.source == own).map(|f| f.text.matches("NCTRANS UNSUPPORTED").count()).sum();
        (t.has_errors() || marked > 0).then(|| own_diags.iter().filter(|d| d.is_error()).count().max(marked))
    }

    fn output(rel: &Path, f: &OutFile) -> PathBuf {
        discover::sinumerik_output(rel, &f.program, !f.main)
    }
}

/// The runs of the macros a FANUC file calls by G65/G66 among its own programs after the
/// first (file `file`, parsed as `unit`, translated in `tr`): each alone, as every path runs
/// a called macro (`translate::called::macro_runs`: with the arguments of the library's call
/// sites, then each of them vacant unless `--specialise-callers`, behind its gate). A macro
/// only other files call runs as a main of its own in `verify`. Shared by the whole job and
/// the streamed one (`streamed_calls::macro_runs`), so both give the file one verdict.
pub(crate) fn in_file_macro_runs(
    db: &SourceDb,
    ctx: &BatchContext,
    file: &InputFile,
    unit: &Unit,
    tr: &Translation,
    settings: &RunSettings,
    callees: &dyn Fn() -> Box<dyn CalleeSource + Send>,
) -> Vec<(String, CheckReport)> {
    let each_vacant = !ctx.options.specialise_callers;
    verify_called::macro_runs_in(db, (&ctx.library, file.index, each_vacant), unit, tr, settings, callees)
}

/// What a streamed translation to Sinumerik keeps for its proof and its other outputs.
pub struct Kept {
    /// The main program's name and the translation's symbol map.
    program: String,
    symbols: ts::SymbolMap,
    /// The callees' units (the FANUC side's), the skeleton they were loaded for, and the
    /// translation's other files (the file's own subprograms, the callees').
    units: Vec<Unit>,
    skeleton: Option<Unit>,
    subs: Vec<OutFile>,
    /// Translated with callees (then served to both sides).
    calls: bool,
}

impl Streams for Sinumerik {
    const SCRATCH: &'static str = "batch.utf8.mpf";
    const EXCLUDE: crate::check::Exclude = crate::check::Exclude { messages: false };
    /// The callee files of a main that calls subprograms (its own after M30, other files').
    type With = Option<Vec<usize>>;
    type Kept = Kept;

    const SCRATCH_DECODED: bool = true;

    fn with((_, ctx, file): Here<'_, Sinumerik>) -> Option<Option<Vec<usize>>> {
        Some(if streamed::streamable(file, ctx) { None } else { Some(streamed_calls::callees(file, ctx)?) })
    }

    /// The translator writes the byte-order mark itself.
    fn translate(
        h: Here<'_, Sinumerik>,
        callees: &Option<Vec<usize>>,
        path: &Path,
        first_eol: LineEnding,
        into: &Path,
        _bom: bool,
    ) -> Option<Translated<Kept>> {
        let (job, ctx, file) = h;
        let opts = job.options(ctx, file).ok()?;
        let eol = job.settings.line_ending(first_eol);
        let mut units: Vec<Unit> = Vec::new();
        let mut skeleton: Option<Unit> = None;
        use crate::stream::{segmented::sinumerik as seg, target::sinumerik as sts};
        // The straight-line stream, then the segmented one (each writes the mark itself);
        // with calls only the segmented one with the callees.
        let (done, subs) = match callees {
            None => match route(into, false, |w| sts::to_sinumerik(path, &opts, eol, w, None)).ok()? {
                Some(done) => (done, Vec::new()),
                None => (route(into, false, |w| seg::to_sinumerik(path, &opts, eol, w, None)).ok()??, Vec::new()),
            },
            Some(c) => {
                // The stand-in caller (if any) is translated with them, as the whole job does,
                // but neither run nor written.
                let mut load = |main: &Unit| {
                    let stand_in;
                    skeleton = Some(main.clone());
                    (units, stand_in) = streamed_calls::load(job, ctx, file, main, c)?;
                    Ok(units.iter().cloned().chain(stand_in).collect())
                };
                let stand_in = streamed_calls::stand_in_id(c);
                let f = |w: &mut dyn std::io::Write| {
                    seg::to_sinumerik_with_stand_in(path, &opts, eol, &mut load, stand_in, w, None)
                };
                route(into, false, f).ok()??
            }
        };
        let programs: Vec<(Option<u32>, &str)> = std::iter::once((done.fanuc_number, done.program.as_str()))
            .chain(streamed_calls::own(&subs).map(|f| (f.fanuc_number, f.program.as_str())))
            .collect();
        let used = used_names(&programs, &done.symbols);
        let out_dir = crate::batch::rel_string(file.rel.parent().unwrap_or(Path::new("")));
        let shown = if out_dir.is_empty() { done.file_name.clone() } else { format!("{out_dir}/{}", done.file_name) };
        Some(Translated {
            index: done.index,
            diags: done.diags,
            used,
            rel_out: discover::sinumerik_output(&file.rel, &done.program, false),
            shown,
            with_calls: callees.is_some(),
            kept: Kept {
                program: done.program,
                symbols: done.symbols,
                units,
                skeleton,
                subs,
                calls: callees.is_some(),
            },
        })
    }

    fn read_back(job: &Job<Sinumerik>) -> ParseOptions {
        ParseOptions { semantics: job.settings.sinumerik.clone() }
    }

    fn unreadable(e: ReadBack, files: &[(FileId, &str, &Path)]) -> Verified {
        let report = match e {
            ReadBack::Diags(mut d) => {
                d.push(Diagnostic::error("NC372", "the translation does not read back as Sinumerik"));
                streamed::failed(d)
            }
            ReadBack::Unreadable(e) => {
                streamed::failed(vec![Diagnostic::error("NC372", format!("the translation cannot be read back: {e}"))])
            }
        };
        streamed::verdict(vec![(String::new(), report)], files)
    }

    /// As `Job<Sinumerik>::verify` runs a file's only program: its header inputs and
    /// `--set`; the callees as the whole job's verifier serves them: the FANUC units
    /// loaded, the translation's other files under the names it shows them.
    fn sides(
        job: &Job<Sinumerik>,
        k: &Kept,
        (a, b): (&str, &str),
        out_dir: &str,
    ) -> Result<[Side; 2], Box<CheckReport>> {
        let s = &job.settings;
        let mut fanuc = s.set.clone();
        let symbols = crate::translate::Symbols::Sinumerik(k.symbols.clone());
        let tr = Translation { files: vec![], symbols, diags: vec![], unsupported: 0 };
        let siemens = siemens_inputs(&tr, &k.program, &fanuc);
        fanuc.retain(|x| x.trim_start().starts_with('#'));
        let (mut a, mut b) = match (header_inputs(a), header_inputs(b)) {
            (Ok(a), Ok(b)) => (a, b),
            (Err(e), _) | (_, Err(e)) => {
                let d = Diagnostic::error("NC407", format!("bad `nctrans: set` header line: {e}"));
                return Err(Box::new(streamed::failed(vec![d])));
            }
        };
        a.extend(parse_all(&fanuc));
        b.extend(parse_all(&siemens));
        let (a_callees, b_callees): (Box<dyn CalleeSource + Send>, Box<dyn CalleeSource + Send>) = if k.calls {
            let shown = |n: &str| if out_dir.is_empty() { n.to_string() } else { format!("{out_dir}/{n}") };
            let files = k.subs.iter().map(|f| (f.program.clone(), shown(&f.name), f.text.clone())).collect();
            let emitted = ts::verify::Emitted { files, semantics: s.sinumerik.clone() };
            (Box::new(MemCallees(k.units.clone())), Box::new(emitted))
        } else {
            (Box::new(NoCallees), Box::new(NoCallees))
        };
        Ok([
            (streamed::run_options(a, s.max_steps, &s.fanuc), a_callees),
            (streamed::run_options(b, s.max_steps, &s.sinumerik), b_callees),
        ])
    }

    fn more_runs(h: Here<'_, Sinumerik>, k: &Kept, header: &str, out_dir: &str) -> Option<Vec<(String, CheckReport)>> {
        let Some(main) = &k.skeleton else { return Some(Vec::new()) };
        streamed_calls::macro_runs(h.0, h.1, h.2, (main, header), &k.units, (&k.subs, &k.symbols), out_dir)
    }

    fn stage_more(h: Here<'_, Sinumerik>, k: &Kept, out: &'static encoding_rs::Encoding, bom: bool) -> Option<Staged> {
        streamed_calls::stage_own(h.2, h.1, &k.subs, out, bom)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn commons_without_a_default_place_get_one_place_for_the_library() {
        let commons: BTreeSet<u32> = [100, 500, 501, 801, 802, 950].into_iter().collect();
        let rules = vec![VarMapRule::parse("#950=R2").unwrap()];
        let places = library_places(&commons, &rules, 300);
        // R0 and R1 are the default places of #500 and #501, R2 is the rule's.
        assert_eq!(
            places,
            [VarMapRule { from: 801, to: 801, r_start: 3 }, VarMapRule { from: 802, to: 802, r_start: 4 }]
        );
        // Placed per file, #802 would take R0 in a file without #500: not what the library
        // gives it, so the two files would not share R0.
        let only: BTreeSet<u32> = [802].into_iter().collect();
        assert_eq!(library_places(&only, &[], 300), [VarMapRule { from: 802, to: 802, r_start: 0 }]);
        assert!(library_places(&commons, &rules, 2).len() < 2, "no R left past the count");
    }

    #[test]
    fn is_set_flags_get_one_place_for_the_library() {
        use crate::dialect::{Dialect, ParseOptions};
        use crate::read::LineEnding;
        // Program A tests only #501's vacancy; B tests #500's and #501's. Placed per file,
        // #501's flag would be R299 in A and R298 in B.
        let a = "%\nO1\nIF[#501EQ#0]GOTO10\nG0X1.\nN10M30\n%\n";
        let b = "%\nO2\nIF[#500EQ#0]GOTO10\nIF[#501EQ#0]GOTO10\nG0X1.\nN10M30\n%\n";
        let flag_of = |text: &str, places: &BTreeMap<u32, u32>, n: u32| {
            let mut db = crate::span::SourceDb::new();
            let f = db.add("t.nc", text);
            let parsed = crate::parse(&db, f, Dialect::Fanuc, &ParseOptions::for_dialect(Dialect::Fanuc));
            let opts = Options { flag_places: places.clone(), ..Options::default() };
            let t = crate::translate::to_sinumerik::translate(&[&parsed.unit], &opts, LineEnding::Lf);
            t.symbols.sinumerik().common(n).and_then(|e| e.flag.clone())
        };
        let none = BTreeMap::new();
        assert_ne!(flag_of(a, &none, 501), flag_of(b, &none, 501), "per file the places differ");
        let commons: BTreeSet<u32> = [500, 501].into_iter().collect();
        let places = library_flag_places(&commons, &[], 300);
        assert_eq!(places, [(500, 299), (501, 298)].into_iter().collect::<BTreeMap<_, _>>());
        assert_eq!(flag_of(a, &places, 501).as_deref(), Some("R298"));
        assert_eq!(flag_of(b, &places, 501).as_deref(), Some("R298"));
        assert_eq!(flag_of(b, &places, 500).as_deref(), Some("R299"));
        // Default places of the library's commons are never flag places.
        let low: BTreeSet<u32> = [798, 799].into_iter().collect();
        let p = library_flag_places(&low, &[], 300);
        assert!(p.values().all(|r| *r < 298), "{p:?}");
    }
}
