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
//! consecutive blocks no jump can land in; a rotation in G17, or in the one plane G18/G19 a
//! main program selects in its leading blocks, after that word (the centre in the plane's
//! two axes: `G68 Z c X c R a`); anything else is left to `rotation.rs`.

use super::*;

#[derive(Clone, Debug, PartialEq)]
enum Mode {
    /// The angle and the plane (17, 18, 19) it turns in.
    Rot(f64, u32),
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

impl Seqs {
    /// Whether a sequence takes the frame block whose instruction starts at `lo`.
    pub fn takes(&self, lo: u32) -> bool {
        self.at.iter().any(|a| a.0 == lo)
    }
}

fn constant(e: &Expr) -> Option<f64> {
    match &e.kind {
        ExprKind::Num(n) => Some(n.value),
        ExprKind::Unary(UnOp::Neg, a) => constant(a).map(|v| -v),
        ExprKind::Binary(BinOp::Div, a, b) => Some(constant(a)? / constant(b)?).filter(|v| v.is_finite()),
        _ => None,
    }
}

fn frame_of<'a>(s: &'a Stmt, jumps: &crate::lower::landings::Landings) -> Option<(&'a str, &'a [Word], Span, bool)> {
    let StmtKind::Block(b) = &s.kind else { return None };
    let target = jumps.at(&b.meta);
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

/// The plane's two axes (G17 X Y, G18 Z X, G19 Y Z) and its normal.
fn plane_axes(plane: u32) -> (u8, u8, u8) {
    match plane {
        18 => (b'Z', b'X', b'Y'),
        19 => (b'Y', b'Z', b'X'),
        _ => (b'X', b'Y', b'Z'),
    }
}

/// The mode of an additive frame block; a rotation only where the plane is known (`plane`).
fn mode(op: &str, words: &[Word], plane: Option<u32>) -> Option<Mode> {
    match op {
        "AROT" => match words {
            [w] if matches!(&w.addr, Addr::Name(n) if n.as_ref() == "RPL") || w.addr.is(plane_axes(plane?).2) => {
                Some(Mode::Rot(word_value(w)?, plane?))
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

/// The sequence at `list[i..]`: the mode found and the blocks it takes. `plane`: the one
/// plane of the program (17 where it selects no other) and the start of its first word
/// ([`Plane`]); where it is not known so, rotations are left to `rotation.rs`.
fn sequence_at(
    list: &[Stmt],
    i: usize,
    plane: Plane,
    jumps: &crate::lower::landings::Landings,
) -> Option<(Found, usize)> {
    let (op, words, span, _) = frame_of(list.get(i)?, jumps)?;
    let at = plane.filter(|&(p, lo)| p == 17 || span.lo > lo).map(|p| p.0);
    let mode = |op: &str, words: &[Word]| mode(op, words, at);
    if let Some(m) = mode(op, words) {
        return Some((Found { centre: Vec::new(), mode: m }, 1));
    }
    if op != "ATRANS" {
        return None;
    }
    let c = shift(words)?;
    let (op2, w2, _, t2) = frame_of(list.get(i + 1)?, jumps)?;
    let (op3, w3, _, t3) = frame_of(list.get(i + 2)?, jumps)?;
    let m = mode(op2, w2)?;
    let back = shift(w3)?;
    let opposite =
        op3 == "ATRANS" && back.len() == c.len() && c.iter().zip(&back).all(|(a, b)| a.0 == b.0 && a.1 == -b.1);
    // The centre moves only the axes the mode acts on.
    let acts: Vec<u8> = match &m {
        Mode::Rot(_, p) => {
            let (u, v, _) = plane_axes(*p);
            vec![u, v]
        }
        Mode::Scale(f) => f.iter().map(|x| x.0).collect(),
        Mode::Mirror(a) => a.clone(),
    };
    (!t2 && !t3 && opposite && c.iter().all(|x| acts.contains(&x.0))).then_some((Found { centre: c, mode: m }, 3))
}

fn inverse(a: &Found, b: &Found) -> bool {
    let same_centre = a.centre.iter().filter(|c| c.1 != 0.0).eq(b.centre.iter().filter(|c| c.1 != 0.0));
    same_centre
        && match (&a.mode, &b.mode) {
            (Mode::Rot(x, p), Mode::Rot(y, q)) => p == q && (x + y).abs() < 1e-9,
            (Mode::Scale(x), Mode::Scale(y)) => {
                x.len() == y.len() && x.iter().zip(y).all(|(p, q)| p.0 == q.0 && (p.1 * q.1 - 1.0).abs() < 1e-9)
            }
            (Mode::Mirror(x), Mode::Mirror(y)) => x == y,
            _ => false,
        }
}

/// The plane rotations turn in ([`sequence_at`]).
type Plane = Option<(u32, u32)>;

fn scan(list: &[Stmt], start: bool, plane: Plane, jumps: &crate::lower::landings::Landings, seqs: &mut Seqs) {
    let mut plain = start;
    let mut active: Option<Found> = None;
    let mut i = 0;
    while i < list.len() {
        let s = &list[i];
        let StmtKind::Block(b) = &s.kind else {
            for child in crate::ir::visit::child_bodies(&s.kind) {
                scan(child, false, plane, jumps, seqs);
            }
            (plain, active) = (false, None);
            i += 1;
            continue;
        };
        if jumps.at(&b.meta) {
            (plain, active) = (false, None);
        }
        if let Some((found, n)) = sequence_at(list, i, plane, jumps) {
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
        match frame_of(s, jumps) {
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
/// A rotation turns in G17 where the program selects no other plane, or in the one plane a
/// main program selects in its leading blocks (`rotation::single_plane`), after its word.
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
    let plane = if g17 {
        Some((17, 0))
    } else if main {
        super::rotation::single_plane(body)
    } else {
        None
    };
    scan(body, main, plane, &crate::lower::landings::Landings::of(body), &mut s);
    s
}

fn g(v: f64, span: Span) -> Item {
    item(ItemKind::Word(Word { addr: Addr::Letter(b'G'), value: WordValue::Expr(num(v, span)), span }), span)
}

fn letter(l: u8, v: f64, span: Span) -> Item {
    item(ItemKind::Word(Word { addr: Addr::Letter(l), value: WordValue::Expr(Expr::num(v, true, span)), span }), span)
}

/// The FANUC block of a frame block a sequence takes (`Some(vec![])`: it went into the
/// first); `None`: not one.
pub fn block(b: &mut Block, seqs: &Seqs) -> Option<Vec<Stmt>> {
    let first = b.items.first().map_or(b.meta.span.lo, |it| it.span.lo);
    let action = seqs.at.iter().find(|a| a.0 == first)?.1.clone();
    let span = b.items.first().map_or(b.meta.span, |it| it.span);
    let centre = |f: &Found, l: u8| f.centre.iter().find(|c| c.0 == l).map_or(0.0, |c| c.1);
    let items = match action {
        Action::Skip => return Some(Vec::new()),
        Action::Set(f) => match &f.mode {
            Mode::Rot(a, p) => {
                let (u, v, _) = plane_axes(*p);
                vec![
                    g(68.0, span),
                    letter(u, centre(&f, u), span),
                    letter(v, centre(&f, v), span),
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
            Mode::Rot(..) => vec![g(69.0, span)],
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
