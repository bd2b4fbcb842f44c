//! The image beside the panel: a GPU texture the size of the image, written only when a new
//! image is published (and then only the image's pixels), and drawn into the window one
//! pixel to one pixel, under the panel. A frame redrawn for the panel alone uploads nothing.

use super::render_thread::Published;
use pixels::wgpu;

/// The colour of the selection's outline.
const SELECTION_COLOR: [u8; 4] = [255, 150, 0, 255];

/// Where a window pixel finds its image pixel: the image's left edge in the window.
const SHADER: &str = r"
struct Place { left: vec4<i32> }
@group(0) @binding(0) var image: texture_2d<f32>;
@group(0) @binding(1) var<uniform> place: Place;

@vertex
fn vs_main(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    // One triangle over the whole target; the scissor keeps it to the image.
    let xy = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(xy * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn fs_main(@builtin(position) at: vec4<f32>) -> @location(0) vec4<f32> {
    let pixel = vec2<i32>(at.xy) - vec2<i32>(place.left.x, 0);
    return textureLoad(image, pixel, 0);
}
";

/// The image's texture and what draws it.
pub struct ImageLayer {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    place: wgpu::Buffer,
    /// The texture's format: the bytes written come out on the surface unchanged.
    format: wgpu::TextureFormat,
    /// The texture, its size and the bind group that reads it, once an image has come.
    texture: Option<(wgpu::Texture, (u32, u32), wgpu::BindGroup)>,
    /// The image with the selection's outline drawn in (reused between images).
    outlined: Vec<u8>,
}

impl ImageLayer {
    /// The layer for a window whose surface has format `surface`.
    pub fn new(device: &wgpu::Device, surface: wgpu::TextureFormat) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("prism image"),
            source: wgpu::ShaderSource::Wgsl(SHADER.into()),
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("prism image"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: false },
                        multisampled: false,
                        view_dimension: wgpu::TextureViewDimension::D2,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: wgpu::BufferSize::new(16),
                    },
                    count: None,
                },
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("prism image"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("prism image"),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_main"),
                buffers: &[],
                compilation_options: wgpu::PipelineCompilationOptions::default(),
            },
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: None,
            multisample: wgpu::MultisampleState::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs_main"),
                compilation_options: wgpu::PipelineCompilationOptions::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format: surface,
                    blend: None,
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        });
        let place = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("prism image place"),
            size: 16,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        // The image's bytes are sRGB-encoded: an sRGB texture decodes them and an sRGB
        // surface encodes them again; a plain surface takes them as they are.
        let format = if surface.is_srgb() {
            wgpu::TextureFormat::Rgba8UnormSrgb
        } else {
            wgpu::TextureFormat::Rgba8Unorm
        };
        Self {
            pipeline,
            layout,
            place,
            format,
            texture: None,
            outlined: Vec::new(),
        }
    }

    /// Forgets the image (the window's size changed: the next image is its own).
    pub fn clear(&mut self) {
        self.texture = None;
    }

    /// Writes the published image `p` into the texture (made anew when its size changed),
    /// with the selection's outline drawn in; returns the bytes written.
    pub fn upload(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, p: &Published) -> usize {
        let (w, h) = (p.width, p.height);
        let pixels = w as usize * h as usize;
        if pixels == 0 || p.rgba.len() != pixels * 4 {
            return 0;
        }
        if self
            .texture
            .as_ref()
            .is_none_or(|(_, size, _)| *size != (w, h))
        {
            self.texture = Some(self.texture_for(device, (w, h)));
        }
        let rgba = match p.outline.as_deref().filter(|o| o.len() == pixels) {
            None => &p.rgba[..],
            Some(marks) => {
                self.outlined.clear();
                self.outlined.extend_from_slice(&p.rgba);
                for (pixel, _) in self
                    .outlined
                    .chunks_exact_mut(4)
                    .zip(marks)
                    .filter(|(_, m)| **m)
                {
                    pixel.copy_from_slice(&SELECTION_COLOR);
                }
                &self.outlined[..]
            }
        };
        let Some((texture, ..)) = &self.texture else {
            return 0;
        };
        queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            rgba,
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(4 * w),
                rows_per_image: Some(h),
            },
            wgpu::Extent3d {
                width: w,
                height: h,
                depth_or_array_layers: 1,
            },
        );
        rgba.len()
    }

    fn texture_for(
        &self,
        device: &wgpu::Device,
        (w, h): (u32, u32),
    ) -> (wgpu::Texture, (u32, u32), wgpu::BindGroup) {
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("prism image"),
            size: wgpu::Extent3d {
                width: w,
                height: h,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: self.format,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("prism image"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(&view),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: self.place.as_entire_binding(),
                },
            ],
        });
        (texture, (w, h), group)
    }

    /// Clears `target` (`size` pixels) to black and draws the image with its left edge at
    /// column `left`, cut to the target.
    pub fn draw(
        &self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
        size: (u32, u32),
        left: u32,
    ) {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("prism image"),
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
        });
        let Some((_, (w, h), group)) = &self.texture else {
            return;
        };
        // What of the image lies in the target (a resize may be on its way).
        let cols = (*w).min(size.0.saturating_sub(left));
        let rows = (*h).min(size.1);
        if cols == 0 || rows == 0 {
            return;
        }
        let mut place = [0u8; 16];
        place[..4].copy_from_slice(&(left as i32).to_ne_bytes());
        queue.write_buffer(&self.place, 0, &place);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, group, &[]);
        pass.set_scissor_rect(left, 0, cols, rows);
        pass.draw(0..3, 0..1);
    }
}
