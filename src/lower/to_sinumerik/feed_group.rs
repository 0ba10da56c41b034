//! The feed of moves with rotary (or U, V, W) axes: FANUC F is the speed along the path of
//! every axis that moves, degrees counted as millimetres; Siemens F is the path feed of the
//! feed group only, the geometry axes X, Y, Z until `FGROUP(…)` names others
//! (docs/semantics.md, "Feed of moves with rotary axes and FGROUP"). A program that has a
//! word of such an axis gets `FGROUP(X,Y,Z,<those axes>)` once at its start (after its
//! DEFs and opening comments), so that every move's feed refers to every axis it moves, as on FANUC; the proof
//! runs both and compares each move's `f`.

use super::*;

/// The axes outside X, Y, Z that words of `body` name (bits as `XYZABCUVW`).
fn extra_axes(body: &[Stmt]) -> (u16, Option<Span>) {
    let mut bits = 0u16;
    let mut first = None;
    crate::ir::visit::walk_stmts(body, &mut |s| {
        if let StmtKind::Block(b) = &s.kind {
            for it in block_items(b) {
                if let ItemKind::Word(Word { addr: Addr::Letter(l), .. }) = &it.kind {
                    if let Some(i) = b"ABCUVW".iter().position(|c| c == l) {
                        bits |= 1 << (i + 3);
                        first.get_or_insert(it.span);
                    }
                }
            }
        }
    });
    (bits, first)
}

/// `body` (the lowered program) with the FGROUP its source `source` needs.
pub fn insert(source: &[Stmt], mut body: Vec<Stmt>) -> Vec<Stmt> {
    let (extra, Some(span)) = extra_axes(source) else { return body };
    let axes = 0b111 | extra;
    let args = (0..9)
        .filter(|i| axes & (1 << i) != 0)
        .map(|i| {
            let name = (b"XYZABCUVW"[i] as char).to_string();
            let v = VarRef { kind: VarKind::Named { name, indices: vec![] }, span };
            Arg::Value(Expr { kind: ExprKind::Var(Box::new(v)), span })
        })
        .collect();
    let call = Call { kind: CallKind::Named, target: CallTarget::Name("FGROUP".into()), args, repeat: None };
    let stmt = crate::lower::block_stmt(vec![Item { kind: ItemKind::Call(Box::new(call)), span }], span);
    let at = body
        .iter()
        .position(|s| {
            // After the DEFs (they must lead) and the comment lines that open the program.
            !matches!(&s.kind, StmtKind::Block(b) if b.meta.label.is_none() && b.items.iter().all(|i| matches!(i.kind, ItemKind::Def(_))))
        })
        .unwrap_or(body.len());
    body.insert(at, stmt);
    body
}
