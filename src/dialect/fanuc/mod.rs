//! The FANUC Custom Macro B dialect: reading a file block by block into the IR.
//!
//! The reader splits the file into blocks (lines, and `;`-terminated parts of lines), handles
//! `%` tape marks and `O`/`:` program numbers, and hands every block to the grammar
//! (`parse.rs`, or the byte-level fast path in `fast.rs` for plain motion blocks). `block.rs`
//! turns the grammar's parts into IR items (calls, returns, alarms, Macro A lowering), and
//! `structure.rs` builds `DO`/`END` loops and checks `GOTO` targets per program.
//! Owns: FANUC reading, writing (`emit`), cycle spellings. May use: `dialect`, `ir`, base.

mod args;
mod block;
pub mod cycles;
mod expr;
pub(crate) mod fast;
pub mod haas_vars;
mod macro_a;
mod names;
mod parse;
pub mod print;
mod scan;
pub mod scan_words;
mod skeleton;
mod structure;

#[cfg(test)]
mod tests;

pub mod emit;

use crate::diag::Diagnostic;
use crate::dialect::{Dialect, ParseOptions, Parsed};
use crate::ir::{BlockMeta, ProgName, Program, Unit};
use crate::read::{self, CommentStyle, Normalised};
use crate::span::{FileId, SourceFile, Span};
use block::{BlockCx, Line};
use structure::ProgramLines;

pub use block::both_ways_for_test as build_both_ways_for_test;
pub use block::skeleton_both_ways_for_test;
pub use fast::parse_fast_for_test;
pub use names::haas_g_meaning;
pub(crate) use scan::decorative;
pub use skeleton::skeleton_bytes;

/// The index-only reader's decision on one line `text` (at file offset 0), the old way
/// (`Reader::scan_plain`'s `fast::skeleton_raw`) and the buffer way ([`skeleton_bytes`]
/// on `text` followed by `after`, which should start with a line end), each as the
/// block's span, its number (value and span) and whether it has words.
#[doc(hidden)]
#[allow(clippy::type_complexity)]
pub fn skeleton_both_for_test(
    text: &str,
    after: &str,
) -> (Option<(Span, Option<(u32, Span)>, bool)>, Option<(Span, Option<(u32, Span)>, bool)>) {
    let raw = read::RawBlock { text, start: 0, line: 1 };
    let old = if text.is_ascii() {
        fast::skeleton_raw(&raw, 0).map(|(span, n, words)| (span, n.map(|n| (n.value, n.span)), words))
    } else {
        None
    };
    let bytes = [text.as_bytes(), after.as_bytes()].concat();
    let new = skeleton_bytes(&bytes).map(|f| {
        let n = f.number.map(|(v, lo, hi)| (v, Span::new(lo as u32, hi as u32)));
        (Span::new(f.lo as u32, f.hi as u32), n, f.words)
    });
    (old, new)
}
pub use parse::parse_grammar_for_test;

/// Parses one FANUC file. Every bad block gives one diagnostic and reading continues.
pub fn parse(src: &SourceFile, file: FileId, opts: &ParseOptions) -> Parsed {
    let mut r = Reader::new(file, opts);
    for raw in read::blocks(&src.text) {
        r.line(&raw);
    }
    r.finish()
}

/// What a streaming reader needs to resume at a block boundary (see `crate::stream`).
#[derive(Clone, Copy, Debug)]
pub struct Resume {
    tape: Tape,
    param_mode: bool,
}

/// Where we are relative to the `%` tape marks.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Tape {
    /// No `%` seen yet.
    None,
    /// After the opening `%`.
    Open,
    /// After the closing `%`: the control reads nothing more.
    Closed,
}

/// The reader of one file, fed one physical line at a time: the whole-file [`parse`] and
/// the streaming reader (`crate::stream`) are the same code, so they give the same IR.
pub struct Reader<'o> {
    file: FileId,
    opts: &'o ParseOptions,
    diags: Vec<Diagnostic>,
    tape: Tape,
    /// Span of the text after the closing `%` (warned about once).
    after_end: Option<Span>,
    /// `N` numbers seen in the ignored text after the closing `%`, for GOTO notes.
    ignored_numbers: Vec<(u32, Span)>,
    /// `O` numbers starting lines of the ignored text after the closing `%`.
    ignored_programs: Vec<u32>,
    programs: Vec<ProgramLines>,
    /// Plain blocks are read for an index only: their items are not built.
    index_only: bool,
    /// Made by [`Reader::resume`]: re-reading a checked file.
    resumed: bool,
}

impl<'o> Reader<'o> {
    pub fn new(file: FileId, opts: &'o ParseOptions) -> Reader<'o> {
        Reader {
            file,
            opts,
            diags: Vec::new(),
            tape: Tape::None,
            after_end: None,
            ignored_numbers: Vec::new(),
            ignored_programs: Vec::new(),
            programs: Vec::new(),
            index_only: false,
            resumed: false,
        }
    }

    /// A reader for re-reading from a block boundary of a checked file: statements are
    /// handed out as they finish, whichever program they belong to.
    pub fn resume(file: FileId, opts: &'o ParseOptions, from: Resume) -> Reader<'o> {
        let mut r = Reader::new(file, opts);
        r.tape = from.tape;
        let mut p = ProgramLines::new(Some(ProgName::Number(0)), None, Span::default(), file, opts);
        p.param_mode = from.param_mode;
        p.stream();
        r.programs.push(p);
        r.resumed = true;
        r
    }

    /// For a first scan that only builds the index (`crate::stream::scan_index`): plain
    /// blocks get no items (the index needs their numbers and spans). The statements
    /// handed out are then skeletons, not the program's IR.
    pub fn index_only(&mut self) {
        self.index_only = true;
    }

    /// The state to resume from here.
    pub fn checkpoint(&self) -> Resume {
        Resume { tape: self.tape, param_mode: self.programs.last().is_some_and(|p| p.param_mode) }
    }

    /// Index (among all programs started so far) of the program being read.
    pub fn current(&self) -> usize {
        self.programs.len().saturating_sub(1)
    }

    /// The finished top-level statements of the current program so far (streaming; the
    /// jump targets in them are remembered compactly for the final check).
    pub fn drain(&mut self) -> Vec<crate::ir::Stmt> {
        match self.programs.last_mut() {
            Some(p) => {
                p.stream();
                p.drain()
            }
            None => Vec::new(),
        }
    }

    /// [`Reader::drain`] into `out` (appended; an empty `out` lends its capacity).
    pub fn drain_into(&mut self, out: &mut Vec<crate::ir::Stmt>) {
        if let Some(p) = self.programs.last_mut() {
            p.stream();
            p.drain_into(out);
        }
    }

    pub fn at_top(&self) -> bool {
        self.programs.last().is_none_or(|p| p.at_top())
    }

    pub fn diags(&self) -> &[Diagnostic] {
        &self.diags
    }

    /// Reads one physical line.
    pub fn line(&mut self, raw: &read::RawBlock<'_>) {
        let trimmed = read::trim(raw.text);
        if trimmed.is_empty() {
            return;
        }
        let lead = (raw.text.len() - read::trim_start(raw.text).len()) as u32;
        let line_span = Span::new(raw.start + lead, raw.start + lead + trimmed.len() as u32);
        if self.tape == Tape::Closed {
            self.after_end = Some(self.after_end.map_or(line_span, |s| s.to(line_span)));
            if let Some(n) = scan::leading_number(trimmed) {
                self.ignored_numbers.push((n, line_span));
            }
            if let Some(n) = scan::program_number(trimmed) {
                self.ignored_programs.push(n);
            }
            return;
        }
        let norm = read::normalise(raw, CommentStyle::Parens);
        self.diags.extend(norm.warnings(self.file));
        if read::trim_start(&norm.text).starts_with('%') {
            let has_content = self.programs.iter().any(|p| !p.is_empty());
            self.tape = if self.tape == Tape::None && !has_content { Tape::Open } else { Tape::Closed };
            return;
        }
        for (lo, hi, end) in scan::segments(&norm.text) {
            self.segment(&norm, lo, hi, end);
        }
    }

    /// An index-only first scan (see [`Reader::index_only`]): when the line is one plain
    /// block of letter words that [`Reader::line`] would add at the top level of the
    /// current program and the next drain would hand out at once, reads it without a
    /// normalised copy and without a statement, and gives its span and block number; the
    /// reader is then exactly where `line` and the drain would leave it, and the caller adds
    /// the block to the index as the drained statement would be. `None` (the reader is
    /// untouched) for anything else: then read the line with [`Reader::line`].
    ///
    /// Why nothing else changes: the line is ASCII and the fast reader declines every
    /// letter O, so normalising would change nothing and warn of nothing; the rest is as
    /// for [`Reader::plain_words`], with `ProgramLines::push_drained_skeleton` for
    /// `push_skeleton` and the drain.
    /// `ascii`: the caller knows the line is ASCII (else it is checked).
    pub fn scan_plain(&mut self, raw: &read::RawBlock<'_>, ascii: bool) -> Option<(Span, Option<crate::ir::SeqNo>)> {
        if !self.index_only || self.tape == Tape::Closed || !(ascii || raw.text.is_ascii()) {
            return None;
        }
        let prog = self.programs.last()?;
        if prog.param_mode || !prog.drains_at_once() {
            return None;
        }
        let (span, number, words) = fast::skeleton_raw(raw, self.file)?;
        self.take_plain(span, number.as_ref().map(|n| n.value), words);
        Some((span, number))
    }

    /// Whether [`Reader::scan_plain`] would read a line that the fast reader takes (it
    /// then changes the reader only by [`Reader::take_plain`]).
    #[inline]
    pub fn plain_ready(&self) -> bool {
        self.index_only
            && self.tape != Tape::Closed
            && self.programs.last().is_some_and(|p| !p.param_mode && p.drains_at_once())
    }

    /// What [`Reader::scan_plain`] does to the reader with a line it reads (block `span`,
    /// numbered `number`, with or without `words`): for a caller that read the line itself
    /// with [`skeleton_bytes`] when [`Reader::plain_ready`].
    #[inline]
    pub fn take_plain(&mut self, span: Span, number: Option<u32>, words: bool) {
        if let Some(p) = self.programs.last_mut() {
            p.push_drained_skeleton(span, number, words);
        }
    }

    /// A streamed translator's first scan (`crate::stream::scan_words`): [`Reader::scan_plain`]
    /// and, in the same pass over the line, what [`Reader::plain_words`] of a resumed reader
    /// hands `each`. `None` (the reader is untouched) when `scan_plain` declines the line,
    /// the block has a skip (`/2 X1`: its level is not handed out) or `each` declines a
    /// word: then read it with [`Reader::line`]. Else the block's span and number.
    ///
    /// Why this is both: the conditions on the reader are `scan_plain`'s (a resumed reader
    /// fed only such lines is always where `plain_words` reads them), and both read the
    /// line with `fast::plain_words`, whose decisions do not depend on reading the values.
    pub fn scan_plain_words(
        &mut self,
        raw: &read::RawBlock<'_>,
        ascii: bool,
        each: impl FnMut(u8, f64, bool, Span) -> bool,
    ) -> Option<(Span, Option<crate::ir::SeqNo>)> {
        if !self.index_only || self.tape == Tape::Closed || !(ascii || raw.text.is_ascii()) {
            return None;
        }
        let prog = self.programs.last()?;
        if prog.param_mode || !prog.drains_at_once() {
            return None;
        }
        let (span, number, words) = fast::scan_words_raw(raw, self.file, each)?;
        self.programs.last_mut()?.push_drained_skeleton(span, number.as_ref().map(|n| n.value), words);
        Some((span, number))
    }

    /// Re-reading a checked file (a [`Reader::resume`]d reader, see `crate::stream::reread`):
    /// when the line is one plain block of constant letter words that [`Reader::line`] would
    /// add at the top level of the current program and drain at once, hands its items' words
    /// to `each` (see `fast::lit_words`) and gives its span and number; the reader then is
    /// exactly where [`Reader::line`] and [`Reader::drain_into`] would leave it (less the
    /// statement, which the caller built). `None` (the line is not read, the reader is
    /// untouched) for anything else or when `each` declines a word: then read it with
    /// [`Reader::line`].
    ///
    /// Why nothing else changes: on such a line `line` adds no diagnostic (no normalising
    /// warning, the fast path gives none), leaves the tape state alone (not `%`, tape not
    /// closed) and `param_mode` too (the fast path runs only outside it and changes nothing),
    /// reads one block (no second block after a `;`, no `(` comment), pushes it as a plain
    /// statement at the top level (no loop open) that the next drain hands out at once (the
    /// program has a name: nothing is held back as a title; nothing else waits), which
    /// grows the program span and notes the block's number (its words hold no GOTO):
    /// `ProgramLines::push_drained` does just that.
    /// `ascii`: the caller knows the line is ASCII (else it is checked).
    pub fn plain_words(
        &mut self,
        raw: &read::RawBlock<'_>,
        ascii: bool,
        each: impl FnMut(u8, f64, bool, Span) -> bool,
    ) -> Option<(Span, Option<u32>)> {
        let file = self.file;
        self.reread_plain(raw, ascii, |raw| fast::lit_raw(raw, file, each))
    }

    /// [`Reader::plain_words`] straight into the compact block `b` (`fast::lit_block`), for
    /// the streamed re-read; `b` is to be dropped when this gives `None`.
    #[inline]
    pub fn lit(
        &mut self,
        raw: &read::RawBlock<'_>,
        ascii: bool,
        b: &mut crate::dialect::lit::LitBlock,
    ) -> Option<(Span, Option<u32>)> {
        let file = self.file;
        self.reread_plain(raw, ascii, |raw| fast::lit_block(raw, file, b))
    }

    /// Whether the reader is where [`Reader::lit`] reads lines, so that a line the quick
    /// reader takes straight from a read buffer (`fast::lit_buf`) is what `lit` would give:
    /// the line is plain ASCII (`quick::lit_words_buf`), and on such a line `fast::lit_block`
    /// takes it by `quick::lit_words` too, with these words, the line's whole span and no number. Nothing of the
    /// reader changes: once the caller has moved past the line, [`Reader::took_lit`] does
    /// what `lit` does. For a run of lines:
    /// [`Reader::took_lit`] leaves each condition as it was (it grows the span and marks a
    /// drain of a program that has drained already), so one check holds for the run.
    #[inline(always)]
    pub fn lit_ready(&self) -> bool {
        self.resumed
            && !self.index_only
            && self.tape != Tape::Closed
            && self.programs.last().is_some_and(|p| !p.param_mode && p.drains_at_once())
    }

    /// What [`Reader::lit`] does to the reader with a line the quick reader took where [`Reader::lit_ready`] held, its
    /// span `span`.
    #[inline(always)]
    pub fn took_lit(&mut self, span: Span) {
        if let Some(p) = self.programs.last_mut() {
            p.push_drained(span, None);
        }
    }

    /// What [`Reader::plain_words`] and [`Reader::lit`] share: the reader's conditions, and
    /// its state after `take` read the line (it gives the block's span and number).
    #[inline(always)]
    fn reread_plain(
        &mut self,
        raw: &read::RawBlock<'_>,
        ascii: bool,
        take: impl FnOnce(&read::RawBlock<'_>) -> Option<(Span, Option<crate::ir::SeqNo>)>,
    ) -> Option<(Span, Option<u32>)> {
        if !self.resumed || self.index_only || self.tape == Tape::Closed || !(ascii || raw.text.is_ascii()) {
            return None;
        }
        let prog = self.programs.last()?;
        if prog.param_mode || !prog.drains_at_once() {
            return None;
        }
        // An ASCII line the fast reader takes is one normalising leaves alone (it declines
        // every letter O), and neither a `%` line nor one with a comment. Exactly one block
        // (an end-of-block `;` may close it), cut as `line` cuts it.
        let (span, number) = take(raw)?;
        let number = number.map(|n| n.value);
        self.programs.last_mut()?.push_drained(span, number);
        Some((span, number))
    }

    /// One block: `norm.text[lo..hi]` (trimmed, without `;`); `end` is one past the `;`
    /// when the block was terminated by one.
    fn segment(&mut self, norm: &Normalised<'_>, lo: usize, hi: usize, end: usize) {
        let seg = parse::Seg { norm, base: lo, text: &norm.text[lo..hi], file: self.file };
        let span = norm.span(lo, end);
        if self.programs.is_empty() {
            self.programs.push(ProgramLines::new(None, None, span, self.file, self.opts));
        }
        // Plain word blocks (nearly all of CAM output): what the fast path, `block::plain` and
        // `push` make of them, in one pass; in an index-only scan without the items.
        if let Some(prog) = self.programs.last_mut().filter(|p| !p.param_mode) {
            if self.index_only {
                if let Some((skip, number, words)) = fast::skeleton(&seg) {
                    prog.push_skeleton(BlockMeta { span, skip, number, ..BlockMeta::default() }, words > 0);
                    return;
                }
            } else if let Some((skip, number, items)) = fast::plain_line(&seg) {
                let meta = BlockMeta { span, skip, number, ..BlockMeta::default() };
                prog.push(Line::Block(crate::ir::Block { meta, items }));
                return;
            }
        }
        // `* * * *`, `=====`: a separator line that real files carry; the control would alarm.
        if scan::decorative(seg.text) {
            self.diags.push(
                Diagnostic::warning("NC250", "a line of only `*`, `=` or `-` is read as a comment")
                    .primary(self.file, span, "separator line")
                    .note("it is no NC block (no address, no macro statement); the FANUC and Haas manuals do not say that a control skips it")
                    .hint("put separator lines in parentheses: `(* * * *)`"),
            );
            if let Some(prog) = self.programs.last_mut() {
                let comments = vec![crate::ir::Comment { text: seg.text.to_string(), span }];
                prog.push(Line::Block(crate::ir::Block {
                    meta: BlockMeta { span, comments, ..BlockMeta::default() },
                    items: Vec::new(),
                }));
            }
            return;
        }
        // The fast path takes only letters, digits, signs, points, blanks and a leading `/n`:
        // none of the characters `scan::check` looks at, so a block it takes passes the check.
        let parsed = match fast::parse_fast(&seg) {
            Some(p) => {
                debug_assert!(scan::check(&seg, self.opts).is_ok());
                Ok(p)
            }
            None => scan::check(&seg, self.opts).and_then(|()| parse::parse_block(&seg, self.opts)),
        };
        let parts = match parsed {
            Ok(p) => p,
            Err(d) => {
                self.diags.push(d);
                // Keep the block's N number known, so a GOTO to it is not reported as well.
                if let (Some(n), Some(p)) = (scan::leading_number(seg.text), self.programs.last_mut()) {
                    p.note_number(n);
                }
                return;
            }
        };
        let Some(prog) = self.programs.last_mut() else {
            return;
        };
        let mut cx = BlockCx { file: self.file, seg: &seg, span, param_mode: prog.param_mode, opts: self.opts };
        match block::build(&mut cx, parts) {
            Err(d) => {
                self.diags.push(d);
                if let Some(n) = scan::leading_number(seg.text) {
                    prog.note_number(n);
                }
            }
            Ok(Line::Program { number, meta }) => self.start_program(number, meta),
            Ok(line) => {
                if let Line::Block(b) = &line {
                    if !self.opts.semantics.haas {
                        let haas_if = b.items.iter().find(
                            |i| matches!(&i.kind, crate::ir::ItemKind::IfBlock { items, .. } if !items.is_empty()),
                        );
                        if let Some(i) = haas_if {
                            self.diags.push(
                                Diagnostic::warning("NC255", "`IF [..]` followed by NC words is a Haas form")
                                    .primary(self.file, i.span, "the words run only when the condition holds")
                                    .note("a FANUC control requires GOTO or THEN after IF[..] and alarms on this block")
                                    .hint("for a Haas program set `[fanuc] series = \"haas\"` in nctrans.toml"),
                            );
                        }
                        if let Some(m97) = haas_m97(b) {
                            self.diags.push(
                                Diagnostic::warning("NC253", "M97 with P is a Haas local subprogram call")
                                    .primary(self.file, m97, "read as a plain M code")
                                    .note("on a FANUC M97 is a machine builder's M code; on a Haas it runs block N<P> of this program up to its M99")
                                    .hint("for a Haas program set `[fanuc] series = \"haas\"` in nctrans.toml"),
                            );
                        }
                    }
                    if let [crate::ir::Item { kind: crate::ir::ItemKind::IfBlock { items, .. }, span }] =
                        b.items.as_slice()
                    {
                        if items.is_empty() {
                            self.diags.push(
                                Diagnostic::warning("NC251", "`IF [..]` with nothing after it does nothing")
                                    .primary(self.file, *span, "no GOTO, THEN or NC words")
                                    .note("read as a Haas conditional block with no words; FANUC requires GOTO or THEN after IF")
                                    .hint("complete the statement (`IF [..] GOTO n`) or delete the line"),
                            );
                        }
                    }
                }
                prog.param_mode = cx.param_mode;
                prog.push(line);
            }
        }
    }

    /// An `O`/`:` block: a new program starts, unless everything so far was comments before
    /// the first program number (a title), which then belongs to this program.
    fn start_program(&mut self, number: u32, meta: BlockMeta) {
        let name = Some(ProgName::Number(number));
        match self.programs.last_mut() {
            Some(p) if p.name.is_none() && p.head.is_none() && p.only_comments() => {
                p.name = name;
                p.extend_span(meta.span);
                p.head = Some(meta);
            }
            _ => {
                let span = meta.span;
                self.programs.push(ProgramLines::new(name, Some(meta), span, self.file, self.opts));
            }
        }
    }

    /// Ends the file: the unit, and for each of its programs the index it had among the
    /// programs started while reading (nameless empty ones are dropped).
    pub fn finish_indexed(self) -> (Parsed, Vec<usize>) {
        let mut kept = Vec::new();
        for (i, p) in self.programs.iter().enumerate() {
            if !(p.is_empty() && p.name.is_none()) {
                kept.push(i);
            }
        }
        (self.finish(), kept)
    }

    pub fn finish(mut self) -> Parsed {
        if let Some(s) = self.after_end {
            self.diags.push(
                Diagnostic::warning("NC237", "text after the closing `%` is not read")
                    .primary(self.file, s, "ignored: after the end-of-tape mark")
                    .note("the control stops reading a program at the second `%`")
                    .hint("move these blocks before the closing `%`, or delete them"),
            );
        }
        let mut programs: Vec<Program> = Vec::new();
        for p in self.programs {
            if p.is_empty() && p.name.is_none() {
                continue;
            }
            let (prog, diags) = structure::build(p, &self.ignored_numbers);
            self.diags.extend(diags);
            programs.push(prog);
        }
        // Structure diagnostics come per program; order everything by position so the
        // report reads top to bottom.
        self.diags.sort_by_key(|d| d.labels.iter().find(|l| l.primary).map_or(u32::MAX, |l| l.span.lo));
        Parsed {
            unit: Unit { dialect: Dialect::Fanuc, file: self.file, programs },
            diags: self.diags,
            after_end_programs: self.ignored_programs,
        }
    }
}

/// The span of an `M97` word in a block that also has a P word (a Haas local call read
/// without the Haas profile).
fn haas_m97(b: &crate::ir::Block) -> Option<Span> {
    use crate::ir::{ExprKind, ItemKind, WordValue};
    let word = |letter: u8| {
        b.items.iter().find_map(|i| match &i.kind {
            ItemKind::Word(w) if w.addr.is(letter) => Some(w),
            _ => None,
        })
    };
    let m = b.items.iter().find_map(|i| match &i.kind {
        ItemKind::Word(w) if w.addr.is(b'M') => match &w.value {
            WordValue::Expr(e) if matches!(e.kind, ExprKind::Num(n) if n.value == 97.0) => Some(w.span),
            _ => None,
        },
        _ => None,
    })?;
    word(b'P').map(|_| m)
}
