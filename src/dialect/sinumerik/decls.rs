//! Declarations (`DEF`, the PROC line, `EXTERN`) and the explicit call forms `CALL "NAME"`, `CALL PROG_VAR`, `CALL "L"<<R1`,
//! `PCALL NAME(args)`: from the pest pairs to IR.

use super::parse::Lower;
use super::Rule;
use super::{names, structure::ProcHead};
use crate::ir::*;
use crate::{diag::Diagnostic, span::Span};
use pest::iterators::{Pair, Pairs};

impl Lower<'_, '_> {
    /// `EXTERN NAME(REAL, VAR INT[3])`.
    pub(super) fn extern_decl(&mut self, inner: Pairs<'_, Rule>) -> Option<Item> {
        let pairs: Vec<Pair<'_, Rule>> = inner.collect();
        let span = self.span(pairs.first()?).to(self.span(pairs.last()?));
        let mut decl = ExternDecl { name: String::new(), params: Vec::new() };
        for p in pairs {
            match p.as_rule() {
                Rule::user_name => decl.name = p.as_str().to_ascii_uppercase(),
                Rule::ext_param => {
                    let (mut by_ref, mut ty, mut dims) = (false, DataType::Real, Vec::new());
                    for q in p.into_inner() {
                        match q.as_rule() {
                            Rule::kw_var => by_ref = true,
                            Rule::dims => dims = self.dims(q).unwrap_or_default(),
                            _ => ty = self.data_type(q).unwrap_or(ty),
                        }
                    }
                    decl.params.push((by_ref, ty, dims));
                }
                _ => {}
            }
        }
        Some(Item { kind: ItemKind::Extern(Box::new(decl)), span })
    }

    /// `CALL "NAME"` / `CALL VAR` / `CALL "L"<<R1` / `PCALL NAME(args)`: a call by name, the
    /// name written as a string, held in a STRING variable or built by a STRING expression
    /// (the last two found when the call runs). `PCALL NAME` names the program itself unless
    /// NAME is a declared variable: PCALL takes a program name, a path or a variable.
    pub(super) fn call_stmt(&mut self, p: Pair<'_, Rule>) -> Option<ItemKind> {
        let mut inner = p.into_inner();
        let pcall = inner.next()?.as_str().eq_ignore_ascii_case("PCALL");
        let target = inner.next()?;
        if target.as_rule() == Rule::call {
            return self.item(target);
        }
        let e = self.expr(target);
        let target = match e.kind {
            ExprKind::Str(s) => CallTarget::Name(s.trim().to_ascii_uppercase()),
            ExprKind::Var(v) => match &v.kind {
                VarKind::Named { name, indices }
                    if pcall && indices.is_empty() && !self.st.declared.contains_key(name) =>
                {
                    CallTarget::Name(name.clone())
                }
                _ => CallTarget::Computed(Expr::new(ExprKind::Var(v), e.span)),
            },
            kind => CallTarget::Computed(Expr { kind, span: e.span }),
        };
        Some(ItemKind::Call(Box::new(Call { kind: CallKind::Named, target, args: Vec::new(), repeat: None })))
    }
}

impl Lower<'_, '_> {
    pub(super) fn def(&mut self, pairs: Vec<Pair<'_, Rule>>) -> Option<ItemKind> {
        let mut ty = None;
        let mut scope = None;
        let mut vars = Vec::new();
        for p in pairs {
            match p.as_rule() {
                Rule::def_var => vars.push(self.def_var(p)?),
                Rule::def_scope => {
                    scope = Some(if p.as_str().eq_ignore_ascii_case("NCK") { DefScope::Nck } else { DefScope::Chan })
                }
                Rule::kw_def | Rule::comma => {}
                _ => ty = Some(self.data_type(p)?),
            }
        }
        let ty = ty?;
        for v in &vars {
            if names::r_number(&v.name).is_some() {
                self.error(
                    Diagnostic::warning("NC133", format!("DEF variable {} has the name of an R parameter", v.name))
                        .primary(self.file(), v.span, "read as R parameter wherever it is used")
                        .note("Sinumerik names start with two letters; `R12` always means the R parameter")
                        .hint("give the variable a name like `U_VALUE`"),
                );
            }
            self.st.declared.insert(v.name.clone(), ty);
        }
        Some(ItemKind::Def(Box::new(Def { scope, ty, vars })))
    }

    /// A DEF or PROC parameter name the control refuses (an address letter, a reserved
    /// word) is an error at its declaration: read on, `I=0` would be the arc centre.
    pub(super) fn check_name(&mut self, what: &str, name: &str, span: Span) {
        if let Some(why) = names::reserved_name(name) {
            self.error(
                Diagnostic::error("NC212", format!("{what} {name} cannot be a name: {why}"))
                    .primary(self.file(), span, "not a user name on Sinumerik")
                    .note("Sinumerik identifiers begin with two letters or `_` and must not be an address or a reserved word")
                    .hint(format!("give it a name like `U_{name}` or `{name}_CNT`")),
            );
        }
    }

    pub fn data_type(&mut self, p: Pair<'_, Rule>) -> Option<DataType> {
        Some(match p.as_rule() {
            Rule::type_real => DataType::Real,
            Rule::type_int => DataType::Int,
            Rule::type_bool => DataType::Bool,
            Rule::type_char => DataType::Char,
            Rule::type_axis => DataType::Axis,
            Rule::type_frame => DataType::Frame,
            Rule::type_string => {
                let span = self.span(&p);
                let n = p.into_inner().find(|q| q.as_rule() == Rule::uint).and_then(|u| u.as_str().parse::<u16>().ok());
                match n {
                    Some(n) if (1..=200).contains(&n) => DataType::String(n),
                    _ => {
                        self.error(
                            Diagnostic::error("NC134", "STRING length must be 1 to 200")
                                .primary(self.file(), span, "length out of range")
                                .note("the 828D/840D programming manuals give a STRING at most 200 characters")
                                .hint("write e.g. `STRING[32]`"),
                        );
                        return None;
                    }
                }
            }
            _ => return None,
        })
    }

    pub(super) fn def_var(&mut self, p: Pair<'_, Rule>) -> Option<DefVar> {
        let span = self.span(&p);
        let mut name = String::new();
        let mut dims = Vec::new();
        let mut init = None;
        for q in p.into_inner() {
            match q.as_rule() {
                Rule::user_name => {
                    name = q.as_str().to_ascii_uppercase();
                    self.check_name("DEF variable", &name, self.span(&q));
                }
                Rule::dims => dims = self.dims(q)?,
                Rule::def_init => {
                    let Some(v) = q.into_inner().next() else { continue };
                    init = Some(match v.as_rule() {
                        Rule::set_init => {
                            let list = match v.into_inner().find(|a| a.as_rule() == Rule::arg_list) {
                                Some(a) => self.args(a),
                                None => Vec::new(),
                            };
                            Init::Set(
                                list.into_iter()
                                    .map(|a| match a {
                                        Arg::Value(e) => Some(e),
                                        _ => None,
                                    })
                                    .collect(),
                            )
                        }
                        Rule::rep_init => {
                            let mut es = v.into_inner().filter(|a| a.as_rule() == Rule::expr);
                            let value = self.expr(es.next()?);
                            let count = es.next().map(|c| self.expr(c));
                            Init::Rep { value, count }
                        }
                        _ => Init::Value(self.expr(v)),
                    });
                }
                _ => {}
            }
        }
        Some(DefVar { name, dims, init, span })
    }

    pub fn dims(&mut self, p: Pair<'_, Rule>) -> Option<Vec<u32>> {
        let mut out = Vec::new();
        for u in p.into_inner().filter(|q| q.as_rule() == Rule::uint) {
            match u.as_str().parse::<u32>() {
                Ok(n) if n > 0 => out.push(n),
                _ => {
                    let span = self.span(&u);
                    self.error(
                        Diagnostic::error("NC135", "array size must be a positive whole number")
                            .primary(self.file(), span, "invalid size")
                            .hint("write the number of elements, e.g. `[10]` or `[10,3]`"),
                    );
                    return None;
                }
            }
        }
        Some(out)
    }

    pub(super) fn proc_head(&mut self, inner: pest::iterators::Pairs<'_, Rule>) -> ProcHead {
        let mut head = ProcHead::default();
        for p in inner {
            match p.as_rule() {
                Rule::user_name => head.name = p.as_str().to_ascii_uppercase(),
                Rule::param => {
                    let span = self.span(&p);
                    let mut prm = Param { name: String::new(), ty: DataType::Real, by_ref: false, dims: vec![], span };
                    for q in p.into_inner() {
                        match q.as_rule() {
                            Rule::kw_var => prm.by_ref = true,
                            Rule::user_name => {
                                prm.name = q.as_str().to_ascii_uppercase();
                                self.check_name("PROC parameter", &prm.name, self.span(&q));
                            }
                            Rule::dims => prm.dims = self.dims(q).unwrap_or_default(),
                            _ => {
                                if let Some(t) = self.data_type(q) {
                                    prm.ty = t;
                                }
                            }
                        }
                    }
                    self.st.declared.insert(prm.name.clone(), prm.ty);
                    head.params.push(prm);
                }
                Rule::proc_attr => head.save |= p.as_str().eq_ignore_ascii_case("SAVE"),
                _ => {}
            }
        }
        head
    }
}

impl Lower<'_, '_> {
    /// `WRITE(err, "file", text)` (Job Planning, "Write file (WRITE)": the error variable
    /// `VAR INT`, the file name and the line, both STRING; the control appends the line and
    /// its LF): the IR's [`Print`], so both evaluators and translations see text output.
    pub(super) fn write_stmt(&mut self, args: Vec<Arg>, span: Span) -> Option<ItemKind> {
        let mut vals = args.into_iter().map(|a| match a {
            Arg::Value(e) => Some(e),
            _ => None,
        });
        let (status, file, text) = match (vals.next(), vals.next(), vals.next(), vals.next()) {
            (Some(Some(s)), Some(Some(f)), Some(Some(t)), None) => (s, f, t),
            _ => return self.bad_write(span, "WRITE takes three arguments: (error variable, file, text)"),
        };
        let ExprKind::Var(status) = status.kind else {
            return self
                .bad_write(span, "the first argument of WRITE is the variable the control sets to its error code");
        };
        Some(ItemKind::Print(Box::new(Print {
            parts: vec![PrintPart::Str(text)],
            file: Some(file),
            status: Some(status),
        })))
    }

    fn bad_write(&mut self, span: Span, what: &str) -> Option<ItemKind> {
        self.error(
            Diagnostic::error("NC555", format!("malformed WRITE: {what}"))
                .primary(self.file(), span, "here")
                .hint("write `WRITE(ERR, \"FILE\", \"TEXT\")` with `DEF INT ERR` declared"),
        );
        None
    }
}
