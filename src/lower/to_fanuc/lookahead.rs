//! Sinumerik look-ahead and high-speed settings → FANUC (docs/semantics.md, "Look-ahead and
//! high-speed modes"): `FFWON`/`FFWOF` → `G05.1 Q1`/`G05.1 Q0` (AI contour control, which
//! includes feed-forward); `CYCLE832(tol, type, …)` → `G05.1 Q1` (type 1–4) or `G05.1 Q0`
//! (type 0) with a note that the tolerance stays with the FANUC parameters, and for a Haas
//! target → `G187 P1/P2/P3 E tol` (roughing, semi-finishing, finishing / smooth finishing)
//! or a bare `G187` (deselection). Haas has no feed-forward switch: `FFWON` is dropped there
//! with note NC323. Each setting is written in a block of its own, as FANUC wants it; none
//! has a trace event, and the check counts them as not compared (`check::Excluded::modes`).

use super::*;
use crate::eval::cycle832::named_type;
use crate::eval::machine::lookahead::cycle832_type;
use crate::lower::literal;

fn word(letter: u8, v: f64, point: bool, span: Span) -> Item {
    let e = Expr::num(v, point, span);
    Item { kind: ItemKind::Word(Word { addr: Addr::Letter(letter), value: WordValue::Expr(e), span }), span }
}

fn block(items: Vec<Item>, span: Span) -> Stmt {
    super::block_stmt(items, span)
}

/// `G05.1 Q1` / `G05.1 Q0`.
fn aicc(on: bool, span: Span) -> Stmt {
    block(vec![word(b'G', 5.1, true, span), word(b'Q', if on { 1.0 } else { 0.0 }, false, span)], span)
}

/// The block an `FFWON`/`FFWOF` becomes; `None` for a Haas target (no such switch).
pub fn feed_forward(ctx: &Ctx, on: bool, span: Span) -> Option<Stmt> {
    (!ctx.haas).then(|| aicc(on, span))
}

/// The block a `CYCLE832(…)` call becomes, or its refusal (`Err` with the marked comment
/// under the warn policy).
pub fn cycle832(ctx: &mut Ctx, c: &Call, span: Span) -> Result<Stmt, Option<Stmt>> {
    let arg = |i: usize| -> Option<Option<f64>> {
        match c.args.get(i) {
            None | Some(Arg::Omitted(_)) => Some(None),
            Some(a) if i == 1 && named_type(a).is_some() => Some(named_type(a)),
            Some(Arg::Value(e)) | Some(Arg::Letter { value: e, .. }) => literal(e).map(Some),
        }
    };
    let (Some(tol), Some(tolm)) = (arg(0), arg(1)) else {
        return Err(ctx.unsupported(
            "NC563",
            span,
            "CYCLE832 with a computed tolerance or machining type",
            "write CYCLE832 with numbers (or _OFF/_FINISH/_SEMIFIN/_ROUGH)",
        ));
    };
    let m = tolm.unwrap_or(0.0);
    let units = (m >= 0.0 && m.fract() == 0.0).then_some((m as i64) % 10).filter(|u| cycle832_type(*u).is_some());
    let Some(units) = units else {
        return Err(ctx.unsupported(
            "NC563",
            span,
            &format!("CYCLE832 with machining type {m}"),
            "the units digit of the machining type is 0 to 4",
        ));
    };
    if ctx.haas {
        if units == 0 {
            return Ok(block(vec![word(b'G', 187.0, false, span)], span));
        }
        let Some(tol) = tol.filter(|t| *t > 0.0) else {
            return Err(ctx.unsupported(
                "NC563",
                span,
                "CYCLE832 without a tolerance for Haas G187",
                "write the tolerance as the first argument",
            ));
        };
        // Roughing → P1 (rough), semi-finishing → P2 (medium), finishing and smooth
        // finishing → P3 (finish).
        let level = match units {
            3 => 1.0,
            2 => 2.0,
            _ => 3.0,
        };
        return Ok(block(
            vec![word(b'G', 187.0, false, span), word(b'P', level, false, span), word(b'E', tol, true, span)],
            span,
        ));
    }
    if units != 0 {
        ctx.note(
            "NC563",
            span,
            "CYCLE832 becomes G05.1 Q1 (AI contour control)",
            "its tolerance and machining type are FANUC parameters (not written); nothing of it is compared",
        );
    }
    Ok(aicc(units != 0, span))
}
