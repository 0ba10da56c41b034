//! IR→IR lowering passes, one submodule per translation direction.

pub mod to_sinumerik;
