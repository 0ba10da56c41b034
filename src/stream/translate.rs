//! Streaming translation of straight-line Sinumerik programs to FANUC: the source is read
//! once; every [`CHUNK_STMTS`] top-level statements go through the ordinary translator
//! (`translate::to_fanuc`) and are written at once, so neither the source nor the output is
//! ever held whole. Verification then parses the output back (streamed) and runs both
//! programs streamed side by side, comparing their traces as they are produced.
//!
//! Only programs whose translation is local to each block stream: every block holds plain
//! words with constant values (G1 X.. Y.. F..), program ends (M30, M2), comments, block
//! numbers and skips; no
//! labels, jumps, variables, structures, calls or PROC; no `--number-blocks`. Anything else
//! needs the whole-program passes (labels → N numbers, structure lowering, the variable
//! map written in the header) and is translated whole by the caller.

use super::lines::NotStreamable;
use super::{Index, ProgressFn};
use crate::check::{self, Verdict};
use crate::diag::Diagnostic;
use crate::dialect::fanuc::emit::{self, EmitOptions};
use crate::dialect::{Dialect, ParseOptions};
use crate::eval::{DirCallees, NoCallees, RunOptions};
use crate::ir::{Addr, ExprKind, ItemKind, ProgName, Program, Stmt, StmtKind, UnOp, Unit, WordValue};
use crate::span::{SourceDb, Span};
use crate::translate::{self, TranslateOptions};
use std::io::Write;
use std::path::Path;
use std::sync::Arc;

/// Statements translated at a time.
pub const CHUNK_STMTS: usize = 4096;

/// Why a file is not translated as a stream (the caller translates it whole).
#[derive(Debug)]
pub enum Fallback {
    NotStreamable(NotStreamable),
    /// Not a straight-line program (the first block that is not, as a reason).
    NotStraight(String),
    /// The source has diagnostics (rendered by the whole-file path).
    Diagnostics,
}

/// A finished streamed translation.
pub struct Streamed {
    /// The source's first-scan index.
    pub index: Index,
    pub blocks: u64,
    /// Translator diagnostics (spans into the source).
    pub diags: Vec<Diagnostic>,
    pub unsupported: usize,
}

/// A block whose translation does not depend on any other block.
pub fn straight(s: &Stmt) -> Result<(), String> {
    let StmtKind::Block(b) = &s.kind else { return Err("a control structure".into()) };
    if b.meta.label.is_some() {
        return Err("a label".into());
    }
    for it in &b.items {
        let w = match &it.kind {
            ItemKind::Word(w) => w,
            ItemKind::End { .. } => continue,
            _ => return Err("a block that is not plain words".into()),
        };
        let constant = match &w.value {
            WordValue::Expr(e) => match &e.kind {
                ExprKind::Num(_) => true,
                ExprKind::Unary(UnOp::Neg, x) => matches!(x.kind, ExprKind::Num(_)),
                _ => false,
            },
            _ => false,
        };
        if !constant || !matches!(w.addr, Addr::Letter(_)) {
            return Err(format!("a computed or named {} word", w.addr.as_str()));
        }
    }
    Ok(())
}

struct State<'a> {
    opts: &'a TranslateOptions,
    eo: EmitOptions,
    name: Option<String>,
    buf: Vec<Stmt>,
    first: bool,
    /// Statements the translator puts before a program's body (its header comments).
    header_len: usize,
    out: &'a mut dyn Write,
    stop: Option<Fallback>,
    io: Option<std::io::Error>,
    diags: Vec<Diagnostic>,
    unsupported: usize,
}

impl State<'_> {
    fn unit(&self, body: Vec<Stmt>) -> Unit {
        let program = Program {
            name: self.name.clone().map(ProgName::Name),
            head: None,
            params: vec![],
            save: false,
            body,
            span: Span::default(),
        };
        Unit { dialect: Dialect::Sinumerik, file: self.eo.file, programs: vec![program] }
    }

    fn flush(&mut self) {
        if self.buf.is_empty() || self.stop.is_some() || self.io.is_some() {
            return;
        }
        let body = std::mem::take(&mut self.buf);
        let unit = self.unit(body);
        let t = translate::to_fanuc(&unit, &[], self.opts);
        self.unsupported += t.unsupported;
        self.diags.extend(t.diags);
        let text = if self.first {
            self.first = false;
            // The whole file minus its closing `%`, which is written at the very end.
            let eol = self.opts.line_ending.as_str();
            let closing = format!("%{eol}");
            t.text.strip_suffix(&closing).unwrap_or(&t.text).to_string()
        } else {
            let body = t.unit.programs.first().map_or(&[][..], |p| &p.body[self.header_len.min(p.body.len())..]);
            let e = emit::emit_body(body, &self.eo);
            self.diags.extend(e.diags);
            e.text
        };
        if let Err(e) = self.out.write_all(text.as_bytes()) {
            self.io = Some(e);
        }
    }
}

/// Translates `path` (Sinumerik) to FANUC into `out`, reading it once. On `Err` nothing
/// useful was written (the caller discards `out` and translates whole).
pub fn to_fanuc(
    path: &Path,
    opts: &TranslateOptions,
    out: &mut dyn Write,
    progress: Option<ProgressFn<'_>>,
) -> Result<Streamed, Fallback> {
    if opts.number_blocks.is_some() || opts.main_is_sub {
        return Err(Fallback::NotStraight("--number-blocks or a subprogram as main".into()));
    }
    let name = first_header(path).map_err(Fallback::NotStreamable)?;
    let eo = EmitOptions { comments: opts.comments, line_ending: opts.line_ending, file: 0 };
    let mut st = State {
        opts,
        eo,
        name,
        buf: Vec::new(),
        first: true,
        header_len: 0,
        out,
        stop: None,
        io: None,
        diags: Vec::new(),
        unsupported: 0,
    };
    st.header_len = translate::to_fanuc(&st.unit(vec![]), &[], opts).unit.programs.first().map_or(0, |p| p.body.len());
    let popts = ParseOptions::for_dialect(Dialect::Sinumerik);
    let mut blocks = 0u64;
    let r = super::scan_path(
        path,
        0,
        Dialect::Sinumerik,
        &popts,
        &mut |_, s| {
            if st.stop.is_some() {
                return;
            }
            if let Err(why) = straight(s) {
                st.stop = Some(Fallback::NotStraight(why));
                return;
            }
            blocks += 1;
            st.buf.push(s.clone());
            if st.buf.len() >= CHUNK_STMTS {
                st.flush();
            }
        },
        progress,
    );
    let index = r.map_err(Fallback::NotStreamable)?;
    if let Some(f) = st.stop.take() {
        return Err(f);
    }
    if !index.diags.is_empty() || !st.diags.is_empty() || st.unsupported > 0 {
        return Err(Fallback::Diagnostics);
    }
    // The name was taken from the `%_N_` line before reading; a PROC may rename the program.
    let read_name = index.programs.first().and_then(|p| match &p.program.name {
        Some(ProgName::Name(n)) => Some(n.clone()),
        _ => None,
    });
    if index.programs.first().is_some_and(|p| !p.program.params.is_empty()) || read_name != st.name {
        return Err(Fallback::NotStraight("a PROC".into()));
    }
    st.flush();
    if st.first {
        // An empty program: the translator still writes its `O` line.
        st.buf.clear();
        st.first = false;
        let t = translate::to_fanuc(&st.unit(vec![]), &[], opts);
        let eol = opts.line_ending.as_str();
        let text = t.text.strip_suffix(&format!("%{eol}")).unwrap_or(&t.text).to_string();
        if let Err(e) = st.out.write_all(text.as_bytes()) {
            st.io = Some(e);
        }
    }
    let eol = opts.line_ending.as_str();
    if st.io.is_none() {
        if let Err(e) = st.out.write_all(format!("%{eol}").as_bytes()).and_then(|_| st.out.flush()) {
            st.io = Some(e);
        }
    }
    if let Some(e) = st.io {
        return Err(Fallback::NotStreamable(NotStreamable::Io(e)));
    }
    Ok(Streamed { index, blocks, diags: st.diags, unsupported: st.unsupported })
}

/// The program name of a `%_N_NAME_MPF` first line.
fn first_header(path: &Path) -> Result<Option<String>, NotStreamable> {
    let (input, _) = super::open(path)?;
    let mut l = super::lines::Lines::new(input)?;
    while let Some(x) = l.next_line()? {
        let t = x.text.trim_start_matches([' ', '\t']);
        if t.is_empty() {
            continue;
        }
        return Ok(if t.starts_with('%') { crate::dialect::sinumerik::header_name(t.trim_end()) } else { None });
    }
    Ok(None)
}

/// The outcome of verifying a streamed translation.
pub struct Verified {
    pub equivalent: bool,
    pub summary: String,
    /// Diagnostics of the output's parse or of the check (files: 0 source, 1 output).
    pub diags: Vec<Diagnostic>,
    pub diff: String,
}

/// Verifies a streamed translation: the output is read back as FANUC (streamed), then both
/// programs run streamed on two threads and their traces are compared as they come.
pub fn verify(source: Index, output: &Path, max_steps: u64, progress: Option<ProgressFn<'_>>) -> Verified {
    let popts = ParseOptions::for_dialect(Dialect::Fanuc);
    let out_ix = match super::scan_path(output, 1, Dialect::Fanuc, &popts, &mut |_, _| {}, progress) {
        Ok(ix) => ix,
        Err(e) => {
            return Verified {
                equivalent: false,
                summary: format!("not verified: the output cannot be read back ({e})"),
                diags: vec![],
                diff: String::new(),
            }
        }
    };
    if !out_ix.diags.is_empty() {
        return Verified {
            equivalent: false,
            summary: "not verified: the output does not parse as FANUC (a bug in nctrans)".into(),
            diags: out_ix.diags,
            diff: String::new(),
        };
    }
    let mut db = SourceDb::new();
    db.add(source.path.display().to_string(), String::new());
    db.add(output.display().to_string(), String::new());
    let run = RunOptions { max_steps, ..RunOptions::default() };
    let a = super::runner(Arc::new(source), Box::new(DirCallees { semantics: None }), run.clone());
    let b = super::runner(Arc::new(out_ix), Box::new(NoCallees), run);
    let report = check::check_runners(&db, a, b);
    let (equivalent, summary) = match report.verdict {
        Verdict::Equivalent { events } => (true, format!("equivalent ({events} events)")),
        Verdict::Diverged { index } => {
            (false, format!("diverged at trace event {}: the translation is wrong (a bug in nctrans)", index + 1))
        }
        Verdict::Inconclusive { reason } => (false, format!("inconclusive: {reason}")),
        Verdict::Failed => (false, "not verified: a run could not be evaluated (see above)".into()),
    };
    Verified { equivalent, summary, diags: report.diags, diff: report.diff }
}
