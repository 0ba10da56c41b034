//! FANUC and Haas system variables beyond `words::system_var`: for each one real Haas
//! libraries use, what it is and why the translation has nothing it could prove equal
//! (docs/semantics.md, "Haas system variables"), so that a refusal tells the user what to do
//! instead of only "no counterpart"; and computed numbers into the tool offset tables.

use super::*;

/// A computed `#[…]` whose constant part lies in a system variable table (NC514).
pub const COMPUTED_SYSTEM: &str = "NC514";
/// A computed `#[…]` into NGC-only variables that nothing places (warning NC515).
pub const COMPUTED_UNPLACED: &str = "NC515";

/// What system variable `n` is and why it has no Siemens counterpart here: `(what, hint)`
/// for the NC365 refusal; `None` for the numbers without a description (the generic text).
pub fn refusal(ctx: &Ctx, n: u32, write: bool) -> Option<(String, &'static str)> {
    let haas = ctx.opts.source.haas;
    let clock = "the run models no time, so a translation of it could not be proven: remove the timing, or write it by hand for the Siemens control";
    let (what, hint): (String, &'static str) = match n {
        // The manual pages read here stop at #3023; the libraries read #3026 as the tool
        // in the spindle (`#[2400+#3026]`, "the tool's diameter from the table").
        3026 if haas => (
            format!(
                "{}#3026 (on a Haas the tool in the spindle, as programs use it; no manual page read here \
                 lists it)",
                if write { "writing " } else { "" }
            ),
            "Siemens $P_TOOLNO is the active tool's number; until a source settles what #3026 is, set the tool \
             number in a variable where the program changes tools (#10040=5. beside T5 M06)",
        ),
        3001 | 3002 => (
            format!(
                "#{n} (the {} timer, which a program sets and reads)",
                if n == 3001 { "millisecond" } else { "hour" }
            ),
            "Siemens timers ($AC_CYCLE_TIME, $AN_POWERON_TIME) are read-only and count other intervals; measure the time by hand on the Siemens control",
        ),
        3011 => ("#3011 (the date of the machine's clock: year, month, day)".into(), clock),
        3012 => ("#3012 (the time of day of the machine's clock: hour, minute, second)".into(), clock),
        3020 if haas => (
            "#3020 (the Haas power-on timer, read-only: the machine's clock since it was switched on; the Haas table \
             gives no unit)"
                .into(),
            "Siemens $AN_POWERON_TIME counts minutes since the control's last warm start; the run models no time, \
             so the two could not be proven equal: remove the timing, or write it by hand",
        ),
        3021..=3023 if haas => (
            format!("#{n} (the Haas {} timer, the machine's clock)", ["cycle start", "feed", "present part"][(n - 3021) as usize]),
            clock,
        ),
        2001..=2800 if haas => (format!("#{n} ({})", offset_table(n)), OFFSET_HINT),
        _ => return None,
    };
    Some((what, hint))
}

const OFFSET_HINT: &str = "Sinumerik keeps tool data per cutting edge ($TC_DP…), which the translation does not map \
                           and the run does not model: pass the value the program needs as a macro argument or a variable";

/// The Haas tool offset table holding `#n` (HAAS-NGC table, #2001–#2800).
fn offset_kind(n: u32) -> &'static str {
    match n {
        ..=2200 => "length geometry",
        2201..=2400 => "length wear",
        2401..=2600 => "diameter/radius geometry",
        _ => "diameter/radius wear",
    }
}

fn offset_table(n: u32) -> String {
    format!("the Haas tool {} offset of tool {}", offset_kind(n), (n - 2001) % 200 + 1)
}

/// Refuses a computed `#[c + …]` (index `x`, lowered) whose constant part `c` lies in a system
/// variable table the dispatch of common variables cannot reach (`#[2400+#3026]`: the tool
/// offsets): the refusal names the table instead of an alarm at run time. `None`: an index
/// for the common variables' dispatch.
pub fn computed(ctx: &mut Ctx, x: &Expr, span: Span) -> Option<Option<Stmt>> {
    let c = super::varmap::constant_term(x)?.round();
    if !(1000.0..=99_999.0).contains(&c) {
        return None;
    }
    let c = c as u32;
    if crate::dialect::fanuc::haas_vars::common(c, ctx.opts.source.haas_ngc) {
        unplaced_ngc(ctx, c, span);
        return None;
    }
    let table = match c {
        // `#[2400+t]` is tool t's entry of the table after #2400.
        2000..=2799 if ctx.opts.source.haas => format!("the Haas tool {} offsets", offset_kind(c + 1)),
        2000..=2999 => "the tool offset memory".into(),
        _ => format!("the system variables from #{c}"),
    };
    Some(ctx.unsupported(
        COMPUTED_SYSTEM,
        span,
        &format!("a computed variable number into {table} (`#[{c}+…]`)"),
        OFFSET_HINT,
    ))
}

/// Warns where a computed `#[c+…]` starts at an NGC-only number that neither a `--var-map`
/// rule nor a direct use of it gives an R parameter: these numbers have no default place, so
/// the translation reaches them only through a rule, and raises `SETAL(64115)` there (as for
/// `#800..#999`), which the proof then reports as a divergence.
fn unplaced_ngc(ctx: &mut Ctx, c: u32, span: Span) {
    if !crate::dialect::fanuc::haas_vars::ngc_only(c)
        || super::varmap::dispatch_ranges(ctx).iter().any(|&(from, to, _)| from <= c && c <= to)
    {
        return;
    }
    let file = ctx.file();
    ctx.diags.push(
        crate::diag::Diagnostic::warning(
            COMPUTED_UNPLACED,
            format!("the computed `#[{c}+…]` reaches Haas NGC variables that have no R parameter"),
        )
        .primary(file, span, "raises SETAL(64115) on Siemens where FANUC reads the variable")
        .note("NGC-only variables get an R parameter where the job names them, or by a rule")
        .hint(format!("give the range a rule: --var-map '#{c}-#{}=R<k>'", (c / 100) * 100 + 99)),
    );
}
