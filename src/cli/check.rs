//! `nctrans check A B`: runs two programs (either dialect) and reports whether their traces
//! agree; each side is streamed when it is large. With `--tool-map NAME=n` or `--map
//! nctrans-map.toml`, the names a translation used, so a Siemens program and its FANUC
//! translation can be checked again later exactly as the translation was verified (tool
//! names read as their T numbers, a `MSG` the translation wrote as a comment left out,
//! mapped R parameters starting at 0 on FANUC). A Siemens program checked against a FANUC
//! one starts the commons holding its global user data as the translation's proof does
//! (`gud`), and the verdict says so.

mod gud;
mod signals;

use super::args::{load_for_run, EvalOpts, InputOpts};
use super::stream::{self, Source};
use nctrans::diag;
use nctrans::dialect::Dialect;
use nctrans::ir::Unit;
use nctrans::span::SourceDb;
use nctrans::translate::{self, to_fanuc::SymbolMap};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;

/// The flags of `check` that name a translation's maps.
#[derive(clap::Args)]
pub struct MapOpts {
    /// Compare as the translation to FANUC was verified, with this tool name → T number
    /// (NAME=n, repeatable; wins over --map and nctrans.toml [tools]).
    #[arg(long = "tool-map", value_name = "NAME=N")]
    pub tool_map: Vec<String>,
    /// Compare as a translation that used this map (nctrans-map.toml of a batch): its tools
    /// and the variables R parameters went to.
    #[arg(long, value_name = "FILE")]
    pub map: Option<PathBuf>,
}

/// The translation's names, when a map was asked for (`None`: a plain check).
pub struct Names {
    tools: BTreeMap<String, u32>,
    /// FANUC variables R parameters were mapped to (`R1` → 501).
    r_vars: Vec<u32>,
    /// The map's `--var-map` rules (where global user data went).
    rules: Vec<String>,
    /// The map's signal wiring (`[signals]` of nctrans-map.toml).
    signals: nctrans::dialect::signals::SignalMap,
}

impl MapOpts {
    /// Reads the maps: `./nctrans.toml` `[tools]` (as a translation reads it), then `--map`,
    /// then `--tool-map`. `None` when neither flag is given.
    pub fn names(&self) -> Result<Option<Names>, String> {
        if self.tool_map.is_empty() && self.map.is_none() {
            return Ok(None);
        }
        let mut tools = BTreeMap::new();
        let project = Path::new(nctrans::config::FILE_NAME);
        if project.is_file() {
            tools.extend(nctrans::config::Config::load(project)?.tools);
        }
        let mut r_vars = Vec::new();
        let mut rules = Vec::new();
        let mut signals = nctrans::dialect::signals::SignalMap::default();
        if let Some(p) = &self.map {
            let text = std::fs::read_to_string(p).map_err(|e| format!("cannot read {}: {e}", p.display()))?;
            let (maps, target) = nctrans::batch::maps::from_toml(&text).map_err(|e| format!("{}: {e}", p.display()))?;
            if target == Some(Dialect::Sinumerik) {
                return Err(format!(
                    "{}: this map is of a translation to Sinumerik; tool names are mapped only to FANUC",
                    p.display()
                ));
            }
            tools.extend(maps.tools);
            signals = maps.signals;
            rules = maps.var_rules;
            for (source, target) in &maps.variables {
                let is_r = source.strip_prefix('R').is_some_and(|n| n.parse::<u32>().is_ok());
                if let (true, Some(n)) = (is_r, target.strip_prefix('#').and_then(|n| n.parse().ok())) {
                    r_vars.push(n);
                }
            }
        }
        for m in &self.tool_map {
            let (name, n) = m.split_once('=').ok_or_else(|| format!("--tool-map '{m}': expected NAME=N"))?;
            let n: u32 = n.trim().parse().map_err(|_| format!("--tool-map '{m}': expected a T number after ="))?;
            tools.insert(name.trim().to_string(), n);
        }
        Ok(Some(Names { tools, r_vars, rules, signals }))
    }
}

impl Names {
    /// A Siemens side compared with a FANUC one: aligned as the translation's verification
    /// aligns it (`translate::to_fanuc::align_source`).
    pub fn align(&self, unit: &Unit) -> Unit {
        let map = SymbolMap { tools: self.tools.clone(), ..SymbolMap::default() };
        translate::to_fanuc::align_source(unit, &map)
    }

    /// A FANUC side compared with a Siemens one: the variables mapped R parameters went to
    /// start at 0, as R parameters do (unless the run's inputs set them).
    pub fn fanuc_inputs(&self, inputs: &mut Vec<nctrans::eval::Input>) {
        for n in &self.r_vars {
            if let Ok(i) = nctrans::eval::parse_input(&format!("#{n}=0")) {
                if !inputs.iter().any(|h| h.target == i.target) {
                    inputs.push(i);
                }
            }
        }
    }
}

/// Runs `nctrans check`.
pub fn check(
    a: &PathBuf,
    b: &PathBuf,
    (from_a, from_b): (Option<Dialect>, Option<Dialect>),
    eval: &EvalOpts,
    input: &InputOpts,
    maps: &MapOpts,
) -> ExitCode {
    use nctrans::check::{self, Side};
    let shared = match super::args::shared_probes(eval, [a, b]) {
        Ok(e) => e,
        Err(code) => return code,
    };
    let eval = &shared;
    let names = match maps.names() {
        Ok(n) => n,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    if let Some(names) = &names {
        return check_as_translation(a, b, (from_a, from_b), eval, input, names);
    }
    let mut db = SourceDb::new();
    // Each side is streamed when it is large (or --stream), else read whole. A streamed
    // side's source (a decoded copy for a legacy encoding) lives until the check has run.
    let mut sides: Vec<Read> = Vec::new();
    for (path, from) in [(a, from_a), (b, from_b)] {
        let id = db.len();
        let side = stream::wanted(path, input).then(|| side(&mut db, path, from, eval, input.encoding)).flatten();
        sides.push(match side {
            Some(Ok((ix, run, src))) => Read::Streamed { id, ix, run, src },
            Some(Err(code)) => return code,
            None => match load_for_run(&mut db, path, from, eval, input) {
                Ok((unit, run)) => Read::Whole { unit, run },
                Err(code) => return code,
            },
        });
    }
    wire_signal_inputs(&mut sides, &signals::project_wiring());
    let seeded = match &mut sides[..] {
        [x, y] => match seed(&db, [x, y], &[]) {
            Ok(s) => s,
            Err(code) => return code,
        },
        _ => None,
    };
    let unused = match &mut sides[..] {
        [x, y] => unused_def_inputs(&db, [x, y]),
        _ => Vec::new(),
    };
    let mut render: Vec<(usize, &std::path::Path)> = Vec::new();
    let mut runners = Vec::new();
    for s in &sides {
        runners.push(match s {
            Read::Whole { unit, run } => {
                let callees = Box::new(nctrans::eval::DirCallees { semantics: run.semantics.clone() });
                Side { unit: unit.clone(), callees, run: run.clone() }.runner()
            }
            Read::Streamed { id, ix, run, src } => {
                render.push((*id, src.path()));
                let callees = Box::new(nctrans::eval::DirCallees { semantics: run.semantics.clone() });
                nctrans::stream::runner(Arc::clone(ix), callees, run.clone())
            }
        });
    }
    let mut runners = runners.into_iter();
    let (Some(ra), Some(rb)) = (runners.next(), runners.next()) else {
        return ExitCode::from(2);
    };
    let mut report = check::check_runners(&db, ra, rb);
    report.excluded.unused_inputs = unused;
    eprint!("{}", nctrans::excerpt::render(&report.db, &report.diags, &render));
    check_verdict(&report, seeded.as_ref().map(|s| s.said.as_str()))
}

/// One side of a plain `check`: read whole, or streamed (its index, with the source it
/// reads: the file, or a decoded copy kept until the check has run).
enum Read<'a> {
    Whole { unit: Unit, run: nctrans::eval::RunOptions },
    Streamed { id: usize, ix: Arc<nctrans::stream::Index>, run: nctrans::eval::RunOptions, src: Source<'a> },
}

/// A Siemens side against a FANUC one: each side's signal inputs in its own names.
fn wire_signal_inputs(sides: &mut [Read], wiring: &nctrans::dialect::signals::SignalMap) {
    let dialects: Vec<Dialect> = sides.iter().map(Read::dialect).collect();
    if wiring.is_empty() || dialects.windows(2).all(|w| w[0] == w[1]) {
        return;
    }
    for (side, d) in sides.iter_mut().zip(dialects) {
        signals::wire(&mut side.run().inputs, d, wiring);
    }
}

impl Read<'_> {
    fn dialect(&self) -> Dialect {
        match self {
            Read::Whole { unit, .. } => unit.dialect,
            Read::Streamed { ix, .. } => ix.dialect,
        }
    }

    fn run(&mut self) -> &mut nctrans::eval::RunOptions {
        match self {
            Read::Whole { run, .. } | Read::Streamed { run, .. } => run,
        }
    }
}

/// A Siemens side against a FANUC one, each read whole or streamed: the FANUC side's
/// commons of global user data get their start values (`gud::seeding`, the same for both
/// ways of reading: a streamed Siemens side gives it its program without the motion blocks,
/// which name no variable (`stream::target::fanuc::without_straight`), and a streamed FANUC
/// side the lines of its text that name homes of global user data); what was assumed, for
/// the verdict. `Err` (said): a streamed side that cannot be read again (NC594), or whose
/// translation has errors that might mark other blocks than the whole program's (NC595).
fn seed(db: &SourceDb, [x, y]: [&mut Read; 2], map_rules: &[String]) -> Result<Option<gud::Seeded>, ExitCode> {
    let (siemens, fanuc) = match (x.dialect(), y.dialect()) {
        (Dialect::Sinumerik, Dialect::Fanuc) => (&*x, y),
        (Dialect::Fanuc, Dialect::Sinumerik) => (&*y, x),
        _ => return Ok(None),
    };
    let sem = match siemens {
        Read::Whole { run, .. } | Read::Streamed { run, .. } => run.semantics.clone(),
    };
    let Some(sem) = sem.filter(|s| !s.globals.is_empty()) else { return Ok(None) };
    // Never checked unseeded: the verdict would rest on commons the whole check starts.
    let again = |path: &Path, e: String| {
        let d = diag::Diagnostic::error(
            "NC594",
            format!("{} cannot be read again for the global user data it uses: {e}", path.display()),
        )
        .note("the FANUC side's commons are seeded from the programs' use of it, as a whole-file check seeds them")
        .hint("check the files again once they can be read");
        eprint!("{}", diag::render(&SourceDb::new(), &[d]));
        ExitCode::from(1)
    };
    let (unit, path) = match siemens {
        Read::Whole { unit, .. } => (std::borrow::Cow::Borrowed(unit), Path::new(&db.get(unit.file).name)),
        Read::Streamed { ix, src, .. } => {
            let u = nctrans::stream::target::fanuc::without_straight(src.path(), ix)
                .map_err(|e| again(src.original, e.to_string()))?;
            (std::borrow::Cow::Owned(u), src.original)
        }
    };
    let text = match &*fanuc {
        Read::Whole { unit, .. } => db.get(unit.file).text.clone(),
        Read::Streamed { src, .. } => gud::home_lines(src.path()).map_err(|e| again(src.original, e))?,
    };
    let Some(mut seeded) = gud::seeding(&unit, path, &sem, &text, map_rules) else { return Ok(None) };
    if seeded.doubtful && matches!(siemens, Read::Streamed { .. }) {
        let d = diag::Diagnostic::error(
            "NC595",
            format!("{}: where a translation puts the global user data it uses is not settled for a streamed program", path.display()),
        )
        .note("its translation has errors, and which blocks they take out may depend on the motion blocks a streamed check leaves out")
        .hint("check the translation's source as it translates (nctrans --to fanuc), or a smaller program");
        eprint!("{}", diag::render(&SourceDb::new(), &[d]));
        return Err(ExitCode::from(1));
    }
    seeded.give(&mut fanuc.run().inputs);
    Ok(Some(seeded))
}

/// Prints a check's verdict, with what the runs assumed (`assumed`); its exit code.
/// A Siemens side checked against a FANUC one leaves out the inputs that name a DEF
/// variable of its main program, as a translation's proof does
/// (`translate::to_fanuc::proof_sets`): the FANUC side assigns that start value itself.
/// Warns NC661 for each; returns them for the verdict.
fn unused_def_inputs(db: &SourceDb, [x, y]: [&mut Read; 2]) -> Vec<String> {
    let siemens = match (x.dialect(), y.dialect()) {
        (Dialect::Sinumerik, Dialect::Fanuc) => x,
        (Dialect::Fanuc, Dialect::Sinumerik) => y,
        _ => return Vec::new(),
    };
    let Read::Whole { unit, run } = siemens else { return Vec::new() };
    let Some(main) = unit.programs.first() else { return Vec::new() };
    let names = translate::to_fanuc::main_def_names(main);
    let (unused, kept): (Vec<_>, Vec<_>) = std::mem::take(&mut run.inputs)
        .into_iter()
        .partition(|i| matches!(&i.target, nctrans::eval::InputTarget::Name(n) if names.contains(n)));
    run.inputs = kept;
    let texts: Vec<String> = unused.into_iter().map(|i| i.text).collect();
    let warnings: Vec<_> =
        texts.iter().filter_map(|t| translate::to_fanuc::unused_input_warning(t, main, unit.file)).collect();
    eprint!("{}", diag::render(db, &warnings));
    texts
}

fn check_verdict(report: &nctrans::check::CheckReport, assumed: Option<&str>) -> ExitCode {
    use nctrans::check::Verdict;
    // The `comp` event names registers, not G44's direction nor Siemens ISO-mode G43/G44/G49
    // (NC387): a program that ran one may apply another length than the other, unseen.
    let compensates = report.diags.iter().any(|d| d.code == nctrans::eval::machine::COMPENSATION_NOTE);
    // Output whose text is not modelled (NC554: a DPRNT number field, BPRNT) is not compared.
    let unprinted = report.diags.iter().any(|d| d.code == nctrans::eval::print::PRINT_NOT_MODELLED);
    // A FANUC rigid tap from a turning spindle (NC592): what the spindle does after it is
    // the run's assumption, not a sourced fact, so a trace resting on it proves nothing.
    let tapped_turning = report.diags.iter().any(|d| d.code == nctrans::eval::cycles::fanuc::RIGID_TURNING);
    let diff = &report.diff;
    // What the runs assumed goes with every verdict: inside an equivalence's parentheses,
    // else on a line of its own after the verdict.
    let println = |line: String| {
        println!("{line}");
        if let Some(a) = assumed {
            println!("assumed: {a}");
        }
    };
    match &report.verdict {
        Verdict::Equivalent { events } if tapped_turning => {
            println(format!(
                "inconclusive: {events} trace events agree, but the spindle after rigid tapping from a turning spindle (NC592) is not settled"
            ));
            ExitCode::from(4)
        }
        Verdict::Equivalent { events } if unprinted && !compensates => {
            println(format!("inconclusive: {events} trace events agree, but output whose text is not modelled (NC554) is not compared"));
            ExitCode::from(4)
        }
        Verdict::Equivalent { events } if compensates => {
            println(format!(
                "inconclusive: {events} trace events agree, but tool compensation (G44, ISO-mode G43/G44/G49) is not compared"
            ));
            ExitCode::from(4)
        }
        Verdict::Equivalent { events } => {
            let detail = match assumed {
                Some(a) => format!("{events} trace events agree; {a}"),
                None => format!("{events} trace events agree"),
            };
            println!("{}", report.excluded.equivalent(&detail));
            ExitCode::SUCCESS
        }
        Verdict::Diverged { index } => {
            // Where the first program stops with its own alarm, say so: the two differ on a
            // path where the first is in error, not necessarily in what they would machine.
            let alarm = if report.diverged_on_alarm {
                ": the first program stops with an alarm there and the second does not stop the same way"
            } else {
                ""
            };
            println(format!("diverged at trace event {}{alarm}", index + 1));
            print!("{diff}");
            ExitCode::from(1)
        }
        Verdict::Inconclusive { reason } => {
            println(format!("inconclusive: {reason}"));
            ExitCode::from(4)
        }
        Verdict::Failed => {
            println("failed: a program could not be evaluated".to_string());
            ExitCode::from(1)
        }
    }
}

/// `check` with a translation's maps (`--tool-map`, `--map`): both sides read whole, a
/// Siemens side compared with a FANUC one aligned as the translation's verification aligns
/// it (see [`Names`]).
fn check_as_translation(
    a: &PathBuf,
    b: &PathBuf,
    (from_a, from_b): (Option<Dialect>, Option<Dialect>),
    eval: &EvalOpts,
    input: &InputOpts,
    names: &Names,
) -> ExitCode {
    use nctrans::check::{self, Side};
    let mut db = SourceDb::new();
    let mut sides = Vec::new();
    for (path, from) in [(a, from_a), (b, from_b)] {
        match load_for_run(&mut db, path, from, eval, input) {
            Ok(side) => sides.push(side),
            Err(code) => return code,
        }
    }
    let mut read: Vec<Read> = sides.into_iter().map(|(unit, run)| Read::Whole { unit, run }).collect();
    let mut wiring = signals::project_wiring();
    for (k, v) in &names.signals.pairs {
        let _ = wiring.add(&k.key(), &v.key());
    }
    wire_signal_inputs(&mut read, &wiring);
    let seeded = match &mut read[..] {
        [x, y] => match seed(&db, [x, y], &names.rules) {
            Ok(s) => s,
            Err(code) => return code,
        },
        _ => None,
    };
    let unused = match &mut read[..] {
        [x, y] => unused_def_inputs(&db, [x, y]),
        _ => Vec::new(),
    };
    let sides: Vec<(Unit, nctrans::eval::RunOptions)> = read
        .into_iter()
        .filter_map(|r| match r {
            Read::Whole { unit, run } => Some((unit, run)),
            Read::Streamed { .. } => None,
        })
        .collect();
    let dialects: Vec<Dialect> = sides.iter().map(|(u, _)| u.dialect).collect();
    let cross = dialects[0] != dialects[1];
    let runners: Vec<_> = sides
        .into_iter()
        .map(|(unit, mut run)| {
            // GETT("NAME") returns the mapped number, as in the translation's verification
            // (`translate::to_fanuc`), where `T="NAME"` is aligned to it.
            if unit.dialect == Dialect::Sinumerik && !names.tools.is_empty() {
                let mut s = run
                    .semantics
                    .take()
                    .unwrap_or_else(|| nctrans::dialect::Semantics::default_for(Dialect::Sinumerik));
                s.tools = std::sync::Arc::new(names.tools.clone());
                run.semantics = Some(s);
            }
            let unit = match unit.dialect {
                Dialect::Sinumerik if cross => names.align(&unit),
                Dialect::Fanuc if cross => {
                    names.fanuc_inputs(&mut run.inputs);
                    unit
                }
                _ => unit,
            };
            let callees = Box::new(nctrans::eval::DirCallees { semantics: run.semantics.clone() });
            Side { unit, callees, run }.runner()
        })
        .collect();
    let mut runners = runners.into_iter();
    let (Some(ra), Some(rb)) = (runners.next(), runners.next()) else {
        return ExitCode::from(2);
    };
    // Compared as the translation's verification compares: a Siemens first side's messages
    // shown without a stop are what a FANUC translation keeps as comments.
    let exclude = if cross && dialects[0] == Dialect::Sinumerik {
        nctrans::translate::to_fanuc::EXCLUDE
    } else {
        check::Exclude::default()
    };
    let mut report = check::check_runners_excluding(&db, ra, rb, exclude);
    report.excluded.unused_inputs = unused;
    eprint!("{}", diag::render(&report.db, &report.diags));
    check_verdict(&report, seeded.as_ref().map(|s| s.said.as_str()))
}

/// One side of `nctrans check`: streamed when wanted and possible, with what it reads (the
/// file, or a decoded copy of a legacy-encoded one: the caller keeps it until the check has
/// run, and renders the check's diagnostics from its [`Source::path`]). The run has the
/// profile the file was read with, as a side read whole has (`args::load_for_run`).
#[allow(clippy::type_complexity)]
fn side<'a>(
    db: &mut SourceDb,
    path: &'a Path,
    from: Option<Dialect>,
    eval: &EvalOpts,
    forced: Option<&'static encoding_rs::Encoding>,
) -> Option<Result<(Arc<nctrans::stream::Index>, nctrans::eval::RunOptions, Source<'a>), ExitCode>> {
    let file = db.len();
    let mut src = Source::new(path, forced)?;
    let ix = match stream::scan(&mut src, from, file)? {
        Ok(ix) => ix,
        Err(code) => return Some(Err(code)),
    };
    let mut opts = match stream::run_options(&ix, path, eval) {
        Ok(o) => o,
        Err(code) => return Some(Err(code)),
    };
    opts.semantics = Some(ix.opts.semantics.clone());
    db.add(path.display().to_string(), String::new());
    Some(Ok((Arc::new(ix), opts, src)))
}
