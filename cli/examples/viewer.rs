//! The interactive viewer as an example: the same window as `sweepffd view`.
//!
//! ```text
//! cargo run --release --example viewer -- MESH [RIG] [POSE]
//! cargo run --release --example viewer            # the demo tube and its rig
//! ```
//!
//! How a real-time application uses the engine is in `src/view`: the window's device is handed
//! to a `GpuDeformer` (`GpuContext::from_device`), each edit uploads the posed sweeps'
//! coefficients (`set_pose`), `encode` records the deform and normals passes, and the mesh is
//! drawn straight from `positions()` and `normals()` (`src/view/draw.rs`).

use std::path::PathBuf;

use sweepffd::edit::VolumeRule;
use sweepffd::formats::LoadedMesh;
use sweepffd::synthetic::{Tube, tube_rig};
use sweepffd_cli::view::{Subdivide, ViewOptions, run};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1).map(PathBuf::from);
    let (mesh, rig) = match args.next() {
        Some(mesh) => (mesh, args.next()),
        None => {
            // No files: a tube and its rig, written to the temporary folder.
            let folder = std::env::temp_dir().join("sweepffd-viewer-example");
            std::fs::create_dir_all(&folder)?;
            let tube = Tube { rings: 60, around: 48, length: 4.0, radius: 0.5 };
            let (mesh_path, rig_path) = (folder.join("tube.obj"), folder.join("tube-rig.json"));
            let mesh = LoadedMesh::from(tube.mesh());
            mesh.save(&mesh_path, &mesh.mesh.positions)?;
            std::fs::write(&rig_path, tube_rig(&tube, 5, 16).to_document().to_json())?;
            (mesh_path, Some(rig_path))
        }
    };
    let options = ViewOptions {
        mesh,
        rig,
        pose: args.next(),
        subdivide: Subdivide::No,
        volume: VolumeRule::None,
        script: None,
        size: (1280, 800),
        pose_out: PathBuf::from("pose.json"),
    };
    run(options)?;
    Ok(())
}
