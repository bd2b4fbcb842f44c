//! The window and what draws into it: the `pixels` framebuffer that holds the image beside
//! the panel, and egui's renderer on top. Event handling lives in mod.rs; this file only
//! opens the window and draws frames.

use super::panel::PANEL_WIDTH;
use super::render_thread::{Published, RenderThread};
use anyhow::{Context, Result, anyhow};
use pixels::{Pixels, PixelsBuilder, SurfaceTexture, wgpu};
use std::sync::Arc;
use winit::dpi::{LogicalSize, PhysicalSize};
use winit::event_loop::ActiveEventLoop;
use winit::window::Window;

/// Everything that exists only while the window does.
pub struct Gfx {
    pub window: Arc<Window>,
    pub pixels: Pixels<'static>,
    pub egui_ctx: egui::Context,
    pub egui_state: egui_winit::State,
    renderer: egui_wgpu::Renderer,
    pub render: RenderThread,
    pub size: PhysicalSize<u32>,
}

impl Gfx {
    /// Opens a window for an image of `image` pixels beside the panel, with its
    /// framebuffer and egui; `start_render` starts the render thread for the image size
    /// the window really has.
    pub fn open(
        event_loop: &ActiveEventLoop,
        image: (u32, u32),
        start_render: impl FnOnce((u32, u32)) -> RenderThread,
    ) -> Result<Gfx> {
        let (w, h) = image;
        let attrs = Window::default_attributes()
            .with_title("prism")
            .with_inner_size(LogicalSize::new(w as f64 + PANEL_WIDTH as f64, h as f64))
            .with_min_inner_size(LogicalSize::new(PANEL_WIDTH as f64 + 64.0, 200.0));
        let window = Arc::new(
            event_loop
                .create_window(attrs)
                .context("cannot create the window")?,
        );
        let size = window.inner_size();
        let surface = SurfaceTexture::new(size.width.max(1), size.height.max(1), window.clone());
        let pixels = PixelsBuilder::new(size.width.max(1), size.height.max(1), surface)
            .enable_vsync(true)
            .build()
            .map_err(|e| {
                anyhow!(
                    "no usable GPU adapter for the window ({e}); \
                     `prism render` renders without one"
                )
            })?;
        let egui_ctx = egui::Context::default();
        let max_texture = pixels.device().limits().max_texture_dimension_2d as usize;
        let egui_state = egui_winit::State::new(
            egui_ctx.clone(),
            egui::ViewportId::ROOT,
            &*window,
            Some(window.scale_factor() as f32),
            None,
            Some(max_texture),
        );
        let renderer = egui_wgpu::Renderer::new(
            pixels.device(),
            pixels.surface_texture_format(),
            egui_wgpu::RendererOptions::default(),
        );
        let render = start_render(image_size(size, &window));
        Ok(Gfx {
            window,
            pixels,
            egui_ctx,
            egui_state,
            renderer,
            render,
            size,
        })
    }

    /// Width of the panel in physical pixels.
    pub fn panel_px(&self) -> u32 {
        panel_px(&self.window)
    }

    /// The render resolution: the window area beside the panel.
    pub fn image_size(&self) -> (u32, u32) {
        image_size(self.size, &self.window)
    }

    /// Shows the render thread's latest image if it is newer than `shown` (a publication
    /// serial), and returns what the thread reports with it and the serial now shown.
    pub fn take_published(&mut self, shown: u64) -> (super::render_thread::Status, u64) {
        let x0 = self.panel_px();
        let (fw, fh) = (self.size.width, self.size.height);
        let p = self.render.published();
        if p.serial != shown {
            copy_image(self.pixels.frame_mut(), fw, fh, x0, &p);
        }
        (p.status.clone(), p.serial)
    }

    /// Draws one frame: the framebuffer scaled to the window, then egui's `shapes` with
    /// its texture changes.
    pub fn draw(
        &mut self,
        shapes: Vec<egui::epaint::ClippedShape>,
        pixels_per_point: f32,
        textures: egui::TexturesDelta,
    ) -> Result<()> {
        let paint_jobs = self.egui_ctx.tessellate(shapes, pixels_per_point);
        let screen = egui_wgpu::ScreenDescriptor {
            size_in_pixels: [self.size.width, self.size.height],
            pixels_per_point,
        };
        let renderer = &mut self.renderer;
        self.pixels
            .render_with(|encoder, target, context| {
                context.scaling_renderer.render(encoder, target);
                for (id, delta) in &textures.set {
                    renderer.update_texture(&context.device, &context.queue, *id, delta);
                }
                let extra = renderer.update_buffers(
                    &context.device,
                    &context.queue,
                    encoder,
                    &paint_jobs,
                    &screen,
                );
                debug_assert!(extra.is_empty(), "no egui paint callbacks are used");
                // egui draws over what the framebuffer put in `target`, and keeps it.
                let mut pass = encoder
                    .begin_render_pass(&wgpu::RenderPassDescriptor {
                        label: Some("egui"),
                        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                            view: target,
                            depth_slice: None,
                            resolve_target: None,
                            ops: wgpu::Operations {
                                load: wgpu::LoadOp::Load,
                                store: wgpu::StoreOp::Store,
                            },
                        })],
                        depth_stencil_attachment: None,
                        timestamp_writes: None,
                        occlusion_query_set: None,
                        multiview_mask: None,
                    })
                    .forget_lifetime();
                renderer.render(&mut pass, &paint_jobs, &screen);
                drop(pass);
                for id in &textures.free {
                    renderer.free_texture(id);
                }
                Ok(())
            })
            .context("drawing the window failed")
    }
}

/// Width of the panel in physical pixels.
fn panel_px(window: &Window) -> u32 {
    (PANEL_WIDTH * window.scale_factor() as f32).ceil() as u32
}

/// The render resolution: the window area beside the panel.
fn image_size(size: PhysicalSize<u32>, window: &Window) -> (u32, u32) {
    let w = size.width.saturating_sub(panel_px(window)).max(1);
    (w, size.height.max(1))
}

/// Copies the published image into a frame of `fw` × `fh` RGBA pixels at column `x0` (to
/// the right of the panel), clipping to whichever is smaller while a resize is on its way to
/// the render thread.
fn copy_image(frame: &mut [u8], fw: u32, fh: u32, x0: u32, p: &Published) {
    let cols = p.width.min(fw.saturating_sub(x0)) as usize;
    let rows = p.height.min(fh) as usize;
    // A window narrower than the panel shows no image at all.
    if cols == 0 {
        return;
    }
    let outline = p
        .outline
        .as_deref()
        .filter(|o| o.len() == p.width as usize * p.height as usize);
    for y in 0..rows {
        let src = y * p.width as usize * 4;
        let dst = (y * fw as usize + x0 as usize) * 4;
        let row = &mut frame[dst..dst + cols * 4];
        row.copy_from_slice(&p.rgba[src..src + cols * 4]);
        if let Some(outline) = outline {
            let marks = &outline[y * p.width as usize..][..cols];
            for (pixel, _) in row.chunks_exact_mut(4).zip(marks).filter(|(_, m)| **m) {
                pixel.copy_from_slice(&SELECTION_COLOR);
            }
        }
    }
}

/// The colour the selected object is outlined in on screen.
const SELECTION_COLOR: [u8; 4] = [255, 150, 0, 255];
