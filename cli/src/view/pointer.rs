//! Pointer handling: what a press grabs (a key ring, a bound mesh point, a part to fit, or the
//! camera), the edit each move makes, and committing it on release.

use std::f64::consts::TAU;
use std::time::Instant;

use glam::{Vec2, Vec3};

use super::app::App;
use super::gesture::Gesture;
use super::input::Button;
use super::panel::SweepDisplay;
use super::part::{PartRule, select_part};
use super::picking::{Hit, RingOnScreen, pick_ring, pick_triangle};
use crate::render::SweepStyle;
use sweepffd::bind::{SweepBinder, UNOWNED};

/// How near (pixels) the pointer must come to a ring to grab it.
const RING_REACH: f32 = 8.0;
/// Points per ring when picking.
const RING_POINTS: usize = 48;

impl App {
    pub(super) fn press(&mut self, button: Button) {
        let at = self.pointer;
        self.gesture = Some(match button {
            Button::Right => Gesture::Pan { last: at },
            Button::Middle => Gesture::Orbit { last: at },
            Button::Left => self.grab(at),
        });
    }

    /// What a left press at `at` grabs.
    fn grab(&mut self, at: Vec2) -> Gesture {
        if let Some((sweep, key)) = self.ring_under(at) {
            self.selected_key = Some((sweep, key));
            self.overlay_changed = true; // the ring in the selection colour
            if let (Some(rig), Some(session)) = (&self.model.rig, &self.model.session) {
                let center = session.keys()[sweep][key].center.as_vec3();
                let center_pixel = self.camera.project(center, self.size()).unwrap_or(at);
                return Gesture::Key {
                    sweep: rig.sweeps()[sweep].name.clone(),
                    key,
                    tool: self.panel.tool,
                    start: at,
                    center,
                    center_pixel,
                };
            }
        }
        let Some(hit) = self.mesh_under(at) else { return Gesture::Orbit { last: at } };
        let positions = self.picked_positions.as_deref().expect("read by mesh_under");
        let vertex = hit.nearest_corner(positions);
        let owner = self.model.owners[vertex as usize];
        if let (true, Some(rig), Some(Ok(posed))) = (owner != UNOWNED, &self.model.rig, self.model.posed()) {
            let sweep = owner as usize;
            let binding = SweepBinder::new(&rig.rest()[sweep]).bind(self.model.mesh.positions[vertex as usize]);
            let anchor = posed[sweep].point(binding.theta, binding.t, binding.d, binding.h).as_vec3();
            let name = rig.sweeps()[sweep].name.clone();
            if self.model.settings.bend {
                let (t, span) = (binding.t, self.model.settings.bend_span);
                let (pivot, frame) = (posed[sweep].center(t).as_vec3(), posed[sweep].orientation(t));
                let end = posed[sweep].center(1.0).as_vec3();
                self.overlay_changed = true; // the span's rings
                return Gesture::Bend { sweep: name, t, span, start: at, end, pivot, frame };
            }
            let below = posed[sweep].locate(binding.t).segment;
            let pivot = self.model.session.as_ref().map_or(anchor, |s| s.keys()[sweep][below].center.as_vec3());
            return Gesture::Point { sweep: name, binding, anchor, below, pivot };
        }
        self.select_part(vertex, hit.triangle);
        Gesture::Orbit { last: at }
    }

    pub(super) fn pointer_moved(&mut self, to: Vec2) {
        let delta = to - self.pointer;
        self.pointer = to;
        let size = self.size();
        match &mut self.gesture {
            None => {}
            Some(Gesture::Orbit { last }) => {
                self.camera.rotate(to - *last);
                *last = to;
            }
            Some(Gesture::Pan { last }) => {
                self.camera.pan(to - *last, size.y);
                *last = to;
            }
            Some(gesture) => {
                if delta == Vec2::ZERO {
                    return;
                }
                let Some(edit) = gesture.edit(to, &self.camera, size, &self.model.settings) else { return };
                let started = Instant::now();
                match self.model.preview(edit) {
                    Ok(_) => {
                        self.pose_changed = true;
                        self.panel.status.clear();
                    }
                    Err(error) => {
                        self.panel.status = format!("edit not applied: {error}");
                        self.edits_not_applied += 1;
                    }
                }
                self.pending_edit_ms += started.elapsed().as_secs_f64() * 1e3;
            }
        }
    }

    pub(super) fn release(&mut self, _button: Button) {
        if matches!(self.gesture, Some(Gesture::Bend { .. })) {
            self.overlay_changed = true; // the span's rings go
        }
        self.gesture = None;
        if let Some(session) = &mut self.model.session
            && session.commit()
        {
            self.mesh_volume_stale = true;
        }
    }

    /// The key ring drawn nearest the pointer, if the sweeps are shown and one is near.
    fn ring_under(&self, at: Vec2) -> Option<(usize, usize)> {
        if self.panel.sweeps == SweepDisplay::Hidden {
            return None;
        }
        let posed = self.model.posed()?.ok()?;
        let style = SweepStyle::for_diagonal(self.model.mesh.diagonal());
        let size = self.size();
        let rings: Vec<RingOnScreen> = posed
            .iter()
            .enumerate()
            .flat_map(|(s, sweep)| sweep.knots().iter().enumerate().map(move |(k, &u)| (s, k, u, sweep)))
            .map(|(sweep_index, key, u, sweep)| RingOnScreen {
                sweep: sweep_index,
                key,
                pixels: (0..RING_POINTS)
                    .filter_map(|j| {
                        let theta = TAU * j as f64 / RING_POINTS as f64;
                        let point = sweep.point(theta, u, style.offset + style.ring_radius, 0.0).as_vec3();
                        self.camera.project(point, size)
                    })
                    .collect(),
            })
            .collect();
        pick_ring(&rings, at, RING_REACH)
    }

    /// The mesh triangle under the pointer, reading the drawn positions back if the pose changed
    /// since the last pick.
    fn mesh_under(&mut self, at: Vec2) -> Option<Hit> {
        if self.picked_positions.is_none() {
            let running = self.running.as_ref()?;
            match running.mesh.current_positions(&self.model.mesh) {
                Ok(positions) => self.picked_positions = Some(positions),
                Err(error) => {
                    self.panel.status = error.to_string();
                    return None;
                }
            }
        }
        let (origin, direction) = self.camera.ray(at, self.size());
        let positions: &[Vec3] = self.picked_positions.as_deref()?;
        pick_triangle(positions, &self.model.triangles, origin, direction)
    }

    /// Selects the part around `vertex` for fitting and shows it.
    fn select_part(&mut self, vertex: u32, triangle: usize) {
        let face = self.face_of_triangle(triangle);
        let rule = if self.panel.by_group && !self.model.mesh.groups.is_empty() {
            PartRule::Group
        } else {
            PartRule::Radius(self.panel.radius)
        };
        self.part = select_part(&self.model.mesh, vertex, face, rule, &self.model.taken());
        self.show_part();
    }

    /// The face a fan triangle comes from.
    fn face_of_triangle(&self, triangle: usize) -> usize {
        let offsets = &self.model.mesh.faces.offsets;
        // Face f has offsets[f+1] − offsets[f] − 2 triangles; count them up.
        let mut seen = 0;
        for f in 0..offsets.len().saturating_sub(1) {
            let count = (offsets[f + 1] - offsets[f]).saturating_sub(2) as usize;
            if triangle < seen + count {
                return f;
            }
            seen += count;
        }
        0
    }

    /// Uploads the selected part's triangles for drawing.
    pub(super) fn show_part(&mut self) {
        let Some(running) = &mut self.running else { return };
        let triangles: Vec<u32> = match &self.part {
            Some(part) => {
                let mut inside = vec![false; self.model.mesh.positions.len()];
                for &v in &part.vertices {
                    inside[v as usize] = true;
                }
                self.model
                    .triangles
                    .iter()
                    .filter(|t| t.iter().all(|&v| inside[v as usize]))
                    .flatten()
                    .copied()
                    .collect()
            }
            None => Vec::new(),
        };
        running.mesh.set_selection(&running.gpu.context, &triangles);
    }
}
