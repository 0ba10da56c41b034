//! The pest grammar (grammar/fanuc.pest) applied to one block, and the walk from its pairs to
//! the block's parts: words, macro statements and comments, with spans into the file.
//! A grammar failure becomes one diagnostic that says in words what was expected.

use super::expr::{self, ExprCx};
use super::names;
use crate::diag::Diagnostic;
use crate::dialect::ParseOptions;
use crate::ir::{Comment, Expr, ExprKind, Number, SeqNo, Target, VarRef};
use crate::read::Normalised;
use crate::span::{FileId, Span};
use pest::iterators::Pair;
use pest::Parser;

#[derive(pest_derive::Parser)]
#[grammar = "../grammar/common.pest"]
#[grammar = "../grammar/fanuc.pest"]
pub struct FanucParser;

/// One block's text and the way back to file spans.
pub struct Seg<'a> {
    pub norm: &'a Normalised<'a>,
    /// Offset of `text` in `norm.text`.
    pub base: usize,
    pub text: &'a str,
    pub file: FileId,
}

impl Seg<'_> {
    /// File span of `text[lo..hi]`.
    #[inline]
    pub fn span(&self, lo: usize, hi: usize) -> Span {
        self.norm.span(self.base + lo, self.base + hi)
    }
}

/// A literal number as written after an address: its place in the block text.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lit {
    /// Digits (and point) only, without the sign: `text[lo..hi]`.
    pub lo: usize,
    pub hi: usize,
    pub point: bool,
    pub signed: bool,
}

/// An address word before its meaning is decided (`G65`, `M98`, `N`, … are words here).
#[derive(Clone, Debug, PartialEq)]
pub struct RawWord {
    /// Upper-case ASCII letter.
    pub letter: u8,
    pub value: Expr,
    pub span: Span,
    /// Set when the value is a plain literal (`X-10.`), not a variable or expression.
    pub lit: Option<Lit>,
}

impl RawWord {
    /// The value as a non-negative integer literal written without a point.
    pub fn int(&self) -> Option<u64> {
        match (self.lit, &self.value.kind) {
            (Some(l), ExprKind::Num(n)) if !l.point && !l.signed && n.value >= 0.0 => Some(n.value as u64),
            _ => None,
        }
    }

    /// Number of digits of an integer literal (`P0003` has 4).
    pub fn digits(&self) -> usize {
        self.lit.map_or(0, |l| l.hi - l.lo)
    }
}

/// What a block consists of, in written order.
#[derive(Clone, Debug, PartialEq)]
pub enum Part {
    Comment(Comment),
    /// ISO `:1234` program number.
    ColonProg {
        number: u64,
        span: Span,
    },
    Word(RawWord),
    /// `,C` (chamfer, `chamfer`) or `,R` (corner R) and its value.
    Corner {
        chamfer: bool,
        value: Expr,
        span: Span,
    },
    Assign {
        target: VarRef,
        value: Expr,
        span: Span,
    },
    Goto {
        target: Target,
        span: Span,
    },
    /// `IF[c]GOTO n` (`then` is a `Goto`), `IF[c]THEN #i=…` (`then` is an `Assign`), or the
    /// Haas `IF[c] <NC words>` (`then` is `None`: the block's words are conditional).
    If {
        cond: Expr,
        then: Option<Box<Part>>,
        span: Span,
    },
    While {
        cond: Expr,
        id: u64,
        id_span: Span,
        span: Span,
    },
    Do {
        id: u64,
        id_span: Span,
        span: Span,
    },
    End {
        id: u64,
        id_span: Span,
        span: Span,
    },
    /// `POPEN`, `DPRNT[…]`, `BPRNT[…]`, `PCLOS`: external data output, kept as written.
    DataOut {
        text: String,
        span: Span,
    },
}

/// A parsed block: optional skip and its parts.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Parts {
    /// `/` → 0, `/3` → 3.
    pub skip: Option<u8>,
    pub parts: Vec<Part>,
}

/// Parses one block with the grammar.
pub fn parse_block(seg: &Seg<'_>, opts: &ParseOptions) -> Result<Parts, Diagnostic> {
    let pairs = match FanucParser::parse(Rule::block, seg.text) {
        Ok(p) => p,
        Err(e) => return Err(grammar_error(seg, &e)),
    };
    let cx = ExprCx { seg, opts };
    let mut out = Parts::default();
    for block in pairs {
        for p in block.into_inner() {
            match p.as_rule() {
                Rule::skip => out.skip = Some(skip_level(p.as_str())),
                Rule::EOI => {}
                _ => out.parts.push(part(&cx, p)?),
            }
        }
    }
    Ok(out)
}

/// For tests: the parts the grammar gives for one line of text (no fast path).
pub fn parse_grammar_for_test(text: &str) -> Result<Parts, String> {
    with_seg(text, |seg, opts| parse_block(seg, opts).map_err(|d| d.message))
}

/// Runs `f` on a one-block segment of `text`, for tests of the two parsing paths.
pub(super) fn with_seg<R>(text: &str, f: impl FnOnce(&Seg<'_>, &ParseOptions) -> R) -> R {
    let raw = crate::read::RawBlock { text, start: 0, line: 1 };
    let norm = crate::read::normalise(&raw, crate::read::CommentStyle::Parens);
    let seg = Seg { norm: &norm, base: 0, text: &norm.text, file: 0 };
    let opts = ParseOptions::for_dialect(crate::dialect::Dialect::Fanuc);
    f(&seg, &opts)
}

pub fn skip_level(s: &str) -> u8 {
    s.as_bytes().get(1).filter(|c| c.is_ascii_digit()).map_or(0, |c| c - b'0')
}

fn span_of(seg: &Seg<'_>, p: &Pair<'_, Rule>) -> Span {
    let s = p.as_span();
    seg.span(s.start(), s.end())
}

fn part(cx: &ExprCx<'_, '_>, p: Pair<'_, Rule>) -> Result<Part, Diagnostic> {
    let seg = cx.seg;
    let span = span_of(seg, &p);
    match p.as_rule() {
        Rule::comment => {
            let text = p.into_inner().next().map_or(String::new(), |t| t.as_str().to_string());
            Ok(Part::Comment(Comment { text, span }))
        }
        Rule::colon_prog => {
            let n = p.into_inner().next();
            let number = n.map_or(Ok(0), |n| big_int(seg, &n))?;
            Ok(Part::ColonProg { number, span })
        }
        Rule::word => word(cx, p, span).map(Part::Word),
        Rule::corner => corner(cx, p, span),
        Rule::data_out => Ok(Part::DataOut { text: p.as_str().trim().to_ascii_uppercase(), span }),
        Rule::assign => assign(cx, p, span),
        Rule::goto_stmt => goto(cx, p, span),
        Rule::if_stmt => {
            let mut it = p.into_inner();
            let _kw = it.next();
            let cond = match it.next() {
                Some(b) => expr::condition(cx, b)?,
                None => return Err(internal(seg, span)),
            };
            let then = match it.next() {
                Some(t) if t.as_rule() == Rule::goto_stmt => {
                    let s = span_of(seg, &t);
                    Some(goto(cx, t, s)?)
                }
                Some(t) => {
                    // then_part: [THEN] [#i=…]
                    match t.into_inner().find(|a| a.as_rule() == Rule::assign) {
                        Some(a) => {
                            let s = span_of(seg, &a);
                            Some(assign(cx, a, s)?)
                        }
                        None => None,
                    }
                }
                None => None,
            };
            Ok(Part::If { cond, then: then.map(Box::new), span })
        }
        Rule::while_stmt => {
            let mut it = p.into_inner();
            let _kw = it.next();
            let cond = match it.next() {
                Some(b) => expr::condition(cx, b)?,
                None => return Err(internal(seg, span)),
            };
            let _do = it.next();
            let (id, id_span) = loop_id(seg, it.next(), span)?;
            Ok(Part::While { cond, id, id_span, span })
        }
        Rule::do_stmt | Rule::end_stmt => {
            let is_do = p.as_rule() == Rule::do_stmt;
            let mut it = p.into_inner();
            let _kw = it.next();
            let (id, id_span) = loop_id(seg, it.next(), span)?;
            Ok(if is_do { Part::Do { id, id_span, span } } else { Part::End { id, id_span, span } })
        }
        _ => Err(internal(seg, span)),
    }
}

fn internal(seg: &Seg<'_>, span: Span) -> Diagnostic {
    Diagnostic::error("NC199", "this block could not be read")
        .primary(seg.file, span, "here")
        .note("the grammar accepted the block but its parts were not as expected (a bug in nctrans)")
        .hint("please report this block")
}

fn loop_id(seg: &Seg<'_>, p: Option<Pair<'_, Rule>>, span: Span) -> Result<(u64, Span), Diagnostic> {
    let p = p.ok_or_else(|| internal(seg, span))?;
    let s = span_of(seg, &p);
    // Absurdly long numbers saturate; the structurer reports anything outside 1..3.
    let v = p.as_str().parse::<u64>().unwrap_or(u64::MAX);
    Ok((v, s))
}

fn big_int(seg: &Seg<'_>, p: &Pair<'_, Rule>) -> Result<u64, Diagnostic> {
    p.as_str().parse::<u64>().map_err(|_| {
        Diagnostic::error("NC180", "number too large")
            .primary(seg.file, span_of(seg, p), "too many digits")
            .hint("program, sequence and variable numbers have at most 8 digits")
    })
}

fn assign(cx: &ExprCx<'_, '_>, p: Pair<'_, Rule>, span: Span) -> Result<Part, Diagnostic> {
    let mut it = p.into_inner();
    let target = match it.next() {
        Some(v) => expr::variable_ref(cx, v)?,
        None => return Err(internal(cx.seg, span)),
    };
    let _eq = it.next();
    let value = match it.next() {
        Some(e) => expr::value(cx, e)?,
        None => return Err(internal(cx.seg, span)),
    };
    Ok(Part::Assign { target, value, span })
}

fn goto(cx: &ExprCx<'_, '_>, p: Pair<'_, Rule>, span: Span) -> Result<Part, Diagnostic> {
    let seg = cx.seg;
    let mut it = p.into_inner();
    let _kw = it.next();
    let t = it.next().ok_or_else(|| internal(seg, span))?;
    let tspan = span_of(seg, &t);
    let target = match t.as_rule() {
        Rule::unsigned => {
            let s = t.as_str();
            match s.parse::<u32>() {
                Ok(n) if (1..=99999).contains(&n) => Target::Number(SeqNo { value: n, span: tspan }),
                _ => {
                    return Err(Diagnostic::error("NC173", format!("`GOTO {s}`: a sequence number is 1 to 99999"))
                        .primary(seg.file, tspan, "not a sequence number")
                        .note("the target of GOTO is a whole number 1..99999 (alarm 128 otherwise)")
                        .hint("write the N number of the target block without a decimal point, e.g. `GOTO100`"))
                }
            }
        }
        _ => Target::Computed(expr::value(cx, t)?),
    };
    Ok(Part::Goto { target, span })
}

fn word(cx: &ExprCx<'_, '_>, p: Pair<'_, Rule>, span: Span) -> Result<RawWord, Diagnostic> {
    let mut it = p.into_inner();
    addressed(cx, &mut it, span)
}

/// `,C5.` / `,R8.`: the chamfer's leg or the corner radius, as the word the IR gives every
/// dialect (`CHR`, `RND`: the Siemens names of the same two meanings).
fn corner(cx: &ExprCx<'_, '_>, p: Pair<'_, Rule>, span: Span) -> Result<Part, Diagnostic> {
    let mut it = p.into_inner();
    let _comma = it.next();
    let w = addressed(cx, &mut it, span)?;
    Ok(Part::Corner { chamfer: w.letter == b'C', value: w.value, span })
}

/// The letter and value pairs of a word, from `it`.
fn addressed<'i>(
    cx: &ExprCx<'_, '_>,
    it: &mut impl Iterator<Item = Pair<'i, Rule>>,
    span: Span,
) -> Result<RawWord, Diagnostic> {
    let seg = cx.seg;
    let letter = it
        .next()
        .and_then(|l| l.as_str().bytes().next())
        .map(|b| b.to_ascii_uppercase())
        .ok_or_else(|| internal(seg, span))?;
    let value_pair = it.next().ok_or_else(|| internal(seg, span))?;
    let vspan = span_of(seg, &value_pair);
    let mut vit = value_pair.into_inner();
    let mut neg = None;
    let mut body = vit.next().ok_or_else(|| internal(seg, span))?;
    if body.as_rule() == Rule::sign {
        neg = Some(body.as_str() == "-");
        body = vit.next().ok_or_else(|| internal(seg, span))?;
    }
    if body.as_rule() == Rule::unsigned {
        let s = body.as_span();
        let (lo, hi) = (s.start(), s.end());
        let n = literal(body.as_str());
        let value = if neg == Some(true) { -n.value } else { n.value };
        return Ok(RawWord {
            letter,
            value: Expr::num(value, n.point, vspan),
            span,
            lit: Some(Lit { lo, hi, point: n.point, signed: neg.is_some() }),
        });
    }
    let bracketed = body.as_rule() == Rule::bracket;
    let mut inner = expr::value(cx, body)?;
    // `X[1]`: a bracketed constant is a computed value, read in units like `X1.` (a `[?]`
    // row of docs/semantics.md; Mitsubishi documents this rule, FANUC is believed to agree).
    // Marking the point keeps it apart from the increment-scaled `X1`.
    if let (true, ExprKind::Num(n)) = (bracketed, &mut inner.kind) {
        n.point = true;
    }
    let value = match neg {
        Some(true) => cx.bounded(Expr::new(ExprKind::Unary(crate::ir::UnOp::Neg, Box::new(inner)), vspan))?,
        _ => Expr { span: vspan, ..inner },
    };
    Ok(RawWord { letter, value, span, lit: None })
}

/// Reads a literal matched by `unsigned` (digits with an optional point).
pub fn literal(s: &str) -> Number {
    Number { value: crate::read::decimal(s).or_else(|| s.parse().ok()).unwrap_or(0.0), point: s.contains('.') }
}

/// Turns a pest failure into one diagnostic saying what was expected at the failing column.
fn grammar_error(seg: &Seg<'_>, e: &pest::error::Error<Rule>) -> Diagnostic {
    let pos = match e.location {
        pest::error::InputLocation::Pos(p) => p,
        pest::error::InputLocation::Span((p, _)) => p,
    }
    .min(seg.text.len());
    let expected: Vec<Rule> = match &e.variant {
        pest::error::ErrorVariant::ParsingError { positives, .. } => positives.clone(),
        pest::error::ErrorVariant::CustomError { .. } => vec![],
    };
    let found = seg.text[pos..].chars().next();
    let after_hash = seg.text[..pos].trim_end().ends_with('#');
    let mut words: Vec<&'static str> = Vec::new();
    // Between parts every block-level alternative is possible; say so in one phrase.
    if expected.contains(&Rule::EOI) {
        words.push("another address word, a macro statement or the end of the block");
    }
    let per_rule = if words.is_empty() { &expected[..] } else { &[] };
    for r in per_rule {
        let w = names::describe(*r, after_hash);
        if !words.contains(&w) {
            words.push(w);
        }
    }
    if words.is_empty() {
        words.push("an address word or a macro statement");
    }
    let what = join_or(&words);
    let found_text = match found {
        Some(c) => format!("`{c}`"),
        None => "the end of the block".to_string(),
    };
    let width = found.map_or(0, char::len_utf8);
    let in_brackets = seg.text[..pos].matches('[').count() > seg.text[..pos].matches(']').count();
    let outside = rel_op_outside(seg.text, pos, in_brackets);
    let message = match &outside {
        Some(op) => format!("comparison `{op}` outside brackets"),
        None => format!("expected {what}, found {found_text}"),
    };
    let (label, hint) = match outside {
        Some(op) => (
            format!("`{op}` outside brackets"),
            format!("a comparison is written in brackets and used only by IF/WHILE: `IF[#1 {op} 3]GOTO10`"),
        ),
        None => names::hint_for(found, &words, in_brackets),
    };
    Diagnostic::error("NC160", message).primary(seg.file, seg.span(pos, pos + width), label).hint(hint)
}

/// `#1=#2 EQ 3`: the grammar read `E` as an address; the real problem is the comparison.
fn rel_op_outside(text: &str, pos: usize, in_brackets: bool) -> Option<String> {
    if in_brackets || pos == 0 {
        return None;
    }
    let two = text.get(pos - 1..pos + 1)?.to_ascii_uppercase();
    ["EQ", "NE", "GT", "GE", "LT", "LE"].contains(&two.as_str()).then_some(two)
}

fn join_or(words: &[&str]) -> String {
    match words {
        [] => String::new(),
        [one] => one.to_string(),
        [init @ .., last] => format!("{} or {last}", init.join(", ")),
    }
}
