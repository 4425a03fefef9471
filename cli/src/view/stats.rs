//! Frame timings: the panel shows recent medians; a scripted session reports medians over the
//! frames of its drags as JSON.

use serde::Serialize;

/// Milliseconds one frame spent in each stage.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct FrameTimes {
    /// From the start of the previous frame to the start of this one.
    pub frame: f64,
    /// CPU work on the rig: the edit with its hierarchy and volume rule, the sweep overlay,
    /// the coefficient upload.
    pub edit: f64,
    /// GPU deform and normals passes, waited for (0 when the pose did not change).
    pub deform: f64,
    /// Drawing the mesh, the sweeps and the panel, and presenting, waited for.
    pub render: f64,
}

/// Timings kept over a session.
#[derive(Clone, Debug, Default)]
pub struct Stats {
    recent: Vec<FrameTimes>,
    /// Frames in which a scripted drag moved the pose.
    pub dragging: Vec<FrameTimes>,
    /// Every frame.
    pub frames: usize,
}

/// Frames the panel's medians are taken over.
const RECENT: usize = 60;

impl Stats {
    /// Records a frame; `dragging` marks frames of a scripted drag that deformed the mesh.
    pub fn record(&mut self, times: FrameTimes, dragging: bool) {
        if self.recent.len() == RECENT {
            self.recent.remove(0);
        }
        self.recent.push(times);
        self.frames += 1;
        if dragging {
            self.dragging.push(times);
        }
    }

    /// Medians of the last frames; edit and deform over those of them that changed the pose.
    pub fn recent_medians(&self) -> FrameTimes {
        let changed: Vec<FrameTimes> = self.recent.iter().filter(|t| t.deform > 0.0).copied().collect();
        let (all, changed) = (medians(&self.recent), medians(&changed));
        FrameTimes { edit: changed.edit, deform: changed.deform, ..all }
    }
}

/// Each stage's median over `frames` (zeros when there is none).
pub fn medians(frames: &[FrameTimes]) -> FrameTimes {
    let median = |pick: fn(&FrameTimes) -> f64| {
        let mut values: Vec<f64> = frames.iter().map(pick).collect();
        if values.is_empty() { 0.0 } else { sweepffd::bench::median(&mut values) }
    };
    FrameTimes {
        frame: median(|t| t.frame),
        edit: median(|t| t.edit),
        deform: median(|t| t.deform),
        render: median(|t| t.render),
    }
}

/// What a scripted session reports.
#[derive(Clone, Debug, Serialize)]
pub struct Report {
    /// The GPU adapter and its backend.
    pub adapter: String,
    /// Mesh vertices and triangles.
    pub vertices: usize,
    /// See `vertices`.
    pub triangles: usize,
    /// Window size in pixels.
    pub window: [u32; 2],
    /// Frames drawn in all.
    pub frames: usize,
    /// Frames of scripted drags that deformed the mesh.
    pub drag_frames: usize,
    /// Medians over those frames, milliseconds.
    pub drag_median_ms: FrameTimes,
    /// Screenshots written.
    pub screenshots: Vec<String>,
    /// Errors met while playing (failed saves and loads, failed fits).
    pub errors: Vec<String>,
    /// Pointer moves whose edit failed (e.g. did not converge), keeping the previous one.
    pub edits_not_applied: usize,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn medians_of_odd_and_even_counts() {
        let times = |v: f64| FrameTimes { frame: v, edit: 2.0 * v, deform: v % 2.0, render: v };
        assert_eq!(medians(&[times(3.0), times(1.0), times(2.0)]).edit, 4.0);
        assert_eq!(medians(&[times(4.0), times(1.0), times(2.0), times(3.0)]).frame, 2.5);
        assert_eq!(medians(&[]).render, 0.0);
        let mut stats = Stats::default();
        for i in 0..100 {
            stats.record(times(i as f64), i % 2 == 0);
        }
        assert_eq!(stats.frames, 100);
        assert_eq!(stats.dragging.len(), 50);
        let recent = stats.recent_medians();
        assert_eq!(recent.frame, 69.5, "median of the last 60 frames, 40..=99");
        assert_eq!(recent.edit, 140.0, "median over the odd frames (deform > 0) of 40..=99");
    }
}
