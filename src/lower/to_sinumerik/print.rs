//! FANUC text output to Siemens: `DPRNT[PART*OK]` → `WRITE(NCTRANS_WERR,"NCTRANS_PRINT","PART OK")`.
//! FANUC prints to the I/O channel POPEN opened; `WRITE` appends the line to a file, which
//! the profile names (`[sinumerik] write_file`), and sets an INT error variable the output
//! declares. Only text is carried: the text of a number field (`#100[53]`) is not modelled
//! (NC554: no stored source settles its spaces, zeros, sign or rounding), and neither `<<`
//! (a REAL in its own form) nor SPRINT (whose `%F` rules no stored page gives) is proven to
//! write it, so a field is refused (NC556).
//! `POPEN` / `PCLOS` become comments: WRITE needs no channel opened or closed.

use super::*;

/// The error variable every translated `WRITE` sets.
pub const WRITE_STATUS: &str = "NCTRANS_WERR";

/// The item for `p` (a FANUC DPRNT), or the statement (comment, refusal) that stands for it.
pub fn lower(ctx: &mut Ctx, p: Print, span: Span, out: &mut Vec<Stmt>) -> Option<Item> {
    if let Some(f) = p.parts.iter().find_map(crate::eval::print::field_format) {
        let what = format!("the DPRNT number field `{f}`");
        let hint = "Siemens `<<` writes a REAL in its own form, not in fixed places, and SPRINT's `%F` rules are \
                    not sourced; print the text alone, or build the number's text by hand";
        let msg = format!(
            "{what}: its text is not modelled (NC554: no source settles its leading spaces or zeros, the sign's \
             place or the rounding) and Siemens cannot be proven to write the same, so it is not translated"
        );
        if let Some(st) = ctx.refuse("NC556", span, &msg, &what, hint) {
            out.push(st);
        }
        return None;
    }
    let text: String = p
        .parts
        .iter()
        .map(|part| match part {
            PrintPart::Text(t) => t.as_str(),
            _ => "",
        })
        .collect();
    let file = ctx.opts.target.write_file.clone();
    let plan = &mut ctx.progs[ctx.cur];
    if !plan.defs.iter().any(|(n, _)| n == WRITE_STATUS) {
        plan.defs.push((WRITE_STATUS.to_string(), DataType::Int));
        let note = format!("DPRNT lines are written to file {file} ([sinumerik] write_file in nctrans.toml)");
        out.push(comment_stmt(note, span));
    }
    let print = Print {
        parts: vec![PrintPart::Str(Expr::new(ExprKind::Str(text), span))],
        file: Some(Expr::new(ExprKind::Str(file), span)),
        status: Some(Box::new(named_ref(WRITE_STATUS, span))),
    };
    Some(Item { kind: ItemKind::Print(Box::new(print)), span })
}

/// The comment `lower::to_fanuc::print` puts on the POPEN of a translated WRITE.
pub fn is_write_note(text: &str) -> bool {
    let t = text.trim();
    t.starts_with("WRITE TO ") && t.ends_with(": DPRNT PRINTS TO THE I/O CHANNEL")
}

/// The comments this module writes (dropped when the output is translated back to FANUC,
/// so a round trip does not pile them up).
pub fn is_own_note(text: &str) -> bool {
    let t = text.trim();
    t == "POPEN: WRITE opens and closes its file itself"
        || t == "PCLOS: WRITE opens and closes its file itself"
        || t.starts_with("DPRNT lines are written to file ") && t.ends_with("([sinumerik] write_file in nctrans.toml)")
}

/// `POPEN` / `PCLOS`: the comment that says why nothing stands for it.
pub fn channel_comment(name: &str, span: Span) -> Stmt {
    comment_stmt(format!("{name}: WRITE opens and closes its file itself"), span)
}
