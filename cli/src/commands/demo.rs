//! `sweepffd demo`: a self-contained tour. Builds a tube and a five-key rig, bends, twists and
//! tapers it, and writes the rest mesh, the deformed mesh, the rig and the pose.

use std::path::{Path, PathBuf};
use std::time::Instant;

use std::io::Write;

use glam::DVec3;

use super::CliResult;
use sweepffd::atomic_file::write_atomically;
use sweepffd::deform::deform_vertices;
use sweepffd::formats::LoadedMesh;
use sweepffd::synthetic::{BendTwistTaper, Tube, tube_rig};

/// The arguments of `sweepffd demo`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Folder for the demo's files.
    #[arg(long, default_value = "sweepffd-demo")]
    pub out: PathBuf,
}

pub fn run(args: &Args, quiet: bool) -> CliResult {
    let out = args.out.as_path();
    std::fs::create_dir_all(out).map_err(|e| format!("cannot create {}: {e}", out.display()))?;
    let tube = Tube { rings: 160, around: 96, length: 4.0, radius: 0.5 };
    let mesh = tube.mesh();
    let rig = tube_rig(&tube, 5, 16);
    let pose = BendTwistTaper { bend: 0.6 * std::f64::consts::PI, twist: 0.75 * std::f64::consts::PI, taper: 0.45 };
    let posed_keys = pose.keys(&rig);
    let posed = rig.pose(&posed_keys)?;

    let owners = rig.owners(&mesh, "tube")?;
    let start = Instant::now();
    let bindings = rig.bind_mesh(&mesh, &owners, &|_| {});
    let bind_seconds = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let mut deformed = vec![DVec3::ZERO; mesh.positions.len()];
    deform_vertices(rig.rest(), &posed, &bindings, &mesh.positions, &mut deformed);
    let deform_seconds = start.elapsed().as_secs_f64();

    let [rest_path, deformed_path, rig_path, pose_path] =
        ["rest.obj", "deformed.obj", "rig.json", "pose.json"].map(|name| out.join(name));
    let file = LoadedMesh::from(mesh);
    file.save(&rest_path, &file.mesh.positions)?;
    file.save(&deformed_path, &deformed)?;
    write_text(&rig_path, &rig.to_document().try_to_json(&rig_path)?)?;
    write_text(&pose_path, &rig.pose_document(&posed_keys).try_to_json(&pose_path)?)?;

    if !quiet {
        let (rest_volume, posed_volume) = (rig.rest()[0].volume(), posed[0].volume());
        out!(
            "sweepffd demo: a tube of {} vertices bound to a 5-key sweep, bent 108°, twisted 135°, tapered to 45%",
            file.mesh.positions.len()
        );
        out!("  bound in {bind_seconds:.3} s, deformed in {deform_seconds:.4} s");
        out!("  sweep volume (Eq. 1): rest {rest_volume:.4}, posed {posed_volume:.4}");
        out!("  wrote {}", rest_path.display());
        out!("  wrote {}", deformed_path.display());
        out!("  wrote {}", rig_path.display());
        out!("  wrote {}", pose_path.display());
        out!(
            "  the same from the command line: sweepffd deform --mesh {} --rig {} --pose {} --out deformed.ply",
            rest_path.display(),
            rig_path.display(),
            pose_path.display()
        );
    }
    Ok(())
}

fn write_text(path: &Path, text: &str) -> CliResult {
    write_atomically(path, |out| out.write_all(text.as_bytes()))
        .map_err(|e| format!("cannot write {}: {e}", path.display()).into())
}
