//! The targets of the straight-line stream (`stream::straight`): what each target supplies to
//! the one driver (its straight-block test, its fast writer from `lower::to_<name>::fast_write`,
//! its header and the end of its file) and its entry. A new target adds a module here that
//! implements `straight::Target`.
//!
//! Owns: [`fanuc`] (Sinumerik source → FANUC) and [`sinumerik`] (FANUC source → Sinumerik,
//! with the program plan its chunks are lowered with, which the segmented stream shares).
//! May use what `stream` may use, and `stream::straight`.

pub mod fanuc;
pub mod sinumerik;
