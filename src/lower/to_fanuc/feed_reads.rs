//! Siemens `$P_F` (the path feed F last programmed) and `$P_S` (the spindle speed S last
//! programmed) on FANUC: `#4109` and `#4119`, the F and S codes of the preceding block
//! (docs/semantics.md, Modal information; `varmap::system` maps them, `words::sysunits`
//! scales `$P_F` under G70, where Siemens reads it in mm/min and FANUC in inch/min).
//! This pass refuses the reads where the two may differ:
//! - a read in a block that writes F (S) itself: whether the read sees the old or the new
//!   value is not settled for Siemens, and FANUC never has a macro statement and an F word
//!   in one block (NC588 for F, NC589 for S);
//! - `$P_S[n]` with a spindle number (FANUC `#4119` has one S);
//! - `$P_S` where a CYCLE84 may have run before: the translation makes it `M29 S<SST>`,
//!   which leaves FANUC's S at the tapping speed where Siemens keeps the S programmed. So
//!   `$P_S` is refused in a program that taps, calls a program (it may tap), or is called.
//!
//! The F a cycle's translation writes (`G84 … F`, `G85 … F`) is written back after its
//! G80 (`cycles`), and no statement other than words is translated inside a modal cycle
//! call (NC396), so `$P_F` needs no such rule.

use super::varmap::visit_vars;
use super::*;

/// Siemens cycles whose FANUC translation writes no S (drilling and boring).
const NO_S_CYCLES: &[&str] =
    &["CYCLE81", "CYCLE82", "CYCLE83", "CYCLE85", "CYCLE86", "CYCLE87", "CYCLE88", "CYCLE89", "WORKPIECE"];

/// Whether an item writes the address `letter` (F, S; `S1=` and the like for S), also as the
/// THEN of an `IF … THEN`.
fn writes(it: &Item, letter: u8) -> bool {
    match &it.kind {
        ItemKind::Word(w) => match &w.addr {
            Addr::Letter(l) => *l == letter,
            Addr::Name(n) => {
                let b = n.as_bytes();
                b.first().is_some_and(|c| c.eq_ignore_ascii_case(&letter))
                    && (letter == b'F' || b.get(1).is_some_and(u8::is_ascii_digit))
            }
            Addr::Axis(_) => false,
        },
        ItemKind::IfThen { then, .. } => writes(then, letter),
        _ => false,
    }
}

/// Why `$P_S` may read another value on FANUC anywhere in this program, if it may.
fn speed_unsettled(prog: &Program, is_sub: bool) -> Option<&'static str> {
    if is_sub {
        return Some("in a called program (a CYCLE84 of a caller becomes FANUC `M29 S<SST>`, which leaves #4119 at the tapping speed while $P_S keeps the S programmed)");
    }
    let mut why = None;
    crate::ir::visit::walk_stmts(&prog.body, &mut |s| {
        let StmtKind::Block(b) = &s.kind else { return };
        for it in &b.items {
            let ItemKind::Call(c) = &it.kind else { continue };
            let name = match &c.target {
                CallTarget::Name(n) => n.as_str(),
                _ => "",
            };
            if name.eq_ignore_ascii_case("CYCLE84") {
                why = why.or(Some("in a program with CYCLE84 (FANUC `M29 S<SST>` leaves #4119 at the tapping speed while $P_S keeps the S programmed)"));
            } else if !NO_S_CYCLES.iter().any(|n| name.eq_ignore_ascii_case(n)) {
                why = why.or(Some("in a program that calls another (it may tap: FANUC `M29 S<SST>` leaves #4119 at the tapping speed while $P_S keeps the S programmed)"));
            }
        }
    });
    why
}

const OWN_BLOCK: &str = "read it into a variable in a block of its own before";
const IN_VARIABLE: &str = "program the value in a variable (`R1=…`, `F=R1`) and read that";

pub fn run(ctx: &mut Ctx, prog: &mut Program, is_sub: bool) {
    // Most programs read neither: one walk over them and nothing else.
    let mut any = false;
    visit_vars(&mut prog.body, &mut |v| {
        any |= matches!(&v.kind, VarKind::System { name, .. }
            if name.eq_ignore_ascii_case("P_F") || name.eq_ignore_ascii_case("P_S"));
    });
    if !any {
        return;
    }
    let mut refusals: Vec<(&'static str, Span, String, &'static str)> = Vec::new();
    // Reads in IF/WHILE conditions are no block reads: only the program-wide rule of $P_S.
    let speed = speed_unsettled(prog, is_sub);
    visit_vars(&mut prog.body, &mut |v| {
        let span = v.span;
        let VarKind::System { name, indices } = &mut v.kind else { return };
        if !name.eq_ignore_ascii_case("P_S") {
            return;
        }
        if !indices.is_empty() {
            refusals.push((
                "NC589",
                span,
                "$P_S[…] with a spindle number (FANUC's #4119 is the one S code)".into(),
                IN_VARIABLE,
            ));
            // Refused here: the variable map is not to refuse it again.
            indices.clear();
        } else if let Some(why) = speed {
            refusals.push(("NC589", span, format!("$P_S {why}"), IN_VARIABLE));
        }
    });
    crate::ir::visit::walk_stmts(&prog.body, &mut |s| {
        let StmtKind::Block(b) = &s.kind else { return };
        for (which, letter, code) in [("P_F", b'F', "NC588"), ("P_S", b'S', "NC589")] {
            if !b.items.iter().any(|it| writes(it, letter)) {
                continue;
            }
            for it in &b.items {
                for e in crate::ir::visit::item_exprs(it) {
                    collect(e, which, &mut |span| {
                        if !refusals.iter().any(|r| r.1 == span) {
                            let what = format!(
                                "${which} read in a block that writes {} itself (whether the read sees the value before or after it is not settled; FANUC's #{} is the preceding block's)",
                                letter as char,
                                if letter == b'F' { 4109 } else { 4119 }
                            );
                            refusals.push((code, span, what, OWN_BLOCK));
                        }
                    });
                }
            }
        }
    });
    refusals.sort_by_key(|r| (r.1.lo, r.0));
    for (code, span, what, hint) in refusals {
        ctx.unsupported(code, span, &what, hint);
    }
}

/// Calls `f` with the span of every read of `which` in `e`.
fn collect(e: &Expr, which: &str, f: &mut dyn FnMut(Span)) {
    if let ExprKind::Var(v) = &e.kind {
        if matches!(&v.kind, VarKind::System { name, .. } if name.eq_ignore_ascii_case(which)) {
            f(v.span);
            return;
        }
    }
    for c in e.children() {
        collect(c, which, f);
    }
}
