//! The typed IR shared by both dialects: meaning, not spelling.
//!
//! Owns: the IR types and their visitors, and [`Dialect`] (which dialect a unit was read
//! from; its names and sniffing are `dialect`'s). May use: `span`; nothing else, since
//! every other module uses the IR (`tests/layering.rs`).
//!
//! A parsed file is a [`Unit`] of one or more [`Program`]s (FANUC files may hold several
//! `O` programs). A program is a tree of [`Stmt`]s whose leaves are NC [`Block`]s.
//! Every node carries a [`Span`](crate::span::Span) into the decoded source text.

pub mod cycle;
pub mod dump;
pub mod expr;
pub mod interrupt;
pub mod stmt;
pub mod visit;

pub use expr::*;
pub use stmt::*;

use crate::span::{FileId, Span};

/// The dialect a unit was read from (named, recognised and read in `dialect`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Dialect {
    Sinumerik,
    Fanuc,
}

/// Everything parsed from one file.
#[derive(Clone, Debug, PartialEq)]
pub struct Unit {
    pub dialect: Dialect,
    pub file: FileId,
    pub programs: Vec<Program>,
}

#[derive(Clone, Debug, PartialEq)]
pub enum ProgName {
    /// FANUC `O1234`.
    Number(u32),
    /// Siemens `PROC NAME` or the name from a `%_N_NAME_MPF` header, upper case.
    Name(String),
}

#[derive(Clone, Debug, PartialEq)]
pub struct Program {
    /// `None` for a Siemens main program without header, or a FANUC file without `O`.
    pub name: Option<ProgName>,
    /// The block that names the program (`O1234 (TITLE)`, `PROC NAME(…)`), if any.
    pub head: Option<BlockMeta>,
    /// Siemens `PROC` formal parameters, in order.
    pub params: Vec<Param>,
    /// Siemens `PROC … SAVE`: modal G functions are restored on return.
    pub save: bool,
    pub body: Vec<Stmt>,
    pub span: Span,
}

/// The element count of an array of `dims` (1 for a scalar), saturating: a declaration
/// like `DEF REAL A[70000,70000]` must reach the diagnostic that refuses it, not overflow.
pub fn elements(dims: &[u32]) -> u32 {
    dims.iter().fold(1u32, |a, &d| a.saturating_mul(d)).max(1)
}

/// A Siemens `PROC` formal parameter.
#[derive(Clone, Debug, PartialEq)]
pub struct Param {
    /// Upper case.
    pub name: String,
    pub ty: DataType,
    /// `VAR`: passed by reference.
    pub by_ref: bool,
    /// Array dimensions (`VAR REAL A[3]`); empty for scalars.
    pub dims: Vec<u32>,
    pub span: Span,
}
