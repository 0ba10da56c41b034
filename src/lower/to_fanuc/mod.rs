//! Sinumerik → FANUC lowering: small IR→IR passes, listed in order here; the shared builders
//! and walkers are in [`crate::lower`].
//!
//! Siemens → FANUC runs, per program: [`blocks`] (one statement per block, DEF → assignments),
//! [`corners`] (CHR/RND kept, RNDM spread over its blocks, CHF at a corner known at translation
//! made its leg CHR by [`corners_chf`], else refused),
//! [`words`] (address words, calls, messages; around it [`probe`]: MEAS=1 → G31), [`cycles`] (drilling cycles), [`exprs`] (exact function rewrites, the
//! relative-equality rule, bracket depth), [`lower_structures`] (IF/WHILE/LOOP/FOR/REPEAT/CASE
//! → IF-GOTO and WHILE-DOm), [`varmap`] (R, DEF, PROC parameters and temporaries → `#n`) and
//! [`labels`] (labels and N numbers → unique FANUC N numbers). The result is IR that the FANUC
//! writer (`dialect::fanuc::emit`) can print; anything it cannot express was reported as NC3xx.
//! `fast_write` is the same translation of one plain block written straight to bytes, for
//! the streamed translator (held to these passes' bytes by the differential tests).

pub mod axis_vars;
pub mod blocks;
pub mod comp;
pub mod constants;
pub mod corners;
pub mod corners_chf;
pub mod cycles;
mod cycles_frames;
pub mod cycles_known;
pub mod cycles_tap;
pub mod exprs;
pub(crate) mod fast_write;
pub mod feed_group;
pub mod feed_reads;
pub mod frame_chain;
pub mod frame_seq;
pub mod frames;
pub mod frames_incr;
pub mod haas_mirror;
pub mod integral;
pub mod interrupt;
pub mod labels;
pub mod lookahead;
pub mod lower_structures;
pub mod modal_reads;
pub mod polar;
pub mod position_length;
pub mod print;
pub mod probe;
pub mod probe_length;
pub mod prog_vars;
pub mod repeat_sections;
pub mod rotation;
pub mod signals;
pub mod string_calls;
pub mod tool_data;
pub mod tool_reads;
pub mod varmap;
pub mod words;

// The passes below reach the shared builders and modules through `super::` (`use super::*`).
#[cfg(test)]
use super::build;
use super::{
    assign_item, bin, block_stmt, cmp, func, goto_item, if_then, item, label_stmt, meta_is_marked, meta_stmt, num,
    take_target, var_expr,
};
use crate::diag::Diagnostic;
use crate::ir::*;
use crate::span::{FileId, Span};
use std::collections::BTreeMap;

/// What to do with a construct the target cannot express.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum UnsupportedPolicy {
    /// An NC3xx error; the translation is refused.
    #[default]
    Error,
    /// An NC3xx warning and a visibly marked comment line in the output.
    Warn,
}

/// Prefix of the names of temporaries the passes introduce (never a Siemens user name:
/// names starting with `_` are reserved for Siemens cycles).
pub const TEMP_PREFIX: &str = "__NCT_T";
/// Prefix of labels the passes introduce.
pub const LABEL_PREFIX: &str = "__NCT_L";
/// The comment text that marks a line standing for an unsupported construct.
pub const UNSUPPORTED_MARK: &str = "*** NCTRANS UNSUPPORTED:";

/// The text a streamed translation's stand-in for a run of straight blocks begins its only
/// comment with (`stream::segmented::MARK`: the lowering may not name the streaming layer).
pub const SEGMENT_MARK: &str = "NCTRANS SEGMENT ";

/// The run a block stands in for, when it is a segmented stream's stand-in (its comment is
/// `SEGMENT_MARK` and the run's index).
pub fn stand_in(m: &BlockMeta) -> Option<usize> {
    m.comments.iter().find_map(|c| c.text.strip_prefix(SEGMENT_MARK)?.parse().ok())
}

/// In [`Ctx::stand_in_runs`], a run with a block that stops a dead start value's search
/// (`blocks::drop_dead_zero_stores`): one that may be skipped (`/`) or ends the program.
pub const RUN_STOPS_SEARCH: u8 = u8::MAX;

/// Facts about one source program the passes share.
#[derive(Clone, Debug, Default)]
pub struct ProgInfo {
    /// Declared type and dimensions of each named variable (DEF and PROC parameters).
    pub types: BTreeMap<String, (DataType, Vec<u32>)>,
    /// Program is a subprogram (`PROC`): runs at its own FANUC local level.
    pub is_sub: bool,
    /// Spans of the comparisons whose sides are provably integers there ([`integral`]):
    /// written as plain FANUC comparisons.
    pub exact_cmps: std::collections::BTreeSet<Span>,
}

/// A callee the translation knows: its O number, its parameters in order, and what it
/// changes of its caller's modes.
#[derive(Clone, Debug, Default)]
pub struct Callee {
    pub number: u32,
    pub params: Vec<Param>,
    pub effect: words::effects::Effect,
}

/// Why an `L<k>` program has no `O<k>` under `--l-numbers`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum LFault {
    /// `O<k>` is another program's (the main program's, a `--program-map` entry's).
    Clash { other: String },
    /// `k` is 0 or beyond the series' largest O number.
    Beyond { max: u32 },
    /// A program map (`--program-map`, `[programs.to_fanuc]`, a batch's map) gives it `O<to>`.
    Mapped { to: u32 },
}

/// State shared by the passes of one translation.
#[derive(Debug)]
pub struct Ctx {
    pub file: FileId,
    pub policy: UnsupportedPolicy,
    /// FANUC NAT bit (6004#0) of the target profile: ranges of ATAN/ASIN.
    pub nat: bool,
    /// The target accepts `[[a] AND [b]]` compound conditions.
    pub compound_conditions: bool,
    /// Tool name → FANUC T number (`--tool-map`).
    pub tools: BTreeMap<String, u32>,
    /// Tool names actually used, with their numbers (for the symbol map).
    pub tools_used: BTreeMap<String, u32>,
    /// The FANUC registers of each cutting edge (`crate::dialect::offsets::OffsetMap`).
    pub offsets: crate::dialect::offsets::OffsetMap,
    /// The Siemens profile's MD20270, when it states one (`Semantics::cutting_edge_default`).
    pub edge_default: Option<u32>,
    /// Known callees by upper-case name.
    pub callees: BTreeMap<String, Callee>,
    pub diags: Vec<Diagnostic>,
    /// Number of unsupported constructs met (also under the warn policy).
    pub unsupported: usize,
    /// The words pass met paths that disagree on the units, or a call that changes them
    /// (`words::modes`): the units did not simply follow the text.
    pub units_inexact: bool,
    /// Siemens global user data (the source profile's `Semantics::globals`).
    pub globals: std::sync::Arc<Vec<crate::ir::Def>>,
    /// Global user data mapped to FANUC commons: each element's number and start value,
    /// where the FANUC side of a check starts (`Translation::gud_seeds`).
    pub gud_seeds: Vec<(u32, f64)>,
    /// The Siemens master spindle (`Semantics::master_spindle`): `M1=3` is `M3` there.
    pub master_spindle: u32,
    /// The target is a Haas control (`Semantics::haas`): look-ahead settings become G187.
    pub haas: bool,
    /// The target is a Haas NGC (`Semantics::haas_ngc`): the NGC-only general-purpose
    /// variables (`#10000..#10099`, `#10200..#10499`, `#10700..#10799`) are retained
    /// commons a `--var-map` rule may place a variable or global user data in.
    pub haas_ngc: bool,
    /// The target has the custom macro interrupt (`Semantics::macro_interrupt`).
    pub macro_interrupt: bool,
    /// The O number the last `SETINT(1)` of this program assigned (what `ENABLE(1)`
    /// enables again), and whether two different ones were met.
    pub int_routine: Option<u32>,
    pub int_routine_changes: bool,
    /// `--l-numbers`: every `L<k>` program of the translation with its `O<k>`, or why it has
    /// none; `None` without the option (a call of `"L"<<n` is then refused).
    pub l_programs: Option<BTreeMap<String, Result<u32, LFault>>>,
    /// Spans of the numbers of `"L"<<n` calls that are provably integers where the call
    /// stands ([`integral::integral_call_numbers`]).
    pub integral_calls: std::collections::BTreeSet<Span>,
    /// The kept Z measurements of the program being lowered (`probe::take`): the measuring
    /// block's span and the span of the `T=#5063` it became, for `probe_length`.
    pub z_keeps: Vec<(Span, Span)>,
    /// The H register FANUC applies at each G31 block (`comp`, by the block's span):
    /// `Some(None)` under G49, `None` where the flow does not know it.
    pub skip_lengths: Vec<(Span, Option<Option<u32>>)>,
    /// The dropped keeps of the translation's own Z skip variable (`probe::take`): the
    /// measuring block and the `+R` each added, and the spans of its reads (now `#5063`).
    pub own_z_keeps: Vec<(Span, Option<Expr>)>,
    pub own_z_reads: Vec<Span>,
    /// The STRING variables of this program that hold program names, with the names they can
    /// hold (`prog_vars`), and those called through that cannot, with why.
    pub prog_vars: BTreeMap<String, Vec<String>>,
    pub prog_var_why: BTreeMap<String, String>,
    /// Values the machine's set-up fixes (`Semantics::fixed`), and those the translation
    /// folded into axis letters ([`axis_vars`]): what its verdict says it assumed.
    pub fixed: std::sync::Arc<BTreeMap<String, String>>,
    pub fixed_used: BTreeMap<String, String>,
    /// The machine's signal wiring (`Semantics::signals`, [`signals`]).
    pub signals: std::sync::Arc<crate::dialect::signals::SignalMap>,
    /// Spans of the axis words and AXIS DEFs [`axis_vars`] refused, saying why: the general
    /// refusals (NC310, NC635) are not repeated for them.
    pub axis_reported: std::collections::BTreeSet<Span>,
    /// For a segmented stream's skeleton, what the run each stand-in stands for ([`stand_in`],
    /// by its index) is to a dead start value's search: its number of blocks (up to
    /// [`blocks::DEAD_STORE_WINDOW`]), all of which let the search go on, or
    /// [`RUN_STOPS_SEARCH`]. A stand-in of no run given (the whole program has none) stops it.
    pub stand_in_runs: Vec<u8>,
    /// The units the words pass had going into each stand-in, by the run's index (`None`: not
    /// known there), in text order of the lowered program: the stream compares them with the
    /// units it translated each run in.
    pub stand_in_units: Vec<(usize, Option<words::units::Units>)>,
    /// The least input increment in mm of the source and of the target profile
    /// (`Semantics::least_increment_mm`): what lengths are rounded to on each side
    /// ([`corners_chf`], where a chamfer's leg must land on the target's grid).
    pub source_increment_mm: f64,
    pub target_increment_mm: f64,
    next_temp: u32,
    next_label: u32,
}

impl Ctx {
    pub fn new(file: FileId, policy: UnsupportedPolicy) -> Self {
        Ctx {
            file,
            policy,
            nat: false,
            compound_conditions: false,
            tools: BTreeMap::new(),
            tools_used: BTreeMap::new(),
            offsets: crate::dialect::offsets::OffsetMap::default(),
            edge_default: None,
            callees: BTreeMap::new(),
            diags: Vec::new(),
            units_inexact: false,
            globals: Default::default(),
            gud_seeds: Vec::new(),
            master_spindle: 1,
            haas: false,
            haas_ngc: false,
            macro_interrupt: false,
            int_routine: None,
            int_routine_changes: false,
            l_programs: None,
            integral_calls: Default::default(),
            z_keeps: Vec::new(),
            skip_lengths: Vec::new(),
            own_z_keeps: Vec::new(),
            own_z_reads: Vec::new(),
            prog_vars: BTreeMap::new(),
            prog_var_why: BTreeMap::new(),
            fixed: Default::default(),
            signals: Default::default(),
            fixed_used: BTreeMap::new(),
            axis_reported: Default::default(),
            stand_in_runs: Vec::new(),
            stand_in_units: Vec::new(),
            source_increment_mm: 0.001,
            target_increment_mm: 0.001,
            unsupported: 0,
            next_temp: 0,
            next_label: 0,
        }
    }

    /// A fresh temporary variable (mapped to a free `#n` by [`varmap`]).
    pub fn temp(&mut self, span: Span) -> VarRef {
        self.next_temp += 1;
        VarRef { kind: VarKind::Named { name: format!("{TEMP_PREFIX}{}", self.next_temp), indices: vec![] }, span }
    }

    /// A fresh label name.
    pub fn label(&mut self, span: Span) -> Label {
        self.next_label += 1;
        Label { name: format!("{LABEL_PREFIX}{}", self.next_label), span }
    }

    /// Reports a construct FANUC cannot express (NC300 unless `code` says more) and returns the
    /// replacement statement: under the warn policy a marked comment line, else nothing.
    pub fn unsupported(&mut self, code: &'static str, span: Span, what: &str, hint: &str) -> Option<Stmt> {
        self.unsupported += 1;
        let msg = format!("{what} cannot be translated to FANUC Macro B");
        let d = match self.policy {
            UnsupportedPolicy::Error => Diagnostic::error(code, msg),
            UnsupportedPolicy::Warn => Diagnostic::warning(code, msg),
        };
        let mut d = d.primary(self.file, span, "not expressible on the target");
        if !hint.is_empty() {
            d = d.hint(hint);
        }
        if self.policy == UnsupportedPolicy::Warn {
            d = d.note("--unsupported warn: a marked comment line stands in its place and the run fails");
        }
        self.diags.push(d);
        match self.policy {
            UnsupportedPolicy::Error => None,
            UnsupportedPolicy::Warn => {
                let meta = BlockMeta {
                    span,
                    comments: vec![Comment { text: format!("{UNSUPPORTED_MARK} {what} ***"), span }],
                    ..BlockMeta::default()
                };
                Some(Stmt { kind: StmtKind::Block(Block { meta, items: vec![] }), span })
            }
        }
    }

    /// A remark on a construct that was translated with a caveat (dropped, or changed form).
    pub fn note(&mut self, code: &'static str, span: Span, msg: &str, note: &str) {
        let mut d = Diagnostic::new(crate::diag::Severity::Note, code, msg).primary(self.file, span, "here");
        if !note.is_empty() {
            d = d.note(note);
        }
        self.diags.push(d);
    }

    pub fn error(&mut self, code: &'static str, span: Span, msg: &str, hint: &str) {
        let mut d = Diagnostic::error(code, msg).primary(self.file, span, "here");
        if !hint.is_empty() {
            d = d.hint(hint);
        }
        self.diags.push(d);
    }
}

/// Runs the structural passes (everything before variable mapping) on one program.
pub fn lower_program(ctx: &mut Ctx, prog: &mut Program, info: &mut ProgInfo) {
    axis_vars::run(ctx, prog);
    feed_group::run(ctx, prog, info.is_sub);
    tool_data::run(ctx, prog);
    signals::run(ctx, prog);
    tool_reads::run(prog);
    constants::run(prog);
    modal_reads::run(prog);
    feed_reads::run(ctx, prog, info.is_sub);
    blocks::run(ctx, prog, info);
    corners::run(ctx, prog, info);
    ctx.z_keeps.clear();
    ctx.skip_lengths.clear();
    ctx.own_z_keeps.clear();
    ctx.own_z_reads.clear();
    let measuring = probe::take(ctx, prog);
    let edge = !measuring.is_empty() && probe_length::check(ctx, prog);
    position_length::run(prog);
    words::run(ctx, prog, info);
    probe::put(prog, &measuring);
    comp::run(ctx, prog, info);
    if edge {
        probe_length::apply(ctx, prog);
    }
    cycles::run(ctx, prog, info);
    exprs::run(ctx, prog, info);
    lower_structures::run(ctx, prog);
    haas_mirror::run(ctx, prog);
}
