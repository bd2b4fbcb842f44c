//! The window and what draws into it: the `pixels` surface, the image beside the panel as
//! a texture of its own (uploaded only when a new image arrives, and only the image's
//! area), and egui's panel on top. Event handling lives elsewhere; this file only opens
//! the window and draws frames.

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
    /// The image shown beside the panel, once one has arrived.
    image: Option<egui::TextureHandle>,
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
        let render = start_render(image_size(size, &window));
        Ok(Gfx {
            window,
            pixels,
            egui_ctx,
            egui_state,
            renderer,
            render,
            size,
            image: None,
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
    /// `shown` (a publication serial), and returns what the thread reports with it and the
    /// serial now shown.
    pub fn take_published(&mut self, shown: u64) -> (super::render_thread::Status, u64) {
        let p = self.render.published();
        if p.serial != shown
            && let Some(image) = shown_image(&p)
        {
            match &mut self.image {
                Some(texture) => texture.set(image, egui::TextureOptions::NEAREST),
                None => {
                    let texture =
                        self.egui_ctx
                            .load_texture("image", image, egui::TextureOptions::NEAREST);
                    self.image = Some(texture);
                }
            }
        }
        (p.status.clone(), p.serial)
    }

    /// Forgets the image shown (the window's size changed; the next image is its own).
    pub fn clear_image(&mut self) {
        self.image = None;
    }

    /// Paints the image beside the panel, under everything egui draws.
    pub fn paint_image(&self, ctx: &egui::Context) {
        let Some(texture) = &self.image else {
            return;
        };
        // Physical pixels one to one: the image starts where the panel ends.
        let ppp = ctx.pixels_per_point();
        let [w, h] = texture.size();
        let rect = egui::Rect::from_min_size(
            egui::pos2(self.panel_px() as f32 / ppp, 0.0),
            egui::vec2(w as f32 / ppp, h as f32 / ppp),
        );
        let whole = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0));
        ctx.layer_painter(egui::LayerId::background()).image(
            texture.id(),
            rect,
            whole,
            egui::Color32::WHITE,
        );
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
                // egui draws the whole window: the image (see `paint_image`), then the panel.
                let mut pass = encoder
                    .begin_render_pass(&wgpu::RenderPassDescriptor {
                        label: Some("egui"),
                        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                            view: target,
                            depth_slice: None,
                            resolve_target: None,
                            ops: wgpu::Operations {
                                load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
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

/// The published image as a texture's pixels, with the selection's outline drawn in;
/// None before the first image.
fn shown_image(p: &Published) -> Option<egui::ColorImage> {
    let (w, h) = (p.width as usize, p.height as usize);
    if w == 0 || h == 0 || p.rgba.len() != w * h * 4 {
        return None;
    }
    let outline = p.outline.as_deref().filter(|o| o.len() == w * h);
    let pixels = p
        .rgba
        .chunks_exact(4)
        .enumerate()
        .map(|(i, c)| match outline {
            Some(marks) if marks[i] => SELECTION_COLOR,
            _ => egui::Color32::from_rgba_premultiplied(c[0], c[1], c[2], c[3]),
        })
        .collect();
    Some(egui::ColorImage::new([w, h], pixels))
}

const SELECTION_COLOR: egui::Color32 = egui::Color32::from_rgb(255, 150, 0);
