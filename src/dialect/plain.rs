//! What a streamed translator's fast writer reads of a block: a word of a plain line as the
//! quick readers hand it out ([`PlainWord`], no IR built), and one view ([`View`]) of an IR
//! item or such a word, so that both go through the same writer code.

use crate::dialect::sinumerik::scan_words::Canon;
use crate::ir::{Addr, Item, ItemKind, WordValue};
use crate::span::Span;

/// One word of a plain line read straight into words (`stream::scan_words`): the letter (upper
/// case), the value (negated when written with `-`), whether it was written with a point,
/// and the word's span; the item the whole-file reader builds for it is a word of that
/// letter holding that number.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlainWord {
    pub letter: u8,
    pub value: f64,
    pub point: bool,
    pub span: Span,
    /// The word's text in the writers' form when the quick reader found it so
    /// (`Canon::NONE` from the general readers: the writers then read the text).
    pub canon: Canon,
}

/// What the streamed translators' fast paths look at in an item, the same whether it is an
/// IR item or a [`PlainWord`] (so both go through one code).
pub enum View {
    /// A word: its letter when it has a letter address and an expression value (else
    /// `None`), whether the address is `G`, the value when it is a number as written
    /// (value, point), and when it is one after folding a `-n`.
    Word { letter: Option<u8>, is_g: bool, num: Option<(f64, bool)>, folded: Option<f64> },
    /// A program end.
    End(crate::ir::EndCode),
    /// Anything else.
    Other,
}

/// An item as [`View`].
pub trait ItemView {
    fn view(&self) -> View;
}

impl ItemView for Item {
    #[inline]
    fn view(&self) -> View {
        use crate::ir::{ExprKind, UnOp};
        match &self.kind {
            ItemKind::Word(w) => {
                let e = match &w.value {
                    WordValue::Expr(e) => Some(e),
                    _ => None,
                };
                let num = match e.map(|e| &e.kind) {
                    Some(ExprKind::Num(n)) => Some((n.value, n.point)),
                    _ => None,
                };
                let folded = match e.map(|e| &e.kind) {
                    Some(ExprKind::Num(n)) => Some(n.value),
                    Some(ExprKind::Unary(UnOp::Neg, x)) => match &x.kind {
                        ExprKind::Num(n) => Some(-n.value),
                        _ => None,
                    },
                    _ => None,
                };
                let letter = match (&w.addr, e) {
                    (Addr::Letter(l), Some(_)) => Some(*l),
                    _ => None,
                };
                View::Word { letter, is_g: w.addr.is(b'G'), num, folded }
            }
            ItemKind::End { code } => View::End(*code),
            _ => View::Other,
        }
    }
}

impl ItemView for PlainWord {
    #[inline]
    fn view(&self) -> View {
        View::Word {
            letter: Some(self.letter),
            is_g: self.letter == b'G',
            num: Some((self.value, self.point)),
            folded: Some(self.value),
        }
    }
}
