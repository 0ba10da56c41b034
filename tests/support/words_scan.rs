//! The words-scan comparison of one program file (shared by `tests/stream_words.rs` and the
//! external programs' test): `stream::scan_words` against `scan_index` and the whole-file
//! `scan`, with plain lines taken as words and not, by the quick readers and not; and
//! (`same_as_whole_parse`) the streamed `scan` against the whole-file parse, the reference.

use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::ir::{Addr, BlockMeta, ExprKind, ItemKind, Stmt, StmtKind, WordValue};
use nctrans::stream::{self, Canon, PlainWord, WordsSink};
use std::path::{Path, PathBuf};

/// What a sink got, one entry per statement: a plain line as its meta and words, or a
/// statement's debug form.
#[derive(Debug, PartialEq)]
enum Got {
    Plain {
        prog: usize,
        number: Option<u32>,
        span: (u32, u32),
        comments: Vec<String>,
        words: Vec<(u8, u64, bool, (u32, u32))>,
    },
    Stmt(usize, String),
}

/// A plain block of a whole-file statement, as [`Got::Plain`]; else its debug form.
fn of_stmt(prog: usize, s: &Stmt, plain_ok: bool) -> Got {
    if plain_ok {
        if let StmtKind::Block(b) = &s.kind {
            let words: Option<Vec<_>> = b
                .items
                .iter()
                .map(|it| match &it.kind {
                    ItemKind::Word(w) => match (&w.addr, &w.value) {
                        (Addr::Letter(l), WordValue::Expr(e)) => match &e.kind {
                            ExprKind::Num(n) => Some((*l, n.value.to_bits(), n.point, (it.span.lo, it.span.hi))),
                            _ => None,
                        },
                        _ => None,
                    },
                    _ => None,
                })
                .collect();
            if let Some(words) = words.filter(|_| b.meta.label.is_none() && b.meta.skip.is_none()) {
                return plain(prog, &b.meta, words);
            }
        }
    }
    Got::Stmt(prog, format!("{s:?}"))
}

fn plain(prog: usize, meta: &BlockMeta, words: Vec<(u8, u64, bool, (u32, u32))>) -> Got {
    Got::Plain {
        prog,
        number: meta.number.as_ref().map(|n| n.value),
        span: (meta.span.lo, meta.span.hi),
        comments: meta.comments.iter().map(|c| c.text.clone()).collect(),
        words,
    }
}

struct Record {
    got: Vec<Got>,
    /// Whether plain lines are taken as words (else each is asked for as a statement).
    take: bool,
    /// Whether the scan may read plain lines with the quick readers (else all the general way).
    quick: bool,
}

impl WordsSink for Record {
    fn plain(&mut self, prog: usize, meta: &BlockMeta, words: &[PlainWord], _: &nctrans::read::RawBlock<'_>) -> bool {
        if self.take {
            let words = words.iter().map(|w| (w.letter, w.value.to_bits(), w.point, (w.span.lo, w.span.hi))).collect();
            self.got.push(plain(prog, meta, words));
        }
        self.take
    }

    fn stmt(&mut self, prog: usize, s: &Stmt) {
        self.got.push(Got::Stmt(prog, format!("{s:?}")));
    }

    fn active(&self) -> bool {
        true
    }

    fn quick(&self) -> bool {
        self.quick
    }
}

/// The plain lines a words scan should take, found as the words scan did before it read
/// a line once (`scan_plain_words`): a re-reading reader reads the line into its words
/// (`plain_words`; FANUC: no block skip) and the index-only reader takes it whole
/// (`scan_plain`); every other line goes through the index reader's `line`. `None` for a
/// file that is not UTF-8.
fn plain_lines_two_readers(path: &Path, dialect: Dialect) -> Option<Vec<Got>> {
    use nctrans::dialect::{fanuc, sinumerik};
    use nctrans::span::Span;
    let bytes = std::fs::read(path).ok()?;
    let text = std::str::from_utf8(bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(&bytes)).ok()?;
    let opts = ParseOptions::for_dialect(dialect);
    let mut out = Vec::new();
    let mut stmts = Vec::new();
    let mut words: Vec<PlainWord> = Vec::new();
    fn push(words: &mut Vec<PlainWord>) -> impl FnMut(u8, f64, bool, Span) -> bool + '_ {
        |letter, value, point, span| {
            words.push(PlainWord { letter, value, point, span, canon: Canon::NONE });
            true
        }
    }
    // What a sink gets for a plain line (the Sinumerik comment as the scan finds it).
    let got = |prog: usize, raw: &nctrans::read::RawBlock<'_>, span: Span, number, words: &[PlainWord]| {
        let from = words.last().map_or(0, |w| (w.span.hi - raw.start) as usize);
        let comment = match dialect {
            Dialect::Sinumerik => {
                raw.text.get(from..).and_then(|t| t.find(';')).map(|i| raw.text[from + i + 1..].to_string())
            }
            Dialect::Fanuc => None,
        };
        Got::Plain {
            prog,
            number,
            span: (span.lo, span.hi),
            comments: comment.into_iter().collect(),
            words: words.iter().map(|w| (w.letter, w.value.to_bits(), w.point, (w.span.lo, w.span.hi))).collect(),
        }
    };
    match dialect {
        Dialect::Sinumerik => {
            let mut r = sinumerik::Reader::new(0, &opts, text.len() as u32);
            r.compact_targets();
            r.index_only();
            let mut w = sinumerik::Reader::resume(0, &opts, &r.checkpoint());
            for raw in nctrans::read::blocks(text) {
                words.clear();
                // A test input line goes as a statement (`stream::scan_words`).
                let input = raw.text.split_once(';').is_some_and(|(_, c)| nctrans::lower::own_header::is_test_input(c));
                if !input && w.plain_words(&raw, false, push(&mut words)).is_some() {
                    if let Some((span, number)) = r.scan_plain(&raw, false) {
                        out.push(got(0, &raw, span, number.map(|n| n.value), &words));
                        continue;
                    }
                }
                r.line(&raw);
                r.drain_into(&mut stmts);
                stmts.clear();
            }
        }
        Dialect::Fanuc => {
            let mut r = fanuc::Reader::new(0, &opts);
            r.index_only();
            let mut w = fanuc::Reader::resume(0, &opts, r.checkpoint());
            for raw in nctrans::read::blocks(text) {
                words.clear();
                let skip = raw.text.trim_start_matches([' ', '\t', '\x0C']).starts_with('/');
                if !skip && w.plain_words(&raw, false, push(&mut words)).is_some() {
                    if let Some((span, number)) = r.scan_plain(&raw, false) {
                        out.push(got(r.current(), &raw, span, number.map(|n| n.value), &words));
                        continue;
                    }
                }
                r.line(&raw);
                r.drain_into(&mut stmts);
                stmts.clear();
            }
        }
    }
    Some(out)
}

/// Checks one file; returns how many lines went as words.
pub fn check(path: &Path, dialect: Dialect) -> usize {
    let opts = ParseOptions::for_dialect(dialect);
    let Ok(index) = stream::scan_index_path(path, 0, dialect, &opts, None) else { return 0 };
    let mut whole = Vec::new();
    let full = stream::scan_path(path, 0, dialect, &opts, &mut |p, s| whole.push((p, s.clone())), None).expect("scan");
    let mut words = 0;
    for (take, quick) in [(true, true), (false, true), (true, false), (false, false)] {
        let mut rec = Record { got: Vec::new(), take, quick };
        let ix = stream::scan_words_path(path, 0, dialect, &opts, &mut rec, None).expect("scan_words");
        assert_eq!(format!("{ix:?}"), format!("{index:?}"), "index of {}", path.display());
        // The whole-file scan's index is the same too (but for what index-only readers
        // leave out: compare what the runs need).
        assert_eq!(ix.blocks, full.blocks, "{}", path.display());
        assert_eq!(ix.diags.len(), full.diags.len(), "{}", path.display());
        let expected: Vec<Got> = if take {
            // Which whole-file statements are plain lines: those the words scan took.
            let mut exp = Vec::new();
            for (k, (p, s)) in whole.iter().enumerate() {
                let as_plain = matches!(rec.got.get(k), Some(Got::Plain { .. }));
                exp.push(of_stmt(*p, s, as_plain));
            }
            words = rec.got.iter().filter(|g| matches!(g, Got::Plain { .. })).count();
            exp
        } else {
            whole.iter().map(|(p, s)| Got::Stmt(*p, format!("{s:?}"))).collect()
        };
        if take {
            // Exactly the lines the two readers took as words, with the same words.
            if let Some(two) = plain_lines_two_readers(path, dialect) {
                let plain: Vec<&Got> = rec.got.iter().filter(|g| matches!(g, Got::Plain { .. })).collect();
                assert_eq!(plain.len(), two.len(), "plain lines of {}", path.display());
                for (a, b) in plain.iter().zip(&two) {
                    assert_eq!(*a, b, "{}", path.display());
                }
            }
        }
        assert_eq!(rec.got.len(), expected.len(), "{} (take {take}, quick {quick})", path.display());
        for (a, b) in rec.got.iter().zip(&expected) {
            assert_eq!(a, b, "{} (take {take}, quick {quick})", path.display());
        }
    }
    words
}

pub fn files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let Ok(rd) = std::fs::read_dir(dir) else { return out };
    for e in rd.filter_map(|e| e.ok()) {
        let p = e.path();
        if p.is_dir() {
            out.extend(files(&p));
        } else {
            out.push(p);
        }
    }
    out.sort();
    out
}

/// The statements the streamed whole scan (`stream::scan_path`) hands out are exactly the
/// whole-file parse's (the pest reader, the reference), program by program. Returns whether
/// it compared: `false` for a file the whole-file parse refuses (errors) or does not read.
pub fn same_as_whole_parse(path: &Path, dialect: Dialect) -> bool {
    let opts = ParseOptions::for_dialect(dialect);
    let bytes = std::fs::read(path).expect("read");
    let mut db = nctrans::span::SourceDb::new();
    let loaded = nctrans::load(&mut db, &path.display().to_string(), &bytes, None);
    let parsed = nctrans::parse(&db, loaded.file, dialect, &opts);
    if nctrans::diag::has_errors(&parsed.diags) {
        return false;
    }
    let mut streamed = Vec::new();
    let Ok(_) = stream::scan_path(path, 0, dialect, &opts, &mut |p, s| streamed.push((p, format!("{s:?}"))), None)
    else {
        return false;
    };
    let whole: Vec<(usize, String)> = parsed
        .unit
        .programs
        .iter()
        .enumerate()
        .flat_map(|(k, p)| p.body.iter().map(move |s| (k, format!("{s:?}"))))
        .collect();
    assert_eq!(streamed.len(), whole.len(), "statements of {}", path.display());
    for (a, b) in streamed.iter().zip(&whole) {
        assert_eq!(a, b, "{}", path.display());
    }
    true
}
