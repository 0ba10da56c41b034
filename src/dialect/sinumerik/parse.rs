//! From the pest pairs of one block to a [`Line`]: block metadata plus either the items of an
//! ordinary block or one control-structure keyword line for the structurer.

use super::names;
use super::structure::{Line, LineKind};
use super::Rule;
use crate::diag::Diagnostic;
use crate::ir::*;
use crate::read::Normalised;
use crate::span::{FileId, Span};
use pest::iterators::Pair;
use std::collections::HashMap;

/// What the reader learns from earlier blocks of the same file.
pub struct FileState {
    pub file: FileId,
    pub diags: Vec<Diagnostic>,
    pub r_count: u32,
    /// Names declared by DEF or PROC so far (upper case), with their type.
    pub declared: HashMap<String, DataType>,
    /// `DEFINE` macros of the library (`Semantics::macros`), replaced before the grammar.
    pub macros: std::sync::Arc<Vec<(String, String)>>,
}

/// Converts the pairs of one block; spans go through `norm` back to the file.
pub struct Lower<'n, 'a> {
    pub norm: &'n Normalised<'a>,
    pub st: &'n mut FileState,
    /// An error was already reported for this block (one bad block, one error).
    pub failed: bool,
    /// The whole block: the span of stand-in values after an error.
    pub whole: Span,
}

impl Lower<'_, '_> {
    /// The file span of a pair, without the blanks pest's implicit whitespace leaves at the
    /// end of a rule (`a ~ b*` keeps the skip before an empty `b*`).
    pub fn span(&self, p: &Pair<'_, Rule>) -> Span {
        let s = p.as_span();
        let end = if p.as_rule() == Rule::comment {
            s.end()
        } else {
            let t = p.as_str();
            s.start() + t.trim_end_matches(|c: char| c == ' ' || c == '&' || c.is_ascii_control()).len()
        };
        self.norm.span(s.start(), end)
    }

    /// Reports a problem in this block; after the first error, further errors of the same
    /// block are dropped (they are usually consequences of the first).
    pub fn error(&mut self, d: Diagnostic) {
        if d.is_error() {
            if self.failed {
                return;
            }
            self.failed = true;
        }
        self.st.diags.push(d);
    }

    pub fn file(&self) -> FileId {
        self.st.file
    }

    /// The whole `block` pair → a line (`None` for a blank line).
    pub fn block(&mut self, block: Pair<'_, Rule>, whole: Span) -> Option<Line> {
        let mut meta = BlockMeta { span: whole, ..Default::default() };
        let mut kind = None;
        let mut kw = whole;
        for p in block.into_inner() {
            match p.as_rule() {
                Rule::skip => {
                    let d = p.as_str().as_bytes().get(1).map_or(0, |c| c - b'0');
                    meta.skip = Some(d);
                }
                Rule::block_no => meta.number = self.seq_no(&p),
                Rule::label => {
                    let span = self.span(&p);
                    let name = p.into_inner().next().map(|n| n.as_str().to_ascii_uppercase()).unwrap_or_default();
                    self.check_label_name(&name, span);
                    meta.label = Some(Label { name, span });
                }
                Rule::comment => {
                    let span = self.span(&p);
                    let text = p.into_inner().next().map(|t| t.as_str().to_string()).unwrap_or_default();
                    meta.comments.push(Comment { text, span });
                }
                Rule::EOI => {}
                _ => {
                    if let Some(first) = p.clone().into_inner().next() {
                        kw = self.span(&first);
                    }
                    kind = Some(self.content(p));
                }
            }
        }
        if kind.is_none()
            && meta.number.is_none()
            && meta.label.is_none()
            && meta.comments.is_empty()
            && meta.skip.is_none()
        {
            return None;
        }
        Some(Line { meta, kind: kind.unwrap_or(LineKind::Plain(Vec::new())), kw })
    }

    fn seq_no(&mut self, p: &Pair<'_, Rule>) -> Option<SeqNo> {
        let span = self.span(p);
        let digits = p.as_str().trim_start_matches(['N', 'n', ':']);
        match digits.parse::<u32>() {
            Ok(value) => Some(SeqNo { value, span }),
            Err(_) => {
                self.error(
                    Diagnostic::error("NC131", "block number too large")
                        .primary(self.file(), span, "more than 4294967295")
                        .hint("use a block number with at most 9 digits"),
                );
                None
            }
        }
    }

    fn check_label_name(&mut self, name: &str, span: Span) {
        let b = name.as_bytes();
        let ok = b.len() >= 2 && b[..2].iter().all(|c| c.is_ascii_alphabetic() || *c == b'_');
        if !ok {
            self.error(
                Diagnostic::error("NC126", format!("`{name}` is not a valid label name"))
                    .primary(self.file(), span, "label here")
                    .note("Sinumerik label names start with two letters or underscores")
                    .hint(format!("rename the label, e.g. `LBL_{name}:`")),
            );
        }
    }

    fn content(&mut self, p: Pair<'_, Rule>) -> LineKind {
        let rule = p.as_rule();
        let mut inner = p.into_inner();
        let next_expr = |me: &mut Self, it: &mut pest::iterators::Pairs<'_, Rule>| -> Expr {
            let e = it.find(|q| q.as_rule() == Rule::expr);
            match e {
                Some(e) => me.expr(e),
                None => Expr::num(0.0, false, me.whole),
            }
        };
        match rule {
            Rule::if_line => {
                let cond = next_expr(self, &mut inner);
                match inner.find(|q| q.as_rule() == Rule::goto_stmt) {
                    Some(g) => {
                        let span = cond.span.to(self.span(&g));
                        let mut goto = self.goto(g);
                        goto.cond = Some(cond);
                        LineKind::Plain(vec![Item { kind: ItemKind::Goto(Box::new(goto)), span }])
                    }
                    None => LineKind::If(cond),
                }
            }
            Rule::else_line => LineKind::Else,
            Rule::endif_line => LineKind::EndIf,
            Rule::while_line => LineKind::While(next_expr(self, &mut inner)),
            Rule::endwhile_line => LineKind::EndWhile,
            Rule::loop_line => LineKind::Loop,
            Rule::endloop_line => LineKind::EndLoop,
            Rule::endfor_line => LineKind::EndFor,
            Rule::repeat_line => LineKind::Repeat,
            Rule::until_line => LineKind::Until(next_expr(self, &mut inner)),
            Rule::for_line => {
                let var = match inner.find(|q| q.as_rule() == Rule::for_var).and_then(|v| v.into_inner().next()) {
                    Some(v) => self.simple_var(&v),
                    None => VarRef { kind: VarKind::R(0), span: self.whole },
                };
                let from = next_expr(self, &mut inner);
                let to = next_expr(self, &mut inner);
                LineKind::For { var, from, to }
            }
            Rule::proc_stmt => LineKind::Proc(self.proc_head(inner)),
            Rule::repeat_section | Rule::case_stmt | Rule::def_stmt => {
                // A whole-block statement that is still an ordinary item.
                let item = self.item_of(rule, inner);
                LineKind::Plain(item.into_iter().collect())
            }
            Rule::items => LineKind::Plain(self.items(inner)),
            Rule::sync_line => LineKind::Plain(self.sync_line(inner).into_iter().collect()),
            Rule::extern_stmt => LineKind::Plain(self.extern_decl(inner).into_iter().collect()),
            _ => LineKind::Plain(Vec::new()),
        }
    }

    fn item_of(&mut self, rule: Rule, inner: pest::iterators::Pairs<'_, Rule>) -> Option<Item> {
        // Re-wrap: the span of a whole-block statement is the span of its children.
        let pairs: Vec<Pair<'_, Rule>> = inner.collect();
        let (lo, hi) = match (pairs.first(), pairs.last()) {
            (Some(a), Some(b)) => (self.span(a), self.span(b)),
            _ => return None,
        };
        let span = lo.to(hi);
        let kind = match rule {
            Rule::repeat_section => self.repeat_section(pairs),
            Rule::case_stmt => self.case(pairs),
            Rule::def_stmt => self.def(pairs),
            _ => return None,
        }?;
        Some(Item { kind, span })
    }

    pub(super) fn items(&mut self, inner: pest::iterators::Pairs<'_, Rule>) -> Vec<Item> {
        let mut out: Vec<Item> = Vec::new();
        // The text of each item, for the interrupt instructions (`interrupt`).
        let mut raw: Vec<String> = Vec::new();
        for p in inner {
            let span = self.span(&p);
            let text = p.as_str().trim().to_string();
            let Some(kind) = self.item(p) else { continue };
            // `NAME P3`, `L123 P=2`: the P word right after a call is its repeat count.
            if let (ItemKind::Word(w), Some(prev)) = (&kind, out.last_mut()) {
                if let ItemKind::Call(c) = &mut prev.kind {
                    if w.addr.is(b'P') && c.repeat.is_none() && c.kind != CallKind::Mcall {
                        if let WordValue::Expr(e) = &w.value {
                            c.repeat = Some(e.clone());
                            prev.span = prev.span.to(span);
                            continue;
                        }
                    }
                }
            }
            out.push(Item { kind, span });
            raw.push(text);
        }
        interrupt(out, &raw)
    }

    pub(super) fn item(&mut self, p: Pair<'_, Rule>) -> Option<ItemKind> {
        let span = self.span(&p);
        match p.as_rule() {
            Rule::word_const => self.word_const(&p),
            Rule::goto_stmt => Some(ItemKind::Goto(Box::new(self.goto(p)))),
            Rule::gotos_stmt => {
                self.error(
                    Diagnostic::error("NC150", "GOTOS is not supported yet")
                        .primary(self.file(), span, "jump to the program start")
                        .note("the IR has no jump target for \"the first block of the program\"")
                        .hint("put a label on the first block and write `GOTOB <label>`"),
                );
                None
            }
            Rule::msg_stmt => {
                let text = p.into_inner().find(|q| q.as_rule() == Rule::expr).map(|e| self.expr(e));
                Some(ItemKind::Message { text })
            }
            Rule::setal_stmt => {
                let number = match p.into_inner().find(|q| q.as_rule() == Rule::expr) {
                    Some(e) => self.expr(e),
                    None => Expr::num(0.0, false, span),
                };
                Some(ItemKind::Alarm { style: AlarmStyle::Setal, number, text: None })
            }
            Rule::stopre_stmt => Some(ItemKind::Stopre),
            Rule::ret_stmt => match p.into_inner().find(|q| q.as_rule() == Rule::ret_args) {
                None => Some(ItemKind::Return { to: None }),
                // Kept as written; the evaluator and the translation refuse it by name.
                Some(a) => Some(ItemKind::Instruction { name: format!("RET({})", a.as_str().trim()) }),
            },
            Rule::mcall_stmt => match p.into_inner().nth(1) {
                None => Some(ItemKind::ModalCallOff),
                Some(c) => match self.item(c)? {
                    ItemKind::Call(mut call) => {
                        call.kind = CallKind::Mcall;
                        Some(ItemKind::Call(call))
                    }
                    _ => {
                        self.error(
                            Diagnostic::error("NC137", "MCALL needs a subprogram name")
                                .primary(self.file(), span, "not a subprogram")
                                .hint("write `MCALL NAME` to call NAME after every motion block, or `MCALL` alone to cancel"),
                        );
                        None
                    }
                },
            },
            Rule::frame_stmt => {
                let mut it = p.into_inner();
                let op = it.next().map(|k| k.as_str().to_ascii_uppercase()).unwrap_or_default();
                let mut words = Vec::new();
                for w in it {
                    let wspan = self.span(&w);
                    match self.item(w) {
                        Some(ItemKind::Word(w)) => words.push(w),
                        Some(_) => self.error(
                            Diagnostic::error("NC138", format!("{op} takes axis words only"))
                                .primary(self.file(), wspan, "not an axis word")
                                .hint(format!(
                                    "write `{op} X10 Y20` with axis addresses; put other statements in their own block"
                                )),
                        ),
                        None => {}
                    }
                }
                Some(ItemKind::Frame { op, words })
            }
            Rule::assign => self.assign(p),
            Rule::call_stmt => self.call_stmt(p),
            Rule::call => {
                let mut it = p.into_inner();
                let name = it.next().map(|n| n.as_str().to_ascii_uppercase()).unwrap_or_default();
                let args = match it.find(|q| q.as_rule() == Rule::arg_list) {
                    Some(a) => self.args(a),
                    None => Vec::new(),
                };
                if name == "WRITE" {
                    return self.write_stmt(args, span);
                }
                // EXTOPEN / EXTCLOSE open and close an external device of the control's set-up
                // (`/dev/ext/n`, extdev.ini), not a program: kept as written for the evaluator
                // and the translation to name (`eval::print::external_device`).
                if matches!(name.as_str(), "EXTOPEN" | "EXTCLOSE") {
                    let text = p_text(&span, self.norm);
                    let text = text.trim();
                    let args = text.get(name.len()..).unwrap_or("");
                    return Some(ItemKind::Instruction { name: format!("{name}{args}") });
                }
                if names::builtin(&name).is_some() {
                    self.error(
                        Diagnostic::error("NC139", format!("{name} is a function; its value must be used"))
                            .primary(self.file(), span, "function result not used")
                            .hint(format!("assign it, e.g. `R1={}`", p_text(&span, self.norm))),
                    );
                    return None;
                }
                Some(call_named(name, args))
            }
            Rule::bare_name => {
                let name = p.as_str().to_ascii_uppercase();
                // `X` or `X1` alone is an address without its value; a longer name with digits
                // (`SH602`, `PLCASUP1`) is a program name: the control looks it up in the
                // program directory first (see `calls::not_found` for the message if absent).
                if name.len() == 1 || (is_numbered(&name) && letters_of(&name) == 1) {
                    self.error(
                        Diagnostic::error("NC127", format!("address {name} has no value"))
                            .primary(self.file(), span, "value missing")
                            .note("Sinumerik never shortens `X0` to `X`; a numbered address needs `=`")
                            .hint(format!("write a value: `{name}0`, `{name}=R1`")),
                    );
                    return None;
                }
                if names::is_instruction(&name) {
                    return Some(ItemKind::Instruction { name });
                }
                Some(call_named(name, Vec::new()))
            }
            _ => None,
        }
    }

    /// `X10`, `G1`, `M30`, `L0123`: letter and constant.
    pub fn word_const(&mut self, p: &Pair<'_, Rule>) -> Option<ItemKind> {
        let text = p.as_str();
        let span = self.span(p);
        let letter = text.as_bytes()[0].to_ascii_uppercase();
        let vs = p.as_span();
        let vspan = self.norm.span(vs.start() + 1, vs.end());
        let (value, point) = self.number_text(&text[1..], vspan)?;
        Some(word_item(letter, &text[1..], value, point, span, vspan))
    }

    /// Parses a signed decimal with optional `EX` exponent. `None` after a diagnostic.
    pub fn number_text(&mut self, t: &str, span: Span) -> Option<(f64, bool)> {
        match parse_number(t) {
            Some(v) => Some(v),
            None => {
                self.error(
                    Diagnostic::error("NC132", "number out of range")
                        .primary(self.file(), span, "not a finite number")
                        .hint("Sinumerik REAL values lie within ±1.8e308"),
                );
                None
            }
        }
    }

    fn assign(&mut self, p: Pair<'_, Rule>) -> Option<ItemKind> {
        let mut it = p.into_inner();
        let target = it.next()?;
        let tspan = self.span(&target);
        let value_pair = it.find(|q| matches!(q.as_rule(), Rule::expr | Rule::ac_ic))?;
        let (value, ac_ic) = self.word_value(value_pair);
        let mut tin = target.into_inner();
        let first = tin.next()?;
        let var = match first.as_rule() {
            Rule::r_indirect | Rule::sys_var => self.var(first),
            _ => {
                let name = first.as_str().to_ascii_uppercase();
                let subs: Vec<Pair<'_, Rule>> = tin.filter(|q| q.as_rule() == Rule::subscripts).collect();
                if subs.is_empty() && names::r_number(&name).is_none() {
                    let declared = self.st.declared.contains_key(&name);
                    if name.len() == 1 || names::is_address_name(&name, declared) {
                        let addr =
                            if name.len() == 1 { Addr::Letter(name.as_bytes()[0]) } else { Addr::Name(name.into()) };
                        let value = match ac_ic {
                            None => WordValue::Expr(value),
                            Some(Pos::Ac) => WordValue::Ac(value),
                            Some(Pos::Ic) => WordValue::Ic(value),
                            Some(Pos::Rotary(m)) => WordValue::Rotary(m, value),
                        };
                        let span = tspan.to(vspan_of(&value));
                        return Some(special_word(Word { addr, value, span }));
                    }
                }
                let indices = match subs.into_iter().next() {
                    Some(s) => self.subscripts(s, names::axis_indexed(&name)),
                    None => Vec::new(),
                };
                // `AX[X]=10`, `AX[AX_W]=IC(2)`: an axis word whose axis is named in the brackets.
                if name == "AX" && indices.len() == 1 && !self.st.declared.contains_key(&name) {
                    let axis = indices.into_iter().next()?;
                    let addr = match &axis.kind {
                        ExprKind::Ident(a) if a.len() == 1 => Addr::Letter(a.as_bytes()[0]),
                        ExprKind::Ident(a) => Addr::Name(a.as_str().into()),
                        _ => Addr::Axis(Box::new(axis)),
                    };
                    let value = match ac_ic {
                        None => WordValue::Expr(value),
                        Some(Pos::Ac) => WordValue::Ac(value),
                        Some(Pos::Ic) => WordValue::Ic(value),
                        Some(Pos::Rotary(m)) => WordValue::Rotary(m, value),
                    };
                    let span = tspan.to(vspan_of(&value));
                    return Some(ItemKind::Word(Word { addr, value, span }));
                }
                match names::r_number(&name) {
                    Some(d) if indices.is_empty() => self.r_param(d, tspan),
                    _ => VarRef { kind: VarKind::Named { name, indices }, span: tspan },
                }
            }
        };
        if let Some(pos) = ac_ic {
            let what = match pos {
                Pos::Rotary(m) => format!("{}(…) only applies", m.name()),
                _ => "AC(…)/IC(…) only apply".to_string(),
            };
            self.error(
                Diagnostic::error("NC125", format!("{what} to address words"))
                    .primary(self.file(), value.span, "not an address")
                    .hint("assign the plain value to the variable; use AC/IC on axis words like `X=IC(5)`"),
            );
        }
        Some(ItemKind::Assign { target: Box::new(var), value })
    }

    /// The value after `=`: an expression, or `AC(e)` / `IC(e)` / a rotary `ACP(e)` ….
    fn word_value(&mut self, p: Pair<'_, Rule>) -> (Expr, Option<Pos>) {
        if p.as_rule() == Rule::ac_ic {
            let span = self.span(&p);
            let mut it = p.into_inner();
            let kw = it.next().map(|k| k.as_str().to_ascii_uppercase()).unwrap_or_default();
            let ac = match kw.as_str() {
                "AC" => Pos::Ac,
                "IC" => Pos::Ic,
                other => Pos::Rotary(RotaryMode::from_name(other).unwrap_or(RotaryMode::Dc)),
            };
            let e = match it.find(|q| q.as_rule() == Rule::expr) {
                Some(e) => self.expr(e),
                None => Expr::num(0.0, false, span),
            };
            return (Expr { span, ..e }, Some(ac));
        }
        (self.expr(p), None)
    }

    pub fn r_param(&mut self, digits: &str, span: Span) -> VarRef {
        let n = digits.parse::<u32>().unwrap_or(u32::MAX);
        if n >= self.st.r_count {
            let last = self.st.r_count.saturating_sub(1);
            self.error(
                Diagnostic::error("NC208", format!("R parameter R{digits} does not exist"))
                    .primary(self.file(), span, format!("the control has R0 to R{last}"))
                    .note("the number of R parameters is machine data MD28050 (828D default 300)")
                    .hint(format!("use an R parameter from R0 to R{last}, or a DEF variable")),
            );
        }
        VarRef { kind: VarKind::R(n), span }
    }

    fn goto(&mut self, p: Pair<'_, Rule>) -> Goto {
        let mut it = p.into_inner();
        let kw = it.next().map(|k| k.as_str().to_ascii_uppercase()).unwrap_or_default();
        let (search, missing_continues) = match kw.as_str() {
            "GOTOF" => (Search::Forward, false),
            "GOTOB" => (Search::Backward, false),
            "GOTOC" => (Search::ForwardThenBackward, true),
            _ => (Search::ForwardThenBackward, false),
        };
        let target = match it.next() {
            Some(t) if t.as_rule() == Rule::target_number => {
                let span = self.span(&t);
                let value = t.as_str().trim_start_matches(['N', 'n']).parse::<u32>().unwrap_or(u32::MAX);
                Target::Number(SeqNo { value, span })
            }
            Some(t) => {
                let span = self.span(&t);
                let name = t.as_str().to_ascii_uppercase();
                if matches!(self.st.declared.get(&name), Some(DataType::String(_))) {
                    // A STRING variable holding the label name.
                    let v = VarRef { kind: VarKind::Named { name, indices: vec![] }, span };
                    Target::Computed(Expr::new(ExprKind::Var(Box::new(v)), span))
                } else {
                    Target::Label(Label { name, span })
                }
            }
            None => Target::Label(Label { name: String::new(), span: self.whole }),
        };
        Goto { search, target, cond: None, missing_continues }
    }

    fn repeat_section(&mut self, pairs: Vec<Pair<'_, Rule>>) -> Option<ItemKind> {
        let single = pairs.first().is_some_and(|k| k.as_rule() == Rule::kw_repeatb);
        let mut labels = Vec::new();
        let mut count = None;
        for p in pairs.into_iter().skip(1) {
            match p.as_rule() {
                Rule::label_ref => labels.push(Label { name: p.as_str().to_ascii_uppercase(), span: self.span(&p) }),
                Rule::p_count => {
                    let inner = p.into_inner().find(|q| matches!(q.as_rule(), Rule::expr | Rule::word_const))?;
                    count = Some(if inner.as_rule() == Rule::expr {
                        self.expr(inner)
                    } else {
                        let s = inner.as_span();
                        let vspan = self.norm.span(s.start() + 1, s.end());
                        let (v, point) = self.number_text(&inner.as_str()[1..], vspan)?;
                        Expr::num(v, point, vspan)
                    });
                }
                _ => {}
            }
        }
        let mut labels = labels.into_iter();
        let start = labels.next()?;
        Some(ItemKind::RepeatSection(Box::new(RepeatSection { start, end: labels.next(), count, single })))
    }

    fn case(&mut self, pairs: Vec<Pair<'_, Rule>>) -> Option<ItemKind> {
        let mut selector = None;
        let mut arms = Vec::new();
        let mut default = None;
        for p in pairs {
            match p.as_rule() {
                Rule::expr => selector = Some(self.expr(p)),
                Rule::case_arm => {
                    let mut it = p.into_inner();
                    let v = it.next()?;
                    let value = self.case_value(v)?;
                    let goto = self.goto(it.next()?);
                    arms.push(CaseArm { value, goto });
                }
                Rule::case_default => {
                    let g = p.into_inner().find(|q| q.as_rule() == Rule::goto_stmt)?;
                    default = Some(self.goto(g));
                }
                _ => {}
            }
        }
        Some(ItemKind::Case(Box::new(Case { selector: selector?, arms, default })))
    }

    fn case_value(&mut self, p: Pair<'_, Rule>) -> Option<Expr> {
        let span = self.span(&p);
        let mut neg = false;
        let mut out = None;
        for q in p.into_inner() {
            match q.as_rule() {
                Rule::op_neg => neg = true,
                Rule::op_plus => {}
                _ => out = Some(self.operand(q)),
            }
        }
        let mut e = out?;
        if neg {
            if let ExprKind::Num(n) = &mut e.kind {
                n.value = -n.value;
            } else {
                e = Expr::new(ExprKind::Unary(UnOp::Neg, Box::new(e)), span);
            }
        }
        e.span = span;
        Some(e)
    }
}

fn p_text(span: &Span, norm: &Normalised<'_>) -> String {
    // The call as written, for the hint; spans are file offsets, the normalised text starts at `norm.start`.
    let lo = span.lo.saturating_sub(norm.start) as usize;
    let hi = span.hi.saturating_sub(norm.start) as usize;
    norm.text.get(lo..hi).unwrap_or("…").to_string()
}

fn letters_of(name: &str) -> usize {
    name.bytes().take_while(u8::is_ascii_alphabetic).count()
}

fn is_numbered(name: &str) -> bool {
    let letters = name.bytes().take_while(u8::is_ascii_alphabetic).count();
    letters < name.len() && name.bytes().skip(letters).all(|c| c.is_ascii_digit())
}

fn vspan_of(v: &WordValue) -> Span {
    match v {
        WordValue::Expr(e) | WordValue::Ac(e) | WordValue::Ic(e) | WordValue::Rotary(_, e) => e.span,
    }
}

/// The positioning function written around a word's value.
#[derive(Clone, Copy)]
enum Pos {
    Ac,
    Ic,
    Rotary(RotaryMode),
}

fn call_named(name: String, args: Vec<Arg>) -> ItemKind {
    ItemKind::Call(Box::new(Call { kind: CallKind::Named, target: CallTarget::Name(name), args, repeat: None }))
}

/// Parses `[+-]digits[.digits][EX[+-]digits]` (the exponent makes it count as having a point).
pub fn parse_number(t: &str) -> Option<(f64, bool)> {
    let (mant, exp) = match t.find(['E', 'e']) {
        Some(i) => (&t[..i], Some(&t[i + 2..])),
        None => (t, None),
    };
    let point = mant.contains('.') || exp.is_some();
    let v: f64 = match exp {
        Some(e) => format!("{mant}e{e}").parse().ok()?,
        None => mant.parse().ok()?,
    };
    v.is_finite().then_some((v, point))
}

/// The item for a letter-constant word: `L123` is a call, `M17` a return, `M2`/`M30` the end;
/// everything else a plain word. Shared with the fast path so both give the same IR.
#[inline(always)]
pub fn word_item(letter: u8, text: &str, value: f64, point: bool, span: Span, vspan: Span) -> ItemKind {
    if letter == b'L' && !point && !text.starts_with(['+', '-']) {
        return ItemKind::Call(Box::new(Call {
            kind: CallKind::LNumber,
            target: CallTarget::Name(format!("L{text}")),
            args: Vec::new(),
            repeat: None,
        }));
    }
    special_word(Word { addr: Addr::Letter(letter), value: WordValue::Expr(Expr::num(value, point, vspan)), span })
}

/// `M17` → return, `M2`/`M30` → end of program (also written `M=30`); other words stay words.
#[inline(always)]
fn special_word(w: Word) -> ItemKind {
    if w.addr.is(b'M') {
        if let WordValue::Expr(Expr { kind: ExprKind::Num(Number { value, point: false }), .. }) = &w.value {
            match *value as i64 {
                17 if *value == 17.0 => return ItemKind::Return { to: None },
                2 if *value == 2.0 => return ItemKind::End { code: EndCode::M2 },
                30 if *value == 30.0 => return ItemKind::End { code: EndCode::M30 },
                _ => {}
            }
        }
    }
    ItemKind::Word(w)
}

/// `SETINT(n) PRIO=p NAME [LIFTFAST] [BLSYNC]`, `ENABLE(n)`, `DISABLE(n)`, `CLRINT(n)`: the
/// interrupt instructions, read as one instruction each with their text (the grammar sees a
/// call, an assignment and a call). The evaluator and the translations name them.
fn interrupt(items: Vec<Item>, raw: &[String]) -> Vec<Item> {
    let is_int = |it: &Item| match &it.kind {
        ItemKind::Call(c) => matches!(&c.target, CallTarget::Name(n)
            if matches!(n.as_str(), "SETINT" | "ENABLE" | "DISABLE" | "CLRINT") && !c.args.is_empty()),
        _ => false,
    };
    let Some(first) = items.iter().position(is_int) else { return items };
    let setint = matches!(&items[first].kind, ItemKind::Call(c) if c.target == CallTarget::Name("SETINT".into()));
    // SETINT takes the rest of the block; the others stand alone.
    let last = if setint { items.len() - 1 } else { first };
    let name = raw[first..=last].join(" ").to_ascii_uppercase();
    let span = items[first].span.to(items[last].span);
    let mut out = Vec::with_capacity(items.len());
    for (i, item) in items.into_iter().enumerate() {
        if i == first {
            out.push(Item { kind: ItemKind::Instruction { name: name.clone() }, span });
        } else if i < first || i > last {
            out.push(item);
        }
    }
    out
}
