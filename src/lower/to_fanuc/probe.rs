//! Siemens measuring blocks on FANUC: `MEAS=1 G1 X.. F..` (probe 1, rising edge, the rest
//! of the move deleted at the trigger) is `G31 X.. F..` (skip signal 1, a G1 move that stops
//! where the signal arrives). The measured values do not carry over: Siemens keeps
//! `$AA_MW`/`$AA_MM` from the last probe that switched and tells it by `$AC_MEA`, FANUC has
//! no such flag and writes the end point into `#5061+` on a miss, so those reads stay
//! refused (NC342, `varmap`). MEAW (the move goes on to its end point), the falling edge and
//! probe 2 have no G31 form (NC540); a measuring block without G1 in it is refused too
//! (NC541), since G31 does not say which motion mode holds after it.
//!
//! Runs around [`super::words`]: [`take`] removes the `MEAS=` word (words would refuse the
//! address) and the block's `G1`, remembering the block; [`put`] then writes `G31` into it,
//! with a `G1` block after it so the motion mode after the block is G1 as on Siemens (after,
//! not before: a jump to the block's label or N number must meet it too).

use super::*;

/// Removes `MEAS=1` and `G1` from every measuring block; the spans of those blocks.
pub fn take(ctx: &mut Ctx, prog: &mut Program) -> Vec<Span> {
    let mut found = Vec::new();
    let body = std::mem::take(&mut prog.body);
    prog.body = crate::lower::map_bodies(body, &mut |list: Vec<Stmt>| {
        let mut out = Vec::with_capacity(list.len());
        for mut s in list {
            if let StmtKind::Block(b) = &mut s.kind {
                if let Some(at) = b.items.iter().position(measuring_word) {
                    let isp = b.items[at].span;
                    let ok = match &b.items[at].kind {
                        ItemKind::Word(w) => {
                            let meaw = matches!(&w.addr, Addr::Name(n) if n.eq_ignore_ascii_case("MEAW"));
                            let one = matches!(&w.value, WordValue::Expr(e) if crate::lower::literal(e) == Some(1.0));
                            !meaw && one
                        }
                        _ => false,
                    };
                    let g1 = b.items.iter().position(|it| g_of(it) == Some(1.0));
                    if !ok {
                        out.extend(ctx.unsupported(
                            "NC540",
                            isp,
                            "a measuring word other than MEAS=1 (MEAW goes on to the end point; the falling edge and probe 2 have no G31 form)",
                            "probe with MEAS=1 (FANUC G31: skip signal 1, the move stops at the signal)",
                        ));
                        // The whole block is refused (a marked comment under warn).
                        continue;
                    } else if g1.is_none() {
                        out.extend(ctx.unsupported(
                            "NC541",
                            isp,
                            "a measuring block (MEAS=1) without G1 in it",
                            "write G1 in the measuring block: MEAS=1 G1 X.. F..",
                        ));
                        continue;
                    } else {
                        let g1 = g1.unwrap_or(0);
                        let (hi, lo) = if g1 > at { (g1, at) } else { (at, g1) };
                        b.items.remove(hi);
                        b.items.remove(lo);
                        found.push(s.span);
                    }
                }
            }
            out.push(s);
        }
        out
    });
    found
}

fn measuring_word(it: &Item) -> bool {
    matches!(&it.kind, ItemKind::Word(Word { addr: Addr::Name(n), .. })
        if n.eq_ignore_ascii_case("MEAS") || n.eq_ignore_ascii_case("MEAW"))
}

fn g_of(it: &Item) -> Option<f64> {
    match &it.kind {
        ItemKind::Word(Word { addr: Addr::Letter(b'G'), value: WordValue::Expr(e), .. }) => crate::lower::literal(e),
        _ => None,
    }
}

fn g_word(v: f64, span: Span) -> Item {
    item(ItemKind::Word(Word { addr: Addr::Letter(b'G'), value: WordValue::Expr(num(v, span)), span }), span)
}

/// Writes `G31` into the blocks [`take`] found (`G1` in a block of its own after each).
pub fn put(prog: &mut Program, blocks: &[Span]) {
    if blocks.is_empty() {
        return;
    }
    let body = std::mem::take(&mut prog.body);
    prog.body = crate::lower::map_bodies(body, &mut |list: Vec<Stmt>| {
        let mut out = Vec::with_capacity(list.len());
        for mut s in list {
            if let StmtKind::Block(b) = &mut s.kind {
                if blocks.contains(&s.span) {
                    b.items.insert(0, g_word(31.0, s.span));
                    let span = s.span;
                    out.push(s);
                    out.push(block_stmt(vec![g_word(1.0, span)], span));
                    continue;
                }
            }
            out.push(s);
        }
        out
    });
}
