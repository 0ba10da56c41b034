//! From a block's parts to its IR: program and sequence numbers, macro statements (one per
//! block), `#3000`/`#3006`, calls (`G65`, `G66`, `M98`), returns and ends, Macro A, and the
//! `G10 L50` … `G11` parameter-write mode in which `N` is a parameter number.

use super::parse::{Part, Parts, RawWord, Seg};
use super::{args, macro_a};
use crate::diag::Diagnostic;
use crate::dialect::ParseOptions;
use crate::ir::{
    Addr, AlarmStyle, Block, BlockMeta, CallKind, Comment, EndCode, Expr, ExprKind, Goto, Item, ItemKind, ParamWrite,
    Search, SeqNo, VarKind, VarRef, Word, WordValue,
};
use crate::span::{FileId, Span};

pub struct BlockCx<'s, 'a> {
    pub file: FileId,
    pub seg: &'s Seg<'a>,
    /// The whole block, `;` included.
    pub span: Span,
    /// Inside `G10 L50` … `G11`; updated by the block.
    pub param_mode: bool,
    #[allow(dead_code)]
    pub opts: &'s ParseOptions,
}

/// A block as the structurer sees it.
#[derive(Clone, Debug)]
pub enum Line {
    /// `O1234` / `:1234`: a new program starts.
    Program {
        number: u32,
        meta: BlockMeta,
    },
    Block(Block),
    /// `WHILE[c]DOm` (`cond` set) or `DOm`.
    DoHead {
        meta: BlockMeta,
        id: u64,
        id_span: Span,
        cond: Option<Expr>,
    },
    /// `ENDm`.
    DoEnd {
        meta: BlockMeta,
        id: u64,
        id_span: Span,
    },
}

impl Line {
    pub fn meta(&self) -> &BlockMeta {
        match self {
            Line::Program { meta, .. } | Line::DoHead { meta, .. } | Line::DoEnd { meta, .. } => meta,
            Line::Block(b) => &b.meta,
        }
    }
}

fn is_g(w: &RawWord, code: u64) -> bool {
    w.letter == b'G' && w.int() == Some(code)
}

fn is_m(w: &RawWord, code: u64) -> bool {
    w.letter == b'M' && w.int() == Some(code)
}

/// Builds one block. Errors are returned as the block's single diagnostic.
pub fn build(cx: &mut BlockCx<'_, '_>, parts: Parts) -> Result<Line, Diagnostic> {
    match plain(cx, parts) {
        Ok(line) => Ok(line),
        Err(parts) => build_general(cx, parts),
    }
}

/// The words of a plain motion block (nearly every block of a CAM program) become its items
/// directly: what [`build_general`] does for a block of address words only, outside
/// parameter-write mode, with at most a leading valid `N`, and none of the words that mean
/// more (`O`, a later `N`, G10 G65 G66 G67, M2 M30 M98 M99). Any other block is handed back.
fn plain(cx: &BlockCx<'_, '_>, parts: Parts) -> Result<Line, Parts> {
    if cx.param_mode || parts.parts.is_empty() {
        return Err(parts);
    }
    let mut words = 0;
    for (i, p) in parts.parts.iter().enumerate() {
        let Part::Word(w) = p else { return Err(parts) };
        let ok = match w.letter {
            b'N' => i == 0 && w.int().is_some_and(|n| (1..=99_999).contains(&n)),
            b'O' => false,
            b'G' => !matches!(w.int(), Some(10 | 65 | 66 | 67)),
            b'M' => !matches!(w.int(), Some(2 | 30 | 96 | 97 | 98 | 99)),
            _ => true,
        };
        if !ok {
            return Err(parts);
        }
        words += usize::from(w.letter != b'N');
    }
    let mut meta = BlockMeta { span: cx.span, skip: parts.skip, ..BlockMeta::default() };
    let mut items = Vec::with_capacity(words);
    for p in parts.parts {
        let Part::Word(w) = p else { continue };
        if w.letter == b'N' {
            meta.number = w.int().map(|n| SeqNo { value: n as u32, span: w.span });
            continue;
        }
        // In written order, so already sorted by position as `build_general` sorts them.
        items.push(Item {
            kind: ItemKind::Word(crate::ir::Word {
                addr: crate::ir::Addr::Letter(w.letter),
                value: crate::ir::WordValue::Expr(w.value),
                span: w.span,
            }),
            span: w.span,
        });
    }
    Ok(Line::Block(Block { meta, items }))
}

/// Builds any block (see [`build`]).
fn build_general(cx: &mut BlockCx<'_, '_>, parts: Parts) -> Result<Line, Diagnostic> {
    let seg = cx.seg;
    let mut meta = BlockMeta { span: cx.span, skip: parts.skip, ..BlockMeta::default() };
    let mut comments: Vec<Comment> = Vec::new();
    let mut rest: Vec<Part> = parts.parts;
    // Most blocks have no comment: then the parts are used as they are.
    if rest.iter().any(|p| matches!(p, Part::Comment(_))) {
        let all = std::mem::take(&mut rest);
        rest.reserve(all.len());
        for p in all {
            match p {
                Part::Comment(c) => comments.push(c),
                other => rest.push(other),
            }
        }
    }

    // Program number: O1234 / :1234, alone in its block (comments allowed).
    if let Some((number, span)) = program_number(seg, rest.first())? {
        if let Some(extra) = rest.get(1) {
            return Err(Diagnostic::error("NC169", "a program number must be alone in its block")
                .primary(cx.file, part_span(extra), "more after the program number")
                .secondary(cx.file, span, "program number")
                .hint("start the next block on a new line"));
        }
        if meta.skip.is_some() {
            return Err(Diagnostic::error("NC169", "a program number cannot be skipped")
                .primary(cx.file, span, "after `/`")
                .hint("remove the `/` before the program number"));
        }
        meta.comments = comments;
        return Ok(Line::Program { number, meta });
    }

    let has_g11 = rest.iter().any(|p| matches!(p, Part::Word(w) if is_g(w, 11)));
    let params = cx.param_mode && !has_g11;
    // The leading N is the sequence number; inside G10 L50 only when another N follows
    // (`N160 N6200 R…`), since there `N` alone is the parameter number.
    let n_words = rest.iter().filter(|p| matches!(p, Part::Word(w) if w.letter == b'N')).count();
    if let Some(Part::Word(w)) = rest.first() {
        if w.letter == b'N' && (!params || n_words >= 2) {
            meta.number = Some(seq_no(seg, w)?);
            rest.remove(0);
        }
    }

    let mut items: Vec<Item> = Vec::new();
    let mut words: Vec<RawWord> = Vec::with_capacity(rest.len());
    // The macro statement of the block, if any: (span, is plain GOTO).
    let mut statement: Option<(Span, bool)> = None;
    let mut note_statement = |span: Span, plain_goto: bool| -> Result<(), Diagnostic> {
        if let Some((first, _)) = statement {
            return Err(Diagnostic::error("NC167", "two macro statements in one block")
                .primary(cx.file, span, "second statement")
                .secondary(cx.file, first, "first statement")
                .note("a FANUC block holds at most one macro statement")
                .hint("put each statement in its own block"));
        }
        statement = Some((span, plain_goto));
        Ok(())
    };
    let only = rest.len() == 1;
    // Haas `IF [c] <NC words>`: the condition over the rest of the block.
    let mut haas_if: Option<(Expr, Span)> = None;
    for p in rest {
        match p {
            Part::Word(w) => words.push(w),
            Part::Corner { chamfer, value, span } => {
                let name = if chamfer { "CHR" } else { "RND" };
                let w = Word { addr: Addr::Name(name.into()), value: WordValue::Expr(value), span };
                items.push(Item { kind: ItemKind::Word(w), span });
            }
            Part::ColonProg { span, .. } => return Err(misplaced_program(cx.file, span)),
            Part::Comment(_) => {}
            Part::Assign { target, value, span } => {
                note_statement(span, false)?;
                items.push(assign(cx, target, value, span, &mut comments)?);
            }
            Part::Goto { target, span } => {
                note_statement(span, true)?;
                items.push(Item {
                    kind: ItemKind::Goto(Box::new(Goto {
                        search: Search::ForwardThenWrap,
                        target,
                        cond: None,
                        missing_continues: false,
                    })),
                    span,
                });
            }
            Part::If { cond, then: None, span } => {
                note_statement(span, false)?;
                haas_if = Some((cond, span));
            }
            Part::If { cond, then: Some(then), span } => {
                note_statement(span, false)?;
                let kind = match *then {
                    Part::Goto { target, .. } => ItemKind::Goto(Box::new(Goto {
                        search: Search::ForwardThenWrap,
                        target,
                        cond: Some(cond),
                        missing_continues: false,
                    })),
                    Part::Assign { target, value, span: s } => {
                        ItemKind::IfThen { cond, then: Box::new(assign(cx, target, value, s, &mut comments)?) }
                    }
                    other => return Err(misplaced(cx.file, part_span(&other))),
                };
                items.push(Item { kind, span });
            }
            Part::DataOut { text, span } => {
                note_statement(span, false)?;
                let kind = super::print::dprnt(&text, span).unwrap_or(ItemKind::Instruction { name: text });
                items.push(Item { kind, span });
            }
            Part::While { cond, id, id_span, span } => {
                if !only {
                    return Err(not_alone(cx.file, span, "WHILE"));
                }
                meta.comments = comments;
                return Ok(Line::DoHead { meta, id, id_span, cond: Some(cond) });
            }
            Part::Do { id, id_span, span } => {
                if !only {
                    return Err(not_alone(cx.file, span, "DO"));
                }
                meta.comments = comments;
                return Ok(Line::DoHead { meta, id, id_span, cond: None });
            }
            Part::End { id, id_span, span } => {
                if !only {
                    return Err(not_alone(cx.file, span, "END"));
                }
                meta.comments = comments;
                return Ok(Line::DoEnd { meta, id, id_span });
            }
        }
    }

    if !words.is_empty() {
        // Read before `nc_words`, which may move the words' values into the items.
        let opens_params =
            words.iter().any(|w| is_g(w, 10)) && words.iter().any(|w| w.letter == b'L' && w.int() == Some(50));
        let (word_items, is_macro) =
            if params { (vec![param_write(cx, &words)?], false) } else { nc_words(cx, &mut words)? };
        let wspan = words.iter().map(|w| w.span).reduce(Span::to).unwrap_or_default();
        // Haas `IF [c] THEN #i=… <words>`: the assignment and the words are conditional.
        let then_words =
            !is_macro && haas_if.is_none() && items.len() == 1 && matches!(items[0].kind, ItemKind::IfThen { .. });
        if then_words {
            if let Some(Item { kind: ItemKind::IfThen { cond, then }, span }) = items.pop() {
                items.push(*then);
                haas_if = Some((cond, span));
            }
        }
        if is_macro && haas_if.is_none() {
            note_statement(wspan, false)?;
        } else if let (Some((s, plain_goto)), None) = (statement, &haas_if) {
            if !plain_goto {
                return Err(Diagnostic::error("NC167", "a macro statement and NC words in one block")
                    .primary(cx.file, s, "macro statement")
                    .secondary(cx.file, wspan, "NC words")
                    .note("FANUC executes a block as either one macro statement or NC words, not both")
                    .hint("put the macro statement and the NC words in separate blocks"));
            }
        }
        if items.is_empty() {
            items = word_items;
        } else {
            items.extend(word_items);
        }
        items.sort_by_key(|i| i.span.lo);
        if opens_params {
            cx.param_mode = true;
        }
        if has_g11 {
            cx.param_mode = false;
        }
    }
    if let Some((cond, span)) = haas_if {
        let span = items.iter().map(|i| i.span).fold(span, Span::to);
        items = vec![Item { kind: ItemKind::IfBlock { cond, items }, span }];
    }
    meta.comments = comments;
    Ok(Line::Block(Block { meta, items }))
}

fn part_span(p: &Part) -> Span {
    match p {
        Part::Comment(c) => c.span,
        Part::Word(w) => w.span,
        Part::ColonProg { span, .. }
        | Part::Corner { span, .. }
        | Part::Assign { span, .. }
        | Part::Goto { span, .. }
        | Part::If { span, .. }
        | Part::While { span, .. }
        | Part::Do { span, .. }
        | Part::End { span, .. }
        | Part::DataOut { span, .. } => *span,
    }
}

fn program_number(seg: &Seg<'_>, first: Option<&Part>) -> Result<Option<(u32, Span)>, Diagnostic> {
    let (n, span, lit_ok) = match first {
        Some(Part::ColonProg { number, span }) => (Some(*number), *span, true),
        Some(Part::Word(w)) if w.letter == b'O' => (w.int(), w.span, w.lit.is_some()),
        _ => return Ok(None),
    };
    match n {
        Some(n) if (1..=99_999_999).contains(&n) => Ok(Some((n as u32, span))),
        Some(0) => Err(Diagnostic::error("NC169", "program number 0 is not allowed")
            .primary(seg.file, span, "O0")
            .note("program numbers run from 1 (O0 is rejected by the control)")
            .hint("give the program a number from 1 to 9999, e.g. `O1000`")),
        _ if !lit_ok => Err(Diagnostic::error("NC169", "a program number cannot come from a variable")
            .primary(seg.file, span, "variable program number")
            .hint("write the number itself, e.g. `O1000`")),
        _ => Err(Diagnostic::error("NC169", "not a program number")
            .primary(seg.file, span, "whole number 1..99999999 expected")
            .hint("write the program number without sign or decimal point, e.g. `O1000`")),
    }
}

fn misplaced_program(file: FileId, span: Span) -> Diagnostic {
    Diagnostic::error("NC169", "a program number must start its own block")
        .primary(file, span, "program number in the middle of a block")
        .hint("put `O…` on its own line")
}

fn misplaced(file: FileId, span: Span) -> Diagnostic {
    Diagnostic::error("NC178", "THEN must be followed by one assignment")
        .primary(file, span, "not an assignment")
        .hint("write `IF[cond]THEN #i=…`")
}

fn not_alone(file: FileId, span: Span, what: &str) -> Diagnostic {
    Diagnostic::error("NC167", format!("{what} must be alone in its block"))
        .primary(file, span, format!("{what} statement"))
        .note("a loop statement is a macro statement; it cannot share its block")
        .hint("move the other words to a separate block")
}

fn seq_no(seg: &Seg<'_>, w: &RawWord) -> Result<SeqNo, Diagnostic> {
    match w.int() {
        Some(n) if (1..=99_999).contains(&n) => Ok(SeqNo { value: n as u32, span: w.span }),
        Some(0) => Err(Diagnostic::error("NC168", "N0 is not a sequence number")
            .primary(seg.file, w.span, "N0")
            .note("sequence numbers run from 1 to 99999; N0 must not be used")
            .hint("number the block from 1, e.g. `N1`, or remove the N word")),
        _ if w.lit.is_none() => Err(Diagnostic::error("NC168", "a sequence number cannot come from a variable")
            .primary(seg.file, w.span, "N with a variable or expression")
            .hint("write the number itself, e.g. `N100`; to jump to a computed number use `GOTO#1`")),
        _ => Err(Diagnostic::error("NC168", "not a sequence number")
            .primary(seg.file, w.span, "whole number 1..99999 expected")
            .hint("write N with up to five digits and no decimal point, e.g. `N100`")),
    }
}

fn assign(
    cx: &BlockCx<'_, '_>,
    target: VarRef,
    value: Expr,
    span: Span,
    comments: &mut Vec<Comment>,
) -> Result<Item, Diagnostic> {
    // The message of #3000/#3006 is the comment that follows the value.
    let mut take_text = |after: u32| -> Option<String> {
        let i = comments.iter().position(|c| c.span.lo >= after)?;
        Some(comments.remove(i).text)
    };
    let kind = match target.kind {
        VarKind::Hash(0) => {
            return Err(Diagnostic::error("NC170", "#0 cannot be assigned")
                .primary(cx.file, target.span, "#0 is always vacant")
                .note("#0 is the null variable: it can be read (as vacant) but never written")
                .hint("to make a variable vacant write `#1=#0`; to store a value use another variable"));
        }
        VarKind::Hash(3000) => {
            ItemKind::Alarm { style: AlarmStyle::FanucMacro, number: value, text: take_text(span.hi) }
        }
        VarKind::Hash(3006) => ItemKind::StopMessage { text: take_text(span.hi) },
        _ => ItemKind::Assign { target: Box::new(target), value },
    };
    Ok(Item { kind, span })
}

/// NC words, with the calls, returns and ends they spell. Returns the items and whether the
/// block is a macro statement (a G65/G66 call or Macro A).
fn nc_words(cx: &BlockCx<'_, '_>, words: &mut [RawWord]) -> Result<(Vec<Item>, bool), Diagnostic> {
    let seg = cx.seg;
    if let Some(gi) = words.iter().position(|w| is_g(w, 65) || is_g(w, 66)) {
        let g = &words[gi];
        let others: Vec<&RawWord> = words.iter().enumerate().filter(|(i, _)| *i != gi).map(|(_, w)| w).collect();
        let h = others.iter().position(|w| w.letter == b'H');
        let p = others.iter().position(|w| w.letter == b'P');
        let macro_a = is_g(g, 65)
            && match (h, p) {
                (Some(_), None) => true,
                (Some(h), Some(p)) => h < p || matches!(others[p].value.kind, ExprKind::Var(_)),
                _ => false,
            };
        let item = if macro_a {
            macro_a::lower(seg, g, &others)?
        } else {
            let kind = if is_g(g, 65) { CallKind::G65 } else { CallKind::G66 };
            args::macro_call(seg, kind, g, &others)?
        };
        return Ok((vec![item], true));
    }
    let mut items = Vec::with_capacity(words.len());
    // M98 and M99 take the first P (and L) word as their argument: those are the only
    // words ever used up, so two flags stand for a per-word table.
    let first_p = words.iter().position(|w| w.letter == b'P');
    let first_l = words.iter().position(|w| w.letter == b'L');
    let (mut used_p, mut used_l) = (false, false);
    // Without M98/M99 no word is read after its own turn, so a plain word's value can be
    // moved into its item instead of cloned.
    let haas = cx.opts.semantics.haas;
    let movable = !words.iter().any(|w| is_m(w, 98) || is_m(w, 99) || is_m(w, 96) || (haas && is_m(w, 97)));
    for i in 0..words.len() {
        if (used_p && Some(i) == first_p) || (used_l && Some(i) == first_l) {
            continue;
        }
        let w = &words[i];
        if w.letter == b'M' {
            if is_m(w, 98) {
                let (p, l) = (first_p, first_l);
                used_p |= p.is_some();
                used_l |= l.is_some();
                items.push(args::m98(seg, w, p.map(|k| &words[k]), l.map(|k| &words[k]))?);
                continue;
            }
            // The custom macro interrupt, where the profile says the machine has it.
            let interrupt = cx.opts.semantics.macro_interrupt && !haas;
            if interrupt && is_m(w, 96) {
                let Some(k) = first_p.filter(|_| !used_p) else {
                    return Err(Diagnostic::error("NC638", "M96 without the interrupt program's number")
                        .primary(seg.file, w.span, "M96 enables the interrupt program P")
                        .hint("write the program number: `M96 P9000`"));
                };
                used_p = true;
                let n = match &words[k].value.kind {
                    ExprKind::Num(n) if !n.point && n.value >= 1.0 && n.value.fract() == 0.0 => n.value as u32,
                    _ => {
                        return Err(Diagnostic::error("NC638", "M96 P takes a constant program number")
                            .primary(seg.file, words[k].span, "not a whole constant")
                            .hint("write the program number: `M96 P9000`"))
                    }
                };
                let span = w.span.to(words[k].span);
                items.push(Item { kind: ItemKind::Instruction { name: format!("M96 P{n}") }, span });
                continue;
            }
            if interrupt && is_m(w, 97) {
                items.push(Item { kind: ItemKind::Instruction { name: "M97".into() }, span: w.span });
                continue;
            }
            if haas && is_m(w, 97) {
                let (p, l) = (first_p, first_l);
                used_p |= p.is_some();
                used_l |= l.is_some();
                items.push(args::m97(seg, w, p.map(|k| &words[k]), l.map(|k| &words[k]))?);
                continue;
            }
            if is_m(w, 99) {
                let p = first_p;
                let mut span = w.span;
                if let Some(k) = p {
                    used_p = true;
                    span = span.to(words[k].span);
                }
                items.push(Item { kind: ItemKind::Return { to: p.map(|k| words[k].value.clone()) }, span });
                continue;
            }
            let code = if is_m(w, 30) {
                Some(EndCode::M30)
            } else if is_m(w, 2) {
                Some(EndCode::M2)
            } else {
                None
            };
            if let Some(code) = code {
                items.push(Item { kind: ItemKind::End { code }, span: w.span });
                continue;
            }
        }
        if is_g(w, 67) {
            items.push(Item { kind: ItemKind::ModalCallOff, span: w.span });
            continue;
        }
        if w.letter == b'N' {
            return Err(Diagnostic::error("NC168", "N in the middle of a block")
                .primary(seg.file, w.span, "a sequence number must start the block")
                .note("`N` is only allowed at the start of a block (after `/`), or as a parameter number inside G10 L50 … G11")
                .hint("move the N number to the start of the block"));
        }
        if w.letter == b'O' {
            return Err(misplaced_program(seg.file, w.span));
        }
        let (letter, span) = (w.letter, w.span);
        let value =
            if movable { std::mem::replace(&mut words[i].value, Expr::num(0.0, false, span)) } else { w.value.clone() };
        items.push(Item {
            kind: ItemKind::Word(crate::ir::Word {
                addr: crate::ir::Addr::Letter(letter),
                value: crate::ir::WordValue::Expr(value),
                span,
            }),
            span,
        });
    }
    Ok((items, false))
}

/// Inside `G10 L50` … `G11`: `N<param> [P<axis>] [Q<bit>] R<value>`.
fn param_write(cx: &BlockCx<'_, '_>, words: &[RawWord]) -> Result<Item, Diagnostic> {
    let get = |l: u8| words.iter().find(|w| w.letter == l).map(|w| w.value.clone());
    if let Some(w) = words.iter().find(|w| !matches!(w.letter, b'N' | b'P' | b'Q' | b'R')) {
        return Err(Diagnostic::error("NC181", format!("`{}` in parameter-write mode", w.letter as char))
            .primary(cx.file, w.span, "only N, P, Q and R are read here")
            .note("between `G10 L50` and `G11` every block is `N<parameter> [P<axis>] [Q<bit>] R<value>`")
            .hint("end parameter-write mode with `G11` before other commands"));
    }
    let span = words.iter().map(|w| w.span).reduce(Span::to).unwrap_or(cx.span);
    let (Some(number), Some(value)) = (get(b'N'), get(b'R')) else {
        return Err(Diagnostic::error("NC181", "a parameter write needs N and R")
            .primary(cx.file, span, "incomplete parameter write")
            .hint("write `N<parameter number> R<value>`, e.g. `N6200 R11000000`"));
    };
    Ok(Item {
        kind: ItemKind::ParamWrite(Box::new(ParamWrite { number, axis: get(b'P'), bit: get(b'Q'), value })),
        span,
    })
}

/// For tests: one block's line built by [`plain`] (when it takes the block) and by
/// [`build_general`], from the grammar's parts, in or outside parameter-write mode; each as
/// its debug text with the parameter-write mode after it. `None` when the grammar rejects
/// the block or `plain` declines it.
#[doc(hidden)]
pub fn both_ways_for_test(text: &str, param_mode: bool) -> Option<(String, String)> {
    super::parse::with_seg(text, |seg, opts| {
        let parts = super::parse::parse_block(seg, opts).ok()?;
        let span = seg.span(0, seg.text.len());
        let mut cx = BlockCx { file: seg.file, seg, span, param_mode, opts };
        let fast = plain(&cx, parts.clone()).ok()?;
        let fast = format!("{fast:?} {}", cx.param_mode);
        let general = match build_general(&mut cx, parts) {
            Ok(line) => format!("{line:?} {}", cx.param_mode),
            Err(d) => format!("error {d:?}"),
        };
        Some((fast, general))
    })
}

/// For tests: a block by the one-pass readers (`fast::plain_line`, and `fast::skeleton`
/// as the meta and number of items) and by the fast path and [`plain`] (outside
/// parameter-write mode). `None` when the one-pass reader declines (the full route then
/// reads the block).
#[doc(hidden)]
pub fn skeleton_both_ways_for_test(text: &str) -> Option<(String, String)> {
    super::parse::with_seg(text, |seg, opts| {
        let (skip, number, items) = super::fast::plain_line(seg)?;
        let span = seg.span(0, seg.text.len());
        let meta = BlockMeta { span, skip, number, ..BlockMeta::default() };
        let sk = super::fast::skeleton(seg).map(|(skip, number, words)| {
            format!("{:?} {words}", BlockMeta { span, skip, number, ..BlockMeta::default() })
        });
        let one_pass = format!("{:?} / {sk:?}", Line::Block(Block { meta: meta.clone(), items }));
        let cx = BlockCx { file: seg.file, seg, span, param_mode: false, opts };
        let full = match super::fast::parse_fast(seg).map(|parts| plain(&cx, parts)) {
            Some(Ok(Line::Block(b))) => {
                let sk = format!("{:?} {}", b.meta, b.items.len());
                format!("{:?} / {:?}", Line::Block(b), Some(sk))
            }
            Some(Ok(other)) => format!("not a plain block: {other:?}"),
            Some(Err(_)) => "handed back by `plain`".to_string(),
            None => "declined by the fast path".to_string(),
        };
        Some((one_pass, full))
    })
}
