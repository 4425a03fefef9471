//! sweepffd inside an application's own frame loop, top to bottom: the app's device, a mesh and
//! a rig built in code, instances posed and animated over frames, and one command encoder that
//! holds the deformation and the app's render pass drawing our buffers as vertex buffers.
//!
//! `cargo run --release --example embed [FOLDER]` writes `FOLDER/embed.png` (default: a folder
//! in the system's temporary directory) and checks every instance against the f64 reference.

use std::f64::consts::{FRAC_PI_2, TAU};

use sweepffd::glam::{DQuat, DVec3};
use sweepffd::{BindingSource, DeformerDescriptor, GpuContext, GpuDeformer, Key, Rig, RigSweep, VertexSelection, wgpu};

const INSTANCES: u32 = 5;
const FRAMES: u32 = 30;
const RINGS: u32 = 48;
const AROUND: u32 = 32;
/// Picture width and height in pixels.
const SIZE: u32 = 640;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // 1. The application's device: sweepffd says which limits to request.
    let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle());
    let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions::default()))?;
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        required_limits: GpuDeformer::required_limits(),
        ..Default::default()
    }))?;
    let context = GpuContext::from_device(device.clone(), queue.clone(), adapter.get_info());

    // 2. A tube along +y, held as an engine holds meshes: f32 positions, a u32 triangle list.
    let positions: Vec<[f32; 3]> = (0..RINGS * AROUND)
        .map(|v| {
            let angle = std::f32::consts::TAU * (v % AROUND) as f32 / AROUND as f32;
            [0.3 * angle.cos(), 2.0 * (v / AROUND) as f32 / (RINGS - 1) as f32, 0.3 * angle.sin()]
        })
        .collect();
    let at = |r: u32, a: u32| r * AROUND + a % AROUND;
    let triangles: Vec<u32> = (0..RINGS - 1)
        .flat_map(|r| {
            (0..AROUND).flat_map(move |a| [(r, a), (r + 1, a), (r, a + 1), (r, a + 1), (r + 1, a), (r + 1, a + 1)])
        })
        .map(|(r, a)| at(r, a))
        .collect();

    // 3. A rig built in code: one sweep of five round keys owning every vertex. Keys look down
    //    +z; turning z onto +y makes them cross-sections of the tube.
    let upright = DQuat::from_rotation_x(-FRAC_PI_2);
    let rest_keys: Vec<Key> = (0..5)
        .map(|k| Key { center: DVec3::new(0.0, 0.5 * k as f64, 0.0), rotation: upright, radii: vec![0.3; 8] })
        .collect();
    let sweep = RigSweep::new("tube", rest_keys.clone()).owning(VertexSelection::All);
    let rig = Rig::new(vec![sweep])?;
    let owners = rig.vertex_owners(positions.len())?;

    // 4. One deformer with INSTANCES instances: bound once on the GPU, one dispatch a frame.
    let bindings = BindingSource::bind(&owners);
    let descriptor = DeformerDescriptor::new(rig.rest(), &positions, bindings)
        .with_triangles(&triangles)
        .with_instances(INSTANCES)
        .with_bounds();
    let mut deformer = GpuDeformer::new(&context, &descriptor)?;

    // 5. The app's own render pipeline, index buffer and offscreen target, made once.
    let app = app::App::new(&device, &triangles, SIZE);

    // 6. The frame loop: pose each instance into storage made once, encode the deformation and
    //    the draw into one encoder, submit.
    let mut poses: Vec<_> = (0..INSTANCES).map(|_| rig.pose_buffer()).collect();
    let mut keys = rest_keys.clone();
    for frame in 1..=FRAMES {
        for (i, pose) in poses.iter_mut().enumerate() {
            let bend = (i as f64 - 2.0) * 0.15 * frame as f64 / FRAMES as f64;
            for (k, key) in keys.iter_mut().enumerate() {
                // Key k turns by k·bend about z around the tube's foot, and twists as it goes.
                let turn = DQuat::from_rotation_z(k as f64 * bend);
                key.center = turn * rest_keys[k].center;
                key.rotation =
                    turn * DQuat::from_rotation_y(0.1 * k as f64 * frame as f64 / FRAMES as f64 * TAU) * upright;
            }
            rig.pose_into(&[&keys[..]], pose)?;
            deformer.set_pose(i as u32, pose.sweeps())?;
        }
        let mut encoder = device.create_command_encoder(&Default::default());
        deformer.encode(&mut encoder);
        app.draw(&mut encoder, &deformer);
        queue.submit([encoder.finish()]);
    }

    // 7. Every instance against the f64 reference path (bind and Eq. 2 in f64 on the CPU).
    let rest: Vec<DVec3> = positions.iter().map(|&p| DVec3::from_array(p.map(f64::from))).collect();
    let mut worst = 0.0f64;
    for (i, pose) in poses.iter().enumerate() {
        let expected = rig.deform_reference(&owners, &rest, pose.sweeps());
        let gpu = deformer.read_instance_positions(i as u32)?;
        for (v, e) in expected.iter().enumerate() {
            let p = DVec3::new(gpu[3 * v] as f64, gpu[3 * v + 1] as f64, gpu[3 * v + 2] as f64);
            worst = worst.max((p - *e).length());
        }
    }
    println!("{INSTANCES} instances x {} vertices: worst |GPU - f64| = {worst:.2e} mesh units", rest.len());
    // Each instance's bounds, computed on the GPU for culling: min.xyz, 0, max.xyz, 0.
    for (i, b) in deformer.read_bounds()?.ok_or("the deformer keeps bounds")?.iter().enumerate() {
        println!(
            "instance {i}: bounds [{:.3}, {:.3}, {:.3}] to [{:.3}, {:.3}, {:.3}]",
            b[0], b[1], b[2], b[4], b[5], b[6]
        );
    }
    if worst > 1e-4 {
        return Err(format!("the GPU left the f64 reference by {worst}").into());
    }
    let folder: std::path::PathBuf =
        std::env::args_os().nth(1).map(Into::into).unwrap_or_else(|| std::env::temp_dir().join("sweepffd-embed"));
    std::fs::create_dir_all(&folder)?;
    let path = folder.join("embed.png");
    app.save(&device, &queue, &path)?;
    println!("wrote {}", path.display());
    Ok(())
}

#[path = "embed/app.rs"]
mod app;
