//! The stable text form of the IR printed by `nctrans parse` and committed under
//! `corpus/out/ir/`. One node per line, indented by depth, spans as `@lo..hi` byte ranges;
//! expressions are fully parenthesised prefix forms whose operator names carry the meaning
//! (`fup` vs `roundup`, `band.f` vs `and`, `eq` vs `eq~`).

use super::*;
use std::fmt::Write;

/// Dumps a whole unit.
pub fn dump(unit: &Unit) -> String {
    let mut d = Dumper { out: String::new(), depth: 0 };
    d.line(format!("unit {}", unit.dialect.name()));
    d.depth += 1;
    for p in &unit.programs {
        d.program(p);
    }
    d.out
}

struct Dumper {
    out: String,
    depth: usize,
}

impl Dumper {
    fn line(&mut self, s: String) {
        for _ in 0..self.depth {
            self.out.push_str("  ");
        }
        self.out.push_str(&s);
        self.out.push('\n');
    }

    fn nested(&mut self, f: impl FnOnce(&mut Self)) {
        self.depth += 1;
        f(self);
        self.depth -= 1;
    }

    fn program(&mut self, p: &Program) {
        let name = match &p.name {
            Some(ProgName::Number(n)) => format!("O{n}"),
            Some(ProgName::Name(s)) => s.clone(),
            None => "-".into(),
        };
        self.line(format!("program {name}{} {}", if p.save { " save" } else { "" }, sp(p.span)));
        self.nested(|d| {
            if let Some(h) = &p.head {
                d.line(format!("head {}", meta(h)));
            }
            for prm in &p.params {
                let dims = dims(&prm.dims);
                let by = if prm.by_ref { "var " } else { "" };
                d.line(format!("param {by}{} {}{dims} {}", ty(prm.ty), prm.name, sp(prm.span)));
            }
            d.body(&p.body);
        });
    }

    fn body(&mut self, body: &[Stmt]) {
        for s in body {
            self.stmt(s);
        }
    }

    fn stmt(&mut self, s: &Stmt) {
        match &s.kind {
            StmtKind::Block(b) => {
                self.line(format!("block {}", meta(&b.meta)));
                self.nested(|d| {
                    for it in &b.items {
                        d.item(it);
                    }
                });
            }
            StmtKind::If(i) => {
                self.line(format!("if {} {} head {}", expr(&i.cond), sp(s.span), meta(&i.head)));
                self.nested(|d| d.body(&i.then_body));
                if let Some(e) = &i.else_part {
                    self.line(format!("else {}", meta(&e.head)));
                    self.nested(|d| d.body(&e.body));
                }
                self.line(format!("endif {}", meta(&i.end)));
            }
            StmtKind::While(w) => {
                self.line(format!("while {} {} head {}", expr(&w.cond), sp(s.span), meta(&w.head)));
                self.nested(|d| d.body(&w.body));
                self.line(format!("endwhile {}", meta(&w.end)));
            }
            StmtKind::Loop(l) => {
                self.line(format!("loop {} head {}", sp(s.span), meta(&l.head)));
                self.nested(|d| d.body(&l.body));
                self.line(format!("endloop {}", meta(&l.end)));
            }
            StmtKind::For(f) => {
                self.line(format!(
                    "for {} = {} to {} {} head {}",
                    var(&f.var),
                    expr(&f.from),
                    expr(&f.to),
                    sp(s.span),
                    meta(&f.head)
                ));
                self.nested(|d| d.body(&f.body));
                self.line(format!("endfor {}", meta(&f.end)));
            }
            StmtKind::Repeat(r) => {
                self.line(format!("repeat {} head {}", sp(s.span), meta(&r.head)));
                self.nested(|d| d.body(&r.body));
                self.line(format!("until {} {}", expr(&r.until), meta(&r.end)));
            }
            StmtKind::Do(d) => {
                let c = d.cond.as_ref().map_or("forever".to_string(), |c| format!("while {}", expr(c)));
                self.line(format!("do{} {c} {} head {}", d.id, sp(s.span), meta(&d.head)));
                self.nested(|dd| dd.body(&d.body));
                self.line(format!("end{} {}", d.id, meta(&d.end)));
            }
        }
    }

    fn item(&mut self, it: &Item) {
        let at = sp(it.span);
        let text = match &it.kind {
            ItemKind::Assign { target, value } => {
                format!("assign {} = {}", var(target), expr(value))
            }
            ItemKind::Word(w) => format!("word {}", word(w)),
            ItemKind::Goto(g) => format!("goto {}", goto(g)),
            ItemKind::IfThen { cond, then } => {
                self.line(format!("if-then {} {at}", expr(cond)));
                self.nested(|d| d.item(then));
                return;
            }
            ItemKind::Extern(e) => {
                let ps: Vec<String> = e
                    .params
                    .iter()
                    .map(|(by_ref, t, dims)| format!("{}{}{dims:?}", if *by_ref { "var " } else { "" }, ty(*t)))
                    .collect();
                format!("extern {} ({})", e.name, ps.join(", "))
            }
            ItemKind::IfBlock { cond, items } => {
                self.line(format!("if-block {} {at}", expr(cond)));
                self.nested(|d| {
                    for i in items {
                        d.item(i);
                    }
                });
                return;
            }
            ItemKind::SyncAction(a) => {
                let mut s = String::from("sync-action");
                if let Some((scope, id)) = &a.id {
                    let kw = if *scope == SyncScope::Static { "ids" } else { "id" };
                    let _ = write!(s, " {kw}={}", expr(id));
                }
                if let Some((t, c)) = &a.trigger {
                    let _ = write!(s, " {} {}", t.name().to_ascii_lowercase(), expr(c));
                }
                self.line(format!("{s} {at}"));
                self.nested(|d| {
                    for i in &a.actions {
                        d.item(i);
                    }
                });
                return;
            }
            ItemKind::Case(c) => {
                let mut s = format!("case {}", expr(&c.selector));
                for a in &c.arms {
                    let _ = write!(s, " | {} -> {}", expr(&a.value), goto(&a.goto));
                }
                if let Some(dft) = &c.default {
                    let _ = write!(s, " | default -> {}", goto(dft));
                }
                s
            }
            ItemKind::Call(c) => call(c),
            ItemKind::ModalCallOff => "modal-call-off".into(),
            ItemKind::Return { to } => match to {
                Some(e) => format!("return to {}", expr(e)),
                None => "return".into(),
            },
            ItemKind::End { code } => format!("end {code:?}"),
            ItemKind::Def(def) => {
                let vars: Vec<String> = def.vars.iter().map(defvar).collect();
                let scope = match def.scope {
                    Some(DefScope::Nck) => "nck ",
                    Some(DefScope::Chan) => "chan ",
                    None => "",
                };
                format!("def {scope}{} {}", ty(def.ty), vars.join(", "))
            }
            ItemKind::Alarm { style, number, text } => {
                let st = match style {
                    AlarmStyle::FanucMacro => "fanuc-3000",
                    AlarmStyle::Setal => "setal",
                };
                format!("alarm {st} {}{}", expr(number), opt_text(text))
            }
            ItemKind::StopMessage { text } => format!("stop-message{}", opt_text(text)),
            ItemKind::Message { text } => match text {
                Some(e) => format!("message {}", expr(e)),
                None => "message clear".into(),
            },
            ItemKind::Stopre => "stopre".into(),
            ItemKind::Print(p) => print(p),
            ItemKind::ParamWrite(p) => {
                let mut s = format!("param-write n={}", expr(&p.number));
                if let Some(a) = &p.axis {
                    let _ = write!(s, " p={}", expr(a));
                }
                if let Some(b) = &p.bit {
                    let _ = write!(s, " q={}", expr(b));
                }
                let _ = write!(s, " r={}", expr(&p.value));
                s
            }
            ItemKind::RepeatSection(r) => {
                let kw = if r.single { "repeatb" } else { "repeat-section" };
                let mut s = format!("{kw} {}", r.start.name);
                if let Some(e) = &r.end {
                    let _ = write!(s, " .. {}", e.name);
                }
                if let Some(c) = &r.count {
                    let _ = write!(s, " times {}", expr(c));
                }
                s
            }
            ItemKind::Instruction { name } => format!("instruction {name}"),
            ItemKind::Frame { op, words } => {
                let ws: Vec<String> = words.iter().map(word).collect();
                format!("frame {op} {}", ws.join(" ")).trim_end().to_string()
            }
        };
        self.line(format!("{text} {at}"));
    }
}

/// `print "X" #100[53] (concat …) file="F" status=ERR`.
fn print(p: &Print) -> String {
    let mut s = String::from("print");
    for part in &p.parts {
        match part {
            PrintPart::Text(t) => {
                let _ = write!(s, " {}", quote(t));
            }
            PrintPart::Field { value, int, frac } => {
                let _ = write!(s, " {}[{int}{frac}]", expr(value));
            }
            PrintPart::Str(e) => {
                let _ = write!(s, " {}", expr(e));
            }
        }
    }
    if let Some(f) = &p.file {
        let _ = write!(s, " file={}", expr(f));
    }
    if let Some(v) = &p.status {
        let _ = write!(s, " status={}", var(v));
    }
    s
}

fn opt_text(t: &Option<String>) -> String {
    t.as_ref().map_or(String::new(), |t| format!(" {}", quote(t)))
}

fn sp(s: Span) -> String {
    format!("@{}..{}", s.lo, s.hi)
}

fn meta(m: &BlockMeta) -> String {
    let mut s = sp(m.span);
    if let Some(k) = m.skip {
        let _ = write!(s, " skip/{k}");
    }
    if let Some(n) = &m.number {
        let _ = write!(s, " N{}", n.value);
    }
    if let Some(l) = &m.label {
        let _ = write!(s, " label {}", l.name);
    }
    for c in &m.comments {
        let _ = write!(s, " comment {}", quote(&c.text));
    }
    s
}

fn quote(t: &str) -> String {
    format!("{t:?}")
}

fn ty(t: DataType) -> String {
    t.to_string()
}

fn dims(d: &[u32]) -> String {
    if d.is_empty() {
        String::new()
    } else {
        let v: Vec<String> = d.iter().map(u32::to_string).collect();
        format!("[{}]", v.join(","))
    }
}

fn defvar(v: &DefVar) -> String {
    let mut s = format!("{}{}", v.name, dims(&v.dims));
    match &v.init {
        Some(Init::Value(e)) => {
            let _ = write!(s, " = {}", expr(e));
        }
        Some(Init::Set(list)) => {
            let items: Vec<String> = list.iter().map(|e| e.as_ref().map_or("_".into(), expr)).collect();
            let _ = write!(s, " = set({})", items.join(", "));
        }
        Some(Init::Rep { value, count }) => {
            let c = count.as_ref().map_or(String::new(), |c| format!(", {}", expr(c)));
            let _ = write!(s, " = rep({}{c})", expr(value));
        }
        None => {}
    }
    s
}

fn word(w: &Word) -> String {
    let v = match &w.value {
        WordValue::Expr(e) => expr(e),
        WordValue::Ac(e) => format!("ac({})", expr(e)),
        WordValue::Ic(e) => format!("ic({})", expr(e)),
        WordValue::Rotary(m, e) => format!("{}({})", m.name().to_ascii_lowercase(), expr(e)),
    };
    match &w.addr {
        Addr::Axis(e) => format!("AX[{}] {v}", expr(e)),
        a => format!("{} {v}", a.as_str()),
    }
}

fn goto(g: &Goto) -> String {
    let kw = match (g.search, g.missing_continues) {
        (Search::Forward, _) => "forward",
        (Search::Backward, _) => "backward",
        (Search::ForwardThenBackward, false) => "forward-then-backward",
        (Search::ForwardThenBackward, true) => "forward-then-backward-or-continue",
        (Search::ForwardThenWrap, _) => "forward-then-wrap",
    };
    let t = match &g.target {
        Target::Label(l) => l.name.clone(),
        Target::Number(n) => format!("N{}", n.value),
        Target::Computed(e) => expr(e),
    };
    match &g.cond {
        Some(c) => format!("{kw} {t} if {}", expr(c)),
        None => format!("{kw} {t}"),
    }
}

fn call(c: &Call) -> String {
    let kind = match c.kind {
        CallKind::G65 => "g65",
        CallKind::G66 => "g66",
        CallKind::M98 => "m98",
        CallKind::M97 => "m97",
        CallKind::Named => "call",
        CallKind::LNumber => "call-l",
        CallKind::Mcall => "mcall",
    };
    let target = match &c.target {
        CallTarget::Number(n) => format!("O{n}"),
        CallTarget::Name(s) => s.clone(),
        CallTarget::Computed(e) => expr(e),
    };
    let args: Vec<String> = c
        .args
        .iter()
        .map(|a| match a {
            Arg::Value(e) => expr(e),
            Arg::Omitted(_) => "_".into(),
            Arg::Letter { letter, var, value } => {
                format!("{}=#{var}:{}", *letter as char, expr(value))
            }
        })
        .collect();
    let mut s = format!("{kind} {target}");
    if !c.args.is_empty() {
        let _ = write!(s, " ({})", args.join(", "));
    }
    if let Some(r) = &c.repeat {
        let _ = write!(s, " times {}", expr(r));
    }
    s
}

/// A number: integers without a point as `12`, with a point as `12.`; others in the
/// shortest form that reads back exactly.
pub fn num(n: Number) -> String {
    if n.value.fract() == 0.0 && n.value.abs() < 1e15 {
        let i = n.value as i64;
        let neg = if n.value.is_sign_negative() && i == 0 { "-" } else { "" };
        if n.point {
            format!("{neg}{i}.")
        } else {
            format!("{neg}{i}")
        }
    } else {
        format!("{:?}", n.value)
    }
}

pub fn var(v: &VarRef) -> String {
    match &v.kind {
        VarKind::Hash(n) => format!("#{n}"),
        VarKind::HashIndirect(e) => format!("#[{}]", expr(e)),
        VarKind::R(n) => format!("R{n}"),
        VarKind::RIndirect(e) => format!("R[{}]", expr(e)),
        VarKind::Named { name, indices } => indexed(name, indices),
        VarKind::System { name, indices } => indexed(&format!("${name}"), indices),
    }
}

fn indexed(name: &str, indices: &[Expr]) -> String {
    if indices.is_empty() {
        name.to_string()
    } else {
        let v: Vec<String> = indices.iter().map(expr).collect();
        format!("{name}[{}]", v.join(","))
    }
}

/// Fully parenthesised prefix form of an expression.
pub fn expr(e: &Expr) -> String {
    match &e.kind {
        ExprKind::Num(n) => num(*n),
        ExprKind::Vacant => "vacant".into(),
        ExprKind::Str(s) => quote(s),
        ExprKind::Ident(s) => format!("'{s}"),
        ExprKind::Var(v) => var(v),
        ExprKind::Unary(op, a) => {
            let o = match op {
                UnOp::Neg => "neg",
                UnOp::Not => "not",
                UnOp::BitNot => "bnot",
            };
            format!("({o} {})", expr(a))
        }
        ExprKind::Binary(op, a, b) => format!("({} {} {})", binop(*op), expr(a), expr(b)),
        ExprKind::Cmp(op, tol, a, b) => {
            let o = match op {
                CmpOp::Eq => "eq",
                CmpOp::Ne => "ne",
                CmpOp::Gt => "gt",
                CmpOp::Ge => "ge",
                CmpOp::Lt => "lt",
                CmpOp::Le => "le",
            };
            let t = if *tol == Tolerance::Relative { "~" } else { "" };
            format!("({o}{t} {} {})", expr(a), expr(b))
        }
        ExprKind::Func(f, args) => {
            let a: Vec<String> = args.iter().map(expr).collect();
            format!("({} {})", func_name(*f), a.join(" "))
        }
    }
}

pub fn binop(op: BinOp) -> &'static str {
    match op {
        BinOp::Add => "+",
        BinOp::Sub => "-",
        BinOp::Mul => "*",
        BinOp::Div => "/",
        BinOp::IntDiv => "div",
        BinOp::Mod => "mod",
        BinOp::FanucBitAnd => "band.f",
        BinOp::FanucBitOr => "bor.f",
        BinOp::FanucBitXor => "bxor.f",
        BinOp::BitAnd => "band",
        BinOp::BitOr => "bor",
        BinOp::BitXor => "bxor",
        BinOp::And => "and",
        BinOp::Or => "or",
        BinOp::Xor => "xor",
        BinOp::Concat => "concat",
    }
}

pub fn func_name(f: Func) -> &'static str {
    match f {
        Func::Sin => "sin",
        Func::Cos => "cos",
        Func::Tan => "tan",
        Func::FanucAsin => "asin.f",
        Func::FanucAcos => "acos.f",
        Func::FanucAtan2 => "atan2.f",
        Func::FanucAtan => "atan.f",
        Func::Asin => "asin",
        Func::Acos => "acos",
        Func::Atan2 => "atan2",
        Func::Sqrt => "sqrt",
        Func::Abs => "abs",
        Func::FanucRound => "round.f",
        Func::Round => "round",
        Func::Trunc => "trunc",
        Func::FanucFup => "fup",
        Func::RoundUp => "roundup",
        Func::Ln => "ln",
        Func::Exp => "exp",
        Func::Pot => "pot",
        Func::Pow => "pow",
        Func::MinVal => "minval",
        Func::MaxVal => "maxval",
        Func::Bound => "bound",
        Func::AxName => "axname",
        Func::StrLen => "strlen",
        Func::ToUpper => "toupper",
        Func::ToLower => "tolower",
        Func::Index => "index",
        Func::RIndex => "rindex",
        Func::Substr => "substr",
        Func::Number => "number",
        Func::IsNumber => "isnumber",
        Func::GetT => "gett",
        Func::Sprint => "sprint",
        Func::IsVar => "isvar",
        Func::IsFile => "isfile",
        Func::GetSelT => "getselt",
        Func::Bin => "bin",
        Func::Bcd => "bcd",
        Func::Adp => "adp",
    }
}
