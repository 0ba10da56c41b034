//! FANUC's custom macro interrupt to Siemens: `M96 P9000` becomes `SETINT(1) PRIO=1 <name of
//! O9000>` (the one signal is input 1, its routine the translated subprogram), `M97`
//! `DISABLE(1)` (the assignment stays, as FANUC's next `M96 P…` names it again). Read as
//! interrupts only where the source profile has `[fanuc] macro_interrupt = true`.

use super::Ctx;
use crate::ir::interrupt::{op_of, IntOp};
use crate::ir::{Item, ItemKind, ProgName, Stmt};
use crate::span::Span;

/// The Siemens instruction of one FANUC interrupt instruction, or the refusal.
pub fn lower(ctx: &mut Ctx, name: &str, span: Span) -> Result<Item, Option<Stmt>> {
    let text = match op_of(name) {
        Some(Ok(IntOp::Assign { routine: ProgName::Number(n), .. })) => match ctx.program_by_number(n) {
            Some(i) => format!("SETINT(1) PRIO=1 {}", ctx.progs[i].name),
            None => {
                return Err(ctx.refuse(
                    "NC640",
                    span,
                    &format!("the interrupt program O{n} was not found"),
                    &format!("{name} (interrupt program O{n} missing)"),
                    &format!("put O{n:04} in the same file, or beside it as O{n:04}.nc"),
                ))
            }
        },
        Some(Ok(IntOp::Disable(1))) => "DISABLE(1)".to_string(),
        _ => {
            return Err(ctx.unsupported(
                "NC638",
                span,
                &format!("{name} (an interrupt instruction)"),
                "write M96 P<program number> or M97",
            ))
        }
    };
    Ok(Item { kind: ItemKind::Instruction { name: text }, span })
}
