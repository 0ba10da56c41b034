//! Siemens `CALL "L"<<n` (the name of a DIN subprogram built at run time) to FANUC under
//! `--l-numbers`, where every program `L<k>` of the translation is `O<k>`: the call is
//! `G65 P<n>`, the same program for every value `n` can take. Exact only when `n` is an
//! integer where the call stands (`<<` then writes its digits alone, and P is not rounded;
//! [`crate::lower::to_fanuc::integral::integral_call_numbers`]), when every `L<k>` program the
//! call can reach is numbered `O<k>` (no clash with another program's number, within the
//! series' digits), takes no parameters (`CALL` passes none; `G65` would leave them vacant,
//! not 0) and leaves G90/G91 and the units as they were (the words pass would otherwise have to
//! follow them through a callee known only at run time). Anything else is refused.

use super::*;

const OPTION: &str = "--l-numbers (`[programs] l_numbers = true` in nctrans.toml)";

/// Lowers a call whose target is built by `<<`; `None` when it was translated.
pub(super) fn built_call(ctx: &mut Ctx, c: Call, span: Span, m: &mut Modal, kept: &mut Vec<Item>) -> Option<Stmt> {
    let what = "a call of a program whose name is built at run time (`<<`)";
    let Some(l_programs) = ctx.l_programs.clone() else {
        let hint = format!(
            "FANUC numbers the translated subprograms from O9000 up by name, so no `M98 P#n` calls the same \
             program; with {OPTION} a program L<k> is O<k> and `CALL \"L\"<<n` is `G65 P<n>`"
        );
        return ctx.unsupported("NC585", span, what, &hint);
    };
    let Some(n) = crate::lower::to_fanuc::integral::built_l_number(&c.target).cloned() else {
        let hint = format!(
            "only `\"L\"<<n` has a FANUC counterpart ({OPTION} numbers program L<k> as O<k>); \
             other names are numbered from O9000 by name: call each by its name (`CASE … OF`)"
        );
        return ctx.unsupported("NC585", span, what, &hint);
    };
    if !ctx.integral_calls.contains(&n.span) {
        return ctx.unsupported(
            "NC647",
            n.span,
            "a call of \"L\"<< a number not provably an integer where the call stands",
            "`<<` writes a fraction as digits with a point (no such program) where FANUC rounds P: \
             set the number from integers only (an INT variable, or R parameters assigned integer constants \
             and steps), before the call on every path",
        );
    }
    let mut after = m.s;
    let mut first = true;
    for (name, numbered) in &l_programs {
        match numbered {
            Err(LFault::Clash { other }) => {
                let what = format!("a call of \"L\"<<… that can reach {name}, whose O number is {other}'s");
                let hint = format!("number {other} otherwise (--program-map {other}=<n>, --program-number)");
                return ctx.unsupported("NC648", span, &what, &hint);
            }
            Err(LFault::Beyond { max }) => {
                let what = format!("a call of \"L\"<<… that can reach {name}, which is no O number (1 to {max})");
                let hint =
                    "rename the program within the series' O numbers ([fanuc] series: 4 digits, 8 on the 30i class)";
                return ctx.unsupported("NC649", span, &what, hint);
            }
            Err(LFault::Mapped { to }) => {
                let what = format!("a call of \"L\"<<… that can reach {name}, which the program map numbers O{to}");
                let hint = format!("map {name} to its own number ({name}={}) or leave it out of the map", &name[1..]);
                return ctx.unsupported("NC648", span, &what, &hint);
            }
            Ok(_) => {}
        }
        let Some(callee) = ctx.callees.get(name).cloned() else { continue };
        let modes = callee.effect.leaves() & effects::ABS != 0 || callee.effect.units != effects::UnitEffect::None;
        if !callee.params.is_empty() || modes {
            let why = if callee.params.is_empty() { "leaves G90/G91 or the units changed" } else { "has parameters" };
            let what = format!("a call of \"L\"<<… that can reach {name}, which {why}");
            return ctx.unsupported("NC650", span, &what, "call the programs by name (`CASE … OF` over the names)");
        }
        let mut s = m.s;
        s.call(&callee.effect);
        after = if first { s } else { after.merge(s) };
        first = false;
    }
    if !m.s.units.one_unit() {
        let what = "a call of \"L\"<<… where lengths and feeds are not in one known unit";
        let hint = "set both units with G700 or G710 before the call (a subprogram starts in its caller's units)";
        return ctx.unsupported("NC324", span, what, hint);
    }
    let g65 = Call { kind: CallKind::G65, target: CallTarget::Computed(n), args: vec![], repeat: c.repeat };
    kept.push(item(ItemKind::Call(Box::new(g65)), span));
    m.s = after;
    None
}
