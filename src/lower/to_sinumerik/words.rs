//! Address words, G codes, messages, alarms and system variables.
//!
//! - Dimensional words written without a decimal point are in least input increments on
//!   FANUC: `X10` → `X0.01` on the default IS-B metric profile, `Z1000` → `Z0.1` under G20
//!   (0.0001 in; the Siemens program runs in G700, in inch), by the evaluator's rule
//!   (`dialect::semantics::input_increment`); none with calculator-type input. Where the
//!   unit is not known (paths disagree, a caller's unit that differs between calls) such a
//!   value is refused (NC375). Expressions (`X[#1+2]`, `X#1`) are already in the unit.
//! - G codes: identical ones are kept; `G20/G21` → `G700/G710` (feeds follow the unit, as on
//!   FANUC); `G58/G59` → `G505/G506`; `G61` → `G60`; `G80` dropped (no cycle can be active),
//!   `G69`/`G15` too (G68/G16 are refused, frames.rs);
//!   `G43/G44/G49` and their `H` dropped with a warning (Siemens applies the length of the
//!   active D itself); everything else is unsupported.
//! - `G04 P500` → `G4 F0.5`, `G04 X1.5` → `G4 F1.5`, in a block of its own.
//! - `R` in an arc block → `CR=`.
//! - `#3000=n(TEXT)` → `SETAL(65000+n) ; TEXT` (the checker pairs 3000+n with 65000+n); `#3006=n(TEXT)` → `MSG("TEXT")`
//!   and `M0`.
//! - System variables as `docs/translation-fanuc-to-sinumerik.md` lists them (see [`system_var`]); reading an actual position
//!   puts `STOPRE` in front; writing a work offset re-selects the active offset.

use super::*;

/// Siemens alarm number base for FANUC macro alarms: `#3000=n` → `SETAL(65000+n)`.
pub const MACRO_ALARM_BASE: i64 = 65000;

pub use crate::lower::restate::{rotary_letter, scaled_letter};

/// A value written without a decimal point, in the unit it is read in (mm, or inch under
/// G20 `inch`; degrees when `rotary`; seconds for a dwell `X`, also `rotary`): the
/// evaluator's rule, [`crate::dialect::semantics::input_increment`].
pub fn scale(opts: &Options, v: f64, inch: bool, rotary: bool) -> f64 {
    if opts.source.increment_scaling && !opts.source.calculator_input {
        let inc = opts.source.input_increment(inch, rotary);
        // Round to the increment's decimals so 10 × 0.001 prints as 0.01, not 0.010000000000000002.
        let digits = (-inc.log10()).ceil().max(0.0) as i32 + 1;
        let f = 10f64.powi(digits);
        (v * inc * f).round() / f
    } else {
        v
    }
}

/// Whether FANUC counts a value without a decimal point in increments (not calculator-type input).
pub fn scales_bare(opts: &Options) -> bool {
    opts.source.increment_scaling && !opts.source.calculator_input
}

pub fn g_word(g10: u32, span: Span) -> Item {
    let v = f64::from(g10) / 10.0;
    Item { kind: ItemKind::Word(Word { addr: Addr::Letter(b'G'), value: WordValue::Expr(num(v, span)), span }), span }
}

pub use super::modal::ModalScan;

/// A work offset written where the offset in force depends on the path taken (or on the
/// caller): the write must be re-selected to act on Siemens, and which one is not known.
pub fn unknown_offset(ctx: &mut Ctx, span: Span) -> Option<Stmt> {
    ctx.unsupported(
        "NC373",
        span,
        "a work-offset write where the active offset (G54..G59) depends on the path taken or on the caller",
        "select the work offset (G54..G59) before the write, on every path (in a subprogram: in the subprogram)",
    )
}

/// The Siemens spelling of a FANUC G code (×10), `None` when unsupported, `Some(None)` when
/// it is dropped.
fn map_g(g: u32) -> Option<Option<u32>> {
    Some(match g {
        0 | 10 | 20 | 30 | 90 | 170 | 180 | 190 | 400 | 410 | 420 | 530 | 540 | 550 | 560 | 570 | 640 | 900 | 910
        | 940 | 950 => Some(g),
        200 => Some(7000),
        210 => Some(7100),
        580 => Some(5050),
        590 => Some(5060),
        610 => Some(600),
        // G69/G15 cancel a rotation / polar mode that cannot be active (G68/G16 are refused).
        800 | 430 | 440 | 490 | 690 | 150 => None,
        _ => return None,
    })
}

const AXES: [&str; 6] = ["X", "Y", "Z", "A", "B", "C"];

/// A FANUC system variable on Siemens (`docs/translation-fanuc-to-sinumerik.md`, Variables),
/// or `None` without a counterpart.
/// Axis numbers 1..6 are X, Y, Z, A, B, C (the profile's axis order).
pub fn system_var(n: u32, span: Span) -> Option<VarKind> {
    let axis = |base: u32| -> Option<Expr> {
        let i = n.checked_sub(base)? as usize;
        AXES.get(i).map(|a| Expr::new(ExprKind::Ident((*a).to_string()), span))
    };
    let sys = |name: &str, indices: Vec<Expr>| Some(VarKind::System { name: name.into(), indices });
    match n {
        5001..=5006 => sys("P_EP", vec![axis(5001)?]),
        5021..=5026 => sys("AA_IM", vec![axis(5021)?]),
        5041..=5046 => sys("AA_IW", vec![axis(5041)?]),
        5061..=5066 => sys("AA_MW", vec![axis(5061)?]),
        5221..=5340 => {
            let k = (n - 5221) / 20;
            let i = (n - 5221) % 20;
            let a = AXES.get(i as usize)?;
            sys(
                "P_UIFR",
                vec![
                    int(i64::from(k) + 1, span),
                    Expr::new(ExprKind::Ident((*a).to_string()), span),
                    Expr::new(ExprKind::Ident("TR".into()), span),
                ],
            )
        }
        // Modal words F and S. The G groups (`$P_GG` gives group indices, not G numbers) and
        // D (`$P_TOOL` is the edge the translation writes, not FANUC's register number)
        // become constants where known (`modal_reads`).
        4109 => sys("P_F", vec![]),
        4119 => sys("P_S", vec![]),
        3901 => sys("AC_ACTUAL_PARTS", vec![]),
        3902 => sys("AC_REQUIRED_PARTS", vec![]),
        _ => None,
    }
}

fn reads_actual(e: &Expr) -> bool {
    if let ExprKind::Var(v) = &e.kind {
        if let VarKind::Hash(5021..=5026 | 5041..=5046) = v.kind {
            return true;
        }
    }
    e.children().into_iter().any(reads_actual)
}

/// Lowers the words and messages of the current program.
pub fn lower(ctx: &mut Ctx, body: Vec<Stmt>) -> Vec<Stmt> {
    let modal = std::mem::take(&mut ctx.modal);
    let mut arc = false;
    let out = lower_list(ctx, body, &modal, &mut arc);
    ctx.modal = modal;
    out
}

fn lower_list(ctx: &mut Ctx, body: Vec<Stmt>, modal: &ModalScan, arc: &mut bool) -> Vec<Stmt> {
    let mut out = Vec::with_capacity(body.len());
    for s in body {
        let span = s.span;
        match s.kind {
            StmtKind::Block(b) => lower_block(ctx, b, span, modal, arc, &mut out),
            mut kind => {
                match &mut kind {
                    StmtKind::If(i) => {
                        i.then_body = lower_list(ctx, std::mem::take(&mut i.then_body), modal, arc);
                        if let Some(e) = &mut i.else_part {
                            e.body = lower_list(ctx, std::mem::take(&mut e.body), modal, arc);
                        }
                    }
                    StmtKind::While(w) => w.body = lower_list(ctx, std::mem::take(&mut w.body), modal, arc),
                    StmtKind::Loop(l) => l.body = lower_list(ctx, std::mem::take(&mut l.body), modal, arc),
                    StmtKind::For(f) => f.body = lower_list(ctx, std::mem::take(&mut f.body), modal, arc),
                    StmtKind::Repeat(r) => r.body = lower_list(ctx, std::mem::take(&mut r.body), modal, arc),
                    StmtKind::Do(d) => d.body = lower_list(ctx, std::mem::take(&mut d.body), modal, arc),
                    StmtKind::Block(_) => {}
                }
                out.push(Stmt { kind, span });
            }
        }
    }
    merge_reselects(&mut out);
    out
}

/// A block that only selects a work offset (`G54`): its G value.
fn selection(s: &Stmt) -> Option<f64> {
    let StmtKind::Block(b) = &s.kind else { return None };
    let m = &b.meta;
    if m.label.is_some() || m.number.is_some() || m.skip.is_some() || !m.comments.is_empty() || b.items.len() != 1 {
        return None;
    }
    match &b.items[0].kind {
        ItemKind::Word(Word { addr: Addr::Letter(b'G'), value: WordValue::Expr(e), .. }) => {
            literal(e).filter(|g| (54.0..=57.0).contains(g) || (500.0..=599.0).contains(g))
        }
        _ => None,
    }
}

/// The work offset a block of the program selects itself (`N120 G54 G0 X0`): a block that is
/// surely executed (no `/`) and holds only address words, so nothing in it reads the frame
/// before the selection takes effect.
fn selects(s: &Stmt) -> Option<f64> {
    let StmtKind::Block(b) = &s.kind else { return None };
    if b.meta.skip.is_some() || !b.items.iter().all(|it| matches!(it.kind, ItemKind::Word(_))) {
        return None;
    }
    b.items.iter().find_map(|it| match &it.kind {
        ItemKind::Word(Word { addr: Addr::Letter(b'G'), value: WordValue::Expr(e), .. }) => {
            literal(e).filter(|g| (54.0..=57.0).contains(g) || (500.0..=599.0).contains(g))
        }
        _ => None,
    })
}

/// A block of work-offset writes (`#5221=…`, `$P_UIFR` once mapped) whose values read
/// no other system variable (an actual position would depend on the frame in force).
fn frame_writes_only(s: &Stmt) -> bool {
    let StmtKind::Block(b) = &s.kind else { return false };
    let m = &b.meta;
    let system = |e: &Expr| {
        let mut other = false;
        let mut stack = vec![e];
        while let Some(e) = stack.pop() {
            match &e.kind {
                // Still FANUC variables here: `#5221..#5340` are the work offsets.
                ExprKind::Var(v) => match &v.kind {
                    VarKind::Hash(n) => other |= *n >= 1000 && !(5221..=5340).contains(n),
                    // A work offset written by G10 L2 (`calls::lower`): a stored value.
                    VarKind::System { name, .. } if name == "P_UIFR" => {}
                    VarKind::HashIndirect(_) | VarKind::System { .. } => other = true,
                    VarKind::Named { indices, .. } => stack.extend(indices.iter()),
                    VarKind::RIndirect(x) => stack.push(x),
                    VarKind::R(_) => {}
                },
                ExprKind::Binary(_, a, b) | ExprKind::Cmp(_, _, a, b) => {
                    stack.push(a);
                    stack.push(b);
                }
                ExprKind::Unary(_, a) => stack.push(a),
                ExprKind::Func(_, args) => stack.extend(args.iter()),
                _ => {}
            }
        }
        other
    };
    // A label or N number may stand on it: a jump to it writes and meets the same selection.
    m.skip.is_none()
        && !b.items.is_empty()
        && b.items.iter().all(|it| match &it.kind {
            ItemKind::Assign { target, value } => {
                let offset = match &target.kind {
                    VarKind::Hash(n @ 5221..=5340) => system_var(*n, it.span).is_some(),
                    VarKind::System { name, .. } => name == "P_UIFR",
                    _ => false,
                };
                offset && !system(value)
            }
            _ => false,
        })
}

/// Each work-offset write re-selects the offset in force; where writes follow one another
/// (`#5221=…`, `#5222=…`) or the program selects it itself right after, one selection after
/// the last does the same (nothing in between moves or reads the frame in force), and a
/// round trip does not add a `G54` line each time.
fn merge_reselects(out: &mut Vec<Stmt>) {
    // The translation's own selection is written `G540` (G54 ×10, as G54.1 … come); the
    // program's own words may still read `G54`.
    let norm = |g: Option<f64>| g.map(|g| if g < 100.0 { g * 10.0 } else { g });
    let mut i = 0;
    while i + 1 < out.len() {
        let g = norm(selection(&out[i]));
        let same_next = g.is_some() && norm(selects(&out[i + 1])) == g;
        let delayed =
            g.is_some() && i + 2 < out.len() && frame_writes_only(&out[i + 1]) && norm(selects(&out[i + 2])) == g;
        // Only a selection that follows a frame write is the translation's own.
        let after_write = i > 0 && frame_writes_only(&out[i - 1]);
        if after_write && (same_next || delayed) {
            out.remove(i);
        } else {
            i += 1;
        }
    }
}

fn message(text: &Option<String>, span: Span) -> Item {
    let t = text.clone().unwrap_or_default();
    Item { kind: ItemKind::Message { text: Some(Expr::new(ExprKind::Str(t), span)) }, span }
}

fn word_item(letter: u8, v: Expr, span: Span) -> Item {
    Item { kind: ItemKind::Word(Word { addr: Addr::Letter(letter), value: WordValue::Expr(v), span }), span }
}

fn lower_block(ctx: &mut Ctx, b: Block, span: Span, modal: &ModalScan, arc: &mut bool, out: &mut Vec<Stmt>) {
    let gs = g_codes(&b.items);
    let mut b = match super::frames::split(ctx, b, span, modal, &gs) {
        Err(b) => b,
        Ok(split) => {
            // G52, G54.1 and G28/G30 (frames.rs); the rest of the block is lowered here,
            // with the arc mode of the source block (G28 leaves the motion mode alone).
            out.extend(split.before);
            let keep_arc = *arc;
            if let Some(rest) = split.block {
                lower_block(ctx, rest, span, modal, arc, out);
            }
            *arc = keep_arc;
            out.extend(split.after);
            return;
        }
    };
    for &g in &gs {
        match g {
            20 | 30 => *arc = true,
            0 | 10 => *arc = false,
            _ => {}
        }
    }
    let dwell = gs.contains(&40);
    let comment_text = b.meta.comments.first().map(|c| c.text.clone());
    let needs_stopre = b.items.iter().any(|it| crate::ir::visit::item_exprs(it).into_iter().any(reads_actual));
    let mut items: Vec<Item> = Vec::with_capacity(b.items.len());
    let mut after: Vec<Stmt> = Vec::new();
    let mut dwell_value: Option<Expr> = None;
    let mut offset_written = false;
    for it in std::mem::take(&mut b.items) {
        let isp = it.span;
        match it.kind {
            ItemKind::Word(w) => {
                let inch = modal.inch_at(span.lo);
                if let Some(x) = lower_word(ctx, w, *arc, dwell, inch, &mut dwell_value, &gs, isp, &mut after) {
                    items.push(x);
                }
            }
            ItemKind::Alarm { style: AlarmStyle::FanucMacro, number, text } => {
                let text = text.or_else(|| comment_text.clone());
                let number_copy = number.clone();
                let n = match literal(&number) {
                    Some(v) => int(MACRO_ALARM_BASE + v.round() as i64, number.span),
                    None => bin(BinOp::Add, int(MACRO_ALARM_BASE, number.span), number),
                };
                // The text rides along as the comment of the SETAL line: a MSG before it would
                // be an extra message event the FANUC alarm does not have.
                items.push(Item {
                    kind: ItemKind::Alarm { style: AlarmStyle::Setal, number: n, text: None },
                    span: isp,
                });
                // `SETAL 65000` is the text the Sinumerik → FANUC translation gives `#3000=0`
                // (the SETAL it came from): the SETAL line says it, a round trip would repeat it.
                let own = |t: &str| {
                    literal(&number_copy)
                        .is_some_and(|v| t.trim() == format!("SETAL {}", MACRO_ALARM_BASE + v.round() as i64))
                };
                if let Some(t) = text.filter(|t| !own(t)) {
                    if !b.meta.comments.iter().any(|c| c.text.trim() == t.trim()) {
                        b.meta.comments.push(Comment { text: t, span: isp });
                    }
                }
            }
            ItemKind::StopMessage { text } => {
                let text = text.or_else(|| comment_text.clone());
                items.push(message(&text, isp));
                after.push(plain_block(vec![word_item(b'M', int(0, isp), isp)], isp));
            }
            ItemKind::Assign { target, value } => {
                if let VarKind::Hash(n @ 5221..=5340) = target.kind {
                    // Only the active offset needs re-selecting (below); unknown: NC373.
                    let active = modal.offset_at(span.lo).map(|g| g / 10 - 53);
                    offset_written |= system_var(n, isp).is_some() && active.is_none_or(|a| a == (n - 5221) / 20 + 1);
                }
                items.push(Item { kind: ItemKind::Assign { target, value }, span: isp });
            }
            kind => items.push(Item { kind, span: isp }),
        }
    }
    if dwell && dwell_value.is_none() {
        if let Some(st) = ctx.unsupported(
            "NC363",
            span,
            "G04 without a P or X time",
            "write the dwell as G04 P<ms> or G04 X<seconds>",
        ) {
            out.push(st);
        }
    }
    if let Some(v) = dwell_value {
        // G4 stands alone on Siemens.
        after.insert(
            0,
            plain_block(
                vec![
                    g_word(40, span),
                    Item {
                        kind: ItemKind::Word(Word { addr: Addr::Letter(b'F'), value: WordValue::Expr(v), span }),
                        span,
                    },
                ],
                span,
            ),
        );
    }
    if offset_written {
        match modal.offset_at(span.lo) {
            Some(g) => {
                let sg = map_g(g).flatten().unwrap_or(g);
                after.push(plain_block(vec![g_word(sg, span)], span));
            }
            None => after.extend(unknown_offset(ctx, span)),
        }
    }
    if needs_stopre {
        out.push(plain_block(vec![Item { kind: ItemKind::Stopre, span }], span));
    }
    let keep = !items.is_empty() || b.meta.number.is_some() || b.meta.label.is_some() || !b.meta.comments.is_empty();
    if keep {
        b.items = items;
        out.push(Stmt { kind: StmtKind::Block(b), span });
    }
    out.extend(after);
}

#[allow(clippy::too_many_arguments)]
fn lower_word(
    ctx: &mut Ctx,
    mut w: Word,
    arc: bool,
    dwell: bool,
    inch: Option<bool>,
    dwell_value: &mut Option<Expr>,
    gs: &[u32],
    isp: Span,
    after: &mut Vec<Stmt>,
) -> Option<Item> {
    let WordValue::Expr(e) = &mut w.value else {
        return Some(Item { kind: ItemKind::Word(w), span: isp });
    };
    if is_vacant_literal(e) {
        return None; // a vacant value drops the word
    }
    let Addr::Letter(l) = w.addr else {
        // `,C5` / `,R8`: lengths, so without a decimal point in increments like X (the
        // evaluator's rule, `eval::machine::corners`); `CHR=`/`RND=` are the same words.
        let corner = matches!(w.addr.as_str(), "CHR" | "RND");
        if let (true, ExprKind::Num(n)) = (corner, &mut e.kind) {
            if !n.point && scales_bare(ctx.opts) {
                let Some(inch) = inch else {
                    if let Some(st) = ctx.unsupported(
                        crate::eval::corner::NOT_TRANSLATABLE,
                        w.span,
                        "a chamfer or corner R without a decimal point where the unit (G20/G21) is not known",
                        "write the value with a decimal point (`,C5.`)",
                    ) {
                        after.push(st);
                    }
                    return None;
                };
                n.value = scale(ctx.opts, n.value, inch, false);
                n.point = true;
            }
        }
        return Some(Item { kind: ItemKind::Word(w), span: isp });
    };
    if l == b'G' {
        let g = literal(e).map(|v| (v * 10.0).round() as u32);
        let Some(g) = g else {
            if let Some(st) = ctx.unsupported(
                "NC363",
                w.span,
                "a G code from a variable (`G#1`)",
                "write the G code as a number; select between codes with IF/GOTO",
            ) {
                after.push(st);
            }
            return None;
        };
        if g == 40 {
            return None; // G4 is written with its value below
        }
        return match map_g(g) {
            Some(Some(sg)) => Some(g_word(sg, w.span)),
            // G43/G44/G49 are refused with their block (`passes::compensation`).
            Some(None) => None,
            None => {
                if let Some(st) = ctx.unsupported(
                    "NC363",
                    w.span,
                    &match crate::dialect::fanuc::haas_g_meaning(g) {
                        Some(m) if ctx.opts.source.haas => format!("G{} ({m})", g / 10),
                        _ => format!("G{}{}", g / 10, if g % 10 != 0 { format!(".{}", g % 10) } else { String::new() }),
                    },
                    if ctx.opts.source.haas && matches!(g, 1000 | 1010) {
                        "G101/G100 translate (AMIRROR) where every axis is written 0 and no program of the job \
                         shifts with G52: the Haas mirror is about the work zero, which its manual does not relate to G52"
                    } else {
                        "rewrite the block with G0/G1/G2/G3 moves, or translate the cycle by hand"
                    },
                ) {
                    after.push(st);
                }
                None
            }
        };
    }
    if l == b'H' && (gs.contains(&430) || gs.contains(&440) || gs.contains(&490)) {
        return None;
    }
    // Letters whose FANUC meaning here (outside calls, dwell, G10) Siemens does not share.
    if matches!(l, b'P' | b'L' | b'Q' | b'E' | b'O' | b'H') && !(dwell && l == b'P') {
        if let Some(st) = ctx.unsupported(
            "NC362",
            w.span,
            &format!("the address {} in this block", l as char),
            if l == b'P' {
                "FANUC gives it a meaning only in calls, dwells, cycles and G10 (and `M96 P…`, the custom macro \
                 interrupt, where nctrans.toml says `[fanuc] macro_interrupt = true`); remove it or translate the \
                 block by hand"
            } else {
                "FANUC gives it a meaning only in calls, dwells, cycles and G10; remove it or translate the block by hand"
            },
        ) {
            after.push(st);
        }
        return None;
    }
    if dwell && matches!(l, b'P' | b'X') {
        // G04 P as the evaluator reads it (`eval::machine::motion`, dwell_p): milliseconds,
        // a Haas literal with a decimal point seconds; the forms it refuses are refused here.
        let haas = ctx.opts.source.haas;
        let secs = match (l, &e.kind) {
            (b'P', ExprKind::Num(n)) if n.point && haas => num(n.value, e.span),
            (b'P', ExprKind::Num(n)) if n.point => {
                if let Some(st) = ctx.unsupported(
                    crate::eval::machine::DWELL_FANUC_POINT,
                    w.span,
                    "a FANUC G04 P with a decimal point (P is whole milliseconds; a point there is not settled)",
                    "write the milliseconds without a point (G04 P500) or the seconds as G04 X0.5",
                ) {
                    after.push(st);
                }
                // Refused: no second diagnostic for a G04 "without a time".
                *dwell_value = Some(num(0.0, e.span));
                return None;
            }
            (b'P', ExprKind::Num(n)) => num(n.value.round() / 1000.0, e.span),
            (b'P', _) if haas => {
                if let Some(st) = ctx.unsupported(
                    crate::eval::machine::DWELL_HAAS_COMPUTED,
                    w.span,
                    "a Haas G04 P from a variable or expression (its unit is the written decimal point's, which a computed value has not)",
                    "write the time as a literal (P0.5 is 0.5 s, P500 is 500 ms) or as G04 X<seconds>",
                ) {
                    after.push(st);
                }
                *dwell_value = Some(num(0.0, e.span));
                return None;
            }
            // An integer address: FANUC rounds the value to whole milliseconds.
            (b'P', _) => bin(BinOp::Div, func(Func::Round, vec![e.clone()], e.span), int(1000, e.span)),
            (_, ExprKind::Num(n)) if !n.point => num(scale(ctx.opts, n.value, false, true), e.span),
            _ => e.clone(),
        };
        *dwell_value = Some(secs);
        return None;
    }
    if scaled_letter(l) {
        let rotary = rotary_letter(l);
        let counted = matches!(&e.kind, ExprKind::Num(n) if !n.point) && scales_bare(ctx.opts);
        let rounds = matches!(&e.kind, ExprKind::Func(Func::FanucRound, _));
        let inch = match inch {
            Some(u) => u,
            None if (counted && !rotary) || rounds => {
                let what = if rounds { "ROUND in an address" } else { "a value without a decimal point" };
                if let Some(st) = ctx.refuse(
                    "NC375",
                    w.span,
                    &format!("{what} where the unit (G20/G21) depends on the path taken or on the caller"),
                    what,
                    "write the value with a decimal point, or select G20/G21 before it (in a subprogram: in the subprogram)",
                ) {
                    after.push(st);
                }
                return None;
            }
            None => false,
        };
        if let ExprKind::Num(n) = &mut e.kind {
            if !n.point {
                n.value = scale(ctx.opts, n.value, inch, rotary);
                n.point = true;
            }
        }
        // ROUND in an address rounds to the address increment (pitfall 3).
        if let ExprKind::Func(Func::FanucRound, args) = &e.kind {
            if let Some(a) = args.first() {
                // The evaluator's address increment (`eval::expr` in_address), angles too.
                let f = (1.0 / ctx.opts.source.input_increment(inch, false)).round();
                let sp = e.span;
                *e = bin(BinOp::Div, func(Func::Round, vec![bin(BinOp::Mul, a.clone(), num(f, sp))], sp), num(f, sp));
            }
        }
    }
    // FANUC rounds the spindle speed to a whole number (half away from zero); Siemens keeps
    // the fraction: `S[#10]` → `S=ROUND(…)`, as its ROUND rounds.
    if l == b'S' {
        match &mut e.kind {
            ExprKind::Num(n) => n.value = n.value.round(),
            _ => {
                let sp = e.span;
                *e = func(Func::Round, vec![e.clone()], sp);
            }
        }
    }
    if l == b'R' {
        if arc {
            w.addr = Addr::Name("CR".into());
        } else {
            if let Some(st) = ctx.unsupported(
                "NC364",
                w.span,
                "an R word outside an arc (canned-cycle R plane)",
                "translate the cycle by hand; in arcs R becomes CR=",
            ) {
                after.push(st);
            }
            return None;
        }
    }
    Some(Item { kind: ItemKind::Word(w), span: isp })
}
