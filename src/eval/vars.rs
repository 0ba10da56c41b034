//! Variable storage: FANUC local levels and common variables (with vacancy), Siemens R
//! parameters and typed DEF variables per program level (with VAR references).

use super::value::Value;
use crate::ir::DataType;
use std::collections::HashMap;

/// A FANUC local level: `#1..#33` (index 0 unused) and which were ever written.
#[derive(Clone, Debug)]
pub struct Level {
    pub vals: [Option<f64>; 34],
    pub written: u64,
}

impl Default for Level {
    fn default() -> Self {
        Level { vals: [None; 34], written: 0 }
    }
}

/// Where a Siemens `VAR` parameter points.
#[derive(Clone, Debug, PartialEq)]
pub enum Place {
    R(usize),
    /// A named variable in Siemens frame `frame`; `index` selects one element (a scalar
    /// reference to an array element) or `None` for the whole variable.
    Named {
        frame: usize,
        name: String,
        index: Option<usize>,
    },
}

#[derive(Clone, Debug)]
pub enum Slot {
    Own { ty: DataType, dims: Vec<u32>, data: Vec<Value> },
    Ref(Place),
}

#[derive(Debug)]
pub struct Vars {
    pub levels: Vec<Level>,
    /// `#100..#999` (index = number).
    pub commons: Vec<Option<f64>>,
    pub commons_written: Vec<bool>,
    pub r: Vec<f64>,
    pub r_written: Vec<bool>,
    /// Siemens variable frames; frame 0 belongs to the main program (its DEFs are PUD,
    /// visible to subprograms).
    pub frames: Vec<HashMap<String, Slot>>,
    /// Haas NGC general-purpose variables without a legacy number (`#10000..#10099`, …),
    /// vacant until written.
    pub ngc: HashMap<u32, f64>,
}

impl Vars {
    pub fn new(r_count: usize) -> Vars {
        Vars {
            levels: vec![Level::default()],
            commons: vec![None; 1000],
            commons_written: vec![false; 1000],
            r: vec![0.0; r_count],
            r_written: vec![false; r_count],
            frames: vec![HashMap::new()],
            ngc: HashMap::new(),
        }
    }

    /// The frame holding `name` as seen from frame `cur`: its own, else the main
    /// program's (PUD).
    pub fn frame_of(&self, cur: usize, name: &str) -> Option<usize> {
        if self.frames.get(cur).is_some_and(|f| f.contains_key(name)) {
            Some(cur)
        } else if self.frames.first().is_some_and(|f| f.contains_key(name)) {
            Some(0)
        } else {
            None
        }
    }
}

/// Flat index of `idx` in an array of `dims`, `None` when out of range.
pub fn flat_index(dims: &[u32], idx: &[i64]) -> Option<usize> {
    if dims.len() != idx.len() {
        return None;
    }
    let mut flat = 0usize;
    for (d, i) in dims.iter().zip(idx) {
        if *i < 0 || *i >= i64::from(*d) {
            return None;
        }
        flat = flat * (*d as usize) + *i as usize;
    }
    Some(flat)
}

/// The start value of a Siemens variable of type `ty`: 0, FALSE, or "".
pub fn zero_of(ty: DataType) -> Value {
    match ty {
        DataType::String(_) => Value::Str(String::new()),
        _ => Value::Num(0.0),
    }
}

/// Elements of an array with `dims` (1 for a scalar); `None` above a million elements,
/// which no control holds (the evaluator must not allocate what the input asks blindly).
pub fn array_len(dims: &[u32]) -> Option<usize> {
    let mut n = 1usize;
    for d in dims {
        n = n.checked_mul(*d as usize)?;
    }
    (n <= 1_000_000).then_some(n.max(1))
}
