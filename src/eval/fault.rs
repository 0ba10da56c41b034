//! Why a run stops early: a machine alarm (part of the trace), an evaluator error (a
//! diagnostic: the program uses something this evaluator cannot run), or a limit.

use crate::diag::Diagnostic;
use crate::span::Span;

#[derive(Clone, Debug, PartialEq)]
pub enum Fault {
    /// The control would raise this alarm: an `alarm` event ends the trace.
    Alarm { number: i64, message: String, span: Span },
    /// Something the evaluator does not model or cannot find (NC4xx).
    Error(Box<Diagnostic>),
    /// Step or call-depth limit: the run is inconclusive.
    Limit { reason: String, span: Span },
}

impl Fault {
    pub fn alarm(number: i64, message: impl Into<String>, span: Span) -> Fault {
        Fault::Alarm { number, message: message.into(), span }
    }

    pub fn error(d: Diagnostic) -> Fault {
        Fault::Error(Box::new(d))
    }
}

/// The alarm numbers of one control for run-time faults.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AlarmNumbers {
    pub div_zero: i64,
    pub domain: i64,
    pub overflow: i64,
    /// Jump target not found.
    pub no_target: i64,
    /// Variable number / array index out of range.
    pub bad_index: i64,
    /// Write to a read-only variable.
    pub read_only: i64,
    /// G1/G2/G3 without any feed programmed.
    pub no_feed: i64,
    /// Arc end point not on the circle / radius too small.
    pub arc: i64,
}

impl AlarmNumbers {
    /// FANUC 0i/16i: 112 division by zero, 111 calculated data overflow (also domain
    /// errors, source F7 of `docs/semantics.md`), 128 sequence number not found, 115 variable number out of
    /// range, 116 write-protected variable, 011 feed zero, 020 over tolerance of radius.
    pub const FANUC: AlarmNumbers = AlarmNumbers {
        div_zero: 112,
        domain: 111,
        overflow: 111,
        no_target: 128,
        bad_index: 115,
        read_only: 116,
        no_feed: 11,
        arc: 20,
    };
    /// Sinumerik: 14051 arithmetic error in part program (division by zero, domain,
    /// overflow: the choice in docs/semantics.md), 14080 jump destination not found,
    /// 17020 illegal array index, 14130 write-protected, 10860 no feed programmed,
    /// 14040 error in end point of circle.
    pub const SINUMERIK: AlarmNumbers = AlarmNumbers {
        div_zero: 14051,
        domain: 14051,
        overflow: 14051,
        no_target: 14080,
        bad_index: 17020,
        read_only: 14130,
        no_feed: 10860,
        arc: 14040,
    };
}
