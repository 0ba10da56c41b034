//! Sinumerik → FANUC: the additive frame sequences that turn, scale or mirror about a point,
//! `ATRANS X=c..` / `AROT RPL=a` (`ASCALE`, `AMIRROR`) / `ATRANS X=-c..` (what the FANUC →
//! Sinumerik translation writes for G68, G51, G51.1), and the sequence undoing one
//! (docs/translation.md, "Coordinate systems").
//!
//! A sequence where no such mode is in force becomes `G68 X c Y c R a` (`G51 X c .. I f ..`,
//! `G51.1 X c`): FANUC turns about the centre in the local coordinate system, as the
//! sequence does on top of a TRANS (its G52). The sequence with the inverse values (the
//! angle negated, the factors inverted, the same mirror) right after it becomes G69 (G50,
//! G50.1). Also without the ATRANS pair, about the origin. Found in a statement list from
//! the start of a main program or an absolute frame instruction on, with constants, in
//! consecutive blocks no jump can land in; anything else is left to `rotation.rs`.

use super::*;

#[derive(Clone, Debug, PartialEq)]
enum Mode {
    Rot(f64),
    Scale(Vec<(u8, f64)>),
    Mirror(Vec<u8>),
}

#[derive(Clone, Debug, PartialEq)]
struct Found {
    centre: Vec<(u8, f64)>,
    mode: Mode,
}

#[derive(Clone, Debug)]
enum Action {
    Set(Found),
    Undo(Found),
    /// The second and third block of a sequence: they went into its first.
    Skip,
}

/// The sequences of a program, by the start of each block they take.
#[derive(Clone, Debug, Default)]
pub struct Seqs {
    at: Vec<(u32, Action)>,
}

fn constant(e: &Expr) -> Option<f64> {
    match &e.kind {
        ExprKind::Num(n) => Some(n.value),
        ExprKind::Unary(UnOp::Neg, a) => constant(a).map(|v| -v),
        ExprKind::Binary(BinOp::Div, a, b) => Some(constant(a)? / constant(b)?).filter(|v| v.is_finite()),
        _ => None,
    }
}

fn frame_of(s: &Stmt) -> Option<(&str, &[Word], Span, bool)> {
    let StmtKind::Block(b) = &s.kind else { return None };
    let target = b.meta.number.is_some() || b.meta.label.is_some();
    match b.items.as_slice() {
        [Item { kind: ItemKind::Frame { op, words }, span }] => Some((op.as_str(), words.as_slice(), *span, target)),
        _ => None,
    }
}

fn axis(w: &Word) -> Option<u8> {
    b"XYZ".iter().copied().find(|&c| w.addr.is(c))
}

fn word_value(w: &Word) -> Option<f64> {
    match &w.value {
        WordValue::Expr(e) => constant(e),
        _ => None,
    }
}

fn shift(words: &[Word]) -> Option<Vec<(u8, f64)>> {
    words.iter().map(|w| Some((axis(w)?, word_value(w)?))).collect()
}

fn mode(op: &str, words: &[Word]) -> Option<Mode> {
    match op {
        "AROT" => match words {
            [w] if matches!(&w.addr, Addr::Name(n) if n.as_ref() == "RPL") || w.addr.is(b'Z') => {
                Some(Mode::Rot(word_value(w)?))
            }
            _ => None,
        },
        "ASCALE" => {
            Some(Mode::Scale(words.iter().map(|w| Some((axis(w)?, word_value(w)?))).collect::<Option<Vec<_>>>()?))
        }
        "AMIRROR" => Some(Mode::Mirror(words.iter().map(axis).collect::<Option<Vec<_>>>()?)),
        _ => None,
    }
}

/// The sequence at `list[i..]`: the mode found and the blocks it takes. `g17`: the program
/// selects no other plane (else rotations are left to `rotation.rs`, which knows the plane).
fn sequence_at(list: &[Stmt], i: usize, g17: bool) -> Option<(Found, usize)> {
    let (op, words, _, _) = frame_of(list.get(i)?)?;
    let mode = |op: &str, words: &[Word]| mode(op, words).filter(|m| g17 || !matches!(m, Mode::Rot(_)));
    if let Some(m) = mode(op, words) {
        return Some((Found { centre: Vec::new(), mode: m }, 1));
    }
    if op != "ATRANS" {
        return None;
    }
    let c = shift(words)?;
    let (op2, w2, _, t2) = frame_of(list.get(i + 1)?)?;
    let (op3, w3, _, t3) = frame_of(list.get(i + 2)?)?;
    let m = mode(op2, w2)?;
    let back = shift(w3)?;
    let opposite =
        op3 == "ATRANS" && back.len() == c.len() && c.iter().zip(&back).all(|(a, b)| a.0 == b.0 && a.1 == -b.1);
    // The centre moves only the axes the mode acts on.
    let acts: Vec<u8> = match &m {
        Mode::Rot(_) => b"XY".to_vec(),
        Mode::Scale(f) => f.iter().map(|x| x.0).collect(),
        Mode::Mirror(a) => a.clone(),
    };
    (!t2 && !t3 && opposite && c.iter().all(|x| acts.contains(&x.0))).then_some((Found { centre: c, mode: m }, 3))
}

fn inverse(a: &Found, b: &Found) -> bool {
    let same_centre = a.centre.iter().filter(|c| c.1 != 0.0).eq(b.centre.iter().filter(|c| c.1 != 0.0));
    same_centre
        && match (&a.mode, &b.mode) {
            (Mode::Rot(x), Mode::Rot(y)) => (x + y).abs() < 1e-9,
            (Mode::Scale(x), Mode::Scale(y)) => {
                x.len() == y.len() && x.iter().zip(y).all(|(p, q)| p.0 == q.0 && (p.1 * q.1 - 1.0).abs() < 1e-9)
            }
            (Mode::Mirror(x), Mode::Mirror(y)) => x == y,
            _ => false,
        }
}

fn scan(list: &[Stmt], start: bool, g17: bool, seqs: &mut Seqs) {
    let mut plain = start;
    let mut active: Option<Found> = None;
    let mut i = 0;
    while i < list.len() {
        let s = &list[i];
        let StmtKind::Block(b) = &s.kind else {
            for child in crate::ir::visit::child_bodies(&s.kind) {
                scan(child, false, g17, seqs);
            }
            (plain, active) = (false, None);
            i += 1;
            continue;
        };
        if b.meta.number.is_some() || b.meta.label.is_some() {
            (plain, active) = (false, None);
        }
        if let Some((found, n)) = sequence_at(list, i, g17) {
            let first = b.items.first().map_or(b.meta.span.lo, |it| it.span.lo);
            let action = match &active {
                Some(a) if inverse(a, &found) => {
                    (plain, active) = (true, None);
                    Some(Action::Undo(found))
                }
                None if plain => {
                    (plain, active) = (false, Some(found.clone()));
                    Some(Action::Set(found))
                }
                _ => None,
            };
            if let Some(action) = action {
                seqs.at.push((first, action));
                for s in &list[i + 1..i + n] {
                    if let StmtKind::Block(b) = &s.kind {
                        seqs.at.push((b.items.first().map_or(b.meta.span.lo, |it| it.span.lo), Action::Skip));
                    }
                }
                i += n;
                continue;
            }
            (plain, active) = (false, None);
            i += 1;
            continue;
        }
        match frame_of(s) {
            Some((op, words, _, _)) => {
                let absolute = op == "TRANS" || (matches!(op, "ROT" | "SCALE" | "MIRROR") && words.is_empty());
                (plain, active) = (absolute, None);
            }
            None if b.items.iter().any(|it| matches!(it.kind, ItemKind::Call(_))) => (plain, active) = (false, None),
            None => {}
        }
        i += 1;
    }
}

/// The sequences of a program (`main`: not a called one, so no mode is in force at its start).
pub fn seqs(body: &[Stmt], main: bool) -> Seqs {
    let mut s = Seqs::default();
    let mut g17 = true;
    crate::ir::visit::walk_stmts(body, &mut |st| {
        if let StmtKind::Block(b) = &st.kind {
            g17 &= !b.items.iter().any(|it| {
                matches!(&it.kind, ItemKind::Word(Word { addr: Addr::Letter(b'G'), value: WordValue::Expr(Expr { kind: ExprKind::Num(n), .. }), .. }) if n.value == 18.0 || n.value == 19.0)
            });
        }
    });
    scan(body, main, g17, &mut s);
    s
}

fn g(v: f64, span: Span) -> Item {
    item(ItemKind::Word(Word { addr: Addr::Letter(b'G'), value: WordValue::Expr(num(v, span)), span }), span)
}

fn letter(l: u8, v: f64, span: Span) -> Item {
    item(ItemKind::Word(Word { addr: Addr::Letter(l), value: WordValue::Expr(Expr::num(v, true, span)), span }), span)
}

/// The FANUC block of a frame block a sequence takes (`Some(vec![])`: it went into the
/// first); `None`: not one. `g17`: the program rotates in G17 only.
pub fn block(ctx: &mut Ctx, b: &mut Block, seqs: &Seqs, g17: bool) -> Option<Vec<Stmt>> {
    let first = b.items.first().map_or(b.meta.span.lo, |it| it.span.lo);
    let action = seqs.at.iter().find(|a| a.0 == first)?.1.clone();
    let span = b.items.first().map_or(b.meta.span, |it| it.span);
    let centre = |f: &Found, l: u8| f.centre.iter().find(|c| c.0 == l).map_or(0.0, |c| c.1);
    let items = match action {
        Action::Skip => return Some(Vec::new()),
        Action::Set(f) => match &f.mode {
            Mode::Rot(a) => {
                if !g17 {
                    return Some(
                        ctx.unsupported(
                            "NC498",
                            span,
                            "a rotation in a program that selects G18/G19 (FANUC G68 rotates in the plane of the block, which is not known here)",
                            "rotate in G17",
                        )
                        .into_iter()
                        .collect(),
                    );
                }
                vec![
                    g(68.0, span),
                    letter(b'X', centre(&f, b'X'), span),
                    letter(b'Y', centre(&f, b'Y'), span),
                    letter(b'R', *a, span),
                ]
            }
            Mode::Scale(fs) => {
                let mut v = vec![g(51.0, span)];
                v.extend(fs.iter().map(|&(l, _)| letter(l, centre(&f, l), span)));
                v.extend(fs.iter().map(|&(l, k)| letter(b"IJK"[(l - b'X') as usize], k, span)));
                v
            }
            Mode::Mirror(axes) => {
                let mut v = vec![g(51.1, span)];
                v.extend(axes.iter().map(|&l| letter(l, centre(&f, l), span)));
                v
            }
        },
        Action::Undo(f) => match &f.mode {
            Mode::Rot(_) => vec![g(69.0, span)],
            Mode::Scale(_) => vec![g(50.0, span)],
            Mode::Mirror(axes) => {
                let mut v = vec![g(50.1, span)];
                v.extend(axes.iter().map(|&l| letter(l, 0.0, span)));
                v
            }
        },
    };
    let meta = std::mem::take(&mut b.meta);
    Some(vec![meta_stmt(meta, items)])
}
