//! Twin of `shaders/normals.wgsl`: area-weighted vertex normals in f32, the normalized sum of
//! (p_j − p_i) × (p_k − p_i) over the incident triangles (i, j, k) of each vertex, read from its
//! fans of one-ring neighbours, for every vertex ([`normals`]) or only listed ones
//! ([`normals_of`], the kernel's dispatch over the vertices whose one-ring moves).

use crate::parallel::prelude::*;
use glam::Vec3;

use super::position;
use crate::normals::{FAN_CLOSE, FAN_END, FAN_INDEX, FAN_START, NormalAdjacency};

/// One invocation of the kernel: the unit normal of vertex `i`, or zero if its triangles have
/// no area. Its row starts at `offsets[i]` and ends with the entry carrying [`FAN_END`]; a
/// vertex with an empty row is never listed (see [`normals`]). (The kernel reads positions
/// through two windows and the rows of its listed vertices only; here one slice holds all
/// positions and `offsets` all rows.)
pub fn vertex_normal(positions: &[f32], offsets: &[u32], fans: &[u32], i: usize) -> Vec3 {
    let p = position(positions, i);
    let mut sum = Vec3::ZERO;
    let mut previous = Vec3::ZERO;
    let mut first = Vec3::ZERO;
    for &entry in &fans[offsets[i] as usize..] {
        let q = position(positions, (entry & FAN_INDEX) as usize) - p;
        if entry & FAN_START == 0 {
            sum += previous.cross(q);
        } else {
            first = q;
        }
        if entry & FAN_CLOSE != 0 {
            sum += q.cross(first);
        }
        previous = q;
        if entry & FAN_END != 0 {
            break;
        }
    }
    let mut n = Vec3::ZERO;
    let length2 = sum.dot(sum);
    if length2 > 0.0 {
        n = sum * length2.sqrt().recip();
    }
    n
}

/// Every invocation of the kernel: the normal of each vertex of `positions` (tightly packed
/// xyz), written tightly packed into `normals`, in parallel. Like the pass, which lists only
/// vertices with incident triangles, a vertex without any gets zero.
pub fn normals(positions: &[f32], adjacency: &NormalAdjacency, normals: &mut [f32]) {
    normals.par_chunks_mut(3).enumerate().for_each(|(i, out)| {
        let n = if adjacency.fans_of(i).is_empty() {
            Vec3::ZERO
        } else {
            vertex_normal(positions, &adjacency.offsets, &adjacency.fans, i)
        };
        out.copy_from_slice(&n.to_array());
    });
}

/// The invocations of the kernel over `vertices` (each with incident triangles, as the pass
/// lists them): writes the normals of those vertices into `normals` (tightly packed xyz, one
/// per vertex of `positions`); the others are left alone.
pub fn normals_of(positions: &[f32], adjacency: &NormalAdjacency, vertices: &[u32], normals: &mut [f32]) {
    let computed: Vec<Vec3> = vertices
        .par_iter()
        .map(|&v| vertex_normal(positions, &adjacency.offsets, &adjacency.fans, v as usize))
        .collect();
    for (&v, n) in vertices.iter().zip(computed) {
        normals[3 * v as usize..3 * v as usize + 3].copy_from_slice(&n.to_array());
    }
}
