//! A program that cannot run alone, proven in its callers' runs. A file whose every program
//! another file calls is proven alone from the power-on state and with its callers'
//! arguments; some cannot run so (a drilling cycle whose R plane and depth come from the
//! caller, started below that plane). When those runs are only inconclusive (never
//! divergent), the file waits ([`super::CallProof::waits`]) until its callers' verdicts are
//! known: it is written, as verified, when every file that calls it is verified, its programs
//! were called in those callers' equivalent runs, and the callers ran the very programs the
//! file writes (same fingerprints). Otherwise it stays inconclusive and unwritten.

use super::{CallProof, Status};
use crate::translate::library::Library;
use std::collections::{BTreeSet, HashMap};

/// The verdict of a waiting file (`index` in the batch) from its callers' proofs (`proofs`:
/// each committed file's status and proof, by batch index; `names`: each file's path as
/// reported): `Some(summary)` when its callers prove it, else `None`.
pub fn proven_by_callers(
    index: usize,
    waiting: &CallProof,
    lib: &Library,
    proofs: &HashMap<usize, (Status, CallProof)>,
    names: &dyn Fn(usize) -> String,
) -> Option<String> {
    let programs: Vec<String> =
        lib.files.get(index)?.programs.iter().map(|k| k.as_ref().map(ToString::to_string)).collect::<Option<_>>()?;
    let callers: BTreeSet<usize> = lib
        .calls
        .iter()
        .filter(|c| c.file != index && programs.iter().any(|p| *p == c.target.to_string()))
        .map(|c| c.file)
        .collect();
    if callers.is_empty() {
        return None;
    }
    let mut reached = BTreeSet::new();
    for c in &callers {
        let (status, proof) = proofs.get(c)?;
        if *status != Status::Verified {
            return None;
        }
        let ran_it = programs.iter().any(|p| proof.reached.contains(p));
        // What the caller's runs ran of this file must be what this file writes.
        if ran_it && !waiting.own.iter().all(|own| proof.ran.contains(own)) {
            return None;
        }
        reached.extend(programs.iter().filter(|p| proof.reached.contains(*p)).cloned());
    }
    if reached.len() < programs.len() {
        return None;
    }
    let list: Vec<String> = callers.iter().map(|&c| names(c)).collect();
    Some(format!("proven in the runs of its callers: {}", list.join(", ")))
}
