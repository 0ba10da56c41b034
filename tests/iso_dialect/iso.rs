//! A trivial third dialect, written outside the crate against its public API only: plain
//! ISO G-code (N, G0–G3 with X Y Z I J K R F, G17–G19, G20/G21, G90/G91, S, M3/M4/M5,
//! M30, `( )` comments, `%`). It runs as FANUC with its own profile (calculator-type
//! input: `X10` is 10 mm, as plain G-code writers mean it), reads into real IR nodes with
//! spans, refuses in its lowering everything beyond plain motion, and writes plain text.
//! Its diagnostics are NC519.

use nctrans::diag::Diagnostic;
use nctrans::dialect::{Dialect, ParseOptions, Parsed, Semantics, Spec, Written};
use nctrans::ir::*;
use nctrans::read::LineEnding;
use nctrans::span::{FileId, SourceFile, Span};

/// The ISO subset's description.
pub struct Iso;

/// The G codes the subset has.
const G_CODES: [u32; 11] = [0, 1, 2, 3, 17, 18, 19, 20, 21, 90, 91];
/// The M codes besides M30 (the end, `ItemKind::End`).
const M_CODES: [u32; 3] = [3, 4, 5];
/// The addresses with a value besides G, M and a leading N.
const VALUE_LETTERS: &[u8] = b"XYZIJKRFS";

fn err(file: FileId, span: Span, msg: impl Into<String>, label: &str, hint: &str) -> Diagnostic {
    Diagnostic::error("NC519", msg).primary(file, span, label).hint(hint)
}

fn sp(lo: usize, hi: usize) -> Span {
    Span::new(lo as u32, hi as u32)
}

/// Reads one line (`at`: its offset in the file) into a block, or the first error in it.
fn block(file: FileId, line: &str, at: usize) -> Result<Block, Diagnostic> {
    let b = line.as_bytes();
    let mut meta = BlockMeta { span: sp(at, at + line.trim_end().len()), ..BlockMeta::default() };
    let mut items = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        if c == b' ' || c == b'\t' {
            i += 1;
            continue;
        }
        if c == b'(' {
            let Some(close) = line[i..].find(')') else {
                return Err(err(
                    file,
                    sp(at + i, at + line.len()),
                    "a comment without `)`",
                    "opened here",
                    "close the comment with `)` on the same line",
                ));
            };
            meta.comments
                .push(Comment { text: line[i + 1..i + close].to_string(), span: sp(at + i, at + i + close + 1) });
            i += close + 1;
            continue;
        }
        let start = i;
        let letter = c.to_ascii_uppercase();
        if !letter.is_ascii_alphabetic() {
            let ch = line[i..].chars().next().unwrap_or('?');
            return Err(err(
                file,
                sp(at + i, at + i + ch.len_utf8()),
                format!("`{ch}` where an address letter was expected"),
                "here",
                "plain G-code is letters with numbers, e.g. `G1 X10 F100`",
            ));
        }
        i += 1;
        let num_start = i;
        if i < b.len() && (b[i] == b'-' || b[i] == b'+') {
            i += 1;
        }
        while i < b.len() && (b[i].is_ascii_digit() || b[i] == b'.') {
            i += 1;
        }
        let text = &line[num_start..i];
        let value: f64 = match text.parse() {
            Ok(v) if text.bytes().any(|d| d.is_ascii_digit()) && text.matches('.').count() <= 1 => v,
            _ => {
                return Err(err(
                    file,
                    sp(at + start, at + i.max(start + 1)),
                    format!("`{}` without a number", letter as char),
                    "a number was expected after the letter",
                    "write the value, e.g. `X10` or `X-2.5`",
                ));
            }
        };
        let point = text.contains('.');
        let span = sp(at + start, at + i);
        let nspan = sp(at + num_start, at + i);
        let whole = value.fract() == 0.0 && value >= 0.0 && !point;
        match letter {
            b'N' if items.is_empty() && meta.number.is_none() && whole => {
                meta.number = Some(SeqNo { value: value as u32, span });
                continue;
            }
            b'N' => {
                return Err(err(
                    file,
                    span,
                    "a block number that is not the block's first word",
                    "here",
                    "write `N` first, as a whole number: `N10 G1 X10`",
                ))
            }
            b'G' if whole && G_CODES.contains(&(value as u32)) => {}
            b'M' if whole && value as u32 == 30 => {
                items.push(Item { kind: ItemKind::End { code: EndCode::M30 }, span });
                continue;
            }
            b'M' if whole && M_CODES.contains(&(value as u32)) => {}
            l if VALUE_LETTERS.contains(&l) => {}
            _ => {
                return Err(err(
                    file,
                    span,
                    format!("`{}` is not in the ISO subset", &line[start..i]),
                    "not plain motion",
                    "the subset has G0-G3, G17-G19, G20/G21, G90/G91, X Y Z I J K R F S, M3/M4/M5 and M30",
                ))
            }
        }
        let value = WordValue::Expr(Expr::num(value, point, nspan));
        items.push(Item { kind: ItemKind::Word(Word { addr: Addr::Letter(letter), value, span }), span });
    }
    Ok(Block { meta, items })
}

impl Spec for Iso {
    fn name(&self) -> &str {
        "iso"
    }

    fn extensions(&self) -> &[&str] {
        &["iso", "gcode"]
    }

    /// Lines of plain words score; anything of a macro language scores nothing at all.
    fn sniff(&self, text: &str) -> u32 {
        let mut score = 0;
        for line in text.lines().take(400) {
            if line.contains(['#', '[', '=', ';', '$']) || line.trim_start().starts_with('O') {
                return 0;
            }
            if line.trim_start().starts_with(['G', 'N', 'X', 'Y', 'Z']) {
                score += 1;
            }
        }
        score
    }

    fn runs_as(&self) -> Dialect {
        Dialect::Fanuc
    }

    fn semantics(&self) -> Semantics {
        Semantics { calculator_input: true, ..Semantics::default_for(Dialect::Fanuc) }
    }

    fn parse(&self, src: &SourceFile, file: FileId, _opts: &ParseOptions) -> Parsed {
        let mut body = Vec::new();
        let mut diags = Vec::new();
        let mut at = 0;
        for raw in src.text.split_inclusive('\n') {
            let line = raw.trim_end_matches(['\n', '\r']);
            let trimmed = line.trim();
            if !trimmed.is_empty() && trimmed != "%" {
                match block(file, line, at) {
                    Ok(b) => body.push(Stmt { span: b.meta.span, kind: StmtKind::Block(b) }),
                    Err(d) => diags.push(d),
                }
            }
            at += raw.len();
        }
        let span = match (body.first(), body.last()) {
            (Some(a), Some(b)) => a.span.to(b.span),
            _ => Span::default(),
        };
        let programs = if body.is_empty() {
            vec![]
        } else {
            vec![Program { name: None, head: None, params: vec![], save: false, body, span }]
        };
        let unit = Unit { dialect: Dialect::Fanuc, file, programs };
        // Nothing to run is said as every reader says it (NC145).
        if diags.is_empty() && nctrans::dialect::empty::program_less(&unit) {
            diags.push(nctrans::dialect::empty::diagnostic(file, &src.text));
        }
        Parsed { unit, diags, after_end_programs: vec![] }
    }

    fn lower(&self, unit: &Unit, source: &Semantics) -> Result<Unit, Vec<Diagnostic>> {
        let f = unit.file;
        let mut diags = Vec::new();
        for p in unit.programs.iter().skip(1) {
            diags.push(err(
                f,
                p.span,
                "a second program",
                "ISO has one program per file",
                "translate a program without subprograms",
            ));
        }
        if let Some(p) = unit.programs.first() {
            for s in &p.body {
                let StmtKind::Block(b) = &s.kind else {
                    diags.push(err(
                        f,
                        s.span,
                        "a control structure has no ISO spelling",
                        "a loop or branch",
                        "the ISO subset is plain motion: unroll it",
                    ));
                    continue;
                };
                if b.meta.skip.is_some() {
                    diags.push(err(
                        f,
                        b.meta.span,
                        "a block skip `/` has no ISO spelling",
                        "this block",
                        "remove the `/`",
                    ));
                }
                if let Some(l) = &b.meta.label {
                    diags.push(err(
                        f,
                        l.span,
                        "a jump label has no ISO spelling",
                        "this label",
                        "the ISO subset has no jumps",
                    ));
                }
                for c in b.meta.comments.iter().filter(|c| c.text.contains(['(', ')'])) {
                    diags.push(err(
                        f,
                        c.span,
                        "a comment with a parenthesis",
                        "ISO comments end at `)`",
                        "reword the comment",
                    ));
                }
                for it in &b.items {
                    if let Some(what) = refused(it) {
                        diags.push(err(
                            f,
                            it.span,
                            format!("{what} has no ISO spelling"),
                            "not plain motion",
                            "the ISO subset is plain motion: G0-G3 with literal coordinates, S, M3/M4/M5, M30",
                        ));
                    }
                }
            }
        }
        if !diags.is_empty() {
            return Err(diags);
        }
        let mut u = unit.clone();
        let d = nctrans::lower::restate::restate(&mut u, source, &self.semantics());
        if nctrans::diag::has_errors(&d) {
            return Err(d);
        }
        Ok(u)
    }

    fn emit(&self, unit: &Unit, line_ending: LineEnding) -> Written {
        let mut lines = vec!["%".to_string()];
        for p in &unit.programs {
            if let Some(h) = p.head.as_ref().filter(|h| !h.comments.is_empty()) {
                lines.push(h.comments.iter().map(|c| format!("({})", c.text)).collect::<Vec<_>>().join(" "));
            }
            for s in &p.body {
                let StmtKind::Block(b) = &s.kind else { continue };
                let mut words: Vec<String> = b.meta.number.iter().map(|n| format!("N{}", n.value)).collect();
                for it in &b.items {
                    match &it.kind {
                        ItemKind::End { .. } => words.push("M30".into()),
                        ItemKind::Word(Word { addr, value: WordValue::Expr(e), .. }) => {
                            if let ExprKind::Num(n) = e.kind {
                                words.push(format!("{}{}", addr.as_str(), n.value));
                            }
                        }
                        _ => {}
                    }
                }
                words.extend(b.meta.comments.iter().map(|c| format!("({})", c.text)));
                if !words.is_empty() {
                    lines.push(words.join(" "));
                }
            }
        }
        lines.push("%".into());
        let eol = line_ending.as_str();
        Written { text: lines.join(eol) + eol, diags: vec![] }
    }
}

/// What an item is when the subset cannot write it (`None`: plain motion).
fn refused(it: &Item) -> Option<String> {
    Some(match &it.kind {
        ItemKind::End { code: EndCode::M30 } => return None,
        ItemKind::Word(Word { addr: Addr::Letter(l), value: WordValue::Expr(e), .. }) => {
            let ExprKind::Num(n) = e.kind else { return Some(format!("a computed `{}` value", *l as char)) };
            let whole = n.value.fract() == 0.0 && n.value >= 0.0;
            let ok = match l {
                b'G' => whole && G_CODES.contains(&(n.value as u32)),
                b'M' => whole && M_CODES.contains(&(n.value as u32)),
                l => VALUE_LETTERS.contains(l),
            };
            if ok {
                return None;
            }
            format!("`{}{}`", *l as char, n.value)
        }
        ItemKind::Word(w) => format!("the word `{}`", w.addr.as_str()),
        ItemKind::Assign { .. } => "a variable assignment".into(),
        ItemKind::Goto(_) => "a jump".into(),
        ItemKind::Call(_) => "a subprogram call".into(),
        ItemKind::End { .. } => "an end other than M30".into(),
        ItemKind::Return { .. } => "a return".into(),
        _ => "this statement".into(),
    })
}
