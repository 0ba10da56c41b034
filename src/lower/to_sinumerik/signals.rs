//! FANUC interface signals (`#1000..#1015`, `#1032`, `#1100..#1115`, `#1132`) → the Siemens
//! signal the set-up wires them to (`[signals]`: `"$A_DBB[2]" = "#1002"`), docs/translation.md,
//! Machine signals. The mirror of `to_fanuc::signals`: a signal with no entry keeps the
//! refusal of every system variable without a counterpart (NC365), naming the key to add;
//! a value the Siemens signal cannot carry (the 16 inputs at once on a byte) only where the
//! program compares it with 0 or 1 (else NC597); a write is refused (NC579: the trace has no
//! signal event, so the proof could not compare it). Runs first on a body, while the
//! variables are still FANUC's; a Haas source is left alone (its inputs are numbered otherwise).

use super::Ctx;
use crate::dialect::signals::{Signal, KEY};
use crate::eval::signals::{RANGE, WRITE};
use crate::ir::*;
use crate::lower::signals::{walk, Use};
use crate::span::Span;

pub fn lower(ctx: &mut Ctx, mut body: Vec<Stmt>) -> Vec<Stmt> {
    if ctx.opts.source.haas {
        return body;
    }
    let map = ctx.opts.source.signals.clone();
    let mut errs: Vec<(&'static str, Span, String, String)> = Vec::new();
    walk(&mut body, &mut |v, how| {
        let VarKind::Hash(n) = v.kind else { return };
        let Some(f) = Signal::fanuc(n) else { return };
        let span = v.span;
        let unsupported = VarKind::Named { name: format!("NCTRANS_UNSUPPORTED_{n}"), indices: vec![] };
        if how == Use::Write {
            let what = format!("writing {}", f.named());
            let hint = "the trace has no event for signals, so the proof could not compare the write".into();
            errs.push((WRITE, span, what, hint));
            v.kind = unsupported;
            return;
        }
        let Some(sig) = map.siemens_of(f) else {
            let what = format!("the system variable {}", f.named());
            let hint = format!(
                "give the Siemens signal the machine wires it to in nctrans.toml: {KEY} \"{}\" = \"{}\" \
                 (docs/translation-fanuc-to-sinumerik.md, Machine signals)",
                if f.read_only() { "$A_DBB[..]" } else { "$A_OUT[..]" },
                f.key()
            );
            errs.push(("NC365", span, what, hint));
            v.kind = unsupported;
            return;
        };
        if how == (Use::Read { bit_compared: false }) && !f.range().within(sig.range()) {
            let what = format!(
                "{} used as a value ({}) on {} ({})",
                f.named(),
                f.range().describe(),
                sig.named(),
                sig.range().describe()
            );
            let hint = "only a comparison of it with 0 or 1 carries over; compare it or wire it to a Siemens signal \
                        that holds its values"
                .into();
            errs.push((RANGE, span, what, hint));
            v.kind = unsupported;
            return;
        }
        let name = sig.key();
        let name = name[1..name.find('[').unwrap_or(name.len())].to_string();
        v.kind = VarKind::System { name, indices: vec![Expr::num(f64::from(sig.index), false, span)] };
    });
    for (code, span, what, hint) in errs {
        ctx.unsupported(code, span, &what, &hint);
    }
    body
}
