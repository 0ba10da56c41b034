//! Siemens interrupts to FANUC's custom macro interrupt: `SETINT(1) PRIO=p NAME` becomes
//! `M96 P<O number of NAME>`, `DISABLE(1)` and `CLRINT(1)` `M97`, `ENABLE(1)` `M96 P…` again,
//! only where the target profile says the machine has it (`Semantics::macro_interrupt`).
//! FANUC has one interrupt signal, so only input 1 maps (docs/translation.md, "Interrupts").

use super::Ctx;
use crate::ir::interrupt::{op_of, IntOp};
use crate::ir::{Addr, Expr, Item, ItemKind, ProgName, Stmt, Word, WordValue};
use crate::span::Span;

/// The FANUC words of one Siemens interrupt instruction, or the refusal (a marked line under
/// `--unsupported warn`).
pub fn lower(ctx: &mut Ctx, name: &str, span: Span) -> Result<Vec<Item>, Option<Stmt>> {
    if !ctx.macro_interrupt {
        return Err(ctx.unsupported(
            "NC566",
            span,
            &format!("{name} (an interrupt routine for an input)"),
            "the profile does not say this machine has FANUC's custom macro interrupt (M96 P… / M97 on the UINT \
             signal, set up by parameter 6003 and the wiring); set `[fanuc] macro_interrupt = true` in nctrans.toml \
             where it has, or call the routine where the program needs it",
        ));
    }
    let op = match op_of(name) {
        Some(Ok(op)) => op,
        Some(Err(msg)) => {
            return Err(ctx.unsupported("NC638", span, &msg, "write SETINT(1) PRIO=1 NAME with constants"))
        }
        None => return Ok(vec![]),
    };
    let input = match &op {
        IntOp::Assign { input, .. } | IntOp::Enable(input) | IntOp::Disable(input) | IntOp::Clear(input) => *input,
    };
    if input != 1 {
        return Err(ctx.unsupported(
            "NC640",
            span,
            &format!("{name} (interrupt input {input})"),
            "FANUC's custom macro interrupt has one signal (UINT), which nctrans maps to Siemens input 1; \
             rewire the input to 1 or call the routine where the program needs it",
        ));
    }
    let number = match op {
        IntOp::Assign { extra, .. } if !extra.is_empty() => {
            return Err(ctx.unsupported(
                "NC639",
                span,
                &format!("{name} ({} has no counterpart in M96)", extra.join(", ")),
                "LIFTFAST's fast lift and BLSYNC's end of block are Siemens settings FANUC's M96 does not take; \
                 program the retract inside the routine",
            ))
        }
        IntOp::Assign { routine: ProgName::Name(r), .. } => match ctx.callees.get(&r) {
            Some(c) => {
                if ctx.int_routine.is_some_and(|n| n != c.number) {
                    ctx.int_routine_changes = true;
                }
                ctx.int_routine = Some(c.number);
                c.number
            }
            None => {
                return Err(ctx.unsupported(
                    "NC640",
                    span,
                    &format!("{name} (routine {r} not found)"),
                    &format!("put {r}.SPF beside the program: the routine is translated as a subprogram"),
                ))
            }
        },
        IntOp::Assign { routine: ProgName::Number(n), .. } => n,
        IntOp::Enable(_) => match ctx.int_routine {
            Some(n) if !ctx.int_routine_changes => n,
            _ => {
                return Err(ctx.unsupported(
                    "NC640",
                    span,
                    &format!("{name} (which routine it enables is not one SETINT before it)"),
                    "FANUC's M96 names the program it enables; write SETINT(1) PRIO=1 NAME instead of ENABLE(1)",
                ))
            }
        },
        IntOp::Disable(_) | IntOp::Clear(_) => return Ok(vec![m_word(97.0, span)]),
    };
    Ok(vec![m_word(96.0, span), word(b'P', f64::from(number), span)])
}

fn m_word(n: f64, span: Span) -> Item {
    word(b'M', n, span)
}

fn word(letter: u8, n: f64, span: Span) -> Item {
    let w = Word { addr: Addr::Letter(letter), value: WordValue::Expr(Expr::num(n, false, span)), span };
    Item { kind: ItemKind::Word(w), span }
}
