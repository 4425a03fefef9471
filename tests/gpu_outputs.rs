//! What the deformer hands the application besides positions: per-instance bounds computed on
//! the GPU, equal to the CPU min and max of the read-back positions exactly.

mod common;

use sweepffd::gpu::{BindingSource, DeformerDescriptor, GpuDeformer};
use sweepffd::synthetic::{BendTwistTaper, Tube, attached_tube_rig};

#[test]
fn per_instance_bounds_equal_the_cpu_extremes_of_the_read_back_positions_exactly() {
    let Some(context) = common::gpu() else { return };
    let tube = Tube::with_vertex_count(5_000, 4.0, 0.5);
    let (mesh, rig) = (tube.mesh(), attached_tube_rig(&tube, 8, 16, 0.6));
    let owners = rig.owners(&mesh, "tube").unwrap();
    let bands = rig.band_weights(&mesh, &owners);
    let positions = sweepffd::gpu::rest_positions(&mesh.positions);
    let n = 30;
    let descriptor =
        DeformerDescriptor::new(rig.rest(), &positions, BindingSource::Bind { owners: &owners, bands: &bands })
            .with_instances(n)
            .with_bounds()
            .with_previous_positions();
    let mut deformer = GpuDeformer::new(context, &descriptor).unwrap();
    for frame in 0..2 {
        for i in 0..n {
            let f = (i + frame * n) as f64 / (2 * n) as f64;
            let keys = BendTwistTaper { bend: 3.0 * f - 1.5, twist: 2.0 * f, taper: 0.4 + 1.2 * f }.keys(&rig);
            deformer.set_pose(i, &rig.pose(&keys).unwrap()).unwrap();
        }
        let mut encoder = context.device.create_command_encoder(&Default::default());
        deformer.encode(&mut encoder);
        context.queue.submit([encoder.finish()]);
        let bounds = deformer.read_bounds().unwrap().expect("asked for bounds");
        assert_eq!(bounds.len(), n as usize);
        for i in 0..n {
            let p = deformer.read_instance_positions(i).unwrap();
            let mut expected = [
                f32::INFINITY,
                f32::INFINITY,
                f32::INFINITY,
                0.0,
                f32::NEG_INFINITY,
                f32::NEG_INFINITY,
                f32::NEG_INFINITY,
                0.0,
            ];
            for v in p.chunks_exact(3) {
                for c in 0..3 {
                    expected[c] = expected[c].min(v[c]);
                    expected[4 + c] = expected[4 + c].max(v[c]);
                }
            }
            assert_eq!(bounds[i as usize], expected, "frame {frame}, instance {i}");
        }
        assert_ne!(bounds[0], bounds[n as usize - 1], "frame {frame}: the instances' bounds differ");
    }
}
