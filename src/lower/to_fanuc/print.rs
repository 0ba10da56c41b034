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
