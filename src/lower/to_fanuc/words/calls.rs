//! Subprogram calls → FANUC `G65 P<o>` with one argument letter per parameter
//! ([`param_letters`]); drilling cycles kept for `passes::cycles`, simulation-only calls
//! dropped, `CYCLE832` to its look-ahead form, and what FANUC cannot call refused.

use super::*;

/// Argument letters for `n` parameters, with the local variable each fills: specification I
/// in alphabetical order (A B C D E F H I J K M Q R S T U V W X Y Z; G L N O P cannot carry
/// arguments) up to 21 parameters, else specification II (A B C, then I J K sets) up to 33.
pub fn param_letters(n: usize) -> Option<Vec<(u8, u8)>> {
    const SPEC1: &[(u8, u8)] = &[
        (b'A', 1),
        (b'B', 2),
        (b'C', 3),
        (b'D', 7),
        (b'E', 8),
        (b'F', 9),
        (b'H', 11),
        (b'I', 4),
        (b'J', 5),
        (b'K', 6),
        (b'M', 13),
        (b'Q', 17),
        (b'R', 18),
        (b'S', 19),
        (b'T', 20),
        (b'U', 21),
        (b'V', 22),
        (b'W', 23),
        (b'X', 24),
        (b'Y', 25),
        (b'Z', 26),
    ];
    if n <= SPEC1.len() {
        return Some(SPEC1[..n].to_vec());
    }
    if n > 33 {
        return None;
    }
    let mut v = vec![(b'A', 1), (b'B', 2), (b'C', 3)];
    for k in 0..(n - 3) {
        v.push((b"IJK"[k % 3], 4 + k as u8));
    }
    Some(v)
}

/// A call: a translated subprogram becomes `G65 P<o> <letters>`; simulation-only calls are
/// dropped; anything else is unsupported. Returns a marker statement when unsupported.
/// A subprogram assumes it starts with lengths and feeds in one unit: declined where they
/// differ. The modes `m` continue in what the callee leaves of them ([`Effect`]).
pub(super) fn call(ctx: &mut Ctx, c: Call, span: Span, m: &mut Modal, kept: &mut Vec<Item>) -> Option<Stmt> {
    let name = match &c.target {
        CallTarget::Name(n) => n.to_ascii_uppercase(),
        CallTarget::Computed(Expr { kind: ExprKind::Binary(BinOp::Concat, ..), .. }) => {
            return built::built_call(ctx, c, span, m, kept)
        }
        // A STRING variable that holds program names only (`prog_vars`): their O numbers.
        CallTarget::Computed(e) if prog_call::holds_names(ctx, e) => return prog_call::call(ctx, c, span, m, kept),
        CallTarget::Computed(e) if prog_call::why_not(ctx, e).is_some() => return prog_call::refuse(ctx, e, span),
        // A STRING variable holding a name known only at run time: FANUC has no strings.
        _ => {
            let hint = "FANUC has no strings to hold a program name: write the name in the call, \
                        `CALL \"L\"<<n` (with --l-numbers, `[programs] l_numbers = true`, a program L<k> is O<k> \
                        and that call is `G65 P<n>`), or call each program by its name";
            return ctx.unsupported("NC303", span, "a computed call target", hint);
        }
    };
    if crate::dialect::sinumerik::cycles::cycle_of(&name).is_some() {
        // A drilling cycle: `passes::cycles` writes it.
        kept.push(Item { kind: ItemKind::Call(Box::new(c)), span });
        return None;
    }
    if name == "FGROUP" {
        // FANUC's F already runs along every axis that moves; the proof compares each
        // move's feed, so a move the group gives another feed diverges there (and a known
        // one is refused first, `feed_group`).
        return None;
    }
    if name == "CYCLE832" {
        return match super::super::lookahead::cycle832(ctx, &c, span) {
            Ok(s) => Some(s),
            Err(mark) => mark,
        };
    }
    if SIMULATION_ONLY.contains(&name.as_str()) {
        ctx.note(
            "NC322",
            span,
            &format!("{name} dropped"),
            "it only sets up the HMI simulation; it does not move the machine",
        );
        return None;
    }
    let Some(callee) = ctx.callees.get(&name).cloned() else {
        if crate::dialect::sinumerik::is_predefined_procedure(&name) {
            let what = format!("{name} (a predefined procedure of the control, not modelled)");
            let hint = "FANUC Macro B has no counterpart nctrans knows of: the program must do without it";
            return ctx.unsupported("NC303", span, &what, hint);
        }
        if crate::dialect::sinumerik::cycles::is_package_name(&name) {
            // A cycle of the control's package other than the drilling ones: its motion is
            // the control's program, which nctrans neither has nor models.
            let what = format!("cycle {name} (of the control's cycle package; only the drilling cycles are modelled)");
            let hint = format!(
                "replace {name} by explicit moves (CAM or the control can write them out), or put its \
                 program {name}.SPF beside the main program to translate it as a subprogram"
            );
            return ctx.unsupported("NC303", span, &what, &hint);
        }
        let hint = format!("translate {name} too: put {name}.SPF beside the main program");
        return ctx.unsupported("NC303", span, &format!("call of {name}"), &hint);
    };
    if c.args.len() > callee.params.len() {
        let what = format!("call of {name} with {} arguments ({} parameters)", c.args.len(), callee.params.len());
        return ctx.unsupported("NC303", span, &what, "");
    }
    let Some(letters) = param_letters(callee.params.len()) else {
        return ctx.unsupported("NC304", span, &format!("{name} with more than 33 parameters"), "");
    };
    if let Some(p) = callee.params.iter().find(|p| !p.by_ref && !p.dims.is_empty()) {
        let what = format!("array parameter {} of {name} passed by value", p.name);
        return ctx.unsupported("NC304", p.span, &what, "declare it VAR (Siemens passes arrays by reference)");
    }
    // A VAR parameter becomes the number of the caller's variable (`varmap` writes it
    // and checks the variable can have one): only a variable can be passed.
    for (k, p) in callee.params.iter().enumerate().filter(|(_, p)| p.by_ref) {
        let is_var = matches!(c.args.get(k), Some(Arg::Value(Expr { kind: ExprKind::Var(_), .. })));
        if !is_var {
            let at = match c.args.get(k) {
                Some(Arg::Value(e)) => e.span,
                Some(Arg::Omitted(s)) => *s,
                _ => span,
            };
            let what = format!("argument {} of {name} for VAR parameter {} that is not a variable", k + 1, p.name);
            let hint = "pass a variable (an R parameter or a DEF variable); Siemens writes the result back into it";
            return ctx.unsupported("NC380", at, &what, hint);
        }
    }
    if !m.s.units.one_unit() {
        let what = if matches!(m.s.units, UnitState::Unknown) {
            format!("call of {name} where the units (G70/G71/G700/G710) depend on the path taken or on a call")
        } else {
            format!("call of {name} while lengths and feeds are in different units (G70/G71)")
        };
        let hint = "set both units with G700 or G710 before the call (a subprogram starts in its caller's units)";
        return ctx.unsupported("NC324", span, &what, hint);
    }
    let modal = c.kind == CallKind::Mcall;
    // The motion mode (G0–G3) a modal call's program leaves is the next block's on both
    // controls alike (neither restores it), and the words this pass writes do not read it.
    const MOTION: u16 = 1;
    if modal {
        // `MCALL NAME(…)` is `G66 P… A…`: both call the program after every later block that
        // moves, with the values the arguments had at the MCALL. Those later calls are not at
        // the MCALL's place, so what follows it (modes, tool, frames, the values the cycles
        // read) must not depend on the program having run.
        let e = &callee.effect;
        let why = if callee.params.iter().any(|p| p.by_ref) {
            Some("a VAR parameter (G66 passes values)")
        } else if e.leaves() & !MOTION != 0 || e.units != super::effects::UnitEffect::None {
            Some("modes (G90/G91, the units, …) that it leaves changed")
        } else if e.tools || e.frames {
            Some("a tool, compensation or frame that it changes")
        } else if e.r_params || e.interrupts {
            Some("R parameters or interrupts that it sets")
        } else if c.repeat.is_some() {
            Some("a repeat count")
        } else {
            None
        };
        if let Some(why) = why {
            let what = format!("modal call MCALL {name} with {why}");
            let hint = "call the subprogram after each move instead";
            return ctx.unsupported("NC318", span, &what, hint);
        }
    }
    let repeat = c.repeat.clone();
    if repeat.is_some() && !callee.params.is_empty() {
        let what = format!("repeated call of {name} with parameters");
        return ctx.unsupported("NC303", span, &what, "call it in a FOR loop");
    }
    // Every parameter is passed explicitly: an omitted Siemens argument is 0, while an
    // omitted G65 letter would leave the local vacant.
    let mut args = Vec::with_capacity(letters.len());
    for (k, &(letter, var)) in letters.iter().enumerate() {
        let value = match c.args.get(k) {
            Some(Arg::Value(e)) | Some(Arg::Letter { value: e, .. }) => e.clone(),
            Some(Arg::Omitted(s)) => num(0.0, *s),
            None => num(0.0, span),
        };
        args.push(Arg::Letter { letter, var, value });
    }
    let kind = if modal { CallKind::G66 } else { CallKind::G65 };
    let g65 = Call { kind, target: CallTarget::Number(callee.number), args, repeat };
    kept.push(item(ItemKind::Call(Box::new(g65)), span));
    if modal {
        return None;
    }
    // The modes as the callee leaves them (G90/G91 read from #4003 by an AC()/IC() word
    // until the caller's next G90/G91).
    let before = m.s;
    m.s.call(&callee.effect);
    ctx.units_inexact |= m.s.units != before.units;
    None
}
