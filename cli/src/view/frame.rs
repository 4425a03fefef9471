//! One frame: the script's actions, the new pose on the deformer (coefficients only), the
//! deform and normals passes, then the scene and the panel drawn and presented. With the
//! stages waited for one by one, the frame's time splits into edit, deform and render.

use std::time::Instant;

use winit::event_loop::ActiveEventLoop;

use super::ViewError;
use super::app::App;
use super::draw::{BEND_SPAN_RING, FOLD_RING, FOLD_RINGS, SELECTED_RING};
use super::gesture::Gesture;
use super::panel::{PanelAction, PanelFacts, SweepDisplay, panel};
use super::script::Action;
use super::stats::FrameTimes;
use super::surface::Capture;
use super::weights::weight_colours;
use crate::render::{RING, Scene, SweepStyle, ViewUniform, add_key_ring, add_sweep_surface};
use sweepffd::gpu::wait;

impl App {
    pub(super) fn redraw(&mut self, event_loop: &ActiveEventLoop) {
        let started = Instant::now();
        let frame_ms = started.duration_since(self.last_frame).as_secs_f64() * 1e3;
        self.last_frame = started;
        let mut dragging = false;
        // A screenshot waits for a frame that is drawn before the script goes on.
        if let Some(player) = self.player.as_mut().filter(|_| self.pending_screenshot.is_none()) {
            let actions = player.frame(started);
            dragging = player.dragging();
            for action in actions {
                match action {
                    Action::Input(input) => self.input(input),
                    Action::Screenshot(path) => self.pending_screenshot = Some(path),
                    Action::SavePose(path) => self.save_pose(&path),
                    Action::SaveEdits(path) => self.save_edits(&path),
                    Action::LoadPose(path) => self.load_pose(&path),
                    Action::SaveRig(path) => self.save_rig(&path),
                    Action::Falloff { sweep, width } => self.set_falloff_of(&sweep, width),
                }
            }
        }
        let edit_started = Instant::now();
        let deform = self.pose_changed;
        if let Err(error) = self.update_pose() {
            self.fail(event_loop, error);
            return;
        }
        let edit_ms = self.pending_edit_ms + edit_started.elapsed().as_secs_f64() * 1e3;
        self.pending_edit_ms = 0.0;
        let deform_ms = match self.deform() {
            Ok(ms) => ms,
            Err(error) => return self.fail(event_loop, error),
        };
        self.measure_mesh_volume();
        let render_ms = match self.render() {
            Ok(ms) => ms,
            Err(error) => return self.fail(event_loop, error),
        };
        let times = FrameTimes { frame: frame_ms, edit: edit_ms, deform: deform_ms, render: render_ms };
        self.stats.record(times, dragging && deform);
        if self.player.as_ref().is_some_and(|p| p.finished()) && self.pending_screenshot.is_none() {
            event_loop.exit();
        }
    }

    /// Sets a changed pose on the deformer and rebuilds the sweeps' overlay.
    fn update_pose(&mut self) -> Result<(), ViewError> {
        if !(self.pose_changed || std::mem::take(&mut self.overlay_changed)) {
            return Ok(());
        }
        let Some(running) = &mut self.running else { return Ok(()) };
        let posed = match self.model.posed() {
            Some(posed) => posed?,
            None => Vec::new(),
        };
        if let Some(deformer) = running.mesh.deformer().filter(|_| self.pose_changed) {
            deformer.set_pose(0, &posed).map_err(|e| ViewError::Gpu(e.to_string()))?;
        }
        if self.pose_changed {
            self.fold_warnings = match &self.model.rig {
                Some(rig) => sweepffd::edit::pose_warnings(rig, &posed),
                None => Vec::new(),
            };
        }
        let mut scene = Scene::new();
        if self.panel.sweeps != SweepDisplay::Hidden {
            let style = SweepStyle::for_diagonal(self.model.mesh.diagonal());
            for (s, sweep) in posed.iter().enumerate() {
                if self.panel.sweeps == SweepDisplay::RingsAndSurface {
                    add_sweep_surface(&mut scene, sweep, &style);
                }
                for (k, &u) in sweep.knots().iter().enumerate() {
                    let colour = if self.selected_key == Some((s, k)) { SELECTED_RING } else { RING };
                    add_key_ring(&mut scene, sweep, u, &style, colour);
                }
            }
            // A bend drag's span, between two rings.
            if let (Some(Gesture::Bend { sweep, t, span, .. }), Some(rig)) = (&self.gesture, &self.model.rig)
                && let Some(sweep) = rig.sweep_index(sweep).and_then(|s| posed.get(s))
            {
                for end in [t - 0.5 * span, t + 0.5 * span] {
                    add_key_ring(&mut scene, sweep, end.clamp(0.0, 1.0), &style, BEND_SPAN_RING);
                }
            }
            // Each stretch that folds, in red rings across it (the stretches of one sweep that
            // overlap, of its several kinds of fold, drawn once).
            for (sweep, [t0, t1]) in fold_stretches(&self.fold_warnings, self.model.rig.as_ref()) {
                for i in 0..FOLD_RINGS {
                    let t = t0 + (t1 - t0) * i as f64 / (FOLD_RINGS - 1) as f64;
                    add_key_ring(&mut scene, &posed[sweep], t, &style, FOLD_RING);
                }
            }
        }
        running.overlay.upload(&running.gpu.context, &scene);
        if self.pose_changed {
            self.picked_positions = None;
        }
        self.sweep_volumes = match &self.model.rig {
            Some(rig) => rig
                .sweeps()
                .iter()
                .zip(&posed)
                .zip(&self.rest_volumes)
                .map(|((s, sweep), &rest)| (s.name.clone(), sweep.volume(), rest))
                .collect(),
            None => Vec::new(),
        };
        Ok(())
    }

    /// Records, submits and waits for the deform and normals passes if the pose changed;
    /// returns their milliseconds.
    fn deform(&mut self) -> Result<f64, ViewError> {
        if !std::mem::take(&mut self.pose_changed) {
            return Ok(0.0);
        }
        let Some(running) = &mut self.running else { return Ok(0.0) };
        let context = running.gpu.context.clone();
        let Some(deformer) = running.mesh.deformer() else { return Ok(0.0) };
        let started = Instant::now();
        let mut encoder =
            context.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("deform") });
        deformer.encode(&mut encoder);
        context.queue.submit([encoder.finish()]);
        wait(&context).map_err(|e| ViewError::Gpu(e.to_string()))?;
        Ok(started.elapsed().as_secs_f64() * 1e3)
    }

    /// Draws the scene and the panel, captures a screenshot if asked, presents and waits;
    /// returns the milliseconds.
    fn render(&mut self) -> Result<f64, ViewError> {
        let started = Instant::now();
        let facts = self.panel_facts();
        let size = self.size();
        let uniform = ViewUniform::of(&self.camera.camera(), size.x / size.y);
        let Some(running) = &mut self.running else { return Ok(0.0) };
        let (owners, bands) = (&self.model.owners, &self.model.bands);
        let context = running.gpu.context.clone();
        running.mesh.show_weights(&context, self.panel.paint_weights, || weight_colours(owners, bands));
        let Some(texture) = running.gpu.acquire() else { return Ok(0.0) };
        let screenshot = self.pending_screenshot.take();
        let target = running.gpu.view_of(&texture);
        let mut encoder =
            context.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("frame") });
        running.drawing.encode(
            &context,
            &mut encoder,
            &uniform,
            size,
            (&running.gpu.colour, &running.gpu.depth, &target),
            &running.mesh,
            &running.overlay,
        );

        // The panel, drawn over the scene.
        let egui = &mut running.egui;
        let input = egui.state.take_egui_input(&running.window);
        let mut actions = Vec::new();
        let (panel_state, settings) = (&mut self.panel, &mut self.model.settings);
        let output = egui.context.run_ui(input, |ui| actions = panel(ui, &facts, panel_state, settings));
        egui.state.handle_platform_output(&running.window, output.platform_output);
        let jobs = egui.context.tessellate(output.shapes, output.pixels_per_point);
        let (width, height) = running.gpu.size();
        let screen =
            egui_wgpu::ScreenDescriptor { size_in_pixels: [width, height], pixels_per_point: output.pixels_per_point };
        for (id, deltas) in &output.textures_delta.set {
            for delta in deltas {
                egui.renderer.update_texture(&context.device, &context.queue, *id, delta);
            }
        }
        let extra = egui.renderer.update_buffers(&context.device, &context.queue, &mut encoder, &jobs, &screen);
        {
            let pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("sweepffd panel"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &target,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations { load: wgpu::LoadOp::Load, store: wgpu::StoreOp::Store },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            egui.renderer.render(&mut pass.forget_lifetime(), &jobs, &screen);
        }
        for id in &output.textures_delta.free {
            egui.renderer.free_texture(id);
        }
        let capture = match &screenshot {
            Some(_) if running.gpu.readable => Some(Capture::record(&mut encoder, &context.device, &texture.texture)),
            _ => None,
        };
        context.queue.submit(extra.into_iter().chain([encoder.finish()]));
        running.window.pre_present_notify();
        context.queue.present(texture);
        wait(&context).map_err(|e| ViewError::Gpu(e.to_string()))?;
        let elapsed = started.elapsed().as_secs_f64() * 1e3;
        if output.viewport_output.values().any(|v| v.repaint_delay.is_zero()) {
            running.window.request_redraw();
        }
        if let Some(path) = &screenshot {
            let outcome = match capture {
                Some(capture) => capture
                    .finish(&context)
                    .and_then(|picture| {
                        crate::render::save_png(&picture, path).map_err(|e| ViewError::Gpu(e.to_string()))
                    })
                    .map(|()| {
                        self.screenshots.push(path.display().to_string());
                        format!("screenshot {}", path.display())
                    })
                    .map_err(|e| e.to_string()),
                None => Err(format!("{}: this window's surface cannot be read back", path.display())),
            };
            self.report(outcome);
        }
        for action in actions {
            match action {
                PanelAction::Command(command) => self.command(command),
                PanelAction::SaveRig => self.save_rig(std::path::Path::new(&self.panel.rig_path.clone())),
                PanelAction::SetFalloff { sweep, width } => self.set_falloff(sweep, width),
            }
        }
        Ok(elapsed)
    }

    /// What the panel shows this frame.
    fn panel_facts(&self) -> PanelFacts {
        let rig = self.model.rig.as_ref();
        PanelFacts {
            adapter: self.adapter(),
            vertices: self.model.mesh.positions.len(),
            triangles: self.model.triangles.len(),
            times: self.stats.recent_medians(),
            sweep_volumes: self.sweep_volumes.clone(),
            folds: self.fold_warnings.iter().map(ToString::to_string).collect(),
            mesh_volume: self.model.closed.then_some((self.mesh_volume, self.rest_mesh_volume)),
            history: self.model.session.as_ref().map_or((0, 0), |s| s.history()),
            has_rig: rig.is_some(),
            has_groups: !self.model.mesh.groups.is_empty(),
            selected_key: self.selected_key.and_then(|(s, k)| Some(format!("{} key {k}", rig?.sweeps()[s].name))),
            part: self.part.as_ref().map(|p| format!("part {:?}: {} vertices", p.name, p.vertices.len())),
            falloffs: rig.map_or(Vec::new(), |rig| {
                let owning = rig.sweeps().iter().enumerate().filter(|(_, s)| s.vertices.is_some());
                owning.map(|(i, s)| (i, s.name.clone(), s.falloff)).collect()
            }),
            diagonal: self.model.diagonal,
        }
    }
}

/// The stretches [t0, t1] of each sweep (by index in `rig`) that `warnings` name, those of one
/// sweep that overlap merged.
fn fold_stretches(
    warnings: &[sweepffd::edit::PoseWarning],
    rig: Option<&sweepffd::rig::Rig>,
) -> Vec<(usize, [f64; 2])> {
    let Some(rig) = rig else { return Vec::new() };
    let mut stretches: Vec<(usize, [f64; 2])> =
        warnings.iter().filter_map(|w| Some((rig.sweep_index(&w.sweep)?, w.fold.t))).collect();
    stretches.sort_by(|a, b| a.0.cmp(&b.0).then(a.1[0].total_cmp(&b.1[0])));
    let mut merged: Vec<(usize, [f64; 2])> = Vec::with_capacity(stretches.len());
    for (sweep, t) in stretches {
        match merged.last_mut() {
            Some((last, range)) if *last == sweep && range[1] >= t[0] => range[1] = range[1].max(t[1]),
            _ => merged.push((sweep, t)),
        }
    }
    merged
}

#[cfg(test)]
mod tests {
    use super::*;
    use sweepffd::edit::PoseWarning;
    use sweepffd::sweep::{Fold, FoldKind};
    use sweepffd::synthetic::{Tube, tube_rig};

    #[test]
    fn overlapping_folds_of_one_sweep_are_one_stretch() {
        let rig = tube_rig(&Tube { rings: 4, around: 4, length: 1.0, radius: 0.1 }, 5, 8);
        let warning = |kind, t| PoseWarning { sweep: "tube".into(), fold: Fold { kind, t, amount: 2.0 } };
        let warnings = [
            warning(FoldKind::SectionsCross, [0.3, 0.5]),
            warning(FoldKind::KeysStepBack, [0.25, 0.5]),
            warning(FoldKind::FrameFlips, [0.25, 0.5]),
            warning(FoldKind::SectionsCross, [0.8, 0.9]),
            PoseWarning {
                sweep: "no such sweep".into(),
                fold: Fold { kind: FoldKind::FrameFlips, t: [0.0, 1.0], amount: 100.0 },
            },
        ];
        assert_eq!(fold_stretches(&warnings, Some(&rig)), vec![(0, [0.25, 0.5]), (0, [0.8, 0.9])]);
        assert_eq!(fold_stretches(&warnings, None), vec![]);
    }
}
