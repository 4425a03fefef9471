//! Which sweep owns which vertex: groups, index lists or all vertices; no vertex twice.

use super::{Rig, RigError, RigErrorKind, VertexSelection};
use crate::bind::UNOWNED;
use crate::mesh::Mesh;

impl Rig {
    /// The owning sweep of every vertex of `mesh` (an index into [`Rig::sweeps`], or
    /// [`UNOWNED`]). `mesh_name` names the mesh in errors: an unknown group, an index out of
    /// range, a vertex claimed by two sweeps, or a falloff wider than the mesh.
    pub fn owners(&self, mesh: &Mesh, mesh_name: &str) -> Result<Vec<u32>, RigError> {
        self.check_falloffs_fit(mesh, mesh_name)?;
        let fail = |kind| RigError::new(self.file.clone(), kind);
        let count = mesh.positions.len();
        let mut owners = vec![UNOWNED; count];
        for (s, sweep) in self.sweeps.iter().enumerate() {
            let claimed: Vec<u32> = match &sweep.vertices {
                None => Vec::new(),
                Some(VertexSelection::All) => (0..count as u32).collect(),
                Some(VertexSelection::Indices(indices)) => {
                    if let Some(&index) = indices.iter().find(|&&i| i as usize >= count) {
                        let (sweep, mesh) = (sweep.name.clone(), mesh_name.to_string());
                        return Err(fail(RigErrorKind::VertexOutOfRange { sweep, index, mesh, count }));
                    }
                    let mut indices = indices.clone();
                    indices.sort_unstable();
                    indices.dedup();
                    indices
                }
                Some(VertexSelection::Groups(groups)) => {
                    let mut vertices = Vec::new();
                    for group in groups {
                        let Some(members) = mesh.group_vertices(group) else {
                            let available = mesh.groups.iter().map(|g| g.name.as_str()).collect::<Vec<_>>().join(", ");
                            return Err(fail(RigErrorKind::UnknownGroup {
                                sweep: sweep.name.clone(),
                                group: group.clone(),
                                mesh: mesh_name.to_string(),
                                available: if available.is_empty() { "none".to_string() } else { available },
                            }));
                        };
                        vertices.extend(members);
                    }
                    vertices.sort_unstable();
                    vertices.dedup();
                    vertices
                }
            };
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
