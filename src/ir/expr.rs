//! Expressions, variables and numbers: the meaning of both dialects' arithmetic.
//!
//! Where the two controls disagree, the IR has distinct operations (FANUC `FUP` is not
//! Siemens `ROUNDUP`, FANUC bitwise `AND` is not Siemens logical `AND`, FANUC `EQ` is exact
//! while Siemens `==` has a 1e-12 relative tolerance). Each variant says how each dialect
//! spells it.

use crate::span::Span;

/// A literal number as written.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Number {
    /// The value as written, before any increment scaling: FANUC `X10` is 10.0 here with
    /// `point == false`; the evaluator applies the profile's decimal-point rule.
    pub value: f64,
    /// Whether the literal had a decimal point (`10.`, `1.5`, `.5`). Siemens `EX` exponents
    /// and FANUC values that are not plain integers count as having one.
    pub point: bool,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    pub kind: ExprKind,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub enum ExprKind {
    /// `12`, `1.5`, `1.874EX8`, `'H1F'`, `'B101'`, Siemens `TRUE`/`FALSE` (1/0).
    Num(Number),
    /// FANUC `#0`: the vacant value. Never written by Siemens.
    Vacant,
    /// Siemens `"text"` (strings, tool names, MSG texts).
    Str(String),
    /// A bare identifier used as data: an axis name in `$AA_IW[X]`, a frame component `TR`,
    /// or a label name held as a GOTO target. Resolved by its consumer.
    Ident(String),
    /// Boxed: keeps `Expr` small for the constant-only words of CAM blocks.
    Var(Box<VarRef>),
    Unary(UnOp, Box<Expr>),
    Binary(BinOp, Box<Expr>, Box<Expr>),
    Cmp(CmpOp, Tolerance, Box<Expr>, Box<Expr>),
    Func(Func, Vec<Expr>),
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum UnOp {
    /// `-x` (both).
    Neg,
    /// Siemens `NOT x`: logical negation, 0 → 1, non-zero → 0.
    Not,
    /// Siemens `B_NOT x`: bitwise complement of the integer value.
    BitNot,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BinOp {
    Add,
    Sub,
    Mul,
    /// `/` (both); division by zero is an alarm.
    Div,
    /// Siemens `a DIV b`: integer division (see docs/semantics.md for signs).
    IntDiv,
    /// FANUC `a MOD b` and Siemens `a MOD b` (sign rule in docs/semantics.md).
    Mod,
    /// FANUC `AND`/`OR`/`XOR` between values: bit by bit on the integer parts.
    FanucBitAnd,
    FanucBitOr,
    FanucBitXor,
    /// Siemens `B_AND`/`B_OR`/`B_XOR`: bitwise on INT values.
    BitAnd,
    BitOr,
    BitXor,
    /// Logical `AND`/`OR`/`XOR`: Siemens `AND OR XOR`, FANUC `[c1] AND [c2]` between
    /// conditions. Non-zero is true; the result is 1 or 0.
    And,
    Or,
    Xor,
    /// Siemens `<<`: string concatenation.
    Concat,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CmpOp {
    /// FANUC `EQ`, Siemens `==`.
    Eq,
    /// FANUC `NE`, Siemens `<>`.
    Ne,
    /// FANUC `GT`, Siemens `>`.
    Gt,
    /// FANUC `GE`, Siemens `>=`.
    Ge,
    /// FANUC `LT`, Siemens `<`.
    Lt,
    /// FANUC `LE`, Siemens `<=`.
    Le,
}

/// How a comparison decides equality.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Tolerance {
    /// FANUC: raw values, vacant differs from 0 only in EQ/NE.
    Exact,
    /// Siemens: relative equality with tolerance 1e-12 (MD10280 bit0 = 0 default).
    Relative,
}

/// Built-in functions. Angles are degrees in both controls.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Func {
    /// `SIN` (both).
    Sin,
    /// `COS` (both).
    Cos,
    /// `TAN` (both).
    Tan,
    /// FANUC `ASIN[x]`: 270..90 when NAT=0 (the profile), −90..90 when NAT=1.
    FanucAsin,
    /// FANUC `ACOS[x]`: 180..0.
    FanucAcos,
    /// FANUC `ATAN[y]/[x]` or `ATAN[y,x]`: 0..360 when NAT=0, −180..180 when NAT=1.
    FanucAtan2,
    /// FANUC one-argument `ATAN[t]` (30i).
    FanucAtan,
    /// Siemens `ASIN(x)`: −90..90.
    Asin,
    /// Siemens `ACOS(x)`: 0..180.
    Acos,
    /// Siemens `ATAN2(y,x)`: −180..180.
    Atan2,
    /// `SQRT` (both); negative argument is an alarm.
    Sqrt,
    /// `ABS` (both).
    Abs,
    /// FANUC `ROUND[x]`: half away from zero in arithmetic; in an address, to the increment.
    FanucRound,
    /// Siemens `ROUND(x)`: to integer (ties per docs/semantics.md).
    Round,
    /// FANUC `FIX`, Siemens `TRUNC`: toward zero.
    Trunc,
    /// FANUC `FUP[x]`: away from zero (FUP[−1.2] = −2).
    FanucFup,
    /// Siemens `ROUNDUP(x)`: toward +∞ (ROUNDUP(−3.1) = −3).
    RoundUp,
    /// `LN` (both); x ≤ 0 is an alarm.
    Ln,
    /// `EXP` (both).
    Exp,
    /// Siemens `POT(x)`: x².
    Pot,
    /// FANUC `POW[a,b]` (30i): a^b.
    Pow,
    /// Siemens `MINVAL(a,b)`.
    MinVal,
    /// Siemens `MAXVAL(a,b)`.
    MaxVal,
    /// Siemens `BOUND(min,max,x)`.
    Bound,
    /// FANUC `BIN[x]`: BCD → binary.
    Bin,
    /// FANUC `BCD[x]`: binary → BCD.
    Bcd,
    /// FANUC `ADP[x]` (30i): add a decimal point to a value passed without one.
    Adp,
    /// Siemens `AXNAME("X")`: the axis whose name is the string (upper case).
    AxName,
    /// Siemens string functions (`eval::strings`): `STRLEN(s)`, the number of characters.
    StrLen,
    /// Siemens `TOUPPER(s)` / `TOLOWER(s)`: the letters a–z / A–Z changed.
    ToUpper,
    ToLower,
    /// Siemens `INDEX(s, c)` / `RINDEX(s, c)`: position of the first / last character `c`
    /// (0 = the first character), −1 when it is not there.
    Index,
    RIndex,
    /// Siemens `SUBSTR(s, start[, count])`: `count` characters (all the rest without it)
    /// from position `start` (0 = the first character).
    Substr,
    /// Siemens `NUMBER(s)`: the REAL a string spells; `ISNUMBER(s)`: whether it spells one.
    Number,
    IsNumber,
    /// Siemens `GETT("name", duplo)`: the T number tool management gives a tool name (read,
    /// and refused: tool management is not modelled).
    GetT,
    /// Siemens `SPRINT(format, …)`, `ISVAR("name")`, `ISFILE("file")`, `GETSELT(list, chan)`:
    /// read, refused in run and translation (`eval::strings::refused`): the format rules, the
    /// control's name tables and file system, and tool management are not modelled.
    Sprint,
    IsVar,
    IsFile,
    GetSelT,
}

impl Func {
    /// The Siemens string functions: arguments or result are strings.
    pub fn is_string(self) -> bool {
        matches!(
            self,
            Func::StrLen
                | Func::ToUpper
                | Func::ToLower
                | Func::Index
                | Func::RIndex
                | Func::Substr
                | Func::Number
                | Func::IsNumber
                | Func::GetT
                | Func::Sprint
                | Func::IsVar
                | Func::IsFile
                | Func::GetSelT
        )
    }
}

/// A variable reference.
#[derive(Clone, Debug, PartialEq)]
pub struct VarRef {
    pub kind: VarKind,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub enum VarKind {
    /// FANUC `#n` with a literal number; its class follows from the number ([`VarClass::of_fanuc`]).
    Hash(u32),
    /// FANUC `#[expr]`: number computed at run time (rounded to an integer).
    HashIndirect(Box<Expr>),
    /// Siemens `R12`.
    R(u32),
    /// Siemens `R[expr]`.
    RIndirect(Box<Expr>),
    /// A Siemens named variable: a DEF local, a PROC parameter, or an undeclared user name
    /// (the validator decides). `indices` holds array subscripts (`A[1,2]`).
    Named { name: String, indices: Vec<Expr> },
    /// A `$` system variable, name without `$` and in upper case (`AA_IW`), with its
    /// subscripts (`$P_UIFR[1,X,TR]` → `[Num 1, Ident X, Ident TR]`).
    System { name: String, indices: Vec<Expr> },
}

/// The storage class of a variable, where the two controls' spaces are compared.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum VarClass {
    /// FANUC `#1..#33`: per macro call level.
    Local,
    /// FANUC `#100..#499`: common, cleared at power-off.
    CommonVolatile,
    /// FANUC `#500..#999`: common, retained.
    CommonRetained,
    /// FANUC `#0` (always vacant).
    Null,
    /// FANUC `#1000+`, Siemens `$…`.
    System,
    /// Siemens `R0..`: channel-global REAL.
    RParam,
    /// Siemens DEF variable or PROC parameter.
    DefLocal,
}

impl VarClass {
    /// The class of FANUC variable `#n` (the ranges of `docs/semantics.md`, Reading: source F8).
    pub fn of_fanuc(n: u32) -> VarClass {
        match n {
            0 => VarClass::Null,
            1..=33 => VarClass::Local,
            100..=499 => VarClass::CommonVolatile,
            500..=999 => VarClass::CommonRetained,
            _ => VarClass::System,
        }
    }
}

impl VarKind {
    /// The class, where it is known without running the program.
    pub fn class(&self) -> Option<VarClass> {
        match self {
            VarKind::Hash(n) => Some(VarClass::of_fanuc(*n)),
            VarKind::HashIndirect(_) => None,
            VarKind::R(_) | VarKind::RIndirect(_) => Some(VarClass::RParam),
            VarKind::Named { .. } => Some(VarClass::DefLocal),
            VarKind::System { .. } => Some(VarClass::System),
        }
    }
}

impl Expr {
    pub fn new(kind: ExprKind, span: Span) -> Self {
        Expr { kind, span }
    }

    pub fn num(value: f64, point: bool, span: Span) -> Self {
        Expr { kind: ExprKind::Num(Number { value, point }), span }
    }

    /// Direct sub-expressions, in source order.
    pub fn children(&self) -> Vec<&Expr> {
        match &self.kind {
            ExprKind::Num(_) | ExprKind::Vacant | ExprKind::Str(_) | ExprKind::Ident(_) => vec![],
            ExprKind::Var(v) => v.children(),
            ExprKind::Unary(_, a) => vec![a],
            ExprKind::Binary(_, a, b) | ExprKind::Cmp(_, _, a, b) => vec![a, b],
            ExprKind::Func(_, args) => args.iter().collect(),
        }
    }
}

impl VarRef {
    pub fn children(&self) -> Vec<&Expr> {
        match &self.kind {
            VarKind::Hash(_) | VarKind::R(_) => vec![],
            VarKind::HashIndirect(e) | VarKind::RIndirect(e) => vec![e],
            VarKind::Named { indices, .. } | VarKind::System { indices, .. } => indices.iter().collect(),
        }
    }
}
