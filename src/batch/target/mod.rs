//! What a batch job does per target (`jobs::Target`): its options from the batch's maps,
//! its output names, the names it used, what it refuses and, to Sinumerik, the stand-in
//! caller, and its part of a streamed job (`streamed::Streams`). One file per target; the
//! job itself is `jobs::Job`, the streamed one `streamed::run`. May use what `batch` may
//! (`translate` for the options and the proof's pieces, `config`, `check`, `eval`).

pub mod fanuc;
pub mod sinumerik;
