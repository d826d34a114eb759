//! Showing a rendered picture in a window: the RGBA8 sRGB pixels uploaded to a texture and
//! drawn over the whole surface by a full-screen triangle (scaled: coarse frames are smaller).

use sdfc::gpu::{Error, Gpu};

const BLIT_WGSL: &str = r#"
struct Out {
    @builtin(position) position: vec4<f32>,
    @location(0) uv: vec2<f32>,
}

@vertex
fn blit_vertex(@builtin(vertex_index) i: u32) -> Out {
    let xy = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    var out: Out;
    out.position = vec4<f32>(xy * 2.0 - 1.0, 0.0, 1.0);
    out.uv = vec2<f32>(xy.x, 1.0 - xy.y);
    return out;
}

@group(0) @binding(0) var picture: texture_2d<f32>;
@group(0) @binding(1) var picture_sampler: sampler;

@fragment
fn blit_fragment(in: Out) -> @location(0) vec4<f32> {
    return textureSample(picture, picture_sampler, in.uv);
}
"#;

/// The pipeline that draws a picture over a surface.
pub struct Present {
    pipeline: wgpu::RenderPipeline,
    sampler: wgpu::Sampler,
    /// The pictures' texture format: sRGB when the surface is (sampling decodes and the surface
    /// encodes again), else plain (the bytes pass through).
    texture_format: wgpu::TextureFormat,
    /// The current picture's texture, its size and bind group.
    picture: Option<(wgpu::Texture, (u32, u32), wgpu::BindGroup)>,
}

impl Present {
    /// A presenter for surfaces of `format`.
    pub fn new(gpu: &Gpu, format: wgpu::TextureFormat) -> Result<Present, Error> {
        let module = naga::front::wgsl::parse_str(BLIT_WGSL)
            .map_err(|e| Error::Wgsl(e.emit_to_string(BLIT_WGSL)))?;
        let shader = gpu
            .device()
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("blit"),
                source: wgpu::ShaderSource::Naga(std::borrow::Cow::Owned(module)),
            });
        let pipeline = gpu
            .device()
            .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some("blit"),
                layout: None,
                vertex: wgpu::VertexState {
                    module: &shader,
                    entry_point: Some("blit_vertex"),
                    compilation_options: Default::default(),
                    buffers: &[],
                },
                fragment: Some(wgpu::FragmentState {
                    module: &shader,
                    entry_point: Some("blit_fragment"),
                    compilation_options: Default::default(),
                    targets: &[Some(format.into())],
                }),
                primitive: Default::default(),
                depth_stencil: None,
                multisample: Default::default(),
                multiview_mask: None,
                cache: None,
            });
        let sampler = gpu.device().create_sampler(&wgpu::SamplerDescriptor {
            label: Some("blit"),
            mag_filter: wgpu::FilterMode::Nearest,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        let texture_format = if format.is_srgb() {
            wgpu::TextureFormat::Rgba8UnormSrgb
        } else {
            wgpu::TextureFormat::Rgba8Unorm
        };
        Ok(Present {
            pipeline,
            sampler,
            texture_format,
            picture: None,
        })
    }

    /// Draws `rgba` (sRGB, `size`, row-major) over the whole of `surface`'s next frame; false
    /// when the surface had no frame to give (outdated after a resize, lost, hidden or timed
    /// out: configure it again and draw later).
    pub fn show(
        &mut self,
        gpu: &Gpu,
        surface: &wgpu::Surface,
        rgba: &[u8],
        size: (u32, u32),
    ) -> Result<bool, Error> {
        let (w, h) = size;
        if self.picture.as_ref().map(|p| p.1) != Some(size) {
            self.picture = Some(self.texture(gpu, size));
        }
        let (texture, _, bind) = self.picture.as_ref().expect("a picture");
        gpu.queue().write_texture(
            texture.as_image_copy(),
            rgba,
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(4 * w),
                rows_per_image: None,
            },
            wgpu::Extent3d {
                width: w,
                height: h,
                depth_or_array_layers: 1,
            },
        );
        let frame = match surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(f)
            | wgpu::CurrentSurfaceTexture::Suboptimal(f) => f,
            wgpu::CurrentSurfaceTexture::Validation => {
                return Err(Error::SurfaceRefused);
            }
            _ => return Ok(false),
        };
        let target = frame.texture.create_view(&Default::default());
        let mut encoder = gpu.device().create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("blit"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &target,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                ..Default::default()
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, bind, &[]);
            pass.draw(0..3, 0..1);
        }
        gpu.queue().submit([encoder.finish()]);
        gpu.queue().present(frame);
        Ok(true)
    }

    /// A texture of `size` for the pictures, and its bind group.
    fn texture(&self, gpu: &Gpu, size: (u32, u32)) -> (wgpu::Texture, (u32, u32), wgpu::BindGroup) {
        let (w, h) = size;
        let texture = gpu.device().create_texture(&wgpu::TextureDescriptor {
            label: Some("picture"),
            size: wgpu::Extent3d {
                width: w,
                height: h,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: self.texture_format,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        let view = texture.create_view(&Default::default());
        let bind = gpu.device().create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("picture"),
            layout: &self.pipeline.get_bind_group_layout(0),
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(&view),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::Sampler(&self.sampler),
                },
            ],
        });
        (texture, size, bind)
    }
}
