//! Binding a mesh to a rig: every owned vertex to its sweep, with the falloff bands of the
//! sweeps that have one.

use super::{Rig, RigError, RigErrorKind};
use crate::bind::MeshBindings;
use crate::bind::falloff::{BandWeight, band_weights};
use crate::limits::MAX_RADIUS_PER_MESH_SIZE;
use crate::mesh::Mesh;

impl Rig {
    /// Binds every vertex of `mesh` that `owners` (from [`Rig::owners`]) gives a sweep, and
    /// computes the falloff bands along the mesh's surface ([`MeshBindings::bind`]).
    pub fn bind_mesh(&self, mesh: &Mesh, owners: &[u32], progress: &(dyn Fn(usize) + Sync)) -> MeshBindings {
        MeshBindings::bind(self.rest(), &self.falloffs(), owners, &mesh.positions, &mesh.faces, progress)
    }

    /// The falloff weights of `mesh`'s band vertices ([`band_weights`]), for the GPU deformer;
    /// empty when no sweep has a falloff.
    pub fn band_weights(&self, mesh: &Mesh, owners: &[u32]) -> Vec<BandWeight> {
        band_weights(&mesh.faces, &mesh.positions, owners, &self.falloffs())
    }

    /// Fails, naming the sweep, if a falloff is wider than `mesh` (its bounding box diagonal):
    /// a band that wide would cover every part and is a units mistake. Fails, naming the sweep
    /// and key, if a radius is more than [`MAX_RADIUS_PER_MESH_SIZE`] times the diagonal, where
    /// f64 no longer places the mesh's vertices accurately.
    pub fn check_fits_mesh(&self, mesh: &Mesh, mesh_name: &str) -> Result<(), RigError> {
        let diagonal = mesh.diagonal();
        for sweep in self.sweeps() {
            let mut radii = sweep.keys.iter().enumerate().flat_map(|(k, key)| key.radii.iter().map(move |&r| (k, r)));
            if let Some((key, radius)) = radii.find(|(_, r)| diagonal > 0.0 && *r > MAX_RADIUS_PER_MESH_SIZE * diagonal)
            {
                return Err(RigError::new(
                    self.file().map(Into::into),
                    RigErrorKind::RadiusTooLarge {
                        sweep: sweep.name.clone(),
                        key,
                        radius,
                        mesh: mesh_name.to_string(),
                        diagonal,
                    },
                ));
            }
        }
        match self.sweeps().iter().find(|sweep| sweep.falloff > diagonal) {
            Some(sweep) => Err(RigError::new(
                self.file().map(Into::into),
                RigErrorKind::FalloffTooLarge {
                    sweep: sweep.name.clone(),
                    falloff: sweep.falloff,
                    mesh: mesh_name.to_string(),
                    diagonal,
                },
            )),
            None => Ok(()),
        }
    }
}
