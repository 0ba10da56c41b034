//! Siemens machine signals (`$A_DBB[n]`, `$A_IN[n]` …) → the FANUC interface signal the
//! set-up wires them to (`[signals]`: `"$A_DBB[2]" = "#1002"`), docs/translation.md,
//! Machine signals. A signal with no entry keeps the refusal every unmodelled system
//! variable gets (NC342), naming the key to add; a value the FANUC variable cannot carry (a
//! PLC byte on a bit) only where the program compares it with 0 or 1 (else NC597); a write
//! is refused (NC579: the trace has no signal event, so the proof could not compare it).
//! Runs before the variable mapping, which leaves `#n` alone. The mirror of
//! `to_sinumerik::signals`.

use super::Ctx;
use crate::dialect::signals::{is_siemens_signal, Signal, KEY};
use crate::eval::signals::{RANGE, WRITE};
use crate::ir::*;
use crate::lower::signals::{walk, Use};
use crate::span::Span;

pub fn run(ctx: &mut Ctx, prog: &mut Program) {
    let map = ctx.signals.clone();
    let haas = ctx.haas;
    let mut errs: Vec<(&'static str, Span, String, String)> = Vec::new();
    walk(&mut prog.body, &mut |v, how| {
        let VarKind::System { name, indices } = &v.kind else { return };
        if !is_siemens_signal(name) {
            return;
        }
        let span = v.span;
        let sig = match indices.as_slice() {
            [Expr { kind: ExprKind::Num(x), .. }] if x.value >= 0.0 && x.value.fract() == 0.0 => {
                Signal::siemens(name, x.value as u32)
            }
            _ => None,
        };
        let Some(sig) = sig else {
            let what = format!("system variable ${name} with a computed index");
            errs.push(("NC342", span, what, "write the index as a number: the wiring names each signal".into()));
            v.kind = VarKind::Hash(0);
            return;
        };
        v.kind = VarKind::Hash(0);
        if how == Use::Write {
            let what = format!("writing {}", sig.named());
            let hint = "the trace has no event for signals, so the proof could not compare the write".into();
            errs.push((WRITE, span, what, hint));
            return;
        }
        let Some(f) = map.fanuc_of(sig) else {
            let what = format!("system variable {}", sig.named());
            let hint = format!(
                "give the FANUC interface signal the machine wires it to in nctrans.toml: {KEY} \"{}\" = \"{}\" \
                 (inputs #1000..#1015, #1032; outputs #1100..#1115, #1132; docs/translation.md, Machine signals)",
                sig.key(),
                if sig.kind == crate::dialect::signals::Kind::Out { "#1100" } else { "#1000" }
            );
            errs.push(("NC342", span, what, hint));
            return;
        };
        if haas {
            let what = format!("{} on a Haas control", sig.named());
            let hint = "the Haas table read here lists NGC discrete inputs #11000..#11063 and no outputs; \
                        this translation knows the FANUC interface signals only"
                .into();
            errs.push((RANGE, span, what, hint));
            return;
        }
        if how == (Use::Read { bit_compared: false }) && !sig.range().within(f.range()) {
            let what = format!(
                "{} used as a value ({}) on {} ({})",
                sig.named(),
                sig.range().describe(),
                f.named(),
                f.range().describe()
            );
            let hint = "only a comparison of it with 0 or 1 carries over; compare it (IF $A_DBB[2]==1 …) or wire it \
                        to a FANUC variable that holds its values"
                .into();
            errs.push((RANGE, span, what, hint));
            return;
        }
        v.kind = VarKind::Hash(f.index);
    });
    for (code, span, what, hint) in errs {
        ctx.unsupported(code, span, &what, &hint);
    }
}
