//! The Sinumerik writer: IR (as the FANUC→Sinumerik passes leave it) → part-program text.
//!
//! One statement per line, `PROC` line first in a subprogram, then the header comments and
//! the DEF block, then the body indented by structure. Expressions are parenthesised by
//! Siemens priorities (comparisons bind weakest, so any comparison inside another operator
//! gets parentheses), numbers are written in their shortest exact form (`EX` exponent for
//! very large or small ones). Deterministic: the same IR gives the same bytes.
//!
//! Besides the text, the writer returns for every output line the source span it came from
//! (the checker uses it to label a divergence in both files), and every IR node it could not
//! write in Siemens syntax (a pass bug, reported by the caller as NC370).

use crate::ir::*;
use crate::span::Span;

/// Written text and what it maps back to.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Emitted {
    /// LF line ends; the caller converts to the input's.
    pub text: String,
    /// Source span of every output line (`None` for generated header lines).
    pub lines: Vec<Option<Span>>,
    /// Constructs without Siemens spelling: where, and what.
    pub problems: Vec<(Span, String)>,
}

/// The parts of a Siemens program file beyond its body.
pub struct Frame<'a> {
    /// Comment lines (without `;`) written after the PROC line (or at the top of an MPF).
    pub header: &'a [String],
    /// DEF declarations: name and type, grouped by type in order of first appearance.
    pub defs: &'a [(String, DataType)],
    /// Write a `PROC` line (subprograms), even without parameters.
    pub proc_line: bool,
}

/// Writes one program.
pub fn emit_program(p: &Program, frame: &Frame) -> Emitted {
    let mut w = Writer { out: Emitted::default(), depth: 0, buf: String::new() };
    let name = match &p.name {
        Some(ProgName::Name(n)) => n.clone(),
        Some(ProgName::Number(n)) => format!("O_{n:04}"),
        None => "MAIN".into(),
    };
    if frame.proc_line || !p.params.is_empty() {
        let params: Vec<String> = p
            .params
            .iter()
            .map(|prm| format!("{}{} {}", if prm.by_ref { "VAR " } else { "" }, ty(prm.ty), prm.name))
            .collect();
        let save = if p.save { " SAVE" } else { "" };
        let line = if params.is_empty() {
            format!("PROC {name}{save}")
        } else {
            format!("PROC {name}({}){save}", params.join(", "))
        };
        w.line(line, p.head.as_ref().map(|h| h.span));
    }
    for h in frame.header {
        w.line(format!("; {h}"), None);
    }
    let mut groups: Vec<(DataType, Vec<&str>)> = Vec::new();
    for (n, t) in frame.defs {
        match groups.iter_mut().find(|(gt, _)| gt == t) {
            Some((_, v)) => v.push(n),
            None => groups.push((*t, vec![n])),
        }
    }
    for (t, names) in groups {
        // Keep DEF lines readable: at most 8 names each.
        for chunk in names.chunks(8) {
            w.line(format!("DEF {} {}", ty(t), chunk.join(", ")), None);
        }
    }
    w.body(&p.body);
    w.out
}

fn ty(t: DataType) -> String {
    match t {
        DataType::Int => "INT".into(),
        DataType::Real => "REAL".into(),
        DataType::Bool => "BOOL".into(),
        DataType::Char => "CHAR".into(),
        DataType::String(n) => format!("STRING[{n}]"),
        DataType::Axis => "AXIS".into(),
        DataType::Frame => "FRAME".into(),
    }
}

struct Writer {
    out: Emitted,
    depth: usize,
    /// The line being built (kept to reuse its allocation).
    buf: String,
}

impl Writer {
    fn line(&mut self, s: String, span: Option<Span>) {
        self.line_str(&s, span);
    }

    fn line_str(&mut self, s: &str, span: Option<Span>) {
        for _ in 0..self.depth {
            self.out.text.push_str("  ");
        }
        self.out.text.push_str(s.trim_end());
        self.out.text.push('\n');
        self.out.lines.push(span);
    }

    fn problem(&mut self, span: Span, what: &str) -> String {
        self.out.problems.push((span, what.to_string()));
        format!("; NCTRANS CANNOT WRITE: {what}")
    }

    fn body(&mut self, body: &[Stmt]) {
        for s in body {
            self.stmt(s);
        }
    }

    fn nested(&mut self, body: &[Stmt]) {
        self.depth += 1;
        self.body(body);
        self.depth -= 1;
    }

    fn stmt(&mut self, s: &Stmt) {
        match &s.kind {
            StmtKind::Block(b) => self.block(b),
            StmtKind::If(i) => {
                let c = cond(&i.cond);
                self.line(head(&i.head, &format!("IF {c}")), Some(i.head.span));
                self.nested(&i.then_body);
                if let Some(e) = &i.else_part {
                    self.line(head(&e.head, "ELSE"), Some(e.head.span));
                    self.nested(&e.body);
                }
                self.line(head(&i.end, "ENDIF"), Some(i.end.span));
            }
            StmtKind::While(wh) => {
                self.line(head(&wh.head, &format!("WHILE {}", cond(&wh.cond))), Some(wh.head.span));
                self.nested(&wh.body);
                self.line(head(&wh.end, "ENDWHILE"), Some(wh.end.span));
            }
            StmtKind::Loop(l) => {
                self.line(head(&l.head, "LOOP"), Some(l.head.span));
                self.nested(&l.body);
                self.line(head(&l.end, "ENDLOOP"), Some(l.end.span));
            }
            StmtKind::For(f) => {
                let text = format!("FOR {}={} TO {}", var(&f.var), expr(&f.from), expr(&f.to));
                self.line(head(&f.head, &text), Some(f.head.span));
                self.nested(&f.body);
                self.line(head(&f.end, "ENDFOR"), Some(f.end.span));
            }
            StmtKind::Repeat(r) => {
                self.line(head(&r.head, "REPEAT"), Some(r.head.span));
                self.nested(&r.body);
                self.line(head(&r.end, &format!("UNTIL {}", cond(&r.until))), Some(r.end.span));
            }
            StmtKind::Do(d) => {
                let t = self.problem(d.head.span, "a FANUC DO loop");
                self.line(t, Some(d.head.span));
            }
        }
    }

    /// One block: its parts (skip, N, label, items, comments) separated by a space. Built
    /// in one buffer, as plain CAM blocks are most of a large program.
    fn block(&mut self, b: &Block) {
        use std::fmt::Write;
        let mut s = std::mem::take(&mut self.buf);
        s.clear();
        let sep = |s: &mut String| {
            if !s.is_empty() {
                s.push(' ');
            }
        };
        if let Some(k) = b.meta.skip {
            s.push('/');
            if k != 0 {
                let _ = write!(s, "{k}");
            }
        }
        if let Some(n) = &b.meta.number {
            sep(&mut s);
            let _ = write!(s, "N{}", n.value);
        }
        if let Some(l) = &b.meta.label {
            sep(&mut s);
            let _ = write!(s, "{}:", l.name);
        }
        for it in &b.items {
            match &it.kind {
                ItemKind::Word(w) => {
                    sep(&mut s);
                    word_into(&mut s, w);
                }
                _ => {
                    let t = self.item(it);
                    if !t.is_empty() {
                        sep(&mut s);
                        s.push_str(&t);
                    }
                }
            }
        }
        for (i, c) in b.meta.comments.iter().enumerate() {
            if i == 0 {
                sep(&mut s);
                s.push_str("; ");
            } else {
                s.push_str(" ; ");
            }
            s.push_str(&comment_text(&c.text));
        }
        self.line_str(&s, Some(b.meta.span));
        self.buf = s;
    }

    fn item(&mut self, it: &Item) -> String {
        match &it.kind {
            ItemKind::Assign { target, value } => format!("{}={}", var(target), expr(value)),
            ItemKind::Word(w) => word(w),
            ItemKind::Goto(g) => goto(g),
            ItemKind::Case(c) => {
                let mut s = format!("CASE({}) OF", expr(&c.selector));
                for a in &c.arms {
                    s.push_str(&format!(" {} {}", expr(&a.value), goto(&a.goto)));
                }
                if let Some(d) = &c.default {
                    s.push_str(&format!(" DEFAULT {}", goto(d)));
                }
                s
            }
            ItemKind::Call(c) => {
                let name = match &c.target {
                    CallTarget::Name(n) => n.clone(),
                    CallTarget::Number(n) => format!("O_{n:04}"),
                    CallTarget::Computed(_) => return self.problem(it.span, "a computed call target"),
                };
                let mut s = String::new();
                if c.kind == CallKind::Mcall {
                    s.push_str("MCALL ");
                }
                s.push_str(&name);
                if !c.args.is_empty() {
                    let args: Vec<String> = c
                        .args
                        .iter()
                        .map(|a| match a {
                            Arg::Value(e) | Arg::Letter { value: e, .. } => expr(e),
                            Arg::Omitted(_) => String::new(),
                        })
                        .collect();
                    s.push_str(&format!("({})", args.join(",")));
                }
                if let Some(r) = &c.repeat {
                    s.push_str(&format!(" P={}", expr(r)));
                }
                s
            }
            ItemKind::ModalCallOff => "MCALL".into(),
            ItemKind::Instruction { name } => name.clone(),
            ItemKind::Return { to: None } => "RET".into(),
            ItemKind::Return { to: Some(_) } => self.problem(it.span, "a return to a block number"),
            ItemKind::End { code } => match code {
                EndCode::M30 => "M30".into(),
                EndCode::M2 => "M2".into(),
            },
            ItemKind::Def(d) => {
                let vars: Vec<String> = d
                    .vars
                    .iter()
                    .map(|v| {
                        let mut s = v.name.clone();
                        if !v.dims.is_empty() {
                            let dims: Vec<String> = v.dims.iter().map(|d| d.to_string()).collect();
                            s.push_str(&format!("[{}]", dims.join(",")));
                        }
                        if let Some(Init::Value(e)) = &v.init {
                            s.push_str(&format!("={}", expr(e)));
                        }
                        s
                    })
                    .collect();
                let scope = match d.scope {
                    Some(DefScope::Nck) => "NCK ",
                    Some(DefScope::Chan) => "CHAN ",
                    None => "",
                };
                format!("DEF {scope}{} {}", ty(d.ty), vars.join(", "))
            }
            ItemKind::Alarm { style: AlarmStyle::Setal, number, .. } => format!("SETAL({})", expr(number)),
            ItemKind::Alarm { style: AlarmStyle::FanucMacro, .. } => self.problem(it.span, "a FANUC #3000 alarm"),
            ItemKind::StopMessage { .. } => self.problem(it.span, "a FANUC #3006 stop"),
            ItemKind::Message { text: Some(e) } => format!("MSG({})", expr(e)),
            ItemKind::Message { text: None } => "MSG()".into(),
            ItemKind::Stopre => "STOPRE".into(),
            ItemKind::Print(p) => match (&p.status, &p.file, &p.parts[..]) {
                (Some(v), Some(f), [PrintPart::Str(e)]) => format!("WRITE({},{},{})", var(v), expr(f), expr(e)),
                _ => self.problem(it.span, "a FANUC DPRNT"),
            },
            ItemKind::IfThen { .. } => self.problem(it.span, "a FANUC IF-THEN"),
            ItemKind::IfBlock { .. } => self.problem(it.span, "a Haas IF with NC words"),
            ItemKind::Extern(e) => {
                let ps: Vec<String> = e
                    .params
                    .iter()
                    .map(|(by_ref, t, dims)| {
                        let dims: Vec<String> = dims.iter().map(|d| d.to_string()).collect();
                        let dims = if dims.is_empty() { String::new() } else { format!("[{}]", dims.join(",")) };
                        format!("{}{}{dims}", if *by_ref { "VAR " } else { "" }, ty(*t))
                    })
                    .collect();
                format!("EXTERN {}({})", e.name, ps.join(", "))
            }
            ItemKind::SyncAction(a) => {
                let mut s = String::new();
                if let Some((scope, id)) = &a.id {
                    let kw = if *scope == SyncScope::Static { "IDS" } else { "ID" };
                    s.push_str(&format!("{kw}={} ", expr(id)));
                }
                if let Some((t, c)) = &a.trigger {
                    s.push_str(&format!("{} {} ", t.name(), expr(c)));
                }
                let acts: Vec<String> = a.actions.iter().map(|i| self.item(i)).collect();
                format!("{s}DO {}", acts.join(" "))
            }
            ItemKind::ParamWrite(_) => self.problem(it.span, "a FANUC parameter write"),
            ItemKind::RepeatSection(r) => {
                let kw = if r.single { "REPEATB" } else { "REPEAT" };
                let mut s = format!("{kw} {}", r.start.name);
                if let Some(e) = &r.end {
                    s.push_str(&format!(" {}", e.name));
                }
                if let Some(c) = &r.count {
                    s.push_str(&format!(" P={}", expr(c)));
                }
                s
            }
            ItemKind::Frame { op, words } => {
                let ws: Vec<String> = words.iter().map(word).collect();
                format!("{op} {}", ws.join(" ")).trim_end().to_string()
            }
        }
    }
}

/// A comment as Siemens text: `;` ends nothing inside a comment, but a line end would.
fn comment_text(t: &str) -> String {
    t.replace(['\n', '\r'], " ").trim().to_string()
}

fn head(meta: &BlockMeta, text: &str) -> String {
    let mut s = String::new();
    if let Some(n) = &meta.number {
        s.push_str(&format!("N{} ", n.value));
    }
    s.push_str(text);
    if !meta.comments.is_empty() {
        let c: Vec<String> = meta.comments.iter().map(|c| comment_text(&c.text)).collect();
        s.push_str(&format!(" ; {}", c.join(" ; ")));
    }
    s
}

fn goto(g: &Goto) -> String {
    let kw = match (g.search, g.missing_continues) {
        (_, true) => "GOTOC",
        (Search::Forward, _) => "GOTOF",
        (Search::Backward, _) => "GOTOB",
        (Search::ForwardThenBackward | Search::ForwardThenWrap, _) => "GOTO",
    };
    let target = match &g.target {
        Target::Label(l) => l.name.clone(),
        Target::Number(n) => format!("N{}", n.value),
        Target::Computed(e) => expr(e),
    };
    match &g.cond {
        Some(c) => format!("IF {} {kw} {target}", cond(c)),
        None => format!("{kw} {target}"),
    }
}

/// [`word`] written into `out`, without the allocations for a plain number.
fn word_into(out: &mut String, w: &Word) {
    use std::fmt::Write;
    match &w.value {
        WordValue::Expr(Expr { kind: ExprKind::Num(n), .. }) if matches!(w.addr, Addr::Letter(_)) => {
            out.push_str(w.addr.as_str());
            let v = n.value;
            if v == 0.0 {
                out.push('0');
            } else if (1e-6..1e15).contains(&v.abs()) {
                let _ = write!(out, "{v}");
            } else {
                // The `EX` form needs `=` (as [`word`] writes it).
                let t = number(v);
                if t.contains("EX") {
                    out.push('=');
                }
                out.push_str(&t);
            }
        }
        _ => out.push_str(&word(w)),
    }
}

fn word(w: &Word) -> String {
    let ax;
    let addr = match &w.addr {
        Addr::Axis(e) => {
            ax = format!("AX[{}]", expr(e));
            ax.as_str()
        }
        a => a.as_str(),
    };
    let single = matches!(w.addr, Addr::Letter(_));
    match &w.value {
        WordValue::Expr(e) => match &e.kind {
            ExprKind::Num(n) if single => {
                let t = number(n.value);
                if t.contains("EX") {
                    format!("{addr}={t}")
                } else {
                    format!("{addr}{t}")
                }
            }
            ExprKind::Str(s) => format!("{addr}={}", string(s)),
            _ => format!("{addr}={}", expr(e)),
        },
        WordValue::Ac(e) => format!("{addr}=AC({})", expr(e)),
        WordValue::Ic(e) => format!("{addr}=IC({})", expr(e)),
        WordValue::Rotary(m, e) => format!("{addr}={}({})", m.name(), expr(e)),
    }
}

fn string(s: &str) -> String {
    // Siemens strings cannot hold a double quote.
    format!("\"{}\"", s.replace('"', "'"))
}

/// Shortest text that reads back as exactly `v`.
pub fn number(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    let a = v.abs();
    if (1e-6..1e15).contains(&a) {
        let s = format!("{v}");
        // Rust writes integers without a point; keep that ("10").
        s
    } else {
        format!("{v:e}").replace('e', "EX")
    }
}

fn var(v: &VarRef) -> String {
    match &v.kind {
        VarKind::R(n) => format!("R{n}"),
        VarKind::RIndirect(e) => format!("R[{}]", expr(e)),
        VarKind::Named { name, indices } => with_indices(name, indices),
        VarKind::System { name, indices } => with_indices(&format!("${name}"), indices),
        VarKind::Hash(n) => format!("#{n}"),
        VarKind::HashIndirect(e) => format!("#[{}]", expr(e)),
    }
}

fn with_indices(name: &str, indices: &[Expr]) -> String {
    if indices.is_empty() {
        name.to_string()
    } else {
        let ix: Vec<String> = indices.iter().map(expr).collect();
        format!("{name}[{}]", ix.join(","))
    }
}

/// Priority of an expression's top operator (higher binds tighter), per the Siemens
/// priority table (sources S1 and S13 of `docs/semantics.md`).
fn prec(e: &Expr) -> u8 {
    match &e.kind {
        ExprKind::Num(n) if n.value < 0.0 => 65,
        ExprKind::Unary(UnOp::Neg, _) => 65,
        ExprKind::Unary(_, _) => 90,
        ExprKind::Binary(op, _, _) => binprec(*op),
        ExprKind::Cmp(..) => 10,
        _ => 100,
    }
}

fn binprec(op: BinOp) -> u8 {
    match op {
        BinOp::Mul | BinOp::Div | BinOp::IntDiv | BinOp::Mod => 80,
        BinOp::Add | BinOp::Sub => 70,
        BinOp::BitAnd | BinOp::FanucBitAnd => 60,
        BinOp::BitXor | BinOp::FanucBitXor => 55,
        BinOp::BitOr | BinOp::FanucBitOr => 50,
        BinOp::And => 40,
        BinOp::Xor => 35,
        BinOp::Or => 30,
        BinOp::Concat => 20,
    }
}

fn binop(op: BinOp) -> &'static str {
    match op {
        BinOp::Add => "+",
        BinOp::Sub => "-",
        BinOp::Mul => "*",
        BinOp::Div => "/",
        BinOp::IntDiv => " DIV ",
        BinOp::Mod => " MOD ",
        BinOp::BitAnd | BinOp::FanucBitAnd => " B_AND ",
        BinOp::BitOr | BinOp::FanucBitOr => " B_OR ",
        BinOp::BitXor | BinOp::FanucBitXor => " B_XOR ",
        BinOp::And => " AND ",
        BinOp::Or => " OR ",
        BinOp::Xor => " XOR ",
        BinOp::Concat => "<<",
    }
}

fn cmpop(op: CmpOp) -> &'static str {
    match op {
        CmpOp::Eq => "==",
        CmpOp::Ne => "<>",
        CmpOp::Gt => ">",
        CmpOp::Ge => ">=",
        CmpOp::Lt => "<",
        CmpOp::Le => "<=",
    }
}

pub fn func_name(f: Func) -> &'static str {
    match f {
        Func::Sin => "SIN",
        Func::Cos => "COS",
        Func::Tan => "TAN",
        Func::Asin => "ASIN",
        Func::Acos => "ACOS",
        Func::Atan2 => "ATAN2",
        Func::Sqrt => "SQRT",
        Func::Abs => "ABS",
        Func::Round => "ROUND",
        Func::Trunc => "TRUNC",
        Func::RoundUp => "ROUNDUP",
        Func::Ln => "LN",
        Func::Exp => "EXP",
        Func::Pot => "POT",
        Func::MinVal => "MINVAL",
        Func::MaxVal => "MAXVAL",
        Func::Bound => "BOUND",
        Func::AxName => "AXNAME",
        Func::StrLen => "STRLEN",
        Func::ToUpper => "TOUPPER",
        Func::ToLower => "TOLOWER",
        Func::Index => "INDEX",
        Func::RIndex => "RINDEX",
        Func::Substr => "SUBSTR",
        Func::Number => "NUMBER",
        Func::IsNumber => "ISNUMBER",
        Func::GetT => "GETT",
        Func::Sprint => "SPRINT",
        Func::IsVar => "ISVAR",
        Func::IsFile => "ISFILE",
        Func::GetSelT => "GETSELT",
        // FANUC-only functions have no Siemens spelling; the passes lower them. Should one
        // slip through, a name Siemens does not know makes the re-parse fail loudly.
        Func::FanucAsin => "FANUC_ASIN",
        Func::FanucAcos => "FANUC_ACOS",
        Func::FanucAtan2 | Func::FanucAtan => "FANUC_ATAN",
        Func::FanucRound => "FANUC_ROUND",
        Func::FanucFup => "FANUC_FUP",
        Func::Pow => "FANUC_POW",
        Func::Bin => "FANUC_BIN",
        Func::Bcd => "FANUC_BCD",
        Func::Adp => "FANUC_ADP",
    }
}

/// A condition at the top of IF/WHILE/UNTIL: no outer parentheses needed.
fn cond(e: &Expr) -> String {
    expr(e)
}

fn wrap(e: &Expr, paren: bool) -> String {
    if paren {
        format!("({})", expr(e))
    } else {
        expr(e)
    }
}

/// Writes an expression with the parentheses Siemens priorities need.
pub fn expr(e: &Expr) -> String {
    match &e.kind {
        ExprKind::Num(n) => number(n.value),
        ExprKind::Vacant => "0".into(),
        ExprKind::Str(s) => string(s),
        ExprKind::Ident(s) => s.clone(),
        ExprKind::Var(v) => var(v),
        ExprKind::Unary(op, a) => {
            let (kw, p) = match op {
                UnOp::Neg => ("-", 65),
                UnOp::Not => ("NOT ", 90),
                UnOp::BitNot => ("B_NOT ", 90),
            };
            // Any operator below a prefix needs parentheses: `-(R1-R2)`, `NOT (A==B)`.
            let _ = p;
            format!("{kw}{}", wrap(a, prec(a) < 100))
        }
        ExprKind::Binary(op, a, b) => {
            let p = binprec(*op);
            // Any comparison inside another operator is parenthesised (pitfall 6), and so is
            // a different bitwise operator: few readers know B_AND binds tighter than B_OR.
            let mixed = |x: &Expr| matches!(&x.kind, ExprKind::Binary(o, ..) if (50..=60).contains(&p) && (50..=60).contains(&binprec(*o)) && binprec(*o) != p);
            let lp = prec(a) < p || matches!(a.kind, ExprKind::Cmp(..)) || mixed(a);
            let rp = prec(b) <= p || matches!(b.kind, ExprKind::Cmp(..)) || mixed(b);
            format!("{}{}{}", wrap(a, lp), binop(*op), wrap(b, rp))
        }
        ExprKind::Cmp(op, _, a, b) => {
            let lp = matches!(a.kind, ExprKind::Cmp(..));
            let rp = matches!(b.kind, ExprKind::Cmp(..));
            format!("{}{}{}", wrap(a, lp), cmpop(*op), wrap(b, rp))
        }
        ExprKind::Func(f, args) => {
            let a: Vec<String> = args.iter().map(expr).collect();
            format!("{}({})", func_name(*f), a.join(","))
        }
    }
}
