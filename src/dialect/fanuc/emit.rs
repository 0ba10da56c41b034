//! The FANUC Custom Macro B writer: FANUC-shaped IR (as left by the lowering passes) → text.
//!
//! `%`, `O####`, one statement per block, upper case, expressions bracketed so that FANUC's
//! precedence (functions; `* / AND MOD`; `+ - OR XOR`) gives the IR's tree, a decimal point on
//! every dimensional value and every constant in an expression, integers on integer-only
//! addresses (G M S T H D P L N), at most 8 digits per number, `( )` comments. [`depth`] and
//! [`cond_depth`] tell the passes how many bracket levels (FANUC allows 5) a value will take.

use crate::diag::{Diagnostic, Severity};
use crate::ir::*;
use crate::read::LineEnding;
use crate::span::FileId;

/// What to do with comment text (`--comments`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum CommentMode {
    /// Carry comments as they are (parentheses inside become brackets).
    #[default]
    Keep,
    /// Transliterate to ASCII (accents dropped, other characters `?`).
    Ascii,
    /// Drop source comments (messages, the header and unsupported markers stay).
    Drop,
}

#[derive(Clone, Debug)]
pub struct EmitOptions {
    pub comments: CommentMode,
    pub line_ending: LineEnding,
    /// File the IR spans point into (for diagnostics).
    pub file: FileId,
}

impl Default for EmitOptions {
    fn default() -> Self {
        EmitOptions { comments: CommentMode::Keep, line_ending: LineEnding::Lf, file: 0 }
    }
}

/// The text and any problems met while writing it.
#[derive(Clone, Debug, Default)]
pub struct Emitted {
    pub text: String,
    pub diags: Vec<Diagnostic>,
}

/// Comments whose text starts with this are written even with `--comments drop`.
pub const KEEP_PREFIX: &str = "NCTRANS";

const MAX_DIGITS: usize = 8;

/// Writes every program of `unit` as one FANUC file.
pub fn emit(unit: &Unit, opts: &EmitOptions) -> Emitted {
    let mut w = Writer { opts, lines: vec!["%".to_string()], diags: vec![], mode_q: false, cycle_k: false };
    for p in &unit.programs {
        w.program(p);
    }
    w.lines.push("%".into());
    let eol = opts.line_ending.as_str();
    let mut text = w.lines.join(eol);
    text.push_str(eol);
    Emitted { text, diags: w.diags }
}

/// Writes statements alone, without `%` and `O` line (a streamed translation writes a
/// program's body block by block; this is its way for blocks its fast path declines).
pub fn emit_body(body: &[Stmt], opts: &EmitOptions) -> Emitted {
    let mut w = Writer { opts, lines: vec![], diags: vec![], mode_q: false, cycle_k: false };
    w.body(body);
    let eol = opts.line_ending.as_str();
    let mut text = w.lines.join(eol);
    if !text.is_empty() {
        text.push_str(eol);
    }
    Emitted { text, diags: w.diags }
}

struct Writer<'a> {
    opts: &'a EmitOptions,
    lines: Vec<String>,
    diags: Vec<Diagnostic>,
    /// The block being written is `G05.1 Q…`: its Q is a mode number, written without a
    /// decimal point (a point there is alarm PS0007 on the controls that check it).
    mode_q: bool,
    /// The block being written is a canned cycle's (G73–G89): its K is the repeat count.
    cycle_k: bool,
}

impl Writer<'_> {
    fn program(&mut self, p: &Program) {
        let mut line = match &p.name {
            Some(ProgName::Number(n)) => format!("O{n:04}"),
            _ => {
                self.bug(p.span, "a program without an O number");
                "O0001".into()
            }
        };
        if let Some(h) = &p.head {
            self.comments(&mut line, &h.comments);
        }
        self.lines.push(line);
        self.body(&p.body);
    }

    fn body(&mut self, body: &[Stmt]) {
        for s in body {
            match &s.kind {
                StmtKind::Block(b) => {
                    self.mode_q = b.items.iter().any(is_g5_1);
                    self.cycle_k = b.items.iter().any(is_cycle_g);
                    let items: Vec<String> = b.items.iter().map(|i| self.item(i)).collect();
                    (self.mode_q, self.cycle_k) = (false, false);
                    self.line(&b.meta, items.join(" "));
                }
                StmtKind::Do(d) => {
                    let head = match &d.cond {
                        Some(c) => format!("WHILE {} DO{}", self.cond(c), d.id),
                        None => format!("DO{}", d.id),
                    };
                    self.line(&d.head, head);
                    self.body(&d.body);
                    self.line(&d.end, format!("END{}", d.id));
                }
                _ => self.bug(s.span, "a Siemens control structure"),
            }
        }
    }

    fn line(&mut self, m: &BlockMeta, code: String) {
        let mut parts: Vec<String> = Vec::new();
        match m.skip {
            Some(0) => parts.push("/".into()),
            Some(k) => parts.push(format!("/{k}")),
            None => {}
        }
        if let Some(n) = &m.number {
            parts.push(format!("N{}", n.value));
        }
        if !code.is_empty() {
            parts.push(code);
        }
        let mut line = parts.join(" ");
        self.comments(&mut line, &m.comments);
        if !line.is_empty() && line != "/" {
            self.lines.push(line);
        }
    }

    fn comments(&self, line: &mut String, comments: &[Comment]) {
        for c in comments {
            let keep = c.text.starts_with(KEEP_PREFIX) || c.text.starts_with("*** NCTRANS");
            if self.opts.comments == CommentMode::Drop && !keep {
                continue;
            }
            if !line.is_empty() {
                line.push(' ');
            }
            line.push('(');
            line.push_str(&comment_text(&c.text, self.opts.comments));
            line.push(')');
        }
    }

    fn bug(&mut self, span: crate::span::Span, what: &str) {
        let d = Diagnostic::error("NC399", format!("internal: {what} reached the FANUC writer"))
            .primary(self.opts.file, span, "not lowered")
            .note("this is a bug in nctrans; please report it with the input program");
        self.diags.push(d);
    }

    fn item(&mut self, it: &Item) -> String {
        match &it.kind {
            ItemKind::Assign { target, value } => format!("{}={}", self.var(target), self.expr(value)),
            ItemKind::Word(w) => self.word(w),
            ItemKind::Goto(g) => {
                let n = match &g.target {
                    Target::Number(n) => n.value.to_string(),
                    Target::Computed(e) => self.word_value(e),
                    Target::Label(l) => {
                        self.bug(l.span, "a label jump");
                        l.name.clone()
                    }
                };
                match &g.cond {
                    Some(c) => format!("IF {} GOTO {n}", self.cond(c)),
                    None => format!("GOTO {n}"),
                }
            }
            ItemKind::IfThen { cond, then } => format!("IF {} THEN {}", self.cond(cond), self.item(then)),
            ItemKind::IfBlock { cond, items } => {
                let words: Vec<String> = items.iter().map(|i| self.item(i)).collect();
                format!("IF {} {}", self.cond(cond), words.join(" ")).trim_end().to_string()
            }
            ItemKind::Call(c) => {
                let code = match c.kind {
                    CallKind::G65 => "G65",
                    CallKind::G66 => "G66",
                    CallKind::M98 => "M98",
                    CallKind::M97 => "M97",
                    _ => {
                        self.bug(it.span, "a Siemens call");
                        "G65"
                    }
                };
                let mut s = code.to_string();
                match &c.target {
                    CallTarget::Number(n) => s.push_str(&format!(" P{n}")),
                    CallTarget::Computed(e) => s.push_str(&format!(" P{}", self.word_value(e))),
                    CallTarget::Name(n) => {
                        self.bug(it.span, "a call by name");
                        s.push_str(&format!(" P{n}"));
                    }
                }
                if let Some(r) = &c.repeat {
                    s.push_str(&format!(" L{}", self.int_value(r)));
                }
                for a in &c.args {
                    if let Arg::Letter { letter, value, .. } = a {
                        s.push_str(&format!(" {}{}", *letter as char, self.dim_value(value)));
                    }
                }
                s
            }
            ItemKind::ModalCallOff => "G67".into(),
            ItemKind::Return { to: None } => "M99".into(),
            ItemKind::Return { to: Some(e) } => format!("M99 P{}", self.int_value(e)),
            ItemKind::End { code: EndCode::M30 } => "M30".into(),
            ItemKind::End { code: EndCode::M2 } => "M02".into(),
            ItemKind::Alarm { number, text, .. } => {
                format!("#3000={}{}", self.int_value(number), self.msg(text.as_deref()))
            }
            ItemKind::StopMessage { text } => format!("#3006=1{}", self.msg(text.as_deref())),
            ItemKind::ParamWrite(p) => {
                let mut s = format!("N{}", self.int_value(&p.number));
                if let Some(a) = &p.axis {
                    s.push_str(&format!(" P{}", self.int_value(a)));
                }
                if let Some(b) = &p.bit {
                    s.push_str(&format!(" Q{}", self.int_value(b)));
                }
                s.push_str(&format!(" R{}", self.int_value(&p.value)));
                s
            }
            ItemKind::Print(p) if p.file.is_none() => {
                let mut s = String::from("DPRNT[");
                for part in &p.parts {
                    match part {
                        PrintPart::Text(t) => s.extend(t.chars().map(|c| if c == ' ' { '*' } else { c })),
                        _ => self.bug(it.span, "a DPRNT of text alone"),
                    }
                }
                s.push(']');
                s
            }
            // `POPEN` / `PCLOS` around a translated WRITE.
            ItemKind::Instruction { name } if name == "POPEN" || name == "PCLOS" => name.clone(),
            _ => {
                self.bug(it.span, "a Siemens-only statement");
                String::new()
            }
        }
    }

    fn msg(&self, text: Option<&str>) -> String {
        match text {
            Some(t) if self.opts.comments != CommentMode::Drop || !t.is_empty() => {
                let mode = if self.opts.comments == CommentMode::Drop { CommentMode::Keep } else { self.opts.comments };
                format!("({})", comment_text(t, mode))
            }
            _ => String::new(),
        }
    }

    fn word(&mut self, w: &Word) -> String {
        // Chamfering and corner R: the IR's names of the two meanings (`dialect::fanuc::parse`).
        let letter = match w.addr.as_str() {
            "CHR" => ",C".to_string(),
            "RND" => ",R".to_string(),
            a => a.to_string(),
        };
        let e = match &w.value {
            WordValue::Expr(e) => e,
            WordValue::Ac(e) | WordValue::Ic(e) | WordValue::Rotary(_, e) => {
                self.bug(w.span, "AC()/IC()/ACP()");
                e
            }
        };
        let int_addr =
            matches!(w.addr, Addr::Letter(b'G' | b'M' | b'S' | b'T' | b'H' | b'D' | b'P' | b'L' | b'N' | b'O'))
                || (self.mode_q && w.addr.is(b'Q'))
                || (self.cycle_k && w.addr.is(b'K'));
        if let (Addr::Letter(l @ (b'G' | b'M')), ExprKind::Num(n)) = (&w.addr, &e.kind) {
            if n.value >= 0.0 && n.value < 10.0 && n.value.fract() == 0.0 {
                return format!("{}0{}", *l as char, n.value as u32);
            }
            if *l == b'G' && n.value >= 0.0 {
                // G54.1 and the like keep their subcode; G05.1 its leading zero.
                let zero = if n.value < 10.0 { "0" } else { "" };
                return format!("G{zero}{}", fmt_num(n.value, false).0);
            }
        }
        let v = if int_addr { self.int_value(e) } else { self.dim_value(e) };
        format!("{letter}{v}")
    }

    /// A value in an integer-only address: an integer, a variable or `[expr]`.
    fn int_value(&mut self, e: &Expr) -> String {
        match &e.kind {
            ExprKind::Num(n) if n.value.fract() == 0.0 => fmt_num(n.value, false).0,
            _ => self.word_value(e),
        }
    }

    /// A dimensional value: a constant always with a decimal point.
    fn dim_value(&mut self, e: &Expr) -> String {
        self.word_value(e)
    }

    fn word_value(&mut self, e: &Expr) -> String {
        match &e.kind {
            ExprKind::Num(_) | ExprKind::Var(_) | ExprKind::Vacant => self.expr(e),
            ExprKind::Unary(UnOp::Neg, x) if matches!(x.kind, ExprKind::Var(_)) => self.expr(e),
            _ => format!("[{}]", self.expr(e)),
        }
    }

    fn var(&mut self, v: &VarRef) -> String {
        match &v.kind {
            VarKind::Hash(n) => format!("#{n}"),
            VarKind::HashIndirect(e) => format!("#[{}]", self.expr(e)),
            _ => {
                self.bug(v.span, "an unmapped variable");
                "#0".into()
            }
        }
    }

    fn number(&mut self, v: f64, e: &Expr) -> String {
        let (s, exact) = fmt_num(v, true);
        if !exact {
            let d = Diagnostic::new(Severity::Warning, "NC350", format!("{v} written as {s}"))
                .primary(self.opts.file, e.span, "more than 8 digits")
                .note("FANUC accepts at most 8 digits in a number; the value was rounded");
            self.diags.push(d);
        }
        s
    }

    fn expr(&mut self, e: &Expr) -> String {
        match &e.kind {
            ExprKind::Num(n) => self.number(n.value, e),
            ExprKind::Vacant => "#0".into(),
            ExprKind::Var(v) => self.var(v),
            ExprKind::Unary(UnOp::Neg, x) => match &x.kind {
                ExprKind::Var(_) => format!("-{}", self.expr(x)),
                ExprKind::Num(n) => self.number(-n.value, x),
                _ => format!("-[{}]", self.expr(x)),
            },
            ExprKind::Binary(op, a, b) if is_logical_op(*op) => {
                let _ = (a, b);
                self.cond(e)
            }
            ExprKind::Binary(op, a, b) => {
                let l = self.operand(*op, a, false);
                let r = self.operand(*op, b, true);
                let sym = match op {
                    BinOp::Add => "+",
                    BinOp::Sub => "-",
                    BinOp::Mul => "*",
                    BinOp::Div => "/",
                    BinOp::FanucBitAnd => " AND ",
                    BinOp::FanucBitOr => " OR ",
                    BinOp::FanucBitXor => " XOR ",
                    BinOp::Mod => " MOD ",
                    _ => {
                        self.bug(e.span, "a Siemens operator");
                        "?"
                    }
                };
                format!("{l}{sym}{r}")
            }
            ExprKind::Func(f, args) => {
                let a: Vec<String> = args.iter().map(|x| self.expr(x)).collect();
                match (f, a.as_slice()) {
                    (Func::FanucAtan2, [y, x]) => format!("ATAN[{y}]/[{x}]"),
                    (Func::Pow, [x, y]) => format!("POW[{x},{y}]"),
                    (_, [x]) => match func_name(*f) {
                        Some(name) => format!("{name}[{x}]"),
                        None => {
                            self.bug(e.span, "a Siemens function");
                            format!("{f:?}[{x}]").to_uppercase()
                        }
                    },
                    _ => {
                        self.bug(e.span, "a function with the wrong number of arguments");
                        "0".into()
                    }
                }
            }
            ExprKind::Cmp(..) => self.cond(e),
            ExprKind::Unary(..) | ExprKind::Str(_) | ExprKind::Ident(_) => {
                self.bug(e.span, "a Siemens value");
                "0".into()
            }
        }
    }

    fn operand(&mut self, op: BinOp, e: &Expr, right: bool) -> String {
        let s = self.expr(e);
        if operand_bracketed(op, e, right) {
            format!("[{s}]")
        } else {
            s
        }
    }

    /// A condition with its outer brackets: `[#1 GT 0.]`, `[[#1 GT 0.] AND [#2 LT 1.]]`.
    fn cond(&mut self, c: &Expr) -> String {
        format!("[{}]", self.cond_inner(c))
    }

    fn cond_inner(&mut self, c: &Expr) -> String {
        match &c.kind {
            ExprKind::Cmp(op, _, a, b) => {
                let o = match op {
                    CmpOp::Eq => "EQ",
                    CmpOp::Ne => "NE",
                    CmpOp::Gt => "GT",
                    CmpOp::Ge => "GE",
                    CmpOp::Lt => "LT",
                    CmpOp::Le => "LE",
                };
                format!("{} {o} {}", self.expr(a), self.expr(b))
            }
            ExprKind::Binary(op, a, b) if is_logical_op(*op) => {
                let o = match op {
                    BinOp::And => "AND",
                    BinOp::Or => "OR",
                    _ => "XOR",
                };
                format!("[{}] {o} [{}]", self.cond_inner(a), self.cond_inner(b))
            }
            _ => {
                self.bug(c.span, "a value used as a condition");
                self.expr(c)
            }
        }
    }
}

fn is_logical_op(op: BinOp) -> bool {
    matches!(op, BinOp::And | BinOp::Or | BinOp::Xor)
}

fn func_name(f: Func) -> Option<&'static str> {
    Some(match f {
        Func::Sin => "SIN",
        Func::Cos => "COS",
        Func::Tan => "TAN",
        Func::FanucAsin => "ASIN",
        Func::FanucAcos => "ACOS",
        Func::FanucAtan => "ATAN",
        Func::Sqrt => "SQRT",
        Func::Abs => "ABS",
        Func::FanucRound => "ROUND",
        Func::Trunc => "FIX",
        Func::FanucFup => "FUP",
        Func::Ln => "LN",
        Func::Exp => "EXP",
        Func::Bin => "BIN",
        Func::Bcd => "BCD",
        Func::Adp => "ADP",
        _ => return None,
    })
}

fn prec(op: BinOp) -> u8 {
    match op {
        BinOp::Mul | BinOp::Div | BinOp::Mod | BinOp::FanucBitAnd | BinOp::IntDiv | BinOp::BitAnd => 2,
        BinOp::And | BinOp::Or | BinOp::Xor => 0,
        _ => 1,
    }
}

fn bitwise(op: BinOp) -> bool {
    matches!(op, BinOp::FanucBitAnd | BinOp::FanucBitOr | BinOp::FanucBitXor | BinOp::Mod)
}

/// Whether the writer puts `[ ]` around operand `e` of `op` (`right`: the right operand).
/// Bitwise operators and MOD are always bracketed against other operators.
pub fn operand_bracketed(op: BinOp, e: &Expr, right: bool) -> bool {
    match &e.kind {
        ExprKind::Binary(cop, _, _) => {
            if bitwise(op) != bitwise(*cop) || (bitwise(op) && op != *cop) {
                return true;
            }
            let (pp, cp) = (prec(op), prec(*cop));
            cp < pp || (right && cp == pp)
        }
        ExprKind::Unary(UnOp::Neg, _) => right,
        ExprKind::Num(n) => right && n.value < 0.0,
        ExprKind::Func(Func::FanucAtan2, _) => true,
        _ => false,
    }
}

/// Bracket levels the written value takes (FANUC allows 5, functions' brackets included).
pub fn depth(e: &Expr) -> u32 {
    match &e.kind {
        ExprKind::Num(_) | ExprKind::Vacant | ExprKind::Str(_) | ExprKind::Ident(_) => 0,
        ExprKind::Var(v) => var_depth(v),
        ExprKind::Unary(_, x) => match x.kind {
            ExprKind::Var(_) | ExprKind::Num(_) => depth(x),
            _ => 1 + depth(x),
        },
        ExprKind::Binary(op, a, b) => {
            let da = depth(a) + operand_bracketed(*op, a, false) as u32;
            let db = depth(b) + operand_bracketed(*op, b, true) as u32;
            da.max(db)
        }
        ExprKind::Func(_, args) => 1 + args.iter().map(depth).max().unwrap_or(0),
        ExprKind::Cmp(_, _, a, b) => 1 + depth(a).max(depth(b)),
    }
}

fn var_depth(v: &VarRef) -> u32 {
    match &v.kind {
        VarKind::Hash(_) | VarKind::R(_) | VarKind::System { .. } => 0,
        VarKind::HashIndirect(e) | VarKind::RIndirect(e) => 1 + depth(e),
        VarKind::Named { indices, .. } if indices.is_empty() => 0,
        VarKind::Named { indices, .. } => 2 + indices.iter().map(depth).max().unwrap_or(0),
    }
}

/// Bracket levels of a condition written as `IF [..]` / `WHILE [..]`, outer brackets included.
pub fn cond_depth(c: &Expr) -> u32 {
    fn inner(c: &Expr) -> u32 {
        match &c.kind {
            ExprKind::Cmp(_, _, a, b) => depth(a).max(depth(b)),
            ExprKind::Binary(op, a, b) if is_logical_op(*op) => 1 + inner(a).max(inner(b)),
            _ => depth(c),
        }
    }
    1 + inner(c)
}

/// A `G05.1` word (AI contour control).
/// A drilling-cycle G code (G73, G74, G76, G81–G89).
fn is_cycle_g(it: &Item) -> bool {
    matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'G')
        && matches!(&w.value, WordValue::Expr(Expr { kind: ExprKind::Num(n), .. })
            if n.value.fract() == 0.0 && matches!(n.value as u32, 73 | 74 | 76 | 81..=89)))
}

fn is_g5_1(it: &Item) -> bool {
    matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'G')
        && matches!(&w.value, WordValue::Expr(Expr { kind: ExprKind::Num(n), .. }) if (n.value - 5.1).abs() < 1e-9))
}

/// A number as FANUC accepts it: shortest form, `point` adds `.` to integers, at most 8 digits
/// (rounded when longer; `false` in the second field then).
pub fn fmt_num(v: f64, point: bool) -> (String, bool) {
    let v = if v == 0.0 { 0.0 } else { v };
    let s = format!("{v}");
    let (int, frac) = s.trim_start_matches('-').split_once('.').unwrap_or((s.trim_start_matches('-'), ""));
    let int_digits = int.trim_start_matches('0').len();
    let (s, exact) = if int_digits + frac.len() > MAX_DIGITS && !frac.is_empty() {
        let decimals = MAX_DIGITS.saturating_sub(int_digits.max(if int_digits == 0 { 0 } else { 1 }));
        let r = format!("{v:.decimals$}");
        let r = if r.contains('.') { r.trim_end_matches('0').to_string() } else { r };
        (r, false)
    } else {
        (s, true)
    };
    let s = if s.ends_with('.') { s[..s.len() - 1].to_string() } else { s };
    let s = if s == "-0" { "0".to_string() } else { s };
    if point && !s.contains('.') {
        (format!("{s}."), exact)
    } else {
        (s, exact)
    }
}

/// Comment text FANUC can carry: no parentheses (they would end the comment), no `%` or `;`,
/// and per `mode`, ASCII only.
pub fn comment_text(t: &str, mode: CommentMode) -> String {
    t.chars()
        .map(|c| match c {
            '(' => "[".to_string(),
            ')' => "]".to_string(),
            '%' | ';' => " ".to_string(),
            c if c.is_control() => " ".to_string(),
            c if mode == CommentMode::Ascii && !c.is_ascii() => translit(c).to_string(),
            c => c.to_string(),
        })
        .collect()
}

/// ASCII for the common accented Latin letters; `?` for anything else.
fn translit(c: char) -> &'static str {
    const TABLE: &[(&str, &str)] = &[
        ("ÀÁÂÃÄÅĀĂĄ", "A"),
        ("àáâãäåāăą", "a"),
        ("ÇĆČ", "C"),
        ("çćč", "c"),
        ("ĎĐ", "D"),
        ("ďđ", "d"),
        ("ÈÉÊËĒĘĚ", "E"),
        ("èéêëēęě", "e"),
        ("ÌÍÎÏ", "I"),
        ("ìíîï", "i"),
        ("ŁĹĽ", "L"),
        ("łĺľ", "l"),
        ("ÑŃŇ", "N"),
        ("ñńň", "n"),
        ("ÒÓÔÕÖØŐ", "O"),
        ("òóôõöøő", "o"),
        ("ŔŘ", "R"),
        ("ŕř", "r"),
        ("ŚŠŞ", "S"),
        ("śšş", "s"),
        ("ŤŢ", "T"),
        ("ťţ", "t"),
        ("ÙÚÛÜŮŰ", "U"),
        ("ùúûüůű", "u"),
        ("ÝŸ", "Y"),
        ("ýÿ", "y"),
        ("ŹŻŽ", "Z"),
        ("źżž", "z"),
        ("ß", "ss"),
        ("Ææ", "AE"),
        ("°", "DEG"),
        ("Ø", "D"),
    ];
    TABLE.iter().find(|(set, _)| set.contains(c)).map_or("?", |(_, a)| a)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lower::build::*;
    use crate::lower::{bin, cmp, func, item};

    fn prog(body: Vec<Stmt>) -> Unit {
        let mut p = program(body);
        p.name = Some(ProgName::Number(1));
        Unit { dialect: crate::dialect::Dialect::Fanuc, file: 0, programs: vec![p] }
    }

    fn text(body: Vec<Stmt>) -> String {
        let e = emit(&prog(body), &EmitOptions::default());
        assert!(e.diags.is_empty(), "{:?}", e.diags);
        e.text
    }

    #[test]
    fn numbers_keep_points_and_eight_digits() {
        assert_eq!(fmt_num(10.0, true), ("10.".into(), true));
        assert_eq!(fmt_num(-0.5, true), ("-0.5".into(), true));
        assert_eq!(fmt_num(0.000001, true), ("0.000001".into(), true));
        assert_eq!(fmt_num(57.295779513, true), ("57.29578".into(), false));
        assert_eq!(fmt_num(3.0, false), ("3".into(), true));
    }

    #[test]
    fn words_and_assignments() {
        let body = vec![
            block(vec![assign(hv(501), bin(BinOp::Add, h(501), bin(BinOp::Mul, h(502), n(2.0))))]),
            block(vec![
                word_item(b'G', n(1.0)),
                word_item(b'X', h(501)),
                word_item(b'Y', n(10.0)),
                word_item(b'F', n(300.0)),
            ]),
            block(vec![
                word_item(b'M', n(3.0)),
                word_item(b'S', n(1000.0)),
                word_item(b'Z', bin(BinOp::Sub, h(1), n(1.5))),
            ]),
        ];
        assert_eq!(text(body), "%\nO0001\n#501=#501+#502*2.\nG01 X#501 Y10. F300.\nM03 S1000 Z[#1-1.5]\n%\n");
    }

    #[test]
    fn brackets_keep_the_tree() {
        let e = bin(BinOp::Sub, h(1), bin(BinOp::Sub, h(2), h(3)));
        let f = bin(BinOp::Mul, bin(BinOp::Add, h(1), h(2)), func(Func::Sin, vec![h(3)], sp()));
        let g = bin(BinOp::Add, bin(BinOp::FanucBitAnd, h(1), n(8.0)), h(2));
        let body = vec![block(vec![assign(hv(4), e)]), block(vec![assign(hv(5), f)]), block(vec![assign(hv(6), g)])];
        assert_eq!(text(body), "%\nO0001\n#4=#1-[#2-#3]\n#5=[#1+#2]*SIN[#3]\n#6=[#1 AND 8.]+#2\n%\n");
    }

    #[test]
    fn conditions_jumps_and_loops() {
        let c = cmp(CmpOp::Gt, h(1), n(0.0));
        let goto = Goto {
            search: Search::ForwardThenWrap,
            target: Target::Number(SeqNo { value: 1000, span: sp() }),
            cond: Some(c.clone()),
            missing_continues: false,
        };
        let and = bin(BinOp::And, c.clone(), cmp(CmpOp::Lt, h(2), n(5.0)));
        let d = DoStmt {
            head: BlockMeta::default(),
            id: 1,
            cond: Some(and),
            body: vec![block(vec![item(ItemKind::IfThen { cond: c, then: Box::new(assign(hv(3), n(1.0))) }, sp())])],
            end: BlockMeta::default(),
        };
        let body = vec![
            block(vec![item(ItemKind::Goto(Box::new(goto)), sp())]),
            Stmt { kind: StmtKind::Do(Box::new(d)), span: sp() },
        ];
        assert_eq!(
            text(body),
            "%\nO0001\nIF [#1 GT 0.] GOTO 1000\nWHILE [[#1 GT 0.] AND [#2 LT 5.]] DO1\nIF [#1 GT 0.] THEN #3=1.\nEND1\n%\n"
        );
    }

    #[test]
    fn calls_messages_and_comments() {
        let call = Call {
            kind: CallKind::G65,
            target: CallTarget::Number(9000),
            args: vec![
                Arg::Letter { letter: b'A', var: 1, value: n(1.0) },
                Arg::Letter { letter: b'B', var: 2, value: h(501) },
            ],
            repeat: None,
        };
        let mut b = block(vec![item(ItemKind::Call(Box::new(call)), sp())]);
        if let StmtKind::Block(bl) = &mut b.kind {
            bl.meta.comments.push(Comment { text: "Tiefe (mm); Ä".into(), span: sp() });
        }
        let body = vec![
            b,
            block(vec![item(ItemKind::StopMessage { text: Some("CHECK".into()) }, sp())]),
            block(vec![ret_item()]),
        ];
        assert_eq!(text(body.clone()), "%\nO0001\nG65 P9000 A1. B#501 (Tiefe [mm]  Ä)\n#3006=1(CHECK)\nM99\n%\n");
        let opts = EmitOptions { comments: CommentMode::Ascii, ..EmitOptions::default() };
        assert!(emit(&prog(body.clone()), &opts).text.contains("(Tiefe [mm]  A)"));
        let opts = EmitOptions { comments: CommentMode::Drop, line_ending: LineEnding::CrLf, file: 0 };
        assert_eq!(
            emit(&prog(body), &opts).text,
            "%\r\nO0001\r\nG65 P9000 A1. B#501\r\n#3006=1(CHECK)\r\nM99\r\n%\r\n"
        );
    }

    #[test]
    fn depth_counts_function_and_index_brackets() {
        let e = func(Func::Sin, vec![bin(BinOp::Mul, bin(BinOp::Add, h(1), h(2)), n(2.0))], sp());
        assert_eq!(depth(&e), 2);
        assert_eq!(cond_depth(&cmp(CmpOp::Eq, e, n(0.0))), 3);
    }
}
