//! The tests over real programs nobody on this project wrote, kept beside the repository in
//! `../shared/external` (CEAD Sinumerik examples with golden CSVs, cnc4me FANUC macros). A
//! clone has no such folder, so these are not part of the default `cargo test`; they are
//! their own target, `cargo test --test external`, which `.ci/run` runs too. Without the
//! folder every test here fails with a message naming the path it looked for: a missing
//! folder is never a silent pass.

#[path = "../eval_support/mod.rs"]
mod eval_support;
#[path = "../support/fast_same.rs"]
mod fast_same;
#[path = "../support/skeleton.rs"]
mod skeleton;
#[path = "../support/tool_names.rs"]
mod tool_names;
#[path = "../support/words_scan.rs"]
mod words_scan;

mod eval;
mod fanuc_parse;
mod fanuc_to_sinumerik;
mod sinumerik_parse;
mod streamed;
mod to_fanuc;
mod to_fanuc_axes;
mod to_fanuc_repeat;
mod to_fanuc_signals;

use std::path::PathBuf;

/// `<repo>/../shared/external/<sub>`; panics, naming the path, when it is not a folder.
pub fn external(sub: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../shared/external").join(sub);
    assert!(
        dir.is_dir(),
        "{} is missing: `cargo test --test external` needs the external programs beside the \
         repository (../shared/external); the default `cargo test` does not",
        dir.display()
    );
    dir
}
