//! Targets `rig` and `pose`: rig and pose files parsed and validated as `sweepffd` reads them,
//! then used as `bind`, `deform` and `volume` use them.

use sweepffd::deform::deform_vertices;
use sweepffd::rig::{Rig, RigDocument};
use sweepffd::sweep::Sweep;

use super::Outcome;
use super::scene::scene;

/// The name the rig input goes by in errors.
pub const RIG_FILE: &str = "rig.json";
/// The name the pose input goes by in errors.
pub const POSE_FILE: &str = "pose.json";

/// Parses a rig or pose document as [`RigDocument::load`] does, `file` named in errors.
pub fn document(data: &[u8], file: &str) -> Result<RigDocument, String> {
    let text = std::str::from_utf8(data)
        .map_err(|_| format!("{file}: cannot read the file: stream did not contain valid UTF-8"))?;
    RigDocument::parse(text).map_err(|e| format!("{file}: not a valid rig file: {e}"))
}

/// A rig file: validated, its ownership and binding of the scene's tube, its volumes as
/// `sweepffd volume` reports them; what the rig writes must read back as the same rig.
pub fn rig(data: &[u8]) -> Outcome {
    let document = document(data, RIG_FILE)?;
    let rig = Rig::from_document(&document, Some(RIG_FILE.into())).map_err(|e| e.to_string())?;
    let mesh = &scene().mesh;
    let owners = rig.owners(mesh, "tube.obj").map_err(|e| e.to_string())?;
    let _bindings = rig.bind_mesh(mesh, &owners, &|_| {});
    check_volumes(&rig, rig.rest(), RIG_FILE)?;
    let written = rig.to_document();
    let read_back = RigDocument::parse(&written.to_json()).expect("a written rig parses");
    assert_eq!(read_back, written, "a written rig reads back the same");
    Rig::from_document(&read_back, None).expect("a written rig is valid");
    Ok(())
}

/// A pose file of the scene's rig: validated, then the tube deformed with it (on the CPU) and
/// its volumes measured, each refusing a non-finite result as `deform` and `volume` do.
pub fn pose(data: &[u8]) -> Outcome {
    let scene = scene();
    let document = document(data, POSE_FILE)?;
    let posed = scene.rig.pose_from_document(&document, Some(POSE_FILE.into())).map_err(|e| e.to_string())?;
    let mut deformed = vec![glam::DVec3::ZERO; scene.mesh.positions.len()];
    deform_vertices(scene.rig.rest(), &posed, &scene.bindings, &scene.mesh.positions, &mut deformed);
    check_deformed(&deformed, &scene.bindings, &scene.rig, POSE_FILE)?;
    check_volumes(&scene.rig, &posed, POSE_FILE)
}

/// `deform`'s refusal of a non-finite deformed position.
pub fn check_deformed(
    deformed: &[glam::DVec3],
    bindings: &sweepffd::bind::MeshBindings,
    rig: &Rig,
    pose_file: &str,
) -> Outcome {
    match deformed.iter().position(|p| !p.is_finite()) {
        None => Ok(()),
        Some(i) => {
            let sweep = &rig.sweeps()[bindings.vertices[i].sweep as usize].name;
            Err(format!(
                "{pose_file}: vertex index {i} (sweep {sweep:?}) deforms to a non-finite position; nothing was written"
            ))
        }
    }
}

/// `volume`'s refusal of a non-finite volume.
fn check_volumes(rig: &Rig, sweeps: &[Sweep], file: &str) -> Outcome {
    let mut total = 0.0;
    for (sweep, surface) in rig.sweeps().iter().zip(sweeps) {
        let volume = surface.volume();
        if !volume.is_finite() {
            return Err(format!("{file}: sweep {:?}: the volume (Eq. 1) is not a finite number", sweep.name));
        }
        total += volume;
    }
    if !f64::is_finite(total) {
        return Err(format!("{file}: the total volume is not a finite number"));
    }
    Ok(())
}
