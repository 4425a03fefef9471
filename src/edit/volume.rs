//! Volume-preserving interaction (§5, Fig. 13), after an edit and its hierarchy propagation.
//!
//! Scaling every radius of a sweep by f scales its volume (Eq. 1) by exactly f², so a sweep is
//! given a target volume V* by one uniform rescale f = √(V*/V). Rescaling a parent moves the
//! keys its children hang from, so the rules re-run the downward propagation and repeat until
//! every target holds (to 1e-9 relative). The rounds rescale the sweeps' memos only; the keys'
//! radii are multiplied once per sweep, by the product of its factors, once the rule is done
//! and the pose is checked ([`Pending`]). Virtual sweeps (which own no vertices) take no part.

use glam::DVec3;
#[cfg(feature = "json")]
use serde::{Deserialize, Serialize};

use super::EditError;
use super::hierarchy::propagate_down_from;
use super::journal::Journal;
use super::shapes::Shape;
use crate::bind::MeshBindings;
use crate::deform::deform_vertices;
use crate::limits::MAX_RIG_COORDINATE;
use crate::mesh::Mesh;
use crate::rig::Rig;
use crate::sweep::{Key, Sweep};

/// Which volumes an edit keeps.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "json", derive(Serialize, Deserialize))]
#[cfg_attr(feature = "json", serde(rename_all = "lowercase"))]
pub enum VolumeRule {
    /// Volumes follow the edit.
    #[default]
    None,
    /// The edited sweep's volume change ΔV is divided evenly among the other sweeps, each
    /// rescaled to its volume before the edit less its share (Fig. 13a); the sum of the sweeps'
    /// volumes is kept.
    Total,
    /// Each child keeps its volume ratio to its parent (Fig. 13b), rescaled outward from the
    /// edited sweep.
    Ratio,
    /// The enclosed volume of the deformed closed mesh is kept (within 1e-6 relative) by one
    /// common rescale of the other sweeps, solved on the mesh itself.
    Mesh,
}

/// Rounds of rescaling and propagation before a rule is reported as not converging.
const ROUNDS: usize = 20;
/// Relative tolerance of the sweep-volume rules.
const SWEEP_TOLERANCE: f64 = 1e-9;
/// Relative tolerance of the mesh rule.
const MESH_TOLERANCE: f64 = 1e-6;

/// A closed mesh bound to the rig, for [`VolumeRule::Mesh`].
#[derive(Clone, Debug)]
pub struct BoundMesh<'a> {
    /// The mesh at rest.
    pub mesh: &'a Mesh,
    /// Its vertices' bindings to the rig.
    pub bindings: &'a MeshBindings,
}

impl BoundMesh<'_> {
    /// The enclosed volume of the mesh deformed by `keys`.
    pub fn volume(&self, rig: &Rig, keys: &[Vec<Key>]) -> Result<f64, EditError> {
        let posed = rig.pose(keys).map_err(|e| EditError::Invalid(e.to_string()))?;
        let mut positions = vec![DVec3::ZERO; self.mesh.positions.len()];
        deform_vertices(rig.rest(), &posed, self.bindings, &self.mesh.positions, &mut positions);
        Ok(self.mesh.enclosed_volume(&positions))
    }
}

/// The volumes a rule keeps, measured before an edit.
#[derive(Clone, Debug, PartialEq)]
pub struct Volumes {
    /// Eq. 1 of every sweep.
    pub sweeps: Vec<f64>,
    /// The deformed mesh's enclosed volume, when a mesh is bound.
    pub mesh: Option<f64>,
}

impl Volumes {
    /// Measures `keys`.
    pub fn measure(rig: &Rig, keys: &[Vec<Key>], mesh: Option<&BoundMesh>) -> Result<Volumes, EditError> {
        Volumes::measure_kept(rig, keys, mesh, &mut rig.rest().iter().map(Shape::like).collect::<Vec<_>>())
    }

    /// [`Volumes::measure`] with the sweeps' memos `shapes`: a sweep unchanged since its last
    /// volume costs nothing.
    pub(super) fn measure_kept(
        rig: &Rig,
        keys: &[Vec<Key>],
        mesh: Option<&BoundMesh>,
        shapes: &mut [Shape],
    ) -> Result<Volumes, EditError> {
        let sweeps = (0..keys.len()).map(|i| sweep_volume(rig, keys, i, shapes)).collect::<Result<_, _>>()?;
        let mesh = mesh.map(|m| m.volume(rig, keys)).transpose()?;
        Ok(Volumes { sweeps, mesh })
    }
}

/// Applies `rule` after sweep `edited` changed, given the volumes `before` the edit, saving in
/// `journal` the radii it changes. Returns the rescales still to apply to the keys' radii
/// ([`Pending::apply`]), once the pose is checked.
#[expect(
    clippy::too_many_arguments,
    reason = "the rule, the rig and its keys, the edit, and the state the rule keeps (volumes, mesh, shapes, journal)"
)]
pub(super) fn apply_rule(
    rule: VolumeRule,
    rig: &Rig,
    keys: &mut [Vec<Key>],
    edited: usize,
    before: &Volumes,
    mesh: Option<&BoundMesh>,
    shapes: &mut [Shape],
    journal: &mut Journal,
) -> Result<Pending, EditError> {
    if rule == VolumeRule::None || !is_handle(rig, edited) {
        return Ok(Pending::none(keys.len()));
    }
    match rule {
        VolumeRule::None => Ok(Pending::none(keys.len())),
        VolumeRule::Total => keep_total(rig, keys, edited, before, shapes, journal),
        VolumeRule::Ratio => keep_ratios(rig, keys, edited, before, shapes, journal),
        VolumeRule::Mesh => {
            keep_mesh(rig, keys, edited, before, mesh.ok_or(EditError::MeshNeeded)?, journal)?;
            // The mesh rule rescales copies of the keys, not through the memos.
            shapes.iter_mut().for_each(Shape::forget);
            Ok(Pending::none(keys.len()))
        }
    }
}

fn is_handle(rig: &Rig, sweep: usize) -> bool {
    rig.sweeps()[sweep].vertices.is_some()
}

/// The sweeps that absorb the edit: the other handles, or the edited one if it is alone.
fn absorbers(rig: &Rig, edited: usize) -> Vec<usize> {
    let others: Vec<usize> = (0..rig.sweeps().len()).filter(|&i| i != edited && is_handle(rig, i)).collect();
    if others.is_empty() { vec![edited] } else { others }
}

fn sweep_volume(rig: &Rig, keys: &[Vec<Key>], sweep: usize, shapes: &mut [Shape]) -> Result<f64, EditError> {
    Ok(shapes[sweep].volume(&keys[sweep], rig.rest()[sweep].knots())?)
}

fn scale(keys: &mut [Key], factor: f64) {
    for key in keys {
        for radius in &mut key.radii {
            *radius *= factor;
        }
    }
}

/// The factors by which a rule has rescaled each sweep's memo but not yet its keys' radii: a
/// rule rescales a sweep once per round, and its keys' radii are multiplied once, at the end,
/// by the product ([`Pending::apply`]), so a round costs time independent of the radii.
pub(super) struct Pending(Vec<f64>);

impl Pending {
    /// No rescale, for `sweeps` sweeps.
    pub(super) fn none(sweeps: usize) -> Pending {
        Pending(vec![1.0; sweeps])
    }

    /// Multiplies every radius of every sweep by its pending factor. The memo bounds the
    /// scaled radii (its largest radius carries the factors, [`Shape::largest_radius`]);
    /// multiplying by a positive factor is monotonic in the radius, even rounded, so the
    /// largest scaled radius is the bound up to the few ulps by which the product of the
    /// factors rounds differently. A sweep whose bound, with a margin for those, stays within
    /// [`MAX_RIG_COORDINATE`] is scaled in place; any other (none in practice) has its radii
    /// saved in `journal` first and is checked after, failing as its keys would.
    pub(super) fn apply(
        self,
        rig: &Rig,
        keys: &mut [Vec<Key>],
        shapes: &mut [Shape],
        journal: &mut Journal,
    ) -> Result<(), EditError> {
        for (sweep, factor) in self.0.into_iter().enumerate() {
            if factor == 1.0 {
                continue;
            }
            let bounded = shapes[sweep].largest_radius().is_some_and(|r| r * (1.0 + 1e-12) <= MAX_RIG_COORDINATE);
            if bounded {
                scale(&mut keys[sweep], factor);
            } else {
                journal.save_sweep_radii(keys, sweep);
                scale(&mut keys[sweep], factor);
                Sweep::validate(&keys[sweep])
                    .map_err(|source| EditError::Sweep { sweep: rig.sweeps()[sweep].name.clone(), source })?;
            }
        }
        Ok(())
    }
}

/// Rescales `sweep` to volume `target`; its descendants are re-attached at the end of the
/// round ([`propagate_down_from`]), once for all the sweeps the round rescaled.
fn rescale_to(
    rig: &Rig,
    keys: &mut [Vec<Key>],
    sweep: usize,
    target: f64,
    shapes: &mut [Shape],
    pending: &mut Pending,
    journal: &mut Journal,
) -> Result<(), EditError> {
    let volume = sweep_volume(rig, keys, sweep, shapes)?;
    if !(target > 0.0 && volume > 0.0 && target.is_finite()) {
        return Err(EditError::VolumeUnreachable { sweep: rig.sweeps()[sweep].name.clone(), target });
    }
    let factor = (target / volume).sqrt();
    if shapes[sweep].scale_radii(factor) {
        pending.0[sweep] *= factor;
    } else {
        // The memo is gone: its next build reads (and checks) the keys' radii.
        journal.save_sweep_radii(keys, sweep);
        scale(&mut keys[sweep], pending.0[sweep] * factor);
        pending.0[sweep] = 1.0;
    }
    Ok(())
}

/// Repeats `round` (which returns the largest relative error left) until it is within tolerance.
fn until_converged(mut round: impl FnMut() -> Result<f64, EditError>) -> Result<(), EditError> {
    for _ in 0..ROUNDS {
        if round()? <= SWEEP_TOLERANCE {
            return Ok(());
        }
    }
    let remaining = round()?;
    if remaining <= SWEEP_TOLERANCE {
        Ok(())
    } else {
        Err(EditError::VolumeNotConverged { rounds: ROUNDS + 1, remaining })
    }
}

fn keep_total(
    rig: &Rig,
    keys: &mut [Vec<Key>],
    edited: usize,
    before: &Volumes,
    shapes: &mut [Shape],
    journal: &mut Journal,
) -> Result<Pending, EditError> {
    let absorbers = absorbers(rig, edited);
    let alone = absorbers == [edited];
    let mut pending = Pending::none(keys.len());
    until_converged(|| {
        let delta = if alone { 0.0 } else { sweep_volume(rig, keys, edited, shapes)? - before.sweeps[edited] };
        let mut worst = 0.0f64;
        for &a in &absorbers {
            let target = before.sweeps[a] - delta / absorbers.len() as f64;
            worst = worst.max(((sweep_volume(rig, keys, a, shapes)? - target) / target).abs());
            rescale_to(rig, keys, a, target, shapes, &mut pending, journal)?;
        }
        propagate_down_from(rig, keys, &absorbers, shapes)?;
        Ok(worst)
    })?;
    Ok(pending)
}

/// Each (child, parent) pair of handles keeps the ratio of its volumes before the edit,
/// rescaling outward from the edited sweep: a child to its parent, a parent to its child.
fn keep_ratios(
    rig: &Rig,
    keys: &mut [Vec<Key>],
    edited: usize,
    before: &Volumes,
    shapes: &mut [Shape],
    journal: &mut Journal,
) -> Result<Pending, EditError> {
    let order = outward_pairs(rig, edited);
    let mut pending = Pending::none(keys.len());
    until_converged(|| {
        let mut worst = 0.0f64;
        let mut rescaled = Vec::with_capacity(order.len());
        for &(child, parent, rescale_child) in &order {
            // A ratio needs both volumes: a sweep of zero radii has none to keep.
            if let Some(&none) = [child, parent]
                .iter()
                .find(|&&s| before.sweeps[s].partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater))
            {
                return Err(EditError::NoVolumeToKeep { sweep: rig.sweeps()[none].name.clone() });
            }
            let ratio = before.sweeps[child] / before.sweeps[parent];
            let (child_volume, parent_volume) =
                (sweep_volume(rig, keys, child, shapes)?, sweep_volume(rig, keys, parent, shapes)?);
            worst = worst.max(((child_volume / parent_volume - ratio) / ratio).abs());
            if rescale_child {
                rescale_to(rig, keys, child, parent_volume * ratio, shapes, &mut pending, journal)?;
                rescaled.push(child);
            } else {
                rescale_to(rig, keys, parent, child_volume / ratio, shapes, &mut pending, journal)?;
                rescaled.push(parent);
            }
        }
        propagate_down_from(rig, keys, &rescaled, shapes)?;
        Ok(worst)
    })?;
    Ok(pending)
}

/// The (child, parent) links between handles in breadth-first order from `start`, each with
/// whether the child (reached from its parent) or the parent (reached from its child) is the
/// one to rescale.
fn outward_pairs(rig: &Rig, start: usize) -> Vec<(usize, usize, bool)> {
    let mut pairs = Vec::new();
    let mut visited = vec![false; rig.sweeps().len()];
    let mut queue = std::collections::VecDeque::from([start]);
    visited[start] = true;
    while let Some(node) = queue.pop_front() {
        let neighbours = rig.links().iter().enumerate().filter_map(|(child, link)| {
            let link = link.as_ref()?;
            if link.parent == node {
                Some((child, child, node, true))
            } else if child == node {
                Some((link.parent, node, link.parent, false))
            } else {
                None
            }
        });
        for (next, child, parent, rescale_child) in neighbours.collect::<Vec<_>>() {
            if visited[next] {
                continue;
            }
            visited[next] = true;
            queue.push_back(next);
            if is_handle(rig, child) && is_handle(rig, parent) {
                pairs.push((child, parent, rescale_child));
            }
        }
    }
    pairs
}

/// Solves for one common radius scale f of the absorbing sweeps such that the deformed mesh
/// encloses its volume before the edit, by the secant method (volume grows with f, about as f²).
fn keep_mesh(
    rig: &Rig,
    keys: &mut [Vec<Key>],
    edited: usize,
    before: &Volumes,
    mesh: &BoundMesh,
    journal: &mut Journal,
) -> Result<(), EditError> {
    let target = before.mesh.ok_or(EditError::MeshNeeded)?;
    let absorbers = absorbers(rig, edited);
    let start: Vec<Vec<Key>> = keys.to_vec();
    let trial = |f: f64| -> Result<(Vec<Vec<Key>>, f64), EditError> {
        let mut scaled = start.clone();
        for &a in &absorbers {
            scale(&mut scaled[a], f);
            super::hierarchy::propagate_down(rig, &mut scaled, a)?;
        }
        let volume = mesh.volume(rig, &scaled)?;
        Ok((scaled, volume - target))
    };
    let (mut f0, (_, mut g0)) = (1.0, trial(1.0)?);
    let mut f1 = (target / (target + g0)).abs().sqrt();
    for _ in 0..ROUNDS {
        let (scaled, g1) = trial(f1)?;
        if (g1 / target).abs() <= MESH_TOLERANCE {
            // The absorbers' radii change; their descendants only move.
            absorbers.iter().for_each(|&a| journal.save_sweep_radii(keys, a));
            keys.clone_from_slice(&scaled);
            return Ok(());
        }
        let next = if g1 != g0 { f1 - g1 * (f1 - f0) / (g1 - g0) } else { f1 * (target / (target + g1)).abs().sqrt() };
        (f0, g0, f1) = (f1, g1, next);
        if !(f1 > 0.0 && f1.is_finite()) {
            break;
        }
    }
    Err(EditError::VolumeUnreachable { sweep: rig.sweeps()[absorbers[0]].name.clone(), target })
}
