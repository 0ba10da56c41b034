//! A forward must/may analysis over a program's flat control-flow graph (`vacancy::flatten`):
//! the state at each node, from a start state at the first node, through each block's items
//! and the meet where paths join, to a fixed point. Shared by the passes that follow values
//! through a FANUC program (`indirect`, `dispatch`).

use super::vacancy::{succs, Flat, Node};
use crate::ir::Item;

/// The state entering each node of `flat` (`None`: not reached), and whether the rounds
/// (bounded by the graph's size, at most 200) settled.
pub(super) fn run<E: Clone + PartialEq>(
    flat: &Flat,
    start: E,
    transfer: impl Fn(&Item, &mut E),
    meet: impl Fn(&E, &E) -> E,
) -> (Vec<Option<E>>, bool) {
    let len = flat.nodes.len();
    let mut ins: Vec<Option<E>> = vec![None; len];
    if len > 0 {
        ins[0] = Some(start);
    }
    let next: Vec<Vec<usize>> = (0..len).map(|i| succs(flat, i)).collect();
    for _round in 0..(len + 2).min(200) {
        let mut changed = false;
        for i in 0..len {
            let Some(mut env) = ins[i].clone() else { continue };
            if let Node::Items(items) = &flat.nodes[i] {
                for it in items.iter() {
                    transfer(it, &mut env);
                }
            }
            for &s in &next[i] {
                let new = match &ins[s] {
                    None => env.clone(),
                    Some(old) => meet(old, &env),
                };
                if ins[s].as_ref() != Some(&new) {
                    ins[s] = Some(new);
                    changed = true;
                }
            }
        }
        if !changed {
            return (ins, true);
        }
    }
    (ins, false)
}
