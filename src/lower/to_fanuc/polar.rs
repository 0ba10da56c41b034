//! Sinumerik → FANUC: polar coordinates (docs/translation.md, "Coordinate systems").
//!
//! A move with `AP=` and `RP=` about a pole set by `G111 X a Y b` (or about the workpiece
//! zero where none is set) becomes the Cartesian point `X[a+r*COS[θ]] Y[b+r*SIN[θ]]`, which
//! FANUC works out as Sinumerik does; the `G111` block itself moves nothing and goes.
//!
//! The pole must be known from the text: the last `G111` with constants before the move in
//! the same statement list, with no jump target, subprogram call or structure between (at
//! the start of a main program: the workpiece zero); so must an angle or radius the move
//! leaves out (the stored one, a constant) or adds to (`AP=IC(..)` on a constant). A polar
//! arc (its centre is the pole), G110/G112 (relative poles), a program that selects
//! G18/G19, and a called program are refused (NC498).

use super::*;

/// A polar block's start, its pole, angle and radius (`None`: not known from the text).
type PolarAt = (u32, Option<(Expr, Expr)>, Option<Expr>, Option<Expr>);

/// The pole in force at each polar block (the start of its first item), found once.
#[derive(Clone, Debug, Default)]
pub struct Poles {
    /// Per polar block: the pole, and the angle and radius it goes to (`None`: not known).
    at: Vec<PolarAt>,
    g17: bool,
}

fn constant(e: &Expr) -> Option<f64> {
    match &e.kind {
        ExprKind::Num(n) => Some(n.value),
        ExprKind::Unary(UnOp::Neg, a) => constant(a).map(|v| -v),
        _ => None,
    }
}

/// The value a polar word gives with `stored` in force: its own (absolute), or `IC(v)` on
/// a constant stored value (the sum, a constant); none: the stored one.
fn polar_value(w: Option<&Word>, stored: &Option<Expr>) -> Option<Expr> {
    match w.map(|w| &w.value) {
        None => stored.clone(),
        Some(WordValue::Expr(e) | WordValue::Ac(e)) => Some(e.clone()),
        Some(WordValue::Ic(e)) => {
            let sum = constant(stored.as_ref()?)? + constant(e)?;
            Some(Expr::num(sum, true, e.span))
        }
        Some(WordValue::Rotary(..)) => None,
    }
}

fn g_const(it: &Item) -> Option<f64> {
    match &it.kind {
        ItemKind::Word(Word {
            addr: Addr::Letter(b'G'),
            value: WordValue::Expr(Expr { kind: ExprKind::Num(n), .. }),
            ..
        }) => Some(n.value),
        _ => None,
    }
}

fn named<'a>(b: &'a Block, name: &str) -> Option<&'a Word> {
    b.items.iter().rev().find_map(|it| match &it.kind {
        ItemKind::Word(w) if matches!(&w.addr, Addr::Name(n) if n.as_ref() == name) => Some(w),
        _ => None,
    })
}

fn letter(b: &Block, l: u8) -> Option<&Expr> {
    b.items.iter().rev().find_map(|it| match &it.kind {
        ItemKind::Word(Word { addr: Addr::Letter(c), value: WordValue::Expr(e), .. }) if *c == l => Some(e),
        _ => None,
    })
}

fn scan(body: &[Stmt], start: Option<(Expr, Expr)>, jumps: &crate::lower::landings::Landings, poles: &mut Poles) {
    let mut pole = start;
    let (mut ap, mut rp): (Option<Expr>, Option<Expr>) = (None, None);
    for s in body {
        let StmtKind::Block(b) = &s.kind else {
            for child in crate::ir::visit::child_bodies(&s.kind) {
                scan(child, None, jumps, poles);
            }
            (pole, ap, rp) = (None, None, None);
            continue;
        };
        if jumps.at(&b.meta) {
            (pole, ap, rp) = (None, None, None);
        }
        let gs: Vec<f64> = b.items.iter().filter_map(g_const).collect();
        if gs.iter().any(|&g| g == 18.0 || g == 19.0) {
            poles.g17 = false;
        }
        if gs.contains(&111.0) {
            let c = |l| letter(b, l).filter(|e| matches!(e.kind, ExprKind::Num(_))).cloned();
            pole = match (c(b'X'), c(b'Y')) {
                (Some(x), Some(y)) => Some((x, y)),
                _ => None,
            };
            // A new pole: the angle and radius are written again (828D manual: "after
            // changing the pole").
            (ap, rp) = (None, None);
        } else if gs.contains(&110.0) || gs.contains(&112.0) || gs.iter().any(|&g| g == 18.0 || g == 19.0 || g == 17.0)
        {
            (pole, ap, rp) = (None, None, None);
        }
        let (apw, rpw) = (named(b, "AP"), named(b, "RP"));
        if apw.is_some() || rpw.is_some() {
            let first = b.items.first().map_or(b.meta.span.lo, |it| it.span.lo);
            ap = polar_value(apw, &ap);
            rp = polar_value(rpw, &rp);
            poles.at.push((first, pole.clone(), ap.clone(), rp.clone()));
        }
        // A subprogram may set a pole of its own; a drilling cycle does not.
        let call = b.items.iter().any(|it| match &it.kind {
            ItemKind::Call(c) => !matches!(&c.target, CallTarget::Name(n) if n.starts_with("CYCLE")),
            _ => false,
        });
        if call {
            (pole, ap, rp) = (None, None, None);
        }
    }
}

/// The poles of a program (`main`: not a called one).
pub fn poles(body: &[Stmt], main: bool) -> Poles {
    let zero = |span| Expr::num(0.0, true, span);
    let start = main.then(|| (zero(Span::default()), zero(Span::default())));
    let mut p = Poles { at: Vec::new(), g17: main };
    scan(body, start, &crate::lower::landings::Landings::of(body), &mut p);
    p
}

fn refuse(ctx: &mut Ctx, span: Span, what: &str, hint: &str) -> Vec<Stmt> {
    ctx.unsupported("NC498", span, what, hint).into_iter().collect()
}

/// Rewrites a G111 block (it goes) or a polar move (Cartesian words); `Some`: the block
/// was refused or emptied.
pub fn block(ctx: &mut Ctx, b: &mut Block, poles: &Poles) -> Option<Vec<Stmt>> {
    let gs: Vec<f64> = b.items.iter().filter_map(g_const).collect();
    let span = b.meta.span;
    let pole_block = gs.iter().any(|g| [110.0, 111.0, 112.0].contains(g));
    let (ap, rp) = (named(b, "AP"), named(b, "RP"));
    if !pole_block && ap.is_none() && rp.is_none() {
        return None;
    }
    if pole_block {
        if gs.contains(&111.0) && ap.is_none() && rp.is_none() && letter(b, b'X').is_some() && letter(b, b'Y').is_some()
        {
            // The pole is read by the polar moves after it; the block itself moves nothing.
            b.items.retain(|it| {
                !matches!(g_const(it), Some(g) if g == 111.0)
                    && !matches!(&it.kind, ItemKind::Word(Word { addr: Addr::Letter(b'X' | b'Y' | b'Z'), .. }))
            });
            if b.items.is_empty() && b.meta.number.is_none() && b.meta.label.is_none() && b.meta.comments.is_empty() {
                return Some(Vec::new());
            }
            return None;
        }
        return Some(refuse(
            ctx,
            span,
            "a pole other than `G111 X.. Y..` (G110/G112, or in polar form)",
            "set the pole with G111 X.. Y..",
        ));
    }
    let first = b.items.first().map_or(span.lo, |it| it.span.lo);
    let found = poles.at.iter().find(|p| p.0 == first);
    let pole = found.and_then(|p| p.1.clone());
    let (Some(a), Some(r)) = (found.and_then(|p| p.2.clone()), found.and_then(|p| p.3.clone())) else {
        return Some(refuse(
            ctx,
            span,
            "a polar move whose angle or radius is not known from the text (left out since the pole was set, or IC() on a value that is not a constant)",
            "write AP= and RP= after each G111, as constants where AP=IC(..) adds to them",
        ));
    };
    let arc = gs.iter().any(|&g| g == 2.0 || g == 3.0);
    let Some((px, py)) = pole.filter(|_| poles.g17 && !arc) else {
        return Some(refuse(
            ctx,
            span,
            "a polar move where the pole is not known from the text, in a called program or one that selects G18/G19, or a polar arc",
            "set the pole with `G111 X.. Y..` (constants) before the polar moves, in the main program, in G17",
        ));
    };
    let coord = |p: Expr, f: Func| bin(BinOp::Add, p, bin(BinOp::Mul, r.clone(), func(f, vec![a.clone()], span)));
    b.items.retain(
        |it| !matches!(&it.kind, ItemKind::Word(Word { addr: Addr::Name(n), .. }) if matches!(n.as_ref(), "AP" | "RP")),
    );
    for (l, e) in [(b'X', coord(px, Func::Cos)), (b'Y', coord(py, Func::Sin))] {
        b.items.push(item(ItemKind::Word(Word { addr: Addr::Letter(l), value: WordValue::Expr(e), span }), span));
    }
    None
}
