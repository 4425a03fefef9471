//! The window's life: created on `resumed`, fed window events, redrawn on request (every frame
//! while a script plays), closed on request or at the script's end.

use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use glam::{Vec2, Vec3};
use winit::application::ApplicationHandler;
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::keyboard::{Key, NamedKey};
use winit::window::{Window, WindowId};

use super::draw::{Drawing, MeshDraw, Overlay};
use super::gesture::Gesture;
use super::input::{Button, Command, Input};
use super::model::Model;
use super::orbit::Orbit;
use super::panel::{PANEL_WIDTH, PanelState, SweepDisplay};
use super::part::Part;
use super::script::Player;
use super::stats::{Report, Stats, medians};
use super::surface::WindowGpu;
use super::{ViewError, ViewOptions};

/// The window and everything drawn into it.
pub(super) struct Running {
    pub window: Arc<Window>,
    pub gpu: WindowGpu,
    pub drawing: Drawing,
    pub mesh: MeshDraw,
    pub overlay: Overlay,
    pub egui: EguiLayer,
}

/// egui's context, its winit input state and its wgpu renderer.
pub(super) struct EguiLayer {
    pub context: egui::Context,
    pub state: egui_winit::State,
    pub renderer: egui_wgpu::Renderer,
}

/// The viewer.
pub(super) struct App {
    pub options: ViewOptions,
    pub instance: wgpu::Instance,
    pub model: Model,
    pub camera: Orbit,
    pub running: Option<Running>,
    pub player: Option<Player>,
    pub stats: Stats,
    pub panel: PanelState,
    pub pointer: Vec2,
    pub modifiers: winit::keyboard::ModifiersState,
    pub gesture: Option<Gesture>,
    pub selected_key: Option<(usize, usize)>,
    pub part: Option<Part>,
    /// The pose changed: set it on the deformer, deform, and rebuild the sweeps' overlay.
    pub pose_changed: bool,
    /// Only the overlay changed (a key selected, the sweeps' display switched).
    pub overlay_changed: bool,
    /// Positions read back for picking, until the pose changes.
    pub picked_positions: Option<Vec<Vec3>>,
    /// Milliseconds of rig edits since the last frame.
    pub pending_edit_ms: f64,
    pub last_frame: Instant,
    /// Volumes at rest (Eq. 1 per sweep, the mesh's enclosed one) and the mesh's now.
    pub rest_volumes: Vec<f64>,
    pub rest_mesh_volume: f64,
    pub mesh_volume: f64,
    /// A committed change awaits its mesh volume (measured after the frame's deform).
    pub mesh_volume_stale: bool,
    /// A screenshot the script asked for, taken with the next frame drawn.
    pub pending_screenshot: Option<PathBuf>,
    pub screenshots: Vec<String>,
    pub errors: Vec<String>,
    /// Pointer moves whose edit failed (the previous one stayed).
    pub edits_not_applied: usize,
    /// Each sweep's name, volume now and at rest, measured when the pose changes.
    pub sweep_volumes: Vec<(String, f64, f64)>,
    /// Where the pose folds its sweeps, drawn in red and listed in the panel.
    pub fold_warnings: Vec<sweepffd::edit::PoseWarning>,
    pub fatal: Option<ViewError>,
}

impl App {
    /// The viewer of `model`, playing `player` if given; the window opens on `resumed`.
    pub fn new(options: ViewOptions, model: Model, player: Option<Player>, event_loop: &EventLoop<()>) -> App {
        let mut descriptor =
            wgpu::InstanceDescriptor::new_with_display_handle(Box::new(event_loop.owned_display_handle()));
        descriptor.backends = wgpu::Backends::from_env().unwrap_or(wgpu::Backends::PRIMARY);
        let instance = wgpu::Instance::new(descriptor);
        let (min, max) = model.mesh.bounds();
        let aspect = (options.size.0 as f32 - PANEL_WIDTH).max(1.0) / options.size.1.max(1) as f32;
        let camera = Orbit::framing(min.as_vec3(), max.as_vec3(), aspect);
        let stem = options.mesh.file_stem().map_or("mesh".into(), |s| s.to_string_lossy().into_owned());
        let panel = PanelState {
            sweeps: SweepDisplay::default(),
            tool: Default::default(),
            by_group: !model.mesh.groups.is_empty(),
            radius: 0.15,
            pose_path: options.pose_out.display().to_string(),
            edits_path: format!("{stem}-edits.json"),
            rig_path: format!("{stem}-rig.json"),
            status: String::new(),
            paint_weights: false,
        };
        let mut app = App {
            options,
            instance,
            model,
            camera,
            running: None,
            player,
            stats: Stats::default(),
            panel,
            pointer: Vec2::ZERO,
            modifiers: Default::default(),
            gesture: None,
            selected_key: None,
            part: None,
            pose_changed: true,
            overlay_changed: true,
            picked_positions: None,
            pending_edit_ms: 0.0,
            last_frame: Instant::now(),
            rest_volumes: Vec::new(),
            rest_mesh_volume: 0.0,
            mesh_volume: 0.0,
            mesh_volume_stale: false,
            pending_screenshot: None,
            screenshots: Vec::new(),
            errors: Vec::new(),
            edits_not_applied: 0,
            sweep_volumes: Vec::new(),
            fold_warnings: Vec::new(),
            fatal: None,
        };
        app.measure_rest_volumes();
        app
    }

    /// The outcome once the event loop has ended.
    pub fn finish(self) -> Result<Option<Report>, ViewError> {
        if let Some(error) = self.fatal {
            return Err(error);
        }
        let Some(player) = &self.player else { return Ok(None) };
        if !player.finished() {
            return Err(ViewError::Script("the window closed before the script ended".into()));
        }
        Ok(Some(Report {
            adapter: self.adapter(),
            vertices: self.model.mesh.positions.len(),
            triangles: self.model.triangles.len(),
            window: [self.options.size.0, self.options.size.1],
            frames: self.stats.frames,
            drag_frames: self.stats.dragging.len(),
            drag_median_ms: medians(&self.stats.dragging),
            screenshots: self.screenshots,
            errors: self.errors,
            edits_not_applied: self.edits_not_applied,
        }))
    }

    /// The adapter and its backend, as the panel shows them.
    pub fn adapter(&self) -> String {
        self.running.as_ref().map_or(String::new(), |r| {
            let info = &r.gpu.context.info;
            format!("{} ({:?})", info.name, info.backend)
        })
    }

    /// The size in pixels of the scene's part of the window, left of the panel (its top
    /// left is the window's).
    pub fn size(&self) -> Vec2 {
        self.running.as_ref().map_or(Vec2::ONE, |r| {
            let (w, h) = r.gpu.size();
            let panel = PANEL_WIDTH * r.window.scale_factor() as f32;
            Vec2::new((w as f32 - panel).max(1.0), h.max(1) as f32)
        })
    }

    fn open(&mut self, event_loop: &ActiveEventLoop) -> Result<(), ViewError> {
        let (width, height) = self.options.size;
        let attributes = Window::default_attributes()
            .with_title(format!("sweepffd — {}", self.options.mesh.display()))
            .with_inner_size(winit::dpi::PhysicalSize::new(width, height))
            .with_resizable(self.player.is_none());
        let window = Arc::new(event_loop.create_window(attributes).map_err(|e| ViewError::Window(e.to_string()))?);
        let gpu = WindowGpu::new(&self.instance, Arc::clone(&window), self.player.is_none())?;
        let drawing = Drawing::new(&gpu.context.device, gpu.format);
        let model = &self.model;
        let rig = model.rig.as_ref().map(|r| (r, &model.owners[..], &model.bands[..]));
        let mesh = MeshDraw::new(&gpu.context, &model.mesh, rig)?;
        let context = egui::Context::default();
        let max_texture = gpu.context.device.limits().max_texture_dimension_2d as usize;
        let state = egui_winit::State::new(
            context.clone(),
            egui::ViewportId::ROOT,
            &window,
            Some(window.scale_factor() as f32),
            None,
            Some(max_texture),
        );
        let renderer = egui_wgpu::Renderer::new(&gpu.context.device, gpu.format, egui_wgpu::RendererOptions::default());
        self.running = Some(Running {
            window,
            gpu,
            drawing,
            mesh,
            overlay: Overlay::default(),
            egui: EguiLayer { context, state, renderer },
        });
        self.pose_changed = true;
        Ok(())
    }

    /// Stops the event loop with a fatal error.
    pub fn fail(&mut self, event_loop: &ActiveEventLoop, error: ViewError) {
        self.fatal.get_or_insert(error);
        event_loop.exit();
    }

    /// Feeds one input event to the handlers.
    pub fn input(&mut self, input: Input) {
        match input {
            Input::Pointer(to) => self.pointer_moved(to),
            Input::Button { button, pressed: true } => self.press(button),
            Input::Button { button, pressed: false } => self.release(button),
            Input::Scroll(lines) => self.camera.zoom(lines),
            Input::Command(command) => self.command(command),
        }
    }
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.running.is_some() {
            return;
        }
        if let Err(error) = self.open(event_loop) {
            self.fail(event_loop, error);
            return;
        }
        if let Some(running) = &self.running {
            running.window.request_redraw();
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        let Some(running) = &mut self.running else { return };
        let consumed = running.egui.state.on_window_event(&running.window, &event);
        if consumed.repaint {
            running.window.request_redraw();
        }
        match event {
            WindowEvent::CloseRequested | WindowEvent::Destroyed => return event_loop.exit(),
            WindowEvent::Resized(size) => {
                running.gpu.resize(size.width, size.height);
                return running.window.request_redraw();
            }
            WindowEvent::RedrawRequested => return self.redraw(event_loop),
            WindowEvent::ModifiersChanged(modifiers) => {
                self.modifiers = modifiers.state();
                return;
            }
            // A script plays alone: the hand's input goes to the panel only.
            _ if self.player.is_some() => return,
            // A drag that began in the scene follows the pointer over the panel and ends
            // wherever the button is released.
            WindowEvent::CursorMoved { .. } | WindowEvent::MouseInput { state: ElementState::Released, .. }
                if self.gesture.is_some() => {}
            _ if consumed.consumed => return,
            _ => {}
        }
        match event {
            WindowEvent::CursorMoved { position, .. } => {
                self.input(Input::Pointer(Vec2::new(position.x as f32, position.y as f32)));
                self.request_redraw();
            }
            WindowEvent::MouseInput { state, button, .. } => {
                let button = match button {
                    MouseButton::Left => Button::Left,
                    MouseButton::Right => Button::Right,
                    MouseButton::Middle => Button::Middle,
                    _ => return,
                };
                self.input(Input::Button { button, pressed: state == ElementState::Pressed });
                self.request_redraw();
            }
            WindowEvent::MouseWheel { delta, .. } => {
                let lines = match delta {
                    MouseScrollDelta::LineDelta(_, y) => y,
                    MouseScrollDelta::PixelDelta(p) => p.y as f32 / 40.0,
                };
                self.input(Input::Scroll(lines));
                self.request_redraw();
            }
            WindowEvent::KeyboardInput { event, .. } if event.state == ElementState::Pressed && !event.repeat => {
                let name = match &event.logical_key {
                    Key::Character(text) => text.to_string(),
                    Key::Named(NamedKey::Escape) => "escape".into(),
                    Key::Named(NamedKey::Home) => "home".into(),
                    _ => return,
                };
                if let Some(command) = Command::for_key(&name, self.modifiers.control_key(), self.modifiers.shift_key())
                {
                    self.input(Input::Command(command));
                    self.request_redraw();
                }
            }
            _ => {}
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        if self.player.is_some() {
            event_loop.set_control_flow(ControlFlow::Poll);
            self.request_redraw();
        } else {
            event_loop.set_control_flow(ControlFlow::Wait);
        }
    }
}

impl App {
    fn request_redraw(&self) {
        if let Some(running) = &self.running {
            running.window.request_redraw();
        }
    }
}
