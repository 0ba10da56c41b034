//! The Sinumerik → FANUC work behind [`crate::translate::translate`]: a parsed Siemens main
//! program (and the subprograms it calls) → FANUC Custom Macro B text, the symbol map that
//! relates the two, and diagnostics; and its proof ([`verify`]).
//!
//! Constructs FANUC cannot express are NC3xx errors by default; with
//! [`UnsupportedPolicy::Warn`] they are warnings and a visibly marked comment line stands in
//! their place (the translation is still not [`Output::ok`]).
//! Owns: the FANUC text, symbol map and proof of a translation. May use: `lower`, `dialect`,
//! `unfinished`, `check`, `eval`; never `batch`, `stream` or the CLI (`tests/layering.rs`).

use super::Verification;
use crate::diag::{self, Diagnostic};
use crate::dialect::fanuc::emit::{self, CommentMode, EmitOptions, KEEP_PREFIX};
use crate::dialect::{Dialect, Semantics};
use crate::ir::*;
use crate::lower::to_fanuc::varmap::{self, Mapped, VarRule};
use crate::lower::to_fanuc::{self as passes, Callee, Ctx, ProgInfo, UnsupportedPolicy};
use crate::read::LineEnding;
use crate::span::Span;
use std::collections::BTreeMap;

mod inputs;
pub mod numbers;
mod proof;
pub use proof::{align_source, reparse, source_semantics, target_semantics, verify, with_globals, EXCLUDE};
mod start_values;
use inputs::map_set_lines;
pub use inputs::{
    fanuc_set_inputs, gud_homes_in, gud_inputs, gud_seed_inputs, main_proof, proof_homes, proof_source, r_param_homes,
    r_param_inputs, standalone_args, var_param_inputs, MainProof,
};
pub use start_values::{def_names as main_def_names, proof_sets, warning as unused_input_warning};

/// First O number given to subprograms without a `--program-map` entry.
pub const FIRST_SUB_NUMBER: u32 = 9000;
/// O number of the main program without `--program-number` or a map entry.
pub const DEFAULT_MAIN_NUMBER: u32 = 1;

#[derive(Clone, Debug)]
pub struct TranslateOptions {
    pub unsupported: UnsupportedPolicy,
    /// `--var-map` rules.
    pub var_rules: Vec<VarRule>,
    /// `--tool-map NAME=n`.
    pub tool_map: BTreeMap<String, u32>,
    /// `--program-map NAME=9001` (names upper case).
    pub program_map: BTreeMap<String, u32>,
    /// `--l-numbers`: a program named `L<k>` (no leading zero) is `O<k>`, and a call of
    /// `"L"<<n` is `G65 P<n>` ([`crate::lower::to_fanuc::words`]).
    pub l_numbers: bool,
    /// Largest O number of the target series (9999; 99999999 on the 30i class).
    pub max_program_number: u32,
    /// `--program-number`: O number of the main program.
    pub program_number: Option<u32>,
    pub comments: CommentMode,
    /// `--number-blocks k`.
    pub number_blocks: Option<u32>,
    pub line_ending: LineEnding,
    /// The target control accepts `[[a] AND [b]]`.
    pub compound_conditions: bool,
    /// The target profile (NAT bit).
    pub target: Semantics,
    /// The source profile (number of R parameters).
    pub source: Semantics,
    /// Name of the main program (file stem) when the program does not name itself.
    pub main_name: String,
    /// File name shown in the header.
    pub source_name: String,
    /// The main file is a subprogram (`.SPF`) translated on its own.
    pub main_is_sub: bool,
}

impl Default for TranslateOptions {
    fn default() -> Self {
        TranslateOptions {
            unsupported: UnsupportedPolicy::Error,
            var_rules: vec![],
            tool_map: BTreeMap::new(),
            program_map: BTreeMap::new(),
            program_number: None,
            l_numbers: false,
            max_program_number: 9999,
            comments: CommentMode::Keep,
            number_blocks: None,
            line_ending: LineEnding::Lf,
            compound_conditions: false,
            target: Semantics::default_for(Dialect::Fanuc),
            source: Semantics::default_for(Dialect::Sinumerik),
            main_name: "MAIN".into(),
            source_name: String::new(),
            main_is_sub: false,
        }
    }
}

/// How source names appear in the output.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SymbolMap {
    /// Variables: R parameters (program `None`), DEF variables, parameters, temporaries.
    pub vars: Vec<Mapped>,
    /// Per program (O number): jump-target label or `N10` → FANUC N number.
    pub labels: BTreeMap<u32, BTreeMap<String, u32>>,
    /// Tool name → T number (the tools the program uses).
    pub tools: BTreeMap<String, u32>,
    /// Program name → O number.
    pub programs: BTreeMap<String, u32>,
    /// Siemens SETAL number → FANUC alarm number (3000 + n).
    pub alarms: BTreeMap<u32, u32>,
    /// Global user data mapped to FANUC commons: `(number, start value)` of every element,
    /// where the FANUC side of a check starts (the Siemens side starts at the definitions').
    pub gud_seeds: Vec<(u32, f64)>,
    /// The Siemens global user data the source was read with (its `.DEF` files), which the
    /// Siemens side of a check declares before it runs.
    pub globals: Vec<crate::ir::Def>,
    /// The output is for a Haas control (`[fanuc] series`): a check reads it back with the
    /// Haas semantics (its `G187` and `G103` look-ahead settings).
    pub haas: bool,
    /// The output is for a Haas NGC (`[fanuc] series = "haas-ngc"`): a check reads it back
    /// with the NGC variables (`#10200` is a retained common there, a tool offset on a 0i),
    /// where the translation may have placed global user data.
    pub haas_ngc: bool,
    /// The output is for a machine with the custom macro interrupt
    /// (`Semantics::macro_interrupt`): a check reads its `M96 P…`/`M97` back as interrupts.
    pub macro_interrupt: bool,
    /// The H and D registers of each Siemens cutting edge the translation used
    /// (`[offsets]`), so that a check's `$TC_DP` inputs reach the same FANUC registers.
    pub offsets: crate::dialect::offsets::OffsetMap,
    /// The values of `[variables] fixed` the translation rests on (an axis letter it wrote
    /// for `AXNAME(AXIS_HORI)`): the Siemens side of a check starts with them, and every
    /// verdict names them.
    pub fixed: BTreeMap<String, String>,
    /// The main program's own DEF variables (upper case): an input naming one replaces its
    /// start value in `run`, but not in the FANUC program, so a proof leaves it out
    /// ([`proof_sets`]).
    pub def_inputs: std::collections::BTreeSet<String>,
    /// The signal wiring the translation used (`[signals]`), so that a check's `$A_DBB[2]=…`
    /// inputs reach the FANUC variable the output reads.
    pub signals: crate::dialect::signals::SignalMap,
}

impl SymbolMap {
    /// The FANUC variable an R parameter or a main-program variable lives in (`"R1"`, `"CNT"`).
    pub fn fanuc_var(&self, source: &str) -> Option<u32> {
        let s = source.to_ascii_uppercase();
        self.vars.iter().find(|m| m.source == s).map(|m| m.number)
    }
}

/// What the FANUC writer gives: the text with the IR it was written from, which the
/// streaming translators build on (the entry turns it into a [`super::Translation`]).
#[derive(Clone, Debug)]
pub struct Output {
    pub text: String,
    /// The FANUC IR that was written (spans point into the Siemens sources).
    pub unit: Unit,
    pub symbol_map: SymbolMap,
    pub diags: Vec<Diagnostic>,
    /// Constructs that could not be expressed (also counted under the warn policy).
    pub unsupported: usize,
    /// The main program's units followed its text block by block (no paths that disagree
    /// on them, no call that changes them): what the streamed translators, which convert
    /// F words in text order, need to give the same output.
    pub units_follow_text: bool,
    /// The units the main program's words pass had going into each stand-in of a segmented
    /// stream's skeleton (`lower::to_fanuc::Ctx::stand_in_units`; none elsewhere), for the
    /// stream to check against the units its runs were translated in.
    pub stand_in_units: Vec<(usize, Option<passes::words::units::Units>)>,
}

impl Output {
    /// True when the text is a complete translation (no error, nothing unsupported).
    pub fn ok(&self) -> bool {
        !diag::has_errors(&self.diags) && self.unsupported == 0
    }
}

fn prog_name(p: &Program, fallback: &str) -> String {
    match &p.name {
        Some(ProgName::Name(n)) => n.to_ascii_uppercase(),
        Some(ProgName::Number(n)) => format!("O{n}"),
        None => fallback.to_ascii_uppercase(),
    }
}

/// Translates a Siemens main program and the subprograms it calls (each a parsed `.SPF`).
/// Under the warn policy refused blocks become marked comments whole and the program
/// alarms on its first line ([`crate::unfinished`]).
pub fn to_fanuc(main: &Unit, subs: &[&Unit], opts: &TranslateOptions) -> Output {
    to_fanuc_runs(main, subs, opts, &[])
}

/// [`to_fanuc`] of a segmented stream's skeleton: `runs` tells the passes what each run its
/// stand-ins stand for is to them (`lower::to_fanuc::Ctx::stand_in_runs`), as they would
/// see its blocks in the whole program.
pub fn to_fanuc_runs(main: &Unit, subs: &[&Unit], opts: &TranslateOptions, runs: &[u8]) -> Output {
    if opts.unsupported == UnsupportedPolicy::Error {
        return to_fanuc_strict(main, subs, opts, runs);
    }
    let strict = TranslateOptions { unsupported: UnsupportedPolicy::Error, ..opts.clone() };
    let mut all = vec![main];
    all.extend(subs.iter().copied());
    let style = |m: &str| format!("{} {m} ***", passes::UNSUPPORTED_MARK);
    let (mut t, warnings, marked, _) = crate::unfinished::translate_marking(&all, style, |us| {
        let t = to_fanuc_strict(us[0], &us[1..], &strict, runs);
        let d = t.diags.clone();
        (t, d)
    });
    if marked == 0 {
        return t;
    }
    let mut diags = warnings;
    diags.append(&mut t.diags);
    t.diags = diags;
    t.unsupported += marked;
    if let Some(p) = t.unit.programs.first_mut() {
        let span = Span::new(p.span.lo, p.span.lo);
        p.body.insert(0, crate::unfinished::summary_block(span, "*** NCTRANS:", marked));
        p.body.insert(0, crate::unfinished::alarm_block(span));
    }
    let eo = EmitOptions { comments: opts.comments, line_ending: opts.line_ending, file: main.file };
    t.text = emit::emit(&t.unit, &eo).text;
    t
}

fn to_fanuc_strict(main: &Unit, subs: &[&Unit], opts: &TranslateOptions, runs: &[u8]) -> Output {
    let mut diags = Vec::new();
    let mut unsupported = 0;
    // Programs: the main one first, then the subprograms by name.
    // Section repetitions become copies first (reported in `copies`), so every pass sees them.
    let mut copies = new_ctx(main.file, opts);
    let mut progs: Vec<(Program, crate::span::FileId, bool)> = Vec::new();
    if let Some(p) = main.programs.first() {
        progs.push((resolved(&mut copies, p), main.file, opts.main_is_sub));
    }
    let mut sub_progs: Vec<(Program, crate::span::FileId)> = Vec::new();
    for u in subs {
        copies.file = u.file;
        sub_progs.extend(u.programs.iter().map(|p| (resolved(&mut copies, p), u.file)));
    }
    unsupported += copies.unsupported;
    diags.append(&mut copies.diags);
    sub_progs.sort_by_key(|(p, _)| prog_name(p, ""));
    sub_progs.dedup_by_key(|(p, _)| prog_name(p, ""));
    progs.extend(sub_progs.into_iter().map(|(p, f)| (p, f, true)));

    // O numbers.
    let main_name =
        main.programs.first().map_or(opts.main_name.to_ascii_uppercase(), |p| prog_name(p, &opts.main_name));
    let sub_names: Vec<String> = progs.iter().skip(1).map(|(p, _, _)| prog_name(p, "")).collect();
    let numbers::Numbers { numbers, l_programs } = numbers::assign(&main_name, &sub_names, opts);
    // What each subprogram leaves changed for its caller (the words pass follows modes
    // across calls) and, for SAVE ones, restores.
    // STRING variables that hold program names (`prog_vars`): found before the effects, which
    // see a call through one as a call of every program it can name.
    let prog_vars = {
        let translated: std::collections::BTreeSet<String> = sub_names.iter().cloned().collect();
        let list: Vec<&Program> = progs.iter().map(|(p, _, _)| p).collect();
        crate::lower::to_fanuc::prog_vars::find(&list, &opts.source.globals, &translated)
    };
    let for_effects: Vec<Program> = progs
        .iter()
        .enumerate()
        .map(|(k, (p, _, _))| crate::lower::to_fanuc::prog_vars::calls_by_name(p, &prog_vars.per_prog[k]))
        .collect();
    let named: Vec<(String, &Program)> = for_effects.iter().skip(1).map(|p| (prog_name(p, ""), p)).collect();
    let effects = passes::words::effects::effects(&named);
    let mut callees = BTreeMap::new();
    for (name, p) in named {
        let number = numbers.get(&name).copied().unwrap_or(FIRST_SUB_NUMBER);
        let effect = effects.get(&name).copied().unwrap_or_default();
        callees.insert(name, Callee { number, params: p.params.clone(), effect });
    }

    // Those variables become the O numbers of the programs they name.
    for (k, (p, _, _)) in progs.iter_mut().enumerate() {
        crate::lower::to_fanuc::prog_vars::rewrite(p, &prog_vars.per_prog[k], &|n| callees.get(n).map(|c| c.number));
    }

    // Comparisons of integers (counters included) need no tolerance form.
    let types: Vec<passes::integral::Types> = progs.iter().map(|(p, _, _)| declared_types(p)).collect();
    let names: std::collections::BTreeSet<String> = progs.iter().skip(1).map(|(p, _, _)| prog_name(p, "")).collect();
    let with_types: Vec<(&Program, &passes::integral::Types)> =
        progs.iter().zip(&types).map(|((p, _, _), t)| (p, t)).collect();
    let mut exact_cmps = passes::integral::exact_comparisons(&with_types, &names).into_iter();
    let mut integral_calls = passes::integral::integral_call_numbers(&with_types, &names).into_iter();

    // Structural passes, per program.
    let mut lowered: Vec<(Program, ProgInfo, crate::span::FileId, String)> = Vec::new();
    let mut units_follow_text = true;
    let mut stand_in_units = Vec::new();
    let mut tools_used = BTreeMap::new();
    let mut fixed_used = BTreeMap::new();
    for (mut p, file, is_sub) in progs {
        crate::lower::own_header::drop_own_header(&mut p);
        if is_sub {
            p.body = ends_return(std::mem::take(&mut p.body));
        }
        let name = if lowered.is_empty() { main_name.clone() } else { prog_name(&p, "") };
        let mut ctx = new_ctx(file, opts);
        ctx.callees = callees.clone();
        ctx.prog_vars = prog_vars.per_prog.get(lowered.len()).cloned().unwrap_or_default();
        ctx.prog_var_why = prog_vars.refused.get(lowered.len()).cloned().unwrap_or_default();
        ctx.l_programs = l_programs.clone();
        ctx.integral_calls = integral_calls.next().unwrap_or_default();
        let mut info = ProgInfo { is_sub, exact_cmps: exact_cmps.next().unwrap_or_default(), ..ProgInfo::default() };
        if lowered.is_empty() {
            ctx.stand_in_runs = runs.to_vec();
        }
        passes::lower_program(&mut ctx, &mut p, &mut info);
        if lowered.is_empty() {
            units_follow_text = !ctx.units_inexact;
            stand_in_units = std::mem::take(&mut ctx.stand_in_units);
        }
        tools_used.extend(ctx.tools_used);
        fixed_used.extend(ctx.fixed_used);
        unsupported += ctx.unsupported;
        diags.extend(ctx.diags);
        lowered.push((p, info, file, name));
    }

    // Variables, across programs (R parameters and commons are shared).
    let mut vctx = new_ctx(main.file, opts);
    vctx.callees = callees.clone();
    if !prog_vars.guds.is_empty() {
        vctx.globals =
            std::sync::Arc::new(crate::lower::to_fanuc::prog_vars::globals_as_numbers(&vctx.globals, &prog_vars.guds));
    }
    let mapped = {
        let mut jobs: Vec<varmap::Job> = lowered
            .iter_mut()
            .map(|(p, info, file, name)| varmap::Job { prog: p, info, name: name.clone(), file: *file })
            .collect();
        varmap::run(&mut vctx, &mut jobs, &opts.var_rules, opts.source.r_param_count)
    };
    unsupported += vctx.unsupported;
    diags.extend(vctx.diags);

    // Jumps, headers, O numbers.
    let mut symbol_map = SymbolMap {
        vars: mapped.clone(),
        tools: tools_used,
        programs: numbers.clone(),
        gud_seeds: vctx.gud_seeds,
        globals: opts.source.globals.to_vec(),
        haas: opts.target.haas,
        haas_ngc: opts.target.haas_ngc,
        macro_interrupt: opts.target.macro_interrupt,
        offsets: opts.target.offsets.clone(),
        fixed: fixed_used,
        def_inputs: main.programs.first().map(start_values::def_names).unwrap_or_default(),
        signals: (*opts.source.signals).clone(),
        ..SymbolMap::default()
    };
    let mut programs = Vec::new();
    for (mut p, info, file, name) in lowered {
        let number = numbers.get(&name).copied().unwrap_or(DEFAULT_MAIN_NUMBER);
        if info.is_sub && !ends_with_return(&p.body) {
            let span = Span::new(p.span.hi, p.span.hi);
            p.body.push(crate::lower::block_stmt(vec![crate::lower::item(ItemKind::Return { to: None }, span)], span));
        }
        let mut ctx = new_ctx(file, opts);
        let labels = passes::labels::run(&mut ctx, &mut p, opts.number_blocks);
        unsupported += ctx.unsupported;
        diags.extend(ctx.diags);
        symbol_map.labels.insert(number, labels);
        collect_alarms(&p.body, &mut symbol_map.alarms);
        diags.extend(crate::dialect::limits::deepened(&p.body, file, Dialect::Fanuc));
        if programs.is_empty() {
            if let Some(src) = main.programs.first() {
                let (_, dropped) = proof_sets(&start_values::header_sets(&p.body), &symbol_map);
                diags.extend(dropped.iter().filter_map(|d| start_values::warning(d, src, main.file)));
            }
            map_set_lines(&mut p.body, &symbol_map);
        }
        let header = header(&name, &mapped, !programs.is_empty(), opts);
        let span = p.span;
        let head_comments = vec![Comment { text: name.clone(), span }];
        let mut body: Vec<Stmt> = header
            .into_iter()
            .map(|text| {
                crate::lower::meta_stmt(
                    BlockMeta { span, comments: vec![Comment { text, span }], ..BlockMeta::default() },
                    vec![],
                )
            })
            .collect();
        body.append(&mut p.body);
        programs.push(Program {
            name: Some(ProgName::Number(number)),
            head: Some(BlockMeta { span, comments: head_comments, ..BlockMeta::default() }),
            params: vec![],
            save: false,
            body,
            span,
        });
    }
    let unit = Unit { dialect: Dialect::Fanuc, file: main.file, programs };
    let eo = EmitOptions { comments: opts.comments, line_ending: opts.line_ending, file: main.file };
    let emitted = emit::emit(&unit, &eo);
    diags.extend(emitted.diags);
    Output { text: emitted.text, unit, symbol_map, diags, unsupported, units_follow_text, stand_in_units }
}

/// The declared types of a program's scalar names (DEF and PROC parameters).
fn declared_types(p: &Program) -> passes::integral::Types {
    let mut t: passes::integral::Types = p.params.iter().map(|prm| (prm.name.clone(), prm.ty)).collect();
    crate::ir::visit::walk_stmts(&p.body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            for it in &b.items {
                if let ItemKind::Def(d) = &it.kind {
                    t.extend(d.vars.iter().filter(|v| v.dims.is_empty()).map(|v| (v.name.clone(), d.ty)));
                }
            }
        }
    });
    t
}

fn new_ctx(file: crate::span::FileId, opts: &TranslateOptions) -> Ctx {
    let mut ctx = Ctx::new(file, opts.unsupported);
    ctx.nat = opts.target.nat;
    ctx.haas = opts.target.haas;
    ctx.haas_ngc = opts.target.haas_ngc;
    ctx.macro_interrupt = opts.target.macro_interrupt;
    ctx.compound_conditions = opts.compound_conditions;
    ctx.tools = opts.tool_map.clone();
    ctx.offsets = opts.target.offsets.clone();
    ctx.edge_default = opts.source.cutting_edge_default;
    ctx.globals = opts.source.globals.clone();
    ctx.master_spindle = opts.source.master_spindle;
    ctx.fixed = opts.source.fixed.clone();
    ctx.signals = opts.source.signals.clone();
    ctx.source_increment_mm = opts.source.least_increment_mm;
    ctx.target_increment_mm = opts.target.least_increment_mm;
    ctx
}

/// A Siemens M30/M2 in a subprogram returns to the caller (docs/semantics.md): on FANUC,
/// where it would end the whole run, it is M99.
fn ends_return(body: Vec<Stmt>) -> Vec<Stmt> {
    crate::lower::map_bodies(body, &mut |mut list| {
        let blocks = list.iter_mut().filter_map(|s| if let StmtKind::Block(b) = &mut s.kind { Some(b) } else { None });
        for it in blocks.flat_map(|b| b.items.iter_mut()).filter(|it| matches!(it.kind, ItemKind::End { .. })) {
            it.kind = ItemKind::Return { to: None };
        }
        list
    })
}

fn ends_with_return(body: &[Stmt]) -> bool {
    match body.last().map(|s| &s.kind) {
        Some(StmtKind::Block(b)) => {
            matches!(b.items.last().map(|i| &i.kind), Some(ItemKind::Return { .. } | ItemKind::End { .. }))
        }
        _ => false,
    }
}

fn collect_alarms(body: &[Stmt], out: &mut BTreeMap<u32, u32>) {
    crate::ir::visit::walk_stmts(body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            for it in &b.items {
                if let ItemKind::Alarm { number: Expr { kind: ExprKind::Num(n), .. }, text: Some(t), .. } = &it.kind {
                    if let Some(src) = t.strip_prefix("SETAL ").and_then(|s| s.parse::<u32>().ok()) {
                        out.insert(src, 3000 + n.value as u32);
                    }
                }
            }
        }
    });
}

/// The header comment lines of one program: where it came from and its variable map.
fn header(name: &str, mapped: &[Mapped], is_sub: bool, opts: &TranslateOptions) -> Vec<String> {
    let mut v = Vec::new();
    if !is_sub {
        let from = if opts.source_name.is_empty() { name.to_string() } else { opts.source_name.clone() };
        v.push(format!("{KEEP_PREFIX}: SINUMERIK {from} TO FANUC MACRO B"));
    }
    let mut temps = Vec::new();
    for m in mapped {
        let mine = match &m.program {
            None => !is_sub,
            Some(p) => p == name,
        };
        if !mine {
            continue;
        }
        if m.source == "temporary" {
            temps.push(format!("#{}", m.number));
        } else {
            v.push(format!("{KEEP_PREFIX}: {} = #{}", m.source, m.number));
        }
    }
    if !temps.is_empty() {
        v.push(format!("{KEEP_PREFIX}: TEMPORARIES {}", temps.join(" ")));
    }
    v
}

/// `p` with its calls through a STRING variable that names one program made calls by name
/// (`lower::to_fanuc::string_calls`), and its WRITEs' unread error variables gone
/// (`lower::to_fanuc::print::drop_unread_status`).
fn resolved(ctx: &mut Ctx, p: &Program) -> Program {
    let copied = passes::repeat_sections::copied(ctx, p);
    let p = copied.as_ref().unwrap_or(p);
    let p = crate::lower::to_fanuc::string_calls::resolve(p).unwrap_or_else(|| p.clone());
    crate::lower::to_fanuc::print::drop_unread_status(&p).unwrap_or(p)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lower::build::*;
    use crate::lower::{bin, cmp, func};

    fn unit(body: Vec<Stmt>) -> Unit {
        Unit { dialect: Dialect::Sinumerik, file: 0, programs: vec![program(body)] }
    }

    #[test]
    fn a_small_program_end_to_end() {
        // R1=0 / WHILE R1<3 / G1 X=R1*2 F100 / R1=R1+1 / ENDWHILE / M30
        let w = while_stmt(
            cmp_rel(CmpOp::Lt, r(1), n(3.0)),
            vec![
                block(vec![
                    word_item(b'G', n(1.0)),
                    word_item(b'X', bin(BinOp::Mul, r(1), n(2.0))),
                    word_item(b'F', n(100.0)),
                ]),
                block(vec![assign(rv(1), bin(BinOp::Add, r(1), n(1.0)))]),
            ],
        );
        let body = vec![
            block(vec![assign(rv(1), n(0.0))]),
            w,
            block(vec![crate::lower::item(ItemKind::End { code: EndCode::M30 }, sp())]),
        ];
        let t = to_fanuc(&unit(body), &[], &TranslateOptions::default());
        assert!(t.ok(), "{:?}", t.diags);
        assert_eq!(
            t.text,
            "%\nO0001 (MAIN)\n(NCTRANS: SINUMERIK MAIN TO FANUC MACRO B)\n(NCTRANS: R1 = #501)\n#501=0.\n\
             WHILE [#501 LT 3.] DO1\nG01 X[#501*2.] F100.\n#501=#501+1.\nEND1\nM30\n%\n"
        );
        assert_eq!(t.symbol_map.fanuc_var("r1"), Some(501));
    }

    #[test]
    fn roundup_and_atan2_lower_exactly() {
        let body = vec![
            block(vec![assign(rv(1), func(Func::RoundUp, vec![r(2)], sp()))]),
            block(vec![assign(rv(3), func(Func::Atan2, vec![r(4), r(5)], sp()))]),
        ];
        let t = to_fanuc(&unit(body), &[], &TranslateOptions::default());
        assert!(t.ok(), "{:?}", t.diags);
        let body: Vec<&str> =
            t.text.lines().filter(|l| !l.starts_with('(') && !l.starts_with('O') && *l != "%").collect();
        assert_eq!(
            body,
            [
                "#1=FIX[#502]",
                "IF [#502 GT #1] THEN #1=#1+1.",
                "#501=#1",
                "#2=ATAN[#504]/[#505]",
                "IF [#2 GT 180.] THEN #2=#2-360.",
                "#503=#2"
            ]
        );
    }

    #[test]
    fn if_else_with_labels_gets_fresh_n_numbers() {
        let i = if_stmt(
            cmp(CmpOp::Gt, r(1), n(0.0)),
            vec![block(vec![word_item(b'X', n(1.0))])],
            Some(vec![block(vec![word_item(b'X', n(2.0))])]),
        );
        let t = to_fanuc(&unit(vec![i]), &[], &TranslateOptions::default());
        let body: Vec<&str> =
            t.text.lines().filter(|l| !l.starts_with('(') && !l.starts_with('O') && *l != "%").collect();
        assert_eq!(body, ["IF [#501 LE 0.] GOTO 1000", "X1.", "GOTO 1001", "N1000", "X2.", "N1001"]);
    }

    #[test]
    fn unsupported_warn_marks_the_line() {
        // Marking finds the block by its span: a parsed program.
        let mut db = crate::span::SourceDb::new();
        let file = db.add("w.mpf", "G500 X1\nM30\n".to_string());
        let p =
            crate::parse(&db, file, Dialect::Sinumerik, &crate::dialect::ParseOptions::for_dialect(Dialect::Sinumerik));
        let opts = TranslateOptions { unsupported: UnsupportedPolicy::Warn, ..TranslateOptions::default() };
        let t = to_fanuc(&p.unit, &[], &opts);
        assert!(!t.ok());
        assert!(!t.text.contains("X1."), "{}", t.text);
        // Synthetic IR without spans cannot be marked: the errors stay errors.
        let body = vec![block(vec![word_item(b'G', n(500.0))])];
        let t2 = to_fanuc(&unit(body), &[], &opts);
        assert!(crate::diag::has_errors(&t2.diags));
        assert!(
            t.text.contains("(*** NCTRANS UNSUPPORTED: G500 cannot be translated to FANUC Macro B ***)"),
            "{}",
            t.text
        );
        assert!(t.text.contains("\n#3000=999(UNFINISHED TRANSLATION)\n"), "{}", t.text);
    }
}
