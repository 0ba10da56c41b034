//! The Sinumerik dialect (828D/840D): reading part programs into the IR.
//!
//! One block at a time: each line is normalised (`read::normalise`), tried by the byte-level
//! fast path for plain motion blocks, else parsed by `grammar/sinumerik.pest` (rule `block`)
//! and converted (`parse.rs`, `expr.rs`). A bad block gives one diagnostic (`errors.rs`) and
//! reading goes on. The structurer (`structure.rs`) then builds the program tree.
//! Owns: Sinumerik reading, writing (`emit`), cycle spellings. May use: `dialect`, `ir`, base.

pub mod cycles;
mod decls;
mod errors;
mod expr;
pub(crate) mod fast;
pub mod macros;
mod names;
mod parse;
pub mod scan_words;
mod skeleton;
mod structure;
mod sync;

pub mod emit;

pub use names::is_predefined_procedure;
pub use skeleton::skeleton_bytes;

use crate::diag::Diagnostic;
use crate::dialect::{Dialect, ParseOptions, Parsed};
use crate::ir::{BlockMeta, Unit};
use crate::read::{self, CommentStyle};
use crate::span::{FileId, SourceFile, Span};
use parse::{FileState, Lower};
use pest::Parser;
use structure::Header;

#[derive(pest_derive::Parser)]
#[grammar = "../grammar/common.pest"]
#[grammar = "../grammar/sinumerik.pest"]
pub struct SinumerikParser;

/// Parses one Sinumerik file into a unit with one program.
pub fn parse(src: &SourceFile, file: FileId, opts: &ParseOptions) -> Parsed {
    let mut r = Reader::new(file, opts, src.text.len() as u32);
    for raw in read::blocks(&src.text) {
        r.line(&raw);
    }
    let (program, diags) = r.finish();
    Parsed {
        unit: Unit { dialect: Dialect::Sinumerik, file, programs: vec![program] },
        diags,
        after_end_programs: vec![],
    }
}

/// The reader of one file, fed one physical line at a time: the whole-file [`parse`] and
/// the streaming reader (`crate::stream`) are the same code, so they give the same IR.
pub struct Reader {
    st: FileState,
    builder: structure::Builder,
    header_seen: bool,
    any: bool,
    /// Plain blocks are read for an index only: their items are not built.
    index_only: bool,
    /// Whether a line may be read raw, not through [`Reader::line`] (the quick readers):
    /// not where a library macro could stand in a plain line (`macros::raw_safe`), which
    /// only `line` expands.
    raw: bool,
}

/// What a streaming reader needs to resume at a block boundary (see `crate::stream`).
#[derive(Clone)]
pub struct Resume {
    declared: std::collections::HashMap<String, crate::ir::DataType>,
    header_seen: bool,
    any: bool,
    /// Whether a block of code came before (a `PROC` line is then an error, NC129).
    seen_code: bool,
}

/// With the declarations in name order, so equal states print the same.
impl std::fmt::Debug for Resume {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let declared: std::collections::BTreeMap<_, _> = self.declared.iter().collect();
        f.debug_struct("Resume")
            .field("declared", &declared)
            .field("header_seen", &self.header_seen)
            .field("any", &self.any)
            .field("seen_code", &self.seen_code)
            .finish()
    }
}

impl Reader {
    /// `len`: the length of the file text (the program's span until it is known).
    pub fn new(file: FileId, opts: &ParseOptions, len: u32) -> Reader {
        Reader {
            st: FileState {
                file,
                diags: Vec::new(),
                r_count: opts.semantics.r_param_count,
                declared: Default::default(),
                macros: opts.semantics.macros.clone(),
            },
            builder: structure::Builder::new(None, len),
            header_seen: false,
            any: false,
            index_only: false,
            raw: macros::raw_safe(&opts.semantics.macros),
        }
    }

    /// A reader for re-reading from a block boundary: no header, no PROC check, jump
    /// targets not collected (the first scan did that).
    pub fn resume(file: FileId, opts: &ParseOptions, from: &Resume) -> Reader {
        let mut r = Reader::new(file, opts, 0);
        r.st.declared = from.declared.clone();
        r.header_seen = from.header_seen;
        r.any = from.any;
        r.builder.resumed(from.seen_code);
        r
    }

    /// The state to resume from here (valid when [`Reader::at_top`]).
    pub fn checkpoint(&self) -> Resume {
        Resume {
            declared: self.st.declared.clone(),
            header_seen: self.header_seen,
            any: self.any,
            seen_code: self.builder.seen_code(),
        }
    }

    /// Streaming: jump targets are kept as compact runs (memory follows the macro part).
    pub fn compact_targets(&mut self) {
        self.builder.compact_targets();
    }

    /// For a first scan that only builds the index (`crate::stream::scan_index`): the
    /// blocks the fast path reads get no items (the index needs their numbers, labels and
    /// spans). The statements handed out are then skeletons, not the program's IR.
    pub fn index_only(&mut self) {
        self.index_only = true;
    }

    /// No structure is open: the next block starts a top-level statement.
    pub fn at_top(&self) -> bool {
        self.builder.at_top()
    }

    /// The finished top-level statements so far (taken out of the program).
    pub fn drain(&mut self) -> Vec<crate::ir::Stmt> {
        self.builder.drain()
    }

    /// [`Reader::drain`] into `out` (appended; an empty `out` lends its capacity).
    pub fn drain_into(&mut self, out: &mut Vec<crate::ir::Stmt>) {
        self.builder.drain_into(out)
    }

    pub fn diags(&self) -> &[Diagnostic] {
        &self.st.diags
    }

    /// Reads one physical line.
    pub fn line(&mut self, raw: &read::RawBlock<'_>) {
        let file = self.st.file;
        let (st, builder) = (&mut self.st, &mut self.builder);
        let mut norm = read::normalise(raw, CommentStyle::Semicolon);
        if !st.macros.is_empty() {
            if let Some(expanded) = macros::expand(&norm, &st.macros) {
                norm = expanded;
            }
        }
        if !norm.full_width.is_empty() || !norm.letter_o.is_empty() {
            st.diags.extend(norm.warnings(file));
        }
        let whole = Span::new(raw.start, raw.start + raw.text.len() as u32);
        let text: &str = &norm.text;
        let trimmed = text.trim_start_matches([' ', '\t']);
        if trimmed.is_empty() {
            return;
        }
        if trimmed.starts_with('%') {
            if self.any || self.header_seen {
                st.diags.push(
                    Diagnostic::error("NC128", "a `%` line is only allowed as the first line")
                        .primary(file, whole, "`%` line inside the program")
                        .hint("the `%_N_NAME_MPF` header starts the file; remove this line"),
                );
            } else {
                self.header_seen = true;
                builder.header(Header {
                    name: header_name(trimmed),
                    meta: BlockMeta { span: whole, ..Default::default() },
                });
            }
            return;
        }
        self.any = true;
        if self.index_only {
            if let Some((meta, words)) = fast::skeleton(&norm, whole) {
                builder.push_skeleton(meta, words, st);
                return;
            }
        } else if let Some(line) = fast::line(&norm, whole) {
            builder.push(line, st);
            return;
        }
        if let Some(d) = errors::too_deep(text, &norm, file) {
            st.diags.push(d);
            return;
        }
        match SinumerikParser::parse(Rule::block, text) {
            Ok(mut pairs) => {
                if let Some(block) = pairs.next() {
                    let mut lower = Lower { norm: &norm, st, failed: false, whole };
                    if let Some(line) = lower.block(block, whole) {
                        builder.push(line, st);
                    }
                }
            }
            Err(e) => {
                st.diags.push(errors::syntax(&e, &norm, file));
                // A broken IF/WHILE/…/ENDIF line still opens or closes its structure, so
                // that one bad block does not also give an "END without opener" error.
                if let Some(kind) = structure::keyword_only(text, whole) {
                    builder.push(
                        structure::Line { meta: BlockMeta { span: whole, ..Default::default() }, kind, kw: whole },
                        st,
                    );
                }
            }
        }
    }

    /// An index-only first scan (see [`Reader::index_only`]): when the line is a plain block
    /// that [`Reader::line`] would add at the top level, reads it in one pass over the raw
    /// text (no normalised copy, no statement) and gives its span and block number; the
    /// reader is then exactly where `line` and a drain would leave it, and the caller adds
    /// the block to the index as the drained statement would be. `None` (the reader is
    /// untouched) for anything else: then read the line with [`Reader::line`].
    ///
    /// Why nothing else changes: on an ASCII line that the fast reader takes (no letter O,
    /// see `fast::skeleton_raw`) normalising changes nothing and warns of nothing; such a
    /// line is neither blank nor a `%` line, so `line` sets `any` and pushes a plain
    /// skeleton block, which at the top level (no structure open, none suppressed) only
    /// records the number as a jump target, notes code and adds the statement, which the
    /// next drain hands out (nothing else waits: the program body is empty).
    /// `ascii`: the caller knows the line is ASCII (else it is checked).
    pub fn scan_plain(&mut self, raw: &read::RawBlock<'_>, ascii: bool) -> Option<(Span, Option<crate::ir::SeqNo>)> {
        if !self.raw || !self.index_only || !self.builder.plain_at_top() || !(ascii || raw.text.is_ascii()) {
            return None;
        }
        let (number, words) = fast::skeleton_raw(raw)?;
        self.take_plain(number.as_ref(), words);
        Some((Span::new(raw.start, raw.start + raw.text.len() as u32), number))
    }

    /// Whether [`Reader::scan_plain`] would read a line that the fast reader takes (it
    /// then changes the reader only by [`Reader::take_plain`]).
    #[inline]
    pub fn plain_ready(&self) -> bool {
        self.raw && self.index_only && self.builder.plain_at_top()
    }

    /// What [`Reader::scan_plain`] does to the reader with a line it reads: for a caller
    /// that read the line itself with [`skeleton_bytes`] when [`Reader::plain_ready`].
    #[inline]
    pub fn take_plain(&mut self, number: Option<&crate::ir::SeqNo>, words: bool) {
        self.any = true;
        self.builder.push_plain_top(number, words);
    }

    /// A streamed translator's first scan (`crate::stream::scan_words`): [`Reader::scan_plain`]
    /// and, in the same pass over the line, what [`Reader::plain_words`] of a resumed reader
    /// hands `each`. `None` (the reader is untouched) when `scan_plain` declines the line or
    /// `each` declines a word (`plain_words` would decline the line: then read it with
    /// [`Reader::line`]); else the block's span, its number and where its comment starts
    /// (the first `;` after the last word, an offset into `raw.text`).
    ///
    /// Why this is both: the conditions on the reader are `scan_plain`'s (a resumed reader
    /// fed only such lines is always at top level), and both read the line with `fast::read`,
    /// whose decisions do not depend on the sink; `plain_words` would change only `any` of a
    /// reader that is not this one.
    pub fn scan_plain_words(
        &mut self,
        raw: &read::RawBlock<'_>,
        ascii: bool,
        each: impl FnMut(u8, f64, bool, Span) -> bool,
    ) -> Option<(Span, Option<crate::ir::SeqNo>, Option<usize>)> {
        if !self.raw || !self.index_only || !self.builder.plain_at_top() || !(ascii || raw.text.is_ascii()) {
            return None;
        }
        let (number, words, comment) = fast::scan_words_raw(raw, each)?;
        self.any = true;
        self.builder.push_plain_top(number.as_ref(), words);
        Some((Span::new(raw.start, raw.start + raw.text.len() as u32), number, comment))
    }

    /// Re-reading a checked file (a [`Reader::resume`]d reader, see `crate::stream::reread`):
    /// when the line is a plain block of constant letter words at top level, hands its words to
    /// `each` (see `fast::words`) and gives its span and number; the reader then is where
    /// [`Reader::line`] would leave it (less the statement, which the caller built). `None`
    /// (the line is not read) when the line is anything else, needs normalising, or `each`
    /// declines a word: then read it with [`Reader::line`].
    /// `ascii`: the caller knows the line is ASCII (else it is checked).
    pub fn plain_words(
        &mut self,
        raw: &read::RawBlock<'_>,
        ascii: bool,
        mut each: impl FnMut(u8, f64, bool, Span) -> bool,
    ) -> Option<(Span, Option<u32>)> {
        // Only `any` and, with a word, "code seen" change on a plain top-level line of a
        // resumed reader (`builder.push` adds the statement and nothing else there: see
        // `Builder::resumed_at_top`).
        self.reread_plain(raw, ascii, |raw| {
            let mut words = false;
            let (span, number) = fast::words_raw(raw, |letter, value, point, span| {
                words = true;
                each(letter, value, point, span)
            })?;
            Some((span, number, words))
        })
    }

    /// [`Reader::plain_words`] straight into the compact block `b` (`fast::lit_raw`), for
    /// the streamed re-read; `b` is to be dropped when this gives `None`.
    #[inline]
    pub fn lit(
        &mut self,
        raw: &read::RawBlock<'_>,
        ascii: bool,
        b: &mut crate::dialect::lit::LitBlock,
    ) -> Option<(Span, Option<u32>)> {
        self.reread_plain(raw, ascii, |raw| fast::lit_raw(raw, b))
    }

    /// Whether the reader is where [`Reader::lit`] reads lines, so that a line the quick
    /// reader takes straight from a read buffer (`fast::lit_buf`) is what `lit` would give:
    /// the line is plain ASCII (`quick::lit_words_buf`), and on such a line `fast::lit_raw`
    /// takes it by `quick::lit_words` too, with these words, the line's span, no number, and words. Nothing of the
    /// reader changes: once the caller has moved past the line, [`Reader::took_lit`] does
    /// what `lit` does. For a run of lines:
    /// [`Reader::took_lit`] leaves both conditions as they were (it notes code seen), so
    /// one check holds for the run.
    #[inline(always)]
    pub fn lit_ready(&self) -> bool {
        self.raw && !self.index_only && self.builder.resumed_at_top()
    }

    /// What [`Reader::lit`] does to the reader with a line the quick reader took where [`Reader::lit_ready`] held.
    #[inline(always)]
    pub fn took_lit(&mut self) {
        self.any = true;
        self.builder.code_seen();
    }

    /// What [`Reader::plain_words`] and [`Reader::lit`] share: the reader's conditions, and
    /// its state after `read` took the line (it gives the span, number and whether the
    /// line has words).
    #[inline(always)]
    fn reread_plain(
        &mut self,
        raw: &read::RawBlock<'_>,
        ascii: bool,
        take: impl FnOnce(&read::RawBlock<'_>) -> Option<(Span, Option<u32>, bool)>,
    ) -> Option<(Span, Option<u32>)> {
        if !self.raw || self.index_only || !self.builder.resumed_at_top() || !(ascii || raw.text.is_ascii()) {
            return None;
        }
        // An ASCII line the fast reader takes is one normalising leaves alone (see
        // `fast::skeleton_raw`); a `%` line it declines (`%` is not a letter).
        let (span, number, words) = take(raw)?;
        self.any = true;
        if words {
            self.builder.code_seen();
        }
        Some((span, number))
    }

    /// Closes what is open, checks jump targets; the program holds what was not drained.
    pub fn finish(mut self) -> (crate::ir::Program, Vec<Diagnostic>) {
        let program = self.builder.finish(&mut self.st);
        (program, self.st.diags)
    }
}

/// `%_N_PART1_MPF` → `PART1`; `%_N_SUB_SPF` → `SUB`; other `%` lines give no name.
pub(crate) fn header_name(line: &str) -> Option<String> {
    let t = line.trim_end();
    let body = t.strip_prefix("%_N_").or_else(|| t.strip_prefix("%_n_"))?;
    let upper = body.to_ascii_uppercase();
    let name = upper.strip_suffix("_MPF").or_else(|| upper.strip_suffix("_SPF")).unwrap_or(&upper);
    (!name.is_empty()).then(|| name.to_string())
}

/// Siemens finds a program by its file name: a file of one program without a PROC line
/// (`L100.SPF`) is the program `name` (upper case), as its callers name it.
pub fn name_after_file(unit: &mut crate::ir::Unit, name: &str) {
    if let [one] = &mut unit.programs[..] {
        one.name.get_or_insert_with(|| crate::ir::ProgName::Name(name.to_ascii_uppercase()));
    }
}

/// Whether `text` is a program name the reader takes, written alone in a block, as the call
/// of that program (`D_TRIANGLE`, `SH602`): letters, digits and `_`, starting with a letter
/// or `_`, not one letter with digits (`X10` is an address) and not an instruction or a
/// function. The line `EXECSTRING` can run as a call (`eval::calls`).
pub fn is_program_name_line(text: &str) -> bool {
    let upper = text.to_ascii_uppercase();
    let b = upper.as_bytes();
    let letters = b.iter().take_while(|c| c.is_ascii_alphabetic()).count();
    let address = letters == 1 && b[1..].iter().all(u8::is_ascii_digit);
    b.len() >= 2
        && (b[0].is_ascii_alphabetic() || b[0] == b'_')
        && b.iter().all(|c| c.is_ascii_alphanumeric() || *c == b'_')
        && !address
        && !names::is_instruction(&upper)
        && names::builtin(&upper).is_none()
}

/// Whether an instruction the reader kept as written is a `RET` with a jump target
/// (`RET("L")`, `RET(N100)`, `RET("L", n)`): the reader spells it `RET(<arguments>)` and
/// the evaluator and the FANUC translation both refuse it (NC507), for the reason in
/// [`RET_TARGET_UNSOURCED`].
pub fn is_ret_with_target(instruction: &str) -> bool {
    instruction.starts_with("RET(")
}

/// Why a `RET` with a jump target is refused rather than run: the stored manuals searched
/// for issue 21 (docs/semantics.md, calls) have no page with its parameters.
pub const RET_TARGET_UNSOURCED: &str = "no Siemens manual page at hand gives RET's parameters: which argument is the \
     target, where the control searches it in the caller, whether the target block itself runs, \
     and how many levels it returns; nctrans does not guess where the machine goes on";

/// The IR of one block by the grammar alone (no fast path), for tests that compare the two.
#[doc(hidden)]
pub fn block_via_grammar(text: &str) -> Option<String> {
    block_dump(text, false)
}

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
        fast::skeleton_raw(&raw)
            .map(|(n, words)| (Span::new(0, text.len() as u32), n.map(|n| (n.value, n.span)), words))
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

/// The IR of one block through the fast path only (`None` when it declines).
#[doc(hidden)]
pub fn block_via_fast_path(text: &str) -> Option<String> {
    block_dump(text, true)
}

fn block_dump(text: &str, fast_path: bool) -> Option<String> {
    let raw = read::RawBlock { text, start: 0, line: 1 };
    let norm = read::normalise(&raw, CommentStyle::Semicolon);
    let whole = Span::new(0, text.len() as u32);
    let line = if fast_path {
        fast::line(&norm, whole)?
    } else {
        let mut st = FileState {
            file: 0,
            diags: Vec::new(),
            r_count: 300,
            declared: Default::default(),
            macros: Default::default(),
        };
        let mut pairs = SinumerikParser::parse(Rule::block, &norm.text).ok()?;
        let mut lower = Lower { norm: &norm, st: &mut st, failed: false, whole };
        let line = lower.block(pairs.next()?, whole)?;
        if !st.diags.is_empty() {
            return None;
        }
        line
    };
    match line.kind {
        structure::LineKind::Plain(items) => {
            let block = crate::ir::Block { meta: line.meta, items };
            Some(format!("{block:?}"))
        }
        _ => None,
    }
}
