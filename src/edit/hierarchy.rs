//! Hierarchy-based interaction (§5, Fig. 1, 11, 12): after one sweep is edited, every link of
//! the rig's tree is satisfied again, working outward from the edited sweep.
//!
//! - Down to a child: a branch child's first key goes where its binding (θ, t, d, h, q̂) puts
//!   it on the posed parent and its other keys follow rigidly (their local transforms kept); a
//!   loop child's first and last keys both go to their bound places and the keys between blend
//!   the two motions by their knots, so the loop bends rather than breaks.
//! - Up to a parent: the parent's cross-sections bound to the child's first key (and last, for
//!   a loop) are driven to match those keys by direct cross-section control (Fig. 10) — editing
//!   a loop child (the teapot's handle) moves the body so that the loop stays closed (Fig. 1c),
//!   and a virtual sweep carries an edit on to the sweeps it joins (Fig. 16).

use std::collections::VecDeque;

use super::EditError;
use super::controls::Controls;
use super::rigid::Motion;
use super::section::{SectionTarget, move_sections_kept};
use super::shapes::Shape;
use crate::bind::VertexBinding;
use crate::rig::{KeyBinding, Link, Rig};
use crate::sweep::{Key, Sweep};

/// Satisfies every link of `rig` again after sweep `edited` changed in `keys`.
pub fn propagate(rig: &Rig, keys: &mut [Vec<Key>], edited: usize, controls: &Controls) -> Result<(), EditError> {
    propagate_kept(rig, keys, edited, controls, &mut rig.rest().iter().map(Shape::like).collect::<Vec<_>>())
}

/// [`propagate`] with the sweeps' memos `shapes`.
pub(super) fn propagate_kept(
    rig: &Rig,
    keys: &mut [Vec<Key>],
    edited: usize,
    controls: &Controls,
    shapes: &mut [Shape],
) -> Result<(), EditError> {
    let mut visited = vec![false; keys.len()];
    let mut queue = VecDeque::from([edited]);
    visited[edited] = true;
    while let Some(node) = queue.pop_front() {
        for (child, link) in children(rig, node) {
            if !visited[child] {
                follow_parent(rig, keys, child, link, shapes)?;
                visited[child] = true;
                queue.push_back(child);
            }
        }
        if let Some(link) = &rig.links()[node]
            && !visited[link.parent]
        {
            hold_child(rig, keys, node, link, controls, shapes)?;
            visited[link.parent] = true;
            queue.push_back(link.parent);
        }
    }
    Ok(())
}

/// Updates every descendant of `node` from it (downward only).
pub fn propagate_down(rig: &Rig, keys: &mut [Vec<Key>], node: usize) -> Result<(), EditError> {
    propagate_down_kept(rig, keys, node, &mut rig.rest().iter().map(Shape::like).collect::<Vec<_>>())
}

/// [`propagate_down`] with the sweeps' memos `shapes`.
pub(super) fn propagate_down_kept(
    rig: &Rig,
    keys: &mut [Vec<Key>],
    node: usize,
    shapes: &mut [Shape],
) -> Result<(), EditError> {
    let mut queue = VecDeque::from([node]);
    while let Some(node) = queue.pop_front() {
        for (child, link) in children(rig, node) {
            follow_parent(rig, keys, child, link, shapes)?;
            queue.push_back(child);
        }
    }
    Ok(())
}

/// Updates every descendant of the sweeps `nodes` from them (downward only), each once, parents
/// before children: the same keys as [`propagate_down_kept`] from each of `nodes` in turn, for
/// the cost of one pass.
pub(super) fn propagate_down_from(
    rig: &Rig,
    keys: &mut [Vec<Key>],
    nodes: &[usize],
    shapes: &mut [Shape],
) -> Result<(), EditError> {
    let mut moved = vec![false; keys.len()];
    nodes.iter().for_each(|&node| moved[node] = true);
    // From the roots down, breadth first: every parent is done before its children.
    let mut queue: VecDeque<usize> = (0..keys.len()).filter(|&sweep| rig.links()[sweep].is_none()).collect();
    while let Some(node) = queue.pop_front() {
        for (child, link) in children(rig, node) {
            if moved[node] {
                follow_parent(rig, keys, child, link, shapes)?;
                moved[child] = true;
            }
            queue.push_back(child);
        }
    }
    Ok(())
}

/// The children of `node` with their links.
fn children(rig: &Rig, node: usize) -> impl Iterator<Item = (usize, &Link)> {
    rig.links()
        .iter()
        .enumerate()
        .filter_map(move |(i, link)| link.as_ref().filter(|l| l.parent == node).map(|l| (i, l)))
}

fn posed<'a>(rig: &Rig, keys: &[Vec<Key>], sweep: usize, shapes: &'a mut [Shape]) -> Result<&'a Sweep, EditError> {
    shapes[sweep].sweep(&keys[sweep], rig.rest()[sweep].knots()).map_err(|source| EditError::Hierarchy {
        sweep: rig.sweeps()[sweep].name.clone(),
        source: Box::new(EditError::Degenerate(source)),
    })
}

/// Moves `child`'s keys to where its link puts them on its (posed) parent.
fn follow_parent(
    rig: &Rig,
    keys: &mut [Vec<Key>],
    child: usize,
    link: &Link,
    shapes: &mut [Shape],
) -> Result<(), EditError> {
    let parent = posed(rig, keys, link.parent, shapes)?;
    let chain = &mut keys[child];
    let last = chain.len() - 1;
    let first_motion = Motion::between(&chain[0], &link.first.key_on(parent, &[]));
    match &link.last {
        None => shapes[child].move_rigidly(chain, &first_motion),
        Some(binding) => {
            let last_motion = Motion::between(&chain[last], &binding.key_on(parent, &[]));
            let knots = rig.rest()[child].knots();
            for (key, &w) in chain.iter_mut().zip(knots) {
                let (a, b) = (first_motion.frame(key), last_motion.frame(key));
                key.center = a.0.lerp(b.0, w);
                key.rotation = a.1.slerp(b.1, w).normalize();
            }
        }
    }
    // A parent far out can carry its child beyond the representable: fail here, naming the
    // child and its key, rather than later on a non-finite pose. The radii did not move.
    Sweep::validate_frames(chain).map_err(|source| EditError::Hierarchy {
        sweep: rig.sweeps()[child].name.clone(),
        source: Box::new(EditError::Degenerate(source)),
    })
}

/// Drives the parent's cross-sections bound to `child`'s first (and last) key to hold them.
fn hold_child(
    rig: &Rig,
    keys: &mut [Vec<Key>],
    child: usize,
    link: &Link,
    controls: &Controls,
    shapes: &mut [Shape],
) -> Result<(), EditError> {
    let parent = posed(rig, keys, link.parent, shapes)?;
    let chain = &keys[child];
    let mut targets = vec![section_holding(parent, &link.first, &chain[0])];
    if let Some(last) = &link.last {
        targets.push(section_holding(parent, last, &chain[chain.len() - 1]));
    }
    let knots = rig.rest()[link.parent].knots();
    let shape = &mut shapes[link.parent];
    move_sections_kept(&mut keys[link.parent], knots, &targets, controls, shape).map_err(|source| {
        EditError::Hierarchy { sweep: rig.sweeps()[link.parent].name.clone(), source: Box::new(source) }
    })?;
    Ok(())
}

/// The frame the parent's cross-section at the binding's t must have for the binding to put
/// its key exactly at `key`: R(t) = q_key·q̂⁻¹ and C(t) = p_key − R(t)·((r + d) cos θ, (r + d) sin θ, h),
/// with r the parent's radius there (rigid moves of the parent's keys leave r unchanged).
fn section_holding(parent: &Sweep, binding: &KeyBinding, key: &Key) -> SectionTarget {
    let VertexBinding { t, theta, d, h } = binding.params;
    let rotation = (key.rotation * binding.relative.inverse()).normalize();
    let rho = parent.radius(theta, t) + d;
    let offset = glam::DVec3::new(rho * theta.cos(), rho * theta.sin(), h);
    SectionTarget { t, center: key.center - rotation * offset, rotation }
}
