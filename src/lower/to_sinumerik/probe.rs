//! FANUC `G31` probing moves and `#5061+` skip-position reads on Sinumerik.
//!
//! `G31 X.. F..` is a linear move at F that stops where the skip signal arrives; FANUC then
//! holds that position in `#5061+` (every axis, workpiece coordinates), or the end point when
//! the signal never came. Siemens `MEAS=1 G1 X.. F..` makes the same move (probe 1, rising
//! edge, distance to go deleted) but writes `$AA_MW` only when the probe switched and only
//! for the axes of the block (`$AC_MEA[1]` tells which happened). So the translation keeps
//! the skip position itself: after each measuring block
//!
//! ```text
//! MEAS=1 G1 X30 F100
//! STOPRE
//! IF $AC_MEA[1]==1
//!   NCTRANS_SKIP_X=$AA_MW[X]      ; the axes of the block: the measured value
//! ELSE
//!   NCTRANS_SKIP_X=$AA_IW[X]      ; no contact: the move reached its end point
//! ENDIF
//! NCTRANS_SKIP_Y=$AA_IW[Y]        ; axes not in the block stand where they stood
//! ```
//!
//! for the axes whose `#5061+` the program reads, and `#5061+i` reads `NCTRANS_SKIP_<axis>`.
//! G31 is one-shot: where the motion mode in force after it is not G1, the translation
//! selects it again (`G0`, `G2`, `G3`); unknown (paths disagree) is refused (NC537). A read
//! of `#5061+` that some path of its program reaches without passing a G31 of the same
//! program (a caller's G31, or none yet) is refused (NC536): the value it would see is not
//! kept on Siemens. G31 P (multi-step skip) is refused (NC538); G31.1–G31.3 stay unsupported
//! G codes (NC363).

use super::vacancy::{flatten, succs, Node};
use super::*;

const AXES: [&str; 6] = ["X", "Y", "Z", "A", "B", "C"];

/// The DEF variable holding the skip position of axis `i`.
fn skip_name(i: usize) -> String {
    format!("NCTRANS_SKIP_{}", AXES[i])
}

fn is_g31(it: &Item) -> bool {
    matches!(&it.kind, ItemKind::Word(Word { addr: Addr::Letter(b'G'), value: WordValue::Expr(e), .. })
        if literal(e) == Some(31.0))
}

/// `#5061+i` reads in `e` (axis index and span), outermost first.
fn skip_reads(e: &Expr, out: &mut Vec<(u32, Span)>) {
    if let ExprKind::Var(v) = &e.kind {
        if let VarKind::Hash(n @ 5061..=5080) = v.kind {
            out.push((n - 5061, v.span));
        }
    }
    for c in e.children() {
        skip_reads(c, out);
    }
}

fn item_reads(items: &[Item]) -> Vec<(u32, Span)> {
    let mut out = Vec::new();
    for it in items {
        for e in crate::ir::visit::item_exprs(it) {
            skip_reads(e, &mut out);
        }
    }
    out
}

/// Checks the program as read (before the passes restructure it): every `#5061+` read must
/// follow a G31 of the program on every path. Returns the axes read (bit per index).
pub fn scan(ctx: &mut Ctx, body: &[Stmt]) -> u16 {
    let flat = flatten(body);
    let len = flat.nodes.len();
    let reads_at = |i: usize| -> Vec<(u32, Span)> {
        match &flat.nodes[i] {
            Node::Items(items) => item_reads(items),
            Node::Head { cond: Some(c), .. } => {
                let mut v = Vec::new();
                skip_reads(c, &mut v);
                v
            }
            _ => Vec::new(),
        }
    };
    let mut axes = 0u16;
    let mut bad: Vec<(u32, Span)> = Vec::new();
    for i in 0..len {
        for (a, sp) in reads_at(i) {
            if (a as usize) < AXES.len() {
                axes |= 1 << a;
            } else {
                bad.push((a, sp));
            }
        }
    }
    for (a, sp) in bad {
        ctx.unsupported(
            "NC536",
            sp,
            &format!("#{} (the skip position of axis {}, beyond X Y Z A B C)", 5061 + a, a + 1),
            "read the skip position of X, Y, Z, A, B or C (#5061–#5066)",
        );
    }
    if axes == 0 || len == 0 {
        return axes;
    }
    // Nodes reached from the entry without passing a G31 block (whose own reads come
    // before its skip).
    let mut seen = vec![false; len];
    let mut stack = vec![0usize];
    seen[0] = true;
    while let Some(i) = stack.pop() {
        if let Node::Items(items) = &flat.nodes[i] {
            if items.iter().any(is_g31) {
                continue;
            }
        }
        for j in succs(&flat, i) {
            if j < len && !seen[j] {
                seen[j] = true;
                stack.push(j);
            }
        }
    }
    for i in (0..len).filter(|&i| seen[i]) {
        for (a, sp) in reads_at(i) {
            ctx.unsupported(
                "NC536",
                sp,
                &format!("#{} read where a path reaches it without a G31 of this program before it", 5061 + a),
                "probe (G31) in the program that reads the skip position, before the read on every path; Siemens \
                 keeps $AA_MW only from a probe that switched, so a skip position from elsewhere has no counterpart",
            );
        }
    }
    axes
}

/// Rewrites the G31 blocks and the `#5061+` reads (`axes`: what [`scan`] found read).
pub fn lower(ctx: &mut Ctx, mut body: Vec<Stmt>, axes: u16) -> Vec<Stmt> {
    if axes != 0 {
        map_exprs(&mut body, &mut |e: &mut Expr| rename_reads(e));
        for i in (0..AXES.len()).filter(|i| axes & (1 << i) != 0) {
            let plan = &mut ctx.progs[ctx.cur];
            if !plan.defs.iter().any(|(n, _)| *n == skip_name(i)) {
                plan.defs.push((skip_name(i), DataType::Real));
            }
        }
    }
    map_bodies(body, &mut |list: Vec<Stmt>| {
        let mut out = Vec::with_capacity(list.len());
        let mut list = list.into_iter().peekable();
        while let Some(s) = list.next() {
            match s.kind {
                StmtKind::Block(b) if b.items.iter().any(is_g31) => {
                    // The next block selecting the motion mode itself needs no restore.
                    let next_selects = list.peek().is_some_and(crate::lower::to_fanuc::probe::selects_motion);
                    measuring_block(ctx, b, s.span, axes, next_selects, &mut out)
                }
                kind => out.push(Stmt { kind, span: s.span }),
            }
        }
        out
    })
}

fn rename_reads(e: &mut Expr) {
    if let ExprKind::Var(v) = &mut e.kind {
        if let VarKind::Hash(n @ 5061..=5066) = v.kind {
            v.kind = VarKind::Named { name: skip_name((n - 5061) as usize), indices: vec![] };
            return;
        }
    }
    match &mut e.kind {
        ExprKind::Var(v) => match &mut v.kind {
            VarKind::Named { indices, .. } | VarKind::System { indices, .. } => {
                indices.iter_mut().for_each(rename_reads)
            }
            VarKind::HashIndirect(x) | VarKind::RIndirect(x) => rename_reads(x),
            _ => {}
        },
        ExprKind::Binary(_, a, b) | ExprKind::Cmp(_, _, a, b) => {
            rename_reads(a);
            rename_reads(b);
        }
        ExprKind::Unary(_, a) => rename_reads(a),
        ExprKind::Func(_, args) => args.iter_mut().for_each(rename_reads),
        _ => {}
    }
}

fn sys(name: &str, axis: usize, span: Span) -> Expr {
    var_expr(
        VarKind::System { name: name.into(), indices: vec![Expr::new(ExprKind::Ident(AXES[axis].into()), span)] },
        span,
    )
}

/// `NCTRANS_SKIP_<axis>=value`, Z with the length offset FANUC's `#5063` holds.
fn keep(ctx: &Ctx, axis: usize, value: Expr, span: Span) -> Stmt {
    let value = if axis == 2 { super::probe_length::with_length(ctx, span, value) } else { value };
    plain_block(vec![crate::lower::assign_item(&named_ref(&skip_name(axis), span), value, span)], span)
}

fn measuring_block(ctx: &mut Ctx, mut b: Block, span: Span, axes: u16, next_selects: bool, out: &mut Vec<Stmt>) {
    if let Some(p) = b.items.iter().find(|it| matches!(&it.kind, ItemKind::Word(w) if w.addr == Addr::Letter(b'P'))) {
        if let Some(st) = ctx.unsupported(
            "NC538",
            p.span,
            "G31 P (multi-step skip: the skip signal chosen by P)",
            "write G31 without P (skip signal 1, Siemens MEAS=1)",
        ) {
            out.push(st);
        }
        return;
    }
    let motion = ctx.modal.motion_at(span.lo);
    let restore = match motion {
        _ if next_selects => None,
        Some(10) => None,
        Some(g @ (0 | 20 | 30)) => Some(g),
        _ => {
            if let Some(st) = ctx.unsupported(
                "NC537",
                span,
                "G31 where the motion mode (G0/G1/G2/G3) in force after it depends on the path taken",
                "select G0 or G1 before the G31 on every path, so the mode after it is known",
            ) {
                out.push(st);
            }
            return;
        }
    };
    let programmed: Vec<usize> = b
        .items
        .iter()
        .filter_map(|it| match &it.kind {
            ItemKind::Word(Word { addr: Addr::Letter(l), .. }) => AXES.iter().position(|a| a.as_bytes()[0] == *l),
            _ => None,
        })
        .collect();
    let g31 = b.items.iter().position(is_g31).unwrap_or(0);
    let gsp = b.items[g31].span;
    b.items.remove(g31);
    let meas = Item {
        kind: ItemKind::Word(Word { addr: Addr::Name("MEAS".into()), value: WordValue::Expr(int(1, gsp)), span: gsp }),
        span: gsp,
    };
    b.items.insert(0, super::words::g_word(10, gsp));
    b.items.insert(0, meas);
    out.push(Stmt { kind: StmtKind::Block(b), span });
    let read: Vec<usize> = (0..AXES.len()).filter(|i| axes & (1 << i) != 0).collect();
    if !read.is_empty() {
        out.push(plain_block(vec![Item { kind: ItemKind::Stopre, span }], span));
        let moved: Vec<usize> = read.iter().copied().filter(|a| programmed.contains(a)).collect();
        if !moved.is_empty() {
            let cond = Expr::new(
                ExprKind::Cmp(
                    CmpOp::Eq,
                    Tolerance::Relative,
                    Box::new(var_expr(VarKind::System { name: "AC_MEA".into(), indices: vec![int(1, span)] }, span)),
                    Box::new(int(1, span)),
                ),
                span,
            );
            let meta = BlockMeta { span, ..BlockMeta::default() };
            out.push(Stmt {
                kind: StmtKind::If(Box::new(IfStmt {
                    head: meta.clone(),
                    cond,
                    then_body: moved.iter().map(|&a| keep(ctx, a, sys("AA_MW", a, span), span)).collect(),
                    else_part: Some(ElsePart {
                        head: meta.clone(),
                        body: moved.iter().map(|&a| keep(ctx, a, sys("AA_IW", a, span), span)).collect(),
                    }),
                    end: meta,
                })),
                span,
            });
        }
        for &a in read.iter().filter(|a| !programmed.contains(a)) {
            out.push(keep(ctx, a, sys("AA_IW", a, span), span));
        }
    }
    if let Some(g) = restore {
        out.push(plain_block(vec![super::words::g_word(g, span)], span));
    }
}
