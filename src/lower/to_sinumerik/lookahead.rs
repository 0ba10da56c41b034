//! FANUC look-ahead and high-speed modes → Sinumerik (docs/semantics.md, "Look-ahead and
//! high-speed modes"): `G05.1 Q1`, `G08 P1`, `G05 P10000` (feed planning ahead with
//! feed-forward) → `FFWON`, their `Q0`/`P0` → `FFWOF`; Haas `G187 P1/P2/P3 E` → `CYCLE832(E,
//! 3/2/1, 1)` (rough, medium, finish → roughing, semi-finishing, finishing), bare `G187` →
//! `CYCLE832(0, 0, 1)` (deselection: the machine's default dynamics); Haas `G103`/`G103 P0`
//! (no look-ahead limit, the Sinumerik default) is dropped with a warning, `G103 Pn` (n > 0)
//! is refused (NC562: Sinumerik has no look-ahead limit of n blocks). None of them has a
//! trace event: the check counts them as not compared (`check::Excluded::modes`).

use super::*;
use crate::eval::machine::lookahead::{fanuc_mode, is_mode_g};

/// Rewrites the look-ahead blocks of `body` (every nesting level).
pub fn lower(ctx: &mut Ctx, body: Vec<Stmt>) -> Vec<Stmt> {
    let haas = ctx.opts.source.haas;
    super::map_bodies(body, &mut |list| {
        let mut out = Vec::with_capacity(list.len());
        for s in list {
            match s.kind {
                StmtKind::Block(b) if mode_g(&b, haas).is_some() => out.extend(block(ctx, b, s.span, haas)),
                kind => out.push(Stmt { kind, span: s.span }),
            }
        }
        out
    })
}

/// The look-ahead G code of a block (`g_index` form: 51 for G05.1) and its span.
fn mode_g(b: &Block, haas: bool) -> Option<(i64, Span)> {
    b.items.iter().find_map(|it| match &it.kind {
        ItemKind::Word(Word { addr: Addr::Letter(b'G'), value: WordValue::Expr(e), span }) => {
            let gi = (literal(e)? * 10.0).round() as i64;
            is_mode_g(gi, haas).then_some((gi, *span))
        }
        _ => None,
    })
}

fn letter_value(b: &Block, letter: u8) -> Option<Option<f64>> {
    b.items.iter().find_map(|it| match &it.kind {
        ItemKind::Word(Word { addr: Addr::Letter(l), value: WordValue::Expr(e), .. }) if *l == letter => {
            Some(literal(e))
        }
        _ => None,
    })
}

fn block(ctx: &mut Ctx, mut b: Block, span: Span, haas: bool) -> Vec<Stmt> {
    let Some((gi, gspan)) = mode_g(&b, haas) else { return vec![] };
    // The mode's own words; anything else in the block is refused (FANUC and Haas want the
    // mode in a block of its own).
    let own: &[u8] = match gi {
        51 => b"GQ",
        1870 => b"GPE",
        _ => b"GP",
    };
    let other = b.items.iter().any(|it| match &it.kind {
        ItemKind::Word(Word { addr: Addr::Letter(l), .. }) => !own.contains(l),
        _ => true,
    });
    let (p, q, e) = (letter_value(&b, b'P'), letter_value(&b, b'Q'), letter_value(&b, b'E'));
    let computed = [p, q, e].iter().any(|v| matches!(v, Some(None)));
    let refuse =
        |ctx: &mut Ctx, what: String, hint: &str| ctx.unsupported("NC562", gspan, &what, hint).into_iter().collect();
    if other || computed {
        let what = if other {
            "a look-ahead G code (G05, G05.1, G08, G103, G187) with other words in its block".to_string()
        } else {
            "a look-ahead G code with a computed value".to_string()
        };
        return refuse(ctx, what, "write the mode in a block of its own, with numbers");
    }
    let (p, q, e) = (p.flatten(), q.flatten(), e.flatten());
    let what = match fanuc_mode(gi, p, q, e) {
        Ok(w) => w,
        Err(w) => return refuse(ctx, w, "write the mode with one of the values listed, or remove it"),
    };
    let on = |x: Option<f64>, one: f64| x == Some(one);
    let item = match gi {
        51 | 80 | 50 => {
            let on = match gi {
                51 => on(q, 1.0),
                80 => on(p, 1.0),
                _ => on(p, 10000.0),
            };
            Item { kind: ItemKind::Instruction { name: if on { "FFWON" } else { "FFWOF" }.into() }, span: gspan }
        }
        1870 => {
            let Some(level) = p else {
                if e.is_some() {
                    return refuse(
                        ctx,
                        format!("{what} without P (the smoothness of Setting 191 is not in the program)"),
                        "write G187 P1, P2 or P3 with the E tolerance",
                    );
                }
                return vec![cycle832(b, gspan, 0.0, 0)];
            };
            let Some(tol) = e else {
                return refuse(
                    ctx,
                    format!("{what} without E (the corner tolerance of Setting 85 is not in the program)"),
                    "write the tolerance as G187 P.. E..",
                );
            };
            // Rough, medium, finish → CYCLE832 roughing (3), semi-finishing (2), finishing (1).
            return vec![cycle832(b, gspan, tol, 4 - level as i64)];
        }
        _ => {
            if p.is_some_and(|n| n != 0.0) {
                return refuse(
                    ctx,
                    what,
                    "Sinumerik has no limit of look-ahead to n blocks; STOPRE before a block stops the preprocessing there",
                );
            }
            ctx.warn(
                "NC562",
                gspan,
                format!("{what} dropped: Sinumerik looks ahead without a limit by default"),
                "dropped",
            );
            b.items.clear();
            return (b.meta.number.is_some() || b.meta.label.is_some() || !b.meta.comments.is_empty())
                .then(|| block_stmt(b.meta, vec![]))
                .into_iter()
                .collect();
        }
    };
    b.items = vec![item];
    vec![Stmt { kind: StmtKind::Block(b), span }]
}

/// `CYCLE832(tol, tolm, 1)` in the place of the block `b`: the third argument 1 is the
/// version identifier for a program without tool orientation (programming manual).
fn cycle832(mut b: Block, span: Span, tol: f64, tolm: i64) -> Stmt {
    let call = Call {
        kind: CallKind::Named,
        target: CallTarget::Name("CYCLE832".into()),
        args: vec![Arg::Value(num(tol, span)), Arg::Value(int(tolm, span)), Arg::Value(int(1, span))],
        repeat: None,
    };
    b.items = vec![Item { kind: ItemKind::Call(Box::new(call)), span }];
    let s = b.meta.span;
    Stmt { kind: StmtKind::Block(b), span: s }
}
