//! The hierarchy of a rig (§5, Fig. 11): each child sweep's first key (and, for a loop, its last
//! key) bound to a cross-section of its parent by (θ, t, d, h, q̂), computed on the rest rig.

use glam::DQuat;

use super::document::{LinkKind, ParentLink};
use super::{RigErrorKind, RigSweep};
use crate::bind::{SweepBinder, VertexBinding};
use crate::sweep::{Key, Sweep};

/// A key of a child sweep bound to its parent: the key's center bound to the parent's surface
/// as a vertex is (Eq. 2 parameters), and q̂ its orientation relative to the parent's frame R(t)
/// at that cross-section: `q_key = R(t)·q̂`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KeyBinding {
    /// (θ, t, d, h) of the key's center on the parent.
    pub params: VertexBinding,
    /// q̂, the key's orientation in the parent's frame at t.
    pub relative: DQuat,
}

impl KeyBinding {
    /// Binds `key` to `parent`; `None` if its center lies beyond the parent's ends (no
    /// cross-section plane of the parent passes through it).
    pub fn new(parent: &Sweep, key: &Key) -> Option<KeyBinding> {
        let binder = SweepBinder::new(parent);
        if binder.roots(key.center).is_empty() {
            return None;
        }
        let params = binder.bind(key.center);
        let relative = parent.orientation(params.t).inverse() * key.rotation.normalize();
        Some(KeyBinding { params, relative })
    }

    /// The key this binding places on `parent`: its center at the bound point and its rotation
    /// R(t)·q̂. The radii are `radii`.
    pub fn key_on(&self, parent: &Sweep, radii: &[f64]) -> Key {
        let VertexBinding { t, theta, d, h } = self.params;
        Key {
            center: parent.point(theta, t, d, h),
            rotation: (parent.orientation(t) * self.relative).normalize(),
            radii: radii.to_vec(),
        }
    }
}

/// A child sweep's link to its parent.
#[derive(Clone, Debug, PartialEq)]
pub struct Link {
    /// The parent's index in the rig.
    pub parent: usize,
    /// Branch or loop.
    pub kind: LinkKind,
    /// The binding of the child's first key.
    pub first: KeyBinding,
    /// The binding of the child's last key (loops only).
    pub last: Option<KeyBinding>,
}

/// Resolves every sweep's parent and binds its keys to the parent's rest surface; fails on an
/// unknown parent, a cycle, a loop of fewer than 3 keys or a key that cannot be bound.
pub fn bind_links(sweeps: &[RigSweep], rest: &[Sweep]) -> Result<Vec<Option<Link>>, RigErrorKind> {
    let parents = sweeps
        .iter()
        .map(|sweep| match &sweep.parent {
            None => Ok(None),
            Some(ParentLink { sweep: parent, .. }) => match sweeps.iter().position(|s| &s.name == parent) {
                Some(index) => Ok(Some(index)),
                None => Err(RigErrorKind::UnknownParent { sweep: sweep.name.clone(), parent: parent.clone() }),
            },
        })
        .collect::<Result<Vec<Option<usize>>, _>>()?;
    check_acyclic(sweeps, &parents)?;
    sweeps
        .iter()
        .zip(&parents)
        .map(|(sweep, parent)| {
            let (Some(parent), Some(link)) = (*parent, &sweep.parent) else { return Ok(None) };
            if link.kind == LinkKind::Loop && sweep.keys.len() < 3 {
                return Err(RigErrorKind::LoopTooShort { sweep: sweep.name.clone(), keys: sweep.keys.len() });
            }
            let bind = |key: usize| {
                KeyBinding::new(&rest[parent], &sweep.keys[key]).ok_or_else(|| RigErrorKind::LinkUnbound {
                    sweep: sweep.name.clone(),
                    key,
                    parent: link.sweep.clone(),
                })
            };
            let first = bind(0)?;
            let last = match link.kind {
                LinkKind::Branch => None,
                LinkKind::Loop => Some(bind(sweep.keys.len() - 1)?),
            };
            Ok(Some(Link { parent, kind: link.kind, first, last }))
        })
        .collect()
}

/// Fails if following parents from some sweep comes back to it.
fn check_acyclic(sweeps: &[RigSweep], parents: &[Option<usize>]) -> Result<(), RigErrorKind> {
    for start in 0..sweeps.len() {
        let mut chain = vec![start];
        let mut current = start;
        while let Some(parent) = parents[current] {
            chain.push(parent);
            if parent == start || chain.len() > sweeps.len() + 1 {
                let names: Vec<&str> = chain.iter().map(|&i| sweeps[i].name.as_str()).collect();
                return Err(RigErrorKind::ParentCycle { chain: names.join(" → ") });
            }
            current = parent;
        }
    }
    Ok(())
}
