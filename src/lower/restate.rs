//! Literal numbers restated for another control profile under the FANUC rules: a unit read
//! with one profile (say calculator-type input, `X10` = 10 mm) that is to be written for
//! another (IS-B, `X10` = 0.010 mm) keeps its meaning only if every length or angle written
//! without a decimal point is written with one, in units. Used by the generic entry's
//! lowerings (the built-in FANUC description and any dialect that runs as FANUC); the
//! letters it restates are also the FANUC → Sinumerik lowering's (`to_sinumerik::words`).

use crate::diag::Diagnostic;
use crate::dialect::{Dialect, Semantics};
use crate::ir::*;

/// Letters whose values are lengths or angles (scaled by the increment without a point).
pub fn scaled_letter(l: u8) -> bool {
    matches!(l, b'X' | b'Y' | b'Z' | b'U' | b'V' | b'W' | b'A' | b'B' | b'C' | b'I' | b'J' | b'K' | b'R' | b'Q')
}

/// Letters whose bare values count the metric increment whatever the unit: angles.
pub fn rotary_letter(l: u8) -> bool {
    matches!(l, b'A' | b'B' | b'C')
}

/// Whether `s` reads a length written without a decimal point in increments.
fn scales(s: &Semantics) -> bool {
    s.increment_scaling && !s.calculator_input
}

/// Rewrites every bare literal length or angle of `unit` (read with `from`) as a literal
/// with a decimal point, in units, so that it reads the same with `to`. Nothing changes
/// for a Siemens unit (no increment scaling) or when both profiles read bare values alike.
/// A value whose unit (G20 inch or G21 mm) depends on the path taken is refused (NC517).
pub fn restate(unit: &mut Unit, from: &Semantics, to: &Semantics) -> Vec<Diagnostic> {
    let same = scales(from) == scales(to) && (!scales(from) || from.least_increment_mm == to.least_increment_mm);
    if unit.dialect != Dialect::Fanuc || same {
        return vec![];
    }
    let straight = unit.programs.len() == 1
        && unit.programs[0].body.iter().all(|s| match &s.kind {
            StmtKind::Block(b) => b.items.iter().all(|i| !matches!(i.kind, ItemKind::Goto(_) | ItemKind::Call(_))),
            _ => false,
        });
    let mut w = Walk { from, inch: false, path_units: false, diags: vec![], file: unit.file };
    w.path_units = scales(from) && !straight && unit.programs.iter().any(|p| mentions_inch(&p.body));
    for p in &mut unit.programs {
        w.inch = false;
        w.body(&mut p.body);
    }
    w.diags
}

struct Walk<'a> {
    from: &'a Semantics,
    /// G20 in force, in text order (exact for straight-line code).
    inch: bool,
    /// The unit of a bare length depends on the path: such a length is refused.
    path_units: bool,
    diags: Vec<Diagnostic>,
    file: crate::span::FileId,
}

fn g_value(it: &Item) -> Option<f64> {
    match &it.kind {
        ItemKind::Word(Word { addr: Addr::Letter(b'G'), value: WordValue::Expr(e), .. }) => match e.kind {
            ExprKind::Num(n) => Some(n.value),
            _ => None,
        },
        _ => None,
    }
}

fn mentions_inch(body: &[Stmt]) -> bool {
    let mut found = false;
    crate::ir::visit::walk_stmts(body, &mut |s: &Stmt| {
        if let StmtKind::Block(b) = &s.kind {
            found |= b.items.iter().any(|i| g_value(i) == Some(20.0));
        }
    });
    found
}

impl Walk<'_> {
    fn body(&mut self, body: &mut [Stmt]) {
        for s in body {
            if let StmtKind::Block(b) = &mut s.kind {
                self.block(&mut b.items);
            } else {
                for inner in crate::ir::visit::child_bodies_mut(&mut s.kind) {
                    self.body(inner);
                }
            }
        }
    }

    fn block(&mut self, items: &mut [Item]) {
        for i in items.iter() {
            match g_value(i) {
                Some(20.0) => self.inch = true,
                Some(21.0) => self.inch = false,
                _ => {}
            }
        }
        // G04 X is a dwell in seconds, counted in the metric increment like an angle.
        let dwell = items.iter().any(|i| g_value(i) == Some(4.0));
        for i in items {
            self.item(i, dwell);
        }
    }

    fn item(&mut self, it: &mut Item, dwell: bool) {
        match &mut it.kind {
            ItemKind::Word(w) => self.word(w, dwell),
            ItemKind::IfThen { then, .. } => self.item(then, dwell),
            ItemKind::IfBlock { items, .. } => items.iter_mut().for_each(|i| self.item(i, dwell)),
            _ => {}
        }
    }

    fn word(&mut self, w: &mut Word, dwell: bool) {
        let Addr::Letter(l) = w.addr else { return };
        let WordValue::Expr(e) = &mut w.value else { return };
        if !scaled_letter(l) {
            return;
        }
        let num = match &mut e.kind {
            ExprKind::Num(n) => n,
            ExprKind::Unary(UnOp::Neg, a) => match &mut a.kind {
                ExprKind::Num(n) => n,
                _ => return,
            },
            _ => return,
        };
        if num.point {
            return;
        }
        let rotary = rotary_letter(l) || (dwell && l == b'X');
        if scales(self.from) {
            if self.path_units && !rotary {
                self.diags.push(
                    Diagnostic::error("NC517", "a length without a decimal point whose unit (G20 or G21) depends on the path taken")
                        .primary(self.file, w.span, "read in increments of the unit in force here")
                        .note("the target reads values without a decimal point differently, so it is written in units, and the unit is not known")
                        .hint("write the value with a decimal point (`X10.`), or select G20/G21 before it on every path"),
                );
                return;
            }
            let inc = self.from.input_increment(self.inch, rotary);
            // The increment's decimals, so 10 × 0.001 is 0.01 and not 0.010000000000000002.
            let digits = (-inc.log10()).ceil().max(0.0) as i32 + 1;
            let f = 10f64.powi(digits);
            num.value = (num.value * inc * f).round() / f;
        }
        num.point = true;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dialect::{ParseOptions, Semantics};
    use crate::span::SourceFile;

    fn read(text: &str) -> Unit {
        let src = SourceFile::new("t.nc", text);
        let p = crate::dialect::parse(&src, 0, Dialect::Fanuc, &ParseOptions::for_dialect(Dialect::Fanuc));
        assert!(p.diags.is_empty(), "{:?}", p.diags);
        p.unit
    }

    fn calculator() -> Semantics {
        Semantics { calculator_input: true, ..Semantics::default_for(Dialect::Fanuc) }
    }

    fn words(u: &Unit) -> Vec<(f64, bool)> {
        let mut out = vec![];
        crate::ir::visit::walk_stmts(&u.programs[0].body, &mut |s: &Stmt| {
            if let StmtKind::Block(b) = &s.kind {
                for i in &b.items {
                    if let ItemKind::Word(Word { addr: Addr::Letter(b'X'), value: WordValue::Expr(e), .. }) = &i.kind {
                        if let ExprKind::Num(n) = e.kind {
                            out.push((n.value, n.point));
                        }
                    }
                }
            }
        });
        out
    }

    #[test]
    fn increments_become_units_in_the_unit_in_force() {
        let mut u = read("%\nO1\nG1 X10 F100\nG20\nG1 X10\nG4 X1000\nG1 X2.5\nM30\n%\n");
        let d = restate(&mut u, &Semantics::default_for(Dialect::Fanuc), &calculator());
        assert!(d.is_empty(), "{d:?}");
        // Metric 0.001 mm, inch 0.0001 in, a dwell in the metric increment (seconds).
        assert_eq!(words(&u), vec![(0.01, true), (0.001, true), (1.0, true), (2.5, true)]);
    }

    #[test]
    fn units_become_points_and_alike_profiles_change_nothing() {
        let mut u = read("%\nO1\nG1 X10 F100\nM30\n%\n");
        assert!(restate(&mut u, &calculator(), &Semantics::default_for(Dialect::Fanuc)).is_empty());
        assert_eq!(words(&u), vec![(10.0, true)]);
        let mut u = read("%\nO1\nG1 X10 F100\nM30\n%\n");
        let fanuc = Semantics::default_for(Dialect::Fanuc);
        assert!(restate(&mut u, &fanuc, &fanuc).is_empty());
        assert_eq!(words(&u), vec![(10.0, false)]);
    }

    #[test]
    fn a_unit_that_depends_on_the_path_is_refused() {
        let mut u = read("%\nO1\nIF[#1EQ1]GOTO5\nG20\nN5 G1 X10 F100\nM30\n%\n");
        let d = restate(&mut u, &Semantics::default_for(Dialect::Fanuc), &calculator());
        assert_eq!(d.iter().map(|d| d.code).collect::<Vec<_>>(), vec!["NC517"]);
    }
}
