//! The window and what draws into it: the `pixels` surface, the image beside the panel
//! (image_layer.rs), and egui's panel on top. Event handling lives elsewhere; this file
//! only opens the window and draws frames.

use super::image_layer::ImageLayer;
use super::panel::PANEL_WIDTH;
use super::render_thread::RenderThread;
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
    /// The image shown beside the panel.
    image: ImageLayer,
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
        // The framebuffer `pixels` uploads on every draw is one pixel, unused: the image is
        // a texture that changes only when the image does.
        let pixels = PixelsBuilder::new(1, 1, surface)
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
        let image = ImageLayer::new(pixels.device(), pixels.render_texture_format());
        let render = start_render(image_size(size, &window));
        Ok(Gfx {
            window,
            pixels,
            egui_ctx,
            egui_state,
            renderer,
            render,
            size,
            image,
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

    /// Takes the render thread's latest image as the one to show if it is newer than
    /// `shown` (a publication serial), and returns what the thread reports with it, the
    /// serial now shown and the bytes of image uploaded (0 when it was not new).
    pub fn take_published(&mut self, shown: u64) -> (super::render_thread::Status, u64, usize) {
        let p = self.render.published();
        let mut uploaded = 0;
        if p.serial != shown {
            let context = self.pixels.context();
            uploaded = self.image.upload(&context.device, &context.queue, &p);
        }
        (p.status.clone(), p.serial, uploaded)
    }

    /// Forgets the image shown (the window's size changed; the next image is its own).
    pub fn clear_image(&mut self) {
        self.image.clear();
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
        let (size, left) = ((self.size.width, self.size.height), self.panel_px());
        let renderer = &mut self.renderer;
        let image = &self.image;
        self.pixels
            .render_with(|encoder, target, context| {
                image.draw(&context.queue, encoder, target, size, left);
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
                // egui draws the panel over the image, keeping what is there.
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
