//! The deform pass as the adapter did not choose it, measured in the same rounds as the choice:
//! the other cell records ([`CellRecords`]) in the chosen order, and each other order
//! ([`DeformOrder`]) with the chosen records, so that one bench run on a new adapter says
//! whether its choices hold there.

use serde::Serialize;

use super::passes::time;
use super::{BenchScene, GpuTimer};
use crate::coeffs::SweepCoefficients;
use crate::gpu::{
    BindingSource, CellRecords, DeformOrder, DeformVariant, DeformerDescriptor, GpuContext, GpuDeformer, GpuError,
    rest_positions,
};

/// One alternative to the deformer's choices.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct AlternativeReport {
    /// Its deform order (`vertices`, `staged vertices` or `cell groups`).
    pub deform_order: &'static str,
    /// Its cell records (`uniform` or `storage`).
    pub cell_records: &'static str,
    /// Vertices a second of its deform pass.
    pub deform_verts_per_s: f64,
    /// Its deform time over the chosen deformer's, same round (above 1: the choice is faster).
    pub over_chosen: f64,
}

/// One round's alternative deform times and the chosen deformer's, seconds.
pub(super) type RoundTimes = (Vec<f64>, f64);

/// Posed deformers of the scene (no triangles, no bands) for each alternative.
pub(super) struct Alternatives {
    deformers: Vec<GpuDeformer>,
}

impl Alternatives {
    /// The alternatives to `chosen`'s order and records on `scene`.
    pub(super) fn new(
        context: &GpuContext,
        scene: &BenchScene,
        chosen: &GpuDeformer,
    ) -> Result<Alternatives, GpuError> {
        let (order, records) = (chosen.deform_order(), chosen.cell_records());
        // A rig too large for a uniform buffer keeps storage records: no other records to time.
        let cells = SweepCoefficients::new(scene.rig.rest()).cells.len();
        let limits = context.device.limits();
        let mut choices = Vec::new();
        if CellRecords::Uniform.variant(cells, &limits, context.info.device_type) == DeformVariant::Uniform {
            choices.push((order, CellRecords::from(records.other())));
        }
        for other in [DeformOrder::Vertices, DeformOrder::StagedVertices, DeformOrder::CellGroups] {
            if other != order {
                choices.push((other, CellRecords::from(records)));
            }
        }
        let positions = rest_positions(&scene.mesh.positions);
        let mut deformers = Vec::with_capacity(choices.len());
        for (order, records) in choices {
            let source = BindingSource::bind(&scene.owners);
            let descriptor = DeformerDescriptor::new(scene.rig.rest(), &positions, source)
                .with_deform_order(order)
                .with_cell_records(records);
            let mut deformer = GpuDeformer::new(context, &descriptor)?;
            deformer.set_pose(0, &scene.posed)?;
            deformers.push(deformer);
        }
        Ok(Alternatives { deformers })
    }

    /// Seconds of each alternative's deform pass.
    pub(super) fn time(&mut self, context: &GpuContext, timer: Option<&GpuTimer>) -> Result<Vec<f64>, GpuError> {
        self.deformers
            .iter_mut()
            .map(|deformer| time(context, timer, |encoder, stamps| deformer.encode_deform_pass(encoder, stamps.pass())))
            .collect()
    }

    /// The reports, from each round's alternative times and chosen deform time, over `n`
    /// vertices.
    pub(super) fn reports(&self, n: f64, rounds: &[RoundTimes]) -> Vec<AlternativeReport> {
        let median = |f: &dyn Fn(&RoundTimes) -> f64| super::median(&mut rounds.iter().map(f).collect::<Vec<_>>());
        self.deformers
            .iter()
            .enumerate()
            .map(|(i, deformer)| AlternativeReport {
                deform_order: deformer.deform_order().name(),
                cell_records: deformer.cell_records().name(),
                deform_verts_per_s: n / median(&|r| r.0[i]),
                over_chosen: median(&|r| r.0[i] / r.1),
            })
            .collect()
    }
}
