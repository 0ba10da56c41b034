//! FANUC modal information reads on Siemens (docs/semantics.md, Modal information): `#4001`
//! (G00..G03), `#4002` (G17..G19), `#4003` (G90/G91), `#4005` (G94/G95), `#4006` (G20/G21),
//! `#4007` (G40..G42), `#4008` (G43/G44/G49), `#4010` (G98/G99), `#4014` (G54..G59), `#4015`
//! (G61..G64), `#4107` (D), `#4111` (H), `#4113` (M), `#4114` (N), `#4120` (T). Each holds
//! the value of the preceding block (SEED3: "the modal information of the blocks before the
//! one being processed"; M-MODAL). Siemens `$P_GG[n]` returns a group's internal number
//! (group 1: G0..G3 are 1..4, groups 6 and 7 below; no source numbers the others here), group 1 holds other codes
//! (G33, and a cycle's own moves) where FANUC's group 01 does not, and the translation writes
//! cutting edges (`D1` of tool n) where FANUC numbers registers (`D5`); Siemens has no M or
//! sequence number variable; so none of them has a Siemens variable with FANUC's value
//! everywhere. What is
//! exact is the constant, where the program itself has written that mode or word on every
//! path to the read: a forward flow over the program as read (`vacancy::flatten`, FANUC
//! jump order), starting from nothing known (no power-on or caller assumption), where a call
//! may change anything. Elsewhere `#4002` and `#4007` become `$P_GG[6]+16` and `$P_GG[7]+39`
//! (groups 6 and 7 number G17..G19 and G40..G42 1..3), the others are refused by name
//! (NC549), as are `#4102` (B),
//! `#4115` (the program number) and `#4130` (the P of G54.1), whose values no source read
//! here settles.

use super::vacancy::{flatten, succs, Node};
use super::*;

/// The diagnostic of a modal information read that cannot be folded.
pub const MODAL_READ: &str = "NC549";

/// The variables followed, in [`State`] order, and what each holds.
const VARS: [(u32, &str); 15] = [
    (4001, "#4001 (the motion G code G00..G03 of the preceding block)"),
    (4002, "#4002 (the plane G17..G19 of the preceding block)"),
    (4003, "#4003 (G90/G91 of the preceding block)"),
    (4005, "#4005 (G94/G95 of the preceding block)"),
    (4006, "#4006 (G20/G21 of the preceding block)"),
    (4007, "#4007 (the cutter compensation G40..G42 of the preceding block)"),
    (4008, "#4008 (the tool length compensation G43/G44/G49 of the preceding block)"),
    (4010, "#4010 (the cycle return level G98/G99 of the preceding block)"),
    (4014, "#4014 (the work offset G54..G59 of the preceding block)"),
    (4015, "#4015 (G61..G64 of the preceding block)"),
    (4107, "#4107 (the D number of the preceding block)"),
    (4111, "#4111 (the H number of the preceding block)"),
    (4120, "#4120 (the T number of the preceding block)"),
    (4113, "#4113 (the M code of the preceding block)"),
    (4114, "#4114 (the sequence number N of the preceding block)"),
];
const G_FIELDS: u16 = (1 << 10) - 1;
const D: usize = 10;
const H: usize = 11;
const T: usize = 12;
const M: usize = 13;
const N: usize = 14;

/// The value of each of [`VARS`], `None` where not known.
type State = [Option<f64>; 15];

/// Per block (and loop condition) of a program, in text order: its start, the values on
/// entry, and the fields its own words set (bit per [`VARS`] index).
#[derive(Default)]
pub struct Reads {
    at: Vec<(u32, Option<State>, u16)>,
}

/// The field (index into [`VARS`]) and value a literal G code (×10) sets; `Err(field)` for a
/// code of the group whose value is not followed (a cycle, G54.1).
fn g_field(g: u32, p_word: bool) -> Option<Result<(usize, f64), usize>> {
    let v = f64::from(g) / 10.0;
    Some(match g {
        0 | 10 | 20 | 30 => Ok((0, v)),
        // Other codes of the groups followed (G02.x, G33 threading, G60, the cycles; G93,
        // G17.1, G41.2, G43.4 …): the value is not followed, so not known after them.
        1..=39 | 330..=350 | 600 | 730..=890 => Err(0),
        170 | 180 | 190 => Ok((1, v)),
        171..=199 => Err(1),
        900 | 910 => Ok((2, v)),
        940 | 950 => Ok((3, v)),
        930 => Err(3),
        200 | 210 => Ok((4, v)),
        400 | 410 | 420 => Ok((5, v)),
        401..=429 => Err(5),
        430 | 440 | 490 => Ok((6, v)),
        431..=499 => Err(6),
        980 | 990 => Ok((7, v)),
        // `G54 Pn` is `G54.1 Pn` (an extended offset).
        540 | 550 | 560 | 570 | 580 | 590 if !p_word => Ok((8, v)),
        540..=599 => Err(8),
        610 | 620 | 630 | 640 => Ok((9, v)),
        611..=649 => Err(9),
        _ => return None,
    })
}

/// The state after a block (sequence number `number`) entered with `s`, and the fields the
/// block's words set.
fn apply(items: &[Item], number: Option<u32>, mut s: State) -> (State, u16) {
    let mut own = 0u16;
    // A call may change anything; so may the words of a Haas `IF [c] <words>` (run or not).
    let opaque = |it: &Item| match &it.kind {
        ItemKind::Call(_) | ItemKind::IfBlock { .. } => true,
        ItemKind::IfThen { then, .. } => !matches!(then.kind, ItemKind::Assign { .. }),
        _ => false,
    };
    if items.iter().any(opaque) {
        return ([None; 15], u16::MAX);
    }
    if let Some(n) = number {
        s[N] = Some(f64::from(n));
        own |= 1 << N;
    }
    // Which of two M codes of one block FANUC keeps is not settled here: neither.
    let m_words = items.iter().filter(|it| matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'M'))).count();
    let p_word = items.iter().any(|it| matches!(&it.kind, ItemKind::Word(w) if w.addr.is(b'P')));
    for it in items {
        let ItemKind::Word(w) = &it.kind else { continue };
        let value = match &w.value {
            WordValue::Expr(e) => literal(e),
            _ => None,
        };
        let field = match &w.addr {
            Addr::Letter(b'G') => match value {
                Some(v) => match g_field((v * 10.0).round() as u32, p_word) {
                    Some(Ok((f, x))) => {
                        s[f] = Some(x);
                        own |= 1 << f;
                        continue;
                    }
                    Some(Err(f)) => f,
                    None => continue,
                },
                // A computed G code may set any group.
                None => {
                    for f in s.iter_mut().take(D) {
                        *f = None;
                    }
                    own |= G_FIELDS;
                    continue;
                }
            },
            Addr::Letter(b'D') => D,
            Addr::Letter(b'H') => H,
            Addr::Letter(b'T') => T,
            Addr::Letter(b'M') => M,
            _ => continue,
        };
        own |= 1 << field;
        s[field] = match field {
            D | H | T => value,
            M if m_words == 1 => value,
            _ => None,
        };
    }
    (s, own)
}

fn merge(a: Option<State>, b: State) -> State {
    match a {
        None => b,
        Some(a) => std::array::from_fn(|i| if a[i] == b[i] { a[i] } else { None }),
    }
}

impl Reads {
    /// The flow over `body` (the program as read).
    pub fn new(body: &[Stmt]) -> Reads {
        let flat = flatten(body);
        let len = flat.nodes.len();
        let mut ins: Vec<Option<State>> = vec![None; len];
        if len == 0 {
            return Reads::default();
        }
        ins[0] = Some([None; 15]);
        // Under G66 the macro runs after every later move, where it may change anything.
        let mut modal_call = false;
        crate::ir::visit::walk_stmts(body, &mut |s| {
            if let StmtKind::Block(b) = &s.kind {
                modal_call |= b.items.iter().any(|it| matches!(&it.kind, ItemKind::Call(c) if c.kind == CallKind::G66));
            }
        });
        let mut work = if modal_call { Vec::new() } else { vec![0usize] };
        while let Some(i) = work.pop() {
            let Some(s) = ins[i] else { continue };
            let out = match &flat.nodes[i] {
                Node::Items(items) => {
                    let after = apply(items, flat.numbers[i], s).0;
                    // A block that may be skipped (`/`) passes its entry on as well.
                    if flat.blocks[i].is_some_and(|b| b.1) {
                        merge(Some(after), s)
                    } else {
                        after
                    }
                }
                // A DO or END block's own sequence number.
                _ if flat.numbers[i].is_some() => {
                    let mut s = s;
                    s[N] = None;
                    s
                }
                _ => s,
            };
            for j in succs(&flat, i) {
                if j < len {
                    let m = merge(ins[j], out);
                    if ins[j] != Some(m) {
                        ins[j] = Some(m);
                        work.push(j);
                    }
                }
            }
        }
        let mut at = Vec::new();
        for (i, node) in flat.nodes.iter().enumerate() {
            match node {
                Node::Items(items) => {
                    if let Some((lo, _)) = flat.blocks[i] {
                        at.push((lo, ins[i], apply(items, flat.numbers[i], [None; 15]).1));
                    }
                }
                Node::Head { cond: Some(c), .. } => at.push((c.span.lo, ins[i], 0)),
                _ => {}
            }
        }
        at.sort_by_key(|a| a.0);
        Reads { at }
    }

    /// The value of `#n` (one of [`VARS`]: a G group's code, D, H or T) every path to the
    /// block of the expression at `lo` has set, `None` where not known or where that block
    /// sets it itself.
    pub fn known(&self, n: u32, lo: u32) -> Option<f64> {
        let field = VARS.iter().position(|v| v.0 == n)?;
        let (_, s, own) = self.entry(lo)?;
        if own & (1 << field) != 0 {
            return None;
        }
        s.and_then(|s| s[field])
    }

    /// The entry of the block (or loop condition) an expression starting at `lo` lies in.
    fn entry(&self, lo: u32) -> Option<&(u32, Option<State>, u16)> {
        let i = self.at.partition_point(|a| a.0 <= lo);
        i.checked_sub(1).and_then(|i| self.at.get(i))
    }
}

/// `#n` as the constant it holds at `span`, `None` when `n` is not one of [`VARS`]; a
/// refusal (NC549) when it is and the value is not known there.
pub fn read(ctx: &mut Ctx, n: u32, span: Span) -> Option<Result<Expr, Vec<Stmt>>> {
    if let Some((what, why)) = unsettled(n) {
        let message = format!("{what} cannot be translated: {why}");
        let hint = "keep the value in a variable where the program writes it";
        return Some(Err(ctx.refuse(MODAL_READ, span, &message, what, hint).into_iter().collect()));
    }
    let field = VARS.iter().position(|v| v.0 == n)?;
    let what = VARS[field].1;
    let (state, own) = match ctx.modal.reads.entry(span.lo) {
        Some((_, s, own)) => (*s, *own),
        None => (None, 0),
    };
    let value = state.and_then(|s| s[field]);
    match value {
        // The block's own word of the same group: which value a FANUC read sees is not settled.
        Some(v) if own & (1 << field) == 0 => Some(Ok(Expr::num(v, v.fract() != 0.0, span))),
        _ if own & (1 << field) == 0 && p_gg_form(n).is_some() => p_gg_form(n).map(|(g, base)| Ok(p_gg(g, base, span))),
        _ => {
            let why = if own & (1 << field) != 0 {
                "in a block that sets it"
            } else {
                "where the program has not set it itself on every path to the read (a path, the caller, a called \
                 program or the power-on state decides it)"
            };
            let message = format!("{what} read {why} cannot be translated");
            let hint = "set the mode (or the D, H, M, T word, the N number) in the program before the read, on every \
                        path, in a block of its own; Siemens $P_GG numbers group 1 otherwise and no source read here numbers \
                        its groups other than 1, 6 and 7 (#4002 and #4007 are read as $P_GG[6]+16, $P_GG[7]+39), \
                        $P_TOOL gives edge numbers, and Siemens has no M or N variable";
            Some(Err(ctx.refuse(MODAL_READ, span, &message, what, hint).into_iter().collect()))
        }
    }
}

/// The Siemens group and the FANUC code of its function number 0 for the modal reads that
/// have an exact run-time form: `#4002` is `$P_GG[6]+16` (G17/G18/G19 are 1..3 in both
/// numberings' order) and `#4007` `$P_GG[7]+39` (G40/G41/G42 are 1..3). Neither Siemens
/// group holds another function the translation writes, and the translation selects the
/// plane and the side where the FANUC program does, so the two agree wherever the program has
/// not set the mode itself (the caller's, a path's, the power-on mode alike).
fn p_gg_form(n: u32) -> Option<(f64, f64)> {
    match n {
        4002 => Some((6.0, 16.0)),
        4007 => Some((7.0, 39.0)),
        _ => None,
    }
}

/// `$P_GG[group]+base` at `span`.
fn p_gg(group: f64, base: f64, span: Span) -> Expr {
    let read = var_expr(VarKind::System { name: "P_GG".into(), indices: vec![Expr::num(group, false, span)] }, span);
    Expr::new(ExprKind::Binary(BinOp::Add, Box::new(read), Box::new(Expr::num(base, false, span))), span)
}

/// The modal information reads whose value no source read here settles, with why.
fn unsettled(n: u32) -> Option<(&'static str, &'static str)> {
    Some(match n {
        4102 => (
            "#4102 (the B code of the preceding block)",
            "B is the second auxiliary function only where the machine has no B axis, and Siemens has no variable \
             holding the last auxiliary value",
        ),
        4115 => (
            "#4115 (the program number of the preceding block)",
            "which number it holds in a subprogram and at a call's first block is in no source read here, and the \
             Siemens program names are not FANUC's numbers",
        ),
        4130 => (
            "#4130 (the P number of the additional work offset G54.1)",
            "its value is in no source read here (the evaluator refuses it too)",
        ),
        _ => return None,
    })
}
