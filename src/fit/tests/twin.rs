//! The f32 twins of the deform and band kernels run on a mesh's f64 bindings.

use sweepffd::bind::MeshBindings;
use sweepffd::coeffs::SweepCoefficients;
use sweepffd::cpu;
use sweepffd::mesh::Mesh;
use sweepffd::rig::Rig;
use sweepffd::sweep::Key;

/// The twins' positions (tightly packed f32) of `mesh` deformed by `keys`, from `bindings`
/// converted to the GPU form: the deform kernel's twin, then the band kernel's.
pub fn twin_positions(rig: &Rig, mesh: &Mesh, bindings: &MeshBindings, keys: &[Vec<Key>]) -> Vec<f32> {
    let rest = rig.rest();
    let coefficients = SweepCoefficients::new(rest);
    let (gpu, records) = coefficients.gpu_mesh_bindings(rest, bindings);
    let mut posed = SweepCoefficients::new(rest);
    posed.update(&rig.pose(keys).unwrap()).unwrap();
    let mut positions = cpu::packed(&mesh.positions);
    cpu::deform::deform(&posed.cells, &gpu, &mut positions);
    cpu::band::band(&posed.cells, &coefficients.cells, &gpu, &records, &mut positions);
    positions
}
