//! The FANUC Custom Macro B dialect: reading a file block by block into the IR.
//!
//! The reader splits the file into blocks (lines, and `;`-terminated parts of lines), handles
//! `%` tape marks and `O`/`:` program numbers, and hands every block to the grammar
//! (`parse.rs`, or the byte-level fast path in `fast.rs` for plain motion blocks). `block.rs`
//! turns the grammar's parts into IR items (calls, returns, alarms, Macro A lowering), and
//! `structure.rs` builds `DO`/`END` loops and checks `GOTO` targets per program.

mod args;
mod block;
mod expr;
mod fast;
mod macro_a;
mod names;
mod parse;
mod scan;
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

pub use fast::parse_fast_for_test;
pub use parse::parse_grammar_for_test;

/// Parses one FANUC file. Every bad block gives one diagnostic and reading continues.
pub fn parse(src: &SourceFile, file: FileId, opts: &ParseOptions) -> Parsed {
    let mut r = Reader {
        file,
        opts,
        diags: Vec::new(),
        tape: Tape::None,
        after_end: None,
        ignored_numbers: Vec::new(),
        programs: Vec::new(),
    };
    for raw in read::blocks(&src.text) {
        r.line(&raw);
    }
    r.finish()
}

/// Where we are relative to the `%` tape marks.
#[derive(Clone, Copy, PartialEq)]
enum Tape {
    /// No `%` seen yet.
    None,
    /// After the opening `%`.
    Open,
    /// After the closing `%`: the control reads nothing more.
    Closed,
}

struct Reader<'o> {
    file: FileId,
    opts: &'o ParseOptions,
    diags: Vec<Diagnostic>,
    tape: Tape,
    /// Span of the text after the closing `%` (warned about once).
    after_end: Option<Span>,
    /// `N` numbers seen in the ignored text after the closing `%`, for GOTO notes.
    ignored_numbers: Vec<(u32, Span)>,
    programs: Vec<ProgramLines>,
}

impl Reader<'_> {
    fn line(&mut self, raw: &read::RawBlock<'_>) {
        let trimmed = raw.text.trim();
        if trimmed.is_empty() {
            return;
        }
        let lead = (raw.text.len() - raw.text.trim_start().len()) as u32;
        let line_span = Span::new(raw.start + lead, raw.start + lead + trimmed.len() as u32);
        if self.tape == Tape::Closed {
            self.after_end = Some(self.after_end.map_or(line_span, |s| s.to(line_span)));
            if let Some(n) = scan::leading_number(trimmed) {
                self.ignored_numbers.push((n, line_span));
            }
            return;
        }
        let norm = read::normalise(raw, CommentStyle::Parens);
        self.diags.extend(norm.warnings(self.file));
        if norm.text.trim_start().starts_with('%') {
            let has_content = self.programs.iter().any(|p| !p.is_empty());
            self.tape = if self.tape == Tape::None && !has_content { Tape::Open } else { Tape::Closed };
            return;
        }
        for (lo, hi, end) in scan::segments(&norm.text) {
            self.segment(&norm, lo, hi, end);
        }
    }

    /// One block: `norm.text[lo..hi]` (trimmed, without `;`); `end` is one past the `;`
    /// when the block was terminated by one.
    fn segment(&mut self, norm: &Normalised<'_>, lo: usize, hi: usize, end: usize) {
        let seg = parse::Seg { norm, base: lo, text: &norm.text[lo..hi], file: self.file };
        let span = norm.span(lo, end);
        if self.programs.is_empty() {
            self.programs.push(ProgramLines::new(None, None, span, self.file, self.opts));
        }
        let parsed = match scan::check(&seg, self.opts) {
            Err(d) => Err(d),
            Ok(()) => match fast::parse_fast(&seg) {
                Some(p) => Ok(p),
                None => parse::parse_block(&seg, self.opts),
            },
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

    fn finish(mut self) -> Parsed {
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
        Parsed { unit: Unit { dialect: Dialect::Fanuc, file: self.file, programs }, diags: self.diags }
    }
}
