//! Which sweep owns which vertex: groups, index lists or all vertices; no vertex twice.
//!
//! [`Rig::owners_of`] resolves ownership from named vertex groups as an engine keeps them (a
//! name and its vertex indices), without a [`Mesh`]; [`Rig::owners`] is the same for a mesh's
//! face groups, plus the check that no falloff is wider than the mesh.

use std::collections::HashSet;

use super::{Rig, RigError, RigErrorKind, RigSweep, VertexSelection};
use crate::layout::UNOWNED;
use crate::mesh::Mesh;

impl Rig {
    /// The owning sweep of every vertex of `mesh` (an index into [`Rig::sweeps`], or
    /// [`UNOWNED`]), the groups being the vertices of its face groups
    /// ([`Mesh::group_vertices`]). `mesh_name` names the mesh in errors: an unknown group, an
    /// index out of range, a vertex claimed by two sweeps, or a falloff wider than the mesh.
    pub fn owners(&self, mesh: &Mesh, mesh_name: &str) -> Result<Vec<u32>, RigError> {
        self.check_fits_mesh(mesh, mesh_name)?;
        // Only the groups a sweep names are gathered: a file may have 100,000 groups.
        let named: HashSet<&str> = self
            .sweeps
            .iter()
            .filter_map(|sweep| match &sweep.vertices {
                Some(VertexSelection::Groups(names)) => Some(names.iter().map(String::as_str)),
                _ => None,
            })
            .flatten()
            .collect();
        let groups: Vec<(&str, Vec<u32>)> = mesh
            .groups
            .iter()
            .map(|group| {
                let vertices =
                    if named.contains(group.name.as_str()) { mesh.face_group_vertices(group) } else { Vec::new() };
                (group.name.as_str(), vertices)
            })
            .collect();
        let groups: Vec<(&str, &[u32])> = groups.iter().map(|(name, vertices)| (*name, vertices.as_slice())).collect();
        self.owners_of(mesh.positions.len(), &groups, mesh_name)
    }

    /// The owning sweep of each of `vertex_count` vertices of a mesh held as plain arrays,
    /// without named groups (an index into [`Rig::sweeps`], or [`UNOWNED`]): sweeps select
    /// [`VertexSelection::All`] or [`VertexSelection::Indices`]. Errors call the mesh "built in
    /// code": a group named, an index out of range, a vertex claimed by two sweeps.
    pub fn vertex_owners(&self, vertex_count: usize) -> Result<Vec<u32>, RigError> {
        self.owners_of(vertex_count, &[], "built in code")
    }

    /// The owning sweep of each of `vertex_count` vertices (an index into [`Rig::sweeps`], or
    /// [`UNOWNED`]), a sweep's [`VertexSelection::Groups`] looked up by name in `groups` (the
    /// first of a name counts; indices in any order, repeats allowed). `mesh_name` names the
    /// mesh in errors: an unknown group (listing `groups`), an index out of range, a vertex
    /// claimed by two sweeps.
    ///
    /// Unlike [`Rig::owners`] it cannot check that no falloff is wider than the mesh (it has no
    /// positions); a falloff that wide covers every part.
    pub fn owners_of(
        &self,
        vertex_count: usize,
        groups: &[(&str, &[u32])],
        mesh_name: &str,
    ) -> Result<Vec<u32>, RigError> {
        let fail = |kind| RigError::new(self.file.clone(), kind);
        let mut owners = vec![UNOWNED; vertex_count];
        for (s, sweep) in self.sweeps.iter().enumerate() {
            let claimed = claimed_vertices(sweep, vertex_count, groups, mesh_name).map_err(fail)?;
            for vertex in claimed {
                let owner = &mut owners[vertex as usize];
                if *owner != UNOWNED {
                    return Err(fail(RigErrorKind::VertexClaimedTwice {
                        vertex,
                        first: self.sweeps[*owner as usize].name.clone(),
                        second: sweep.name.clone(),
                    }));
                }
                *owner = s as u32;
            }
        }
        Ok(owners)
    }
}

/// The vertices `sweep` selects out of `count`, increasing and deduplicated.
fn claimed_vertices(
    sweep: &RigSweep,
    count: usize,
    groups: &[(&str, &[u32])],
    mesh_name: &str,
) -> Result<Vec<u32>, RigErrorKind> {
    let out_of_range = |index: u32| RigErrorKind::VertexOutOfRange {
        sweep: sweep.name.clone(),
        index,
        mesh: mesh_name.to_string(),
        count,
    };
    let mut vertices = match &sweep.vertices {
        None => return Ok(Vec::new()),
        Some(VertexSelection::All) => return Ok((0..count as u32).collect()),
        Some(VertexSelection::Indices(indices)) => indices.clone(),
        Some(VertexSelection::Groups(names)) => {
            let mut vertices = Vec::new();
            for name in names {
                let Some((_, members)) = groups.iter().find(|(group, _)| group == name) else {
                    return Err(RigErrorKind::UnknownGroup {
                        sweep: sweep.name.clone(),
                        group: crate::names::shown(name),
                        mesh: mesh_name.to_string(),
                        available: crate::names::listed(groups.iter().map(|(group, _)| *group)),
                    });
                };
                vertices.extend_from_slice(members);
            }
            vertices
        }
    };
    if let Some(&index) = vertices.iter().find(|&&i| i as usize >= count) {
        return Err(out_of_range(index));
    }
    vertices.sort_unstable();
    vertices.dedup();
    Ok(vertices)
}
