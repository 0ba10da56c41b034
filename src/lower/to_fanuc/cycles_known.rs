//! The drilling cycles' arguments known at translation (`cycles::plan`): a variable (an R
//! parameter, a DEF variable with its start value or assigned, a PROC parameter assigned)
//! that holds one constant on every path to the call counts as that constant wherever the
//! FANUC cycle must be decided from a number (G98/G99, the R plane, G73/G83, the dwell, the
//! pitch, …), found by the shared forward walk of [`crate::lower::known`]. The rules of this
//! direction: an R parameter is global (a call of a program that may write one, an
//! interrupt routine this program or a program it calls sets up, in a subprogram on a
//! machine with the macro interrupt one its caller may have set up, a synchronized action
//! makes it unknown), a variable passed to a VAR
//! parameter may come back changed, global user data and a name the program's own
//! `nctrans: set` header line sets (an input) are never known, nor a FOR loop's variable.
//! A variable the cycle needs that is not known is refused (NC660) naming the place that
//! makes it so. Rules: docs/translation.md ("Drilling cycles").

use super::*;
use crate::dialect::sinumerik::cycles::{cycle_of, SieCycle};
use crate::lower::known::{self, CallWrites, Key, Known, Miss, Rules};
use crate::lower::literal;

/// The arguments that may stay an expression (they become a word's value, never decide the
/// cycle): the depth and the infeeds, and the tapping speed.
const EXPRESSIONS: &[&str] = &["DP", "DPR", "FDEP", "FDPR", "SST"];

/// What is known before each cycle call and each computed Z word of one program.
#[derive(Default)]
pub struct Vals {
    at: BTreeMap<Span, Known>,
    /// Why a variable is never known in this program.
    never: BTreeMap<Key, String>,
    /// Why every R parameter is never known here (an interrupt, a synchronized action).
    r_never: Option<&'static str>,
}

fn is_cycle(c: &Call) -> bool {
    matches!(&c.target, CallTarget::Name(n) if cycle_of(&n.to_ascii_uppercase()).is_some())
}

/// The analysis of `prog`, where it has a drilling cycle (else nothing is walked).
pub fn vals(ctx: &Ctx, prog: &Program, info: &ProgInfo) -> Vals {
    let mut cycles = false;
    crate::ir::visit::walk_stmts(&prog.body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            cycles |= b.items.iter().any(|it| matches!(&it.kind, ItemKind::Call(c) if is_cycle(c)));
        }
    });
    if !cycles {
        return Vals::default();
    }
    let want = |it: &Item| match &it.kind {
        ItemKind::Call(c) => is_cycle(c),
        ItemKind::Word(w) if w.addr.is(b'Z') => matches!(&w.value, WordValue::Expr(e) if literal(e).is_none()),
        _ => false,
    };
    vals_where(ctx, prog, info, interrupt_and_sync(prog), &want)
}

/// Whether `prog` sets up an interrupt routine and has a synchronized action (each makes R
/// parameters unknown everywhere).
pub fn interrupt_and_sync(prog: &Program) -> (bool, bool) {
    let (mut interrupt, mut sync) = (false, false);
    crate::ir::visit::walk_stmts(&prog.body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            for it in &b.items {
                match &it.kind {
                    ItemKind::Instruction { name } => {
                        interrupt |= crate::ir::interrupt::op_of(&name.to_ascii_uppercase()).is_some()
                    }
                    ItemKind::Word(w) if w.addr.is(b'M') => {
                        interrupt |= matches!(&w.value, WordValue::Expr(e) if literal(e) == Some(96.0))
                    }
                    ItemKind::SyncAction(_) => sync = true,
                    _ => {}
                }
            }
        }
    });
    (interrupt, sync)
}

/// The analysis of `prog` at the items `want` picks, under this direction's rules (the
/// module's head); `(interrupt, sync)`: [`interrupt_and_sync`] of `prog`.
pub fn vals_where(
    ctx: &Ctx,
    prog: &Program,
    info: &ProgInfo,
    (interrupt, sync): (bool, bool),
    want: &dyn Fn(&Item) -> bool,
) -> Vals {
    let mut never: BTreeMap<Key, String> = BTreeMap::new();
    crate::ir::visit::walk_stmts(&prog.body, &mut |s| {
        if let StmtKind::For(f) = &s.kind {
            if let Some(k) = Key::of(&f.var) {
                never.insert(k, "the variable of a FOR loop".into());
            }
        }
    });
    for g in ctx.globals.iter() {
        for v in &g.vars {
            never.insert(Key::Named(v.name.clone()), "global user data, which may be set outside the program".into());
        }
    }
    for name in header_names(&prog.body) {
        never.insert(
            Key::Named(name),
            "set by the program's `nctrans: set` header line (an input, which replaces its DEF start value)".into(),
        );
    }
    // A called program that sets up an interrupt leaves it armed in this one.
    let armed_by_callee = {
        let armers: Vec<u32> = ctx.callees.values().filter(|c| c.effect.interrupts).map(|c| c.number).collect();
        let mut any = false;
        crate::ir::visit::walk_stmts(&prog.body, &mut |s| {
            if let StmtKind::Block(b) = &s.kind {
                any |= b.items.iter().any(|it| {
                    matches!(&it.kind, ItemKind::Call(c)
                    if matches!(c.target, CallTarget::Number(n) if armers.contains(&n)))
                });
            }
        });
        any
    };
    let r_never = if interrupt || armed_by_callee {
        Some("an R parameter: the program sets up an interrupt routine, which may write R parameters at any block")
    } else if info.is_sub && ctx.macro_interrupt {
        Some("an R parameter: in a subprogram on a machine with the custom macro interrupt, its caller may have set up an interrupt routine, which may write R parameters at any block")
    } else if sync {
        Some("an R parameter: the program has a synchronized action, which may write R parameters at any time")
    } else {
        None
    };
    let by_ref: Vec<String> = prog.params.iter().filter(|p| p.by_ref).map(|p| p.name.clone()).collect();
    let callees: BTreeMap<u32, (bool, Vec<bool>)> = ctx
        .callees
        .values()
        .map(|c| (c.number, (c.effect.r_params, c.params.iter().map(|p| p.by_ref).collect())))
        .collect();
    let tracked = |k: &Key| {
        !never.contains_key(k)
            && match k {
                Key::R(_) => r_never.is_none(),
                Key::Named(n) => info.types.get(n).is_some_and(|(ty, dims)| {
                    dims.is_empty() && matches!(ty, DataType::Int | DataType::Real | DataType::Bool | DataType::Char)
                }),
            }
    };
    let global = |k: &Key| match k {
        Key::R(_) => true,
        Key::Named(n) => by_ref.contains(n),
    };
    let call = |c: &Call| {
        if is_cycle(c) {
            return None;
        }
        let unknown = CallWrites { globals: Some("R parameters are global"), by_ref: vec![] };
        let CallTarget::Number(n) = &c.target else { return Some(unknown) };
        Some(match callees.get(n) {
            Some((r, refs)) => CallWrites {
                globals: r.then_some("R parameters are global, and the called program may write one"),
                by_ref: refs.clone(),
            },
            None => unknown,
        })
    };
    let rules = Rules { tracked: &tracked, global: &global, call: &call };
    let at = known::analyse(&prog.body, &rules, want);
    Vals { at, never, r_never }
}

/// The names the leading `nctrans: set` comment lines of `body` set (not `Rn`, `#n`, `$…`).
fn header_names(body: &[Stmt]) -> Vec<String> {
    let mut out = Vec::new();
    for s in body {
        let StmtKind::Block(b) = &s.kind else { break };
        if !b.items.is_empty() {
            break;
        }
        for c in &b.meta.comments {
            let Some(rest) = c.text.trim().strip_prefix("nctrans: set") else { continue };
            for w in rest.split_whitespace() {
                let name = w.split('=').next().unwrap_or("").trim().to_ascii_uppercase();
                let r = name.len() > 1 && name.starts_with('R') && name[1..].bytes().all(|b| b.is_ascii_digit());
                if !name.is_empty() && !r && !name.starts_with('#') && !name.starts_with('$') {
                    out.push(name);
                }
            }
        }
    }
    out
}

/// A refusal: the code, what, the hint, and the place that makes a variable unknown.
pub type Refusal = (&'static str, String, &'static str, Option<(Span, String)>);

impl Vals {
    /// The value of a computed Z word (the level the tool stands at), where known.
    pub fn z(&self, w: &Word, e: &Expr) -> Option<f64> {
        literal(e).or_else(|| self.at.get(&w.span)?.eval(e).ok())
    }

    /// The call with each argument known at translation written as its number (the rest as
    /// written); `Err`: an argument that decides the cycle reads a variable not known there.
    pub fn resolve(&self, c: &Call, k: SieCycle, span: Span) -> Result<Call, Refusal> {
        let mut out = c.clone();
        let kn = self.at.get(&span);
        for (i, p) in k.params().iter().enumerate() {
            let Some(Arg::Value(e)) = out.args.get_mut(i) else { continue };
            if literal(e).is_some() || is_system(e) {
                continue;
            }
            let Some(kn) = kn else { continue };
            match kn.eval(e) {
                Ok(v) => *e = Expr::num(v, true, e.span),
                Err(Miss::Var(key, why)) if !EXPRESSIONS.contains(p) => {
                    return Err(self.refusal(k, p, &key, why));
                }
                Err(_) => {}
            }
        }
        Ok(out)
    }

    fn refusal(&self, k: SieCycle, p: &str, key: &Key, why: Option<known::Why>) -> Refusal {
        let var = key.name();
        let (reason, at) = self.unknown_reason(key, why, "the call");
        (
            "NC660",
            format!("{} with {p} = {var}, which is not one value known at translation: {reason}", k.name()),
            "give the variable one value on every path to the call (a DEF start value or an assignment before it, no other value in an IF, loop or jump between, no call that may write it), or write the number in the call",
            at,
        )
    }

    /// Why `key` is not known at `place` (`"the call"`), and the place that made it so.
    pub fn unknown_reason(&self, key: &Key, why: Option<known::Why>, place: &str) -> (String, Option<(Span, String)>) {
        let var = key.name();
        match why {
            Some(w) => (format!("{var} {}", w.what), Some((w.span, format!("{var} {}", w.what)))),
            None => {
                let never = self.never.get(key).cloned().or_else(|| match key {
                    Key::R(_) => self.r_never.map(str::to_string),
                    Key::Named(_) => None,
                });
                let r = match (never, key) {
                    (Some(n), _) => format!("{var} is {n}"),
                    (None, Key::R(_)) => format!(
                        "{var} is not set in this program on every path to {place} (R parameters are global: it holds what was there before, or what a jump brings)"
                    ),
                    (None, Key::Named(_)) => format!(
                        "{var} is not set in this program on every path to {place} (a parameter holds what the caller passed, a jump brings what was there)"
                    ),
                };
                (r, None)
            }
        }
    }

    /// The value of `e` at the item of span `at` (a word), or why it is not known there.
    pub fn value_at(&self, at: Span, e: &Expr, place: &str) -> Result<f64, String> {
        if let Some(v) = literal(e) {
            return Ok(v);
        }
        let Some(kn) = self.at.get(&at) else { return Err("it is not one value known at translation".into()) };
        match kn.eval(e) {
            Ok(v) => Ok(v),
            Err(Miss::Var(key, why)) => Err(self.unknown_reason(&key, why, place).0),
            Err(Miss::Expr) => Err("it is computed by a function or reads a system variable".into()),
        }
    }
}

/// `$P_EP[Z]`, `$P_F` and the like: forms `plan` reads as they are.
fn is_system(e: &Expr) -> bool {
    matches!(&e.kind, ExprKind::Var(v) if matches!(v.kind, VarKind::System { .. }))
}
