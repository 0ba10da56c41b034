//! Blocks, their items, and the structured statements the structurer builds from them.

use super::expr::{Expr, VarRef};
use crate::span::Span;

/// What every block has besides its contents: number, label, skip, comments.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BlockMeta {
    /// The whole block, line end excluded (FANUC trailing `;` included).
    pub span: Span,
    /// Block skip: `/` is `Some(0)`, `/3` is `Some(3)`.
    pub skip: Option<u8>,
    /// Sequence number `N123` (FANUC leading N; Siemens `N…` or main block `:…`).
    pub number: Option<SeqNo>,
    /// Siemens jump label `NAME:`.
    pub label: Option<Label>,
    /// Comments in text order: FANUC `( … )` (any position), Siemens `; …` (end of line).
    pub comments: Vec<Comment>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct SeqNo {
    pub value: u32,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Label {
    /// Upper case (labels are case-insensitive).
    pub name: String,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Comment {
    /// The text between the delimiters, exactly as in the file (any script, any encoding
    /// after decoding).
    pub text: String,
    pub span: Span,
}

/// One NC block: metadata and the ordered items written in it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Block {
    pub meta: BlockMeta,
    pub items: Vec<Item>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Item {
    pub kind: ItemKind,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub enum ItemKind {
    /// `#1=…` (FANUC), `R1=…`, `NAME=…`, `A[1,2]=…` (Siemens).
    Assign { target: Box<VarRef>, value: Expr },
    /// An NC address word: `G1`, `X10.`, `X=R1+2`, `T="DRILL"`, `CR=5`, `X#1`, `M#5`.
    Word(Word),
    /// FANUC `GOTO n`, `IF[c]GOTO n`; Siemens `GOTOF L`, `IF c GOTOB N5`.
    Goto(Box<Goto>),
    /// FANUC `IF[cond]THEN stmt`: exactly one macro statement, run when `cond` holds.
    IfThen { cond: Expr, then: Box<Item> },
    /// Haas `IF [cond] S800 F600.` / `IF [cond] THEN M31`: the block's other items, run only
    /// when `cond` holds (Haas operator's manual, macros: IF without GOTO or THEN). Empty
    /// for `IF [cond]` alone.
    IfBlock { cond: Expr, items: Vec<Item> },
    /// Siemens `CASE (e) OF 1 GOTOF A 2 GOTOF B DEFAULT GOTOF C`.
    Case(Box<Case>),
    /// Any subprogram or macro call (see [`CallKind`]).
    Call(Box<Call>),
    /// FANUC `G67`, Siemens `MCALL` with no name: cancel the modal call.
    ModalCallOff,
    /// FANUC `M99` (optionally `M99 Pn`: continue at Nn of the caller), Siemens `RET`, `M17`.
    Return { to: Option<Expr> },
    /// FANUC `M30`/`M02`, Siemens `M30`/`M2`: end of program.
    End { code: EndCode },
    /// Siemens `DEF type name[dims]=init, …`.
    Def(Box<Def>),
    /// FANUC `#3000=n(TEXT)` (shows alarm 3000+n), Siemens `SETAL(n)`.
    Alarm { style: AlarmStyle, number: Expr, text: Option<String> },
    /// FANUC `#3006=n(TEXT)`: stop with a message; cycle start continues.
    StopMessage { text: Option<String> },
    /// Siemens `MSG("…")` (a message, no stop); `MSG()` clears (`text == None`).
    Message { text: Option<Expr> },
    /// Siemens `STOPRE`: preprocessing stop.
    Stopre,
    /// A FANUC parameter write between `G10 L50` and `G11`: `N<param> [P<axis>] [Q<bit>] R<value>`.
    ParamWrite(Box<ParamWrite>),
    /// Siemens program-section repetition `REPEAT A [B] P=n` / `REPEATB A P=n`.
    RepeatSection(Box<RepeatSection>),
    /// Siemens frame instruction with axis words: `TRANS X10`, `ATRANS …`, `ROT Z45`, bare `TRANS`.
    Frame { op: String, words: Vec<Word> },
    /// Siemens named NC instruction written without a value, upper case: interpolation and
    /// path modes (`CIP`, `BSPLINE`, `SOFT`, `CFC`), spline end conditions (`BNAT`, `ETAN`),
    /// `SUPA`, `SBLOF`. Like a G function, but named; never a subprogram call.
    Instruction { name: String },
    /// Siemens synchronized action: `ID=1 WHEN cond DO actions` and its forms. It runs in
    /// the interpolation cycle beside the program, so neither the evaluator nor FANUC can
    /// carry it; it is read so that the rest of the file can be checked.
    SyncAction(Box<SyncAction>),
    /// Siemens `EXTERN NAME(REAL, VAR INT)`: the parameters of a subprogram this program
    /// calls. A declaration only: nothing runs.
    Extern(Box<ExternDecl>),
    /// One line of text output: FANUC `DPRNT[…]` (to the I/O channel), Siemens
    /// `WRITE(err, "file", text)` (appended to a file). The trace's `print` event.
    Print(Box<Print>),
}

/// A line of text output (see [`ItemKind::Print`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Print {
    pub parts: Vec<PrintPart>,
    /// Siemens `WRITE`: the file (its second argument) and the error variable the control
    /// sets (its first). `None` for FANUC, whose output goes to the channel POPEN opened.
    pub file: Option<Expr>,
    pub status: Option<Box<VarRef>>,
}

/// A piece of a [`Print`] line, in order.
#[derive(Clone, Debug, PartialEq)]
pub enum PrintPart {
    /// Characters output as they are (FANUC's `*` already made a space).
    Text(String),
    /// FANUC `#n[wf]`: the value with `int` places before the point and `frac` after it.
    Field { value: Expr, int: u8, frac: u8 },
    /// Siemens: a STRING expression, output as the control builds it (`"X"<<R1`).
    Str(Expr),
}

#[derive(Clone, Debug, PartialEq)]
pub struct ExternDecl {
    /// Upper case.
    pub name: String,
    /// Each parameter: by reference (`VAR`), its type and array dimensions.
    pub params: Vec<(bool, DataType, Vec<u32>)>,
}

/// A Siemens synchronized action.
#[derive(Clone, Debug, PartialEq)]
pub struct SyncAction {
    /// `ID=n` (modal, this program) or `IDS=n` (static, beyond the program end).
    pub id: Option<(SyncScope, Expr)>,
    /// `WHEN`, `WHENEVER`, `EVERY`, `FROM`, or `None` for an action without condition.
    pub trigger: Option<(SyncTrigger, Expr)>,
    /// The items after `DO`, in order.
    pub actions: Vec<Item>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SyncScope {
    /// `ID=n`.
    Modal,
    /// `IDS=n`.
    Static,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SyncTrigger {
    /// `WHEN c`: once, the first time c holds.
    When,
    /// `WHENEVER c`: in every interpolation cycle in which c holds.
    Whenever,
    /// `EVERY c`: each time c becomes true.
    Every,
    /// `FROM c`: in every cycle once c has held.
    From,
}

impl SyncTrigger {
    pub fn name(self) -> &'static str {
        match self {
            SyncTrigger::When => "WHEN",
            SyncTrigger::Whenever => "WHENEVER",
            SyncTrigger::Every => "EVERY",
            SyncTrigger::From => "FROM",
        }
    }
}

/// FANUC `G10 L50` mode: `N<param> [P<axis>] [Q<bit>] R<value>`.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamWrite {
    pub number: Expr,
    pub axis: Option<Expr>,
    pub bit: Option<Expr>,
    pub value: Expr,
}

/// The Siemens label that ends the section of a `REPEAT start` without an end label: the
/// first block so labelled after `start` (it may stand on several blocks of a program).
pub const ENDLABEL: &str = "ENDLABEL";

/// Siemens `REPEAT start [end] P=count` (`single`: `REPEATB`, the one labelled block).
#[derive(Clone, Debug, PartialEq)]
pub struct RepeatSection {
    pub start: Label,
    pub end: Option<Label>,
    pub count: Option<Expr>,
    pub single: bool,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum EndCode {
    M30,
    M2,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum AlarmStyle {
    /// FANUC `#3000=n`: alarm number shown is 3000+n.
    FanucMacro,
    /// Siemens `SETAL(n)`: alarm number n.
    Setal,
}

/// An address: a single letter (the common case, no allocation) or a longer name (`CR`,
/// `AR`, `SPOS`, `ELX`, `I1`), or Siemens `AX[e]`: the axis whose name `e` gives at run time
/// (an AXIS variable or `AXNAME("X")`).
#[derive(Clone, Debug, PartialEq)]
pub enum Addr {
    Letter(u8),
    Name(Box<str>),
    Axis(Box<Expr>),
}

// Addresses are compared and hashed by what they are written as; `AX[e]` by its expression
// (structurally, like every IR comparison).
impl Eq for Addr {}

impl std::hash::Hash for Addr {
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        self.as_str().hash(state);
    }
}

impl Addr {
    /// The address as written; `AX` for an axis chosen at run time.
    pub fn as_str(&self) -> &str {
        match self {
            // Letters are upper-case ASCII by construction.
            Addr::Letter(b) => std::str::from_utf8(std::slice::from_ref(b)).unwrap_or("?"),
            Addr::Name(s) => s,
            Addr::Axis(_) => "AX",
        }
    }

    pub fn is(&self, letter: u8) -> bool {
        *self == Addr::Letter(letter)
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct Word {
    pub addr: Addr,
    pub value: WordValue,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub enum WordValue {
    /// A constant or expression (`X10`, `X=R1*2`, `X[#1+2]`, `X#1`, `X-#1`).
    Expr(Expr),
    /// Siemens `X=AC(…)`: absolute for this word only.
    Ac(Expr),
    /// Siemens `X=IC(…)`: incremental for this word only.
    Ic(Expr),
    /// Siemens rotary-axis positioning `C=ACP(…)`, `ACN`, `DC`, `CAC`, `CACP`, `CACN`,
    /// `CIC`, `CDC`: the value with the direction or coding rule that goes with it.
    Rotary(RotaryMode, Expr),
}

/// How a Siemens rotary-axis word positions (Siemens PGA "ACP, ACN, DC").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RotaryMode {
    /// `ACP(a)`: absolute, approached in the positive direction.
    Acp,
    /// `ACN(a)`: absolute, approached in the negative direction.
    Acn,
    /// `DC(a)`: absolute along the shortest path.
    Dc,
    /// `CAC(n)`: coded position n from the machine data table, absolute.
    Cac,
    /// `CACP(n)`: coded position, positive direction.
    Cacp,
    /// `CACN(n)`: coded position, negative direction.
    Cacn,
    /// `CIC(n)`: coded position, incremental.
    Cic,
    /// `CDC(n)`: coded position, shortest path.
    Cdc,
}

impl RotaryMode {
    /// The Siemens spelling (`ACP`).
    pub fn name(self) -> &'static str {
        match self {
            RotaryMode::Acp => "ACP",
            RotaryMode::Acn => "ACN",
            RotaryMode::Dc => "DC",
            RotaryMode::Cac => "CAC",
            RotaryMode::Cacp => "CACP",
            RotaryMode::Cacn => "CACN",
            RotaryMode::Cic => "CIC",
            RotaryMode::Cdc => "CDC",
        }
    }

    /// From the upper-case Siemens keyword.
    pub fn from_name(upper: &str) -> Option<RotaryMode> {
        Some(match upper {
            "ACP" => RotaryMode::Acp,
            "ACN" => RotaryMode::Acn,
            "DC" => RotaryMode::Dc,
            "CAC" => RotaryMode::Cac,
            "CACP" => RotaryMode::Cacp,
            "CACN" => RotaryMode::Cacn,
            "CIC" => RotaryMode::Cic,
            "CDC" => RotaryMode::Cdc,
            _ => return None,
        })
    }
}

/// How a jump searches for its target.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Search {
    /// Siemens `GOTOF`: toward the program end.
    Forward,
    /// Siemens `GOTOB`: toward the program start.
    Backward,
    /// Siemens `GOTO`/`GOTOC`: forward first, then backward.
    ForwardThenBackward,
    /// FANUC `GOTO`: forward to the end, then from the top.
    ForwardThenWrap,
}

#[derive(Clone, Debug, PartialEq)]
pub enum Target {
    /// Siemens label.
    Label(Label),
    /// A sequence number `N10` (Siemens) or `10` (FANUC `GOTO10`).
    Number(SeqNo),
    /// FANUC `GOTO#1`, `GOTO[expr]`; Siemens label held in a STRING variable.
    Computed(Expr),
}

#[derive(Clone, Debug, PartialEq)]
pub struct Goto {
    pub search: Search,
    pub target: Target,
    /// `IF cond GOTO…`.
    pub cond: Option<Expr>,
    /// Siemens `GOTOC`: a missing target continues with the next block instead of an alarm.
    pub missing_continues: bool,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Case {
    pub selector: Expr,
    pub arms: Vec<CaseArm>,
    pub default: Option<Goto>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct CaseArm {
    pub value: Expr,
    pub goto: Goto,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CallKind {
    /// FANUC `G65 P… L… args`: new local level.
    G65,
    /// FANUC `G66 P… L… args`: modal call after every move until `G67`.
    G66,
    /// FANUC `M98 P… L…` (or packed `P68003`): no new local level.
    M98,
    /// Haas `M97 Pn Lm`: the local subprogram starting at block Nn of the same program, up
    /// to its M99; no new local level. The target is `CallTarget::Number(n)`, a sequence number.
    M97,
    /// Siemens call by name: `CONTOUR`, `CONTOUR(5.5,,R3)`, `CYCLE81(…)`, `WORKPIECE(…)`.
    Named,
    /// Siemens `L123` (leading zeros significant: the name keeps them).
    LNumber,
    /// Siemens `MCALL NAME`: modal call after every path-motion block.
    Mcall,
}

#[derive(Clone, Debug, PartialEq)]
pub enum CallTarget {
    /// FANUC program number (`P9010`).
    Number(u32),
    /// Siemens program name, upper case (`CONTOUR`, `L0123`).
    Name(String),
    /// FANUC `P#1`.
    Computed(Expr),
}

#[derive(Clone, Debug, PartialEq)]
pub enum Arg {
    /// Siemens positional argument.
    Value(Expr),
    /// Siemens omitted argument (`CONTOUR(5.5,,R3)`): the callee sees 0.
    Omitted(Span),
    /// FANUC argument letter, with the local variable it fills (spec I/II resolved by the
    /// parser: `A` → 1, the second `I` → 7, …).
    Letter { letter: u8, var: u8, value: Expr },
}

#[derive(Clone, Debug, PartialEq)]
pub struct Call {
    pub kind: CallKind,
    pub target: CallTarget,
    pub args: Vec<Arg>,
    /// FANUC `L`, Siemens `P`: how many times to run the callee.
    pub repeat: Option<Expr>,
}

/// Siemens data types.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DataType {
    Int,
    Real,
    Bool,
    Char,
    /// `STRING[n]`.
    String(u16),
    Axis,
    Frame,
}

/// The declared type as `DEF` writes it (`REAL`, `STRING[20]`), for dumps and messages.
impl std::fmt::Display for DataType {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            DataType::Int => f.write_str("INT"),
            DataType::Real => f.write_str("REAL"),
            DataType::Bool => f.write_str("BOOL"),
            DataType::Char => f.write_str("CHAR"),
            DataType::String(n) => write!(f, "STRING[{n}]"),
            DataType::Axis => f.write_str("AXIS"),
            DataType::Frame => f.write_str("FRAME"),
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct Def {
    /// `DEF NCK …` / `DEF CHAN …` (global user data in a definition file); `None` for a
    /// program's own DEF.
    pub scope: Option<DefScope>,
    pub ty: DataType,
    pub vars: Vec<DefVar>,
}

/// Where Siemens global user data lives.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DefScope {
    /// `NCK`: one value for the whole control.
    Nck,
    /// `CHAN`: one value per channel.
    Chan,
}

#[derive(Clone, Debug, PartialEq)]
pub struct DefVar {
    /// Upper case (names are case-insensitive).
    pub name: String,
    /// Array dimensions (`[10,3]`), empty for scalars.
    pub dims: Vec<u32>,
    /// Initial value(s): one for a scalar; for arrays the `SET(…)` list with omitted entries
    /// as `None`, or `REP(v[,n])` expanded to its explicit form by the parser.
    pub init: Option<Init>,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub enum Init {
    Value(Expr),
    /// `SET(a, , c)`.
    Set(Vec<Option<Expr>>),
    /// `REP(v)` (all) or `REP(v, n)` (first n).
    Rep {
        value: Expr,
        count: Option<Expr>,
    },
}

/// A statement of the program tree: a plain block, or a structure built from several blocks.
#[derive(Clone, Debug, PartialEq)]
pub struct Stmt {
    pub kind: StmtKind,
    /// From the first block of the construct to its last.
    pub span: Span,
}

/// Structured statements are boxed so that the common plain block stays small.
#[derive(Clone, Debug, PartialEq)]
pub enum StmtKind {
    Block(Block),
    /// Siemens `IF c … [ELSE …] ENDIF`.
    If(Box<IfStmt>),
    /// Siemens `WHILE c … ENDWHILE`.
    While(Box<WhileStmt>),
    /// Siemens `LOOP … ENDLOOP`.
    Loop(Box<LoopStmt>),
    /// Siemens `FOR v = a TO b … ENDFOR`.
    For(Box<ForStmt>),
    /// Siemens `REPEAT … UNTIL c`.
    Repeat(Box<RepeatStmt>),
    /// FANUC `WHILE[c]DOm … ENDm`, or bare `DOm … ENDm` (`cond == None`: endless).
    Do(Box<DoStmt>),
}

#[derive(Clone, Debug, PartialEq)]
pub struct IfStmt {
    pub head: BlockMeta,
    pub cond: Expr,
    pub then_body: Vec<Stmt>,
    pub else_part: Option<ElsePart>,
    pub end: BlockMeta,
}

#[derive(Clone, Debug, PartialEq)]
pub struct WhileStmt {
    pub head: BlockMeta,
    pub cond: Expr,
    pub body: Vec<Stmt>,
    pub end: BlockMeta,
}

#[derive(Clone, Debug, PartialEq)]
pub struct LoopStmt {
    pub head: BlockMeta,
    pub body: Vec<Stmt>,
    pub end: BlockMeta,
}

#[derive(Clone, Debug, PartialEq)]
pub struct ForStmt {
    pub head: BlockMeta,
    pub var: VarRef,
    pub from: Expr,
    pub to: Expr,
    pub body: Vec<Stmt>,
    pub end: BlockMeta,
}

#[derive(Clone, Debug, PartialEq)]
pub struct RepeatStmt {
    pub head: BlockMeta,
    pub body: Vec<Stmt>,
    /// The `UNTIL` block.
    pub end: BlockMeta,
    pub until: Expr,
}

#[derive(Clone, Debug, PartialEq)]
pub struct DoStmt {
    pub head: BlockMeta,
    pub id: u8,
    pub cond: Option<Expr>,
    pub body: Vec<Stmt>,
    pub end: BlockMeta,
}

#[derive(Clone, Debug, PartialEq)]
pub struct ElsePart {
    pub head: BlockMeta,
    pub body: Vec<Stmt>,
}
