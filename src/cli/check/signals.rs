//! `nctrans check` of a Siemens program against a FANUC one with machine signal inputs
//! (`--set '$A_DBB[2]=1'`): each side gets them in its own names through the machine's
//! wiring (`[signals]` of `./nctrans.toml`, and of `--map`), as a translation's proof does
//! (`translate::to_fanuc::fanuc_set_inputs`). An input the wiring does not name stays as given,
//! so the side it does not fit says so (NC407).

use nctrans::dialect::signals::{Signal, SignalMap};
use nctrans::dialect::Dialect;
use nctrans::eval::{Input, InputTarget};

/// The wiring of `./nctrans.toml` (empty without one or when it does not read: the
/// translation's own reading reports that).
pub fn project_wiring() -> SignalMap {
    let project = std::path::Path::new(nctrans::config::FILE_NAME);
    match project.is_file() {
        true => nctrans::config::Config::load(project).map(|c| c.signals).unwrap_or_default(),
        false => SignalMap::default(),
    }
}

/// Rewrites the other dialect's signal inputs of a `dialect` side through `wiring`.
pub fn wire(inputs: &mut [Input], dialect: Dialect, wiring: &SignalMap) {
    for i in inputs.iter_mut() {
        let to = match (&i.target, dialect) {
            (InputTarget::Signal(s), Dialect::Fanuc) => wiring.fanuc_of(*s).map(|f| InputTarget::Hash(f.index)),
            (InputTarget::Hash(n), Dialect::Sinumerik) => {
                Signal::fanuc(*n).and_then(|f| wiring.siemens_of(f)).map(InputTarget::Signal)
            }
            _ => None,
        };
        if let Some(t) = to {
            i.target = t;
        }
    }
}
