//! The FANUC → Sinumerik work behind [`crate::translate::translate`]: FANUC units in (the main
//! file first, then the files its callees were found in), Siemens files out (`NAME.MPF` for main
//! programs, `NAME.SPF` per called O program), with the symbol map the checker needs and
//! every diagnostic. Unsupported constructs are NC35x errors by default; with
//! [`UnsupportedPolicy::Warn`] they are warnings and a `; NCTRANS UNSUPPORTED: …` line.
//!
//! Owns: the Siemens files of a translation (names, header, variable map lines) and their
//! proof (`verify`). May use: `lower::to_sinumerik` (lowering), `dialect::sinumerik::emit`,
//! `unfinished`, `empty`, `check`/`eval` for the proof; never `batch`, `stream` or the CLI.

pub use super::{OutFile, Translation};
pub use crate::lower::to_sinumerik::{Options, Role, UnsupportedPolicy, VarMapRule};

pub mod verify;

use crate::diag::Diagnostic;
use crate::dialect::sinumerik::emit::{emit_program, Frame};
use crate::ir::*;
use crate::lower::to_sinumerik::{self as passes, ProgPlan};
use crate::read::LineEnding;
use crate::span::FileId;
use std::collections::BTreeSet;

/// Where a FANUC variable went.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct VarEntry {
    /// Siemens program name for locals, `None` for common variables (global).
    pub program: Option<String>,
    /// `#24`.
    pub fanuc: String,
    /// `ARG_X`, `R100`.
    pub siemens: String,
    /// Its is-set flag, when the program observes its vacancy.
    pub flag: Option<String>,
}

/// FANUC names → Siemens names, for the header, the checker (inputs such as `--set '#500=1'`)
/// and diagnostics.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SymbolMap {
    pub vars: Vec<VarEntry>,
    /// `O9010` → `PROBE_X`.
    pub programs: Vec<(String, String)>,
}

impl SymbolMap {
    /// The Siemens variable and flag for a FANUC common variable.
    pub fn common(&self, n: u32) -> Option<&VarEntry> {
        let key = format!("#{n}");
        self.vars.iter().find(|v| v.program.is_none() && v.fanuc == key)
    }
}

/// The common variables (`#100`..`#999`, and the Haas NGC-only numbers:
/// `haas_vars::maybe_common`) a program reads or writes by number.
pub fn commons_of(p: &Program) -> BTreeSet<u32> {
    let mut set = BTreeSet::new();
    fn expr(e: &Expr, set: &mut BTreeSet<u32>) {
        if let ExprKind::Var(v) = &e.kind {
            if let VarKind::Hash(n) = v.kind {
                if crate::dialect::fanuc::haas_vars::maybe_common(n) {
                    set.insert(n);
                }
            }
        }
        for c in e.children() {
            expr(c, set);
        }
    }
    fn item(it: &Item, set: &mut BTreeSet<u32>) {
        if let ItemKind::Assign { target, .. } = &it.kind {
            if let VarKind::Hash(n) = target.kind {
                if crate::dialect::fanuc::haas_vars::maybe_common(n) {
                    set.insert(n);
                }
            }
        }
        if let ItemKind::IfThen { then, .. } = &it.kind {
            item(then, set);
        }
        if let ItemKind::IfBlock { items, .. } = &it.kind {
            items.iter().for_each(|i| item(i, set));
        }
        for e in crate::ir::visit::item_exprs(it) {
            expr(e, set);
        }
    }
    crate::ir::visit::walk_stmts(&p.body, &mut |s| match &s.kind {
        StmtKind::Block(b) => b.items.iter().for_each(|it| item(it, &mut set)),
        StmtKind::Do(d) => {
            if let Some(c) = &d.cond {
                expr(c, &mut set);
            }
        }
        _ => {}
    });
    set
}

fn local_entries(plan: &ProgPlan) -> Vec<VarEntry> {
    plan.locals
        .iter()
        .map(|&n| VarEntry {
            program: Some(plan.name.clone()),
            fanuc: format!("#{n}"),
            siemens: passes::varmap::local_name(plan, n),
            flag: plan.tracked.contains(&n).then(|| passes::varmap::flag_name(plan, n)),
        })
        .collect()
}

fn entry_text(e: &VarEntry) -> String {
    match &e.flag {
        Some(f) => format!("{} = {} (is-set flag {f})", e.fanuc, e.siemens),
        None => format!("{} = {}", e.fanuc, e.siemens),
    }
}

/// The Siemens form of a FANUC input line `nctrans: set #24=10. #500=#0`: each variable by
/// the map, with its is-set flag when it has one (a vacant input is value 0, flag 0).
fn map_inputs(rest: &str, plan: &ProgPlan, lowered: &passes::Lowered, source: &crate::dialect::Semantics) -> String {
    let mut parts = Vec::new();
    for part in rest.split_whitespace() {
        let Some((lhs, rhs)) = part.split_once('=') else {
            parts.push(part.to_string());
            continue;
        };
        let Some(n) = lhs.trim().strip_prefix('#').and_then(|n| n.parse::<u32>().ok()) else {
            parts.push(part.to_string());
            continue;
        };
        let vacant = rhs.trim() == "#0";
        let value = if vacant { "0".to_string() } else { rhs.trim().to_string() };
        let (name, flag) = match n {
            1..=33 => (
                passes::varmap::local_name(plan, n),
                plan.tracked.contains(&n).then(|| passes::varmap::flag_name(plan, n)),
            ),
            // Tool compensation memory C: the cutting edge data of the register's edge.
            n if !source.haas && crate::eval::tool_data::fanuc_field(i64::from(n)).is_some() => {
                match crate::lower::to_sinumerik::tool_data::edge_var(n, &source.offsets) {
                    Some(name) => (name, None),
                    None => {
                        parts.push(part.to_string());
                        continue;
                    }
                }
            }
            // An interface signal: the Siemens signal the wiring gives it.
            n if !source.haas && crate::dialect::signals::Signal::fanuc(n).is_some() => {
                match crate::dialect::signals::Signal::fanuc(n).and_then(|f| source.signals.siemens_of(f)) {
                    Some(s) => (s.key(), None),
                    None => {
                        parts.push(part.to_string());
                        continue;
                    }
                }
            }
            _ if crate::dialect::fanuc::haas_vars::maybe_common(n) => match lowered.commons.get(&n) {
                Some(r) => (format!("R{r}"), lowered.common_flags.get(&n).map(|f| format!("R{f}"))),
                None => continue, // not used by the program: nothing to set
            },
            _ => {
                parts.push(part.to_string());
                continue;
            }
        };
        parts.push(format!("{name}={value}"));
        if let Some(f) = flag {
            parts.push(format!("{f}={}", u8::from(!vacant)));
        }
    }
    format!("nctrans: set {}", parts.join(" "))
}

/// Takes the `(nctrans: set …)` comment blocks off the top of a program body (they become
/// header lines of the output, in Siemens names).
fn take_inputs(prog: &mut Program) -> Vec<String> {
    let mut found = Vec::new();
    let mut i = 0;
    while i < prog.body.len() {
        let StmtKind::Block(b) = &prog.body[i].kind else { break };
        if !b.items.is_empty() || b.meta.number.is_some() || b.meta.label.is_some() {
            break;
        }
        let sets: Vec<String> = b
            .meta
            .comments
            .iter()
            .filter_map(|c| c.text.trim().strip_prefix("nctrans: set").map(str::to_string))
            .collect();
        if sets.is_empty() {
            i += 1;
            continue;
        }
        found.extend(sets);
        prog.body.remove(i);
    }
    found
}

/// Translates FANUC programs to Sinumerik. `units[0]` holds the main program (its first
/// program); further programs of any unit are the subprograms and macros it may call.
use crate::lower::own_header as passes_header;

/// Translates FANUC programs to Sinumerik files. Under the warn policy refused blocks become
/// marked comments whole and the main program alarms on its first line
/// ([`crate::unfinished`]).
pub fn translate(units: &[&Unit], opts: &Options, line_ending: LineEnding) -> Translation {
    if opts.unsupported == UnsupportedPolicy::Error {
        return translate_strict(units, opts, line_ending);
    }
    let strict = Options { unsupported: UnsupportedPolicy::Error, ..opts.clone() };
    let style = |m: &str| format!("NCTRANS UNSUPPORTED: {m}");
    let (t, warnings, marked, mut owned) = crate::unfinished::translate_marking(units, style, |us| {
        let t = translate_strict(us, &strict, line_ending);
        let d = t.diags.clone();
        (t, d)
    });
    if marked == 0 {
        return t;
    }
    if let Some(p) = owned.first_mut().and_then(|u| u.programs.first_mut()) {
        let span = crate::span::Span::new(p.span.lo, p.span.lo);
        p.body.insert(0, crate::unfinished::summary_block(span, "NCTRANS:", marked));
        p.body.insert(0, crate::unfinished::alarm_block(span));
    }
    let refs: Vec<&Unit> = owned.iter().collect();
    let mut t = translate_strict(&refs, &strict, line_ending);
    let mut diags = warnings;
    diags.append(&mut t.diags);
    t.diags = diags;
    t.unsupported = marked;
    t
}

fn translate_strict(units: &[&Unit], opts: &Options, line_ending: LineEnding) -> Translation {
    let mut programs: Vec<(FileId, &Program)> =
        units.iter().flat_map(|u| u.programs.iter().map(move |p| (u.file, p))).collect();
    // A translation translated back: its old header goes (copied only then).
    let cleaned: Vec<Program> = programs
        .iter()
        .filter(|(_, p)| passes_header::has_own_header(p))
        .map(|(_, p)| {
            let mut p = (*p).clone();
            // Its `O` line's title is the name nctrans gave it, not a programmer's.
            if passes_header::translated_by_nctrans(&p.body) {
                p.head.iter_mut().for_each(|h| h.comments.clear());
            }
            passes_header::drop_own_header(&mut p);
            p
        })
        .collect();
    let mut cleaned = cleaned.iter();
    for (_, p) in programs.iter_mut() {
        if passes_header::has_own_header(p) {
            if let Some(c) = cleaned.next() {
                *p = c;
            }
        }
    }
    let lowered = passes::lower(&programs, opts);
    let mut diags = lowered.diags.clone();
    let mut symbols = SymbolMap::default();
    for (&n, &r) in &lowered.commons {
        symbols.vars.push(VarEntry {
            program: None,
            fanuc: format!("#{n}"),
            siemens: format!("R{r}"),
            flag: lowered.common_flags.get(&n).map(|f| format!("R{f}")),
        });
    }
    for (plan, _) in &lowered.programs {
        if let Some(n) = plan.number {
            symbols.programs.push((format!("O{n:04}"), plan.name.clone()));
        }
        symbols.vars.extend(local_entries(plan));
    }
    let mut files = Vec::new();
    let mut names: BTreeSet<String> = BTreeSet::new();
    for ((plan, prog), (file, src)) in lowered.programs.iter().zip(&programs) {
        let mut prog = prog.clone();
        let inputs: Vec<String> =
            take_inputs(&mut prog).iter().map(|rest| map_inputs(rest, plan, &lowered, &opts.source)).collect();
        let main = plan.role == Role::Main;
        let ext = if main { "MPF" } else { "SPF" };
        let fname = format!("{}.{ext}", plan.name);
        // A program of a FANUC file may be empty; its Siemens file would hold no program,
        // which every command refuses (NC145), so the translation says it here.
        if !crate::dialect::empty::has_content(&prog) {
            let name = plan.number.map_or_else(|| "the main program".to_string(), |n| format!("program O{n:04}"));
            diags.push(
                Diagnostic::error("NC146", format!("{name} holds no block to translate"))
                    .primary(*file, src.span, "this program")
                    .note(format!("{fname} would hold no program (NC145)"))
                    .hint("delete the empty program, or give it its blocks"),
            );
        }
        if !names.insert(fname.clone()) {
            diags.push(
                Diagnostic::error("NC371", format!("two programs would both be written as {fname}"))
                    .primary(*file, src.span, "this program")
                    .hint("give them distinct names with --program-map N=NAME"),
            );
        }
        // The program's title (`O2010 (FLANGE)`) stays with it: the name a FANUC directory
        // shows, which the Siemens file name cannot carry.
        let title: Vec<&str> =
            src.head.iter().flat_map(|h| &h.comments).map(|c| c.text.trim()).filter(|t| !t.is_empty()).collect();
        let title = if title.is_empty() { String::new() } else { format!(" ({})", title.join(") (")) };
        let mut header = vec![
            match plan.number {
                Some(n) => format!("Translated by nctrans from FANUC O{n:04}{title}"),
                None => format!("Translated by nctrans from FANUC{title}"),
            },
            "FANUC variable map:".to_string(),
        ];
        let used = commons_of(src);
        for e in &symbols.vars {
            let mine = match &e.program {
                None => e.fanuc[1..].parse::<u32>().is_ok_and(|n| used.contains(&n)),
                Some(p) => *p == plan.name,
            };
            if mine {
                header.push(format!("  {}", entry_text(e)));
            }
        }
        if header.len() == 2 {
            header.pop();
        }
        if header.iter().any(|h| h.contains("(is-set flag")) {
            header.push("  (an is-set flag FALSE means FANUC's vacant; the value is then 0)".to_string());
        }
        // Inputs first: the evaluator reads only the comment lines at the top.
        let header: Vec<String> = inputs.into_iter().chain(header).collect();
        diags.extend(crate::dialect::limits::deepened(&prog.body, *file, crate::dialect::Dialect::Sinumerik));
        let frame = Frame { header: &header, defs: &plan.defs, proc_line: !main };
        let emitted = emit_program(&prog, &frame);
        for (span, what) in &emitted.problems {
            diags.push(
                Diagnostic::error("NC370", format!("cannot write {what} in Sinumerik syntax"))
                    .primary(*file, *span, "from here")
                    .note("this is a gap in nctrans's lowering, not in the program")
                    .hint("report it with the program; translate this block by hand meanwhile"),
            );
        }
        let text = match line_ending {
            LineEnding::Lf => emitted.text,
            other => emitted.text.replace('\n', other.as_str()),
        };
        files.push(OutFile {
            name: fname,
            program: plan.name.clone(),
            fanuc_number: plan.number,
            main,
            text,
            source: *file,
            lines: emitted.lines,
        });
    }
    Translation { files, symbols: super::Symbols::Sinumerik(symbols), diags, unsupported: 0 }
}
