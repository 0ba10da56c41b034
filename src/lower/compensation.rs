//! Tool compensation is refused in translation, both directions, until the trace compares it.
//!
//! The trace holds programmed positions; neither the tool length nor the cutter radius the
//! machine applies is in it, so two programs that compensate differently trace alike. And the
//! dialects spell compensation differently: Siemens `T6 D1` applies length and radius of
//! cutting edge 1 of tool 6 (FANUC needs `G43 H6` and a `D` radius register); FANUC `G41 D04`
//! takes radius register 4 (Siemens `D4` is cutting edge 4 of the active tool). Copying the
//! words would change which length or radius the machine applies, and the check could not
//! see it. So every block with a compensation word is refused here, in one place, to be lifted
//! when the evaluator models compensation: Siemens `D` (also `D0`), `G40/G41/G42`; FANUC `D`,
//! `H`, `G40`…`G49` (radius, length, offset increase/decrease, cancel). `G65` arguments `D`/`H`
//! are call arguments, not words, and are not affected.

use crate::dialect::Dialect;
use crate::ir::*;
use crate::span::Span;

/// The diagnostic code of the refusal (both directions).
pub const CODE: &str = "NC385";

/// The hint every refusal carries.
pub const HINT: &str = "nctrans cannot yet prove which tool length or radius the machine applies; \
translate the compensation by hand (FANUC G43 H / G41 D register, Siemens D cutting edge) and prove it on the machine";

/// A compensation word found in a block.
#[derive(Clone, Debug, PartialEq)]
pub struct Found {
    /// What it is, for the diagnostic: "tool radius compensation `G41`".
    pub what: String,
    pub span: Span,
}

/// The first compensation word among a block's items, read in the `source` dialect.
pub fn in_block(items: &[Item], source: Dialect) -> Option<Found> {
    items.iter().find_map(|it| in_item(it, source))
}

fn in_item(it: &Item, source: Dialect) -> Option<Found> {
    match &it.kind {
        ItemKind::Word(w) => in_word(w, source),
        ItemKind::IfThen { then, .. } => in_item(then, source),
        _ => None,
    }
}

fn in_word(w: &Word, source: Dialect) -> Option<Found> {
    let Addr::Letter(l) = w.addr else { return None };
    let found = |what: String| {
        Some(Found { what: format!("{what} (the trace does not compare tool compensation yet)"), span: w.span })
    };
    match l {
        b'D' if source == Dialect::Sinumerik => {
            found("the cutting edge `D` (tool length and radius compensation)".into())
        }
        b'D' => found("the radius offset register `D` (tool radius compensation)".into()),
        b'H' if source == Dialect::Fanuc => found("the length offset register `H` (tool length compensation)".into()),
        b'G' => {
            let WordValue::Expr(Expr { kind: ExprKind::Num(n), .. }) = &w.value else { return None };
            let g = (n.value * 10.0).round() as i64;
            let name = if g % 10 == 0 { format!("G{}", g / 10) } else { format!("G{}.{}", g / 10, g % 10) };
            match (source, g) {
                (_, 400..=420) => found(format!("tool radius compensation `{name}`")),
                (Dialect::Fanuc, 430..=449 | 490..=499) => found(format!("tool length compensation `{name}`")),
                (Dialect::Fanuc, 450..=489) => found(format!("tool offset `{name}`")),
                _ => None,
            }
        }
        _ => None,
    }
}

/// The first compensation word anywhere in a program body (for `check`, which must not
/// call two programs equivalent when either compensates).
pub fn in_body(body: &[Stmt], source: Dialect) -> Option<Found> {
    let mut first = None;
    crate::ir::visit::walk_stmts(body, &mut |s| {
        if first.is_none() {
            if let StmtKind::Block(b) = &s.kind {
                first = in_block(&b.items, source);
            }
        }
    });
    first
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dialect::ParseOptions;
    use crate::span::SourceDb;

    fn first(text: &str, d: Dialect) -> Option<String> {
        let mut db = SourceDb::new();
        let f = db.add("t", text.to_string());
        let p = crate::parse(&db, f, d, &ParseOptions::for_dialect(d));
        p.unit.programs.first().and_then(|p| in_body(&p.body, d)).map(|f| f.what)
    }

    #[test]
    fn compensation_words_of_both_dialects_are_found() {
        assert!(first("T6 D1\nM30\n", Dialect::Sinumerik).unwrap().contains("`D`"));
        assert!(first("D0\nM30\n", Dialect::Sinumerik).is_some());
        assert!(first("G41 X1 Y1\nM30\n", Dialect::Sinumerik).unwrap().contains("G41"));
        assert!(first("G40\nM30\n", Dialect::Sinumerik).is_some());
        assert_eq!(first("T6 M6\nH1\nG1 X1 F100\nM30\n", Dialect::Sinumerik), None);
        assert!(first("%\nO1\nG43 H6 Z50.\nM30\n%\n", Dialect::Fanuc).unwrap().contains("G43"));
        assert!(first("%\nO1\nG49\nM30\n%\n", Dialect::Fanuc).is_some());
        assert!(first("%\nO1\nG41 D04 X1.\nM30\n%\n", Dialect::Fanuc).unwrap().contains("G41"));
        assert_eq!(first("%\nO1\nG65 P9000 D5. H2.\nM30\n%\n", Dialect::Fanuc), None);
        assert_eq!(first("%\nO1\nG54 G90 G0 X0\nM30\n%\n", Dialect::Fanuc), None);
    }
}
