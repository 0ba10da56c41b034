//! The structurer: assembles the block lines of one file into the program tree
//! (IF/ELSE/ENDIF, WHILE, LOOP, FOR, REPEAT/UNTIL), without recursion, and checks what needs
//! the whole program: labels and block numbers as jump targets, duplicate labels, labels and
//! skips on control-structure blocks, the place of PROC.

use super::parse::FileState;
use crate::diag::Diagnostic;
use crate::ir::*;
use crate::span::Span;
use std::collections::HashMap;

/// Control structures nested deeper than this are rejected (the IR tree is walked
/// recursively by later phases, so its depth must stay bounded).
pub const MAX_NESTING: usize = 64;

/// One block as read by the grammar, before structuring.
pub struct Line {
    pub meta: BlockMeta,
    pub kind: LineKind,
    /// The keyword of a control line (for diagnostics); the whole block otherwise.
    pub kw: Span,
}

pub enum LineKind {
    Plain(Vec<Item>),
    If(Expr),
    Else,
    EndIf,
    While(Expr),
    EndWhile,
    Loop,
    EndLoop,
    For { var: VarRef, from: Expr, to: Expr },
    EndFor,
    Repeat,
    Until(Expr),
    Proc(ProcHead),
}

#[derive(Default)]
pub struct ProcHead {
    pub name: String,
    pub params: Vec<Param>,
    pub save: bool,
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Kind {
    If,
    While,
    Loop,
    For,
    Repeat,
}

impl Kind {
    fn opener(self) -> &'static str {
        match self {
            Kind::If => "IF",
            Kind::While => "WHILE",
            Kind::Loop => "LOOP",
            Kind::For => "FOR",
            Kind::Repeat => "REPEAT",
        }
    }

    fn closer(self) -> &'static str {
        match self {
            Kind::If => "ENDIF",
            Kind::While => "ENDWHILE",
            Kind::Loop => "ENDLOOP",
            Kind::For => "ENDFOR",
            Kind::Repeat => "UNTIL",
        }
    }

    fn body_word(self) -> &'static str {
        match self {
            Kind::If => "the IF body",
            Kind::Repeat => "the loop body (`UNTIL condition`)",
            _ => "the loop body",
        }
    }
}

/// An open structure on the stack.
struct Open {
    kind: Kind,
    head: BlockMeta,
    kw: Span,
    cond: Option<Expr>,
    for_var: Option<(VarRef, Expr, Expr)>,
    body: Vec<Stmt>,
    else_part: Option<ElsePart>,
}

impl Open {
    fn body_mut(&mut self) -> &mut Vec<Stmt> {
        match &mut self.else_part {
            Some(e) => &mut e.body,
            None => &mut self.body,
        }
    }

    /// The finished statement, closed by `end` (and `until` for REPEAT).
    fn close(self, end: BlockMeta, until: Option<Expr>) -> Stmt {
        // Also covers the body when an unclosed structure is closed at its own head.
        let mut span = self.head.span.to(end.span);
        for st in self.body.last().into_iter().chain(self.else_part.as_ref().and_then(|e| e.body.last())) {
            span = span.to(st.span);
        }
        if let Some(e) = &self.else_part {
            span = span.to(e.head.span);
        }
        let zero = || Expr::num(0.0, false, self.head.span);
        let kind = match self.kind {
            Kind::If => StmtKind::If(Box::new(IfStmt {
                cond: self.cond.unwrap_or_else(zero),
                head: self.head,
                then_body: self.body,
                else_part: self.else_part,
                end,
            })),
            Kind::While => StmtKind::While(Box::new(WhileStmt {
                cond: self.cond.unwrap_or_else(zero),
                head: self.head,
                body: self.body,
                end,
            })),
            Kind::Loop => StmtKind::Loop(Box::new(LoopStmt { head: self.head, body: self.body, end })),
            Kind::For => {
                let (var, from, to) = match self.for_var {
                    Some(f) => f,
                    None => (VarRef { kind: VarKind::R(0), span: self.head.span }, zero(), zero()),
                };
                StmtKind::For(Box::new(ForStmt { head: self.head, var, from, to, body: self.body, end }))
            }
            Kind::Repeat => {
                let until = until.unwrap_or_else(|| Expr::num(1.0, false, end.span));
                StmtKind::Repeat(Box::new(RepeatStmt { head: self.head, body: self.body, end, until }))
            }
        };
        Stmt { kind, span }
    }
}

/// For a block the grammar rejected: the structure keyword it starts with, as a stand-in line
/// (conditions replaced by 0). `IF … GOTO…` and `REPEAT label` are not structures.
pub fn keyword_only(text: &str, whole: Span) -> Option<LineKind> {
    let upper = text.trim_start_matches([' ', '\t', '/']).to_ascii_uppercase();
    let mut t = upper.as_str();
    // Skip a block number; a label on a control block is its own error.
    if let Some(rest) = t.strip_prefix('N') {
        let d = rest.bytes().take_while(u8::is_ascii_digit).count();
        if d > 0 {
            t = rest[d..].trim_start();
        }
    }
    let word: String = t.chars().take_while(|c| c.is_ascii_alphanumeric() || *c == '_').collect();
    let rest = t[word.len()..].trim_start();
    let zero = || Expr::num(0.0, false, whole);
    Some(match word.as_str() {
        "IF" if !upper.contains("GOTO") => LineKind::If(zero()),
        "WHILE" => LineKind::While(zero()),
        "LOOP" => LineKind::Loop,
        "FOR" => LineKind::For { var: VarRef { kind: VarKind::R(0), span: whole }, from: zero(), to: zero() },
        "REPEAT" if rest.is_empty() || rest.starts_with(';') => LineKind::Repeat,
        "ENDIF" => LineKind::EndIf,
        "ELSE" => LineKind::Else,
        "ENDWHILE" => LineKind::EndWhile,
        "ENDLOOP" => LineKind::EndLoop,
        "ENDFOR" => LineKind::EndFor,
        "UNTIL" => LineKind::Until(zero()),
        _ => return None,
    })
}

/// The header line `%_N_NAME_MPF`, if the file has one.
pub struct Header {
    pub name: Option<String>,
    pub meta: BlockMeta,
}

/// Builds the one program of a file from its lines.
/// Builds the one program of a file, one line at a time (the lines are not kept).
pub struct Builder {
    program: Program,
    stack: Vec<Open>,
    suppressed: usize,
    seen_code: bool,
    deep_reported: bool,
    targets: Targets,
    /// Re-reading part of a file already checked: jump targets are not collected again.
    resumed: bool,
}

impl Builder {
    pub fn new(header: Option<Header>, len: u32) -> Builder {
        let mut program = Program {
            name: None,
            head: None,
            params: Vec::new(),
            save: false,
            body: Vec::new(),
            span: Span::new(0, len),
        };
        if let Some(h) = header {
            program.name = h.name.map(ProgName::Name);
            program.head = Some(h.meta);
        }
        Builder {
            program,
            stack: Vec::new(),
            suppressed: 0,
            seen_code: false,
            deep_reported: false,
            targets: Targets::default(),
            resumed: false,
        }
    }

    /// Re-reading from a block boundary of a checked file (see `crate::stream`), with
    /// `seen_code` as the first scan had it there (so a chunk's first `PROC` line is read
    /// as the first scan read it).
    pub fn resumed(&mut self, seen_code: bool) {
        self.resumed = true;
        self.seen_code = seen_code;
    }

    /// Whether a block of code came before (for a resume checkpoint).
    pub fn seen_code(&self) -> bool {
        self.seen_code
    }

    /// A block with words was read past the builder (a re-read's direct route).
    pub fn code_seen(&mut self) {
        self.seen_code = true;
    }

    /// Block numbers are kept as runs (`N10 N20 N30 …` is one entry), so a streamed
    /// million-block file does not hold one entry per numbered block.
    pub fn compact_targets(&mut self) {
        self.targets.compact = true;
    }

    pub fn at_top(&self) -> bool {
        self.stack.is_empty() && self.suppressed == 0
    }

    /// A re-read at top level: a plain block read now only adds its statement (no jump
    /// targets are recorded; `seen_code` only decides NC129, which the first scan already
    /// reported for a file that runs), so a caller may take it as read.
    pub fn resumed_at_top(&self) -> bool {
        self.resumed && self.at_top() && self.program.body.is_empty()
    }

    /// Takes the finished top-level statements (streaming).
    pub fn drain(&mut self) -> Vec<Stmt> {
        std::mem::take(&mut self.program.body)
    }

    /// [`Builder::drain`] into `out`; when `out` is empty the vectors trade places, so a stream of
    /// one-block statements allocates no new vector per block.
    pub fn drain_into(&mut self, out: &mut Vec<Stmt>) {
        if out.is_empty() {
            std::mem::swap(&mut self.program.body, out);
        } else {
            out.append(&mut self.program.body);
        }
    }

    /// Sets the `%_N_…` header (it is read before any block).
    pub fn header(&mut self, h: Header) {
        self.program.name = h.name.map(ProgName::Name);
        self.program.head = Some(h.meta);
    }

    /// Adds the next block of the file.
    pub fn push(&mut self, line: Line, st: &mut FileState) {
        let file = st.file;
        if !self.resumed {
            self.targets.record(&line, st);
        }
        let Line { meta, kind, kw } = line;
        let is_control = !matches!(kind, LineKind::Plain(_) | LineKind::Proc(_));
        if is_control {
            control_block_checks(&meta, kw, st);
        }
        let opener = match &kind {
            LineKind::If(_) => Some(Kind::If),
            LineKind::While(_) => Some(Kind::While),
            LineKind::Loop => Some(Kind::Loop),
            LineKind::For { .. } => Some(Kind::For),
            LineKind::Repeat => Some(Kind::Repeat),
            _ => None,
        };
        let closer = match &kind {
            LineKind::EndIf => Some(Kind::If),
            LineKind::EndWhile => Some(Kind::While),
            LineKind::EndLoop => Some(Kind::Loop),
            LineKind::EndFor => Some(Kind::For),
            LineKind::Until(_) => Some(Kind::Repeat),
            _ => None,
        };
        if self.suppressed > 0 {
            // Inside a structure nested too deep: only count, so the ENDs pair up.
            if opener.is_some() {
                self.suppressed += 1;
            } else if closer.is_some() {
                self.suppressed -= 1;
            }
            return;
        }
        if let Some(k) = opener {
            if self.stack.len() >= MAX_NESTING {
                if !self.deep_reported {
                    st.diags.push(
                        Diagnostic::error(
                            "NC211",
                            format!("control structures nested deeper than {MAX_NESTING} levels"),
                        )
                        .primary(file, kw, format!("{} at nesting level {}", k.opener(), self.stack.len() + 1))
                        .hint("move the inner part into a subprogram"),
                    );
                    self.deep_reported = true;
                }
                self.suppressed = 1;
                return;
            }
            self.seen_code = true;
            let mut open =
                Open { kind: k, head: meta, kw, cond: None, for_var: None, body: Vec::new(), else_part: None };
            match kind {
                LineKind::If(c) | LineKind::While(c) => open.cond = Some(c),
                LineKind::For { var, from, to } => open.for_var = Some((var, from, to)),
                _ => {}
            }
            self.stack.push(open);
            return;
        }
        if let Some(k) = closer {
            self.seen_code = true;
            let until = match kind {
                LineKind::Until(c) => Some(c),
                _ => None,
            };
            close(&mut self.stack, &mut self.program.body, k, meta, kw, until, st);
            return;
        }
        match kind {
            LineKind::Else => {
                self.seen_code = true;
                match self.stack.last_mut() {
                    Some(o) if o.kind == Kind::If && o.else_part.is_none() => {
                        o.else_part = Some(ElsePart { head: meta, body: Vec::new() });
                    }
                    Some(o) if o.kind == Kind::If => {
                        let first = o.else_part.as_ref().map_or(o.kw, |e| e.head.span);
                        st.diags.push(
                            Diagnostic::error("NC209", "second ELSE in one IF")
                                .primary(file, kw, "second ELSE")
                                .secondary(file, first, "first ELSE here")
                                .hint("an IF has at most one ELSE; close the IF with ENDIF first"),
                        );
                    }
                    other => {
                        let mut d = Diagnostic::error("NC209", "ELSE without IF").primary(file, kw, "no open IF");
                        if let Some(o) = other {
                            d = d.secondary(
                                file,
                                o.kw,
                                format!("the innermost open structure is this {}", o.kind.opener()),
                            );
                        }
                        st.diags.push(d.hint("ELSE belongs between `IF condition` and ENDIF"));
                    }
                }
            }
            LineKind::Proc(p) => {
                if self.seen_code {
                    st.diags.push(
                        Diagnostic::error("NC129", "PROC must be the first block of the program")
                            .primary(file, kw, "PROC after other blocks")
                            .hint("move the PROC line to the top; only comments and the `%_N_…` header may precede it"),
                    );
                } else {
                    self.program.name = Some(ProgName::Name(p.name));
                    self.program.head = Some(meta);
                    self.program.params = p.params;
                    self.program.save = p.save;
                }
                self.seen_code = true;
            }
            LineKind::Plain(items) => {
                self.seen_code |= !items.is_empty();
                let span = meta.span;
                let stmt = Stmt { kind: StmtKind::Block(Block { meta, items }), span };
                match self.stack.last_mut() {
                    Some(o) => o.body_mut().push(stmt),
                    None => self.program.body.push(stmt),
                }
            }
            _ => {}
        }
    }

    /// Adds a plain block read for an index only (see `fast::skeleton`): its items were not
    /// built, `words` says whether it had any. Everything but the items is as [`push`]
    /// would have it; a plain block's items matter here only as "the block holds code"
    /// (for the PROC check) and as jumps, which the fast path never reads.
    ///
    /// [`push`]: Builder::push
    pub fn push_skeleton(&mut self, meta: BlockMeta, words: bool, st: &mut FileState) {
        let kw = meta.span;
        let counted = self.suppressed == 0;
        self.push(Line { meta, kind: LineKind::Plain(Vec::new()), kw }, st);
        if counted {
            self.seen_code |= words;
        }
    }

    /// No structure is open and no statement waits to be drained: a plain block now is a
    /// top-level statement handed out alone (see [`Builder::push_plain_top`]).
    pub fn plain_at_top(&self) -> bool {
        self.at_top() && self.program.body.is_empty()
    }

    /// What [`push_skeleton`] of a plain block numbered `number` and a drain leave behind
    /// when [`Builder::plain_at_top`]: the number recorded as a jump target (the block has
    /// no label and no jump), code noted when it has words. The statement is not made.
    ///
    /// [`push_skeleton`]: Builder::push_skeleton
    pub fn push_plain_top(&mut self, number: Option<&SeqNo>, words: bool) {
        if !self.resumed {
            self.targets.record_plain(number);
        }
        self.seen_code |= words;
    }

    /// Closes what is still open, checks the jump targets, and returns the program.
    pub fn finish(mut self, st: &mut FileState) -> Program {
        let file = st.file;
        if !self.resumed {
            self.targets.check(st);
        }
        // Unterminated structures: report each (outermost first), then close them so the tree is whole.
        for o in &self.stack {
            st.diags.push(
                Diagnostic::error("NC200", format!("{} is never closed", o.kind.opener()))
                    .primary(file, o.kw, format!("this {} needs {}", o.kind.opener(), o.kind.closer()))
                    .hint(format!("add {} after {}", o.kind.closer(), o.kind.body_word())),
            );
        }
        while let Some(o) = self.stack.pop() {
            let end = o.head.clone();
            let stmt = o.close(end, None);
            match self.stack.last_mut() {
                Some(p) => p.body_mut().push(stmt),
                None => self.program.body.push(stmt),
            }
        }
        self.program
    }
}

/// Handles an END line (`ENDIF`, `ENDWHILE`, …, `UNTIL`): closes the matching structure or
/// reports why it cannot.
fn close(
    stack: &mut Vec<Open>,
    root: &mut Vec<Stmt>,
    k: Kind,
    meta: BlockMeta,
    kw: Span,
    until: Option<Expr>,
    st: &mut FileState,
) {
    let file = st.file;
    let Some(top) = stack.last() else {
        st.diags.push(
            Diagnostic::error("NC201", format!("{} without {}", k.closer(), k.opener()))
                .primary(file, kw, format!("no open {}", k.opener()))
                .hint(format!("remove it, or open the structure with {} before", k.opener())),
        );
        return;
    };
    if top.kind != k {
        let hint = if stack.iter().any(|o| o.kind == k) {
            format!("close the inner {} with {} first", top.kind.opener(), top.kind.closer())
        } else {
            format!("write {} to close this {}", top.kind.closer(), top.kind.opener())
        };
        st.diags.push(
            Diagnostic::error("NC202", format!("{} cannot close {}", k.closer(), top.kind.opener()))
                .primary(file, kw, format!("{} here", k.closer()))
                .secondary(
                    file,
                    top.kw,
                    format!("this {} is still open and needs {}", top.kind.opener(), top.kind.closer()),
                )
                .hint(hint),
        );
        // Recover: if a matching structure is open further out, close everything up to it;
        // otherwise take this END as the end of the innermost structure.
        if !stack.iter().any(|o| o.kind == k) {
            if let Some(o) = stack.pop() {
                push(stack, root, o.close(meta, until));
            }
            return;
        }
        while let Some(o) = stack.pop() {
            if o.kind == k {
                push(stack, root, o.close(meta, until));
                return;
            }
            let end = meta.clone();
            push(stack, root, o.close(end, None));
        }
        return;
    }
    if let Some(o) = stack.pop() {
        push(stack, root, o.close(meta, until));
    }
}

fn push(stack: &mut [Open], root: &mut Vec<Stmt>, s: Stmt) {
    match stack.last_mut() {
        Some(o) => o.body_mut().push(s),
        None => root.push(s),
    }
}

/// A control-structure block may carry neither a label nor a skip (source S16 of
/// `docs/semantics.md`).
fn control_block_checks(meta: &BlockMeta, kw: Span, st: &mut FileState) {
    let file = st.file;
    if let Some(l) = &meta.label {
        st.diags.push(
            Diagnostic::error("NC203", "a label is not allowed on a control-structure block")
                .primary(file, l.span, format!("label {}", l.name))
                .secondary(file, kw, "control-structure keyword")
                .note("Sinumerik does not allow jump labels in blocks with IF, ELSE, ENDIF, WHILE, LOOP, FOR, REPEAT, UNTIL")
                .hint(format!("put `{}:` on a block of its own before this one", l.name)),
        );
    }
    if meta.skip.is_some() {
        st.diags.push(
            Diagnostic::error("NC204", "a control-structure block cannot be skipped")
                .primary(file, meta.span, "block with `/`")
                .hint("remove the `/`; skip the blocks inside the structure instead"),
        );
    }
}

/// Labels, block numbers and jumps seen so far, by block ordinal; checked at the end:
/// duplicate labels, every GOTOF/GOTOB/GOTO target must exist in its search direction
/// (GOTOC may miss), REPEAT section labels must exist above.
#[derive(Default)]
struct Targets {
    count: usize,
    labels: HashMap<String, Vec<(usize, Span)>>,
    numbers: HashMap<u32, Vec<(usize, Span)>>,
    /// Streaming: `numbers` stays empty and block numbers go here, as runs.
    compact: bool,
    runs: crate::dialect::runs::Runs,
    jumps: Vec<(usize, Jump)>,
}

enum Jump {
    Goto(Goto),
    /// A REPEAT label; `true`: REPEATB's, which may also stand below it.
    Section(Label, bool),
}

impl Targets {
    /// [`Targets::record`] of a plain block without label and jumps.
    fn record_plain(&mut self, number: Option<&SeqNo>) {
        let i = self.count;
        self.count += 1;
        if let Some(n) = number {
            if self.compact {
                self.runs.push(n.value, i as u64, n.span);
            } else {
                self.numbers.entry(n.value).or_default().push((i, n.span));
            }
        }
    }

    fn record(&mut self, l: &Line, st: &mut FileState) {
        let i = self.count;
        self.count += 1;
        if let Some(lb) = &l.meta.label {
            let v = self.labels.entry(lb.name.clone()).or_default();
            // ENDLABEL may end several sections of one program (docs/semantics.md).
            let first = v.first().filter(|_| lb.name != crate::ir::ENDLABEL);
            if let Some(&(_, first)) = first {
                st.diags.push(
                    Diagnostic::error("NC207", format!("label {} is defined twice", lb.name))
                        .primary(st.file, lb.span, "second definition")
                        .secondary(st.file, first, "first definition")
                        .hint("give every label a unique name"),
                );
            }
            v.push((i, lb.span));
        }
        if let Some(n) = &l.meta.number {
            if self.compact {
                self.runs.push(n.value, i as u64, n.span);
            } else {
                self.numbers.entry(n.value).or_default().push((i, n.span));
            }
        }
        let LineKind::Plain(items) = &l.kind else { return };
        for it in items {
            match &it.kind {
                ItemKind::Goto(g) => self.jumps.push((i, Jump::Goto((**g).clone()))),
                ItemKind::Case(c) => {
                    for g in c.arms.iter().map(|a| &a.goto).chain(c.default.iter()) {
                        self.jumps.push((i, Jump::Goto(g.clone())));
                    }
                }
                ItemKind::RepeatSection(r) => {
                    for lb in std::iter::once(&r.start).chain(r.end.iter()) {
                        self.jumps.push((i, Jump::Section(lb.clone(), r.single)));
                    }
                }
                _ => {}
            }
        }
    }

    fn check(&self, st: &mut FileState) {
        let file = st.file;
        for (i, j) in &self.jumps {
            match j {
                Jump::Goto(g) if self.compact => {
                    // Only the places of the jump's own number are expanded from the runs.
                    let mut numbers = HashMap::new();
                    if let Target::Number(n) = &g.target {
                        let places: Vec<(usize, Span)> =
                            self.runs.places(n.value, *i as u64).into_iter().map(|(at, s)| (at as usize, s)).collect();
                        if !places.is_empty() {
                            numbers.insert(n.value, places);
                        }
                    }
                    check_goto(g, *i, &self.labels, &numbers, st)
                }
                Jump::Goto(g) => check_goto(g, *i, &self.labels, &self.numbers, st),
                Jump::Section(lb, single) => {
                    let before = self.labels.get(&lb.name).is_some_and(|v| v.iter().any(|&(j, _)| j <= *i || *single));
                    if !before && *single {
                        st.diags.push(
                            Diagnostic::error("NC205", format!("label {} of this REPEATB does not exist", lb.name))
                                .primary(file, lb.span, "no such label in this program")
                                .hint(format!("REPEATB repeats one block; put `{}:` on it", lb.name)),
                        );
                    } else if !before {
                        st.diags.push(
                            Diagnostic::error("NC205", format!("label {} is not defined before this REPEAT", lb.name))
                                .primary(file, lb.span, "no such label above")
                                .hint(format!(
                                    "REPEAT repeats a section above it; put `{}:` on its first block",
                                    lb.name
                                )),
                        );
                    }
                }
            }
        }
    }
}

fn check_goto(
    g: &Goto,
    at: usize,
    labels: &HashMap<String, Vec<(usize, Span)>>,
    numbers: &HashMap<u32, Vec<(usize, Span)>>,
    st: &mut FileState,
) {
    if g.missing_continues {
        return;
    }
    let file = st.file;
    let (places, what, span, define) = match &g.target {
        Target::Label(l) => (labels.get(&l.name), format!("label {}", l.name), l.span, format!("`{}:`", l.name)),
        Target::Number(n) => {
            (numbers.get(&n.value), format!("block number N{}", n.value), n.span, format!("`N{}`", n.value))
        }
        Target::Computed(_) => return,
    };
    let places: &[(usize, Span)] = places.map_or(&[], |v| v.as_slice());
    let found = places.iter().any(|&(j, _)| match g.search {
        Search::Forward => j >= at,
        Search::Backward => j <= at,
        _ => true,
    });
    if found {
        return;
    }
    let (kw, dir, other) = match g.search {
        Search::Forward => ("GOTOF", "forward", "GOTOB"),
        Search::Backward => ("GOTOB", "backward", "GOTOF"),
        _ => ("GOTO", "", ""),
    };
    let d = match places.first() {
        Some(&(_, there)) => {
            Diagnostic::error("NC210", format!("{kw} searches {dir}, but {what} is only on the other side"))
                .primary(file, span, format!("{what} not found {dir}"))
                .secondary(file, there, format!("{what} is here"))
                .hint(format!("jump with {other} (or GOTO, which searches both ways)"))
        }
        None => {
            let code = if matches!(g.target, Target::Label(_)) { "NC205" } else { "NC206" };
            Diagnostic::error(code, format!("jump to {what}, which does not exist"))
                .primary(file, span, format!("no {what} in this program"))
                .hint(format!(
                    "add {define} at the start of the block to jump to, or use GOTOC to continue when it is missing"
                ))
        }
    };
    st.diags.push(d);
}
