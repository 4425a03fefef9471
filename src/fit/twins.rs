//! Mirror twins rigged alike, for [`super::autorig`]: a character's left and right limbs,
//! found as mirror images of each other ([`super::protrusions::made_alike`]), are fitted each
//! on its own, and the fit, whose key insertion stops where a round of keys does not tighten
//! it, may take a different path on each: spot's front legs, made of the same vertices
//! mirrored, were fitted with 15 and 6 keys, the public ogre's arms' stems with 23 and 16. So
//! of the two rigs, each with its mirror image on the other twin, the one whose looser twin
//! fits better (each link measured against its own target) is kept. The image maps every
//! link's vertices across the plane and reflects its keys ([`Mirror::reflect_key`]); its fit
//! is measured again on its own vertices. Both twins are then posed alike and named in the
//! same order.

use std::time::Instant;

use super::autorig::looseness_of;
use super::chain::FittedLink;
use super::mirror::{Mirror, NO_TWIN};
use super::quality::measure;
use super::{Fit, FitStep};
use crate::mesh::Mesh;
use crate::sweep::Sweep;

/// The pairs `(j, i)`, `j < i`, of `parts` (each a part's vertices, increasing, or `None`)
/// that are each other's mirror images by `mirror`: every vertex of each has its twin (that of
/// the vertex it is welded to, `weld`) welded to a vertex of the other. Each part is in at most
/// one pair; a part on the plane (a tail), its own image, is in none.
pub fn twin_pairs(parts: &[Option<&[u32]>], weld: &[u32], mirror: &Mirror) -> Vec<(usize, usize)> {
    let welded: Vec<Option<Vec<u32>>> = parts.iter().map(|part| part.map(|vertices| welded(vertices, weld))).collect();
    // Whether every vertex of `part` has its twin in `other` (welded, increasing).
    let lands_in = |part: &[u32], other: &[u32]| {
        part.iter().all(|&v| {
            let twin = mirror.map[weld[v as usize] as usize];
            twin != NO_TWIN && other.binary_search(&twin).is_ok()
        })
    };
    let mut paired = vec![false; parts.len()];
    let mut pairs = Vec::new();
    for i in 0..parts.len() {
        let (Some(part), Some(own)) = (parts[i], &welded[i]) else { continue };
        if lands_in(part, own) {
            continue;
        }
        let twin = (0..i).find(|&j| {
            !paired[j]
                && matches!(
                    (parts[j], &welded[j]),
                    (Some(other), Some(theirs)) if lands_in(part, theirs) && lands_in(other, own)
                )
        });
        if let Some(j) = twin {
            paired[j] = true;
            paired[i] = true;
            pairs.push((j, i));
        }
    }
    pairs
}

/// The vertices `vertices` are welded to (`weld`), increasing, each once.
fn welded(vertices: &[u32], weld: &[u32]) -> Vec<u32> {
    let mut welded: Vec<u32> = vertices.iter().map(|&v| weld[v as usize]).collect();
    welded.sort_unstable();
    welded.dedup();
    welded
}

/// How loosely a limb's links fit: the largest of its links' [`looseness_of`] (RMS |d| over
/// the target).
pub fn looseness(links: &[FittedLink]) -> f64 {
    links.iter().map(|link| looseness_of(&link.fit)).fold(0.0, f64::max)
}

/// The mirror image of the limb `links` on its twin, whose vertices are `twin` (increasing, a
/// twin by [`twin_pairs`]): each vertex of `twin` goes to the link that holds its mirror twin
/// (the twin of the vertex it is welded to, `weld`; else a link holding a vertex welded to
/// that), so that the links stay disjoint; each link's fitted vertices are those of `twin`
/// whose mirror twins are welded to its own; its keys and those of each of its steps are
/// reflected, and its fit measured again on its fitted vertices of `mesh`. `None` where a
/// reflected sweep cannot be built.
pub fn mirrored(
    links: &[FittedLink],
    twin: &[u32],
    weld: &[u32],
    mirror: &Mirror,
    mesh: &Mesh,
) -> Option<Vec<FittedLink>> {
    // Per welded vertex of the limb, its link: the one holding it, else one holding a vertex
    // welded to it.
    let mut owner: std::collections::HashMap<u32, usize> = Default::default();
    for (k, link) in links.iter().enumerate() {
        for &v in &link.vertices {
            if weld[v as usize] == v {
                owner.insert(v, k);
            }
        }
    }
    for (k, link) in links.iter().enumerate() {
        for &v in &link.vertices {
            owner.entry(weld[v as usize]).or_insert(k);
        }
    }
    let source = |v: u32| mirror.map[weld[v as usize] as usize];
    let mut vertices: Vec<Vec<u32>> = vec![Vec::new(); links.len()];
    for &v in twin {
        if let Some(&k) = owner.get(&source(v)) {
            vertices[k].push(v);
        }
    }
    let image = |of: &[u32]| {
        let own = welded(of, weld);
        twin.iter().copied().filter(|&v| own.binary_search(&source(v)).is_ok()).collect::<Vec<u32>>()
    };
    links
        .iter()
        .zip(vertices)
        .map(|(link, vertices)| {
            let started = Instant::now();
            let fitted = image(&link.fitted);
            let reflect =
                |keys: &[crate::sweep::Key]| keys.iter().map(|key| mirror.reflect_key(key)).collect::<Vec<_>>();
            let keys = reflect(&link.fit.keys);
            let sweep = Sweep::try_new(&keys, None).ok()?;
            let positions: Vec<_> = fitted.iter().map(|&v| mesh.positions[v as usize]).collect();
            let quality = measure(&sweep, &positions).quality;
            let steps = link
                .fit
                .steps
                .iter()
                .map(|step| FitStep { label: step.label.clone(), keys: reflect(&step.keys), quality: step.quality })
                .collect();
            let fit = Fit { keys, quality, steps, ..link.fit.clone() };
            Some(FittedLink { vertices, fitted, fit, seconds: started.elapsed().as_secs_f64(), parent: link.parent })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    /// Vertices 0–9 mirror 10–19 (v ↔ v + 10), 20–29 lie on the plane (each its own twin).
    fn mirror() -> Mirror {
        let map = (0..30u32).map(|v| if v < 10 { v + 10 } else if v < 20 { v - 10 } else { v }).collect();
        Mirror { point: DVec3::ZERO, normal: DVec3::X, map, near: false }
    }

    #[test]
    fn parts_that_are_each_others_images_are_twins_and_a_part_on_the_plane_is_none() {
        let weld: Vec<u32> = (0..30).collect();
        let left: Vec<u32> = (0..10).collect();
        let right: Vec<u32> = (10..20).collect();
        let tail: Vec<u32> = (20..30).collect();
        let parts = [Some(&tail[..]), Some(&left[..]), None, Some(&right[..])];
        assert_eq!(twin_pairs(&parts, &weld, &mirror()), vec![(1, 3)]);
        // A part short of one vertex's image is no twin.
        let short: Vec<u32> = (10..19).collect();
        assert_eq!(twin_pairs(&[Some(&left[..]), Some(&short[..])], &weld, &mirror()), vec![]);
    }

    #[test]
    fn a_vertex_welded_to_a_twins_image_goes_with_it() {
        // Vertex 30 is a seam's copy of 12: welded to it, it takes the link 12 takes.
        let mut weld: Vec<u32> = (0..31).collect();
        weld[30] = 12;
        let mut mirror = mirror();
        mirror.map.push(NO_TWIN);
        let right: Vec<u32> = (10..20).chain([30]).collect();
        let left: Vec<u32> = (0..10).collect();
        assert_eq!(twin_pairs(&[Some(&left[..]), Some(&right[..])], &weld, &mirror), vec![(0, 1)]);
    }
}

