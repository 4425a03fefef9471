//! The scene of issue 15's file-speed figures: the Stanford bunny subdivided to 2M vertices,
//! as OBJ (shortest round-trip f64 digits, about 17 per coordinate) and as binary PLY, with two
//! rigs and their poses: `ears.json`, the two fitted ears (about 3 % of the vertices move), and
//! `axis.json`, one sweep along the principal axis that owns every vertex (every line of the
//! OBJ is rewritten). An ignored test, run by hand:
//!
//! ```text
//! SWEEPFFD_SCENE_DIR=DIR cargo test --release --test io_scene -- --ignored --nocapture
//! sweepffd deform --mesh DIR/bunny_2m.obj --rig DIR/ears.json --pose DIR/ears_pose.json --out DIR/out.obj
//! ```

use crate::common;

use std::path::PathBuf;

use glam::DVec3;
use sweepffd::fit::{FitOptions, fit, largest_connected};
use sweepffd::formats::LoadedMesh;
use sweepffd::mesh::Mesh;
use sweepffd::rig::{FORMAT, Rig, RigDocument, VERSION, VertexSelection};
use sweepffd::synthetic::BendTwistTaper;

fn front_ear(p: DVec3) -> bool {
    p.z < -0.012 && p.x < -0.055 && p.y > 0.13
}

fn back_ear(p: DVec3) -> bool {
    p.x > -0.055 && p.x < 0.0 && p.y > 0.148 && p.z < 0.01
}

#[test]
#[ignore = "writes the 2M-vertex bunny scene for the file-speed figures; set SWEEPFFD_SCENE_DIR"]
fn write_the_two_million_vertex_bunny_with_two_rigs() {
    let Some(path) = common::shared_mesh("bunny_stanford_zipper.obj") else { return };
    let dir = PathBuf::from(std::env::var("SWEEPFFD_SCENE_DIR").expect("SWEEPFFD_SCENE_DIR names the output folder"));
    let bunny = Mesh::load(&path).unwrap();
    let (mesh, steps) = bunny.subdivided_to(2_000_000).unwrap();
    let mut sweeps = Vec::new();
    for (name, inside) in [("front_ear", front_ear as fn(DVec3) -> bool), ("back_ear", back_ear)] {
        let ear = largest_connected(&bunny, inside);
        let fitted = fit(&bunny, &ear, &FitOptions::default()).unwrap();
        let owned = steps.iter().fold(ear, |owned, step| step.carry(&owned));
        sweeps.push(fitted.sweep_document(name.into(), VertexSelection::Indices(owned), None));
    }
    let ears = RigDocument { format: FORMAT.into(), version: VERSION, rotation_interpolation: None, sweeps };
    let ears = Rig::from_document(&ears, None).unwrap();
    let axis = common::axis_rig(&mesh, 9, 16);
    let pose = BendTwistTaper { bend: 0.3, twist: 0.2, taper: 0.8 };
    for (name, rig) in [("ears", &ears), ("axis", &axis)] {
        std::fs::write(dir.join(format!("{name}.json")), rig.to_document().to_json()).unwrap();
        std::fs::write(dir.join(format!("{name}_pose.json")), rig.pose_document(&pose.keys(rig)).to_json()).unwrap();
    }
    println!("{} vertices, {} faces", mesh.positions.len(), mesh.faces.len());
    let file = LoadedMesh::from(mesh);
    file.save(&dir.join("bunny_2m.obj"), &file.mesh.positions).unwrap();
    file.save(&dir.join("bunny_2m.ply"), &file.mesh.positions).unwrap();
}

/// The process's CPU time so far (user + system), from `/proc/self/stat`, in seconds; 0 where
/// there is no such file.
fn cpu_seconds() -> f64 {
    let Ok(stat) = std::fs::read_to_string("/proc/self/stat") else { return 0.0 };
    // The fields after the command name, which ends in the last ')': utime and stime are the
    // 12th and 13th of them, in clock ticks of 1/100 s.
    let fields: Vec<&str> = stat[stat.rfind(')').unwrap_or(0) + 1..].split_whitespace().collect();
    let ticks = |i: usize| fields.get(i).and_then(|f| f.parse::<f64>().ok()).unwrap_or(0.0);
    (ticks(11) + ticks(12)) / 100.0
}

/// Best of `runs` of `f`: (wall seconds, CPU seconds) of the run with the least wall time.
fn best_of(runs: usize, mut f: impl FnMut()) -> (f64, f64) {
    (0..runs)
        .map(|_| {
            let (wall, cpu) = (std::time::Instant::now(), cpu_seconds());
            f();
            (wall.elapsed().as_secs_f64(), cpu_seconds() - cpu)
        })
        .fold((f64::MAX, 0.0), |best, run| if run.0 < best.0 { run } else { best })
}

#[test]
#[ignore = "times Mesh::load and Mesh::save on the scene of the test above; set SWEEPFFD_SCENE_DIR"]
fn time_loading_and_saving_the_scene() {
    let dir = PathBuf::from(std::env::var("SWEEPFFD_SCENE_DIR").expect("SWEEPFFD_SCENE_DIR names the scene folder"));
    let runs = std::env::var("SWEEPFFD_RUNS").ok().and_then(|r| r.parse().ok()).unwrap_or(3);
    for name in ["bunny_2m.obj", "bunny_2m.ply", "bunny_2m_ascii.ply"] {
        let path = dir.join(name);
        if !path.is_file() {
            continue;
        }
        let mut mesh = None;
        let (wall, cpu) = best_of(runs, || mesh = Some(LoadedMesh::load(&path).unwrap()));
        println!("{name}: load {wall:.3} s wall, {cpu:.2} s CPU");
        let mesh = mesh.unwrap();
        for rig in ["ears", "axis"] {
            let rig = Rig::load(&dir.join(format!("{rig}.json"))).unwrap();
            let owners = rig.owners(&mesh.mesh, name).unwrap();
            // Every owned vertex moved by a little, as a deformation moves it.
            let moved: Vec<DVec3> = mesh
                .mesh
                .positions
                .iter()
                .zip(&owners)
                .map(|(&p, &o)| if o == sweepffd::bind::UNOWNED { p } else { p * 1.001 + DVec3::splat(1e-4) })
                .collect();
            let out = dir.join(format!("timed_{name}"));
            let (wall, cpu) = best_of(runs, || mesh.save(&out, &moved).unwrap());
            let count = owners.iter().filter(|&&o| o != sweepffd::bind::UNOWNED).count();
            println!("{name}: save with {count} moved {wall:.3} s wall, {cpu:.2} s CPU");
        }
    }
}
