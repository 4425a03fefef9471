//! `sweepffd batch`: a 40-job manifest over two (mesh, rig) pairs with two hostile jobs (a
//! missing mesh, a rig for another mesh), run as 4 shards in 4 processes at once. The union of
//! their outputs is what running every job alone with `deform` writes, byte for byte; the two
//! failures are in the reports with their errors and fail their shards' exit statuses; a rerun
//! does no work; a shard stopped mid-run leaves no partial output, and its rerun completes it.

use crate::common;

use std::fs;
use std::path::Path;
use std::process::{Child, Command, Output};

use serde_json::Value;
use sweepffd::formats::LoadedMesh;
use sweepffd::rig::{Rig, RigSweep, VertexSelection};
use sweepffd::sweep::Key;
use sweepffd::synthetic::{BendTwistTaper, Tube};

use common::sweepffd;

const SHARDS: usize = 4;

/// A tube and a rig of it owning its vertices by index, so that it is a rig for no mesh with
/// fewer vertices.
fn tube_scene(dir: &Path, name: &str, tube: &Tube, poses: usize) {
    let mesh = LoadedMesh::from(tube.mesh());
    mesh.save(&dir.join(format!("{name}.obj")), &mesh.mesh.positions).unwrap();
    let keys: Vec<Key> = (0..5)
        .map(|i| {
            let z = tube.length * i as f64 / 4.0;
            Key::circle(glam::DVec3::new(0.0, 0.0, z), glam::DQuat::IDENTITY, tube.radius, 8)
        })
        .collect();
    let owned = VertexSelection::Indices((0..mesh.mesh.positions.len() as u32).collect());
    let rig = Rig::new(vec![RigSweep::new("tube", keys).owning(owned)]).unwrap();
    fs::write(dir.join(format!("{name}-rig.json")), rig.to_document().to_json()).unwrap();
    for i in 0..poses {
        let pose = BendTwistTaper { bend: 0.1 * i as f64, twist: 0.07 * i as f64, taper: 1.0 - 0.02 * i as f64 };
        fs::write(dir.join(format!("{name}-pose-{i}.json")), rig.pose_document(&pose.keys(&rig)).to_json()).unwrap();
    }
}

/// The manifest's 40 jobs: 19 of each tube, interleaved, a job on a missing mesh (line 7) and
/// one of tube a with tube b's rig (line 30), whose vertices a lacks.
fn manifest(dir: &Path) -> Vec<Value> {
    tube_scene(dir, "a", &Tube { rings: 30, around: 16, length: 3.0, radius: 0.4 }, 19);
    tube_scene(dir, "b", &Tube { rings: 50, around: 12, length: 2.0, radius: 0.3 }, 19);
    let (mut a, mut b) = (0, 0);
    let jobs: Vec<Value> = (0..40)
        .map(|n| {
            let job = |mesh: &str, rig: &str, pose: String| {
                serde_json::json!({"mesh": mesh, "rig": rig, "pose": pose, "out": format!("out/job-{n}.obj")})
            };
            match n {
                7 => job("nowhere.obj", "a-rig.json", "a-pose-0.json".into()),
                30 => job("a.obj", "b-rig.json", "b-pose-0.json".into()),
                _ if n % 2 == 0 => {
                    a += 1;
                    job("a.obj", "a-rig.json", format!("a-pose-{}.json", a - 1))
                }
                _ => {
                    b += 1;
                    job("b.obj", "b-rig.json", format!("b-pose-{}.json", b - 1))
                }
            }
        })
        .collect();
    let text: String = jobs.iter().map(|job| format!("{job}\n")).collect();
    fs::write(dir.join("jobs.jsonl"), text).unwrap();
    fs::create_dir_all(dir.join("out")).unwrap();
    fs::create_dir_all(dir.join("alone")).unwrap();
    jobs
}

fn shard(dir: &Path, k: usize) -> Child {
    let report = format!("report-{k}.jsonl");
    let shard = format!("{k}/{SHARDS}");
    sweepffd(dir)
        .args(["--quiet", "batch", "--manifest", "jobs.jsonl", "--shard", &shard, "--report", &report])
        .args(["--backend", "cpu"])
        .stderr(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .spawn()
        .unwrap()
}

/// Runs the 4 shards at once; their outputs, and the merged report lines by job.
fn run_shards(dir: &Path) -> (Vec<Output>, Vec<Value>) {
    let children: Vec<Child> = (0..SHARDS).map(|k| shard(dir, k)).collect();
    let outputs: Vec<Output> = children.into_iter().map(|c| c.wait_with_output().unwrap()).collect();
    let mut lines: Vec<Value> = (0..SHARDS)
        .flat_map(|k| {
            let text = fs::read_to_string(dir.join(format!("report-{k}.jsonl"))).unwrap();
            text.lines().map(|l| serde_json::from_str::<Value>(l).unwrap()).collect::<Vec<_>>()
        })
        .collect();
    lines.sort_by_key(|line| line["job"].as_u64());
    (outputs, lines)
}

#[test]
fn four_shards_make_what_every_job_makes_alone_and_a_rerun_does_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    let jobs = manifest(dir);
    // Every job alone, as `deform` runs it.
    for (n, job) in jobs.iter().enumerate() {
        let out = format!("alone/job-{n}.obj");
        let status = sweepffd(dir)
            .args(["--quiet", "deform", "--backend", "cpu", "--out", &out])
            .args(["--mesh", job["mesh"].as_str().unwrap(), "--rig", job["rig"].as_str().unwrap()])
            .args(["--pose", job["pose"].as_str().unwrap()])
            .stderr(std::process::Stdio::null())
            .status()
            .unwrap();
        assert_eq!(status.success(), n != 7 && n != 30, "job {n} alone");
    }
    let (outputs, report) = run_shards(dir);
    // Shard 3 holds job 7 (7 mod 4 = 3), shard 2 holds job 30 (30 mod 4 = 2).
    for (k, output) in outputs.iter().enumerate() {
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.success(), k != 2 && k != 3, "shard {k}: {stderr}");
        if !output.status.success() {
            assert!(stderr.contains("1 of the 10 jobs of shard"), "shard {k}: {stderr}");
        }
    }
    assert_eq!(report.len(), 40, "one report line per job");
    for (n, line) in report.iter().enumerate() {
        assert_eq!(line["job"], n);
        let out = dir.join(format!("out/job-{n}.obj"));
        match n {
            7 | 30 => {
                assert_eq!(line["status"], "failed", "{line}");
                assert!(!out.exists(), "job {n} wrote its output");
            }
            _ => {
                assert_eq!(line["status"], "done", "{line}");
                let alone = fs::read(dir.join(format!("alone/job-{n}.obj"))).unwrap();
                assert!(fs::read(&out).unwrap() == alone, "job {n}: the batch's output differs from deform's");
            }
        }
    }
    let error = |n: usize| report[n]["error"].as_str().unwrap().to_string();
    assert!(error(7).contains("nowhere.obj"), "{}", error(7));
    assert!(error(30).contains("a.obj"), "the rig for another mesh names the mesh: {}", error(30));
    // A rerun finds every output made: nothing is done again.
    let (_, again) = run_shards(dir);
    let done = again.iter().filter(|l| l["status"] == "done").count();
    let skipped = again.iter().filter(|l| l["status"] == "skipped").count();
    assert_eq!((done, skipped), (0, 38), "{again:?}");
}

/// A shard stopped by SIGTERM mid-run leaves each output whole or absent (no temporary file
/// either); its rerun makes the rest, the same as an uninterrupted run.
#[test]
fn a_shard_stopped_mid_run_leaves_no_partial_output_and_its_rerun_completes_it() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    // Bigger meshes, so that each job takes a while.
    tube_scene(dir, "big", &Tube { rings: 400, around: 250, length: 3.0, radius: 0.4 }, 12);
    let text: String = (0..12)
        .map(|i| {
            let job = serde_json::json!({"mesh": "big.obj", "rig": "big-rig.json", "pose": format!("big-pose-{i}.json"),
                "out": format!("out/job-{i}.obj")});
            format!("{job}\n")
        })
        .collect();
    fs::write(dir.join("jobs.jsonl"), text).unwrap();
    fs::create_dir_all(dir.join("out")).unwrap();
    let run = |report: &str| {
        sweepffd(dir)
            .args(["--quiet", "batch", "--manifest", "jobs.jsonl", "--report", report, "--backend", "cpu"])
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap()
    };
    let mut child = run("stopped.jsonl");
    // Stop it once its first output is written.
    let started = std::time::Instant::now();
    while !dir.join("out/job-0.obj").exists() && started.elapsed().as_secs() < 60 {
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    let status = Command::new("kill").args(["-TERM", &child.id().to_string()]).status().unwrap();
    assert!(status.success());
    let stopped = child.wait().unwrap();
    assert_eq!(stopped.code(), Some(143), "SIGTERM ends it with 128 + 15");
    let made: Vec<String> =
        fs::read_dir(dir.join("out")).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
    eprintln!("stopped after {} of 12 outputs", made.len());
    assert!(made.len() < 12, "the shard was stopped before the end: {made:?}");
    assert!(
        made.iter().all(|name| name.starts_with("job-") && name.ends_with(".obj")),
        "a temporary file was left: {made:?}"
    );
    assert!(!dir.join("stopped.jsonl").exists(), "no report from a stopped shard");
    let finished = run("finished.jsonl").wait().unwrap();
    assert!(finished.success());
    let report = fs::read_to_string(dir.join("finished.jsonl")).unwrap();
    let skipped = report.lines().filter(|l| l.contains("\"skipped\"")).count();
    assert_eq!(skipped, made.len(), "{report}");
    // Every output, whether made before the stop or after, is what `deform` makes.
    for i in 0..12 {
        let alone = format!("alone-{i}.obj");
        let status = sweepffd(dir)
            .args(["--quiet", "deform", "--backend", "cpu", "--mesh", "big.obj", "--rig", "big-rig.json"])
            .args(["--pose", &format!("big-pose-{i}.json"), "--out", &alone])
            .stderr(std::process::Stdio::null())
            .status()
            .unwrap();
        assert!(status.success());
        assert!(
            fs::read(dir.join(&alone)).unwrap() == fs::read(dir.join(format!("out/job-{i}.obj"))).unwrap(),
            "job {i}"
        );
    }
}

/// A rig with no sweeps (autorig's for a mesh with nothing to rig) moves nothing: its jobs
/// write the mesh as it is, as `deform` does, and count as done.
#[test]
fn jobs_of_a_rig_without_sweeps_write_the_mesh_as_it_is() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    tube_scene(dir, "a", &Tube { rings: 10, around: 8, length: 1.0, radius: 0.2 }, 1);
    let mut empty = sweepffd::rig::RigDocument::parse(&fs::read_to_string(dir.join("a-rig.json")).unwrap()).unwrap();
    empty.sweeps.clear();
    fs::write(dir.join("empty.json"), empty.to_json()).unwrap();
    let job = serde_json::json!({"mesh": "a.obj", "rig": "empty.json", "pose": "a-pose-0.json", "out": "out.obj"});
    fs::write(dir.join("jobs.jsonl"), format!("{job}\n")).unwrap();
    let output = sweepffd(dir)
        .args(["--quiet", "batch", "--manifest", "jobs.jsonl", "--report", "r.jsonl", "--backend", "cpu"])
        .output()
        .unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert!(String::from_utf8_lossy(&output.stderr).contains("wrote the mesh unchanged"));
    assert_eq!(fs::read(dir.join("out.obj")).unwrap(), fs::read(dir.join("a.obj")).unwrap());
    assert!(fs::read_to_string(dir.join("r.jsonl")).unwrap().contains("\"status\":\"done\""));
}
