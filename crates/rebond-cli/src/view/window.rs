//! The window and its event loop (winit, with an OpenGL context from glutin through three-d).
//! Each frame either steps in real time and answers the user, or, for `--screenshot`, takes the
//! asked-for steps, draws once, saves the frame and closes.

use std::panic;
use std::path::PathBuf;
use std::time::Duration;

use glam::Vec2;
use three_d::{FrameInput, FrameInputGenerator, SurfaceSettings, WindowedContext};
use winit::dpi::PhysicalSize;
use winit::event::{Event, WindowEvent};
use winit::event_loop::{ControlFlow, EventLoop};
use winit::platform::run_return::EventLoopExtRunReturn;
use winit::window::{Window, WindowBuilder};

use super::render::Renderer;
use super::screenshot::{save_png, ScreenshotReport};
use super::simulation::Simulation;
use super::viewer::Viewer;
use super::ViewError;
use crate::failure::Failure;

/// Size of the interactive window, physical pixels.
const WINDOW_SIZE: (u32, u32) = (1280, 720);
/// Size of a screenshot, physical pixels.
pub const SCREENSHOT_SIZE: (u32, u32) = (960, 540);
/// Samples per pixel for antialiasing, when the display offers them.
const MULTISAMPLES: u8 = 4;

/// What the window is for.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Mode {
    /// Live until the user closes it.
    Interactive,
    /// Take `steps` steps, save the frame to `path` as PNG, close.
    Screenshot {
        /// The PNG to write.
        path: PathBuf,
        /// Steps before the picture.
        steps: u64,
    },
}

/// Opens the window on `simulation` and runs until it closes; returns what to print on stdout.
pub fn run(simulation: Simulation, scene: String, mode: Mode) -> Result<String, ViewError> {
    let mut event_loop = open_event_loop()?;
    let (width, height) = match mode {
        Mode::Interactive => WINDOW_SIZE,
        Mode::Screenshot { .. } => SCREENSHOT_SIZE,
    };
    let window = WindowBuilder::new()
        .with_title(format!("rebond view: {scene}"))
        .with_inner_size(PhysicalSize::new(width, height))
        .with_resizable(mode == Mode::Interactive)
        .build(&event_loop)
        .map_err(|error| ViewError::Window(error.to_string()))?;
    let context = windowed_context(&window)?;
    let mut input = FrameInputGenerator::from_winit_window(&window);
    let mut frames = FrameLoop {
        renderer: Renderer::new(&context),
        viewer: Viewer::new(simulation, Vec2::new(width as f32, height as f32)),
        scene,
        mode,
    };
    let mut outcome: Option<Result<String, ViewError>> = None;
    event_loop.run_return(|event, _, control_flow| {
        *control_flow = ControlFlow::Poll;
        match event {
            Event::WindowEvent { event, .. } => {
                input.handle_winit_window_event(&event);
                match event {
                    WindowEvent::Resized(size) => context.resize(size),
                    WindowEvent::ScaleFactorChanged { new_inner_size, .. } => {
                        context.resize(*new_inner_size);
                    }
                    WindowEvent::CloseRequested => outcome = Some(Ok(String::new())),
                    _ => {}
                }
            }
            Event::MainEventsCleared => window.request_redraw(),
            Event::RedrawRequested(_) => {
                let frame = input.generate(&context);
                outcome = frames.frame(&frame).or_else(|| {
                    context
                        .swap_buffers()
                        .err()
                        .map(|error| Err(ViewError::Window(error.to_string())))
                });
            }
            _ => {}
        }
        if outcome.is_some() {
            *control_flow = ControlFlow::Exit;
        }
    });
    outcome.unwrap_or_else(|| Ok(String::new()))
}

/// winit's event loop, or an error when no display can be opened. winit 0.28 panics in that
/// case; the panic is caught here, with the default panic message silenced, and turned into an
/// error line.
fn open_event_loop() -> Result<EventLoop<()>, ViewError> {
    let has_display = ["DISPLAY", "WAYLAND_DISPLAY"]
        .iter()
        .any(|variable| std::env::var_os(variable).is_some_and(|value| !value.is_empty()));
    if cfg!(target_os = "linux") && !has_display {
        return Err(ViewError::Window(
            "no display: neither DISPLAY nor WAYLAND_DISPLAY is set (on a machine without a \
             screen, run under xvfb-run)"
                .to_owned(),
        ));
    }
    let default_hook = panic::take_hook();
    panic::set_hook(Box::new(|_| {}));
    let event_loop = panic::catch_unwind(EventLoop::new);
    panic::set_hook(default_hook);
    event_loop.map_err(|payload| {
        let reason = payload
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| payload.downcast_ref::<&str>().copied())
            .unwrap_or("the windowing system refused");
        ViewError::Window(format!("cannot connect to the display: {reason}"))
    })
}

/// An OpenGL context for `window`, antialiased when the display allows it.
fn windowed_context(window: &Window) -> Result<WindowedContext, ViewError> {
    let settings = SurfaceSettings {
        multisamples: MULTISAMPLES,
        ..SurfaceSettings::default()
    };
    WindowedContext::from_winit_window(window, settings)
        .or_else(|_| {
            WindowedContext::from_winit_window(
                window,
                SurfaceSettings {
                    multisamples: 0,
                    ..settings
                },
            )
        })
        .map_err(|error| ViewError::Window(format!("cannot create an OpenGL context: {error}")))
}

/// What each frame does.
struct FrameLoop {
    /// Draws the frames.
    renderer: Renderer,
    /// The simulation, the camera and what is shown.
    viewer: Viewer,
    /// How the scene is named in the overlay, the report and errors.
    scene: String,
    /// Interactive, or a screenshot.
    mode: Mode,
}

impl FrameLoop {
    /// Handles one frame; `Some` ends the loop with that outcome.
    fn frame(&mut self, frame: &FrameInput) -> Option<Result<String, ViewError>> {
        match self.mode.clone() {
            Mode::Interactive => match self.interactive_frame(frame) {
                Ok(true) => None,
                Ok(false) => Some(Ok(String::new())),
                Err(error) => Some(Err(error)),
            },
            Mode::Screenshot { path, steps } => Some(self.screenshot(frame, &path, steps)),
        }
    }

    /// Answers the input, steps in real time, draws; returns whether to go on (not when the
    /// user quits).
    fn interactive_frame(&mut self, frame: &FrameInput) -> Result<bool, ViewError> {
        let viewport = Vec2::new(frame.viewport.width as f32, frame.viewport.height as f32);
        for event in &frame.events {
            self.viewer
                .handle_event(event, viewport)
                .map_err(|error| self.step_failure(error))?;
        }
        self.viewer
            .simulation
            .advance(Duration::from_secs_f64(
                frame.elapsed_time.max(0.0) / 1000.0,
            ))
            .map_err(|error| self.step_failure(error))?;
        // A minimised window has no pixels to draw.
        if frame.viewport.width > 0 && frame.viewport.height > 0 {
            self.renderer
                .render(&frame.screen(), &self.viewer, frame.viewport, &self.scene);
        }
        Ok(!self.viewer.should_quit())
    }

    /// Takes the steps, draws, saves the frame and reports on it.
    fn screenshot(
        &mut self,
        frame: &FrameInput,
        path: &std::path::Path,
        steps: u64,
    ) -> Result<String, ViewError> {
        while self.viewer.simulation.steps() < steps {
            self.viewer
                .simulation
                .step()
                .map_err(|error| self.step_failure(error))?;
        }
        let screen = frame.screen();
        self.renderer
            .render(&screen, &self.viewer, frame.viewport, &self.scene);
        let pixels = screen.read_color::<[u8; 4]>();
        let (width, height) = (frame.viewport.width, frame.viewport.height);
        save_png(path, width, height, &pixels)?;
        Ok(
            ScreenshotReport::new(self.scene.clone(), &self.viewer, path, width, height)
                .to_string(),
        )
    }

    /// The error line for a step the engine refused.
    fn step_failure(&self, error: rebond::Error) -> ViewError {
        ViewError::Failure(Failure::Step {
            source: self.scene.clone(),
            step: self.viewer.simulation.steps() + 1,
            error,
        })
    }
}
