//! Siemens `WRITE(err, "file", "TEXT")` to FANUC: `POPEN`, `DPRNT[TEXT]`, `PCLOS`, and the
//! error variable set to 0 as the control sets it after a write that succeeded. FANUC prints
//! to the I/O channel, so the file name goes into a comment. Only a constant text whose every
//! character DPRNT prints as itself is carried (letters, digits, `+ - /`; a space becomes `*`):
//! a text built at run time (`"X"<<R1`) or another character is refused (NC557).

use super::*;

/// The statements that stand for `p` (a Siemens WRITE) in the FANUC output.
pub fn lower(ctx: &mut Ctx, p: Print, span: Span) -> Vec<Stmt> {
    let text = match &p.parts[..] {
        [PrintPart::Str(Expr { kind: ExprKind::Str(t), .. })] => t.clone(),
        [PrintPart::Str(e)] => {
            let what = format!("WRITE of the computed text `{}`", crate::dialect::sinumerik::emit::expr(e));
            let hint =
                "FANUC DPRNT prints text and number fields, whose text is not modelled (NC554); write a constant text";
            return ctx.unsupported("NC557", span, &what, hint).into_iter().collect();
        }
        _ => {
            return ctx
                .unsupported("NC557", span, "this WRITE", "write `WRITE(ERR, \"FILE\", \"TEXT\")`")
                .into_iter()
                .collect()
        }
    };
    if let Some(c) = text.chars().find(|&c| c != ' ' && !crate::dialect::fanuc::print::is_print_char(c)) {
        let what = format!("WRITE of the text \"{text}\" (its character `{c}`)");
        let hint = "DPRNT prints upper-case letters, digits, + - / and * for a space; write the text with those";
        return ctx.unsupported("NC557", span, &what, hint).into_iter().collect();
    }
    let file = match p.file.as_ref().map(|f| &f.kind) {
        Some(ExprKind::Str(f)) => f.clone(),
        Some(_) => crate::dialect::sinumerik::emit::expr(p.file.as_ref().expect("matched")),
        None => String::new(),
    };
    let mut out = Vec::new();
    if let Some(status) = &p.status {
        out.push(block_stmt(vec![assign_item(status, num(0.0, span), span)], span));
    }
    let mut open = BlockMeta { span, ..BlockMeta::default() };
    open.comments.push(Comment { text: format!("WRITE TO {file}: DPRNT PRINTS TO THE I/O CHANNEL"), span });
    out.push(meta_stmt(open, vec![item(ItemKind::Instruction { name: "POPEN".into() }, span)]));
    let print = Print { parts: vec![PrintPart::Text(text)], file: None, status: None };
    out.push(block_stmt(vec![item(ItemKind::Print(Box::new(print)), span)], span));
    out.push(block_stmt(vec![item(ItemKind::Instruction { name: "PCLOS".into() }, span)], span));
    out
}

/// `p` without the comments a FANUC → Sinumerik translation wrote about POPEN, PCLOS and
/// the WRITE file, and without the error variable of its WRITEs where nothing reads it (the
/// `NCTRANS_WERR` a FANUC → Sinumerik translation declares is such a one): FANUC needs no
/// variable for it, so none is written and a round trip comes back to the same text. `None`
/// when there is none.
pub fn drop_unread_status(p: &Program) -> Option<Program> {
    let mut statuses: Vec<String> = Vec::new();
    let mut read: Vec<String> = Vec::new();
    crate::ir::visit::walk_stmts(&p.body, &mut |s| {
        let StmtKind::Block(b) = &s.kind else { return };
        for it in &b.items {
            if let ItemKind::Print(pr) = &it.kind {
                if let Some(VarRef { kind: VarKind::Named { name, indices }, .. }) = pr.status.as_deref() {
                    if indices.is_empty() {
                        statuses.push(name.clone());
                    }
                }
            }
            if let ItemKind::Assign { target, .. } = &it.kind {
                if let VarKind::Named { name, .. } = &target.kind {
                    read.push(name.clone());
                }
            }
        }
    });
    // Every expression, structure conditions included (a WRITE's error variable is not one).
    let mut body = p.body.clone();
    crate::lower::map_exprs(&mut body, &mut |e| names(e, &mut read));
    statuses.retain(|n| !read.contains(n));
    let notes = p.body.iter().any(|s| matches!(&s.kind, StmtKind::Block(b) if own_note_block(b)));
    if statuses.is_empty() && !notes {
        return None;
    }
    let mut p = p.clone();
    p.body = crate::lower::map_bodies(std::mem::take(&mut p.body), &mut |list| {
        list.into_iter()
            .filter_map(|mut s| {
                if let StmtKind::Block(b) = &mut s.kind {
                    if own_note_block(b) {
                        return None;
                    }
                    let had = b.items.len();
                    b.items.retain_mut(|it| match &mut it.kind {
                        ItemKind::Print(pr) => {
                            if matches!(pr.status.as_deref(), Some(VarRef { kind: VarKind::Named { name, .. }, .. }) if statuses.contains(name))
                            {
                                pr.status = None;
                            }
                            true
                        }
                        ItemKind::Def(d) if d.scope.is_none() => {
                            d.vars.retain(|v| !statuses.contains(&v.name));
                            !d.vars.is_empty()
                        }
                        _ => true,
                    });
                    let m = &b.meta;
                    if had > 0 && b.items.is_empty() && m.label.is_none() && m.number.is_none() && m.comments.is_empty() {
                        return None;
                    }
                }
                Some(s)
            })
            .collect()
    });
    Some(p)
}

/// A comment-only block a FANUC → Sinumerik translation wrote for POPEN, PCLOS or the
/// WRITE file (`lower::to_sinumerik::print::is_own_note`).
fn own_note_block(b: &Block) -> bool {
    let m = &b.meta;
    b.items.is_empty()
        && m.label.is_none()
        && m.number.is_none()
        && matches!(&m.comments[..], [c] if crate::lower::to_sinumerik::print::is_own_note(&c.text))
}

fn names(e: &Expr, out: &mut Vec<String>) {
    if let ExprKind::Var(v) = &e.kind {
        if let VarKind::Named { name, .. } = &v.kind {
            out.push(name.clone());
        }
    }
    for c in e.children() {
        names(c, out);
    }
}
