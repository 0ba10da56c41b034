//! FANUC Macro B → Sinumerik lowering: the passes in the order they run, the plan they
//! share (program roles and names, variable map, vacancy tracking) and small IR builders.
//!
//! Order (see [`lower`]):
//! 1. `indirect::resolve` — `#[expr]` with an index known at translation time → `#n`.
//! 2. plan — program roles (main / G65 macro / M98 subprogram), Siemens names, PROC
//!    parameters (`calls::plan_programs`), the vacancy analysis (`vacancy::analyse`) and the
//!    variable map (`varmap::build`).
//! 3. `vacancy::rewrite` — is-set flags on writes, EQ/NE against vacancy, conditional words.
//! 4. `calls::lower_return_jumps` — after a call of a program that ends with `M99 P<n>`,
//!    a computed jump on the return code it passes back.
//! 5. `gotos::lower` — `GOTO n` → `GOTOF`/`GOTOB` to generated labels, computed GOTO → `CASE`.
//!    Then `m97::lower` — Haas `M97 Pn Lm` → a jump to `REPEAT <start> <end> P=m` and back
//!    (checked, and its sections' M99 dropped, by `m97::prepare` before step 3).
//! 6. `structures::lower` — `WHILE[..]DOm` → `WHILE`, bare `DOm` → `LOOP`, `IF..THEN` → `IF`.
//! 7. `calls::lower` — G65/G66/G67/M98/M99/G10 → Siemens calls, `MCALL`, `RET`, `$P_UIFR`.
//! 8. `lookahead::lower` — look-ahead modes (`G05.1 Q1`, `G08 P1`, Haas `G187`) → `FFWON`,
//!    `FFWOF`, `CYCLE832(…)`.
//!    `cycles::lower` — drilling cycles → `MCALL CYCLEnn(…)`, positions, `MCALL`.
//!    Then `comp::lower` — G43 H / G49, G41 D / G40 → cutting edges `D1` / `D0`, G41/G40.
//!    Then `probe::lower` — G31 → `MEAS=1 G1`, the skip position `#5061+` kept in DEF variables.
//! 9. `words::lower` — decimal-point rule, G-code spellings, dwell, arcs, alarms, messages,
//!    system variables.
//! 10. `exprs::lower` — functions, bitwise operators, exact comparisons, variables by the map.
//!
//! Every pass keeps source spans on what it builds, so a divergence found later can point
//! back at the FANUC text. `fast_write` is these passes' translation of one plain block
//! written straight to bytes, for the streamed translator (held to the passes' bytes by the
//! differential tests).

pub mod calls;
pub mod comp;
pub mod cycles;
pub mod dead;
pub mod dispatch;
pub mod ends;
pub mod exprs;
pub(crate) mod fast_write;
pub mod feed_group;
pub mod forward;
pub mod frames;
pub mod gotos;
pub mod haas_if;
pub mod haas_mirror;
pub mod haas_sys;
pub mod indirect;
pub mod interrupt;
pub mod lookahead;
pub mod m97;
pub mod modal;
pub mod modal_flow;
pub mod modal_reads;
pub mod planes;
pub mod polar;
pub mod position_length;
pub mod print;
pub mod probe;
pub mod probe_length;
pub mod rotation;
pub mod save_idiom;
pub mod signals;
pub mod structures;
pub mod tapping;
pub mod tool_data;
pub mod vacancy;
pub mod varmap;
pub mod words;

use crate::diag::Diagnostic;
use crate::dialect::Semantics;
use crate::ir::*;
use crate::span::{FileId, Span};
use std::collections::{BTreeMap, BTreeSet};

// The passes below reach the shared walkers through `super::` (`use super::*`).
use super::{bin, block_items, func, item_exprs_mut, literal, map_bodies, map_exprs};

/// What to do with a construct Sinumerik cannot express.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum UnsupportedPolicy {
    /// An NC35x error; no output is written.
    #[default]
    Error,
    /// A warning, and a visibly marked comment line `; NCTRANS UNSUPPORTED: …` in the output.
    Warn,
}

/// One `--var-map` rule: FANUC `#from..=#to` → `R<r_start>` upwards.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct VarMapRule {
    pub from: u32,
    pub to: u32,
    pub r_start: u32,
}

impl VarMapRule {
    /// Parses `#500-#599=R100` (or `#500=R7` for one variable).
    pub fn parse(s: &str) -> Result<VarMapRule, String> {
        let bad = || format!("bad --var-map '{s}' (expected like '#500-#599=R100')");
        let (lhs, rhs) = s.split_once('=').ok_or_else(bad)?;
        if rhs.trim_start().starts_with('#') && !lhs.trim_start().starts_with('#') {
            return Err(format!(
                "--var-map '{s}' maps Siemens variables onto # variables, a Sinumerik → FANUC rule (--to fanuc); \
                 to Sinumerik a rule maps FANUC common variables onto R parameters, like '#500-#599=R100'"
            ));
        }
        let num = |t: &str, p: char| -> Option<u32> {
            let t = t.trim();
            let t = t.strip_prefix(p).or_else(|| t.strip_prefix(p.to_ascii_lowercase()))?;
            t.trim().parse().ok()
        };
        let (from, to) = match lhs.split_once('-') {
            Some((a, b)) => (num(a, '#').ok_or_else(bad)?, num(b, '#').ok_or_else(bad)?),
            None => {
                let a = num(lhs, '#').ok_or_else(bad)?;
                (a, a)
            }
        };
        let r_start = num(rhs, 'R').ok_or_else(bad)?;
        if from > to {
            return Err(format!("bad --var-map '{s}': range runs backwards"));
        }
        // Only common variables are placed by a rule; a rule over others would do nothing.
        if from < 100 {
            return Err(format!(
                "--var-map '{s}': #{from} is a local variable (#1–#33: one set per macro call, written as DEF \
                 variables of each Siemens program), not placed by a rule; a rule maps common variables #100–#999"
            ));
        }
        // The Haas NGC-only general-purpose ranges are commons too (under `haas-ngc`).
        let ngc = |n: u32| crate::dialect::fanuc::haas_vars::ngc_only(n);
        let ngc_range = ngc(from) && ngc(to) && (from..=to).all(ngc);
        if to > 999 && !ngc_range {
            return Err(format!(
                "--var-map '{s}': #{to} is a system variable (#1000 and up, translated by meaning), not placed by \
                 a rule; a rule maps common variables #100–#999 (and, for a Haas NGC, the general-purpose \
                 #10000–#10099, #10200–#10499, #10700–#10799)"
            ));
        }
        Ok(VarMapRule { from, to, r_start })
    }
}

/// Options of the FANUC → Sinumerik translation.
#[derive(Clone, Debug)]
pub struct Options {
    /// The FANUC profile the source was written for (increment, DPI, NAT).
    pub source: Semantics,
    /// The Siemens target profile (number of R parameters).
    pub target: Semantics,
    pub var_map: Vec<VarMapRule>,
    /// `--program-map 9010=PROBE_X`.
    pub program_map: BTreeMap<u32, String>,
    pub unsupported: UnsupportedPolicy,
    /// Name of the main program when it has no `O` number (the input file stem).
    pub main_name: String,
    /// Fixed R parameters for the is-set flags of common variables (a batch fixes them for
    /// the whole library, so every file tests a common variable's vacancy in the same place);
    /// these R parameters are never given to anything else.
    pub flag_places: BTreeMap<u32, u32>,
    /// Specialise each macro to the calls the translation sees (`--specialise-callers`): an
    /// argument every one of them gives surely is taken as set on entry, so the macro's test
    /// of it (`IF [#11 EQ #0]`) is decided and its default dropped. Off: a macro is written
    /// for every possible caller, its vacancy logic kept (any argument may be vacant).
    pub specialise_callers: bool,
    /// Program numbers found after the closing `%` of a file read (not read by the
    /// control): a call of one is told it is there but after the `%` (NC353).
    pub after_end: std::collections::BTreeSet<u32>,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            source: Semantics::default_for(crate::dialect::Dialect::Fanuc),
            target: Semantics::default_for(crate::dialect::Dialect::Sinumerik),
            var_map: Vec::new(),
            program_map: BTreeMap::new(),
            unsupported: UnsupportedPolicy::Error,
            main_name: "MAIN".into(),
            flag_places: BTreeMap::new(),
            specialise_callers: false,
            after_end: std::collections::BTreeSet::new(),
        }
    }
}

/// How a FANUC program is used, which decides its Siemens form.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    /// Run as the main program: `.MPF`, locals become `DEF` variables.
    Main,
    /// Called by `G65`/`G66` (or a standalone macro ending in M99): `.SPF` with a `PROC` whose
    /// parameters are the argument locals, passed by value, plus is-set flags.
    Macro,
    /// Called by `M98`: `.SPF` whose `PROC` takes the caller's locals by reference (`VAR`).
    Sub,
}

/// A PROC parameter of a translated program.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamSpec {
    /// The FANUC local variable it stands for.
    pub local: u32,
    /// True for the is-set flag of `local` (BOOL), false for its value (REAL).
    pub flag: bool,
    pub name: String,
    pub by_ref: bool,
}

/// What the passes know about one program.
#[derive(Clone, Debug)]
pub struct ProgPlan {
    pub file: FileId,
    pub number: Option<u32>,
    /// Siemens program name (upper case, no extension).
    pub name: String,
    pub role: Role,
    pub params: Vec<ParamSpec>,
    /// Locals `#1..#33` this program (and its M98 callees) reads or writes.
    pub locals: BTreeSet<u32>,
    /// Locals with an is-set flag.
    pub tracked: BTreeSet<u32>,
    /// Address words (`lo, hi` of the value's span) whose variable is set on every path to
    /// them: a tracked variable's flag is surely TRUE there, so the word needs no IF.
    pub sure_words: BTreeSet<(u32, u32)>,
    /// Argument locals some G65/G66 call site in the job fills.
    pub given: BTreeSet<u32>,
    /// The program writes a local (any; decides whether `G65 … L` can repeat by `P`).
    pub writes_locals: bool,
    /// The program returns with `M99 P<n>`: it gets a `VAR REAL NCTRANS_RET` parameter
    /// through which the caller learns where to continue.
    pub returns_to: bool,
    /// DEF declarations the output needs (name, type), in order.
    pub defs: Vec<(String, DataType)>,
    /// The unit (G20 `true`, G21) the program starts in, where known: metric for the main
    /// program, its callers' one unit for a called program (`modal::call_units`).
    pub start_inch: Option<bool>,
    /// The program (or a call in it) may select G20/G21: its caller's unit after the call
    /// is not known.
    pub sets_units: bool,
    /// G90 (`false`) or G91 the program starts in, where every call of it in the job is
    /// made in the same one (G90 for the main program; `modal::call_units`).
    pub start_incremental: Option<bool>,
    /// The motion mode (G code ×10) the program starts in, likewise (G00 for the main
    /// program).
    pub start_motion: Option<u32>,
    /// The program (or a call in it) may select G91, which outlives its return; G90.
    pub sets_distance: bool,
    pub sets_g90: bool,
    /// The program (or a program it calls, or a call of a program not in the job) may
    /// change the tool or the compensation (`comp_flow::tool_effects`): only a call of a
    /// program without it leaves the caller's compensation known (`comp`).
    pub tools: bool,
    /// No G68, G51 or G51.1 is in force at any call of the program in the job (a main
    /// program: at its start), so its frame codes know the mode in force
    /// (`modal::frame_calls`).
    pub start_clear: bool,
    /// A call of the program may leave a G68, G51 or G51.1 in force (or one not known):
    /// the caller's mode after it is not known (`modal::frame_calls`).
    pub leaves_frames: bool,
    /// Likewise G16 polar coordinates.
    pub leaves_polar: bool,
    /// The plane (G code ×10) and the axes on the grid the program starts with, where known:
    /// G17 and all for the main program, what every call agrees on for a called one
    /// (`planes::start_planes`).
    pub start_plane: planes::At,
    /// The program (or a call in it) may select a plane; may move the tool off the grid
    /// (`planes::setters`).
    pub sets_plane: (bool, bool),
    /// The macro is the save/restore idiom (`save_idiom`): written as `PROC … SAVE`, its
    /// return gives the caller its modes back, so it sets none of them for its callers.
    pub save: bool,
}

/// The shared state of one translation.
pub struct Ctx<'a> {
    pub opts: &'a Options,
    pub progs: Vec<ProgPlan>,
    /// FANUC common variable → R number.
    pub commons: BTreeMap<u32, u32>,
    /// Tracked common variable → R number of its is-set flag.
    pub common_flags: BTreeMap<u32, u32>,
    pub diags: Vec<Diagnostic>,
    /// Index into `progs` of the program being lowered.
    pub cur: usize,
    /// True while lowering the items of a plain block (a guard block may go in front).
    pub guard_ok: bool,
    /// The work offset and G90/G91 at each block of the program being lowered, found on
    /// it as read (`modal`).
    pub modal: modal::ModalScan,
    /// Common variable numbers the computed `#[…]` indices of the job start from (their
    /// constant term): which variable ranges they are meant for (`varmap::dispatch_ranges`).
    pub index_bases: BTreeSet<u32>,
    /// The R parameter of the end flag (`ends`), when a called program can end the run.
    pub end_flag: Option<u32>,
    /// FANUC programs whose call can end the run, with their end codes (`ends::ending`).
    pub end_codes: BTreeMap<u32, BTreeSet<u8>>,
}

impl<'a> Ctx<'a> {
    pub fn file(&self) -> FileId {
        self.progs.get(self.cur).map_or(0, |p| p.file)
    }

    pub fn plan(&self) -> &ProgPlan {
        &self.progs[self.cur]
    }

    /// The program planned for FANUC number `n`.
    pub fn program_by_number(&self, n: u32) -> Option<usize> {
        self.progs.iter().position(|p| p.number == Some(n))
    }

    /// Reports a construct without a Siemens counterpart. Returns the marked comment
    /// statement to put in its place under the warn policy.
    pub fn unsupported(&mut self, code: &'static str, span: Span, what: &str, hint: &str) -> Option<Stmt> {
        self.refuse(code, span, &format!("{what} has no Sinumerik counterpart"), what, hint)
    }

    /// Reports something the translation cannot write (error, or warning and a marked
    /// comment line under the warn policy).
    pub fn refuse(&mut self, code: &'static str, span: Span, message: &str, what: &str, hint: &str) -> Option<Stmt> {
        let file = self.file();
        match self.opts.unsupported {
            UnsupportedPolicy::Error => {
                self.diags.push(
                    Diagnostic::error(code, message.to_string()).primary(file, span, "cannot be translated").hint(hint),
                );
                None
            }
            UnsupportedPolicy::Warn => {
                self.diags.push(
                    Diagnostic::warning(code, message.to_string())
                        .primary(file, span, "written as a marked comment")
                        .hint(hint),
                );
                Some(comment_stmt(format!("NCTRANS UNSUPPORTED: {what}"), span))
            }
        }
    }

    pub fn error(&mut self, code: &'static str, span: Span, msg: String, label: &str, hint: &str) {
        let file = self.file();
        self.diags.push(Diagnostic::error(code, msg).primary(file, span, label).hint(hint));
    }

    pub fn warn(&mut self, code: &'static str, span: Span, msg: String, label: &str) {
        let file = self.file();
        self.diags.push(Diagnostic::warning(code, msg).primary(file, span, label));
    }
}

/// The result of lowering: Sinumerik IR per program, with the plans and variable map the
/// emitter and the symbol map need.
pub struct Lowered {
    pub programs: Vec<(ProgPlan, Program)>,
    pub commons: BTreeMap<u32, u32>,
    pub common_flags: BTreeMap<u32, u32>,
    pub diags: Vec<Diagnostic>,
}

/// Runs every pass on the programs of a FANUC translation job (the main file first, then
/// the callees found beside it).
pub fn lower(programs: &[(FileId, &Program)], opts: &Options) -> Lowered {
    let shifted = opts.source.haas && programs.iter().any(|(_, p)| crate::lower::g52_axes(&p.body) & 0b111 != 0);
    let mirrored: Vec<Option<Program>> =
        programs.iter().map(|(_, p)| opts.source.haas.then(|| haas_mirror::spell(p, shifted)).flatten()).collect();
    let programs: Vec<(FileId, &Program)> =
        programs.iter().zip(&mirrored).map(|((f, p), s)| (*f, s.as_ref().unwrap_or(p))).collect();
    let split: Vec<Option<Program>> = programs.iter().map(|(_, p)| haas_if::split(p)).collect();
    let programs: Vec<(FileId, &Program)> =
        programs.iter().zip(&split).map(|((f, p), s)| (*f, s.as_ref().unwrap_or(p))).collect();
    let programs = programs.as_slice();
    let resolved: Vec<Option<Program>> = programs.iter().map(|(_, p)| indirect::resolve(p)).collect();
    let programs: Vec<(FileId, &Program)> =
        programs.iter().zip(&resolved).map(|((f, p), r)| (*f, r.as_ref().unwrap_or(p))).collect();
    // A computed call the constants did not fix: a dispatch over the job's other programs.
    let reachable: Vec<u32> = programs
        .iter()
        .skip(1)
        .filter_map(|(_, p)| match p.name {
            Some(ProgName::Number(n)) => Some(n),
            _ => None,
        })
        .collect::<BTreeSet<u32>>()
        .into_iter()
        .collect();
    let main_no = programs.first().and_then(|(_, p)| match p.name {
        Some(ProgName::Number(n)) => Some(n),
        _ => None,
    });
    let dispatched: Vec<Option<Program>> =
        programs.iter().map(|(_, p)| dispatch::expand(p, &reachable, main_no)).collect();
    let programs: Vec<(FileId, &Program)> =
        programs.iter().zip(&dispatched).map(|((f, p), r)| (*f, r.as_ref().unwrap_or(p))).collect();
    let programs = programs.as_slice();
    let idiom = save_idiom::recognise(programs);
    let programs: Vec<(FileId, &Program)> =
        programs.iter().zip(&idiom.programs).map(|((f, p), r)| (*f, r.as_ref().unwrap_or(p))).collect();
    let programs = programs.as_slice();
    let mut ctx = Ctx {
        opts,
        progs: Vec::new(),
        commons: BTreeMap::new(),
        common_flags: BTreeMap::new(),
        diags: Vec::new(),
        cur: 0,
        guard_ok: false,
        modal: modal::ModalScan::default(),
        index_bases: BTreeSet::new(),
        end_flag: None,
        end_codes: BTreeMap::new(),
    };
    calls::plan_programs(&mut ctx, programs);
    for (p, stripped) in ctx.progs.iter_mut().zip(&idiom.programs) {
        if stripped.is_some() {
            // SAVE gives the caller back every mode the macro selects.
            p.save = true;
            p.sets_units = false;
            p.sets_distance = false;
            p.sets_g90 = false;
        }
    }
    let bodies: Vec<&[Stmt]> = programs.iter().map(|(_, p)| p.body.as_slice()).collect();
    modal::close_setters(&mut ctx.progs, &bodies);
    let units = modal::call_units(&ctx.progs, &bodies);
    for (p, (u, d, m)) in ctx.progs.iter_mut().zip(units) {
        p.start_inch = u;
        p.start_incremental = d;
        p.start_motion = m;
    }
    let frames = modal::frame_calls(&ctx.progs, programs);
    for (p, (clear, leaves, polar)) in ctx.progs.iter_mut().zip(frames) {
        p.start_clear = clear;
        p.leaves_frames = leaves;
        p.leaves_polar = polar;
    }
    let plane_setters = (planes::setters(&ctx.progs, &bodies, false), planes::setters(&ctx.progs, &bodies, true));
    for p in ctx.progs.iter_mut() {
        let sets = |list: &[u32]| p.number.is_some_and(|k| list.contains(&k));
        p.sets_plane = (sets(&plane_setters.0), sets(&plane_setters.1));
    }
    let lists = planes::Lists::of(&ctx.progs);
    let starts = planes::start_planes(&ctx.progs, &bodies, lists.calls());
    for (p, start) in ctx.progs.iter_mut().zip(starts) {
        p.start_plane = start;
    }
    let info = vacancy::analyse(&mut ctx, programs);
    varmap::build(&mut ctx, programs, &info);
    ctx.end_codes = ends::ending(programs, &ctx.progs);
    if !ctx.end_codes.is_empty() {
        ctx.end_flag = varmap::free_r(&ctx);
    }
    let mut out = Vec::new();
    for (i, (_, p)) in programs.iter().enumerate() {
        ctx.cur = i;
        let body = feed_group::insert(&p.body, lower_body(&mut ctx, p.body.clone()));
        let plan = ctx.progs[i].clone();
        let prog = Program {
            name: Some(ProgName::Name(plan.name.clone())),
            head: p.head.clone(),
            params: plan
                .params
                .iter()
                .map(|s| Param {
                    name: s.name.clone(),
                    ty: if s.flag { DataType::Bool } else { DataType::Real },
                    by_ref: s.by_ref,
                    dims: vec![],
                    span: p.head.as_ref().map_or(p.span, |h| h.span),
                })
                .collect(),
            save: plan.save,
            body,
            span: p.span,
        };
        out.push((plan, prog));
    }
    exprs::plain_comparisons(&mut out);
    // After the refusals they explain (the NC549, NC363 a near miss keeps).
    ctx.diags.extend(idiom.diags);
    crate::diag::dedup(&mut ctx.diags);
    Lowered { programs: out, commons: ctx.commons, common_flags: ctx.common_flags, diags: ctx.diags }
}

/// The passes that rewrite the body of program `ctx.cur` once the plan is made (steps 3 to
/// 9 of [`lower`]). A streamed translation runs them on each chunk of a straight-line
/// program with the plan made once.
pub fn lower_body(ctx: &mut Ctx, mut body: Vec<Stmt>) -> Vec<Stmt> {
    body = tool_data::lower(ctx, body);
    body = signals::lower(ctx, body);
    body = haas_if::refuse(ctx, body);
    let (b, local_subs) = m97::prepare(ctx, body);
    body = b;
    let setters: Vec<u32> = ctx.progs.iter().filter(|p| p.sets_units).filter_map(|p| p.number).collect();
    let distance: Vec<u32> = ctx.progs.iter().filter(|p| p.sets_distance).filter_map(|p| p.number).collect();
    let g90: Vec<u32> = ctx.progs.iter().filter(|p| p.sets_g90).filter_map(|p| p.number).collect();
    let framers: Vec<u32> = ctx.progs.iter().filter(|p| p.leaves_frames).filter_map(|p| p.number).collect();
    let polar_framers: Vec<u32> = ctx.progs.iter().filter(|p| p.leaves_polar).filter_map(|p| p.number).collect();
    let calls = modal::CallModes {
        setters: &setters,
        distance_setters: &distance,
        g90_setters: &g90,
        framers: &framers,
        polar_framers: &polar_framers,
    };
    let plan = ctx.plan();
    let main = plan.role == Role::Main;
    let locals = local_subs.as_ref().map_or(&[][..], |p| &p.locals[..]);
    let start = (plan.start_inch, plan.start_incremental, plan.start_motion);
    ctx.modal = modal::ModalScan::new(&body, main, start, plan.start_clear, calls, locals);
    ctx.modal.reads = modal_reads::Reads::new(&body);
    ctx.modal.lengths = position_length::Lengths::new(&body, main);
    let lists = planes::Lists::of(&ctx.progs);
    ctx.modal.planes = planes::Planes::new(&body, ctx.plan().start_plane, lists.calls());
    let skip_axes = probe::scan(ctx, &body);
    if skip_axes != 0 {
        probe_length::check(ctx, &body, main);
    }
    body = vacancy::rewrite(ctx, body);
    body = calls::lower_return_jumps(ctx, body);
    body = ends::lower(ctx, body);
    body = haas_if::restructure(body);
    body = gotos::lower(ctx, body);
    if let Some(plan) = &local_subs {
        body = m97::lower(body, plan);
    }
    body = structures::lower(ctx, body);
    body = calls::lower(ctx, body);
    body = lookahead::lower(ctx, body);
    body = cycles::lower(ctx, body);
    body = comp::lower(ctx, body);
    body = probe::lower(ctx, body, skip_axes);
    body = words::lower(ctx, body);
    dead::fold(exprs::lower(ctx, body))
}

// ---- small IR builders shared by the passes ----

pub fn num(v: f64, span: Span) -> Expr {
    Expr::num(v, true, span)
}

pub fn int(v: i64, span: Span) -> Expr {
    Expr::num(v as f64, false, span)
}

pub fn var_expr(kind: VarKind, span: Span) -> Expr {
    Expr::new(ExprKind::Var(Box::new(VarRef { kind, span })), span)
}

pub fn named(name: &str, span: Span) -> Expr {
    var_expr(VarKind::Named { name: name.to_string(), indices: vec![] }, span)
}

pub fn named_ref(name: &str, span: Span) -> VarRef {
    VarRef { kind: VarKind::Named { name: name.to_string(), indices: vec![] }, span }
}

pub fn not(a: Expr) -> Expr {
    let span = a.span;
    Expr::new(ExprKind::Unary(UnOp::Not, Box::new(a)), span)
}

pub fn assign(target: VarRef, value: Expr, span: Span) -> Item {
    Item { kind: ItemKind::Assign { target: Box::new(target), value }, span }
}

pub fn block_stmt(meta: BlockMeta, items: Vec<Item>) -> Stmt {
    let span = meta.span;
    Stmt { kind: StmtKind::Block(Block { meta, items }), span }
}

/// A block with the given items and no number, label or comment.
pub fn plain_block(items: Vec<Item>, span: Span) -> Stmt {
    block_stmt(BlockMeta { span, ..BlockMeta::default() }, items)
}

/// A block holding only a comment.
pub fn comment_stmt(text: String, span: Span) -> Stmt {
    block_stmt(BlockMeta { span, comments: vec![Comment { text, span }], ..BlockMeta::default() }, vec![])
}

/// A block holding only a label (a GOTO target placed before a structure).
pub fn label_stmt(name: &str, span: Span) -> Stmt {
    block_stmt(BlockMeta { span, label: Some(Label { name: name.to_string(), span }), ..BlockMeta::default() }, vec![])
}

pub fn if_stmt(cond: Expr, then_body: Vec<Stmt>, else_body: Option<Vec<Stmt>>, span: Span) -> Stmt {
    let meta = BlockMeta { span, ..BlockMeta::default() };
    Stmt {
        kind: StmtKind::If(Box::new(IfStmt {
            head: meta.clone(),
            cond,
            then_body,
            else_part: else_body.map(|body| ElsePart { head: meta.clone(), body }),
            end: meta,
        })),
        span,
    }
}

/// The plain variable number of `#n` in `e` (`Some(n)` only for a bare `#n`).
pub fn bare_hash(e: &Expr) -> Option<u32> {
    match &e.kind {
        ExprKind::Var(v) => match v.kind {
            VarKind::Hash(n) => Some(n),
            _ => None,
        },
        _ => None,
    }
}

/// The variable whose vacancy `e` carries on FANUC: `#n`, `-#n`, `-[-#n]` (a negated vacant
/// value stays vacant, so `X-#1` drops its word like `X#1`).
pub fn vacancy_var(e: &Expr) -> Option<u32> {
    match &e.kind {
        ExprKind::Unary(UnOp::Neg, a) => vacancy_var(a),
        _ => bare_hash(e),
    }
}

/// Whether `e` is the vacant value itself (`#0`, `-#0`).
pub fn is_vacant_literal(e: &Expr) -> bool {
    match &e.kind {
        ExprKind::Vacant => true,
        ExprKind::Unary(UnOp::Neg, a) => is_vacant_literal(a),
        _ => bare_hash(e) == Some(0),
    }
}

pub use crate::lower::g_codes;
