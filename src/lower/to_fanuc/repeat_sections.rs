//! Siemens program-section repetition (`REPEAT A B P=n`, `REPEAT A P=n` with or without
//! `ENDLABEL`, `REPEATB A P=n`) → the section's own statements written again where the
//! REPEAT stands, in a counted `WHILE` (lowered to `WHILE [..] DOm` with the DO levels of
//! every loop, past the third a label/GOTO loop) or, for one pass, as they are.
//!
//! Runs on each Siemens program before any other pass (`translate::to_fanuc`), so the copies
//! are translated, followed for modes and numbered like any statement written there. A copy
//! is exact only when the section is a run of whole statements of one statement list and
//! nothing in it leaves it: a GOTO or CASE in it would land in the original blocks (or out of
//! the section), a RET/M17/M30/M2 ends the run of the section in a way no stored source
//! settles, so those are refused (NC657); a section that is not such a run, a DEF in it, a
//! `/` skip or other words on the REPEAT block, a literal P below 1 or not whole, NC658;
//! repetitions nested in copies deeper than [`MAX_NESTING`] or copies growing past
//! [`MAX_COPIED`] statements (each nested REPEAT copies its section again), NC659. Labels and
//! N numbers stay on the original blocks only: no jump names a block of a copy.

use super::*;
use std::collections::HashMap;

/// Repetitions a copy may hold inside one another.
pub const MAX_NESTING: usize = 4;
/// Statements the copies of one program may add in all.
pub const MAX_COPIED: usize = 100_000;

/// Where a statement stands: the statement list (numbered in source order) and its index.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct At {
    list: usize,
    index: usize,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Role {
    /// A plain block: the statement's first and last line.
    Whole,
    /// A structure's head (`IF`, `WHILE`, …): its first line.
    Head,
    /// An `ELSE` line.
    Inner,
    /// A structure's end (`ENDIF`, …): its last line.
    End,
}

/// One line of the program, in source order.
struct Line {
    at: At,
    role: Role,
    label: Option<String>,
}

struct Site {
    line: usize,
    at: At,
    rs: RepeatSection,
    span: Span,
}

/// The statements `from..=to` of a list.
#[derive(Clone, Copy)]
struct Section {
    list: usize,
    from: usize,
    to: usize,
}

struct Index<'a> {
    lists: Vec<&'a [Stmt]>,
    lines: Vec<Line>,
    sites: Vec<Site>,
}

impl<'a> Index<'a> {
    fn list(&mut self, body: &'a [Stmt]) {
        let list = self.lists.len();
        self.lists.push(body);
        for (index, s) in body.iter().enumerate() {
            let at = At { list, index };
            let line = |this: &mut Self, role, m: &BlockMeta| {
                this.lines.push(Line { at, role, label: m.label.as_ref().map(|l| l.name.clone()) })
            };
            match &s.kind {
                StmtKind::Block(b) => {
                    for it in &b.items {
                        if let ItemKind::RepeatSection(rs) = &it.kind {
                            let rs = (**rs).clone();
                            self.sites.push(Site { line: self.lines.len(), at, rs, span: it.span });
                        }
                    }
                    line(self, Role::Whole, &b.meta);
                }
                StmtKind::If(i) => {
                    line(self, Role::Head, &i.head);
                    self.list(&i.then_body);
                    if let Some(e) = &i.else_part {
                        line(self, Role::Inner, &e.head);
                        self.list(&e.body);
                    }
                    line(self, Role::End, &i.end);
                }
                k => {
                    let ms = crate::ir::visit::metas(k);
                    line(self, Role::Head, ms[0]);
                    for child in crate::ir::visit::child_bodies(k) {
                        self.list(child);
                    }
                    line(self, Role::End, ms[ms.len() - 1]);
                }
            }
        }
    }
}

/// Why a section cannot be copied: code, what, hint.
type Refusal = (&'static str, String, String);

/// `prog` with its program-section repetitions copied ([`run`]), `None` when it has none.
pub fn copied(ctx: &mut Ctx, prog: &Program) -> Option<Program> {
    let mut any = false;
    crate::ir::visit::walk_stmts(&prog.body, &mut |s| {
        any |= matches!(&s.kind, StmtKind::Block(b)
            if b.items.iter().any(|it| matches!(it.kind, ItemKind::RepeatSection(_))));
    });
    any.then(|| {
        let mut p = prog.clone();
        run(ctx, &mut p);
        p
    })
}

/// Copies every program-section repetition of `prog` where it stands (see the module doc);
/// reports what it refuses in `ctx`.
pub fn run(ctx: &mut Ctx, prog: &mut Program) {
    let body = std::mem::take(&mut prog.body);
    let mut ix = Index { lists: Vec::new(), lines: Vec::new(), sites: Vec::new() };
    ix.list(&body);
    if ix.sites.is_empty() {
        prog.body = body;
        return;
    }
    let mut sections = Vec::with_capacity(ix.sites.len());
    for site in &ix.sites {
        let sec = resolve(&ix, site).and_then(|sec| contents(&ix, sec).map(|()| sec));
        sections.push(match sec {
            Ok(sec) => Some(sec),
            Err((code, what, hint)) => {
                ctx.unsupported(code, site.span, &what, &hint);
                None
            }
        });
    }
    let by_span = ix.sites.iter().enumerate().map(|(k, s)| (s.span, k)).collect();
    let mut cp = Copier { ctx, ix: &ix, sections, by_span, copied: 0, reported: vec![false; ix.sites.len()] };
    let out = cp.body(&body, false, &mut Vec::new());
    prog.body = out;
}

/// The section a REPEAT runs, found as the control finds it (docs/semantics.md, Section
/// repetition), or why it is not a run of whole statements the copy can take.
fn resolve(ix: &Index<'_>, site: &Site) -> Result<Section, Refusal> {
    let rs = &site.rs;
    let r = site.line;
    let back = |name: &str| (0..=r).rev().find(|&k| ix.lines[k].label.as_deref() == Some(name));
    let shape = |what: String, hint: &str| ("NC658", what, hint.to_string());
    let Some(ls) = back(&rs.start.name).or_else(|| {
        // REPEATB searches toward the program end too.
        rs.single.then(|| (r + 1..ix.lines.len()).find(|&k| ix.lines[k].label.as_deref() == Some(&rs.start.name)))?
    }) else {
        let hint = format!("put `{}:` on the first block of the section, above the REPEAT", rs.start.name);
        return Err(shape(format!("REPEAT of label {}, which is not above it", rs.start.name), &hint));
    };
    let recursion = || {
        (
            "NC659",
            format!("REPEAT {} whose section holds this REPEAT itself", rs.start.name),
            "the section would repeat without end: end it on the block before the REPEAT".to_string(),
        )
    };
    let start = &ix.lines[ls];
    if rs.single {
        if ls == r {
            return Err(recursion());
        }
        if start.role != Role::Whole {
            return Err(shape(
                format!("REPEATB {} of a structure's line (IF, WHILE, …)", rs.start.name),
                "REPEATB repeats one plain block: label a block that is not a control structure",
            ));
        }
        return Ok(Section { list: start.at.list, from: start.at.index, to: start.at.index });
    }
    let end = match &rs.end {
        Some(l) => match back(&l.name) {
            Some(le) => Some(le),
            None => {
                let hint = format!("put `{}:` on the last block of the section, above the REPEAT", l.name);
                return Err(shape(format!("REPEAT to label {}, which is not above it", l.name), &hint));
            }
        },
        None => (ls + 1..r).find(|&k| ix.lines[k].label.as_deref() == Some(ENDLABEL)),
    };
    if ls == r || end == Some(r) {
        return Err(recursion());
    }
    let (end_at, end_role) = match end {
        Some(le) => (ix.lines[le].at, ix.lines[le].role),
        // The block before the REPEAT.
        None if site.at.index > 0 => (At { list: site.at.list, index: site.at.index - 1 }, Role::Whole),
        None => (site.at, Role::Head),
    };
    let across = shape(
        format!(
            "REPEAT {}: its section begins or ends inside a control structure (IF, WHILE, LOOP, FOR, …)",
            rs.start.name
        ),
        "copied, it would be a part of a structure: let the section hold whole structures, its labels on lines of \
         one level",
    );
    if !matches!(start.role, Role::Whole | Role::Head) || !matches!(end_role, Role::Whole | Role::End) {
        return Err(across);
    }
    if start.at.list != end_at.list {
        return Err(across);
    }
    if end_at.index < start.at.index {
        return Err(shape(
            format!("REPEAT {}: its end label stands above its start label", rs.start.name),
            "the section runs from the start label down to the end label",
        ));
    }
    Ok(Section { list: start.at.list, from: start.at.index, to: end_at.index })
}

/// Refuses what a copy cannot carry over: flow leaving the section, DEFs.
fn contents(ix: &Index<'_>, sec: Section) -> Result<(), Refusal> {
    let stmts = &ix.lists[sec.list][sec.from..=sec.to];
    let mut found: Option<Refusal> = None;
    crate::ir::visit::walk_stmts(stmts, &mut |s| {
        let StmtKind::Block(b) = &s.kind else { return };
        for it in &b.items {
            let why = match &it.kind {
                ItemKind::Goto(_) | ItemKind::Case(_) => Some((
                    "NC657",
                    "a jump (GOTO, CASE) in a repeated section",
                    "its copy would jump into the original blocks or out of the section: write the section with \
                     IF/WHILE, or repeat a section without the jump",
                )),
                ItemKind::Return { .. } | ItemKind::End { .. } => Some((
                    "NC657",
                    "a RET/M17/M30/M2 in a repeated section",
                    "no stored source says where a Sinumerik control goes on when a repeated section returns or \
                     ends: end the program after the REPEAT",
                )),
                ItemKind::Def(_) => Some((
                    "NC658",
                    "a DEF in a repeated section",
                    "declarations stand at the top of the program, before any section",
                )),
                _ => None,
            };
            if let (None, Some((code, what, hint))) = (&found, why) {
                found = Some((code, what.to_string(), hint.to_string()));
            }
        }
    });
    found.map_or(Ok(()), Err)
}

struct Copier<'c, 'a> {
    ctx: &'c mut Ctx,
    ix: &'c Index<'a>,
    sections: Vec<Option<Section>>,
    by_span: HashMap<Span, usize>,
    copied: usize,
    reported: Vec<bool>,
}

/// Drops what makes a line of a copy a jump target: the original keeps it.
fn unmark(m: &mut BlockMeta) {
    m.label = None;
    m.number = None;
}

impl Copier<'_, '_> {
    /// `body` with each REPEAT replaced by its copy; `copy`: these statements are a copy.
    /// `open`: the repetitions being copied (outermost first), each with whether it loops.
    fn body(&mut self, body: &[Stmt], copy: bool, open: &mut Vec<(usize, bool)>) -> Vec<Stmt> {
        let mut out = Vec::with_capacity(body.len());
        for s in body {
            let site = match &s.kind {
                StmtKind::Block(b) => b.items.iter().find_map(|it| match it.kind {
                    ItemKind::RepeatSection(_) => Some(self.by_span.get(&it.span).copied()),
                    _ => None,
                }),
                _ => None,
            };
            if let (Some(Some(k)), StmtKind::Block(b)) = (site, &s.kind) {
                self.site(k, b, copy, open, &mut out);
                continue;
            }
            let s = self.stmt(s, copy, open);
            out.push(s);
        }
        out
    }

    /// `s` with its bodies copied (see [`Copier::body`]).
    fn stmt(&mut self, s: &Stmt, copy: bool, open: &mut Vec<(usize, bool)>) -> Stmt {
        let m = |meta: &BlockMeta| {
            let mut meta = meta.clone();
            if copy {
                unmark(&mut meta);
            }
            meta
        };
        let kind = match &s.kind {
            StmtKind::Block(b) => StmtKind::Block(Block { meta: m(&b.meta), items: b.items.clone() }),
            StmtKind::If(i) => {
                let then_body = self.body(&i.then_body, copy, open);
                let else_part =
                    i.else_part.as_ref().map(|e| ElsePart { head: m(&e.head), body: self.body(&e.body, copy, open) });
                let (head, cond, end) = (m(&i.head), i.cond.clone(), m(&i.end));
                StmtKind::If(Box::new(IfStmt { head, cond, then_body, else_part, end }))
            }
            StmtKind::While(w) => {
                let body = self.body(&w.body, copy, open);
                StmtKind::While(Box::new(WhileStmt { head: m(&w.head), cond: w.cond.clone(), body, end: m(&w.end) }))
            }
            StmtKind::Loop(l) => {
                let body = self.body(&l.body, copy, open);
                StmtKind::Loop(Box::new(LoopStmt { head: m(&l.head), body, end: m(&l.end) }))
            }
            StmtKind::For(f) => {
                let body = self.body(&f.body, copy, open);
                let (var, from, to) = (f.var.clone(), f.from.clone(), f.to.clone());
                StmtKind::For(Box::new(ForStmt { head: m(&f.head), var, from, to, body, end: m(&f.end) }))
            }
            StmtKind::Repeat(r) => {
                let body = self.body(&r.body, copy, open);
                let until = r.until.clone();
                StmtKind::Repeat(Box::new(RepeatStmt { head: m(&r.head), body, end: m(&r.end), until }))
            }
            StmtKind::Do(d) => {
                let body = self.body(&d.body, copy, open);
                let (id, cond) = (d.id, d.cond.clone());
                StmtKind::Do(Box::new(DoStmt { head: m(&d.head), id, cond, body, end: m(&d.end) }))
            }
        };
        Stmt { kind, span: s.span }
    }

    fn refuse_once(&mut self, k: usize, r: Refusal) {
        if !std::mem::replace(&mut self.reported[k], true) {
            let (code, what, hint) = r;
            self.ctx.unsupported(code, self.ix.sites[k].span, &what, &hint);
        }
    }

    /// The statements standing for REPEAT site `k` (block `b`).
    fn site(&mut self, k: usize, b: &Block, copy: bool, open: &mut Vec<(usize, bool)>, out: &mut Vec<Stmt>) {
        let site = &self.ix.sites[k];
        let rs = site.rs.clone();
        let span = site.span;
        let mut meta = b.meta.clone();
        if copy {
            unmark(&mut meta);
        }
        let Some(sec) = self.sections[k] else {
            // Refused (reported): the block stays without its REPEAT.
            out.push(meta_stmt(meta, vec![]));
            return;
        };
        let shape = |what: String, hint: &str| ("NC658", what, hint.to_string());
        if b.items.len() > 1 || meta.skip.is_some() {
            let r = shape(
                format!("REPEAT {} with a block skip or other words in its block", rs.start.name),
                "write the REPEAT alone in its block, without `/`",
            );
            self.refuse_once(k, r);
            out.push(meta_stmt(meta, vec![]));
            return;
        }
        if open.iter().any(|&(o, _)| o == k) {
            let r = (
                "NC659",
                format!("REPEAT {} that its own section repeats again", rs.start.name),
                "the copies would not end".to_string(),
            );
            self.refuse_once(k, r);
            return;
        }
        if open.len() >= MAX_NESTING {
            // Told at the outermost REPEAT, whose copy holds them all.
            let outer = open[0].0;
            let r = (
                "NC659",
                format!(
                    "REPEAT {} whose section holds repetitions nested more than {MAX_NESTING} deep",
                    self.ix.sites[outer].rs.start.name
                ),
                "each nested REPEAT copies its section again: repeat a section that holds fewer REPEATs".to_string(),
            );
            self.refuse_once(outer, r);
            return;
        }
        // The pass count: a literal as it is, else ROUND(P) (P is an INT) counted down.
        let literal = match rs.count.as_ref().map(|c| &c.kind) {
            None => Some(1.0),
            Some(ExprKind::Num(n)) => Some(n.value),
            _ => None,
        };
        if let Some(v) = literal {
            if v < 1.0 || v.fract() != 0.0 {
                let r = shape(
                    format!("REPEAT {} P={v}", rs.start.name),
                    "P counts the passes: write a whole number of at least 1 (what a control does with P=0 is not \
                     documented)",
                );
                self.refuse_once(k, r);
                out.push(meta_stmt(meta, vec![]));
                return;
            }
        }
        let looped = literal != Some(1.0);
        let stmts = &self.ix.lists[sec.list][sec.from..=sec.to];
        open.push((k, looped));
        let copy_body = self.body(stmts, true, open);
        open.pop();
        // Counted once, for the outermost copy (it holds the nested ones).
        if open.is_empty() {
            self.copied += count(&copy_body);
        }
        if self.copied > MAX_COPIED {
            let r = (
                "NC659",
                format!("REPEAT {}: the copies of the repeated sections pass {MAX_COPIED} statements", rs.start.name),
                "nested REPEATs copy their sections again each: repeat fewer or shorter sections".to_string(),
            );
            self.refuse_once(k, r);
            return;
        }
        // One comment (a second one in the block would not come back the same way from
        // Sinumerik, whose line has one): the REPEAT's own text after the description.
        let desc = describe(&rs, literal);
        match meta.comments.first_mut() {
            Some(c) if c.text.starts_with(' ') => c.text = format!("{desc}:{}", c.text),
            Some(c) => c.text = format!("{desc}: {}", c.text),
            None => meta.comments.push(Comment { text: desc, span }),
        }
        out.push(meta_stmt(meta, vec![]));
        if !looped {
            out.extend(copy_body);
            return;
        }
        let depth = open.iter().filter(|o| o.1).count() + 1;
        let c = VarRef { kind: VarKind::Named { name: format!("{TEMP_PREFIX}REPEAT_{depth}"), indices: vec![] }, span };
        let cv = var_expr(&c);
        let exact = |op, a, b| Expr::new(ExprKind::Cmp(op, Tolerance::Exact, Box::new(a), Box::new(b)), span);
        let (init, cond, step) = match (literal, &rs.count) {
            (Some(v), _) => (num(1.0, span), exact(CmpOp::Le, cv.clone(), num(v, span)), BinOp::Add),
            (None, Some(p)) => {
                (func(Func::Round, vec![p.clone()], span), exact(CmpOp::Gt, cv.clone(), num(0.0, span)), BinOp::Sub)
            }
            (None, None) => return,
        };
        out.push(block_stmt(vec![assign_item(&c, init, span)], span));
        let mut body = copy_body;
        body.push(block_stmt(vec![assign_item(&c, bin(step, cv, num(1.0, span)), span)], span));
        let plain = BlockMeta { span, ..BlockMeta::default() };
        let w = WhileStmt { head: plain.clone(), cond, body, end: plain };
        out.push(Stmt { kind: StmtKind::While(Box::new(w)), span });
    }
}

/// The comment naming what the copy below it repeats.
fn describe(rs: &RepeatSection, literal: Option<f64>) -> String {
    let what = match (&rs.end, rs.single) {
        (_, true) => format!("BLOCK {}", rs.start.name),
        (Some(e), false) => format!("SECTION {} TO {}", rs.start.name, e.name),
        (None, false) => format!("SECTION FROM {}", rs.start.name),
    };
    let times = match (literal, &rs.count) {
        (Some(1.0), _) => "ONCE".to_string(),
        (Some(v), _) => format!("{v} TIMES"),
        (None, Some(p)) => format!("P={} TIMES", crate::dialect::sinumerik::emit::expr(p)),
        (None, None) => String::new(),
    };
    format!("REPEAT {what}, {times}")
}

fn count(body: &[Stmt]) -> usize {
    let mut n = 0;
    crate::ir::visit::walk_stmts(body, &mut |_| n += 1);
    n
}
